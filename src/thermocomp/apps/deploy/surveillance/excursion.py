"""The shape of an excursion in time for :class:`~.monitor.SensorMonitor`: a regime that steps
and stays, or a fault that keeps growing.

The monitor keeps the field as it was ``EXCURSION_TAU_S`` seconds ago on the average (an
exponential memory of the referenced readings in the samples' own time, so the same at any
cadence); the field's self-prediction error then was the error of that memory (the errors are
linear in the readings).  A sensor out of band whose error is a share of its rise no larger than
it was that long ago (the error hovers, or grows with the field) shows a regime training never
held; one whose error outgrows its rise (``EXCURSION_GROWTH``) shows a fault: a drift, a leak, a
sensor frozen while the field moves.  A lathe's steady 5000 rpm put ``T_Tool_holder_1`` just
past its band within 25 min and held it there for 24 h (mon73)."""

from __future__ import annotations

import numpy as np

from .states import EXCURSION_GROWTH, EXCURSION_TAU_S, WARNING


class Excursion:
    """Mixin of :class:`~.monitor.SensorMonitor` (its state): the slow memory of the field and
    whether the excursion out of band hovers."""

    def _slow_reset(self) -> None:
        """A new campaign: its reference is the memory's start (every change zero there)."""
        self._slow = np.zeros(len(self.names))
        self._slow_t = float("nan")    # time of the last sample folded in (none yet)
        self._slow_ok = True           # every sample came with its time: the memory holds

    def _slow_step(self, d: np.ndarray, time: float) -> None:
        """Fold the sample ``d`` (referenced, NaN: missing) taken at ``time`` (s) in."""
        if not np.isfinite(time):
            self._slow_ok = False      # a sample without its time: the memory's age is unknown
            return
        if np.isfinite(self._slow_t):
            keep = np.exp(-max(time - self._slow_t, 0.0) / EXCURSION_TAU_S)
            self._slow = np.where(np.isfinite(d), keep * self._slow + (1 - keep) * d, self._slow)
        self._slow_t = time

    def _slow_block(self, D: np.ndarray, times) -> None:
        """Fold the rows ``D`` taken at ``times`` in, as :meth:`_slow_step` row by row."""
        if times is None or not len(D):
            if len(D):
                self._slow_ok = False
            return
        t = np.asarray(times, float)
        if not np.isfinite(t).all():
            self._slow_ok = False
            return
        before = np.r_[self._slow_t if np.isfinite(self._slow_t) else t[0], t[:-1]]
        # each row's weight in the memory at the last row: its share when folded in, decayed since
        weight = (1 - np.exp(-np.maximum(t - before, 0.0) / EXCURSION_TAU_S)) * np.exp(
            -(t[-1] - t) / EXCURSION_TAU_S)
        self._slow = np.exp(-(t[-1] - before[0]) / EXCURSION_TAU_S) * self._slow + weight @ D
        self._slow_t = float(t[-1])

    def _excursion_hovers(self, level: np.ndarray, err: np.ndarray) -> bool:
        """Whether every judged sensor out of band has an error that is no larger a share of its
        rise than ``EXCURSION_TAU_S`` ago (the memory's error against its rise then), within
        ``EXCURSION_GROWTH``: a regime, not a fault.  False where the memory is not known."""
        out = np.flatnonzero(self._judging & (level >= WARNING))
        if not self._slow_ok or not np.isfinite(self._slow_t) or not len(out):
            return False
        slow = self._slow[self._active]
        past = (self._slow - self._M @ slow) * self._scale          # the memory's own error
        rows = self._hist[self._recent[self._pos, :min(self._count, self.confirm)]]
        rise = np.abs(rows.mean(axis=0))
        now = np.abs(err[out]) * np.abs(self._slow[out])
        then = np.maximum(past[out] * np.sign(err[out]), 0.0) * rise[out]
        return bool(np.all(now <= EXCURSION_GROWTH * then))
