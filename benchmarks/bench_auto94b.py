"""``model=auto`` on ONE-campaign training: why its forward-chaining folds misrank the families
(issue 34; stop 94, auto94b).  TRACED: no src, no fresh seed.  The brief's hypothesis (the first
fold's short train below a lag family's memory) fits 2 of the 6 records and NOT the two
losers it was drawn from (sw9697, lr9587); no fold design measured here passes the bar below.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_auto94b.py trace OUT VARIANT RECORD ...  # fit auto + each family, save folds
    python benchmarks/bench_auto94b.py probe OUT RECORD ...   # lag families: fold CV vs whole-train params
    python benchmarks/bench_auto94b.py table OUT RECORD ...   # per family: folds, test, rankings

``trace``: the record (:data:`RECORDS`) simulated from its seed, ``model=auto`` fitted on its one
train campaign as ``run`` fits it (bench_auto_rank's ``setup`` / ``LIGHT``: ``keep_oof``) with the
fold design VARIANT (:data:`VARIANTS`: ``main``; ``mtf07`` min_train_fraction 0.7, a minimum-train
rule; ``gap2`` gap_blocks 2; ``blocks`` one_record=blocks, leave-block-out), each candidate family
then fitted alone on the whole train campaign and the test campaign predicted in simulation from
the state the train left (bench_auto_rank's ``_test``, as ``run`` scores it).  OUT/VARIANT/RECORD.json:
per target every family's squared error per fold, its test RMSE, auto's weights and test RMSE; per
fold its train span (0 to the last fitted row, h; under ``blocks`` the fit is both sides of the
block), its scored span, where it sits (slope of the mean machine temperature over the fold, degC/h:
heating > 0.1, cooling < -0.1, else steady; mean of the S_* states, 0 = spindle idle); per family
its memory as fitted on the whole train: lagbank / hammerstein ``taus_[-1]`` (conf tau_max_s, 48 h,
fixed), arx the AR pole's time constant (no AR term chosen on any record here: 0), mlr / pcr 0, lstm
n/a.  ``probe`` (needs ``trace OUT main``): the test part's phase; mlr / lagbank / hammerstein fold
errors with each fold's own CV (main), with the hyper-parameters their CV chose on the WHOLE train
(``chosen_params``: the fold's own choice removed), and with tau_max_s capped at the first fold's
train span (and that capped family's test RMSE).  ``table``: per record the detail, then per fold
design the test RMSE / MLR's of the family its pooled validation ranks first, the Spearman of its
ranking against the test's, and auto refitted with it.  Subsets of main's folds: ``all``;
``drop1`` (folds 2-5); ``last2``; ``reach`` (per family the folds whose train span reaches its
memory, none: its last fold); ``fixed``: main's folds, the lag families at whole-train params.

Records (named before running; seeds all seen): sw9697 (bench_audit94: swiss_lathe_door cut to 8 h
train + 4 h test), lr9587 (bench_audit93: long_record, 3 days, R1b the last 20 % continuing R1a),
and four seen one-campaign records chosen before running: sw9696 (bench_audit94: swiss_lathe_door
80 h + 24 h), lr9211 and lr9212 (bench_deploy88, 3 days), lr9640 (bench_auto94's fresh, now seen:
its E_Z's first nested fold failed).

BAR for the next stop's rule (written here before any trace was read; the rule is NOT built here):
a fold design that drops the forward folds whose train span is below the candidates' memory (or
a minimum-train rule) is worth building only if, on these 6 records, (a) the family it ranks first
per target has a mean test RMSE / MLR below main's on at least 4 of 6 records and worse on none by
> 1 %, and (b) its mean Spearman against the test ranking is above main's.  Then it is scored
through auto (the votes, not the first-ranked family) on fresh seeds of the same generators.
The bar is unchanged; ``reach``, the three refitted VARIANTS, ``fixed`` and the ``probe`` were
ADDED after the first table (all / drop1 / last2 on the 6 records) was read.

Measured (2026-12-05, this tree = main 3f12b172 + the bench; ``trace`` x 4 variants 8 + 22 + 26 +
22 + 28 s CPU, ``probe`` 5 + 20 s, nice, ``OMP_NUM_THREADS=1``; auto / MLR as the table's mean over
targets: sw9697 1.044 = bench_audit94's 1.5646 / 1.4990; lr9587 1.059 = bench_auto94's (audit93's
1.5412 / 1.4652 = 1.052: auto's lstm member, run to run)).  Folds of main (train span -> scored
span, phase) and the lag families' fold RMSE over MLR's, test RMSE over MLR's::

  record  folds' train h       lagbank / MLR per fold     hammerstein / MLR       test lb  hm
  sw9697  3.6 4.4 5.2 6.0 6.8  E_X 1.96 0.48 2.13 2.55 1.44  1.14 0.34 0.57 1.76 0.27  0.35 0.59
                               E_Y 1.03 0.49 3.46 2.38 1.80  0.48 0.41 0.49 1.16 1.44  0.36 1.01
  lr9587  26 32 38 43 49       E_Z 0.89 0.32 0.61 0.75 2.53  0.94 0.37 0.61 0.75 2.53  1.55 1.61
  sw9696  36 44 52 60 68       E_X 1.14 1.83 0.63 0.81 1.01  0.78 0.69 0.45 0.58 0.76  0.76 0.56
                               E_Y 1.10 1.51 0.62 0.75 0.94  1.10 0.70 0.44 0.61 0.70  0.66 0.58
  lr9211  26 32 38 43 49       E_Z 1.09 1.86 0.26 0.58 0.55  0.52 1.50 0.30 0.81 0.43  1.11 1.21
  lr9212  26 32 38 43 49       E_Z 1.61 0.83 0.63 1.72 1.13  1.09 0.81 0.84 1.06 0.84  0.78 0.74
  lr9640  26 32 38 43 49       E_Z 2.88 0.37 0.29 0.67 0.96  2.62 0.23 0.30 0.62 0.96  0.71 1.20

  phases: sw9697 heating / cooling / cooling / heating / heating (+2.50 degC/h, spindle 4167, the
  hardest fold for every family: MLR 6.03 on E_X), test heating +0.74; lr folds 3-5 spindle idle,
  lr tests idle cooling or steady (lr9587 -0.23 degC/h); sw9696 test steady, spindle 2389.

(1) Do the folds' train lengths fall below the family's memory?  Yes, always for the lag families:
lagbank / hammerstein keep tau_max 48 h whatever the train (conf); every sw9697 fold (3.6-6.8 h)
and its WHOLE train (8 h) are below it, lr folds 1-4 (26-43 h), sw9696 folds 1-2 (36-44 h).
ARX chose no AR term here (static, memory 0).  Is that the misranking?  On 3 records it looks so:
sw9696 and lr9640 -- lagbank loses the folds below 48 h (1.14 1.83; 2.88) and wins the later ones,
and the test (0.76, 0.71); lr9211 shows the same fold pattern (1.09 1.86, then 0.26 0.58 0.55) but
lagbank loses its test (1.11).  On the brief's two losers it is NOT:
* sw9697: lagbank loses 4 of 5 folds, the last (longest train) too (1.44 / 1.80); its test win
  (0.553 against MLR 1.573 on E_X) NEEDS the lags longer than any fold's train and than the train
  itself: capped at the first fold's span (3.6 h) its test goes 0.553 -> 2.300 (E_X), 0.520 ->
  1.458 (E_Y).  Its folds at whole-train hyper-parameters (alpha 316) still lose to MLR on 4 of 5
  (E_X 4.28 2.30 1.29 2.65 6.11 against 1.92 2.22 1.22 0.95 6.03).  The 4 h test (production,
  after 8 h of calibration) holds what no fold of the calibration holds.
* lr9587: the short folds say lagbank WINS (1-4: 0.89 0.32 0.61 0.75); the one fold whose train
  reaches 48 h (fold 5, 49 h) says it loses (2.53), as the test (1.55).  With whole-train params
  fold 5 flips to a win (0.519 against 0.604); capped at 26 h its test is unchanged (2.262).
(2) Would folds reaching each family's memory, a minimum-train rule or a gap rank as the test does?

  first-ranked family's test RMSE / MLR's (mean over targets)
  record  main:all drop1  last2  reach  mtf07  gap2   blocks fixed
  sw9697  1.074    1.074  1.495  1.074  0.784  1.344  1.000  0.791
  lr9587  1.545    1.545  1.000  1.000  1.000  1.000  1.000  1.615
  sw9696  0.566    0.566  0.566  0.566  0.566  1.000  1.000  0.566
  lr9211  1.211    1.211  1.109  1.211  1.109  1.000  1.109  1.211
  lr9212  0.736    0.736  1.892  0.736  0.736  1.000  1.000  0.736
  lr9640  1.198    1.198  1.198  0.713  1.198  1.000  1.000  1.198
  Spearman (validation vs test ranking), mean over the 6:
          0.076    0.162  0.115  0.250  0.257  -0.024 -0.048 0.071
  auto refitted with the design, test RMSE / MLR's (main's subsets and fixed leave auto as main's):
  record  main   mtf07  gap2   blocks
  sw9697  1.044  1.092  1.164  1.000
  lr9587  1.059  1.000  1.000  1.044
  sw9696  0.566  0.566  0.959  1.000
  lr9211  0.761  1.190  1.000  0.733
  lr9212  0.760  0.857  1.000  1.147
  lr9640  0.858  1.184  0.936  1.000

Against the bar (unchanged): (a) fails for every design -- better than main on 0 (drop1), 2 (last2,
with 2 worse), 2 (reach: lr9587 1.545 -> 1.000, lr9640 1.198 -> 0.713; 0 worse), 3 (mtf07: sw9697,
lr9587, lr9211; 0 worse), 3 (gap2, 3 worse), 2 (blocks, 3 worse), 1 (fixed, lr9587 worse) of 6;
(b) met by drop1, last2, reach, mtf07.  The nearest, ``reach`` and ``mtf07``, rank better, but
auto refitted with mtf07 is worse than main's on 4 of 6 (lr9211 0.761 -> 1.190, lr9640 0.858 ->
1.184: fewer rows per fold, the votes' resamples thinner).  TRACED, no src.

Next rule to try (its bar, for the next stop): ``reach`` inside auto's votes, one record only
(FORWARD_ONE; campaign folds untouched by construction): a candidate with a memory M (lagbank /
hammerstein ``tau_max_s``) votes only on the forward folds whose fit rows span >= M (none: its last
fold), the static families on all.  SEEN gate: these 6 plus bench_auto94's one-record rows
(lr9639-9643) through the built code: no record worse than auto by > 1 %, geo rule / auto <= 1.0,
lr9587 brought within 2 % of MLR; then FRESH long_record (3 days) and swiss_lathe_door 8 h + 4 h
seeds scored once: (a) no record worse than auto by > 1 %, (b) geo <= 1.0, (c) at least one
improved.  sw9697 it cannot reach (no fold holds production): left with the one-campaign swiss
cut's production test as its own question (a fold in the test's regime does not exist in training).
"""
from __future__ import annotations

import json
import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
os.environ.setdefault("OMP_NUM_THREADS", "1")
from _cli import run_commands  # noqa: E402
from bench_deploy88 import LONG  # noqa: E402

RECORDS = {
    "sw9697": ["sim=swiss_lathe_door", "seed=9697", "sim.generator.calibration_hours=8",
               "sim.generator.production_hours=4"],
    "lr9587": [*LONG, "seed=9587", "sim.generator.duration_days=3.0"],
    "sw9696": ["sim=swiss_lathe_door", "seed=9696"],
    "lr9211": [*LONG, "seed=9211", "sim.generator.duration_days=3.0"],
    "lr9212": [*LONG, "seed=9212", "sim.generator.duration_days=3.0"],
    "lr9640": [*LONG, "seed=9640", "sim.generator.duration_days=3.0"],
}
SUBSETS = ("all", "drop1", "last2", "reach")
# other fold designs auto already has (``model.estimator`` keys), refitted: a minimum-train rule
# (folds over the last 30 %), a wider gap before each fold, leave-block-out (one_record=blocks)
VARIANTS = {"main": [], "mtf07": ["model.estimator.min_train_fraction=0.7"],
            "gap2": ["model.estimator.gap_blocks=2.0"], "blocks": ["model.estimator.one_record=blocks"]}


def _memory_h(est) -> float | None:
    """The family's memory as fitted (hours): the longest lag, the AR pole's time constant."""
    inner = getattr(est, "lagbank_", None) or est
    if hasattr(inner, "taus_"):
        return float(inner.taus_[-1]) / 3600
    if hasattr(est, "ar_coef_"):
        a = float(np.ravel(est.ar_coef_)[0]) if np.size(est.ar_coef_) else 0.0
        period = getattr(est, "sample_period_s_", None) or 60.0
        return float(-period / np.log(a) / 3600) if 0 < a < 1 else 0.0
    if hasattr(est, "coef_"):
        return 0.0
    return None


def _where(frame, rows: np.ndarray, period_h: float) -> dict:
    """Where ``rows`` sit in the campaign: mean machine-temperature slope (degC/h), mean state."""
    temps = [c for c in frame.columns if str(c).startswith("T_") and "amb" not in str(c)]
    states = [c for c in frame.columns if str(c).startswith("S_")]
    level = frame[temps].to_numpy(float).mean(axis=1)[rows]
    slope = float(np.polyfit(np.arange(rows.size) * period_h, level, 1)[0]) if rows.size > 2 else 0.0
    state = float(np.nanmean(frame[states].to_numpy(float)[rows])) if states else float("nan")
    return {"slope_c_per_h": slope, "state": state,
            "phase": "heating" if slope > 0.1 else "cooling" if slope < -0.1 else "steady"}


def trace(out: str, variant: str, *records: str) -> None:
    import bench_auto_rank as rank
    from sklearn.base import clone

    from thermocomp.shell.builders import build_compensator

    out = Path(out, variant)
    out.mkdir(parents=True, exist_ok=True)
    for name in records:
        sys.argv[2:] = list(RECORDS[name])      # rank._dataset reads sim= from argv
        cfg, ds, train = rank.setup([*RECORDS[name], *VARIANTS[variant]])
        (cid, frame), = train.items()
        period_h = float(np.median(np.diff(frame["time"].to_numpy(float)))) / 3600 \
            if "time" in frame else 1 / 60
        auto = build_compensator(cfg, ds=ds).fit(train)
        meas, kept = rank._test(auto, ds)
        names = list(dict.fromkeys(n for e in auto.estimators_.values() for n in e.oof_))
        singles, memory = {}, {}
        for n in names:
            cand = auto.estimator.candidates.get(n) or rank._mlr()
            comp = clone(auto).set_params(estimator=clone(cand)).fit(train)
            singles[n] = rank._test(comp, ds)[1]
            memory[n] = {t: _memory_h(e) for t, e in comp.estimators_.items()}
        report = {"record": name, "overrides": RECORDS[name], "train_h": len(frame) * period_h,
                  "period_h": period_h, "targets": {}}
        for t, est in auto.estimators_.items():
            n_rows, folds = est.oof_folds_
            fold_info = [{"train_h": (fit[-1] + 1) * period_h, "from_h": score[0] * period_h,
                          "to_h": (score[-1] + 1) * period_h, **_where(frame, score, period_h)}
                         for fit, score in folds]
            sq = {n: [float(np.sum((est.oof_y_ - est.oof_[n])[est.oof_fold_ == k] ** 2))
                      for k in range(len(folds))] for n in est.oof_}
            rows = [int(np.sum(est.oof_fold_ == k)) for k in range(len(folds))]
            test = {n: float(np.sqrt(np.nanmean((meas[t] - singles[n][t]) ** 2))) for n in singles}
            report["targets"][t] = {
                "folds": fold_info, "fold_rows": rows, "fold_sse": sq, "test": test,
                "auto_test": float(np.sqrt(np.nanmean((meas[t] - kept[t]) ** 2))),
                "weights": est.weights_, "validation": est.validation_,
                "memory_h": {n: memory[n][t] for n in memory}}
        Path(out, f"{name}.json").write_text(json.dumps(report, indent=1, default=float))
        print(f"{variant} {name}: train {report['train_h']:.1f} h, written", flush=True)


_TAU_MAX = {"lagbank": "tau_max_s", "hammerstein": "lagbank__tau_max_s"}


def _fold_rmse(fitted, name: str) -> list[float]:
    """``name``'s free-run RMSE on each validation fold of a fitted AutoRegressor."""
    err = fitted.oof_y_ - fitted.oof_[name]
    return [float(np.sqrt(np.mean(err[fitted.oof_fold_ == k] ** 2))) for k in np.unique(fitted.oof_fold_)]


def probe(out: str, *records: str) -> None:
    """Per record: the test part's phase, and the lag families' fold errors with their own CV
    in each fold (main) against the hyper-parameters their CV chose on the WHOLE train
    (``chosen_params``, per target): is it the fold's short train choosing badly?"""
    import bench_auto_rank as rank
    from sklearn.base import clone

    from thermocomp.shell.builders import build_compensator

    lagged = ("lagbank", "hammerstein")
    for name in records:
        sys.argv[2:] = list(RECORDS[name])
        cfg, ds, train = rank.setup(list(RECORDS[name]))
        (cid, frame), = train.items()
        tid = list(ds.ids("test"))[0]
        test = ds.campaigns[tid]
        period_h = json.loads(Path(out, "main", f"{name}.json").read_text())["period_h"]
        where = _where(test, np.arange(len(test)), period_h)
        auto = build_compensator(cfg, ds=ds)
        cands = {n: c for n, c in auto.estimator.candidates.items() if n in (*lagged, "mlr")}
        full = {n: clone(auto).set_params(estimator=clone(c)).fit(train) for n, c in cands.items()}
        res = {"test_phase": where, "targets": {}}
        for t in full["mlr"].estimators_:
            fixed = {n: (clone(c).set_params(**full[n].estimators_[t].chosen_params())
                         if callable(getattr(full[n].estimators_[t], "chosen_params", None)) else clone(c))
                     for n, c in cands.items()}
            traced = json.loads(Path(out, "main", f"{name}.json").read_text())["targets"][t]
            span_s = traced["folds"][0]["train_h"] * 3600
            capped = {n: clone(c).set_params(**{_TAU_MAX[n]: span_s}) if n in lagged else clone(c)
                      for n, c in cands.items()}
            row = {"capped_test": {}, "capped_tau_max_h": span_s / 3600}
            for n in lagged:
                if n in capped:
                    pred = rank._test(clone(auto).set_params(estimator=capped[n]).fit(train), ds)
                    row["capped_test"][n] = float(np.sqrt(np.nanmean((pred[0][t] - pred[1][t]) ** 2)))
            for label, members in (("own_cv", cands), ("whole_train_params", fixed), ("tau_capped", capped)):
                est = clone(auto.estimator).set_params(candidates={n: clone(c) for n, c in members.items()},
                                                       keep_oof=True)
                fitted = clone(auto).set_params(estimator=est).fit(train).estimators_[t]
                row[label] = {n: _fold_rmse(fitted, n) for n in fitted.oof_}
                row[label + "_params"] = {n: getattr(full[n].estimators_[t], "chosen_params", dict)()
                                          for n in lagged if n in full}
            res["targets"][t] = row
            print(f"{name} {t}: test phase {where['phase']} {where['slope_c_per_h']:+.2f} degC/h, "
                  f"state {where['state']:.2f}")
            print(f"   capped at the first fold's train span {span_s / 3600:.1f} h: test "
                  + " ".join(f"{n} {v:.3f}" for n, v in row["capped_test"].items()))
            for label in ("own_cv", "whole_train_params", "tau_capped"):
                for n, v in row[label].items():
                    print(f"   {label:19s} {n:12s} " + " ".join(f"{x:7.3f}" for x in v))
            print(f"   whole-train params: {row['whole_train_params_params']}")
        Path(out, f"{name}.probe.json").write_text(json.dumps(res, indent=1, default=str))


def _ranks(v: dict) -> dict:
    order = sorted(v, key=v.get)
    return {n: i for i, n in enumerate(order)}


def _spearman(a: dict, b: dict) -> float:
    from scipy.stats import spearmanr

    keys = [k for k in a if k in b and np.isfinite(a[k]) and np.isfinite(b[k])]
    return float(spearmanr([a[k] for k in keys], [b[k] for k in keys])[0]) if len(keys) > 2 else float("nan")


def _validation(row: dict, subset: str) -> dict:
    """Pooled validation RMSE per family over a subset of the folds; ``reach``: per family the
    folds whose train span reaches its memory (none: its last fold, the longest train held)."""
    k = len(row["fold_rows"])
    out = {}
    for f, s in row["fold_sse"].items():
        if subset == "reach":
            mem = row["memory_h"].get(f) or 0.0
            keep = [i for i in range(k) if row["folds"][i]["train_h"] >= mem] or [k - 1]
        else:
            keep = {"all": range(k), "drop1": range(1, k), "last2": range(max(0, k - 2), k)}[subset]
        out[f] = float(np.sqrt(sum(s[i] for i in keep) / sum(row["fold_rows"][i] for i in keep)))
    return out


DESIGNS = [("main", s) for s in SUBSETS] + [(v, "all") for v in VARIANTS if v != "main"] + [("fixed", "all")]


def _detail(name: str, rep: dict) -> None:
    """Per target: the folds' spans and phases, each family's fold / subset / test RMSE."""
    print(f"== {name}: one train campaign of {rep['train_h']:.1f} h")
    for t, row in rep["targets"].items():
        fams = [f for f in row["fold_sse"] if f in row["test"]]
        print(f"  {t}: folds (train h | scored h | phase, slope degC/h, mean state):")
        for k, f in enumerate(row["folds"]):
            print(f"    {k + 1}: train 0-{f['train_h']:.1f} | {f['from_h']:.1f}-{f['to_h']:.1f} | "
                  f"{f['phase']} {f['slope_c_per_h']:+.2f} {f['state']:.2f}")
        print("    family       memory_h " + " ".join(f"fold{k + 1:<4d}" for k in range(len(row["folds"])))
              + " " + " ".join(f"{s:6s}" for s in SUBSETS) + " test")
        for f in fams:
            per = [np.sqrt(s / m) for s, m in zip(row["fold_sse"][f], row["fold_rows"])]
            mem = row["memory_h"].get(f)
            print(f"    {f:12s} {'n/a' if mem is None else f'{mem:8.2f}':>8s} "
                  + " ".join(f"{v:8.3f}" for v in per) + " "
                  + " ".join(f"{_validation(row, s)[f]:6.3f}" for s in SUBSETS) + f" {row['test'][f]:6.3f}")
        print("    first-ranked: " + ", ".join(
            f"{s} {min(fams, key=lambda f, s=s: _validation(row, s)[f])}" for s in SUBSETS)
            + f"; test best {min(fams, key=row['test'].get)}; auto {row['auto_test']:.3f} ("
            + ", ".join(f"{f} {w:.2f}" for f, w in row["weights"].items()) + ")")


def _score(rep: dict, subset: str) -> dict:
    """Over the record's targets: the first-ranked family's test RMSE / MLR's (mean over targets,
    ratio of means), auto's, and the mean Spearman of the validation ranking against the test's."""
    first, rho, auto, mlr = [], [], [], []
    for row in rep["targets"].values():
        fams = [f for f in row["fold_sse"] if f in row["test"]]
        val = {f: _validation(row, subset)[f] for f in fams}
        test = {f: row["test"][f] for f in fams}
        first.append(test[min(val, key=val.get)])
        rho.append(_spearman(val, test))
        auto.append(row["auto_test"])
        mlr.append(row["test"]["mlr"])
    m = float(np.mean(mlr))
    return {"first": float(np.mean(first)) / m, "rho": float(np.nanmean(rho)),
            "auto": float(np.mean(auto)) / m}


def _fixed(rep: dict, probe: dict) -> dict:
    """``rep`` with the lag families' fold errors as fitted with the hyper-parameters their own CV
    chose on the WHOLE train (``probe``'s ``whole_train_params``): their folds' own choice removed."""
    rep = json.loads(json.dumps(rep))
    for t, row in rep["targets"].items():
        for f, per in probe["targets"][t]["whole_train_params"].items():
            row["fold_sse"][f] = [r * r * m for r, m in zip(per, row["fold_rows"])]
    return rep


def table(out: str, *records: str) -> None:
    scores = {}
    for name in records:
        paths = {v: Path(out, v, f"{name}.json") for v in VARIANTS}
        reps = {v: json.loads(p.read_text()) for v, p in paths.items() if p.exists()}
        _detail(name, reps["main"])
        scores[name] = {(v, s): _score(reps[v], s) for v, s in DESIGNS if v in reps}
        if (p := Path(out, f"{name}.probe.json")).exists():
            scores[name][("fixed", "all")] = _score(_fixed(reps["main"], json.loads(p.read_text())), "all")
    designs = [d for d in DESIGNS if any(d in sc for sc in scores.values())]
    head = " ".join(f"{v + ':' + s if v == 'main' else v:>11s}" for v, s in designs)
    for key, what in (("first", "first-ranked family's test RMSE / MLR's"),
                      ("rho", "Spearman, validation ranking vs test ranking (mean over targets)"),
                      ("auto", "auto refitted with the design, test RMSE / MLR's (subsets: main's)")):
        print(f"\n{what}\nrecord   {head}")
        for name, sc in scores.items():
            cells = (f"{sc[d][key]:11.3f}" if d in sc else f"{'-':>11s}" for d in designs)
            print(f"{name:8s} " + " ".join(cells))
        print(f"{'mean':8s} " + " ".join(f"{np.mean([sc[d][key] for sc in scores.values() if d in sc]):11.3f}"
                                          for d in designs))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "table": table, "probe": probe}, argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
