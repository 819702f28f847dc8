"""One line of CSV text split into its fields (quotes honoured), the one place the few lines
read by hand (header, preamble, footer, the lines sniffed) are split."""

from __future__ import annotations

import csv
import re

RAISE, EMPTY, SPLIT = "raise", "empty", "split"
# what the csv module reads otherwise than a plain split at the delimiter does: a quote, a line
# end, a NUL byte (ci108d: a line without any is split as the module splits it, 10x cheaper)
_SPECIAL = re.compile('["\r\n\0]')


def split_line(line: str, delimiter: str, on_error: str = RAISE) -> list[str]:
    """The fields of ``line``.  A line the csv module does not read (a carriage return inside
    an unquoted field, bytes that are no text): ``on_error`` says what it gives, ``'raise'``
    :class:`csv.Error`, ``'empty'`` no field (no table starts there, no footer), ``'split'``
    the line split at every ``delimiter`` (a header named as best it can be)."""
    if (len(delimiter) == 1 and not _SPECIAL.search(delimiter) and not _SPECIAL.search(line)
            and len(line) <= csv.field_size_limit()):
        return line.split(delimiter) if line else []
    try:
        return next(csv.reader([line], delimiter=delimiter), [])
    except csv.Error:
        if on_error == EMPTY:
            return []
        if on_error == SPLIT:
            return line.split(delimiter)
        raise
