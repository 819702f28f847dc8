"""A campaign streamed as CSV text (``thermocomp monitor monitor.input=-``): read as a campaign
file is (``data.delimiter``, ``data.decimal``, ``data.columns``, ``data.roles``, ``data.units``,
``data.time``; a logger's preamble and unit row, its header written again: :mod:`.again`), so a
lab's logger rows stream as they are written; empty cells stay NaN, a non-numeric one is
refused with its row.  With ``data.roles.campaign`` a long file's runs stream as a campaign
each (:func:`stream_campaigns`)."""

from __future__ import annotations

import csv
import fnmatch
import re
from collections.abc import Mapping
from dataclasses import replace
from io import StringIO

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.compute as pc

from ...base.errors import position
from ...base.log import logger, say
from ..context import TIME
from . import marks
from .again import STRAY, comments_in, kept, lines_in, spans_in, warn
from .bits import decoded_frame
from .campbell import has_unit_row
from .campbell import units as campbell_units
from .catman import catman_as_csv, is_catman_text
from .clocksets import undone
from .contract import ContractError
from .csvline import EMPTY, SPLIT, split_line
from .dayfirst import ORDER, WAY, text_says
from .derived import on_frame, without_derived
from .encoding import AUTO, UTF8, check_text, decoded
from .footer import BLANK_UNTIMED, TAIL_BYTES, footer_of
from .graphtec import graphtec_as_csv, is_graphtec_text
from .labfile import RUN_HEADER
from .layout import (
    MAX_PROPERTY_ROWS,
    header_line,
    is_unit_row,
    property_rows,
    uncommented,
    unquoted,
    with_units,
)
from .lvm import is_lvm_text, lvm_as_csv
from .options import RUN_ROLE
from .own_headers import as_named
from .rates import said_if_rate_changes, said_if_rows_missing
from .roles import RUN, active, left_out, named_as_time, naming, said_notes, split_unit
from .runs import run_blocks, run_values
from .scope import is_scope_text, scope_as_csv
from .separators import UNICODE_MINUS, decimal_comma_hint, grouped
from .sinumerik import TRACE_ROOT
from .slashed import stream_format
from .sniff import SNIFF_LINES, detected
from .streamed import check_streamed
from .tables import MISSING_TOKENS, NO_TIME_COLUMN, first_cast_failure, shortened
from .timestamps import (
    CLOCK,
    ELAPSED,
    HOUR_S,
    OF_DAY_KIND,
    compact_format,
    described,
    dst_said,
    elapsed_seconds,
    keyed_format,
    maybe_elapsed,
    on_local_clock,
    parsed,
    pauses,
    seconds_of_day,
    time_kind,
    time_type,
    written_seconds,
)
from .twins import occurrences, same_cells
from .twins import said as said_twice
from .utf16 import has_utf16_mark
from .yokogawa import is_yokogawa_text, yokogawa_as_csv

SOURCE = "<stdin>"
STDIN = "stdin"                 # the campaign id of a stream without a run column
HEADERS = "headers"             # frame attrs: contract name -> the stream's own header
# frame attrs: the instant (UTC) a campaign's timestamps count from (its first read), where its
# time is timestamps: a stream said to continue a campaign is placed on that campaign's clock
TIME_ORIGIN = "time_origin"
BLANK_ROWS = "blank_rows"       # frame attrs: the data rows that follow a blank line (dep107)
BLANK_BACK = "blank_back"       # frame attrs: those of them whose time as written goes back (con109)
# frame attrs (deploy74): data.clock_sets' sets and the server's clock at the last timed row as
# the rows have it (s since the epoch), where sets were given: a restarted connect's live
# sample is read as the log's next row (:func:`.clocksets.after`)
CLOCK_SETS, LAST_READ = "clock_sets", "last_read"
_UNNAMED = re.compile(r"Unnamed: \d+")      # pandas' name for a column without a header


# a lab's binary files by their first bytes: read from a path (data.path), never a stream
_BINARY = {b"\x89HDF\r\n\x1a\n": "an HDF5 file", b"TDSm": "a TDMS log",
           b"PK\x03\x04": "a zip file (an Excel workbook?)", b"PAR1": "a Parquet file",
           b"MATLAB 5.0 MAT-file": "a MATLAB file"}


def _is_tdm(head: bytes) -> bool:
    """The head of NI's USI XML (a TDM header), the element ``usi:tdm`` in its first lines."""
    return head.lstrip(b"\xef\xbb\xbf \t\r\n").startswith(b"<?xml") and b":tdm" in head


# a logger's text export piped in as written, told apart by its head, read as its channels:
# a TwinCAT Scope export (stranger76), a Graphtec logger's CSV (stranger82), a Yokogawa
# viewer's ASCII conversion (stranger82b), HBM catman's ASCII export (stranger84), a LabVIEW
# Measurement File (data86b)
_TEXT_EXPORTS = ((is_scope_text, scope_as_csv), (is_graphtec_text, graphtec_as_csv),
                 (is_yokogawa_text, yokogawa_as_csv), (is_catman_text, catman_as_csv),
                 (is_lvm_text, lvm_as_csv))
# their dates with slashes: data.dayfirst (dates84)
_DATED = (catman_as_csv, scope_as_csv, lvm_as_csv)


def _is_trace(head: bytes) -> bool:
    """The head of a SINUMERIK trace's XML (:mod:`.sinumerik`): its root ``traceCaptureFile``."""
    return head.lstrip(b"\xef\xbb\xbf \t\r\n").startswith(b"<?xml") and TRACE_ROOT in head


def stdin_text(stream, encoding: str = UTF8) -> str:
    """What ``stream`` (``sys.stdin``) holds, decoded with ``data.encoding`` (a Windows
    logger's rows: cp1252) rather than the locale's, or as UTF-16 where it begins with its
    byte-order mark (as a file is, :mod:`.utf16`); a byte it does not read is refused."""
    raw = getattr(stream, "buffer", None)
    if raw is None:                   # already text (a caller's StringIO)
        return stream.read()
    data = raw.read()
    kind = next((k for mark, k in _BINARY.items() if data.startswith(mark)), None)
    if kind is None and _is_tdm(data[:2048]):  # (stranger78: was "not a CSV table ... ','")
        kind = "a DIAdem TDM header, the XML of a TDM/TDX pair"
    if kind is None and _is_trace(data[:4096]):  # (stranger81: "'<?xml ...' is not numeric")
        kind = "a SINUMERIK trace's XML"
    if kind is not None:              # (stranger77: was "byte 0x89 is not utf-8 text ... cp1252")
        raise ContractError(f"stdin holds {kind} (its signature), no rows of text: give the file "
                            "as data.path=<file> (a stream is CSV rows, as they are written)",
                            file=SOURCE)
    if has_utf16_mark(data[:4]):           # Excel's 'Unicode Text'
        encoding = "utf-16"
    else:
        check_text(data[:4], encoding, SOURCE)
    try:
        return decoded(data, encoding)    # (data87: auto, UTF-8 where it reads so, else cp1252)
    except UnicodeDecodeError as exc:
        row = data[:exc.start].count(b"\n")
        said = "UTF-8 or cp1252" if encoding == AUTO else encoding
        raise ContractError(f"byte 0x{data[exc.start]:02x} is not {said} text (set "
                            "data.encoding to the stream's character set, e.g. cp1252)",
                            file=SOURCE, row=row or None) from None


def read_stream(text: str, columns: list[str], opts, recorded: str | None = None,
                lab: Mapping | None = None) -> tuple[pd.DataFrame, dict]:
    """``(frame, missing cells per column)`` of CSV ``text`` (header first) holding ``columns``
    (those the compensator reads).  ``time`` in seconds or as ISO 8601 timestamps (``auto``: as
    the first row reads, like a campaign file, dates with slashes in the order ``recorded``, the
    training record's, where one is: :func:`.slashed.stream_format`; the instant they count from
    in ``attrs`` :data:`TIME_ORIGIN`, None for seconds); the headers named as a campaign file's
    are (``data.columns``, ``data.roles`` with a date and a time of day joined, ``data.units``);
    a column it lacks is named as ``lab`` (the model's ``lab_names_``) names it."""
    df, counts, _, origins = _read_runs(text, columns, opts, recorded, lab, sessions=False)
    df.attrs[TIME_ORIGIN] = origins[0]
    return df, counts


def read_last_run(text: str, columns: list[str], opts, recorded: str | None = None,
                  lab: Mapping | None = None) -> tuple[pd.DataFrame, int]:
    """``(frame, runs)``: :func:`read_stream`'s frame of the last run of a log of ``runs``
    (data88: ``connect.warm``'s log, LabVIEW sessions appended to one file or runs named by
    ``data.roles.campaign``; each told as :func:`stream_campaigns` tells them), its times and
    :data:`TIME_ORIGIN` its own.  A log is written forward, so the last run is the campaign
    running when it was copied: the earlier ones are campaigns a restart does not continue
    (each starts from a reset).  Before, such a log was refused, or (a run column) read as
    one campaign whose times restarted at each run."""
    df, counts, blocks, origins = _read_runs(text, columns, opts, recorded, lab)
    if blocks is None:
        df.attrs[TIME_ORIGIN] = origins[0]
        return df, 1
    _, start, end = blocks[-1]
    last = df.iloc[start:end].drop(columns=RUN).reset_index(drop=True)
    last.attrs[TIME_ORIGIN] = origins[-1]
    return last, len(blocks)


def _read_runs(text: str, columns: list[str], opts, recorded: str | None = None,
               lab: Mapping | None = None, sessions: bool = True
               ) -> tuple[pd.DataFrame, dict, list | None, list]:
    """:func:`read_stream`'s ``(frame, missing cells per column)``, the runs' row blocks
    ``(campaign id, first row, end row)`` (None without a run column) and each run's
    :data:`TIME_ORIGIN` (None: its time is no timestamp): the runs are found once, where their
    ids are checked, and both the times and the campaigns are cut by them."""
    text = text.lstrip("\ufeff").replace(UNICODE_MINUS, "-")
    as_csv = next((convert for is_export, convert in _TEXT_EXPORTS if is_export(text)), None)
    if as_csv is not None:          # a logger's export piped in as written, its rows as CSV
        dayfirst = _dayfirst(opts.dayfirst, recorded, text) if as_csv in _DATED else None
        text = (lvm_as_csv(text, SOURCE, dayfirst, STDIN if sessions else None)
                if as_csv is lvm_as_csv else as_csv(text, SOURCE, dayfirst) if as_csv in _DATED
                else as_csv(text, SOURCE))
        opts = replace(opts, delimiter=",", decimal=".", thousands=None)
        if as_csv is lvm_as_csv and text.startswith(f"{RUN_HEADER},"):   # (data87) a run each
            opts = replace(opts, roles={**opts.roles, RUN_ROLE: RUN_HEADER})
    opts = detected(text.splitlines()[:SNIFF_LINES], opts, SOURCE)   # data.delimiter=auto ...
    text = _table(text, opts.delimiter)
    header = split_line(text.split("\n", 1)[0], opts.delimiter, SPLIT)
    # (the file reader's missing values: pandas' own lack a Campbell logger's NAN, lab74)
    texts = [*MISSING_TOKENS, *marks.texts(opts.missing_values)]   # (a number's: by value)
    try:
        if opts.thousands is None:
            df = pd.read_csv(StringIO(text), sep=opts.delimiter, decimal=opts.decimal,
                             na_values=texts)
        else:
            df = _grouped(pd.read_csv(StringIO(text), sep=opts.delimiter, dtype=str,
                                      na_values=texts), opts)
    except Exception as exc:    # pandas raises several kinds for a bad stream
        raise ContractError(f"stdin is not a CSV table with a header, data.delimiter="
                            f"{opts.delimiter!r} ({' '.join(str(exc).split())})",
                            file=SOURCE) from None
    blank_rows = _after_blank_lines(text, len(df))
    df = _twins(df, header)
    df, scales, blocks = _named(df, opts)
    if opts.bits:             # a PLC's status word: its declared bits, as a file's (lab83)
        df = decoded_frame(df, opts.bits, df.attrs.get(HEADERS, {}), SOURCE)
    absent = [c for c in columns if c not in df.columns]
    if not absent and df.empty:
        raise ContractError("stdin has a header but no data row", file=SOURCE)
    if absent:
        raise ContractError("stdin lacks a column the compensator reads, "
                            + as_named(absent, lab or {}) + _unread(df, columns),
                            file=SOURCE, column=",".join(absent))
    origins = [None] * (1 if blocks is None else len(blocks))
    back = []
    if TIME in df.columns:        # timestamps counted from each run's first, as a file's runs
        back = _written_back(df[TIME], blank_rows)
        runs = [df[TIME]] if blocks is None else [df[TIME].iloc[start:end]
                                                  for _, start, end in blocks]
        timed = [_sets_undone(*seconds_and_origin(t, _time_format(t, opts.time, recorded,
                                                               opts.dayfirst),
                                                  opts.timezone, df.attrs.get(HEADERS, {}).get(TIME)),
                                opts.clock_sets, df.attrs)
                 for t in runs]
        df[TIME] = pd.concat([seconds for seconds, _ in timed])
        origins = [origin for _, origin in timed]
    else:                         # (stranger73: a lab's untimed rows crashed the monitor)
        df.insert(0, TIME, _untimed(len(df), blocks, opts.sample_period_s))
        if blank_rows:            # (dep108b) left out, said as the file reader and stream.c say it
            logger.warning(f"{SOURCE}, {position(blank_rows[0])}: {BLANK_UNTIMED}")
    # every data column is numeric (the contract's T_, E_, S_ and time), not only those the
    # model reads: the measured errors and the context are read from the same frame
    numeric = list(dict.fromkeys([*columns, *(c for c in df.columns
                                              if c == TIME or str(c)[:2] in ("T_", "E_", "S_"))]))
    for c in numeric:
        values = _with_decimal(df[c], opts.decimal)
        bad = pd.to_numeric(values, errors="coerce").isna() & df[c].notna()
        if bad.any():
            row = int(np.flatnonzero(bad)[0])
            raise ContractError(f"non-numeric value: {df[c].iloc[row]!r} is not a number"
                                + decimal_comma_hint(df[c].iloc[row], opts.decimal),
                                file=SOURCE, column=c, row=row + 1)
        df[c] = pd.to_numeric(values, errors="coerce")
        if c != TIME:          # data.missing_values' -9999, however written, and INF (.marks)
            _infinite_said(df[c], c)
            df[c] = df[c].mask(marks.hits(df[c], opts.missing_values))
        if c in scales:            # a unit in the header (or data.units): the contract's
            scale, offset = scales[c]
            df[c] = df[c] * scale + offset
    df = on_frame(df, opts.derive, SOURCE)      # data.derive: the same arithmetic as a file's
    df.attrs[BLANK_ROWS], df.attrs[BLANK_BACK] = blank_rows, back
    return df, {c: int(n) for c, n in df[numeric].isna().sum().items() if n}, blocks, origins


def _after_blank_lines(table: str, rows: int) -> list[int]:
    """(dep107) The data rows of ``table`` (its header first, as :func:`_table` gives it) that
    follow a blank line among the rows (0-based; not after the last row); none where its lines
    are not its ``rows`` one to one (the reader leaves blank lines out)."""
    filled = [line.strip() != "" for line in table.split("\n")[1:]]
    if sum(filled) != rows:
        return []
    after, row, blank = [], 0, False
    for full in filled:
        if full:
            if blank and row:
                after.append(row)
            row, blank = row + 1, False
        else:
            blank = True
    return after


def _written_back(time: pd.Series, rows: list[int]) -> list[int]:
    """(con109) The data rows of ``rows`` (those after a blank line) whose time as written (a
    number, an ``h:mm:ss``) is not after the row above's: a time of day gone back past midnight,
    which the reader carries on a day (:func:`.timestamps.past_midnight`), where ``stream.c``
    (its ``day_passed``) starts a campaign at the blank line, as the data contract says."""
    return [r for r in rows if written_seconds(time.iloc[r]) <= written_seconds(time.iloc[r - 1])]


def _with_decimal(column: pd.Series, decimal: str) -> pd.Series:
    """``column`` with ``data.decimal`` read as the point where pandas left it text: a column
    holding one cell that is no number is read as text, its decimal commas as written (audit86:
    every cell of it was then no number, and the first row named for a bad one further down)."""
    if decimal == "." or pd.api.types.is_numeric_dtype(column):
        return column
    return column.str.strip().str.replace(decimal, ".", regex=False)


def _infinite_said(column: pd.Series, name: str) -> None:
    """Say the infinite readings of ``column`` (``INF``), read as missing, as the file reader
    says them (stream rows counted as a file's data rows)."""
    infinite = np.flatnonzero(np.isinf(column.to_numpy(float)))
    if infinite.size:
        shown = [position(int(r) + 1) for r in infinite[:marks.SHOWN_ROWS]]
        logger.warning(f"{SOURCE}: {marks.infinite_said(name, shown, infinite.size)}")


def _sets_undone(seconds: pd.Series, origin, sets, attrs: dict):
    """``(seconds, origin)`` of a run with ``data.clock_sets`` undone in them, as a file's are
    (:func:`.clocksets.undone`: the rows streamed are the machine's log as ``replay`` reads it);
    the sets and the last row's clock as the stream has it kept in ``attrs``."""
    if not sets or origin is None:
        return seconds, origin
    read = seconds.dropna()
    attrs.update({CLOCK_SETS: sets,
                  LAST_READ: origin.timestamp() + float(read.iloc[-1]) if len(read) else None})
    values, origin, found = undone(seconds.to_numpy(float), origin, sets, SOURCE)
    if found:
        say(f"data.clock_sets: {len(found)} of the {len(sets)} clock set(s) undone in "
            f"{SOURCE}'s times")
    return pd.Series(values, index=seconds.index), origin


def _untimed(rows: int, blocks: list | None, period_s: float | None) -> np.ndarray:
    """The time of rows without a time column, as a file's: ``row * data.sample_period_s``,
    from 0 in each run (``blocks``); refused as a file is without the period."""
    if period_s is None:
        raise ContractError(NO_TIME_COLUMN, file=SOURCE)
    row = np.arange(rows, dtype=float)
    for _, start, end in blocks or ():
        row[start:end] -= start
    return row * float(period_s)


def _dayfirst(given: bool | None, recorded: str | None, text: str) -> bool | None:
    """The order a logger's export streamed (``text``) reads its dates with slashes in:
    ``data.dayfirst``, else the training record's, ``recorded`` (data86: a Scope export of a
    morning, no day past 12, was refused where the record's night run had settled it); an
    export whose own dates say the other order is refused naming the date."""
    if given is not None or not recorded or not recorded.startswith(tuple(ORDER.values())):
        return given
    day_first = recorded.startswith(ORDER[True])
    other = next((s for s in text_says(text, SOURCE) or () if s.day_first != day_first), None)
    if other is not None:
        raise ContractError(f"date {other} says its dates with slashes are {WAY[not day_first]}, "
                            f"but the record the model was trained on says {WAY[day_first]}: a "
                            "stream is read in its record's order; stream the exports of the PC "
                            "that wrote the record, or set data.dayfirst", file=SOURCE,
                            line=text.count("\n", 0, text.find(other.date)) + 1)
    return day_first


def _time_format(time: pd.Series, given: str, recorded: str | None,
                 dayfirst: bool | None = None) -> str:
    """``data.time`` of a run's time cells: as given, or (``auto``) in the order of the training
    record's dates with slashes, ``recorded`` (:func:`.slashed.stream_format`; a row saying the
    other order refused), where it holds such dates; else in ``data.dayfirst``'s (dates84)."""
    if given != "auto":
        return given
    told = stream_format(time, recorded, SOURCE)
    if told or dayfirst is None:
        return told or given
    first = time.dropna().astype(str).str.strip()
    return (not first.empty and keyed_format(first.iloc[0], dayfirst)) or given


def stream_campaigns(text: str, columns: list[str], opts, recorded: str | None = None,
                     lab: Mapping | None = None) -> tuple[dict, dict]:
    """``({campaign id: frame}, {campaign id: missing cells per column})`` of the stream: one
    campaign ``stdin``, or, with ``data.roles.campaign``, a campaign per run named as the long
    file's are (:mod:`.runs`), so each starts from a reset as a file's run does (:func:`read_stream`;
    ``recorded``: the training record's order of dates with slashes; ``lab``: as there)."""
    df, counts, blocks, origins = _read_runs(text, columns, opts, recorded, lab)
    if blocks is None and TIME in df.columns:
        blocks, origins = _pause_runs(df, origins[0], opts.runs_at_pauses)
    check_streamed(df[without_derived(df.columns, opts.derive)], blocks, opts, SOURCE,
                   df.attrs.get(HEADERS, {}))        # (data87) as a streamed file's values
    _said_if_rate_changes(df, blocks, opts.time != OF_DAY_KIND)
    if blocks is None:
        df.attrs[TIME_ORIGIN] = origins[0]
        return {STDIN: df}, ({STDIN: counts} if counts else {})
    parts = {cid: df.iloc[start:end].drop(columns=RUN, errors="ignore").reset_index(drop=True)
             for cid, start, end in blocks}
    for part, origin in zip(parts.values(), origins):
        part.attrs[TIME_ORIGIN] = origin
    missing = {cid: {c: int(n) for c, n in part[list(counts)].isna().sum().items() if n}
               for cid, part in parts.items()}
    return parts, {cid: n for cid, n in missing.items() if n}


def _said_if_rate_changes(df: pd.DataFrame, blocks: list | None, gaps: bool = True) -> None:
    """(audit107) A logger set to another sample rate within a run of the stream, said as the
    file reader says it of the same rows, naming the stream's data row: 100 s rows, then 1000 s
    ones from data row 202, were monitored without a word (``replay`` of the file said it).
    (dep107c) Else its stretches without rows, as the file reader says them (``gaps``: not
    said already, as a time of day's are by :func:`seconds_and_origin`): 5 rows left out of a
    100 s stream were monitored without a word."""
    if TIME not in df.columns:
        return
    for _, start, end in blocks or [(STDIN, 0, len(df))]:
        seconds, at = df[TIME].to_numpy(float)[start:end], (lambda row, start=start: position(row + start))
        if not said_if_rate_changes(seconds, SOURCE, at=at) and gaps:
            said_if_rows_missing(seconds, SOURCE, at=at)


def _pause_runs(df: pd.DataFrame, origin, at_pauses: bool) -> tuple[list | None, list]:
    """(audit106) ``data.runs_at_pauses`` on a stream: its runs ``stdin_1``, ``stdin_2`` ... where
    its time pauses (:func:`.runs.pause_blocks`' rule), each from its first sample as the file's
    runs and stream.c's (``TC_PAUSE_S``) are, timestamps counted from it (a stream of one run: no
    pause, one campaign); it went on as one campaign, the pause unsaid.  (dep107) With or without
    the key, a blank line whose next row's time is not after the last (the campaigns ``thermocomp
    rows`` writes, each from its time 0, a blank line between: where stream.c starts one) parts
    them too; they were streamed as one campaign, each start read as a clock set back and a
    common step of every sensor.  A stray blank line within a run (its time going on) stays
    nothing, as the file's read leaves it out.  (con109) A time of day carried past midnight
    (dep108d) goes on, but as written it goes back: a blank line there parts them as in
    stream.c (it was nothing, the C starting a campaign).  ``df``'s time re-based in place;
    ``(blocks, each run's time origin)``."""
    seconds = df[TIME].to_numpy(float)
    found = pauses(seconds) + 1 if at_pauses else np.array([], int)
    anew = [r for r in df.attrs.get(BLANK_ROWS, []) if not seconds[r] > seconds[r - 1]
            or r in df.attrs.get(BLANK_BACK, ())]
    found = np.union1d(found, np.asarray(anew, int)).astype(int)
    if not found.size:
        return None, [origin]
    edges = [0, *map(int, found), len(seconds)]
    blocks = [(f"{STDIN}_{k}", a, b) for k, (a, b) in enumerate(zip(edges, edges[1:]), 1)]
    origins = [origin] * len(blocks)
    if origin is not None:                     # a run's timestamps from its own first
        for k, (_, a, b) in enumerate(blocks):
            origins[k] = origin + pd.Timedelta(seconds=float(seconds[a]))
            df.iloc[a:b, df.columns.get_loc(TIME)] = seconds[a:b] - seconds[a]
    why = [*(["the time's pauses (data.runs_at_pauses)"] if len(anew) < len(found) else []),
           *([f"{len(anew)} blank line(s) after which the time starts again or a time of day "
              "passes midnight (where stream.c starts a campaign)"] if anew else [])]
    say(f"{SOURCE}: {len(blocks)} runs by {' and '.join(why)} streamed as campaigns, each from a "
        "reset")
    return blocks, origins


def _table(text: str, sep: str) -> str:
    """``text`` from its header on, a unit row's units joined to the headers (``T1`` over
    ``°C``: ``T1 [°C]``), as a campaign file's table is found (:mod:`.layout`): a logger's
    preamble, unit row and rows describing the channels under it stream as they are written."""
    lines = text.splitlines()
    start = header_line(lines[:SNIFF_LINES], sep) or 0
    campbell = has_unit_row(lines)          # (a TOA5 file's units, in its own words)
    units = len(lines) > start + 1 and (
        campbell or is_unit_row(split_line(lines[start + 1], sep, EMPTY)))
    text = _without_again(_without_footer(text, lines, start, sep), start, units, sep)
    lines = text.splitlines()
    if not lines:
        return text
    written = split_line(lines[start], sep, SPLIT)
    header = unquoted(uncommented(written, lines[:start]))   # (stranger66: '# t [s]'; lab75)
    if not start and not units and header == written:
        return text
    if units:
        row = split_line(lines[start + 1], sep, EMPTY)
        header = with_units(header, campbell_units(row) if campbell else row)
    body = lines[start + 1 + units:]
    if units:      # (catman70: rows describing the channels under the unit row, left out)
        body = body[property_rows([split_line(ln, sep, EMPTY)
                                   for ln in body[:MAX_PROPERTY_ROWS + 1] if ln.strip()]):]
    out = StringIO()
    csv.writer(out, delimiter=sep, lineterminator="\n").writerow(header)
    return out.getvalue() + "\n".join(body) + "\n"


def _without_footer(text: str, lines: list[str], start: int, sep: str) -> str:
    """``text`` without the footer under its rows (a logger's ``#`` run summary, ``End of
    data``), left out and said as the file reader says it (stranger75: the run file the
    reader read was refused on stdin, "a '#' line among the rows")."""
    if len(lines) <= start:
        return text
    data = text.encode()
    said, cut = footer_of(data[-TAIL_BYTES:], len(data), sep, len(split_line(lines[start], sep, EMPTY)))
    if not said:
        return text
    logger.warning(f"{SOURCE}: footer left out ({len(said)} line(s) under the data: "
                   f"{shortened(said[0])!r})")
    return data[:cut].decode()


def _without_again(text: str, start: int, units: bool, sep: str) -> str:
    """``text`` without the header written again under its data (and the unit row after it)
    and, in a stream that writes ``#`` comments, a comment among its rows, said with their
    stream lines, by the file reader's rule (:mod:`.again`): a logger's day file piped in as it
    was written (the header's text in a number column refused the stream); a ``#`` line of
    another width among the rows of a stream that writes no comment refused as the file
    reader refuses it."""
    data = text.encode()
    spans = spans_in(data, start, units, sep)
    _no_stray(data, spans, start, units, sep)
    if not spans:
        return text
    warn(SOURCE, lines_in(data, spans), lines_in(data, spans.comments))
    return kept(data, spans, len(data)).decode()


def _no_stray(data: bytes, spans, start: int, units: bool, sep: str) -> None:
    """Refuse a ``#`` line among the rows not left out (:data:`.again.STRAY`) whose fields are
    not the header's: the file reader's malformed row, said as it says it."""
    body = 0
    for _ in range(start + 1 + units):
        body = data.find(b"\n", body) + 1
        if not body:
            return
    width = len(split_line(data[:body].decode().splitlines()[start], sep, EMPTY))
    for first, end in comments_in(data, body, len(data), spans):
        got = len(split_line(data[first:end].decode().rstrip("\r\n"), sep, EMPTY))
        if got != width:
            raise ContractError(f"expected {width} fields, got {got}: {STRAY}", file=SOURCE,
                                line=lines_in(data, [(first, end)])[0])


def _grouped(df: pd.DataFrame, opts) -> pd.DataFrame:
    """``df`` read as text, each column whose every cell is a number (``data.decimal``, its
    digits grouped by three with ``data.thousands`` or not) as numbers, the others as written,
    as the file reader reads them (stranger65: pandas' ``thousands`` took the '.' out of a date
    too, '14.06.2027' -> 14062027, and the lab's day file piped into ``monitor`` was refused)."""
    pattern = grouped(opts.thousands, opts.decimal)     # the file reader's own rule
    for c in df.columns:
        text = df[c].str.strip()
        text = text.mask(text.str.fullmatch(pattern).fillna(False).astype(bool),
                         text.str.replace(opts.thousands, "", regex=False))
        if opts.decimal != ".":
            text = text.str.replace(opts.decimal, ".", regex=False)
        number = pd.to_numeric(text, errors="coerce")
        if number.notna().sum() == df[c].notna().sum():
            df[c] = number
    return df


def _twins(df: pd.DataFrame, header: list[str]) -> pd.DataFrame:
    """``df`` with a header written twice read as a file's is (:mod:`.twins`: pandas read them
    as 'T1' and 'T1.1'): the second ``T1#2``, or left out where its values are the first's."""
    names, doubled = occurrences([h.strip() for h in header])
    if not doubled or len(names) != len(df.columns):
        return df
    names = same_cells(names, doubled, df.astype(str).itertuples(index=False))
    for line in said_twice(names, dict(zip(names, names))):
        say(f"{SOURCE}: {line}")
    return df.set_axis(names, axis=1).drop(columns=[n for n in names if left_out(n) is not None])


def _named(df: pd.DataFrame, opts) -> tuple[pd.DataFrame, dict, list | None]:
    """``df`` under contract names, the unit conversions and the runs' row blocks (None without
    ``data.roles.campaign``): ``data.columns`` alone as before, or, with ``data.roles`` or
    ``data.units`` set, as :func:`.roles.naming` names a campaign file's headers (a date and a
    time of day joined into one time)."""
    if not (active(opts.roles) or opts.units):
        df = df.rename(columns={k: v for k, v in opts.columns.items() if k in df.columns})
        # (lead91) the time under a header the file reader takes for it (``t``, ``Zeit``, in
        # seconds: another unit is data.units' to convert): the stream refused the record's
        # own file, "no 'time' column"
        timed = [c for c in df.columns if named_as_time(str(c))
                 and split_unit(str(c))[1] in (None, "s")]
        if TIME not in df.columns and len(timed) == 1:
            df = df.rename(columns={timed[0]: TIME})
            df.attrs[HEADERS] = {TIME: timed[0]}
        return df, {}, None
    # Excel's trailing separator: a column without a header ('Unnamed: 4') that holds nothing
    df = df.drop(columns=[c for c in df.columns if _UNNAMED.fullmatch(str(c))
                          and df[c].isna().all()])
    first = {c: None if df.empty or pd.isna(df[c].iloc[0])
             else str(_with_decimal(df[c].iloc[:1], opts.decimal).iloc[0]) for c in df.columns}
    roles = _runs_if_named(list(df.columns), opts.roles)
    plan = naming(list(df.columns), roles, opts.columns, first, ".", SOURCE, opts.units)
    said_notes(plan.noted)          # (a stream: its cells still to come)
    df = df[[c for c in df.columns if c in plan.names]].rename(columns=plan.names)
    df.attrs[HEADERS] = {name: raw for raw, name in plan.names.items() if raw != name}
    run = next((raw for raw, name in plan.names.items() if name == RUN), None)
    blocks = None
    if run is not None:
        blocks = run_blocks(run_values(pa.array(df[RUN], from_pandas=True)), run, SOURCE)
        df[RUN] = _run_ids(blocks, df.index)
    return with_clock_joined(df), plan.scales, blocks


def with_clock_joined(df: pd.DataFrame) -> pd.DataFrame:
    """``df`` with a date (``time``) and its time of day (:data:`CLOCK`, ``Datum;Uhrzeit``)
    joined into one time (``'05.03.2027 21:30:00'``), as the file reader joins the pair
    (``data.roles.time=[date, time of day]``); as it is without the two (a time of day without
    its date column is left to the time's own rule: a model that reads no time serves such a
    block, as before).  (data94) The served model's block reads the pair so too, as
    ``stream.c`` does: it was refused, "a date without a time of day"."""
    if CLOCK not in df.columns or TIME not in df.columns:
        return df
    date, clock = (df[c].astype("string").str.strip() for c in (TIME, CLOCK))
    return df.drop(columns=CLOCK).assign(**{TIME: (date + " " + clock).astype(object)})


def _unread(df: pd.DataFrame, columns: list[str]) -> str:
    """The stream's sensor columns the compensator does not read, with their own headers: a
    lacking column is often one of them renamed ('Gestell2 [°C]' for 'Gestell 2 [°C]'), and the
    message named only the contract name the model wants."""
    own = df.attrs.get(HEADERS, {})
    unread = [c for c in df.columns if str(c)[:2] == "T_" and c not in columns]
    if not unread:
        return ("; give the rows every column of the data the model was fitted on, under the "
                "header it had there")
    return ("; stdin's sensor column(s) it does not read: "
            + ", ".join(f"{own[c]!r} (read as {c})" if c in own else repr(c) for c in unread)
            + ": renamed? give each the header it had in the data the model was fitted on")


def _runs_if_named(headers: list[str], roles: dict) -> dict:
    """``roles`` without ``data.roles.campaign`` where no header of the stream matches it: the
    model was fitted on a long file of runs (its data config needs the key), and a logger's
    file of one run, without that column, streams as one campaign (it was refused as a column
    'not read', with no key to give)."""
    pattern = roles.get(RUN_ROLE)
    if not pattern or any(fnmatch.fnmatchcase(name, pattern)
                          for h in headers for name in (str(h), split_unit(str(h))[0])):
        return roles
    say(f"{SOURCE}: no column matches data.roles.{RUN_ROLE}={pattern!r}: "
        f"the rows stream as one campaign '{STDIN}'")
    return {k: v for k, v in roles.items() if k != RUN_ROLE}


def _run_ids(blocks: list, index: pd.Index) -> pd.Series:
    """Each row's campaign id by its run (``Lauf_3``), from the runs' row blocks as
    :func:`.runs.run_blocks` checks a long file's (every row says its run, a run's rows stand
    together)."""
    ids = np.empty(len(index), dtype=object)
    for cid, start, end in blocks:
        ids[start:end] = cid
    return pd.Series(ids, index=index)


def stream_seconds(time: pd.Series, time_format: str, zone: str | None = None) -> pd.Series:
    """The stream's ``time`` in seconds since its first row when it holds timestamps, read as a
    campaign file's are (:func:`stream_stamps`); as given otherwise: the numeric check refuses
    what is no number.  A missing time or one that goes back is no refusal here: the stream's
    guard judges it, as on the machine; the first time read (not row 1's, which may be missing)
    is the origin of timestamps (seconds are kept: a missing first one is the stream's time
    rule's, :mod:`thermocomp.core.timerule`)."""
    return seconds_and_origin(time, time_format, zone)[0]


def seconds_and_origin(time: pd.Series, time_format: str, zone: str | None = None,
                       header: str | None = None) -> tuple[pd.Series, pd.Timestamp | None]:
    """:func:`stream_seconds` and the instant (UTC) they count from where ``time`` holds
    timestamps (a time without an offset as written, or on ``zone``'s clock: as a file's
    ``time_origin`` becomes its ``start``, :mod:`.instants`), else None (seconds, elapsed).
    (dep108d) Plain seconds of the day (``header``, the stream's own, or the values say so) are
    carried past midnight as a file's are, by the file reader's function."""
    stamps = stream_stamps(time, time_format, zone)
    if stamps is None and time_format in ("auto", OF_DAY_KIND):     # (data91) as a file's are read
        # (data92) by the file's one function: a value outside a day refused with its row
        seconds = pd.to_numeric(time, errors="coerce").to_numpy(float)
        of_day = seconds_of_day(seconds, SOURCE, header, pauses_said=False, kind=time_format)
        stamps = None if of_day is None else pd.Series(of_day, index=time.index)
    if time_format == OF_DAY_KIND and isinstance(stamps, pd.Series):
        # (data93) rows missing in a time of day: as well a day longer, said as a file's gap is
        said_if_rows_missing(stamps.to_numpy(float), SOURCE, dateless=True)
    if stamps is None or isinstance(stamps, pd.Series):   # seconds; h:mm:ss in seconds
        return (time if stamps is None else stamps), None
    ns, valid = stamps
    origin = ns[np.argmax(valid)]
    return (pd.Series(since(ns, valid, origin), index=time.index),
            pd.Timestamp(int(origin), unit="ns", tz="UTC"))


def since(ns: np.ndarray, valid: np.ndarray, origin: int) -> np.ndarray:
    """Seconds from ``origin`` (ns) of the timestamps ``ns`` (int64), NaN where not ``valid``
    (int64 nanoseconds subtracted before the float: a float64 epoch in ns keeps ~256 ns)."""
    return np.where(valid, (ns - origin) / 1e9, np.nan)


def stream_stamps(time: pd.Series, time_format: str = "auto", zone: str | None = None,
                  served: bool = False, carried: list | None = None):
    """A stream's timestamps as ``(int64 nanoseconds since the epoch, valid)``, read as a
    campaign file's are (:func:`.timestamps.parsed`: ISO 8601 with or without its offset, a
    decimal comma, a day-first ``07.01.2023 08:45:00``, ``data.time``'s format; ``zone``:
    ``data.timezone``, the local clock of timestamps without an offset); the elapsed
    ``h:mm:ss``, or (data89) a time of day passing midnight, as seconds (a Series:
    :func:`.timestamps.elapsed_seconds`, the file's rule); None where the time is seconds (or none is read).
    ``served``: a served model's block (no ``data.timezone`` read), said so in a clock set back;
    (data91) ``carried``: its session's time of day, the block's read on from it
    (:func:`.timestamps.continued`, updated in place), None: a block read alone."""
    read = time.dropna()
    if read.empty:                 # no time at all: every row's for the guard to substitute
        return None
    first, kind = read.iloc[0], time_format
    # h:mm:ss: an elapsed time (data.time=elapsed, or said by its hours or header) or (data89) a
    # time of day passing midnight, read as a file's (it was refused, a time of day)
    clock = kind == ELAPSED or isinstance(first, str) and maybe_elapsed(first.strip(), kind)
    if kind == "auto" and isinstance(first, str) and not clock:    # read as a campaign file's
        kind = time_kind(first.strip(), kind, not pd.isna(pd.to_numeric(first, errors="coerce")),
                         SOURCE, stream=True)
    elif (kind == "auto" and not clock and float(first).is_integer()
          and (form := compact_format(f"{first:.0f}"))):
        kind = form                                     # (realexport73: an AmeriFlux table's
        time = time.map(lambda v: v if pd.isna(v) else f"{v:.0f}")    # 202503272330, as digits)
    text = pa.chunked_array([pa.array(time.astype("string"), type=pa.string())])
    if clock:
        ns = elapsed_seconds(text, kind, SOURCE, stream=True, unwrap=not served,
                             carried=carried).cast(pa.int64())
        return pd.Series(ns.to_numpy(zero_copy_only=False) / 1e9, index=time.index)
    if kind in ("auto", "seconds", OF_DAY_KIND):     # (data91: of_day's numbers, as a file's)
        return None
    target = time_type(kind, str(first).strip())
    found = first_cast_failure(text, target, kind)
    if found is not None:
        row, value = found
        raise ContractError(f"value {value!r} is not {described(target, kind, value)} (data.time="
                            f"{time_format}: the stream's first row is a timestamp)",
                            file=SOURCE, column=TIME, row=row + 1)
    stamps = pc.cast(parsed(text, target, kind), pa.int64())
    valid = stamps.is_valid().to_numpy(zero_copy_only=False)    # a missing time stays NaN
    ns = pc.fill_null(stamps, 0).to_numpy(zero_copy_only=False).copy()
    if zone is not None and target.tz is None:
        ns[valid] = on_local_clock(ns[valid], zone, SOURCE)
    elif target.tz is None:
        said_if_set_back(ns[valid], np.flatnonzero(valid), served)
    return ns, valid


def said_if_set_back(ns: np.ndarray, rows: np.ndarray, served: bool = False) -> None:
    """Say a stream's timestamps without an offset (``ns``, of the data rows ``rows``) set back
    by up to an hour, in the file reader's words (lab77: daylight saving time ending, the zones
    whose clocks went back then named; the stream goes on by the time rule, as stream.c does);
    ``served``: with what a served model's client can do instead of data.timezone (tidy77)."""
    back = np.flatnonzero((np.diff(ns) < 0) & (np.diff(ns) >= -HOUR_S * 1e9))
    if not back.size:
        return
    k = int(back[0])
    origin = str(np.datetime64(int(ns[0]), "ns"))
    row = int(rows[k + 1]) + 1          # (a served block's rows are the request's, not stdin's)
    where = f"column {TIME!r}, data row {row} of the block" if served else (
        f"{SOURCE}, column {TIME!r}, data row {row}")
    said = dst_said(origin, (ns[k] - ns[0]) / 1e9, (ns[k + 1] - ns[0]) / 1e9, "ending", served)
    logger.warning(f"{where}: the clock set back by an hour{said}")
