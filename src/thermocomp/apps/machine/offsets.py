"""What the client may write to the machine: bounded, rate-limited offsets that are held and
then decay to zero while the inputs are stale (pure).

The compensator's own guard (the adaptive one's) bounds and rate-limits each correction it
computes; this limiter keeps the same promise for what reaches the machine's registers, also
when no correction is computed: a missing one (NaN) holds the last offset, and without a
fresh sample for ``hold_s`` the offset decays with time constant ``decay_s``; the first fresh
ones after that come back at the rate limit, not in one jump.  With ``widen`` the bound of a
fresh offset widens as the compensator's guard widens it for a machine hotter than training
(``widen()``: µm per target, or None; :func:`thermocomp.apps.deploy.adaptive.stream_allowance`),
so that what reaches the machine is what the compensator computed; a stale offset decays inside
the bound of its last fresh one.

The rate limit is the guard's rule (connect72: :func:`~thermocomp.apps.deploy.guard.rate_span`
of the step of the stream's time).  Before, one training period's change per sample, counted in
``connect.period_s`` (on the twin's ``time`` node not at all): stricter than the guard where
samples come further apart (a control publishing every 3 periods: the lag bank's offsets up to
0.76 µm behind its guarded correction, bench_connect72).  (deploy73) The step is the
compensator's own, its clock's (the client passes it): the limiter keeps no second clock of the
same time.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ..deploy.guard import rate_span


class OffsetLimiter:
    """Per target: bound ``[lo, hi]`` µm and a largest rate ``max_rate_per_s`` µm/s over each
    step of the stream's time, at least one training period ``period_s`` (the guard's)."""

    def __init__(self, lo, hi, max_rate_per_s, hold_s: float, decay_s: float,
                 widen: Callable[[], np.ndarray | None] | None = None, period_s: float = 1.0):
        self.lo, self.hi = np.asarray(lo, float), np.asarray(hi, float)
        self.widen = widen
        self._lo_now, self._hi_now = self.lo, self.hi     # the bound of the last fresh offset
        self.max_rate_per_s, self.period_s = np.asarray(max_rate_per_s, float), float(period_s)
        self.hold_s, self.decay_s = float(hold_s), float(decay_s)
        self.offset = np.zeros_like(self.lo)
        self._fresh_at = None          # wall time of the last fresh correction
        self._free = True              # the next fresh one is not rate-limited

    def new_campaign(self, held=None) -> None:
        """A campaign starts (the error is zeroed with the workpiece): its first correction is
        taken as it is, within the bound, as the compensator's own guard takes it.  ``held``
        (restart69): the campaign is joined mid-way (a new process), its error not zeroed: the
        first correction is rate-limited from the offsets the machine holds (µm; NaN: this
        limiter's own), as after a decay, not taken in one jump."""
        if held is None:
            self._free = True
            return
        held = np.asarray(held, float)
        self.offset = np.where(np.isfinite(held), held, self.offset)
        self._free = False

    def fresh(self, y, now: float, step_s: float = math.nan) -> np.ndarray:
        """The offset to write for a new correction ``y`` (NaN entries: held) of a sample
        ``step_s`` after the previous one on the compensator's clock (NaN: a campaign's first,
        one period): the change allowed is the guard's, its rate over :func:`rate_span` of the
        step (opcleft67: after a gap, the time gone on)."""
        y = np.where(np.isfinite(y), np.asarray(y, float), self.offset)
        most = self.max_rate_per_s * rate_span(float(step_s), self.period_s)
        step = y - self.offset if self._free else np.clip(y - self.offset, -most, most)
        extra = self.widen() if self.widen is not None else None
        self._lo_now, self._hi_now = ((self.lo, self.hi) if extra is None
                                      else (self.lo - extra, self.hi + extra))
        self.offset = np.clip(self.offset + step, self._lo_now, self._hi_now)
        self._free = False
        self._fresh_at = now
        return self.offset

    def stale(self, now: float) -> np.ndarray:
        """The offset while no fresh sample arrives: held ``hold_s``, then decaying to zero."""
        if self._fresh_at is None:
            return self.offset
        late = now - self._fresh_at - self.hold_s
        if late > 0:
            factor = np.exp(-late / self.decay_s) if self.decay_s > 0 else 0.0
            self.offset = np.clip(self.offset * factor, self._lo_now, self._hi_now)
            self._fresh_at = now - self.hold_s     # decay from here on, not twice over the same span
        return self.offset

    @property
    def started(self) -> bool:
        """A fresh correction has been given (before it there is no offset of its own to hold)."""
        return self._fresh_at is not None

    def decaying(self, now: float) -> bool:
        """No fresh correction for longer than ``hold_s`` (after a first one)."""
        return self._fresh_at is not None and now - self._fresh_at > self.hold_s
