"""Does a fold that extrapolates as the test does rank ``model=auto``'s candidates better?
(issue 34 item 3; stop 70, auto70)

Usage (from the repository root, ``PYTHONPATH=<tree>/src``; ROOT and WORK: bench_automore69's,
read only: its records, draws and ``pred/RECORD.TARGET.npz`` arrays)::

    python benchmarks/bench_auto70.py novelty ROOT OUT WORK [WORK ...]   # -> OUT/novelty.jsonl
    python benchmarks/bench_auto70.py measure OUT WORK [WORK ...]        # the Spearman tables

``novelty``: per record of the WORKs and target, the inputs auto's folds saw (the record set up as
bench_automore69 sets it up, fitted with MLR as the only candidate: the same folds, the design
matrix captured) and, per fold, how far its held-out rows lie outside its fit rows: ``beyond``,
the share of scored rows whose leverage in the fit rows' design exceeds every fit row's (the
``within_range`` check ``validation_rows=in_range`` and diagnose use), and ``lev``, the median
over scored rows of that leverage over the fit rows' largest (a Mahalanobis distance squared, 1
on the ellipsoid that holds the fit data).  The same two for the record's own test and its new
campaigns against all train rows.  Checked: every fold's scored rows are as many as the stored
arrays' (``oof_fold``).

``measure``: per candidate x target x fold (candidates other than MLR, cases with >= 3 folds, as
autorule69 counted them), the fold measure (the fold's squared error over MLR's) against the
candidate's new-campaign ratio (its squared error over MLR's, pooled over the new campaigns);
folds split into terciles of novelty; per tercile the Spearman of log fold measure with log new
ratio, and how often the fold and the new campaigns agree on the side of 1 (beats MLR or not).
Then per case, the votes' measure (the folds' mean) against (a) novelty-weighted means and (b) the
folds restricted to their most novel rows (above the fold's median leverage; beyond its range,
a fold with fewer than 20 such rows whole), and the members that lose on the new campaigns.
(b)'s other form, the campaign farthest from the rest held out, needs refits and cannot touch
the real losses: five columns and mill1514 are one record each, lab5401 has one fold.

Measured (2026-12-02, stop 70: novelty at main 48af5bfc, every fold's rows checked equal to the
arrays' of automore69's rows at 3d65c78c; ROOT /tmp/automore69-root, WORKs its three work folders;
``novelty`` 54.6 s user + 1.8 s sys for the 22 records, 0.6-10.2 s each; ``measure`` 0.3 s)
--------------------------------------------------------------------------------------------------
390 candidate x target cases, 322 with >= 3 folds (autorule69's count; the new ratio here from
the stored squares, the scores' frame: Spearman of the votes' measure 0.362; autorule69's 0.38
took it from the label as measured, checked: 0.378 so).  Figures: n, Spearman / side agreement.

The premise does not hold.  Held-out rows beyond the fold's range (``beyond``), median over the
1500 folds 0.035 (quartiles 0-0.575), own test 0.197, new campaigns 0.172 (81 record x target);
``lev`` 0.571 (0.348-1.17), 0.508, 0.614.  The new campaigns lie beyond every fold of their record
x target on 7 % of them, below every fold on 23 %; a forward chain's first folds extrapolate more
than the test: on the column folds 0-1 are beyond on 0.83-1.00 of their rows (lev 1.6-5.2), its
new campaigns on 0.55-0.76 (lev 1.1-1.6).

Novel folds rank worse, not better (per fold, terciles)::

  beyond  0-0.004      517 +0.511 / 0.662   real-loss records 132 +0.241 / 0.598   others 385 +0.583 / 0.683
          0.004-0.13   499 +0.243 / 0.561                     222 +0.210 / 0.559          277 +0.231 / 0.563
          0.24-1       484 +0.254 / 0.562                     456 +0.248 / 0.566           28 +0.309 / 0.500
  lev     0.076-0.44   505 +0.526 / 0.661                      30 +0.265 / 0.633          475 +0.543 / 0.663
          0.45-0.78    511 +0.222 / 0.564                     324 +0.214 / 0.568          187 +0.141 / 0.556
          0.83-11.6    484 +0.254 / 0.562                     456 +0.248 / 0.566           28 +0.309 / 0.500

On the real-loss records' folds the ranking is as weak in every tercile (0.21-0.27): novelty does
not say where their measure misranks.  Per case (all 322 | the six real-loss records with >= 3
folds, 162 | the others, 160)::

  the votes' mean fold ratio       +0.362 / 0.612 | +0.284 / 0.586 | +0.461 / 0.637
  (a) weighted by beyond           +0.334 / 0.590 | +0.293 / 0.568 | +0.379 / 0.613
  (a) weighted by lev              +0.355 / 0.609 | +0.291 / 0.574 | +0.458 / 0.644
  the most novel fold (lev)        +0.334 / 0.587 | +0.297 / 0.580 | +0.367 / 0.594
  the least novel fold (lev)       +0.395 / 0.609 | +0.251 / 0.568 | +0.524 / 0.650
  the fold nearest the new's lev   +0.261 / 0.571 | +0.188 / 0.543 | +0.333 / 0.600   (reads the test)
  (b) folds' most novel half       +0.360 / 0.606 | +0.286 / 0.593 | +0.465 / 0.619
  (b) folds' rows beyond range     +0.367 / 0.624 | +0.290 / 0.593 | +0.481 / 0.656

No variant raises the losses' Spearman by more than 0.013 (the votes' 0.284, 0.297 at best), and
(a) loses agreement on the side of 1 there (0.586 -> 0.568-0.574).  The members that make the
losses keep a measure below 1 under every variant (votes' / novel half / beyond rows, new-campaign
MSE over MLR's): col5791 E_Z_mid lagbank (w 0.81) 0.67 / 0.65 / 0.71, tests 11.3; col1403 E_Y
lagbank (0.84) 0.51 / 0.40 / 0.44, tests 4.42; E_Y_mid hammerstein (0.64) 0.49 / 0.47 / 0.47, tests
4.99; col1514 E_Z_mid hammerstein (0.41) 0.78 / 0.83 / 0.74, tests 9.35; col6511 E_X arx (0.57)
0.92 / 0.93 / 0.92, tests 2.28; col6512 E_X_mid arx (0.65) 0.89 / 0.92 / 0.92, tests 1.21.  The
novel rows favour col1403's lag families as much or more.  The one hint, the least novel fold
ranking the other records better (0.524 against 0.461), is "later folds weigh more" again (forward
folds grow less novel as their fit grows), measured and refused before (``vote_weights``'s
docstring: large_mill_week seed 101 lost to MLR), and it ranks the losses worse (0.251).  **No rule
follows: none written, none scored, no src change.**
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
from cpu import cpu_seconds  # noqa: E402

from thermocomp.core.models.auto import BASELINE  # noqa: E402


def leverage_ratio(X: np.ndarray, fit: np.ndarray, scored: np.ndarray) -> np.ndarray:
    """Per row of ``X[scored]``: its leverage in the centred design of ``X[fit]`` over the largest
    leverage of a fit row (``within_range``'s test: in range where <= 1)."""
    Z = X[fit]
    mean = Z.mean(axis=0)
    U, s, Vt = np.linalg.svd(Z - mean, full_matrices=False)
    keep = s > (s[0] * 1e-8 if s.size else 0.0)
    W = Vt[keep].T / s[keep]
    limit = float(np.max(np.sum(U[:, keep] ** 2, axis=1)))
    return np.sum(((X[scored] - mean) @ W) ** 2, axis=1) / limit


def summary(ratio: np.ndarray) -> dict:
    return {"beyond": float(np.mean(ratio > 1.0 + 1e-9)), "lev": float(np.median(ratio))}


def _captured():
    """AutoRegressor.fit spied on: the design matrix kept on the fitted estimator (``X70_``)."""
    from thermocomp.core.models.auto import AutoRegressor

    shipped = AutoRegressor.fit

    def fit(self, X, y, context=None):
        out = shipped(self, X, y, context)
        self.X70_ = np.asarray(X, float)
        return out
    AutoRegressor.fit = fit
    return lambda: setattr(AutoRegressor, "fit", shipped)


def record_novelty(root: Path, work: Path, name: str, out_dir: Path) -> dict:
    import bench_auto_rank as rank
    from bench_moretest68 import with_new

    from thermocomp.shell.builders import build_compensator

    overrides = [o.format(root=root) for o in automore.OVERRIDES[name]
                 if not o.startswith("model.candidates=")] + ["model.candidates=[mlr]"]
    sys.argv[2:] = overrides
    cfg, ds, train = rank.setup(overrides)
    undo = _captured()
    try:
        comp = build_compensator(cfg, ds=ds).fit(train)
    finally:
        undo()
    full = with_new(ds, automore.draws(automore.OF[name], work, cfg))
    own = ds.ids("test")
    new = [c for c in full.ids("test") if c not in ds.ids()]
    m_own = comp.stacked({c: full.campaigns[c] for c in own})
    m_new = comp.stacked({c: full.campaigns[c] for c in new})
    out = {"record": name, "targets": {}}
    for t, est in comp.estimators_.items():
        X, (n, folds) = est.X70_, est.oof_folds_
        stored = np.load(work / "pred" / f"{name}.{t}.npz")["oof_fold"]
        assert [len(s) for _, s in folds] == np.bincount(stored).tolist(), (name, t)
        rows = np.arange(n)
        lev = [leverage_ratio(X, np.isin(rows, f), np.isin(rows, s)) for f, s in folds]
        per = [summary(r) for r in lev]
        (out_dir / "lev").mkdir(parents=True, exist_ok=True)    # per out-of-fold row, in oof order
        np.save(out_dir / "lev" / f"{name}.{t}.npy", np.concatenate(lev))
        cols = est.X70_.shape[1]
        whole = np.vstack([X, m_own.X[comp.selected_[t]].to_numpy(), m_new.X[comp.selected_[t]].to_numpy()])
        assert whole.shape[1] == cols
        fit = np.zeros(len(whole), bool)
        fit[:n] = True
        part = {"own": (n, n + len(m_own.X)), "new": (n + len(m_own.X), len(whole))}
        test = {}
        for k, (a, b) in part.items():
            pick = np.zeros(len(whole), bool)
            pick[a:b] = True
            pick &= np.isfinite(whole).all(axis=1)
            test[k] = summary(leverage_ratio(whole, fit, pick))
        out["targets"][t] = {"folds": per, "test": test, "scheme": est.scheme_}
    return out


def novelty(root: Path, out: Path, works: list[Path]) -> None:
    out.mkdir(parents=True, exist_ok=True)
    path = out / "novelty.jsonl"
    done = {json.loads(x)["record"] for x in path.read_text().splitlines()} if path.exists() else set()
    for work in works:
        for row in map(json.loads, open(work / "automore.jsonl")):
            if row["record"] in done:
                continue
            start = cpu_seconds()
            got = record_novelty(root, work, row["record"], out)
            got["cpu_s"] = round(cpu_seconds() - start, 1)
            with open(path, "a") as f:
                f.write(json.dumps(got) + "\n")
            print(row["record"], got["cpu_s"], "s", file=sys.stderr)


# --- the measure ---

MIN_ROWS = 20      # (b) a fold with fewer rows beyond range is scored whole (in_range's minimum)
REAL_LOSSES = ("col5791", "col1403", "col1514", "col6511", "col6512", "lab5401", "mill1514")


def _novel_rows(lev: np.ndarray, fold: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(b) each fold restricted to its most novel rows: those at or above its median leverage
    (``half``), or beyond its fit rows' range (``beyond``; a fold with fewer than MIN_ROWS: whole)."""
    half, beyond = np.zeros(len(lev), bool), np.zeros(len(lev), bool)
    for f in np.unique(fold):
        rows = fold == f
        half |= rows & (lev >= np.median(lev[rows]))
        out = rows & (lev > 1.0 + 1e-9)
        beyond |= out if out.sum() >= MIN_ROWS else rows
    return half, beyond


def _fold_ratios(e: np.ndarray, base: np.ndarray, fold: np.ndarray, keep: np.ndarray) -> list[float]:
    """Per fold, the candidate's summed squared error over MLR's on the rows ``keep``."""
    return [e[keep & (fold == f)].sum() / max(base[keep & (fold == f)].sum(), 1e-300)
            for f in range(fold.max() + 1)]


def cases(out: Path, works: list[Path]) -> list[dict]:
    """One per record x target x candidate (not MLR): its per-fold measures and novelties, its
    new-campaign MSE ratio over MLR's, its weight in shipped auto."""
    nov = {r["record"]: r for r in map(json.loads, open(out / "novelty.jsonl"))}
    got = []
    for work in works:
        for row in map(json.loads, open(work / "automore.jsonl")):
            name, sq = row["record"], row["squares"]
            for t, w in row["weights"].items():
                a = np.load(work / "pred" / f"{name}.{t}.npz")
                y, fold = a["oof_y"], a["oof_fold"]
                base = (y - a[f"oof_{BASELINE}"]) ** 2
                lev = np.load(out / "lev" / f"{name}.{t}.npy")
                assert len(lev) == len(y), (name, t)
                half, beyond = _novel_rows(lev, fold)
                everything = np.ones(len(y), bool)
                folds = nov[name]["targets"][t]["folds"]
                new_base = sum(sq[BASELINE][t][c][1] for c in row["new"])
                for n in (k[4:] for k in a.files if k.startswith("oof_") and k not in ("oof_y", "oof_fold")):
                    if n == BASELINE or n not in sq:
                        continue
                    e = (y - a[f"oof_{n}"]) ** 2
                    got.append({"record": name, "target": t, "candidate": n, "weight": w.get(n, 0.0),
                                "fold_ratio": _fold_ratios(e, base, fold, everything),
                                "novel_half": _fold_ratios(e, base, fold, half),
                                "beyond_rows": _fold_ratios(e, base, fold, beyond),
                                "beyond": [f["beyond"] for f in folds], "lev": [f["lev"] for f in folds],
                                "new_ratio": sum(sq[n][t][c][1] for c in row["new"]) / new_base,
                                "test": nov[name]["targets"][t]["test"]})
    return got


def _spearman(a, b) -> float:
    from scipy.stats import spearmanr

    return float(spearmanr(a, b)[0]) if len(a) > 2 else float("nan")


def _agreement(m: np.ndarray, new: np.ndarray, pick: np.ndarray) -> str:
    """Spearman of log measure ``m`` with log new ratio ``new`` on ``pick``, and how often the two
    agree on the side of 1 (the candidate beats MLR or not)."""
    return (f"{pick.sum()} {_spearman(m[pick], new[pick]):+.3f} / "
            f"{np.mean((m[pick] < 0) == (new[pick] < 0)):.3f}")


def premise(every: list[dict]) -> None:
    """Do the tests lie beyond the train more than the folds' held-out rows do?"""
    recs = {(c["record"], c["target"]): c for c in every}.values()
    for key in ("beyond", "lev"):
        fold = np.concatenate([c[key] for c in recs])
        own, new = ([c["test"][p][key] for c in recs] for p in ("own", "new"))
        print(f"{key}: folds median {np.median(fold):.3g} (quartiles {np.percentile(fold, 25):.3g}-"
              f"{np.percentile(fold, 75):.3g}); own test {np.median(own):.3g}; new campaigns "
              f"{np.median(new):.3g} ({len(recs)} record x target)")
    more = np.array([np.mean(c["test"]["new"]["lev"] > np.asarray(c["lev"])) for c in recs])
    print(f"share of a record x target's folds less novel (lev) than its new campaigns: median "
          f"{np.median(more):.2f}, mean {np.mean(more):.2f}; new campaigns beyond every fold on "
          f"{np.mean(more == 1.0):.2f} of them, below every fold on {np.mean(more == 0.0):.2f}")


def terciles(many: list[dict], key: str) -> None:
    """Per fold: Spearman of its log measure with the candidate's log new ratio, per novelty tercile."""
    fr, nr, v = (np.array(x) for x in zip(*[(np.log(r), np.log(c["new_ratio"]), n) for c in many
                                           for r, n in zip(c["fold_ratio"], c[key])]))
    lost = np.array([c["record"] in REAL_LOSSES for c in many for _ in c["fold_ratio"]])
    cut = np.percentile(v, [100 / 3, 200 / 3])
    tier = np.digitize(v, cut, right=True)
    print(f"\nper fold, terciles of {key} (cuts {cut[0]:.3g}, {cut[1]:.3g}): all folds "
          f"{_agreement(fr, nr, np.ones(len(v), bool))}")
    for k in range(3):
        s = tier == k
        print(f"  tercile {k + 1} ({key} {v[s].min():.3g}-{v[s].max():.3g}, median fold ratio "
              f"{np.exp(np.median(fr[s])):.3g}): {_agreement(fr, nr, s)}; real-loss records' "
              f"{_agreement(fr, nr, s & lost)}; others' {_agreement(fr, nr, s & ~lost)}")


def one_fold(pick):
    """A weighting that keeps the one fold ``pick(case)`` names."""
    return lambda c: np.eye(len(c["lev"]))[pick(c)]


MEASURES = {    # per case: a weighting of its fold ratios, or (b) the ratios on the novel rows
    "mean fold ratio (the votes')": lambda c: np.ones(len(c["lev"])),
    "(a) weighted by beyond": lambda c: np.asarray(c["beyond"]) + 1e-3,
    "(a) weighted by lev": lambda c: np.asarray(c["lev"]),
    "the most novel fold (lev)": one_fold(lambda c: np.argmax(c["lev"])),
    "the least novel fold (lev)": one_fold(lambda c: np.argmin(c["lev"])),
    "the fold nearest the new's lev": one_fold(
        lambda c: np.argmin(np.abs(np.log(c["lev"]) - np.log(c["test"]["new"]["lev"])))),
    "(b) folds' most novel half": "novel_half",
    "(b) folds' rows beyond range": "beyond_rows"}


def measure(out: Path, works: list[Path]) -> None:
    every = cases(out, works)
    many = [c for c in every if len(c["fold_ratio"]) >= 3]
    print(f"{len(every)} candidate x target cases, {len(many)} with >= 3 folds")
    premise(every)
    for key in ("beyond", "lev"):
        terciles(many, key)
    new = np.log([c["new_ratio"] for c in many])
    lost = np.array([c["record"] in REAL_LOSSES for c in many])
    print("\nper case: Spearman / side agreement of the log measure with the log new ratio")
    for label, how in MEASURES.items():
        m = np.log([np.mean(c[how]) if isinstance(how, str)
                    else np.average(c["fold_ratio"], weights=how(c)) for c in many])
        print(f"  {label:31s} all {_agreement(m, new, np.ones(len(m), bool))}; the 7 real-loss records "
              f"{_agreement(m, new, lost)}; the others {_agreement(m, new, ~lost)}")
    print("\nshipped members with weight >= 0.1 that test worse than MLR on the new campaigns "
          "(folds: ratio@beyond/lev; test: beyond/lev):")
    for c in every:
        if c["weight"] >= 0.1 and c["new_ratio"] > 1:
            folds = " ".join(f"{r:.2f}@{b:.2f}/{v:.3g}"
                             for r, b, v in zip(c["fold_ratio"], c["beyond"], c["lev"]))
            print(f"  {c['record']:11s} {c['target']:9s} {c['candidate']:11s} w {c['weight']:.2f} new "
                  f"{c['new_ratio']:.2f}; measure: votes' {np.mean(c['fold_ratio']):.2f}, novel half "
                  f"{np.mean(c['novel_half']):.2f}, beyond rows {np.mean(c['beyond_rows']):.2f}; "
                  f"folds {folds}; "
                  f"test own {c['test']['own']['beyond']:.2f}/{c['test']['own']['lev']:.3g} new "
                  f"{c['test']['new']['beyond']:.2f}/{c['test']['new']['lev']:.3g}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "novelty": lambda root, out, *works: novelty(Path(root).resolve(), Path(out).resolve(),
                                                     [Path(w).resolve() for w in works]),
        "measure": lambda out, *works: measure(Path(out).resolve(), [Path(w).resolve() for w in works]),
    }, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
