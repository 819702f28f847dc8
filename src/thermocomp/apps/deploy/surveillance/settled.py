"""A level shift of a sensor no other predicts, told from heat by two windows (jump94b).

A blind sensor's step below its jump limit is read as heat: nothing else judges a sensor no
other predicts.  fl_thermal's ``T_t16`` reads healthy bursts of 2-3 °C that come back within a
few samples, so its jump limit is 8.6 °C and a +3 °C step at 1 h raised the adaptive error from
83.90 to 123.35 µm² (``benchmarks/bench_jump94.py``).  What tells a step from a burst is that it
stays: the last ``window`` samples lie wholly above (or below) the ``window`` before them.  In
training two successive windows of ``T_t16`` never part by more than 0.12 °C (a burst lifts one
window's maximum, not the next one's minimum); a heating ramp parts them by its rise over a
window, so the bound scales with the sensor's own fastest training warming.  A sensor parted
past ``jump_factor`` x its largest training separation is re-referenced by the difference of the
two windows' medians and kept in (as :meth:`~.faults.InstantFaults._bent`: held out it would be
read at its last value), a window after the step.

A fast ramp parts two windows too (by its rise over one sample), so the separation alone read a
blind sensor's ramp of 0.8 °C a sample as two settled steps, -9.77 and +8.81 °C, and left the
sensor that far off its truth (tests/shell/test_export_cmon91.py's ``T_u``; settle95).  A step
moves the windows' medians far more than either window spreads; a ramp spreads each window about
as much as it moves them (a straight ramp over ``w`` samples: median difference ``w`` x its rate,
each window's median absolute deviation about ``w / 4`` x it, a ratio of 4).  So the windows'
median difference must also pass :data:`STEADY` x the larger of their median absolute deviations
(fl_thermal's planted ``T_t16`` steps the rule catches: ratios 8.5-52; ``bench_settle95.py``).
"""

from __future__ import annotations

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from .states import STATES

STEADY = 6.0
"""A settled step's windows' median difference over the larger of their median absolute
deviations must pass this (a straight ramp's ratio is 4, fl_thermal's planted steps' 8.5-52)."""


def _windows(a, w: int) -> tuple[np.ndarray, int]:
    """The windows of ``w`` rows of ``a`` that :func:`separation` and :func:`steadiness` compare
    (``(windows, cols, w)``), and how many windows apart one is from the ``w`` rows before it.

    Every window in general (``sliding_window_view``, ``w`` apart); of ``2 w`` rows (the one
    sample's test of the served monitor and the code's mirror) only the two it compares, 1
    apart: the same values without the ``w - 1`` windows between them (ci97b)."""
    a = np.asarray(a, float)
    if len(a) == 2 * w:
        # rows (2, w, cols...) -> (2, cols..., w), what sliding_window_view's axis=0 gives
        return a.reshape(2, w, *a.shape[1:]).transpose(0, *range(2, a.ndim + 1), 1), 1
    return sliding_window_view(a, w, axis=0), w     # (n - w + 1, cols, w)


def separation(a: np.ndarray, w: int) -> np.ndarray:
    """Per sample ``t >= 2w - 1`` (rows of the result: ``t - 2w + 1``) and column: how far the
    window ``a[t-w+1..t]`` lies wholly above or below the ``w`` samples before it (the minimum of
    one less the maximum of the other; negative where they overlap, NaN where one is missing)."""
    win, k = _windows(a, w)
    lo, hi = win.min(-1), win.max(-1)
    return np.maximum(lo[k:] - hi[:-k], lo[:-k] - hi[k:])


def steadiness(a: np.ndarray, w: int) -> tuple[np.ndarray, np.ndarray]:
    """Per sample ``t >= 2w - 1`` (rows ``t - 2w + 1``) and column, as :func:`separation`: the
    median of the window ``a[t-w+1..t]`` less the median of the ``w`` samples before it, and the
    larger of the two windows' median absolute deviations (a ramp's spread; NaN where one is
    missing)."""
    win, k = _windows(a, w)
    med = np.median(win, -1)
    mad = np.median(np.abs(win - med[..., None]), -1)
    return med[k:] - med[:-k], np.maximum(mad[k:], mad[:-k])


def level_shift(a: np.ndarray, w: int, lim, steady: float = STEADY) -> tuple[np.ndarray, np.ndarray]:
    """Per sample ``t >= 2w - 1`` (rows ``t - 2w + 1``) and column, as :func:`separation`: whether
    the window ending at ``t`` settled off the one before -- parted from it by more than ``lim``
    (:func:`separation`) and moved by a median difference past ``steady`` x their spread, not a
    ramp (:func:`steadiness`; ``steady`` 0: the parting alone, an export from before settle95) --
    and that median difference, the shift a re-reference takes out.  The one test of the served
    monitor's sample and fast block and of the exported code's mirror.  Where no window parted
    the medians are not computed (nearly every sample; ci97b) and the shift is all NaN: its
    callers take it only where one settled."""
    parted = separation(a, w) > lim
    if not parted.any():
        return parted, np.full(parted.shape, np.nan)
    shift, spread = steadiness(a, w)
    return parted & (np.abs(shift) > steady * spread), shift


def level_shift_now(ring: np.ndarray, row: np.ndarray, w: int, lim,
                    steady: float = STEADY) -> tuple[np.ndarray, np.ndarray]:
    """:func:`level_shift` of the one sample ``row`` after the ring of the ``2 w - 1`` before it
    (per column: parted, its shift), the sample's test of the served monitor and of the code's
    mirror.  Whether a window parted is asked first of the two windows' extremes as they stand
    (ci101b: no stacked copy of the ring a sample; a minimum and a maximum are the same whatever
    the order they are taken in, NaN where one is missing); only where one parted is the ring
    stacked and :func:`level_shift` asked (nearly never)."""
    lo_b, hi_b = ring[:w].min(0), ring[:w].max(0)
    after = ring[w:]
    lo_a = np.minimum(after.min(0), row) if len(after) else row
    hi_a = np.maximum(after.max(0), row) if len(after) else row
    parted = np.maximum(lo_a - hi_b, lo_b - hi_a) > lim
    if not parted.any():
        return parted, np.full(parted.shape, np.nan)
    return tuple(v[0] for v in level_shift(np.vstack([ring, row]), w, lim, steady))


def largest_separation(arrays, w: int, n: int) -> np.ndarray:
    """Each sensor's largest training :func:`separation` (never below 0; inf: no campaign holds
    two windows)."""
    worst = np.full(n, -np.inf)
    for a in arrays:
        if len(a) >= 2 * w:
            worst = np.maximum(worst, separation(a, w).max(0))
    return np.where(np.isfinite(worst), np.maximum(worst, 0.0), np.inf)


def advanced(ring: np.ndarray, age: np.ndarray, ref: np.ndarray, ref_before, row: np.ndarray):
    """``(ring, age)`` after a sample: the ring's oldest row dropped and ``row`` (the sample as
    the monitor read it) last; each sensor's reference age one older, 1 where the sample moved
    its reference (``ref_before``: the reference before it; None at a campaign's first).  One
    step for the served monitor and the code's mirror (``CodeMonitor.step``)."""
    with np.errstate(invalid="ignore"):
        # np.isclose(ref, ref_before, rtol=0, atol=1e-12) without its per-call overhead (a
        # sample's): within 1e-12, or equal (an infinite reference); NaN is moved
        moved = True if ref_before is None else ~((np.abs(ref - ref_before) <= 1e-12)
                                                  | (ref == ref_before))
    return np.concatenate((ring[1:], row[None])), np.where(moved, 1, age + 1)


class Settled:
    """Mixin of :class:`~.monitor.SensorMonitor` (its state): the last ``2 window - 1`` readings
    of each sensor on its current reference, and the rule on them (module doc)."""

    def _settle_reset(self) -> None:
        n = len(self.names)
        self._settle = np.full((2 * self.window - 1, n), np.nan)   # oldest first
        self._settle_age = np.zeros(n, dtype=np.int64)    # samples since its reference moved

    def _settled(self, x: np.ndarray, time: float, events: list) -> None:
        """Before the sample ``x`` (absolute °C) is read: a blind sensor in, or out for another
        reason than a jump (main undoes a blind sensor's jumps on its return), whose window
        ending at ``x`` lies wholly off the window before by more than its limit is
        re-referenced by the two windows' median difference.  Only readings on the sensor's
        current reference are compared (none moved it -- a jump, its undo on a return, BENT, a
        common step -- for ``2 window - 1`` samples): the undo of a noise burst's jumps read as a
        settled step left yearround's ``T_amb`` out (tests/shell/test_monitor.py)."""
        if self._ref is None:
            return
        w, cols = self.window, self._settle_cols
        parted, shift = level_shift_now(self._settle[:, cols], x[cols] - self._ref[cols], w,
                                        self._settle_lim[cols])
        if not parted.any():       # nearly every sample: nothing to re-reference
            return
        fire = ((self._active[cols] | (self._jumps[cols] == 0)) & parted
                & (self._gap[cols] == 1) & (self._settle_age[cols] >= 2 * w - 1))
        if fire.any():
            # the fast path leaves one array as the last reading, the last good one and the
            # field served (monitor._fast): each shifted once, on its own copy
            self._prev, self._last_good = self._prev.copy(), self._last_good.copy()
        for k in np.flatnonzero(fire):
            j = int(cols[k])
            off = float(shift[k])
            self._ref[j] += off
            self._prev[j] -= off
            self._hist[:, j] -= off
            if self._active[j]:     # out: its last good reading is from before the step
                self._last_good[j] -= off
            self._settle[w:, j] -= off     # the window after: compared like with like next
            events.append({"time": float(time), "sensor": self.names[j],
                           "from": STATES[self._state[j]] if self._active[j] else "excluded",
                           "to": "re-referenced", "reason": f"settled off its own: its last {w} "
                           f"samples {off:+.3g} °C off the {w} before (no other sensor predicts "
                           f"it; limit {self._settle_lim[j]:.3g} °C); re-referenced"})

    def _settle_push(self, ref_before) -> None:
        """After the sample: its reading as the monitor read it (the window's row: on the
        reference it left, NaN beyond its range -- no measurement: a nut back from out of range
        read its return as a settled step), and the age of each sensor's reference (1 where the
        sample moved it)."""
        self._settle, self._settle_age = advanced(self._settle, self._settle_age, self._ref,
                                                  ref_before, self._hist[(self._pos - 1) % self.window])

    def _settle_block(self, d: np.ndarray) -> np.ndarray:
        """Rows of a fast block (``d``: referenced, every sensor in, one reference) on which the
        rule would fire: the block stops before the first."""
        w, cols = self.window, self._settle_cols
        rows = np.vstack([self._settle[:, cols], d[:, cols]])
        m = len(d)
        parted = level_shift(rows, w, self._settle_lim[cols])[0][:m]   # row i: against the one before
        age = self._settle_age[cols] + np.arange(m)[:, None]
        gap = np.ones((m, len(cols)))
        gap[0] = self._gap[cols]
        return (parted & (gap == 1) & (age >= 2 * w - 1)).any(axis=1)

    def _settle_commit(self, d: np.ndarray) -> None:
        """A fast block's rows taken: the ring's last rows, each reference older by them."""
        self._settle = np.vstack([self._settle, d])[-len(self._settle):]
        self._settle_age = self._settle_age + len(d)
