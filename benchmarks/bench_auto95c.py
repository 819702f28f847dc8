"""``reach=memory`` as bench_auto95's "next" inside ``model=auto``'s votes on ONE-campaign training
(issue 34; stop 95, auto95c): on forward folds of one record (1) the lag families (those with a
``tau_max_s``: lagbank / hammerstein, 48 h) are ranked among themselves on ALL the voting folds (the
share of resamples each wins among them, as main's votes draw) and all but the first dropped; (2)
that one is compared with the static families on the folds whose fit rows span its memory (none:
its last fold), those folds resampled by their blocks (bench_auto95's ``voting``); the static ones
on every fold (the same draws); (3) the one-SE fallback judges the blend on each fold from the
members judged there (their weights renormalised; a fold none of the weighted ones is judged on
left out, fewer than 2 folds: no fallback).  ``AutoRegressor._best_lag`` / ``_judged_blend``,
key ``model.estimator.reach`` (default ``all``: main).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``; the commands are bench_auto95's)::

    python benchmarks/bench_auto95c.py fit OUT RECORD ...   # fit auto (reach all / memory) + MLR, save
    python benchmarks/bench_auto95c.py nose OUT RECORD ...  # the same, auto's one-SE fallback off
    python benchmarks/bench_auto95c.py many OUT             # a many-campaign record: both ways identical?
    python benchmarks/bench_auto95c.py table OUT RECORD ... # test RMSE / MLR's per record, the bar

Records (:data:`RECORDS`): bench_auto94c's ten seen (sw9697 lr9587 sw9696 lr9211 lr9212 lr9640 and
lr9639-lr9643) and the fresh 9719-9728 (bench_auto95's :data:`FRESH`: 9719-9723 long_record 3 days,
9724-9728 swiss_lathe_door 8 h calibration + 4 h production).

BAR (bench_auto95's, unchanged, clause by clause; committed before the seen ``fit`` is run with
this rule and before any FRESH seed is simulated): (1) on bench_auto94b's 6 named records (sw9697
lr9587 sw9696 lr9211 lr9212 lr9640) the rule's auto / MLR (mean over targets of test RMSE / MLR's)
below main's on >= 4 and above main's by > 1 % on none; (2) on bench_auto94c's 10 seen records the
geometric mean of auto / MLR not above main's (0.766), and no record's rule / main > 1.01; (3) the
FRESH records 9719-9728, scored once: geo auto / MLR not above main's, no record's rule / main >
1.02; (4) a many-campaign record (yearround_spindle seed 101) identical both ways (``many``).  All
four: KEPT.  (1) or (2) failing on the seen records: REFUSED, src reverted,
``benchmarks/auto95c_rule.patch``, the fresh seeds NOT drawn.

REFUSED on the SEEN gate: src as on main; the rule is ``benchmarks/auto95c_rule.patch`` (against
da11b4dd: bench_auto95's patch plus ``_best_lag`` / ``_judged_blend``; src + conf + bench_auto95's
vote_weights test: apply it to run ``fit`` / ``nose`` / ``many``, whose ``reach`` key main does not
have).  No fresh seed drawn (9719-9728 stay fresh).

Measured (2026-12-06, da11b4dd + the patch; nice, ``OMP_NUM_THREADS=1``, 2 cores shared by up to 8
helpers: ``fit`` on the 10 seen 47.6 s CPU / 49 s wall, ``nose`` 49.9 s / 93 s, ``many`` 11.9 s).
Auto's test RMSE / MLR's, mean over targets; main = ``reach=all`` (bench_auto95's main column to
0.001); auto95 = bench_auto95's refused rule (its table); nose = this rule with the one-SE fallback
off (a trace; main with it off differs on lr9639 only, 1.000 -> 0.928)::

  record  main   auto95  rule   rule/main  nose   weights main -> rule (E_Z; sw9697 E_X)
  sw9697  1.044  1.049   0.844  0.808      0.844  E_X mlr .41 pcr .40 hammerstein .17 -> hammerstein 1.0
  lr9587  1.059  1.000   1.000  0.944      1.007  mlr .86 lagbank .10 lstm .03 -> mlr 1.0
  sw9696  0.567  0.567   0.567  1.000      0.567
  lr9211  0.761  1.000   1.211  1.592      1.211  mlr .43 hammerstein .54 lagbank .04 -> hammerstein 1.0
  lr9212  0.760  0.755   0.755  0.992      0.755  hammerstein .77 -> .83
  lr9640  0.858  1.000   1.000  1.165      0.744  votes hammerstein .58 mlr .42; one-SE: MLR kept
  lr9639  1.000  1.000   0.499  0.499      0.499  mlr 1.0 -> hammerstein 1.0
  lr9641  0.637  1.329   0.617  0.969      0.617  hammerstein .95 lagbank .05 -> hammerstein .88 mlr .12
  lr9642  0.674  0.674   0.674  1.000      0.674
  lr9643  0.519  0.519   0.519  1.000      0.519  lagbank 1.0 both ways
  geo     0.766  0.855   0.737

Against the bar (unchanged): (1) fails: better than main on 4 of 6 (sw9697, lr9587, lr9212, sw9696 by
0.002 %), worse by > 1 % on lr9211 (+59 %) and lr9640 (+17 %); (2) fails on its second clause:
geo 0.737 below main's 0.766, but 2 records worse by > 1 % (lr9211, lr9640); (4) met: ``many``
(yearround_spindle seed 101, 16 campaigns, leave-campaigns-out on all three targets) weights and
test predictions identical both ways.  REFUSED; (3) not drawn.  (1) of the rule does what it was
built for: lr9641 is no longer handed to lagbank (auto95 1.329 -> 0.617, below main's 0.637), and
sw9697 / lr9639 gain 19 % / 50 %.  Why it still fails (fold SSE / MLR's from a trace of the fits,
folds' fit spans 26.0 / 31.7 / 37.5 / 43.2 / 49.0 h, the 48 h families reach fold 5 only):
* lr9211: hammerstein ranks first of the lag families on all folds (0.272 2.259 0.092 0.661 0.187
  against lagbank 1.183 3.446 0.068 0.333 0.305), wins fold 5 on every block resample (0.187) and
  tests 1.211 x MLR; main's blend (MLR .43 with it) 0.761.  With hammerstein 1.0 judged on one fold
  no one-SE variant that uses the members' own folds falls back (nose 1.211 too): the 48 h fold's
  verdict alone loses this record, as bench_auto95 found.
* lr9640: hammerstein .58 / MLR .42 on fold 5 (0.930 both lag families); (3) as built counts
  folds 1-4 with MLR alone judged there (ratio 1): 0.928 +- 0.072 over 5 folds, MLR kept (1.000).
  Judged on fold 5 alone (no fallback: nose) it tests 0.744, below main; that variant is not
  built: lr9211 fails the bar either way.
Next (not built): the lag families' one reaching fold cannot say whether one beats MLR (lr9211);
a rule that keeps main's all-fold votes and only moves weight among the lag families (their
ranking, (1) here) touches none of MLR's share.
"""
from __future__ import annotations

import sys

from _cli import run_commands
from bench_auto95 import FRESH, RECORDS, SEEN, fit, many, nose, table  # noqa: F401


def main(argv: list[str]) -> int:
    commands = {"fit": fit, "nose": nose, "many": many, "table": table}
    return run_commands(__doc__, commands, argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
