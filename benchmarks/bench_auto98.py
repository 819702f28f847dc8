"""auto no worse than MLR where the lag families extrapolate: a lead held only beyond every fold's
range (issue 34; stop 98, auto98; the "next" of bench_auto97).

REFUSED on the SEEN gate (1), both forms the brief named: the hold at auto's final refit only
leaves the votes and fl_thermal as they were (90/10 2.481 -> 2.481 µm at margin 0.1) but keeps 8
losers on the 22-table at every margin (col5791 1.258 -> 1.075, col1403 1.311 -> 1.065, col1514
1.019 -> 1.011 at 0.1) and makes 5 of the 10 one-campaign records > 1 % worse (lr9587 1.144, lr9212
1.140 x main); the held lag bank beside lagbank moves votes (lr9587 1.122, lab5401 1.068 x main),
losers 8 -> 8.  Fresh 9795-9804 NOT drawn (they stay fresh).  src as on 16d3b58d; the rule built is
``benchmarks/auto98_rule.patch`` (against 16d3b58d: lagbank.py ``lead_margin`` / ``lead_bounds_`` /
``lead_range`` / ``hold_leads``, auto.py ``lead_margin`` on the final refit,
``tests/core/test_auto_lead_hold98.py`` 5 cases).  Apply it to run the commands below.

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

    python benchmarks/bench_auto98.py ways ROOT OUT MARGINS RECORD ...      # one auto fit, held at MARGINS
    python benchmarks/bench_auto98.py ways_table OUT MARGIN RECORD ...      # auto / MLR main -> held, beside
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

Measured (2026-12-06, 16d3b58d + the patch; nice, ``OMP_NUM_THREADS=1``, 2 cores shared, load
12-24; CPU: ``seen22`` of the 22 at 4 margins 67.6 s (the 3 col records twice), ``ways`` seen 10
36.8 s, fl_thermal 37.1 s, ``beside`` 10 32.3 s, ``beside22`` 22 158.8 s, the variants below 119 s;
wall ~35 min in all).
Every free refit of ``seen22`` reproduced the stored prediction (``reproduced`` True on all
targets); ``ways``'s main reproduced bench_auto97's main (lr9587 1.059, fl_thermal 2.481 µm).

(1) The hold at the final refit (votes main's), auto / MLR, margin 0 / 0.1 / 0.5 / 1:

  22-table geo 0.8264 -> 0.8303 / 0.8176 / 0.8152 / 0.8217; losers 8 -> 8 at every margin (FAILS);
  > 1 % worse 5 / 2 / 0 / 0 (year6_5411 1.299 / 1.132 x main, tsc_a2 1.157 / 1.012, iso_b 1.017 / 1.004)
  col5791 1.258 -> 1.067 / 1.075 / 1.127 / 1.209   col1403 1.311 -> 1.090 / 1.065 / 1.107 / 1.213
  col1514 1.019 -> 1.009 / 1.011 / 1.015 / 1.018   (the other 16 within 1 % at 0.1; the losers
  lab5401, iso_a, mtc_b, col6512, hmc stay losers)
  one-campaign 10 geo 0.7658 -> 0.9640 / 0.7995 / 0.7982; > 1 % worse 6 / 5 / 5 (FAILS); at 0.1:
  lr9587 1.144, lr9212 1.140, lr9643 1.138, lr9211 1.081, lr9642 1.079 x main, lr9641 0.889;
  at margin 1 lr9212 still 1.254 x main (0.760 -> 0.953)
  fl_thermal 90/10 mean RMSE 2.481 -> 2.476 / 2.481 / 2.481 / 2.481 µm (met: auto97's 2.744 was
  its moved votes)

Where the col records still lose, held at 0.1 (weights unchanged): col5791 E_Z_mid auto 15.47 ->
8.47 µm against MLR's 5.26, col1403 E_Y 24.18 -> 18.17 against 13.05: a third to a half of the
excess over MLR is made where every lead is inside its train range, which no hold touches (at margin
0 still 8.22 and 19.84 µm).

Variants traced on the same records (scratch switches in lagbank.py, not kept; margin 0.1):
* the lag bank's whole dynamic part ``sum_k b_k (L_k[x] - x)`` held to its train range (one
  clamp, the leads' cancellation kept): lr9587 untouched (1.059) but lr9643 0.519 -> 0.667 (1.032
  at margin 0), and col barely moves: col5791 E_Z_mid 15.47 -> 12.75, col1403 E_Y 24.18 -> 23.93,
  col1514 E_Z_mid 4.50 -> 4.53 µm.
* only the leads of short taus held (<= 2000 s / <= 6000 s): col5791 1.259 / 1.262, col1403 1.374 /
  1.246; lr9211 0.901 (1.18 x main), lr9212 1.200 (1.58 x) -- worse both ways.
* only the leads of long taus held (> 6000 s): col5791 1.083, col1403 1.102 (most of the gain), and
  lr9587 1.212, lr9212 0.859 (1.13 x), year6_5411 0.560 (1.08 x): the leads that mend the column
  records are the ones the long records need free; no margin nor tau split separates them.

(2) The held lag bank beside lagbank (``beside``, margin 0.1, held in every fold at its own range):
  one-campaign 10 geo 0.7658 -> 0.7744, lr9587 1.059 -> 1.189 (1.122 x: the folds hand lagbank's
  0.105 to lagheld 0.089), lr9211 0.761 -> 0.758, the rest unchanged; 22-table geo 0.8264 ->
  0.8255, losers 8 -> 8, lab5401 1.070 -> 1.143 (1.068 x), iso_a 1.083 -> 1.024, col5791 1.258 ->
  1.227, col1403 1.311 -> 1.310: the folds never see the column records' excursion, so they do not
  pick the held bank there, and pick it where it tests worse.  FAILS (1).

(3) FRESH: not drawn.  Export: not carried (the rule is refused); the patch holds the leads in
``predict`` and the stream, not in the exported C / ST.

Next, if any: the column losers are an unseen source (Q3) the lag families extrapolate wrongly
partly beyond and partly inside the train range, while the long records' leads leave the range
rightly; a train-side signal has not separated them (bench_auto96 / 96b / 97 / 98).  What is left
is outside the lag family: e.g. the deployed watch's range check (a sensor beyond its train
range) handing a target to MLR, judged on the same seen tables.
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


def _column(word: str) -> str:
    """A table's column: ``beside`` (the held candidate beside lagbank) or a margin's."""
    return word if word == "beside" else _key(_margins(word)[0])


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


def _mean(by_target: dict) -> float:
    return float(np.mean(list(by_target.values())))


def ways_table(out: str, margin: str, *records: str) -> None:
    from bench_auto96 import _geo

    key, main, held = _column(margin), [], []
    for name in records:
        rep = json.loads(Path(out, f"{name}.json").read_text())
        m, h = _figure(rep, "main"), _figure(rep, key)
        main.append(m)
        held.append(h)
        print(f"{name:11s} main {m:.3f} {key} {h:.3f} held/main {h / m:.3f}   "
              f"mean RMSE {_mean(rep['main']):.4g} -> {_mean(rep[key]):.4g}")
    ratio = np.divide(held, main)
    print(f"{len(main)} records: geo auto/MLR main {_geo(main):.4f} {key} {_geo(held):.4f}; losers "
          f"{sum(v > 1 for v in main)} -> {sum(v > 1 for v in held)}; worst held/main {ratio.max():.3f}; "
          f"> 1 % worse {int(np.sum(ratio > 1.01))}")


def with_new_campaigns(root: str, work: Path, name: str):
    """``(cfg, dataset, train, dataset with the new campaigns, scored ids)`` of a 22-table record
    (bench_automore69's, main's stored rows in WORK: its own test campaigns, then the new ones)."""
    import bench_auto_rank as rank
    from bench_automore69 import OF, OVERRIDES, draws
    from bench_moretest68 import with_new

    overrides = [o.format(root=Path(root).resolve()) for o in OVERRIDES[name]]
    sys.argv[2:] = overrides
    cfg, ds, train = rank.setup(overrides)
    full = with_new(ds, draws(OF[name], work, cfg))
    row = json.loads(next(line for line in (work / "automore.jsonl").read_text().splitlines()
                          if json.loads(line)["record"] == name))
    return cfg, ds, train, full, row["own"] + row["new"]


def seen22(root: str, main_work: str, out: str, margins: str, *records: str) -> None:
    from bench_auto91 import stored_targets
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
            cfg, ds, train, full, ids = with_new_campaigns(root, work, name)
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
            held = {f"{t}.{m:g}": v for (f, m), by in preds.items() if f == "lagbank" and m is not None
                    for t, v in by.items()}
            np.savez(Path(out, f"{name}.npz"), **held)
        print(name, families, {t: {k: (round(v, 4) if isinstance(v, float) else v) for k, v in c.items()}
                               for t, c in rep["targets"].items()}, flush=True)


def _rmse(y, p) -> float:
    keep = np.isfinite(y) & np.isfinite(p)
    return float(np.sqrt(np.mean((y[keep] - p[keep]) ** 2)))


def seen22_table(out: str, margin: str, *records: str) -> None:
    """bench_auto96's figure (mean over targets of auto's RMSE over the mean of MLR's), main ->
    held at MARGIN, per record, the geometric mean, losers, the worst held / main."""
    from bench_auto96 import _geo

    key, main, held = _column(margin), [], []
    for name in records:
        rep = json.loads(Path(out, f"{name}.json").read_text())
        cells = rep["targets"].values()
        mlr = np.mean([c["mlr"] for c in cells])
        m = np.mean([c["stored"] for c in cells]) / mlr
        h = np.mean([c.get(key, c["stored"]) for c in cells]) / mlr
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
    """bench_auto96's record table: :data:`RECORDS` with ROOT in place (bench_auto96b's)."""
    from bench_auto96b import _with_records

    _with_records(root, RECORDS, LABS, records)


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
