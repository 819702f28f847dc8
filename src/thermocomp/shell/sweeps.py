"""A Hydra multirun as MLflow sees it: the parent run of a sweep and one row per child run.

Shared by ``thermocomp compare`` (the table), ``thermocomp promote`` (the best
child) and the sweep callbacks (which write :data:`SWEEP_FILE` and hand a search
sweeper its :func:`objective`).
"""

from __future__ import annotations

import json
import tempfile
from pathlib import Path

from omegaconf import DictConfig

from ..base.errors import ConfigError
from ..base.paths import resolve
from ..core.scoring.leaderboard import (
    FIGURES,
    MEAN_OVER,
    VAL_FIGURES,
    mean_label,
    persistence_summary,
    summary,
    validation_method,
    validation_mode,
)
from ..core.scoring.results import DEPLOYED_MODE, VAL_RMSE
from .tracking import DATASET_TAG, child_runs, latest_sweep, retry_locked

# Written to the sweep folder by the callback: ``{"parent_run_id": ..., "overrides": [...]}``.
SWEEP_FILE = "sweep.json"

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
                              f"{cfg.tracking_uri}; run `thermocomp run -m ...` first (runs "
                              "made one at a time: promote one with promote.run_id=<its MLflow "
                              "run id>)")
        return found
    path = resolve(str(sweep))
    if path.is_dir():
        path = path / SWEEP_FILE
    folder = path.is_file()
    run_id = json.loads(path.read_text())["parent_run_id"] if folder else str(sweep)
    try:
        retry_locked(client.get_run, run_id)
    except Exception as exc:
        raise ConfigError(
            f"compare.sweep={sweep}: its parent run {run_id} is not in {cfg.tracking_uri} (the "
            "sweep was tracked in another store: give its tracking_uri)" if folder else
            f"compare.sweep={sweep!r} is neither a sweep folder with {SWEEP_FILE} nor a run id "
            f"of {cfg.tracking_uri}") from exc
    return run_id


def sweep_folder(cfg: DictConfig, client, run_id: str) -> Path | None:
    """The folder of the sweep ``run_id`` (``compare.sweep`` when a folder, else the folder its
    parent run recorded in the ``sweep.dir`` tag), None when it is not on this machine."""
    given = cfg.compare.get("sweep")
    if given is not None and resolve(str(given)).is_dir():
        return resolve(str(given))
    recorded = retry_locked(client.get_run, run_id).data.tags.get("sweep.dir")
    return resolve(recorded) if recorded and resolve(recorded).is_dir() else None


def objective(metrics: dict, criterion: str = VAL_RMSE, target: str = "mean") -> float:
    """The number a search sweeper minimises for one run: ``criterion`` of ``target`` from the
    run's ``metrics.json`` (as :func:`sweep_rows` ranks it), NaN when the run has none.

    Parameters
    ----------
    metrics : dict
        What ``thermocomp run`` returns (its ``metrics.json``).
    criterion : str
        A validation figure (``val_rmse``, ``val_rsd_mean``, ``val_rsd_sd``).
    target : str
        One ``E_`` column, or ``mean`` over targets.
    """
    try:
        value = summary(metrics["targets"], target)[criterion]
    except KeyError as exc:
        raise ConfigError(f"promote.target / promote.criterion: {exc.args[0]}") from None
    return float("nan") if value is None else float(value)


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


def _datasets(children: list) -> dict[str, str]:
    """``{run_id: dataset}`` where the runs were scored on more than one dataset (their
    ``data.path``'s name; with the digest where two differ under one name), else ``{}``."""
    digests = {r.info.run_id: r.data.tags.get(DATASET_TAG) for r in children}
    if len(set(digests.values())) < 2:
        return {}
    names = {d: Path(str(r.data.params.get("data.path", ""))).name or "?" for r in children
             for d in [digests[r.info.run_id]]}
    shared = {n for n in names.values() if list(names.values()).count(n) > 1}
    return {run: names[d] if names[d] not in shared else f"{names[d]} ({(d or 'none')[:8]})"
            for run, d in digests.items()}


def failed_jobs(client, parent_id: str) -> tuple[int, int]:
    """``(failed, jobs)`` of a sweep as its parent run counted them when it ended (the metrics
    ``sweep.failed_jobs``, ``sweep.jobs``; ``(0, 0)`` for a sweep still running or older): a job
    refused on its data has no child run, so the table of the children alone cannot tell."""
    metrics = retry_locked(client.get_run, parent_id).data.metrics
    return int(metrics.get("sweep.failed_jobs", 0)), int(metrics.get("sweep.jobs", 0))


def failed_note(failed: int, jobs: int) -> str:
    """What a table or a choice of a sweep with failed jobs says of them ("" when none did)."""
    return f"{failed} of its {jobs} jobs failed" if failed else ""


def sweep_rows(client, uri: str, parent_id: str, target: str = "mean",
               baselines: list | None = None) -> list[dict]:
    """One row per child run of ``parent_id`` (unsorted); its ``val_*`` figures are of the
    deployed (simulation) mode, ``val_mode`` says so (or names the fallback of an old run); the
    reported test figures are of the run's own ``eval.mode``, ``test_mode`` says which.

    ``baselines``, when given, receives each run's persistence figures
    (:func:`~thermocomp.core.scoring.leaderboard.persistence_summary`, None when absent).
    Runs of a sweep over several datasets get a ``dataset`` column, their baselines too.
    """
    children = child_runs(client, parent_id)
    varied = _varied([r.data.params for r in children])
    datasets = _datasets(children)
    rows = []
    for r in children:
        p = r.data.params
        row = {"run_id": r.info.run_id, "status": r.info.status}
        if datasets:
            row["dataset"] = datasets[r.info.run_id]
        row.update({col: p.get(key, "none" if col in ("ati", "denoise") else None)
                    for key, col in _NAMED.items()})
        row["settings"] = " ".join(f"{k}={p.get(k)}" for k in varied)
        metrics = run_metrics(r.info.run_id, uri)
        try:
            figures = (summary(metrics["targets"], target) if metrics
                       else dict.fromkeys((*VAL_FIGURES, *FIGURES)))
            method = validation_method(metrics["targets"], target) if metrics else None
        except KeyError as exc:
            raise ConfigError(f"compare.target: {exc.args[0]}") from None
        label = mean_label(metrics["targets"], target) if metrics else target
        if label != target:
            row[MEAN_OVER] = label      # a mean with the µm/m targets left out
        row.update({f: figures[f] for f in VAL_FIGURES})     # what ranks, then what is reported
        row["val_method"] = method
        row["val_mode"] = validation_mode(metrics) if metrics else None   # simulation, or a fallback
        # the reported test figures are of the run's own eval.mode: a one_step run's beside the
        # simulation-mode validation read 0.62 µm where the same model deploys at 2.21 (audit96b)
        row["test_mode"] = metrics.get("mode", DEPLOYED_MODE) if metrics else None
        row.update({f: figures[f] for f in FIGURES})
        if baselines is not None:
            base = persistence_summary(metrics["targets"], target) if metrics else None
            if base:     # whose it is: a late first probe's label is completed per model
                base["run_id"] = r.info.run_id
            baselines.append({**base, "dataset": datasets[r.info.run_id]} if base and datasets else base)
        row["fit_time_s"] = r.data.metrics.get("fit_time_s")
        rows.append(row)
    return rows
