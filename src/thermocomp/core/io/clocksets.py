"""(deploy73) The server's clock sets ``connect`` told (its ``clock_set`` events), undone in a
log of the machine's timestamps at read time (``data.clock_sets``).

``connect`` tells an operator's clock set from a pause by its own clock and goes on with the
stream's time as its own clock did (connect71); the machine's log keeps the set in its
timestamps, where a file cannot tell it from a pause (set forward) and the reader refuses a time
going back (set back).  Each event names the server's clock at the sample before the set
(``from_utc``) and at the sample it was told at (``at_utc``): the log's row at ``at_utc`` that
follows a row at ``from_utc`` is where the set is, and the rows from it on (of that file) move
back by ``step_s``, so that ``replay`` of the log streams the time ``connect`` streamed.
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


def undone(seconds: np.ndarray, origin: str | None, sets, path) -> tuple[np.ndarray, int]:
    """``seconds`` (since the file's first timestamp, ``origin``) with each clock set found in
    them undone (the rows from the set on moved back by its step), and how many were found;
    the seconds as they are without timestamps or sets."""
    if not sets or origin is None:
        return seconds, 0
    zero = pd.Timestamp(origin).timestamp()
    shift = np.zeros(len(seconds))
    found = 0
    for before, at, step in sets:
        rows = np.flatnonzero((np.abs(seconds[1:] - (at - zero)) <= MATCH_S)
                              & (np.abs(seconds[:-1] - (before - zero)) <= MATCH_S)) + 1
        if len(rows) > 1:
            raise ContractError(f"data.clock_sets: the clock set at {pd.Timestamp(at, unit='s')} "
                                f"is at {len(rows)} rows of the file (rows {rows[0] + 1} and "
                                f"{rows[1] + 1})", file=path, column=TIME, row=int(rows[1]) + 1)
        if len(rows):
            shift[rows[0]:] += step
            found += 1
    return seconds - shift, found
