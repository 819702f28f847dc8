"""Where a lab's CSV table starts: lines a logger writes above the header (``Logger: XY-200``,
``Date: 28.11.2026``) and a row of units under it (``s;°C;°C;µm``).

The header is the first line, most of its fields named, from which every sampled line splits into
the same number (> 1) of fields; below a preamble it must hold no number (a data row is never
taken for it). A unit row is the line under the header whose every cell is a unit the reader knows
(or empty), or one written as a unit of no sensor of the model (``l/min``, ``W/m^2``: its column
left out by its unit, as in a header): its units join the headers (``T1`` over ``°C`` is ``T1
[°C]``). A logger writes the time column's FORMAT in that row (``h:mm:ss``, ``yyyy/mm/dd
hh:mm:ss``): a cell of the row, joined to no header (the column's cells say their time
themselves). Between the unit row and the samples a logger may write rows that describe its
channels (HBM catman's ASCII export: a row of channel comments, rows ``T0`` / ``dt`` of each
channel's start and step, catman70): they are left out (:func:`property_rows`). A Campbell
Scientific logger's TOA5 file has a fixed layout, read so (:mod:`.campbell`): its environment line
above the header, a units row and a processing row.
"""

from __future__ import annotations

import re

from .campbell import environment
from .csvline import EMPTY, split_line
from .roles import STATE_UNITS, UNITS, split_unit
from .separators import any_number
from .timestamps import looks_like_timestamp
from .units import ANGLE_UNITS, foreign_unit

MAX_PREAMBLE = 20
MAX_PROPERTY_ROWS = 6
# a channel property's label in a row's first cell ('T0', 'dt', 'Delta t'): a word, no number
_LABEL = re.compile(r"[^\W\d][\w.]*(?: [^\W\d][\w.]*)?")
# a time column's format as a logger's unit row spells it: a date of y / m / d letters, a time
# of h : mm (: ss, a fraction), or both ('h:mm:ss', '[h]:mm:ss', 'yyyy/mm/dd hh:mm:ss.000')
_DATE_FORMAT = r"(?:[ymd]{1,4}[-/.]){2}[ymd]{1,4}"
_TIME_FORMAT = r"\[?h{1,2}\]?:m{1,2}(?::s{1,2}(?:[.,](?:0+|s+))?)?"
TIME_FORMAT = re.compile(rf"{_DATE_FORMAT}(?:\s*{_TIME_FORMAT})?|{_TIME_FORMAT}")


def cells(line: str, sep: str) -> list[str]:
    return split_line(line, sep, EMPTY)          # (no CSV text: no table starts there)


def header_line(lines: list[str], sep: str) -> int | None:
    """Index of the header among ``lines`` (the file's first, physical), None when no line
    starts a table of ``sep``-separated fields."""
    if sep == "," and len(lines) > 1 and environment(lines[0]) is not None:
        return 1           # (a TOA5 environment line of the table's width was taken for its header)
    widths = [len(cells(ln, sep)) if ln.strip() else None for ln in lines]
    for k, width in enumerate(widths[:MAX_PREAMBLE + 1]):
        if width is None or width < 2 or not _named(cells(lines[k], sep)):
            continue
        if k and not _preamble(lines[:k + 1], lines[k + 1:], sep):
            if not _text(lines[k]):        # bytes that are no text (a gzip file): no preamble
                return None
            continue
        # (a '#' comment among the rows: a DAQ's block written again with its header, stranger66;
        # a line of the preamble so, audit96: a second export's Excel 'sep=;' above its header)
        above = set(lines[:k])
        body = [w for w, ln in zip(widths[k + 1:], lines[k + 1:])
                if w is not None and not ln.lstrip().startswith("#") and ln not in above]
        body = body[:-1] if len(body) > 1 else body        # the last may be cut short
        if all(w == width for w in body):
            return k
    return None


def _preamble(above: list[str], below: list[str], sep: str) -> bool:
    """Lines of text, the last a header (no number in it) over a row holding a number (under
    a unit row and rows of channel properties, maybe)."""
    rows = [cells(ln, sep) for ln in below[:MAX_PROPERTY_ROWS + 3] if ln.strip()]
    # (rows describing channels only under a unit row: a group row over the names is no header)
    samples = rows[1 + property_rows(rows[1:]):] if rows and is_unit_row(rows[0]) else []
    return (all(map(_text, above)) and not any(any_number(c) for c in cells(above[-1], sep))
            and any(any_number(c) for row in rows[:2] + samples[:1] for c in row))


def property_rows(rows: list[list[str]]) -> int:
    """How many of ``rows`` (the lines under the header's unit row, split) describe the
    channels, not samples: rows before the first that holds a number (catman's channel
    comments, its ``T0`` row of dates), and rows labelled in the first cell (``dt``) over a
    first column the samples start with a number or a date in; none where no sample row follows
    within :data:`MAX_PROPERTY_ROWS` (a text row there is the reader's to refuse)."""
    def labelled(row, first):
        return bool(row and _LABEL.fullmatch(row[0].strip())) and (
            any_number(first) or looks_like_timestamp(first))

    for k, row in enumerate(rows[:MAX_PROPERTY_ROWS + 1]):
        if not any(c.strip() for c in row):
            return 0
        if any(any_number(c) for c in row):
            rest = rows[k:]
            first = next((r[0] for r in rest if r and not _LABEL.fullmatch(r[0].strip())), "")
            labels = 0
            while labels < len(rest) - 1 and labelled(rest[labels], first):
                labels += 1
            return k + labels if k + labels <= MAX_PROPERTY_ROWS else 0
    return 0


def _named(fields: list[str]) -> bool:
    """Fields a header could be: most of them named (Excel pads a title line ``Run 3;;;;;``
    to the table's width, and that line is no header)."""
    named = sum(1 for f in fields if f.strip())
    return named >= 2 and 2 * named > len(fields)


def _text(line: str) -> bool:
    return line.replace("\t", " ").isprintable()


def is_unit_row(row: list[str]) -> bool:
    """Every cell a unit (or empty), at least one."""
    units = [c.strip().lower().replace(" ", "") for c in row if c.strip()]
    # (an axis' angle, '°', is a state's unit: stranger68's 'B axis' over '°' made the row data;
    # audit96: a coolant's 'l/min' among them did too, every column then refused as text)
    known = {u for table in UNITS.values() for u in table} | STATE_UNITS | ANGLE_UNITS | {"-"}
    return bool(units) and all(u.strip("[]()") in known or is_time_format(u) or foreign_unit(u)
                               for u in units)


def is_time_format(cell: str) -> bool:
    """``cell`` spells a time column's format (``h:mm:ss``, ``yyyy/mm/dd hh:mm``), as a logger's
    unit row gives it for its time column."""
    return bool(TIME_FORMAT.fullmatch(cell.strip().lower().replace(" ", "")))


# a header written as a comment (numpy's ``savetxt``, a DAQ script: ``# t [s]<TAB>T1 [degC]``)
_COMMENTED = re.compile(r"#+\s*(?=\S)")


def uncommented(header: list[str], above: list[str]) -> list[str]:
    """``header`` without the ``#`` a DAQ script writes before it (``# t [s]`` -> ``t [s]``,
    stranger66), where every non-blank line above it is a ``#`` comment too (or none is above
    it); a first column named ``#`` alone (a sample counter) stays as it is."""
    if not header or not _COMMENTED.match(header[0].lstrip()):
        return header
    if not all(ln.lstrip().startswith("#") for ln in above if ln.strip()):
        return header
    return [_COMMENTED.sub("", header[0].lstrip(), count=1), *header[1:]]


def unquoted(header: list[str]) -> list[str]:
    """``header`` with a name still in double quotes after the CSV reading read as its text
    (lab75: AmeriFlux's ``_21`` tables quote their names twice, ``\"\"\"TIMESTAMP_START\"\"\"``,
    which the CSV dialect reads as ``\"TIMESTAMP_START\"``): a quoted header is its text, as
    ``stream.c`` reads it."""
    out = []
    for name in header:
        bare = name.strip()
        while len(bare) >= 2 and bare[0] == bare[-1] == '"':
            bare = bare[1:-1].strip()
        out.append(bare if bare != name.strip() else name)
    return out


def with_units(header: list[str], units: list[str]) -> list[str]:
    """``header`` with the unit row's units, where a header says none itself."""
    return [f"{h} [{u.strip().strip('[]()')}]"
            if u.strip() and not is_time_format(u) and split_unit(h)[1] is None else h
            for h, u in zip(header, [*units, *[""] * len(header)])]


_JOINED = re.compile(r"(.*\S) \[[^\[\]]+\]")


def bare_header(header: str) -> str | None:
    """The header as the lab's logger writes it above a unit row: ``Temperatura ambiente`` for
    ``Temperatura ambiente [°C]`` (:func:`with_units`' join undone; the exported ``stream.c``
    reads a header so, ``named``); None for a header without a unit in brackets at its end."""
    match = _JOINED.fullmatch(str(header))
    return match.group(1) if match else None


