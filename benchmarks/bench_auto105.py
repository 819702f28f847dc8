"""``model=auto`` hedged towards MLR by a NESTED convex weight: the kept blend W and MLR mixed as
``lam * W + (1 - lam) * MLR``, ``lam`` chosen on out-of-fold predictions of auto's whole choice
made WITHOUT the fold they score (issue 34; stop 105, auto105).

REFUSED on the SEEN gate (1): losers 8 -> 7 (bar: at most 6), geo 0.8257 -> 0.8259; the hedge moves
losses rather than removing them (col1514, hmc, mtc_b out; col6511, iso_b in) and costs 5 records
> 1 % (iso_b 1.160, tsc_a2 1.126 x main).  Fresh 10030-10034 NOT drawn (they stay fresh).  src as
on 4b70457f; the rule built is ``benchmarks/auto105_rule.patch`` (against 4b70457f:
``model.estimator.hedge`` none | nested, ``core/models/hedge.py``, ``AutoRegressor._hedged``,
conf/model/auto.yaml, ``tests/core/test_auto_hedge105.py`` 2 cases, 1.8 s CPU with the import).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the vote code is that tree's)::

    python benchmarks/bench_auto91.py rows ROOT STORE RECORD ...   # the 22-table's rows (main's auto)
    python benchmarks/bench_auto105.py replay STORE                # main / hedge / sign probe, the 22
    python benchmarks/bench_auto105.py probes STORE                # after the fact: two probes
    python benchmarks/bench_auto105.py seen1 OUT                   # after the fact: 10 one-campaign
    python benchmarks/bench_auto105.py fl OUT                      # fl_thermal 90/10 + authors' split
    python benchmarks/bench_auto105.py fresh OUT                   # seeds 10030-10034, once (bar)

Not in the list of what was tried (bench_auto80-101, their patches): those kept W or sent a target
to MLR alone (one-SE, t-SE, nested fallbacks, votes' forms, gates, held leads); none mixed the two
by a weight between 0 and 1.  Where the blend and MLR are near on the folds, their errors are not
the same errors, and a mix can beat both; where validation says little (few folds, the nested
choice unstable) the weight falls towards MLR; where the nested choice wins every fold it stays
at W.  Chosen on train data only, and a blend of the same members: the C / ST export carries it
as it carries any blend (no export change would be needed).

The rule (``hedge``), per target, from auto's stored out-of-fold arrays (STORE: a WORK of
bench_automore69's ``rows``; ``pred/RECORD.TARGET.npz``), where auto kept a blend W that is neither
MLR alone nor a zero correction, MLR was validated and there are k >= 2 folds:

1. for each fold j, auto's choice again on the other folds alone (bench_auto87b's ``choose``: the
   votes with ``min_folds`` = the configured 5, the one-SE fallback, the zero rule -- exactly
   ``AutoRegressor._blend``, checked to give every stored W on all folds), its weights W_j, and
   its prediction on fold j: the nested out-of-fold prediction A (never chosen on the rows it scores);
2. with e = y - MLR and d = A - MLR on each fold, the mix's squared error over MLR's on fold j is
   ``1 - 2 lam <e, d>_j / |e|_j^2 + lam^2 |d|_j^2 / |e|_j^2``; its mean over the folds (the votes'
   measure: every fold alike) is least at ``lam = sum_j <e,d>_j/|e|_j^2 / sum_j |d|_j^2/|e|_j^2``,
   clipped to [0, 1] (1 where d is 0 on every fold);
3. deployed: ``lam * W + (1 - lam) * MLR`` (one fold, MLR alone, a zero: W as on main).

A probe the brief named, reported only (not the rule the bar judges): ``sign`` keeps W only where
the nested prediction A beats MLR on enough folds for a one-sided sign test at 10 % (k=4: 4 of 4,
k=5: 5 of 5; k <= 3: never), else MLR alone.

Record figure (bench_automore69's): the mean over targets of the pooled RMSE on the record's NEW
campaigns (``replay``) or its own test (``fresh``, ``fl``), over MLR's.  A member's deployed
prediction is the weighted sum of the stored single-family predictions (each Blend member is fitted
alone: bench_auto87b, to 1e-13), so the hedge is scored exactly, without a refit.

BAR (written and committed before ``replay`` was run and before seeds 10030-10034 were simulated;
the rule is KEPT only if all hold, else REFUSED):
(1) SEEN 22-table (``replay`` on main 4b70457f's rows): losers (auto / MLR > 1.0) at most 6 (main
    8), the geometric mean of auto / MLR at most 0.8264 x 1.01 = 0.8347.
(2) fl_thermal: the authors' 60/20/20 split's MAE beats the authors' GRU (3.56 / 3.76 / 3.70 / 3.46
    / 4.28) on >= 4 of 5 channels and on the mean, and the 90/10 cut's mean RMSE >= 25 % under MLR's.
(3) FRESH 10030-10034 (named before drawing, the 22 table's kinds, own test): col10030
    (``column_moving_source``), sw10031 (``swiss_lathe_door``), lab10032 (bench_auto_losses56's
    ``lab_record``: lab5401's kind), year6_10033 (``yearround_spindle``, 6 campaigns: year6_5411's
    kind), year10034 (``yearround_spindle``: year6511's kind): no record's hedge / main > 1.01.
KEPT would still need the rule built in ``AutoRegressor._blend`` (export unchanged: the weights
change); until then it is a bench-only rule.

Measured (2026-12-07, 4b70457f's src; nice, ``OMP_NUM_THREADS=1``, 2 cores shared, load 7-19; CPU:
``rows`` of the 22 283 s (ROOT's writes not timed), ``replay`` 6.1 s, ``probes`` 4.1 s, ``fl`` 61.6 s (the
90/10 fits) + 14.4 s, ``seen1`` 44.9 s).  Main's rows were drawn again here: they read geo 0.8257,
col5791 1.245 (the brief: 0.8264, 1.258), the same 8 losers.

(1) SEEN 22 (``replay /tmp/auto105/main``), auto / MLR on the new campaigns, main -> hedge::

  col5791 1.245 -> 1.184   col1403 1.311 -> 1.298   col1514 1.019 -> 0.997   col6511 0.995 -> 1.002
  col6512 1.005 -> 1.003   hmc 1.005 -> 0.954       iso_a 1.083 -> 1.073     iso_b 0.862 -> 1.000
  mtc_a 0.704 -> 0.675     mtc_b 1.075 -> 0.901     tsc_a2 0.376 -> 0.423    swiss303 0.569 -> 0.547
  swiss5454 0.950 -> 0.984 year6_5411 0.518 -> 0.537  year6511 0.348 -> 0.367  lab5401 1.070 (1 fold)
  the other 6 within 0.1 %
  losers 8 -> 7; geo 0.8257 -> 0.8259; > 1 % worse than main: swiss5454 1.036, year6_5411 1.038,
  year6511 1.055, tsc_a2 1.126, iso_b 1.160.  NOT met (losers).

  lam over the 49 hedged targets: 1.00 on 11, 0.00 on 6 (year6511 E_X, col1514 E_Z_mid, col6511 /
  col6512 E_Z_mid, iso_a E_Y1, iso_b E_Z).  With 2 folds the nested choice is one fold's and
  says little (iso_b, tsc_a2 lose their wins).  The losers' own blends win their nested folds, so
  lam stays high there (col1403 0.89-1.00, col5791 E_Z_mid 0.75): what bench_auto87b found for the
  votes holds for a mix too.
  Sign probe (brief's second idea, not barred): losers 3 but geo 0.8686, tsc_a2 2.660, mtc_a 1.421,
  year6511 1.133 x main: with 2-3 folds no win can pass a sign test.
(2) fl_thermal: 90/10 mean RMSE 2.481 -> 2.929 (38.9 % -> 27.9 % under MLR's 4.060; >= 25 %: met,
    lam 0.65 0.47 0.80 0.70 0.005); the authors' split keeps the best on its val split (every
    target's ``scheme_`` 'val split'): the hedge cannot act there, main's MAE stands (not re-run).
(3) FRESH: not drawn.

After the bar failed (no bar, no rule; for a next stop, on its own fresh seeds): ``probes`` on the
22 -- only with >= 3 folds: losers 6, geo 0.8163 (swiss5454 1.036, year6_5411 1.038, year6511
1.055 x main); lam on W's own out-of-fold prediction (not nested): 6, 0.8161 (year6_5411 1.102,
tsc_a2 1.061); both: 6, 0.8146 (year6_5411 1.102); fl 90/10 plain 2.556.  ``seen1``, the 10 seen
one-campaign records (own test, main -> hedge): sw9697 1.044 -> 1.029, lr9587 1.059 -> 1.014 (still
losers), lr9640 0.858 -> 0.962, lr9641 0.637 -> 0.681; geo 0.7654 -> 0.7717, losers 2 -> 2; the
plain probe 0.7770 (lr9212 1.066, lr9641 1.068 x main).  Every form moves a loss to MLR's side
somewhere and costs a win elsewhere by more than 1 %.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto87b as b87  # noqa: E402
from _cli import run_commands  # noqa: E402

N_FOLDS = 5                   # conf/model/auto.yaml's n_folds: the votes' min_folds
SIGN_ALPHA = 0.10
MAIN_GEO, MAIN_LOSERS = 0.8264, 8
FL = ["data=fl_thermal"]
FL60 = [*FL, "data.split_order=[train,test,val]", "data.test_fraction=0.2", "data.val_fraction=0.2"]
AUTHORS = (3.56, 3.76, 3.70, 3.46, 4.28)
FRESH = {"col10030": ["sim=column_moving_source", "seed=10030"],
         "sw10031": ["sim=swiss_lathe_door", "seed=10031"],
         "lab10032": ["data.path={out}/lab10032"],
         "year6_10033": ["sim=yearround_spindle", "sim.generator.n_campaigns=6", "seed=10033"],
         "year10034": ["sim=yearround_spindle", "seed=10034"]}


def _part(a: dict, keep: np.ndarray) -> dict:
    """The out-of-fold arrays on rows ``keep``, folds renumbered 0..k-1."""
    part = {x: (v[keep] if x.startswith("oof_") and np.ndim(v) and len(v) == len(keep) else v)
            for x, v in a.items()}
    part["oof_fold"] = np.unique(a["oof_fold"][keep], return_inverse=True)[1]
    return part


def nested(a: dict) -> np.ndarray:
    """A: on each fold j, the prediction of auto's choice made on the other folds alone."""
    names = [n for n in b87.ORDER if f"oof_{n}" in a]
    out = np.zeros(len(a["oof_y"]))
    for j in np.unique(a["oof_fold"]):
        on = a["oof_fold"] == j
        w = b87.choose(_part(a, ~on), n_folds=N_FOLDS)
        out[on] = sum(v * a[f"oof_{n}"][on] for n, v in w.items() if n in names) if w else 0.0
    return out


def _active(a: dict, kept: dict) -> bool:
    return (np.unique(a["oof_fold"]).size >= 2 and "oof_mlr" in a and sum(kept.values()) > 0
            and b87._nonzero(kept) != {"mlr": 1.0})


def hedge_weight(a: dict, kept: dict, min_folds: int = 2, plain: bool = False) -> float:
    """lam of the rule (1: W as on main).  ``min_folds`` / ``plain`` (lam on W's own out-of-fold
    prediction, not the nested one): the after-the-fact probes of ``probes``, not the rule."""
    if not _active(a, kept) or np.unique(a["oof_fold"]).size < min_folds:
        return 1.0
    y, f, m = a["oof_y"], a["oof_fold"], a["oof_mlr"]
    own = b87._deployed({k[4:]: v for k, v in a.items() if k.startswith("oof_")} | {
        f"pred_{k[4:]}": v for k, v in a.items() if k.startswith("oof_")}, kept) if plain else None
    e, d = y - m, (nested(a) if own is None else own) - m
    num = den = 0.0
    for j in np.unique(f):
        on = f == j
        ee = max(float(e[on] @ e[on]), 1e-300)
        num += float(e[on] @ d[on]) / ee
        den += float(d[on] @ d[on]) / ee
    return 1.0 if den <= 0 else float(np.clip(num / den, 0.0, 1.0))


def mixed(kept: dict, lam: float) -> dict:
    out = {n: lam * v for n, v in kept.items()}
    out["mlr"] = out.get("mlr", 0.0) + (1.0 - lam)
    return out


def sign_keep(a: dict, kept: dict) -> dict:
    """The probe: W where the nested A beats MLR on enough folds (one-sided sign test), else MLR."""
    from scipy.stats import binom

    from thermocomp.core.models.blend import fold_ratios

    if not _active(a, kept):
        return kept
    y, f, m = a["oof_y"], a["oof_fold"], a["oof_mlr"]
    r = fold_ratios((y - nested(a)) ** 2, (y - m) ** 2, f)
    wins = int((r < 1).sum())
    return kept if binom.sf(wins - 1, r.size, 0.5) <= SIGN_ALPHA else {"mlr": 1.0}


def _geo(r) -> float:
    return float(np.exp(np.mean(np.log(r))))


def replay(store: str) -> None:
    """Per record of STORE: auto / MLR on the new campaigns, main (the stored W), hedge, sign."""
    store_p = Path(store)
    got, lams = {}, []
    for name, row in b87._load(store_p).items():
        fig = {k: [] for k in ("mlr", "main", "hedge", "sign")}
        for t, w in row["weights"].items():
            a = b87._arrays(store_p, name, t)
            if b87._nonzero(b87.choose(a)) != b87._nonzero(w):
                raise SystemExit(f"{name} {t}: stored weights {w}, choose gives {b87.choose(a)}")
            lam = hedge_weight(a, w)
            if _active(a, w):
                lams.append((name, t, np.unique(a["oof_fold"]).size, lam))
            fig["mlr"].append(b87._new(a, row, a["pred_mlr"]))
            fig["main"].append(b87._new(a, row, b87._deployed(a, w)))
            fig["hedge"].append(b87._new(a, row, b87._deployed(a, mixed(w, lam))))
            fig["sign"].append(b87._new(a, row, b87._deployed(a, sign_keep(a, w))))
        got[name] = {k: float(np.mean(fig[k]) / np.mean(fig["mlr"])) for k in ("main", "hedge", "sign")}
        g = got[name]
        print(f"{name:12s} main {g['main']:.3f}  hedge {g['hedge']:.3f} ({g['hedge'] / g['main']:.3f})  "
              f"sign {g['sign']:.3f} ({g['sign'] / g['main']:.3f})", flush=True)
    print("targets hedged (record target folds lam): " + "; ".join(
        f"{n} {t} {k} {lam:.2f}" for n, t, k, lam in lams))
    for k in ("main", "hedge", "sign"):
        r = np.array([g[k] for g in got.values()])
        worse = {n: round(g[k] / g["main"], 3) for n, g in got.items() if g[k] > 1.01 * g["main"]}
        print(f"{k:6s} losers {int((r > 1).sum())} of {r.size} "
              f"({', '.join(n for n, g in got.items() if g[k] > 1)}); geo {_geo(r):.4f}; "
              f"> 1 % worse than main: {worse or 'none'}")
    r = np.array([g["hedge"] for g in got.values()])
    ok = int((r > 1).sum()) <= MAIN_LOSERS - 2 and _geo(r) <= MAIN_GEO * 1.01
    print(f"BAR (1) seen: {'met' if ok else 'NOT met'}")


PROBES = {"hedge": {}, "k>=3": {"min_folds": 3}, "plain": {"plain": True},
          "plain k>=3": {"plain": True, "min_folds": 3}}


def probes(store: str) -> None:
    """AFTER the bar failed, on the same 22 (no bar, no rule): the hedge only with >= 3 folds (a
    nested choice on 2 folds is one fold's), and lam on W's own out-of-fold prediction."""
    store_p = Path(store)
    got = {}
    for name, row in b87._load(store_p).items():
        fig = {k: [] for k in ("mlr", "main", *PROBES)}
        for t, w in row["weights"].items():
            a = b87._arrays(store_p, name, t)
            fig["mlr"].append(b87._new(a, row, a["pred_mlr"]))
            fig["main"].append(b87._new(a, row, b87._deployed(a, w)))
            for k, kw in PROBES.items():
                fig[k].append(b87._new(a, row, b87._deployed(a, mixed(w, hedge_weight(a, w, **kw)))))
        got[name] = {k: float(np.mean(fig[k]) / np.mean(fig["mlr"])) for k in ("main", *PROBES)}
        print(f"{name:12s} " + "  ".join(f"{k} {v:.3f}" for k, v in got[name].items()), flush=True)
    for k in ("main", *PROBES):
        r = np.array([g[k] for g in got.values()])
        worse = {n: round(g[k] / g["main"], 3) for n, g in got.items() if g[k] > 1.01 * g["main"]}
        print(f"{k:10s} losers {int((r > 1).sum())}; geo {_geo(r):.4f}; > 1 % worse than main: "
              f"{worse or 'none'}")


def _rank(out: Path, name: str, overrides: list[str]) -> dict:
    """bench_auto_rank's ``main`` into OUT (auto with keep_oof, every candidate alone, own test)."""
    import bench_auto_rank as rank

    os.environ["OUT"] = str(out)
    sys.argv[2:] = overrides
    return rank.main(name, overrides)


def _own(out: Path, name: str, ways: dict | None = None) -> dict:
    """Per record from OUT: mean over targets of the test RMSE, MLR / main / each of ``ways``
    (default the rule alone), and the rule's lams."""
    ways = ways or {"hedge": {}}
    rep = json.loads((out / f"{name}.json").read_text())
    fig, lams = {k: [] for k in ("mlr", "main", *ways)}, {}
    for t, row in rep["targets"].items():
        with np.load(out / f"{name}.{t}.npz", allow_pickle=True) as z:
            a = {k: z[k] for k in z.files}
        w = {n: float(v) for n, v in row["auto"]["weights"].items()}
        lams[t] = round(hedge_weight(a, w), 3)
        y = a["test_y"]

        def dep(ws: dict):
            return sum(v * a[f"test_{n}"] for n, v in ws.items()) if sum(ws.values()) > 0 else 0.0
        fig["mlr"].append(b87._rmse(y - a["test_mlr"]))
        fig["main"].append(b87._rmse(y - dep(w)))
        for k, kw in ways.items():
            fig[k].append(b87._rmse(y - dep(mixed(w, hedge_weight(a, w, **kw)))))
    return {"record": name, **{k: float(np.mean(v)) for k, v in fig.items()}, "lam": lams}


def seen1(out: str) -> None:
    """AFTER the bar failed: the 10 seen one-campaign records (bench_auto94c's :data:`RECORDS`,
    own test), main / the rule / the probes, each over MLR."""
    from bench_auto94c import RECORDS as ONE

    out_p = Path(out).resolve()
    rows = []
    for name, ov in ONE.items():
        if not (out_p / f"{name}.json").exists():
            _rank(out_p, name, list(ov))
        rows.append(_own(out_p, name, PROBES))
        r = rows[-1]
        print(f"{name:8s} " + "  ".join(f"{k} {r[k] / r['mlr']:.3f}" for k in ("main", *PROBES)), flush=True)
    for k in ("main", *PROBES):
        g = [r[k] / r["mlr"] for r in rows]
        worse = {r["record"]: round(r[k] / r["main"], 3) for r in rows if r[k] > 1.01 * r["main"]}
        print(f"{k:10s} losers {sum(x > 1 for x in g)}; geo {_geo(g):.4f}; > 1 % worse than main: "
              f"{worse or 'none'}")


def fresh(out: str) -> None:
    """Seeds 10030-10034 (:data:`FRESH`), fitted and scored ONCE: hedge / main, each / MLR."""
    from bench_auto_losses56 import lab_record

    out_p = Path(out).resolve()
    out_p.mkdir(parents=True, exist_ok=True)
    if not (out_p / "lab10032").exists():
        lab_record(out_p / "lab10032", seed=10032)
    rows = []
    for name, ov in FRESH.items():
        if not (out_p / f"{name}.json").exists():
            _rank(out_p, name, [o.format(out=out_p) for o in ov])
        rows.append(_own(out_p, name))
    worst = max(r["hedge"] / r["main"] for r in rows)
    for r in rows:
        print(f"{r['record']:12s} main/MLR {r['main'] / r['mlr']:.3f}  hedge/MLR {r['hedge'] / r['mlr']:.3f}"
              f"  hedge/main {r['hedge'] / r['main']:.3f}  lam {r['lam']}")
    print(f"geo main/MLR {_geo([r['main'] / r['mlr'] for r in rows]):.4f} hedge/MLR "
          f"{_geo([r['hedge'] / r['mlr'] for r in rows]):.4f}; worst hedge/main {worst:.3f}: "
          f"BAR (3) {'met' if worst <= 1.01 else 'NOT met'}")


def fl(out: str) -> None:
    """fl_thermal: the 90/10 cut replayed (main / hedge / MLR mean RMSE) and the authors' split's
    scheme (a val split: auto keeps the best on it, no folds, so the hedge cannot act there)."""
    out_p = Path(out).resolve()
    if not (out_p / "fl9010.json").exists():
        _rank(out_p, "fl9010", FL)
    r = _own(out_p, "fl9010", PROBES)
    print(f"fl_thermal 90/10 mean RMSE: MLR {r['mlr']:.3f} main {r['main']:.3f} "
          f"({1 - r['main'] / r['mlr']:.1%} under MLR) hedge {r['hedge']:.3f} "
          f"({1 - r['hedge'] / r['mlr']:.1%} under MLR); lam {r['lam']}; after the fact: "
          + ", ".join(f"{k} {r[k]:.3f}" for k in PROBES if k != "hedge"))
    import bench_auto_rank as rank

    from thermocomp.shell.builders import build_compensator

    sys.argv[2:] = FL60
    cfg, ds, train = rank.setup(FL60)
    auto = build_compensator(cfg, ds=ds).fit(train)
    print("authors' split, auto's scheme per target: "
          + ", ".join(f"{t} {e.scheme_}" for t, e in auto.estimators_.items()))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"replay": lambda store: replay(store),
                                  "probes": lambda store: probes(store),
                                  "seen1": lambda out: seen1(out),
                                  "fresh": lambda out: fresh(out),
                                  "fl": lambda out: fl(out)}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
