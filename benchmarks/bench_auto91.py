"""``model=auto`` on the records with one train record (or one validation fold) that lose to MLR:
which blend the folds keep, each member's fold ratios, and where in the test the loss lies
(issue 34; stop 91, auto91).  TRACED (no rule)

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code and conf measured are that
tree's; ROOT holds lab5401's written record, WORK the rows)::

    python benchmarks/bench_auto91.py rows ROOT WORK RECORD ...    # bench_automore69's rows
    python benchmarks/bench_auto91.py folds WORK RECORD ...        # kept blend, per-fold ratios
    python benchmarks/bench_auto91.py where ROOT WORK RECORD ...   # the loss in time, in range
    python benchmarks/bench_auto91.py guard ROOT WORK RECORD ...   # a probe: MLR out of range
    python benchmarks/bench_auto91.py rooms RECORD ...             # the probe on climate rooms

``rows``: lab5401's record written into ROOT where absent (bench_auto_losses56's ``lab_record``),
then bench_automore69's ``rows`` (auto and every candidate alone fitted on the record's train part,
scored on its own test and on the 12 new campaigns of its machine, seeds 6911-6922, already
looked at; their out-of-fold and test predictions kept in WORK/pred).  ``folds``: per target, the
kept weights, every member's summed squared error over MLR's per validation fold (the votes'
measure), the blend's, the figures the one-SE fallback reads (mean + SE over the folds; with one
fold, its ratio + the SE over bootstrap resamples of the blocks the votes resample), each member's
test RMSE over MLR's on the new campaigns, auto's excess squared error over MLR's per tenth of the
new campaigns (a share of MLR's total), and each kept member's ratio per fifth of the folds' rows
and of the new campaigns (does its error grow with a horizon the folds do not reach?).  ``where``:
whether each row's inputs (the ``T_`` columns less the campaign's first sample, as
``data.reference=first_sample`` takes them) lie within the leverage range of the train rows
(:func:`thermocomp.core.model_selection.extrapolation.within_range`): each forward fold's block
against its fit rows, the new campaigns per tenth against the whole train record, and per target
with a blend the share of auto's excess squared error in out-of-range rows.  ``guard``: a probe,
not a rule (it reads the deployed rows' inputs): auto's prediction replaced by MLR's in the rows
out of range; the record's figure (mean over targets of the new campaigns' pooled RMSE) over MLR's.
``rooms``: the same probe on climate rooms of bench_auto88b's :data:`RECORDS` (several campaigns,
scored on their own test campaigns; auto and MLR fitted again here, simulated in memory).

The question (stop 90's "what remains": 8 of 22 records worse than MLR on their new campaigns, the
largest the column's, col5791 x1.258, col1403 x1.311, and lab5401 x1.070): is the loss the test
extrapolating past the last fold's operating range, a member whose error grows with a horizon longer
than the fold's, or folds shorter than the test?  A rule only where a general cause showed.

Traced (2026-12-05; this tree = main 277a181d; 2 shared cores, load 2-3, ``OMP_NUM_THREADS=1``;
``rows /tmp/auto91/root /tmp/auto91/seen col5791 col1403 lab5401 col1514 col6512 swiss303
swiss5454 year6511 year6_5411 mill1514``, then ``folds``, ``where`` and ``guard`` on them; CPU of
the rows 17 / 13 / 6 / 13 / 13 s for the first five, 60 s for the other five)
-------------------------------------------------------------------------------------------------
auto / MLR on the new campaigns as stop 90 has them: col5791 1.258, col1403 1.311, lab5401 1.070,
col1514 1.019, col6512 1.004 (swiss303 0.569, swiss5454 0.950, year6511 0.351, year6_5411 0.518,
mill1514 1.000).

* Not the horizon.  The column (``column_moving_source``): ONE train campaign of 1441 rows (40 h);
  its test a separate 40 h cycle of 1441 rows referenced at its own first sample (a new campaign,
  not a continuation: shifted ambient, and a source, Q3, that the train record never runs, from 50
  to 75 % of the cycle).  auto's folds: 5 forward blocks of 144 rows over the later half, each
  predicted in free run from the record's start: horizons of 793-1441 rows, the test's 1441.
  lab5401: three 10 h train runs, a 12 h test run; campaign folds, min_train_fraction 0.5 leaves
  ONE fold (Lauf_3, 1200 rows; the test 1441).  The members' error does not grow across the fold
  (col1403 E_Y lagbank per fifth of the blocks 0.41 0.45 0.41 0.59 0.29 x MLR; lab5401 E_Z arx
  1.30 2.26 0.26 1.51 0.78); on the new campaigns it grows (lab5401's arx 1.51 4.41 5.33 6.80
  7.68) or peaks where Q3 runs (col5791 E_Z_mid's lag bank 0.17 0.87 12.23 13.21 3.70): the test's
  conditions, not a horizon the folds miss.
* Where the column loses: in the tenths 6-8 of the cycle (Q3 running), where the inputs leave the
  train record's range: the new campaigns' in-range share per tenth 0.47 0.42 0.57 0.40 0.72 0.03
  0.00 0.00 0.09 0.48 (col5791; col1403, col1514, col6512 alike, 0.00-0.02 in tenths 6-8).
  col5791 E_Z_mid (lagbank 0.81, arx 0.02, hammerstein 0.02, MLR 0.15; 2.944 x MLR): auto's excess
  per tenth -0.007 -0.024 -0.008 +0.004 +0.002 +1.238 +3.286 +2.977 +0.204 -0.005 (of MLR's total
  SSE).  Share of auto's excess SSE in out-of-range rows (the rows out of range): col5791 E_Z 1.00,
  E_X_mid 1.00, E_Z_mid 1.00 (0.68); col1514 E_Z_mid 0.90 (0.73); col6512 E_X_mid 1.00, E_Z_mid
  0.97 (0.76); col1403 E_Y 0.80, E_Y_mid 0.92 (0.64).  The forward folds extrapolate too (col5791's
  blocks in range of their fit rows 0.00 0.17 0.50 0.92 0.97, col1403's 0.00 0.00 0.76 0.99 1.00,
  col1514's 0.01 0.00 0.58 1.00 1.00), but along the record's own warming, where the lag families
  win (col5791 E_Z_mid lagbank per fold 1.04 1.14 0.13 0.11 0.92 x MLR, the blend 1.03 0.68 0.09
  0.08 0.48, one-SE 0.473 + 0.181: kept; col1403 E_Y blend 0.29 0.06 0.92 0.42 0.59, 0.457 +
  0.145; E_Y_mid 0.22 0.20 0.33 0.80 0.88, 0.485 + 0.148), never along Q3's, which no part of the
  train record holds.
* col1403 loses in range as well (E_Y's excess per tenth -0.028 +0.126 +0.270 +0.211 +0.210
  +1.077 +0.301 +0.103 +0.168 -0.003): a new campaign starts its frame and its states afresh where
  no fold of one record does (auto86: a restarted block and a shifted frame both read this loss and
  the Swiss lathe's right hammerstein as failing alike; refused there).
* lab5401 (one fold: the votes resample its blocks; the one-SE fallback needs k >= 2 folds and
  is off): E_Z keeps MLR 0.57, lstm 0.28, arx 0.15 (1.187 x MLR on the new campaigns): on Lauf_3
  arx 0.97, lstm 0.96, the blend 0.67 x MLR: the members' errors cancel on the one fold and not on
  the new runs, where arx's error grows with the hour (above).  E_Y (lagbank 0.04) 1.047 x.  A
  one-SE rule on the fold's blocks (the fold's ratio + the bootstrap SE over the 4-6 blocks the
  votes use) would keep every blend: E_X 0.963 + 0.014, E_Y 0.902 + 0.034, E_Z 0.666 + 0.069; it
  does not fire, so it was not written as a rule.  Two folds instead (probe: bench_automore69's
  ``rows`` with ``model.estimator.min_train_fraction=0.33``, Lauf_2 and Lauf_3 validate; into
  /tmp/auto91/probe2f): lab5401 1.070 -> 1.29 x MLR (E_X keeps a zero correction, 1.785 x: the
  Lauf_2 fold, fitted on one run, sends it there; E_Z 1.187 -> 1.041).  With 52 inputs and 3600
  train rows the new runs are out of range from their third tenth (0.27 0.12 0.03 0.00 ...): the
  range says little here.
* The brief's candidate rules, each read from these figures without a refit: folds as long as
  the test (they are: above); folds weighted to the latest (the last folds keep the losing blends:
  col5791 E_Z_mid 0.48, col1403 E_Y 0.59, E_Y_mid 0.88, col1514 E_Z_mid 0.36 x MLR); the one-SE
  rule on forward folds (main's fallback; the losing blends pass it, above).  None touches them.
* ``guard`` (the probe, reading the deployed rows' inputs, so not a train-side rule and not
  proposed): auto / MLR col5791 1.258 -> 0.999, col1403 1.311 -> 1.074, lab5401 1.070 -> 1.000
  (0.96 of its rows out of range: MLR nearly everywhere), col1514 1.019 -> 1.003, col6512 1.004 ->
  1.000; swiss303, swiss5454, year6511, mill1514 unchanged (0.00-0.17 out of range); year6_5411
  0.518 -> 0.744 (0.22 out of range: ATI's win at ambient levels outside the train span is lost).
  On 13 seen climate rooms (``rooms cr9031 cr9076 cr9079 cr9081 cr9083 cr9088 cr9089 cr9181
  cr9182 cr9183 cr9244 cr9248`` and ``rooms cr9245``; 6 s CPU a room; auto refitted here is within
  0.4 % of the stored rows but for cr9079, 0.882 against 0.850), auto -> guarded (µm, mean of E_X /
  E_Z): cr9245 2.485 -> 2.049 (MLR 1.922: the one loss mended in part), but cr9079 0.882 -> 1.889,
  cr9182 1.268 -> 1.803, cr9248 0.798 -> 1.041, cr9244 0.869 -> 1.113, cr9181 0.655 -> 0.736,
  cr9183 1.421 -> 1.517; cr9031 / 9076 / 9081 / 9083 / 9088 / 9089 within 0.3 %.  Geo guarded /
  auto 1.133 over the 13, six rooms more than 2 % worse: out of the train range is where the
  wins of ATI and the lag families lie too, so the range alone does not mark the losses.

Verdict: TRACED, no rule, src as on main.  The column's losses lie where its test runs a source
the train record never runs (its inputs outside the record's range, a direction no fold can hold);
col1403's also in range, where a new campaign's fresh start misleads the lag families (auto86's
ground); lab5401's is a one-fold blend whose members' errors cancel on that fold.  None has a
train-side signal here, so no bar was written and fresh seeds 9271-9280 were NOT drawn (left for a
rule).  Left: a deployed fallback to MLR where the inputs leave the train range cures the column
and lab5401 on these rows but costs year6_5411's ATI win (0.518 -> 0.744) and the climate rooms'
(geo x1.133 on 13, above); a version that keeps
extrapolation along directions the folds did see would have to tell ATI's ambient (right beyond the
span on year6_5411, wrong on cr9245, ati90) from the column's Q3, and it reads the deployed inputs:
a runtime guard, outside the train-side choice; for one validation fold, a blend that beats each of
its members on that fold by more than their own margins over MLR (lab5401 E_Z 0.67 against 0.96 /
0.97) is a cancellation that did not carry to new runs here (one record: a lead, not a finding).
"""

from __future__ import annotations

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


def stored_targets(work: Path, name: str):
    """Per target of ``name``'s stored row in WORK: ``(target, kept weights, its npz arrays, the
    label as scored, the new campaigns' scored rows, the members' out-of-fold predictions)``."""
    row = _row(work, name)
    for target, weights in row["weights"].items():
        a = np.load(work / "pred" / f"{name}.{target}.npz")
        y_new = automore.label(a, row["reference"])
        new = (a["campaign"] >= len(row["own"])) & np.isfinite(y_new)
        members = {k[4:]: a[k] for k in a.files if k.startswith("oof_") and k not in ("oof_y", "oof_fold")}
        yield target, weights, a, y_new, new, members


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
            gap = (y_new - a["pred_auto"]) ** 2 - (y_new - a["pred_mlr"]) ** 2
            excess = [np.sum(gap[new & (part == p)]) / total for p in range(TENTHS)]
            print("    new campaigns, auto's excess SSE over MLR's per tenth (of MLR's total): "
                  + " ".join(f"{e:+.3f}" for e in excess))
            # a horizon longer than the folds': each kept member's ratio per fifth of a fold (its
            # rows in time order, the folds pooled) and per fifth of the new campaigns
            fifth, fifth_new = _parts(fold, FIFTHS), _parts(a["campaign"], FIFTHS)
            for m in (m for m in weights if m != "mlr"):
                in_folds = [_ratio(y, a[f"oof_{m}"], base, fifth == p) for p in range(FIFTHS)]
                in_new = [_ratio(y_new, a[f"pred_{m}"], a["pred_mlr"], new & (fifth_new == p))
                          for p in range(FIFTHS)]
                print(f"    {m} / MLR per fifth: folds " + " ".join(f"{r:5.2f}" for r in in_folds)
                      + "; new campaigns " + " ".join(f"{r:5.2f}" for r in in_new))


def _inputs(frame, columns) -> np.ndarray:
    """A campaign's inputs referenced at its first sample (``data.reference=first_sample``)."""
    values = frame[columns].to_numpy(float)
    return values - values[0]


def _in_range_rows(x_train: np.ndarray, frames, columns) -> list[np.ndarray]:
    """Per campaign of ``frames``, each row's inputs within the leverage range of ``x_train``."""
    from thermocomp.core.model_selection.extrapolation import within_range

    flags = []
    for frame in frames:
        x = np.vstack([x_train, _inputs(frame, columns)])
        fit = np.arange(len(x)) < len(x_train)
        flags.append(within_range(x, fit, ~fit)[~fit])
    return flags


def _in_range(root: str, work_path: Path, name: str):
    """``(row, in_range, shares)``: the stored row of ``name``, per row of its stored test arrays
    (own test, then the new campaigns) whether its inputs lie in the train record's range, and
    the in-range share of each forward fold's block against its fit rows (one train record)."""
    import bench_auto_rank as rank

    from thermocomp.core.model_selection import BlockedForward
    from thermocomp.core.model_selection.extrapolation import within_range

    overrides = [o.format(root=Path(root).resolve()) for o in automore.OVERRIDES[name]]
    sys.argv[2:] = overrides                      # bench_auto_rank simulates when sim= is asked
    cfg, ds, train = rank.setup(overrides)
    frames = list(train.values())
    columns = [c for c in frames[0].columns if c.startswith("T_")]
    x_train = np.vstack([_inputs(f, columns) for f in frames])
    shares = []
    if len(frames) == 1:
        groups = np.zeros(len(x_train), int)
        shares = [float(within_range(x_train, fit, score)[score].mean())
                  for fit, _, score in BlockedForward(5, 0.5, 0.5).folds(groups, len(x_train))]
    row = _row(work_path, name)
    news = automore.draws(automore.OF[name], work_path, cfg)
    tests = [ds.campaigns[c] for c in row["own"]] + [d.campaigns[c] for d in news for c in d.ids()]
    flags = _in_range_rows(x_train, tests, columns)
    print(f"== {name}: {len(frames)} train campaign(s), {len(x_train)} rows, {len(columns)} inputs")
    return row, np.concatenate(flags), shares


def where(root: str, work: str, *records: str) -> None:
    work_path = Path(work).resolve()
    for name in records:
        row, in_range, shares = _in_range(root, work_path, name)
        if shares:
            print("  forward folds' blocks in range of their fit rows: "
                  + " ".join(f"{s:.2f}" for s in shares))
        a = np.load(work_path / "pred" / f"{name}.{next(iter(row['weights']))}.npz")
        assert len(a["campaign"]) == len(in_range), name
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


def guard(root: str, work: str, *records: str) -> None:
    """A probe, not a rule (it reads the deployed rows' inputs, not the train side): auto's
    prediction replaced by MLR's wherever the row's inputs lie outside the train record's range;
    per record the mean over targets of the pooled RMSE on the new campaigns, over MLR's."""
    work_path = Path(work).resolve()
    for name in records:
        row, in_range, _ = _in_range(root, work_path, name)
        figures = {"auto": [], "guarded": [], "mlr": []}
        for target in row["weights"]:
            a = np.load(work_path / "pred" / f"{name}.{target}.npz")
            y = automore.label(a, row["reference"])
            keep = (a["campaign"] >= len(row["own"])) & np.isfinite(y)
            guarded = np.where(in_range, a["pred_auto"], a["pred_mlr"])
            for key, predicted in (("auto", a["pred_auto"]), ("guarded", guarded), ("mlr", a["pred_mlr"])):
                figures[key].append(np.sqrt(np.mean((y - predicted)[keep] ** 2)))
        auto, guarded, mlr = (float(np.mean(figures[k])) for k in ("auto", "guarded", "mlr"))
        out = 1 - in_range[a["campaign"] >= len(row["own"])].mean()
        print(f"  {name}: new campaigns out of range {out:.2f}; "
              f"auto / MLR {auto / mlr:.3f} -> guarded {guarded / mlr:.3f}")


def room(name: str):
    """``(ds, ids, columns, x_train, series)`` of the climate room ``name`` (bench_auto88b's
    :data:`RECORDS`): auto and MLR fitted on its train campaigns, its test campaign ids, the ``T_``
    columns, the train inputs (:func:`_inputs`, stacked) and per model (``auto``, ``mlr``) the
    simulation-mode residual series as ``run`` scores them."""
    import bench_auto88b as auto88b
    import bench_auto_rank as rank
    from sklearn.base import clone

    from thermocomp.core.scoring.evaluation import split_residuals
    from thermocomp.shell.builders import build_compensator

    overrides = list(auto88b.RECORDS[name])
    sys.argv[2:] = overrides
    cfg, ds, train = rank.setup(overrides)
    auto = build_compensator(cfg, ds=ds).fit(train)
    mlr = clone(auto).set_params(estimator=rank._mlr()).fit(train)
    ids = ds.ids("test")
    columns = [c for c in next(iter(train.values())).columns if c.startswith("T_")]
    x_train = np.vstack([_inputs(f, columns) for f in train.values()])
    series = {k: split_residuals(m, ds, ids, "simulation")[2] for k, m in (("auto", auto), ("mlr", mlr))}
    return ds, ids, columns, x_train, series


def rooms(*records: str) -> None:
    """``guard`` on climate rooms (bench_auto88b's :data:`RECORDS`: several campaigns, the test
    campaigns their own): auto and MLR fitted on the train campaigns, each test campaign predicted
    as ``run`` scores it; the guard's rows out of range of all train rows (inputs less each
    campaign's first sample); mean over targets of the pooled test RMSE, over MLR's."""
    for name in records:
        ds, ids, columns, x_train, series = room(name)
        flags = dict(zip(ids, _in_range_rows(x_train, [ds.campaigns[c] for c in ids], columns)))
        figures = {"auto": [], "guarded": [], "mlr": []}
        for t in series["auto"]:
            y = np.concatenate([series["auto"][t][0][c] for c in ids])
            r_auto = np.concatenate([series["auto"][t][1][c] for c in ids])
            r_mlr = np.concatenate([series["mlr"][t][1][c] for c in ids])
            ok = np.concatenate([flags[c] for c in ids])
            keep = np.isfinite(y)
            for key, r in (("auto", r_auto), ("guarded", np.where(ok, r_auto, r_mlr)), ("mlr", r_mlr)):
                figures[key].append(np.sqrt(np.mean(r[keep] ** 2)))
        a, g, m = (float(np.mean(figures[k])) for k in ("auto", "guarded", "mlr"))
        out = 1 - np.concatenate(list(flags.values())).mean()
        print(f"  {name}: test rows out of range {out:.2f}; auto {a:.4f}, guarded {g:.4f}, MLR {m:.4f}: "
              f"auto / MLR {a / m:.3f} -> guarded {g / m:.3f}", flush=True)


def main(argv: list[str]) -> int:
    commands = {"rows": rows, "folds": folds, "where": where, "guard": guard, "rooms": rooms}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
