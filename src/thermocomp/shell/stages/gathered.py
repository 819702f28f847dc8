"""(refusals100) ``thermocomp init``'s refusals gathered into one message.

The reader stops at the first thing it cannot read: a lab's Excel export (the clock's repeated
hour, an empty column) took one try of the command per refusal (audit100: three for excel.csv).
Where a refusal names the key that settles it, :func:`gathered` reads the file again with that
key set (nothing written, nothing printed), and so on while each refusal names one; the
refusals that do not depend on each other come out as ONE message, each as the reader words it
(file, column, row and its key), with one command line holding every key.  A refusal that names
no key it can follow (a file without rows, a time that runs back) stays alone, as the reader
says it; one met after others is listed last, the keys before it still given together.

(data103) A refusal no key settles but a look can step past -- no time column (the period is
the lab's to give), a temperature's bracket that reads as a unit or as a note (the lab's to
choose) -- is gathered too: the file is looked at past it (:func:`looked_past`: a period of
1 s, that column left out; keys never given as its fix), so that the problems after it (an
empty column, a unit that is no temperature's) are named in the same message; the command line
then holds the keys of the others, the open ones said as the reader says them.
"""

from __future__ import annotations

import ast
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
from ...core.io.roles import header_pattern
from ...core.io.tables import NO_TIME_COLUMN
from ...core.io.units import TWO_READINGS

# keys a refusal names that settle one thing each, independent of the others: a list's entries
# add up (two empty columns, a unit-less sensor: one data.roles.ignore), a value is set once
FOLLOWED = ("data.timezone", "data.roles.ignore", "data.thousands", "data.dayfirst")
MOST = 6                    # reads of the file at most: a refusal per try, then no more
_KEY = re.compile(r"\b(data\.[A-Za-z_][\w.]*)=(\[[^\]]*\]|\{[^}]*\}|'[^']*'|[^\s,;)]+)")
# (data103) a look past a refusal no key settles: a period for a file without a time column (any:
# the look reads on, the lab gives the true one), a bracket read both ways left out
LOOK_PERIOD = 1.0
IGNORE = "data.roles.ignore"
_TWO_WAYS = re.compile(r"""('(?:[^'\\]|\\.)*'|"(?:[^"\\]|\\.)*"): \([^()]*\) """
                       + re.escape(TWO_READINGS))


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


def looked_past(said: str) -> dict | None:
    """``{key: value}`` with which a look at the file steps past a refusal no key settles
    (never given as its fix): ``data.sample_period_s`` for a file without a time column, the
    columns whose bracket reads as a unit or as a note left out (with the other columns the
    same refusal leaves out by ``data.roles.ignore``); None where no look steps past it."""
    if NO_TIME_COLUMN in said:
        return {"data.sample_period_s": LOOK_PERIOD}
    headers = [ast.literal_eval(h) for h in _TWO_WAYS.findall(said)]
    if not headers:
        return None
    hinted = [named_keys(f"{key}={text}") or {} for key, text in _KEY.findall(said) if key == IGNORE]
    return {IGNORE: list(dict.fromkeys([*map(header_pattern, headers),
                                        *(v for h in hinted for v in h.get(IGNORE, []))]))}


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
    writes nothing): ``first`` itself where it names no key to follow and no look steps past it
    (:func:`looked_past`), else every refusal met while following the keys and looking past the
    open ones, in one message with one command line."""
    keys = named_keys(str(first))
    look = looked_past(str(first)) if keys is None else {}
    if look is None:
        return first
    keys = keys or {}
    refusals, last = [(first, not look)], None      # (a refusal, settled by its key)
    while len(refusals) < MOST:
        try:
            _quietly(read, _with(cfg, _full(cfg, _merged(keys, look) or {**look, **keys})))
            break
        except ContractError as exc:
            more = named_keys(str(exc))
            merged = None if more is None else _merged(keys, more)
            if merged is not None and merged != keys:
                refusals.append((exc, True))
                keys = merged
                continue
            past = looked_past(str(exc))
            ahead = None if past is None else _merged(look, past)
            if ahead is None or ahead == look:
                last = exc                      # (not settled by a key: said, not followed)
                break
            refusals.append((exc, False))       # (the lab's to settle: looked past)
            look = ahead
    if len(refusals) == 1 and last is None:
        return first                            # one refusal: the reader's words, as before
    said = "; ".join(f"({n}) {exc}" for n, (exc, _) in enumerate(refusals, 1))
    open_ = [f"({n})" for n, (_, settled) in enumerate(refusals, 1) if not settled]
    if not open_:
        after = (f"; with those keys it then refuses: {last} (not settled by a key, said as the "
                 "reader says it)") if last is not None else ""
        runs = "" if last is not None else ", with which it reads the file"
        return ContractError(f"{len(refusals)} refusals of the file at once (each is settled by "
                             f"its key; check that each is right for your record): {said}{after}; "
                             f"all the keys together{runs}: {command_line(_full(cfg, keys))}")
    return ContractError(_open_said(refusals, open_, said, last, keys, cfg))


def _open_said(refusals: list, open_: list[str], said: str, last, keys: dict,
               cfg: DictConfig) -> str:
    """(data103) The message where some refusals are the lab's to settle (``open_``, looked
    past): each said as the reader says it, then the keys that settle the others."""
    n_open = ", ".join(open_)
    after = (f"; read past those, it then refuses: {last} (not settled by a key, said as the "
             "reader says it)") if last is not None else ""
    head = (f"{len(refusals)} refusals of the file at once ({n_open}: yours to settle as "
            f"{'it says' if len(open_) == 1 else 'each says'}, the file read past "
            f"{'it' if len(open_) == 1 else 'them'} to find the rest"
            + ("; each other is settled by its key: check that each is right for your record"
               if keys else "") + f"): {said}{after}")
    if not keys:
        return head
    return (f"{head}; the keys of the others together, with {n_open} settled too: "
            f"{command_line(_full(cfg, keys))}")
