"""``data.delimiter=auto`` and ``data.decimal=auto``: the separator and decimal mark a CSV file
is written with, read from its first lines (a lab's export: ``;`` and decimal commas, a BOM)."""

from __future__ import annotations

import re
from dataclasses import replace
from pathlib import Path

from .contract import ContractError
from .csvline import SPLIT, split_line
from .encoding import UTF8, check_text, text_codec
from .layout import header_line
from .options import _OTHER_DELIMITERS, AUTO, ReadOptions

SNIFF_LINES = 50
_SNIFF_BYTES = 1 << 16
_DECIMAL_COMMA = re.compile(r"\s*[+\-\u2212]?\d*,\d+(?:[eE][+-]?\d+)?\s*")   # (U+2212: a minus)
_DECIMAL_POINT = re.compile(r"\s*[+\-\u2212]?\d*\.\d+(?:[eE][+-]?\d+)?\s*")
_GROUPED = {mark: re.compile(rf"\s*[+\-\u2212]?\d{{1,3}}(?:{re.escape(mark)}\d{{3}})+\s*")
            for mark in ",."}


def resolved(path: Path, opts: ReadOptions) -> ReadOptions:
    """``opts`` with ``delimiter`` and ``decimal`` detected where they say ``auto``.

    Raises
    ------
    ContractError
        When two separators (or both decimal marks) read the file equally well: naming the
        key to set.
    """
    if AUTO not in (opts.delimiter, opts.decimal):
        return opts
    return detected(head_lines(path, opts.encoding), opts, path)


def detected(lines: list[str], opts: ReadOptions, where) -> ReadOptions:
    """:func:`resolved` on the first (non-empty) lines of a CSV text; ``where`` names it."""
    lines = [ln for ln in lines if ln.strip()][:SNIFF_LINES]
    delimiter = _delimiter(lines, where) if opts.delimiter == AUTO else opts.delimiter
    body = lines[(header_line(lines, delimiter) or 0):]       # below a logger's preamble
    decimal = _decimal(body, delimiter, where) if opts.decimal == AUTO else opts.decimal
    return replace(opts, delimiter=delimiter, decimal=decimal)


def head_lines(path: Path, encoding: str = UTF8) -> list[str]:
    """The first whole lines of a file (in its first 64 KiB; undecodable bytes replaced): a
    line the window cuts is left out (a historian's long file cut inside its tag column read as
    a row without a tag, the file then read as wide: labfiles62)."""
    with open(path, "rb") as f:
        head = f.read(_SNIFF_BYTES)
        cut = len(head) == _SNIFF_BYTES and f.read(1) not in (b"", b"\n", b"\r")
    check_text(head, encoding, path)
    lines = head.decode(text_codec(encoding), "replace").splitlines()
    return lines[:-1] if cut and len(lines) > 1 and not head.endswith((b"\n", b"\r")) else lines


def _delimiter(lines: list[str], path: Path) -> str:
    """The separator splitting every sampled line into the same number (> 1) of fields, below
    the fewest lines of a logger's preamble (:mod:`.layout`); ``,`` (the contract's) for a file
    of one column."""
    if not lines:
        return ","
    starts = {sep: header_line(lines, sep) for sep in dict.fromkeys((",", *_OTHER_DELIMITERS))}
    starts = {sep: k for sep, k in starts.items() if k is not None}
    fits = [sep for sep, k in starts.items() if k == min(starts.values())]
    if len(fits) > 1:
        raise ContractError(f"the field separator is ambiguous ({' or '.join(map(repr, fits))} "
                            "both split every line alike): set data.delimiter", file=path)
    return fits[0] if fits else ","


def _decimal(lines: list[str], delimiter: str, path: Path) -> str:
    """``,`` when number cells hold decimal commas and none a decimal point (never with ``,``
    separating the fields), else ``.``."""
    if delimiter == ",":
        return "."
    cells = [c for ln in lines[1:] for c in split_line(ln, delimiter, SPLIT)]
    comma = [c for c in cells if _DECIMAL_COMMA.fullmatch(c)]
    point = [c for c in cells if _DECIMAL_POINT.fullmatch(c)]
    if comma and point:
        # one mark grouping digits by three in every cell, the other not in one (a German
        # export's speed `6.000` beside `21,18`): the other is the decimal mark, and the read
        # (init: data.thousands) names the grouping
        for decimal, grouped, other in ((",", point, comma), (".", comma, point)):
            thousands = "." if decimal == "," else ","
            if all(_GROUPED[thousands].fullmatch(c) for c in grouped) and not all(
                    _GROUPED[decimal].fullmatch(c) for c in other):
                return decimal
        raise ContractError("the decimal mark is ambiguous (cells with ',' and with '.'): set "
                            "data.decimal (and data.thousands if one of them groups digits)",
                            file=path)
    return "," if comma else "."
