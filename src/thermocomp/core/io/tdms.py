"""A National Instruments TDMS log (``.tdms``: LabVIEW's, DIAdem's, a DAQ's ``TDMS logging``)
read as its CSV export (:mod:`.labfile`), through npTDMS (the ``tdms`` extra).

A TDMS file holds groups, each of channels.  A channel's time is NI's own: its waveform
properties ``wf_start_time`` (UTC) and ``wf_increment`` (s; ``wf_start_offset`` added), as
DAQmx logging writes them, or a time channel of its group (timestamps, or a channel named as a
time: ``Time [s]``); its unit NI's ``unit_string`` property, else its name's (``Spindle nose
[degC]``), read by the header rules of a CSV file.

Groups: LabVIEW's DAQmx logging writes one group per task (a temperature module's group and a
displacement module's, side by side over the same hours); a program logging test after test
into one file (DIAdem's, a ``TDMS Write`` per test) writes a group per run, each holding the
same channels.  So groups holding the same channels, one after the other in time (or untimed),
are runs (each a campaign, by the ``run`` column :mod:`.labfile` writes); any other groups are
one record's channel groups, their channels read together (on one grid where their times
differ: :mod:`.labfile`).  A channel name two groups share is then ``<group>/<channel>``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...base.extras import require
from .contract import ContractError
from .labfile import Channel, Record, with_unit
from .roles import named_as_time

TDMS_SUFFIXES = (".tdms",)


def is_tdms(path) -> bool:
    return Path(path).suffix.lower() in TDMS_SUFFIXES


def tdms_records(path: Path) -> list[Record]:
    """The runs of the TDMS file ``path`` (one, or one per group where the groups are runs)."""
    require("nptdms")
    from nptdms import TdmsFile

    try:
        tdms = TdmsFile.read(path)
    except Exception as exc:        # npTDMS's errors of a file it does not read
        raise ContractError(f"not a TDMS file that is read ({type(exc).__name__}: {exc})",
                            file=path) from None
    groups = [_group(g, path) for g in tdms.groups()]
    groups = [g for g in groups if g.channels]
    if not groups:
        raise ContractError("no channel with values in the TDMS file", file=path)
    if len(groups) > 1 and groups_are_runs(groups):
        return groups
    return [joined_groups(groups)]


def _group(group, path: Path) -> Record:
    """A group's channels, each with its time (its group's time channel, else its waveform)."""
    channels = [c for c in group.channels() if len(c) > 0]
    clock = next((c for c in channels if np.issubdtype(c.dtype, np.datetime64)), None) or next(
        (c for c in channels if named_as_time(_header(c))), None)
    time_header = _header(clock) if clock is not None else "time"
    time = None if clock is None else np.asarray(clock[:])
    out = []
    for c in channels:
        if c is clock:
            continue
        where = f"group {group.name!r}, channel {c.name!r}"
        values = np.asarray(c[:])
        if not np.issubdtype(values.dtype, np.number) and values.dtype != bool:
            continue                           # (a text channel: a comment, left out)
        if time is not None and values.size != time.size:
            raise ContractError(f"{where} has {values.size} values, its group's time channel "
                                f"{clock.name!r} {time.size}: give each channel its time (NI's "
                                "wf_start_time / wf_increment) or one length", file=path)
        out.append(Channel(_header(c), values.astype(float), time if time is not None
                           else _waveform(c), where))
    return Record(group.name, out, time_header)


def _header(channel) -> str:
    return with_unit(channel.name, channel.properties.get("unit_string"))


def _waveform(channel) -> np.ndarray | None:
    """The channel's time from NI's waveform properties: timestamps from ``wf_start_time``, or
    seconds where it is not given; None without ``wf_increment``."""
    props = channel.properties
    step = props.get("wf_increment")
    if step is None or not float(step) > 0:
        return None
    seconds = float(props.get("wf_start_offset", 0.0) or 0.0) + float(step) * np.arange(len(channel))
    start = props.get("wf_start_time")
    if start is None or np.datetime64(start).astype("datetime64[us]").astype(int) <= 0:
        return seconds                         # (LabVIEW's zero time: 1904, no start)
    return np.datetime64(start, "us") + (seconds * 1e6).round().astype("timedelta64[us]")


def time_span(record: Record) -> tuple | None:
    times = [c.time for c in record.channels if c.time is not None]
    if not times or any(not np.issubdtype(t.dtype, np.datetime64) for t in times):
        return None
    return min(t[0] for t in times), max(t[-1] for t in times)


def groups_are_runs(groups: list[Record]) -> bool:
    """Groups are runs where each holds the same channels and, timed by dates, none overlaps
    another (a DAQ's modules log over the same hours)."""
    names = {tuple(sorted(c.header for c in g.channels)) for g in groups}
    if len(names) > 1:
        return False
    spans = [time_span(g) for g in groups]
    if any(s is None for s in spans):
        return all(s is None for s in spans) and all(c.time is None or not np.issubdtype(
            c.time.dtype, np.datetime64) for g in groups for c in g.channels)
    spans.sort()
    return all(a[1] < b[0] for a, b in zip(spans, spans[1:]))


def joined_groups(groups: list[Record]) -> Record:
    """The groups' channels as one record; a name two groups share as ``<group>/<name>``."""
    counts: dict[str, int] = {}
    for g in groups:
        for c in g.channels:
            counts[c.header] = counts.get(c.header, 0) + 1
    channels = []
    for g in groups:
        for c in g.channels:
            header = f"{g.label}/{c.header}" if counts[c.header] > 1 else c.header
            channels.append(Channel(header, c.values, c.time, c.where))
    label = groups[0].label if len(groups) == 1 else "the groups " + ", ".join(
        repr(g.label) for g in groups)
    time_headers = {g.time_header for g in groups}
    # (stranger78: a DIAdem group's dates, on the PC's clock, were joined as UTC: data.timezone
    # left unread)
    return Record(label, channels, time_headers.pop() if len(time_headers) == 1 else "time",
                  utc=all(g.utc for g in groups))
