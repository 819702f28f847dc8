"""Thousands separators in CSV numbers: read with ``data.thousands``, and named when a cell
holds one that the settings do not read (rather than blaming a decimal comma)."""

from __future__ import annotations

import re

import numpy as np
import pyarrow as pa
import pyarrow.compute as pc

# marks a lab may group digits with (6,000  6.000  6'000, and a French or SI export's 6 000 with
# a no-break space, U+00A0, or a narrow one, U+202F); a plain space is never one in a CSV cell
# that Arrow reads, it would be a field of its own or trimmed
NO_BREAK_SPACES = ("\u00a0", "\u202f")
GROUP_MARKS = (",", ".", "'", *NO_BREAK_SPACES)
UNICODE_MINUS = "\u2212"      # '−1,5': a minus sign, read as '-'


def any_number(text: str) -> bool:
    """``text`` is a number with either decimal mark (a header line, a unit row or a mark for a
    missing value is none; an empty cell is none either)."""
    return bool(str(text).strip()) and reads_as_number(str(text).replace(",", "."))


def reads_as_number(text, decimal: str = ".", thousands: str | None = None) -> bool:
    """A cell's text reads as a number (with ``decimal``, ``thousands`` and a Unicode minus as
    the reader takes them); a missing cell (None, empty) counts as one."""
    return text is None or not str(text).strip() or number(text, decimal, thousands) is not None


def number(text, decimal: str = ".", thousands: str | None = None) -> float | None:
    """The number a cell's text reads as (:func:`reads_as_number`), None if none."""
    text = str(text).strip().replace(UNICODE_MINUS, "-")
    if thousands is not None:
        text = text.replace(thousands, "")
    try:
        return float(text.replace(decimal, ".") if decimal != "." else text)
    except ValueError:
        return None


def grouped(mark: str, decimal: str) -> str:
    """A number whose digits are grouped by three with ``mark`` (a regex, whole cell)."""
    m, d = re.escape(mark), re.escape(decimal)
    return rf"\s*[+-]?\d{{1,3}}(?:{m}\d{{3}})+(?:{d}\d*)?(?:[eE][+-]?\d+)?\s*"


def decimal_comma_hint(value: str, decimal: str) -> str:
    """``": a decimal comma? set data.decimal=','"`` where ``value`` is a number written with a
    decimal comma the settings (``decimal``) do not read; else ``""``.  The file reader's hint and
    a stream's (stdin, dep107c) alike."""
    if decimal == "," or not re.fullmatch(r"\s*[+-]?\d*,\d+\s*", str(value)):
        return ""
    return ": a decimal comma? set data.decimal=','"


def thousands_hint(value: str, column: pa.ChunkedArray, decimal: str) -> str | None:
    """``": a thousands separator? set data.thousands=','"`` when ``value`` groups its digits
    by three with a mark other than ``decimal``.  ``6,000`` could also be a decimal comma with
    three decimals: it is one only if another cell of ``column`` (the raw text) has a comma
    followed by other than three digits (``21,35``)."""
    for mark in GROUP_MARKS:
        if mark == decimal or not re.fullmatch(grouped(mark, decimal), value):
            continue
        if mark in ",." and value.count(mark) == 1 and decimal not in value:
            m = re.escape(mark)
            as_decimal = pc.match_substring_regex(
                column, rf"^\s*[+-]?\d*{m}(?:\d{{1,2}}|\d{{4,}})(?:[eE][+-]?\d+)?\s*$")
            if pc.any(as_decimal).as_py():
                return None
        said = " (a no-break space)" if mark in NO_BREAK_SPACES else ""
        # a cell the key would refuse next is named now (audit99: one '1.00,5' at data row 700
        # took a second try, the key's refusal naming it only after the key was set)
        bad = misgrouped(column, mark, decimal)
        then = ("" if bad is None else f"; then data row {bad + 1}, {column[bad].as_py()!r}, "
                "does not group its digits by three: mend that cell")
        return f": a thousands separator{said}? set data.thousands={mark!r}{then}"
    return None


def misgrouped(column: pa.ChunkedArray, mark: str, decimal: str) -> int | None:
    """Position of the first cell that holds ``mark`` without grouping digits by three with
    it (``6,00`` with ``data.thousands=','`` is no thousand: it is refused, not read as 600).
    A cell without a digit (``n.d.``, an Italian lab's "not available") is no number: the cast
    refuses it as the text it is (audit96: it was said not to group its digits by three)."""
    bad = pc.and_(pc.and_(pc.match_substring(column, mark), pc.match_substring_regex(column, r"\d")),
                  pc.invert(pc.match_substring_regex(column, f"^{grouped(mark, decimal)}$")))
    flags = pc.fill_null(bad, False).to_numpy(zero_copy_only=False)
    return int(np.argmax(flags)) if flags.any() else None


def ungrouped(column: pa.ChunkedArray, mark: str | None, decimal: str) -> pa.ChunkedArray:
    """The text of ``column`` as Arrow casts it to float: no ``mark`` (none when ``None``), a
    Unicode minus as ``-``,
    ``.`` as the decimal mark (a ``.`` where ``decimal`` is another mark stays invalid, as
    Arrow's reader has it)."""
    text = column if mark is None else pc.replace_substring(column, mark, "")
    text = pc.replace_substring(text, UNICODE_MINUS, "-")
    if decimal != ".":
        text = pc.replace_substring(pc.replace_substring(text, ".", "!"), decimal, ".")
    return text
