"""A fixed-width text (an old measuring program's report: a title block, a header of names padded
with spaces, maybe a line of units and a dashed rule, then columns of numbers padded with spaces
and no delimiter) read as its CSV export: written, one line for each of the file's, into a
temporary UTF-8 CSV file that the CSV reader reads (as a workbook's sheet, :mod:`.workbook`), so
that a preamble, a unit row, roles, units and every check work as on a CSV file.

The columns are told by the numbers: the block of lines (from the first 50) that split on spaces
into the same count of numbers, each number of a column in the same place of every line (the
columns' spans do not overlap).  A column of right-aligned numbers reaches left to the column
before it (a wider number grows to the left), a left-aligned one right to the next.  A header
line's names (split where 2 spaces part them, so that a name may hold one) go to the column they
overlap.  A line of the title block is one cell; a rule of ``-`` or ``=`` is dropped.

Written by hand, not with :func:`pandas.read_fwf`: its spans are inferred from the lines after a
number of lines to skip that must be known, so a title block of any length, a header whose
names hold a space, and a unit row under it would each need the table found first, which is
this module's work; the CSV reader then does the rest.
"""

from __future__ import annotations

import csv
import re
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

from .contract import ContractError
from .converted import at_file, named_as
from .encoding import UTF8, own
from .sniff import SNIFF_LINES

_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
_TOKEN = re.compile(r"\S+")
_NAME = re.compile(r"\S+(?: \S+)*")           # words parted by one space: one header cell
_RULE = re.compile(r"\s*[-=_]{3,}[-=_ ]*")
_OTHER_SEPARATORS = (",", ";", "\t", "|")
MIN_ROWS = 3                                   # numeric lines that make a table


@dataclass(frozen=True)
class Layout:
    """Where a fixed-width file's table is: its header lines (the file's 0-based line indices),
    the first line of numbers, and each column's ``(start, end)`` characters (end excluded)."""

    header: tuple[int, ...]
    first_data: int
    regions: tuple[tuple[int, int], ...]

    def cells(self, line: str) -> list[str]:
        return [line[a:b].strip() for a, b in self.regions]


def _numeric_spans(line: str) -> list[tuple[int, int]] | None:
    """The spans of a line's cells where each is a number and no other separator is in it."""
    if not line.strip() or any(s in line for s in _OTHER_SEPARATORS):
        return None
    spans = [m.span() for m in _TOKEN.finditer(line)]
    if all(_NUMBER.fullmatch(line[a:b]) for a, b in spans):
        return spans
    return None


def layout(lines: list[str]) -> Layout | None:
    """The fixed-width table of ``lines`` (a file's first lines, no line ends), or None: no run
    of :data:`MIN_ROWS` lines of numbers aligned in 2 columns or more."""
    for start in range(len(lines)):
        spans = _numeric_spans(lines[start])
        if not spans or len(spans) < 2:
            continue
        block = [spans]
        for line in lines[start + 1:]:
            nxt = _numeric_spans(line)
            if nxt is None or len(nxt) != len(spans):
                break
            block.append(nxt)
        if len(block) < MIN_ROWS:
            continue
        columns = list(zip(*block))               # per column: its span on each line
        lefts = [min(a for a, _ in c) for c in columns]
        rights = [max(b for _, b in c) for c in columns]
        if any(rights[i] > lefts[i + 1] for i in range(len(columns) - 1)):
            return None                           # spans overlap: not aligned in columns
        # right-aligned: every number of the column ends in one place (or none starts in one)
        right = [len({b for _, b in c}) == 1 or len({a for a, _ in c}) > 1 for c in columns]
        starts = [(rights[i - 1] if i else 0) if right[i] else lefts[i] for i in range(len(columns))]
        regions = tuple(zip(starts, [*starts[1:], 10**9]))
        header = []
        i = start - 1
        while i >= 0 and lines[i].strip():
            if not _RULE.fullmatch(lines[i]):
                header.insert(0, i)
            i -= 1
        return Layout(tuple(header), start, regions)
    return None


def _header_cells(line: str, regions) -> list[str]:
    """A header line's names, each in the column it overlaps most (none: the nearest)."""
    cells = [""] * len(regions)
    for m in _NAME.finditer(line):
        a, b = m.span()
        overlap = [min(b, y) - max(a, x) for x, y in regions]
        best = max(range(len(regions)), key=lambda k: overlap[k])
        if overlap[best] <= 0:
            best = min(range(len(regions)), key=lambda k: min(abs(a - regions[k][1]), abs(b - regions[k][0])))
        cells[best] = f"{cells[best]} {m.group()}".strip()
    return cells


def _text(path: Path, encoding: str) -> str:
    data = path.read_bytes()
    try:
        return data.decode(encoding)
    except (UnicodeDecodeError, LookupError):
        return data.decode("cp1252", errors="replace")   # (the reader's own look says why)


def is_fixed_width(path, encoding: str = UTF8) -> bool:
    """``path`` is a text file (``.txt``, ``.dat``, ``.prn``, ``.csv``) whose first lines hold a
    fixed-width table (:func:`layout`) and no line of them a CSV separator in its table."""
    path = Path(path)
    if path.suffix.lower() not in (".txt", ".dat", ".prn", ".csv") or not path.is_file():
        return False
    try:
        with open(path, "rb") as f:
            head = f.read(1 << 16)
    except OSError:
        return False
    if head[:2] in (b"\xff\xfe", b"\xfe\xff"):          # UTF-16: :mod:`.utf16`
        return False
    lines = head.decode("latin-1").splitlines()[:SNIFF_LINES]
    return layout(lines) is not None


@contextmanager
def fixed_as_csv(path: Path, encoding: str = UTF8) -> Iterator[Path]:
    """The fixed-width file ``path`` as a temporary UTF-8 CSV file, line for line (a rule an empty
    line), removed after; a :class:`ContractError` or a warning about it names ``path``."""
    lines = _text(path, own(path, encoding)).splitlines()
    found = layout(lines[:SNIFF_LINES])
    if found is None:
        raise ContractError("no fixed-width table in the first lines", file=path)
    with tempfile.TemporaryDirectory(prefix="thermocomp-fixed-") as tmp:
        out = Path(tmp) / (path.stem + ".csv")
        with open(out, "w", encoding=UTF8, newline="") as f:
            writer = csv.writer(f, lineterminator="\n")
            for i, line in enumerate(lines):
                if i >= found.first_data:
                    writer.writerow(found.cells(line) if line.strip() else [])
                elif i in found.header:
                    writer.writerow(_header_cells(line, found.regions))
                elif _RULE.fullmatch(line) or not line.strip():
                    writer.writerow([])
                else:
                    writer.writerow([line.strip()])
        with named_as(out, str(path), lambda exc: at_file(exc, out, path)):
            yield out

