"""A TRAIN-SIDE signal telling a lag family that will fail on new data from one that will not, inside
``model=auto``'s blend (issue 34; stop 96, auto96; follow-up of bench_auto95b's "next").

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_auto96.py one OUT RECORD ...          # one-campaign records: fit, keep arrays
    python benchmarks/bench_auto96.py signals SIDE WORK ...       # per target with lag weight: signals
    python benchmarks/bench_auto96.py table SIDE SIGNAL LIMIT WORK ... # the prototype rule
    python benchmarks/bench_auto96.py amp ROOT OUT RECORD ...     # refits: amplification
    python benchmarks/bench_auto96.py leo ROOT OUT RECORD ...     # refits: leave the extremes out
    python benchmarks/bench_auto96.py stab ROOT OUT RECORD ...    # refits: fold models' spread

Two kinds of stored rows, both fitted on the record's train part only (nothing of a test is read
to compute a signal; the tests are only scored):

* bench_automore69's ``rows`` (bench_auto91's ``rows ROOT WORK RECORD ...``, a WORK holding
  ``automore.jsonl`` and ``pred/``): the 22-record table's records, scored on the 12-16 NEW
  campaigns of their machine; the record figure is the mean over targets of the pooled RMSE, auto
  over MLR (bench_remeasure62's).
* ``one`` (bench_auto_rank's ``main``: auto with ``keep_oof`` and every candidate alone, their
  out-of-fold and test predictions in OUT/RECORD.TARGET.npz, the weights in OUT/RECORD.json):
  bench_auto95's one-campaign records (:data:`RECORDS`: its 10 seen, and FRESH 9719-9728), scored
  on their own test; the record figure is the mean over targets of auto's RMSE / MLR's
  (bench_auto95's).

``signals``: per target where a lag family (``lagbank`` / ``hammerstein``: a ``tau_max_s``, 48 h)
holds weight, the heaviest such family L and, from its out-of-fold predictions against MLR's on the
validation folds (``fold_ratios``: the votes' own measure, fold k's summed squared error over
MLR's), the candidate signals (:data:`SIGNALS`), beside the target's test RMSE over MLR's: auto's
and L's alone.  ``table``: the prototype rule -- where SIGNAL of L exceeds LIMIT, L's weight goes
to MLR (the other members keep theirs) -- scored from the stored test predictions (a blend predicts
``sum w_i * member_i``: no refit), per record main -> rule.  ``amp`` / ``leo`` / ``stab`` (ROOT
as bench_auto91's, the records of either kind) refit on the train record only and write per record
a json under OUT, which ``signals`` / ``table`` read from SIDE/amp, SIDE/leo, SIDE/stab:

* ``amp``: amplification -- per target the sum over inputs of the RMS of each input's part of the
  train prediction (the prediction less the one with that input held at its first sample) over the
  RMS of their sum: a prediction that is a difference of large parts extrapolates badly; the lag
  family's over MLR's.
* ``leo``: leave the extremes out -- per input and tail (top / bottom tenth of its rows), MLR and
  the lag families fitted on the other rows, the record predicted in free run, scored on the held
  rows (:func:`extreme_folds`); the lag family's pooled squared error over MLR's (``leo_top``: the
  top tails only, inputs beyond the fitted envelope).
* ``stab``: coefficient stability -- each family fitted on each of auto's validation folds' fit
  rows predicts the WHOLE train record; the RMS over rows of the spread across the fold models, the
  lag family's over MLR's.
* from the stored out-of-fold predictions (:data:`SIGNALS`): the lag family's fold ratios'
  dispersion ``disp`` (fold-gain variance, log), ``last`` (the fold nearest the test), ``trend``
  (slope of the log ratio over the folds: a gain fading with more data), ``worst``, ``cv``.

BAR (written and committed before ``table`` was run on any signal, before any FRESH seed): a
prototype rule (one signal, one limit; :func:`_moved`: the lag family's weight to MLR) is built
into src only if on the SEEN records (the 22-record table's records stored here and bench_auto95's
10 one-campaign records) (1) no record's auto / MLR is > 1 % above main's, (2) the geometric mean of
auto / MLR is below main's, (3) fewer records lose to MLR (> 1.0) than on main.  Then FRESH 9719-9728
(bench_auto95's :data:`FRESH`) scored ONCE through src: no record > 2 % worse than main, geo not
above main's.  (1)-(3) failing for every signal: no src, no fresh seed drawn (TRACED), the
signal table kept as the finding.  Limits tried (named here, from the signal table's gaps on the
seen targets): ``last`` 0.9, ``trend`` 0.3, ``amp`` 0.9, ``disp`` 1.2.
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


def _records():
    from bench_auto95 import RECORDS

    return RECORDS


def one(out: str, *records: str) -> None:
    import bench_auto_rank as rank

    os.environ["OUT"] = str(Path(out).resolve())
    recs = _records()
    for name in records:
        sys.argv[2:] = list(recs[name])           # rank._dataset reads sim= from argv
        rank.main(name, list(recs[name]))


def ways(root: str, out: str, *records: str) -> None:
    """Each record fitted as ``run`` fits it with ``lag_fade`` off (main) and at its default (the
    rule), and MLR alone; OUT/RECORD.json: per target the test RMSEs and both weights; the record's
    auto / MLR both ways (bench_auto95's figure: the mean over targets of the ratio)."""
    import bench_auto_rank as rank
    from sklearn.base import clone

    from thermocomp.shell.builders import build_compensator

    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        cfg, ds, train = _setup(name, root)
        rep = {"weights": {}}
        for way, fade in (("main", None), ("rule", 0.3)):
            auto = build_compensator(cfg, ds=ds)
            auto.estimator.set_params(lag_fade=fade)
            auto.fit(train)
            meas, pred = rank._test(auto, ds)
            rep[way] = {t: _rmse(meas[t], pred[t]) for t in meas}
            rep["weights"][way] = {t: e.weights_ for t, e in auto.estimators_.items()}
        meas, pred = rank._test(clone(auto).set_params(estimator=rank._mlr()).fit(train), ds)
        rep["mlr"] = {t: _rmse(meas[t], pred[t]) for t in meas}
        Path(out, f"{name}.json").write_text(json.dumps(rep, indent=1, default=float))
        fig = {w: float(np.mean([rep[w][t] / rep["mlr"][t] for t in rep["mlr"]])) for w in ("main", "rule")}
        print(f"{name} auto/MLR main {fig['main']:.3f} rule {fig['rule']:.3f} rule/main "
              f"{fig['rule'] / fig['main']:.3f}; weights rule {rep['weights']['rule']}", flush=True)


def ways_table(out: str, *records: str) -> None:
    figs = {}
    for name in records:
        rep = json.loads(Path(out, f"{name}.json").read_text())
        figs[name] = {w: float(np.mean([rep[w][t] / rep["mlr"][t] for t in rep["mlr"]]))
                      for w in ("main", "rule")}
        f = figs[name]
        print(f"{name:8s} main {f['main']:.3f} rule {f['rule']:.3f} rule/main {f['rule'] / f['main']:.3f}")
    m, r = [f["main"] for f in figs.values()], [f["rule"] for f in figs.values()]
    print(f"geo auto/MLR main {_geo(m):.4f} rule {_geo(r):.4f}; worst rule/main "
          f"{max(np.divide(r, m)):.3f}; losers {sum(v > 1 for v in m)} -> {sum(v > 1 for v in r)}")


# --------------------------------------------------------------------------- amplification
def _setup(name: str, root: str):
    """``(cfg, dataset, train)`` of a record: bench_automore69's (ROOT) or bench_auto95's."""
    import bench_auto_rank as rank
    from bench_automore69 import OVERRIDES

    overrides = ([o.format(root=Path(root).resolve()) for o in OVERRIDES[name]] if name in OVERRIDES
                 else list(_records()[name]))
    sys.argv[2:] = overrides                      # rank._dataset reads sim= from argv
    return rank.setup(overrides)


def _train_predictions(comp, ds, frozen=()) -> dict:
    """Per target, ``comp``'s free-run prediction of the train campaigns (concatenated), the
    inputs named in ``frozen`` held at each campaign's first sample."""
    from dataclasses import replace

    from thermocomp.core import continuation

    ids = ds.ids("train")
    camps = dict(ds.campaigns)
    for c in ids:
        frame = camps[c].copy()
        for col in frozen:
            frame[col] = frame[col].iloc[0]
        camps[c] = frame
    pred, _ = continuation.predict(comp, replace(ds, campaigns=camps), ids, "simulation")
    return {t: np.concatenate([pred[c][t].to_numpy(float) for c in ids]) for t in comp.targets_}


def amplification(comp, ds) -> dict:
    """Per target, how much ``comp``'s train prediction is a difference of large parts: the sum
    over inputs of the RMS of each input's contribution (the prediction less the one with that
    input held at its first sample) over the RMS of their sum (less the one with all held); 1
    where the inputs' parts add up, large where they cancel on the train record."""
    inputs = [c for c in ds.columns_of("T_")]
    full, held = _train_predictions(comp, ds), _train_predictions(comp, ds, inputs)
    parts = {c: _train_predictions(comp, ds, [c]) for c in inputs}
    return {t: float(sum(np.sqrt(np.mean((full[t] - parts[c][t]) ** 2)) for c in inputs)
                     / max(np.sqrt(np.mean((full[t] - held[t]) ** 2)), 1e-300)) for t in comp.targets_}


def amp(root: str, out: str, *records: str) -> None:
    from sklearn.base import clone

    from thermocomp.shell.builders import build_compensator

    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        cfg, ds, train = _setup(name, root)
        auto = build_compensator(cfg, ds=ds)
        got = {}
        for fam in ("mlr", *LAG):
            cand = auto.estimator.candidates.get(fam)
            if cand is None and fam != "mlr":
                continue
            import bench_auto_rank as rank

            comp = clone(auto).set_params(estimator=clone(cand) if cand is not None else rank._mlr())
            got[fam] = amplification(comp.fit(train), ds)
        Path(out, f"{name}.json").write_text(json.dumps(got, indent=1))
        print(name, {f: {t: round(v, 2) for t, v in a.items()} for f, a in got.items()}, flush=True)


# --------------------------------------------------------------------------- leave the extremes out
TAIL = 0.1    # a fold holds out the rows where one input lies in its top (or bottom) tenth


def extreme_folds(X: np.ndarray, tail: float = TAIL) -> list:
    """``(fit, predict, score)`` masks: per input column and tail, the rows beyond its ``tail``
    quantile held out (scored), every other row fitted, the whole record predicted in free run;
    identical masks once, columns with fewer than 3 values (states) none."""
    folds, seen = [], set()
    for j in range(X.shape[1]):
        x = X[:, j]
        if np.unique(x).size < 3:
            continue
        lo, hi = np.quantile(x, [tail, 1 - tail])
        for held in (x > hi, x < lo):
            key = held.tobytes()
            if held.sum() >= 10 and key not in seen:
                seen.add(key)
                folds.append((~held, np.ones(len(x), bool), held))
    return folds


def _tails(X: np.ndarray, tail: float = TAIL) -> list:
    """``"top"`` / ``"bottom"`` for each of :func:`extreme_folds`'s folds, in order."""
    out, seen = [], set()
    for j in range(X.shape[1]):
        x = X[:, j]
        if np.unique(x).size < 3:
            continue
        lo, hi = np.quantile(x, [tail, 1 - tail])
        for side, held in (("top", x > hi), ("bottom", x < lo)):
            key = held.tobytes()
            if held.sum() >= 10 and key not in seen:
                seen.add(key)
                out.append(side)
    return out


def leo(root: str, out: str, *records: str) -> None:
    """Per record and target, MLR and the lag families fitted without each input's extreme rows,
    scored on them (:func:`extreme_folds`): the lag family's fold ratios to MLR."""
    from sklearn.base import clone

    from thermocomp.core.models.auto import AutoRegressor
    from thermocomp.shell.builders import build_compensator

    AutoRegressor._folds = lambda self, groups, n: extreme_folds(self._X_leo)
    fit0 = AutoRegressor.fit

    def fit(self, X, y, context=None):
        self._X_leo = np.asarray(X, float)
        return fit0(self, X, y, context)

    AutoRegressor.fit = fit
    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        cfg, ds, train = _setup(name, root)
        auto = build_compensator(cfg, ds=ds)
        cands = {n: c for n, c in auto.estimator.candidates.items() if n in ("mlr", *LAG)}
        est = clone(auto.estimator).set_params(candidates=cands, combine="best", keep_oof=True,
                                               fallback="none")
        comp = clone(auto).set_params(estimator=est).fit(train)
        got = {}
        for t, e in comp.estimators_.items():
            got[t] = {n: np.bincount(e.oof_fold_, (e.oof_y_ - e.oof_[n]) ** 2).tolist() for n in e.oof_}
            got[t]["tail"] = _tails(e._X_leo)
        Path(out, f"{name}.json").write_text(json.dumps(got, indent=1))
        print(name, {t: {n: round(_pooled(g, n), 3) for n in LAG if n in g} for t, g in got.items()},
              flush=True)


def stab(root: str, out: str, *records: str) -> None:
    """Per record and target, MLR and the lag families fitted on each of auto's own validation
    folds' fit rows, each predicting the WHOLE train record in free run: the spread of a family's
    fold models' predictions (RMS over rows of their standard deviation across folds) over MLR's,
    its coefficients' instability seen through what they predict."""
    from sklearn.base import clone

    from thermocomp.core.models.auto import AutoRegressor
    from thermocomp.shell.builders import build_compensator

    folds0 = AutoRegressor._folds
    AutoRegressor._folds = lambda self, groups, n: [(fit, np.ones(n, bool), np.ones(n, bool))
                                                    for fit, *_ in folds0(self, groups, n)]
    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        cfg, ds, train = _setup(name, root)
        auto = build_compensator(cfg, ds=ds)
        cands = {n: c for n, c in auto.estimator.candidates.items() if n in ("mlr", *LAG)}
        est = clone(auto.estimator).set_params(candidates=cands, combine="best", keep_oof=True,
                                               fallback="none")
        comp = clone(auto).set_params(estimator=est).fit(train)
        got = {}
        for t, e in comp.estimators_.items():
            k = int(e.oof_fold_.max()) + 1
            spread = {n: float(np.sqrt(np.mean(np.var(e.oof_[n].reshape(k, -1), axis=0))))
                      for n in e.oof_}
            got[t] = {n: spread[n] / max(spread["mlr"], 1e-300) for n in spread}
        Path(out, f"{name}.json").write_text(json.dumps(got, indent=1))
        print(name, {t: {n: round(v, 2) for n, v in g.items()} for t, g in got.items()}, flush=True)


def _pooled(g: dict, name: str, side: str | None = None) -> float:
    """The lag family's summed squared error over MLR's on the held-out extremes (``side``: the
    top or bottom tails only)."""
    keep = [side is None or s == side for s in g["tail"]]
    return float(np.sum(np.compress(keep, g[name])) / np.sum(np.compress(keep, g["mlr"])))


# --------------------------------------------------------------------------- stored rows
def _targets(work: Path):
    """Per record of WORK: ``(record, kind, [(target, weights, oof, oof_y, oof_fold, test_y,
    test)])``; ``oof`` / ``test`` dicts of candidate -> predictions (``test`` only on the scored
    rows: the new campaigns, or the own test)."""
    if (work / "automore.jsonl").exists():
        from bench_auto91 import _row, stored_targets

        names = [json.loads(line)["record"] for line in (work / "automore.jsonl").read_text().splitlines()]
        for name in dict.fromkeys(names):
            rows = []
            for t, w, a, y_new, new, members in stored_targets(work, name):
                test = {k[5:]: a[k][new] for k in a.files if k.startswith("pred_") and k != "pred_auto"}
                rows.append((t, w, members, a["oof_y"], a["oof_fold"], y_new[new], test))
            yield name, "new", rows, _row(work, name)
        return
    for rep_path in sorted(work.glob("*.json")):
        rep = json.loads(rep_path.read_text())
        rows = []
        for t, row in rep["targets"].items():
            a = np.load(work / f"{rep['record']}.{t}.npz")
            oof = {k[4:]: a[k] for k in a.files if k.startswith("oof_") and k not in (
                "oof_y", "oof_fold", "oof_in_range", "oof_group")}
            test = {k[5:]: a[k] for k in a.files if k.startswith("test_") and k != "test_y"}
            rows.append((t, row["auto"]["weights"], oof, a["oof_y"], a["oof_fold"], a["test_y"], test))
        yield rep["record"], "own", rows, rep


def _rmse(y, p) -> float:
    return float(np.sqrt(np.mean((y - p) ** 2)))


def _blend(weights: dict, test: dict) -> np.ndarray:
    return sum(w * test[n] for n, w in weights.items())


# --------------------------------------------------------------------------- signals
def _ratios(oof, y, fold, name) -> np.ndarray:
    from thermocomp.core.models.blend import fold_ratios

    return fold_ratios((y - oof[name]) ** 2, (y - oof["mlr"]) ** 2, fold)


def _slope(v: np.ndarray) -> float:
    return float(np.polyfit(np.arange(v.size), v, 1)[0]) if v.size > 1 else 0.0


SIGNALS = {   # of the lag family's fold ratios r_k (k = 1..K, forward folds in order)
    "disp": lambda r: float(np.std(np.log(r))),         # fold-gain variance (log scale)
    "last": lambda r: float(r[-1]),                     # the fold nearest the test, fitted on most
    "trend": lambda r: _slope(np.log(r)),               # the gain fading over later folds (> 0)
    "worst": lambda r: float(np.max(r)),                # its worst fold
    "cv": lambda r: float(np.std(r) / np.mean(r)),      # dispersion relative to its mean ratio
}


def _side(side: Path, kind: str, name: str) -> dict | None:
    path = side / kind / f"{name}.json"
    return json.loads(path.read_text()) if path.exists() else None


def _trained(side: Path, name: str, t: str, L: str) -> dict:
    """The signals measured by refits on the train record (``amp``, ``leo``), where measured."""
    out = {}
    a, e = _side(side, "amp", name), _side(side, "leo", name)
    if a is not None:
        out["amp"] = a[L][t] / a["mlr"][t]
    if e is not None and "tail" in e[t]:
        out["leo"] = _pooled(e[t], L)
        out["leo_top"] = _pooled(e[t], L, "top")
    b = _side(side, "stab", name)
    if b is not None:
        out["stab"] = b[t][L]
    return out


def _lag_rows(side: Path, work: Path):
    for name, kind, rows, _ in _targets(work):
        for t, w, oof, y, fold, ty, test in rows:
            lag = [n for n in LAG if w.get(n, 0) > 0]
            if not lag:
                continue
            L = max(lag, key=w.get)
            r = _ratios(oof, y, fold, L)
            sig = {k: f(r) for k, f in SIGNALS.items()} | _trained(side, name, t, L)
            yield name, kind, t, w, L, r, sig, {
                "auto": _rmse(ty, _blend(w, test)) / _rmse(ty, test["mlr"]),
                "alone": _rmse(ty, test[L]) / _rmse(ty, test["mlr"])}


TRAINED = ("amp", "leo", "leo_top", "stab")


def signals(side: str, *works: str) -> None:
    print("record    kind target    L            w(L) w(lag) folds r_k (L / MLR)          "
          + " ".join(f"{s:>6s}" for s in (*SIGNALS, *TRAINED)) + "  auto/MLR L/MLR (test)")
    seen = []
    for work in works:
        for name, kind, t, w, L, r, sig, test in _lag_rows(Path(side), Path(work).resolve()):
            seen.append((sig, test["alone"] > 1.0))
            wl = sum(w.get(n, 0) for n in LAG)
            rs = " ".join(f"{v:.2f}" for v in r)
            print(f"{name:9s} {kind:4s} {t:9s} {L:12s} {w[L]:.2f} {wl:.2f}   {rs:28s} "
                  + " ".join(f"{sig[k]:6.2f}" if k in sig else "     -" for k in (*SIGNALS, *TRAINED))
                  + f"  {test['auto']:.3f}    {test['alone']:.3f}")
    print("separation of the targets whose lag family alone loses to MLR on test (L/MLR > 1) from "
          "those where it wins: AUC (1: every loser's signal above every winner's), n losers / winners")
    for k in (*SIGNALS, *TRAINED):
        lose = [sg[k] for sg, bad in seen if bad and k in sg]
        win = [sg[k] for sg, bad in seen if not bad and k in sg]
        if lose and win:
            auc = np.mean([(a > b) + 0.5 * (a == b) for a in lose for b in win])
            print(f"  {k:8s} AUC {auc:.2f}  ({len(lose)} / {len(win)}); losers {np.min(lose):.2f}.."
                  f"{np.max(lose):.2f}, winners {np.min(win):.2f}..{np.max(win):.2f}")


# --------------------------------------------------------------------------- the prototype rule
def _moved(w: dict, oof, y, fold, value) -> dict:
    """``w`` with each lag family whose signal (``value(name, fold ratios)``; None: not measured,
    kept) exceeds the limit handing its weight to MLR."""
    out = dict(w)
    for n in LAG:
        if out.get(n, 0) > 0 and value(n, _ratios(oof, y, fold, n)):
            out["mlr"] = out.get("mlr", 0.0) + out.pop(n)
    return out


def _figure(kind: str, rows, weights) -> float:
    auto = [_rmse(ty, _blend(w, test)) for (_, _, _, _, _, ty, test), w in zip(rows, weights)]
    mlr = [_rmse(ty, test["mlr"]) for *_, ty, test in rows]
    if kind == "new":
        return float(np.mean(auto) / np.mean(mlr))
    return float(np.mean(np.divide(auto, mlr)))


def _geo(v) -> float:
    return float(np.exp(np.mean(np.log(v))))


def table(side: str, signal: str, limit: str, *works: str) -> None:
    lim = float(limit)
    print(f"rule: a lag family with {signal} > {lim} hands its weight to MLR")
    print("record    kind main   rule   rule/main  moved")
    main_all, rule_all = [], []
    for work in works:
        for name, kind, rows, _ in _targets(Path(work).resolve()):
            def value(n, r, t):
                sig = {k: f(r) for k, f in SIGNALS.items()} | _trained(Path(side), name, t, n)
                return signal in sig and sig[signal] > lim

            base = [w for _, w, *_ in rows]
            new = [_moved(w, oof, y, fold, lambda n, r, t=t: value(n, r, t))
                   for t, w, oof, y, fold, *_ in rows]
            m, r = _figure(kind, rows, base), _figure(kind, rows, new)
            moved = [t for (t, *_), a, b in zip(rows, base, new) if a != b]
            main_all.append(m)
            rule_all.append(r)
            print(f"{name:9s} {kind:4s} {m:.3f}  {r:.3f}  {r / m:.3f}      {' '.join(moved)}")
    worse = int(np.sum(np.divide(rule_all, main_all) > 1.01))
    print(f"geo auto/MLR main {_geo(main_all):.4f} rule {_geo(rule_all):.4f}; losers (> 1.0) "
          f"{sum(v > 1.0 for v in main_all)} -> {sum(v > 1.0 for v in rule_all)}; > 1 % worse than "
          f"main {worse}; worst rule/main {max(np.divide(rule_all, main_all)):.3f}")


def main(argv: list[str]) -> int:
    commands = {"one": one, "amp": amp, "leo": leo, "stab": stab, "ways": ways, "ways_table": ways_table, "signals": signals, "table": table}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
