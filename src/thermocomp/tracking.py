"""MLflow logging for stage runs (the shell's only door to MLflow).

The store is SQLite (``sqlite:///mlruns/mlflow.db``, resolved against the
project root) with artifacts under ``mlruns/<experiment>/``: MLflow 3 refuses
the plain-file store, and the model registry needs a database anyway.  A team
points ``tracking_uri`` at an MLflow server (``http://host:5000``, PostgreSQL
behind it); nothing else changes.

Sweeps: a Hydra callback (:mod:`thermocomp.callbacks`) opens one *parent* run
per sweep and exports its id as ``THERMOCOMP_PARENT_RUN_ID``; every job's stage
run becomes its child (jobs in other processes inherit the variable).  Parallel
jobs on one SQLite file contend for its write lock: every MLflow call here is
retried with exponential backoff on ``database is locked``.
"""

from __future__ import annotations

import logging
import math
import os
import random
import time
from contextlib import contextmanager
from pathlib import Path

from omegaconf import DictConfig, OmegaConf

from .paths import project_root, resolve

DEFAULT_URI = "sqlite:///mlruns/mlflow.db"
PARENT_ENV = "THERMOCOMP_PARENT_RUN_ID"
SWEEP_TAG = "thermocomp.sweep"          # "parent" on a sweep's parent run
_LOCKED = ("database is locked", "database table is locked")


def _is_locked(exc: BaseException) -> bool:
    seen = set()
    while exc is not None and id(exc) not in seen:
        seen.add(id(exc))
        if any(m in str(exc) for m in _LOCKED):
            return True
        exc = exc.__cause__ or exc.__context__
    return False


def retry_locked(fn, *args, attempts: int = 12, base_delay: float = 0.05,
                 max_delay: float = 3.0, **kwargs):
    """``fn(*args, **kwargs)``, retried with jittered exponential backoff while
    SQLite answers ``database is locked`` (parallel sweep jobs on one store)."""
    for attempt in range(attempts):
        try:
            return fn(*args, **kwargs)
        except Exception as exc:
            if attempt == attempts - 1 or not _is_locked(exc):
                raise
            time.sleep(min(max_delay, base_delay * 2**attempt) * random.uniform(0.5, 1.5))


def resolve_uri(uri: str) -> str:
    """Make a relative ``sqlite:///path`` absolute (against the project root)."""
    prefix = "sqlite:///"
    if uri.startswith(prefix) and not uri.startswith(prefix + "/"):
        path = resolve(uri[len(prefix):])
        path.parent.mkdir(parents=True, exist_ok=True)
        return prefix + str(path)
    return uri


def artifact_root(uri: str, experiment: str) -> str | None:
    """Artifacts next to a SQLite store, under ``mlruns/``; a server decides its own."""
    if uri.startswith("sqlite:"):
        db = Path(uri[len("sqlite:///"):])
        return (db.parent / experiment).as_uri()
    return None


def flatten(d, prefix: str = "", sep: str = ".") -> dict:
    """Nested dict -> {'a.b.c': scalar}; lists and None are skipped."""
    out = {}
    for k, v in d.items():
        key = f"{prefix}{sep}{k}" if prefix else str(k)
        if isinstance(v, dict):
            out.update(flatten(v, key, sep))
        elif isinstance(v, bool) or v is None or isinstance(v, (list, tuple)):
            continue
        elif isinstance(v, (int, float)):
            out[key] = v
    return out


class _Null:
    """Tracker used with ``track=false``: every call is a no-op."""

    run_id = None

    def log_metrics(self, metrics: dict) -> None: ...
    def log_artifact(self, path) -> None: ...
    def log_artifacts(self, path, artifact_path=None) -> None: ...
    def set_tags(self, tags: dict) -> None: ...


class _Tracker(_Null):
    def __init__(self, mlflow, run):
        self._mlflow, self.run_id = mlflow, run.info.run_id

    def log_metrics(self, metrics: dict) -> None:
        clean = {k.replace(" ", "_"): float(v) for k, v in flatten(metrics).items()
                 if math.isfinite(float(v))}
        if clean:
            retry_locked(self._mlflow.log_metrics, clean)

    def log_artifact(self, path) -> None:
        retry_locked(self._mlflow.log_artifact, str(path))

    def log_artifacts(self, path, artifact_path=None) -> None:
        retry_locked(self._mlflow.log_artifacts, str(path), artifact_path)

    def set_tags(self, tags: dict) -> None:
        retry_locked(self._mlflow.set_tags, {k: str(v) for k, v in tags.items()})


def _quiet_mlflow() -> None:
    # Alembic prints every migration step when the SQLite store is created.
    for name in ("alembic", "mlflow.store.db.utils", "mlflow.tracking.fluent"):
        logging.getLogger(name).setLevel(logging.WARNING)


def connect(cfg) -> str:
    """Point MLflow at ``cfg.tracking_uri`` (resolved); returns the URI."""
    os.environ.setdefault("MLFLOW_ENABLE_ARTIFACTS_PROGRESS_BAR", "false")
    import mlflow

    _quiet_mlflow()
    uri = resolve_uri(str(cfg.get("tracking_uri") or DEFAULT_URI))
    mlflow.set_tracking_uri(uri)
    return uri


def client(cfg):
    """An ``MlflowClient`` on ``cfg.tracking_uri``; stages that read runs need ``track=true``."""
    if not cfg.get("track", True):
        from .errors import ConfigError

        raise ConfigError("this stage reads MLflow runs: it needs track=true")
    from mlflow import MlflowClient

    return MlflowClient(connect(cfg))


def experiment_id(uri: str, name: str) -> str:
    """Id of experiment ``name``, created (with artifacts under ``mlruns/``) if missing.

    Safe when parallel jobs race to create it.
    """
    import mlflow

    exp = retry_locked(mlflow.get_experiment_by_name, name)
    if exp is not None:
        return exp.experiment_id
    try:
        return retry_locked(mlflow.create_experiment, name,
                            artifact_location=artifact_root(uri, name))
    except Exception:  # another job created it meanwhile
        exp = retry_locked(mlflow.get_experiment_by_name, name)
        if exp is None:
            raise
        return exp.experiment_id


def config_container(cfg: DictConfig) -> dict:
    container = OmegaConf.to_container(cfg, resolve=True)
    container.pop("hydra", None)
    return container


@contextmanager
def stage_run(cfg: DictConfig, stage: str):
    """An MLflow run for one stage, with the resolved config logged; yields a tracker.

    Inside a sweep (``THERMOCOMP_PARENT_RUN_ID`` set) the run is a child of the
    sweep's parent run.
    """
    if not cfg.get("track", True):
        yield _Null()
        return
    import mlflow

    uri = connect(cfg)
    exp_id = experiment_id(uri, str(cfg.get("experiment_name", "thermocomp")))
    tags = {"stage": stage, "run_name": str(cfg.get("name")), "project_root": str(project_root())}
    parent = os.environ.get(PARENT_ENV) or None
    run = retry_locked(mlflow.start_run, experiment_id=exp_id, run_name=f"{cfg.get('name')}/{stage}",
                       tags=tags, parent_run_id=parent)
    status = "FAILED"
    try:
        container = config_container(cfg)
        retry_locked(mlflow.log_dict, container, "config.yaml")
        params = list(_flat_params(container).items())
        for i in range(0, len(params), 100):
            retry_locked(mlflow.log_params, dict(params[i:i + 100]))
        yield _Tracker(mlflow, run)
        status = "FINISHED"
    finally:
        from .log import current_file  # the run's log so far (thermocomp.log), failed runs too

        if current_file() is not None and current_file().is_file():
            retry_locked(mlflow.log_artifact, str(current_file()))
        retry_locked(mlflow.end_run, status)


def start_parent_run(cfg: DictConfig, run_name: str, tags: dict | None = None) -> str:
    """Create (not activate) a sweep's parent run; returns its id."""
    from mlflow import MlflowClient

    uri = connect(cfg)
    exp_id = experiment_id(uri, str(cfg.get("experiment_name", "thermocomp")))
    all_tags = {SWEEP_TAG: "parent", "mlflow.runName": run_name,
                "project_root": str(project_root()), **(tags or {})}
    client = MlflowClient(uri)
    run = retry_locked(client.create_run, exp_id, tags={k: str(v) for k, v in all_tags.items()},
                       run_name=run_name)
    return run.info.run_id


def end_parent_run(cfg: DictConfig, run_id: str, status: str = "FINISHED",
                   metrics: dict | None = None) -> None:
    from mlflow import MlflowClient

    client = MlflowClient(connect(cfg))
    for k, v in (metrics or {}).items():
        retry_locked(client.log_metric, run_id, k, float(v))
    retry_locked(client.set_terminated, run_id, status)


def child_runs(client, parent_run_id: str) -> list:
    """Every run whose parent is ``parent_run_id`` (all pages), oldest first."""
    exp_id = retry_locked(client.get_run, parent_run_id).info.experiment_id
    runs, token = [], None
    while True:
        page = retry_locked(client.search_runs, [exp_id],
                            filter_string=f"tags.mlflow.parentRunId = '{parent_run_id}'",
                            max_results=1000, page_token=token, order_by=["attributes.start_time ASC"])
        runs.extend(page)
        token = page.token
        if not token:
            return runs


def latest_sweep(client, experiment_name: str) -> str | None:
    """Id of the most recent sweep parent run of the experiment, or None."""
    exp = retry_locked(client.get_experiment_by_name, experiment_name)
    if exp is None:
        return None
    runs = retry_locked(client.search_runs, [exp.experiment_id],
                        filter_string=f"tags.`{SWEEP_TAG}` = 'parent'",
                        order_by=["attributes.start_time DESC"], max_results=1)
    return runs[0].info.run_id if runs else None


def _flat_params(d, prefix=""):
    out = {}
    for k, v in d.items():
        key = f"{prefix}.{k}" if prefix else str(k)
        if isinstance(v, dict):
            out.update(_flat_params(v, key))
        else:
            out[key] = str(v)[:500]
    return out
