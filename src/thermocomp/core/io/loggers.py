"""A folder whose files split one run's columns between two loggers (temperatures from one,
displacements from another; extension, twolog70): which files are such a pair, read as one
campaign by :mod:`.joined`; a file without an error that pairs with none is refused naming the
file that holds the errors.

A pair is two files of one folder whose names are one stem and a last word each after ``_``,
``-``, ``.`` or a space (``run03_temp.csv`` and ``run03_disp.csv``, ``K1-DAQ.csv`` and
``K1-Laser.txt``), of which exactly one holds an error column, the other none but a temperature
(each judged by its header as the read names it: a contract name, ``data.columns``,
``data.roles``, a length's unit; the error file may log temperatures too, an interferometer's
air and material sensors).  The temperature file is the campaign's file (a manifest's ``file``),
the stem its id in a folder without a manifest.  A manifest may name a run's error file in its
column ``error_file`` (extension, pair70: two loggers' files named apart, ``daq_0412.csv`` and
``laser_0412.csv``), checked by :mod:`.manifest`.
"""

from __future__ import annotations

import re
from collections import defaultdict
from pathlib import Path

import pandas as pd

from ...base.errors import listed
from .contract import MANIFEST, ContractError, role
from .options import ReadOptions
from .plain import as_read, is_converted
from .roles import matching_roles, named_as_time, split_unit
from .separators import reads_as_number
from .starts import first_row, named_head
from .units import role_by_unit
from .workbook import HEAD_ROWS

_LAST_WORD = re.compile(r"^(.+?)[_\-. ]([^_\-. ]+)$")
_KINDS = {"error": "E", "state": "S", "ambient": "T", "temperature": "T"}

NO_ERROR = "no E_ column"     # the refusal of a campaign file without a measured error
ERROR_FILE = "error_file"     # a manifest's column naming a run's error file (pair70)


def named_error_file(root: Path, manifest: pd.DataFrame, cid: str) -> Path | None:
    """The error file the manifest's ``error_file`` column names for campaign ``cid`` of the
    folder ``root``; None where the column is absent or the cell empty (found by name then)."""
    if ERROR_FILE not in manifest.columns:
        return None
    name = manifest.at[cid, ERROR_FILE]
    return None if pd.isna(name) or not str(name).strip() else root / str(name).strip()


def errors_elsewhere(exc: ContractError, root: Path, manifest: pd.DataFrame, cid: str,
                     opts: ReadOptions) -> ContractError:
    """``exc`` (campaign ``cid`` of the folder ``root`` refused) as it is, or, where it has no
    error column and another file of ``manifest`` holds errors but no temperature, a refusal
    naming that file and how a pair is named to be joined (:func:`logger_pairs`); a file
    without data rows, said to be left out (:func:`unrecorded`)."""
    if exc.reason.endswith("no data rows") and exc.row is None:
        return unrecorded(exc, root)
    if not exc.reason.startswith(NO_ERROR):
        return exc
    for other, file in manifest["file"].items():
        errors = [] if other == cid else _errors_only(root / file, opts)
        if errors:
            return ContractError(
                f"{NO_ERROR}, and {file} beside it holds errors ({listed(errors)}) without a "
                "temperature: the errors and the temperatures of one run in two files (two "
                "loggers)? Two files are read as one run, joined by time, where their names "
                "are one stem and a last word each (run03_temp.csv and run03_disp.csv): rename "
                f"them so, or name it in {MANIFEST}'s column {ERROR_FILE}, or join them into "
                "one file first, one row per time", file=exc.file)
    return exc


def unrecorded(exc: ContractError, root: Path) -> ContractError:
    """``exc``, the refusal of a file of the folder ``root`` without data rows, saying to leave
    it out: a run not recorded (its logger's header alone) among a lab's runs (messy58)."""
    where = (f"its row out of {MANIFEST}" if (root / MANIFEST).is_file() else
             "the file out of the folder")
    return ContractError(f"{exc.reason}: a run not recorded? a campaign needs samples; leave "
                         f"{where}", file=exc.file, column=exc.column, sheet=exc.sheet)


def _errors_only(path: Path, opts: ReadOptions) -> list[str]:
    """The ``E_`` columns of the file ``path`` as its header is named, where it has no ``T_``
    column; [] otherwise, or where its header does not read (its own read says why)."""
    try:
        if is_converted(path, opts):      # a workbook's sheet, a UTF-16 text: its head as read
            with as_read(path, opts, rows=HEAD_ROWS) as (source, source_opts):
                return _errors_only(source, source_opts)
        names = [n for n in named_head(path, opts)[2] if n]
    except (ContractError, OSError):
        return []
    kinds = {role(n) for n in names}
    return [n for n in names if role(n) == "E"] if "T" not in kinds else []


def stem_and_word(path: Path) -> tuple[str, str] | None:
    """``('run03', 'temp')`` of ``run03_temp.csv``; None for a name without a last word."""
    found = _LAST_WORD.match(path.stem)
    return (found.group(1), found.group(2)) if found else None


def logger_pairs(files: list[Path], opts: ReadOptions) -> dict[Path, Path]:
    """``{temperature file: error file}`` of every pair among ``files`` (one folder's)."""
    by_stem = defaultdict(list)
    for f in files:
        if (split := stem_and_word(f)) is not None:
            by_stem[split[0]].append(f)
    out = {}
    for group in by_stem.values():
        if len(group) == 2 and (pair := _ordered_pair(group, opts)) is not None:
            out[pair[0]] = pair[1]
    return out


def partner(path: Path, opts: ReadOptions, files: list[Path]) -> Path | None:
    """The error file ``path`` (a file without an error column) pairs with among ``files`` (its
    folder's campaign files), or None (a manifest lists the temperature file alone)."""
    split = stem_and_word(path)
    if split is None:
        return None
    group = [f for f in files
             if (s := stem_and_word(f)) is not None and s[0] == split[0]]
    pair = _ordered_pair(group, opts) if len(group) == 2 else None
    return pair[1] if pair is not None and pair[0].resolve() == path.resolve() else None


def paired_id(path: Path) -> str:
    """The campaign id of a pair whose temperature file is ``path``: the stem both share."""
    return stem_and_word(path)[0]


def _ordered_pair(group: list[Path], opts: ReadOptions) -> tuple[Path, Path] | None:
    """``(temperature file, error file)`` of two files, or None where they are no such pair."""
    kinds = [header_roles(f, opts) for f in group]
    errors = [("E" in k) for k in kinds]
    if sum(errors) != 1:
        return None
    i = errors.index(True)
    other = kinds[1 - i]
    return (group[1 - i], group[i]) if "T" in other else None


def header_roles(path: Path, opts: ReadOptions) -> set[str]:
    """The roles (``T``, ``E``, ``S``) the columns of ``path`` read as, by its header and first
    row (a contract name, ``data.columns``, ``data.roles``, the unit; any other number a
    temperature); an empty set where the header does not read (its own read says why)."""
    try:
        if is_converted(path, opts):
            with as_read(path, opts, rows=HEAD_ROWS) as (source, source_opts):
                return header_roles(source, source_opts)
        header, first, opts = first_row(path, opts)
    except (ContractError, OSError, ValueError):
        return set()
    out = set()
    for h in header:
        base, unit = split_unit(h)
        hits = matching_roles(h, opts.roles)
        if h in opts.columns:
            out.add(role(opts.columns[h]))
        elif hits:
            out.add(_KINDS.get(hits[0]))
        elif role(base) is not None:
            out.add(role(base))
        elif not named_as_time(h) and reads_as_number(first.get(h), opts.decimal):
            kind = role_by_unit(base, opts.units.get(h, unit))
            out.add("S" if kind == "state" else "T" if kind is None else "E")
    return out - {None}
