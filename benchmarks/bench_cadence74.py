"""The training grid for row-counting memories only (cadence74, issue 34): a model whose memory
advances by the elapsed time steps every row of a faster stream; one that counts rows keeps the
grid (cadence72, between73).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_cadence74.py mixed ROOT [seed ...]
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_cadence74.py truth ROOT [seed ...]
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_cadence74.py digests ROOT [seed]

``mixed`` (default seeds 7471-7475, fresh; and 7336-7340, deploy73's): bench_deploy73's
mixed-cadence record (``sim=yearround_spindle`` at 60 s, cut to 300 s but K01 / K03), ``run``
per family (lagbank, hammerstein, arx, lstm as bench lab_matrix shortens it), the unseen 60 s
K03 predicted (``Compensator.predict``, what ``run`` scores and every deployed form streams)
three ways: ``rule`` (the code's own grid), ``grid`` (the grid as before: the training period
wherever a model keeps a memory, ``keeps_memory``), ``every`` (no grid); RMSE against the error
measured every row (µm, mean over E_X / E_Y / E_Z), and whether ``rule`` is byte-identical to
``grid``.  Each model's memory per target as the rule asks it (``counts_rows``).
``truth`` (default seeds 7476-7480, fresh): between73's records (the swiss lathe, its error known
every 60 s, trained on 300 s rows, its production run streamed at 60 s): the lag bank (and, for
the record, hammerstein) ``rule`` / ``grid`` / ``every`` against the truth at every row.
``digests`` (default seed 7476): between73's all300 record (every row 300 s) run per family (mlr,
pcr, arx, lagbank, hammerstein, lstm, arx_rf): the sha256 of each ``metrics.json``; run once
with the code before and once after, the lines compared.

Rule (one, committed before any figure was measured)
----------------------------------------------------
A memory is asked of the stream itself (``core.context.counts_rows``): every input (and every
raw column the model reads) at 0 on a campaign's first sample, then at 1 held for 1200 s,
streamed at 60 s and at 300 s steps.  A memory that advances by the elapsed time (a lag bank's
continuous lags, ``exp(-dt / tau)`` with the row's own dt) answers alike at every 300 s instant;
one that counts rows (ARX's delays, an AR feedback, an LSTM's cell) does not; a stream that
refuses the probe counts rows (the safe side).  ``Compensator.grid_period_s_`` is the training
period only where some target's model counts rows (or a denoiser's FIR counts the rows of a
model with a memory); else None, every row stepped.  One place, so batch ``run``, the streams,
the Simulator, the C and the ST follow it alike (deployed = scored, replay = run).

Bar (all, else REFUSED: src reverted, this bench and ``benchmarks/cadence74_rule.patch`` kept)
----------------------------------------------------------------------------------------------
1. ``mixed``, per seed set (7471-7475 and 7336-7340): the lag bank's K03 RMSE under ``rule``
   lower than or equal to ``grid``'s in the mean over the five seeds AND on at least 4 of 5.
2. ``mixed``: hammerstein, arx and lstm byte-identical to ``grid`` (the grid kept) on every seed.
3. ``digests``: every family's ``metrics.json`` byte-identical before and after (a 300 s-only
   record).
4. ``truth`` on 7476-7480: the 300 s-trained lag bank streamed at 60 s, its RMSE against the
   truth (every row, mean over dX / dY) under ``rule`` not above ``grid``'s, in the mean over the
   five seeds and on each seed.
"""

from __future__ import annotations

import hashlib
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]

import bench_between73 as between73  # noqa: E402
import bench_deploy73 as deploy73  # noqa: E402
import lab_matrix  # noqa: E402
from _cli import made_folder, run_commands  # noqa: E402

MIXED_SEEDS = (7471, 7472, 7473, 7474, 7475)
TRUTH_SEEDS = (7476, 7477, 7478, 7479, 7480)
FAMILIES = {"lagbank": [], "hammerstein": [], "arx": [], "lstm": lab_matrix.matrix_families()["lstm"]}
DIGEST_FAMILIES = ("mlr", "pcr", "arx", "lagbank", "hammerstein", "lstm", "arx_rf")


def three_ways(comp, frame) -> dict:
    """``comp``'s prediction of one campaign ``frame`` under the rule, the grid as before and no
    grid (the same fitted model; only the grid set)."""
    from thermocomp.core.context import keeps_memory

    period = comp.__dict__.get("_sample_period_s")
    memory = any(keeps_memory(e, len(comp.selected_[t])) for t, e in comp.estimators_.items())
    out = {}
    for way, grid in (("rule", "own"), ("grid", period if memory else None), ("every", None)):
        comp.__dict__.pop("_grid_period_s", None)
        if grid != "own":
            comp.__dict__["_grid_period_s"] = grid
        out[way] = comp.predict({"c": frame})["c"][comp.targets_].to_numpy(float)
    comp.__dict__.pop("_grid_period_s", None)
    return out


def _rmse(measured, predicted) -> float:
    return float(np.sqrt(np.nanmean((measured - predicted) ** 2, axis=0)).mean())


def _memories(comp) -> dict:
    from thermocomp.core.context import counts_rows

    return {t: "rows" if counts_rows(e, len(comp.selected_[t])) else "time"
            for t, e in comp.estimators_.items()}


def mixed(where: str, *seeds: str) -> None:
    import pandas as pd

    from thermocomp.shell.model_store import load_model

    root = made_folder(where)
    lab_matrix.project(root)
    for seed in [int(s) for s in seeds] or MIXED_SEEDS:
        data = deploy73.mixed_record(root, seed)
        k03 = pd.read_csv(data / "K03.csv")
        for family, extra in FAMILIES.items():
            out = root / f"run-{seed}-{family}"
            rc, err, _ = lab_matrix.stage("run", f"data.path={data}", f"model={family}", *extra,
                                          "track=false", "plots=none", f"out={out}")
            if rc:
                print(f"{seed} {family}: run exit {rc}: {err[:200]}", flush=True)
                continue
            comp = load_model(out / "model.pkl")
            ways = three_ways(comp, k03)
            meas = comp.measured({"c": k03})["c"][comp.targets_].to_numpy(float)
            same = ways["rule"].tobytes() == ways["grid"].tobytes()
            print(f"{seed} {family}: memory {_memories(comp)} grid {comp.grid_period_s_}; K03 rule "
                  f"{_rmse(meas, ways['rule']):.4f} grid {_rmse(meas, ways['grid']):.4f} every "
                  f"{_rmse(meas, ways['every']):.4f}; rule {'byte-identical to' if same else 'DIFFERS from'}"
                  f" grid", flush=True)


def truth(where: str, *seeds: str) -> None:
    root = made_folder(where).resolve()
    lab_matrix.project(root)
    for seed in [int(s) for s in seeds] or TRUTH_SEEDS:
        base = between73.records(root, seed)
        for family in ("lagbank", "hammerstein"):
            out = base / "out" / f"mixed-{family}"
            rc, err, _ = lab_matrix.stage("run", f"data.path={base / 'mixed'}", f"model={family}",
                                          "track=false", "plots=none", f"out={out}")
            if rc:
                print(f"{seed} {family}: run exit {rc}: {err[:200]}", flush=True)
                continue
            comp, test, _, meas = between73._scored(out, base / "mixed")
            ways = three_ways(comp, test)
            print(f"{seed} {family}: memory {_memories(comp)} grid {comp.grid_period_s_}; 60 s "
                  f"stream vs truth rule {_rmse(meas, ways['rule']):.4f} grid "
                  f"{_rmse(meas, ways['grid']):.4f} every {_rmse(meas, ways['every']):.4f}", flush=True)


def digests(where: str, seed: str = str(TRUTH_SEEDS[0])) -> None:
    root = made_folder(where).resolve()
    lab_matrix.project(root)
    base = between73.records(root, int(seed))
    for family in DIGEST_FAMILIES:
        out = root / "digests" / family
        extra = FAMILIES.get(family, [])
        rc, err, _ = lab_matrix.stage("run", f"data.path={base / 'all300'}", f"model={family}",
                                      *extra, "track=false", "plots=none", f"out={out}")
        said = f"exit {rc}: {err[:200]}" if rc else \
            hashlib.sha256((out / "metrics.json").read_bytes()).hexdigest()
        print(f"{seed} all300 {family}: metrics.json {said}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"mixed": mixed, "truth": truth, "digests": digests}, argv,
                        cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
