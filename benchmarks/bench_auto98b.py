"""auto hands a sample to MLR where a lag family would extrapolate (issue 34; stop 98, auto98b; the
"next" of bench_auto98).

REFUSED on the SEEN gate (1), every region x form: the beyond rows carry the column losers' loss
(lev swap: col5791 1.258 -> 1.012, col1403 1.311 -> 1.050 x MLR) but also the lag families' wins
(beyond its fit region MLR extrapolates worse than they do on most records): 22-table losers 8 -> 8,
tsc_a2 1.069 x main; one-campaign lr9211 1.172, lr9212 1.165, lr9643 1.173 x main.  Fresh 9795-9804
NOT drawn (they stay fresh).  src as on cd4efbd5; the rule built is ``benchmarks/auto98b_rule.patch``
(against cd4efbd5: ``AutoRegressor(beyond_fit='mlr')`` / ``beyond_mlr_`` / ``fit_region_`` in
auto.py, ``FitRegion`` in model_selection/extrapolation.py (``within_range`` through it),
``tests/core/test_auto_beyond98b.py`` 4 cases); ``rule`` needs it applied.

The mechanism: where a target's kept model is a lag family (the
blend's heaviest member ``lagbank`` / ``hammerstein``) and a sample's INPUTS (the temperatures in
the model's frame, not the lag bank's leads) leave the region the final fit saw, the prediction
is MLR's (fitted on the same rows, always among auto's candidates) for that sample, else the
blend's.  Two regions, both the train fit's (no test-split choice; the CV votes untouched):
``lev`` -- :func:`~thermocomp.core.model_selection.extrapolation.within_range` (leverage in the
fit rows' centred design above the largest fit row's: the check ``validation_rows`` and
``diagnose`` use); ``box`` -- a sensor outside its [min, max] over the fit rows (the deployed
watch's range check without its 10 °C margin).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_auto98b.py trace ROOT OUT RECORD ...        # fit auto + MLR, own test
    python benchmarks/bench_auto98b.py trace22 ROOT MAIN_WORK OUT RECORD ...   # the 22-table
    python benchmarks/bench_auto98b.py table OUT RECORD ...
    python benchmarks/bench_auto98b.py rule ROOT OUT RECORD ...         # the built rule (the patch)

``trace``: each record of bench_auto98's RECORDS (the 10 seen one-campaign, ``fl_thermal`` 90/10,
the FRESH ten) fitted as ``run`` fits it (``model=auto``) and MLR alone, scored on its own test
(bench_auto_rank's ``_test``: a test that continues the train part continues its stream);
per target: the weights, the rows beyond each region, auto's and MLR's RMSE on all and on the
beyond rows, and the swap (MLR's prediction on the beyond rows of a lag-family target).
``trace22``: the 22 records of bench_auto96's table from main's stored rows (MAIN_WORK =
``/tmp/auto96/seen``: every candidate's prediction of 12-16 new campaigns of the machine, auto's
weights), the region of the train part's stacked inputs (an MLR compensator fitted for the frame
only).  ``table``: per record the figure (bench_auto96's: mean over targets of auto's RMSE / mean
of MLR's) main -> each region x form, the geometric mean, losers, > 1 % worse.

The trace IS the rule's output: in simulation the blend and MLR each run free on every row, so
taking MLR's prediction on a row changes no state; the region is the final fit's (all train rows),
so the CV votes and weights are main's.  Two forms: ``swap`` (the brief's: where the target's
heaviest member is a lag family, the whole prediction is MLR's on a beyond row) and ``share`` (the
lag members' weight handed to MLR on a beyond row, whatever the heaviest member).

BAR (the brief's, written here and committed before FRESH 9795-9804 are simulated; the region
(lev / box) and the form (swap / share) are chosen on the SEEN records only; the rule is KEPT only
if all hold, and on by default only with the hand-over carried into the exported C / ST so that
deployed = scored, else a key off by default):
(1) SEEN 22-table (``trace22`` against main's stored rows /tmp/auto96/seen): losers (auto / MLR >
    1.0) fewer than main's 8, no record's rule / main > 1.01.  The 10 seen one-campaign records
    (bench_auto95's SEEN, ``trace``): no record's rule / main > 1.01.
(2) fl_thermal 90/10 (``trace ... fl_thermal``): mean RMSE over ch1..ch5 not above 2.481 µm by
    more than 1 % (<= 2.506).
(3) FRESH 9795-9804 (bench_auto98's FRESH, bench_auto96b.fresh_records(9795)), scored ONCE with
    ``trace``: losers no more than main's, the geometric mean of auto / MLR not above main's.
Fresh seeds are drawn only if (1) and (2) hold for one region x form; else REFUSED / TRACED on the
seen gate and they stay fresh.

Measured (SEEN, before the bar; 2026-12-06, cd4efbd5, nice, ``OMP_NUM_THREADS=1``; CPU ``trace22``
of the 22 17.8 s)::

  22-table, auto / MLR main -> lev.swap / lev.share / box.swap / box.share
  col5791 1.258 -> 1.012 / 1.020 / 1.015 / 1.022   col1403 1.311 -> 1.050 / 1.043 / 1.062 / 1.056
  tsc_a2 0.376 -> 0.402 / 0.402 / 0.419 / 0.419    year6_5411 0.518 -> 0.482 / 0.473 / 0.517 / 0.517
  swiss303 0.569 -> 0.569 / 0.569 / 0.641 / 0.641  mtc_a 0.704 -> 0.705 / 0.705 / 0.767 / 0.767
  geo 0.8264 -> 0.8101 / 0.8091 / 0.8215 / 0.8222; losers 8 -> 8 / 8 / 7 / 8;
  > 1 % worse 1 / 3 / 3 / 4 (worst tsc_a2 1.069 / 1.069 / swiss303 1.126 / 1.126)

  one-campaign 10 (``trace``), main -> lev.swap / lev.share / box.swap / box.share
  lr9211 0.761 -> 0.892 / 0.892 / 1.003 / 1.003   lr9212 0.760 -> 0.886 / 0.886 / 0.839 / 0.839
  lr9643 0.519 -> 0.609 / 0.609 / 0.887 / 0.887   sw9696 0.566 -> 0.573 / 0.573 / 0.574 / 0.574
  lr9641 0.637 -> 0.637 / 0.637 / 0.742 / 0.742   lr9642 0.674 -> 0.674 / 0.674 / 0.887 / 0.887
  geo 0.7657 -> 0.8036 / 0.8066 / 0.8764 / 0.8721; > 1 % worse 4 / 5 / 6 / 6 (FAILS every one)
  fl_thermal 90/10 mean RMSE 2.481 -> 2.481 / 2.481 / 2.779 / 3.491 µm (lev: no test row beyond;
  box: 58 % of its test rows beyond, E_ch1 2.893 -> 4.384 µm)

Main's figures reproduced (22 geo 0.8264, col5791 1.258, col1403 1.311; one-campaign lr9587 1.059,
fl_thermal 2.481 µm).  The built rule (``rule``, the patch applied; lev, swap) gives the trace's
numbers to the digit, its continuing test streamed: lr9211 E_Z 0.6882, lr9212 0.9649 µm.  The beyond rows do
carry the column losers' loss (lev: col5791's lag targets' excess squared error over MLR 3.669e6
of 3.662e6 on its beyond rows, col1403's 6.389e6 of 7.895e6; 68 % / 64 % of the new campaigns' rows
beyond), but they carry the lag families' wins too: beyond the fit region MLR extrapolates worse
than the lag families on most records (tsc_a2 E_dZ1 beyond rows auto 0.532 vs MLR 9.94 µm, mtc_b
E_dZ 6.23 vs 9.54, swiss303 box E_X 0.895 vs 2.05, lr9643 E_Z lev 0.482 vs 12.3 on its 4 rows),
against col5791 E_Z_mid 18.7 vs 6.21.  A few rows beyond carry most of the harm: lr9211 1 row of
864 (auto 4.45 vs MLR 11.5 µm there), lr9212 3, lr9643 4, tsc_a2 256 of 28798.

What differs (measured, not a rule): the share of the scored rows beyond (lev) is 0.55-0.76 on the
five column records (all new campaigns from an unseen source), <= 0.06 on every other record with
a lag target but year6_5411 (0.22, helped: 0.518 -> 0.482); lab5401 0.96, sw9697 0.53 and
twin_lathe 0.27 have no lag target.  A sustained excursion, not a sample, is what separates the
column losers; a rule on it needs its own bar on these seen records (fresh 9795-9804 unspent).

CPU (nice, ``OMP_NUM_THREADS=1``, 2 cores shared, load 15-25): ``trace22`` 22 records 17.8 s,
``trace`` one-campaign 10 31.5 s, fl_thermal 34.8 s, ``rule`` lr9211 + lr9212 9.6 s; ~15 min wall.
"""

import json
import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
os.environ.setdefault("OMP_NUM_THREADS", "1")
from _cli import run_commands  # noqa: E402

LAG = ("lagbank", "hammerstein")
REGIONS = ("lev", "box")


def beyond(X_fit: np.ndarray, X: np.ndarray) -> dict:
    """Rows of ``X`` outside the region of the fit rows ``X_fit``, per region of :data:`REGIONS`."""
    from thermocomp.core.model_selection.extrapolation import within_range

    both = np.vstack([X_fit, X])
    fit = np.r_[np.ones(len(X_fit), bool), np.zeros(len(X), bool)]
    lev = ~within_range(both, fit, ~fit)[~fit]
    lo, hi = np.nanmin(X_fit, axis=0), np.nanmax(X_fit, axis=0)
    box = np.any((X < lo) | (X > hi), axis=1)
    return {"lev": lev, "box": box}


def _rmse(y, p) -> float:
    keep = np.isfinite(y) & np.isfinite(p)
    return float(np.sqrt(np.mean((y[keep] - p[keep]) ** 2))) if keep.any() else float("nan")


def cell(y, blend, mlr, weights: dict, regions: dict, handed=None) -> dict:
    """One target: RMSEs of auto (``blend``) and MLR on all rows, the swap and the beyond rows.

    ``swap``: the whole blend handed to MLR on the beyond rows where the heaviest member is a lag
    family; ``share`` (with ``handed``: the blend with its lag members' weight given to MLR): the
    lag members' share handed over on the beyond rows, whatever the heaviest member."""
    lag = max(weights, key=weights.get) in LAG and max(weights.values()) > 0   # not a zero kept
    out = {"weights": weights, "lag": lag, "n": int(np.isfinite(y).sum()),
           "main": _rmse(y, blend), "mlr": _rmse(y, mlr)}
    for name, rows in regions.items():
        swapped = np.where(rows, mlr, blend) if lag else blend
        out[name] = {"beyond": int((rows & np.isfinite(y)).sum()), "swap": _rmse(y, swapped),
                     "share": _rmse(y, blend if handed is None else np.where(rows, handed, blend)),
                     "auto_beyond": _rmse(y[rows], blend[rows]), "mlr_beyond": _rmse(y[rows], mlr[rows]),
                     # auto's excess squared error over MLR's: all rows, the beyond rows
                     "excess": float(np.nansum((y - blend) ** 2 - (y - mlr) ** 2)),
                     "excess_beyond": float(np.nansum(((y - blend) ** 2 - (y - mlr) ** 2)[rows]))}
    return out


def fitted(root: str, name: str) -> tuple:
    """``(auto, dataset, train, measured, auto's prediction, MLR's)`` of a record of bench_auto98's
    table (``_with_root`` done): ``model=auto`` and MLR alone fitted on its train part as ``run``
    fits it, scored on its own test (bench_auto_rank's ``_test``: a test that continues the train
    part continues its stream)."""
    import bench_auto96
    import bench_auto_rank as rank
    from sklearn.base import clone

    from thermocomp.shell.builders import build_compensator

    cfg, ds, train = bench_auto96._setup(name, root)
    auto = build_compensator(cfg, ds=ds).fit(train)
    mlr = clone(auto).set_params(estimator=rank._mlr()).fit(train)
    meas, pred = rank._test(auto, ds)
    return auto, ds, train, meas, pred, rank._test(mlr, ds)[1]


def trace(root: str, out: str, *records: str) -> None:
    import bench_auto_rank as rank
    from bench_auto98 import _with_root

    _with_root(root, records)
    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        auto, ds, train, meas, pred, base = fitted(root, name)
        _, lagless = rank._test(without_lag(auto), ds)
        m_fit = auto.stacked(train)
        m_test = auto.stacked({c: ds.campaigns[c] for c in ds.ids("test")})
        rep = {}
        for t, est in auto.estimators_.items():
            cols = auto.selected_[t]
            X = m_test.X[cols].to_numpy()
            assert len(X) == len(meas[t]), (name, t, len(X), len(meas[t]))
            regions = beyond(m_fit.X[cols].to_numpy(), X)
            w = dict(est.weights_)
            handed = lagless[t] + sum(v for n, v in w.items() if n in LAG) * base[t]
            rep[t] = cell(meas[t], pred[t], base[t], w, regions, handed)
        Path(out, f"{name}.json").write_text(json.dumps(rep, indent=1, default=float))
        _said(name, rep)


def without_lag(auto):
    """A copy of the fitted ``auto`` compensator whose blends weight their lag members 0 (a lag
    family kept alone: a zero prediction), the rest as fitted."""
    import copy

    from thermocomp.core.models.blend import Blend

    out = copy.deepcopy(auto)
    for est in out.estimators_.values():
        kept = est.estimator_
        if isinstance(kept, Blend):
            kept.weights_ = np.array([0.0 if n in LAG else w
                                      for n, w in zip(kept.estimators_, kept.weights_)])
        elif est.family_ in LAG:
            est.estimator_ = Blend({est.family_: kept}, {est.family_: 1.0})
            est.estimator_.estimators_, est.estimator_.weights_ = {est.family_: kept}, np.zeros(1)
            est.estimator_.context_columns_ = est.context_columns_
    return out


def _said(name: str, rep: dict) -> None:
    parts = []
    for t, c in rep.items():
        regs = " ".join(f"{r} {c[r]['beyond']}/{c['n']} a|m {c[r]['auto_beyond']:.3g}|"
                        f"{c[r]['mlr_beyond']:.3g} swap {c[r]['swap']:.4g}" for r in REGIONS)
        parts.append(f"{t} lag={c['lag']} auto {c['main']:.4g} mlr {c['mlr']:.4g} {regs}")
    print(name, "; ".join(parts), flush=True)


def rule(root: str, out: str, *records: str) -> None:
    """Each record fitted with the built rule (``beyond_fit='mlr'``, a tree with
    benchmarks/auto98b_rule.patch applied) and scored on its own test as ``trace`` scores it:
    OUT/RECORD.rule.json, its RMSE per target beside ``trace``'s lev.swap (run ``trace`` first)."""
    import bench_auto96
    import bench_auto_rank as rank
    from bench_auto98 import _with_root

    from thermocomp.shell.builders import build_compensator

    _with_root(root, records)
    for name in records:
        cfg, ds, train = bench_auto96._setup(name, root)
        comp = build_compensator(cfg, ds=ds)
        comp.estimator.set_params(beyond_fit="mlr")
        meas, pred = rank._test(comp.fit(train), ds)
        traced = json.loads(Path(out, f"{name}.json").read_text())
        rep = {t: {"rule": _rmse(meas[t], pred[t]), "traced": traced[t]["lev"]["swap"],
                   "main": traced[t]["main"]} for t in meas}
        Path(out, f"{name}.rule.json").write_text(json.dumps(rep, indent=1))
        print(name, {t: {k: round(v, 4) for k, v in c.items()} for t, c in rep.items()}, flush=True)


def framed(root: str, work: Path, name: str) -> tuple:
    """A 22-table record (bench_auto98.with_new_campaigns's) with an MLR compensator fitted on its
    train part for the frame and columns only: ``(cfg, dataset, scored dataset, scored ids, the
    compensator, the train rows stacked, the scored rows stacked)``."""
    import bench_auto_rank as rank
    from bench_auto98 import with_new_campaigns

    from thermocomp.shell.builders import build_compensator

    cfg, ds, train, full, ids = with_new_campaigns(root, work, name)
    comp = build_compensator(cfg, ds=ds).set_params(estimator=rank._mlr()).fit(train)
    return cfg, ds, full, ids, comp, comp.stacked(train), comp.stacked({c: full.campaigns[c] for c in ids})


def trace22(root: str, main_work: str, out: str, *records: str) -> None:
    from bench_auto91 import stored_targets

    work = Path(main_work).resolve()
    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        *_, comp, m_fit, m_all = framed(root, work, name)
        rep = {}
        for t, w, a, y_new, new, _ in stored_targets(work, name):
            X = m_all.X[comp.selected_[t]].to_numpy()
            assert len(X) == len(y_new), (name, t, len(X), len(y_new))
            regions = beyond(m_fit.X[comp.selected_[t]].to_numpy(), X)
            test = {k[5:]: a[k] for k in a.files if k.startswith("pred_") and k != "pred_auto"}
            blend = sum(v * test[n] for n, v in w.items())
            y = np.where(new, y_new, np.nan)
            handed = sum(v * test["mlr" if n in LAG else n] for n, v in w.items())
            rep[t] = cell(y, blend, test["mlr"], dict(w), {r: v & new for r, v in regions.items()}, handed)
        Path(out, f"{name}.json").write_text(json.dumps(rep, indent=1, default=float))
        _said(name, rep)


def table(out: str, *records: str) -> None:
    """Per record bench_auto96's figure main -> swap in each region; the geometric mean, losers."""
    from bench_auto96 import _geo

    figs = {}
    for name in records:
        rep = json.loads(Path(out, f"{name}.json").read_text())
        mlr = np.mean([c["mlr"] for c in rep.values()])
        fig = {"main": np.mean([c["main"] for c in rep.values()]) / mlr}
        fig.update({f"{r}.{how}": np.mean([c[r][how] for c in rep.values()]) / mlr
                    for r in REGIONS for how in ("swap", "share")})
        share = {r: _share(rep, r) for r in REGIONS}
        figs[name] = fig
        print(f"{name:11s} main {fig['main']:.3f} " + " ".join(
            f"{k} {v:.3f} ({v / fig['main']:.3f})" for k, v in fig.items() if k != "main")
            + "; lag targets' excess over MLR on the beyond rows "
            + ", ".join(f"{r} {share[r]}" for r in REGIONS))
    main = [f["main"] for f in figs.values()]
    for r in [k for k in next(iter(figs.values())) if k != "main"]:
        rule = [f[r] for f in figs.values()]
        ratio = np.divide(rule, main)
        print(f"{len(main)} records, {r}: geo auto/MLR main {_geo(main):.4f} swap {_geo(rule):.4f}; losers "
              f"{sum(v > 1 for v in main)} -> {sum(v > 1 for v in rule)}; > 1 % worse "
              f"{int(np.sum(ratio > 1.01))}; worst swap/main {ratio.max():.3f}")


def _share(rep: dict, region: str) -> str:
    """The share of auto's excess squared error over MLR's (positive only: a loss) on the beyond
    rows, over the lag targets."""
    lag = [c for c in rep.values() if c["lag"]]
    total = sum(c[region]["excess"] for c in lag)
    inside = sum(c[region]["excess_beyond"] for c in lag)
    return f"{inside:.4g} of {total:.4g}" if lag else "no lag target"


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "rule": rule, "trace22": trace22, "table": table}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
