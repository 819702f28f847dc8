"""freeze90's long-freeze rule on top of mon89's spike rule, by bar91b's distance bar (issue 34;
stop 91, freeze91).  freeze90 (benchmarks/freeze90_rule.patch: a predicted sensor constant past
``blind_run`` taken for frozen; served ``InstantFaults._frozen``, the export's mirror and C
behind the compensator.json key ``long_freeze``) failed bar91b's bar on main before mon89 was
kept (clauses (a), (b): cr9435/mlr E_X +5.37 -> +9.03, log x 100) while it detected 42 -> 62
faults.  Here it is scored again ON TOP of mon89's spike rule (kept by bar91b, merged in this
branch's base 6d1f04a4), on records never drawn before.  REFUSED (src as on 6d1f04a4; the rule
as ported: ``benchmarks/freeze91_rule.patch``): it PASSES the bar below, but takes every healthy
sensor of a settled field on a 0.1 K logger out for a freeze (the monitor's own tests, below).

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

Scored (2026-12-05, after the bar's commit a1525963; each tree once, ``score ROOT 9446-9455`` ->
``table``; 10 records x 2 families = 20 record-families, 30 rows; CPU 28.8 s base, 29.1 s rule)
------
Trees: ``base`` = ``git archive 6d1f04a4 src conf``; ``freeze90`` = the same with
freeze90_rule.patch: ``faults.py`` applied whole (offset 41 lines), ``watch_c.py``'s C hunk
(offset 30) and ``watch.py``'s mirror hunk (offset 11); its three key-list hunks (``watch.py``'s
``monitor_fields`` and ``CodeMonitor`` defaults, ``watch_c.py``'s ``MON_*`` list) failed on
bar91b's ``spike`` key and were ported by hand (``long_freeze`` added after ``spike``)::

    row                      truth    main  freeze90   (truth RMSE µm; log(deployed / truth) x 100 per tree)
    lr9446/mlr E_Z          1.6331   +0.00     +0.00
    lr9446/lagbank E_Z      0.9485   -0.00     -0.00
    lr9447/mlr E_Z          1.0999   +0.00     +0.00
    lr9447/lagbank E_Z      0.7672   -0.20     -0.20
    lr9448/mlr E_Z          0.8277   +0.00     +0.00
    lr9448/lagbank E_Z      0.6706   +0.16     +0.16
    lr9449/mlr E_Z          1.3226   +0.00     +0.00
    lr9449/lagbank E_Z      0.7012   +0.09     +0.09
    lr9450/mlr E_Z          1.2157   -0.02     -0.02
    lr9450/lagbank E_Z      1.5496   -0.04     -0.04
    cr9451/mlr E_X          1.1252   +1.27     +1.60
    cr9451/mlr E_Z          1.7837   +2.43     +2.33
    cr9451/lagbank E_X      1.0088   +1.85     +1.14
    cr9451/lagbank E_Z      1.6551   +1.12     +0.35
    cr9452/mlr E_X          1.9501   -0.08     -0.42
    cr9452/mlr E_Z          2.5980   -0.12     -0.27
    cr9452/lagbank E_X      1.3211   +0.63     +0.61
    cr9452/lagbank E_Z      2.9148   +0.22     +0.89
    cr9453/mlr E_X          1.8600   +9.54     +0.38
    cr9453/mlr E_Z          3.2411   -0.40     -0.22
    cr9453/lagbank E_X      2.1037  +22.72     +1.74
    cr9453/lagbank E_Z      2.4708  +31.51     +4.26
    cr9454/mlr E_X          1.7058   +1.88     +0.13
    cr9454/mlr E_Z          3.2266   +2.92     +1.04
    cr9454/lagbank E_X      1.5450   +4.61     +5.11
    cr9454/lagbank E_Z      2.7217   +1.04     +1.48
    cr9455/mlr E_X          1.0940  +24.24    +22.46
    cr9455/mlr E_Z          1.6887  +27.15    +22.59
    cr9455/lagbank E_X      1.2037   +2.21     +0.80
    cr9455/lagbank E_Z      1.3033   +0.36     -0.13

    base: mean d 0.0456 (lr 0.0005, cr 0.0682); rows > 2 % above the truth 9; faults detected 52
    freeze90: mean d 0.0228 (lr 0.0005, cr 0.0340); rows > 2 % above the truth 5; rows past (b)
    0; true records with other events 0; faults detected 52 -> 64: PASSES (a)-(d)

The ``lr`` rows are identical (no long constant run on a noisy lathe); the ``cr`` rows move with
the frozen ``T_amb`` taken out earlier: cr9453/lagbank E_Z +31.51 -> +4.26, E_X +22.72 -> +1.74,
cr9453/mlr E_X +9.54 -> +0.38; the largest step away from the truth cr9452/lagbank E_Z +0.22 ->
+0.89 (within (b)).

Verdict: REFUSED, the bar passed.  The bar, written before scoring and unchanged, passed; with
the rule in src the monitor's tests (run after scoring: tests/apps/test_monitor*.py) failed 5:
test_monitor_rounding83.py's four (a warm-up settling on a noiseless 0.1 K logger: each healthy
sensor constant past its ``blind_run`` goes out for a freeze, T_5 at sample 301 ``freeze: 22.9 °C
for 62 samples (longest constant run in training 30)``, then T_b, T_3, T_a, T_4, T_0 ...: 18
exclusions where the tests assert one drift, or a warning alone), and test_monitor_frozen_pair77's
strict xfail XPASSED (the frozen ``T_a`` out alone: the rule closes that gap).  tests/shell/
test_monitor*.py: 121 passed, 1 failed (test_monitor_readmit88's partner test: T_amb now out
before the healthy cabinet is ever taken for it, the premise of the test gone: not a harm).  A
settled machine on a coarse logger is a record the bar's noisy simulations never draw; the rule
cannot be kept while it empties the monitor there.  Trace (served only, seen seeds, not scored
for a verdict): a guard "no long freeze while most sensors are past their ``blind_run``" leaves
the table above as the rule's, and does not mend rounding83 (its sensors settle one by one, the
first out while most still move): two of its tests still fail.  Kept: the gap as a strict xfail
(tests/apps/test_monitor_long_freeze91.py, 3 cases: a predicted sensor frozen on a still,
noisy field, the mirror as served; they pass with freeze91_rule.patch and fail on 6d1f04a4).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_bar91b as bar91b  # noqa: E402
from _cli import run_commands  # noqa: E402


def main(argv: list[str]) -> int:
    return run_commands(__doc__, bar91b.commands_on(9446), argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
