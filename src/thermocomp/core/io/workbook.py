"""A lab's Excel workbook (``.xlsx``, ``.xlsm``) read as its CSV export is.

The sheet (``data.sheet``; else the first that holds a table: a cover sheet above the runs left
out, stranger68) is written, as openpyxl reads it (the values a formula
had when Excel last saved it), into a temporary UTF-8 CSV file, ``,``-separated with ``.`` as the
decimal mark, one line per sheet row from row 1: the CSV reader then reads it, so a preamble, a
unit row, roles, units and every check work as on the lab's CSV export.  A date cell is written
as ISO 8601, a duration (``[h]:mm:ss``) as ``h:mm:ss``, a number as Python's ``repr`` (every
digit kept), a boolean as 1/0, an empty cell empty, a line break inside a cell as a space (so that
the CSV file's line is the sheet's row).  A message about the CSV file names the workbook, the
sheet and the sheet's row instead (:func:`sheet_as_csv`).

A lab's macro writes a test's runs into one workbook, one sheet each, behind a cover sheet of
notes (stranger68): :func:`run_sheets` tells the sheets that hold a table of the first such
table's header (each a run, a campaign of a record: :mod:`.sheetruns`) from the others.  Its
two-row header merges a column's name down over the group row (``Date / time`` over rows 3-4,
beside ``Temperatures`` merged across): a cell under a merge's top in its first column is
written with the top's value (:func:`_rows`), so that column is named in the header row.
"""

from __future__ import annotations

import csv
import datetime as dt
import functools
import io
import re
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, replace
from pathlib import Path

from ...base.errors import listed
from ...base.extras import require
from .contract import ContractError
from .converted import named_as
from .encoding import UTF8
from .layout import header_line
from .separators import any_number
from .sniff import SNIFF_LINES

WORKBOOK_SUFFIXES = (".xlsx", ".xlsm")
# spreadsheets openpyxl does not read: refused with the remedy
NOT_READ = {".xls": "an Excel 97-2003 workbook", ".xlsb": "a binary Excel workbook",
            ".ods": "an OpenDocument spreadsheet"}
SAVE_AS = "save it as an Excel workbook (.xlsx), or its sheet as CSV"
HEAD_ROWS = SNIFF_LINES         # the rows a look at the header reads (a preamble, a unit row)
_OLE = b"\xd0\xcf\x11\xe0"        # a compound file: an encrypted .xlsx, or an .xls renamed
_BREAK = re.compile(r"\r\n|[\r\n]")
_MERGE = re.compile(rb'<(?:\w+:)?mergeCell\s+ref="([A-Z]+)(\d+):([A-Z]+)(\d+)"')
_COMMA_NUMBER = re.compile(r"\s*[+-]?\d*,\d+(?:[eE][+-]?\d+)?\s*")   # '0,38' typed as text


@dataclass(frozen=True)
class Sheet:
    """A workbook's sheet written as CSV: the ``workbook``, the sheet's ``name``, the ``csv``."""

    workbook: Path
    name: str
    csv: Path

    def where(self) -> str:
        return f"{self.workbook}, sheet {self.name!r}"

    def located(self, exc: ContractError) -> ContractError:
        """``exc`` about the CSV file as about the sheet (its line is the sheet's row)."""
        if exc.file is None or Path(exc.file) != self.csv:
            return exc
        return ContractError(exc.reason.replace(str(self.csv), self.where()), file=self.workbook,
                             column=exc.column, row=exc.row, line=exc.line, sheet=self.name)


def is_workbook(path) -> bool:
    return Path(path).suffix.lower() in WORKBOOK_SUFFIXES


def not_read(path) -> str | None:
    """What a spreadsheet openpyxl does not read is, with the remedy (None: not one)."""
    kind = NOT_READ.get(Path(path).suffix.lower())
    return None if kind is None else f"{kind}, which is not read: {SAVE_AS}"


def csv_options(opts):
    """The read options of the CSV file a sheet is written to (separators, encoding: ours)."""
    return replace(opts, delimiter=",", decimal=".", thousands=None, encoding=UTF8)


@dataclass(frozen=True)
class Sheets:
    """A workbook's worksheets by what their first rows hold: ``runs``, those holding a table
    whose header is the first such table's (in the workbook's order); ``other``, the rest (a
    cover of notes, a summary table of its own header)."""

    runs: tuple[str, ...]
    other: tuple[str, ...]


def run_sheets(path: Path) -> Sheets:
    """The sheets of the workbook ``path`` holding its runs (:class:`Sheets`)."""
    stat = Path(path).stat()
    return _run_sheets(str(path), stat.st_mtime_ns, stat.st_size)


@functools.lru_cache(maxsize=8)
def _run_sheets(path: str, _mtime: int, _size: int) -> Sheets:   # (a file saved again: read again)
    book = _opened(Path(path))
    try:
        heads = {s.title: _table_header(Path(path), s) for s in book.worksheets}
    finally:
        book.close()
    first = next((h for h in heads.values() if h is not None), None)
    runs = tuple(t for t, h in heads.items() if first is not None and h == first)
    return Sheets(runs, tuple(t for t in heads if t not in runs))


def _table_header(path: Path, sheet) -> str | None:
    """The header line of the table ``sheet``'s first rows hold (as its CSV export), None where
    they hold none: no header, or no row under it mostly numbers (a cover's ``Runs | 8``)."""
    text = io.StringIO()
    writer = csv.writer(text, lineterminator="\n")
    for cells in _rows(path, sheet, HEAD_ROWS):
        writer.writerow([_text(v) for v in cells])
    lines = text.getvalue().splitlines()
    k = header_line(lines, ",")
    if k is None:
        return None
    rows = list(csv.reader(lines[k + 1:]))
    numeric = any(2 * sum(map(any_number, row)) > len(row) for row in rows if row)
    return lines[k] if numeric else None


@contextmanager
def sheet_as_csv(path: Path, opts, rows: int | None = None) -> Iterator[Sheet]:
    """The sheet ``opts.sheet`` (``data.sheet``; None: the first holding a table, else the first:
    :func:`run_sheets`) of the workbook ``path`` as a
    temporary CSV file (its first ``rows`` only, where given: what a look at the header needs),
    removed after.  ``opts.decimal`` (``data.decimal``) ``','`` or ``auto`` reads a number
    typed as text with a decimal comma (``'0,38'``, pasted from a European export) as the
    number, as a CSV file's are read (a number Excel holds is a number whatever its locale
    shows; ``'.'``: text).  Every look at a sheet (its header, its first time, its rows) goes
    through here with the same options, so each sees the same CSV.  A :class:`ContractError`
    about it, and a warning logged naming it, name the workbook, the sheet and the sheet's row."""
    with tempfile.TemporaryDirectory(prefix="thermocomp-sheet-") as tmp:
        text = Path(tmp) / f"{path.stem}.csv"
        out = Sheet(path, _write(path, opts.sheet, text, rows, opts.decimal in (",", "auto")),
                    text)
        with named_as(text, out.where(), out.located, "row"):
            yield out


def _write(path: Path, sheet: str | None, out: Path, rows: int | None, comma: bool) -> str:
    """Write the sheet into ``out`` as CSV (``comma``: text cells with a decimal comma as
    numbers); the sheet's name."""
    book = _opened(path)
    try:
        found = _sheet(book, sheet, path)
        try:
            with open(out, "w", newline="", encoding=UTF8) as f:
                writer = csv.writer(f, lineterminator="\n")
                for cells in _rows(path, found, rows):
                    writer.writerow([_text(v, comma) for v in cells])
        except Exception as exc:     # a damaged sheet (its XML)
            raise ContractError(f"sheet {found.title!r} is not read ({type(exc).__name__}: "
                                f"{exc}): {SAVE_AS}", file=path) from None
        return found.title
    finally:
        book.close()


def _rows(path: Path, sheet, rows: int | None) -> Iterator[list]:
    """The values of ``sheet``'s rows (its first ``rows``), a cell under a vertical merge's top
    in its first column given the top's value (a header's name merged down over a group row)."""
    below: dict[int, list[tuple[int, int]]] = {}        # row -> [(column, the merge's top row)]
    for col, top, bottom in _merged_down(path, sheet):
        for r in range(top + 1, bottom + 1):
            below.setdefault(r, []).append((col, top))
    tops = {(top, col) for spans in below.values() for col, top in spans}
    kept = {}
    for r, values in enumerate(sheet.iter_rows(max_row=rows, values_only=True), 1):
        cells = list(values)
        for col, top in below.get(r, ()):
            if col <= len(cells) and cells[col - 1] is None:
                cells[col - 1] = kept.get((top, col))
        kept.update({(r, c): cells[c - 1] for t, c in tops if t == r and c <= len(cells)})
        yield cells


def _merged_down(path: Path, sheet) -> list[tuple[int, int, int]]:
    """``(column, top row, bottom row)`` of each merge of ``sheet`` over several rows (from the
    sheet's XML: a read-only sheet does not say them)."""
    import zipfile

    from openpyxl.utils import column_index_from_string

    part = getattr(sheet, "_worksheet_path", None)
    if part is None:
        return []
    with zipfile.ZipFile(path) as z:
        xml = z.read(part.lstrip("/"))
    return [(column_index_from_string(c1.decode()), int(r1), int(r2))
            for c1, r1, _, r2 in _MERGE.findall(xml) if int(r2) > int(r1)]


def _opened(path: Path):
    """The workbook ``path`` opened read-only, its cells' values (refused: one not read)."""
    require("openpyxl")
    import openpyxl

    try:
        return openpyxl.load_workbook(path, read_only=True, data_only=True)
    except Exception as exc:   # zipfile, XML and openpyxl errors of a file it does not read
        raise ContractError(_unread(path, exc), file=path) from None


def _unread(path: Path, exc: Exception) -> str:
    """Why the workbook ``path`` is not read (``exc``: what openpyxl raised), and the remedy."""
    with open(path, "rb") as f:
        ole = f.read(4) == _OLE       # what Excel writes when a password encrypts a workbook
    if ole:
        return ("an encrypted workbook (or an Excel 97-2003 file named .xlsx), which is not "
                "read: save it as .xlsx without a password, or its sheet as CSV")
    return f"not a workbook that is read ({type(exc).__name__}: {exc}): {SAVE_AS}"


def _sheet(book, name: str | None, path: Path):
    sheets = book.worksheets          # (not a chart sheet)
    if not sheets:
        raise ContractError("the workbook has no worksheet", file=path)
    if name is None:         # the first holding a table (a cover sheet above it: left out)
        runs = run_sheets(path).runs
        return next((s for s in sheets if s.title in runs[:1]), sheets[0])
    found = [s for s in sheets if s.title == name]
    if not found:
        raise ContractError(f"data.sheet={name!r} is no sheet of it: its sheets are "
                            + listed([repr(s.title) for s in sheets], most=20), file=path)
    return found[0]


def _text(value, comma: bool = False) -> str:
    """A cell as its CSV export writes it (ours: ISO 8601 dates, every digit; ``comma``: a
    text cell with a decimal comma as its number)."""
    if comma and isinstance(value, str) and _COMMA_NUMBER.fullmatch(value):
        return value.strip().replace(",", ".")
    if value is None:
        return ""
    if isinstance(value, bool):
        return str(int(value))
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, (dt.datetime, dt.date, dt.time)):
        return value.isoformat()
    if isinstance(value, dt.timedelta):
        seconds = value.total_seconds()
        hours, rest = divmod(abs(seconds), 3600)
        text = f"{'-' if seconds < 0 else ''}{int(hours)}:{int(rest // 60):02d}:{rest % 60:06.3f}"
        return text.rstrip("0").rstrip(".")
    return _BREAK.sub(" ", str(value))
