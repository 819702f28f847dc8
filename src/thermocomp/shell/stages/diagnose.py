"""`thermocomp diagnose`: closed loop -- residual -> missing effect -> refit -> before/after.

Reads ``data.path``, runs :func:`thermocomp.apps.diagnose.diagnose` on the
configured model and writes, under ``out``:

* ``diagnosis.json`` -- CLI.md layout, for the primary target (the one with
  the largest CV RMSE before);
* ``diagnosis/``: ``diagnosis_<target>.json`` for every target, ``report.md``
  and ``report.html`` (every target; the HTML embeds the figures), ``plots/``;
* ``diagnosis/conf/model/diagnosed.yaml`` -- the model plus the accepted
  effects -- and ``diagnosis/conf/experiment/diagnosed.yaml`` pinning what the
  diagnosis ran with, so ``thermocomp run hydra.searchpath=[file://<out>/diagnosis/conf]
  experiment=diagnosed data.path=...`` reproduces the "after" figures.

The diagnosed model is built from that very config (as ``run`` builds it), so
the figures in the report are the ones the rerun gives.
"""

from __future__ import annotations

import copy
import shlex
from pathlib import Path

import yaml
from omegaconf import DictConfig, OmegaConf

from ...apps.diagnose import CandidateOptions, SearchOptions
from ...apps.diagnose import diagnose as run_diagnosis
from ...apps.diagnose.augmented import MODEL_NAME
from ...apps.diagnose.features import KINDS
from ...apps.diagnose.figures import diagnosis_figures
from ...apps.diagnose.report import write_report
from ...base.errors import ConfigError
from ...base.files import atomic_dir, write_json
from ...base.log import logger, say
from ...base.params import (
    check_values,
    subset,
)
from ...base.paths import resolve
from ...core import io
from ...core.scoring.headline import DIAGNOSIS_HEADLINE, diagnosis_headline, write_headline
from ...core.scoring.results import TargetResult
from ..source import check_declared, resolve_reference
from ..tracking import stage_run
from . import rules
from .builders import build_compensator
from .common import check_config, data_options

# What each ``diagnose.*`` key may be: every stage checks rules.DIAGNOSE_RULES; the families are
# this stage's (``targets`` is also checked against the modelled targets).
DIAGNOSE_RULES = {**rules.DIAGNOSE_RULES, "families": subset(KINDS)}


def search_options(dcfg) -> SearchOptions:
    """``diagnose.*`` -> SearchOptions; a value outside its rule is a ConfigError (exit 2)."""
    check_values(dcfg, DIAGNOSE_RULES, "diagnose")
    return SearchOptions(
        max_effects=dcfg.max_effects, min_gain_pct=float(dcfg.min_gain_pct),
        alpha=float(dcfg.alpha), shortlist=dcfg.shortlist, n_folds=dcfg.n_folds,
        n_blocks=dcfg.n_blocks, seed=int(dcfg.seed), cv=str(dcfg.cv),
        min_train_fraction=float(dcfg.min_train_fraction), shrink=dcfg.shrink,
        candidates=CandidateOptions(taus_s=tuple(float(t) for t in dcfg.taus_s),
                                    n_squares=dcfg.n_squares, fault_ratio=float(dcfg.fault_ratio),
                                    families=tuple(dcfg.families),
                                    initial_directions=tuple(dcfg.initial_directions)))


def _container(node):
    return OmegaConf.to_container(node, resolve=True) if node is not None else None


def diagnosed_model(cfg: DictConfig, effects: dict, name: str, alphas: dict | None = None) -> dict:
    """The ``model`` config of the diagnosed model (an ATI wrapper moves inside it);
    ``alphas``: per target, the CV-chosen penalty on the effect features (MLR base)."""
    base = _container(cfg.model.estimator)
    ati = cfg.get("ati")
    if ati is not None and ati.get("estimator") is not None:
        inner = _container(ati.estimator)
        inner.pop("_partial_", None)
        inner["base_estimator"] = base
        base = inner
    return {"name": name, "estimator": {
        "_target_": "thermocomp.apps.diagnose.AugmentedRegressor", "_convert_": "all",
        "reference": str(cfg.data.reference),
        "effects": {t: [e.to_dict() for e in es] for t, es in effects.items()},
        "alpha": {t: float(a) for t, a in (alphas or {}).items() if a} or None,
        "estimator": base}}


def _kept_inputs(inputs: list[str], excluded) -> list[str]:
    return [c for c in inputs if c not in set(excluded)]


def after_config(cfg: DictConfig, model: dict, kept_inputs: list[str] | None) -> DictConfig:
    """``cfg`` with the diagnosed model, as the written experiment composes it."""
    out = copy.deepcopy(cfg)
    OmegaConf.set_struct(out, False)
    OmegaConf.update(out, "model", model, merge=False)
    if out.get("ati") is not None and out.ati.get("estimator") is not None:
        OmegaConf.update(out, "ati", {"name": "none", "estimator": None}, merge=False)
    if kept_inputs is not None:
        OmegaConf.update(out, "data.inputs", kept_inputs, merge=False)
    return out


def experiment(cfg: DictConfig, kept_inputs: list[str] | None) -> dict:
    """``conf/experiment/diagnosed.yaml``: the diagnosed model with what the diagnosis ran with."""
    defaults = [{"override /model": MODEL_NAME}]
    if cfg.get("ati") is not None and cfg.ati.get("estimator") is not None:
        defaults.append({"override /ati": "none"})
    for group in ("select", "denoise"):
        node = cfg.get(group)
        if node is not None and node.get("name") is not None:
            defaults.append({f"override /{group}": str(node.name)})
    out: dict = {"defaults": defaults, "name": f"{cfg.name}-{MODEL_NAME}"}
    for group in ("select", "denoise"):
        if cfg.get(group) is not None:
            out[group] = _container(cfg[group])
    data = {"reference": str(cfg.data.reference)}
    if kept_inputs is not None:
        data["inputs"] = list(kept_inputs)
    out["data"] = data
    out["eval"] = {"mode": str(cfg.eval.mode)}
    return out


def rerun_command(cfg: DictConfig, conf_dir: Path, out: Path, kept_inputs) -> str:
    """The ``thermocomp run`` that reproduces the "after" figures: the written experiment, and
    how this diagnosis read its data, the user's own search path, ``data=`` config and
    ``data.*`` overrides included (without them a lab's ';'-separated files were refused)."""
    from hydra.core.hydra_config import HydraConfig

    from ..tracking import _split, task_overrides

    paths, data_config = [], None
    if HydraConfig.initialized():
        hc = HydraConfig.get()
        paths = [str(p) for p in (hc.searchpath or [])]
        data_config = hc.runtime.choices.get("data")
    pinned = {"data.path", "data.interim", "data.reference"} | (
        {"data.inputs"} if kept_inputs is not None else set())     # the experiment pins these
    extra = [o for o in task_overrides() or []
             if _split(o)[0].startswith("data.") and _split(o)[0] not in pinned]
    parts = ["thermocomp run", f"hydra.searchpath=[{','.join([*paths, f'file://{conf_dir}'])}]"]
    if data_config not in (None, "default"):
        parts.append(f"data={data_config}")
    parts += [f"experiment={MODEL_NAME}", *extra, f"data.path={resolve(cfg.data.path)}", f"out={out}"]
    return " ".join(shlex.quote(p) if i else p for i, p in enumerate(parts))


def _yaml(header: str, body: dict) -> str:
    return header + yaml.safe_dump(body, sort_keys=False, allow_unicode=True, width=100)


def _write(cfg: DictConfig, ds, result, written: dict, out: Path) -> tuple[Path, str, Path]:
    """``diagnosis.json``, its headline and the ``diagnosis/`` folder (per-target JSONs,
    the config to rerun the diagnosed model, figures, report): (folder, rerun, diagnosis.json)."""
    out.mkdir(parents=True, exist_ok=True)
    folder = out / "diagnosis"
    conf_dir = folder / "conf"
    rerun = rerun_command(cfg, conf_dir, out / MODEL_NAME, written.get("kept"))
    primary = result.primary
    jsons = {}
    for t in result.targets:
        j = result.to_json(t)
        j.update(config=str(conf_dir / "model" / f"{MODEL_NAME}.yaml"),
                 experiment=str(conf_dir / "experiment" / f"{MODEL_NAME}.yaml"),
                 rerun=rerun, report=str(folder / "report.html"))
        jsons[t] = j
    with atomic_dir(folder) as tmp:
        figures = diagnosis_figures(result, tmp / "plots") if cfg.plots != "none" else {}
        header = (f"# Written by `thermocomp diagnose` on {ds.name}: {cfg.model.name} + the effects "
                  f"it accepted.\n# Rerun: {rerun}\n")
        (tmp / "conf" / "model").mkdir(parents=True)
        (tmp / "conf" / "experiment").mkdir(parents=True)
        (tmp / "conf" / "model" / f"{MODEL_NAME}.yaml").write_text(_yaml(header, written["model"]))
        (tmp / "conf" / "experiment" / f"{MODEL_NAME}.yaml").write_text(
            _yaml("# @package _global_\n" + header, experiment(cfg, written["kept"])))
        for t, j in jsons.items():
            write_json(tmp / f"diagnosis_{t}.json", j)
        write_report(tmp, jsons, {t: [f"plots/{p.name}" for p in ps] for t, ps in figures.items()},
                     rerun, primary)
    main = write_json(out / "diagnosis.json", jsons[primary])
    write_headline(out / DIAGNOSIS_HEADLINE, diagnosis_headline(jsons))  # `dvc metrics show`
    return folder, rerun, main


def _track(tracker, result, main: Path, folder: Path) -> None:
    tracker.log_metrics({"diagnose": {t: {
        "before_test_rmse": TargetResult(d.before).test.rmse,
        "after_test_rmse": TargetResult(d.after).test.rmse,
        "before_cv_rmse": d.original_cv_rmse, "after_cv_rmse": d.final_cv_rmse,
        "n_accepted": len(d.accepted)} for t, d in result.targets.items()},
        "diagnose_seconds": result.seconds})
    tracker.set_tags({"diagnose.primary": result.primary,
                      "diagnose.accepted": "; ".join(
                          f"{t}: {ev.effect.kind} {ev.effect.column or ''} {ev.effect.label}"
                          for t, d in result.targets.items() for ev in d.accepted) or "none"})
    tracker.log_artifact(main)
    tracker.log_artifacts(folder, "diagnosis")


def diagnose(cfg: DictConfig) -> dict:
    """Diagnose the configured model on ``data.path``; write the report under ``out``."""
    check_config(cfg)
    if cfg.get("diagnose") is None:
        raise ConfigError("no `diagnose` config group (conf/diagnose/default.yaml)")
    dcfg = cfg.diagnose
    options = search_options(dcfg)
    targets = None if dcfg.targets is None else (
        [str(dcfg.targets)] if isinstance(dcfg.targets, str) else [str(t) for t in dcfg.targets])
    say(f"reading {resolve(cfg.data.path)}")
    ds, _ = io.read_dataset(resolve(cfg.data.path), data_options(cfg))
    resolve_reference(cfg, ds)
    template = build_compensator(cfg)
    check_declared(cfg, ds)
    name = f"{cfg.model.name}+{MODEL_NAME}"
    written: dict = {}

    def make_after(effects, excluded, inputs, alphas=None):
        kept = _kept_inputs(inputs, excluded) if excluded else None
        written["model"] = diagnosed_model(cfg, effects, name, alphas)
        written["kept"] = kept
        return build_compensator(after_config(cfg, written["model"], kept))

    say(f"diagnosing {cfg.model.name} ({cfg.select.name} inputs) on {ds.name}: "
        f"{len(ds.ids('train'))} train / {len(ds.ids('test'))} test campaigns")
    if str(cfg.eval.mode) != "simulation":
        logger.warning("diagnose: eval.mode=%s scores the test split only; the search's "
                       "cross-validation (cv_rmse, the bar) stays in simulation mode, what the "
                       "deployed compensator runs (diagnosis.json cv.mode)", cfg.eval.mode)
    with stage_run(cfg, "diagnose") as tracker:
        result = run_diagnosis(ds, template, targets, str(cfg.eval.mode), options, make_after,
                               str(cfg.eval.e_p95.statistic), cfg.eval.e_p95.get("max_points", 200),
                               model_name=str(cfg.model.name))
        out = resolve(cfg.out)
        folder, rerun, main = _write(cfg, ds, result, written, out)
        _track(tracker, result, main, folder)
    print(summary_table(result))
    say(f"diagnosis: {main}; report: {folder / 'report.html'}")
    say(f"rerun the diagnosed model: {rerun}")
    return result.to_json(result.primary)


def summary_table(result) -> str:
    """What the stage prints: per target, test RMSE before -> after and the accepted effects."""
    lines = [f"model={result.model}  dataset={result.dataset}  mode={result.mode}"
             + ("" if result.mode == "simulation" else " (test; CV: simulation)"),
             f"{'target':<8} {'test RMSE before':>16} -> {'after':>6}   {'CV before':>9} -> {'after':>6}"
             "   accepted effects", "-" * 96]
    for t, d in result.targets.items():
        acc = ", ".join(f"{ev.effect.kind}:{ev.effect.column or '-'} {ev.effect.label}"
                        for ev in d.accepted) or "none"
        before, after = TargetResult(d.before).test.rmse, TargetResult(d.after).test.rmse
        lines.append(f"{t:<8} {before:>16.2f} -> {after:>6.2f}   "
                     f"{d.original_cv_rmse:>9.2f} -> {d.final_cv_rmse:>6.2f}   {acc}")
    cv = result.cv
    lines.append(f"acceptance test: {cv['test_blocks']} time blocks of ~{cv['block_samples']} samples "
                 f"in {cv['units']} CV units; smallest reachable p {cv['min_p']:.2g} "
                 f"(alpha {result.options.alpha:g})")
    return "\n".join(lines)
