"""``model=auto`` worse than MLR on 8 of the 22 records: would a vote that one blown-up fold cannot
carry (medians, capped ratios, a count of folds won) separate the losses from the wins?  (issue 34;
stop 87, auto87b)  Traced: NO -- no rule, no src change.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the vote code is that tree's; every
command reads stored rows only, nothing is fitted)::

    python benchmarks/bench_auto87b.py trace STORE RECORD ...     # per target: folds, new, drops
    python benchmarks/bench_auto87b.py votes STORE ...            # the 22 / seen records re-voted
    python benchmarks/bench_auto87b.py agree STORE ...            # fold statistics against new

STORE: a WORK of bench_automore69's ``rows`` (``automore.jsonl`` and ``pred/RECORD.TARGET.npz``:
every validated candidate's out-of-fold free-run predictions on auto's folds, ``oof_*``, and its
predictions, fitted on the train campaigns, on the record's own test and new campaigns,
``pred_*``).  :func:`choose` is auto's choice again from the out-of-fold arrays (``vote_weights``,
the one-SE fallback, the zero rule, as ``AutoRegressor._blend``); ``votes`` checks that it gives
every stored target's kept weights before it re-votes, so a variant's figure is what the src
would have deployed with that vote (each member is fitted alone as in the Blend: the blend's
prediction is the weighted sum of the stored ``pred_*``, to 1e-13).  ``trace``: per target, the
kept weights and auto / MLR pooled RMSE on the new campaigns; per candidate its RMSE over MLR's
there and its per-fold MSE over MLR's (``fold_ratios``: the votes' measure) with their mean,
median, mean capped at 2 and the folds won; then the kept choice again with each fold left out.
``votes``: per record, auto / MLR on the new campaigns (bench_automore69's record figure: mean
over targets of the pooled RMSE) with the shipped vote (``mean``) and the variants of
:data:`VARIANTS`.  ``agree``: every kept blend that is not MLR alone, its fold ratios beside its
new-campaign ratio; every candidate, how often each fold statistic puts it on the side of MLR the
new campaigns put it.  The new campaigns are read, never chosen by: this is a trace, no rule is
taken from it.

Stores read: /tmp/auto80/new (the 22, shipped rows; the ratios in the brief are these) and the
fresh records of the stops since (``fresh_old``: main's code of the day, most with one train campaign,
the new campaigns of their machines): /tmp/auto82b, auto84, auto84b, auto84c, auto85, auto85b,
auto85c, auto86 -- 52 records (columns, Swiss lathes, lab mills, mill weeks, year-round
spindles, an HMC, a grinder), looked at by those stops for their own rules, never for a vote form.
``choose`` gives the stored weights on every target of all 74 (the three zero-weight targets of
grind_a, grind_b and grind8903 name their members differently, same prediction 0).

Traced (2026-12-04, this tree at main 25b18da6's src; ``trace /tmp/auto80/new`` on the 8 and 4
winners, ``votes`` and ``agree`` on the 22 and the 52; CPU user + sys 0.9 to 3.1 s a command)
------------------------------------------------------------------------------------------------
1. The losses are carried by a dozen targets whose kept blend wins EVERY fold or all but one,
   by much; the new campaigns disagree.  Kept blend's fold MSE over MLR's -> its new RMSE over
   MLR's (the candidate's figures where one member carries it):

   * col5791 E_Z_mid (lagbank 0.81): blend 1.03 0.68 0.09 0.08 0.48 -> 2.94 (record 1.258);
     lagbank 1.04 1.14 0.13 0.11 0.92 (median 0.92, mean 0.67) -> 3.36.
   * col1403 E_Y (lagbank 0.84): 0.29 0.06 0.92 0.42 0.59 -> 1.85; E_Y_mid (lagbank 0.36,
     hammerstein 0.64): 0.22 0.20 0.33 0.80 0.88 -> 2.08 (record 1.311).
   * col1514 E_Z_mid (mlr 0.41, hammerstein 0.41, lagbank 0.18): 0.85 0.31 0.77 1.48 0.36 -> 1.61.
   * col6512 E_X_mid (arx 0.65): 0.60 0.97 0.97 1.02 1.00 -> 1.07.
   * lab5401 (one fold, its blocks resampled): E_Z 0.67 -> 1.19, E_Y 0.90 -> 1.05.
   * hmc E_CH15_Disp_Y (hammerstein 1.0): 0.39 0.92 0.48 -> 1.08.
   * iso_a E_Tilt_B (ati 1.0): 0.08 0.86 -> 1.53; E_X1 0.86 0.95 -> 1.09.
   * mtc_b E_dX (hammerstein 1.0): 0.24 0.37 0.15 -> 1.12; E_dZ 0.30 0.27 0.19 -> 1.05.

   The test's verdict agrees with neither the median fold nor the mean: both are below 1 on every
   one of these.  No fold decides: the kept choice re-voted with each fold left out stays a loss
   (col5791 E_Z_mid 3.04 3.18 2.18 2.18 2.53, col1403 E_Y 1.84 1.70 2.08 1.48 1.48, E_Y_mid
   2.08 2.21 1.93 2.08 2.06, hmc 1.08 x3, mtc_b E_dX 1.12 x3); col1514 E_Z_mid alone is a near
   thing: 1.35 2.99 without fold 0 / 3, MLR (the one-SE, 1.00) without fold 1, 2 or 4.
2. The winners look the same on their folds: swiss303 E_X / E_Y (hammerstein 1.0) 0.47 0.50 0.24
   0.30 0.31 / 0.28 0.68 0.25 0.37 0.24 -> 0.57 / 0.57; mtc_a E_dY (lagbank 1.0) 0.42 0.37 0.36
   -> 0.70; tsc_a2 E_dZ1 0.01 0.02 -> 0.10.  A median or capped vote changes nothing on swiss303
   and tsc_a2 (0.569, 0.376), swiss5454 0.950 -> 0.866 (median) / 0.871 (cap 2), year6511 0.351
   -> 0.353 / 0.355, mtc_a 0.704 -> 0.703 / 0.709, twin_lathe 0.973 -> 0.966 / 0.973.
3. One blown-up fold does not carry any kept blend: the one-SE fallback already sends a blend
   with a bad fold to MLR; of the 157 kept blends (the 22 and the 52) the largest fold is 1.67 x
   MLR (col8301 E_Z, new 0.358), the next 1.48 (col1514 E_Z_mid), none above 2.  Blown-up folds
   are among the candidates voted OUT, some right on new campaigns
   (col1403 E_Z hammerstein 0.08 1.89 1.25 8.95 3.48 -> 0.35; col1514 E_Y lagbank 0.26 7.14 11.6
   0.16 6.54 -> 0.59; iso_a E_Z hammerstein 1061 0.05 -> 0.65), some rightly out (col5791 E_X
   lagbank 1.47 19.4 65.8 2.11 23.7 -> 10.7).
4. Over every candidate of every target (1292: the 22's 407, the 52's 885), the side of MLR a fold
   statistic puts it on agrees with the new campaigns' side: mean 0.65, median 0.66, mean capped
   at 2 0.65, geometric mean 0.65, share of folds lost (< half) 0.66; Spearman with the new ratio
   +0.49 +0.49 +0.47 +0.49 +0.41.  What the folds know about new campaigns limits the vote, not
   the vote's form.
5. The votes re-run (auto / MLR on the new campaigns; worse than MLR, geometric mean, records more
   than 2 % worse than the shipped vote):

   ====================  =======================  ==========================================
   vote                  the 22                   the 52 seen fresh records
   ====================  =======================  ==========================================
   mean (shipped)        8, 0.8264                10, 0.7823
   median                8, 0.8104, none          8, 0.7934, 14 (col8802 0.691 -> 0.895,
                                                  swiss8804 0.577 -> 0.820, labmill8870
                                                  0.837 -> 1.002, col8957 1.183 -> 1.320, ...)
   mean capped at 2      7, 0.8207, none          10, 0.7773, 6 (col8302 0.922 -> 0.979,
                                                  col8732 1.013 -> 1.079, col8957 1.183 ->
                                                  1.286, col8951, col8747, year6_8897)
   capped at 3           8, 0.8254, none          10, 0.7821, 3 (col8302, col8747, year6_8897)
   capped at 5           8, 0.8264, none          10, 0.7823, none (changes nothing)
   share of folds won    8, 0.8154, none          11, 0.7887, 10
   ====================  =======================  ==========================================

   On the 22: median col5791 1.258 -> 1.106, col1514 1.019 -> 0.879, col1403 1.311 -> 1.247 but
   col6511 0.996 -> 1.003; cap 2 col1514 -> 0.961, col6511 -> 0.979, col5791 -> 1.249.  What a
   form wins on the 22 it loses on the 52 (the median: 14 records > 2 % worse, the geometric mean
   up), or it is the shipped vote (cap 5).  Each would fail the brief's bar on fresh records (no
   record > 2 % worse than main): NO vote form separates the losses, so no rule was written, no
   fresh draw made (seeds 9091-9100 unused), nothing scored against a bar.

What to try next (from this trace; hypotheses, none measured against a bar)
---------------------------------------------------------------------------
* The losses are transfer, not voting: the folds of one record (forward blocks continuing it)
  and of 2-3 campaigns agree among themselves and disagree with new campaigns.  A signal has to
  come from outside the fold ratios.  bench_auto86 (restarted / shifted blocks) and bench_auto84
  (static parts) found none on one record; a next stop should not re-try vote forms.
* Fold count (``agree``): kept blends validated on <= 3 folds lose to MLR on new campaigns 15 of
  29 times (6 by > 10 %: lab5401 E_Z, iso_a E_Tilt_B, iso_b E_X1, mtc_b E_dX, hmc8902's two), on
  5 folds 28 of 122 (11 by > 10 %).  With few
  folds the one-SE's standard error is itself one of 2-3 numbers; a rule that asks more of a blend
  there (e.g. the blocks' resampling, which auto uses below n_folds for the votes, also for the
  fallback) is testable -- on fresh seeds of its own, its bar before scoring.
* The column's test cycle runs the unseen source Q3 (bench_automore69): an input no train fold
  saw.  A check on the new campaign's inputs against the train range belongs to the monitor
  (deployed = scored), not to the choice.
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

ORDER = ("mlr", "pcr", "arx", "lagbank", "hammerstein", "lstm", "ati")   # conf/model/auto.yaml's
N_RESAMPLES, WORSE = 500, 1.02


def _rmse(e) -> float:
    return float(np.sqrt(np.mean(np.square(e))))


def _draws(squared, y, fold, base, blocks: bool) -> np.ndarray:
    """(resample, drawn fold, candidate) ratios: blend._nested_resamples' draws, not averaged."""
    from thermocomp.core.model_selection.blocks import cut_blocks, decorrelation_length

    n_folds = fold.max() + 1
    block = (cut_blocks(np.zeros(len(y), int), fold,
                        decorrelation_length(y - base, fold, np.ones(len(y), bool))) if blocks else fold)
    sse = np.vstack([squared[block == b].sum(axis=0) for b in range(block.max() + 1)])
    rng = np.random.default_rng(0)
    picks = rng.integers(0, n_folds, (N_RESAMPLES, n_folds))
    out = np.zeros((N_RESAMPLES, n_folds, squared.shape[1] - 1))
    for f in range(n_folds):
        own = np.unique(block[fold == f])
        draws, slot = np.nonzero(picks == f)
        counts = rng.multinomial(own.size, np.full(own.size, 1.0 / own.size), size=draws.size)
        drawn = counts @ sse[own]
        out[draws, slot] = drawn[:, :-1] / np.maximum(drawn[:, -1:], 1e-300)
    return out


def vote_by(aggregate, sure_by=None):
    """``vote_weights`` with the drawn folds' ratios combined by ``aggregate`` (the shipped one:
    their mean) and MLR's share by ``sure_by`` (default the same)."""
    from thermocomp.core.models.blend import MIN_WEIGHT

    def vote(predictions, y, fold, base, base_column, min_folds):
        unit = np.unique(fold, return_inverse=True)[1]
        squared = np.column_stack([(y[:, None] - predictions) ** 2, (y - base) ** 2])
        d = _draws(squared, y, unit, base, unit.max() + 1 < min_folds)
        w = np.bincount(np.argmin(aggregate(d), axis=1), minlength=predictions.shape[1]) / N_RESAMPLES
        sure = np.mean((sure_by or aggregate)(d) < 1.0, axis=0)
        sure[base_column] = 1.0
        w, doubt = w * sure, w * (1.0 - sure)
        w[base_column] += doubt.sum()
        w[w < MIN_WEIGHT] = 0.0
        return w / w.sum()
    return vote


def _won(d):
    return -(d < 1).mean(axis=1) + 1e-3 * d.mean(axis=1)   # folds won, ties by the mean


VARIANTS = {"mean": vote_by(lambda d: d.mean(axis=1)), "median": vote_by(lambda d: np.median(d, axis=1)),
            "cap2": vote_by(lambda d: np.minimum(d, 2.0).mean(axis=1)),
            "cap3": vote_by(lambda d: np.minimum(d, 3.0).mean(axis=1)),
            "cap5": vote_by(lambda d: np.minimum(d, 5.0).mean(axis=1)),
            "won": vote_by(_won, lambda d: d.mean(axis=1))}


def choose(a, vote=None, n_folds: int = 5) -> dict:
    """Auto's kept weights from the stored out-of-fold arrays ``a``: the votes (``vote``: the
    shipped ``vote_weights``), the one-SE fallback, the zero rule (AutoRegressor._blend's)."""
    from thermocomp.core.models.blend import fold_ratios, mean_fold_ratio, vote_weights

    names = [n for n in ORDER if f"oof_{n}" in a]
    y, f, mlr = a["oof_y"], a["oof_fold"], a["oof_mlr"]
    preds = np.column_stack([a[f"oof_{n}"] for n in names])
    w = (vote or vote_weights)(preds, y, f, mlr, base_column=names.index("mlr"), min_folds=n_folds)
    weights, pred = {n: float(v) for n, v in zip(names, w) if v > 0}, preds @ w
    if weights != {"mlr": 1.0}:
        r = fold_ratios((y - pred) ** 2, (y - mlr) ** 2, f)
        if r.size >= 2 and np.mean(r) + np.std(r, ddof=1) / np.sqrt(r.size) >= 1.0:
            weights, pred = {"mlr": 1.0}, mlr
    if _rmse(y - pred) >= _rmse(y):
        base = (y - mlr) ** 2
        if not 2.0 * mean_fold_ratio((y - pred) ** 2, base, f) < mean_fold_ratio(y ** 2, base, f):
            weights = {k: 0.0 for k in weights}
    return weights


def _load(store: Path) -> dict:
    return {r["record"]: r for r in map(json.loads, (store / "automore.jsonl").read_text().splitlines())}


def _arrays(store: Path, name: str, target: str) -> dict:
    with np.load(store / "pred" / f"{name}.{target}.npz") as a:
        return {k: a[k] for k in a.files}


def _new(a: dict, row: dict, predicted) -> float:
    """Pooled RMSE over the record's new campaigns, in the frame the stored squares were in."""
    y = automore.label(a, row["reference"])
    keep = (a["campaign"] >= len(row["own"])) & np.isfinite(y)
    return _rmse(y[keep] - np.broadcast_to(predicted, y.shape)[keep])


def _nonzero(weights: dict) -> dict:
    return {k: round(v, 9) for k, v in weights.items() if v}


def _deployed(a: dict, weights: dict):
    return sum(v * a[f"pred_{n}"] for n, v in weights.items()) if sum(weights.values()) > 0 else 0.0


def _ratios(a: dict, name: str) -> np.ndarray:
    from thermocomp.core.models.blend import fold_ratios

    y = a["oof_y"]
    return fold_ratios((y - a[f"oof_{name}"]) ** 2, (y - a["oof_mlr"]) ** 2, a["oof_fold"])


def trace(store: Path, names: list[str]) -> None:
    rows = _load(store)
    for name in names:
        row = rows[name]
        print(f"== {name} ({row['machine']}, {len(row['own'])} train campaign(s)): auto / MLR new "
              f"{automore.summary(row)['to_mlr'][1]:.3f}")
        for t, w in row["weights"].items():
            a = _arrays(store, name, t)
            mlr = _new(a, row, a["pred_mlr"])
            print(f"  {t}: kept {({k: round(v, 2) for k, v in w.items()})}; auto / MLR new "
                  f"{_new(a, row, a['pred_auto']) / mlr:.3f}")
            for n in ORDER[1:]:
                if f"oof_{n}" in a:
                    r = _ratios(a, n)
                    print(f"    {n:11s} new {_new(a, row, a[f'pred_{n}']) / mlr:6.2f}; folds "
                          + " ".join(f"{x:6.2f}" for x in r) + f" | mean {r.mean():6.2f} median "
                          f"{np.median(r):5.2f} cap2 {np.minimum(r, 2).mean():5.2f} won "
                          f"{int((r < 1).sum())}/{r.size}")
            folds = np.unique(a["oof_fold"])
            if folds.size >= 3 and set(w) != {"mlr"}:
                got = []
                for k in folds:
                    keep = a["oof_fold"] != k
                    part = {x: (v[keep] if x.startswith("oof_") else v) for x, v in a.items()}
                    part["oof_fold"] = np.unique(a["oof_fold"][keep], return_inverse=True)[1]
                    got.append(_new(a, row, _deployed(a, choose(part, n_folds=folds.size - 1))) / mlr)
                print("    without fold 0.." + f"{folds.size - 1}: " + " ".join(f"{x:.2f}" for x in got))


def votes(stores: list[Path]) -> None:
    got = {}
    for store in stores:
        for name, row in _load(store).items():
            fig = {k: [] for k in ("mlr", *VARIANTS)}
            for t, w in row["weights"].items():
                a = _arrays(store, name, t)
                shipped = choose(a)
                if _nonzero(shipped) != _nonzero(w):
                    raise SystemExit(f"{store} {name} {t}: stored weights {w}, choose gives {shipped}")
                fig["mlr"].append(_new(a, row, a["pred_mlr"]))
                for k, vote in VARIANTS.items():
                    fig[k].append(_new(a, row, _deployed(a, choose(a, vote))))
            got[name] = {k: float(np.mean(fig[k]) / np.mean(fig["mlr"])) for k in VARIANTS}
            print(f"{name:14s} " + " ".join(f"{k} {v:.3f}{'!' if v > WORSE * got[name]['mean'] else ''}"
                                            for k, v in got[name].items()), flush=True)
    for k in VARIANTS:
        r = np.array([g[k] for g in got.values()])
        over = [n for n, g in got.items() if g[k] > WORSE * g["mean"]]
        print(f"{k:6s} worse than MLR {int((r > 1).sum())} of {r.size}, geometric mean "
              f"{np.exp(np.mean(np.log(r))):.4f}; > 2 % worse than the shipped vote: {over or 'none'}")


def agree(stores: list[Path]) -> None:
    from scipy.stats import spearmanr

    from thermocomp.core.models.blend import fold_ratios

    kept, cands = [], []
    for store in stores:
        for name, row in _load(store).items():
            for t, w in row["weights"].items():
                a = _arrays(store, name, t)
                mlr = _new(a, row, a["pred_mlr"])
                cands += [(_ratios(a, n), _new(a, row, a[f"pred_{n}"]) / mlr)
                          for n in ORDER[1:] if f"oof_{n}" in a]
                if set(w) != {"mlr"} and sum(w.values()) > 0:
                    y = a["oof_y"]
                    r = fold_ratios((y - sum(v * a[f"oof_{n}"] for n, v in w.items())) ** 2,
                                    (y - a["oof_mlr"]) ** 2, a["oof_fold"])
                    kept.append((r, _new(a, row, a["pred_auto"]) / mlr))
                    print(f"{name:14s} {t:14s} " + " ".join(f"{x:5.2f}" for x in r) +
                          f" | median {np.median(r):.2f} max {r.max():.2f} -> new {kept[-1][1]:.3f}")
    new = np.array([n for _, n in kept])
    k = np.array([r.size for r, _ in kept])
    print(f"kept blends {len(kept)}, worse than MLR on new {int((new > 1).sum())}, largest fold "
          f"{max(r.max() for r, _ in kept):.2f}; <= 3 folds: {int((new[k <= 3] > 1).sum())} of "
          f"{int((k <= 3).sum())} worse, 5 folds: {int((new[k == 5] > 1).sum())} of {int((k == 5).sum())}")
    side = np.array([n for _, n in cands])
    stats = {"mean": [r.mean() for r, _ in cands], "median": [np.median(r) for r, _ in cands],
             "cap2": [np.minimum(r, 2).mean() for r, _ in cands],
             "geometric": [np.exp(np.log(r).mean()) for r, _ in cands],
             "lost share": [(r >= 1).mean() for r, _ in cands]}
    for name, v in stats.items():
        v = np.asarray(v)
        below = v < (0.5 if name == "lost share" else 1.0)
        print(f"{len(cands)} candidates, {name:10s}: on new's side of MLR "
              f"{np.mean(below == (side < 1)):.2f}, Spearman with new {spearmanr(v, side).statistic:+.2f}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "trace": lambda store, *names: trace(Path(store), list(names)),
        "votes": lambda *stores: votes([Path(s) for s in stores]),
        "agree": lambda *stores: agree([Path(s) for s in stores]),
    }, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
