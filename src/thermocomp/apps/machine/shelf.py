"""The OPC UA standard address space on a shelf asyncua finds: made once, read at every twin start.

``Server.init()`` builds the standard address space (thousands of nodes) from asyncua's generated
code at every start: ~2.5 s of CPU per twin (each test that starts one, each restart of the
command).  ``Server.init(shelf)`` loads it lazily from a :mod:`shelve` instead, and makes the
shelf when it finds none; but it looks for ``<shelf>`` or ``<shelf>.db``, and on a Python without
gdbm or ndbm :mod:`shelve` falls back to dbm.dumb, which writes ``<shelf>.dat`` and
``<shelf>.dir``: asyncua never found its shelf, and built (and wrote) it again at every start.

Here the shelf is made by a server of its own, in a folder renamed into place once complete
(:func:`~thermocomp.base.files.atomic_dir`: a killed maker's folder is swept), under a file lock
(parallel twins wait for the one that makes it, none reads it half-made), with an empty
``<shelf>`` beside dbm.dumb's files for asyncua to find and the SHA-256 of its files beside
them: a shelf whose files are not those made (its empty ``<shelf>`` swept by a temp cleaner, a
``.dat`` truncated: asyncua's start failed, ``BadInternalError``) is made anew, whole.  One per
asyncua and Python version (the nodes are pickled asyncua objects in that Python's dbm) and
user; read-only after.
"""

from __future__ import annotations

import asyncio
import logging
import sys
from pathlib import Path

from ...base.files import atomic_dir, folder_digest, user_temp_folder

log = logging.getLogger(__name__)
SHELF = "standard"          # no dot in it: asyncua also looks for the name with its suffix -> .db
NODES = "nodes"             # the folder of the shelf's files (dbm.dumb's .dat, .dir, .bak)
DIGEST = "nodes.sha256"     # their SHA-256 as made (~20 ms of CPU to check, against ~2.5 s to build)
# the folder's layout in its name: an older thermocomp's shelf (its files at the top, no digest)
# is its own, which it would remake in its layout as this one would in this (each, in turn)
LAYOUT = "digested"


def shelf_folder() -> Path:
    """Where the shelves are kept (one per user: the temp folder is shared)."""
    return user_temp_folder("opcua")


def version_folder() -> Path:
    """The folder of this asyncua's and this Python's shelf."""
    import asyncua

    python = f"{sys.version_info[0]}.{sys.version_info[1]}"
    return shelf_folder() / f"asyncua-{asyncua.__version__}-py{python}-{LAYOUT}"


def standard_shelf() -> Path:
    """The shelf of the standard address space to hand ``Server.init``, made the first time.

    Blocks (up to 10 min while another process makes it): call it off the event loop.
    """
    from filelock import FileLock

    folder = version_folder()
    shelf = folder / NODES / SHELF
    if _whole(folder):
        return shelf
    folder.parent.mkdir(parents=True, exist_ok=True)
    with FileLock(f"{folder}.lock", timeout=600):
        if not _whole(folder):    # none, or damaged (a file swept, truncated): anew, whole
            with atomic_dir(folder) as tmp:
                (tmp / NODES).mkdir()
                _make(tmp / NODES / SHELF)
                (tmp / DIGEST).write_text(folder_digest(tmp / NODES))
    return shelf


def standard_shelf_or_none() -> Path | None:
    """:func:`standard_shelf`, or None (asyncua then builds the address space at this start, as
    before the shelf) where it cannot be made: a temp folder not writable, a lock held too long."""
    try:
        return standard_shelf()
    except OSError as exc:             # filelock's Timeout is one (TimeoutError)
        log.warning("the OPC UA address space is built at this start (no shelf: %s)", exc)
        return None


def _whole(folder: Path) -> bool:
    """The shelf in ``folder`` is as it was made: asyncua finds it (:func:`_found`) and its
    files have the digest written with them.  A folder swapped while it is read is not."""
    try:
        return (_found(folder / NODES / SHELF)
                and (folder / DIGEST).read_text() == folder_digest(folder / NODES))
    except OSError:
        return False


def _found(shelf: Path) -> bool:
    """asyncua's own test: else it would build the address space and write the shelf in place,
    under the feet of the twins reading it."""
    return shelf.is_file() or shelf.with_suffix(".db").is_file()


def _make(shelf: Path) -> None:
    """The standard address space built and shelved at ``shelf`` by a server never started."""
    from asyncua import Server

    asyncio.run(Server().init(shelf))
    if not _found(shelf):
        shelf.touch()             # dbm.dumb's files are <shelf>.dat/.dir: the name asyncua checks
