"""The pattern gate judged on low-passed inputs, door room (stop 112, guard112d): REFUSED.

guard112c traced door-room arx_rf / arx E_Z deployed 1.61 um (1.123 x unguarded) to the pattern
gate switching the clamp on and off on test K5, whose 0.03 K sensor noise carries its residual
across ``tol`` (measured 0.41-1.46 tol; noise-free 0.65-0.90).  The rule tried here (fixed in
benchmarks/guard112d_bar.md before any measurement; benchmarks/guard112d_rule.patch, Python stream
and guard only): off the pattern when the residual of the inputs low-passed by an exponential
filter (time constant ``TAU_S``, a = 1 - exp(-P / TAU_S), P the training grid's step) exceeds
``tol_f``, the largest such residual of the training inputs filtered the same way, or at once when
the raw residual exceeds ``SPIKE_K`` x ``tol``.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_guard112d.py gate OUT            # K5's filtered residuals vs tol_f
    python benchmarks/bench_guard112d.py rule BENCH ARGS...  # benchmarks/BENCH.py: patch vs tree

OUT as bench_guard111b's (its rooms made there once).  ``gate`` computes the rule's filter and
``tol_f`` here (on any tree's src) for arx_rf/none's door room.  ``rule``: BENCH (e.g.
``bench_guard111b cost OUT CASE DATA``) under a copy of the tree's src with the patch applied,
then under the tree's own.

MEASURED (2026-12-08; bar committed first, 3d3602fc; tree = dff72f87's src, a detached worktree;
CPU by /usr/bin/time, each pair run at once on the same load).  ``gate``: tol 0.03552, tol_f
0.01513 (0.426 tol): training's raw residual is mostly its own noise, so the filter shrinks the
tolerance as much as K5's noise.  K5's 61 rows beyond the envelope: filtered residual / tol_f
1.76 - 2.59 (median 2.16, all 61 > 1); noise-free path 1.93 median, 2.10 max; raw / tol max 1.46
(none > SPIKE_K).  Training filtered / tol_f q50 0.358 q90 0.746 q99 0.937.  K5 is OFF the
training pattern once the noise is discounted (twice as far as any training row): the gate
clamps all of it, as guard112c's hysteresis did.
``rule`` bench_guard111b ``cost`` (deployed RMSE um, tree -> rule; every case's E_Z is its
all-clamped value, no row guarded): door room arx_rf/none E_Z 1.6134 -> 2.5432, E_X 17.6227 ->
20.1175; arx/none E_Z 1.6163 -> 2.5464, E_X 17.7170 -> 20.2442; arx_rf/per-interval E_Z 1.6072 ->
2.5202, E_X 12.5308 -> 16.3258; room mlr/none E_Z 1.6246 -> 2.5497, E_X 18.2025 -> 20.3755;
lagbank/none E_Z 1.5527 -> 2.4426, E_X 16.9690 -> 16.9979; mlr/ati E_Z 1.6133 -> 2.5227, E_X
12.1263 -> 13.8870 (3.0 - 4.1 s CPU per case, either src).
``table``: all 60 case x target sha1 differ (25.2 / 25.4 s CPU).  bench_deploy_faults: every
fault line identical (each fault clamped as before); the real air steps (not faults) worse:
plain mlr +5 K 6.46 -> 8.08, arx 5.61 -> 7.43, lagbank 11.77 -> 12.12 um; adaptive +5 K/30 min
mlr 6.21 -> 7.38, arx 7.39 -> 8.20 (15.5 / 15.7 s CPU).  bench_envelope_policy (``--only
cms3141,mill7717,long7717``, the lines that leave the envelope): pattern Sigma^2 within 0.03 % or
better (cms3141 lagbank 943.5 -> 943.8; mill7717 mlr 8.298 -> 8.281, lagbank 297.8 -> 297.4),
clamped samples 419 -> 416, 1 -> 0 (93.7 / 95.6 s CPU).  Fresh seeds 10257-10259 not drawn.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from scipy.signal import lfilter

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_guard111b as g111b  # noqa: E402
import bench_guard112c as g112c  # noqa: E402
from _cli import run_commands  # noqa: E402

HERE = Path(__file__).resolve().parent
PATCH = HERE / "guard112d_rule.patch"
TAU_S, SPIKE_K = 600.0, 2.0        # the rule's, as the bar fixed them


def _low_pass(X: np.ndarray, a: float) -> np.ndarray:
    """``f <- f + a (x - f)`` down the rows of ``X``, from its first row."""
    return lfilter([a], [1.0, a - 1.0], X, axis=0, zi=((1.0 - a) * X[0])[None, :])[0]


def gate(out: str) -> None:
    """K5's filtered pattern residuals against the rule's ``tol_f`` (door room, arx_rf/none)."""
    dep, train, tests, _ = g111b._deployed(g111b._rooms(out)[1], "arx_rf/none")
    env, comp = dep.envelope, dep.compensator
    m = comp.stacked(train, targets=[])
    a = float(-np.expm1(-np.median(np.diff(m.time[m.groups == m.groups[0]])) / TAU_S))
    X = m.X.to_numpy(float)
    filtered = np.vstack([_low_pass(X[m.groups == g], a) for g in dict.fromkeys(m.groups)])
    train_f = g112c._residual(env, filtered)
    tol_f = float(train_f.max())
    q = np.quantile(train_f / tol_f, [0.5, 0.9, 0.99])
    print(f"tol {env.tol:.5f} tol_f {tol_f:.5f} ({tol_f / env.tol:.3f} tol), a {a:.4f}; training "
          f"filtered / tol_f q50 {q[0]:.3f} q90 {q[1]:.3f} q99 {q[2]:.3f}")
    for cid, df in tests.items():
        Xt = comp.stacked({cid: df.reset_index(drop=True)}, targets=[]).X.to_numpy(float)
        out_rows = ((Xt < env.lo) | (Xt > env.hi)).any(axis=1)
        f = g112c._residual(env, _low_pass(Xt, a))[out_rows] / tol_f
        clean = g112c._residual(env, g112c._noise_free_k5(env.columns))[out_rows] / tol_f
        raw = g112c._residual(env, Xt)[out_rows] / env.tol
        print(f"{cid}: {int(out_rows.sum())} rows beyond the envelope; filtered / tol_f min "
              f"{f.min():.3f} median {np.median(f):.3f} max {f.max():.3f} (> 1: {int((f > 1).sum())}); "
              f"noise-free median {np.median(clean):.3f} max {clean.max():.3f}; raw / tol max "
              f"{raw.max():.3f} (> {SPIKE_K:g}: {int((raw > SPIKE_K).sum())})")


def rule(bench: str, *args: str) -> None:
    """benchmarks/BENCH.py ARGS under the tree's src with the rule's patch, then under its own."""
    src = Path(__import__("thermocomp").__file__).resolve().parents[1]
    with tempfile.TemporaryDirectory() as tmp:
        shutil.copytree(src, Path(tmp) / "src")
        subprocess.run(["patch", "-s", "-p1", "-d", tmp, "-i", str(PATCH)], check=True)
        for label, path in (("rule", Path(tmp) / "src"), ("tree", src)):
            run = subprocess.run([sys.executable, str(HERE / f"{bench}.py"), *args],
                                 env={**os.environ, "PYTHONPATH": str(path)},
                                 capture_output=True, text=True, check=True)
            for line in run.stdout.splitlines():
                if line.strip():
                    print(f"{label}: {line}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"gate": gate, "rule": rule}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
