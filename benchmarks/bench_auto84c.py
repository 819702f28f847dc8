"""``model=auto``'s lag bank and hammerstein candidates: the levels' shrink target (0 or MLR's
static fit) chosen on folds that extrapolate as new campaigns do (issue 34; stop 84, auto84c).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code and conf measured are that
tree's)::

    python benchmarks/bench_auto84c.py rows ROOT WORK [RECORD ...]   # the 22 records' rows
    python benchmarks/bench_auto80.py fl WORK                        # fl_thermal -> WORK/fl.jsonl
    python benchmarks/bench_auto84c.py fresh ROOT WORK               # this stop's fresh records
    python benchmarks/bench_auto84c.py bar OLD NEW OLDFRESH NEWFRESH # the verdict

``rows``, ``fresh`` and ``bar`` are bench_auto84b's (bench_auto84's ``rows ... as_is``, its bar's
five items unchanged), ``fresh`` on the same machines with this stop's seeds (:data:`FRESH`).

Why (bench_auto84b, REFUSED): the bank's CV, choosing between the levels shrunk towards 0 and
towards MLR's static fit (the anchor refitted per fold), picked MLR's on all 32 traced fits, its
CV error 4-95 % lower, where the new campaigns lose (swiss303 +10.9 %, tsc_a2 +8.2 %, the fresh
Swiss lathes +25 / +40 %) as where they win: the campaign folds share the training range, and the
losses sit where a new campaign's inputs leave it (bench_auto81b).

The rule (ONE rule, written and committed before anything below was scored)
---------------------------------------------------------------------------
auto84b's rule (``LagBank(anchor="cv")`` for auto's lag bank and hammerstein candidates, the
per-fold anchor, ``chosen_params`` carrying the choice) with one change: the CV chooses each
shrink target's penalty and level share as before (its campaign or forward folds), but the
shrink target itself on two *extrapolation folds*
(:func:`thermocomp.core.models.lagbank.extrapolation_folds`): the training rows ordered by their
projection on the standardised inputs' first principal direction and cut in ``n_splits`` blocks
(the bank's own fold count: the share each fold holds out, no new number), the lowest block held
out and the rest fitted, then the highest; each target scored at its own chosen penalty by the
mean validation MSE of the two folds, the anchor refitted on each fold's fitting rows, the lower
kept (ties: 0).  So each choice is scored where the held-out inputs lie past the fitting rows'
range.  No threshold fitted to the records; nothing else changes.

The bar (bench_auto84's five items as written there, unchanged; fails -> src and conf reverted,
the rule kept as ``benchmarks/auto84c_rule.patch``, REFUSED here)
----------------------------------------------------------------------------------------------
Record figure = mean over targets of the pooled test RMSE on the new campaigns (bench_automore69's);
OLD = the shipped rows (/tmp/auto80/new), NEW = this tree's (``rows ROOT WORK``).

1. the 22 records: the count where auto is worse than MLR on the new campaigns falls below 8;
2. the count where auto is better than MLR there does not fall (13);
3. no record's auto figure worse than shipped's by more than 2 %;
4. ``fl_thermal`` 90/10 auto mean test RMSE not worse than shipped (2.481 µm) by more than 1 %,
   and 60/20/20 auto's test MAE below the authors' GRU on >= 4 of 5 channels and on the mean;
5. fresh records of this stop's seeds 8801-8809 (never looked at; bench_auto84b ``fresh``'s
   machines, one train campaign each, scored on its own test and 3 new campaigns of its machine,
   seeds 8807-8809): the column (``column_moving_source``, 8801-8802), the Swiss lathe
   (``swiss_lathe_door``, 8803-8804), the lab mill (8805) and the mill week (8806), each with the
   shipped code (OLDFRESH: main's src and conf) and with the rule (NEWFRESH): the count worse
   than MLR on their new campaigns not higher, and the geometric mean of auto / MLR there not
   higher.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto84 as auto84  # noqa: E402
import bench_auto84b as auto84b  # noqa: E402
from _cli import run_commands  # noqa: E402

automore = auto84.automore
FRESH = {"col8801": ("column", ["sim=column_moving_source", "seed=8801"]),
         "col8802": ("column", ["sim=column_moving_source", "seed=8802"]),
         "swiss8803": ("swiss", ["sim=swiss_lathe_door", "seed=8803"]),
         "swiss8804": ("swiss", ["sim=swiss_lathe_door", "seed=8804"]),
         "labmill8805": ("lab_mill", [*automore.LAB_MILL, "seed=8805"]),
         "mill8806": ("mill", [*automore.remeasure.MILL, "seed=8806"])}
FRESH_NEW = [8807, 8808, 8809]       # the new campaigns of each fresh record's machine


def fresh(root: Path, work: Path) -> None:
    """The fresh records of :data:`FRESH` through bench_auto84's ``fresh`` -> WORK."""
    auto84b.FRESH, auto84b.FRESH_NEW = FRESH, FRESH_NEW
    auto84b.fresh(root, work)


def bar(old: Path, new: Path, oldf: Path, newf: Path) -> None:
    """bench_auto84's bar, the fresh records this stop's."""
    auto84b.FRESH = FRESH
    auto84b.bar(old, new, oldf, newf)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "fresh": lambda root, work: fresh(Path(root).resolve(), Path(work).resolve()),
        "bar": lambda old, new, oldf, newf: bar(Path(old), Path(new), Path(oldf), Path(newf)),
        "rows": lambda root, work, *names: auto84.rows(Path(root).resolve(), Path(work).resolve(),
                                                       "as_is", list(names)),
    }, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
