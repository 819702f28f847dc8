"""A lab's binary record (a National Instruments TDMS log, :mod:`.tdms`; a MATLAB ``.mat`` file,
:mod:`.matfile`) read as its CSV export (extension), as a workbook's sheet is (:mod:`.workbook`):
its channels written into a temporary UTF-8 CSV file that the CSV reader reads, so that roles,
units (in the header: ``Spindle nose [degC]``), the time and every check work as on a CSV file.
No value is read twice: this module only lays the channels out.

A record is a list of :class:`Channel` s (a name with its unit, the values, the time of each
value where the file gives one).  One record whose channels share one time (or, none timed, one
length) is a wide CSV, one row a sample; several records (runs: TDMS groups, a struct array)
the same, one after the other, with a ``run`` column naming each, which ``thermocomp init``
proposes as ``data.roles.campaign`` (:mod:`.runs`: each run a campaign).  One record whose
channels are timed on different grids (a slow temperature module and a fast displacement
module) is written as a long file (``time, channel, value``): the historian's path
(:mod:`.historian`) holds every channel onto one grid of ``data.resample_s`` by sample and
hold, the contract's one rule for channels at different rates (``init`` proposes the period).
Channels of different lengths without a time are refused naming them.

A message about the temporary file names the lab's file, the channel (and its group or
variable) and the data row instead.
"""

from __future__ import annotations

import csv
import re
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...base.log import logger
from .contract import ContractError
from .converted import named_as
from .encoding import UTF8
from .roles import split_unit
from .twins import occurrences

RUN_HEADER = "run"          # the column naming each run of a file holding several
TIME_HEADER = "time"        # the time a file gives as timestamps (UTC) or seconds
_SAFE = re.compile(r"[^\w.\-]+")     # a header's letters a contract name keeps (.roles)


@dataclass
class Channel:
    """One channel: its ``header`` (name and unit, as the CSV header), ``values``, the
    ``time`` of each (``datetime64`` or float seconds; None: none given) and ``where`` it is
    in the file (``group 'Temperatures', channel 'T1'``)."""

    header: str
    values: np.ndarray
    time: np.ndarray | None
    where: str


@dataclass
class Record:
    """One run: its ``label`` (a run column's value) and channels; ``time_header``: the header
    of the time where the file names its time channel (else :data:`TIME_HEADER`)."""

    label: str
    channels: list[Channel]
    time_header: str = TIME_HEADER
    utc: bool = True           # timestamps in UTC (NI's); False: on a clock not said (a datenum)


def with_unit(name: str, unit: str | None) -> str:
    """``name [unit]`` where a unit is given and the name does not say one already."""
    unit = (unit or "").strip()
    return f"{name} [{unit}]" if unit and f"[{unit}]" not in name else name


def on_union_grid(channels: list[Channel]) -> list[Channel]:
    """``channels``, each timed on its own clock (a TwinCAT Scope export's ``Time;Value`` pairs:
    another task's cycle, another target's clock), on the union of their times, each channel's
    cells at the others' times left empty, never held (lab77): channels of one clock share their
    rows, a slower one's cells between its samples empty (stranger76: a tracker every 5 min
    beside temperatures every 10 s)."""
    if not channels or any(c.time is None for c in channels):
        return channels
    grid = np.unique(np.concatenate([c.time for c in channels]))
    laid = []
    for c in channels:
        values = np.full(grid.size, np.nan)
        values[np.searchsorted(grid, c.time)] = c.values
        laid.append(Channel(c.header, values, grid, c.where))
    return laid


def _one_grid(record: Record) -> bool:
    times = [c.time for c in record.channels]
    if all(t is None for t in times):
        return len({c.values.size for c in record.channels}) == 1
    return all(t is not None and t.shape == times[0].shape and np.array_equal(t, times[0])
               for t in times)


def _check(records: list[Record], path: Path) -> bool:
    """Whether the records are written wide (else long: one record, its channels timed on
    different grids); refused: channels of different lengths without a time, runs whose
    channels differ or are on different grids."""
    for record in records:
        if _one_grid(record):
            continue
        untimed = [c for c in record.channels if c.time is None]
        if untimed or len(records) > 1:
            sizes = ", ".join(f"{c.where} {c.values.size}" for c in record.channels[:8])
            fix = ("each channel's time (NI's waveform properties wf_start_time / wf_increment, or "
                   "a time channel), or the channels resampled to one rate before saving"
                   if untimed else "one file per run")
            raise ContractError(f"{record.label}: channels of different lengths or times ({sizes} "
                                f"samples): no grid reads them together; give {fix}", file=path)
        return False
    headers = [c.header for c in records[0].channels]
    timed = {_time_kind(r) for r in records}
    if len(timed) > 1:                  # (a row of one run would lack the time cell)
        said = ", ".join(f"{r.label!r} {_time_kind(r)}" for r in records[:6])
        raise ContractError(f"the runs of one file are timed alike or not at all ({said}): give "
                            "each run the same time (timestamps, or seconds)", file=path)
    if _replaced(records):
        return True
    for record in records[1:]:
        other = [c.header for c in record.channels]
        if set(other) != set(headers):
            odd = sorted(set(other) ^ set(headers))
            raise ContractError(f"run {record.label!r} holds other channels than run "
                                f"{records[0].label!r} ({', '.join(map(repr, odd[:6]))}): the runs "
                                "of one file are read as one table; one file per run",
                                file=path)
    return True


def _replaced(records: list[Record]) -> bool:
    """Runs holding as many channels each, a channel's runs one stretch of them (a sensor
    replaced from one run on under a new name, stranger77: a logger's HDF5 file a group a day):
    written as one table, a channel's cells empty in the runs without it (``init`` proposes the
    ``data.columns`` entry reading the new name as the old, :func:`.frame.renamed_sensors`)."""
    held = [{c.header for c in r.channels} for r in records]
    if len({len(h) for h in held}) > 1 or len({frozenset(h) for h in held}) == 1:
        return False
    for header in set().union(*held):
        runs = [k for k, h in enumerate(held) if header in h]
        if runs[-1] - runs[0] + 1 != len(runs):
            return False
    return True


SHARED = {"": "(the channels every run holds)"}     # lab_as_csv's ``columns`` for :func:`shared`


def shared(records: list[Record]) -> list[Record]:
    """``records`` with the channels every one holds (all, where they hold the same)."""
    every = set.intersection(*({c.header for c in r.channels} for r in records))
    if all(len(r.channels) == len(every) for r in records):
        return records
    return [Record(r.label, [c for c in r.channels if c.header in every], r.time_header, r.utc)
            for r in records]


def replaced_joined(records: list[Record], columns: dict | None) -> list[Record]:
    """``records`` with each channel of a replaced sensor (:func:`_replaced`) that
    ``data.columns`` maps (its header, or its name without the unit) onto the name the old
    channel reads as (``T_`` / ``E_`` / ``S_`` and its name) written under the new channel's
    header: one column, the old values in the runs before, the new after (``init`` proposes the
    entry); ``records`` themselves where none is."""
    if not columns or len(records) < 2 or not _replaced(records):
        return records
    held = [{c.header for c in r.channels} for r in records]
    every = set.intersection(*held)
    moved: dict[str, str] = {}                  # old header -> new header
    for new in set().union(*held) - every:
        name = columns.get(new, columns.get(split_unit(new)[0]))
        if not name:
            continue
        runs = {k for k, h in enumerate(held) if new in h}
        for old in set().union(*held) - every - {new} - set(moved):
            apart = not runs & {k for k, h in enumerate(held) if old in h}
            if apart and old not in columns and _SAFE.sub("_", split_unit(old)[0]).strip("_") == (
                    str(name)[2:]):
                moved[old] = new
    if not moved:
        return records
    return [Record(r.label, [Channel(moved.get(c.header, c.header), c.values, c.time, c.where)
                             for c in r.channels], r.time_header, r.utc) for r in records]


def _time_kind(record: Record) -> str:
    time = record.channels[0].time
    return "untimed" if time is None else "by timestamps" if np.issubdtype(
        time.dtype, np.datetime64) else "in seconds"


def _time_cells(time: np.ndarray | None, n: int, utc: bool) -> list[str] | None:
    if time is None:
        return None
    if np.issubdtype(time.dtype, np.datetime64):      # NI's are UTC; a datenum's on no clock said
        text = np.datetime_as_string(time.astype("datetime64[us]"), unit="us")
        return [f"{s}+00:00" for s in text] if utc else list(text)
    return [repr(float(v)) for v in time[:n]]


def _cell(v) -> str:
    # (lab77) an infinity (a Campbell FP2 INF, a logger's overflow) written as one, so the CSV
    # reader names it as a TOA5 file's INF is (its column and rows), not an unnamed gap
    return "" if np.isnan(v) else repr(float(v)) if np.isfinite(v) else ("inf" if v > 0 else "-inf")


def write_wide(records: list[Record], out: Path) -> dict[str, str]:
    """The records as one CSV table (a ``run`` column where several); ``{header: where}``."""
    first = records[0]
    # (a channel replaced from a run on: after the others, in the order the runs hold them)
    headers = list(dict.fromkeys(c.header for r in records for c in r.channels))
    time = first.channels[0].time
    dated = time is not None and np.issubdtype(time.dtype, np.datetime64)
    # a time channel's own header (its unit); else ours: timestamps, or seconds
    time_header = first.time_header if first.time_header != TIME_HEADER else (
        TIME_HEADER if dated else f"{TIME_HEADER} [s]")
    runs = len(records) > 1
    with open(out, "w", encoding=UTF8, newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(([RUN_HEADER] if runs else []) + ([time_header] if time is not None else [])
                        + headers)
        for record in records:
            by = {c.header: c.values for c in record.channels}
            n = record.channels[0].values.size
            times = _time_cells(record.channels[0].time, n, record.utc)
            for i in range(n):
                writer.writerow(([record.label] if runs else []) + ([times[i]] if times else [])
                                + [_cell(by[h][i]) if h in by else "" for h in headers])
    return {c.header: c.where for r in reversed(records) for c in r.channels}


def write_long(record: Record, out: Path, starts: dict | None = None) -> dict[str, str]:
    """One record's channels, each on its own time, as a long CSV file (``time``, ``channel``,
    ``value``: the historian's path holds them onto one grid); ``{header: where}``; ``starts``
    (where given) gets each channel's first data row of the long file."""
    absolute = {np.issubdtype(c.time.dtype, np.datetime64) for c in record.channels}
    if len(absolute) > 1:
        raise ContractError(f"{record.label}: some channels timed by a date, others by seconds "
                            "only: no grid reads them together", file=out)
    with open(out, "w", encoding=UTF8, newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow([TIME_HEADER if absolute == {True} else "time [s]", "channel", "value"])
        row = 0
        for c in record.channels:
            if starts is not None:
                starts[c.header] = row + 1
            row += c.values.size
            for stamp, v in zip(_time_cells(c.time, c.values.size, record.utc), c.values):
                writer.writerow([stamp, c.header, _cell(v)])
    return {c.header: c.where for c in record.channels}


@contextmanager
def records_as_csv(records: list[Record], path: Path) -> Iterator[Path]:
    """``records`` (the lab's file ``path``) as a temporary CSV file, removed after; a
    :class:`ContractError` about it names ``path``, the channel's place and the data row."""
    records = [_twinned(r) for r in records]
    wide = _check(records, path)
    with tempfile.TemporaryDirectory(prefix="thermocomp-lab-") as tmp:
        out = Path(tmp) / (path.stem + ".csv")
        starts: dict = {}
        where = write_wide(records, out) if wide else write_long(records[0], out, starts)
        with named_as(out, str(path), lambda exc: _located(exc, out, path, where, starts), "row",
                      line_of=lambda n: n - 1):
            yield out


def text_as_csv(record_of, text: str, source: str) -> str:
    """A logger's text export streamed (``monitor.input=-``) as the CSV text its channels are
    read as from a file: ``record_of(lines, label, path)`` its one record (a ``time`` of
    timestamps, each channel a column)."""
    path = Path(source)
    with records_as_csv([record_of(text.splitlines(), path.stem, path)], path) as table:
        return table.read_text(encoding=UTF8)


def _twinned(record: Record) -> Record:
    """``record`` with a name two of its channels share read as a CSV header written twice is
    (:mod:`.twins`: the second ``BETT_L#2 [degC]``): stranger82, a logger's two channels given
    one signal name were written as one column, the second's values lost without a word."""
    names, twins = occurrences([c.header for c in record.channels])
    if not twins:
        return record
    return Record(record.label, [Channel(n, c.values, c.time, c.where)
                                 for n, c in zip(names, record.channels)],
                  record.time_header, record.utc)


def _located(exc: ContractError, temp: Path, path: Path, where: dict[str, str],
             starts: dict | None = None) -> ContractError:
    """``exc`` about the temporary file as about the lab's file: its data row, the channel's
    group or variable said; a row of the long file a record of channels at their own rates is
    written to (``starts``: each channel's first) as the channel's own sample (stranger80: a
    TDMS log's open thermocouple was "data row 5001 ... of the long file", a file the lab
    never saw)."""
    if exc.file is None or str(temp) not in str(exc.file) and str(temp) not in exc.reason:
        return exc
    reason = exc.reason.replace(str(temp), str(path))
    header = exc.column if exc.column in where else next(
        (h for h in where if repr(h) in reason), None)
    place = where.get(header) if header is not None else None
    row = exc.row
    if starts and header in starts and row is not None and row >= starts[header]:
        sample, said = row - starts[header] + 1, f"data row {row} of the long file"
        if said in reason:
            reason = reason.replace(said, f"its sample {sample}")
        else:
            place = f"{place}, its sample {sample}" if place else f"its sample {sample}"
        row = None
    if place:
        reason += f" ({place})"
    return ContractError(reason, file=path, column=exc.column, row=row)


def marked_values(body, j: int, what: str, path: Path, missing: re.Pattern, marks_are: str,
                  comma: bool = False) -> np.ndarray:
    """Column ``j`` of a logger export's table rows ``body`` (``(line, cells)``) as numbers: a blank
    cell or one the logger marks (``missing``: a broken thermocouple, out of range; said once as
    ``marks_are``) missing, a decimal comma read where ``comma``; any other text refused naming
    ``what`` and its line."""
    out = np.empty(len(body))
    marks = 0
    for i, (line, r) in enumerate(body):
        text = r[j].strip() if j < len(r) else ""
        if not text or missing.fullmatch(text):
            out[i] = np.nan
            marks += bool(text)
            continue
        try:
            out[i] = float(text.replace(",", ".") if comma else text)
        except ValueError:
            raise ContractError(f"{what}: {text!r} is no number", file=path, line=line) from None
    if marks:
        logger.info(f"{path}: {what}: {marks} value(s) {marks_are} or out of range, read as missing")
    return out
