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

Measured
--------
(filled in after the run)
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from thermocomp.core.metrics import rmse  # noqa: E402
from thermocomp.core.models.auto import BASELINE  # noqa: E402
from thermocomp.core.models.blend import nested_rmse, vote_weights  # noqa: E402

N_FOLDS = 5      # model.estimator.n_folds, the default every record here runs with
RECORDS = ["hmc", "twin_lathe", "jig_grinder", "lab5401", "year6_5411", "col5791", "col1403",
           "col1514", "swiss303", "swiss5454", "mill1514", "fl9010"]


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
    count = {k: 0 for k in ("better_b", "better_a", "near_b", "near_a")}
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
              f"within 10 % of the best single {count['near_b']} -> {count['near_a']}",
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
    what, root = argv[0], Path(argv[1]).resolve()
    if what == "score":
        print("\n".join(table(score(root, argv[2:] or RECORDS))))
    elif what == "check":
        print("\n".join(check(root, Path(argv[2]).resolve())))
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
