"""A footer under a lab's CSV export (``End of data``, ``Stop 13:45``): the last lines of one
field of text, left out (and said), where every line above holds the header's fields; so are
summary rows (messy58: ``Mittelwert;25,3;...``, a statistic's word then numbers) under rows
whose first cell holds a digit (a time, a number), and a block of ``#`` comments under the rows
(stranger75), however many lines (:data:`MAX_LINES` bounds the others).  A last
line of numbers cut short stays a malformed row, refused with its row."""

from __future__ import annotations

import mmap
import re
from pathlib import Path

import pyarrow as pa

from .csvline import EMPTY, split_line
from .encoding import UTF8

TAIL_BYTES = 1 << 14
MAX_LINES = 5
# a summary row's label (its first word, any case): a statistic a lab's export writes under
# the data; a word else in a last row (``later``) stays a time or a value not read, refused
_SUMMARY = re.compile(
    r"(mittelwert|durchschnitt|mean|average|avg|moyenne|media|median|max|maximum|maximal|massimo|"
    r"min|minimum|minimal|minimo|summe|sum|total|std|stdabw|standardabweichung|stabw|stddev|"
    r"sigma|anzahl|count|spanne|range|ecart|écart)\b[^\d]*", re.IGNORECASE)
_DIGIT = re.compile(r"\d")


def footer(path: Path, delimiter: str, fields: int, encoding: str = UTF8
           ) -> tuple[list[str], int]:
    """``(the footer's lines, the bytes before it)``; ``([], size)`` without one."""
    size = path.stat().st_size
    if fields < 2:                         # one column: every line is one field
        return [], size
    with open(path, "rb") as f:
        f.seek(max(0, size - TAIL_BYTES))
        tail = f.read()
    return footer_of(tail, size, delimiter, fields, encoding)


def footer_of(tail: bytes, size: int, delimiter: str, fields: int, encoding: str = UTF8
              ) -> tuple[list[str], int]:
    """:func:`footer` of the last bytes ``tail`` of ``size`` (a file's, or a stream's whole:
    a lab's run file piped into ``monitor monitor.input=-`` reads as the file reader reads it)."""
    if fields < 2:
        return [], size
    lines = tail.splitlines(keepends=True)
    found, cut, above, summary, comments = [], size, "", False, 0
    for raw in reversed(lines[1:] if size > TAIL_BYTES else lines):
        text = raw.decode(encoding, "replace").strip()
        if text and not any(c.strip() for c in split_line(text, delimiter, EMPTY)):
            text = ""       # a row of empty cells (a sheet's empty row above its summary rows)
        comment = _comment_line(text, delimiter, fields)
        if text and not comment and not _footer_line(text, delimiter):
            if not _summary_line(text, delimiter):
                above = text
                break
            summary = True
        comments += comment
        if len(found) - comments == MAX_LINES:
            return [], size
        cut -= len(raw)
        if text:
            found.insert(0, text)
    if summary and not _DIGIT.search(split_line(above, delimiter, EMPTY)[0]):
        return [], size         # a first column of words: those are data rows, not a summary
    return (found, cut) if found else ([], size)


def source(path: Path, cut: int | None):
    """What Arrow reads: the file (``cut`` None), or its first ``cut`` bytes (memory-mapped,
    not copied)."""
    if cut is None or cut >= path.stat().st_size:
        return path
    return pa.BufferReader(pa.memory_map(str(path)).read_buffer(cut))


def _comment_line(text: str, delimiter: str, fields: int) -> bool:
    """A ``#`` line of other than the header's width: no row (Excel's ``#N/A`` in a row's first
    cell keeps the row's width), a logger's run summary under its rows (stranger75: seven
    ``# start: ...``, ``# note: run 4, test mandrel 300 mm`` lines, refused as a '#' line among
    the rows); any number of them, their commas too."""
    return text.startswith("#") and len(split_line(text, delimiter, EMPTY)) != fields


def _footer_line(text: str, delimiter: str) -> bool:
    cells = split_line(text, delimiter, EMPTY)          # (no CSV text: no footer)
    if len([c for c in cells if c.strip()]) != 1 or len(cells) > 1 and cells[0].strip() == "":
        return False
    try:
        float(cells[0].replace(",", "."))
    except ValueError:
        return True
    return False


def _summary_line(text: str, delimiter: str) -> bool:
    """A summary row under the data (``Mittelwert;25,3;...``, ``Max;...``): its first cell a
    statistic's word without a digit, every other cell a number or empty."""
    cells = split_line(text, delimiter, EMPTY)
    if len(cells) < 2 or not _SUMMARY.fullmatch(cells[0].strip()):
        return False
    return all(_number(c) for c in cells[1:] if c.strip())


def _number(cell: str) -> bool:
    try:
        float(cell.strip().replace(",", "."))
    except ValueError:
        return False
    return True


# (dep108b) what every reader of rows without a time column says of a blank line among them
BLANK_UNTIMED = ("a blank line under it is left out, and the rows after it read data.sample_period_s "
                 "earlier: if it is a sample not taken, leave its cells empty instead (a gap, "
                 "data.max_gap_samples)")


def blank_inside(path: Path, skip: int, cut: int) -> int | None:
    """The data row under which the first blank line among the data rows stands (``skip``:
    the lines above the first data row; ``cut``: the bytes before a footer), or None.  Arrow
    skips a blank line: where the rows' positions are the time (``data.sample_period_s``) it
    is a sample not taken, or nothing."""
    with open(path, "rb") as f, mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ) as m:
        start = 0
        for _ in range(skip):                       # past the preamble, header, units
            start = m.find(b"\n", start) + 1
            if start == 0:
                return None
        body = m[start:cut].rstrip(b"\r\n\t ")       # (blank lines at the end: no row follows)
    found = re.search(rb"\n[ \t\r]*\n", body)
    return None if found is None else body[:found.start()].count(b"\n") + 1
