"""A frozen sensor's held reading against its stand-in, chosen from the stream's own past (issue
34; stop 105, mon105c; bench_mon97b's cr9763 +24 %).

Since mon97 a dithered sensor frozen past ``blind_run`` is excluded and the model reads its
stand-in (the POD rebuild from the others).  mon97b traced cr9763: the room's ambient stood
still, the held reading was 0.033 °C rms off the truth, the stand-in 0.100 (a drifting bias),
+24 % RMSE; on lr9376 the reverse (a structure sensor falling 0.28 °C: held 0.218, stand-in
0.052).  Training cannot tell them apart (each frozen sensor moves 1.6-2.1 °C over 60 rows in
training, its stand-in errs 0.07-0.12 °C); the stream's own past can.

RULE (measured served-only, ``SensorMonitor``; not in src: benchmarks/mon105c_rule.patch).
At a freeze exclusion the monitor fits the sensor's rate (least squares, °C/s) to its own readings over the
``EXCURSION_TAU_S`` = 1800 s before the constant run began (``TREND_ROWS`` kept).  The model reads
the HELD value instead of the stand-in while the drift that rate projects since the run began,
over at least the span the rate was fitted on, stays within the stand-in's training spread
(``floor_c`` / ``SPREAD_FACTOR``): |rate| x max(t - t0, span) <= spread.  A sensor that moved in
its recent past (lr9376: 0.13 °C over 1800 s against 0.074) gets the stand-in from its exclusion
on, as before; a still one (cr9763's ambient, 0.02 °C) keeps its held reading until the
projected drift reaches the spread.  No time, too few readings, spread 0 (a monitor fitted
without it): the stand-in, as before.  Flags and events are unchanged (only the model's input).

Chosen on dev data (seen cr9763, sw9776, lr9376 and mon97's spent 9815-9819; per record the
first predicted sensor, the first predicted ambient and the first predicted structure sensor;
14 cases), before the bar below.  Variants tried there (served, patched in a dev script):
a per-row switch without the span floor (lr9376 +2.0 %), a variance blend (cr9763 1.3091 > held
1.3041), the rate from the exponential memory ``_slow`` (lr9376 +4.1 %); the span floor with a
least-squares rate kept every case within +0.1 % of the stand-in and cr9763 at the held value.

Usage (``PYTHONPATH=<tree>/src``; the code measured is that tree's: the rule's is a tree with
benchmarks/mon105c_rule.patch applied)::

    python benchmarks/bench_mon105c.py frozen ROOT RECORD [RECORD ...]

``frozen``: per record (:data:`SEEN`, bench_mon97's FRESH as spent, :data:`FRESH`; simulated and
``run model=mlr`` into ROOT once, bench_cmon92's ``made``) its healthy frame's served events and
per frozen case (bench_cmon92's ``planted`` 60 rows + 60, from a quarter in; the sensors above)
the served RMSE over the case (µm, mean over targets), the RMSE with the held reading read while
the sensor is out (``hold``, mon97b's), and the case's served events.

BAR (written and committed BEFORE any of fresh 10038-10040 was simulated; scored once, main =
4b70457f's src and this branch, each run on the same ROOT's fitted models)
---
M1. seen cr9763 T_amb frozen: the rule's RMSE <= the held reading's (1.3041 µm on main).
M2. mon97b's other frozen cases (sw9776 T_amb, lr9376 T_head_left, the five spent records' first
    predicted sensor): the rule's RMSE no worse than main's by more than 1 %.
M3. healthy frames: the served events identical to main's (sw / cr: 0); every frozen case's
    served events identical to main's (the rule moves no flag).
M4. tests/shell/test_monitor*.py and tests/apps/test_monitor_*.py pass.
M5. fresh cr10038, sw10039, lr10040 (bench_mon97's generators, these seeds), each frozen sensor
    above (ambient and structure): the rule's RMSE no worse than main's by more than 1 % on
    every case, and lower than main's on every still-room case (an ambient case where main's
    ``hold`` beats main's stand-in by more than 1 %).
KEPT if M1-M5 hold; else REFUSED (benchmarks/mon105c_rule.patch, src as on 4b70457f).

Measured (2026-12-07; ``frozen`` on one ROOT /tmp/mon105c/root, its models fitted once by main's
src, ``PYTHONPATH`` main = ``git archive 4b70457f src``, then this branch, one after the other;
CPU user+sys: dev 8 records 27.5 / 29.7 s, fresh 3 records 14.9 (simulation included) / 13.0 s).
RMSE µm over the case's 120 rows, main -> rule (main's ``hold``)::

    seen   cr9763  T_amb           1.6133 -> 1.3041 (1.3041)   M1 met: = held
           cr9763  T_headstock     1.4994 -> 1.4994 (7.2011)
           sw9776  T_amb           0.6545 -> 0.6466 (0.6466)   -1.2 %
           sw9776  T_headstock     0.6397 -> 0.6397 (0.6514)
           lr9376  T_head_left     0.4908 -> 0.4908 (0.5677)
    spent  sw9815  T_amb           0.8555 -> 0.8518 (0.8518)   -0.4 %
           sw9815  T_headstock     0.8558 -> 0.8558 (0.8512)
           cr9816  T_amb           2.6239 -> 2.6271 (2.6278)   +0.12 %
           cr9816  T_headstock     2.6327 -> 2.6327 (4.4433)
           lr9817  T_spindle_rear  1.2112 -> 1.2128 (1.2128)   +0.13 %
           sw9818  T_amb           1.4646 -> 1.4589 (1.4589)   -0.4 %
           sw9818  T_headstock     1.4691 -> 1.4691 (1.4672)
           cr9819  T_amb           1.7956 -> 1.7956 (1.7064)   (its past moved: stand-in)
           cr9819  T_headstock     1.8179 -> 1.8179 (1.9017)
    fresh  cr10038 T_amb           5.1005 -> 5.0995 (5.0995)   -0.02 %
           cr10038 T_headstock     4.9883 -> 4.9883 (6.0903)
           sw10039 T_amb           1.5250 -> 1.5305 (1.5311)   +0.36 %
           sw10039 T_headstock     1.5293 -> 1.5293 (1.5587)
           lr10040 T_head_right    0.8045 -> 0.7955 (0.7824)   -1.1 % (no predicted ambient there)

M1 met.  M2 met (worst +0.13 %, lr9817).  M3 met: every healthy frame's and every frozen case's
served events identical, main and rule (diffed).  M4 met: tests/apps/test_monitor_*.py (with
the new test_monitor_frozen_hold105) passed 1 xfailed (frozen_pair77's, as on main) and
tests/shell/test_monitor*.py 130 passed 2 xfailed.
M5 met: no fresh case worse than main by more than 1 % (worst sw10039 T_amb +0.36 %); its
still-room clause had no case to score: no fresh ambient case had main's ``hold`` better than its
stand-in by more than 1 % (cr10038 0.02 %, sw10039 worse), so "better on the still-room ones"
is met only vacuously.  The one fresh case where holding paid (lr10040's structure sensor,
hold -2.7 %) the rule took -1.1 %.

VERDICT: REFUSED, the bar met but the branch not green.  M1-M5 hold served-only, but the
mirror and the C read the stand-in still, so served and code part on a still sensor's frozen
rows, and the export's own check pack plants such a freeze: tests/shell/test_export_inputs_product62
(test_the_export_commands_check_pack_passes_for_it) and test_export_atiprod65
(test_the_export_command_writes_it_and_its_check_pack_passes) fail with the rule (the pack
cuts K09.freeze.T_b at row 37, "the served model's sensor monitor acted there, which is not in
the code": 6 of 7 cases checked, the test wants 7); both pass on 4b70457f (29 passed).  A rule
that breaks modules outside the bar is reverted, so src is as on 4b70457f; the rule, its test
(tests/apps/test_monitor_frozen_hold105.py: 3 tests, 2.1 s CPU, 2 fail on 4b70457f) and its
docs/monitoring.md paragraph are in benchmarks/mon105c_rule.patch (``git apply`` from the root).
Its served cost per row: one ring write; ``SensorMonitor.update`` over 2 x 20000 rows, 3 pairs
main / rule 14.95 / 15.59 s CPU (+4 %, within the pairs' own spread 4.7-6.0 s).

To land it, the code needs the rule too (then the pack checks the held rows as served):
``spread_c`` per sensor (``floor_c`` / ``SPREAD_FACTOR``) in compensator.json's monitor; a ring of
TREND_ROWS referenced readings and their times in the code's state (mirror watch.py's
CodeMonitor, watch_c.py's tc_state and its --state file: 128 x n doubles + 128 times); the
least-squares rate at a freeze exclusion by the run alone and its ``hold_to`` time; the clean
row's held value while ``time <= hold_to`` and no reading off it; an export without the key:
the stand-in, as before.  The ST block does not take the freeze (unchanged).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_mon97 import CR, LR, SEEN, SW, _rmse  # noqa: E402
from bench_mon97 import FRESH as SPENT  # noqa: E402

FRESH = {"cr10038": [*CR, "seed=10038"], "sw10039": [*SW, "seed=10039"],
         "lr10040": [*LR, "seed=10040"]}


def frozen_sensors(mon) -> list[str]:
    """The first predicted sensor, the first predicted ambient and the first predicted structure
    sensor (each once)."""
    from thermocomp.core.io.contract import is_ambient

    pred = [n for n, p in zip(mon.names, mon._predictable) if p]
    amb = next((n for n in pred if is_ambient(n)), None)
    struct = next((n for n in pred if not is_ambient(n)), None)
    return [s for s in dict.fromkeys([pred[0], amb, struct]) if s is not None]


def frozen(root: str, *records: str) -> None:
    """The ``frozen`` rows (module doc)."""
    from bench_audit95 import _stepped
    from bench_cmon92 import faulted_cell, made, planted
    from bench_mon97b import _run

    base = Path(root).resolve()
    for record in records:
        made(base, record, "mlr", {**SEEN, **SPENT, **FRESH})
        deployed, ss, frame, lead, start, cid = faulted_cell(base, record, "mlr-none")
        targets = list(deployed.targets_)
        healthy = _stepped(deployed, ss, frame)
        print(f"{record} test campaign {cid}, faults from row {start}; healthy served events "
              f"{[(i, e.get('sensor'), e.get('to')) for i, r in enumerate(healthy) for e in r[1]]}",
              flush=True)
        for sensor in frozen_sensors(deployed.monitor):
            part = planted(frame, start, (sensor,), "freeze")
            whole = pd.concat([frame.iloc[:start], part])
            rows = _stepped(deployed, ss, whole)[start:]
            held = _run(deployed, ss, whole, sensor, np.inf)[0][start:]
            events = [(i, e.get("sensor"), e.get("to")) for i, r in enumerate(rows) for e in r[1]]
            ok = _rmse(healthy[start:start + len(part)], part, targets)
            print(f"  {sensor:<18} RMSE {_rmse(rows, part, targets):.4f} hold "
                  f"{_rmse(held, part, targets):.4f} (healthy {ok:.4f}) µm; served events {events}",
                  flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"frozen": frozen}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
