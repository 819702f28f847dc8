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
created (schema migrations) by one process at a time under a file lock
(``mlflow.db.lock`` next to it) before any other MLflow call.

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
import re
import tempfile
from contextlib import contextmanager
from pathlib import Path

from omegaconf import DictConfig, OmegaConf

from ..base.files import Terminated, signals_raise
from ..base.paths import project_root, resolve
from . import store
from .store import _is_locked, retry_locked  # the store's lock retries, used here and re-exported

DEFAULT_URI = "sqlite:///mlruns/mlflow.db"
PARENT_ENV = "THERMOCOMP_PARENT_RUN_ID"
SWEEP_TAG = "thermocomp.sweep"          # "parent" on a sweep's parent run
DATASET_TAG = "dataset_hash"            # folder digest of data.path a run read
def resolve_uri(uri: str) -> str:
    """Make a relative ``sqlite:///path`` absolute (against the project root)."""
    prefix = "sqlite:///"
    if uri.startswith(prefix) and not uri.startswith(prefix + "/"):
        path = resolve(uri[len(prefix):])
        path.parent.mkdir(parents=True, exist_ok=True)
        return prefix + str(path)
    return uri


def enabled(cfg, default: bool = True) -> bool:
    """Whether a stage logs to MLflow: ``track`` if set (true/false), else the stage's default."""
    track = cfg.get("track")
    return default if track is None else bool(track)


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


def connect(cfg) -> str:
    """Point MLflow at ``cfg.tracking_uri`` (resolved); returns the URI.

    The first time in a process, runs left RUNNING by processes of this machine that are
    gone are marked KILLED (:func:`~thermocomp.shell.store.mark_orphan_runs`).
    """
    os.environ.setdefault("MLFLOW_ENABLE_ARTIFACTS_PROGRESS_BAR", "false")
    import mlflow

    _quiet_mlflow()
    uri = store_uri(cfg)
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


def store_uri(cfg) -> str:
    """``cfg.tracking_uri`` resolved, once checked that MLflow can open it (ConfigError)."""
    raw = str(cfg.get("tracking_uri") or DEFAULT_URI)
    store.check_sqlite_path(raw)
    try:
        uri = resolve_uri(raw)
    except OSError as exc:
        from ..base.errors import ConfigError

        raise ConfigError(f"tracking_uri={raw}: cannot create its folder ({exc.strerror})") from None
    check_reachable(uri)
    return uri


_REACHABLE: set[str] = set()   # stores this process has found it can open
STORE_SCHEMES = ("sqlite", "http", "https", "postgresql", "mysql", "mssql", "databricks")


def check_reachable(uri: str) -> None:
    """A store MLflow can open: a known scheme, a SQLite file in a folder this process can
    write, a server that answers within seconds (MLflow retries an unreachable one for minutes,
    silently)."""
    if uri in _REACHABLE:      # once per process: every connect() comes here
        return
    from ..base.errors import ConfigError

    scheme = uri.partition(":")[0].partition("+")[0]
    if scheme not in STORE_SCHEMES:
        raise ConfigError(f"tracking_uri={uri}: not a store MLflow opens here (schemes: "
                          f"{', '.join(STORE_SCHEMES)}; the default is {DEFAULT_URI})")
    if scheme == "sqlite" and uri.startswith("sqlite:///"):
        folder = Path(uri[len("sqlite:///"):]).parent
        try:
            folder.mkdir(parents=True, exist_ok=True)
            tempfile.TemporaryFile(dir=folder).close()
        except OSError as exc:
            raise ConfigError(f"tracking_uri={uri}: cannot write in {folder} ({exc.strerror})") from None
    elif scheme in ("http", "https"):
        import requests

        try:
            requests.get(uri.rstrip("/") + "/health", timeout=10)
        except requests.RequestException as exc:
            raise ConfigError(f"tracking_uri={uri}: no server answers "
                              f"({type(exc).__name__}); is it running?") from None
    elif scheme == "databricks":
        store.check_databricks_credentials(uri)
    elif scheme in store.DB_PORTS:
        store.check_database_answers(uri, scheme)
    _REACHABLE.add(uri)


def client(cfg):
    """An ``MlflowClient`` on ``cfg.tracking_uri``; stages that read runs need ``track`` on."""
    if not enabled(cfg):
        from ..base.errors import ConfigError

        raise ConfigError("this stage reads MLflow runs: it needs tracking on "
                          "(track=null, the default, or track=true)")
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
def stage_run(cfg: DictConfig, stage: str, default: bool = True):
    """An MLflow run for one stage, with the meaningful config logged; yields a tracker.

    Inside a sweep (``THERMOCOMP_PARENT_RUN_ID`` set) the run is a child of the
    sweep's parent run.  ``default`` is whether the stage is tracked when
    ``track`` is null.  The run ends FINISHED, FAILED (an exception), or KILLED
    (SIGTERM -> exit 143, SIGINT -> exit 130).
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
    if stage != "simulate" and data is not None and data.is_dir():   # what promote checks
        from ..base.files import folder_digest

        tags[DATASET_TAG] = folder_digest(data)
    parent = os.environ.get(PARENT_ENV) or None
    with signals_raise(sigint=True) as signals:
        # A signal while the run is being created or closed waits for the end of that step:
        # cut there, the run would stay RUNNING in the store for ever.
        run, status = None, "FAILED"
        try:
            with signals.deferred():
                run = retry_locked(mlflow.start_run, experiment_id=exp_id, tags=tags,
                                   parent_run_id=parent, run_name=run_name(cfg, overrides))
            container = config_container(cfg)
            retry_locked(mlflow.log_dict, container, "config.yaml")
            retry_locked(mlflow.log_params, run_params(container, overrides))
            yield _Tracker(mlflow, run)
            status = "FINISHED"
        except (KeyboardInterrupt, Terminated):  # SIGINT / SIGTERM (files.signals_raise)
            status = "KILLED"
            raise
        finally:
            if run is not None:
                with signals.deferred():
                    _close(mlflow, status)


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


# --- what a run is called and what it records ------------------------------------------------

# Config groups in the order they name a run; a group at its default is left out (not the model).
_GROUPS = (("model", None), ("select", "all"), ("ati", "none"), ("denoise", "none"))
# Overrides that say where things go or how much is reported, not what is fitted.
_NOT_NAMING = re.compile(r"^(hydra|tracking_uri|experiment_name|out|model_path|name|track|plots|"
                         r"compare|promote|replay|serve|data\.(path|interim|processed))([./]|$)"
                         r"|^eval\.(?!mode$)")
# Config leaves always logged as params (when present); plus every overridden key.
PARAM_KEYS = ("name", "out", "seed", "data.path", "data.inputs", "data.targets", "data.reference",
              "model.name", "select.name", "ati.name", "denoise.name", "eval.mode",
              "eval.validation")
_HYPER = ("model.estimator.", "select.selector.")    # the fitted model's own parameters


def task_overrides() -> list[str] | None:
    """The command line's overrides of this job (Hydra's ``overrides.task``), or None."""
    from hydra.core.hydra_config import HydraConfig

    if not HydraConfig.initialized():
        return None
    try:
        return [str(o) for o in HydraConfig.get().overrides.task]
    except Exception:  # a Hydra config without overrides (composed by hand)
        return None


def _split(override: str) -> tuple[str, str]:
    key, _, value = override.partition("=")
    return key.lstrip("+~"), value


def _short(value: str) -> str:
    """A value as a run-name token: no brackets, quotes, spaces, slashes."""
    value = re.sub(r"[\[\]{}()'\" ]", "", value)
    value = value.lower() if value in ("True", "False") else value   # a sweep writes `False`
    return re.sub(r"[/\\:]+", "_", value).strip("_") or "none"


def run_name(cfg: DictConfig, overrides: list[str] | None = None) -> str:
    """A short, stable name of what ran, from what differs from the defaults.

    The model, the non-default selector, ATI and denoiser, ``eval.mode``, the
    seed when set, then every other override that changes what is fitted
    (``leaf=value``): ``mlr-pearson-seed1``, ``arx-cmeans-one_step``,
    ``mlr-inputs=T_1``.  A ``name`` other than ``default`` prefixes it (``weak/mlr``).
    """
    parts = []
    for group, default in _GROUPS:
        value = (cfg.get(group) or {}).get("name")
        if value is not None and value != default:
            parts.append(str(value))
    mode = (cfg.get("eval") or {}).get("mode")
    if mode not in (None, "simulation"):
        parts.append(str(mode))
    keys = {_split(o)[0] for o in overrides or ()}
    if "seed" in keys or cfg.get("seed", 0) != 0:
        parts.append(f"seed{cfg.get('seed')}")
    named = {g for g, _ in _GROUPS} | {"seed", "eval.mode"}
    for o in overrides or ():
        key, value = _split(o)
        if key in named or _NOT_NAMING.match(key):
            continue
        leaf = key.rsplit(".", 1)[-1]
        if o.startswith("~"):
            parts.append(f"no-{leaf}")
        elif "." not in key:               # a config group (sim=..., experiment=...): its choice
            parts.append(_short(value))
        else:
            parts.append(f"{leaf}={_short(value)}")
    name = "-".join(parts) or "default"
    if cfg.get("name") not in (None, "default"):
        name = f"{cfg.get('name')}/{name}"
    return name[:250]


def sweep_name(overrides: list[str], name: str = "default") -> str:
    """A sweep's parent run name from what it sweeps: ``sweep/model=mlr,pcr-seed=range0,3``."""
    swept = [(k, v) for k, v in map(_split, overrides)
             if ("," in v or v.startswith(("range(", "choice(", "glob("))) and not _NOT_NAMING.match(k)]
    parts = [f"{k.rsplit('.', 1)[-1]}={_short(v)}" for k, v in swept]
    prefix = "sweep" if name in (None, "default") else f"sweep/{name}"
    return (f"{prefix}/{'-'.join(parts)}" if parts else prefix)[:250]


def run_params(container: dict, overrides: list[str] | None = None) -> dict:
    """The params worth comparing runs by (not all ~130 leaves; ``config.yaml`` has them):
    :data:`PARAM_KEYS`, the model's and selector's own parameters, every overridden key."""
    flat = {k: v for k, v in _flat_params(container).items()
            if not k.rsplit(".", 1)[-1].startswith("_")}          # no _target_ & co
    keys = [k for k in PARAM_KEYS if k in flat] + [k for k in flat if k.startswith(_HYPER)]
    for o in overrides or ():
        key = _split(o)[0]
        if key.startswith(("hydra", "tracking_uri", "experiment_name", "track")):
            continue
        if f"{key}.name" in flat:           # a config group choice: its name, not its leaves
            keys.append(f"{key}.name")
        else:
            keys += [k for k in flat if k == key or k.startswith(key + ".")]
    out = {}
    for k in dict.fromkeys(keys):      # a lab's column name as a key: 'data.columns.dZ [µm]'
        out.setdefault(_UNSAFE.sub("_", k), flat[k])
    return out


# what MLflow allows in a param name; anything else (brackets, °, µ) became an exception that
# ended the run with a traceback
_UNSAFE = re.compile(r"[^A-Za-z0-9_\-. :/]")


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


def _flat_params(d, prefix=""):
    out = {}
    for k, v in d.items():
        key = f"{prefix}.{k}" if prefix else str(k)
        if isinstance(v, dict):
            out.update(_flat_params(v, key))
        else:
            out[key] = str(v)[:500]
    return out
