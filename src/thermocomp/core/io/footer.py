"""A footer under a lab's CSV export (``End of data``, ``Stop 13:45``): the last lines of one
field of text, left out (and said), where every line above holds the header's fields.  A last
line of numbers cut short stays a malformed row, refused with its row."""

from __future__ import annotations

import csv
from pathlib import Path

import pyarrow as pa

from .encoding import UTF8

_TAIL_BYTES = 1 << 14
MAX_LINES = 5


def footer(path: Path, delimiter: str, fields: int, encoding: str = UTF8
           ) -> tuple[list[str], int]:
    """``(the footer's lines, the bytes before it)``; ``([], size)`` without one."""
    size = path.stat().st_size
    if fields < 2:                         # one column: every line is one field
        return [], size
    with open(path, "rb") as f:
        f.seek(max(0, size - _TAIL_BYTES))
        tail = f.read()
    lines = tail.splitlines(keepends=True)
    found, cut = [], size
    for raw in reversed(lines[1:] if size > _TAIL_BYTES else lines):
        text = raw.decode(encoding, "replace").strip()
        if text and not _footer_line(text, delimiter):
            break
        if len(found) == MAX_LINES:
            return [], size
        cut -= len(raw)
        if text:
            found.insert(0, text)
    return (found, cut) if found else ([], size)


def source(path: Path, cut: int):
    """What Arrow reads: the file, or its first ``cut`` bytes (memory-mapped, not copied)."""
    if cut >= path.stat().st_size:
        return path
    return pa.BufferReader(pa.memory_map(str(path)).read_buffer(cut))


def _footer_line(text: str, delimiter: str) -> bool:
    cells = next(csv.reader([text], delimiter=delimiter), [])
    if len([c for c in cells if c.strip()]) != 1 or len(cells) > 1 and cells[0].strip() == "":
        return False
    try:
        float(cells[0].replace(",", "."))
    except ValueError:
        return True
    return False
