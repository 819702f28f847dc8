"""A CSV file's header written again under its data (initone65): a logger that restarted in the
middle of a day file writes its header line (and the unit row under it) once more.  Such a line
is left out of the rows, as a footer is, and said in a warning naming the file and the line;
rows after it are counted without it (:class:`.lines.Lines`).

The rule: a line equal, byte for byte, to the file's header line (and the line under it, where
it equals the file's unit row) is no data; nor are the lines right above it that a logger writes
again with it (stranger66): each equal to a line of the file's own preamble, or, where that
preamble is all ``#`` comments, a ``#`` comment (a DAQ script's block, its start time another).
Only the exact header is: a line of other text stays a row, refused with its row as before.
The search is one byte search of the mapped file (no row is parsed), so a file without one
costs nothing noticeable.  A stream piped into ``monitor monitor.input=-`` (or ``connect``) is
searched by the same rule (:func:`spans_in`, leftovers66: the header's text was read as a cell
of each number column and refused).

A file that writes ``#`` comments (every non-blank line above its header one, or its header
written as one: a DAQ script's) may write one among its rows too (a ``# marker: tool change``
mid-run): such a line is left out and said by its line, by the file reader, ``init`` and a
stream alike (leftovers67: the file reader refused it, "expected 7 fields, got 1", and a stream
left out every ``#`` line under a commented header or any unit row, unsaid).  In a file whose
preamble writes no comment, a ``#`` line among the rows is a row as before, and one of other
than the header's width refused saying what it is (:data:`STRAY`): Excel writes ``#N/A`` as a
cell, and such a row is read as a row.
"""

from __future__ import annotations

import mmap
from pathlib import Path

import pyarrow as pa

from ...base.log import logger
from .layout import uncommented

# the refusal of a '#' line among the rows of a file that writes no comment (file and stream)
STRAY = ("a '#' line among the rows, of other than the header's width: a comment? a '#' line is "
         "left out as one only in a file that writes '#' comments (its lines above the header, "
         "or its header itself); delete the line, or write the file's preamble as '#' comments")


class Spans(tuple):
    """The ``(first byte, past last byte)`` spans left out of a file, in order; ``comments``:
    those of a ``#`` comment among the rows (the others a header written again)."""

    comments: tuple = ()

    def __new__(cls, spans=(), comments=()):
        out = super().__new__(cls, spans)
        out.comments = tuple(comments)
        return out


def _line_at(m, start: int) -> tuple[bytes, int]:
    """The line starting at byte ``start`` without its line end, and the byte after its end."""
    end = m.find(b"\n", start)
    end = len(m) if end < 0 else end + 1
    return m[start:end].rstrip(b"\r\n"), end


def header_again(path: Path, preamble: int, units: bool, sep: str, cut: int | None = None
                 ) -> Spans:
    """The :class:`Spans` of each header written again in ``path`` (the header on line
    ``preamble + 1``; ``units``: a unit row under it, left out with it where it is written again
    too) and of each ``#`` comment among its rows (a file that writes them; ``sep``: its
    delimiter), above byte ``cut`` (a footer's start); () where none is."""
    with open(path, "rb") as f:
        try:
            m = mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ)
        except ValueError:                      # an empty file
            return Spans()
        with m:
            return spans_in(m, preamble, units, sep, cut)


def spans_in(m, preamble: int, units: bool, sep: str, cut: int | None = None) -> Spans:
    """:func:`header_again`'s spans in a file's bytes ``m`` (a mapped file, or the bytes of a
    stream: ``monitor.input=-`` reads a lab's day file piped in by the same rule)."""
    start, above = 0, []
    for _ in range(preamble):
        line, start = _line_at(m, start)
        above.append(line)
        if start >= len(m):
            return Spans()
    header, body = _line_at(m, start)
    unit_row, body = _line_at(m, body) if units else (None, body)
    header = header.removeprefix(b"\xef\xbb\xbf")     # (a BOM: written once, first)
    if not header.strip():
        return Spans()
    stop = len(m) if cut is None else min(cut, len(m))
    commented = writes_comments(above, header, sep)
    spans, at = [], body
    while (found := m.find(b"\n" + header, at - 1 if at else 0, stop)) >= 0:
        first = found + 1
        line, end = _line_at(m, first)
        at = end
        if line != header:              # a longer line starting with the header's text
            continue
        if unit_row is not None and end < stop and _line_at(m, end)[0] == unit_row:
            end = _line_at(m, end)[1]
        first = _block_above(m, first, above, preamble, commented)
        spans.append((first, min(end, stop)))
    comments = comments_in(m, body, stop, spans) if commented else []
    return Spans(sorted(spans + comments), comments)


def writes_comments(above: list[bytes], header: bytes, sep: str) -> bool:
    """The file writes ``#`` comments: every non-blank line of its preamble ``above`` is one (at
    least one), or, without a preamble, its ``header`` is written as one (``# t [s]``, not a
    first column named ``#``: :func:`.layout.uncommented`)."""
    written = [ln.removeprefix(b"\xef\xbb\xbf") for ln in above if ln.strip()]
    if written:
        return all(ln.lstrip().startswith(b"#") for ln in written)
    first = header.split(sep.encode(), 1)[0].decode("latin-1")
    return uncommented([first], []) != [first]


def comments_in(m, body: int, stop: int, spans) -> list[tuple[int, int]]:
    """The spans of the ``#`` lines from byte ``body`` to ``stop`` outside the ``spans``."""
    out, at = [], body
    while (found := m.find(b"#", at, stop)) >= 0:
        first = m.rfind(b"\n", 0, found) + 1
        end = _line_at(m, found)[1]
        at = end
        if first >= body and not m[first:found].strip(b" \t") and \
                not any(a <= first < b for a, b in spans):
            out.append((first, min(end, stop)))
    return out


def _block_above(m, first: int, above: list[bytes], most: int, commented: bool) -> int:
    """``first`` moved up over the lines a logger writes again above its header (stranger66: a
    DAQ script's ``#`` block, its ``# start:`` line another time): each equal to a line of the
    file's own preamble ``above``, or a ``#`` comment where the file writes them
    (``commented``); at most ``most`` lines."""
    for _ in range(most):
        if first == 0:
            break
        start = m.rfind(b"\n", 0, first - 1) + 1
        line = m[start:first].rstrip(b"\r\n")
        if not line.strip() or not (line in above or commented and line.lstrip().startswith(b"#")):
            break
        first = start
    return first


def line_numbers(path: Path, spans) -> tuple[int, ...]:
    """The 1-based file lines the ``spans`` cover."""
    if not spans:
        return ()
    with open(path, "rb") as f, mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ) as m:
        return lines_in(m, spans)


def lines_in(m, spans) -> tuple[int, ...]:
    """The 1-based lines of the bytes ``m`` the ``spans`` cover."""
    out = []
    for first, end in spans:
        line = m[:first].count(b"\n") + 1
        out.extend(range(line, line + max(1, m[first:end].rstrip(b"\r\n").count(b"\n") + 1)))
    return tuple(out)


def said(path: Path, lines: tuple[int, ...], spans: Spans) -> None:
    """The warning: each header written again and each comment among the rows, by its file
    line (once a stage run, however often it reads the file: log.said_once)."""
    if not spans:
        return
    warn(path, lines, line_numbers(path, spans.comments))


def warn(source, lines: tuple[int, ...], comments: tuple[int, ...] = ()) -> None:
    """Say that the ``lines`` of ``source`` (a file, ``<stdin>``) are a header written again,
    but the ``comments``, ``#`` comments among its rows."""
    said = set(comments)
    again = [ln for ln in lines if ln not in said]
    if again:
        logger.warning(f"{source}, {_where(again)}: the file's header written again under its "
                       "data (a logger restarted?; the lines of its preamble above it too, where "
                       "written again): left out, the rows after it read as rows of the file")
    if comments:
        logger.warning(f"{source}, {_where(comments)}: a '#' comment among the rows (the file "
                       "writes '#' comments: a logger's note?): left out, the rows after it read "
                       "as rows of the file")


def _where(lines) -> str:
    """``lines 3, 9``: the first line of each block of ``lines``."""
    held = set(lines)
    starts = [ln for ln in lines if ln - 1 not in held]
    return (f"line{'s' * (len(starts) > 1)} " + ", ".join(map(str, starts[:5]))
            + (", ..." if len(starts) > 5 else ""))


def kept(whole, spans, stop: int) -> bytes:
    """The bytes ``whole[:stop]`` (an Arrow buffer, bytes) without the ``spans``."""
    parts, at = [], 0
    for first, end in spans:
        parts.append(bytes(whole[at:first]))
        at = end
    parts.append(bytes(whole[at:stop]))
    return b"".join(parts)


def without(path: Path, cut: int | None, spans):
    """What Arrow reads: the file's first ``cut`` bytes (all: None) without the ``spans``."""
    size = path.stat().st_size
    stop = size if cut is None else min(cut, size)
    whole = pa.memory_map(str(path)).read_buffer(stop)
    return pa.BufferReader(kept(whole, spans, stop))
