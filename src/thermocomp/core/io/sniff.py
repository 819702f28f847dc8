"""``data.delimiter=auto`` and ``data.decimal=auto``: the separator and decimal mark a CSV file
is written with, read from its first lines (a lab's export: ``;`` and decimal commas, a BOM)."""

from __future__ import annotations

import re
from dataclasses import replace
from pathlib import Path

from .contract import ContractError
from .csvline import EMPTY, SPLIT, split_line
from .encoding import UTF8, check_text, own, text_codec
from .layout import header_line, is_unit_row
from .options import _OTHER_DELIMITERS, AUTO, ReadOptions

SNIFF_LINES = 50
_SNIFF_BYTES = 1 << 16
_DECIMAL_COMMA = re.compile(r"\s*[+\-\u2212]?\d*,\d+(?:[eE][+-]?\d+)?\s*")   # (U+2212: a minus)
_DECIMAL_POINT = re.compile(r"\s*[+\-\u2212]?\d*\.\d+(?:[eE][+-]?\d+)?\s*")
_GROUPED = {mark: re.compile(rf"\s*[+\-\u2212]?\d{{1,3}}(?:{re.escape(mark)}\d{{3}})+\s*")
            for mark in ",."}
_MARKED = re.compile(r"\s*[+\-\u2212]?[\d.,]*\d[\d.,]*\s*")     # digits and marks alone


def resolved(path: Path, opts: ReadOptions) -> ReadOptions:
    """``opts`` with ``delimiter`` and ``decimal`` detected where they say ``auto``.

    Raises
    ------
    ContractError
        When two separators (or both decimal marks) read the file equally well: naming the
        key to set.
    """
    if AUTO not in (opts.delimiter, opts.decimal, opts.thousands):
        return opts
    return detected(head_lines(path, opts.encoding), opts, path)


def detected(lines: list[str], opts: ReadOptions, where) -> ReadOptions:
    """:func:`resolved` on the first (non-empty) lines of a CSV text; ``where`` names it."""
    lines = [ln for ln in lines if ln.strip()][:SNIFF_LINES]
    delimiter = _delimiter(lines, where) if opts.delimiter == AUTO else opts.delimiter
    body = lines[(header_line(lines, delimiter) or 0):]       # below a logger's preamble
    decimal = _decimal(body, delimiter, where) if opts.decimal == AUTO else opts.decimal
    thousands = (_thousands(body, delimiter, decimal, where) if opts.thousands == AUTO
                 else opts.thousands)
    return replace(opts, delimiter=delimiter, decimal=decimal, thousands=thousands)


def head_lines(path: Path, encoding: str = UTF8) -> list[str]:
    """The first whole lines of a file (in its first 64 KiB; undecodable bytes replaced): a
    line the window cuts is left out (a historian's long file cut inside its tag column read as
    a row without a tag, the file then read as wide: labfiles62)."""
    encoding = own(path, encoding)
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
        # (data87) named where the file turns ambiguous: of each mark the first cell that does
        # not group digits by three with it (a decimal mark's, then), the later of the two
        seen, here = sorted((_where(lines, delimiter, next(
            (c for c in found if not _GROUPED[mark].fullmatch(c)), found[0]))
            for found, mark in ((comma, ","), (point, "."))), key=lambda w: w[1])
        raise ContractError(f"the decimal mark is ambiguous ({here[2]!r} here, {seen[2]!r} in "
                            f"column {seen[0]!r}, data row {seen[1]}: each mark as a decimal "
                            "mark): set data.decimal (and data.thousands if one of them groups "
                            "digits)", file=path, column=here[0], row=here[1])
    return "," if comma else "."


def _where(lines: list[str], delimiter: str, cell: str) -> tuple[str, int, str]:
    """``(header, data row, cell)`` of the first cell of ``lines`` (the header first, then its
    unit row, if any, and the rows: blank lines left out as the reader leaves them) equal to
    ``cell``."""
    header = split_line(lines[0], delimiter, SPLIT)
    units = len(lines) > 1 and is_unit_row(split_line(lines[1], delimiter, EMPTY))
    for row, line in enumerate(lines[1 + units:], start=1):
        cells = split_line(line, delimiter, SPLIT)
        if cell in cells:
            k = cells.index(cell)
            return (header[k].strip() if k < len(header) else f"column {k + 1}"), row, cell
    return "", 0, cell


def _thousands(lines: list[str], delimiter: str, decimal: str, where) -> str | None:
    """``data.thousands=auto`` (data87): the mark other than ``decimal`` where every number cell
    holding it groups its digits by three with it (a German Excel's ``6.000`` beside ``21,18``),
    else None; a number that holds it otherwise beside cells it groups is refused here, naming
    its column and row."""
    other = "." if decimal == "," else ","
    cells = [c for ln in lines[1:] for c in split_line(ln, delimiter, SPLIT)]
    marked = [c for c in cells if other in c and _MARKED.fullmatch(c)]   # (not a date's dots)
    grouping = [c for c in marked if _GROUPED[other].fullmatch(c)]
    if marked and len(grouping) == len(marked):
        return other
    # (audit112) a number holding the mark otherwise ('1,234.5' beside '6.000'; a bare date's
    # two dots are no number) is named here: left to the read, the first grouped cell was
    # refused instead, '6.000' at row 1, with a data.thousands='.' the folder's other files refuse
    odd = next((c for c in marked if c not in grouping and (decimal in c or c.count(other) == 1)),
               None)
    if grouping and odd is not None:
        column, row, cell = _where(lines, delimiter, odd)
        raise ContractError(f"value {cell.strip()!r} does not group its digits by three with "
                            f"{other!r}, the thousands separator of this file's {grouping[0].strip()!r} "
                            "(data.thousands=auto): mend that cell", file=where, column=column, row=row)
    return None
