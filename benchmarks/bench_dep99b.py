"""dl9878's ambient case, where the C still parted from served after dep99's out set: a jump of a
sensor the others predict with TWO already out (issue 34; stop 99, dep99b).

The lead measured on 90cf3c74 (dep99 merged; swap99's fresh records, ``bench_swap99.py cases``):
tr9876 ambient max|C - served| 49.2 -> 6.22e-12 µm, tr9877 24.6 -> 1.08e-12, but dl9878 ambient
19.3 µm with 1 row mirror != served.

TRACE (seen dl9878, ``trace``: bench_mon98's ambient case, ``T_amb`` +1 K/h from fed row 6120;
14 sensors, 9 modes, ``min_active`` 10).  Rows 815-823: served and the C alike out
``T_col_back`` and ``T_zdrive`` (the generator's faults), C = served (2.3e-13 µm).  Row 824:
``T_bed_right`` (the others predict it) jumps +2.95 °C (largest training step 0.17 °C).  Served
(``InstantFaults._instant`` -> ``_exclude``: no cap on the count out) re-references it and takes it
out as the THIRD (11 in, >= 10).  The C (``CodeMonitor._jump_held`` -> ``_second_held``, C
``mon_jump_held`` -> ``mon_second_held``) holds a jump beside those out only where a place is free
(``out2 < 0``, the cmon85 two-slot cap, which dep99 lifted for a range reading only): refused,
``SECOND`` flagged, the sensor stays IN as read, its +2.95 °C fed to the model: 19.3 µm on that
row (one row's jump through the model's T_bed_right weight).  Row 825: served re-admits it as a
spike (back +0.133 °C off the field, within 0.2); the C never took it out, its next reading is
back: = served again (2.3e-13).  Row 827: ``T_amb`` beyond range (30.67 °C), out as the third in
both (dep99's set): = served.  So 19.3 µm follows from one row, the jump, not the ambient.

RULE (dep99b; mirror ``CodeMonitor._second_held``, C ``mon_second_held``): a jump, like a range
reading (dep99), is held beside ANY number out, where the set's operator solves (``_operator`` /
``mon_operator``) and the sensor is one the code takes out for a jump (``_second_kind``:
predicted, or cmon89's blind spike rule): served takes a jump out whatever the set.  The
mirror's ``_jump_held`` now asks ``_second_held(j, JUMP)`` (it passed no rule; the C's
``mon_jump_held`` passed ``TC_MON_JUMP`` already).  No key: the cap lifted for jumps in the
code that has ``second_jump`` (an export without it flags as before).  Other rules (drift,
freeze, stepped, dropout) keep the two-slot cap.  Traced before the bar with the rule (seen
dl9878 ambient): row 824 the C takes ``T_bed_right`` out as the third (JUMP), 825 back as a SPIKE
with served, 827 ``T_amb`` out: every row 823-829 <= 2.3e-13 µm.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dep99b.py trace ROOT [LO HI [RECORD]]  # dl9878 ambient, drift rows
    python benchmarks/bench_dep99b.py cases ROOT RECORD [...]     # bench_mon98's cases
    python benchmarks/bench_dep99b.py compiled ROOT RECORD        # the compiled C's drifts

``trace``: RECORD's (default dl9878, swap99's fresh; simulated and run into ROOT where missing)
ambient case, drift rows LO..HI-1 (default 815 830): served's out set and events, the C mirror's set, rule and
sensor, the readings beyond range, |C - served| (µm).  ``cases`` / ``compiled``: bench_swap99's
(bench_mon98's healthy / drift / ambient cases; the compiled C, gcc -Werror) with :data:`FRESH`
added to its records.

Records.  SEEN: dl9878 (swap99's fresh, traced above), tr9876 / tr9877 (swap99's fresh),
bench_dep99's tr9828 / tr9873.  FRESH (never simulated before this bar's commit): dl9901, dl9902,
dl9903 (bench_cmon91's dl9377 generator, as dl9878: a column lathe kind with its generator's
faults, ``T_amb`` drifting past range in the ambient case while others are out).

BAR (written and committed BEFORE any of 9901-9903 is simulated; scored once; main = 90cf3c74's
src via ``git archive``, the rule this branch's; a ROOT per src, the same simulated data)
---
B1. seen dl9878 ambient: max|C - served| <= 1e-9 µm, 0 rows mirror != served (main 19.3 µm, 1
    row); the compiled C = served <= 1e-9 µm on its drift and ambient cases.
B2. bench_dep99 ``card`` tr9828 / tr9873 and bench_swap99 ``cases`` tr9876 / tr9877: every line
    as main's (CPU lines aside).
B3. every healthy frame (dl9878, tr9876, tr9877, the fresh): 0 rows apart, 0 µm (<= 1e-9).
B4. fresh dl9901-9903, healthy / drift / ambient, scored once: no case farther from served on the
    rule than on main (max|C - served| and rows apart); every case where the mirror holds a jump
    beside two or more out: C = served <= 1e-9 µm on that row and after it.  A case apart on both
    is said with its first parting row and rule, and counts against the bar if it parts at a jump.
B5. a test (tests/shell/test_export_dep99b.py, < 10 s) that fails on 90cf3c74 and passes on the
    rule; the C monitor export suites, test_export.py (PARSED_DIGEST), test_lint,
    test_benchmarks_cli pass.
KEPT if B1-B5 hold (src + C + test + docs); else REFUSED (benchmarks/dep99b_rule.patch, src as
90cf3c74), the numbers kept here.

Scored (bar 2020e389, the rule 04b32f9f committed after it, before any fresh seed was simulated;
2026-12-06 12:56-13:07 UTC under a load of 3-8 on 2 cores; main = ``git archive 90cf3c74 src``;
the fresh simulated and run by main's tree, the rule's read a copy of that ROOT).  CPU (user +
sys): ``card`` 13.6 / 16.9 s main / rule, ``cases`` tr9876 tr9877 dl9878 92.8 / 101.4 s, fresh
``cases`` 54.9 / 50.9 s, ``compiled`` dl9878 13.7 s, ``trace`` 7-8 s::

    record  case     main: max|C - served|, rows apart   rule
    dl9878  healthy  0 µm, 0                              the same
    dl9878  drift    1.42e-13, 0                          the same; compiled C 1.46e-13
    dl9878  ambient  19.3, 1 (row 824, SECOND)            1.06e-12, 0; compiled C 1.05e-12, nothing said
    tr9876  3 cases  0 / 2.84e-14 / 6.22e-12, 0 rows      the same (every line)
    tr9877  3 cases  0 / 7.11e-14 / 1.08e-12, 0 rows      the same (every line)
    card    tr9828 / tr9873 (bench_dep99)                 the same (every line, ``diff``)
    fresh   dl9901 healthy / drift / ambient              0 / 2.84e-14 / 2.84e-14, 0 rows: the same
    fresh   dl9902 healthy / drift                        0 / 2.84e-14, 0 rows: the same
    fresh   dl9902 ambient                                3.54 µm, 20 rows: the same (apart on both)
    fresh   dl9903 healthy / drift / ambient              0 / 2.84e-14 / 2.84e-14, 0 rows: the same

dl9902 ambient, traced after the score (``trace ROOT 993 996 dl9902``, the rule unchanged): at
drift row 994, ``T_col_back`` and ``T_amb`` (beyond range) out, served's stepped check (cmon86's
rule: its reason "jump: self-prediction error stepped +2.54 °C in one sample", four others
alarmed) takes ``T_head_left`` out as the third; the C's ``STEP_OUT`` keeps the two-slot cap:
``SECOND``, 3.54 µm that row, 0.04-0.09 µm on the rows after, 20 rows apart.  Not the one-sample
reading jump (``JUMP``) this rule lifts; the same shape of defect in another rule.

B1 MET (19.3 µm, 1 row -> 1.06e-12, 0; compiled C 1.05e-12 ambient, 1.46e-13 drift, nothing
"not in the code").  B2 MET (every line as main's).  B3 MET (every healthy frame 0 µm, 0 rows).
B4 MET as worded: no fresh case farther from served on the rule (every line identical to main's);
the one case apart on both parts at served's stepped-error rule (the C's ``STEP_OUT``), not at a
reading's jump (note: served words it "jump: self-prediction error stepped").  B5: see the report
(test_export_dep99b: 2.6 s call, fails on 90cf3c74 with ``SECOND`` at its row 35).
Next: the stepped rule (``STEP_OUT``) beside two or more out, as here (dl9902's row 994).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_swap99  # noqa: E402
from _cli import run_commands  # noqa: E402
from bench_mon98b import _dl  # noqa: E402

FRESH = {"dl9901": _dl(9901), "dl9902": _dl(9902), "dl9903": _dl(9903)}
bench_swap99.RECORDS.update(FRESH)      # swap99's commands read its records: the fresh ones too


def trace(root: str, lo: str = "815", hi: str = "830", record: str = "dl9878") -> None:
    """The ``trace`` lines (module doc)."""
    from bench_cmon92 import Stepped

    from thermocomp.apps.deploy.export.watch import RULES

    deployed, ss, frame, start, names, drifts = bench_swap99._cell(root, record)
    mon = deployed.monitor
    sensor, full = drifts["ambient"]
    print(f"{record} ambient: {sensor} from fed row {start}; n {len(names)}, modes {mon.pod.n_modes_}, "
          f"min_active {mon.min_active_}")
    run = Stepped(deployed, ss)
    X = full[ss.inputs].to_numpy(float)
    for i, (c, want, *_) in enumerate(run.rows(full.iloc[:start + int(hi)])):
        if i < start + int(lo):
            continue
        w = run.sim.watch
        x = X[i][w.idx]
        beyond = [names[k] for k in np.flatnonzero((x < w.a["lo_lim"]) | (x > w.a["hi_lim"]))]
        said = [(e.get("sensor"), e.get("to")) for e in deployed.last_events_]
        print(f"  {i - start}: served out {[names[k] for k in np.flatnonzero(~mon._active)]} {said}; "
              f"C out {[names[k] for k in w.gone]} rule {RULES[w.rule]} "
              f"{names[w.sensor] if w.sensor >= 0 else '-'}; beyond {beyond}; |C - served| "
              f"{np.max(np.abs(c - want)):.3g} µm", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "cases": bench_swap99.cases,
                                  "compiled": bench_swap99.compiled}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
