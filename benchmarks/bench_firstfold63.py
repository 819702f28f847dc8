"""A late first probe: the inner validation folds scored in the run's frame (firstfold63).

    PYTHONPATH=src .venv/bin/python benchmarks/bench_firstfold63.py folds DIR [cases] [candidates]
    PYTHONPATH=src .venv/bin/python benchmarks/bench_firstfold63.py compare BEFORE.json AFTER.json
    PYTHONPATH=src .venv/bin/python benchmarks/bench_firstfold63.py onestep DIR RUN/model.pkl
    PYTHONPATH=src .venv/bin/python benchmarks/bench_firstfold63.py hobber ROOT OUT families

``folds``: on ``bench_firstprobe62``'s copies in ``DIR`` (``swiss_lathe_door`` seed 61, the error
kept on 1 row in 30 from row 15 / 29: ``e30f15``, ``e30f29``; made there when missing), per
target, the first fit's label as ``model=auto`` gets it (the first-sample frame: ``E(t) - E(m)``),
each candidate's folds scored as ``model=auto`` scores them (``raw``: ``y_hat(t)`` against the
label) and as the run scores (``frame``: ``y_hat(t) - y_hat(m)``, :func:`in_frame`), the folds'
``y_hat(m)``, the blend votes both ways, and the lag bank's own CV choice (with the refused
rule's code of e1e98a9 on PYTHONPATH: also with the frame in its context).  The candidates are
fitted per fold as auto fits them, so only the scoring differs.
``compare``: two ``bench_firstprobe62`` result files (the code before and after, by PYTHONPATH)
side by side: run's test RMSE and the true error.  ``onestep``: :func:`one_step`.  ``hobber``:
:func:`hobber`, a record of many runs (auto's folds hold whole runs out).
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np
from sklearn.base import clone

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_auto_rank import setup  # noqa: E402
from bench_firstprobe62 import copies  # noqa: E402

from thermocomp.core.compensator import _simulation  # noqa: E402
from thermocomp.core.context import for_target, groups_of, subset, with_column  # noqa: E402
from thermocomp.core.frame import resolve_columns, stack  # noqa: E402
from thermocomp.core.metrics import rmse  # noqa: E402
from thermocomp.core.models.auto import (  # noqa: E402
    BASELINE,
    BLOCKS_ONE,
    FORWARD_ONE,
    _not_applicable,
    _same_as,
    _scheme,
)
from thermocomp.core.models.blend import vote_weights  # noqa: E402
from thermocomp.core.models.linear import MLR  # noqa: E402
from thermocomp.shell.builders import build_compensator  # noqa: E402

CASES = ("e30f15", "e30f29")


def matrices(path: Path):
    """``(auto compensator, stacked train matrices, context)`` of the record at ``path``."""
    cfg, ds, train = setup([f"data.path={path}"])
    comp = build_compensator(cfg, ds=ds)
    assert comp.denoiser is None and comp.selection is None
    columns = list(dict.fromkeys(c for df in train.values() for c in df.columns))
    inputs, targets = resolve_columns(columns, comp.inputs, comp.targets)
    m = stack(train, inputs, targets, comp.reference)
    return comp, m, _simulation(m.context)


def first_measured_rows(y, groups) -> np.ndarray:
    """Per row, the row of its campaign's late first measurement, -1 where none (the refused
    rule's helper, e1e98a9, here for the diagnosis)."""
    from thermocomp.core.first_probe import late_starts

    rows = np.full(len(y), -1)
    edges = np.flatnonzero(np.r_[True, groups[1:] != groups[:-1], True])
    stops = dict(zip(edges[:-1], edges[1:]))
    for _, start, m in late_starts(y, groups):
        rows[start:stops[start]] = m
    return rows


def in_frame(values, rows) -> np.ndarray:
    """``values`` less their value at ``rows`` where it is >= 0: label and prediction referenced
    at the first measurement, their difference the residual run scores (on the label as
    measured, whose value there is 0)."""
    out = np.array(values, float, copy=True)
    late = rows >= 0
    out[late] -= np.asarray(values, float)[rows[late]]
    return out


def candidate_folds(auto, X, y, context, names) -> dict:
    """Per candidate: raw and in-frame RMSE pooled and per fold, the folds' y_hat(m), the
    out-of-fold predictions both ways (for the votes)."""
    groups = groups_of(context)
    scheme = _scheme(auto.scheme, groups)
    auto.scheme_ = BLOCKS_ONE.get(auto.one_record, FORWARD_ONE) if scheme == FORWARD_ONE else scheme
    folds = [(f, p, s & np.isfinite(y)) for f, p, s in auto._folds(groups, len(y))]
    g = np.zeros(len(y), int) if groups is None else groups
    runs = {n: auto.candidates[n] for n in names if n in auto.candidates}
    runs.setdefault(BASELINE, MLR())
    out = {"scheme": auto.scheme_, "folds": len(folds), "candidates": {}}
    label_raw = np.concatenate([y[s] for *_, s in folds])
    label_frame = np.concatenate([in_frame(y[p], first_measured_rows(y[p], g[p]))[s[p]]
                                  for _, p, s in folds])
    fold_of = np.concatenate([np.full(s.sum(), k) for k, (*_, s) in enumerate(folds)])
    for name, est in runs.items():
        why = _not_applicable(name, context, groups) or _same_as(name, est, runs, context, len(y))
        if why is not None:        # skipped as auto skips it
            out["candidates"][name] = why
            continue
        raw, frame, at_m, t0 = [], [], [], time.process_time()
        try:
            for fit, pred, score in folds:
                model = clone(est).fit(X[fit], y[fit], context=subset(context, fit))
                yhat = np.asarray(model.predict(X[pred], context=subset(context, pred)), float)
                rows = first_measured_rows(y[pred], g[pred])
                raw.append(yhat[score[pred]])
                frame.append(in_frame(yhat, rows)[score[pred]])
                at_m.append(float(yhat[rows[rows >= 0][0]]) if (rows >= 0).any() else float("nan"))
        except (ValueError, ArithmeticError, np.linalg.LinAlgError) as exc:
            out["candidates"][name] = f"cannot fit: {exc}"
            continue
        raw, frame = np.concatenate(raw), np.concatenate(frame)
        out["candidates"][name] = {
            "raw": rmse(label_raw - raw), "frame": rmse(label_frame - frame),
            "raw_folds": [rmse((label_raw - raw)[fold_of == k]) for k in range(len(folds))],
            "frame_folds": [rmse((label_frame - frame)[fold_of == k]) for k in range(len(folds))],
            "y_hat_m": at_m, "cpu_s": time.process_time() - t0, "_raw": raw, "_frame": frame}
    members = [n for n in auto.candidates if isinstance(out["candidates"].get(n), dict)]
    base = members.index(BASELINE) if BASELINE in members else None
    for how, label in (("raw", label_raw), ("frame", label_frame)):
        preds = np.column_stack([out["candidates"][n][f"_{how}"] for n in members])
        w = vote_weights(preds, label, fold_of, out["candidates"][BASELINE][f"_{how}"],
                         base_column=base, min_folds=int(auto.n_folds))
        out[f"votes_{how}"] = {n: round(float(v), 3) for n, v in zip(members, w) if v > 0}
        out[f"blend_{how}"] = rmse(label - preds @ w)
    for c in out["candidates"].values():
        if isinstance(c, dict):
            c.pop("_raw"), c.pop("_frame")
    return out


def lagbank_choice(lagbank, X, y, context) -> dict:
    """The lag bank's CV choice on these rows, without and (the refused rule's code, e1e98a9,
    on PYTHONPATH) with the frame in its context."""
    from thermocomp.core import context as ctx_module

    frame = getattr(ctx_module, "FIRST_PROBE_FRAME", None)
    ways = [("raw", context)]
    if frame is not None:
        ways.append(("frame", with_column(context, frame, 1.0, len(y))))
    out = {}
    for how, ctx in ways:
        est = clone(lagbank).fit(X, y, context=ctx)
        row = est.cv_results_.loc[est.cv_results_["chosen"]].iloc[0]
        out[how] = {"alpha": est.alpha_, "level_penalty": est.level_penalty_,
                    "cv_rmse": float(np.sqrt(row["cv_mse_free_run"])),
                    "intercept": est.intercept_}
    return out


def folds_report(work: Path, cases, names) -> dict:
    copies(work)
    report = {}
    for case in cases:
        comp, m, context = matrices(work / case)
        X = m.X.to_numpy(float)
        for t in m.Y.columns:
            y = m.Y[t].to_numpy(float)
            auto = clone(for_target(comp.estimator, t))
            entry = {"first_measured_row": int(np.flatnonzero(np.isfinite(y))[0]),
                     "auto": candidate_folds(auto, X, y, context, names),
                     "lagbank": lagbank_choice(auto.candidates["lagbank"], X, y, context)}
            report[f"{case} {t}"] = entry
            print(f"{case} {t}: {json.dumps(entry, default=float)}", flush=True)
    (work / "firstfold63_folds.json").write_text(json.dumps(report, indent=1, default=float))
    return report


def one_step(work: Path, model: Path, case: str = "e30f15") -> dict:
    """Why the one-step law fitted and fed the label as measured scored better than in the
    completed label's frame (firstprobe62: 1.58 / 1.32 against 2.32 / 1.95, and 2.38 / 2.12 fitted
    on the label, fed the completed one): the law ``y(t') + k (s(t) - s(t')) - g (y(t') - s(t'))``
    fitted three ways on ``model``'s (a ``run`` of ``case``) training rows, scored against the
    completed label (as run scores) and the true error; ``s(m)``, ``E(m) - E(0)`` of the test."""
    from thermocomp.core.context import Y_MEASURED
    from thermocomp.core.io.read import read_dataset
    from thermocomp.core.models.one_step import OneStepLaw
    from thermocomp.shell.model_store import load_model

    comp = load_model(model)
    sparse, _ = read_dataset(work / case)
    dense, _ = read_dataset(work / "dense")
    out = {}
    for t in comp.targets_:
        frames = {}
        for split in ("train", "test"):
            ids = sparse.ids(split)
            m = comp.stacked({c: sparse.campaigns[c] for c in ids}, [t])
            sim = comp.predict_stacked(m)[:, comp.targets_.index(t)]
            label = m.Y[t].to_numpy(float)
            true = np.concatenate([dense.campaigns[c][t].to_numpy(float) - dense.campaigns[c][t].iloc[0]
                                   for c in ids])
            frames[split] = (m, sim, label, comp.scored_label(label, m.groups, sim), true)
        m, s, raw, done, _ = frames["train"]
        ctx = m.context
        # the label the kept fit was fitted on (a refit's: completed by y_hat(m) - y_hat(0) of
        # the fit before), which firstprobe62's law was fitted on
        X = m.X[comp.selected_[t]].to_numpy()
        _, kept = comp._fit_in_frame(for_target(comp.estimator, t), X, raw, m.groups, ctx)
        laws = {"as measured": (OneStepLaw().fit(s[:, None], raw, context=ctx), "raw"),
                "kept label, fed as measured (firstprobe62)":
                    (OneStepLaw().fit(s[:, None], kept, context=ctx), "raw"),
                "kept label, fed completed (firstprobe62's try)":
                    (OneStepLaw().fit(s[:, None], kept, context=ctx), "done"),
                "completed (now)": (OneStepLaw().fit(s[:, None], done, context=ctx), "done")}
        m, s, raw, done, true = frames["test"]
        ctx = m.context
        rows = np.isfinite(raw)
        m_row = int(np.flatnonzero(rows)[0])
        entry = {"s(m)": float(s[m_row]), "E(m)-E(0)": float(true[m_row]),
                 "simulation": {"scored": rmse((done - s)[rows]), "true": rmse((true - s)[rows])}}
        for name, (law, feed) in laws.items():
            fed = with_column(ctx, Y_MEASURED, raw if feed == "raw" else done, len(s))
            y1 = law.predict(s[:, None], context=fed)
            entry[name] = {"k": law.k_, "g": law.g_, "scored": rmse((done - y1)[rows]),
                           "true": rmse((true - y1)[rows]),
                           "mean_scored": float(np.mean((done - y1)[rows])),
                           "mean_true": float(np.mean((true - y1)[rows]))}
        out[t] = entry
        print(t, json.dumps(entry), flush=True)
    return out


def hobber(root: Path, out: Path, families) -> list[dict]:
    """``bench_stranger62``'s hobber (seed 6221: 15 separate runs, the first probe 10-25 min after
    the logger, the probe zeroed at the run's start, first-sample frame; ``write`` and ``init``
    done in ``root``): per family, ``run``'s test RMSE and the true error, the deployed
    ``y_hat(t)`` against the probe's reading as logged (the rise since the run's start, its
    0.3 um repeatability included) on the test runs' measured rows."""
    from bench_firstprobe62 import FAST, tc
    from bench_stranger62 import data_args
    from hydra import compose, initialize_config_dir

    from thermocomp.base.paths import conf_dir, resolve
    from thermocomp.core import io
    from thermocomp.shell.config.checks import data_options
    from thermocomp.shell.model_store import load_model

    args = data_args(root, "hobber")
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=args)
    ds = io.read_dataset(resolve(cfg.data.path), data_options(cfg))[0]
    ids = ds.ids("test")
    rows = []
    for family in families:
        tc("run", *args, f"model={family}", f"out={out}/{family}", *FAST)
        comp = load_model(out / family / "model.pkl")
        pred = comp.predict({c: ds.campaigns[c] for c in ids})
        run = json.loads((out / family / "metrics.json").read_text())["targets"]
        truth = {}
        for t in comp.targets_:
            res = np.concatenate([ds.campaigns[c][t].to_numpy(float) - pred[c][t].to_numpy()
                                  for c in ids])
            truth[t] = rmse(res[np.isfinite(res)])
        rows.append({"case": "hobber", "family": family,
                     "run": {t: run[t]["test"]["rmse"] for t in run}, "truth": truth})
        print(json.dumps(rows[-1]), flush=True)
    (out / "hobber.json").write_text(json.dumps(rows, indent=1))
    return rows


def compare(before: Path, after: Path) -> None:
    """Print run's test RMSE and the true error, before -> after, per case, family, target."""
    old = {(r["case"], r["family"]): r for r in json.loads(before.read_text())}
    for r in json.loads(after.read_text()):
        o = old.get((r["case"], r["family"]))
        if o is None:
            continue
        for t in r["run"]:
            print(f"{r['case']} {r['family']:8s} {t}: run {o['run'][t]:.3f} -> {r['run'][t]:.3f}"
                  f"   true {o['truth'][t]:.3f} -> {r['truth'][t]:.3f}")


if __name__ == "__main__":
    if sys.argv[1] == "hobber":
        hobber(Path(sys.argv[2]), Path(sys.argv[3]), sys.argv[4].split(","))
    elif sys.argv[1] == "onestep":
        one_step(Path(sys.argv[2]), Path(sys.argv[3]))
    elif sys.argv[1] == "compare":
        compare(Path(sys.argv[2]), Path(sys.argv[3]))
    else:
        folds_report(Path(sys.argv[2]), sys.argv[3].split(",") if len(sys.argv) > 3 else CASES,
                     sys.argv[4].split(",") if len(sys.argv) > 4 else
                     ("mlr", "pcr", "arx", "lagbank", "hammerstein", "lstm", "ati"))
