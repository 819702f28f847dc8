"""MLflow logging for stage runs (the shell's only door to MLflow).

The store is SQLite (``sqlite:///mlruns/mlflow.db``, resolved against the
project root) with artifacts under ``mlruns/<experiment>/``: MLflow 3 refuses
the plain-file store, and the model registry needs a database anyway.
"""

from __future__ import annotations

import logging
import math
import os
from contextlib import contextmanager
from pathlib import Path

from omegaconf import DictConfig, OmegaConf

from .paths import project_root, resolve

DEFAULT_URI = "sqlite:///mlruns/mlflow.db"


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
            self._mlflow.log_metrics(clean)

    def log_artifact(self, path) -> None:
        self._mlflow.log_artifact(str(path))

    def log_artifacts(self, path, artifact_path=None) -> None:
        self._mlflow.log_artifacts(str(path), artifact_path)

    def set_tags(self, tags: dict) -> None:
        self._mlflow.set_tags({k: str(v) for k, v in tags.items()})


def _quiet_mlflow() -> None:
    # Alembic prints every migration step when the SQLite store is created.
    for name in ("alembic", "mlflow.store.db.utils", "mlflow.tracking.fluent"):
        logging.getLogger(name).setLevel(logging.WARNING)


@contextmanager
def stage_run(cfg: DictConfig, stage: str):
    """An MLflow run for one stage, with the resolved config logged; yields a tracker."""
    if not cfg.get("track", True):
        yield _Null()
        return
    os.environ.setdefault("MLFLOW_ENABLE_ARTIFACTS_PROGRESS_BAR", "false")
    import mlflow

    _quiet_mlflow()
    uri = resolve_uri(str(cfg.get("tracking_uri") or DEFAULT_URI))
    mlflow.set_tracking_uri(uri)
    name = str(cfg.get("experiment_name", "thermocomp"))
    exp = mlflow.get_experiment_by_name(name)
    exp_id = exp.experiment_id if exp else mlflow.create_experiment(
        name, artifact_location=artifact_root(uri, name))
    tags = {"stage": stage, "run_name": str(cfg.get("name")), "project_root": str(project_root())}
    parent = os.environ.get("THERMOCOMP_PARENT_RUN_ID")
    with mlflow.start_run(experiment_id=exp_id, run_name=f"{cfg.get('name')}/{stage}",
                          tags=tags, parent_run_id=parent or None) as run:
        container = OmegaConf.to_container(cfg, resolve=True)
        container.pop("hydra", None)
        mlflow.log_dict(container, "config.yaml")
        params = {k: v for k, v in _flat_params(container).items()}
        for i in range(0, len(params), 100):
            mlflow.log_params(dict(list(params.items())[i:i + 100]))
        yield _Tracker(mlflow, run)


def _flat_params(d, prefix=""):
    out = {}
    for k, v in d.items():
        key = f"{prefix}.{k}" if prefix else str(k)
        if isinstance(v, dict):
            out.update(_flat_params(v, key))
        else:
            out[key] = str(v)[:500]
    return out
