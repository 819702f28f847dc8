"""``data.missing_values``' marks as every reader of cells matches them (extension, lab74): a
mark of text (``---``, ``n/a``) cell for cell as written; a mark that is a number (AmeriFlux's
``-9999``, a Keysight DAQ's overload ``+9.90000000E+37``) by its value, however a cell writes
it (``-9999.0``, ``-9999.000``, ``-9999,0`` with a decimal comma).  The file reader, a stream
on stdin, a historian's long file, the served model and ``stream.c`` (its ``TC_MISSING_VALUE``)
read them so.

A number may be a mark only where it is no reading (:func:`is_number_mark`): below absolute zero
(no temperature reads it) or beyond ``data.max_abs_error`` / ``data.max_abs_state`` (no column
does).  The mark is the lab's statement and applies to every column; where it takes a cell of a
column that is no temperature (an error's or a state's, where the number could be measured), the
file reader says so.

An infinite reading (lab75: a Campbell Scientific logger's ``INF`` / ``-INF`` for an overflow or an
open input; ``inf``, ``Infinity`` as other programs write it) is a missing value in every column,
mark or not (:func:`hits`), as ``NAN`` is: no key lists it, and the reader says its column and rows
(:func:`infinite_said`).
"""

from __future__ import annotations

import re
from collections.abc import Iterable

import numpy as np
import pandas as pd

from .separators import any_number, number

ABSOLUTE_ZERO_C = -273.15
AMERIFLUX = "-9999"      # AmeriFlux's mark for a value not measured (its processed products)
INFINITE = re.compile(r"[+-]?(?:inf|infinity)", re.IGNORECASE)   # as a cell writes an infinity
SHOWN_ROWS = 3           # the rows of infinite readings a warning names


def value_of(mark: str) -> float | None:
    """The finite number ``mark`` is (a decimal comma read as a point), None for text (and for
    ``INF``, ``-INF``: an infinity is missing without being listed, :func:`hits`)."""
    found = _number(mark)
    return found if found is not None and np.isfinite(found) else None


def is_number_mark(mark: str, beyond: float) -> bool:
    """``mark`` a number no reading is: below absolute zero, or of a magnitude above
    ``beyond`` (the largest reading an error or a state may have)."""
    found = _number(mark)
    return found is not None and (found < ABSOLUTE_ZERO_C or abs(found) > beyond)


def _number(mark: str) -> float | None:
    return number(str(mark).replace(",", ".")) if any_number(mark) else None


def texts(marks: Iterable) -> list[str]:
    """The marks of text, matched cell for cell."""
    return [str(m) for m in marks if value_of(str(m)) is None]


def values(marks: Iterable) -> list[float]:
    """The marks that are numbers, by value."""
    return [v for v in (value_of(str(m)) for m in marks) if v is not None]


def numbers_given(marks: Iterable) -> str:
    """The marks that are numbers, as given (``'-9999'``), for a message."""
    return ", ".join(repr(str(m)) for m in marks if value_of(str(m)) is not None)


def hits(column, marks: Iterable) -> np.ndarray:
    """Where the numbers of ``column`` (an array of floats) are missing by their value: a mark's,
    or infinite (a logger's overflow, never a reading)."""
    found = values(marks)
    column = np.asarray(column, dtype=float)
    return np.isinf(column) | (np.isin(column, found) if found else False)


def infinite_said(column: str, rows: list[str], count: int) -> str:
    """What a reader says of ``count`` infinite readings of ``column`` (the first ``rows`` as
    the reader names a row)."""
    more = ", ..." if count > len(rows) else ""
    return (f"column {column!r}: {count} infinite reading(s) ({', '.join(rows)}{more}): a "
            "logger's overflow or an open input, read as missing")


def in_frame(frame, given: Iterable, skip: str):
    """``frame`` (a served block: numbers, text a CSV body's cells kept) with each cell that is a
    mark or infinite NaN, the column ``skip`` (the time) as it is: a number's by value, a
    text's as written."""
    given = [str(m) for m in given]
    words = set(texts(given))
    out = frame.copy()
    for c in out.columns:
        if c == skip:
            continue
        cells = out[c]
        numbers = pd.to_numeric(cells, errors="coerce")
        marked = hits(numbers, given) | cells.map(lambda v: isinstance(v, str) and v.strip() in words
                                                 ).to_numpy(bool)
        if marked.any():      # (a text left: the model refuses it, naming its row)
            left = cells.notna().to_numpy() & numbers.isna().to_numpy() & ~marked
            out[c] = cells.mask(marked) if left.any() else numbers.mask(marked)
    return out
