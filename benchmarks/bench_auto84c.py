"""``model=auto``'s lag bank and hammerstein candidates: the levels' shrink target (0 or MLR's
static fit) chosen on folds that extrapolate as new campaigns do (issue 34; stop 84, auto84c).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code and conf measured are that
tree's; a NEW tree and ``cv`` need the rule, ``git apply benchmarks/auto84c_rule.patch``: REFUSED,
below)::

    python benchmarks/bench_auto84c.py rows ROOT WORK [RECORD ...]   # the 22 records' rows
    python benchmarks/bench_auto80.py fl WORK                        # fl_thermal -> WORK/fl.jsonl
    python benchmarks/bench_auto84c.py fresh ROOT WORK               # this stop's fresh records
    python benchmarks/bench_auto84c.py bar OLD NEW OLDFRESH NEWFRESH # the verdict
    python benchmarks/bench_auto84c.py cv ROOT RECORD ...            # the banks' choice, per target

``rows``, ``fresh`` and ``bar`` are bench_auto84b's (bench_auto84's ``rows ... as_is``, its bar's
five items unchanged), ``fresh`` on the same machines with this stop's seeds (:data:`FRESH`).
``cv``: per target of a record (one of the 22 or :data:`FRESH`'s), auto fitted on its train
campaigns, and per kept lag bank or hammerstein member the shrink target chosen and both targets'
CV MSE on the campaign folds and on the extrapolation folds (needs the rule).

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

Scored (2026-12-04; OLD = /tmp/auto80/new and main's src and conf on the fresh records (main
4fc5129e), NEW = this tree at 117a1fcc (the rule the default); 2 shared cores, load 7-9, every
record once, ``OMP_NUM_THREADS=1``; CPU of the rows 268 s for the 22 (auto84b's rule: 188 s at
load 6-8), 57.7 / 83.2 s for the fresh OLD / NEW, fl_thermal 90/10 39.8 / 38.1 s; ``bar
/tmp/auto80/new /tmp/auto84c/new /tmp/auto84c/fresh_old /tmp/auto84c/fresh_new``): **REFUSED**
(items 1, 3 and 5 fail; src, conf and the tests reverted, the rule in
``benchmarks/auto84c_rule.patch``)
-------------------------------------------------------------------------------------------------
auto / MLR on the new campaigns, shipped -> rule (auto rule / shipped): col5791 1.258 -> 1.062
(0.844), col1403 1.311 -> 1.397 (1.065), col1514 1.019 -> 0.869 (0.853), col6511 0.996 -> 1.018
(1.022), col6512 1.004 -> 1.007, swiss303 0.569 -> 0.631 (1.109), swiss5454 0.950 -> 0.624
(0.657), mill1514 1.000 -> 1.002, lab5401 1.070 -> 1.055, year6511 0.351 -> 0.350, year6512
0.376 -> 0.368, year6_5411 0.518 -> 0.493, twin_lathe 0.973 -> 0.916, jig_grinder 0.940 -> 0.957,
hmc 1.005 -> 0.993, tsc_a2 0.376 -> 0.378, iso_a 1.083 -> 1.180 (1.090), iso_b 0.862 -> 0.860,
mtc_a 0.704 -> 0.679, mtc_b 1.075 -> 1.048, grind_a 0.940 = 0.940, grind_b 0.992 -> 0.995.

1. FAILS: worse than MLR on the new campaigns 8 -> 8 (col5791, col1403, col6511, col6512,
   mill1514, lab5401, iso_a, mtc_b; col1514 and hmc turn into wins, col6511 and mill1514, by
   2.2 % and 0.2 %, into losses).
2. holds: better than MLR there 13 -> 14.
3. FAILS: swiss303 10.9 % worse than shipped (as auto84 and auto84b), iso_a 9.0 %, col1403 6.5 %,
   col6511 2.2 % (tsc_a2, 8.2 % under auto84b, now 0.5 %).
4. holds: ``fl_thermal`` 90/10 auto 2.481 -> 2.463 µm (MLR 4.06); 60/20/20 test MAE 1.170 / 1.411 /
   1.876 / 1.399 / 2.529, mean 1.677 (shipped: channel 3 4.078, mean 2.117), below the authors' on
   5 of 5.
5. FAILS: the 6 fresh records worse than MLR on their new campaigns 1 -> 1 (mill8806 1.000 ->
   0.965 leaves, labmill8805 0.975 -> 1.303 enters: +34 % against shipped), geometric mean auto /
   MLR 0.789 -> 0.838: col8801 0.988 -> 0.930, col8802 0.691 -> 0.828 (+20 %), swiss8803 0.625 ->
   0.586, swiss8804 0.577 -> 0.611 (+6 %).
Not in the bar: geometric mean auto / MLR over the 22 0.826 -> 0.802 (auto84b: 0.784); within 10 %
of the best single family 15 -> 17.

Why (``cv``, after the verdict, the rule applied; the MSE towards 0 / towards MLR's of the kept
members, campaign folds then extrapolation folds).  The extrapolation folds also prefer MLR's
anchor almost everywhere, where the new campaigns lose as where they win: swiss303 E_X
(hammerstein) CV 0.740 / 0.606, extrapolation 1.103 / 0.767 (auto +10.9 % on the new campaigns);
labmill8805 E_X (lag bank) 49.6 / 30.2, 34.3 / 1.99 (+34 %); col8802 every member of every target
anchored, e.g. E_Z 9.30 / 1.19, 1.19 / 0.309 (+20 %).  Where they part from the campaign folds,
they part the wrong way: col1403 E_X (lag bank, weight 1.0) CV 29.1 / 2.41 but extrapolation
0.305 / 0.351, so towards 0, and col1403 goes from 1.118 (auto84b, anchored) to 1.397 against MLR;
E_Y's lag bank likewise (42.3 / 37.6, 15.7 / 18.9).  Holding out an end of the training rows'
first principal direction is not how these records' new campaigns leave the range.  A reading,
not measured here: the rows at an end of a training campaign's inputs are still that campaign's
regime (its load cycle, its ambient), fitted by the rest of the same campaign's rows, and a new
campaign may depart along another direction than the training rows' largest spread.

What remains: no fold built from the training rows alone has read which shrink target extrapolates
(auto84b: campaign folds; here: the inputs' ends).  Left: the anchored families as extra
candidates of auto's vote (auto84's (b)), or a fold that holds out a whole campaign where the
record has several and scores only its rows outside the other campaigns' range, on new seeds
(not 8801-8809).
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
FRESH = auto84.fresh_set(8801)
FRESH_NEW = [8807, 8808, 8809]       # the new campaigns of each fresh record's machine


def fresh(root: Path, work: Path) -> None:
    """The fresh records of :data:`FRESH` through bench_auto84's ``fresh`` -> WORK."""
    auto84b.FRESH, auto84b.FRESH_NEW = FRESH, FRESH_NEW
    auto84b.fresh(root, work)


def bar(old: Path, new: Path, oldf: Path, newf: Path) -> None:
    """bench_auto84's bar, the fresh records this stop's."""
    auto84b.FRESH = FRESH
    auto84b.bar(old, new, oldf, newf)


def cv(root: Path, names: list[str]) -> None:
    """Per target of ``names``: each kept bank's CV MSE per shrink target, campaign and
    extrapolation folds."""
    import bench_auto_rank as rank

    from thermocomp.shell.builders import build_compensator

    for name, (machine, overrides) in FRESH.items():
        automore.OVERRIDES[name], automore.OF[name] = overrides, machine
    for name in names:
        overrides = [o.format(root=root) for o in automore.OVERRIDES[name]]
        sys.argv[2:] = overrides          # bench_auto_rank simulates when sim= is asked
        cfg, ds, train = rank.setup(overrides)
        for target, e in build_compensator(cfg, ds=ds).fit(train).estimators_.items():
            members = getattr(e.estimator_, "estimators_", None) or {e.family_: e.estimator_}
            for member, m in members.items():
                bank = getattr(m, "lagbank_", m)
                table = getattr(bank, "cv_results_", None)
                if table is None or "cv_mse_extrapolation" not in table:
                    continue
                cvs = table.groupby("anchor")["cv_mse_free_run"].min()
                ext = table.groupby("anchor")["cv_mse_extrapolation"].min()
                print(f"{name:12s} {target:10s} {member:12s} weight {e.weights_.get(member, 1.0):.2f}  "
                      f"anchored: {bank.anchor_}  towards 0 / MLR's: CV {cvs.get(False):.4g} / "
                      f"{cvs.get(True):.4g}, extrapolation {ext.get(False):.4g} / {ext.get(True):.4g}",
                      flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "fresh": lambda root, work: fresh(Path(root).resolve(), Path(work).resolve()),
        "bar": lambda old, new, oldf, newf: bar(Path(old), Path(new), Path(oldf), Path(newf)),
        "cv": lambda root, *names: cv(Path(root).resolve(), list(names)),
        "rows": lambda root, work, *names: auto84.rows(Path(root).resolve(), Path(work).resolve(),
                                                       "as_is", list(names)),
    }, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
