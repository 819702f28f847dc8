"""Why ``model=auto`` kept MLR on col10144's E_Y (48.4 um on its own test) where the LSTM alone tests
14.1: the folds' votes, the one-SE read, the hedge, and where in the test the families part (issue 34;
stop 107, auto107b).  Reads stored rows only: nothing is fitted.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the vote code is that tree's)::

    python benchmarks/bench_auto107b.py trace STORE RECORD         # per target: folds, votes, one-SE, test
    python benchmarks/bench_auto107b.py q3 STORE RECORD [RECORD ...]   # columns: who wins while Q3 runs

STORE: a WORK of bench_automore69's ``rows`` or bench_acc107's ``fresh`` (``automore.jsonl`` or
``fresh.jsonl``, and ``pred/RECORD.TARGET.npz``: each candidate's out-of-fold predictions ``oof_*``
with ``oof_fold``, its test predictions ``pred_*`` with ``campaign``).  col10144:
``/tmp/acc107/fresh`` (bench_acc107 ``fresh``, seed 10144, scored on its own test cycle); the five
seen column records of the 22 table: ``/tmp/auto105b/main`` (their machine's 12-16 NEW test cycles).

``trace``: per target, each candidate's per-fold summed squared error over MLR's (the votes'
measure, folds in time order) and its fold RMSE; the votes replayed (``vote_weights`` with MLR's
column and ``min_folds=5``, as ``AutoRegressor._blend``) and checked against the stored weights; the
one-SE read of that blend (``fold_ratios``, ``one_se_mean``); whether the hedge could act (only on
>= 3 campaign folds); the test RMSE of auto, of every family alone and of the blend the one-SE rule
replaced, over the test cycle's three windows: before Q3 (first half), Q3 on ([0.5, 0.75) of the
cycle: ``ColumnMovingSource`` switches on the unmeasured 200 W source at right_7, never in training),
after Q3 (its decay).  ``q3``: per record and target, each family's RMSE over MLR's in the first half
and in the Q3 window, and per family the count of (record, target) where it beats MLR there.

BAR (the brief's, written and committed before any rule was built or scored; a rule goes to src only
if the trace points to a general one, not a threshold fitted to col10144, and then only if it meets
all of it): the 22 table's losers <= 6 and geo auto / MLR <= 0.8192 (bench_auto105b's replay /
bench_auto106's stored rows); no seen record > 1 % worse than BASE (fb46731b's src); fresh
10165-10169 (the 22 table's kinds, named before drawing, scored once): no new loser vs MLR, geo <=
BASE's.  No rule: TRACED, src unchanged, 10165-10169 NOT drawn.  (The trace's figures were read
before this docstring was committed; no rule was scored against them.)

Measured: below, once run.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402

FOLDS = 5                      # auto.yaml's n_folds: vote_weights' min_folds
Q3_WINDOW = (0.5, 0.75)        # ColumnMovingSource: Q3 on over this share of each test cycle
FAMILIES = ("mlr", "pcr", "arx", "lagbank", "hammerstein", "lstm")


def _row(store: Path, record: str) -> dict:
    """The stored row of ``record`` (bench_acc107's fresh.jsonl or bench_automore69's automore.jsonl)."""
    for name in ("fresh.jsonl", "automore.jsonl"):
        path = store / name
        if path.exists():
            for line in path.read_text().splitlines():
                row = json.loads(line)
                if row.get("record") == record:
                    return row
    raise SystemExit(f"{store}: no stored row of {record}")


def _arrays(store: Path, record: str) -> dict:
    """target -> its stored npz arrays."""
    paths = sorted((store / "pred").glob(f"{record}.*.npz"))
    if not paths:
        raise SystemExit(f"{store}/pred: no arrays of {record}")
    return {p.name[len(record) + 1:-4]: dict(np.load(p)) for p in paths}


def windows(campaign: np.ndarray) -> dict:
    """Row masks of each test cycle's first half (``pre``), Q3 window (``q3``) and the rest (``after``)."""
    out = {k: np.zeros(len(campaign), bool) for k in ("pre", "q3", "after")}
    for c in np.unique(campaign):
        rows = np.flatnonzero(campaign == c)
        a, b = (int(f * len(rows)) for f in Q3_WINDOW)
        out["pre"][rows[:a]], out["q3"][rows[a:b]], out["after"][rows[b:]] = True, True, True
    return out


def _rmse(e) -> float:
    return float(np.sqrt(np.nanmean(np.square(e))))


def trace(store: str, record: str) -> None:
    """Per target: fold ratios, votes replayed, one-SE read, hedge gate, test by window."""
    from thermocomp.core.models.auto import CAMPAIGN_FOLDS, MIN_HEDGE_FOLDS
    from thermocomp.core.models.blend import fold_ratios, one_se_mean, vote_weights

    row, arrays = _row(Path(store), record), _arrays(Path(store), record)
    for target, a in arrays.items():
        y, fold = a["oof_y"], a["oof_fold"]
        members = [n for n in FAMILIES if f"oof_{n}" in a]
        preds = np.column_stack([a[f"oof_{n}"] for n in members])
        mlr = a["oof_mlr"]
        base = (y - mlr) ** 2
        w = vote_weights(preds, y, fold, mlr, base_column=members.index("mlr"), min_folds=FOLDS)
        stored = row["weights"][target]
        votes = {n: round(float(v), 3) for n, v in zip(members, w) if v > 0}
        blend = fold_ratios((y - preds @ w) ** 2, base, fold)
        read = one_se_mean(blend)
        scheme = row.get("schemes", {}).get(target, "?")
        hedge = ("could act" if scheme in CAMPAIGN_FOLDS and np.unique(fold).size >= MIN_HEDGE_FOLDS
                 else f"not applicable ({scheme}: auto105b hedges >= {MIN_HEDGE_FOLDS} campaign folds)")
        print(f"== {record} {target}: {np.unique(fold).size} folds of {np.bincount(fold).tolist()} rows")
        for k, n in enumerate(members):
            r = fold_ratios((y - preds[:, k]) ** 2, base, fold)
            fr = [_rmse(y[fold == f] - preds[fold == f, k]) for f in np.unique(fold)]
            print(f"  {n:12s} ratios {' '.join(f'{v:6.3f}' for v in r)}  mean {r.mean():6.3f}  "
                  f"fold RMSE {' '.join(f'{v:6.2f}' for v in fr)}")
        print(f"  votes replayed {votes}; stored {({n: round(v, 3) for n, v in stored.items()})}")
        if read is not None and not np.allclose(w, np.eye(len(members))[members.index('mlr')]):
            drop = [one_se_mean(np.delete(blend, j)) for j in range(blend.size)]
            print(f"  blend's fold ratios {' '.join(f'{v:.3f}' for v in blend)}; one-SE read "
                  f"{read[0]:.4f} +- {read[1]:.4f} -> {'MLR kept' if sum(read) >= 1 else 'blend kept'}; "
                  "without fold j: " + ", ".join(f"{j + 1}: {m:.3f} +- {s:.3f}"
                                                 for j, (m, s) in enumerate(drop)))
        print(f"  hedge: {hedge}")
        win = windows(a["campaign"])
        tests = {n[5:]: a[n] for n in a if n.startswith("pred_")}
        tests["blend before one-SE"] = np.column_stack([a[f"pred_{n}"] for n in members]) @ w
        for n, p in tests.items():
            e = a["y"] - p
            print(f"  test {n:20s} {_rmse(e):7.2f}   pre Q3 {_rmse(e[win['pre']]):7.2f} | Q3 on "
                  f"{_rmse(e[win['q3']]):7.2f} | after {_rmse(e[win['after']]):7.2f}")


def q3(store: str, *records: str) -> None:
    """Per record and target, each family's RMSE / MLR's before Q3 and while it runs; counts."""
    wins: dict[str, list[int]] = {}
    for record in records:
        for target, a in _arrays(Path(store), record).items():
            win, y = windows(a["campaign"]), a["y"]
            mlr = {k: _rmse(y[m] - a["pred_mlr"][m]) for k, m in win.items()}
            line = f"{record:9s} {target:8s} MLR pre {mlr['pre']:6.2f} Q3 {mlr['q3']:6.2f} |"
            for n in ("auto", *FAMILIES[1:]):
                if f"pred_{n}" not in a:
                    continue
                r = {k: _rmse(y[m] - a[f"pred_{n}"][m]) / mlr[k] for k, m in win.items()}
                line += f" {n[:5]} {r['q3']:5.2f} ({r['pre']:4.2f})"
                wins.setdefault(n, [0, 0, 0])[0 if r["q3"] < 0.995 else 2 if r["q3"] > 1.005 else 1] += 1
            print(line)
    for n, (better, tie, worse) in wins.items():
        print(f"{n:12s} while Q3 runs: better than MLR {better}, within 0.5 % {tie}, worse {worse}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "q3": q3}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
