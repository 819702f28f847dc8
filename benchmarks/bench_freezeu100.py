"""A freeze of a sensor no other predicts, beside two or more out: the C as served (issue 34;
stop 100, freezeu100).

TRACE (SEEN: bench_dep100 ``machine``'s ``freeze_u``, test_export_dep99b's eight-sensor machine,
``T_e`` / ``T_f`` in kelvin rows 20-49, ``T_u`` (no other predicts it) held at its row-35 reading
from 35).  Served (surveillance/faults.py ``InstantFaults._check_freeze``) takes ``T_u`` out by
freeze at 46 as the third, no cap on the count out, its reading held at the last it read (a
sensor no other predicts is rebuilt as its last reading, cmon84).  The C (mirror
``CodeMonitor._exclude`` -> ``_second_kind``, C ``mon_exclude`` -> ``mon_second_kind``) takes a
second out only for one the others predict (``ported``), save cmon89's dropout / jump and dep99's
range reading of one no other predicts: a freeze of ``T_u`` with two out is ``SECOND`` (not in the
code), flagged at 46-50 and on, 0.177 µm / 16 rows apart on 063630e6 (compiled C the same, 2 "not in
the code" lines).  With ONE out (cmon84) the C already holds such a freeze (``drops``); the cap is
``_second_kind``'s, not the held place.  Served is right by docs/monitoring.md's contract (a
sensor no other predicts, once excluded, "is held at its last good reading ... for a frozen one
that is the frozen value"; served's ``_exclude`` has no count cap): the C is the one to mend.

RULE (freezeu100; mirror ``CodeMonitor._second_kind``, C ``mon_second_kind``): a freeze of one no
other predicts (``drops``: held at its last reading) counts as its dropout's kind beside those out
(under ``second_instant``, cmon89's flag): out where the field is rebuilt without it
(``in - 1 >= min_active``) and the set's operator solves (``_second_held``, unchanged).  No key.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_freezeu100.py planted ROOT RECORD [...]   # F3 / F4 on a record

F1 is bench_dep100.py ``machine`` (its ``freeze_u`` line), F2 bench_dep100.py ``machine``'s other
lines and bench_step99.py ``cases``.  ``planted``: bench_dep100's ``planted`` (the mlr-none cell,
its fault row a quarter into the test campaign, :data:`~bench_dep100.ROWS` rows from it) with the
cases of :func:`_parts`, fixed before any fresh record was drawn: ``healthy`` (nothing planted);
``two_out`` (the first two monitored sensors the others predict, not the air, in kelvin from the
fault row to the end); ``freeze_u`` (``two_out`` and the first monitored sensor no other predicts,
not the air, held at its reading at fault row + :data:`~bench_dep100.LATE` to the end);
``freeze_1`` (that freeze alone: cmon84's, one out).  Per case: max|C - served| µm, rows > 1e-9,
the first parting row and the mirror's rule there, served's exclusions, the count out at the end.

Records.  SEEN: the machine, bench_step99's records, dep100b's fresh dl9934 / sw9935 / cr9936
(spent; unpredicted: dl9934 ``T_spindle_front`` ..., sw / cr ``T_nc_spindle_motor``).  FRESH (never
simulated before this bar's commit): dl9943 (bench_cmon91's dl9377 generator), sw9944 (the Swiss
lathe), cr9945 (the climate room).

BAR (written and committed BEFORE any of 9943-9945 is simulated; scored once; main = ``git archive
063630e6 src``, the rule this branch's src; the fresh records simulated and run by main's tree, a
copy of the same ROOT read by the rule's)
---
F1. bench_dep100 ``machine``, rule: freeze_u max|C - served| <= 1e-9 µm and 0 rows > 1e-9, the
    mirror and the compiled C alike, nothing "not in the code" (main: 0.177 µm / 16 rows).
F2. bench_dep100 ``machine``'s drift_d / drift_c / freeze_a lines and every line of
    ``bench_step99.py cases`` dl9902 dl9901 dl9903 tr9876 tr9877 identical main / rule (``diff``,
    CPU lines aside).
F3. every ``planted`` ``healthy``, ``two_out`` and ``freeze_1`` line as main's (the same numbers and
    served events), fresh and seen.
F4. fresh dl9943 / sw9944 / cr9945 ``planted``, scored once: on the rule, every ``freeze_u`` case
    max|C - served| <= 1e-9 µm, 0 rows > 1e-9.  A case served does not take out by freeze (nothing
    to hold) is said and does not count for the rule.
F5. a test (tests/shell/test_export_freezeu100.py, < 5 s) that fails on 063630e6 (``SECOND`` at
    row 46) and passes on the rule; test_export_dep100 / dep99b / step99 / cmon85 / cmon89,
    test_export.py (PARSED_DIGEST: the ST text unchanged), test_lint, test_benchmarks_cli pass.
KEPT if F1-F5 hold (src + C + test + docs); else REFUSED (benchmarks/freezeu100_rule.patch, src as
063630e6), the numbers kept here.
Seen, measured before this bar (the rule built; 2026-12-06 16:37 UTC, load < 3; main = ``git archive
063630e6 src``; ``planted`` on copies of dep100b's ROOT, CPU 12.7 / 12.9 s main / rule)::

    case                    main: max|C - served|, rows apart (first, rule)   rule
    machine freeze_u        0.177 µm, 16 (46 SECOND); compiled the same,       7.11e-15, 0 (compiled
                            2 "not in the code" lines                          too, 0 such lines)
    machine drift_d/c, freeze_a  1.42e-14 / 7.11e-15 / 1.78e-14, 0           the same lines
    dl9934 freeze_u         14.5, 329 (31 SECOND; T_spindle_front)             1.14e-12, 0
    sw9935 freeze_u         2.91, 329 (31 SECOND; T_nc_spindle_motor)          1.02e-11, 0
    cr9936 freeze_u         8.11, 146 (31 SECOND; T_nc_spindle_motor)          5.68e-14, 0
    healthy / two_out / freeze_1 (all three)  0 / <= 8.53e-14 / 0, 0 rows     the same lines

(served takes the frozen one out at 31 as the third in each; the count out at the end 3 / 2 on
main, 3 / 3 on the rule.)

Scored (bar b27a5efe, the rule 9d364796 committed after it, before any of 9943-9945 was simulated;
2026-12-06 16:38-16:43 UTC under a load of 8-13 on 2 cores; main = ``git archive 063630e6 src``,
which simulated and ran the fresh records into one ROOT, the rule's src then read a copy of it).
CPU (user + sys) ``planted`` 18.4 / 13.2 s main / rule::

    case                    main: max|C - served|, rows apart (first, rule)   rule (9d364796)
    dl9943 freeze_u         30.2 µm, 329 (31 SECOND; T_spindle_front)          5.68e-14, 0
    sw9944 freeze_u         2.77, 329 (31 SECOND; T_nc_spindle_motor)          9.86e-12, 0
    cr9945 freeze_u         9.68, 137 (31 SECOND; T_nc_spindle_motor)          1.95e-14, 0
    healthy / two_out / freeze_1 (all three)  0 / <= 1.28e-13 / 0, 0 rows     the same lines (diff)

(dl9943: n 14, 8 modes, ``min_active`` 9, kelvin ``T_spindle_rear`` / ``T_head_left``; sw9944 and
cr9945: n 12, 7 modes, ``min_active`` 8, kelvin ``T_headstock`` / ``T_guidebush``; served takes
the frozen one out at 31, 12 samples constant, in each.)
F1 / F2 (2026-12-06 16:35-16:58 UTC, load 1-19; ``machine`` into fresh SCRATCH per src, CPU 2.7 /
3.0 s main / rule; ``bench_step99.py cases`` on copies of dep100's seen ROOT per src, CPU 154.7 /
156.4 s): ``machine``'s drift_d / drift_c / freeze_a lines identical main / rule (``diff``); the
37 lines of ``cases`` dl9902 dl9901 dl9903 tr9876 tr9877 identical (``diff``, CPU line aside),
every case there <= 6.22e-12 µm on both.

F1 MET (freeze_u 0.177 µm / 16 -> 7.11e-15 / 0, compiled C too, 0 "not in the code" lines).  F2
MET.  F3 MET (every healthy / two_out / freeze_1 line as main's, seen and fresh).  F4 MET (fresh
freeze_u <= 9.86e-12 µm, 0 rows; served took the frozen one out by freeze in all three).  F5: the
test fails on 063630e6 (AssertionError (46, 9): ``SECOND`` at 46) and passes on the rule (its call
7.3 s wall under a load of 12, the whole pytest process 5.4 s CPU with imports: the "< 5 s" not
shown on an idle machine); its export suites, test_export.py, test_lint, test_benchmarks_cli pass.
VERDICT: KEPT (F1-F4; F5 but for the idle timing).  Left alone: a freeze of one no other predicts
where the field is not rebuilt without it (``in - 1 < min_active``) stays ``SECOND``, as its
dropout (served has no cap there); the ST (no out set, dep99).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_dep100 import KELVIN, LATE, ROWS  # noqa: E402
from bench_dep100 import planted as planted_dep100  # noqa: E402
from bench_dep100b import FRESH as SEEN  # noqa: E402
from bench_mon97 import CR, SW  # noqa: E402
from bench_mon98b import _dl  # noqa: E402

FRESH = {**SEEN, "dl9943": _dl(9943), "sw9944": [*SW, "seed=9944"], "cr9945": [*CR, "seed=9945"]}


def _parts(frame, start: int, names: list[str], predictable) -> tuple[list[str], dict]:
    """``(the two in kelvin and the frozen one, {case: frame rows from start})`` (module doc)."""
    from thermocomp.core.io.contract import is_ambient

    kelvin = [n for n, p in zip(names, predictable) if p and not is_ambient(n)][:2]
    blind = [n for n, p in zip(names, predictable) if not p and not is_ambient(n)][:1]
    part0 = frame.iloc[start:start + ROWS].copy()
    two = part0.copy()
    two[kelvin] += KELVIN
    cases = {"healthy": part0, "two_out": two}
    for case, base in (("freeze_u", two), ("freeze_1", part0)):
        frozen = base.copy()
        col = frozen.columns.get_loc(blind[0])
        frozen.iloc[LATE:, col] = base.iloc[LATE, col]
        cases[case] = frozen
    return kelvin + blind, cases


def planted(root: str, *records: str) -> None:
    """The ``planted`` lines (module doc)."""
    planted_dep100(root, *records, table=FRESH, parts=_parts)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"planted": planted}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
