"""dl9902's ambient case, where the C still parts from served after dep99b: a stepped
self-prediction error (the C's ``STEP_OUT``) of a sensor with TWO already out (issue 34; stop
99, step99).

SEEN (bench_dep99b's fresh, traced after its score, ``bench_dep99b.py trace ROOT 993 996
dl9902``): at drift row 994 ``T_col_back`` and ``T_amb`` (beyond range) are out; served's
stepped check (cmon86's rule, reason "jump: self-prediction error stepped +2.54 °C in one
sample") takes ``T_head_left`` out as the third (``InstantFaults._exclude``: no cap on the count
out).  The C (``CodeMonitor._exclude`` -> ``_second_held``, C ``mon_exclude`` ->
``mon_second_held``) holds a STEP_OUT beside those out only where a place is free (``out2 < 0``,
cmon85's two-slot cap, lifted by dep99 for a range reading and dep99b for a jump): ``SECOND``,
3.54 µm that row, 0.04-0.09 µm after, 20 rows apart (main, 4b0de502).

RULE (step99; mirror ``CodeMonitor._second_held``, C ``mon_second_held``): a stepped error, like
a range reading (dep99) and a jump (dep99b), is held beside ANY number out where the set's
operator solves (``_operator`` / ``mon_operator``) and the sensor is one the others predict
(``_second_kind``, unchanged).  The same one clause: STEP_OUT joins OFF_RANGE and JUMP.  No key.
Drift (``DRIFT_OUT``) and freeze keep the cap (checked, not built: see the scored section).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_step99.py cases ROOT RECORD [...]     # bench_mon98's cases
    python benchmarks/bench_step99.py compiled ROOT RECORD        # the compiled C's drifts
    python benchmarks/bench_step99.py trace ROOT [LO HI [RECORD]]  # bench_dep99b's trace

bench_dep99b's commands (bench_swap99's ``cases`` / ``compiled``, bench_dep99b's ``trace``) with
:data:`FRESH` added to the records.

Records.  SEEN: dl9902 (traced above), dl9901 / dl9903 (bench_dep99b's fresh), dl9878, tr9876,
tr9877 (swap99's fresh).  FRESH (never simulated before this bar's commit): dl9907, tr9908,
dl9909 (bench_cmon91's dl9377 generator, as dl9878; the trunnion as tr9876; ``T_amb`` drifting
past range in the ambient case while others are out).

BAR (written and committed BEFORE any of 9907-9909 is simulated; scored once; main = 4b0de502's
src via ``git archive``, the rule this branch's; a ROOT per src, the same simulated data)
---
S1. seen dl9902 ambient: max|C - served| <= 1e-9 µm, 0 rows mirror != served (main 3.54 µm, 20
    rows); the compiled C (``compiled ROOT dl9902``) = served <= 1e-9 µm on its drift and
    ambient cases.
S2. ``cases`` tr9876 / tr9877 / dl9878 / dl9901 / dl9903 (the lines bench_dep99b / dep99 /
    swap99 scored): every line as main's (CPU lines aside).
S3. every healthy frame: 0 rows apart, 0 µm (<= 1e-9).
S4. fresh dl9907 / tr9908 / dl9909, healthy / drift / ambient, scored once: no case farther from
    served on the rule than on main (max|C - served| and rows apart); every case where the
    mirror holds a STEP_OUT beside two or more out: C = served <= 1e-9 µm.  A case apart on both
    is said with its first parting row and rule, and counts against the bar if it parts at a
    stepped error.
S5. a test (tests/shell/test_export_step99.py, < 5 s) that fails on 4b0de502 and passes on the
    rule; the C monitor export suites touched by the clause, test_export.py (PARSED_DIGEST),
    test_lint, test_benchmarks_cli pass.
KEPT if S1-S5 hold (src + C + test + docs); else REFUSED (benchmarks/step99_rule.patch, src as
4b0de502), the numbers kept here.

Scored (bar 053a0b9c, the rule d2c34dd2 committed after it, before any of 9907-9909 was
simulated; 2026-12-06 13:43-13:54 UTC under a load of 4-6 on 2 cores; main = ``git archive
4b0de502 src``; the seen ROOT a copy of bench_dep99b's, the fresh simulated and run by main's
tree, the rule's read a copy of that ROOT).  CPU (user + sys): seen ``cases`` 132.5 / 145.9 s
main / rule, fresh ``cases`` 90.7 / 76.3 s, ``compiled`` dl9902 11.9 s::

    record  case     main: max|C - served|, rows apart   rule
    dl9902  healthy / drift   0 / 2.84e-14, 0             the same
    dl9902  ambient  3.54 µm, 20 rows (row 994, SECOND)  1.42e-13, 0; compiled C 1.92e-13 (drift
                                                         1.28e-13), nothing "not in the code"
    dl9901, dl9903, dl9878, tr9876, tr9877 (15 lines)    the same (every line, ``diff``)
    fresh   dl9907 healthy / drift / ambient   2.84e-14 / 2.84e-14 / 8.53e-14, 0   the same
    fresh   tr9908 healthy / drift / ambient   0 / 5.68e-14 / 9.77e-15, 0          the same
    fresh   dl9909 healthy / drift / ambient   0 / 2.84e-14 / 2.84e-14, 0          the same

S1 MET (3.54 µm, 20 rows -> 1.42e-13, 0; compiled C <= 1.92e-13).  S2 MET (every line as
main's).  S3 MET (every healthy frame <= 2.84e-14 µm, 0 rows).  S4 MET: every fresh line
identical to main's, none apart on either (the fresh seeds did not part at a stepped error with
two out, so they test only that the rule changes nothing else).  S5: test_export_step99 fails on
4b0de502 (``SECOND`` at its row 35, mirror 0.175 µm off served on 45 rows), passes on the rule.

Drift and freeze beside two out, checked on test_export_step99's machine (rule tree, not built):
served's drift judgement excludes while more than ``min_active`` are in and its freeze check
has no cap, the C keeps the two-slot cap for both: ``T_d`` +0.85 °C for good (a drift exclusion
as the third) ``SECOND`` rows 36-39, 1.37 µm on 4 rows (the same on 4b0de502); ``T_c`` +0.6 °C
0.153 µm on 44 rows; ``T_a`` frozen with ``T_e`` / ``T_f`` out 30 rows: ``SECOND`` 1.09 µm on 24
rows.  They part the same way.  Not the same one line: the C's blind-out drift path
(``mon_second_held(u, TC_MON_DRIFT_OUT)``) and the ST's static freeze pairs read the same clause.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_dep99b  # noqa: E402  (adds dl9901-9903 to bench_swap99's records)
import bench_swap99  # noqa: E402
from _cli import run_commands  # noqa: E402
from bench_audit97 import TRUNNION  # noqa: E402
from bench_mon98b import _dl  # noqa: E402

FRESH = {"dl9907": _dl(9907), "tr9908": [*TRUNNION[1:], "seed=9908"], "dl9909": _dl(9909)}
bench_swap99.RECORDS.update(FRESH)      # swap99's commands read its records: the fresh ones too


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"cases": bench_swap99.cases, "compiled": bench_swap99.compiled,
                                  "trace": bench_dep99b.trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
