"""freeze90's long-freeze rule on top of mon89's spike rule, by bar91b's distance bar (issue 34;
stop 91, freeze91).  freeze90 (benchmarks/freeze90_rule.patch: a predicted sensor constant past
``blind_run`` taken for frozen; served ``InstantFaults._frozen``, the export's mirror and C
behind the compensator.json key ``long_freeze``) failed bar91b's bar on main before mon89 was
kept (clauses (a), (b): cr9435/mlr E_X +5.37 -> +9.03, log x 100) while it detected 42 -> 62
faults.  Here it is scored again ON TOP of mon89's spike rule (kept by bar91b, merged in this
branch's base 6d1f04a4), on records never drawn before.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_freeze91.py score ROOT SEEDS [FAMILIES]   # -> ROOT/score.json
    python benchmarks/bench_freeze91.py table MAIN RULE [RULE ...]    # the distance bar, per rule
    python benchmarks/bench_freeze91.py why ROOT SEED FAMILY          # one record per test campaign

``score``, ``why`` and ``table`` are bench_bar91b's (read its docstring: bench_bar91's ``score``
and ``why``, bar91b's distance bar), with this bench's fresh records in place of bar91b's:
``table`` reads the rows of the records :data:`FRESH` names only.

Trees scored (each ``git archive 6d1f04a4 src conf`` under /tmp/freeze91/trees, ``PYTHONPATH``
its src, as bar91b built its trees): ``base`` (6d1f04a4: mon89's spike rule kept); ``freeze90``
(the base with benchmarks/freeze90_rule.patch applied: served ``faults.py``, the export's mirror
and C).

Records: fresh 9446-9455, never drawn before this bench: 9446-9450 ``lr`` (bench_bar91's long
lathe record of 3 days, the generator's own temperature spikes), 9451-9455 ``cr`` (climate room
of 12 runs, bench_mon88's planted frozen ``T_amb`` and spike in each test campaign).  Every seed
scored before (bar91b's 9426-9435, bar91's 9416-9425 and the seen 9196-9205, 9291-9300,
9366-9375) is spent: it scores nothing here.

Bar (bar91b's, copied unchanged but for the fresh seeds and the base, and committed BEFORE any
record was drawn on any tree)
---
Row = (record, family, target); families mlr and lagbank; 10 records x 2 families x 2 targets
(E_X, E_Z) = 40 rows [the ``lr`` records have one target, E_Z, so 30 rows; the bar itself
unchanged].  d = |log(RMSE_deployed / RMSE_truth)| per row (the distance to the truth: an error
below the truth is as far from it as one above).  A rule PASSES if, over the 40 [30] rows of the
fresh records 9446-9455:

(a) mean d over rows is BELOW main's (to 4 decimals);
(b) no row has d_rule > d_main + log(1.02) (no row pushed more than 2 % further from the truth
    than main leaves it, whichever side);
(c) every TRUE record (nothing planted; the deployed stream on the true readings) has the same
    events as main's, event for event (campaign, time, sensor, state);
(d) the number of faults detected over all records and families is not fewer than main's.
If exactly one rule passes it is KEPT (its served change into src, a test failing on 6d1f04a4,
the monitor tests, docs); if several pass, the one with the lowest mean d; if none, REFUSED
with the table.  (a) strict ("below", not "not above") so that a rule that changes no row of
the fresh records, or moves none nearer, is not kept on no evidence.  Here "main" is the base
6d1f04a4 (mon89 kept) and the one RULE is freeze90 on top of it.  Reported beside the bar (not
the bar): mean d on the ``lr`` and the ``cr`` rows apart, and rows more than 2 % above the truth.

Scored
------
(not yet: filled in after scoring, below the bar above)
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

FRESH = {**{seed: ("lr", mon88.LONG, ("data.reference=none",)) for seed in range(9446, 9451)},
         **{seed: ("cr", mon88.ROOM, ()) for seed in range(9451, 9456)}}
bar91.RECORDS.update(FRESH)     # bar91's score / why draw the records its RECORDS names
bar91b.FRESH = FRESH            # bar91b's table reads the rows of the records FRESH names


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"score": bar91.score, "table": bar91b.table, "why": bar91.why},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
