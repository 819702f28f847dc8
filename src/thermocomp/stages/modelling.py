"""`thermocomp train | evaluate | run`: fit the compensator, score it, report."""

from __future__ import annotations

import time

from omegaconf import DictConfig

from .. import io
from ..compensator import Compensator
from ..evaluation import (ambient_by_campaign, anova, ati_report, mutual_prediction_report,
                          require_split, score)
from ..files import atomic_dir, write_json
from ..iso10791 import a3_campaign
from ..paths import resolve
from ..plots import (ati_intervals_plot, e_p95_plot, elbow_plot, iso_a3_plot,
                     mutual_prediction_plot, residual_plot, rsd_plot)
from ..tracking import stage_run
from .artifacts import fit_from_artifacts
from .common import build_compensator, check_config, data_options, load_model, result_table, save_model, say


def _fit(cfg: DictConfig, ds) -> Compensator:
    ids = require_split(ds, "train")
    say(f"fitting {cfg.model.name} ({cfg.select.name} inputs) on {len(ids)} train campaigns")
    return build_compensator(cfg).fit({c: ds.campaigns[c] for c in ids})


def train(cfg: DictConfig) -> Compensator:
    """Fit the configured model on the train split of ``data.interim``, reusing the outputs of
    ``denoise`` and ``select`` when they match the config (see ``stages/artifacts.py``)."""
    check_config(cfg)
    ds = io.load_interim(resolve(cfg.data.interim))
    t0 = time.perf_counter()
    comp = fit_from_artifacts(cfg, ds)
    fit_s = time.perf_counter() - t0
    path = save_model(comp, cfg.model_path)
    say(f"model saved to {path} ({fit_s:.2f} s)")
    with stage_run(cfg, "train") as tr:
        tr.log_metrics({"fit_time_s": fit_s})
        tr.log_artifact(path)
    return comp


def _report(cfg: DictConfig, comp: Compensator, ds, tracker, extra: dict | None = None) -> dict:
    """Score, write metrics.json and figures under ``out``, print the table."""
    ev = cfg.eval
    targets, predictions = score(comp, ds, ev.mode, ev.e_p95.statistic, ev.e_p95.max_points,
                                 iso_a3=ev.get("iso10791_a3", True))
    metrics = {"model": cfg.model.name, "mode": ev.mode, "targets": targets,
               "select": cfg.select.name, "dataset": ds.name,
               "inputs": {t: comp.selected_[t] for t in comp.targets_}}
    metrics.update(extra or {})
    make_base = lambda: build_compensator(cfg, ati=False)  # noqa: E731
    metrics["anova"] = anova(comp, ds, float(ev.get("anova_alpha", 0.001)), predictions)
    ati_name = cfg.ati.name if cfg.get("ati") is not None else "none"
    if ev.get("ati_baselines", True):
        say("ATI report: cold/warm single-campaign baselines")
        metrics["ati"] = ati_report(comp, ds, make_base, ev.mode, ati_name)
    if ev.get("mutual_prediction", True):
        say(f"mutual prediction: {len(ds.ids())} single-campaign models")
        metrics["mutual_prediction"] = mutual_prediction_report(make_base, ds, ev.mode)
    out = resolve(cfg.out)
    path = write_json(out / "metrics.json", metrics)
    if ev.plots:
        with atomic_dir(out / "plots") as tmp:
            tmp.chmod(0o755)  # mkdtemp makes it private; a report folder is for reading
            _figures(metrics, comp, ds, predictions, tmp)
    tracker.log_metrics({"targets": targets, "anova": metrics["anova"],
                         "ati": _ati_summary(metrics.get("ati", {}))})
    tracker.log_artifact(path)
    if (out / "plots").is_dir():
        tracker.log_artifacts(out / "plots", "plots")
    print(result_table(metrics))
    say(f"metrics: {path}")
    return metrics


def _ati_summary(ati: dict) -> dict:
    """The ATI scalars worth an MLflow metric: intervals and test SM/SD per model."""
    return {t: {"n_intervals": e["n_intervals"],
                "test": {k: {"rsd_mean": v["rsd_mean"], "rsd_sd": v["rsd_sd"]}
                         for k, v in e["test"].items()}}
            for t, e in ati.get("targets", {}).items()}


def _figures(metrics: dict, comp: Compensator, ds, predictions: dict, plots) -> None:
    """Every figure of the report, as PNG under ``plots``."""
    for cid, (meas, pred) in predictions.items():
        time_s = ds.campaigns[cid]["time"].to_numpy()
        for t in comp.targets_:
            residual_plot(time_s, meas[t], pred[t], t, cid, plots / f"residual_{cid}_{t}.png")
            a3 = a3_campaign(time_s, meas[t], (meas[t] - pred[t]))
            if a3["available"]:
                mv = a3["moving"]
                iso_a3_plot(mv["start_s"], mv["range_before"], mv["range_after"], t, cid,
                            plots / f"iso10791_a3_{cid}_{t}.png")
    test_ambient = ambient_by_campaign(ds, list(predictions))
    ati = metrics.get("ati", {}).get("targets", {})
    for t, tm in metrics["targets"].items():
        te = tm["test"]
        e, emax = te["e_p95"], te["e_max"]
        e_p95_plot(e["window_s"], e["before"], e["after"], t, e["statistic"],
                   plots / f"e_p95_{t}.png", emax["before"], emax["after"])
        per = {c: v["rsd"] for c, v in te["per_campaign"].items()}
        baselines = {}
        for name, label in (("coldest", "coldest-campaign model"), ("warmest", "warmest-campaign model"),
                            ("single_model", "one model, all train")):
            if name in ati.get(t, {}).get("test", {}):
                camp = metrics["ati"].get("baseline_campaigns", {}).get(name, {}).get("campaign")
                baselines[f"{label} ({camp})" if camp else label] = \
                    ati[t]["test"][name]["per_campaign"]
        n_int = ati.get(t, {}).get("n_intervals", 1)
        label = metrics["model"] + (f", {n_int} ATIs" if "intervals" in ati.get(t, {}) else "")
        rsd_plot(per, t, plots / f"rsd_{t}.png", test_ambient, baselines, label)
        entry = ati.get(t, {})
        if "intervals" in entry:
            ati_intervals_plot(entry["campaign_ambient_c0"], entry["boundaries_c"], t,
                               plots / f"ati_intervals_{t}.png", test_ambient,
                               [i["campaigns"] for i in entry["intervals"]])
            if entry.get("elbow") and entry["elbow"].get("n_intervals"):
                elbow_plot(entry["elbow"], t, plots / f"ati_elbow_{t}.png")
    for t, mp in metrics.get("mutual_prediction", {}).items():
        mutual_prediction_plot(mp["campaigns"], mp["rsd"], t, plots / f"mutual_prediction_{t}.png",
                               mp["ambient_c0"])


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
