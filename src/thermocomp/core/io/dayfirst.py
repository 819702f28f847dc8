"""Day or month first: the order of a lab file's dates with slashes, decided from the file itself
(dates84), one mechanism for every reader of them (dates85): those that parse a date of their own
(a catman T0, a Scope View start or time column, a LabVIEW segment's Date) and a CSV table's time
column (:mod:`.slashed_rows`, its rows' shapes and a Keysight stamp, a record's files at once).

``05/03/2027`` is the 3rd of May on an en-US PC and the 5th of March on an en-GB one; catman read
it month first wherever the day was 12 or less (stranger84).  So: ``data.dayfirst`` (true /
false) where the config says it; else a field past 12 in any of the file's dates fixes the order
for the whole file (one date past 12 each way: refused, naming both); else an order is possible
where the file's dates, read so, never go back and never step 27 days or more at once (where
the date turns a day in one order it turns a month in the other: a run of samples across
midnight tells); one order possible is taken, both (a file whose dates are one day's) are
refused naming the file, the column, the row and ``data.dayfirst``: never a guess.  A folder's
files are one record, read in one order: a date past 12 in any of them decides for all, or the
run of one's dates (data86) (:func:`record_dayfirst`; ``init`` writes it as ``data.dayfirst``, and
the model carries it: :func:`thermocomp.shell.source.slashed_time`).
"""

from __future__ import annotations

import codecs
import re
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import NamedTuple

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.compute as pc

from .contract import ContractError

# the two fields before the year (Arrow's regex: named groups; the cell's leading spaces allowed)
_FIELDS = r"^\s*(?P<a>\d{1,2})/(?P<b>\d{1,2})/\d{2,4}\b"
_MONTH = np.timedelta64(27, "D")   # the least step a day turned into a month makes (28-31 days)
WAY = {True: "day first", False: "month first"}
ORDER = {True: "%d/%m/", False: "%m/%d/"}     # a strptime format's date with slashes, each way
KEY = "data.dayfirst"


def swapped(forms: Sequence[str], day_first: bool) -> tuple[str, ...]:
    """The strptime formats ``forms`` (written month first, ``%m/%d/``) in the order chosen."""
    return tuple(f.replace(ORDER[False], ORDER[True]) for f in forms) if day_first else tuple(forms)


def fields(cells) -> tuple[np.ndarray, np.ndarray]:
    """The day-or-month fields ``(a, b)`` of ``a/b/year`` in each of ``cells`` (text), -1 in a
    cell that is no date with slashes."""
    if not isinstance(cells, (pa.Array, pa.ChunkedArray)):
        cells = pa.array(cells, pa.string())
    return parts_fields(pc.extract_regex(cells, _FIELDS))


def parts_fields(parts) -> tuple[np.ndarray, np.ndarray]:
    """:func:`fields` of a regex's matches ``parts`` whose groups ``a`` and ``b`` are the two
    fields before the year (null: no date with slashes)."""
    return tuple(pc.fill_null(pc.cast(pc.struct_field(parts, n), pa.int16()), -1)
                 .to_numpy(zero_copy_only=False) for n in "ab")


def slashed_order(dates: Sequence[tuple[str, int | None]], dayfirst: bool | None, parse: Callable,
                  file, column: str) -> bool | None:
    """``True`` (day first) or ``False`` (month first) for a file's dates with slashes.

    Parameters
    ----------
    dates : sequence of (str, int or None)
        The file's date cells in the order it writes them, each with its line (None: unknown);
        cells that are no date with slashes are passed over.
    dayfirst : bool or None
        ``data.dayfirst`` (None: not set, the file decides).
    parse : callable
        ``parse(cells, day_first)``: the cells (a Series of text) as ``datetime64``, NaT where
        one does not read so (:func:`parse_with`).
    file, column
        What a refusal names.

    Returns
    -------
    bool or None
        None where no cell is a date with slashes, or (data88) where each reads the same either
        way, its day and its month one number.

    Raises
    ------
    ContractError
        Where the file says both orders, or gives no way to tell and ``data.dayfirst`` is unset.
    """
    cells = [cell for cell, _ in dates]
    a, b = fields(cells)
    slashed = np.flatnonzero(a >= 0)
    if not slashed.size:
        return None
    if dayfirst is not None:
        return bool(dayfirst)
    day, month = (next((dates[i] for i in slashed if x[i] > 12), None) for x in (a, b))
    if day and month:
        raise ContractError(f"date {day[0]!r} (line {day[1]}) is day first and {month[0]!r} "
                            f"month first: one file's dates are written in one order; set "
                            f"{KEY}=true|false to the one the PC wrote", file=file, column=column,
                            line=month[1])
    if day or month:
        return bool(day)
    if (a[slashed] == b[slashed]).all():
        # (data88) every date reads the same either way (05/05/2027): no order to ask for, and
        # none taken (it would be written as data.dayfirst and carried by the model): refused
        # before as "day or month first?", which either answer read alike
        return None
    kept = [dates[i] for i in slashed]
    return run_order(pd.Series([c for c, _ in kept]), parse, file, column,
                     line=[ln for _, ln in kept])[0]


def run_order(cells: pd.Series | pa.Array, parse: Callable, file, column: str, line=None,
              row=None, also: str = "") -> tuple[bool, int]:
    """The one order in which ``cells`` (text, dates with slashes none of whose day or month is
    past 12, in the file's order; ``parse(cells, day_first)``: as datetimes, NaT where one does
    not read so) never go back and never step 27 days or more, and the position
    of the first cell the other order cannot read so (where it goes back or jumps a month).
    ``line`` / ``row``: each cell's, what a refusal names (at the first cell); ``also``: the
    refusal's other way out.

    Raises
    ------
    ContractError
        Where both orders run so, or neither.
    """
    broken = {order: _broken(cells, order, parse) for order in (True, False)}
    first = cells[0].as_py() if isinstance(cells, pa.Array) else cells.iloc[0]
    possible = [order for order, at in broken.items() if at is None]
    if len(possible) == 1:
        return possible[0], broken[not possible[0]]
    why = ("read in neither order as a run that never goes back" if not possible else
           "read either way (no day past 12, and no change of date that only one order "
           "makes a small step)")
    where = {"line": None if line is None else line[0], "row": None if row is None else row[0]}
    raise ContractError(f"date {first!r} is day or month first? the file's dates {why}: "
                        f"set {KEY}=true|false to the order of the PC that wrote it ({KEY}=true: "
                        f"day first, 05/03 the 5th of March; {KEY}=false: month first, the 3rd "
                        f"of May){also}", file=file, column=column, **where)


def _broken(cells, day_first: bool, parse: Callable) -> int | None:
    """The position of the first of ``cells`` that read ``day_first`` does not parse, goes back
    or steps a month on; None where they run."""
    # (ms, not ns: Arrow's %Y reads a two-digit year, 27, as the year 27, before ns's range)
    times = np.asarray(parse(cells, day_first), dtype="datetime64[ms]")
    bad = np.isnat(times)
    steps = np.diff(times)
    bad[1:] |= (steps < np.timedelta64(0)) | (steps >= _MONTH)
    return int(np.argmax(bad)) if bad.any() else None


def parse_with(forms: Sequence[str]) -> Callable[[pd.Series, bool], pd.Series]:
    """A ``parse`` for :func:`slashed_order`: each cell by the first of ``forms`` (month first,
    swapped for day first) that reads it."""
    def parse(cells: pd.Series, day_first: bool) -> pd.Series:
        text = cells.astype(str).str.strip().reset_index(drop=True)
        out = pd.Series(pd.NaT, index=text.index, dtype="datetime64[ns]")
        for form in swapped(forms, day_first):
            left = out.isna()
            if not left.any():
                break
            out[left] = pd.to_datetime(text[left], format=form, errors="coerce")
        return out
    return parse


# a date with slashes in a lab file's text (no more digits or slashes on either side)
_ANY = re.compile(r"(?<![\d/])\d{1,2}/\d{1,2}/\d{2,4}(?![\d/])")
_DATES = parse_with(("%m/%d/%Y", "%m/%d/%y"))
# how a run says its order: where the date turns a day in one order it turns a month in the other
RUN_SAID = ": a day on read so, a month on or back read the other way"


class Said(NamedTuple):
    """The order a file of a record says for all its files (:func:`record_dayfirst`)."""

    day_first: bool
    file: Path
    date: str            # the date that says it
    run: bool = False    # said by the file's run of dates (``date``: where the other breaks it)

    def __str__(self) -> str:
        return f"{self.date!r}" + (f" (its run{RUN_SAID})" if self.run else "")


def record_dayfirst(files, dated: Callable[[Path], bool], encoding: str = "utf-8") -> Said | None:
    """The order one file of a record's says, for all its files (a catman folder whose tests of
    the 13th say month first, the 3rd's alike): by a field past 12, else (data86) by the run of
    its dates, as a CSV table's (:func:`run_order`: a Scope View export across midnight); None
    where none says one.  ``dated``: a file read by a reader of its own dates.  Each file is
    read only as far as it must be (:func:`_file_says`).

    Raises
    ------
    ContractError
        Where one file says day first and another month first, naming both.
    """
    said: dict[bool, Said] = {}
    either: dict[Path, str] = {}       # a file whose dates read either way: its first
    for path in files:
        if dated(path):
            says, first = _file_says(Path(path), encoding)
            for one in says or ():
                said.setdefault(one.day_first, one)
            if says is None and first is not None and _reads_two_ways(first):
                either[Path(path)] = first
    if not said and len(either) > 1:
        raise _unsettled(either)
    if len(said) == 2:
        day, month = said[True], said[False]
        raise ContractError(f"date {day} is day first, but file {month.file}'s {month} month "
                            f"first: the files of one record are read in one order; set "
                            f"{KEY}=true|false to the one the PC wrote, or read each as a record "
                            "of its own", file=day.file)
    return next(iter(said.values()), None)


_ENDS = 1 << 16        # bytes of a file's head and of its tail, looked at first
_BLOCK = 1 << 20       # then its text from the start, a block at a time


def _reads_two_ways(date: str) -> bool:
    """``date`` (with slashes) is two dates, its day and month not one number (05/05/2027 is
    the 5th of May either way)."""
    a, b = fields([date])
    return bool(a[0] != b[0])


class Unsettled(ContractError):
    """(data88) A record of several files none of whose dates says an order: ``files``, those
    whose dates read either way (the first file's reader names its column and line:
    :func:`thermocomp.core.io.plain.lab_dayfirst`)."""

    def __init__(self, message: str, files: list[Path]):
        super().__init__(message, file=files[0])
        self.files = files


def _unsettled(either: dict[Path, str]) -> Unsettled:
    """(data88) The refusal of a record of several files none of whose dates says an order
    (``either``: each file's first date): each file's reader named itself alone; the user
    choosing ``data.dayfirst`` is shown all of them and what each answer makes of the record."""
    names = list(either)
    cells = pd.Series(list(either.values()))
    spans = {}
    for day_first in (True, False):
        read = pd.to_datetime(_DATES(cells, day_first), errors="coerce").dropna()
        spans[day_first] = (f"{read.min():%Y-%m-%d} to {read.max():%Y-%m-%d}" if len(read)
                            else "no date")
    shown = ", ".join(p.name for p in names[:4]) + (f" ... {names[-1].name}" if len(names) > 4
                                                     else "")
    return Unsettled(f"no file of the record settles it: the dates with slashes of {len(names)} "
                     f"files read either way (no day past 12, no run across midnight), {shown}; "
                     f"their first dates run {spans[True]} read day first, {spans[False]} month "
                     "first", names)


def _file_says(path: Path, encoding: str) -> tuple[list[Said] | None, str | None]:
    """What the dates of the lab file ``path`` say (:func:`dates_say`: None where they read
    either way) and its first date with slashes (None: none), read only as far as
    needed (data86: the whole text of every file was read): a file's dates run forward (its
    reader refuses a time that goes back), so one whose head and tail hold one date is that
    date throughout; any other is read from its start until its dates say an order, which the
    rest can no longer change (an order a part of the file rules out, the whole rules out)."""
    with open(path, "rb") as f:
        size = f.seek(0, 2)
        if size > 4 * _ENDS:
            f.seek(0)
            head = f.read(_ENDS).decode(encoding, "replace")
            f.seek(size - _ENDS - (size - _ENDS) % 4)      # (a UTF-16 text's code units)
            tail = f.read().decode(encoding, "replace")
            # (whole lines only: a date cut in two is none)
            head, tail = (_ANY.findall(t) for t in (head[:head.rfind("\n") + 1],
                                                    tail[tail.find("\n") + 1:]))
            if head and tail and len(ends := set(head + tail)) == 1:
                return dates_say(path, list(ends)), head[0]
        f.seek(0)
        decoder = codecs.getincrementaldecoder(encoding)("replace")
        dates: dict[str, None] = {}
        text = ""
        while True:
            block = f.read(_BLOCK)
            text += decoder.decode(block, final=not block)
            cut = text.rfind("\n") + 1 if block else len(text)      # (whole lines only)
            new = [d for d in dict.fromkeys(_ANY.findall(text, 0, cut)) if d not in dates]
            text = text[cut:]
            if new:
                dates.update(dict.fromkeys(new))
                said = dates_say(path, list(dates))
                if said is not None:
                    return said, next(iter(dates))
            if not block:
                return (None if dates else []), next(iter(dates), None)


def text_says(text: str, source) -> list[Said] | None:
    """:func:`dates_say` of the distinct dates with slashes of ``text`` (a stream's)."""
    return dates_say(Path(source), list(dict.fromkeys(_ANY.findall(text))))


def dates_say(path: Path, dates: list[str]) -> list[Said] | None:
    """The orders a file's distinct ``dates`` (in its order) say: by a field past 12 (both: the
    file's reader refuses it), else by their run (:func:`run_order`); ``[]`` where they rule
    out both orders (its reader refuses), None where either still reads them."""
    a, b = fields(dates)
    said = {}
    for date, x, y in zip(dates, a, b):
        if (x > 12) != (y > 12):
            said.setdefault(bool(x > 12), Said(bool(x > 12), path, date))
    if said or len(dates) < 2:
        return list(said.values()) or None
    cells = pd.Series(dates)
    broken = {order: _broken(cells, order, _DATES) for order in (True, False)}
    possible = [order for order, at in broken.items() if at is None]
    if len(possible) == 2:
        return None
    return [Said(possible[0], path, dates[broken[not possible[0]]], run=True)] if possible else []
