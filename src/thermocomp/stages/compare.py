"""`thermocomp compare`: one table of every child run of a sweep, best first.

Columns: model, selection, ATI, test Rsd SM/SD, RMSE, RMS reduction, E_P95 of
the residual at 1 h / 8 h (``null`` when the campaigns are shorter), fit time,
and the settings that vary across the sweep.  Printed (Markdown), saved as
``compare.csv``, ``compare.md`` and ``compare.json`` (a DVC metric) under
``compare.out``, and logged as artifacts of the sweep's parent run.
"""

from __future__ import annotations

import json
import tempfile
from pathlib import Path

import pandas as pd
from omegaconf import DictConfig

from ..callbacks import SWEEP_FILE
from ..errors import ConfigError
from ..io.contract import atomic_write_text
from ..leaderboard import FIGURES, rank, summary, to_markdown
from ..paths import resolve
from ..tracking import child_runs, connect, latest_sweep, retry_locked
from ..tracking import client as mlflow_client
from .common import say, write_json

# Parameters shown as their own column, or never worth showing as a varied setting.
_NAMED = {"model.name": "model", "select.name": "select", "ati.name": "ati", "denoise.name": "denoise"}
_HIDDEN = {"out", "model_path", "name"}


def parent_run_id(cfg: DictConfig, client) -> str:
    """The sweep to compare: ``compare.sweep`` (run id or sweep folder), else the latest one."""
    sweep = cfg.compare.get("sweep")
    if sweep is None:
        found = latest_sweep(client, str(cfg.experiment_name))
        if found is None:
            raise ConfigError(f"no sweep in MLflow experiment {cfg.experiment_name!r} at "
                              f"{cfg.tracking_uri}; run `thermocomp run -m ...` first")
        return found
    path = resolve(str(sweep))
    if path.is_dir():
        path = path / SWEEP_FILE
    if path.is_file():
        return json.loads(path.read_text())["parent_run_id"]
    try:
        retry_locked(client.get_run, str(sweep))
    except Exception as exc:
        raise ConfigError(f"compare.sweep={sweep!r} is neither a sweep folder with {SWEEP_FILE} "
                          f"nor a run id of {cfg.tracking_uri}") from exc
    return str(sweep)


def run_metrics(run_id: str, uri: str) -> dict | None:
    """The ``metrics.json`` a run logged, or None."""
    import mlflow

    with tempfile.TemporaryDirectory() as tmp:
        try:
            path = mlflow.artifacts.download_artifacts(run_id=run_id, artifact_path="metrics.json",
                                                       dst_path=tmp, tracking_uri=uri)
        except Exception:
            return None
        return json.loads(Path(path).read_text())


def _varied(params: list[dict]) -> list[str]:
    """Parameters that differ across the runs, beyond the named config-group choices.

    A key missing from some runs only reflects their group choice (``model=pcr``
    has no ``max_inputs``), and the keys of a group whose choice varies are
    summed up by its name column: neither is shown.
    """
    groups = {key.split(".")[0] for key in _NAMED if len({p.get(key) for p in params}) > 1}
    keys = sorted({k for p in params for k in p})
    return [k for k in keys if k not in _NAMED and k not in _HIDDEN and not k.endswith("._target_")
            and not k.startswith("hydra") and k.split(".")[0] not in groups
            and all(k in p for p in params) and len({p[k] for p in params}) > 1]


def sweep_rows(client, uri: str, parent_id: str, target: str = "mean") -> list[dict]:
    """One row per child run of ``parent_id`` (unsorted)."""
    children = child_runs(client, parent_id)
    varied = _varied([r.data.params for r in children])
    rows = []
    for r in children:
        p = r.data.params
        row = {"run_id": r.info.run_id, "status": r.info.status}
        row.update({col: p.get(key, "none" if col in ("ati", "denoise") else None)
                    for key, col in _NAMED.items()})
        row["settings"] = " ".join(f"{k}={p.get(k)}" for k in varied)
        metrics = run_metrics(r.info.run_id, uri)
        try:
            figures = summary(metrics["targets"], target) if metrics else dict.fromkeys(FIGURES)
        except KeyError as exc:
            raise ConfigError(f"compare.target: {exc.args[0]}") from None
        row.update(figures)
        row["fit_time_s"] = r.data.metrics.get("fit_time_s")
        rows.append(row)
    return rows


def _json_table(table: pd.DataFrame, sort_by: str, target: str, parent_id: str) -> dict:
    records = json.loads(table.to_json(orient="records"))  # NaN -> null
    numeric = [c for c in (*FIGURES, "fit_time_s") if c in table.columns]
    return {"parent_run_id": parent_id, "sort_by": sort_by, "target": target,
            "n_runs": len(records),
            "best": {k: records[0][k] for k in ("run_id", "model", "select", *numeric)} if records else {},
            "runs": {f"{i:02d}_{r['run_id'][:8]}": {k: r[k] for k in numeric} for i, r in
                     enumerate(records)}}


def compare_sweep(cfg: DictConfig, parent_id: str, out=None) -> pd.DataFrame:
    """Rank the children of ``parent_id``; print, save and log the table."""
    client = mlflow_client(cfg)
    uri = connect(cfg)
    opts = cfg.compare
    rows = sweep_rows(client, uri, parent_id, str(opts.target))
    if not rows:
        raise ConfigError(f"sweep {parent_id} has no child runs")
    try:
        table = rank(rows, str(opts.sort_by), opts.get("descending"))
    except KeyError as exc:
        raise ConfigError(f"compare.sort_by: {exc.args[0]}") from None
    out = resolve(out if out is not None else opts.out)
    md = to_markdown(table.drop(columns=["run_id"]).assign(run=table["run_id"].str[:8]))
    out.mkdir(parents=True, exist_ok=True)
    atomic_write_text(out / "compare.csv", table.to_csv(index=False))
    atomic_write_text(out / "compare.md", md + "\n")
    write_json(out / "compare.json", _json_table(table, str(opts.sort_by), str(opts.target), parent_id))
    for name in ("compare.csv", "compare.md", "compare.json"):
        retry_locked(client.log_artifact, parent_id, str(out / name), "compare")
    print(f"sweep {parent_id}: {len(table)} runs, sorted by {opts.sort_by} "
          f"(target {opts.target}, test split)")
    print(md)
    say(f"comparison: {out / 'compare.md'}")
    return table


def compare(cfg: DictConfig) -> pd.DataFrame:
    """`thermocomp compare`: the comparison table of ``compare.sweep`` (default: latest sweep)."""
    client = mlflow_client(cfg)
    return compare_sweep(cfg, parent_run_id(cfg, client))
