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
    python benchmarks/bench_mon97b.py others ROOT RECORD [RECORD ...]

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
does not contradict the held value), the stand-in past it.  ``others``: bench_mon97's other cases
(spike, frozen, dropout, step, drift) with the stand-in and with ``agree``: RMSE and the served
events (row, sensor, state), which the model's input does not feed.

Measured (2026-12-06, this branch = main 8ee3ec81's src; ROOT: copies of mon97's rule-tree
folders /tmp/mon97/seenr and /tmp/mon97/freshr, the models as fitted there; ``trace`` on the three
seen records 15.8 s CPU, ``others`` 34.6 s on the seen, 49.0 s on the five spent).  ``hold``'s RMSE
is main's to the digit (main flags nothing and reads the held value)::

    record  frozen       spread  60-row chg  RMSE standin / hold / agree (healthy)  |read-true| s / h / a
    cr9763  T_amb        0.118   1.625       1.6133 / 1.3041 / 1.4051 (1.3368)    0.100 / 0.033 / 0.074
    sw9776  T_amb        0.105   1.580       0.6545 / 0.6466 / 0.6422 (0.6424)    0.117 / 0.042 / 0.085
    lr9376  T_head_left  0.074   2.120       0.4908 / 0.5677 / 0.4897 (0.4955)    0.052 / 0.218 / 0.055

Why cr9763 costs 24 %: the room's true ambient stayed within 20.15-20.28 °C over the 60 frozen
rows, so the held 20.21 was near it (0.033 °C rms over the excluded rows); the stand-in read
-0.049 °C off at the exclusion (row 11) and drifted lower, -0.124 / -0.087 / -0.098 / -0.157 °C
at rows 20 / 30 / 40 / 50, mean -0.086 °C over rows 11-59 (a bias, not noise: 0.100 °C rms);
the model reads T_amb steeply enough that this costs 0.31 µm of RMSE over the case's 120 rows.
On lr9376 the frozen structure sensor's truth fell 0.27-0.29 °C below the held reading by rows
40-50 and the stand-in followed it (0.052 against 0.218 °C rms): holding costs +16 %.  The
brief's rate bound does not tell them apart: in training each frozen sensor moves 1.6-2.1 °C
over 60 rows (99.5th percentile), while the stand-ins err 0.07-0.12 °C; the ambient was still on
this test campaign, not in its training.  ``agree`` (k = 1, decided before its run, commit
18ca6124) helps all three seen (-13 % / -1.9 % / -0.2 %), and ``others`` shows it changes no
served event and no spike / step RMSE (dropout: 1.4292 -> 1.3595, 0.6426 -> 0.6409, 0.4046 ->
0.4003; drift the same).  On the five records mon97 spent as fresh (sw9815, cr9816, lr9817,
sw9818, cr9819; now seen) it does NOT hold up: frozen 0.8555 -> 0.8527, 2.6239 -> 2.6364,
1.2112 -> 1.2128, 1.4646 -> 1.4609, 1.7956 -> 1.8141 (2 better, 3 worse, -0.3 % .. +1.0 %),
dropout 2 of 5 worse (sw9815 0.8434 -> 0.8446, lr9817 1.0772 -> 1.0831), drift on the cr records
+0.0006 / +0.0002 µm; every served event the same.

VERDICT: TRACED.  No src change: the candidate was measured served-only (the model's input
patched in the bench, no C, no compensator.json key) and it improves the seen three but 2 of the
5 spent records; the 24 % is one campaign whose room stood still while its stand-in carried a
0.1 °C bias.  Not run: bench_freeze92's records (bar91b's ``score`` machinery; time).
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

from thermocomp.apps.deploy.surveillance.states import SPREAD_FACTOR  # noqa: E402

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

    base = Path(root).resolve()
    for record in records:
        made(base, record, "mlr", SEEN)
        deployed, ss, frame, lead, start, cid = faulted_cell(base, record, "mlr-none")
        model = base / "reports" / record / "mlr-none" / "model.pkl"
        _, ds, train_ids, _ = deployed_cell(base, record, model)
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


def others(root: str, *records: str) -> None:
    """The ``others`` rows (module doc)."""
    from bench_cmon92 import faulted_cell, made
    from bench_mon97 import _cases

    base = Path(root).resolve()
    for record in records:
        made(base, record, "mlr", SEEN)
        deployed, ss, frame, lead, start, cid = faulted_cell(base, record, "mlr-none")
        mon, targets = deployed.monitor, list(deployed.targets_)
        for kind, (sensor, part) in _cases(frame, start, list(mon.names), mon._predictable).items():
            j = list(mon.names).index(sensor)
            spread = float(np.atleast_1d(mon.floor_c)[j]) / SPREAD_FACTOR
            whole = pd.concat([frame.iloc[:start], part])
            said = []
            for hold in (0.0, spread):
                rows, read, out = _run(deployed, ss, whole, sensor, hold)
                events = [(i, e.get("sensor"), e.get("state")) for i, r in enumerate(rows[start:])
                          for e in r[1]]
                said.append((_rmse(rows[start:], part, targets), events, int(out[start:].sum())))
            (a, ea, n), (b, eb, _) = said
            print(f"{record} {kind:<8}{sensor:<18} excluded rows {n}; RMSE standin {a:.4f} -> agree "
                  f"{b:.4f} µm; served events {'the same' if ea == eb else 'DIFFER'} ({len(ea)})",
                  flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "others": others}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
