"""``model=auto``'s blend judged by NESTED folds: for each outer validation fold k, the weights
chosen (main's votes and one-SE fallback) on the other folds only and the blend so chosen scored
on fold k; where that nested blend does not beat MLR, the target's weight goes back to MLR
(issue 34; stop 94, auto94, follow-up of bench_auto93c / 93d).
TRACED: the brief's criteria (the nested blend's pooled SSE, mean, one-SE against MLR's) fix the
room losers (cr9274 1.079, cr9088 1.117, lr9587 1.059 -> 1.000) but lose 7-12 of the 39 seen records
by > 1 % (swiss5454 0.950 -> 1.000, cr9248 0.294 -> 0.540 ...); the one criterion passing the seen
condition (``trim``) fixed 1 seen loser and moved NO fresh record (9634-9643 scored once): untested
on fresh data.  Src as on main.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_auto94.py stored OUT WORK RECORD ...   # bench_automore69's stored rows
    python benchmarks/bench_auto94.py refit OUT RECORD ...         # records refitted (rooms, columns, lr)
    python benchmarks/bench_auto94.py table OUT ...                # per record, per criterion
    python benchmarks/bench_auto94.py fresh OUT                    # seeds 9634-9643, once (bar)

``stored``: the out-of-fold and test predictions bench_automore69's ``rows`` kept (WORK/pred, as
bench_auto91 / 93c read them: the test is the machine's NEW campaigns).  ``refit``: a record of
bench_auto88b's :data:`RECORDS`, bench_auto93's / 93c's :data:`FRESH`, or this bench's
:data:`RECORDS` / :data:`FRESH`, auto and MLR fitted on its train campaigns and scored on its own
test campaigns as ``run`` scores them (bench_auto93c's ``trace``).  Both write per target one line
in OUT/targets.jsonl: main's weights, the nested figures (:func:`nested`), the test RMSE of auto
and of MLR.  ``table``: per record the mean over targets of the pooled test RMSE over MLR's, main
and each criterion, geo over the records, losers fixed, winners lost.  No refit is needed for the
rule: it either keeps main's blend or hands the target to MLR, and both are fitted already.

The rule (a prototype, train side only: nothing of the test is read).  A target whose kept model
is a blend or a family other than MLR, with k >= 2 validation folds: for each outer fold j the
members' out-of-fold predictions on the OTHER k - 1 folds choose weights exactly as ``_blend``
does (``vote_weights`` with MLR's column and ``min_folds=n_folds``, then main's one-SE fallback
where k - 1 >= 2), and fold j is predicted by that blend (:func:`nested`).  The out-of-fold
predictions are the members' own (each fitted without its fold), so no member is refitted; on
forward folds the inner folds after j were fitted on rows that include fold j's: its inputs, not
its choice.  Criteria, each handing the target to MLR where it holds:

* ``pooled``: the nested blend's summed squared error over all outer folds >= MLR's;
* ``one_se``: its per-fold ratio to MLR (:func:`fold_ratios`) has mean + SE >= 1 (main's one-SE
  applied to the nested, not the same-fold, blend);
* ``mean``: the mean per-fold ratio >= 1 (the votes' own measure).

A target voting on ONE fold (lab5401's generator: 3 train runs, min_train_fraction 0.5) cannot be
nested (no fold is left to choose on); it is left as main has it, so every lab record is unchanged
by construction.

Records.  SEEN: the 10 stored rows of bench_auto91 (col5791 col1403 lab5401 col1514 col6512
swiss303 swiss5454 year6511 year6_5411 mill1514, new campaigns); the 13 climate rooms of
bench_auto93's bar (cr9031 cr9076 cr9079 cr9081 cr9083 cr9088 cr9089 cr9181 cr9182 cr9183 cr9244
cr9245 cr9248); auto93's fresh (spent) cr9271-9275 and col9276-9280; auto93c's rooms cr9604-9608
(the labs 9609-9613 and 9629-9633 vote on one fold: untouched); lr9587 (audit93's long_record).
FRESH (named here before any draw): :data:`FRESH`, 9634-9638 ``climate_room`` at bench_auto87's
SMALL (as cr9271-9275, cr9604-9608) and 9639-9643 ``long_record`` as lr9587 (bench_deploy88's
LONG, 3 days), each scored on its own test.

Seen (2026-12-05, this tree = main 4f0fc94a + the bench; ``stored /tmp/auto94/seen /tmp/auto91/seen
<the 10>`` 0.7 s; ``refit /tmp/auto94/rooms <the 23 rooms>`` 57.1 s CPU; ``refit /tmp/auto94/more
lr9587 col9276 ... col9280`` 52.8 s; nice, ``OMP_NUM_THREADS=1``; ``chosen_weights`` on all folds
reproduces main's kept weights to the digit on the stored rows checked: col5791, col1403, lab5401,
swiss5454).  Record figure / MLR (mean over targets of the pooled test RMSE)::

  record    auto   pooled one_se  mean   geo  median  trim
  col5791   1.258  1.249  1.245  1.249  1.249  1.258  1.258
  col1514   1.019  1.019  1.000  1.000  1.000  0.993  1.019
  col6512   1.004  1.000  1.000  1.000  1.000  1.003  1.003
  swiss5454 0.950  1.000  1.000  1.000  0.978  0.950  0.950
  year6511  0.351  0.356  0.394  0.356  0.356  0.356  0.351
  cr9274    1.079  1.000  1.000  1.000  1.000  1.165  1.079
  cr9245    1.293  1.293  0.940  0.940  0.940  0.940  0.940
  cr9088    1.117  1.000  1.000  1.000  1.000  1.086  1.117
  cr9031    0.970  1.000  1.000  1.000  0.970  0.970  0.970
  cr9076    0.831  0.831  1.000  0.796  0.831  0.831  0.831
  cr9182    0.558  0.558  1.000  0.558  0.558  0.558  0.558
  cr9248    0.294  0.540  0.540  0.294  0.294  0.294  0.294
  cr9272    0.846  1.000  1.000  1.000  1.000  0.846  0.846
  cr9273    0.802  0.845  0.845  0.845  0.845  0.802  0.802
  cr9606    0.362  0.469  0.469  0.469  0.362  0.362  0.362
  cr9607    0.859  0.859  1.000  0.896  0.896  0.896  0.859
  lr9587    1.059  1.000  1.000  1.000  1.000  1.059  1.059
  col9276   0.995  0.999  1.000  0.999  0.995  0.999  0.995
  col9277   1.115  0.981  1.000  1.000  1.000  1.115  1.115
  col9278   0.824  0.854  0.854  0.824  0.824  0.877  0.824
  col9279   1.168  1.168  0.716  0.716  1.168  1.168  1.168
  col9280   0.832  0.917  1.014  0.840  0.840  0.909  0.832
  (untouched by every criterion: col1403 1.311, lab5401 1.070 (one fold), swiss303, year6_5411,
  mill1514, cr9079 9081 9083 9089 9181 9183 9244 9271 9275 9604 9605 9608)
  over the 39:   pooled  one_se  mean    geo     median  trim
  geo / auto     1.0243  1.0326  0.9846  0.9901  0.9978  0.9918
  losers fixed   4 of 9  6       6       5       1       1
  > 1 % worse    9       12      7       5       5       0

* The nested blend does see the room losers' cancellation: cr9274 E_Z's same-fold blend wins 4 of
  4 folds (0.705 0.485 0.129 0.789, auto93c), the nested one 0.843 0.573 28.234 0.856 (weights
  chosen without fold 3 put ati in; pooled 11.5); cr9088 E_Z 0.836 0.744 3.729 0.789, E_X 1.812
  0.573 1.796 0.606; lr9587 E_Z 0.734 0.837 1.230 0.936 6.184 (lagbank's last fold).  Any criterion
  reading the whole nested mean (pooled, mean, geo, one-SE) fixes them (cr9274 1.079 -> 1.000,
  cr9088 1.117 -> 1.000, lr9587 1.059 -> 1.000, col9277 1.115 -> 1.000).
* It fails winners the same way: one outer fold where the blend chosen without it fails (first
  forward folds, a member extrapolating there) -- swiss5454 E_Y 3.573 0.874 0.874 0.890 0.879
  (test 0.863 of MLR's SSE), cr9248 E_X, cr9272 E_Z, cr9606 E_X 2.753 0.586 0.602 0.367 (test
  0.335), year6511 E_X 1.000 1.926 0.982 1.000 0.898 (test 0.900).  Nested CV judges the weighting
  PROCEDURE's variance across folds; a winner whose same-fold votes already priced the bad fold
  (down-weighting the member failing there) is charged for it once more.  Losers and winners show
  the same shape (one or two bad nested folds): the brief's three criteria lose 7-12 seen records
  by > 1 %, so by the bar below none qualifies.
* Not reached by any criterion: col1403 (1.311; nested pooled 0.418 / 0.316 on E_Y / E_Y_mid, tested
  3.4 / 4.3: the forward folds misrank its one record, bench_automore69), col5791 E_Z_mid (nested
  0.724, test 8.67: Q3, no fold holds it), lab5401 (one fold).

Criteria ``geo`` (mean log ratio >= 0), ``median`` (median ratio >= 1) and ``trim`` (the mean
ratio without the outer fold where the nested blend does worst >= 1: a loss on most folds, not one
fold's extrapolation) were ADDED after the seen table showed the brief's three losing 7-12 seen
winners; chosen on seen records only, before any fresh seed was drawn.

BAR (written here, committed BEFORE the fresh seeds 9634-9643 were drawn; the brief's, auto93c's):
SEEN -- a criterion qualifies where, over every seen record above (the 10 stored, 23 rooms, lr9587,
col9276-9280), no record is worse than auto by > 1 % (rule / auto > 1.01) and geo rule / auto <= 1.0;
the losers (auto / MLR > 1.02) counted with those brought within 2 % of MLR.  Of the qualifying
criteria the one fixing the most seen losers is scored on fresh (a tie: the first in
:data:`CRITERIA`); none qualifying: no fresh seed drawn, the verdict TRACED (no src).  FRESH
9634-9643 scored ONCE by ``fresh`` with that one criterion: (a) no fresh record worse than auto by
> 1 %, (b) geo rule / auto over the 10 <= 1.0, (c) fresh losers counted with those fixed.  Passes
= (a) and (b) and at least one fresh record improved (none moved: untested, TRACED); else REFUSED.

Fresh (scored ONCE, 2026-12-05, after the bar above was committed in 7efe249d (written in
feb8c367); ``fresh /tmp/auto94/fresh`` 26.9 s CPU, nice, ``OMP_NUM_THREADS=1``; the verdict rests on
``trim`` alone, the other criteria printed as measurement)::

  record   auto/MLR  pooled  one_se  mean    geo     median  trim   folds
  cr9634   0.427     0.427   0.427   0.427   0.427   0.427   0.427  4
  cr9635   0.947     0.947   1.000   0.947   0.947   0.947   0.947  4
  cr9636   0.649     0.649   0.649   0.649   0.649   0.649   0.649  4
  cr9637   0.562     0.562   0.698   0.698   0.698   0.562   0.562  4
  cr9638   0.980     0.980   0.980   0.980   0.980   0.980   0.980  4
  lr9639   1.000     1.000   1.000   1.000   1.000   1.000   1.000  (MLR kept)
  lr9640   0.858     1.000   1.000   1.000   1.000   0.858   0.858  5
  lr9641   0.637     0.637   0.637   0.637   0.637   0.637   0.637  5
  lr9642   0.674     0.674   0.674   0.674   0.674   0.674   0.674  5
  lr9643   0.519     0.519   0.519   0.519   0.519   0.519   0.519  5
  geo / auto       1.0154  1.0434  1.0377  1.0377  1.0000  1.0000
  > 1 % worse      1       3       2       2       0       0

Against the bar (unchanged): no fresh loser (auto beats or equals MLR on all 10); ``trim`` (a) met,
(b) met (1.0000), (c) 0 losers, but NO fresh record moved: by the bar, untested -- TRACED.  The
brief's criteria on fresh (measurement, not the verdict): ``pooled`` loses lr9640 (0.858 -> 1.000,
E_Z 0.13 hammerstein; nested 6.947 0.827 0.844 0.906 0.861: the first forward fold again),
``mean`` / ``geo`` lr9640 and cr9637 (0.562 -> 0.698, E_X nested 2.416 0.908 0.746 0.861, test
0.423), ``one_se`` three: as on seen, one bad nested fold marks winners and losers alike.

Verdict: TRACED, no src.  What nesting shows: the votes' same-fold optimism is real (the room
losers' nested blends fail in one fold their same-fold blends won: cr9274 E_Z 0.129 -> 28.2), but a
winner's nested blend fails one fold just as often (swiss5454 E_Y 3.57, cr9606 E_X 2.75, lr9640
E_Z 6.95), so the nested score does not tell them apart on these records.  One-fold records (lab5401
and its generator: 3 train runs, one validation fold) cannot be nested (no fold to choose on), and
k = 2 leaves one fold to choose on (the votes' block resampling of that fold): nothing here speaks
for changing them.  Left: col1403 (forward folds misrank its one record), the column's Q3 losses
(no fold holds Q3), the labs' one-fold misranking; a nested score on more outer units (blocks of the
forward folds' rows) might separate one bad fold from a steady loss -- not tried.

After the fresh score, measurement only (all 49 records now seen): the winners' bad nested fold
is most often the FIRST forward fold (swiss5454 E_Y, cr9606 E_X, lr9640 E_Z, cr9637 E_X: fitted on
the least data, its weights chosen on the later folds), the losers' a later one (cr9274 E_Z fold 3,
lr9587 E_Z fold 5, col9277 E_Y fold 4).  ``later`` (the mean ratio over outer folds 2..k >= 1 ->
MLR) on the 39 seen: geo / auto 0.9868, 5 of 9 losers fixed (cr9274, cr9245 0.940, lr9587,
col9277, col9279 1.168 -> 0.716; cr9088 1.117 -> 1.031), but 4 records > 1 % worse (cr9182 0.558 ->
1.000, cr9273 0.802 -> 0.845, cr9031 0.970 -> 1.000, year6511 0.351 -> 0.356): it fails the seen
condition too; on 9634-9643 (seen by then) it moves nothing.  A lead, not a rule.

The 22-record table's other 12 records (after the fresh score, measurement only; bench_automore69
``rows`` into /tmp/auto94/rows22 on this tree, ROOT as its docstring says: bench_iso67 / stranger68
/ stranger66 ``write`` + ``init`` (tsc_a2 with ``data.max_gap_samples=4``), bench_automore69
``write``, nm59 / nm60 / lag copied from stop 88's ROOT; 141 s CPU for the 12; every auto / MLR on
the new campaigns = the table's: hmc 1.005, iso_a 1.083, mtc_b 1.075), then ``stored``::

  record      auto    pooled one_se  mean   geo   median  trim   later
  iso_a       1.083   1.073  1.073  1.073  1.073  1.073  1.073  1.073   (2 folds; E_X1 0.955 298.8)
  iso_b       0.862   0.850  1.000  1.000  1.000  1.000  1.000  1.012   (2 folds; E_Z 0.760 1.453, test 0.302)
  col6511     0.996   0.996  1.000  1.005  1.005  1.005  0.996  0.996
  year6512    0.376   0.376  0.383  0.376  0.376  0.376  0.376  0.383
  grind_a     0.940   0.940  0.998  0.940  0.940  0.940  0.940  0.940
  tsc_a2      0.376   0.378  0.378  0.378  0.378  0.378  0.378  0.378
  hmc 1.005, mtc_b 1.075 (single families, hammerstein, winning every nested fold: hmc E_Y 0.395
  0.919 0.480, test 1.172; mtc_b dX 0.236 0.371 0.154, test 1.253), mtc_a, twin_lathe, jig_grinder,
  grind_b: unchanged or within 1 % under every criterion.
  over the 12: geo / auto pooled 0.9984, one_se 1.0202, mean / geo 1.0127, median 1.0128, trim
  1.0121, later 1.0146; > 1 % worse: 0 / 4 / 1 / 1 / 1 / 1 / 2.

``trim`` loses iso_b (0.862 -> 1.000, x1.160): with two folds it is the plain mean.  Had these 12 been
in the seen set before the bar (the brief named the 22; 10 were), ``trim`` would have failed the seen
condition too, and no criterion would have been scored on fresh: the verdict is TRACED either way.
Nesting cannot reach the table's two other losers: hmc and mtc_b keep one family whose nested
folds all say it wins (the test disagrees: a new campaign's conditions, not the votes' optimism).

"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto87 as auto87  # noqa: E402
import bench_auto88b as auto88b  # noqa: E402
import bench_auto91 as auto91  # noqa: E402
import bench_auto93 as auto93  # noqa: E402
import bench_auto93c as auto93c  # noqa: E402
from _cli import run_commands  # noqa: E402
from bench_deploy88 import LONG  # noqa: E402

CRITERIA = ("pooled", "one_se", "mean", "geo", "median", "trim", "later")
RECORDS = {"lr9587": [*LONG, "seed=9587", "sim.generator.duration_days=3.0"]}
FRESH = {**{f"cr{s}": ["sim=climate_room", f"seed={s}", *auto87.SMALL] for s in range(9634, 9639)},
         **{f"lr{s}": [*LONG, f"seed={s}", "sim.generator.duration_days=3.0"] for s in range(9639, 9644)}}
BASELINE = "mlr"


def chosen_weights(preds: np.ndarray, y, fold, base, base_column: int, n_folds: int) -> np.ndarray:
    """The weights ``AutoRegressor._blend`` keeps from these out-of-fold rows: the votes
    (``vote_weights``), then the one-SE fallback where the rows hold >= 2 folds."""
    from thermocomp.core.models.blend import fold_ratios, vote_weights

    w = vote_weights(preds, y, fold, base, base_column=base_column, min_folds=n_folds)
    if np.unique(fold).size >= 2 and w[base_column] < 1.0:
        r = fold_ratios((y - preds @ w) ** 2, (y - base) ** 2, fold)
        if np.mean(r) + np.std(r, ddof=1) / np.sqrt(r.size) >= 1.0:
            w = np.eye(preds.shape[1])[base_column]
    return w


def nested(members: dict, y, fold, n_folds: int = 5) -> dict | None:
    """Per outer fold j, the blend chosen on the other folds (:func:`chosen_weights`) predicting
    fold j; its per-fold SSE over MLR's, the pooled ratio and each criterion's verdict (True: hand
    the target to MLR).  None with fewer than two folds (nothing left to choose on)."""
    from thermocomp.core.models.blend import fold_ratios

    labels = np.unique(fold)
    if labels.size < 2:
        return None
    names = list(members)
    preds = np.column_stack([members[n] for n in names])
    col = names.index(BASELINE)
    base = preds[:, col]
    out_pred = np.empty_like(y)
    inner_w = []
    for j in labels:
        inner, held = fold != j, fold == j
        w = chosen_weights(preds[inner], y[inner], fold[inner], base[inner], col, n_folds)
        out_pred[held] = preds[held] @ w
        inner_w.append({n: round(float(v), 3) for n, v in zip(names, w) if v > 0})
    r = fold_ratios((y - out_pred) ** 2, (y - base) ** 2, fold)
    pooled = float(np.sum((y - out_pred) ** 2) / np.sum((y - base) ** 2))
    se = float(np.std(r, ddof=1) / np.sqrt(r.size))
    return {"ratios": [float(v) for v in r], "pooled": pooled, "se": se, "inner": inner_w,
            "to_mlr": to_mlr(r, pooled)}


def to_mlr(r: np.ndarray, pooled: float) -> dict:
    """Each criterion's verdict on the nested blend's per-fold ratios ``r`` (True: MLR alone).
    The first three are the brief's; ``geo``, ``median`` and ``trim`` were added after the seen
    table (``pooled`` / ``one_se`` / ``mean``: 7-12 seen records > 1 % worse), on seen records only;
    ``later`` (the first outer fold left out of the mean) after the fresh score, a lead only."""
    r = np.asarray(r, float)
    se = float(np.std(r, ddof=1) / np.sqrt(r.size))
    return {"pooled": pooled >= 1.0, "one_se": float(np.mean(r)) + se >= 1.0,
            "mean": float(np.mean(r)) >= 1.0, "geo": float(np.mean(np.log(r))) >= 0.0,
            "median": float(np.median(r)) >= 1.0,
            "trim": float(np.mean(np.sort(r)[:-1] if r.size > 2 else r)) >= 1.0,
            "later": float(np.mean(r[1:])) >= 1.0}


def _is_mlr(weights: dict) -> bool:
    return set(k for k, v in weights.items() if v > 0) <= {BASELINE} and sum(weights.values()) > 0


def _line(out: str, record: str, target: str, weights: dict, verdict, rmse: dict) -> None:
    folder = Path(out).resolve()
    folder.mkdir(parents=True, exist_ok=True)
    with open(folder / "targets.jsonl", "a") as f:
        f.write(json.dumps({"record": record, "target": target, "weights": weights,
                            "nested": verdict, "rmse": rmse}) + "\n")


def _say(record, target, weights, verdict, rmse) -> None:
    kept = " + ".join(f"{w:.2f} {n}" for n, w in sorted(weights.items(), key=lambda kv: -kv[1]))
    test = rmse["auto"] ** 2 / rmse["mlr"] ** 2
    if verdict is None:
        print(f"  {record} {target}: kept {kept}; not nested; test SSE auto / MLR {test:.3f}", flush=True)
        return
    r = " ".join(f"{v:.3f}" for v in verdict["ratios"])
    to = ",".join(k for k, v in verdict["to_mlr"].items() if v) or "-"
    print(f"  {record} {target}: kept {kept}; nested per fold {r} (pooled {verdict['pooled']:.3f}, "
          f"SE {verdict['se']:.3f}) -> MLR by [{to}]; test SSE auto / MLR {test:.3f}", flush=True)


def stored(out: str, work: str, *records: str) -> None:
    """bench_automore69's stored rows in WORK: the members' out-of-fold arrays and test
    predictions (the machine's new campaigns)."""
    work_path = Path(work).resolve()
    for name in records:
        for target, weights, a, y_new, new, members in auto91.stored_targets(work_path, name):
            verdict = None if _is_mlr(weights) else nested(members, a["oof_y"], a["oof_fold"])
            rmse = {k: float(np.sqrt(np.mean((y_new - a[f"pred_{k}"])[new] ** 2))) for k in ("auto", "mlr")}
            _say(name, target, weights, verdict, rmse)
            _line(out, name, target, weights, verdict, rmse)


def refit(out: str, *records: str) -> None:
    """Auto and MLR fitted on each record's train campaigns (bench_auto93c's ``trace``'s fit), its
    own test campaigns scored in simulation mode; the nested figures from auto's ``oof_``."""
    import bench_auto_rank as rank
    from sklearn.base import clone

    from thermocomp.core.scoring.evaluation import split_residuals
    from thermocomp.shell.builders import build_compensator

    known = {**auto88b.RECORDS, **auto93.FRESH, **auto93c.FRESH, **RECORDS, **FRESH}
    for name in records:
        sys.argv[2:] = overrides = list(known[name])
        cfg, ds, train = rank.setup(overrides)
        auto = build_compensator(cfg, ds=ds).fit(train)
        mlr = clone(auto).set_params(estimator=rank._mlr()).fit(train)
        ids = ds.ids("test")
        series = {k: split_residuals(m, ds, ids, "simulation")[2] for k, m in (("auto", auto), ("mlr", mlr))}
        print(f"== {name}: {len(train)} train campaigns, test {list(ids)}", flush=True)
        for t, est in auto.estimators_.items():
            res = {k: np.concatenate([series[k][t][1][c] for c in ids]) for k in series}
            ok = np.isfinite(res["auto"]) & np.isfinite(res["mlr"])
            rmse = {k: float(np.sqrt(np.mean(res[k][ok] ** 2))) for k in res}
            weights = dict(est.weights_)
            verdict = None
            if getattr(est, "oof_", None) and BASELINE in est.oof_ and not _is_mlr(weights):
                members = {n: est.oof_[n] for n in est.candidates if n in est.oof_}
                members.setdefault(BASELINE, est.oof_[BASELINE])
                verdict = nested(members, est.oof_y_, est.oof_fold_, int(est.n_folds))
            _say(name, t, weights, verdict, rmse)
            _line(out, name, t, weights, verdict, rmse)


def _records(paths) -> dict:
    """record -> per target (weights, verdict, rmse), from OUT/targets.jsonl (later lines win)."""
    out: dict = {}
    for p in paths:
        for line in map(json.loads, (Path(p) / "targets.jsonl").read_text().splitlines()):
            out.setdefault(line["record"], {})[line["target"]] = line
    return out


def table(*outs: str) -> None:
    """Per record: auto / MLR and each criterion / MLR (the mean over targets of the pooled test
    RMSE), then per criterion geo rule / auto, losers (auto / MLR > 1.02) fixed (within 2 % of MLR),
    winners (auto / MLR < 0.98) lost (rule / auto > 1.01), records worse than auto by > 1 %."""
    rows = _records(outs)
    print("record       auto/MLR  " + "  ".join(f"{c:>7s}" for c in CRITERIA) + "   targets to MLR by")
    ratios = {c: [] for c in CRITERIA}
    counts = {c: {"fixed": 0, "lost": 0, "worse": 0} for c in CRITERIA}
    losers = 0
    for name, targets in rows.items():
        mlr = np.mean([t["rmse"]["mlr"] for t in targets.values()])
        auto = np.mean([t["rmse"]["auto"] for t in targets.values()])
        losers += auto / mlr > 1.02
        figs, moved = {}, {}
        for c in CRITERIA:
            moved[c] = [k for k, t in targets.items()
                        if t["nested"] and to_mlr(t["nested"]["ratios"], t["nested"]["pooled"])[c]]
            picked = [t["rmse"]["mlr" if k in moved[c] else "auto"] for k, t in targets.items()]
            figs[c] = np.mean(picked) / mlr
            ratios[c].append(figs[c] / (auto / mlr))
            counts[c]["fixed"] += auto / mlr > 1.02 and figs[c] <= 1.02
            counts[c]["lost"] += auto / mlr < 0.98 and figs[c] / (auto / mlr) > 1.01
            counts[c]["worse"] += figs[c] / (auto / mlr) > 1.01
        print(f"{name:12s} {auto / mlr:8.3f}  " + "  ".join(f"{figs[c]:7.3f}" for c in CRITERIA)
              + "   " + "; ".join(f"{c}: {','.join(moved[c])}" for c in CRITERIA if moved[c]))
    for c in CRITERIA:
        geo = float(np.exp(np.mean(np.log(ratios[c]))))
        print(f"{c:7s}: geo rule / auto over {len(ratios[c])} {geo:.4f}; losers {losers}, fixed "
              f"{counts[c]['fixed']}; winners lost {counts[c]['lost']}; worse than auto by > 1 %: "
              f"{counts[c]['worse']}")


def fresh(out: str) -> None:
    """Once, for the bar: :data:`FRESH` refitted into OUT, then the table."""
    refit(out, *FRESH)
    table(out)


def main(argv: list[str]) -> int:
    commands = {"stored": stored, "refit": refit, "table": table, "fresh": fresh}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
