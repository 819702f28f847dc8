"""MLflow logging for stage runs (the shell's only door to MLflow).

The store is SQLite (``sqlite:///mlruns/mlflow.db``, resolved against the
project root) with artifacts under ``mlruns/<experiment>/``: MLflow 3 refuses
the plain-file store, and the model registry needs a database anyway.  A team
points ``tracking_uri`` at an MLflow server (``http://host:5000``, PostgreSQL
behind it); nothing else changes.

Sweeps: a Hydra callback (:mod:`thermocomp.shell.callbacks`) opens one *parent* run
per sweep and exports its id as ``THERMOCOMP_PARENT_RUN_ID``; every job's stage
run becomes its child (jobs in other processes inherit the variable).  Parallel
jobs on one SQLite file contend for its write lock: every MLflow call here is
retried with exponential backoff on ``database is locked``, and a fresh store is
created by one process at a time under a file lock (``mlflow.db.lock`` next to it)
before any other MLflow call, as a copy of an empty store MLflow's Alembic migrations made once
per MLflow version and user (:func:`~thermocomp.shell.store.schema_template`).

What a run records: a name made of what differs from the defaults
(``mlr-pearson-seed1``, :func:`run_name`), the tag ``stage``, the meaningful
config leaves as params (:func:`run_params`; the whole config is the artifact
``config.yaml``), the headline metrics a user compares
(:meth:`~thermocomp.core.scoring.results.EvaluationResult.headline`;
the full ``metrics.json`` is an artifact).  A run ends FINISHED, FAILED on an
exception, KILLED on SIGTERM/SIGINT (then the process exits 143/130); one whose
process died without a word (SIGKILL, the OOM killer) is marked KILLED by the next
command that opens the store on the same machine (the run's ``thermocomp.pid``,
``thermocomp.host`` and ``thermocomp.process_start`` tags say whose it was).

``track``: ``null`` (default) logs every stage but ``simulate`` (a dataset is
not an experiment), ``true`` every stage, ``false`` none.
"""

from __future__ import annotations

import logging
import math
import os
from contextlib import contextmanager
from pathlib import Path

from omegaconf import DictConfig, OmegaConf

from ..base.files import Terminated, signals_raise
from ..base.log import logger
from ..base.paths import project_root, resolve
from . import store
from .config.naming import PARAM_KEYS, _split, run_name, run_params, sweep_name, task_overrides  # noqa: F401
from .store import (  # noqa: F401  (the store's URI checks and lock retries, used here and re-exported)
    DEFAULT_URI,
    _is_locked,
    check_reachable,
    enabled,
    resolve_uri,
    retry_locked,
    store_uri,
)

PARENT_ENV = "THERMOCOMP_PARENT_RUN_ID"
SWEEP_TAG = "thermocomp.sweep"          # "parent" on a sweep's parent run
DATASET_TAG = "dataset_hash"            # folder digest of data.path a run read


_READY: set[str] = set()    # stores this process has made sure exist


def ensure_store(uri: str) -> None:
    """Create (or upgrade) a SQLite store once, under an inter-process file lock.

    MLflow creates the schema with Alembic migrations when a client first opens
    an empty database; parallel processes on a fresh file race there and most
    fail.  The first process to take ``<db>.lock`` creates the store, the others
    find it ready.  MLflow caches the store per URI, so later clients reuse it.
    """
    if not uri.startswith("sqlite:///") or uri in _READY:
        return
    from filelock import FileLock
    from mlflow import MlflowClient

    db = Path(uri[len("sqlite:///"):])
    db.parent.mkdir(parents=True, exist_ok=True)
    with FileLock(f"{db}.lock", timeout=600):
        if not db.is_file() or db.stat().st_size == 0:
            store.create_store(db)
        else:
            store.check_schema(uri, db)
        try:
            retry_locked(MlflowClient(uri).search_experiments, max_results=1)
        except Exception:
            store.check_schema(uri, db, head=True)     # a store of another schema: one line
            raise
    _READY.add(uri)


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
        sig = Path(f"{path}.sig")          # a signed pickle travels with its signature
        if sig.is_file():
            retry_locked(self._mlflow.log_artifact, str(sig))

    def log_artifacts(self, path, artifact_path=None) -> None:
        retry_locked(self._mlflow.log_artifacts, str(path), artifact_path)

    def set_tags(self, tags: dict) -> None:
        retry_locked(self._mlflow.set_tags, {k: str(v) for k, v in tags.items()})


def _quiet_mlflow() -> None:
    # Alembic prints every migration step when the SQLite store is created.
    for name in ("alembic", "mlflow.store.db.utils", "mlflow.tracking.fluent"):
        logging.getLogger(name).setLevel(logging.WARNING)


def connect(cfg, existing: bool = False) -> str:
    """Point MLflow at ``cfg.tracking_uri`` (resolved); returns the URI.  ``existing``: the
    command only reads the store, which must be there (:func:`~thermocomp.shell.store.check_existing`).

    The first time in a process, runs left RUNNING by processes of this machine that are
    gone are marked KILLED (:func:`~thermocomp.shell.store.mark_orphan_runs`).
    """
    os.environ.setdefault("MLFLOW_ENABLE_ARTIFACTS_PROGRESS_BAR", "false")
    import mlflow

    _quiet_mlflow()
    uri = store_uri(cfg, existing)
    mlflow.set_tracking_uri(uri)
    ensure_store(uri)
    if uri not in _SWEPT:
        _SWEPT.add(uri)
        try:
            store.mark_orphan_runs(uri)
        except Exception as exc:   # housekeeping: never the reason a command fails
            from ..base.log import logger

            logger.warning("could not look for runs left RUNNING by dead processes: %s",
                           " ".join(str(exc).split())[:200])
    return uri


_SWEPT: set[str] = set()     # stores whose orphan runs this process has marked


def client(cfg, existing: bool = False):
    """An ``MlflowClient`` on ``cfg.tracking_uri``; stages that read runs need ``track`` on
    (``existing``: as :func:`connect`)."""
    if not enabled(cfg):
        from ..base.errors import ConfigError

        raise ConfigError("this stage reads MLflow runs: it needs tracking on "
                          "(track=null, the default, or track=true)")
    from mlflow import MlflowClient

    return MlflowClient(connect(cfg, existing))


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
def stage_run(cfg: DictConfig, stage: str, default: bool = True, digest: str | None = None,
              given_model: bool = False):
    """An MLflow run for one stage, with the meaningful config logged; yields a tracker.

    Inside a sweep (``THERMOCOMP_PARENT_RUN_ID`` set) the run is a child of the
    sweep's parent run.  ``default`` is whether the stage is tracked when
    ``track`` is null.  ``digest``: the ``data.path`` digest its caller already read
    (``meta["digest"]``), else it is digested here; ``given_model``: a saved model is streamed,
    the config's model params not logged (:func:`run_params`).  The run ends FINISHED, FAILED
    (an exception), or KILLED (SIGTERM -> exit 143, SIGINT -> exit 130).
    """
    if not enabled(cfg, default):
        yield _Null()
        return
    import mlflow

    uri = connect(cfg)
    exp_id = experiment_id(uri, str(cfg.get("experiment_name", "thermocomp")))
    overrides = task_overrides()
    tags = {"stage": stage, "run_name": str(cfg.get("name")), "project_root": str(project_root()),
            **store.process_tags()}
    if overrides is not None:
        tags["overrides"] = " ".join(overrides)[:5000]
    data = (cfg.get("data") or {}).get("path")
    data = resolve(str(data)) if data else None
    # what promote checks; a lab's one-file record (data.path a file) is digested as a
    # folder holding only it: untagged, a sweep on it was refused by promote
    if stage != "simulate" and data is not None and data.exists():
        from .source import dataset_digest

        tags[DATASET_TAG] = digest or dataset_digest(cfg)
    parent = os.environ.get(PARENT_ENV) or None
    with signals_raise(sigint=True) as signals:
        # A signal while the run is being created or closed waits for the end of that step:
        # cut there, the run would stay RUNNING in the store for ever.
        run, status = None, "FAILED"
        try:
            with signals.deferred():
                run = retry_locked(mlflow.start_run, experiment_id=exp_id, tags=tags,
                                   parent_run_id=parent, run_name=run_name(cfg, overrides))
            # its id is what promote.run_id / compare.sweep take, and what the MLflow UI lists
            logger.info(f"MLflow run {run.info.run_id} (experiment "
                        f"{cfg.get('experiment_name', 'thermocomp')!r}, {uri})")
            container = config_container(cfg)
            retry_locked(mlflow.log_dict, container, "config.yaml")
            retry_locked(mlflow.log_params, run_params(container, overrides, given_model))
            yield _Tracker(mlflow, run)
            status = "FINISHED"
        except (KeyboardInterrupt, Terminated):  # SIGINT / SIGTERM (files.signals_raise)
            status = "KILLED"
            raise
        finally:
            if run is not None:
                with signals.deferred():
                    _close(mlflow, status)


def name_given_model(tracker, stage: str, source: str, family: str) -> None:
    """A stage streaming a saved model (``<stage>.model``, logged with ``given_model``) names its
    run after that model (``replay-lagbank``; tags ``<stage>.model``, ``<stage>.model_name``), not
    after the config's ``model`` it never fitted."""
    tracker.set_tags({"mlflow.runName": f"{stage}-{family}", f"{stage}.model": source,
                      f"{stage}.model_name": family})


def _close(mlflow, status: str) -> None:
    """Attach the run's log so far (thermocomp.log, failed runs too) and end it with ``status``."""
    from ..base.log import current_file

    log_file = current_file()
    if log_file is not None and log_file.is_file():
        retry_locked(mlflow.log_artifact, str(log_file))
    end_active_run(mlflow, status)


def end_active_run(mlflow, status: str = "FINISHED") -> None:
    """End the active (fluent) run with ``status``, safe on a busy SQLite store.

    The status is written through the client, retried while the store is locked; only then
    does the run leave the fluent stack.  (``retry_locked(mlflow.end_run)`` was not safe:
    ``end_run`` pops the run before writing, so a retry after a lock error ended nothing and
    the run stayed RUNNING, as a signalled run did when another process read the store.)
    """
    run = mlflow.active_run()
    if run is None:
        return
    retry_locked(mlflow.MlflowClient().set_terminated, run.info.run_id, status)
    try:
        mlflow.end_run(status)     # pops the stack; writes the same status again
    except Exception as exc:
        if not _is_locked(exc):
            raise




def start_parent_run(cfg: DictConfig, run_name: str, tags: dict | None = None) -> str:
    """Create (not activate) a sweep's parent run; returns its id."""
    from mlflow import MlflowClient

    uri = connect(cfg)
    exp_id = experiment_id(uri, str(cfg.get("experiment_name", "thermocomp")))
    all_tags = {SWEEP_TAG: "parent", "mlflow.runName": run_name,
                "project_root": str(project_root()), **store.process_tags(), **(tags or {})}
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
