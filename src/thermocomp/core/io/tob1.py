"""Campbell Scientific's binary table TOB1 (extension, lab75), what LoggerNet and CardConvert
write where a table is kept binary, read as its CSV export (:mod:`.labfile`), as a TOA5 file
is read (:mod:`.campbell`).

Five ASCII lines as TOA5's, each ending CRLF: the environment (``"TOB1","<station>",...``), the
field names, their units, their processing, and the data type of each field (``"ULONG",
"IEEE4","FP2"``); then the records, one after the other with no separator, each field in its
type's bytes: ``ULONG`` / ``LONG`` 4 bytes, ``IEEE4`` / ``IEEE8`` a float, ``USHORT`` /
``SHORT`` 2, ``SecNano`` 8 (seconds, then nanoseconds), little-endian; ``UINT2`` / ``INT2`` /
``UINT4`` / ``INT4`` and ``IEEE4B`` / ``IEEE8B`` big-endian (lab76: as csiio-py 0.4.0 and
camp2ascii 1.1.1 read them; stop 75 read the first four little-endian); ``FP2`` Campbell's
2-byte final storage format, big-endian: a sign bit, a 2-bit decimal exponent, a 13-bit
mantissa (``-1^s * m / 10^e``), its largest mantissa at exponent 0 an infinity (``0x1FFF``,
``0x9FFF``: the logger's ``INF``, read as missing as in a TOA5 file, :mod:`.marks`) and
``0x9FFE`` its NaN (our reading of the format's description; no file a logger wrote was at
hand).  ``SECONDS`` + ``NANOSECONDS`` (or a ``SecNano`` field) since 1990-01-01 are the time,
on the logger's clock; ``RECORD`` (the logger's counter) is left out.  A type not listed, or
bytes that make no whole record at the end, are refused naming the file, the field or the row.
TOB2 / TOB3, the same header over frames, are read by :mod:`.tob3` with these types.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from . import campbell
from .campbell import COUNTERS
from .campbell import units as campbell_units
from .contract import ContractError
from .csvline import split_line
from .labfile import Channel, Record, with_unit

HEADER_LINES = 5
FORMAT = re.compile(rb'\s*"?(TOB[123])"?,')     # a Campbell binary table's first field
EPOCH = np.datetime64("1990-01-01T00:00:00", "ns")     # Campbell's loggers count from it
TIME_FIELDS = ("seconds", "nanoseconds")
# a data type -> its numpy type as the record holds it
# (UINT2 / INT2 / UINT4 / INT4 big-endian: csiio-py's and camp2ascii's reading, lab76)
_TYPES = {"ULONG": "<u4", "UINT4": ">u4", "LONG": "<i4", "INT4": ">i4", "IEEE4": "<f4",
          "IEEE4L": "<f4", "IEEE4B": ">f4", "IEEE8": "<f8", "IEEE8L": "<f8", "IEEE8B": ">f8",
          "USHORT": "<u2", "UINT2": ">u2", "SHORT": "<i2", "INT2": ">i2", "FP2": ">u2",
          "SECNANO": ("<u4", (2,))}
_INFINITE = {0x1FFF: np.inf, 0x9FFF: -np.inf, 0x9FFE: np.nan}     # FP2's own words


def tob_format(path) -> str | None:
    """``'TOB1'``, ``'TOB2'`` or ``'TOB3'``: the Campbell binary table ``path`` is (its first
    field); None for any other file."""
    try:
        with open(path, "rb") as f:
            found = FORMAT.match(f.read(8))
    except OSError:
        return None
    return found and found.group(1).decode()


def is_tob(path) -> bool:
    """``path`` is a Campbell binary table: TOB1, TOB2 or TOB3."""
    return tob_format(path) is not None


def described(path) -> str:
    """How ``init`` names a binary table (:func:`.campbell.said`): a TOB2 / TOB3 file's table
    is named on its line 2, a TOB1's on its line 1."""
    with open(path, "rb") as f:
        first, second = (f.readline().decode("latin-1").rstrip("\r\n") for _ in range(2))
    return campbell.said(first, table=None if tob_format(path) == "TOB1"
                         else split_line(second, ",")[0])


def header_lines(data: bytes, path: Path, count: int) -> tuple[list[list[str]], int]:
    """The first ``count`` ASCII lines of a binary table, split, and the byte its body starts at."""
    lines, start = [], 0
    for _ in range(count):
        end = data.find(b"\n", start)
        if end < 0:
            raise ContractError(f"a {tob_format(path)} file has {count} header lines; this one "
                                f"ends in line {len(lines) + 1}", file=path)
        lines.append(split_line(data[start:end].decode("latin-1").rstrip("\r"), ","))
        start = end + 1
    return lines, start


def record_type(path: Path, names: list[str], units: list[str], types: list[str]) -> np.dtype:
    """One record's numpy type from the data types line (the header's last), fields ``f0`` ..."""
    line = HEADER_LINES if tob_format(path) == "TOB1" else HEADER_LINES + 1
    if not len(names) == len(units) == len(types):
        raise ContractError(f"header lines {line - 3}-{line} differ in width ({len(names)} "
                            f"names, {len(types)} data types)", file=path)
    fields = []
    for name, kind in zip(names, types):
        found = _TYPES.get(kind.strip().upper())
        if found is None:
            raise ContractError(f"data type {kind!r} (line {line}) is not read (read: "
                                f"{', '.join(sorted(_TYPES))})", file=path, column=name)
        fields.append(found)
    return np.dtype([(f"f{i}", *t) if isinstance(t, tuple) else (f"f{i}", t)
                     for i, t in enumerate(fields)])


def channel_values(table, i: int, kind: str) -> np.ndarray:
    """Field ``i`` of the records ``table`` as numbers (FP2 decoded, its INF an infinity)."""
    values = table[f"f{i}"]
    return _fp2(values) if kind.strip().upper() == "FP2" else values.astype(float)


def tob1_records(path: Path) -> list[Record]:
    """The one record of the TOB1 file ``path``: its channels, timed by the logger's clock."""
    data = Path(path).read_bytes()
    lines, start = header_lines(data, path, HEADER_LINES)
    names, units, _, types = lines[1:]
    record = record_type(path, names, units, types)
    body = data[start:]
    rows, left = divmod(len(body), record.itemsize)
    if left:
        raise ContractError(f"the binary records are {record.itemsize} bytes each (line 5's data "
                            f"types); the last {left} bytes make no whole record (a record cut "
                            "short: leave them out)", file=path, row=rows + 1)
    table = np.frombuffer(body, record, count=rows)
    return [_record(path, names, campbell_units(units), types, table)]


def _record(path: Path, names: list[str], units: list[str], types: list[str], table) -> Record:
    by = {n.strip().lower(): i for i, n in enumerate(names)}
    stamp = next((i for i, t in enumerate(types) if t.strip().upper() == "SECNANO"), None)
    if stamp is not None:
        seconds, nanos = table[f"f{stamp}"][:, 0], table[f"f{stamp}"][:, 1]
        clock = {stamp}
    elif all(k in by for k in TIME_FIELDS):
        seconds, nanos = table[f"f{by['seconds']}"], table[f"f{by['nanoseconds']}"]
        clock = {by[k] for k in TIME_FIELDS}
    else:
        raise ContractError("no time: a TOB1 table's SECONDS and NANOSECONDS fields (or a "
                            "SecNano field) are its time", file=path)
    time = EPOCH + seconds.astype("timedelta64[s]") + nanos.astype("timedelta64[ns]")
    channels = []
    for i, (name, unit, kind) in enumerate(zip(names, units, types)):
        if i in clock or name.strip().lower() in COUNTERS:     # (RECORD: the logger's counter)
            continue
        channels.append(Channel(with_unit(name.strip(), unit), channel_values(table, i, kind), time,
                                f"field {i + 1} {name.strip()!r} ({kind.strip()})"))
    return Record(Path(path).stem, channels, utc=False)


def _fp2(raw: np.ndarray) -> np.ndarray:
    """FP2 words (big-endian, read) as numbers: ``-1^sign * mantissa / 10^exponent``."""
    raw = raw.astype(np.uint32)
    value = (raw & 0x1FFF) / 10.0 ** ((raw >> 13) & 0x3)
    value = np.where(raw & 0x8000, -value, value)
    for word, special in _INFINITE.items():
        value[raw == word] = special
    return value
