"""`thermocomp train | evaluate | run`: fit the compensator, score it, report.

A run's outputs (``model.pkl``, ``ingest_report.json``, ``metrics.json``,
``plots/``) are staged in a temp folder next to ``out`` and moved in only
when everything is computed (:func:`~thermocomp.base.files.staged_outputs`): a
refused or killed run leaves ``out`` as it was.
"""

from __future__ import annotations

import shutil
import time
from contextlib import contextmanager
from functools import partial

from omegaconf import DictConfig
from sklearn.base import clone

from ...base.errors import ConfigError
from ...base.files import atomic_write_text, inside, safe_name, staged_outputs, write_json
from ...base.log import Clock, logger, say
from ...base.paths import resolve
from ...core import io
from ...core.compensator import Compensator, with_chosen_hyperparameters
from ...core.continuation import carry_over
from ...core.metrics import E_MAX, E_P95, ISO_A3, PER_CAMPAIGN, RSD, VALIDATION, validation_block
from ...core.scoring.evaluation import (
    VAL_FOLDS,
    ambient_by_campaign,
    anova,
    ati_report,
    mutual_prediction_report,
    predict_split,
    require_split,
    score,
    validation_reports,
)
from ...core.scoring.headline import HEADLINE, write_headline
from ...core.scoring.iso10791 import a3_campaign
from ...core.scoring.leaderboard import DEPLOYED_MODE
from ...core.scoring.results import EvaluationResult, TargetResult
from ..model_store import load_model, model_family, save_model
from ..tracking import stage_run
from .artifacts import fit_from_artifacts
from .auto import add_choices, as_chosen
from .common import (
    build_compensator,
    check_config,
    check_declared,
    data_options,
    load_ingested,
    resolve_reference,
    simulated_truth,
    validation_template,
    volumetric_calibration,
    volumetric_source,
)


def _fit(cfg: DictConfig, ds) -> Compensator:
    ids = require_split(ds, "train")
    say(f"fitting {cfg.model.name} ({cfg.select.name} inputs) on {len(ids)} train campaigns")
    return build_compensator(cfg, ds=ds).fit({c: ds.campaigns[c] for c in ids})


def train(cfg: DictConfig) -> Compensator:
    """Fit the configured model on the train split of ``data.interim``, reusing the outputs of
    ``denoise`` and ``select`` when they match the config (see ``stages/artifacts.py``)."""
    check_config(cfg, outputs=("model_path",), inputs=("data.interim", "data.processed"))
    ds = load_ingested(cfg)
    check_declared(cfg, ds)
    t0 = time.perf_counter()
    comp = fit_from_artifacts(cfg, ds)
    fit_s = time.perf_counter() - t0
    # which ingest it learnt from: evaluate refuses another (two runs sharing data.interim)
    comp.interim_digest_ = ds.meta["digest"]
    path = save_model(comp, cfg.model_path)
    say(f"model saved to {path} ({fit_s:.2f} s)")
    with stage_run(cfg, "train") as tr:
        tr.log_metrics({"fit_time_s": fit_s})
        tr.log_artifact(path)
    return comp


def _report(cfg: DictConfig, comp: Compensator, ds, tracker, clock: Clock | None = None,
            extra: dict | None = None, stage_files=None) -> dict:
    """Score, write metrics.json and the figures ``plots`` asks for under ``out``, print the table.

    Figures are queued as soon as their numbers exist and drawn by worker
    processes while the next numbers are computed (see :class:`~thermocomp.core.figures.plots.FigurePool`).
    ``stage_files(folder)`` writes the run's other outputs into the staging folder first;
    ``out`` receives everything at once at the end (nothing if anything fails).
    """
    out, clock = resolve(cfg.out), clock or Clock()
    with staged_outputs(out) as stage:
        if stage_files is not None:
            stage_files(stage)
        metrics = _score(cfg, comp, ds, stage, clock, extra)
    if cfg.plots == "none":      # no figures of this run: none of an earlier one beside its numbers
        shutil.rmtree(out / "plots", ignore_errors=True)
    _publish(cfg, metrics, out, tracker, clock)
    return metrics


def _score(cfg: DictConfig, comp: Compensator, ds, stage, clock: Clock,
           extra: dict | None) -> dict:
    """The numbers and figures of :func:`_report`, written into ``stage``."""
    ev = cfg.eval
    with _plots_folder(stage, cfg.plots) as (draw, folder):
        targets, predictions = score(comp, ds, ev.mode, ev.e_p95.statistic, ev.e_p95.max_points,
                                     iso_a3=ev.get(ISO_A3, True))   # a key named as its figure
        clock.lap("score")
        add_choices(comp, targets)
        if ev.get("validation", True):
            _add_validation(cfg, comp, ds, targets)
            clock.lap("validation")
        metrics = {"model": cfg.model.name, "mode": ev.mode, "targets": targets,
                   "select": cfg.select.name, "dataset": ds.name,
                   "inputs": {t: comp.selected_[t] for t in comp.targets_},
                   "reference": comp.reference, "carry_over": carry_over(comp, ds)}
        metrics.update(extra or {})
        if cfg.plots != "none":
            _e_p95_figures(draw, folder, targets)
        if cfg.plots in ("test", "all"):
            _campaign_figures(draw, folder, comp, ds, predictions)
        if cfg.plots == "all":
            _campaign_figures(draw, folder, comp, ds, _train_predictions(comp, ds, ev.mode))
        clock.lap("figures")
        _model_reports(cfg, comp, ds, predictions, metrics, (draw, folder), clock)
        result = EvaluationResult(metrics)
        atomic_write_text(stage / "metrics.json", result.to_json())
        write_headline(stage / HEADLINE, result.headline("dvc"))  # for `dvc metrics show`
        clock.lap("write")
    clock.lap("figures")  # drawing still under way once every number is written
    return metrics


def _model_reports(cfg: DictConfig, comp: Compensator, ds, predictions: dict, metrics: dict,
                   figures: tuple, clock: Clock) -> None:
    """ANOVA, the ATI baselines and mutual prediction into ``metrics`` (and their figures)."""
    ev = cfg.eval
    # instantiate once, then copies for the 26 baseline and mutual-prediction models
    make_base = partial(clone, build_compensator(cfg, ati=False))
    metrics["anova"] = anova(comp, ds, float(ev.get("anova_alpha", 0.001)), predictions)
    clock.lap("anova")
    ati_name = cfg.ati.name if cfg.get("ati") is not None else "none"
    if ev.get("ati_baselines", True):
        say("ATI report: cold/warm single-campaign baselines")
        metrics["ati"] = ati_report(comp, ds, make_base, ev.mode, ati_name)
        clock.lap("ati")
    if cfg.plots != "none":
        _rsd_figures(*figures, metrics, ambient_by_campaign(ds, list(predictions)))
        clock.lap("figures")
    if ev.get("mutual_prediction", True):
        say(f"mutual prediction: {len(ds.ids())} single-campaign models")
        # its single-campaign models keep the hyper-parameters the model chose on all train
        # campaigns: one CV per campaign cost 43 x 43 lag banks on a lathe record (model=auto:
        # each target's chosen family, not the whole choice again per campaign)
        make_single = partial(clone, with_chosen_hyperparameters(as_chosen(make_base(), comp), comp))
        metrics["mutual_prediction"] = mutual_prediction_report(make_single, ds, ev.mode)
        clock.lap("mutual_prediction")
        if cfg.plots in ("test", "all"):
            _mutual_figures(*figures, metrics["mutual_prediction"])
            clock.lap("figures")


def _publish(cfg: DictConfig, metrics: dict, out, tracker, clock: Clock) -> None:
    """Log the committed outputs of a run to MLflow and print its table."""
    path = out / "metrics.json"
    result = EvaluationResult(metrics)
    tracker.log_metrics(result.headline("mlflow"))     # the full metrics.json is the artifact
    tracker.log_artifact(path)
    if cfg.plots != "none":  # not the figures an earlier run left
        tracker.log_artifacts(out / "plots", "plots")
    clock.lap("log")
    print(result.summary())
    if "volumetric" in metrics:     # the 22 parameters above; what they add up to here
        from ...apps.volumetric.validation import headline_table

        print("\n" + headline_table(metrics["volumetric"]))
    say(f"metrics: {path}")
    say(clock.line())


def _add_validation(cfg: DictConfig, comp: Compensator, ds, targets: dict) -> None:
    """``targets[t]["validation"]``: the score compare and promote choose by (never the test split).

    The configured compensator (not the loaded one: its selection or denoiser
    may have been fitted on all train campaigns) is refitted per fold.
    """
    say("validation: " + ("the val split" if ds.ids("val") else "cross-validation on the train split"))
    asked = int(cfg.eval.get("validation_folds", VAL_FOLDS))
    mode = str(cfg.eval.mode)
    # model=auto: its choice refitted (a val split scores the fitted model: no template needed)
    template = validation_template(cfg, comp, ds)
    # the deployed mode too: compare and promote choose by it, whatever eval.mode scored the run
    both = validation_reports(partial(clone, template), ds, (mode, DEPLOYED_MODE), fitted=comp,
                              n_folds=asked, scheme=cfg.eval.get("validation_scheme", "auto"))
    val = both[mode]
    used = next(iter(val.values()), {}).get("n_folds", asked)
    if asked != VAL_FOLDS and used != asked:  # the default is clamped quietly: it is not a choice
        logger.warning("eval.validation_folds=%d: %d fold(s), %s", asked, used,
                       next(iter(val.values()))["method"])
    for t, entry in val.items():
        targets[t][VALIDATION] = entry
        if mode != DEPLOYED_MODE:
            targets[t][validation_block(DEPLOYED_MODE)] = both[DEPLOYED_MODE][t]


@contextmanager
def _plots_folder(stage, level: str):
    """``(draw, folder)``: ``draw(plot, *args)`` queues a figure of ``folder``,
    ``<stage>/plots`` (it replaces ``<out>/plots`` when the run is committed); nothing at all
    with ``plots=none`` (not even a matplotlib import)."""
    if level == "none":
        yield None, None
        return
    from ...core.figures.plots import FigurePool

    folder = stage / "plots"
    folder.mkdir()
    with FigurePool() as pool:
        yield pool.submit, folder


def _figure(folder, *parts: str):
    """``<folder>/<parts joined>.png``; the name is sanitised and must stay in ``folder`` (column
    and campaign names are checked at ingest, this is the second line of defence)."""
    return inside(folder, safe_name(*parts) + ".png")


def _train_predictions(comp: Compensator, ds, mode: str) -> dict:
    """``{campaign: (measured, predicted)}`` of the train campaigns (``plots=all``)."""
    return predict_split(comp, ds, "train", mode)


def _campaign_figures(draw, folder, comp: Compensator, ds, predictions: dict) -> None:
    """Residual and ISO 10791-10 A.3 figures of every campaign of ``predictions``."""
    from ...core.figures.plotdata import write_residual
    from ...core.figures.plots import iso_a3_plot, residual_plot

    for cid, (meas, pred) in predictions.items():
        time_s = ds.campaigns[cid]["time"].to_numpy()
        for t in comp.targets_:
            y, yhat = meas[t].to_numpy(), pred[t].to_numpy()
            draw(residual_plot, time_s, y, yhat, t, cid, _figure(folder, "residual", cid, t))
            write_residual(folder, time_s, y, yhat, t, cid)  # the data, for `dvc plots show`
            a3 = a3_campaign(time_s, y, y - yhat)
            if a3["available"]:
                mv = a3["moving"]
                draw(iso_a3_plot, mv["start_s"], mv["range_before"], mv["range_after"], t, cid,
                     _figure(folder, ISO_A3, cid, t))


def _e_p95_figures(draw, folder, targets: dict) -> None:
    """Per target: E_P95 (and E_max) before/after compensation on the test split."""
    from ...core.figures.plotdata import write_e_p95
    from ...core.figures.plots import e_p95_plot

    write_e_p95(folder, targets)  # the curves as data, for `dvc plots show`
    for t, tm in targets.items():
        e, emax = TargetResult(tm).test.e_p95, TargetResult(tm).test.get(E_MAX)
        draw(e_p95_plot, e["window_s"], e["before"], e["after"], t, e["statistic"],
             _figure(folder, E_P95, t), emax["before"], emax["after"])


def _rsd_figures(draw, folder, metrics: dict, test_ambient: dict) -> None:
    """Per target: Rsd per test campaign (with the ATI baselines), the ATI figures of an ATI model."""
    from ...core.figures.plots import ati_intervals_plot, elbow_plot, rsd_plot

    ati = metrics.get("ati", {}).get("targets", {})
    for t, tm in metrics["targets"].items():
        per = {c: v[RSD] for c, v in TargetResult(tm).test.get(PER_CAMPAIGN).items()}
        baselines = {}
        for name, label in (("coldest", "coldest-campaign model"), ("warmest", "warmest-campaign model"),
                            ("single_model", "one model, all train")):
            if name in ati.get(t, {}).get("test", {}):
                camp = metrics["ati"].get("baseline_campaigns", {}).get(name, {}).get("campaign")
                baselines[f"{label} ({camp})" if camp else label] = \
                    ati[t]["test"][name][PER_CAMPAIGN]
        n_int = ati.get(t, {}).get("n_intervals", 1)
        label = metrics["model"] + (f", {n_int} ATIs" if "intervals" in ati.get(t, {}) else "")
        draw(rsd_plot, per, t, _figure(folder, RSD, t), test_ambient, baselines, label)
        entry = ati.get(t, {})
        if "intervals" in entry:
            draw(ati_intervals_plot, entry["campaign_ambient_c0"], entry["boundaries_c"], t,
                 _figure(folder, "ati_intervals", t), test_ambient,
                 [i["campaigns"] for i in entry["intervals"]])
            if entry.get("elbow") and entry["elbow"].get("n_intervals"):
                draw(elbow_plot, entry["elbow"], t, _figure(folder, "ati_elbow", t))


def _mutual_figures(draw, folder, mutual: dict) -> None:
    """The mutual prediction heat map of every target."""
    from ...core.figures.plots import mutual_prediction_plot

    for t, mp in mutual.items():
        draw(mutual_prediction_plot, mp["campaigns"], mp[RSD], t,
             _figure(folder, "mutual_prediction", t), mp["ambient_c0"])


def _check_trained_as_configured(cfg: DictConfig, comp) -> None:
    """``evaluate`` scores the model at ``model_path`` and labels the result with the config:
    the two must agree (``model=pcr`` on an MLR model printed the MLR's figures as pcr's, and
    another ``data.targets`` was a KeyError)."""
    targets = None if cfg.data.targets is None else list(cfg.data.targets)
    for key, given, trained in (("model", str(cfg.model.name), model_family(comp)),
                                ("data.inputs", list(cfg.data.inputs), list(comp.inputs)),
                                ("data.targets", targets,
                                 None if comp.targets is None else list(comp.targets))):
        if given != trained:
            raise ConfigError(f"{key}={given}, but the model at model_path={cfg.model_path} was "
                              f"trained with {'every E_ column' if trained is None else trained}: "
                              "evaluate with the training's settings, or train again")


def evaluate(cfg: DictConfig) -> dict:
    """Score the trained model on train and test splits; write ``out/metrics.json`` (with the
    ``volumetric`` section when ``data.path`` is a volumetric dataset)."""
    check_config(cfg, inputs=("data.interim", "model_path"))
    clock = Clock()
    interim = resolve(cfg.data.interim)
    ds = load_ingested(cfg)
    comp = load_model(cfg.model_path)
    _check_trained_as_configured(cfg, comp)
    trained_on = getattr(comp, "interim_digest_", None)
    if trained_on is not None and trained_on != ds.meta["digest"]:
        raise io.ContractError("the model was trained on another ingest of this folder (another "
                               "run's ingest replaced it since); rerun train", file=interim)
    volumetric = volumetric_source(cfg)
    if volumetric is not None:
        lacking = [n for n in volumetric[1].names_ if n not in ds.columns]
        if lacking:
            raise io.ContractError(f"it does not hold the parameter series of the volumetric dataset "
                                   f"{resolve(cfg.data.path)} (no {lacking[0]}); rerun ingest", file=interim)
    clock.lap("read")
    with stage_run(cfg, "evaluate") as tr:
        if volumetric is None:
            return _report(cfg, comp, ds, tr, clock)
        raw, cal = volumetric
        calibration = ds.meta["ingest_report"].get("calibration") or {}
        return _volumetric_report(cfg, comp, ds, raw, cal, calibration, tr, clock, {})


def run(cfg: DictConfig) -> dict:
    """ingest .. evaluate in one process (nothing written under data/); with ``data.group_by``
    one model per group of campaigns (a fleet's machines, ``stages/fleet.py``).

    On a volumetric dataset (``volumetric.json`` in the folder) the distances are calibrated
    into the error parameter series first, a thermal model is fitted per parameter, and
    ``metrics.json`` gains the ``volumetric`` section (:mod:`thermocomp.apps.volumetric.validation`).
    """
    if cfg.data.get("group_by"):
        from .fleet import run_grouped

        return run_grouped(cfg)
    check_config(cfg)
    say(f"reading {resolve(cfg.data.path)}")
    clock = Clock()
    volumetric = volumetric_calibration(cfg)
    if volumetric is None:
        ds, report = io.read_dataset(resolve(cfg.data.path), data_options(cfg))
    else:
        ds, cal, calibration, raw = volumetric
        report = {"dataset": raw.name, "calibration": calibration}
    report["reference"] = resolve_reference(cfg, ds)
    clock.lap("read")
    with stage_run(cfg, "run") as tr:     # a run refused from here on is recorded FAILED
        if volumetric is None:
            check_declared(cfg, ds)
        clock.lap("log")
        t0 = time.perf_counter()
        comp = _fit(cfg, ds)
        fit_s = time.perf_counter() - t0
        clock.lap("fit")
        extra = {"fit_time_s": fit_s}

        def stage_files(stage):  # committed with metrics.json, or not at all
            save_model(comp, stage / "model.pkl")
            write_json(stage / "ingest_report.json", report)

        if volumetric is None:
            metrics = _report(cfg, comp, ds, tr, clock, extra, stage_files)
        else:
            metrics = _volumetric_report(cfg, comp, ds, raw, cal, calibration, tr, clock, extra,
                                         stage_files)
        tr.log_metrics({"fit_time_s": fit_s})
        tr.log_artifact(resolve(cfg.out) / "model.pkl")
        return metrics


def _volumetric_report(cfg: DictConfig, comp: Compensator, ds, raw, cal, calibration: dict, tracker,
                       clock: Clock, extra: dict, stage_files=None) -> dict:
    """:func:`_report` with the ``volumetric`` section, its figures and its MLflow metrics
    (``calibration``: the calibration's report, whose outliers the distance errors leave out)."""
    extra["volumetric"], curves = _volumetric(cfg, comp, raw, ds, cal, calibration)
    clock.lap("volumetric")

    def files(stage):
        if stage_files is not None:
            stage_files(stage)
        if cfg.plots != "none":
            from ...apps.volumetric.figures import draw_validation

            draw_validation(stage / "volumetric", extra["volumetric"], curves)

    return _report(cfg, comp, ds, tracker, clock, extra, files)   # its MLflow figures: headline


def _volumetric(cfg: DictConfig, comp: Compensator, raw, ds, cal, calibration: dict):
    """The ``volumetric`` section on the test split, and the curves of its figures."""
    from ...apps.volumetric.section import split_series, true_changes, volumetric_section

    say("volumetric validation: distances, VE/VCE, trajectories, ISO 10791-10 A.3")
    series = split_series(comp, raw, ds, cal, calibration, cfg.eval.mode)
    path, truth = simulated_truth(cfg)
    changes, missing = (None, None) if truth is None else true_changes(truth, cal, series["times"])
    if missing is not None:
        say(f"{path} does not hold campaign {missing}'s parameter series: VCE against the "
            "identified parameters")
    return volumetric_section(comp, series, cal, changes)
