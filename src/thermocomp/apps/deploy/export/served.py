"""The served model's streams of one deployed model, made once per input (ci99; pure core).

A conformance pack (:func:`~.pack.conformance_pack`) streams the served model over each
campaign it writes, a continuing campaign and its planted copies after the same lead-in.  A
caller that packs one deployed model more than once (an export and an export without a rule, a
test module's two packs) streams the same rows again: the served stream does not depend on the
exported system, only on the model and the rows.  :class:`ServedStreams` is an explicit cache
the caller makes for one deployed model and hands to each pack (and reads itself): each entry is
keyed on the content of the rows it was streamed over (:func:`frame_digest`: columns,
attributes, index and values), never on the identity of a frame, so a frame changed in place
is a new key.  The model itself must stay as it was when the cache was made (each stream starts
from its reset: ``streaming.warm``); a refitted or changed model needs a new cache.

An entry is shared, not copied: read it, never change it.
"""

from __future__ import annotations

import copy
import hashlib
from collections.abc import Callable

import numpy as np
import pandas as pd

from ....core.io.contract import manifest_ambient
from ..report import Streamed, stream_rows
from ..streaming import OutOfEnvelopeError


def frame_digest(frame: pd.DataFrame) -> str:
    """A digest of ``frame``'s columns, attributes, index and values (NaN alike): equal frames,
    equal digests."""
    values = pd.util.hash_pandas_object(frame, index=True).to_numpy()
    head = repr((list(frame.columns), frame.attrs)).encode()
    return hashlib.sha1(head + values.tobytes()).hexdigest()


def stepped(served, frame: pd.DataFrame, y: np.ndarray, start: int) -> None:
    """``y[start:]``: the served model's ``_step`` (as :func:`stream_rows` steps it) of ``frame``'s
    rows from ``start`` on, from the state it is in (raises ``OutOfEnvelopeError`` as it does)."""
    X = frame[served.columns_].to_numpy(float)
    t = frame["time"].to_numpy(float) if "time" in frame.columns else np.full(len(X), np.nan)
    for i in range(start, len(X)):
        y[i] = served._step(X[i], t[i])[0]


class ServedLead:
    """The served model streamed over a lead-in (the first ``rows`` of a fed frame) from its
    reset: ``state`` (a copy of the model after it; None where a row was refused) and ``y``; and
    the lead-in's rows as CSV text by columns (``text``, filled by the pack).  ``after``: the
    :class:`ServedLead` of the frame's first rows (fewer), the stream going on from a copy of its
    state (ci101: a planted copy's prefix after the lead-in it shares)."""

    def __init__(self, deployed, frame: pd.DataFrame, rows: int, after: ServedLead | None = None):
        self.rows, self.state, self.y, self.text = rows, None, None, {}
        y = np.empty((rows, len(deployed.targets_)))
        if after is not None:
            if after.state is None:
                return                               # (refused in its rows: as a whole stream)
            served, y[:after.rows] = copy.deepcopy(after.state), after.y
        else:
            served = deployed
            deployed.reset(manifest_ambient(frame))   # (stream_rows' warm without a lead-in)
        try:
            stepped(served, frame.iloc[:rows], y, 0 if after is None else after.rows)
        except OutOfEnvelopeError:
            deployed.reset()
            return                                   # (the whole stream raises it, named)
        self.state, self.y = (copy.deepcopy(deployed) if after is None else served), y
        deployed.reset()

    def stream(self, frame: pd.DataFrame) -> np.ndarray:
        """The served model's ``y`` for every row of ``frame`` (the lead-in's rows first), its rows
        after the lead-in streamed from a copy of the state the lead-in left."""
        served = copy.deepcopy(self.state)
        y = np.empty((len(frame), len(served.targets_)))
        y[:self.rows] = self.y
        stepped(served, frame, y, self.rows)
        return y


class ServedStreams:
    """The served streams of ``deployed`` (module doc), each made once: :meth:`rows` (the whole
    :func:`stream_rows` of a campaign), :meth:`y` (what a pack's corrections are made of),
    :meth:`lead` (a lead-in's state)."""

    def __init__(self, deployed):
        self.deployed = deployed
        self._rows: dict[tuple, Streamed] = {}
        self._y: dict[str, np.ndarray] = {}        # {frame's digest: y streamed from a reset}
        self._leads: dict[str, ServedLead] = {}

    def rows(self, frame: pd.DataFrame, cid: str = "", lead_in: pd.DataFrame | None = None,
             file=None) -> Streamed:
        """``stream_rows(deployed, frame, cid, file, lead_in)``, once per equal inputs (``file``
        names a refusal only: a refusal raises and is not kept)."""
        digest = frame_digest(frame)
        key = (cid, digest, None if lead_in is None else frame_digest(lead_in))
        if key not in self._rows:
            self._rows[key] = stream_rows(self.deployed, frame, cid, file, lead_in)
            if lead_in is None:                      # (from a reset: a pack's y of it too)
                self._y.setdefault(digest, self._rows[key].y)
        return self._rows[key]

    def y(self, frame: pd.DataFrame, make: Callable[[], np.ndarray]) -> np.ndarray:
        """The served ``y`` of ``frame`` streamed from its start (a reset, no lead-in): a
        :meth:`rows` or :meth:`y` already made of it, else ``make()``'s, kept."""
        digest = frame_digest(frame)
        if digest not in self._y:
            self._y[digest] = make()
        return self._y[digest]

    def lead(self, frame: pd.DataFrame, rows: int, after: ServedLead | None = None) -> ServedLead:
        """The :class:`ServedLead` of ``frame``'s first ``rows`` (their digest holds the frame's
        attributes: its manifest ambient too), going on from ``after`` where made anew."""
        key = frame_digest(frame.iloc[:rows])
        if key not in self._leads:
            self._leads[key] = ServedLead(self.deployed, frame, rows, after)
        return self._leads[key]
