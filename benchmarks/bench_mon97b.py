"""A frozen slow ambient flagged: its stand-in against its held reading (issue 34; stop 97,
mon97b; bench_mon97's cost).

mon97 (benchmarks/bench_mon97.py) made both monitors flag a frozen dithered sensor 10-11 rows in
(FREEZE, excluded).  The excluded reading is then replaced by the monitor's stand-in (the POD
rebuild from the other sensors, ``SensorMonitor.update``'s clean row, which the model reads), and
on seen cr9763 the frozen case's RMSE over its 120 rows rose 1.304 -> 1.613 µm (+24 %).  This
bench traces why, row by row, and measures one candidate rule SERVED ONLY (no C): the frozen
sensor flagged but its held reading kept for the model (``hold``), against the rule as merged
(``standin``).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_mon97b.py trace ROOT RECORD [RECORD ...]

``trace``: per record of bench_mon97's :data:`~bench_mon97.SEEN` (made into ``ROOT`` as there,
each once) its frozen case (60 rows frozen + 60 after, bench_cmon92's ``planted``): per row the
true reading (the healthy frame), the held one and the stand-in the model reads, their errors
against the truth (°C), and the served compensation's RMSE over the case (µm, mean over targets)
with the stand-in and with the held reading kept (the same flags: only the model's input
differs).  Beside them, per frozen sensor, two candidate discriminants from training: the
stand-in's training spread (99.5th percentile of the windowed leave-one-out error, the monitor's
``floor_c`` / ``SPREAD_FACTOR``) and the reading's own change over 60 rows (99.5th percentile of
|T(t+60) - T(t)| over the training campaigns): hold where the reading moves less than its
stand-in errs.  A third mode, ``agree`` (decided before it was run: k = 1, no other tried): the
held reading kept while it is within the stand-in's training spread of the stand-in (the field
does not contradict the held value), the stand-in past it.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_mon97 import SEEN, _rmse  # noqa: E402

HOLD_ROWS = 60     # the change over the planted freeze's length (bench_cmon92.FREEZE_ROWS)


def _run(deployed, ss, frame, sensor: str, hold: float) -> tuple[list, np.ndarray, np.ndarray]:
    """``(rows as bench_audit95._stepped's, the sensor's value the model read per row, excluded
    per row)``; an excluded ``sensor`` read as it reads (its held value), not its stand-in, while
    the two differ by at most ``hold`` °C (0: the stand-in always; inf: the held value always)."""
    from bench_audit95 import _stepped

    col = list(deployed.columns_).index(sensor)
    j = list(deployed.monitor.names).index(sensor)
    read, out, inputs = [], [], deployed._inputs

    def seen(x, t, events, dt=None):
        row = inputs(x, t, events, dt)
        gone = not deployed.monitor._active[j]
        if gone and abs(row[col] - x[col]) <= hold:
            row = row.copy()
            row[col] = x[col]
        read.append(row[col])
        out.append(gone)
        return row

    deployed._inputs = seen
    try:
        rows = _stepped(deployed, ss, frame)
    finally:
        del deployed._inputs
    return rows, np.array(read), np.array(out)


def _moves(ds, train_ids, sensor: str, rows: int) -> float:
    """99.5th percentile of ``sensor``'s |T(t + rows) - T(t)| over the training campaigns (°C)."""
    d = [np.abs(c[sensor].to_numpy(float)[rows:] - c[sensor].to_numpy(float)[:-rows])
         for cid, c in ds.campaigns.items() if cid in train_ids and len(c) > rows]
    return float(np.quantile(np.concatenate(d), 0.995)) if d else float("nan")


def trace(root: str, *records: str) -> None:
    """The ``trace`` rows (module doc)."""
    from bench_cmon91 import deployed_cell
    from bench_cmon92 import faulted_cell, made, planted

    from thermocomp.apps.deploy.surveillance.states import SPREAD_FACTOR

    base = Path(root).resolve()
    for record in records:
        made(base, record, "mlr", SEEN)
        deployed, ss, frame, lead, start, cid = faulted_cell(base, record, "mlr-none")
        _, ds, train_ids, _ = deployed_cell(base, record, base / "reports" / record / "mlr-none" / "model.pkl")
        mon, targets = deployed.monitor, list(deployed.targets_)
        sensor = next(n for n, p in zip(mon.names, mon._predictable) if p)
        part = planted(frame, start, (sensor,), "freeze")
        whole = pd.concat([frame.iloc[:start], part])
        truth = frame[sensor].to_numpy(float)[start:start + len(part)]
        held = part[sensor].to_numpy(float)
        j = list(mon.names).index(sensor)
        spread = float(np.atleast_1d(mon.floor_c)[j]) / SPREAD_FACTOR
        healthy = _run(deployed, ss, frame, sensor, 0.0)[0][start:start + len(part)]
        print(f"{record} test campaign {cid}, frozen {sensor} from row {start} ({len(part)} rows); "
              f"stand-in's training spread {spread:.3f} °C, the reading's 60-row change "
              f"{_moves(ds, train_ids, sensor, HOLD_ROWS):.3f} °C; healthy RMSE "
              f"{_rmse(healthy, part, targets):.4f} µm", flush=True)
        for mode, hold in (("standin", 0.0), ("hold", np.inf), ("agree", spread)):
            rows, read, out = _run(deployed, ss, whole, sensor, hold)
            rows, read, out = rows[start:], read[start:], out[start:]
            flagged = np.flatnonzero(out)
            print(f"  {mode:<8} excluded rows {flagged.min() if len(flagged) else '-'}-"
                  f"{flagged.max() if len(flagged) else '-'} ({len(flagged)}); RMSE "
                  f"{_rmse(rows, part, targets):.4f} µm; |read - true| rms over the excluded rows "
                  f"{np.sqrt(np.mean((read[out] - truth[out]) ** 2)) if out.any() else 0:.3f} °C",
                  f"; held read on {int(np.sum(out & (read == held)))} of them", flush=True)
            if mode == "standin":
                standin, gone = read, out
        err_s, err_h = standin - truth, held - truth
        print("  row  true    held    stand-in  stand-in-true  held-true  excluded")
        for i in range(0, len(part), 10):
            print(f"  {i:>3}  {truth[i]:6.3f}  {held[i]:6.3f}  {standin[i]:7.3f}   {err_s[i]:+8.3f}"
                  f"      {err_h[i]:+7.3f}    {bool(gone[i])}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
