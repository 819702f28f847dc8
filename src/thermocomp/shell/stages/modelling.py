"""`thermocomp train | evaluate | run`: fit the compensator, score it, report.

Each opens its source (:func:`~thermocomp.shell.source.open_source`: ``data.interim`` for the
DVC stages, ``data.path`` for ``run``), fits or loads, and reports through one core function
(:func:`thermocomp.core.run_report.report_run`).  A run's outputs (``model.pkl``,
``ingest_report.json``, ``metrics.json``, ``plots/``) are staged in a temp folder next to
``out`` and moved in only when everything is computed
(:func:`~thermocomp.base.files.staged_outputs`): a refused or killed run leaves ``out`` as it was.
"""

from __future__ import annotations

import shutil
import time

from omegaconf import DictConfig
from sklearn.base import clone

from ...base.errors import ConfigError
from ...base.files import staged_outputs, write_json
from ...base.log import Clock, logger, say
from ...base.paths import resolve
from ...core import io
from ...core.first_probe import late_first_note
from ...core.models.auto import add_choices, as_chosen
from ...core.models.hammerstein import without_states_note
from ...core.run_report import Refits, ReportSettings, report_run
from ...core.scoring.evaluation import require_split
from ...core.scoring.results import EvaluationResult
from ..builders import build_compensator, validation_template
from ..chain import fit_chain
from ..config.checks import check_config
from ..model_store import load_model, model_family, save_model
from ..source import (
    calibration_of,
    check_declared,
    open_source,
    simulated_truth,
    source_report,
    volumetric_distances,
)
from ..tracking import stage_run
from .artifacts import fit_from_artifacts
from .fleet import FLEET_RUN_OUTPUTS, run_grouped, warn_left_over


def train(cfg: DictConfig):
    """Fit the configured model on the train split of ``data.interim``, reusing the outputs of
    ``denoise`` and ``select`` when they match the config (see ``stages/artifacts.py``)."""
    check_config(cfg, outputs=("model_path",), inputs=("data.interim", "data.processed"))
    ds = open_source(cfg, ingested=True)
    check_declared(cfg, ds)
    t0 = time.perf_counter()
    comp = fit_from_artifacts(cfg, ds)
    fit_s = time.perf_counter() - t0
    comp.interim_digest_ = ds.meta["digest"]   # what it learnt from: evaluate refuses another
    from ...core.io.own_headers import lab_names
    comp.lab_names_ = lab_names(cfg, ds)       # (names97: as run's)
    path = save_model(comp, cfg.model_path)
    say(f"model saved to {path} ({fit_s:.2f} s)")
    with stage_run(cfg, "train") as tr:
        tr.log_metrics({"fit_time_s": fit_s})
        tr.log_artifact(path)
    return comp


def evaluate(cfg: DictConfig) -> dict:
    """Score the trained model on train and test splits; write ``out/metrics.json`` (with the
    ``volumetric`` section when ``data.path`` is a volumetric dataset)."""
    check_config(cfg, inputs=("data.interim", "model_path"))
    clock = Clock()
    ds = open_source(cfg, ingested=True)
    comp = load_model(cfg.model_path)
    _check_trained_on(cfg, comp, ds)
    volumetric = volumetric_distances(cfg, ds)
    clock.lap("read")
    with stage_run(cfg, "evaluate") as tr:
        return _report(cfg, comp, ds, tr, clock, volumetric=volumetric)


def run(cfg: DictConfig) -> dict:
    """ingest .. evaluate in one process, the stages' functions chained in memory (nothing
    written under data/); with ``data.group_by``
    one model per group of campaigns (a fleet's machines, ``stages/fleet.py``).  On a
    volumetric dataset the source is its parameter series, and ``metrics.json`` gains the
    ``volumetric`` section (:mod:`thermocomp.apps.volumetric.validation`)."""
    if cfg.data.get("group_by"):
        return run_grouped(cfg)
    check_config(cfg)
    clock = Clock()
    ds = open_source(cfg)
    volumetric = calibration_of(ds)
    clock.lap("read")
    # a run refused from here on is recorded FAILED; its dataset tag is the digest just read
    with stage_run(cfg, "run", digest=ds.meta["digest"]) as tr:
        if volumetric is None:
            check_declared(cfg, ds)
        clock.lap("log")
        t0 = time.perf_counter()
        ids = require_split(ds, "train")
        say(f"fitting {cfg.model.name} ({cfg.select.name} inputs) on {len(ids)} train campaigns")
        comp = fit_chain(cfg, ds)     # what denoise -> select -> train compute, in memory
        fit_s = time.perf_counter() - t0
        clock.lap("fit")

        # the lab's headers travel with the model: another record's refusal names them (names97)
        from ...core.io.own_headers import lab_names
        comp.lab_names_ = lab_names(cfg, ds)

        def stage_files(stage):  # committed with metrics.json, or not at all
            save_model(comp, stage / "model.pkl")
            write_json(stage / "ingest_report.json", source_report(cfg, ds))

        metrics = _report(cfg, comp, ds, tr, clock, {"fit_time_s": fit_s}, stage_files, volumetric)
        tr.log_metrics({"fit_time_s": fit_s})
        tr.log_artifact(resolve(cfg.out) / "model.pkl")
    warn_left_over(cfg.out, FLEET_RUN_OUTPUTS, "fleet (data.group_by)")
    return metrics


def _report(cfg: DictConfig, comp, ds, tracker, clock: Clock | None = None,
            extra: dict | None = None, stage_files=None, volumetric=None) -> dict:
    """Score ``comp`` on ``ds``, write ``metrics.json`` and the figures under ``out`` at once
    (``stage_files(folder)``: the run's other outputs), log and print them.  ``volumetric``:
    ``(distance dataset, calibration, its report)``, for the ``volumetric`` section."""
    from ...apps.volumetric.section import validate

    out, clock, extra = resolve(cfg.out), clock or Clock(), dict(extra or {})
    notes = [n for n in (without_states_note(comp),
                         late_first_note(comp.reference, comp.targets_, ds.campaigns)) if n]
    for note in notes:        # said, and kept beside the figures it explains
        logger.warning(note)
    if notes:
        extra["warnings"] = notes
    if volumetric is not None:
        extra["volumetric"], curves = validate(comp, ds, *volumetric, str(cfg.eval.mode),
                                               *reversed(simulated_truth(cfg)))
        clock.lap("volumetric")
    with staged_outputs(out) as stage:
        if stage_files is not None:
            stage_files(stage)
        if volumetric is not None and cfg.plots != "none":
            from ...apps.volumetric.figures import draw_validation

            draw_validation(stage / "volumetric", extra["volumetric"], curves)
        base = build_compensator(cfg, ati=False)
        refits = Refits(validation_template(cfg, comp, ds), as_chosen(clone(base), comp))
        metrics = report_run(comp, ds, _settings(cfg), refits, stage, clock, extra, add_choices)
    if cfg.plots == "none":      # no figures of this run: none of an earlier one beside its numbers
        shutil.rmtree(out / "plots", ignore_errors=True)
    _publish(cfg, metrics, out, tracker, clock)
    return metrics


def _settings(cfg: DictConfig) -> ReportSettings:
    ati = cfg.ati.name if cfg.get("ati") is not None else "none"
    denoise = cfg.denoise.name if cfg.get("denoise") is not None else "none"
    return ReportSettings.from_eval(cfg.eval, model=cfg.model.name, select=cfg.select.name,
                                    plots=str(cfg.plots), ati=ati, denoise=denoise)


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


def _check_trained_on(cfg: DictConfig, comp, ds) -> None:
    """``evaluate`` scores the model at ``model_path`` and labels the result with the config:
    the two must agree (``model=pcr`` on an MLR model printed the MLR's figures as pcr's, and
    another ``data.targets`` was a KeyError), and it must have learnt from this ingest."""
    targets = None if cfg.data.targets is None else list(cfg.data.targets)
    for key, given, trained in (("model", str(cfg.model.name), model_family(comp)),
                                ("data.inputs", list(cfg.data.inputs), list(comp.inputs)),
                                ("data.targets", targets,
                                 None if comp.targets is None else list(comp.targets))):
        if given != trained:
            raise ConfigError(f"{key}={given}, but the model at model_path={cfg.model_path} was "
                              f"trained with {'every E_ column' if trained is None else trained}: "
                              "evaluate with the training's settings, or train again")
    trained_on = getattr(comp, "interim_digest_", None)
    if trained_on is not None and trained_on != ds.meta["digest"]:
        raise io.ContractError("the model was trained on another ingest of this folder (another "
                               "run's ingest replaced it since); rerun train",
                               file=resolve(cfg.data.interim))
