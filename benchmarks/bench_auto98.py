"""auto no worse than MLR where the lag families extrapolate: a lead held only beyond every fold's
range (issue 34; stop 98, auto98; the "next" of bench_auto97).

The rule built (``lead_margin``; benchmarks/auto98_rule.patch against 16d3b58d): a fitted LagBank
keeps its leads' range over its fit rows (``lead_bounds_``, always); with ``lead_margin`` set,
``predict`` / ``stream_step`` / ``stream_steps`` hold every lead ``L_tau[x] - x`` in that range
widened by ``lead_margin`` times its span on each side (levels free).  ``model=auto`` sets it
(``AutoRegressor(lead_margin=...)``, :func:`~thermocomp.core.models.lagbank.hold_leads`) on its
FINAL refit only (all train rows: the union of every fold's rows), never on its folds: an
out-of-fold row is a train row, inside that range, so the votes are main's to the bit and the hold
acts only where no fold ever saw a lead (bench_auto97's hold in every fold moved the votes: iso_b
1.122, lr9643 2.308 x main).  With the votes unchanged one fit of auto (main) gives main and the
rule at every margin: the fitted lag banks' ``lead_margin`` set after the fit (:func:`hold`).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``, a tree with the patch applied)::

    python benchmarks/bench_auto98.py ways ROOT OUT MARGINS RECORD ...      # auto fitted once, held at MARGINS
    python benchmarks/bench_auto98.py ways_table OUT MARGIN RECORD ...      # auto / MLR main -> held
    python benchmarks/bench_auto98.py seen22 ROOT MAIN_WORK OUT MARGINS RECORD ...   # the 22-table
    python benchmarks/bench_auto98.py seen22_table OUT MARGIN RECORD ...
    python benchmarks/bench_auto98.py beside ROOT OUT MARGIN RECORD ...     # a held lag bank beside lagbank
    python benchmarks/bench_auto98.py beside22 ROOT MAIN_WORK OUT MARGIN RECORD ...

``ways``: each record (:data:`RECORDS`: bench_auto95's SEEN, ``fl_thermal`` 90/10, the FRESH ten)
fitted as ``run`` fits it (bench_auto_rank's ``setup``, ``model=auto``), scored on its own test with
the held leads off (main) and at each of MARGINS (comma-separated; ``none``: free), and MLR alone
(OUT/RECORD.json; the figure: the mean over targets of auto's RMSE / MLR's).  ``seen22``: the 22
records of bench_auto96's table (main's stored rows MAIN_WORK = ``/tmp/auto96/seen``: auto and
every candidate alone, scored on 12-16 new campaigns of the machine; model code b77996ba = 16d3b58d's):
the lag families fitted alone again on the train part, their new-campaign predictions held at
MARGINS and put in auto's blend in place of the stored free ones (weights unchanged: the folds are
main's); the free refit reproduces the stored prediction (``reproduced``, True on every target
measured).  The figure: bench_auto96's (mean over targets of auto's pooled RMSE / mean of MLR's).
``beside`` / ``beside22``: the brief's other form -- a candidate ``lagheld`` (:data:`HELD`: the
lag bank with ``lead_margin``) beside ``lagbank``, held in every fold at that fold's own range,
so auto's CV may pick it; auto refitted (its folds), the new campaigns scored from the stored
candidates and ``seen22``'s held lag bank.

BAR (the brief's, written here and committed before FRESH 9795-9804 are simulated; the rule is KEPT
only if all hold, and only with the hold carried into the exported C / ST so deployed = scored,
``tests/shell/test_export_auto57.py`` passing):
(1) SEEN 22-table (``seen22`` against main's stored rows): losers (auto / MLR > 1.0) fewer than
    main's 8, no record's rule / main > 1.01.  The 10 seen one-campaign records (bench_auto95's
    SEEN, ``ways``): no record's rule / main > 1.01.
(2) fl_thermal 90/10 (``ways ... fl_thermal``): mean RMSE over ch1..ch5 not above 2.481 µm by more
    than 1 % (<= 2.506).
(3) FRESH 9795-9804 (:data:`FRESH`, bench_auto96b.fresh_records(9795): lr9795-9797, sw9798-9799,
    col9800-9801, year6_9802, climate9803, lab9804), scored ONCE with ``ways``: losers no more than
    main's, the geometric mean of auto / MLR not above main's.
The margin is chosen on the SEEN records only, before (3).  Fresh seeds are drawn only if (1)
and (2) hold.
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
from bench_auto95 import SEEN as SEEN95  # noqa: E402
from bench_auto96b import fresh_records  # noqa: E402

FRESH = fresh_records(9795)   # lr9795-9797 sw9798-9799 col9800-9801 year6_9802 climate9803 lab9804
RECORDS = {**SEEN95, "fl_thermal": ["data=fl_thermal"], **FRESH}
LABS = {"lab9804": 9804}       # written by bench_auto_losses56's lab_record under ROOT
LAG = ("lagbank", "hammerstein")


def hold(est, margin) -> int:
    """(the patch's) :func:`~thermocomp.core.models.lagbank.hold_leads`: ``lead_margin`` on every
    fitted lag bank in ``est`` (None: free, main's behaviour); how many."""
    from thermocomp.core.models.lagbank import hold_leads

    return hold_leads(est, margin)


def _margins(word: str) -> list:
    return [None if m == "none" else float(m) for m in word.split(",")]


def _key(margin) -> str:
    return "main" if margin is None else f"held{margin:g}"


def ways(root: str, out: str, margins: str, *records: str) -> None:
    import bench_auto96
    import bench_auto_rank as rank
    from sklearn.base import clone

    from thermocomp.shell.builders import build_compensator

    _with_root(root, records)
    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        cfg, ds, train = bench_auto96._setup(name, root)
        auto = build_compensator(cfg, ds=ds).fit(train)
        rep = {"weights": {t: e.weights_ for t, e in auto.estimators_.items()},
               "banks": hold(auto, None)}
        for margin in [None, *_margins(margins)]:
            hold(auto, margin)
            meas, pred = rank._test(auto, ds)
            rep[_key(margin)] = {t: bench_auto96._rmse(meas[t], pred[t]) for t in meas}
        meas, pred = rank._test(clone(auto).set_params(estimator=rank._mlr()).fit(train), ds)
        rep["mlr"] = {t: bench_auto96._rmse(meas[t], pred[t]) for t in meas}
        Path(out, f"{name}.json").write_text(json.dumps(rep, indent=1, default=float))
        cells = " ".join(f"{k} {_figure(rep, k):.3f}" for k in rep if k.startswith(("main", "held")))
        print(f"{name} auto/MLR {cells}; weights {rep['weights']}", flush=True)


def _figure(rep: dict, key: str) -> float:
    return float(np.mean([rep[key][t] / rep["mlr"][t] for t in rep["mlr"]]))


def ways_table(out: str, margin: str, *records: str) -> None:
    from bench_auto96 import _geo

    key, main, held = _key(_margins(margin)[0]), [], []
    for name in records:
        rep = json.loads(Path(out, f"{name}.json").read_text())
        m, h = _figure(rep, "main"), _figure(rep, key)
        main.append(m)
        held.append(h)
        print(f"{name:11s} main {m:.3f} {key} {h:.3f} held/main {h / m:.3f}   "
              f"mean RMSE {np.mean(list(rep['main'].values())):.4g} -> {np.mean(list(rep[key].values())):.4g}")
    ratio = np.divide(held, main)
    print(f"{len(main)} records: geo auto/MLR main {_geo(main):.4f} {key} {_geo(held):.4f}; losers "
          f"{sum(v > 1 for v in main)} -> {sum(v > 1 for v in held)}; worst held/main {ratio.max():.3f}; "
          f"> 1 % worse {int(np.sum(ratio > 1.01))}")


def seen22(root: str, main_work: str, out: str, margins: str, *records: str) -> None:
    import bench_auto_rank as rank
    from bench_auto91 import stored_targets
    from bench_automore69 import OF, OVERRIDES, draws
    from bench_moretest68 import with_new
    from sklearn.base import clone

    from thermocomp.core.scoring.evaluation import split_residuals
    from thermocomp.shell.builders import build_compensator

    work = Path(main_work).resolve()
    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        stored = list(stored_targets(work, name))
        families = sorted({n for _, w, *_ in stored for n, v in w.items() if n in LAG and v > 0}
                          | ({"lagbank"} if "pred_lagbank" in stored[0][2].files else set()))
        rep = {"families": families, "targets": {}}
        if families:
            overrides = [o.format(root=Path(root).resolve()) for o in OVERRIDES[name]]
            sys.argv[2:] = overrides
            cfg, ds, train = rank.setup(overrides)
            full = with_new(ds, draws(OF[name], work, cfg))
            row = json.loads(next(line for line in (work / "automore.jsonl").read_text().splitlines()
                                  if json.loads(line)["record"] == name))
            ids = row["own"] + row["new"]
            auto = build_compensator(cfg, ds=ds)
            preds = {}
            for fam in families:
                comp = clone(auto).set_params(estimator=clone(auto.estimator.candidates[fam])).fit(train)
                for margin in [None, *_margins(margins)]:
                    hold(comp, margin)
                    _, _, series = split_residuals(comp, full, ids, "simulation")
                    preds[fam, margin] = {t: np.concatenate([y[c] - r[c] for c in ids])
                                          for t, (y, r) in series.items()}
        for t, w, a, y_new, new, _ in stored:
            test = {k[5:]: a[k] for k in a.files if k.startswith("pred_") and k != "pred_auto"}
            cell = {"mlr": _rmse(y_new[new], test["mlr"][new])}
            for margin in [None, *_margins(margins)]:
                mixed = dict(test)
                for fam in families:
                    mixed[fam] = preds[fam, margin][t]
                    if margin is None:
                        same = np.allclose(mixed[fam][new], test[fam][new], atol=1e-6, equal_nan=True)
                        cell.setdefault("reproduced", {})[fam] = bool(same)
                cell[_key(margin)] = _rmse(y_new[new], sum(v * mixed[n][new] for n, v in w.items()))
            cell["stored"] = _rmse(y_new[new], sum(v * test[n][new] for n, v in w.items()))
            rep["targets"][t] = cell
        Path(out, f"{name}.json").write_text(json.dumps(rep, indent=1, default=float))
        if "lagbank" in families:
            np.savez(Path(out, f"{name}.npz"), **{f"{t}.{m:g}": v for (f, m), by in preds.items()
                                                   if f == "lagbank" and m is not None for t, v in by.items()})
        print(name, families, {t: {k: (round(v, 4) if isinstance(v, float) else v) for k, v in c.items()}
                               for t, c in rep["targets"].items()}, flush=True)


def _rmse(y, p) -> float:
    keep = np.isfinite(y) & np.isfinite(p)
    return float(np.sqrt(np.mean((y[keep] - p[keep]) ** 2)))


def seen22_table(out: str, margin: str, *records: str) -> None:
    """bench_auto96's figure (mean over targets of auto's RMSE over the mean of MLR's), main ->
    held at MARGIN, per record, the geometric mean, losers, the worst held / main."""
    from bench_auto96 import _geo

    key, main, held = _key(_margins(margin)[0]), [], []
    for name in records:
        rep = json.loads(Path(out, f"{name}.json").read_text())
        cells = rep["targets"].values()
        mlr = np.mean([c["mlr"] for c in cells])
        m, h = np.mean([c["stored"] for c in cells]) / mlr, np.mean([c.get(key, c["stored"]) for c in cells]) / mlr
        main.append(m)
        held.append(h)
        print(f"{name:11s} main {m:.3f} {key} {h:.3f} held/main {h / m:.3f}  {rep['families']}")
    ratio = np.divide(held, main)
    print(f"{len(main)} records: geo auto/MLR main {_geo(main):.4f} {key} {_geo(held):.4f}; losers "
          f"{sum(v > 1 for v in main)} -> {sum(v > 1 for v in held)}; worst held/main {ratio.max():.3f}; "
          f"> 1 % worse {int(np.sum(ratio > 1.01))}")


HELD = "lagheld"      # the candidate beside lagbank: the same lag bank, its leads held (trace)


def with_held(auto, margin: float):
    """``auto`` (an unfitted model=auto compensator) with a candidate :data:`HELD` beside
    ``lagbank``: its clone holding its leads at ``margin`` -- in every fold too (each fold's own
    fit range), so the votes see how the hold extrapolates."""
    from sklearn.base import clone

    cands = dict(auto.estimator.candidates)
    if "lagbank" in cands:
        cands[HELD] = clone(cands["lagbank"]).set_params(lead_margin=float(margin))
    auto.estimator.set_params(candidates=cands)
    return auto


def beside(root: str, out: str, margin: str, *records: str) -> None:
    """``ways`` with :data:`HELD` beside lagbank (folds held): OUT/RECORD.json ``beside``, the
    weights; main / MLR read from ``ways``'s OUT (run it first)."""
    import bench_auto96
    import bench_auto_rank as rank

    from thermocomp.shell.builders import build_compensator

    _with_root(root, records)
    for name in records:
        cfg, ds, train = bench_auto96._setup(name, root)
        auto = with_held(build_compensator(cfg, ds=ds), float(margin)).fit(train)
        path = Path(out, f"{name}.json")
        rep = json.loads(path.read_text())
        meas, pred = rank._test(auto, ds)
        rep["beside"] = {t: bench_auto96._rmse(meas[t], pred[t]) for t in meas}
        rep["weights_beside"] = {t: e.weights_ for t, e in auto.estimators_.items()}
        path.write_text(json.dumps(rep, indent=1, default=float))
        print(f"{name} auto/MLR main {_figure(rep, 'main'):.3f} beside {_figure(rep, 'beside'):.3f}; "
              f"weights {rep['weights_beside']}", flush=True)


def _with_root(root: str, records) -> None:
    import bench_auto96
    from bench_auto_losses56 import lab_record

    root_path = Path(root).resolve()
    for name, seed in LABS.items():
        if name in records and not (root_path / name).exists():
            lab_record(root_path / name, seed)
    table = {n: [o.format(root=root_path) for o in ov] for n, ov in RECORDS.items()}
    bench_auto96._records = lambda: table


def beside22(root: str, main_work: str, out: str, margin: str, *records: str) -> None:
    """The 22-table with :data:`HELD` beside lagbank: auto refitted (its folds), its blend scored on
    the new campaigns from the stored candidates' predictions and ``seen22``'s held lag bank
    (OUT/RECORD.npz, run ``seen22`` with MARGIN first)."""
    import bench_auto_rank as rank
    from bench_auto91 import stored_targets
    from bench_automore69 import OVERRIDES

    from thermocomp.shell.builders import build_compensator

    work = Path(main_work).resolve()
    for name in records:
        overrides = [o.format(root=Path(root).resolve()) for o in OVERRIDES[name]]
        sys.argv[2:] = overrides
        cfg, ds, train = rank.setup(overrides)
        auto = with_held(build_compensator(cfg, ds=ds), float(margin)).fit(train)
        path = Path(out, f"{name}.json")
        rep = json.loads(path.read_text())
        held = np.load(Path(out, f"{name}.npz")) if Path(out, f"{name}.npz").exists() else None
        for t, _, a, y_new, new, _ in stored_targets(work, name):
            test = {k[5:]: a[k] for k in a.files if k.startswith("pred_") and k != "pred_auto"}
            w = auto.estimators_[t].weights_
            if w.get(HELD, 0) > 0:
                test[HELD] = held[f"{t}.{margin}"]
            rep["targets"][t]["beside"] = _rmse(y_new[new], sum(v * test[n][new] for n, v in w.items()))
            rep["targets"][t]["weights_beside"] = w
        path.write_text(json.dumps(rep, indent=1, default=float))
        print(name, {t: (round(c["stored"], 4), round(c["beside"], 4), c["weights_beside"])
                     for t, c in rep["targets"].items()}, flush=True)


def main(argv: list[str]) -> int:
    commands = {"ways": ways, "ways_table": ways_table, "seen22": seen22, "seen22_table": seen22_table,
                "beside": beside, "beside22": beside22}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
