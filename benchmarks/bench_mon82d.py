"""The rounding floor on the band that excludes only, the warning as shipped (mon82d): rule, bar.

    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon82d.py trunnion ROOT LABEL [SEEDS \
        [KINDS]]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon82d.py lathe ROOT LABEL [SEEDS [KINDS]]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon82d.py jig ROOT LABEL [SEEDS [KINDS]]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon82d.py table ROOT SHIPPED RULE

bench_mon82c's commands (its harness: ``thermocomp monitor``, MLR, a line per record in
``ROOT/<LABEL>.jsonl``; the code measured is the tree on ``PYTHONPATH``: ``/work/main/src``
shipped, the branch the rule) on fresh seeds: ``trunnion`` (stranger82b's trunnion centre,
8342 the found case and 8441-8442), ``lathe`` (stranger82's lathe, 8443-8444), ``jig``
(stranger80's jig borer, 8445-8446); kinds ``healthy,frozen,jump,drift,dropout``; ``table``:
bench_mon81's side by side.

Verdict: REFUSED (parts 3 and 4 failed; parts 1-2 held; below).

The rule (written before scoring): mon82c's rounding bound,
``(q / 2) · sum_k |(I - M)_jk / (1 - h_j)|`` (``q_k`` sensor ``k``'s smallest non-zero step in
training, every sensor in; 0 for a sensor not judged), is added to both bands only where they
exclude for drift (the drift judgement's trigger, ``Judgement._exclude_by_judgement``: a judged
sensor's error beyond ``band + bound`` at the field level); the warning / alarm states and their
events, the culprit pick, the re-admission and the instant detectors keep the bands as shipped.
mon82c floored both and lost test_monitor_regime73's warning (an offset within the rounding's
bound is still to be said; it is no fault to act on).  ``SensorMonitor.from_training`` fits
the bound (``exclude_margin_c``).  The exported watch (``export/watch.py``, its C) does not
carry it: a KEPT rule needs it there too before it ships (deployed = scored).

The bar (written before scoring; fresh seeds 8441-8446, none tuned on; REFUSED if any part fails):
1. Every fresh healthy draw (trunnion 8441-8442, lathe 8443-8444, jig 8445-8446): no exclusion
   where shipped has none, adaptive RMSE not > 1 % worse than shipped on each target.
2. 8342 (the found case, apart): quiet.
3. Every injected fault (frozen, jump, drift, dropout of each bench's ``faults``, on trunnion
   8441, lathe 8443, jig 8445): the faulted sensor excluded no later than shipped where shipped
   excludes it, adaptive RMSE not > 1 % worse.
4. The monitor test files pass (``tests/apps/test_monitor*.py``, ``tests/shell/test_monitor*.py``);
   ``test_monitor_healthy53``'s strict xfail turning to pass is allowed (its healthy column quiet
   is the wanted behaviour) and then becomes a plain test.

Scored (2026-12-04, shipped = ``/work/main/src`` at 61791dda, rule = 69ca16a0; the commands
as in the usage, each record shipped then rule; only the bar's kinds: healthy on every seed,
the faults on 8441 / 8443 / 8445).  Adaptive RMSE (µm) per target, shipped -> rule, and the
exclusions (count, first in h):

| record | kind | shipped exclusions | rule exclusions | adaptive RMSE shipped -> rule |
|---|---|---|---|---|
| trunnion 8342 (found) | healthy | RUNDTISCH, WIEGE 9.044 | none | 5.222 / 2.299 / 2.568 -> fixed |
| trunnion 8441 | healthy | none | none | 5.721 / 5.946 / 3.369 equal |
| trunnion 8442 | healthy | none | none | 9.282 / 3.409 / 1.212 equal |
| lathe 8443 | healthy | none | none | 1.547 / 4.169 equal |
| lathe 8444 | healthy | none | none | 2.221 / 6.291 equal |
| jig 8445 | healthy | none | none | 4.381 / 4.271 / 1.936 equal |
| jig 8446 | healthy | none | none | 2.461 / 1.193 / 1.449 equal |
| trunnion 8441 | frozen PINOLE | 6.667 | 6.667 | equal |
| trunnion 8441 | jump STAENDER_H | 5.556 | 5.556 | equal |
| trunnion 8441 | drift KUEHLUNG | none (no other predicts it) | none | equal |
| trunnion 8441 | dropout MUTTER_X | 6.667 | 6.667 | equal |
| lathe 8443 | frozen SPINDELKASTEN | none | none | equal |
| lathe 8443 | jump BETT_R | 5.556 | 5.556 | equal |
| lathe 8443 | drift KUEHLMITTEL | REVOLVER 5.5 | REVOLVER 6.05 | 1.679 / 3.989 -> 1.688 / 3.893 |
| lathe 8443 | dropout MUTTER_Z | 6.667 | 6.667 | equal |
| jig 8445 | frozen Pinole | 5.042 | 5.042 | equal |
| jig 8445 | jump Ständer_hinten_oben | 5.828 | 5.828 | equal |
| jig 8445 | drift Hydraulik_Tank | 7.797, 3x | 7.931, 2x | 3.927 / 4.714 / 2.327 -> 3.921 / 4.726 / 2.343 |
| jig 8445 | dropout Mutter_X | 6.661 | 6.661 | equal |

Part 1 held (no exclusion on any fresh healthy draw either way, RMSE equal to the printed
digit).  Part 2 held: 8342 quiet, adaptive = fixed (dX 5.222 -> 5.116, dY 2.299 -> 1.903,
dZ 2.568 -> 2.662, the exclusion's dZ gain chance, as in mon82c).  Part 3 FAILED: jig 8445's
drifting hydraulic tank (a sensor no other predicts: its drift judged through the others'
errors, now against the wider band) out 8 min later, 7.797 -> 7.931 h (it flaps less,
3 -> 2 exclusions; dY +0.25 %, dZ +0.7 %: within the 1 %, but the bar said no later).  Lathe
8443's coolant drift again takes the healthy turret out, 33 min later with the rule (+0.5 % dX, -2.4 % dZ).

Part 4 FAILED (the monitor test files with the rule: 1 failed, 140 passed, 4 xfailed; 153 s
wall): ``tests/shell/test_monitor.py``'s
``test_column_monitor_alarms_only_once_the_new_source_is_on_nearest_sensor_first``.  The
column simulation rounds to 0.01 K, so the bound is 0.011-0.032 °C per sensor (``T_right3``
0.015).  Shipped: ``T_right3`` (nearest to the new source Q3) excluded for drift at 73000 s
(+0.43 °C against 0.4), then a new thermal state; rule: the +0.43 does not clear 0.415 on
both samples, a sample later with ``T_right3`` out the others stay out of band (a new thermal
state at 73100 s, no exclusion), and the first alarm is ``T_left1``'s at 73700 s, not a nearest
sensor.  ``test_monitor_regime73`` passed (its warning kept: the band that warns is shipped's);
``test_monitor_healthy53``'s strict xfail stayed an xfail (its healthy column's exclusion, of
``T_right3`` at -0.17 °C for ``T_left1``'s 0.41, is not a rounding case).  The src change is
reverted; the rule is ``benchmarks/mon82d_rule.patch``.

Left: 8342's table / trunnion pair is still excluded on main.  A bound applied everywhere
delays every drift exclusion by up to its size, also a real fault's (the tank, the column's
source); a narrower rule would widen the band only for the quantisation's flicker (the last
``confirm`` errors' spread within the bound, the offset itself within training's?), not
scored.  The exported watch (``export/watch.py``, its C) would need the bound too.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_mon81 as m81  # noqa: E402
import bench_mon82c as m82c  # noqa: E402
from _cli import run_commands  # noqa: E402

KINDS = m82c.KINDS


def trunnion(root: str, label: str, seeds: str = "8342,8441-8442", kinds: str = KINDS) -> None:
    """stranger82b's trunnion centre, healthy and faulted (docstring)."""
    m82c.trunnion(root, label, seeds, kinds)


def lathe(root: str, label: str, seeds: str = "8443-8444", kinds: str = KINDS) -> None:
    """stranger82's lathe, healthy and faulted (docstring)."""
    m82c.lathe(root, label, seeds, kinds)


def jig(root: str, label: str, seeds: str = "8445-8446", kinds: str = KINDS) -> None:
    """stranger80's jig borer, healthy and faulted (docstring)."""
    m82c.jig(root, label, seeds, kinds)


def main(argv: list[str] | None = None) -> int:
    np.seterr(all="ignore")
    return run_commands(__doc__, {"trunnion": trunnion, "lathe": lathe, "jig": jig,
                                  "table": m81.table},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
