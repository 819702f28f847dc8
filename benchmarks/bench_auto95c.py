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
"""
from __future__ import annotations

import sys

from bench_auto95 import FRESH, RECORDS, SEEN, fit, many, nose, table  # noqa: F401
from _cli import run_commands  # noqa: E402


def main(argv: list[str]) -> int:
    commands = {"fit": fit, "nose": nose, "many": many, "table": table}
    return run_commands(__doc__, commands, argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
