"""A dataset of many machines: one model per group of campaigns, the fleet summed up (pure core).

A fleet is one dataset folder whose manifest has a metadata column naming the
machine of each campaign (DATA_FORMAT.md allows extra manifest columns, e.g.
``machine``).  ``data.group_by=machine`` fits and scores one compensator per
machine on that machine's train and test campaigns; only one machine's
campaigns are in memory at a time per worker.  Here: the groups of a manifest
and the fleet's figures across machines; the stage that reads, fits and
writes is ``stages/fleet.py``.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..base.errors import ContractError
from ..core.scoring.results import HEADLINES, TEST_RMSE, TargetResult

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
