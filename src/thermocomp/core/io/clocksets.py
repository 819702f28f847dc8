"""(deploy73) The server's clock sets ``connect`` told (its ``clock_set`` events), undone in a
log of the machine's timestamps at read time (``data.clock_sets``).

``connect`` tells an operator's clock set from a pause by its own clock and goes on with the
stream's time as its own clock did (connect71); the machine's log keeps the set in its
timestamps, where a file cannot tell it from a pause (set forward) and the reader refuses a time
going back (set back).  Each event names the server's clock at the sample before the set
(``from_utc``) and at the sample it was told at (``at_utc``); the rows from the set on (of
that file) move back by ``step_s``, so that ``replay`` of the log streams the time ``connect``
streamed.

(deploy74) Where the set is: the rows around it, by the event's own instants, not rows at them.
A row at or after ``at_utc`` that follows one at or before ``from_utc`` (a set back: one where the
time goes back) is the first after the set, whether the log holds rows at the two sample
instants or not (thinned, or sampled at other instants).  A file whose first row is the first
after the set (at ``at_utc`` or after it by less than the file's own step, its median; a set
back: past ``from_utc`` too, where no row before the set can be) is on the set clock
throughout: its start moves back by the step (a log rotated at the set: its next file continues
the one before on ``connect``'s clock).  A file that starts later is not said to follow the set
(connect.json may tell sets of other days).  Before, a set was found
only where the log had rows at both instants (within 1 ms), else left as a pause.  The same
rule undoes the rows streamed on stdin (``monitor``) and ``connect.warm``'s log, and places a
restarted ``connect``'s live sample after the log (:func:`after`).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd

from .contract import TIME, ContractError

MATCH_S = 1e-3     # a timestamp is the event's within this (the log's and the client's rounding)


def clock_sets(path) -> tuple[tuple[float, float, float], ...]:
    """``((from, at, step_s), ...)`` (the server's clock in s since the epoch) of the
    ``clock_set`` events of a ``connect.json``; ContractError naming the file where it is none."""
    path = Path(path)
    try:
        events = json.loads(path.read_text(encoding="utf-8"))["events"]
        sets = tuple((pd.Timestamp(e["from_utc"]).timestamp(), pd.Timestamp(e["at_utc"]).timestamp(),
                      float(e["step_s"])) for e in events if e.get("event") == "clock_set")
    except FileNotFoundError:
        raise ContractError("data.clock_sets: no such file (a connect.json)", file=path) from None
    except (ValueError, KeyError, TypeError) as exc:
        raise ContractError(f"data.clock_sets: not a connect.json whose clock_set events name "
                            f"the server's clock (from_utc, at_utc: written since deploy73): "
                            f"{type(exc).__name__} {exc}", file=path) from None
    return sets


def undone(seconds: np.ndarray, origin, sets, path) -> tuple[np.ndarray, object, tuple[int, ...]]:
    """``seconds`` (since the file's first timestamp, ``origin``) with each clock set found in
    them undone (the rows from the set on moved back by its step; a set before the first row
    moves ``origin``, an ISO 8601 text or a Timestamp, back instead), the origin, and the
    indices (in ``sets``) of the sets found; as they are without timestamps or sets."""
    if not sets or origin is None:
        return seconds, origin, ()
    shift, found = _shifts(seconds + pd.Timestamp(origin).timestamp(), sets, path)
    if not found:
        return seconds, origin, ()
    first = shift[np.argmax(np.isfinite(seconds))]      # the origin's row (the first timed)
    moved = pd.Timestamp(origin) - pd.Timedelta(seconds=float(first))
    return (seconds - (shift - first), moved if isinstance(origin, pd.Timestamp)
            else moved.isoformat(), found)


def after(last: float, at: float, sets) -> float:
    """The seconds the sets between a log's last row (``last``, the server's clock as the log
    has it, s since the epoch) and a later sample (``at``) moved that sample's time back by:
    the sample read as the log's next row (a ``connect`` restarted with ``connect.warm``)."""
    if not sets or not (np.isfinite(last) and np.isfinite(at)):
        return 0.0
    shift, _ = _shifts(np.array([last, at]), sets, "connect.warm")
    return float(shift[1] - shift[0])


def _shifts(stamps: np.ndarray, sets, path) -> tuple[np.ndarray, tuple[int, ...]]:
    """Per row of ``stamps`` (the server's clock, s since the epoch; NaN: a missing time) the
    seconds the sets before it moved it forward, and the sets found (the rule: module doc)."""
    shift = np.zeros(len(stamps))
    found = []
    for k, (before, at, step) in enumerate(sets):
        row = _first_after(stamps, before, at, step, path)
        if row is not None:
            shift[row:] += step
            found.append(k)
    return shift, tuple(found)


def _first_after(stamps: np.ndarray, before: float, at: float, step: float, path) -> int | None:
    """The first row after the set ``(before, at, step)``, or None where the rows do not show
    it; refused where two rows would be (rows without a time are passed over)."""
    timed = np.flatnonzero(np.isfinite(stamps))
    if not len(timed):
        return None
    read = stamps[timed]
    prev, this = read[:-1], read[1:]
    inside = (prev <= before + MATCH_S) & (this >= at - MATCH_S) & ((step > 0) | (this < prev))
    rows = timed[np.flatnonzero(inside) + 1]
    if len(rows) > 1:
        raise ContractError(f"data.clock_sets: the clock set at {pd.Timestamp(at, unit='s')} "
                            f"is at {len(rows)} rows of the file (rows {rows[0] + 1} and "
                            f"{rows[1] + 1})", file=path, column=TIME, row=int(rows[1]) + 1)
    if len(rows):
        return int(rows[0])
    own = float(np.median(np.diff(read))) if len(read) > 1 else 0.0    # the file's own step
    if at - MATCH_S <= read[0] < at + max(own, MATCH_S) and (step > 0 or read[0] > before + MATCH_S):
        return int(timed[0])
    return None


def unfound(sets, found) -> str:
    """The sets of ``sets`` whose indices are not in ``found``, each by its instants."""
    found = set(found)
    return "; ".join(f"{pd.Timestamp(at, unit='s', tz='UTC').isoformat()} ({step:+g} s, from "
                     f"{pd.Timestamp(before, unit='s', tz='UTC').isoformat()})"
                     for k, (before, at, step) in enumerate(sets) if k not in found)
