"""The manifest's ``start`` column read one way by every reader of it.

The manifest reader, the hold-out of the last campaigns, the carry-over across a cut record,
validation's forward/interleaved choice and the refusal of a renamed sensor all order or
compare campaigns by ``start``; each parsed the column by its own rules (one gave up on a
manifest mixing a start with an offset and one without, another read both).  They read it
here: :func:`start_stamp` per cell, :func:`start_instants` for a column.
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from .contract import ContractError

START = "start"


def start_stamp(value) -> pd.Timestamp:
    """One ``start`` cell as written: a :class:`pandas.Timestamp` with its offset, or without
    one when the cell has none; NaT for an empty cell (``''``, None, NaN, NaT: not known).

    Raises
    ------
    ValueError
        If the cell is no ISO 8601 time (a day-first ``28.11.2026 13:05``, ``03/11/2026``:
        which order?); :func:`start_instants` names its row.
    """
    if value is None or (not isinstance(value, str) and pd.isna(value)):
        return pd.NaT
    if isinstance(value, pd.Timestamp):
        return value
    text = str(value).strip()
    if not text:
        return pd.NaT
    return pd.Timestamp(pd.to_datetime(text, format="ISO8601"))


def on_clock(stamp: pd.Timestamp, zone: str | None) -> pd.Timestamp:
    """``stamp`` with its offset; one written without is on ``zone``'s clock (``data.timezone``;
    UTC where None): an hour the clock repeats is read as its first (summer) pass, a skipped one
    shifted forward, as a file's timestamps are (:func:`.starts.utc_instant`)."""
    if pd.isna(stamp) or stamp.tzinfo is not None:
        return stamp
    return stamp.tz_localize(zone or "UTC", ambiguous=True, nonexistent="shift_forward")


def start_instants(values: pd.Series, path: Path | None = None, zone: str | None = None) -> pd.Series:
    """The ``start`` cells ``values`` as instants (UTC; the index kept).

    A start with an offset (``Z``, ``+01:00``) is that instant; one without is on ``zone``'s
    clock (``data.timezone``; as UTC where None), as a file's timestamps without an offset are,
    so a manifest may mix both, and a start filled from a file's first timestamp
    (:func:`.read._starts_from_timestamps`) compares with the manifest's; an empty cell is NaT
    (not known).

    Raises
    ------
    ContractError
        For a cell that is no ISO 8601 time, naming ``path`` and its row (1-based).
    """
    out = []
    for row, value in enumerate(values, 1):
        try:
            stamp = start_stamp(value)
        except (ValueError, TypeError):
            raise ContractError(f"start {value!r} is not an ISO 8601 time", file=path,
                                column=START, row=row) from None
        out.append(stamp if pd.isna(stamp) else on_clock(stamp, zone).tz_convert("UTC"))
    return pd.Series(out, index=values.index, dtype="datetime64[ns, UTC]")
