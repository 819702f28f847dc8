"""When each campaign of a folder began: the order its last campaigns are held out in
(:func:`.record.hold_out`, ``data.test_fraction``).

The manifest's ``start`` where it gives one, else the file's first timestamp, read from its
first row alone (the header named, the time column read as the whole file's is), so that a
read of the whole folder and a read of a group of it (a fleet's machine) hold out the same
campaigns: a group is read without the others' files.
"""

from __future__ import annotations

import re
from dataclasses import replace
from pathlib import Path

import pandas as pd
import pyarrow as pa

from .contract import TIME, ContractError
from .dayfirst import ORDER
from .instants import START, on_clock, start_instants, start_stamp
from .layout import header_line
from .options import ReadOptions
from .plain import as_read, is_converted
from .sniff import head_lines, resolved
from .suffixes import is_text
from .tables import (
    NoRows,
    _contract_names,
    _first_text,
    _timed,
    parquet,
    peek_csv,
    without_pandas_index,
)
from .timestamps import CLOCK, dated_format, maybe_elapsed, parsed, slashed_format, time_type
from .workbook import HEAD_ROWS


def campaign_starts(root: Path, manifest: pd.DataFrame, opts: ReadOptions) -> pd.Series:
    """Per campaign of ``manifest`` (a folder ``root``'s): its start, NaT where none is known
    (no ``start``, a file timed in seconds)."""
    given = (start_instants(manifest[START], zone=opts.timezone) if START in manifest.columns
             else pd.Series(pd.NaT, index=manifest.index, dtype="datetime64[ns, UTC]"))
    return pd.Series({cid: given[cid] if pd.notna(given[cid]) else
                      first_timestamp(root / manifest.at[cid, "file"], opts)
                      for cid in manifest.index}, dtype="datetime64[ns, UTC]")


def first_timestamp(path: Path, opts: ReadOptions) -> pd.Timestamp:
    """The first timestamp of a campaign file (UTC; a time without an offset as written, or on
    ``data.timezone``'s clock); NaT when its time is no timestamp or the row does not read (the
    read of the file says why).  A file with no data row is refused (:class:`.tables.NoRows`):
    read as one without a start, the folder was held out in name order, said, and then refused
    for that file (messy58)."""
    if is_converted(path, opts):      # its first rows as the reader reads them (:mod:`.plain`)
        try:
            with as_read(path, opts, rows=HEAD_ROWS) as (source, source_opts):
                return first_timestamp(source, source_opts)
        except NoRows:
            raise
        except ContractError:
            return pd.NaT
    try:     # (half: a run's temperature file, its errors in another logger's: joined.py)
        header, first, names, opts = named_head(path, replace(opts, half=True))
    except NoRows:
        raise
    except ContractError:
        return pd.NaT
    stamp = _first_stamp(path, header, first, names, opts)
    return utc_instant(commented_start(path, opts), opts) if pd.isna(stamp) else stamp


# a DAQ script's comment block above the table: '# start: 2027-03-08 06:00:00' (stranger66)
_START_LINE = re.compile(r"#+\s*start\s*[:=]\s*(?P<stamp>\S.*?)\s*$", re.IGNORECASE)


# (isoleft67) a header block's line over the table, ``key<sep>value``: the keys that say a test's
# start and nothing else (spaces, '-', '_', '/' and '.' aside, any case); a ``Date`` line is none
# (an export's date, maybe), nor ``Time``
START_KEYS = frozenset((
    "start", "starttime", "startdate", "startdatetime", "starttimestamp", "started", "startedat",
    "teststart", "testbegin", "teststarttime", "measurementstart", "measurementbegin",
    "recordingstart", "runstart", "startzeit", "startzeitpunkt", "startdatum", "messbeginn",
    "messstart", "versuchsbeginn", "versuchsstart", "testbeginn"))
_KEY_VALUE = re.compile(r"\s*#*\s*(?P<key>[^\t;,:=]+?)\s*[\t;,:=][\s\t;,:=]*(?P<value>.*?)[\s;,]*")
_DATE_TIME = re.compile(r"\d{4}-\d{2}-\d{2}[T ]\d{1,2}:\d{2}")     # ISO 8601, a date and a time
_TIME_ONLY = re.compile(r"\d{1,2}:\d{2}(:\d{2}(\.\d*)?)?")


def commented_start(path: Path, opts: ReadOptions) -> pd.Timestamp:
    """The start a text file's ``#`` comment block above its table states, ``# start:
    2027-03-08 06:00:00`` (ISO 8601, as the manifest's ``start``; as written, an offset or
    none: :func:`.instants.start_stamp`): one line saying it, above any line that is no
    comment; NaT otherwise (no such line, two, or one that is no ISO 8601 time).  Read for a
    file whose time is no timestamp (seconds since its run's start): its campaign's ``start``.
    Where no ``#`` line says it (extension, isoleft67): one line of the block above the table
    (a test software's ``[Header]``) under a key of :data:`START_KEYS` whose value is an ISO 8601
    date and time (``Test start<TAB>2027-05-07 12:00:00``): :func:`stated_start`."""
    return stated_start(path, opts)[0]


def stated_start(path: Path, opts: ReadOptions) -> tuple[pd.Timestamp, str | None]:
    """(:func:`commented_start`'s start, how it was stated: ``'# start:' line`` or ``'<key>'
    line of the block above the table``; or NaT and, where a start key's line was left, why)."""
    if not is_text(path):
        return pd.NaT, None
    try:
        lines = head_lines(path, opts.encoding)
    except (ContractError, OSError, LookupError):
        return pd.NaT, None
    block = []
    for line in lines:
        if line.strip() and not line.lstrip().startswith("#"):
            break
        block.append(line.strip())
    found = [m["stamp"] for m in map(_START_LINE.fullmatch, block) if m]
    if len(found) > 1:
        return pd.NaT, None
    if found:
        try:
            return start_stamp(found[0]), "'# start:' line"
        except ValueError:
            return pd.NaT, None
    return _header_block_start(path, lines, opts)


def _header_block_start(path: Path, lines: list[str], opts: ReadOptions
                        ) -> tuple[pd.Timestamp, str | None]:
    try:
        k = header_line(lines, resolved(path, opts).delimiter)
    except ContractError:
        return pd.NaT, None
    keyed = [(m["key"], m["value"]) for m in map(_KEY_VALUE.fullmatch, lines[:k or 0]) if m
             and re.sub(r"[\s\-_/.]", "", m["key"]).lower() in START_KEYS]
    if len(keyed) != 1:
        return pd.NaT, None
    key, value = keyed[0]
    said = f"'{key}' line of the block above its table"
    # day first with dots, or slashes whose order a field past 12 says, or data.dayfirst (dates85)
    told = dated_format(value) or (None if opts.dayfirst is None else
                                   slashed_format(value, order=ORDER[opts.dayfirst]))
    if told:
        try:                      # as a time column of that format is read (a second's fraction)
            stamp = parsed(pa.array([value]), time_type(told, value), told)
        except pa.ArrowInvalid:   # no such day (32.05.2027)
            return pd.NaT, f"its '{key}' ({value}) is no date and time"
        return pd.Timestamp(stamp.to_pandas()[0]), said
    if not _DATE_TIME.match(value):
        why = (f"its '{key}' ({value}) holds no date (a 'Date' line beside it may be the "
               "export's)" if _TIME_ONLY.fullmatch(value) else
               f"its '{key}' ({value}) is no date and time (ISO 8601, day first with dots, or "
               "with slashes and a field past 12)")
        return pd.NaT, why
    try:
        return start_stamp(value), said
    except ValueError:
        return pd.NaT, f"its '{key}' ({value}) is no ISO 8601 date and time"


def _first_stamp(path: Path, header, first, names, opts) -> pd.Timestamp:
    cells = {n: first[h] for h, n in zip(header, names) if n in (TIME, CLOCK)}
    value = cells.get(TIME)
    if isinstance(value, pd.Timestamp) or value is None:
        return utc_instant(value, opts)
    text = f"{value.strip()} {cells[CLOCK].strip()}" if CLOCK in cells else value.strip()
    if maybe_elapsed(text, opts.time):
        return pd.NaT
    try:
        kind = _timed(path, text, opts).time
        target = time_type(kind, text)
        if not pa.types.is_timestamp(target):
            return pd.NaT
        stamp = parsed(pa.array([text]), target, kind)[0].as_py()
    except (ContractError, pa.ArrowInvalid):
        return pd.NaT
    return utc_instant(pd.Timestamp(stamp), opts)


def named_head(path: Path, opts: ReadOptions) -> tuple[list[str], dict, list[str | None],
                                                       ReadOptions]:
    """A text or Parquet file's header, its first row (:func:`first_row`), the contract names
    of its columns (None: ignored) and the options with its separators detected."""
    header, first, opts = first_row(path, opts)
    return header, first, _contract_names(header, opts, path, first=first)[0], opts


def first_row(path: Path, opts: ReadOptions) -> tuple[list[str], dict, ReadOptions]:
    """A file's header, its first row (cells as text; a Parquet timestamp as it is) and the
    options with its separators detected (a decimal comma's cells are numbers to the naming:
    with ``auto`` they read as text, every temperature refused and the file's start lost)."""
    if is_text(path):
        opts = resolved(path, opts)
        header, row, _ = peek_csv(path, opts.delimiter, opts.encoding)
        return header, dict(zip(header, row)), opts
    batch = next(parquet().ParquetFile(path).iter_batches(batch_size=1), None)
    if batch is None:
        raise NoRows("no rows", file=path)
    batch = without_pandas_index(pa.Table.from_batches([batch]))
    first = {}
    for name, column in zip(batch.schema.names, batch.columns):
        first[name] = (pd.Timestamp(column[0].as_py()) if pa.types.is_timestamp(column.type)
                       and column[0].is_valid else _first_text(pa.chunked_array([column])) or "")
    return batch.schema.names, first, opts


def utc_instant(stamp, opts: ReadOptions) -> pd.Timestamp:
    """``stamp`` as an instant: one without an offset on ``data.timezone``'s clock (as
    written without it: ordered as the whole read orders them)."""
    if stamp is None or pd.isna(stamp):
        return pd.NaT
    return on_clock(stamp, opts.timezone).tz_convert("UTC")

