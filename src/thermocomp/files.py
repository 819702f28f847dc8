"""Writing result files atomically, and fingerprinting folders.

Nothing half-written is ever visible under a final name: a file is written to
a temp file in the same folder and renamed over the destination, a folder is
built in a temp folder next to it and swapped in.  Files end up readable by
everyone (0644), folders 0755, whatever ``tempfile`` gave the temp object.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import tempfile
from pathlib import Path

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

    ``obj`` goes through :func:`~thermocomp.jsonsafe.json_safe` first (NaN ->
    ``null``, NumPy -> Python); anything still not JSON raises instead of being
    written as non-standard JSON.

    Returns
    -------
    Path
        ``path``.
    """
    text = json.dumps(json_safe(obj), indent=2, allow_nan=False, ensure_ascii=ensure_ascii)
    return atomic_write_text(path, text + "\n")


def atomic_dir(dest: str | os.PathLike):
    """Context manager yielding a temp folder that replaces ``dest`` on success.

    Nothing half-written is ever visible at ``dest``: on error the temp folder
    is removed and ``dest`` keeps its previous content.
    """
    return _AtomicDir(Path(dest))


class _AtomicDir:
    def __init__(self, dest: Path):
        self.dest = dest

    def __enter__(self) -> Path:
        self.dest.parent.mkdir(parents=True, exist_ok=True)
        self.tmp = Path(tempfile.mkdtemp(prefix=f".{self.dest.name}.", dir=self.dest.parent))
        self.tmp.chmod(DIR_MODE)
        return self.tmp

    def __exit__(self, exc_type, exc, tb):
        if exc_type is not None:
            shutil.rmtree(self.tmp, ignore_errors=True)
            return False
        old = None
        if self.dest.exists():
            old = self.dest.with_name(f".{self.dest.name}.old")
            shutil.rmtree(old, ignore_errors=True)
            os.replace(self.dest, old)
        os.replace(self.tmp, self.dest)
        if old is not None:
            shutil.rmtree(old, ignore_errors=True)
        return False


def folder_digest(folder: str | os.PathLike) -> str:
    """SHA-256 over every file under ``folder``: relative path and bytes, recursively, sorted.

    Renaming, moving, adding or changing any file changes the digest; the
    folder's own location and the files' times do not.
    """
    root = Path(folder)
    h = hashlib.sha256()
    for f in sorted(p for p in root.rglob("*") if p.is_file()):
        h.update(f.relative_to(root).as_posix().encode() + b"\0")
        with open(f, "rb") as fh:
            h.update(hashlib.file_digest(fh, "sha256").digest())
    return h.hexdigest()
