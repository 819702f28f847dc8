"""A long freeze of a predicted sensor counted only where the field moved past the sensor's
rounding (issue 34; stop 92, freeze92).  freeze91 (benchmarks/bench_freeze91.py,
benchmarks/freeze91_rule.patch: freeze90's rule, a predicted sensor constant past ``blind_run``
taken for frozen, served ``InstantFaults._frozen``, the export's mirror and C behind the
compensator.json key ``long_freeze``) passed bar91b's distance bar on fresh 9446-9455 (mean d
0.0456 -> 0.0228, faults detected 52 -> 64) and was REFUSED: on a settled machine read by a
noiseless 0.1 K logger (tests/apps/test_monitor_rounding83.py) each healthy sensor constant past
its ``blind_run`` went out as frozen.  The rule here adds one condition: the constant run counts
as a freeze only where the OTHER temperatures' prediction of the sensor (the field's estimate,
the freeze check's ``moved``) has moved since the run began by more than the sensor's rounding
bound ``rounding_c`` (mon83: the most the readings' rounding to their resolution moves its
self-prediction); a sensor that stays constant while its prediction stays within the rounding
is settled, not frozen.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_freeze92.py score ROOT SEEDS [FAMILIES]   # -> ROOT/score.json
    python benchmarks/bench_freeze92.py table MAIN RULE [RULE ...]    # the distance bar, per rule
    python benchmarks/bench_freeze92.py why ROOT SEED FAMILY          # one record per test campaign

``score``, ``why`` and ``table`` are bench_bar91b's (read its docstring: bench_bar91's ``score``
and ``why``, bar91b's distance bar), with this bench's fresh records in place of bar91b's:
``table`` reads the rows of the records :data:`FRESH` names only.

Trees scored (each ``git archive <commit> src conf`` under /tmp/freeze92/trees, ``PYTHONPATH``
its src, as bar91b / freeze91 built their trees): ``main`` (2b918bfd, this branch's base: mon89's
spike rule kept, no long freeze of a predicted sensor); ``freeze92`` (this branch's src: the rule).

Records: fresh 9456-9465, never drawn before this bench: 9456-9460 ``lr`` (bench_bar91's long
lathe record of 3 days, the generator's own temperature spikes), 9461-9465 ``cr`` (climate room
of 12 runs, bench_mon88's planted frozen ``T_amb`` and spike in each test campaign).  Every seed
scored before (freeze91's 9446-9455, bar91b's 9426-9435, bar91's 9416-9425 and the seen
9196-9205, 9291-9300, 9366-9375) is spent: it scores nothing here.

Bar (bar91b's, copied unchanged but for the fresh seeds and the base, plus the tests' clause
(e); written and committed BEFORE any record was drawn on any tree)
---
Row = (record, family, target); families mlr and lagbank; 10 records x 2 families x 2 targets
(E_X, E_Z) = 40 rows [the ``lr`` records have one target, E_Z, so 30 rows; the bar itself
unchanged].  d = |log(RMSE_deployed / RMSE_truth)| per row (the distance to the truth: an error
below the truth is as far from it as one above).  A rule PASSES if, over the 40 [30] rows of the
fresh records 9456-9465:

(a) mean d over rows is BELOW main's (to 4 decimals);
(b) no row has d_rule > d_main + log(1.02) (no row pushed more than 2 % further from the truth
    than main leaves it, whichever side);
(c) every TRUE record (nothing planted; the deployed stream on the true readings) has the same
    events as main's, event for event (campaign, time, sensor, state);
(d) the number of faults detected over all records and families is not fewer than main's;
(e) (freeze92, added by the brief) tests/apps/test_monitor_rounding83.py passes whole, and
    tests/apps/test_monitor_long_freeze91.py passes with its strict xfail marker removed; the
    monitor and export-monitor tests (tests/*/test_monitor*.py, tests/shell/test_export*mon*,
    tests/shell/test_export*freeze*) pass.
If the rule passes it is KEPT (its served change into src, a test failing on 2b918bfd, the
monitor tests, docs); if not, REFUSED with the table.  (a) strict ("below", not "not above") so
that a rule that changes no row of the fresh records, or moves none nearer, is not kept on no
evidence.  Here "main" is 2b918bfd and the one RULE is freeze92.  Reported beside the bar (not
the bar): mean d on the ``lr`` and the ``cr`` rows apart, and rows more than 2 % above the truth.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_bar91 as bar91  # noqa: E402
import bench_bar91b as bar91b  # noqa: E402
import bench_mon88 as mon88  # noqa: E402
from _cli import run_commands  # noqa: E402

FRESH = {**{seed: ("lr", mon88.LONG, ("data.reference=none",)) for seed in range(9456, 9461)},
         **{seed: ("cr", mon88.ROOM, ()) for seed in range(9461, 9466)}}
bar91.RECORDS.update(FRESH)     # bar91's score / why draw the records its RECORDS names
bar91b.FRESH = FRESH            # bar91b's table reads the rows of the records FRESH names


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"score": bar91.score, "table": bar91b.table, "why": bar91.why},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
