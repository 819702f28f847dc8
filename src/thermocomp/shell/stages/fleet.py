"""`thermocomp run data.group_by=<column>`: one compensator per machine of a fleet dataset.

Called by ``stages/modelling.run``.  Each group's campaigns are read, fitted, scored and
validated as a single run's, and dropped before the next group (memory grows with
``data.group_jobs``, not with the machines).  Writes ``metrics.json`` (per group and the fleet,
:func:`thermocomp.apps.fleet.fleet_metrics`), ``fleet.csv`` and ``models/<group>.pkl`` (signed).
"""

from __future__ import annotations

import copy
import time
from functools import partial

from omegaconf import DictConfig
from sklearn.base import clone

from ...apps import fleet
from ...base.errors import ConfigError
from ...base.files import inside, safe_name, staged_outputs, write_json
from ...base.log import logger, say
from ...base.paths import resolve
from ...core import io
from ...core.metrics import VALIDATION
from ...core.models.hammerstein import without_states_note
from ...core.scoring.evaluation import VAL_FOLDS, require_split, validation_report
from ...core.scoring.results import TargetResult
from ..builders import validation_template
from ..chain import fit_chain
from ..config.checks import check_config, data_options
from ..model_store import save_model
from ..source import dataset_digest, is_volumetric, named_inputs_missing, open_source
from ..tracking import stage_run


def _group(cfg: DictConfig, digest: str, group: str, ids: list[str], stage) -> dict:
    """Read, fit, score and save one group; returns its figures (nothing of its data)."""
    # its own copy: data.reference=auto is resolved per group, and the groups of one process
    # (data.group_jobs=1) share the caller's config
    cfg = copy.deepcopy(cfg)
    ds = open_source(cfg, campaigns=ids, digest=digest)
    report = ds.meta["read_report"]
    require_split(ds, "train")
    require_split(ds, "test")
    t0 = time.perf_counter()
    comp = fit_chain(cfg, ds)       # as run fits one model
    fit_s = time.perf_counter() - t0
    ev = cfg.eval
    targets, pooled = fleet.group_scores(comp, ds, ev.mode, ev.e_p95.statistic, ev.e_p95.max_points)
    if ev.get("validation", True):
        template = validation_template(cfg, comp, ds)
        val = validation_report(partial(clone, template), ds, ev.mode, fitted=comp,
                                n_folds=int(ev.get("validation_folds", VAL_FOLDS)),
                                scheme=ev.get("validation_scheme", "auto"))
        for t, entry in val.items():
            targets[t][VALIDATION] = entry
    save_model(comp, inside(stage / "models", safe_name(group) + ".pkl"))
    notes = [n for n in (without_states_note(comp), named_inputs_missing(cfg, ds)) if n]
    for note in notes:                  # said per machine, as a single run says it
        logger.warning(f"{group}: {note}")
    targets = fleet.slim(targets)
    say(f"{group}: {len(ids)} campaigns, {report['rows']} rows, fit {fit_s:.2f} s, test RMSE "
        + ", ".join(f"{t} {TargetResult(m).test.rmse:.2f}" for t, m in targets.items()))
    return {"campaigns": len(ids), "rows": int(report["rows"]), "fit_time_s": fit_s,
            "inputs": {t: comp.selected_[t] for t in comp.targets_}, "targets": targets,
            "pooled": pooled, **({"warnings": notes} if notes else {})}


# what only a single run writes into ``out`` and what only a fleet's run does: ``out`` keeps
# the files a run does not write, so one kind of run into the other's folder leaves them there
SINGLE_RUN_OUTPUTS = ("model.pkl", "headline")
FLEET_RUN_OUTPUTS = ("fleet.csv", "models")


def warn_left_over(out, names: tuple[str, ...], kind: str) -> None:
    """Warn that ``out`` still holds ``names`` of an earlier ``kind`` run: beside this run's
    metrics.json they would read as its own (a fleet's metrics beside a single model)."""
    left = [n for n in names if (resolve(out) / n).exists()]
    if left:
        logger.warning(f"{resolve(out)} still holds {', '.join(left)} of an earlier {kind} run, "
                       "not this run's (a run leaves the files it does not write): delete them "
                       "or give each kind of run its own out=")


def run_grouped(cfg: DictConfig) -> dict:
    """``run`` on a fleet: one compensator per value of the manifest column ``data.group_by``."""
    from joblib import delayed

    from ...base.lifetime import parallel

    check_config(cfg)
    column, jobs = str(cfg.data.group_by), cfg.data.get("group_jobs", 1)
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ConfigError(f"data.group_jobs must be an integer >= 1, got {jobs!r}")
    root = resolve(cfg.data.path)
    if is_volumetric(cfg):
        # a group is read as a plain dataset: its ball distances would be the targets, one
        # model per distance, never calibrated into the error parameters the twin models
        raise ConfigError(
            f"file {root / 'volumetric.json'}: data.group_by={column} on a volumetric dataset: "
            "its groups would be fitted on the raw ball distances, not on the calibrated error "
            "parameters; run each machine's folder (its files, manifest rows and volumetric.json) "
            "without data.group_by")
    manifest = io.folder_splits(root, io.ReadOptions.from_cfg(data_options(cfg)))
    members = fleet.groups(manifest, column, root / "campaigns.csv")
    fleet.require_splits(manifest, members, column, root / "campaigns.csv")
    say(f"reading {root}: {len(members)} groups by {column!r}, {jobs} at a time")
    digest = dataset_digest(cfg)        # each group's: the folder digested once
    out, t0 = resolve(cfg.out), time.perf_counter()
    head = {"model": cfg.model.name, "mode": cfg.eval.mode, "select": cfg.select.name,
            "dataset": root.name, "group_by": column}
    with stage_run(cfg, "run") as tr:
        with staged_outputs(out) as stage:
            results = parallel(jobs)(delayed(_group)(cfg, digest, g, ids, stage)
                                     for g, ids in members.items())
            metrics, table = fleet.fleet_metrics(dict(zip(members, results)), head,
                                                 cfg.eval.e_p95.statistic, cfg.eval.e_p95.max_points)
            metrics["wall_time_s"] = time.perf_counter() - t0
            table.to_csv(stage / "fleet.csv", index=False)
            write_json(stage / "metrics.json", metrics)
        tr.log_metrics(fleet.tracked(metrics))
        tr.log_artifact(out / "metrics.json")
        tr.log_artifact(out / "fleet.csv")
    print(fleet.table_text(metrics))
    warn_left_over(out, SINGLE_RUN_OUTPUTS, "single (no data.group_by)")
    say(f"metrics: {out / 'metrics.json'}, per group: {out / 'fleet.csv'}, models: {out / 'models'}")
    return metrics
