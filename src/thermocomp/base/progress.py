"""Progress of long loops (``tqdm`` bars), always on stderr (core: no Hydra here; a sweep's
jobs-done lines are a Hydra callback, :class:`thermocomp.shell.callbacks.SweepProgress`).

A bar shows on a terminal, or anywhere at ``-v``; never with ``-q``, never on
stdout (the result table stays clean when piped).
"""

from __future__ import annotations

import sys

from .log import level_name


def bar(iterable=None, desc: str | None = None, total: int | None = None, unit: str = "it",
        disable: bool | None = None, **kwargs):
    """``tqdm(iterable)`` on stderr: shown on a TTY or at ``-v``, hidden at ``-q`` or when the
    caller passes ``disable=True`` (a loop too short to need one)."""
    from tqdm import tqdm

    level = level_name()
    if disable is not True:
        disable = True if level == "WARNING" else (False if level == "DEBUG" else None)
    return tqdm(iterable, desc=desc, total=total, unit=unit, file=sys.stderr, disable=disable,
                leave=False, dynamic_ncols=True, **kwargs)
