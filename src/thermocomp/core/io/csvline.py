"""One line of CSV text split into its fields (quotes honoured), the one place the few lines
read by hand (header, preamble, footer, the lines sniffed) are split."""

from __future__ import annotations

import csv

RAISE, EMPTY, SPLIT = "raise", "empty", "split"


def split_line(line: str, delimiter: str, on_error: str = RAISE) -> list[str]:
    """The fields of ``line``.  A line the csv module does not read (a carriage return inside
    an unquoted field, bytes that are no text): ``on_error`` says what it gives, ``'raise'``
    :class:`csv.Error`, ``'empty'`` no field (no table starts there, no footer), ``'split'``
    the line split at every ``delimiter`` (a header named as best it can be)."""
    try:
        return next(csv.reader([line], delimiter=delimiter), [])
    except csv.Error:
        if on_error == EMPTY:
            return []
        if on_error == SPLIT:
            return line.split(delimiter)
        raise
