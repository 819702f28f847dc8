"""One campaign file as an Arrow table: contract column names, CSV typed column by column
(the failing cell located by file, column and row), Parquet."""

from __future__ import annotations

import contextlib
import csv
import mmap
import re
from dataclasses import replace
from itertools import chain
from pathlib import Path

import numpy as np
import pyarrow as pa
import pyarrow.compute as pc
import pyarrow.csv as pacsv

from ...base.log import logger
from . import marks
from .again import STRAY, header_again, line_numbers, without
from .again import said as said_again
from .campbell import has_unit_row
from .campbell import units as campbell_units
from .contract import TIME, ContractError, role
from .csvline import SPLIT, split_line
from .encoding import arrow_encoding, first_undecodable, own, text_codec, undecodable
from .footer import BLANK_UNTIMED, blank_inside, footer, source
from .layout import (
    MAX_PROPERTY_ROWS,
    header_line,
    is_unit_row,
    property_rows,
    uncommented,
    unquoted,
    with_units,
)
from .lines import Lines
from .options import _OTHER_DELIMITERS, ROLE_ORDER, ReadOptions, _first_line
from .own_headers import with_own_header
from .period_line import period_hint
from .roles import RUN, active, excel_days_header, naming, said_notes, split_unit
from .separators import (
    UNICODE_MINUS,
    decimal_comma_hint,
    misgrouped,
    reads_as_number,
    thousands_hint,
    ungrouped,
)
from .slashed_rows import read_in, said_by, settled
from .sniff import head_lines, resolved
from .timestamps import (
    CLOCK,
    DATE,
    TIME_OF_DAY,
    described,
    elapsed_seconds,
    is_format,
    is_slashed_stamp,
    maybe_elapsed,
    parsed,
    said_if_not_seconds,
    time_kind,
    time_type,
    unread_fraction,
)
from .twins import occurrences, same_cells
from .twins import said as said_twice
from .units import is_flag

# Larger blocks than Arrow's 1 MiB default: fewer chunks, faster multithreaded parsing.
_CSV_BLOCK_BYTES = 16 << 20
_PANDAS_INDEX = re.compile(r"__index_level_\d+__")
_CONVERSION_ERROR = re.compile(r"In CSV column #(\d+)")
# a formula's error, '#DIV/0!', '#WERT!', or LibreOffice Calc's 'Err:502' (stranger65: refused
# without the hint, as it holds digits)
EXCEL_ERROR = re.compile(r"#[A-Z0-9/]+[!?]|Err:\d{3}")
_ARROW_SOURCE = re.compile(r"^Could not open Parquet input source '.*?': ")
# A contract name: prefix + identifier-like name (it becomes part of file names: no path
# separators, '..', spaces or control characters).
_NAME = re.compile(r"[TES]_[\w.\-]+")
# A file's (or a stream's) rows without a time column and without the period between them.
NO_TIME_COLUMN = ("no 'time' column (none named like 'time', 't(s)', 'Zeit', no ISO 8601 "
                  "timestamps, no data.roles.time): set data.sample_period_s (the seconds "
                  "between rows)")

# ---------------------------------------------------------------------------
# Column names


def shortened(line: str, most: int = 60) -> str:
    """``line`` cut to ``most`` characters (a summary row of 17 means) for a message."""
    return line if len(line) <= most else line[:most - 3] + "..."


def _contract_names(raw_names: list[str], opts: ReadOptions, file: Path, *,
                    first: dict | None = None) -> tuple[list[str | None], dict, dict]:
    """Contract names of the file's columns (None: left out by ``data.roles.ignore``), the
    unit conversions (:mod:`.roles`), checked against the contract's vocabulary, and the
    headers whose bracket is a note (:attr:`.roles.Naming.noted`: said once read,
    :func:`said_read`)."""
    # one logger's file of a run of two: data.units may name the other file's headers
    units = {h: u for h, u in opts.units.items() if h in raw_names} if opts.half else opts.units
    plan = naming(raw_names, opts.roles, opts.columns, first, opts.decimal, file, units)
    names: list[str | None] = []
    seen: set[str] = set()
    for raw in raw_names:
        name = plan.names.get(raw)
        if name is None:
            names.append(None)
            continue
        alias = f" (raw name {raw!r})" if name != raw else ""
        if role(name) is None and name not in (CLOCK, RUN):
            raise ContractError(f"column name{alias} has no contract role: expected 'time' or "
                                "a T_/E_/S_ prefix (map it with data.columns)",
                                file=file, column=name)
        if name not in (TIME, CLOCK, RUN) and (not _NAME.fullmatch(name) or ".." in name):
            raise ContractError(f"column name{alias} is not a prefix plus an identifier-like name "
                                "(letters, digits, '_', '-', '.'; no path separator, '..', space "
                                "or control character): map it with data.columns",
                                file=file, column=name)
        if name in seen:
            raise ContractError("duplicate column (after data.columns mapping)", file=file,
                                column=name)
        names.append(name)
        seen.add(name)
    if not opts.half and not any(role(n) == "E" for n in names if n):
        read_as = [raw for raw, n in zip(raw_names, names) if n and role(n) in ("T", "S")]
        hint = (f"; name it, data.roles.error=[<header>], or give its unit in the header ('dX "
                f"[µm]'): read as temperatures or states here: {', '.join(map(repr, read_as))}"
                if read_as and active(opts.roles) else "")
        raise ContractError(f"no E_ column: a campaign needs at least one measured error{hint}",
                            file=file)
    if TIME not in names and opts.sample_period_s is None:
        for raw in raw_names:      # a time of day or a date alone: refused saying so
            cell = str((first or {}).get(raw) or "")
            if TIME_OF_DAY.fullmatch(cell) or DATE.fullmatch(cell):
                time_kind(cell.strip(), "auto", False, file, raw)
        days = excel_days_header(raw_names, first or {}, opts.units, opts.decimal)
        if days:                   # a date saved as a number: its rows are not a period apart
            raise ContractError(f"no 'time' column: {days!r} from {(first or {}).get(days)} reads "
                                "as Excel's serial days (a date saved as a number): data.roles."
                                f"time={days!r} 'data.units={{{days}: d}}' (thermocomp init "
                                "writes both)", file=file)
        raise ContractError(NO_TIME_COLUMN + period_hint(file, opts.delimiter, opts.encoding),
                            file=file)
    return names, plan.scales, plan.noted


def _converted(columns: dict, scales: dict) -> dict:
    """Columns in the contract's units (µm, °C, s): ``value * scale + offset``."""
    for name, (scale, offset) in scales.items():
        if name in columns:
            columns[name] = pc.add(pc.multiply(pc.cast(columns[name], pa.float64()), scale), offset)
    return columns


def _ordered(names: list[str]) -> list[str]:
    """``time`` first, then ``T_``, ``E_``, ``S_`` columns, each in file order."""
    data = [n for n in names if n != TIME]
    return [TIME] + sorted(data, key=lambda n: ROLE_ORDER.index(role(n)))


# ---------------------------------------------------------------------------
# Loading CSV


# A missing value is an empty cell (the contract), or the NaN a numeric export writes for one.
# Arrow's defaults also read 'n/a', 'NULL', '#N/A', ... as missing: those are refused as text.
MISSING_TOKENS = ("", "nan", "NaN", "NAN", "-nan", "-NaN")


def _load_csv(path: Path, opts: ReadOptions) -> tuple:
    """The file's columns (contract names, units converted), its renames and conversions, and
    its :class:`.Lines` (a message's row located in the file, counted as the columns' rows)."""
    opts = resolved(path, opts)
    header, first_row, skip = peek_csv(path, opts.delimiter, opts.encoding)
    opts = replace(opts, skip_rows=skip)
    preamble = header_line(head_lines(path, opts.encoding), opts.delimiter) or 0
    spans = header_again(path, preamble, skip > preamble + 1, opts.delimiter)
    dropped = line_numbers(path, spans)
    said_again(path, dropped, spans)
    opts = replace(opts, drop_bytes=spans)
    lines = Lines(path, opts.delimiter, opts.encoding, skip, dropped=dropped)
    try:
        return _typed_columns(path, header, first_row, opts, lines)
    except ContractError as exc:
        raise lines.located(with_own_header(exc, _renamed(header, first_row, opts, path))) from None


def _renamed(header: list[str], first_row: list[str], opts: ReadOptions, path: Path) -> dict:
    """The file's headers -> contract names where they differ ({} where they do not read): what
    a refusal of a cell names besides the contract name."""
    try:
        named = _contract_names(header, opts, path, first=dict(zip(header, first_row)))[0]
    except ContractError:
        return {}
    return _renames(header, named)


def _typed_columns(path: Path, header: list[str], first_row: list[str], opts: ReadOptions,
                   lines: Lines) -> tuple:
    if len(header) == 1:
        _check_delimiter(header[0], opts.delimiter.join(first_row), path, opts)
    named, scales, noted = _contract_names(header, opts, path,
                                           first=dict(zip(header, first_row)))
    for line in said_twice(header, {h: n for h, n in zip(header, named) if n}):
        logger.warning(f"{path}: {line}")
    said, cut = footer(path, opts.delimiter, len(header), opts.encoding)
    opts = replace(opts, data_bytes=cut,        # (the tail read once: every read of the data)
                   drop_bytes=tuple((a, b) for a, b in opts.drop_bytes if a < cut))
    if said:
        logger.warning(f"{path}: footer left out ({len(said)} line(s) under the data: "
                       f"{shortened(said[0])!r})")
    blank = None if TIME in named else blank_inside(path, opts.skip_rows, cut)
    if blank is not None:
        logger.warning(f"{path}, {lines.at(blank)}: {BLANK_UNTIMED}")
    if len(first_row) != len(named):
        raise ContractError(f"expected {len(named)} fields, got {len(first_row)}", file=path, row=1)
    # a column left out (data.roles.ignore) is read under a name no contract column can have
    names = [n if n is not None else f" ignored {i}" for i, n in enumerate(named)]
    types = {n: pa.float64() for n in named if n is not None and n not in (TIME, CLOCK, RUN)}
    in_rows = False
    if RUN in names:           # a run's number or name, as written: split by it (.runs)
        types[RUN] = pa.string()
    if CLOCK in names:         # a date and a time of day: read as text, joined, then parsed
        types.update({TIME: pa.string(), CLOCK: pa.string()})
    elif TIME in names:
        first = first_row[names.index(TIME)].strip()
        in_rows = _order_in_rows(first, opts)
        if maybe_elapsed(first, opts.time) or in_rows:
            types[TIME] = pa.string()     # (h:mm:ss, a date with slashes: the column tells)
        else:
            opts = _timed(path, first, opts, header[names.index(TIME)])
            # (a second's fraction Arrow does not read, 13:05:00,500, and (audit97) a date in a
            # strptime format, whose day 31 of February Arrow's reader reads as March 3: read as
            # text, parsed and checked here)
            types[TIME] = pa.string() if unread_fraction(first, opts.time) or is_format(
                opts.time) else time_type(opts.time, first)
    # a state written as an on/off flag ('true' / 'false'): read as such, then as 1 / 0
    flags = [n for n in types if role(n) == "S" and is_flag(first_row[names.index(n)])]
    types.update(dict.fromkeys(flags, pa.bool_()))
    # a column without a header (Excel's trailing separator) is left out if it holds nothing
    unnamed = {names[i]: pa.string() for i, h in enumerate(header) if not h and named[i] is None}
    try:
        table = _read_csv_typed(path, names, {**types, **unnamed}, opts)
    except _TimeAsText:        # a cell Arrow's reader does not read (a fraction after row 1):
        types[TIME] = pa.string()     # the column as text, read and located by _stamps
        table = _read_csv_typed(path, names, {**types, **unnamed}, opts)
    _check_unnamed_empty(table, header, names, unnamed, path)
    if in_rows:
        opts = _read_in_rows_order(table.column(TIME), path, header[names.index(TIME)], opts)
    if TIME in types:          # and from here on rows are counted without them
        table = _without_empty_rows(table, path, lines)
        # (names96) a refusal of the time quotes its cells as written, not as the instant read
        lines = replace(lines, empty_left_out=True, time_field=names.index(TIME))
    if TIME in types and pa.types.is_floating(types[TIME]) and TIME not in scales:
        said_if_not_seconds(_values(table.column(TIME)), path, header[names.index(TIME)],
                            own=active(opts.roles))
    columns = _columns(table.select(list(types)))
    columns.update({n: pc.cast(columns[n], pa.float64()) for n in flags})
    columns.update(_unmarked(columns, types, opts, path, lines,
                             {n: h for n, h in zip(names, header)}))
    said_read(noted, columns)
    try:
        if CLOCK in columns:
            columns[TIME] = _joined_time(columns[TIME], columns.pop(CLOCK), path, opts)
        elif TIME in types and pa.types.is_string(types[TIME]) and (
                opts.time == "iso8601" or is_format(opts.time) or in_rows):
            columns[TIME] = _stamps(columns[TIME], path, opts)
        elif TIME in types and pa.types.is_string(types[TIME]):
            columns[TIME] = elapsed_seconds(columns[TIME], opts.time, path,
                                            header[names.index(TIME)])
    except ContractError as exc:
        raise lines.located(exc) from None
    return _converted(columns, scales), _renames(header, named), _rescaled(scales), lines


def _unmarked(columns: dict, types: dict, opts: ReadOptions, path: Path, lines: Lines,
              header: dict) -> dict:
    """The number columns holding a numeric mark of ``data.missing_values`` (-9999) or an
    infinite reading (``INF``), its cells missing, however written (:mod:`.marks`); said where
    the column is no temperature's (an error or a state could read the number), and an infinity
    always, with its rows (``header``: the file's header of a contract name, for the message)."""
    out = {}
    for name, column in columns.items():
        if types.get(name) != pa.float64() or name == TIME:
            continue
        values = _values(column)
        where = marks.hits(values, opts.missing_values)
        if not where.any():
            continue
        out[name] = pa.chunked_array([pa.array(values, pa.float64(), mask=where | np.isnan(values))])
        infinite = np.isinf(values)
        if infinite.any():
            own = f" (its header in the file: {header[name]!r})" if header.get(name, name) != name \
                else ""
            rows = np.flatnonzero(infinite)
            shown = [lines.at(int(r) + 1) for r in rows[:marks.SHOWN_ROWS]]
            logger.warning(f"{path}: {marks.infinite_said(name, shown, rows.size)}{own}")
        marked = where & ~infinite         # a mark's cells (an infinity is said above)
        if role(name) != "T" and marked.any():
            logger.warning(f"{path}: column {name!r}: {int(marked.sum())} "
                           "cell(s) equal to a number of data.missing_values "
                           f"({marks.numbers_given(opts.missing_values)}) read as missing")
    return out


def _order_in_rows(first: str, opts: ReadOptions) -> bool:
    """A one-file record's time of dates with slashes, ``data.time=auto``: the order its rows
    say is decided from the cells its read reads (:mod:`.slashed`)."""
    return opts.order_in_rows and opts.time == "auto" and is_slashed_stamp(first)


def _read_in_rows_order(cells: pa.ChunkedArray, path: Path, header: str, opts: ReadOptions
                        ) -> ReadOptions:
    """``opts`` with ``time`` the order the time cells ``cells`` say, or their run settles
    (unchanged where none: its first row's, as a record whose rows disagree is read, refused
    naming ``data.time``)."""
    return read_in(settled([(said_by(cells, path, header), path, header, cells)], opts.dayfirst),
                   opts, path, path)


def _without_empty_rows(table: pa.Table, path: Path, lines: Lines) -> pa.Table:
    """``table`` without its rows of empty cells (Excel's empty row, ``;;;``), left out as a
    blank line is, and said: with a time column each row carries its own time, so nothing
    moves (without one, such a row is a sample not taken: a gap)."""
    if not table.column(TIME).null_count:
        return table
    empty = pa.chunked_array([pa.array(np.ones(table.num_rows, bool))])
    for column in table.columns:
        empty = pc.and_(empty, column.is_null())
    flags = empty.to_numpy()
    if not flags.any():
        return table
    logger.warning(f"{path}, {lines.at(int(np.argmax(flags)) + 1)}: {int(flags.sum())} row(s) of "
                   "empty cells left out, as blank lines are (rows after it counted without)")
    return table.filter(pc.invert(empty))


def said_read(noted: dict, columns: dict) -> None:
    """The notes of ``noted`` (:attr:`.roles.Naming.noted`) said, now that ``columns`` are read,
    but of an all-empty one: it is refused as empty (:func:`.values._refuse_empty`), which the
    note would only precede (data101)."""
    said_notes(noted, {name for name in noted.values()
                       if name in columns and all_empty(columns[name])})


def all_empty(column) -> bool:
    """No cell of ``column`` holds a value (empty, or NaN)."""
    valid = len(column) - column.null_count
    return valid == 0 or valid == (pc.sum(pc.is_nan(column)).as_py() or 0)


def _check_unnamed_empty(table: pa.Table, header: list[str], names: list[str], unnamed: dict,
                         path: Path) -> None:
    for name in unnamed:
        column = table.column(name)
        if column.null_count < len(column):
            row = int(np.argmax(column.is_valid().to_numpy(zero_copy_only=False)))
            raise ContractError(f"column {names.index(name) + 1} has no header but holds "
                                f"{column[row].as_py()!r}: give it a header",
                                file=path, row=row + 1)


def _check_delimiter(header: str, first: str, path: Path, opts: ReadOptions) -> None:
    """A single column whose name holds another separator: the file was read with the wrong
    ``data.delimiter`` (say which one reads it, rather than a misleading name error)."""
    for sep in _OTHER_DELIMITERS:
        if sep != opts.delimiter and sep in header:
            cells = split_line(first, sep, SPLIT)
            comma = sep != "," and opts.decimal != "," and any(
                re.fullmatch(r"[+-]?\d+,\d+", c.strip()) for c in cells)
            hint = " data.decimal=','" if comma else ""
            shown = header if len(header) <= 80 else f"{header[:60]}... ({len(header)} characters)"
            raise ContractError(f"file looks {sep!r}-separated (one column {shown!r}): "
                                f"set data.delimiter={sep!r}{hint}", file=path)


class NoRows(ContractError):
    """A file with no data row (empty, or its header alone): no campaign and no start to read,
    refused before a folder's campaigns are held out by their starts."""


def peek_csv(path: Path, delimiter: str, encoding: str) -> tuple[list[str], list[str], int]:
    """Header (stripped names; a unit row's units joined), first data row and the lines above
    it (a logger's preamble, the header, a unit row: :mod:`.layout`), without reading the file."""
    encoding = own(path, encoding)
    head = head_lines(path, encoding)
    preamble = header_line(head, delimiter) or 0
    try:
        with open(path, newline="", encoding=text_codec(encoding)) as f:
            for _ in range(preamble):
                f.readline()
            rows = csv.reader(f, delimiter=delimiter)
            header = next(rows, None)
            header = header and unquoted(uncommented(header, head[:preamble]))
            first = next((r for r in rows if r), None)
            campbell = has_unit_row(head)          # (a TOA5 file's units, in its own words)
            units = first is not None and header is not None and (campbell or is_unit_row(first))
            if units:
                header = with_units(header, campbell_units(first) if campbell else first)
                first = next((r for r in rows if r), None)
            below = [first, *(r for _, r in zip(range(MAX_PROPERTY_ROWS), rows) if r)]
            described = property_rows(below) if units and first is not None else 0
            first = below[described] if described else first
            header, doubled = occurrences([name.strip() for name in header or []])
            if doubled and first is not None:        # (a header written twice: every row read)
                header = same_cells(header, doubled, chain(below[described:], rows))
    except UnicodeDecodeError:
        raise undecodable(path, delimiter, encoding=encoding, header_at=preamble) from None
    except csv.Error as exc:       # binary content (a gzip named .csv): no CSV text
        raise ContractError(f"not a CSV text file ({exc}); a compressed or binary file "
                            "must be unpacked or saved as .parquet", file=path) from None
    if not header:
        raise NoRows("empty file", file=path)
    if first is None:
        raise NoRows("file has a header but no data rows", file=path)
    return header, first, preamble + 1 + units + described


# what a test record read as recorded (``missing="keep"``) with a bad time is told to do instead
PIPED_HINT = ("a test record with bad times streams as on the machine when piped: "
              "thermocomp monitor monitor.input=- < FILE")


def _timed(path: Path, value: str, opts: ReadOptions, header: str | None = None) -> ReadOptions:
    """``opts`` with ``time`` the way this file's time column is read (:mod:`.timestamps`)."""
    if not value:
        hint = f" ({PIPED_HINT})" if opts.missing == "keep" else ""    # as a later row's says
        raise ContractError(f"missing time value{hint}", file=path, column=TIME, row=1)
    number = reads_as_number(value, opts.decimal, opts.thousands)
    return replace(opts, time=time_kind(value, opts.time, number, path, header,
                                        dayfirst=opts.dayfirst))


def _joined_time(date, clock, path: Path, opts: ReadOptions):
    """``data.roles.time=[date, time of day]``: the two columns joined (``'28.11.2026
    13:05:00'``) and read as one time column is, ``data.time`` applying to the joined text."""
    text = pc.binary_join_element_wise(pc.utf8_trim_whitespace(pc.cast(date, pa.string())),
                                       pc.utf8_trim_whitespace(pc.cast(clock, pa.string())), " ")
    return _stamps(text, path, opts, " (the date and the time of day joined)")


def _stamps(text, path: Path, opts: ReadOptions, what: str = ""):
    """A time column of text read as its first cell says (:func:`.parsed`: also what Arrow's
    CSV reader does not read, ISO 8601's decimal comma); a cell that is not refused with its
    row."""
    first = _first_valid(text)
    value = "" if first is None else str(first[1]).strip()
    kind = _timed(path, value, opts).time
    target = time_type(kind, value)
    found = first_cast_failure(text, target, kind)
    if found is not None:
        raise ContractError(f"value {found[1]!r}{what} is not {_describe(target, kind, found[1])}",
                            file=path, column=TIME, row=found[0] + 1)
    return parsed(text, target, kind)


def _csv_options(names: list[str], opts: ReadOptions, *, types=None, include=None,
                 use_threads=True, invalid_row_handler=None):
    read = pacsv.ReadOptions(column_names=names, skip_rows=opts.skip_rows, use_threads=use_threads,
                             block_size=_CSV_BLOCK_BYTES, encoding=arrow_encoding(opts.encoding))
    parse = pacsv.ParseOptions(delimiter=opts.delimiter, invalid_row_handler=invalid_row_handler)
    convert = pacsv.ConvertOptions(column_types=types or {}, include_columns=include or [],
                                   decimal_point=opts.decimal, strings_can_be_null=True,
                                   null_values=[*MISSING_TOKENS, *marks.texts(opts.missing_values)],
                                   timestamp_parsers=[opts.time] if is_format(opts.time) else None)
    return dict(read_options=read, parse_options=parse, convert_options=convert)


def _input(path: Path, opts: ReadOptions):
    """The CSV text Arrow reads: ``path`` without its footer (:mod:`.footer`, found once)."""
    if opts.drop_bytes:          # its header written again: those lines left out (.again)
        return without(path, opts.data_bytes, opts.drop_bytes)
    return source(path, opts.data_bytes)


def _read_csv_typed(path: Path, names: list[str], types: dict, opts: ReadOptions) -> pa.Table:
    # Arrow's reader knows no thousands separator nor a Unicode minus ('−1,5', U+2212, as a
    # word processor or a localised Excel writes it): with one, numbers are read as text first
    as_text = opts.thousands is not None
    try:
        try:
            table = _read_as(path, names, types, opts, as_text)
        except pa.ArrowInvalid as exc:
            if as_text or not _CONVERSION_ERROR.search(_first_line(exc)) or not _signed(path):
                exc = _on_one_thread(path, names, types, opts, as_text, exc)
                raise _locate_csv_error(path, names, types, opts, exc) from None
            as_text, table = True, _read_as(path, names, types, opts, True)
    except UnicodeDecodeError:     # Arrow transcoding data.encoding: a byte it does not read
        raise undecodable(path, opts.delimiter, names, opts.encoding) from None
    return _ungroup(table, names, types, path, opts) if as_text else table


def _read_as(path: Path, names: list[str], types: dict, opts: ReadOptions, as_text: bool,
             use_threads: bool = True):
    read_as = {n: pa.string() if as_text and pa.types.is_floating(t) else t
               for n, t in types.items()}
    return pacsv.read_csv(_input(path, opts), **_csv_options(
        names, opts, types=read_as, include=[n for n in names if n in types],
        use_threads=use_threads))


def _on_one_thread(path, names, types, opts, as_text, exc):
    """Arrow's conversion error as one thread meets it: its threads name whichever column they
    convert first (hostile's decimal commas: 'time' in one run, 'T_0' at the same row in the
    next); one thread converts a block's columns in the file's order.  Only on a refusal."""
    if not _CONVERSION_ERROR.search(_first_line(exc)):
        return exc
    try:
        _read_as(path, names, types, opts, as_text, use_threads=False)
    except pa.ArrowInvalid as serial:
        return serial
    return exc


def _signed(path: Path) -> bool:
    """The file holds a Unicode minus (U+2212, in UTF-8; cp1252 has none)."""
    with open(path, "rb") as f, contextlib.suppress(ValueError):   # (an empty file)
        with mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ) as m:
            return m.find(UNICODE_MINUS.encode()) >= 0
    return False


def _ungroup(table: pa.Table, names: list[str], types: dict, path: Path, opts: ReadOptions
             ) -> pa.Table:
    """The number columns read as text, cast to float without ``data.thousands``; a cell that
    does not read refused, the earliest row's of every column (stranger65: the first column in
    the header's order, row 7001 of ``T cabinet`` where row 592 of another failed)."""
    texts, first = {}, {}
    for name, kind in types.items():
        if not pa.types.is_floating(kind):
            continue
        raw = table.column(name)
        at = None if opts.thousands is None else misgrouped(raw, opts.thousands, opts.decimal)
        texts[name] = ungrouped(raw, opts.thousands, opts.decimal)
        found = first_cast_failure(texts[name], kind)
        rows = [r for r in (at, None if found is None else found[0]) if r is not None]
        if rows:
            first[name] = (min(rows), at)
    if first:
        name = min(first, key=lambda n: (first[n][0], names.index(n)))
        row, at = first[name]
        if at == row:
            raw = table.column(name)
            raise ContractError(f"value {raw[at].as_py()!r} does not group its digits by three "
                                f"with data.thousands={opts.thousands!r}",
                                file=path, column=name, row=at + 1)
        raise _bad_cell_error(path, names, name, types[name], opts, types, table)
    for name, text in texts.items():
        table = table.set_column(table.column_names.index(name), name, pc.cast(text, types[name]))
    return table


class _TimeAsText(Exception):
    """A timestamp cell Arrow's typed reader refused: read the time column as text instead."""


def _locate_csv_error(path, names, types, opts, exc) -> ContractError:
    """Turn Arrow's row-less CSV error into one naming the column and row."""
    message = _first_line(exc)
    if "UTF8" in message or _CONVERSION_ERROR.search(message):
        # a cell that is not UTF-8 cannot be read back as text to locate it
        bad_bytes = first_undecodable(path, opts.delimiter, names, opts.encoding)
        if bad_bytes is not None:
            return bad_bytes
    match = _CONVERSION_ERROR.search(message)
    if match:
        texts = _as_text(path, names, types, opts)     # (read once: located, marks listed)
        column = _earliest_bad(names, types, opts, names[int(match.group(1))], texts)
        return _bad_cell_error(path, names, column, types[column], opts, types, texts)
    if "CSV parse error" in message:
        return _malformed_row_error(path, names, opts, message)
    return ContractError(f"unreadable CSV ({message})", file=path)


def _as_text(path, names, types, opts) -> pa.Table | None:
    """The file's number columns read as text (None: it has none), once for a refusal: the
    earliest bad cell, its value and the file's other marks are all read from it (each read
    the file again: leftovers66)."""
    floats = [n for n, t in types.items() if pa.types.is_floating(t)]
    if not floats:
        return None
    return pacsv.read_csv(_input(path, opts), **_csv_options(
        names, opts, include=floats, types=dict.fromkeys(floats, pa.string())))


def _earliest_bad(names, types, opts, column: str, raw: pa.Table | None) -> str:
    """Of the number columns (``raw``: read as text), the one whose first cell that does not
    read is the earliest row (on a tie the first in the file; ``column``, the one Arrow named,
    where it is no number column): Arrow names the first column its threads meet (stranger65:
    row 7001 of one column in one run, row 592 of another in the next, of the same file)."""
    floats = [n for n, t in types.items() if pa.types.is_floating(t)]
    if column not in floats or len(floats) < 2:
        return column
    rows = {}
    for name in floats:
        found = first_cast_failure(ungrouped(raw.column(name), opts.thousands, opts.decimal),
                                   types[name])
        if found is not None:
            rows[name] = found[0]
    return min(rows, key=lambda n: (rows[n], names.index(n))) if rows else column


def _bad_cell_error(path, names, column, target, opts, types=None, texts=None) -> ContractError:
    """The refusal of ``column``'s first cell that does not read (``texts``: the number columns
    as text where read already, :func:`_as_text`)."""
    if texts is not None and column in texts.column_names and pa.types.is_floating(target):
        raw = texts.column(column)
    else:
        raw = pacsv.read_csv(_input(path, opts), **_csv_options(
            names, opts, include=[column], types={column: pa.string()})).column(column)
    number = pa.types.is_floating(target)
    text = ungrouped(raw, opts.thousands, opts.decimal) if number else raw
    found = first_cast_failure(text, target, opts.time)
    if found is None:
        if column == TIME and pa.types.is_timestamp(target):
            raise _TimeAsText      # every cell parses (a fraction Arrow's reader skips)
        return ContractError(f"cannot convert to {target}", file=path, column=column)
    row, value = found[0], raw[found[0]].as_py()
    # a thousands separator or a decimal comma the settings do not read: name the setting
    hint = thousands_hint(str(value), raw, opts.decimal) if number else None
    if hint is None:
        hint = decimal_comma_hint(str(value), opts.decimal)
    if _is_header(path, opts, str(value)):
        hint = (": the file's header written again under its data (a logger restarted?): delete "
                "that line (and a unit row under it), or cut the file there into two files")
    if number and not hint and (not re.search(r"\d", str(value)) or EXCEL_ERROR.fullmatch(
            str(value).strip())):
        marks = _other_marks(path, names, types, opts, str(value), texts)
        if marks:     # (stranger65: each mark of another column was refused at the next read)
            hint = (f": a mark for a value not measured? list the file's marks in "
                    f"data.missing_values ({[str(value), *marks]!r})"
                    + _gap_hint(raw, value, opts.max_gap_samples, marks.values()))
        else:
            hint = (f": a mark for a value not measured? list it in data.missing_values "
                    f"(['{value}'])" + _gap_hint(raw, value, opts.max_gap_samples))
    return ContractError(f"value {value!r} is not {_describe(target, opts.time)}{hint}",
                         file=path, column=column, row=row + 1)


def _is_header(path: Path, opts: ReadOptions, value: str) -> bool:
    """``value`` (a cell refused) is one of the file's headers, with or without its unit: the
    header line repeated under the data (stranger65: it was taken for a missing-value mark, to
    be listed in data.missing_values)."""
    value = value.strip()
    if not value:
        return False
    try:
        header = peek_csv(path, opts.delimiter, opts.encoding)[0]
    except ContractError:
        return False
    return any(value in (h, split_unit(h)[0]) for h in header)


def is_mark(value: str) -> bool:
    """A cell's text that is a mark for a value not measured: no digit, or a formula's error."""
    return not re.search(r"\d", value) or bool(EXCEL_ERROR.fullmatch(value.strip()))


def _other_marks(path, names, types, opts, first: str, raw: pa.Table | None = None) -> dict:
    """``{mark: its longest run in a column}`` of the other marks (:func:`is_mark`) in the
    file's number columns besides ``first`` (none without ``types``; ``raw``: those columns as
    text where read already), so that one refusal lists them all (at most 5)."""
    floats = [n for n, t in (types or {}).items() if pa.types.is_floating(t)]
    if not floats:
        return {}
    if raw is None:
        raw = _as_text(path, names, types, opts)
    runs: dict = {}
    for name in floats:
        cells = raw.column(name)
        values = set(pc.unique(cells).to_pylist()) - {None}
        for value in values:
            if value == first or value in runs or not is_mark(str(value)):
                continue
            if reads_as_number(str(value), opts.decimal, opts.thousands):
                continue
            runs[value] = _longest(cells, value)
            if len(runs) >= 5:
                return runs
    return runs


def _longest(raw: pa.ChunkedArray, mark: str) -> int:
    marked = pc.fill_null(pc.equal(raw, mark), False).to_numpy(zero_copy_only=False)
    edges = np.flatnonzero(np.diff(np.concatenate([[0], marked.astype(np.int8), [0]])))
    return int((edges[1::2] - edges[::2]).max(initial=0))


def _gap_hint(raw: pa.ChunkedArray, mark: str, allowed: int, others=()) -> str:
    """Where the cells ``mark`` of a column (and ``others``, the longest runs of the file's other
    marks), once missing, make a gap longer than ``allowed`` samples: the
    ``data.max_gap_samples`` that interpolates the longest run of them (said with the mark, not
    at the next read)."""
    longest = max(_longest(raw, mark), *others, 0)
    if longest <= allowed:
        return ""
    return (f", each then a gap: data.max_gap_samples={longest} interpolates the longest run of "
            "them here")


def _malformed_row_error(path, names, opts, message) -> ContractError:
    bad = []

    def remember(row):
        bad.append(row)
        return "error"

    with contextlib.suppress(pa.ArrowInvalid):
        pacsv.read_csv(_input(path, opts), **_csv_options(
            names, opts, include=[names[0]], types={names[0]: pa.string()}, use_threads=False,
            invalid_row_handler=remember))
    if not bad:
        return ContractError(f"unreadable CSV ({message})", file=path)
    row = bad[0]
    said = f"expected {row.expected_columns} fields, got {row.actual_columns}"
    if row.actual_columns < row.expected_columns and _last_line(path, opts) == row.text.strip():
        # (stranger66: a DAQ stopped while writing its last row, cut mid-cell, no line end)
        said = (f"the file's last line holds {row.actual_columns} of its {row.expected_columns} "
                "fields: cut off while it was written (the logger stopped?); its cells are not "
                "read as they are, delete that line")
    elif row.text.lstrip().startswith("#"):        # (leftovers67: a logger's note, said)
        said = f"{said}: {STRAY}"
    return ContractError(said, file=path,
                         row=None if row.number is None else row.number - opts.skip_rows)


def _last_line(path: Path, opts: ReadOptions) -> str:
    """The last non-blank line of the file's data (above a footer), stripped."""
    end = path.stat().st_size if opts.data_bytes is None else opts.data_bytes
    with open(path, "rb") as f:
        f.seek(max(0, end - (1 << 16)))
        tail = f.read(end - max(0, end - (1 << 16)))
    lines = [ln for ln in tail.splitlines() if ln.strip()]
    return lines[-1].decode(text_codec(opts.encoding), "replace").strip() if lines else ""


def first_cast_failure(values: pa.ChunkedArray, target: pa.DataType,
                        kind: str = "seconds") -> tuple[int, object] | None:
    """Position and value of the first element that does not cast to ``target``.

    Bisects inside the first failing chunk, so the cost is a few casts of
    one chunk rather than a Python loop over the column.
    """
    offset = 0
    for chunk in values.chunks:
        if not _casts(chunk, target, kind):
            ok, fails = 0, len(chunk)  # chunk[:ok] casts, chunk[:fails] does not
            while fails - ok > 1:
                mid = (ok + fails) // 2
                ok, fails = (mid, fails) if _casts(chunk[:mid], target, kind) else (ok, mid)
            return offset + fails - 1, chunk[fails - 1].as_py()
        offset += len(chunk)
    return None


def _casts(values, target: pa.DataType, kind: str = "seconds") -> bool:
    try:
        parsed(values, target, kind)
    except (pa.ArrowInvalid, pa.ArrowNotImplementedError):
        return False
    return True


def _describe(target: pa.DataType, kind: str = "seconds", value=None) -> str:
    return described(target, kind, value) if pa.types.is_timestamp(target) else "a number"


# ---------------------------------------------------------------------------
# Loading Parquet


def parquet():
    """``pyarrow.parquet``, imported by the first Parquet file read or written: a command on a
    CSV dataset (``run``, ``simulate``, ``monitor``...) never loads it, nor the ``ssl`` it pulls in."""
    import pyarrow.parquet

    return pyarrow.parquet


def _load_parquet(path: Path, opts: ReadOptions) -> dict:
    try:
        table = parquet().read_table(path)
    except (pa.ArrowInvalid, OSError) as exc:
        reason = _ARROW_SOURCE.sub("", _first_line(exc))
        raise ContractError(f"unreadable Parquet file ({reason})", file=path) from None
    table = without_pandas_index(table)
    first = {c: _first_text(table.column(c)) for c in table.column_names}
    named, scales, noted = _contract_names(table.column_names, opts, path, first=first)
    table = table.drop_columns([c for c, n in zip(table.column_names, named) if n is None])
    names = [n for n in named if n is not None]
    # column by column into a dict: Table.set_column copies the schema each time (quadratic in
    # the columns: 2 s for a volumetric campaign's 1483)
    # a date and a time of day: joined below; a run's number or name: split by (.runs)
    raw = ((TIME, CLOCK) if CLOCK in names else ()) + (RUN,)
    columns = {name: col if name in raw else _parquet_time(col, path, opts) if name == TIME
               else _parquet_numbers(col, name, path) for name, col in zip(names, table.columns)}
    said_read(noted, columns)
    if CLOCK in columns:
        columns[TIME] = _joined_time(columns[TIME], columns.pop(CLOCK), path, opts)
    return _converted(columns, scales), _renames(list(first), named), _rescaled(scales), None


def without_pandas_index(table: pa.Table) -> pa.Table:
    """The table without pandas' unnamed index columns (``__index_level_0__``: row labels, not
    data), but for one index of timestamps: ``df.to_parquet()`` of a frame indexed by its time
    stores the time there. That one is kept as a column without a header, as ``df.to_csv()``
    writes it, and read as the time where no other column is (else left out, as such a column
    of a CSV file is refused)."""
    index = [c for c in table.column_names if _PANDAS_INDEX.fullmatch(c)]
    timed = [c for c in index if pa.types.is_timestamp(table.column(c).type)]
    if len(timed) == 1 and "" not in table.column_names:
        index.remove(timed[0])
        table = table.rename_columns(["" if c == timed[0] else c for c in table.column_names])
    return table.drop_columns(index)


def _rescaled(scales: dict) -> dict[str, list[float]]:
    """``{contract name: [scale, offset]}`` of the columns whose values were converted to the
    contract's unit (not only renamed): what the exported ``stream.c`` applies to the lab's file."""
    return {n: [float(scale), float(offset)] for n, (scale, offset) in sorted(scales.items())
            if (scale, offset) != (1.0, 0.0)}


def _renames(raw: list[str], named: list[str | None]) -> dict[str, str]:
    """The file's headers -> contract names where they differ; a time of day joined to its date
    under :data:`CLOCK` (which the reader's report keeps apart: no column of that name is read)."""
    return {r: n for r, n in zip(raw, named) if n not in (None, r)}


def _first_text(column: pa.ChunkedArray) -> str | None:
    """A Parquet column's first value as text: a number for a numeric column (what a role needs
    to know), the first string or timestamp otherwise."""
    kind = column.type
    if pa.types.is_timestamp(kind):
        found = _first_valid(column)
        return None if found is None else found[1].isoformat()
    if pa.types.is_string(kind) or pa.types.is_large_string(kind):
        found = _first_valid(column)
        return None if found is None else str(found[1])
    return "0" if (pa.types.is_floating(kind) or pa.types.is_integer(kind)
                   or pa.types.is_decimal(kind) or pa.types.is_boolean(kind)) else kind.__str__()


def _parquet_numbers(column: pa.ChunkedArray, name: str, path: Path) -> pa.ChunkedArray:
    kind = column.type
    numeric = (pa.types.is_floating(kind) or pa.types.is_integer(kind)
               or pa.types.is_decimal(kind) or (pa.types.is_boolean(kind) and role(name) == "S"))
    if numeric:      # (a float64 column as it is: a cast per column of 1430 costs 40 ms a file)
        return column if pa.types.is_float64(kind) else pc.cast(column, pa.float64())
    found = first_cast_failure(column, pa.float64()) or _first_valid(column)
    row = None if found is None else found[0] + 1
    raise ContractError(f"Parquet dtype {kind} where numbers are expected",
                        file=path, column=name, row=row)


def _parquet_time(column: pa.ChunkedArray, path: Path, opts: ReadOptions) -> pa.ChunkedArray:
    kind = column.type
    if pa.types.is_string(kind) or pa.types.is_large_string(kind):
        return time_of_text(column, path, opts)
    if (pa.types.is_floating(kind) or pa.types.is_integer(kind) or pa.types.is_timestamp(kind)
            or pa.types.is_duration(kind)):
        return column
    raise ContractError(f"Parquet dtype {kind} where seconds or timestamps are expected",
                        file=path, column=TIME)


def time_of_text(column, path: Path, opts: ReadOptions, header: str | None = None):
    """A time column of text (no cell missing) read as a wide file's is: an elapsed ``h:mm:ss``
    (a duration), else as its first cell says (:func:`_stamps`: seconds, a timestamp); a cell
    that is not refused with its row, the column :data:`.contract.TIME`.  A historian's long
    file reads its time column so too (:mod:`.historian`)."""
    first = _first_valid(column)
    if maybe_elapsed(str(first[1]).strip() if first else "", opts.time):
        return elapsed_seconds(column, opts.time, path, header)
    return _stamps(column, path, opts)


def _first_valid(column: pa.ChunkedArray) -> tuple[int, object] | None:
    valid = np.flatnonzero(column.is_valid().to_numpy(zero_copy_only=False))
    return (int(valid[0]), column[int(valid[0])].as_py()) if valid.size else None


# ---------------------------------------------------------------------------
# Columns
#
# From here on a campaign is a dict {name: Arrow column}.  Steps replace
# entries in place, so a replaced column is freed at once and memory stays at
# about one copy of the campaign.


def _columns(table: pa.Table) -> dict:
    return dict(zip(table.column_names, table.columns))


def _values(column) -> np.ndarray:
    """A float column as a numpy copy, NaN where missing."""
    if column.null_count:
        column = pc.fill_null(column, np.nan)
    if isinstance(column, pa.ChunkedArray):
        return column.to_numpy()
    return column.to_numpy(zero_copy_only=False)


def _chunks(column) -> list:
    return column.chunks if isinstance(column, pa.ChunkedArray) else [column]


