"""The order of a record's dates with slashes, one decision for all its files (small71).

``03/11/2026`` is day first in Europe and month first in the US; a row whose day or month is
past 12 says which (:func:`.timestamps.slashed_format`), and a Keysight DAQ's ``Time`` (its
milliseconds after a colon) is month first where no row says otherwise (lead70).  A folder's
first file alone may say nothing (every day <= 12) where a later one says day first (a 13th):
read by its first file, the later one was refused at its 13th's row, or, where the later one's
first row said day first, the first was read month first without a word (10/03: October).  So
every row of every file of the record counts: one order for the record (``init`` writes it as
``data.time``; a read with ``data.time=auto`` takes it), and files that contradict each other
(one says day first, another month first) are refused naming both.  Where no row of any file
says an order, their runs do (dates85: a run across midnight, :func:`.slashed_rows.by_runs`).

A stream (``monitor.input=-``) cannot see the future: its first row alone decided, and a stream
of the lab's rows from 10/03 23:00 into 11/03 was read month first (October, then November)
without a word.  With ``data.time=auto`` it reads in the order its training record decided
(:func:`stream_format`, code71), and a row of it that says the other order is refused.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import replace
from pathlib import Path

import pandas as pd
import pyarrow as pa

from .contract import TIME, ContractError
from .dayfirst import ORDER, WAY
from .encoding import own
from .lines import Lines
from .plain import is_converted
from .slashed_rows import Order, said_by, settled
from .sniff import resolved
from .suffixes import is_text
from .tables import peek_csv
from .timestamps import is_slashed_stamp, slashed_format
from .utf16 import is_utf16, utf8_options, utf16_as_utf8


def record_order(files: Iterable[Path], opts) -> Order | None:
    """The order every row of ``files`` (one record's) says of its dates with slashes: a day or
    month past 12 in any file, else a Keysight ``Time`` (month first).  None where ``data.time``
    is given, the first file's time is no date with slashes, or rows of one file disagree (its
    read refuses naming ``data.time``, as before); where no row says an order, the one the
    files' runs settle (:func:`.slashed_rows.settled`).

    Raises
    ------
    ContractError
        Where one file says day first and another month first, naming both; where no row says
        an order and no run settles one, ``data.dayfirst`` unset.
    """
    files = list(files)
    if opts.time != "auto" or not files:
        return None
    return settled([_said(path, opts) for path in files], opts.dayfirst,
                   lambda exc: _located(exc, opts))


def rows_tell(path: Path, opts) -> bool:
    """``path``'s rows may say the order of its dates with slashes: a text file read as it is
    or as the UTF-8 text of its UTF-16 (a workbook's cells are dates already; the other
    converted forms' first row decides, as before)."""
    return is_utf16(path) or is_text(path) and not is_converted(path, opts)


def stream_format(time: pd.Series, recorded: str | None, source: str) -> str | None:
    """``data.time`` of a stream's time cells ``time`` (index: the stream's data row - 1) read in
    the order of the training record's dates with slashes, ``recorded`` (the format its read
    took, :func:`record_order`), in the shape of the stream's first time (its seconds, its
    year); None where no order was recorded or that first time is no date with slashes (the
    stream's first row decides, as before).

    Raises
    ------
    ContractError
        At the first row that says the other order (a day or month past 12), naming it.
    """
    if not recorded or not recorded.startswith(tuple(ORDER.values())):
        return None
    cells = time.dropna().astype(str).str.strip()
    if cells.empty or not is_slashed_stamp(cells.iloc[0]):
        return None
    day_first = recorded.startswith("%d/")
    for row, value in cells.drop_duplicates().items():
        told = slashed_format(value, keysight=False)
        if told and told.startswith("%d/") != day_first:
            raise ContractError(
                f"value {value!r} says its dates with slashes are {WAY[not day_first]}, but the "
                f"record the model was trained on says {WAY[day_first]} (data.time={recorded!r}): "
                "a stream is read in its record's order; stream the rows of the PC that wrote "
                "the record, or set data.time to the stream's format",
                file=source, column=TIME, row=int(row) + 1)
    return slashed_format(cells.iloc[0], order=recorded[:6])


def _located(exc: ContractError, opts) -> ContractError:
    """``exc`` naming the line of its file's data row too (a CSV table's, as its read does)."""
    path = Path(exc.file)
    if exc.row is None or is_utf16(path):
        return exc
    try:
        opts = resolved(path, opts)
        skip = peek_csv(path, opts.delimiter, opts.encoding)[2]
    except (ContractError, ValueError):
        return exc
    return Lines(path, opts.delimiter, opts.encoding, skip).located(exc)


def _said(path: Path, opts) -> tuple | None:
    """``(said, path, header, cells)``: the orders ``path``'s rows say (``format``: its first row
    saying it) by a field past 12, and by a Keysight stamp (:func:`.slashed_rows.said_by`), and
    the time cells looked at; None where its first time cell is no date with slashes, it is no
    text file (a workbook's cells are dates already) or it does not read."""
    if is_utf16(path):           # looked at as the UTF-8 text it is read as (catman70)
        with utf16_as_utf8(path) as text:
            read = _said(text, utf8_options(opts))
        return None if read is None else (
            tuple({f: replace(o, file=path) for f, o in d.items()} for d in read[0]), path,
            *read[2:])
    if not rows_tell(path, opts):
        return None
    try:
        opts = resolved(path, opts)
        header, first, skip = peek_csv(path, opts.delimiter, opts.encoding)
        column = next((i for i, cell in enumerate(first) if is_slashed_stamp(cell.strip())), None)
        if column is None:
            return None
        cells = pd.read_csv(path, sep=opts.delimiter, header=None, skiprows=skip,
                            usecols=[column], dtype=str,
                            encoding=own(path, opts.encoding)).iloc[:, 0]
    except (ContractError, ValueError):   # (no evidence: the file's read says what is wrong)
        return None
    cells = pa.array(cells, type=pa.string(), from_pandas=True)
    name = header[column] if column < len(header) else TIME
    return said_by(cells, path, name), path, name, cells


