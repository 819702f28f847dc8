"""Where a process historian's LONG export is told from a wide table (extension): three or four
columns, a time, a tag column of text, one value column of numbers and maybe a quality column
(:class:`Layout`), or InfluxDB's annotated CSV (:mod:`.influx`); the reading of such a file
onto the grid is :mod:`.historian`'s."""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import pandas as pd

from .contract import ContractError
from .csvline import SPLIT, split_line
from .encoding import text_codec
from .influx import SERIES, TIME, VALUE, is_influx
from .layout import header_line
from .roles import TIME_HEADERS, split_unit
from .sniff import detected, head_lines
from .timestamps import looks_like_timestamp

TAG_WORDS = frozenset({"tag", "tagname", "tag_name", "name", "tag name", "signal", "channel",
                       "variable", "item", "itemid", "point", "sensor", "field", "_field",
                       "measurement", "kanal", "messstelle", "node", "nodeid", "browsename"})
VALUE_WORDS = frozenset({"value", "val", "_value", "wert", "messwert", "valeur", "valor", "pv"})
QUALITY_WORDS = frozenset({"quality", "qual", "q", "status", "statuscode", "flag", "qualität",
                           "qualitaet", "qualite", "qualité", "calidad"})
# a quality as text: its first word (OPC UA's BadCommunicationError, UncertainLastUsableValue)
_GOOD = re.compile(r"^(good|ok|valid)(?![a-z])|^good", re.I)
_NOT_GOOD = re.compile(r"^(bad|uncertain|invalid|questionable|substituted|error|fault|"
                       r"no ?data|comm)", re.I)


@dataclass(frozen=True)
class Layout:
    """Where a long file's columns are: ``header`` (the file's), the positions of the ``time``,
    ``tag``, ``value`` and ``quality`` (None: none) columns, the lines above the header
    (``skip``), the separators read; ``influx``: an InfluxDB annotated CSV (:mod:`.influx`: its
    tables' samples, a message naming the file's line)."""

    header: tuple[str, ...]
    time: int
    tag: int
    value: int
    quality: int | None
    skip: int
    delimiter: str
    decimal: str
    influx: bool = False


INFLUX = Layout((TIME, SERIES, VALUE), 0, 1, 2, None, 0, ",", ".", influx=True)


def long_layout(path, opts) -> Layout | None:
    """The long layout of the CSV file ``path`` (None: a wide file, or no text file): three or
    four columns, a time (its header or its cells say so), a tag column of text whose few
    values come back after one another, a value column, and maybe a quality column (its header
    or its cells say so); read from its first lines."""
    path = Path(path)
    try:
        stat = path.stat()
    except OSError:
        return None
    if not path.is_file() or path.suffix.lower() in (".parquet", ".xlsx", ".xlsm"):
        return None
    return _layout(str(path), stat.st_mtime_ns, stat.st_size, opts.delimiter, opts.decimal,
                   opts.encoding)


@lru_cache(maxsize=64)
def _layout(path: str, _mtime: int, _size: int, delimiter: str, decimal: str, encoding: str
            ) -> Layout | None:
    try:
        lines = [ln for ln in head_lines(Path(path), encoding) if ln.strip()]
        if is_influx(lines):                 # InfluxDB's tables: their samples, one per row
            return INFLUX
        opts = detected(lines, _Seps(delimiter, decimal), path)
    except (ContractError, OSError, UnicodeError, LookupError):
        return None                          # (the wide reader says what is wrong)
    skip = header_line(lines, opts.delimiter) or 0
    rows = [split_line(ln, opts.delimiter, SPLIT) for ln in lines[skip:]]
    if len(rows) < 6:
        return None
    header = [h.strip() for h in rows[0]]
    while header and not header[-1]:         # a trailing separator: an empty last column
        header.pop()
    if len(header) not in (3, 4):
        return None
    body = [r[:len(header)] + [""] * (len(header) - len(r)) for r in rows[1:]]
    cells = [[r[i].strip() for r in body] for i in range(len(header))]
    time = next((i for i in range(len(header)) if _is_time(header[i], cells[i])), None)
    tag = next((i for i in range(len(header)) if i != time and _is_tag(header[i], cells[i])),
               None)
    if time is None or tag is None:
        return None
    rest = [i for i in range(len(header)) if i not in (time, tag)]
    quality = next((i for i in rest if len(rest) == 2 and _is_quality(header[i], cells[i])), None)
    values = [i for i in rest if i != quality]
    if len(values) != 1 or not _mostly_numbers(cells[values[0]], opts.decimal):
        return None
    return Layout(tuple(header), time, tag, values[0], quality,
                  _lines_above(Path(path), encoding, lines[skip]), opts.delimiter, opts.decimal)


@dataclass(frozen=True)
class _Seps:           # what :func:`.sniff.detected` reads of the options
    delimiter: str
    decimal: str
    thousands: str | None = None


def _lines_above(path: Path, encoding: str, header: str) -> int:
    """The file's lines above its header line (blank ones too: pandas' ``skiprows``)."""
    with open(path, encoding=text_codec(encoding), errors="replace", newline="") as f:
        for k, line in enumerate(f):
            if line.rstrip("\r\n") == header:
                return k
    return 0


def _bare(header: str) -> str:
    return split_unit(header)[0].strip().lower()


def _is_time(header: str, cells: list[str]) -> bool:
    filled = [c for c in cells if c]
    return bool(filled) and (_bare(header) in TIME_HEADERS or _bare(header).endswith("time")
                             or all(looks_like_timestamp(c) for c in filled))


def _is_tag(header: str, cells: list[str]) -> bool:
    """Text naming tags: under a tag's header (``TagName``; an archive export sorted by tag
    shows one tag in its first lines), or a few values that come back after one another (a
    run's labels do not)."""
    if not cells or any(not re.search(r"[^\W\d_]", c) for c in cells):
        return False
    if _bare(header) in TAG_WORDS or "tag" in _bare(header).split():
        return True
    seen, last = set(), None
    for c in cells:
        if c != last and c in seen:
            return 2 <= len(set(cells)) <= len(cells) // 2 + 1
        seen.add(c)
        last = c
    return False


def _is_quality(header: str, cells: list[str]) -> bool:
    if _bare(header) in QUALITY_WORDS:
        return True
    filled = [c for c in cells if c]
    return bool(filled) and all(quality_of(c) is not None for c in filled) and any(
        not c.isdigit() or int(c) >= 64 for c in filled)


def _mostly_numbers(cells: list[str], decimal: str) -> bool:
    filled = [c for c in cells if c]
    numbers = pd.to_numeric(pd.Series(filled, dtype=object).str.replace(decimal, ".", regex=False)
                            if decimal != "." else pd.Series(filled, dtype=object), errors="coerce")
    return bool(filled) and numbers.notna().mean() >= 0.5


def quality_of(text: str) -> bool | None:
    """True: Good, False: not Good (Bad, Uncertain), None: no rule reads it.  A number is an
    OPC DA quality byte (192-255 Good, 64-127 Uncertain, 0-63 Bad)."""
    text = text.strip()
    if re.fullmatch(r"\d{1,3}", text):
        code = int(text)
        return None if code > 255 or 128 <= code < 192 else code >= 192
    if _NOT_GOOD.match(text):
        return False
    return True if _GOOD.match(text) else None
