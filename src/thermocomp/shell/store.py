"""The MLflow store itself: URIs MLflow can use, a SQLite store created whole and checked before
use, runs left RUNNING by dead processes, the model registry's lock.

:mod:`thermocomp.shell.tracking` calls these when it connects; ``promote`` holds :func:`registry_lock`.
"""

from __future__ import annotations

import hashlib
import logging
import os
import random
import re
import shutil
import socket
import sqlite3
import tempfile
import time
from contextlib import closing, contextmanager
from pathlib import Path

from ..base.errors import ConfigError
from ..base.files import user_temp_folder
from ..base.paths import resolve

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


def check_schema(uri: str, db: Path, head: bool = False) -> None:
    """Refuse (ConfigError, one line, the file untouched) a store that is not a complete store of
    this MLflow: MLflow's own error came as a traceback at every run, in another shape for each
    kind of damage, and after it had written into the file.

    Always: not an SQLite file; migrated (``alembic_version``) but missing tables, as a
    creation cut short by a version that did not create stores whole leaves it.  With
    ``head`` (once MLflow has failed on it): a schema version other than this MLflow's.
    """
    from mlflow.store.tracking.dbmodels.models import Base

    def read() -> tuple[set, str | None]:
        with closing(sqlite3.connect(f"file:{db}?mode=ro", uri=True)) as con:
            tables = {r[0] for r in con.execute("SELECT name FROM sqlite_master WHERE type='table'")}
            return tables, (con.execute("SELECT version_num FROM alembic_version").fetchone()
                            or [None])[0] if "alembic_version" in tables else None

    try:
        # another run writing the store holds its lock a moment: that is no damage (two runs
        # on a fresh store were refused as "not an SQLite database (database is locked)")
        tables, version = retry_locked(read)
    except sqlite3.DatabaseError as err:
        raise ConfigError(f"tracking_uri={uri}: {db} is not an SQLite database ({err})") from None
    missing = set(Base.metadata.tables) - tables
    expected = None
    if head:
        try:
            from alembic.script import ScriptDirectory
            from mlflow.store.db.utils import _get_alembic_config
        except ImportError:      # another MLflow's layout: its own error stands
            return
        expected = ScriptDirectory.from_config(_get_alembic_config(uri)).get_current_head()
    if (version is not None and missing) or (head and version != expected):
        raise ConfigError(
            f"tracking_uri={uri}: {db} is not a complete store of this MLflow (schema {version}"
            + (f", this MLflow's {expected}" if head else "") + f"; {len(missing)} tables "
            f"missing): a creation cut short or an older MLflow; move it away (a new one is "
            f"created) or back it up and run `mlflow db upgrade sqlite:///{db}`") from None


def create_store(db: Path) -> None:
    """Create the SQLite store ``db`` whole or not at all (called under ``<db>.lock``).

    The store is made in a temp file next to it, renamed into place once complete: a
    creation cut short (disk full, SIGKILL) left a half-migrated ``mlflow.db`` that every
    later run failed on ("table ... already exists").  Its schema is a copy of
    :func:`schema_template` (MLflow's migrations, run once per MLflow version: 1.6-2 s of CPU
    for every new store before), then MLflow adds its Default experiment as on a migrated file.
    """
    template = schema_template()

    def copy(tmp: Path) -> None:
        shutil.copyfile(template, tmp)
        try:
            # the Default experiment's artifacts beside the store, not in the working folder
            _open_store(tmp, db.parent)
        except Exception:       # a damaged template: the next creation migrates a new one
            template.unlink(missing_ok=True)
            raise

    _made_whole(db, copy)


def _made_whole(path: Path, make) -> None:
    """``make(tmp)`` on a temp file beside ``path``, renamed to ``path`` once it returns (called
    under ``path``'s lock: a temp file found beside it is a creator's killed outright)."""
    for stale in path.parent.glob(f".{path.name}.*.creating*"):
        stale.unlink(missing_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".creating", dir=path.parent)
    os.close(fd)
    try:
        make(Path(tmp))
        os.replace(tmp, path)
    finally:
        for leftover in (tmp, f"{tmp}-journal"):
            Path(leftover).unlink(missing_ok=True)


def _open_store(db: Path, artifacts: Path) -> None:
    """Let MLflow open ``db`` as a store: an empty file is migrated, a schema is verified, and
    the Default experiment (artifacts under ``artifacts``) is added if missing."""
    from mlflow.store.tracking.sqlalchemy_store import SqlAlchemyStore

    SqlAlchemyStore(f"sqlite:///{db}", artifacts.as_uri()).engine.dispose()


def template_folder() -> Path:
    """Where :func:`schema_template` keeps its stores (one per user: the temp folder is shared)."""
    return user_temp_folder("mlflow")


def schema_template() -> Path:
    """An empty store migrated by this MLflow (no experiment in it), made once per MLflow version
    and user, whole or not at all, under a file lock (parallel first runs all wait for one)."""
    import mlflow
    from filelock import FileLock

    folder = template_folder()
    folder.mkdir(parents=True, exist_ok=True)
    template = folder / f"store-{mlflow.__version__}.db"

    def migrate(tmp: Path) -> None:
        _open_store(tmp, folder)
        with closing(sqlite3.connect(tmp)) as con:     # each store gets its own Default
            con.execute("DELETE FROM experiments")
            con.commit()

    with FileLock(f"{template}.lock", timeout=600):
        if not template.is_file():
            _made_whole(template, migrate)
    return template


REGISTRY_LOCK_TIMEOUT_S = 600


@contextmanager
def registry_lock(uri: str):
    """Hold the model registry of ``uri`` for one decision (read the champion, compare, move the
    alias): two promotes at once each read "no champion yet" and the worse model could win.

    An OS file lock (``flock``: released by the kernel when its holder dies, SIGKILL included):
    ``<db>.registry.lock`` next to a SQLite store; for a server store one per URI in the temp
    folder, which serializes the promotes of this machine only (MLflow has no compare-and-set
    on aliases: promote from one machine per server).
    """
    from filelock import FileLock, Timeout

    if uri.startswith("sqlite:///"):
        path = Path(f"{sqlite_file(uri)}.registry.lock")
    else:
        digest = hashlib.sha256(uri.encode()).hexdigest()[:16]
        path = Path(tempfile.gettempdir()) / f"thermocomp-registry-{digest}.lock"
    lock = FileLock(path)
    try:
        lock.acquire(timeout=REGISTRY_LOCK_TIMEOUT_S)
    except Timeout:
        raise ConfigError(f"tracking_uri={uri}: another promote has held the registry lock "
                          f"{path} for {REGISTRY_LOCK_TIMEOUT_S} s") from None
    try:
        yield
    finally:
        lock.release()


# --- runs of processes that died without closing them (SIGKILL, OOM killer, power loss) ------

PID_TAG, HOST_TAG, STARTED_TAG = "thermocomp.pid", "thermocomp.host", "thermocomp.process_start"


def process_tags() -> dict:
    """Which process owns a run: pid, host and the process's start time (a reused pid has
    another start time)."""
    import psutil

    return {PID_TAG: str(os.getpid()), HOST_TAG: socket.gethostname(),
            STARTED_TAG: repr(psutil.Process().create_time())}


def _owner_gone(tags: dict) -> bool:
    """Whether the process that opened a run (its :func:`process_tags`) no longer runs."""
    import psutil

    try:
        pid, started = int(tags[PID_TAG]), float(tags[STARTED_TAG])
        proc = psutil.Process(pid)
        return (abs(proc.create_time() - started) > 1.0
                or proc.status() == psutil.STATUS_ZOMBIE)
    except (KeyError, ValueError):      # not tagged by this project: not ours to judge
        return False
    except psutil.NoSuchProcess:
        return True


def mark_orphan_runs(uri: str) -> list[str]:
    """Mark KILLED the RUNNING runs of ``uri`` opened on this machine by a process that is
    gone; returns their ids.  (A signalled run closes itself KILLED; SIGKILL leaves no chance.)"""
    from mlflow import MlflowClient

    from ..base.log import logger

    client = MlflowClient(uri)
    experiments = [e.experiment_id for e in retry_locked(client.search_experiments)]
    if not experiments:
        return []
    runs = retry_locked(client.search_runs, experiments, max_results=1000,
                        filter_string=f"attributes.status = 'RUNNING' and "
                                      f"tags.`{HOST_TAG}` = '{socket.gethostname()}'")
    gone = [r for r in runs if _owner_gone(r.data.tags)]
    for run in gone:
        retry_locked(client.set_terminated, run.info.run_id, "KILLED")
        logger.warning("run %s (%s) was left RUNNING by process %s, which is gone: marked KILLED",
                       run.info.run_id, run.info.run_name, run.data.tags[PID_TAG])
    return [r.info.run_id for r in gone]


REGISTERED = "models:/"


def is_registered_model(source) -> bool:
    """Whether a model source names a version in the store's registry (``models:/<name>@<alias>``
    or ``models:/<name>/<version>``) rather than a file or folder: such a source reads the store."""
    return str(source).startswith(REGISTERED)


def sqlite_file(uri: str) -> str:
    """The file a ``sqlite:///<path>`` URI names (``""`` for any other URI)."""
    return uri[len("sqlite:///"):] if uri.startswith("sqlite:///") else ""


def check_sqlite_path(raw: str) -> None:
    """A SQLite store is a file: ``sqlite:///`` alone named the project folder (MLflow then
    retried for minutes), ``sqlite://`` an in-memory store that forgets every run."""
    if raw.partition(":")[0].partition("+")[0] != "sqlite":
        return
    path = sqlite_file(raw)
    if not path or path == ":memory:" or path.endswith("/") or resolve(path).is_dir():
        raise ConfigError(f"tracking_uri={raw}: a SQLite store needs a file path "
                          f"(sqlite:///mlruns/mlflow.db, sqlite:////abs/path/mlflow.db)")


def check_existing(raw: str) -> None:
    """Refuse a SQLite store that is not there, for a command that reads runs or models from it:
    opening it created and migrated a new ``mlflow.db`` (about 1 s) only to find it empty, and
    left it (and its folder) behind."""
    if not raw.startswith("sqlite:///"):
        return
    db = resolve(sqlite_file(raw))
    if not db.is_file() or db.stat().st_size == 0:     # an empty file is a store yet to create
        raise ConfigError(f"tracking_uri={raw}: no store at {db}; this command reads one and "
                          f"creates none (run `thermocomp run` first, or name the store)")


def check_databricks_credentials(uri: str) -> None:
    """MLflow's own credential lookup, once: without credentials MLflow ends in a long
    exception at the first call."""
    from mlflow.utils.databricks_utils import get_databricks_host_creds

    chatty = logging.getLogger("mlflow.utils.databricks_utils")
    level = chatty.level
    chatty.setLevel(logging.ERROR)
    try:
        get_databricks_host_creds(uri)
    except Exception:
        raise ConfigError(f"tracking_uri={uri}: no Databricks credentials (set DATABRICKS_HOST and "
                          f"DATABRICKS_TOKEN, or a profile in ~/.databrickscfg)") from None
    finally:
        chatty.setLevel(level)


DB_PORTS = {"postgresql": 5432, "mysql": 3306, "mssql": 1433}


def check_database_answers(uri: str, scheme: str) -> None:
    """A database server store listens: one TCP connection within seconds, no retries."""
    from urllib.parse import urlsplit

    parts = urlsplit(uri)
    if not parts.hostname:      # a local socket: the driver says
        return
    try:
        socket.create_connection((parts.hostname, parts.port or DB_PORTS[scheme]), timeout=5).close()
    except OSError as exc:
        shown = re.sub(r"//[^@/]*@", "//", uri)          # no password in the error line
        raise ConfigError(f"tracking_uri={shown}: no database server answers at "
                          f"{parts.hostname}:{parts.port or DB_PORTS[scheme]} "
                          f"({exc.strerror or type(exc).__name__}); is it running?") from None


# --- the store a config names: checked before any work --------------------------------------

DEFAULT_URI = "sqlite:///mlruns/mlflow.db"


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


def store_uri(cfg, existing: bool = False) -> str:
    """``cfg.tracking_uri`` resolved, once checked that MLflow can open it (ConfigError);
    with ``existing`` (a command that only reads the store) a SQLite store must be there."""
    raw = str(cfg.get("tracking_uri") or DEFAULT_URI)
    check_sqlite_path(raw)
    if existing:
        check_existing(raw)
    try:
        uri = resolve_uri(raw)
    except OSError as exc:
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
    scheme = uri.partition(":")[0].partition("+")[0]
    if scheme not in STORE_SCHEMES:
        raise ConfigError(f"tracking_uri={uri}: not a store MLflow opens here (schemes: "
                          f"{', '.join(STORE_SCHEMES)}; the default is {DEFAULT_URI})")
    if scheme == "sqlite" and uri.startswith("sqlite:///"):
        folder = Path(sqlite_file(uri)).parent
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
        check_databricks_credentials(uri)
    elif scheme in DB_PORTS:
        check_database_answers(uri, scheme)
    _REACHABLE.add(uri)
