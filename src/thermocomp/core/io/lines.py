"""Where a data row stands in its CSV file: the 1-based line a lab's editor shows.

A row in a message counts the data rows (:class:`~thermocomp.base.errors.ContractError`), but a
lab opens the file: a logger's preamble, the header, a unit row, blank lines among the rows (the
CSV reader skips them) and rows of empty cells left out (:func:`.tables._without_empty_rows`)
all stand between the two.  The file is scanned only when a message needs the line.
"""

from __future__ import annotations

import csv
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from ...base.errors import position
from .contract import ContractError
from .encoding import own, text_codec


@dataclass(frozen=True)
class Lines:
    """The data rows of one CSV file (``skip``: the lines above the first, as the reader skips
    them; ``empty_left_out``: rows of empty cells are not counted, as after they were left out;
    ``shift``: the data rows above the part whose rows are counted, one run of a long file)."""

    path: Path
    delimiter: str
    encoding: str
    skip: int
    empty_left_out: bool = False
    shift: int = 0
    dropped: tuple = ()     # file lines left out (the header written again: .again)
    time_field: int | None = None    # the time column's place among a row's fields

    def line(self, row: int) -> int | None:
        """The file line of the 1-based data ``row`` (None: not in the file)."""
        return self._record(row)[0]

    def time_cell(self, row: int) -> str | None:
        """The time of the 1-based data ``row`` as the file writes it (``2027-03-28
        10:29:00+02:00``, where the reader holds the instant in UTC); None where unknown."""
        fields = self._record(row)[1]
        if self.time_field is None or fields is None or self.time_field >= len(fields):
            return None
        return fields[self.time_field].strip() or None

    def _record(self, row: int) -> tuple[int | None, list[str] | None]:
        """``(file line, fields)`` of the 1-based data ``row`` (None, None: not in the file)."""
        row += self.shift
        with open(self.path, newline="", encoding=text_codec(own(self.path, self.encoding)),
                  errors="replace") as f:
            for _ in range(self.skip):
                f.readline()
            reader = csv.reader(f, delimiter=self.delimiter)
            end, count = 0, 0
            try:
                for record in reader:
                    start, end = end + 1, reader.line_num
                    blank = not record or (self.empty_left_out and not any(
                        c.strip() for c in record)) or self.skip + start in self.dropped
                    count += not blank
                    if count == row and not blank:
                        return self.skip + start, record
            except csv.Error:          # a line the csv module cannot split: no line to name
                return None, None
        return None, None

    def at(self, row: int) -> str:
        """``line 13 (data row 9)``: where a warning points."""
        return position(row + self.shift, self.line(row))

    def located(self, exc: ContractError) -> ContractError:
        """``exc`` naming the file line of its row too (as it is when it names none, or
        another file)."""
        if exc.row is None or exc.line is not None or exc.file is None or \
                Path(exc.file) != self.path:
            return exc
        return ContractError(exc.reason, file=exc.file, column=exc.column,
                             row=exc.row + self.shift, line=self.line(exc.row))


def at(lines: Lines | None) -> Callable[[int], str]:
    """What names a data row in a warning: its line too where the file has lines."""
    return position if lines is None else lines.at
