"""`thermocomp diagnose`: closed loop -- residual -> missing effect -> refit -> before/after.

Reads ``data.path`` (:func:`~thermocomp.shell.source.open_source`), runs
:func:`thermocomp.apps.diagnose.diagnose` on the configured model and writes
``diagnosis.json`` (the primary target's), ``diagnosis/`` (every target's JSON, the report,
figures) and the config that reruns the diagnosed model
(:func:`thermocomp.apps.diagnose.outputs.write_outputs`), which is built from that very config.
"""

from __future__ import annotations

import copy
from pathlib import Path

from omegaconf import DictConfig, OmegaConf

from ...apps.diagnose import diagnose as run_diagnosis
from ...apps.diagnose import outputs
from ...apps.diagnose.augmented import MODEL_NAME
from ...base.errors import ConfigError
from ...base.log import logger, say
from ...base.paths import resolve
from ..builders import build_compensator, deploy_stream, deployable, search_options
from ..config.candidates import is_auto
from ..config.checks import check_config
from ..source import check_declared, open_source
from ..tracking import stage_run


def _container(node):
    return OmegaConf.to_container(node, resolve=True) if node is not None else None


def _ati(cfg: DictConfig):
    """The ATI wrapper's estimator config, or None."""
    ati = cfg.get("ati")
    return _container(ati.estimator) if ati is not None and ati.get("estimator") is not None else None


def after_config(cfg: DictConfig, model: dict, kept_inputs: list[str] | None) -> DictConfig:
    """``cfg`` with the diagnosed model, as the written experiment composes it."""
    out = copy.deepcopy(cfg)
    OmegaConf.set_struct(out, False)
    OmegaConf.update(out, "model", model, merge=False)
    if _ati(out) is not None:
        OmegaConf.update(out, "ati", {"name": "none", "estimator": None}, merge=False)
    if kept_inputs is not None:
        OmegaConf.update(out, "data.inputs", kept_inputs, merge=False)
    return out


def rerun_command(cfg: DictConfig, conf_dir: Path, out: Path, kept_inputs) -> str:
    """:func:`~thermocomp.apps.diagnose.outputs.rerun_command` of how this diagnosis ran."""
    from hydra.core.hydra_config import HydraConfig

    from ..tracking import _split, task_overrides

    paths, data_config = [], None
    if HydraConfig.initialized():
        hc = HydraConfig.get()
        paths, data_config = [str(p) for p in (hc.searchpath or [])], hc.runtime.choices.get("data")
    overrides = [(_split(o)[0], o) for o in task_overrides() or []]
    return outputs.rerun_command(paths, data_config, overrides, conf_dir, resolve(cfg.data.path),
                                 out, kept_inputs is not None)


def _write(cfg: DictConfig, ds, result, written: dict, out: Path) -> tuple[Path, str, Path]:
    rerun = rerun_command(cfg, out / "diagnosis" / "conf", out / MODEL_NAME, written.get("kept"))
    experiment = outputs.experiment(
        str(cfg.name), _ati(cfg) is not None, {g: _container(cfg.get(g)) for g in ("select", "denoise")},
        str(cfg.data.reference), written["kept"], str(cfg.eval.mode))
    header = (f"# Written by `thermocomp diagnose` on {ds.name}: {cfg.model.name} + the effects "
              f"it accepted.\n# Rerun: {rerun}\n")
    folder, main = outputs.write_outputs(out, result, written["model"], experiment, rerun, header,
                                         cfg.plots != "none")
    return folder, rerun, main


def _deployed_of(cfg: DictConfig, ds):
    """``(fitted, train, test ids) -> figures``: the test figures ``promote`` gives a model "as
    deployed", by promote's own steps (:func:`~thermocomp.apps.deploy.promotion.deploy`): the
    plain stream (``promote.envelope``, :func:`~..builders.deploy_stream`), what it registers
    around it (:func:`~..builders.deployable`: with ``monitor.adaptive``, default, the adaptive
    compensator, its sensor monitor and correction guard) and ``stream_scores`` of the test
    campaigns, each warmed on the campaigns it continues, adapted as ``adapt.*`` says (matrix61:
    the plain stream alone scored a column whose test met a source training never saw 5.46 µm
    after, promote's "as deployed" 6.20; diag76: ``adapt.method`` was left out); a model that
    cannot stream raises ValueError (a ConfigError)."""
    from ...apps.deploy.adapt import from_config as adapt_from_config
    from ...apps.deploy.streaming import stream_scores  # loaded only here
    from ...core.continuation import lead_ins
    from ...core.scoring.evaluation import sample_period

    def scored(comp, train: dict, ids: list):
        deployed = deployable(cfg, deploy_stream(cfg, comp, train), train, ds)
        test = {c: ds.campaigns[c] for c in ids}
        return stream_scores(deployed, test, sample_period(ds, ids), cfg.eval.e_p95.statistic,
                             cfg.eval.e_p95.max_points, lead_ins(comp, ds, ids),
                             adapt=adapt_from_config(cfg.get("adapt"), len(deployed.targets_)))
    return scored


def diagnose(cfg: DictConfig) -> dict:
    """Diagnose the configured model on ``data.path``; write the report under ``out``."""
    check_config(cfg)
    if cfg.get("diagnose") is None:
        raise ConfigError("no `diagnose` config group (conf/diagnose/default.yaml)")
    if is_auto(cfg):
        # its search ran (104 s CPU on a 24-run lab file) and then the diagnosed model, auto's
        # unbuilt candidates inside the effects' wrapper, could not be fitted: a traceback
        raise ConfigError("diagnose: model=auto is not diagnosed (the diagnosed model around it "
                          "cannot be built); diagnose the family auto kept, model=<family> "
                          "(for a kept `ati+<family>`: model=<family> ati=cmeans) "
                          "(metrics.json of `thermocomp run model=auto`)")
    dcfg = cfg.diagnose
    options = search_options(dcfg)
    targets = None if dcfg.targets is None else (
        [str(dcfg.targets)] if isinstance(dcfg.targets, str) else [str(t) for t in dcfg.targets])
    ds = open_source(cfg)
    template = build_compensator(cfg)
    check_declared(cfg, ds)
    written: dict = {}

    def make_after(effects, excluded, inputs, alphas=None):
        written["kept"] = [c for c in inputs if c not in set(excluded)] if excluded else None
        written["model"] = outputs.diagnosed_model(
            _container(cfg.model.estimator), _ati(cfg), str(cfg.data.reference), effects,
            f"{cfg.model.name}+{MODEL_NAME}", alphas)
        return build_compensator(after_config(cfg, written["model"], written["kept"]))

    ati = _ati(cfg)
    named = "" if ati is None else f" ati={cfg.ati.name}"   # the ATI wrapper, said where used
    say(f"diagnosing {cfg.model.name}{named} ({cfg.select.name} inputs) on {ds.name}: "
        f"{len(ds.ids('train'))} train / {len(ds.ids('test'))} test campaigns")
    if str(cfg.eval.mode) != "simulation":
        logger.warning("diagnose: eval.mode=%s scores the test split only; the search's "
                       "cross-validation (cv_rmse, the bar) stays in simulation mode, what the "
                       "deployed compensator runs (diagnosis.json cv.mode)", cfg.eval.mode)
    with stage_run(cfg, "diagnose") as tracker:
        result = run_diagnosis(ds, template, targets, str(cfg.eval.mode), options, make_after,
                               str(cfg.eval.e_p95.statistic), cfg.eval.e_p95.get("max_points", 200),
                               model_name=str(cfg.model.name),
                               ati="none" if ati is None else str(cfg.ati.name),
                               deployed_of=_deployed_of(cfg, ds))
        folder, rerun, main = _write(cfg, ds, result, written, resolve(cfg.out))
        metrics, tags = outputs.tracked(result)
        tracker.log_metrics(metrics)
        tracker.set_tags(tags)
        tracker.log_artifact(main)
        tracker.log_artifacts(folder, "diagnosis")
    print(outputs.summary_table(result, named))
    say(f"diagnosis: {main}; report: {folder / 'report.html'}")
    say(f"rerun the diagnosed model: {rerun}")
    return result.to_json(result.primary)

