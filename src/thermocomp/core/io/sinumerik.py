"""A SINUMERIK trace (``.xml``: the trace SINUMERIK Operate saves, its signals sampled by the NC)
read as its CSV export (:mod:`.labfile`), by the standard library (:mod:`xml.etree.ElementTree`,
its rows parsed as they stream).

Read: ``traceCaptureFile`` / ``traceData``, each ``dataFrame`` a trace: its ``frameHeader``'s
``dataSignal`` s (``id``, ``name``: the NC / PLC variable traced, ``unit`` where given) and its
``rec`` rows, ``time`` (s since the trace's start) and ``f<id>`` the signal's value; a value
the NC did not deliver (no ``f<id>`` attribute in a row) is missing.  The frame's
``startTime`` (the NC's clock, no zone: ``data.timezone`` says it where the clock is not UTC)
makes the times instants; without one they are seconds.  A signal is named by the variable's
last part where that is unique (``T_BETT_L`` for ``/NC/_N_NC_GD9_ACX/T_BETT_L``; an axis'
``aaIm[u1,1]`` as ``aaIm_u1_1``: its brackets hold an index, no unit).  Frames are runs where
they follow one another in time or hold the same signals (:mod:`.hdf5`'s rule), else one
record's traces (a session's slow temperatures beside its fast axes: held onto one grid).
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from .contract import ContractError
from .hdf5 import dated_apart
from .labfile import Channel, Record, with_unit
from .tdms import groups_are_runs, joined_groups

TRACE_SUFFIXES = (".xml",)
TRACE_ROOT = b"<traceCaptureFile"
_INDEX = re.compile(r"\[([^\]]*)\]")


def is_trace(path) -> bool:
    """An ``.xml`` file whose root is a SINUMERIK trace's (its first 4 kB say it)."""
    path = Path(path)
    if path.suffix.lower() not in TRACE_SUFFIXES or not path.is_file():
        return False
    with path.open("rb") as f:
        return TRACE_ROOT in f.read(4096)


def not_a_trace(path) -> str | None:
    """Why the ``.xml`` file ``path`` is read as no run (its root is no trace's: a trace's
    settings, a report beside the traces), None for a trace or another suffix."""
    path = Path(path)
    if path.suffix.lower() not in TRACE_SUFFIXES or is_trace(path):
        return None
    try:
        root = next(ET.iterparse(path, events=("start",)))[1].tag.rsplit("}", 1)[-1]
        said = f"its root element is <{root}>"
    except (ET.ParseError, StopIteration, OSError) as exc:
        said = f"its XML does not parse: {exc}"
    return (f"an .xml file is read as a SINUMERIK trace (root <traceCaptureFile>); {said}: "
            "give a trace saved by SINUMERIK Operate, or the lab's channels as CSV")


def _short(names: list[str]) -> list[str]:
    """Each variable's last part (its index's brackets as ``_``) where unique, else its path."""
    def plain(name: str) -> str:
        return _INDEX.sub(lambda m: "_" + re.sub(r"\W+", "_", m.group(1)).strip("_"), name).strip("_")
    last = [plain(n.rstrip("/").rsplit("/", 1)[-1]) for n in names]
    return [s if last.count(s) == 1 else plain(n.strip("/").replace("/", "_"))
            for s, n in zip(last, names)]


def trace_records(path: Path) -> list[Record]:
    """The traces (``dataFrame`` s) of the SINUMERIK trace ``path``, each a record."""
    records, signals, rows, frame = [], [], [], None
    try:
        for event, el in ET.iterparse(path, events=("start", "end")):
            tag = el.tag.rsplit("}", 1)[-1]
            if event == "start" and tag == "dataFrame":
                frame, signals, rows = el.attrib.copy(), [], []
            elif event == "end" and tag == "dataSignal":
                signals.append((el.get("id"), el.get("name") or f"signal {el.get('id')}",
                                el.get("unit")))
            elif event == "end" and tag == "rec":
                rows.append(el.attrib.copy())
                el.clear()
            elif event == "end" and tag == "dataFrame":
                records.append(_record(frame, signals, rows, len(records), path))
                el.clear()
    except ET.ParseError as exc:
        raise ContractError(f"not a SINUMERIK trace that is read (its XML: {exc})",
                            file=path) from None
    if not records:
        raise ContractError("no dataFrame in the SINUMERIK trace: no signal read", file=path)
    if len(records) > 1 and not (dated_apart(records) or groups_are_runs(records)):
        return [joined_groups(records)]     # (one session's traces: slow and fast signals)
    return records


def _numbers(texts: list, path: Path, where) -> np.ndarray:
    """``texts`` as numbers (None: missing); a text that is none refused naming ``where(k)``, the
    k-th row's place (said only then: a trace holds rows x signals values)."""
    out = np.empty(len(texts))
    for k, text in enumerate(texts):
        try:
            out[k] = np.nan if text is None else float(text)
        except ValueError:
            raise ContractError(f"{where(k)}: {text!r} is no number", file=path) from None
    return out


def _record(frame: dict, signals: list, rows: list[dict], n: int, path: Path) -> Record:
    label = frame.get("name") or f"frame {n + 1}"
    if not signals:
        raise ContractError(f"dataFrame {label!r}: no dataSignal in its frameHeader", file=path)
    if not rows:
        raise ContractError(f"dataFrame {label!r}: no rec row", file=path)
    seconds = _numbers([r.get("time") for r in rows], path,
                       lambda k: f"dataFrame {label!r}, rec {k + 1}, time")
    if np.isnan(seconds).any():
        k = int(np.flatnonzero(np.isnan(seconds))[0])
        raise ContractError(f"dataFrame {label!r}, rec {k + 1}: no time", file=path)
    start, utc = frame.get("startTime"), False
    if start:
        t0, utc = _instant(start, label, path)
        time = t0 + np.round(seconds * 1e6).astype("int64").astype("timedelta64[us]")
    else:
        time = seconds
    channels = []
    for (sid, name, unit), short in zip(signals, _short([s[1] for s in signals])):
        key = f"f{sid}"
        where = f"dataFrame {label!r}, signal {name!r} ({key})"
        values = _numbers([r.get(key) for r in rows], path, lambda k, where=where: f"{where}, rec {k + 1}")
        channels.append(Channel(with_unit(short, unit), values, time, where))
    return Record(label, channels, utc=utc)


def _instant(start: str, label: str, path: Path) -> tuple[np.datetime64, bool]:
    """``startTime`` as an instant and whether it is UTC (an offset written: converted), a
    date of four-digit years only (numpy read ``27-05-10`` as the year 27)."""
    try:
        if not re.match(r"\d{4}-\d{2}-\d{2}", start.strip()):
            raise ValueError
        t = datetime.fromisoformat(start.strip())
    except ValueError:
        raise ContractError(f"dataFrame {label!r}: startTime {start!r} is no ISO 8601 time",
                            file=path) from None
    if t.tzinfo is None:
        return np.datetime64(t, "us"), False
    return np.datetime64(t.astimezone(timezone.utc).replace(tzinfo=None), "us"), True
