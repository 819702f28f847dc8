"""Writing result files atomically, and fingerprinting folders.

Nothing half-written is ever visible under a final name: a file is written to
a temp file in the same folder and renamed over the destination, a folder is
built in a temp folder next to it and swapped in, and the outputs of a whole
run are staged in a temp folder next to their destination and moved in at the
end (:func:`staged_outputs`).  Files end up readable by everyone (0644), folders
0755, whatever ``tempfile`` gave the temp object.

Temp folders carry the writer's pid (``.<name>.tmp-<pid>-<random>``): SIGTERM
and SIGINT remove them on the way out, and one left by a killed process
(SIGKILL, power loss) is swept by the next writer of the same destination.
"""

from __future__ import annotations

import getpass
import glob
import hashlib
import itertools
import json
import os
import re
import secrets
import shutil
import signal
import sys
import tempfile
import threading
import time
from contextlib import contextmanager
from pathlib import Path

from .errors import ConfigError
from .jsonsafe import json_safe

FILE_MODE, DIR_MODE = 0o644, 0o755


def atomic_write_bytes(path: str | os.PathLike, data: bytes) -> Path:
    """Write ``data`` to ``path`` through a temp file in the same folder and a rename."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            os.fchmod(f.fileno(), FILE_MODE)
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


def atomic_write_text(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically, as :func:`atomic_write_bytes`."""
    return atomic_write_bytes(path, text.encode("utf-8"))


def write_json(path: str | os.PathLike, obj, *, ensure_ascii: bool = True) -> Path:
    """Write ``obj`` as indented JSON, atomically.

    ``obj`` goes through :func:`~thermocomp.base.jsonsafe.json_safe` first (NaN ->
    ``null``, NumPy -> Python); anything still not JSON raises instead of being
    written as non-standard JSON.

    Returns
    -------
    Path
        ``path``.
    """
    text = json.dumps(json_safe(obj), indent=2, allow_nan=False, ensure_ascii=ensure_ascii)
    return atomic_write_text(path, text + "\n")


@contextmanager
def atomic_dir(dest: str | os.PathLike):
    """Context manager yielding a temp folder that replaces ``dest`` on success.

    Nothing half-written is ever visible at ``dest``: on error (SIGTERM and
    SIGINT included) the temp folder is removed and ``dest`` keeps its previous
    content.  Two writers of one ``dest`` at once each build their own folder;
    the last to finish wins, whole.
    """
    dest = Path(dest)
    with _temp_folder(dest) as tmp:
        yield tmp
        _swap_in(tmp, dest)


@contextmanager
def staged_outputs(out: str | os.PathLike, last: tuple[str, ...] = ("metrics.json",)):
    """Context manager yielding a temp folder whose entries are moved into ``out`` on success.

    Every output of a run is written into the temp folder (next to ``out``, so
    the moves are renames); leaving the block moves each file and folder into
    ``out`` (a folder replaces the one there whole; entries named in ``last``
    go last, so ``metrics.json`` appears only once everything else is in).
    Other files in ``out`` are left alone.  On error, SIGTERM or SIGINT the temp
    folder is removed: a refused run changes nothing in ``out`` and creates no
    folder.

    Raises
    ------
    NotADirectoryError
        If ``out`` exists and is not a folder (checked before the work).
    """
    out = Path(os.path.realpath(out))  # stage beside the real folder: renames stay on one disk
    if out.exists() and not out.is_dir():
        raise NotADirectoryError(f"{out} exists and is not a folder")
    with _temp_folder(out, "stage") as tmp:
        yield tmp
        out.mkdir(parents=True, exist_ok=True)
        order = {name: i + 1 for i, name in enumerate(last)}
        for entry in sorted(tmp.iterdir(), key=lambda p: (order.get(p.name, 0), p.name)):
            if entry.is_dir():
                _swap_in(entry, out / entry.name)
            else:
                os.replace(entry, out / entry.name)


_TEMP = re.compile(r"\.(?P<name>.+)\.(?:tmp|stage|old)-(?P<pid>\d+)-[^/]+")


@contextmanager
def _temp_folder(dest: Path, kind: str = "tmp"):
    """A fresh ``.<dest name>.<kind>-<pid>-<random>`` folder next to ``dest``, removed on any
    exit (SIGTERM/SIGINT too); stale ones of dead processes are swept first.  Folders this
    creates above ``dest`` are removed again if the block fails."""
    made = [p for p in (dest.parent, *dest.parent.parents) if not p.exists()]
    dest.parent.mkdir(parents=True, exist_ok=True)
    sweep_stale(dest)
    tmp = Path(tempfile.mkdtemp(prefix=f".{dest.name}.{kind}-{os.getpid()}-", dir=dest.parent))
    tmp.chmod(DIR_MODE)
    ok = False
    try:
        with signals_raise():
            yield tmp
        ok = True
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
        if not ok:
            for folder in made:  # innermost first; stops at the first one not empty
                try:
                    folder.rmdir()
                except OSError:
                    break


def _swap_in(src: Path, dest: Path) -> None:
    """Rename folder ``src`` to ``dest``, replacing a folder there (moved aside first, under a
    name of this process's own, so two writers never collide)."""
    for _ in range(10):  # another writer may swap its own folder in between two renames
        old = None
        if dest.exists():
            old = dest.with_name(f".{dest.name}.old-{os.getpid()}-{os.urandom(4).hex()}")
            try:
                os.replace(dest, old)
            except FileNotFoundError:
                continue
        try:
            os.replace(src, dest)
        except OSError:
            if old is None:
                continue
            raise
        finally:
            if old is not None:
                shutil.rmtree(old, ignore_errors=True)
        return
    raise OSError(f"could not replace {dest}: other processes keep writing it")


def user_temp_folder(kind: str) -> Path:
    """``thermocomp-<user>-<kind>`` in the temp folder, where what is made once per user is kept
    (the temp folder is shared by the machine's users)."""
    user = os.getuid() if hasattr(os, "getuid") else getpass.getuser()
    return Path(tempfile.gettempdir()) / f"thermocomp-{user}-{kind}"


def sweep_stale(dest: str | os.PathLike) -> list[Path]:
    """Remove the temp folders of ``dest`` (see :func:`atomic_dir`) left by dead processes.

    Returns
    -------
    list of Path
        The folders removed.
    """
    dest = Path(dest)
    removed = []
    if not dest.parent.is_dir():
        return removed
    for p in dest.parent.glob(f".{glob.escape(dest.name)}.*-*-*"):
        m = _TEMP.fullmatch(p.name)
        if m and m["name"] == dest.name and p.is_dir() and not _alive(int(m["pid"])):
            shutil.rmtree(p, ignore_errors=True)
            removed.append(p)
    return removed


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


class Terminated(SystemExit):
    """SIGTERM, raised as an exception (exit status 128 + 15) so that ``finally`` blocks clean up
    and callers can tell a terminated block from one that failed."""


class _Signals:
    """What :func:`signals_raise` yields: ``deferred()`` holds a signal back until the end of a
    block that must not be cut in two (creating a run and entering the ``try`` that closes it;
    closing it), then raises it."""

    def __init__(self) -> None:
        self._depth = 0
        self._pending: int | None = None
        self._raised: int | None = None

    def handle(self, signum: int) -> None:
        if self._depth:
            self._pending = self._pending or signum
            return
        self._raised = signum
        _arm(RETRY_S)
        _raise_for(signum)

    def retry(self) -> None:
        """The raised signal again, unless it is on its way out: a handler runs between any two
        bytecodes, inside a weakref callback or ``__del__`` too, where Python prints "Exception
        ignored" and drops it (a SIGTERM lost so, the run went on to its end)."""
        if self._raised is None:
            return
        if isinstance(sys.exc_info()[1], (Terminated, KeyboardInterrupt)):
            return                        # propagating: cleanup runs, leave it alone
        _arm(RETRY_S)
        if self._depth:
            # a deferred block (closing the run) is never cut, not even by the retry: inside an
            # ``except`` of the store's own code the propagating signal is not sys.exc_info()
            # (CI, stop 44: a SIGINT'd run left RUNNING); again once the block is done
            return
        _raise_for(self._raised)

    @contextmanager
    def deferred(self):
        self._depth += 1
        try:
            yield
        finally:
            self._depth -= 1
            if not self._depth and self._pending is not None:
                signum, self._pending = self._pending, None
                _raise_for(signum)


RETRY_S = 0.5     # a swallowed signal is raised again this much later


def _arm(seconds: float) -> None:
    if hasattr(signal, "setitimer"):
        signal.setitimer(signal.ITIMER_REAL, seconds)


def _raise_for(signum: int) -> None:
    if signum == signal.SIGINT:
        raise KeyboardInterrupt
    raise Terminated(128 + signum)


@contextmanager
def signals_raise(sigint: bool = False):
    """Within the block SIGTERM raises :class:`Terminated` (and, with ``sigint``, SIGINT raises
    KeyboardInterrupt even where it was ignored), so temp files are removed and runs closed on
    the way out; the previous handlers come back after.  Yields a :class:`_Signals` whose
    ``deferred()`` holds a signal back over a critical section.  Only the main thread can set
    handlers: elsewhere this only yields."""
    control = _Signals()
    if threading.current_thread() is not threading.main_thread():
        yield control
        return
    signals = (signal.SIGTERM, signal.SIGINT) if sigint else (signal.SIGTERM,)
    previous = {s: signal.signal(s, lambda signum, frame: control.handle(signum)) for s in signals}
    if hasattr(signal, "SIGALRM"):
        previous[signal.SIGALRM] = signal.signal(signal.SIGALRM, lambda signum, frame: control.retry())
    try:
        yield control
    finally:
        _arm(0)
        for s, h in previous.items():
            signal.signal(s, h)


# a folder whose removal a late writer undoes is removed again, this many times this far apart
REMOVE_TRIES, REMOVE_PAUSE_S = 20, 0.05


def remove_tree(path: str | os.PathLike) -> None:
    """Remove the folder ``path`` and what it holds, OSErrors ignored.  A download's worker threads
    (MLflow's pool) may still copy files into it after a signal ended the download, one after
    rmtree listed the folder ("Directory not empty"): removed again until gone (a worker makes no
    folder, MLflow's calling thread does: once the folder is gone, their copies fail), at most
    :data:`REMOVE_TRIES` times.  A SIGTERM or Ctrl-C that comes as it removes (a model's 270
    files) is raised once the folder is gone, not halfway."""
    signalled = None
    for _ in range(REMOVE_TRIES):
        try:
            shutil.rmtree(path, ignore_errors=True)
            if not os.path.lexists(path):
                break
            time.sleep(REMOVE_PAUSE_S)
        except (Terminated, KeyboardInterrupt) as exc:
            signalled = signalled or exc
    if signalled is not None:
        raise signalled


_SCRATCH = itertools.count()


def scratch_name(prefix: str) -> Path:
    """A name for a new folder in the temp dir that only this process makes:
    ``<prefix><pid>-<n>-<random>`` (made inside the ``try`` that removes it: a signal that comes
    as it is made still has it removed; ``mkdtemp`` made it before)."""
    return Path(tempfile.gettempdir()) / f"{prefix}{os.getpid()}-{next(_SCRATCH)}-{secrets.token_hex(3)}"


@contextmanager
def scratch_folder(prefix: str):
    """A fresh folder in the temp dir (:func:`scratch_name`), removed by :func:`remove_tree` however
    the block ends: its removal never replaces the exception in flight (``TemporaryDirectory``
    raised "Directory not empty" in place of a SIGTERM that came in a model's download, which
    ``thermocomp serve`` then said as a model it cannot load, exit 2, its folder left)."""
    folder = scratch_name(prefix)
    try:
        folder.mkdir(mode=0o700)
        yield folder
    finally:
        remove_tree(folder)


def safe_name(*parts: str) -> str:
    """One file name from ``parts`` (joined with ``_``): every character other than letters,
    digits, ``_``, ``-`` and ``.`` becomes ``_``, and it cannot start with a dot."""
    name = re.sub(r"[^\w.\-]", "_", "_".join(str(p) for p in parts)).replace("..", "__")
    return "_" + name[1:] if name.startswith(".") else name


def inside(folder: str | os.PathLike, name: str) -> Path:
    """``folder / name``, refusing (ValueError) a path that would leave ``folder``."""
    folder = Path(folder)
    path = folder / name
    if path.resolve().parent != folder.resolve():
        raise ValueError(f"file name {name!r} leaves {folder}")
    return path


def folder_digest(folder: str | os.PathLike) -> str:
    """SHA-256 over every file under ``folder``: relative path and bytes, recursively, sorted
    (a file: its name and bytes).

    Renaming, moving, adding or changing any file changes the digest; the
    folder's own location and the files' times do not.
    """
    root = Path(folder)
    h = hashlib.sha256()
    # a one-file record (data.path a file) is digested as a folder holding only it
    files = [root] if root.is_file() else sorted(p for p in root.rglob("*") if p.is_file())
    for f in files:
        h.update((f.name if f == root else f.relative_to(root).as_posix()).encode() + b"\0")
        with open(f, "rb") as fh:
            h.update(hashlib.file_digest(fh, "sha256").digest())
    return h.hexdigest()


def check_replaceable(folder: str | os.PathLike, marker: str, key: str) -> None:
    """``folder`` (the value of config ``key``) is replaced whole by a stage: a non-empty one that
    no earlier run of it wrote (no ``marker`` in it) is refused before any work.  An ingest once
    deleted a folder of the user's given as ``data.interim``, and with ``name=`` (empty) all of
    ``data/interim/``."""
    folder = Path(folder)
    if folder.is_dir() and any(folder.iterdir()) and not (folder / marker).is_file():
        raise ConfigError(f"{key}: {folder} is not empty and holds no {marker}, so this stage did "
                          "not write it; it would be replaced whole: give an empty or new folder")
