"""Hysteresis on the envelope clamp's pattern gate, door room (stop 112, guard112c): REFUSED.

guard112b traced door-room arx_rf / arx E_Z deployed 1.123 x unguarded to the pattern gate switching
the clamp on and off on test K5 and the guard's rate limit pacing each switch.  The rule tried
here (benchmarks/guard112c_rule.patch, fixed in benchmarks/guard112c_bar.md before any
measurement): a sample clamped off the pattern (residual > ``tol``, the largest training one) is
back on it only at a residual within ``tol_back``, the median training residual; a sample within
the envelope ends the episode.  Python stream and guard only (not carried to the C, ST, Simulator).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_guard112c.py gate OUT              # K5's residuals against the gate
    python benchmarks/bench_guard112c.py rule OUT CASE DATA... # cost: the tree vs tree + patch
    python benchmarks/bench_guard112c.py oracle OUT CASE...    # the gate passing K5's rows

OUT as bench_guard111b's (its rooms made there once); CASE, DATA as its ``cost``.  ``gate``: on
the door room's test rows beyond the envelope, the pattern residual / ``tol`` as measured and of
K5's noise-free path (bench_dep108c's ``_room`` without its 0.03 K noise), and the training
residuals' quantiles.  ``rule``: bench_guard111b ``cost`` under a copy of the tree's src with the
patch applied, then under the tree's own.  ``oracle``: counterfactual on the tree's src, the gate
told no sample leaves the pattern (what a gate blind to the sensors' noise would say of K5).

MEASURED (2026-12-08; bar committed first, 66dabeb2; tree = 9e57b021's src, CPU by rusage, each
pair on the same load).  ``gate``: 61 of 80 rows beyond the envelope (from row 19); measured
residual / tol min 0.41 median 0.96 max 1.46, 28 rows > 1 (the switches); noise-free path
0.65 - 0.90 (median 0.82): K5 runs ON the training pattern, the sensors' noise carries it across
``tol``.  Training residual / tol: q50 0.199 (= tol_back), q90 0.50, q99 0.73; no row of K5
falls to tol_back once clamped, so the rule clamps every row from the first switch on.
``rule`` (deployed RMSE um, base -> rule; ratio deployed / unguarded): door room arx_rf/none
E_Z 1.6134 -> 2.5432 (ratio 1.1234 -> 1.0000), E_X 17.6227 -> 20.1536; arx/none E_Z 1.6163 ->
2.5464 (1.1231 -> 1.0000), E_X 17.7170 -> 20.2778; arx_rf/per-interval E_X 12.5308 -> 16.2845,
E_Z 1.6072 -> 2.5202; room mlr/none E_Z 1.6246 -> 2.5497, E_X 18.2025 -> 20.4215; lagbank/none
E_X 16.9690 -> 17.3536, E_Z 1.5527 -> 2.4427; mlr/ati E_X 12.1263 -> 13.8380, E_Z 1.6133 ->
2.5228.  bench_guard111b ``table``: all 60 case x target sha1 differ from BASE (26.2 / 23.7 s CPU).
CPU per ``cost`` equal (2.1 - 3.4 s either way).  ``oracle`` (tree's src, K5 passed as on the
pattern): arx_rf/none E_Z deployed 1.6134 -> 0.1400 um (unguarded 1.4362 -> 0.1400, ratio 1.0000),
E_X 17.6227 -> 15.6422; arx/none E_Z 1.6163 -> 0.1399, E_X 17.7170 -> 15.7301: the cost is the
clamp acting on a noisy on-pattern path, which hysteresis prolongs; a gate that discounts the
sensors' noise (not tried: no rule fixed) is the direction.  Fresh seeds 10257-10259 not drawn.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_guard111b as g111b  # noqa: E402
import bench_guard112b as g112b  # noqa: E402
from _cli import run_commands  # noqa: E402

HERE = Path(__file__).resolve().parent
PATCH = HERE / "guard112c_rule.patch"


def _residual(env, X: np.ndarray) -> np.ndarray:
    """The pattern residual of each row of ``X`` (model frame): what ``leaves_pattern`` compares."""
    Z = (X - env.mean) / env.scale
    return np.linalg.norm(Z - Z @ env.basis @ env.basis.T, axis=1)


def _noise_free_k5(columns) -> np.ndarray:
    """K5's inputs as bench_dep108c's ``_room`` makes them, without the noise, referenced."""
    t = np.arange(80) * 120.0
    amb, power = 14.0 + 2.4 * 5, 9.0
    rise, late = power * (1 - np.exp(-t / 2400)), power * (1 - np.exp(-t / 4800))
    f = pd.DataFrame({"T_amb": amb + 0 * t, "T_a": amb + rise, "T_b": amb + 0.6 * rise,
                      "T_c": amb + 0.8 * late, "T_d": amb + 0.4 * late})[list(columns)]
    return (f - f.iloc[0]).to_numpy(float)


def gate(out: str) -> None:
    """K5's pattern residuals (measured, noise-free) against ``tol``; training quantiles."""
    dep, train, tests, _ = g111b._deployed(g112b._door(out), "arx_rf/none")
    env, comp = dep.envelope, dep.compensator
    q = np.quantile(_residual(env, comp.stacked(train, targets=[]).X.to_numpy(float)), [0.5, 0.9, 0.99])
    print(f"tol {env.tol:.4g}; training residual / tol: q50 {q[0] / env.tol:.3f} q90 {q[1] / env.tol:.3f} "
          f"q99 {q[2] / env.tol:.3f}")
    for cid, df in tests.items():
        X = comp.stacked({cid: df.reset_index(drop=True)}, targets=[]).X.to_numpy(float)
        out_rows = ((X < env.lo) | (X > env.hi)).any(axis=1)
        measured = _residual(env, X)[out_rows] / env.tol
        clean = _residual(env, _noise_free_k5(env.columns))[out_rows] / env.tol
        print(f"{cid}: {int(out_rows.sum())} of {len(X)} rows beyond the envelope (from row "
              f"{int(np.argmax(out_rows))}); residual / tol measured min {measured.min():.3f} median "
              f"{np.median(measured):.3f} max {measured.max():.3f} (> 1: {int((measured > 1).sum())}); "
              f"noise-free min {clean.min():.3f} median {np.median(clean):.3f} max {clean.max():.3f}; "
              f"rows within q50 {int((measured <= q[0] / env.tol).sum())}")


def rule(out: str, case: str, *datas: str) -> None:
    """bench_guard111b ``cost`` under the tree's src with the rule's patch, then under its own."""
    src = Path(__import__("thermocomp").__file__).resolve().parents[1]
    with tempfile.TemporaryDirectory() as tmp:
        shutil.copytree(src, Path(tmp) / "src")
        subprocess.run(["patch", "-s", "-p1", "-d", tmp, "-i", str(PATCH)], check=True)
        for label, path in (("rule", Path(tmp) / "src"), ("tree", src)):
            run = subprocess.run([sys.executable, str(HERE / "bench_guard111b.py"), "cost", out, case,
                                  *datas], env={**os.environ, "PYTHONPATH": str(path)},
                                 capture_output=True, text=True, check=True)
            for line in (run.stdout + run.stderr).splitlines():
                if line.strip():
                    print(f"{label}: {line}", flush=True)


def oracle(out: str, *cases: str) -> None:
    """Per case: deployed / unguarded with the gate told no sample leaves the pattern."""
    from thermocomp.apps.deploy.streaming import Envelope

    def on_pattern(self, x, *_):
        return False
    for case in cases:
        dep, _, tests, _ = g111b._deployed(g112b._door(out), case)
        g112b._score(dep, tests, case, "as_is")
        with g112b._patched(Envelope, "leaves_pattern", on_pattern):
            g112b._score(dep, tests, case, "oracle")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"gate": gate, "rule": rule, "oracle": oracle}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
