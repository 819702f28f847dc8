"""(refusals100) ``thermocomp init``'s refusals gathered into one message.

The reader stops at the first thing it cannot read: a lab's Excel export (the clock's repeated
hour, an empty column) took one try of the command per refusal (audit100: three for excel.csv).
Where a refusal names the key that settles it, :func:`gathered` reads the file again with that
key set (nothing written, nothing printed), and so on while each refusal names one; the
refusals that do not depend on each other come out as ONE message, each as the reader words it
(file, column, row and its key), with one command line holding every key.  A refusal that names
no key it can follow (no time column at all, a file without rows) stays alone, as the reader
says it; one met after others is listed last, the keys before it still given together.
"""

from __future__ import annotations

import contextlib
import io as text_io
import logging
import re
import shlex
from typing import Callable

from hydra.core.override_parser.overrides_parser import OverridesParser
from omegaconf import DictConfig, OmegaConf, open_dict

from ...base.errors import ContractError
from ...base.log import logger

# keys a refusal names that settle one thing each, independent of the others: a list's entries
# add up (two empty columns, a unit-less sensor: one data.roles.ignore), a value is set once
FOLLOWED = ("data.timezone", "data.roles.ignore", "data.thousands", "data.dayfirst")
MOST = 6                    # reads of the file at most: a refusal per try, then no more
_KEY = re.compile(r"\b(data\.[A-Za-z_][\w.]*)=(\[[^\]]*\]|\{[^}]*\}|'[^']*'|[^\s,;)]+)")


def named_keys(said: str) -> dict | None:
    """``{key: value}`` of the ``key=value`` settings a refusal's text names, the value as Hydra
    reads it; None where it names none, a key not :data:`FOLLOWED`, or two values of one key
    (alternatives: the lab's to choose)."""
    keys: dict | None = {}
    for key, text in _KEY.findall(said):
        if key not in FOLLOWED:
            return None
        try:
            value = OverridesParser.create().parse_override(f"{key}={text}").value()
        except Exception:          # (a hint Hydra's grammar does not read: not followed)
            return None
        keys = _merged(keys, {key: value})
        if keys is None:
            return None
    return keys or None


def _merged(keys: dict, more: dict) -> dict | None:
    """``keys`` with ``more`` added (lists joined); None where a value would change."""
    out = dict(keys)
    for key, value in more.items():
        if isinstance(value, list):
            out[key] = [*out.get(key, []), *(v for v in value if v not in out.get(key, []))]
        elif out.setdefault(key, value) != value:
            return None
    return out


def _full(cfg: DictConfig, keys: dict) -> dict:
    """``keys`` as the command must give them: a list key's entries after the config's own
    (the user's ``data.roles.ignore=[KW]`` kept beside ``Reserve``)."""
    return {key: list(dict.fromkeys([*(OmegaConf.select(cfg, key) or []), *value]))
            if isinstance(value, list) else value for key, value in keys.items()}


def _with(cfg: DictConfig, keys: dict) -> DictConfig:
    """A copy of ``cfg`` with ``keys`` (:func:`_full`) set."""
    out = cfg.copy()
    with open_dict(out):
        for key, value in keys.items():
            OmegaConf.update(out, key, value, merge=False, force_add=True)
    return out


def override(key: str, value) -> str:
    """``key=value`` as one shell word Hydra reads back (a list's entries quoted)."""
    if isinstance(value, list):
        value = "[" + ",".join("'" + str(v).replace("'", "\\'") + "'" for v in value) + "]"
    word = f"{key}={value}"
    return f'"{word}"' if "'" in word and not re.search(r'["$`\\!]', word) else shlex.quote(word)


def command_line(keys: dict) -> str:
    """``thermocomp init <path> <the command's own overrides> <keys>``: the command as typed,
    the keys added (where no Hydra run is known, ``thermocomp init`` and the keys)."""
    from hydra.core.hydra_config import HydraConfig

    own = list(HydraConfig.get().overrides.task) if HydraConfig.initialized() else []
    path = [o.partition("=")[2] for o in own if o.startswith("data.path=")]
    rest = [o for o in own if not o.startswith("data.path=") and o.partition("=")[0] not in keys]
    return " ".join(["thermocomp init", *map(shlex.quote, path), *map(shlex.quote, rest),
                     *(override(k, v) for k, v in keys.items())])


def _quietly(read: Callable[[DictConfig], object], cfg: DictConfig):
    """``read(cfg)`` with its prints and warnings held (a look again, not the command's read)."""
    level = logger.level
    logger.setLevel(logging.ERROR)
    try:
        with contextlib.redirect_stdout(text_io.StringIO()):
            return read(cfg)
    finally:
        logger.setLevel(level)


def gathered(first: ContractError, cfg: DictConfig,
             read: Callable[[DictConfig], object]) -> ContractError:
    """The refusal to raise for ``first``, ``read(cfg)``'s (``read``: the command's read that
    writes nothing): ``first`` itself where it names no key to follow, else every refusal met
    while following the keys, in one message with one command line."""
    keys = named_keys(str(first))
    if keys is None:
        return first
    refusals, last = [first], None
    while len(refusals) < MOST:
        try:
            _quietly(read, _with(cfg, _full(cfg, keys)))
            break
        except ContractError as exc:
            more = named_keys(str(exc))
            merged = None if more is None else _merged(keys, more)
            if merged is None or merged == keys:
                last = exc                      # (not settled by a key: said, not followed)
                break
            refusals.append(exc)
            keys = merged
    if len(refusals) == 1 and last is None:
        return first                            # one refusal: the reader's words, as before
    said = "; ".join(f"({n}) {exc}" for n, exc in enumerate(refusals, 1))
    after = (f"; with those keys it then refuses: {last} (not settled by a key, said as the "
             "reader says it)") if last is not None else ""
    runs = "" if last is not None else ", with which it reads the file"
    return ContractError(f"{len(refusals)} refusals of the file at once (each is settled by its "
                         f"key; check that each is right for your record): {said}{after}; all "
                         f"the keys together{runs}: {command_line(_full(cfg, keys))}")
