"""`thermocomp train | evaluate | run`: fit the compensator, score it, report."""

from __future__ import annotations

import time

from omegaconf import DictConfig

from .. import io
from ..compensator import Compensator
from ..evaluation import require_split, score
from ..paths import resolve
from ..plots import residual_plot
from ..tracking import stage_run
from .common import (build_compensator, check_config, data_options, load_model, result_table,
                     save_model, say, write_json)


def _fit(cfg: DictConfig, ds) -> Compensator:
    ids = require_split(ds, "train")
    say(f"fitting {cfg.model.name} ({cfg.select.name} inputs) on {len(ids)} train campaigns")
    return build_compensator(cfg).fit({c: ds.campaigns[c] for c in ids})


def train(cfg: DictConfig) -> Compensator:
    """Fit the configured model on the train split of ``data.interim``."""
    check_config(cfg)
    ds = io.load_interim(resolve(cfg.data.interim))
    t0 = time.perf_counter()
    comp = _fit(cfg, ds)
    fit_s = time.perf_counter() - t0
    path = save_model(comp, cfg.model_path)
    say(f"model saved to {path} ({fit_s:.2f} s)")
    with stage_run(cfg, "train") as tr:
        tr.log_metrics({"fit_time_s": fit_s})
        tr.log_artifact(path)
    return comp


def _report(cfg: DictConfig, comp: Compensator, ds, tracker, extra: dict | None = None) -> dict:
    """Score, write metrics.json and figures under ``out``, print the table."""
    targets, predictions = score(comp, ds, cfg.eval.mode, cfg.eval.e_p95.statistic,
                                 cfg.eval.e_p95.max_points)
    metrics = {"model": cfg.model.name, "mode": cfg.eval.mode, "targets": targets,
               "select": cfg.select.name, "dataset": ds.name,
               "inputs": {t: comp.selected_[t] for t in comp.targets_}}
    metrics.update(extra or {})
    out = resolve(cfg.out)
    path = write_json(out / "metrics.json", metrics)
    if cfg.eval.plots:
        for cid, (meas, pred) in predictions.items():
            time_s = ds.campaigns[cid]["time"].to_numpy()
            for t in comp.targets_:
                residual_plot(time_s, meas[t], pred[t], t, cid,
                              out / "plots" / f"residual_{cid}_{t}.png")
    tracker.log_metrics({"targets": targets})
    tracker.log_artifact(path)
    if (out / "plots").is_dir():
        tracker.log_artifacts(out / "plots", "plots")
    print(result_table(metrics))
    say(f"metrics: {path}")
    return metrics


def evaluate(cfg: DictConfig) -> dict:
    """Score the trained model on train and test splits; write ``out/metrics.json``."""
    check_config(cfg)
    ds = io.load_interim(resolve(cfg.data.interim))
    comp = load_model(cfg.model_path)
    with stage_run(cfg, "evaluate") as tr:
        return _report(cfg, comp, ds, tr)


def run(cfg: DictConfig) -> dict:
    """ingest .. evaluate in one process (nothing written under data/)."""
    check_config(cfg)
    say(f"reading {resolve(cfg.data.path)}")
    ds, report = io.read_dataset(resolve(cfg.data.path), data_options(cfg))
    with stage_run(cfg, "run") as tr:
        t0 = time.perf_counter()
        comp = _fit(cfg, ds)
        fit_s = time.perf_counter() - t0
        out = resolve(cfg.out)
        model_path = save_model(comp, out / "model.pkl")
        write_json(out / "ingest_report.json", report)
        tr.log_metrics({"fit_time_s": fit_s})
        tr.log_artifact(model_path)
        return _report(cfg, comp, ds, tr, {"fit_time_s": fit_s})
