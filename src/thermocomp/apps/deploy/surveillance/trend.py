"""A slow one-sensor drift told by its sum (mon101): a one-sided cumulative sum (CUSUM) of each
judged sensor's self-prediction error beyond ``TREND_ALLOW`` of its warning band.  A drift builds
its error sample by sample and stays on one side; the band alone names it only once the mean of the
last ``confirm`` errors passes it, and a model that leans on the sensor reads the drift as
temperature until then (the default scenario's ``T_motor2`` at +0.2 K/h: 27 samples of 5 min, the
E_Z error 1.8x the healthy one).  The sum reaches ``TREND_SUM`` × the band when the error has
stood beyond the allowance long enough: the sensor is then judged as out of its warning band
(:meth:`Trend._trend_level`), and the judgement (culprit, lone fault, new thermal state) is the
band's.  The sums restart whenever the active set changes (the errors then mean another thing)."""

from __future__ import annotations

import numpy as np

from .states import TREND_GROWTH, WARNING


class Trend:
    """Mixin of :class:`~.monitor.SensorMonitor` (its state): the sums of the judged errors."""

    def _trend_reset(self) -> None:
        self._trend = np.zeros((2, len(self.names)))     # the sums above / below the allowance

    def _trend_quiet(self, e: np.ndarray) -> bool:
        """Whether the sample of errors ``e`` leaves every sum at zero (the fast path may take it)."""
        return not self._trend.any() and not (np.abs(e) > self.trend_allow * self._warn).any()

    def _trend_step(self, e: np.ndarray) -> None:
        """The sums after this sample's errors ``e`` (a sensor not judged, or unread: none)."""
        allow = self.trend_allow * self._warn
        seen = self._judging & np.isfinite(e)
        e0 = np.where(seen, e, 0.0)
        self._trend = np.where(seen, np.maximum(0.0, self._trend + np.array([e0, -e0]) - allow), 0.0)

    def _trend_level(self, level: np.ndarray, err: np.ndarray) -> np.ndarray:
        """``level`` with every judged sensor within its band whose sum reached ``trend_sum`` ×
        the band, and whose error grows, at the warning band (``err``: the errors over the last
        ``confirm`` samples).  Grows: beyond the memory's error on its side (the field
        ``EXCURSION_TAU_S`` ago, :mod:`.excursion`) by ``TREND_GROWTH`` × the band; a healthy
        error that stepped into a regime within its band and stays there sums as well (the
        column's T_right2 at -0.23 °C for hours, out at 3.9 h without this)."""
        summed = self._judging & (level < WARNING) & (
            self._trend.max(axis=0) >= self.trend_sum * self._warn)
        past = self._memory_error() if summed.any() else None
        if past is None:
            return level
        side = np.sign(err)
        grows = summed & (np.abs(err) - np.maximum(past * side, 0.0) >= TREND_GROWTH * self._warn)
        return np.where(grows, WARNING, level).astype(np.int8)

    def _trend_said(self, j: int) -> str:
        """The sum of ``j``'s error beyond the allowance, for an event's reason."""
        return (f", its excess over ±{self.trend_allow * self._warn[j]:.3g} °C summed to "
                f"{self._trend[:, j].max():.3g} °C (the band {self._warn[j]:.3g})")
