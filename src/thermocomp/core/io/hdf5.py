"""An HDF5 file (``.h5``, ``.hdf5``: a lab's own logger writing through h5py or HDF5's C
library) read as its CSV export (:mod:`.labfile`), through h5py (the ``matlab`` extra, which
reads MATLAB's ``-v7.3`` files, HDF5 too).

HDF5 prescribes no layout; a logger's is read where it is plain: groups (the root one too)
holding one-dimensional datasets, a dataset a channel.  A channel's unit is its ``units``
attribute (the CF conventions' name; ``unit`` too), else its name's (``T1 [degC]``); a
group's time is its dataset named as a time (``time``, ``timestamp``), as seconds, or as
instants where its ``units`` say so in CF's words (``seconds since 1970-01-01 00:00:00``,
without a zone UTC, as CF says).  Text datasets (an operator's note) are left out; a dataset of
more dimensions, or of another length than its group's time, is refused naming it.

A group's channels are in the order they were created where the file tracks it (h5py's
``track_order``, HDF5's ``H5P_CRT_ORDER_TRACKED``: a logger's column order); else HDF5 lists them
by name, and that is said (lab78: the order was the name's, silently).

Groups (stranger77): a logger writing a group a day (or a run) into one file writes groups one
after the other in time; so groups timed by instants, none overlapping another, are runs (each
a campaign, by the ``run`` column :mod:`.labfile` writes); other groups the channel groups of
one record, as a TDMS log's (:mod:`.tdms`).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ...base.extras import require
from ...base.log import logger
from .contract import ContractError
from .labfile import Channel, Record, with_unit
from .roles import named_as_time
from .tdms import groups_are_runs, joined_groups, time_span

HDF5_SUFFIXES = (".h5", ".hdf5", ".hdf", ".he5")
_SINCE = re.compile(r"\s*(\w+)\s+since\s+(.+?)\s*$", re.IGNORECASE)
_STEPS = {"s": 1.0, "sec": 1.0, "secs": 1.0, "second": 1.0, "seconds": 1.0, "ms": 1e-3,
          "millisecond": 1e-3, "milliseconds": 1e-3, "min": 60.0, "minute": 60.0, "minutes": 60.0,
          "h": 3600.0, "hr": 3600.0, "hour": 3600.0, "hours": 3600.0, "d": 86400.0, "day": 86400.0,
          "days": 86400.0}


def is_hdf5(path) -> bool:
    return Path(path).suffix.lower() in HDF5_SUFFIXES


def hdf5_records(path: Path) -> list[Record]:
    """The runs of the HDF5 file ``path`` (one, or one per group where the groups are runs)."""
    require("h5py")
    import h5py

    try:
        f = h5py.File(path, "r")
    except Exception as exc:        # h5py's errors of a file it does not read
        raise ContractError(f"not an HDF5 file that is read ({type(exc).__name__}: {exc})",
                            file=path) from None
    with f:
        found: list = []
        f.visititems(lambda name, node: found.append(node) if isinstance(node, h5py.Group) else None)
        groups = [_group(g, path, h5py) for g in (f, *found)]
    groups = [g for g in groups if g.channels]
    if not groups:
        raise ContractError("no dataset of numbers in the HDF5 file (a channel: a "
                            "one-dimensional dataset)", file=path)
    if len(groups) > 1 and (dated_apart(groups) or groups_are_runs(groups)):
        return groups
    return [joined_groups(groups)]


def _group(group, path: Path, h5py) -> Record:
    """A group's datasets, each a channel timed by its group's time dataset (if any), in the
    order they were created where the file tracks it, else by name (said)."""
    sets = _ordered(group, path, h5py)
    clock = next((d for d in sets if named_as_time(_leaf(d)) or _since(d) is not None), None)
    time = None if clock is None else _time(clock, path)
    label = _leaf(group) or "/"
    out = []
    for d in sets:
        if d is clock or d.dtype.kind not in "biuf":
            continue                            # (text: a note, left out)
        where = f"dataset {d.name!r}"
        if d.ndim != 1:
            raise ContractError(f"{where} has shape {d.shape}: a channel is one-dimensional "
                                "(save each column a dataset)", file=path)
        values = np.asarray(d[()], dtype=float)
        if time is not None and values.size != time.size:
            raise ContractError(f"{where} has {values.size} values, its group's time "
                                f"{clock.name!r} {time.size}: one length a group", file=path)
        out.append(Channel(with_unit(_leaf(d), _unit(d)), values, time, where))
    return Record(label, out, "time" if clock is None or _since(clock) else _leaf(clock))


def _ordered(group, path: Path, h5py) -> list:
    """``group``'s datasets by their creation order where the file tracks it (a link's
    ``corder``), else in HDF5's name order, said where more than one is read as a channel."""
    node = group["/"] if isinstance(group, h5py.File) else group     # (a File: its root group)
    sets = [d for d in node.values() if isinstance(d, h5py.Dataset)]
    if node.id.get_create_plist().get_link_creation_order() & h5py.h5p.CRT_ORDER_TRACKED:
        return sorted(sets, key=lambda d: node.id.links.get_info(_leaf(d).encode()).corder)
    if sum(d.dtype.kind in "biuf" and not named_as_time(_leaf(d)) for d in sets) > 1:
        logger.info(f"{Path(path).name}: group {node.name!r} does not track the order its "
                    "datasets were created in (h5py's track_order): its channels are read in "
                    "the order HDF5 lists them, by name")
    return sets


def _leaf(node) -> str:
    return node.name.rsplit("/", 1)[-1]


def _text(value) -> str | None:
    if value is None:
        return None
    if isinstance(value, np.ndarray) and value.size == 1:
        value = value.item()
    return value.decode("utf-8", "replace") if isinstance(value, bytes) else str(value)


def _unit(d) -> str | None:
    return _text(d.attrs.get("units", d.attrs.get("unit")))


def _since(d):
    """``(seconds a step, epoch)`` of a CF time's ``units`` (``hours since 2027-03-01``)."""
    m = _SINCE.match(_text(_unit(d)) or "")
    if m is None or m.group(1).lower() not in _STEPS:
        return None
    return _STEPS[m.group(1).lower()], m.group(2)


def _time(clock, path: Path) -> np.ndarray:
    """A group's time: instants (UTC) where CF's ``units`` give an epoch, else seconds."""
    import pandas as pd

    values = np.asarray(clock[()], dtype=float)
    since = _since(clock)
    if since is None:
        return values
    try:
        epoch = pd.Timestamp(since[1])
    except ValueError:
        raise ContractError(f"dataset {clock.name!r}: units {_unit(clock)!r} name no date "
                            "after 'since'", file=path) from None
    epoch = epoch.tz_localize("UTC") if epoch.tzinfo is None else epoch.tz_convert("UTC")
    start = np.datetime64(epoch.tz_localize(None).to_datetime64(), "us")
    return start + np.round(values * since[0] * 1e6).astype("timedelta64[us]")


def dated_apart(groups: list[Record]) -> bool:
    """Every group timed by instants and none overlapping another: a day's (or a run's) group
    each, whatever channels each holds (a sensor replaced: its new name from one day on)."""
    spans = [time_span(g) for g in groups]
    if any(s is None for s in spans):
        return False
    spans.sort()
    return all(a[1] < b[0] for a, b in zip(spans, spans[1:]))
