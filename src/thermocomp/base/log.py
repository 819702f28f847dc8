"""Logging of the ``thermocomp`` command: one logger, three levels, a log file per run.

Stages log through the ``thermocomp`` logger (:data:`logger`): progress and
information on stderr, so stdout stays the result table.  ``-q/--quiet`` shows
warnings only, ``-v/--verbose`` debug messages too (and progress bars even off a
terminal); the level travels in ``THERMOCOMP_LOG_LEVEL`` so sweep jobs in other
processes (joblib, SLURM) log at the same level through Hydra's job logging
(``conf/hydra/job_logging/thermocomp.yaml``, the same format).

Each stage run also logs at DEBUG level to a temp file (:func:`run_log`): the
MLflow run gets it as the artifact ``thermocomp.log`` and, when the stage
succeeds, it is copied to ``<out>/thermocomp.log`` (a refused run leaves nothing).
"""

from __future__ import annotations

import logging
import os
import re
import shutil
import sys
import tempfile
import time
import warnings
from contextlib import contextmanager
from pathlib import Path

NAME = "thermocomp"
LEVEL_ENV = "THERMOCOMP_LOG_LEVEL"
LOG_FILE = "thermocomp.log"
FILE_FORMAT = "%(asctime)s %(levelname)-7s %(name)s: %(message)s"
LEVELS = {"quiet": "WARNING", "normal": "INFO", "verbose": "DEBUG"}

logger = logging.getLogger(NAME)
_run_files: list[Path] = []  # the log files of the stage runs under way (innermost last)


class Formatter(logging.Formatter):
    """``[thermocomp] message``; ``[hydra] ...`` for Hydra's own logger; warnings and errors
    say so."""

    def format(self, record: logging.LogRecord) -> str:
        tag = record.name.split(".")[0]
        tag = "hydra" if tag == "hydra_plugins" else tag
        level = f"{record.levelname.lower()}: " if record.levelno >= logging.WARNING else ""
        text = f"[{tag}] {level}{record.getMessage()}"
        if record.exc_info:
            text += "\n" + self.formatException(record.exc_info)
        return text


class Handler(logging.Handler):
    """Console handler: the ``sys.stderr`` of the moment (so pytest's capture and redirected
    streams work), written through ``tqdm.write`` so a progress bar is redrawn below the line."""

    def emit(self, record: logging.LogRecord) -> None:
        try:
            from tqdm import tqdm

            tqdm.write(self.format(record), file=sys.stderr)
        except Exception:  # logging must never kill a run
            self.handleError(record)


def level_name() -> str:
    """The console level of this process (``INFO`` unless ``-q``/``-v`` set it)."""
    name = os.environ.get(LEVEL_ENV, "INFO").upper()
    return name if name in LEVELS.values() else "INFO"


def configure(level: str | None = None) -> None:
    """Console logging for this process at ``level`` (``WARNING``/``INFO``/``DEBUG``); the level is
    exported to child processes. Calling it again replaces the handler (no duplicate lines)."""
    if level is not None:
        os.environ[LEVEL_ENV] = level
    for h in [h for h in logger.handlers if isinstance(h, Handler)]:
        logger.removeHandler(h)
    handler = Handler(level_name())
    handler.setFormatter(Formatter())
    logger.addHandler(handler)
    logger.setLevel(logging.DEBUG)  # handlers filter: the run's log file keeps DEBUG
    logger.propagate = False


_ANSI = re.compile(r"\x1b\[[0-9;]*[A-Za-z]")     # terminal colour codes


@contextmanager
def run_log(folder=None):
    """Log this stage run (DEBUG) to a temp ``thermocomp.log``; yields its path.

    On success the file is copied atomically to ``folder() / thermocomp.log``
    when ``folder`` (a callable, evaluated at the end) returns an existing
    folder, i.e. one the stage wrote its outputs to.
    """
    from .files import atomic_write_bytes

    tmp = Path(tempfile.mkdtemp(prefix="thermocomp-log-"))
    path = tmp / LOG_FILE
    handler = logging.FileHandler(path, encoding="utf-8")
    handler.setLevel(logging.DEBUG)
    handler.setFormatter(logging.Formatter(FILE_FORMAT))
    logger.addHandler(handler)
    if logger.level in (logging.NOTSET,) or logger.level > logging.DEBUG:
        logger.setLevel(logging.DEBUG)
    _run_files.append(path)
    ok = False
    try:
        yield path
        ok = True
    finally:
        _run_files.remove(path)
        logger.removeHandler(handler)
        handler.close()
        try:
            dest = folder() if (ok and folder is not None) else None
            if dest is not None and Path(dest).is_dir():
                try:
                    text = path.read_bytes()
                except FileNotFoundError:   # a temp cleaner took it: the run's work stands
                    logger.warning(f"the run's log {path} was removed while the run went on "
                                   f"(a temp cleaner?): {Path(dest) / LOG_FILE} not written")
                else:
                    atomic_write_bytes(Path(dest) / LOG_FILE, text)
        finally:
            shutil.rmtree(tmp, ignore_errors=True)


def current_file() -> Path | None:
    """The log file of the stage run under way, if any (what MLflow logs as an artifact)."""
    return _run_files[-1] if _run_files else None


@contextmanager
def warnings_logged():
    """Within the block a Python warning (a library's ``UserWarning``, numpy's
    ``RuntimeWarning``, ...) is logged as one ``[thermocomp] warning:`` line naming its
    category and source file (its lines joined), instead of the interpreter's two raw lines, once
    per place and text; the filters and the previous display come back after."""
    seen = set()

    def show(message, category, filename, lineno, file=None, line=None):
        # once per place and text: libraries reset the filters (catch_warnings) and with them
        # Python's once-per-place memory, so a numpy warning in a loop came dozens of times
        key = (category, str(message), filename, lineno)
        if key in seen:
            return
        seen.add(key)
        text = " ".join(_ANSI.sub("", str(message)).split())   # MLflow colours its warnings
        logger.warning("%s: %s (%s:%d)", category.__name__, text, Path(filename).name, lineno)

    with warnings.catch_warnings():
        warnings.showwarning = show
        yield


_ONCE_PER_RUN: list[str] = []     # the folders of modules whose notes are said once a stage run


def once_per_run(package: Path) -> None:
    """Register the modules of the folder ``package`` (or the one module file ``package``): a note
    or warning one of them logs is said once per stage run (:func:`said_once`), however often the
    stage reads or fits what it is about."""
    where = os.path.abspath(package)
    where = where + os.sep if os.path.isdir(where) else where
    if where not in _ONCE_PER_RUN:
        _ONCE_PER_RUN.append(where)


class _Once(logging.Filter):
    def __init__(self):
        super().__init__()
        self.said: set[str] = set()

    def filter(self, record: logging.LogRecord) -> bool:
        if (record.levelno < logging.INFO
                or not os.path.abspath(record.pathname).startswith(tuple(_ONCE_PER_RUN))):
            return True
        text = record.getMessage()
        if text in self.said:
            return False
        self.said.add(text)
        return True


@contextmanager
def said_once():
    """Within the block (a stage run) a note or warning of a module registered by
    :func:`once_per_run` (the reader's: a footer left out, a header written again) is said once
    per text: ``init`` reads a file more than once (its look for a run counter, then the
    record), and each read said it again (stranger68: a sheet's footer twice).  The text is the
    one the user reads (a temporary file named as the lab's: :mod:`.core.io.converted`'s filter
    runs first); a connection's or a monitor's repeated events are logged by other modules."""
    once = _Once()
    logger.addFilter(once)
    try:
        yield
    finally:
        logger.removeFilter(once)


@contextmanager
def held_back():
    """Within the block the notes and warnings logged are held, not said: the list yielded, for
    :func:`said_after` to say or to drop (``init``'s first look reads the record with roles it
    may change: stranger77's wheelhead Z, read as an error for its span, said 'constant over
    the whole campaign' before init proposed it as a state).  Held before every other filter
    (a converted file's name, :func:`said_once`), so that a record dropped is not marked said
    and one said later passes them all."""
    held: list[logging.LogRecord] = []

    def hold(record: logging.LogRecord) -> bool:
        held.append(record)
        return False

    logger.filters.insert(0, hold)
    try:
        yield held
    finally:
        logger.removeFilter(hold)


def said_after(held: list[logging.LogRecord]) -> None:
    """Say the records :func:`held_back` held, in their order."""
    for record in held:
        logger.handle(record)


def say(msg: str) -> None:
    """Progress at INFO level through the ``thermocomp`` logger (stderr and the run's log file),
    so stdout stays the result table."""
    logger.info(msg)


class Clock:
    """Wall time of a stage's phases, for the one timing line a stage logs at its end.

    ``lap(name)`` adds the time since the previous lap (or the clock's start)
    to phase ``name``; a phase lapped twice accumulates.
    """

    def __init__(self):
        self.seconds: dict[str, float] = {}
        self._last = time.perf_counter()

    def lap(self, name: str) -> None:
        now = time.perf_counter()
        self.seconds[name] = self.seconds.get(name, 0.0) + now - self._last
        self._last = now

    def line(self) -> str:
        total = sum(self.seconds.values())
        return (f"time (s): {total:.2f} = "
                + " + ".join(f"{name} {s:.2f}" for name, s in self.seconds.items()))


def version() -> str:
    """The installed distribution's version (as ``--version`` prints it and the log records)."""
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as dist_version

    try:
        return dist_version("thermocomp")
    except PackageNotFoundError:  # a source tree without install
        return "unknown"
