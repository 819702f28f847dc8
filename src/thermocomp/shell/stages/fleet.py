"""`thermocomp run data.group_by=<column>`: one compensator per machine of a fleet dataset.

Shared helper of ``stages/modelling.run`` (not a command of its own).  The
manifest is read once; then each group's campaigns (one machine's partitions)
are read, fitted on their train split, scored on their test split (and
validated on the train split, as a single run), and dropped before the next
group: memory grows with ``data.group_jobs`` (groups in flight, one process
each), not with the number of machines.  Outputs, staged and moved into
``out`` at the end like a single run's: ``metrics.json`` (per group and the
fleet summary), ``fleet.csv`` (one row per group and target) and
``models/<group>.pkl`` (signed).
"""

from __future__ import annotations

import copy
import time
from functools import partial

import numpy as np
import pandas as pd
from omegaconf import DictConfig
from sklearn.base import clone

from ...apps import fleet
from ...base.errors import ConfigError
from ...base.files import inside, safe_name, staged_outputs, write_json
from ...base.log import say
from ...base.paths import resolve
from ...core import continuation, io
from ...core.metrics import VALIDATION, pooled_scores, rsd, split_scores
from ...core.scoring.evaluation import (
    VAL_FOLDS,
    require_split,
    sample_period,
    split_residuals,
    validation_report,
)
from ...core.scoring.results import TEST_RMS_AFTER, TEST_RMS_BEFORE, TEST_RMSE, VAL_RMSE, TargetResult
from ..model_store import save_model
from ..source import resolve_reference
from ..tracking import stage_run
from .auto import add_choices
from .builders import build_compensator, validation_template
from .common import check_config, data_options


def _slim(targets: dict) -> dict:
    """The per-group figures kept in ``metrics.json`` (no curves: a fleet has hundreds of groups)."""
    out = {}
    for t, m in targets.items():
        out[t] = TargetResult(m).slim()
        if "auto" in m:      # model=auto: the group's choice, as a single run reports it
            out[t]["auto"] = m["auto"]
    return out


def _group(cfg: DictConfig, root, group: str, ids: list[str], stage) -> dict:
    """Read, fit, score and save one group; returns its figures (nothing of its data)."""
    # its own copy: data.reference=auto is resolved per group, and the groups of one process
    # (data.group_jobs=1) share the caller's config
    cfg = copy.deepcopy(cfg)
    ds, report = io.read_dataset(root, data_options(cfg), campaigns=ids)
    report["reference"] = resolve_reference(cfg, ds)
    train = require_split(ds, "train")
    require_split(ds, "test")
    t0 = time.perf_counter()
    comp = build_compensator(cfg, ds=ds).fit({c: ds.campaigns[c] for c in train})
    fit_s = time.perf_counter() - t0
    ev = cfg.eval
    targets, pooled = _scores(comp, ds, ev)
    add_choices(comp, targets)
    if ev.get("validation", True):
        template = validation_template(cfg, comp, ds)
        val = validation_report(partial(clone, template), ds, ev.mode, fitted=comp,
                                n_folds=int(ev.get("validation_folds", VAL_FOLDS)),
                                scheme=ev.get("validation_scheme", "auto"))
        for t, entry in val.items():
            targets[t][VALIDATION] = entry
    save_model(comp, inside(stage / "models", safe_name(group) + ".pkl"))
    targets = _slim(targets)
    say(f"{group}: {len(ids)} campaigns, {report['rows']} rows, fit {fit_s:.2f} s, test RMSE "
        + ", ".join(f"{t} {TargetResult(m).test.rmse:.2f}" for t, m in targets.items()))
    return {"campaigns": len(ids), "rows": int(report["rows"]), "fit_time_s": fit_s,
            "inputs": {t: comp.selected_[t] for t in comp.targets_}, "targets": targets,
            "pooled": pooled}


def _scores(comp, ds, ev) -> tuple[dict, dict]:
    """``(figures, pooled)`` of one group: its train and test figures (as a single run's), and
    what the fleet's pooled ``targets`` need of it: the test split's measured errors and
    residuals, and of each train campaign only its row count, sum of squared residuals and Rsd
    (the train split is most of the data; its pooled RMSE and SM/SD need no more)."""
    carried = continuation.carry_over(comp, ds)
    figures, pooled = {t: {} for t in comp.targets_}, {t: {} for t in comp.targets_}
    for split in ("train", "test"):
        ids = require_split(ds, split)
        dt = sample_period(ds, ids)
        for t, (y, r) in split_residuals(comp, ds, ids, ev.mode, carried)[2].items():
            figures[t][split] = split_scores(y, r, dt, ev.e_p95.statistic, ev.e_p95.max_points,
                                             with_before_after=(split == "test"))
            pooled[t][split] = ((y, r, dt) if split == "test" else
                                {c: (len(r[c]), float(np.sum(r[c] ** 2)), rsd(r[c])) for c in ids})
    return figures, pooled


def _fleet_targets(results: list[dict], ev) -> dict:
    """CLI.md's ``targets`` of ``metrics.json`` for the whole fleet: every group's campaigns, each
    predicted by its own group's model, pooled as one split (campaign ids are unique in the
    manifest)."""
    out = {}
    for t in results[0]["pooled"]:
        train = {c: v for r in results for c, v in r["pooled"][t]["train"].items()}
        n, ss = sum(v[0] for v in train.values()), sum(v[1] for v in train.values())
        y = {c: a for r in results for c, a in r["pooled"][t]["test"][0].items()}
        res = {c: a for r in results for c, a in r["pooled"][t]["test"][1].items()}
        dt = float(np.median([r["pooled"][t]["test"][2] for r in results]))
        out[t] = {"train": pooled_scores(n, ss, [v[2] for v in train.values()]),
                  "test": split_scores(y, res, dt, ev.e_p95.statistic, ev.e_p95.max_points)}
    return out


def _table(metrics: dict) -> str:
    """Per target: groups, test RMSE mean / median / p95 / max, RMS before -> after (means)."""
    head = (f"model={metrics['model']}  mode={metrics['mode']}  dataset={metrics['dataset']}  "
            f"group_by={metrics['group_by']} ({len(metrics['groups'])} groups)")
    lines = [head, f"{'target':8} {'groups':>6}  test RMSE mean  median    p95    max   "
                   f"RMS before -> after (mean)   worst   (µm)", "-" * 96]
    for t, s in metrics["fleet"].items():
        rmse, before, after = s[TEST_RMSE], s[TEST_RMS_BEFORE], s[TEST_RMS_AFTER]
        lines.append(f"{t:8} {s['groups']:>6}  {rmse['mean']:14.2f} {rmse['median']:7.2f} "
                     f"{rmse['p95']:6.2f} {rmse['max']:6.2f}   {before['mean']:10.2f} -> "
                     f"{after['mean']:6.2f}            {s['worst_group']}")
    chosen = {t: s["chosen"] for t, s in metrics["fleet"].items() if s.get("chosen")}
    if chosen:        # model=auto: the families the groups chose
        lines.append("model=auto chose (groups): " + "; ".join(
            f"{t} " + ", ".join(f"{f} {n}" for f, n in c.items()) for t, c in chosen.items()))
    return "\n".join(lines)


def run_grouped(cfg: DictConfig) -> dict:
    """``run`` on a fleet: one compensator per value of the manifest column ``data.group_by``."""
    from joblib import delayed

    from ...base.lifetime import parallel

    check_config(cfg)
    column, jobs = str(cfg.data.group_by), cfg.data.get("group_jobs", 1)
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ConfigError(f"data.group_jobs must be an integer >= 1, got {jobs!r}")
    root = resolve(cfg.data.path)
    manifest = io.read_manifest(root, io.ReadOptions.from_cfg(data_options(cfg)))
    members = fleet.groups(manifest, column, root / "campaigns.csv")
    say(f"reading {root}: {len(members)} groups by {column!r}, {jobs} at a time")
    out = resolve(cfg.out)
    t0 = time.perf_counter()
    with stage_run(cfg, "run") as tr:
        with staged_outputs(out) as stage:
            results = parallel(jobs)(delayed(_group)(cfg, root, g, ids, stage)
                                            for g, ids in members.items())
            targets = _fleet_targets(results, cfg.eval)
            for r in results:
                del r["pooled"]
            per_group = dict(zip(members, results))
            table = pd.DataFrame([row for g, r in per_group.items()
                                  for row in fleet.machine_rows(g, r["targets"])])
            metrics = {"model": cfg.model.name, "mode": cfg.eval.mode, "select": cfg.select.name,
                       "dataset": root.name, "group_by": column, "targets": targets,
                       "fleet": fleet.summary(table),
                       "groups": per_group, "fit_time_s": sum(r["fit_time_s"] for r in results),
                       "wall_time_s": time.perf_counter() - t0}
            table.to_csv(stage / "fleet.csv", index=False)
            write_json(stage / "metrics.json", metrics)
        tr.log_metrics({"fit_time_s": metrics["fit_time_s"], "groups": len(per_group),
                        **{f"{t}.fleet.{k}_{stat}": s[k][stat] for t, s in metrics["fleet"].items()
                           for k in (TEST_RMSE, VAL_RMSE) if s[k] for stat in ("mean", "p95", "max")}})
        tr.log_artifact(out / "metrics.json")
        tr.log_artifact(out / "fleet.csv")
    print(_table(metrics))
    say(f"metrics: {out / 'metrics.json'}, per group: {out / 'fleet.csv'}, models: {out / 'models'}")
    return metrics
