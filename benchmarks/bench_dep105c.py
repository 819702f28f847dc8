"""Several sensors jumping in one sample, a sensor no other predicts among them and too few left
to rebuild the field: the mirror and the C hold it as served (issue 34; stop 105, dep105c;
dep105b's pt10044).

dep105b (bench_dep105b.py) found fresh pt10044's C parting from served from its test campaign
W3's first row, on the base code, no fault planted.

TRACE (6c013931, pt10044 ``mlr-none``, W3 fed after W2 whole: ``data.reference=auto`` made
``none``, W3 continuing W2 by its time; the reader warns "a restart rather than one record?").
W3's first row (fed row 10080) steps T_bed -2.51, T_col_L -1.83, T_col_R -1.55, T_rail -1.00 degC,
each past 3x its largest training step (0.51 / 0.51 / 0.63 / 0.57).  Served (``_instant``: several
at once) re-references each by its step less its change as the sensors that did not jump predict
it (6 in < ``min_active`` 9: none predicted, its whole step), takes the 4 out (6 left in, the
field not rebuilt: T_col_R, no other predicts it, held at its last reading; no fallback served,
too few in) and re-admits all 4 at row 10092.  The code's ``pair_jump`` (cmon93) takes two jumpers
only: 4 flag ``NOT_IN_CODE`` (``COMMON``) and are read as they are, never re-referenced: C -
served 5.92 um at row 10080, 14.65 um from row 10140 to the end (2640 of 2640 W3 rows past 1e-9).
Served is right by its own contract (a campaign carried over is read as one record; the jump
rule is the served monitor's rule, scored by ``run``); the code lacks the rule.  Two gates in the
code: the count (``n_big == 2``) and, for T_col_R (``spikes``: cmon87's blind jump),
``_second_kind``'s "only where the field is rebuilt without them", which cmon89 set for a
DROPOUT (served feeds a dropped sensor's returned reading where too few are in); a jumper is no
dropped sensor: served holds it at its last reading whatever is in, and serves no fallback
while too few are in.

RULE (``watch.py`` / ``watch_c.py``): ``pair_jump``'s path takes two OR MORE jumpers in one
sample (each re-referenced by its step less its unjumped change, out in the monitor's order
where the code holds each in turn, else ``COMMON`` as before); a jump of one no other predicts
is taken beside those out whether or not the field is rebuilt (``_second_kind`` /
``mon_second_kind``).  No key, no state.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dep105c.py healthy ROOT RECORD [RECORD ...]

``healthy``: per record (bench_dep103's seen and fresh, bench_dep105 / 105b's fresh), the healthy
frame of its first test campaign, lead-in included, to bench_wires99's fault row + 120 (its
``_cell``, no fault planted; dep105b's frame):
mirror ``NOT_IN_CODE`` rows (first row, rule), max|mirror - served|, rows past 1e-9 um,
max|compiled - served|.

BAR (written and committed BEFORE the rule is run on any record but pt10044 (traced above);
base = ``git archive 6c013931 src``; no fresh seed drawn unless said)
---
P1 pt10044 ``healthy``: mirror and compiled C = served <= 1e-9 um on every row, 0 rows past it,
   0 ``NOT_IN_CODE`` (base: 2640 rows past, 1 ``NOT_IN_CODE``).
P2 no case moves: ``healthy`` on bench_dep103's 10 seen records + tr10045, cr10046 identical base /
   rule (``diff``, CPU aside); bench_dep105b ``whole`` on pt9851 tr9891 cr9892 tr10045 cr10046
   identical; bench_dep105 ``returns`` pt9851 identical.
P3 test_export_cmon93 (+ the new test, <= ~3 s CPU, failing on 6c013931), every
   tests/shell/test_export_* module importing watch / watch_c, tests/shell/test_replay*.py,
   test_lint, test_benchmarks_cli -k dep105c: pass.
KEPT if P1-P3 hold; else REFUSED (benchmarks/dep105c_rule.patch, src as 6c013931).

SCORED (bar 4fb41d9a, committed before the rule ran on any record but pt10044; unchanged; base =
``git archive 6c013931 src``, rule = a74364a7; roots: dep105b's seen and fresh roots copied, one
per tree, each building its own C; no fresh seed drawn; CPU (user + sys, /usr/bin/time, base /
rule, run side by side): ``healthy`` 46.5 / 46.6 s (8 records) + 5.6 / 5.7 s (5: one call printed
8 of its 13 lines and ended without an error; the other 5 were run again in a second call),
``whole`` 13.6 / 13.3 s, ``returns`` 12.0 / 11.7 s).

P1 MET: pt10044 mirror - served 3.06e-13 um, compiled - served 8.53e-13 um over 12720 rows, 0
past 1e-9, 0 ``NOT_IN_CODE`` (base: 14.7 um, 2640 rows past, ``COMMON`` at row 10080).
P2 MET: ``healthy`` on the 10 seen + tr10045 / cr10046 identical base / rule (``diff``: only
pt10044's line differs); ``whole`` (5 records, 10 lines) and ``returns`` pt9851 (7 lines) identical.
P3 MET: 40 tests/shell/test_export_* modules importing watch / watch_c + kelvin97 + cdrop77 +
lab75_deploy + test_replay + test_replay_run_name63 + test_lint: 137 passed (130.1 + 3.7 s CPU);
test_docs 45 passed; test_benchmarks_cli -k dep105c 2 passed; test_nines_deploy74, test_export_st94,
test_export_monitor76 7 passed.  New test (test_export_cmon93, five sensors stepping in one sample,
T_table no other predicts, too few left after the fourth): + 1.4 s CPU (module 8.0 -> 9.3 s, same
load); on 6c013931 it fails (``COMMON`` at row 1381).
Reported, not in the bar: bench_cmon94 ``trace`` pt9851 mlr-none sizes 2,3 (seen; 14.5 / 14.5 s):
spiked pairs same 32 -> 45 (13 flagged ``COMMON`` -> 0), spiked triples same 0 -> 41 (41 ``COMMON``
-> 0), freezes unchanged (32/13, 13/28), silent 0 both.  bench_dep105b ``whole`` pt10044: before the
fault max|C - served| 14.7 / 53.4 um, 2520 / 2529 rows past -> 3.06e-13 / 1.31e-12 um, 0 rows;
the whole dropout is still refused (``MISSING_SECOND``; dep105b's rule is not applied here).
How this differs from cmon94's patch (TRACED, not refused): cmon94 changed the mirror's ``== 2``
alone when the code had two places out, so nothing was held; dep101 / dep105 have since given the
code an out set of NM places, and this rule changes the C too and lifts the rebuild gate for a
blind jump.
VERDICT: KEPT.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests"), str(HERE.parent / "tests" / "shell")]
import bench_dep103  # noqa: E402
import bench_dep105  # noqa: E402
import bench_dep105b  # noqa: E402
from _cli import run_commands  # noqa: E402
from bench_dep101 import APART, _stream  # noqa: E402
from bench_wires99 import _cell  # noqa: E402


def healthy(root: str, *records: str) -> None:
    """The ``healthy`` lines (module doc)."""
    from bench_cmon92 import Stepped

    from thermocomp.apps.deploy.export.watch import NOT_IN_CODE, RULES

    base = Path(root).resolve()
    words = {**bench_dep103.SEEN, **bench_dep103.FRESH, **bench_dep105.FRESH, **bench_dep105b.FRESH}
    for record in records:
        deployed, ss, frame, lead, start, cid = _cell(base, record, words)
        run = Stepped(deployed, ss)
        c, served, missed = [], [], []
        for i, (ci, want, fl, rule, *_rest) in enumerate(run.rows(frame)):
            c.append(ci)
            served.append(want)
            if fl & NOT_IN_CODE:
                missed.append(f"{i} {RULES[rule]}")
        c, served = np.array(c), np.array(served)
        gap = np.abs(c - served).max(axis=1)
        compiled, stopped = _stream(base / "c" / record, deployed, ss, frame)
        print(f"{record} {cid}: {len(frame)} rows ({lead} lead-in); NOT_IN_CODE rows {len(missed)}"
              f"{' from ' + missed[0] if missed else ''}; max|mirror - served| {gap.max():.3g} µm, rows "
              f"past {int((gap > APART).sum())}; max|compiled - served| "
              f"{np.abs(compiled - served[:len(compiled)]).max():.3g} µm{stopped}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"healthy": healthy}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
