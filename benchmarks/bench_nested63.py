"""``model=auto``'s choice validated itself: nested folds from the stored out-of-fold predictions
(issue 34; stop 63, nestauto63).

Usage::

    python benchmarks/bench_nested63.py score BEFORE [RECORD ...]   # the rule, from a before run
    python benchmarks/bench_nested63.py check BEFORE AFTER          # the after run against it

``BEFORE`` / ``AFTER``: ``bench_remeasure62.py``'s ROOT (its ``write`` + ``auto`` modes; the
records' ``bench_auto_rank`` reports and arrays in ROOT/rank, ``fl9010`` there too, run as
``OUT=ROOT/rank bench_auto_rank.py fl9010 data=fl_thermal``), BEFORE on the code without the rule,
AFTER with it.  ``score`` applies the rule to BEFORE's saved arrays (every candidate's out-of-fold
and test predictions, the same fits) with the shipped functions (``vote_weights``,
``nested_rmse``): the weights from all folds must equal the ones auto kept (checked), and where
the rule keeps MLR alone the test RMSE is MLR's.  ``check``: AFTER's auto (the rule in src, fitted
again) against that.  Nothing here reads the test split to choose: it is only scored.

The rule (written and committed before anything was scored; not tuned afterwards)
------------------------------------------------------------------------------------
The votes' weights are chosen on the same folds they are judged on, so a blend that won the folds
by chance looks better there than it is (nested cross-validation: Varma & Simon 2006, Cawley &
Talbot 2010).  Where auto votes (``combine='vote'``, MLR a candidate) on K >= 3 validation folds
(not a val split, not one or two folds): for each fold k, the weights ``vote_weights`` gives from
the other K-1 folds' out-of-fold errors only (the same code, the same resampling unit as the call
on all K folds: the folds, or their blocks where K < ``n_folds``; the same voting rows), and the
out-of-fold predictions blended with them scored on fold k.  The nested error is the pooled RMSE
over the folds of those held-out blends; MLR's pooled out-of-fold RMSE on the same rows is the
comparison.  Not lower than MLR's: the target keeps MLR alone (weights {mlr: 1}); lower: the
weights as today (from all K folds).  No refit: the stored out-of-fold predictions only.
``metrics.json`` (auto's block) says ``nested_rmse``, ``mlr_rmse`` and the ``decision``
(``votes`` / ``mlr``), the reason why.

Adopted (decided before scoring) only if: records better than MLR rise, no record goes from
better than MLR to worse, within 10 % of the best single family does not fall, ``fl_thermal``
90/10 stays >= 25 % better than MLR (mean test RMSE, 4.06).  The authors' 60/20/20 split has a
val split: the rule does not reach it (checked).

Measured 2026-12-01 (stop 63; main 1fc8328; BEFORE and AFTER run once each, 2 shared cores;
CPU user + sys: ``auto`` 204 s before / 199 s after for the 11 records, ``fl9010`` 82.6 / 81.1 s,
the nested check itself 4 ms per target).  ``check``: AFTER's auto (the rule in src, every record
fitted again) equals the rule scored from BEFORE's arrays on all 42 targets (test RMSE to 1e-4).
K: validation folds; nested / MLR oof / voted: the votes' nested RMSE, MLR's pooled out-of-fold
RMSE, the blend of all K folds' votes on the same rows (µm); then test RMSE of MLR, of the best
single family (after the fact), auto before -> after::

  record      target           K  nested MLR oof   voted decision    MLR   best before  after
  hmc         E_CH15_Disp_Y    3   0.917   1.387  0.9164 votes      0.78   0.75   1.58   1.58
  hmc         E_CH16_Disp_Z    3  0.4931  0.5455  0.4372 votes     0.411  0.352  0.347  0.347
    hmc mean: MLR 0.5956, best family 0.5813 (ati), auto 0.9649 -> 0.9649
  twin_lathe  E_Z1_error       5  0.4602   0.472  0.3763 votes     0.377  0.326  0.339  0.339
  twin_lathe  E_Z2_error       5  0.4249  0.4597   0.418 votes     0.374  0.374  0.382  0.382
    twin_lathe mean: MLR 0.3757, best family 0.3757 (mlr), auto 0.3605 -> 0.3605
  jig_grinder E_DISP_Y         3  0.3936  0.4666  0.3807 votes     0.944  0.865  0.898  0.898
  jig_grinder E_DISP_Z         3  0.4167  0.4115  0.4117 mlr       0.464  0.389  0.468  0.464
    jig_grinder mean: MLR 0.704, best family 0.6592 (lstm), auto 0.6829 -> 0.6813
  lab5401     E_X              1       -    7.34   7.217 unjudged   2.64   2.58   2.58   2.58
  lab5401     E_Y              1       -   3.315   3.147 unjudged   2.12   2.11   2.01   2.01
  lab5401     E_Z              1       -   1.798   1.246 unjudged   1.28   1.25   1.85   1.85
    lab5401 mean: MLR 2.011, best family 1.978 (lstm), auto 2.145 -> 2.145
  year6_5411  E_X              4  0.5561  0.7056  0.5516 votes     0.919  0.538  0.949  0.949
  year6_5411  E_Y              4   2.482    2.57   2.003 votes       1.1  0.694   1.75   1.75
  year6_5411  E_Z              4   2.351   7.704   2.204 votes      2.82  0.562  0.562  0.562
    year6_5411 mean: MLR 1.611, best family 0.713 (ati), auto 1.089 -> 1.089
  col5791     E_X              5  0.7564  0.7874  0.7779 votes      1.33   1.33   1.32   1.32
  col5791     E_Y              5   12.46   11.76   11.82 mlr        16.3   16.3   18.2   16.3
  col5791     E_Z              5   3.558   2.571   2.344 mlr        12.2   9.11   12.9   12.2
  col5791     E_X_mid          5  0.3378  0.3384  0.3335 votes         3   1.41   3.14   3.14
  col5791     E_Y_mid          5   2.516   2.494   2.493 mlr        3.71   3.71   3.79   3.71
  col5791     E_Z_mid          5   1.608   1.888   1.594 votes      5.29   5.29   15.4   15.4
    col5791 mean: MLR 6.97, best family 6.97 (mlr), auto 9.129 -> 8.676
  col1403     E_X              5   1.809   1.809   1.809 mlr        1.87   1.82   1.87   1.87
  col1403     E_Y              5   7.371   11.43   6.976 votes      12.7   12.7   22.7   22.7
  col1403     E_Z              5   1.738   2.118   1.743 votes      15.3   5.09   15.6   15.6
  col1403     E_X_mid          5  0.4674  0.3932  0.3938 mlr        2.69  0.839   2.68   2.69
  col1403     E_Y_mid          5   1.636   2.909   1.614 votes      4.16   4.16   7.37   7.37
  col1403     E_Z_mid          5   2.044   2.108   1.262 votes      7.73   4.21   6.64   6.64
    col1403 mean: MLR 7.404, best family 7.404 (mlr), auto 9.468 -> 9.47
  col1514     E_X              5  0.9057  0.8248  0.8248 mlr        2.47   2.03   2.47   2.47
  col1514     E_Y              5   10.17   9.548    9.33 mlr        43.2   25.3   42.3   43.2
  col1514     E_Z              5   2.127   2.013   2.005 mlr        2.93   2.93   2.59   2.93
  col1514     E_X_mid          5   0.396    0.39  0.3887 mlr        3.59   2.62   3.54   3.59
  col1514     E_Y_mid          5    2.12   2.125   2.081 votes      7.97   6.12   7.52   7.52
  col1514     E_Z_mid          5   1.694   1.903   1.568 votes      2.47   2.47   4.83   4.83
    col1514 mean: MLR 10.44, best family 9.46 (arx), auto 10.54 -> 10.76
  swiss303    E_X              5   0.987   1.628   0.987 votes      1.64  0.927  0.927  0.927
  swiss303    E_Y              5  0.6429   1.115  0.6429 votes       1.1  0.605  0.605  0.605
    swiss303 mean: MLR 1.369, best family 0.7661 (hammerstein), auto 0.7661 -> 0.7661
  swiss5454   E_X              5   1.567   1.579   1.531 votes      1.74   1.17   1.65   1.65
  swiss5454   E_Y              5   1.272   1.088   1.026 mlr        1.19  0.646   1.07   1.19
    swiss5454 mean: MLR 1.464, best family 0.9079 (hammerstein), auto 1.359 -> 1.417
  mill1514    E_X              5   7.084    6.39   6.387 mlr        1.51   1.51   1.52   1.51
  mill1514    E_Y              5   7.837   7.879   7.722 votes      3.08   1.57   3.19   3.19
  mill1514    E_Z              5   1.499   1.429   1.429 mlr        1.68   1.67   1.68   1.68
    mill1514 mean: MLR 2.092, best family 2.092 (mlr), auto 2.131 -> 2.129
  fl9010      E_ch1            5   3.251   6.063    2.95 votes      4.61   2.77   2.89   2.89
  fl9010      E_ch2            5   4.429   5.194   3.705 votes      3.96    2.7   3.44   3.44
  fl9010      E_ch3            5   9.411   9.876   8.204 votes      4.35    2.5   1.97   1.97
  fl9010      E_ch4            5   8.857   9.643   7.987 votes      4.33   2.26   1.88   1.88
  fl9010      E_ch5            5   10.24    7.29   5.211 mlr        3.05   2.11   2.19   3.05
    fl9010 mean: MLR 4.06, best family 2.949 (hammerstein), auto 2.475 -> 2.647
  record      target           K  nested MLR oof   voted decision    MLR   best before  after
  col5792     E_X              5   1.144   1.114   1.115 mlr        1.37   1.37   1.34   1.37
  col5792     E_Y              5   9.631   10.23   9.323 votes        30   16.4   22.4   22.4
  col5792     E_Z              5   1.705   1.702   1.702 mlr        10.3   7.18   10.3   10.3
  col5792     E_X_mid          5  0.3837  0.3736  0.3648 mlr        3.01   1.07   3.01   3.01
  col5792     E_Y_mid          5   1.372   1.597   1.375 votes      8.19   4.28   6.16   6.16
  col5792     E_Z_mid          5   1.114   1.097   1.088 mlr        4.37   4.37   4.69   4.37
    col5792 mean: MLR 9.545, best family 7.884 (lstm), auto 7.977 -> 7.928
  swiss5791   E_X              5   1.403   1.971    1.39 votes      3.05   0.88  0.876  0.876
  swiss5791   E_Y              5    1.07   1.331    0.92 votes      1.48  0.958  0.976  0.976
    swiss5791 mean: MLR 2.266, best family 0.9192 (hammerstein), auto 0.9259 -> 0.9259
  swiss5792   E_X              5  0.8808   1.597  0.8808 votes      1.58   0.86   0.86   0.86
  swiss5792   E_Y              5  0.6067   1.082  0.6067 votes      1.04   0.53   0.53   0.53
    swiss5792 mean: MLR 1.309, best family 0.6948 (hammerstein), auto 0.6948 -> 0.6948
  year5791    E_X              5  0.4912  0.5348  0.4867 votes     0.909  0.785  0.792  0.792
  year5791    E_Y              5   1.212   1.521   1.108 votes      1.27      1  0.858  0.858
  year5791    E_Z              5   1.101   5.378   1.101 votes      3.74   1.06   1.06   1.06
    year5791 mean: MLR 1.972, best family 0.9904 (ati), auto 0.9024 -> 0.9024
  year5792    E_X              5  0.8257  0.8413  0.8176 votes     0.848  0.701  0.861  0.861
  year5792    E_Y              5   1.609   2.005   1.293 votes      1.25  0.937  0.851  0.851
  year5792    E_Z              5   1.047   5.985   1.047 votes      5.31   1.15   1.15   1.15
    year5792 mean: MLR 2.47, best family 1.007 (ati), auto 0.9531 -> 0.9531
  mill5791    E_X              5   5.426   6.513   5.376 votes      1.53   1.44   1.44   1.44
  mill5791    E_Y              5   7.563   7.345   7.352 mlr        4.84   2.98   4.85   4.84
  mill5791    E_Z              5  0.8432  0.8432  0.8432 mlr        1.42  0.768   1.42   1.42
    mill5791 mean: MLR 2.598, best family 2.292 (arx), auto 2.572 -> 2.565
  mill5792    E_X              5   7.554   7.398   7.163 mlr        1.65   1.65   1.63   1.65
  mill5792    E_Y              5   7.476   7.448   7.455 mlr        2.13   2.13   2.13   2.13
  mill5792    E_Z              5   1.074   1.074   1.074 mlr        1.75   1.11   1.75   1.75
    mill5792 mean: MLR 1.846, best family 1.846 (mlr), auto 1.839 -> 1.846

  bench_remeasure62's 11 records + fl_thermal 90/10 (12 records, 42 targets): records (means)
  better than MLR 6 -> 6, within 10 % of the best single family 6 -> 6, none from better to not;
  targets better than MLR 22 -> 16 (a fallback ties MLR), worse than MLR by > 0.1 % 17 -> 12,
  within 10 % of the best single 19 -> 19.
  rank57's fresh batch (seeds 5791/5792, col5791 above, its mills at the full rate as rank57 ran
  them, 123 / 120 s CPU; 7 records, 22 targets): records better
  than MLR 7 -> 6 (mill5792 1.839 -> 1.846 = MLR), within 10 % 6 -> 6; targets better 15 -> 12,
  worse by > 0.1 % 3 -> 1, within 10 % 14 -> 14.
  fl_thermal 90/10: 2.475 -> 2.647 µm (MLR 4.06: 39.0 % -> 34.8 % better, the 25 % bar kept; ch5
  falls back, 2.19 -> 3.05).  The authors' 60/20/20 split (val split, the rule never reached):
  the same before and after on today's code, MAE 1.170 / 1.411 / 4.078 / 1.399 / 2.529, mean
  2.117 (4 of 5 below the authors' 3.56 / 3.76 / 3.70 / 3.46 / 4.28; the 3.34 of the docs is an
  older code's).

**Refused** (the bar fixed before scoring: records better than MLR must rise; 6 -> 6 and 7 -> 6),
the src change reverted (kept on the branch history, 1f0dbce and its tests 70cca7b). Of the 23
fallbacks to MLR, 8 were ties (the votes had given MLR nearly all), 7 right on the test (col5791 E_Y
18.2 -> 16.3, E_Z 12.9 -> 12.2, E_Y_mid 3.79 -> 3.71; col5792 E_Z_mid 4.69 -> 4.37; jig E_DISP_Z
0.468 -> 0.464; mill1514 E_X, mill5791 E_Y by < 0.5 %) and 8 wrong (fl ch5 2.19 -> 3.05, col1514 E_Z
2.59 -> 2.93, swiss5454 E_Y 1.07 -> 1.19, mill5792 E_X 1.63 -> 1.65, col1514 E_Y 42.3 -> 43.2,
col5792 E_X 1.34 -> 1.37, col1514 E_X_mid 3.54 -> 3.59, col1403 E_X_mid by 0.5 %).

Why the nested error is a poor judge here: it is pooled like the folds' RMSE, so the fold with the
largest errors rules it, and with that fold held out the other four often vote its loser in whole
(fl ch5: with its first fold held out the other four give hammerstein 0.95, which scores 20.8 there
against MLR's 6.8; nested 10.24 against MLR's 7.29, the votes of all five folds 5.21); col5791
E_Z_mid, the loss the rule was hoped to catch (15.4 against MLR's 5.29 on the test), passes it
(nested 1.61 against 1.89): no fold holds the test's heat source. A unit record built for the rule
showed the same: a close sensor off in one campaign of twenty (by 0.8), the votes share it with MLR
(0.55 / 0.45), nested 0.33 against MLR's 0.27, MLR kept, while the blend is 0.18 against MLR's 0.26
on fresh campaigns with the fault.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from _cli import run_commands  # noqa: E402

from thermocomp.core.metrics import rmse  # noqa: E402
from thermocomp.core.models.auto import BASELINE  # noqa: E402
from thermocomp.core.models.blend import N_RESAMPLES, vote_weights  # noqa: E402

N_FOLDS = 5      # model.estimator.n_folds, the default every record here runs with
RECORDS = ["hmc", "twin_lathe", "jig_grinder", "lab5401", "year6_5411", "col5791", "col1403",
           "col1514", "swiss303", "swiss5454", "mill1514", "fl9010"]
MIN_NESTED_FOLDS = 3   # with two folds the inner choice would see one fold alone
RANK57 = ["col5792", "swiss5791", "swiss5792", "year5791", "year5792", "mill5791", "mill5792"]


def nested_rmse(predictions: np.ndarray, y: np.ndarray, fold: np.ndarray, base: np.ndarray,
                base_column: int | None = None, min_folds: int = 2, voting: np.ndarray | None = None,
                n_resamples: int = N_RESAMPLES) -> float | None:
    """The error of the choice itself: the pooled RMSE over the folds of the blend whose weights
    :func:`vote_weights` chose from the other folds only (nested cross-validation, Varma & Simon
    2006, Cawley & Talbot 2010); None with fewer than ``MIN_NESTED_FOLDS`` folds
    (the function the measured rule had in ``thermocomp.core.models.blend``, reverted with it).

    The weights of all the folds are chosen on the very folds that judge them, so a blend that
    won them by chance looks better there than it is; here fold ``k`` is predicted by the
    columns of ``predictions`` (each candidate's out-of-fold predictions, no refit) weighted as
    the other folds vote.  Those votes resample the same unit the call on every fold does
    (``min_folds``: its folds, or their blocks where there are fewer folds than ``min_folds``),
    so one fold fewer does not change how the folds are drawn.  ``voting``: the rows the votes
    score (auto's ``validation_rows``; default every row); each held-out fold is scored whole.
    """
    folds = np.unique(fold)
    if folds.size < MIN_NESTED_FOLDS:
        return None
    voting = np.ones(len(y), bool) if voting is None else np.asarray(voting, bool)
    inner_min_folds = int(min_folds) - 1      # K - 1 folds drawn as K are (folds or blocks)
    squared = []
    for k in folds:
        others = (fold != k) & voting
        w = vote_weights(predictions[others], y[others], fold[others], base[others],
                         n_resamples=n_resamples, base_column=base_column, min_folds=inner_min_folds)
        held = fold == k
        squared.append((y[held] - predictions[held] @ w) ** 2)
    return float(np.sqrt(np.mean(np.concatenate(squared))))


def target_row(report: dict, arrays) -> dict:
    """One target: MLR, the best single, auto before, the nested check and auto after (test RMSE)."""
    cands = list(report["validation"])
    oof = np.column_stack([arrays[f"oof_{n}"] for n in cands])
    y, fold, base = arrays["oof_y"], arrays["oof_fold"], arrays[f"oof_{BASELINE}"]
    test_y = arrays["test_y"]
    row = {"mlr": report["mlr"], "best_single": report["best_single"],
           "before": report["auto"]["rmse"], "weights": report["auto"]["weights"], "folds":
           int(np.unique(fold).size)}
    column = cands.index(BASELINE) if BASELINE in cands else None
    if len(cands) < 2 or column is None:
        return {**row, "after": row["before"], "decision": "unjudged", "nested": None}
    w = vote_weights(oof, y, fold, base, base_column=column, min_folds=N_FOLDS)
    kept = {n: v for n, v in zip(cands, w) if v > 0}
    assert set(kept) == set(row["weights"]) and all(
        abs(kept[n] - row["weights"][n]) < 1e-9 for n in kept), (kept, row["weights"])
    nested = nested_rmse(oof, y, fold, base, base_column=column, min_folds=N_FOLDS)
    mlr_oof = rmse(y - base)
    decision = "unjudged" if nested is None else ("votes" if nested < mlr_oof else "mlr")
    after = rmse(test_y - arrays[f"test_{BASELINE}"]) if decision == "mlr" else row["before"]
    return {**row, "after": after, "decision": decision, "nested": nested, "mlr_oof": mlr_oof,
            "voted_oof": rmse(y - oof @ w)}


def score(before: Path, records: list[str]) -> list[tuple[str, dict, dict]]:
    """``(record, {target: row}, family means)`` of every record of ``records`` in ``before``."""
    out = []
    for name in records:
        path = before / "rank" / f"{name}.json"
        if not path.exists():
            continue
        report = json.loads(path.read_text())
        rows = {t: target_row(r, np.load(before / "rank" / f"{name}.{t}.npz"))
                for t, r in report["targets"].items()}
        out.append((name, rows, report["family_mean"]))
    return out


def table(scored) -> list[str]:
    lines = [f"{'record':11s} {'target':15s} {'K':>2s} {'nested':>7s} {'MLR oof':>7s} {'voted':>7s} "
             f"{'decision':8s} {'MLR':>6s} {'best':>6s} {'before':>6s} {'after':>6s}"]
    count = {k: 0 for k in ("better_b", "better_a", "near_b", "near_a", "worse_b", "worse_a")}
    rec = {k: 0 for k in count}
    n, flips = 0, []
    for name, rows, family in scored:
        for t, r in rows.items():
            nested = "-" if r["nested"] is None else f"{r['nested']:7.4g}"
            lines.append(f"{name:11s} {t[:15]:15s} {r['folds']:2d} {nested:>7s} "
                         f"{r.get('mlr_oof', float('nan')):7.4g} {r.get('voted_oof', float('nan')):7.4g} "
                         f"{r['decision']:8s} {r['mlr']:6.3g} {r['best_single']:6.3g} "
                         f"{r['before']:6.3g} {r['after']:6.3g}")
            n += 1
            for k in ("b", "a"):
                v = r["before" if k == "b" else "after"]
                count[f"better_{k}"] += v < r["mlr"]
                count[f"near_{k}"] += v <= 1.10 * r["best_single"]
                count[f"worse_{k}"] += v > 1.001 * r["mlr"]
        m = {k: float(np.mean([r[k] for r in rows.values()])) for k in ("mlr", "before", "after")}
        best = min(family.values())
        for k in ("b", "a"):
            v = m["before" if k == "b" else "after"]
            rec[f"better_{k}"] += v < m["mlr"]
            rec[f"near_{k}"] += v <= 1.10 * best
        if m["before"] < m["mlr"] <= m["after"]:
            flips.append(name)
        lines.append(f"  {name} mean: MLR {m['mlr']:.4g}, best family {best:.4g} "
                     f"({min(family, key=family.get)}), auto {m['before']:.4g} -> {m['after']:.4g}")
    lines += [f"record x target ({n}): better than MLR {count['better_b']} -> {count['better_a']}, "
              f"within 10 % of the best single {count['near_b']} -> {count['near_a']}, "
              f"worse than MLR by > 0.1 % {count['worse_b']} -> {count['worse_a']}",
              f"records ({len(scored)}, means): better than MLR {rec['better_b']} -> {rec['better_a']}, "
              f"within 10 % of the best single family {rec['near_b']} -> {rec['near_a']}; "
              f"better -> not: {', '.join(flips) or 'none'}"]
    return lines


def check(before: Path, after: Path) -> list[str]:
    """AFTER's auto (the rule in src) against the rule applied to BEFORE's arrays, per target."""
    lines = []
    for name, rows, _ in score(before, RECORDS):
        path = after / "rank" / f"{name}.json"
        if not path.exists():
            continue
        got = json.loads(path.read_text())["targets"]
        for t, r in rows.items():
            a = got[t]["auto"]
            lines.append(f"{name:11s} {t[:15]:15s} scored {r['after']:.6g} ({r['decision']}) "
                         f"run {a['rmse']:.6g} {sorted(a['weights'])}")
    return lines


def main(argv: list[str]) -> int:
    def scored(root: str, *names: str) -> None:
        print("\n".join(table(score(Path(root).resolve(), list(names) or RECORDS))))
        if not names:
            print("\nrank57's fresh batch (bench_auto_rank seeds 5791/5792 but col5791, above)")
            print("\n".join(table(score(Path(root).resolve(), RANK57))))

    return run_commands(__doc__, {
        "score": scored,
        "check": lambda root, after, *_: print("\n".join(
            check(Path(root).resolve(), Path(after).resolve()))),
    }, argv)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
