"""``model=auto`` on ONE-campaign training: why its forward-chaining folds misrank the families
(issue 34; stop 94, auto94b).  TRACE only: no src, no fresh seed.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_auto94b.py trace OUT VARIANT RECORD ...  # fit auto + each family, save folds
    python benchmarks/bench_auto94b.py table OUT RECORD ...   # per family: folds, test, rankings
    python benchmarks/bench_auto94b.py probe OUT RECORD ...   # lag families: fold CV vs whole-train params

``trace``: the record (:data:`RECORDS`) simulated from its seed, ``model=auto`` fitted on its one
train campaign as ``run`` fits it (bench_auto_rank's ``setup`` / ``LIGHT``: ``keep_oof``), each
candidate family then fitted alone on the whole train campaign and the test campaign predicted in
simulation from the state the train left (bench_auto_rank's ``_test``, as ``run`` scores it).
Written to OUT/RECORD.json: per target every family's out-of-fold free-run predictions' squared
error per forward fold, its test RMSE, auto's kept weights and test RMSE; per fold its train span
(h, the rows the fold's model was fitted on), its scored span (h), where it sits in the campaign
(the slope of the mean machine temperature over the fold, degC/h, and the mean of the S_* state
columns); per family its memory as fitted on the whole train: lagbank / hammerstein the longest
lag time constant ``taus_[-1]`` (h), arx the time constant of its AR pole, -dt / ln(a) (h; 0 without
an AR term), mlr / pcr 0, lstm its window (not read: reported as n/a).

``table``: per record and target, the families' pooled validation over all folds (main), over
the folds after the first ("drop1"), over the last two folds ("last2"), and the test RMSE; the
Spearman of each validation ranking against the test ranking, and the test RMSE of the family
each ranks first, over MLR's.  Nothing here chooses a setting: the three fold subsets are fixed
before any number was read, and the test part is read only to score the rankings.

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
            span_s = json.loads(Path(out, "main", f"{name}.json").read_text())["targets"][t]["folds"][0]["train_h"] * 3600
            capped = {n: (clone(c).set_params(**{"lagbank__tau_max_s" if n == "hammerstein" else "tau_max_s":
                                                 span_s}) if n in lagged else clone(c)) for n, c in cands.items()}
            row = {"capped_test": {}, "capped_tau_max_h": span_s / 3600}
            for n in lagged:
                if n in capped:
                    pred = rank._test(clone(auto).set_params(estimator=capped[n]).fit(train), ds)
                    row["capped_test"][n] = float(np.sqrt(np.nanmean((pred[0][t] - pred[1][t]) ** 2)))
            for label, members in (("own_cv", cands), ("whole_train_params", fixed), ("tau_capped", capped)):
                est = clone(auto.estimator).set_params(candidates={n: clone(c) for n, c in members.items()},
                                                       keep_oof=True)
                fitted = clone(auto).set_params(estimator=est).fit(train).estimators_[t]
                row[label] = {n: [float(np.sqrt(np.mean((fitted.oof_y_ - fitted.oof_[n])[fitted.oof_fold_ == k] ** 2)))
                                  for k in np.unique(fitted.oof_fold_)] for n in fitted.oof_}
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


DESIGNS = [("main", s) for s in SUBSETS] + [(v, "all") for v in VARIANTS if v != "main"]


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
    return {"first": float(np.mean(first)) / m, "rho": float(np.nanmean(rho)), "auto": float(np.mean(auto)) / m}


def table(out: str, *records: str) -> None:
    scores = {}
    for name in records:
        reps = {v: json.loads(p.read_text()) for v in VARIANTS if (p := Path(out, v, f"{name}.json")).exists()}
        _detail(name, reps["main"])
        scores[name] = {(v, s): _score(reps[v], s) for v, s in DESIGNS if v in reps}
    designs = [d for d in DESIGNS if any(d in sc for sc in scores.values())]
    head = " ".join(f"{v + ':' + s if v == 'main' else v:>11s}" for v, s in designs)
    for key, what in (("first", "first-ranked family's test RMSE / MLR's"),
                      ("rho", "Spearman, validation ranking vs test ranking (mean over targets)"),
                      ("auto", "auto refitted with the design, test RMSE / MLR's (main's subsets: main's auto)")):
        print(f"\n{what}\nrecord   {head}")
        for name, sc in scores.items():
            print(f"{name:8s} " + " ".join(f"{sc[d][key]:11.3f}" if d in sc else f"{'-':>11s}" for d in designs))
        print(f"{'mean':8s} " + " ".join(f"{np.mean([sc[d][key] for sc in scores.values() if d in sc]):11.3f}"
                                          for d in designs))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "table": table, "probe": probe}, argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
