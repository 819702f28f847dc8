"""Weight rules of ``model=auto`` scored again, without a fit, from ``bench_auto_rank.py``'s output.

Usage::

    python benchmarks/bench_auto_rules.py DIR [--tuning NAME ...]

``DIR`` holds ``NAME.json`` and ``NAME.<target>.npz`` (every candidate's out-of-fold free-run
predictions and its test predictions).  Each rule weighs the candidates from the out-of-fold
predictions alone; the test predictions only score the weights.  Per record it prints the mean
test RMSE over the targets of every rule, MLR and the best single family (the family with the
lowest mean, known only after the fact); per rule the counts the acceptance asks for: better
than MLR, within 10 % of the best family, and the geometric mean of rule / best family.
``--tuning`` names the records a rule was tuned on: the others are counted apart.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from thermocomp.core.models.blend import N_RESAMPLES, vote_weights

WITHIN = 1.10    # "within 10 % of the best single family"


def fold_ratios(P, y, fold, base):
    """Fold x candidate: each candidate's MSE in the fold over MLR's there."""
    out = []
    for f in np.unique(fold):
        rows = fold == f
        out.append(np.mean((y[rows, None] - P[rows]) ** 2, axis=0)
                   / max(float(np.mean((y[rows] - base[rows]) ** 2)), 1e-300))
    return np.array(out)


def _doubted(votes, beats, base_column):
    """``votes`` kept as far as ``beats`` (P(beats MLR)); the rest to MLR (as ``vote_weights``)."""
    beats = beats.copy()
    beats[base_column] = 1.0
    w = votes * beats
    w[base_column] += (votes * (1.0 - beats)).sum()
    w[w < 0.01] = 0.0
    return w / w.sum()


def _resampled(R, fold_weight=None):
    """Bootstrap resamples of the folds' (weighted) mean of ``R``: resample x candidate."""
    K = R.shape[0]
    a = np.ones(K) if fold_weight is None else fold_weight
    picks = np.random.default_rng(0).integers(0, K, (N_RESAMPLES, K))
    return (R[picks] * a[picks][..., None]).sum(1) / a[picks].sum(1)[:, None]


def kept(P, y, fold, base, ib):
    """The rule in ``model=auto`` (``vote_weights(base_column=)``)."""
    return vote_weights(P, y, fold, base, base_column=ib)


def geometric_doubt(P, y, fold, base, ib):
    """Votes as kept; P(beats MLR) on the mean log ratio (a fold's failure counts less)."""
    L = np.log(np.maximum(fold_ratios(P, y, fold, base), 1e-300))
    return _doubted(vote_weights(P, y, fold, base), (_resampled(L) < 0).mean(0), ib)


def recent_folds(P, y, fold, base, ib):
    """Votes and doubt on log ratios, fold k weighted k (later folds: more data, nearer the test)."""
    L = np.log(np.maximum(fold_ratios(P, y, fold, base), 1e-300))
    M = _resampled(L, np.arange(1.0, L.shape[0] + 1))
    votes = np.bincount(M.argmin(1), minlength=L.shape[1]) / N_RESAMPLES
    return _doubted(votes, (M < 0).mean(0), ib)


RULES = {"kept": kept, "geometric_doubt": geometric_doubt, "recent_folds": recent_folds}


def score(directory: Path) -> dict:
    """``{record: {rule: mean test RMSE, 'mlr': ..., 'best_family': ...}}``."""
    rows = {}
    for js in sorted(directory.glob("*.json")):
        report = json.loads(js.read_text())
        res, family = {r: [] for r in [*RULES, "mlr"]}, {}
        for t, row in report["targets"].items():
            a = np.load(directory / f"{report['record']}.{t}.npz")
            cands = [c for c in row["validation"] if f"oof_{c}" in a.files]
            P = np.column_stack([a[f"oof_{c}"] for c in cands])
            T = np.column_stack([a[f"test_{c}"] for c in cands])
            for r, rule in RULES.items():
                w = rule(P, a["oof_y"], a["oof_fold"], a["oof_mlr"], cands.index("mlr"))
                res[r].append(np.sqrt(np.mean((a["test_y"] - T @ w) ** 2)))
            res["mlr"].append(np.sqrt(np.mean((a["test_y"] - a["test_mlr"]) ** 2)))
            for i, c in enumerate(cands):
                family.setdefault(c, []).append(np.sqrt(np.mean((a["test_y"] - T[:, i]) ** 2)))
        means = {k: float(np.mean(v)) for k, v in res.items()}
        means["best_family"] = min(float(np.mean(v)) for v in family.values())
        rows[report["record"]] = means
    return rows


def main(directory: str, tuning: list[str]) -> None:
    rows = score(Path(directory))
    keys = [*RULES, "mlr", "best_family"]
    print(f"{'record':10s} " + " ".join(f"{k[:15]:>15s}" for k in keys))
    for name, m in rows.items():
        print(f"{name:10s} " + " ".join(f"{m[k]:15.4g}" for k in keys))
    groups = {"tuning": [n for n in rows if n in tuning], "other": [n for n in rows if n not in tuning]}
    for rule in RULES:
        parts = []
        for group, names in groups.items():
            if names:
                ms = [rows[n] for n in names]
                beat = sum(m[rule] < m["mlr"] for m in ms)
                near = sum(m[rule] <= WITHIN * m["best_family"] for m in ms)
                geo = np.exp(np.mean([np.log(m[rule] / m["best_family"]) for m in ms]))
                parts.append(f"{group}: better than MLR {beat}/{len(ms)}, within 10 % {near}, "
                             f"geo/best {geo:.3f}")
        print(f"{rule:16s} " + "; ".join(parts))


if __name__ == "__main__":
    args = sys.argv[1:]
    cut = args.index("--tuning") if "--tuning" in args else len(args)
    main(args[0], args[cut + 1:])
