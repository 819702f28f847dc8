"""A dataset of many machines: one model per group of campaigns, the fleet summed up (pure core).

A fleet is one dataset folder whose manifest has a metadata column naming the
machine of each campaign (DATA_FORMAT.md allows extra manifest columns, e.g.
``machine``).  ``data.group_by=machine`` fits and scores one compensator per
machine on that machine's train and test campaigns; only one machine's
campaigns are in memory at a time per worker.  Here: the groups of a manifest
and the figures of one machine and the fleet's across machines, its table; the stage
that reads, fits and writes is ``stages/fleet.py``.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..base.errors import ContractError
from ..base.tables import name_width
from ..core import continuation
from ..core.metrics import pooled_scores, rsd, split_scores
from ..core.models.auto import add_choices
from ..core.scoring.evaluation import require_split, sample_period, split_residuals
from ..core.scoring.results import (
    HEADLINES,
    TEST_RMS_AFTER,
    TEST_RMS_BEFORE,
    TEST_RMSE,
    VAL_RMSE,
    TargetResult,
)

# per target and machine: what the fleet table lists (µm)
COLUMNS = tuple(name for name, _, _ in HEADLINES["fleet"])


def groups(manifest: pd.DataFrame, column: str, path=None) -> dict[str, list[str]]:
    """``{group: [campaign ids]}`` in manifest order, from the manifest column ``column``.

    Raises
    ------
    ContractError
        No such column, or an empty cell (naming the first such campaign's row).
    """
    if column not in manifest.columns:
        raise ContractError(f"data.group_by={column!r}: no such manifest column (columns: "
                            f"{', '.join(map(str, manifest.columns))})", file=path)
    values = manifest[column]
    empty = values.isna() | (values.astype(str).str.strip() == "")
    if empty.any():
        row = int(np.flatnonzero(empty.to_numpy())[0]) + 1
        raise ContractError(f"empty {column!r} for campaign {manifest.index[row - 1]!r}",
                            file=path, column=column, row=row)
    out: dict[str, list[str]] = {}
    for cid, group in values.astype(str).items():
        out.setdefault(group, []).append(str(cid))
    return out


def require_splits(manifest: pd.DataFrame, members: dict[str, list[str]], column: str,
                   path=None) -> None:
    """Every group has a train and a test campaign, checked on the manifest before any group
    is read: a machine without one was refused only when its turn came, after the others were
    fitted, as "the dataset has no 'train' campaign" (the dataset had; the machine had not).

    Raises
    ------
    ContractError
        Naming the first such group, its campaigns with their splits, and the fix.
    """
    split = dict(zip(manifest.index.astype(str), manifest["split"].astype(str)))  # ids as groups() gives them
    for group, ids in members.items():
        lacking = [s for s in ("train", "test") if s not in {split[c] for c in ids}]
        if lacking:
            have = ", ".join(f"{c} {split[c]}" for c in ids[:5]) + (" ..." if len(ids) > 5 else "")
            raise ContractError(
                f"data.group_by={column}: {column} {group!r} has no {' and no '.join(map(repr, lacking))} "
                f"campaign ({len(ids)} campaign(s): {have}); each {column} is fitted on its own "
                f"train campaigns and scored on its own test campaigns: give it both (`split` in "
                f"the manifest, data.split_overrides) or leave its campaigns out of the folder",
                file=path, column="split")


def machine_rows(group: str, targets: dict) -> list[dict]:
    """One row per target of one group from its ``metrics.json``-like ``targets`` block."""
    rows = []
    for t, m in targets.items():
        rows.append({"group": group, "target": t, **TargetResult(m).headline("fleet")})
        if "auto" in m:          # model=auto: the family the group's validation chose
            rows[-1]["chosen"] = m["auto"]["chosen"]
    return rows


def summary(table: pd.DataFrame) -> dict:
    """Per target and figure of :data:`COLUMNS`: mean, median, 95th percentile and max over groups,
    the worst group by test RMSE and (model=auto) how many groups chose each family."""
    out = {}
    for t, rows in table.groupby("target", sort=True):
        entry = {"groups": int(len(rows))}
        for col in COLUMNS:
            v = pd.to_numeric(rows[col], errors="coerce").dropna().to_numpy(float)
            entry[col] = (None if not len(v) else
                          {"mean": float(v.mean()), "median": float(np.median(v)),
                           "p95": float(np.percentile(v, 95)), "max": float(v.max())})
        worst = pd.to_numeric(rows[TEST_RMSE], errors="coerce")
        entry["worst_group"] = None if worst.isna().all() else str(rows.loc[worst.idxmax(), "group"])
        if "chosen" in rows.columns:
            entry["chosen"] = {str(k): int(n) for k, n in rows["chosen"].value_counts().items()}
        out[str(t)] = entry
    return out


def slim(targets: dict) -> dict:
    """The per-group figures kept in ``metrics.json`` (no curves: a fleet has hundreds of groups)."""
    out = {}
    for t, m in targets.items():
        out[t] = TargetResult(m).slim()
        if "auto" in m:      # model=auto: the group's choice, as a single run reports it
            out[t]["auto"] = m["auto"]
    return out


def group_scores(comp, ds, mode: str, statistic: str, max_points: int) -> tuple[dict, dict]:
    """``(figures, pooled)`` of one group: its train and test figures (as a single run's, with
    model=auto's choices), and
    what the fleet's pooled ``targets`` need of it: the test split's measured errors and
    residuals, and of each train campaign only its row count, sum of squared residuals and Rsd
    (the train split is most of the data; its pooled RMSE and SM/SD need no more)."""
    carried = continuation.carry_over(comp, ds)
    figures, pooled = {t: {} for t in comp.targets_}, {t: {} for t in comp.targets_}
    for split in ("train", "test"):
        ids = require_split(ds, split)
        dt = sample_period(ds, ids)
        for t, (y, r) in split_residuals(comp, ds, ids, mode, carried)[2].items():
            figures[t][split] = split_scores(y, r, dt, statistic, max_points,
                                             with_before_after=(split == "test"))
            pooled[t][split] = ((y, r, dt) if split == "test" else
                                {c: (int(np.count_nonzero(~np.isnan(r[c]))),     # (a sparse target:
                                       float(np.nansum(r[c] ** 2)), rsd(r[c]))  # measured rows)
                                 for c in ids})
    return add_choices(comp, figures), pooled


def fleet_targets(results: list[dict], statistic: str, max_points: int) -> dict:
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
                  "test": split_scores(y, res, dt, statistic, max_points)}
    return out


def fleet_metrics(results: dict[str, dict], head: dict, statistic: str, max_points: int
                  ) -> tuple[dict, pd.DataFrame]:
    """(``metrics.json``, the per-group table ``fleet.csv``) of the groups' ``results`` (their
    pooled parts dropped); ``head``: model, mode, select, dataset, group_by."""
    targets = fleet_targets(list(results.values()), statistic, max_points)
    for r in results.values():
        del r["pooled"]
    table = pd.DataFrame([row for g, r in results.items() for row in machine_rows(g, r["targets"])])
    metrics = {**head, "targets": targets, "fleet": summary(table), "groups": results,
               "fit_time_s": sum(r["fit_time_s"] for r in results.values())}
    return metrics, table


def tracked(metrics: dict) -> dict:
    """The fleet's metrics for the tracker."""
    return {"fit_time_s": metrics["fit_time_s"], "groups": len(metrics["groups"]),
            **{f"{t}.fleet.{k}_{stat}": s[k][stat] for t, s in metrics["fleet"].items()
               for k in (TEST_RMSE, VAL_RMSE) if s[k] for stat in ("mean", "p95", "max")}}


def table_text(metrics: dict) -> str:
    """Per target: groups, test RMSE mean / median / p95 / max, RMS before -> after (means)."""
    head = (f"model={metrics['model']}  mode={metrics['mode']}  dataset={metrics['dataset']}  "
            f"group_by={metrics['group_by']} ({len(metrics['groups'])} groups)")
    w = name_width(metrics["fleet"])
    lines = [head, f"{'target':{w}} {'groups':>6}  test RMSE mean  median    p95    max   "
                   f"RMS before -> after (mean)   worst   (µm)", "-" * (88 + w)]
    for t, s in metrics["fleet"].items():
        rmse, before, after = s[TEST_RMSE], s[TEST_RMS_BEFORE], s[TEST_RMS_AFTER]
        lines.append(f"{t:{w}} {s['groups']:>6}  {rmse['mean']:14.2f} {rmse['median']:7.2f} "
                     f"{rmse['p95']:6.2f} {rmse['max']:6.2f}   {before['mean']:10.2f} -> "
                     f"{after['mean']:6.2f}            {s['worst_group']}")
    chosen = {t: s["chosen"] for t, s in metrics["fleet"].items() if s.get("chosen")}
    if chosen:        # model=auto: the families the groups chose
        lines.append("model=auto chose (groups): " + "; ".join(
            f"{t} " + ", ".join(f"{f} {n}" for f, n in c.items()) for t, c in chosen.items()))
    return "\n".join(lines)
