"""A DIAdem TDM/TDX pair (``.tdm``: NI's USI XML header, ``.tdx`` beside it: the values) read
as its CSV export (:mod:`.labfile`), by the standard library: the header is XML
(:mod:`xml.etree.ElementTree`), the values the TDX's blocks (numpy), as NI documents the format
("TDM/TDMS file format", the USI schema).  The TDMS format (one binary file) is :mod:`.tdms`.

Read: the header's ``usi:include`` (the TDX file, its ``byteOrder``, a ``block`` per channel:
``byteOffset``, ``length``, ``valueType``) and ``usi:data``: each ``tdm_channelgroup`` a group
of channels, each ``tdm_channel`` its ``name``, ``unit_string`` and ``datatype``, its values by
its ``localcolumn`` (``explicit``: a sequence, in the TDX or inline; ``implicit_linear``: start
and increment; ``raw_linear``: raw values times a factor plus an offset).  A ``DT_DATE``
channel is its group's time: DIAdem's seconds since 0000-01-01 (float64), on the clock of the PC
that wrote it (no zone: ``data.timezone`` says it where the clock is not UTC), or a LabVIEW
timestamp (``eTimeUsi``, 16 bytes: an unsigned 2^-64 s fraction, then signed seconds since
1904-01-01 UTC; as tdm_loader 1.2.7 (MIT) reads it, its source read, not copied), which is UTC;
a channel named as a time (``Time [s]``) is seconds.  A local column's ``flags`` block (one
byte a value, 0: not valid, as tdm_loader reads it) makes its invalid values missing, not the
numbers stored under them.  Text channels (``DT_STRING``: an operator's note) are left out.
Interleaved blocks (``blockOffset`` / ``blockSize``) are refused: no reference at hand reads
them.  Groups are runs where they follow one another in time (:mod:`.hdf5`'s rule), else the
channel groups of one record.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path

import numpy as np

from ...base.log import logger
from .contract import ContractError
from .hdf5 import dated_apart
from .labfile import Channel, Record, with_unit
from .roles import named_as_time
from .tdms import groups_are_runs, joined_groups

TDM_SUFFIXES = (".tdm",)
# s from DIAdem's 0000-01-01 00:00 to 1970-01-01 00:00: a year 0 of 365 days (not the proleptic
# Gregorian 366, 62167219200, which read every date a day early).  Measured on two files NI's
# software wrote (tdm_loader 1.2.7's test files): a LabVIEW file's DT_DATE minimum less its own
# first eTimeUsi stamp, 62167132800.00 s; a DIAdem file's absolute time read by it as
# 2021-02-26 07:55:01, the time its name gives
DIADEM_EPOCH_S = 62167132800
LABVIEW_EPOCH_S = 2082844800        # s from LabVIEW's 1904-01-01 00:00 UTC to 1970-01-01 00:00
TIME_USI = "eTimeUsi"               # a LabVIEW timestamp: u8 fraction of 2^-64 s, i8 seconds
_TYPES = {"eInt8Usi": "i1", "eInt16Usi": "i2", "eInt32Usi": "i4", "eInt64Usi": "i8",
          "eUInt8Usi": "u1", "eUInt16Usi": "u2", "eUInt32Usi": "u4", "eUInt64Usi": "u8",
          "eFloat32Usi": "f4", "eFloat64Usi": "f8"}
_IDS = re.compile(r'id\("([^"]+)"\)')


def is_tdm(path) -> bool:
    return Path(path).suffix.lower() in TDM_SUFFIXES


def tdm_records(path: Path) -> list[Record]:
    """The runs of the TDM file ``path`` (one, or one per channel group where they are runs)."""
    try:
        root = _header(path)
    except (ET.ParseError, UnicodeDecodeError, zipfile.BadZipFile) as exc:
        raise ContractError(f"not a TDM header that is read (its XML: {exc})", file=path) from None
    data = _child(root, "data")
    if data is None:
        raise ContractError("no usi:data element: not a DIAdem TDM header", file=path)
    by_id = {e.get("id"): e for e in data if e.get("id")}
    blocks = _blocks(root, path)
    groups = [_group(g, by_id, blocks, path) for g in data if _tag(g) == "tdm_channelgroup"]
    groups = [g for g in groups if g.channels]
    if not groups:
        raise ContractError("no channel of numbers in the TDM file", file=path)
    if len(groups) > 1 and (dated_apart(groups) or groups_are_runs(groups)):
        return groups
    return [joined_groups(_on_the_timed_rows(groups, path))]


def _on_the_timed_rows(groups: list[Record], path: Path) -> list[Record]:
    """Groups without a time of their own read on the rows of the one group with a time, where
    none of their channels is longer: DIAdem's evaluation group beside its raw data
    (tdm_loader's DIAdem test file: ``Auswertung``, the raw channels less their offsets, no time,
    beside ``Rohwerte_[200Hz]`` and its dates; joined as they were, "no grid reads them
    together").  Said; any other mix is left to the join's rules."""
    timed = [g for g in groups if g.channels[0].time is not None]
    if len(timed) != 1:
        return groups
    time = timed[0].channels[0].time
    out = []
    for g in groups:
        if g.channels[0].time is not None or any(c.values.size > time.size for c in g.channels):
            out.append(g)
            continue
        logger.warning(f"{path.name}: group {g.label!r} has no time of its own: read on group "
                       f"{timed[0].label!r}'s, row by row")
        out.append(Record(g.label, [Channel(c.header, np.concatenate(
            [c.values, np.full(time.size - c.values.size, np.nan)]), time, c.where)
            for c in g.channels], timed[0].time_header, timed[0].utc))
    return out


def _header(path: Path):
    """The header's XML root: the file's, or a zipped header's first member (some writers zip the
    header; tdm_loader's test file ``2021-02-26_07-55-01.tdm`` is one)."""
    if not zipfile.is_zipfile(path):
        return ET.parse(path).getroot()
    with zipfile.ZipFile(path) as zipped:
        names = zipped.namelist()
        if not names:
            raise zipfile.BadZipFile("a zip archive with no member")
        return ET.fromstring(zipped.read(names[0]))


def _tag(e) -> str:
    return e.tag.rsplit("}", 1)[-1]


def _child(e, name: str):
    return next((c for c in e if _tag(c) == name), None)


def _text(e, name: str) -> str:
    c = _child(e, name)
    return (c.text or "").strip() if c is not None else ""


def _blocks(root, path: Path) -> dict[str, tuple[Path, str, int, int, str]]:
    """``id -> (TDX file, byte order, byte offset, length, numpy type)`` of ``usi:include``."""
    out = {}
    include = _child(root, "include")
    for f in ([] if include is None else [c for c in include if _tag(c) == "file"]):
        order = "<" if f.get("byteOrder", "littleEndian") == "littleEndian" else ">"
        tdx = path.parent / (f.get("url") or "")
        for b in f:
            vtype = b.get("valueType", "")
            if vtype not in _TYPES and vtype != TIME_USI:
                raise ContractError(f"block {b.get('id')!r} of {tdx.name}: value type {vtype!r} "
                                    f"is not read (numbers: {', '.join(_TYPES)}, {TIME_USI})",
                                    file=path)
            if b.get("blockSize") or b.get("blockOffset"):
                raise ContractError(f"block {b.get('id')!r} of {tdx.name} is interleaved "
                                    "(blockOffset / blockSize): save the channels' values one "
                                    "block each", file=path)
            out[b.get("id")] = (tdx, order, int(b.get("byteOffset", 0)), int(b.get("length", 0)),
                                _TYPES.get(vtype, TIME_USI))
    return out


def _refs(text: str) -> list[str]:
    return _IDS.findall(text or "")


def _group(group, by_id: dict, blocks: dict, path: Path) -> Record:
    label = _text(group, "name") or group.get("id")
    named = []
    for cid in _refs(_text(group, "channels")):
        chan = by_id.get(cid)
        if chan is None or _text(chan, "datatype") == "DT_STRING":
            continue                            # (text: a note, left out)
        name = _text(chan, "name") or cid
        where = f"group {label!r}, channel {name!r}"
        values, stamped = _values(chan, by_id, blocks, path, where)
        if values is not None:
            kind = TIME_USI if stamped else "DT_DATE" if _shown_as_time(chan) else _text(
                chan, "datatype")
            named.append((name, _text(chan, "unit_string"), kind, values, where))
    clock = next((c for c in named if c[2] in ("DT_DATE", TIME_USI)), None) or next(
        (c for c in named if named_as_time(c[0])), None)
    time = None
    if clock is not None:
        time = clock[3]
        if clock[2] in ("DT_DATE", TIME_USI):     # (a LabVIEW timestamp: since 1970 already)
            since_1970 = time - DIADEM_EPOCH_S if clock[2] == "DT_DATE" else time
            time = np.round(since_1970 * 1e6).astype("int64").astype("datetime64[us]")
    out, short = [], []
    for name, unit, _, values, where in named:
        if clock is not None and name == clock[0]:
            continue
        if time is not None and values.size > time.size:
            raise ContractError(f"{where} has {values.size} values, its group's time "
                                f"{clock[0]!r} {time.size}: more values than times", file=path)
        if time is not None and values.size < time.size:   # (DIAdem's channels end apart)
            short.append(f"{name!r} {values.size}")
            values = np.concatenate([values, np.full(time.size - values.size, np.nan)])
        out.append(Channel(with_unit(name, unit), values, time, where))
    if short:
        logger.warning(f"{path.name}: group {label!r}: channel(s) shorter than its time "
                       f"{clock[0]!r} ({time.size} rows), their last rows empty: "
                       + ", ".join(short[:4]) + (" ..." if len(short) > 4 else ""))
    dated = clock is not None and clock[2] in ("DT_DATE", TIME_USI)
    return Record(label, out, "time" if clock is None or dated else clock[0],
                  utc=clock is not None and clock[2] == TIME_USI)


def _shown_as_time(chan) -> bool:
    """A channel of doubles DIAdem shows as dates (its ``displaytype`` attribute ``Time``): the
    absolute time of tdm_loader's DIAdem test file, ``Zeit_[200Hz]-abs``, is one (DT_DOUBLE)."""
    attributes = _child(chan, "instance_attributes")
    return attributes is not None and any(
        a.get("name") == "displaytype" and _text(a, "s") == "Time" for a in attributes)


def _values(chan, by_id: dict, blocks: dict, path: Path, where: str
            ) -> tuple[np.ndarray | None, bool]:
    """A channel's values (float) by its first local column, None where it has none; and
    whether they are LabVIEW timestamps (then seconds since 1970, UTC)."""
    col = next((by_id.get(i) for i in _refs(_text(chan, "local_columns"))), None)
    if col is None:
        return None, False
    seq = next((by_id.get(i) for i in _refs(_text(col, "values"))), None)
    if seq is None:
        raise ContractError(f"{where}: its local column points to no values", file=path)
    held = _child(seq, "values")
    external = held.get("external") if held is not None else None
    stamped = external in blocks and blocks[external][4] == TIME_USI
    return _represented(col, seq, by_id, blocks, path, where), stamped


def _represented(col, seq, by_id: dict, blocks: dict, path: Path, where: str) -> np.ndarray:
    """A local column's values as its ``sequence_representation`` makes them of ``seq``'s."""
    values = _sequence(seq, blocks, path, where)
    how = _text(col, "sequence_representation") or "explicit"
    if how in ("explicit", "raw_linear"):
        valid = _flags(col, by_id, blocks, path, where, values.size)
        if valid is not None:
            values = np.where(valid, values, np.nan)
    if how == "explicit":
        return values
    if how == "implicit_linear" and values.size == 2:
        rows = _rows(col, by_id)
        return values[0] + values[1] * np.arange(rows if rows is not None else 0)
    if how == "raw_linear":
        params = [float(v) for v in _text(col, "generation_parameters").split()] or [0.0, 1.0]
        return params[0] + params[1] * values
    raise ContractError(f"{where}: sequence_representation {how!r} is not read (explicit, "
                        "implicit_linear, raw_linear)", file=path)


def _rows(col, by_id: dict) -> int | None:
    sub = next((by_id.get(i) for i in _refs(_text(col, "submatrix"))), None)
    text = _text(sub, "number_of_rows") if sub is not None else ""
    return int(text) if text.isdigit() else None


def _sequence(seq, blocks: dict, path: Path, where: str) -> np.ndarray:
    """A ``*_sequence``'s values: its TDX block (``<values external="inc0"/>``) or inline."""
    vals = _child(seq, "values")
    if vals is None:
        raise ContractError(f"{where}: its sequence {seq.get('id')!r} holds no values", file=path)
    ref = vals.get("external")
    if ref is None:
        try:
            return np.array([float(v.text) for v in vals], dtype=float)
        except (TypeError, ValueError):
            raise ContractError(f"{where}: an inline value is not a number", file=path) from None
    if ref not in blocks:
        raise ContractError(f"{where}: its block {ref!r} is not in usi:include", file=path)
    tdx, order, offset, length, kind = blocks[ref]
    if not tdx.is_file():
        raise ContractError(f"its values' file {tdx.name} is not beside it: keep the .tdx with "
                            "the .tdm", file=path)
    dtype = np.dtype([("fraction", order + "u8"), ("seconds", order + "i8")]
                     if kind == TIME_USI else order + kind)
    if offset + length * dtype.itemsize > tdx.stat().st_size:
        raise ContractError(f"{where}: block {ref!r} ({length} values from byte {offset}) ends "
                            f"past the end of {tdx.name} ({tdx.stat().st_size} bytes)", file=path)
    raw = np.fromfile(tdx, dtype=dtype, count=length, offset=offset)
    if kind == TIME_USI:                        # seconds since 1970 (UTC)
        return (raw["seconds"] - LABVIEW_EPOCH_S) + raw["fraction"] * 2.0 ** -64
    return raw.astype(float)


def _flags(col, by_id: dict, blocks: dict, path: Path, where: str, n: int) -> np.ndarray | None:
    """Which of a local column's ``n`` values are valid by its ``flags`` (a block of one flag a
    value, external or through a sequence; 0: not valid); None without flags."""
    flags = _child(col, "flags")
    if flags is None:
        return None
    if flags.get("external") is not None:
        flags = ET.fromstring(f'<s><values external="{flags.get("external")}"/></s>')
    else:
        flags = next((by_id.get(i) for i in _refs(flags.text)), None)
        if flags is None:
            return None
    valid = _sequence(flags, blocks, path, f"{where}'s flags") != 0
    if valid.size != n:
        raise ContractError(f"{where}: {valid.size} flags for {n} values", file=path)
    return valid
