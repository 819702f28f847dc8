"""The output-path policy: what a stage writes never is, lies inside or holds what it reads.

Each stage declares, by config key, the places it writes and the places it reads; one
check refuses an overlap before any work.  A ``run`` given ``out=<data.path>`` once replaced
the campaign files kept in ``<data.path>/plots/`` by its figures; ``out=<data.path>/out`` put
a model into the raw dataset.  The raw dataset (``data.path``) is read by every stage but
``simulate`` (which writes it), so it is an input of all the others whether they open it or
not: no stage writes into it.
"""

from __future__ import annotations

import os
from pathlib import Path

from omegaconf import DictConfig, OmegaConf

from ...base.errors import ConfigError
from ...base.paths import overlap, resolve
from ..store import is_registered_model

RAW = "data.path"
SQLITE = "sqlite:///"


def place(cfg: DictConfig, key: str) -> Path | None:
    """The real path config ``key`` names (symlinks followed, so a link cannot hide an
    overlap), or None: unset, empty, or not a file path (``models:/...``, ``http://...``).
    A SQLite store is its file (its artifacts go beside it)."""
    value = OmegaConf.select(cfg, key)
    if str(value).startswith(SQLITE):
        value = str(value)[len(SQLITE):]
    if value is None or not str(value).strip() or "://" in str(value) or is_registered_model(value):
        return None
    return Path(os.path.realpath(resolve(str(value))))


def check_apart(cfg: DictConfig, outputs, inputs) -> None:
    """Refuse, naming both keys, an output of ``outputs`` (config keys) that is, lies inside or
    holds one of the ``inputs``; ``data.path`` is always an input."""
    sources = [(key, place(cfg, key)) for key in dict.fromkeys((RAW, *inputs))]
    for out_key in dict.fromkeys(outputs):
        output = place(cfg, out_key)
        if output is None:
            continue
        for in_key, source in sources:
            how = None if source is None or in_key == out_key else overlap(output, source)
            if how:
                raise ConfigError(
                    f"{out_key}={OmegaConf.select(cfg, out_key)} {how} "
                    f"{in_key}={OmegaConf.select(cfg, in_key)}: a stage never writes where it "
                    f"reads (the raw data are never modified); give {out_key} a place of its own")
