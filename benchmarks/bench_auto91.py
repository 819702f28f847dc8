"""``model=auto`` on the records with one train record (or one validation fold) that lose to MLR:
which blend the folds keep, each member's fold ratios, and where in the test the loss lies
(issue 34; stop 91, auto91).  TRACED (no rule)

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code and conf measured are that
tree's; ROOT holds lab5401's written record, WORK the rows)::

    python benchmarks/bench_auto91.py rows ROOT WORK RECORD ...    # bench_automore69's rows
    python benchmarks/bench_auto91.py folds WORK RECORD ...        # kept blend, per-fold ratios
    python benchmarks/bench_auto91.py where ROOT WORK RECORD ...   # the loss in time, in range

``rows``: lab5401's record written into ROOT where absent (bench_auto_losses56's ``lab_record``),
then bench_automore69's ``rows`` (auto and every candidate alone fitted on the record's train part,
scored on its own test and on 12 new campaigns of its machine: seeds 6911-6922, already looked at;
the candidates' and auto's out-of-fold and test predictions kept in WORK/pred).  ``folds``: per
target, the kept weights, every member's summed squared error over MLR's per validation fold (the
votes' measure), the blend's, the one-SE figures the fallback reads (mean and SE over the folds;
with one fold, the fold's ratio and its SE over bootstrap resamples of the blocks the votes
resample) and each member's test RMSE over MLR's on the new campaigns; then the excess squared
error of auto over MLR on the new campaigns per tenth of the campaign (share of MLR's total).
``where``: the share of rows whose inputs (the ``T_`` columns, referenced at the campaign's first
sample as ``data.reference=first_sample`` does) lie within the leverage range of the train rows
(:func:`thermocomp.core.model_selection.extrapolation.within_range`): for each forward fold's
block against its fit rows, and for the new campaigns per tenth against the whole train record;
per lossy target the share of auto's excess squared error (over MLR's) in out-of-range rows.

The question (stop 90's "what remains": 8 of 22 records worse than MLR on their new campaigns, the
largest the column's, col5791 x1.258, col1403 x1.311, and lab5401 x1.070): is the loss the test
extrapolating past the last fold's operating range, a member whose error grows with a horizon longer
than the fold's, or folds shorter than the test?  A rule only where a general cause showed.

Traced (2026-12-05; this tree = main 277a181d; 2 shared cores, load 2-4, ``OMP_NUM_THREADS=1``;
``rows /tmp/auto91/root /tmp/auto91/seen col5791 col1403 lab5401 col1514 col6512``, ``folds`` and
``where`` on them; CPU of the rows 17 / 13 / 6 / 13 / 13 s a record)
------------------------------------------------------------------------------------------------
auto / MLR on the new campaigns reproduce stop 90's: col5791 1.258, col1403 1.311, lab5401 1.070,
col1514 1.019, col6512 1.004.

* The records' shape.  The column (``column_moving_source``): ONE train campaign of 1441 rows
  (40 h), its own test a separate 40 h test cycle of 1441 rows referenced at its first sample (a
  new campaign, not a continuation: shifted ambient, the source Q3 never run in training, from 50
  to 75 % of the cycle); auto's folds: 5 forward blocks of 144 rows over the later half, each
  predicted in free run from the record's start, so a fold's horizon is 793-1441 rows from the
  start, as long as the test's.  lab5401: three 10 h train runs and a 12 h test run (campaign
  folds: min_train_fraction 0.5 leaves ONE fold, Lauf_3, 1200 rows; the test 1441 rows, 1.2 x).
  Neither record's test is longer than its folds' horizon by more than 20 %: the horizon is not
  the cause.
* Where the column loses: the excess of auto over MLR lies in the tenths 6-8 of the cycle (Q3
  running), and there the inputs lie outside the train record's range: the in-range share of
  the new campaigns per tenth 0.47 0.42 0.57 0.40 0.72 0.03 0.00 0.00 0.09 0.48 (col5791;
  col1403 alike).  col5791 E_Z_mid (lagbank 0.81, hammerstein 0.02, arx 0.02, MLR 0.15; 2.94 x
  MLR on the new campaigns): excess per tenth -0.01 -0.02 -0.01 +0.00 +0.00 +1.24 +3.29 +2.98
  +0.20 -0.01 (of MLR's total SSE); E_X_mid (arx 0.50) and E_Z (hammerstein 0.10, lstm 0.22) the
  same tenths, smaller.  col1514 E_Z_mid (lagbank 0.18, hammerstein 0.41; 1.61 x) +0.85 +0.54
  +0.22 in the tenths 7-9, col6512 E_X_mid (arx 0.65; 1.07 x) in 5-7.  The forward folds
  extrapolate too (col5791's blocks in range 0.00 0.17 0.50 0.92 0.97 of their rows, col1403's
  0.00 0.00 0.76 0.99 1.00), but along the record's own warming, where the lag families win
  (col5791 E_Z_mid lagbank per fold 1.04 1.14 0.13 0.11 0.92 x MLR; the blend 1.03 0.68 0.09 0.08
  0.48, one-SE mean 0.47 + SE 0.19: kept), not along Q3's direction, which no fold holds.
* col1403 (E_Y: lagbank 0.84, arx 0.15, 1.85 x MLR; E_Y_mid: hammerstein 0.64, lagbank 0.36,
  2.08 x): the loss also lies in range, over the whole cycle (E_Y excess per tenth -0.03 +0.13
  +0.27 +0.21 +0.21 +1.08 +0.30 +0.10 +0.17 -0.00), the Q3 tenths the largest.  Its folds are
  sure the other way: E_Y lagbank 0.33 0.07 1.09 0.40 0.64, blend 0.29 0.06 0.92 0.42 0.59; even
  the last two (fit on the most, in range 0.99 / 1.00) 0.42 / 0.59.  A new campaign starts its
  frame and states afresh where no fold of one record does (auto86's finding: both a restarted
  block and a shifted frame read this loss, and read the Swiss lathe's right hammerstein as
  failing as well: refused there).
* lab5401 (one fold: the votes resample its blocks, the one-SE fallback needs k >= 2 folds and
  is off): E_Z keeps MLR 0.57, lstm 0.28, arx 0.15 (1.19 x MLR on the new campaigns): on Lauf_3 arx
  0.97, lstm 0.96, the blend 0.67 x MLR -- the members' errors cancel on the one fold.  arx's
  error grows with the hour on the new 12 h runs (per fifth 1.51 4.41 5.33 6.80 7.68 x MLR) where
  on the fold it does not (1.30 2.26 0.26 1.51 0.78); the blend's excess grows likewise (+0.00 ..
  +0.08 per tenth).  E_Y (lagbank 0.04) 1.05 x. A one-SE rule on the fold's blocks (its ratio +
  the bootstrap SE over the 4-6 blocks the votes use) would keep every blend: E_X 0.963 + 0.014,
  E_Y 0.902 + 0.034, E_Z 0.666 + 0.069 (mean + SE over the blocks 0.976 / 0.974 / 0.875): it
  does not fire, so it was not written as a rule.  With 52 inputs and 3600 train rows, the new
  runs are out of range from their third tenth (0.27 0.12 0.03 0.00 ...): the leverage range says
  nothing on this record.
* The brief's rule candidates, each read from these figures without a refit: folds as long as the
  test (the column's folds already run 793-1441 rows from the start; lab5401's fold 10 h of 12);
  folds weighted to the latest (the last folds keep the losing blends: col5791 E_Z_mid 0.48,
  col1403 E_Y 0.59, E_Y_mid 0.88); the one-SE rule on forward folds (already main's fallback; the
  losing blends pass it: col5791 E_Z_mid 0.47 + 0.19, col1403 E_Y 0.46 + 0.15, E_Y_mid 0.49 +
  0.14; on lab5401's one fold by blocks, above).  None touches the losses.

Verdict: TRACED, no rule, src as on main.  The column's losses lie where the test runs a source
(Q3) no part of the train record runs, the inputs outside its range, which no fold of that record
can hold (four of the five columns); col1403's also lie in range, where a new campaign's fresh
start misleads the lag families (auto86's ground, refused twice); lab5401's is a one-fold blend
whose members' errors cancel on that fold.  No bar was written and fresh seeds 9271-9280 were NOT
drawn (left for a rule).  Left: a rule that reads the test rows' extrapolation at predict time (a
deployed guard falling back to MLR where the inputs leave the train range along a direction no
fold saw) is outside the train-side choice this brief allows; for one validation fold, a blend
kept only where it beats its best member by less than the fold's block SE (untested).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_automore69 as automore  # noqa: E402
from _cli import run_commands  # noqa: E402

TENTHS, FIFTHS = 10, 5


def rows(root: str, work: str, *records: str) -> None:
    from bench_auto_losses56 import lab_record

    root_path = Path(root).resolve()
    if "lab5401" in records and not (root_path / "lab5401").exists():
        lab_record(root_path / "lab5401")
    automore.rows(root_path, Path(work).resolve(), list(records))


def _row(work: Path, name: str) -> dict:
    return next(r for r in automore.remeasure._read(work / "automore.jsonl") if r["record"] == name)


def _parts(campaign: np.ndarray, n: int) -> np.ndarray:
    """Each row's part (0 .. n - 1) of its campaign's rows, in order."""
    out = np.zeros(len(campaign), int)
    for k in np.unique(campaign):
        rows_k = np.flatnonzero(campaign == k)
        out[rows_k] = np.minimum(np.arange(rows_k.size) * n // rows_k.size, n - 1)
    return out


def _ratio(y, predicted, base, keep) -> float:
    return float(np.sum((y - predicted)[keep] ** 2) / np.sum((y - base)[keep] ** 2))


def _one_fold_se(y, predicted, base, fold) -> tuple[float, float]:
    """One fold: its ratio and the SE of the ratio over bootstrap resamples of the blocks the votes
    resample (:func:`thermocomp.core.models.blend._nested_resamples`'s blocks)."""
    from thermocomp.core.model_selection.blocks import cut_blocks, decorrelation_length

    unit = np.unique(fold, return_inverse=True)[1]
    block = cut_blocks(np.zeros(len(y), int), unit,
                       decorrelation_length(y - base, unit, np.ones(len(y), bool)))
    kept, mlr = np.bincount(block, (y - predicted) ** 2), np.bincount(block, (y - base) ** 2)
    picks = np.random.default_rng(0).integers(0, kept.size, (500, kept.size))
    boots = kept[picks].sum(1) / mlr[picks].sum(1)
    return float(kept.sum() / mlr.sum()), float(np.std(boots, ddof=1))


def folds(work: str, *records: str) -> None:
    work_path = Path(work).resolve()
    for name in records:
        row = _row(work_path, name)
        print(f"== {name} (reference {row['reference']}; own test {row['own']})")
        for target, weights in row["weights"].items():
            a = np.load(work_path / "pred" / f"{name}.{target}.npz")
            y, fold, base = a["oof_y"], a["oof_fold"], a["oof_mlr"]
            y_new, new = automore.label(a, row["reference"]), a["campaign"] >= len(row["own"])
            new &= np.isfinite(y_new)
            ids = np.unique(fold)
            test = {m: _ratio(y_new, a[f"pred_{m}"], a["pred_mlr"], new)
                    for m in ("auto", *weights) if f"pred_{m}" in a.files}
            print(f" {target}: kept " + ", ".join(f"{m} {w:.2f}" for m, w in weights.items())
                  + f"; {ids.size} fold(s) of {[int((fold == k).sum()) for k in ids]} rows; auto / MLR "
                  f"on the new campaigns {np.sqrt(test['auto']):.3f}")
            for m in (k[4:] for k in a.files if k.startswith("oof_") and k not in ("oof_y", "oof_fold")):
                if m == "mlr":
                    continue
                per = [_ratio(y, a[f"oof_{m}"], base, fold == k) for k in ids]
                new_r = np.sqrt(_ratio(y_new, a[f"pred_{m}"], a["pred_mlr"], new))
                print(f"   {'*' if m in weights else ' '}{m:12s} folds / MLR "
                      + " ".join(f"{r:6.2f}" for r in per) + f"   new / MLR {new_r:6.3f}")
            if weights == {"mlr": 1.0}:
                continue
            blend = sum(w * a[f"oof_{m}"] for m, w in weights.items())
            per = np.array([_ratio(y, blend, base, fold == k) for k in ids])
            se = (f"mean {per.mean():.3f} + SE {per.std(ddof=1) / np.sqrt(per.size):.3f}" if per.size > 1
                  else "one fold: ratio %.3f + block-bootstrap SE %.3f" % _one_fold_se(y, blend, base, fold))
            print("    blend        folds / MLR " + " ".join(f"{r:6.2f}" for r in per) + f"   ({se})")
            part = _parts(a["campaign"], TENTHS)
            total = np.sum((y_new - a["pred_mlr"])[new] ** 2)
            excess = [np.sum(((y_new - a["pred_auto"]) ** 2 - (y_new - a["pred_mlr"]) ** 2)[new & (part == p)])
                      / total for p in range(TENTHS)]
            print("    new campaigns, auto's excess SSE over MLR's per tenth (of MLR's total): "
                  + " ".join(f"{e:+.3f}" for e in excess))


def _inputs(frame, columns) -> np.ndarray:
    """A campaign's inputs referenced at its first sample (``data.reference=first_sample``)."""
    values = frame[columns].to_numpy(float)
    return values - values[0]


def where(root: str, work: str, *records: str) -> None:
    import bench_auto_rank as rank

    from thermocomp.core.model_selection import BlockedForward
    from thermocomp.core.model_selection.extrapolation import within_range

    work_path = Path(work).resolve()
    for name in records:
        overrides = [o.format(root=Path(root).resolve()) for o in automore.OVERRIDES[name]]
        sys.argv[2:] = overrides                      # bench_auto_rank simulates when sim= is asked
        cfg, ds, train = rank.setup(overrides)
        frames = list(train.values())
        columns = [c for c in frames[0].columns if c.startswith("T_")]
        x_train = np.vstack([_inputs(f, columns) for f in frames])
        print(f"== {name}: {len(frames)} train campaign(s), {len(x_train)} rows, {len(columns)} inputs")
        if len(frames) == 1:
            groups = np.zeros(len(x_train), int)
            shares = [within_range(x_train, fit, score)[score].mean()
                      for fit, _, score in BlockedForward(5, 0.5, 0.5).folds(groups, len(x_train))]
            print("  forward folds' blocks in range of their fit rows: " + " ".join(f"{s:.2f}" for s in shares))
        row = _row(work_path, name)
        news = automore.draws(automore.OF[name], work_path, cfg)
        tests = [ds.campaigns[c] for c in row["own"]] + [d.campaigns[c] for d in news for c in d.ids()]
        in_range = []
        for frame in tests:
            x = np.vstack([x_train, _inputs(frame, columns)])
            fit = np.arange(len(x)) < len(x_train)
            in_range.append(within_range(x, fit, ~fit)[~fit])
        in_range = np.concatenate(in_range)
        a = np.load(work_path / "pred" / f"{name}.{next(iter(row['weights']))}.npz")
        new, part = a["campaign"] >= len(row["own"]), _parts(a["campaign"], TENTHS)
        print("  new campaigns in range of the train record, per tenth: "
              + " ".join(f"{in_range[new & (part == p)].mean():.2f}" for p in range(TENTHS)))
        for target, weights in row["weights"].items():
            if weights == {"mlr": 1.0}:
                continue
            a = np.load(work_path / "pred" / f"{name}.{target}.npz")
            y = automore.label(a, row["reference"])
            keep = new & np.isfinite(y)
            excess = ((y - a["pred_auto"]) ** 2 - (y - a["pred_mlr"]) ** 2)
            out = np.sum(excess[keep & ~in_range]) / np.sum(excess[keep])
            print(f"  {target}: auto / MLR {np.sqrt(_ratio(y, a['pred_auto'], a['pred_mlr'], keep)):.3f}; "
                  f"share of auto's excess SSE in out-of-range rows {out:.2f} (rows out of range "
                  f"{np.mean(~in_range[keep]):.2f})")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"rows": rows, "folds": folds, "where": where}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
