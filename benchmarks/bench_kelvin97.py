"""The exported C holds its correction when every input is out of range, as served (kelvin97,
issue 34: deployed as scored; audit97's finding 1).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's
served model, numpy mirror of the C and the C's arithmetic)::

    python benchmarks/bench_kelvin97.py faults ROOT [RECORD]   # bench_audit97's faults + all-NaN

``faults``: bench_audit97's ``faults`` on its FAULTED record (tr9828, trunnion63 seed 9828: seen,
spent by audit97; ROOT a copy of audit97's scratch, or built anew by it): the healthy frame,
spike / frozen / dropout / +3 degC step / +1 K/h drift, and the unit change (``kelvin``: every
``T_`` input +273.15 from the fault row, 60 rows), each stepped through the served model and the
C's numpy mirror together (bench_cmon92's ``Stepped``); then :func:`whole_dropout`: every input
of the model NaN from the fault row for 60 rows (a dropout of the whole logger).  Each line says
where each flags first and max |C - served| before and after (bench_audit96's ``first_flags``).

The rule (where, as audit97 traced it): the served monitor (surveillance/monitor.py ``_update``)
excludes every sensor out of range at once; nothing is left to rebuild the field from, so the
field the model reads is the last one (``_clean``) and the correction holds (E_Z 115.2 um).  The
C (``mon_beyond`` / numpy ``CodeMonitor._beyond``) does not hold several sensors out of range at
once: it flags NOT_IN_CODE RANGE and lets the sample pass the monitor by, the model reading the
kelvin values, so its correction climbs at the guard's rate limit (134.8 -> 185.45 um).  Mend:
where EVERY monitored reading is beyond its range (after a campaign's first sample) the sample
still passes the monitor by (its state as it was, flagged as before), but the model reads the
field of the last sample (each sensor's last reading in, the one out rebuilt from those), as
served: no new key.

BAR (written and committed BEFORE the rule's run; no fresh seeds, by the brief: time):
K1. kelvin (tr9828, mlr-none): max |C - served| <= 1e-9 um on every one of the 60 rows (was 70.2).
K2. the healthy frame and bench_audit97's other cases: C = served as before (max |C - served|
    after <= 1e-9 um each: audit97 measured 0 / 0 / 1.42e-14 / 0 / 7.11e-14 um), each monitor
    first flagging at the same row and naming the same sensor and rule as audit97's lines.
K3. whole dropout (every input NaN from the fault row, 60 rows): max |C - served| <= 1e-9 um on
    every row, with the rule as on main.
KEPT if K1-K3 hold with src (served unchanged; numpy mirror + C), a test failing on f59b6361
(tests/shell/test_export_kelvin97.py) and docs; else REFUSED or TRACED.

Status: the bar above committed in 596ed3c7 before the rule's run; unchanged.  ROOT: a copy of
audit97's scratch (``/tmp/audit97/faults``: tr9828 and its mlr-none model, built on b77996ba's
src), the same files for both runs.  "C" here is the numpy mirror of the C (bench_cmon92's
``Stepped``); the compiled C is held to it by tests/shell/test_export_kelvin97.py.

Scored (2026-12-06, 07:43-07:58 UTC, ``nice``, 2 cores shared, load 5-7): main = f59b6361's src
(``git archive``), 180.3 s CPU; the rule = c2f39d51, 166.5 s CPU:

  case      first flag (served; C)                    max|C - served| after (µm), main -> rule
  healthy   none; none                                 0 -> 0
  spike     0 T_ram jump; 0 T_ram JUMP                 0 -> 0
  frozen    11 T_ram freeze; 11 T_ram FREEZE           1.42e-14 -> 1.42e-14
  dropout   0 T_ram dropout; 0 T_ram DROPOUT           1.42e-14 -> 1.42e-14
  step      0 T_spindle_front jump; 0 ... JUMP         0 -> 0
  drift     148 new thermal state; 817 T_ram OFF_RANGE 7.11e-14 -> 7.11e-14
  kelvin    0 T_spindle_front range; 0 ... RANGE       70.2 -> 0   (C E_Z row 0/1/2/5: 134.82 /
            154.45 / 174.08 / 185.45 -> 115.2 every row; served 115.2; max |C| 185.4 -> 115.2)
  whole     0 T_spindle_front dropout; 0 MISSING_SECOND  0 -> 0  (9 inputs NaN, C held 115.2)

K1 holds (0 µm on every row).  K3 holds (as on main: the C's tc_step refuses the rows, its
correction held; the served model holds its field).  K2: every case as on main, flag rows,
sensors and rules the same; against audit97's lines one differs on main itself, not by the rule:
``frozen`` is flagged at fault row 11 (FREEZE, both monitors) on f59b6361's src where audit97 saw
no flag on b77996ba's (mon97's dithered freeze, merged between: 4917d42a).
VERDICT: KEPT (src: watch.py ``CodeMonitor._step``, watch_c.py ``monitor_step``; no key).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_audit96  # noqa: E402
import bench_audit97  # noqa: E402
from _cli import run_commands  # noqa: E402

WHOLE_ROWS = 60


def whole_dropout(root: Path, record: str) -> None:
    """Every input of the model NaN from the fault row for :data:`WHOLE_ROWS` rows (module doc)."""
    from bench_cmon92 import Stepped, faulted_cell

    deployed, ss, frame, lead, start, cid = faulted_cell(root, record, "mlr-none")
    names = list(deployed.monitor.names)
    part = frame.iloc[start:start + WHOLE_ROWS].copy()
    inputs = [c for c in deployed.columns_ if c in part.columns]
    part[inputs] = np.nan
    run, rows = Stepped(deployed, ss), []
    for c, want, *_ in run.rows(pd.concat([frame.iloc[:start], part])):
        w = run.sim.watch
        rows.append((float(np.max(np.abs(c - want))), list(deployed.last_events_), w.rule, w.sensor,
                     c, want))
    rows = rows[start:]
    for i in (0, 1, WHOLE_ROWS - 1):
        print(f"  whole row {i}: C {np.round(rows[i][4], 2)} served {np.round(rows[i][5], 2)}")
    print(f"  whole   {len(inputs)} inputs NaN from fault row 0 ({WHOLE_ROWS} rows): served flags "
          f"at {bench_audit96.first_flags(rows, names)}", flush=True)


def faults(root: str, record: str = "tr9828") -> None:
    """bench_audit97's ``faults`` and :func:`whole_dropout` (module doc)."""
    bench_audit97.faults(root, record)
    whole_dropout(Path(root).resolve(), record)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"faults": faults}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
