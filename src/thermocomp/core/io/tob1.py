"""Campbell Scientific's binary table TOB1 (extension, lab75), what LoggerNet and CardConvert
write where a table is kept binary, read as its CSV export (:mod:`.labfile`), as a TOA5 file
is read (:mod:`.campbell`).

Five ASCII lines as TOA5's, each ending CRLF: the environment (``"TOB1","<station>",...``), the
field names, their units, their processing, and the data type of each field (``"ULONG",
"IEEE4","FP2"``); then the records, one after the other with no separator, each field in its
type's bytes: ``ULONG`` / ``LONG`` 4 bytes, ``IEEE4`` / ``IEEE8`` a float, ``USHORT`` /
``SHORT`` 2, ``SecNano`` 8 (seconds, then nanoseconds), little-endian; ``FP2`` Campbell's
2-byte final storage format, big-endian: a sign bit, a 2-bit decimal exponent, a 13-bit
mantissa (``-1^s * m / 10^e``), its largest mantissa at exponent 0 an infinity (``0x1FFF``,
``0x9FFF``: the logger's ``INF``, read as missing as in a TOA5 file, :mod:`.marks`) and
``0x9FFE`` its NaN (our reading of the format's description; no file a logger wrote was at
hand).  ``SECONDS`` + ``NANOSECONDS`` (or a ``SecNano`` field) since 1990-01-01 are the time,
on the logger's clock; ``RECORD`` (the logger's counter) is left out.  A type not listed, or
bytes that make no whole record at the end, are refused naming the file, the field or the row.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from .campbell import COUNTERS
from .campbell import units as campbell_units
from .contract import ContractError
from .csvline import split_line
from .labfile import Channel, Record, with_unit

HEADER_LINES = 5
EPOCH = np.datetime64("1990-01-01T00:00:00", "ns")     # Campbell's loggers count from it
TIME_FIELDS = ("seconds", "nanoseconds")
# a data type -> its numpy type as the record holds it
_TYPES = {"ULONG": "<u4", "UINT4": "<u4", "LONG": "<i4", "INT4": "<i4", "IEEE4": "<f4",
          "IEEE4L": "<f4", "IEEE8": "<f8", "IEEE8L": "<f8", "USHORT": "<u2", "UINT2": "<u2",
          "SHORT": "<i2", "INT2": "<i2", "FP2": ">u2", "SECNANO": ("<u4", (2,))}
_INFINITE = {0x1FFF: np.inf, 0x9FFF: -np.inf, 0x9FFE: np.nan}     # FP2's own words


def is_tob1(path) -> bool:
    """``path`` is a TOB1 file (its first field ``"TOB1"``)."""
    try:
        with open(path, "rb") as f:
            return re.match(rb'\s*"?TOB1"?,', f.read(8)) is not None
    except OSError:
        return False


def first_line(path) -> str:
    """The environment line of a TOB1 file (its text: :func:`.campbell.said` names the table)."""
    with open(path, "rb") as f:
        return f.readline().decode("latin-1").rstrip("\r\n")


def tob1_records(path: Path) -> list[Record]:
    """The one record of the TOB1 file ``path``: its channels, timed by the logger's clock."""
    data = Path(path).read_bytes()
    lines, start = [], 0
    for _ in range(HEADER_LINES):
        end = data.find(b"\n", start)
        if end < 0:
            raise ContractError(f"a TOB1 file has {HEADER_LINES} header lines; this one ends in "
                                f"line {len(lines) + 1}", file=path)
        lines.append(split_line(data[start:end].decode("latin-1").rstrip("\r"), ","))
        start = end + 1
    names, units, _, types = lines[1:]
    if not len(names) == len(units) == len(types):
        raise ContractError(f"TOB1 header lines 2-5 differ in width ({len(names)} names, "
                            f"{len(types)} data types)", file=path)
    fields = []
    for name, kind in zip(names, types):
        found = _TYPES.get(kind.strip().upper())
        if found is None:
            raise ContractError(f"data type {kind!r} (line 5) is not read (read: "
                                f"{', '.join(sorted(_TYPES))})", file=path, column=name)
        fields.append((name, found))
    record = np.dtype([(f"f{i}", *t) if isinstance(t, tuple) else (f"f{i}", t)
                       for i, (_, t) in enumerate(fields)])
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
        values = table[f"f{i}"]
        values = _fp2(values) if kind.strip().upper() == "FP2" else values.astype(float)
        channels.append(Channel(with_unit(name.strip(), unit), values, time,
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
