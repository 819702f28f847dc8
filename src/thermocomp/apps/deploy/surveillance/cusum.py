"""A slow drift of one sensor, caught by a CUSUM of its self-prediction error (cusum70).

The bands judge the error of the last few samples: a drift is read as temperature until it is
as large as the band (0.2 K/h on ``T_motor2``: 1.5-1.75 h), and a model that leans on the
sensor pays for it meanwhile.  A drift is a *persistent* departure of the sensor's error
(against the others' prediction) from the level it held at the campaign's start; a one-sided
CUSUM of that departure sees it far sooner than a band on the instantaneous error, and a
constant offset since the start (an error level of its own, which the band rule prices as
unseen) is the level itself, not a departure.

Per sensor the others predict: the error against the leave-one-out prediction with *every*
sensor in (fixed: a drifting sensor's error stays its drift whatever is excluded), its baseline
the mean over the campaign's samples 1..``window``, then two one-sided sums of the departure
less ``k_j`` (``cusum_k`` × its warning band), the larger over the band the statistic.  The
limit is learned on the training campaigns (``cusum_factor`` × the largest statistic there, at
least :data:`CUSUM_FLOOR`).  The sums run while every sensor is in and no new thermal state is
declared (0 otherwise); a sensor past the limit is excluded for drift when it is a lone fault
(at most one other sensor, its coupled partner, at half the limit) and the new-state check lets
it (:meth:`~.judgement.Judgement._drift_vetoed`); it comes back once its error's mean over the
window is within ``k_j`` of its baseline again.
"""

from __future__ import annotations

import numpy as np

from ..pod import ThermalPOD
from .states import CUSUM_FLOOR


def cusum_sums(dev: np.ndarray, k: np.ndarray, start: np.ndarray) -> np.ndarray:
    """The upper one-sided sums ``S_t = max(0, S_{t-1} + dev_t - k)`` of every row of ``dev``
    ((m, n); ``start``: ``S`` before the first row), in one go: ``S_t = C_t - min(0, min_{u<=t}
    C_u)`` with ``C_t = start + sum_{i<=t} (dev_i - k)``."""
    C = start + np.cumsum(dev - k, axis=0)
    return C - np.minimum(np.minimum.accumulate(C, axis=0), 0.0)


def _largest(e: np.ndarray, k: np.ndarray, band: np.ndarray, judged: np.ndarray,
             window: int) -> float:
    """The largest statistic of one campaign's full-set leave-one-out errors ``e`` (the
    reference sample first)."""
    if len(e) <= window + 1:
        return 0.0
    dev = e[window + 1:, judged] - e[1:window + 1, judged].mean(axis=0)
    zero = np.zeros(int(judged.sum()))
    s = np.maximum(cusum_sums(dev, k[judged], zero), cusum_sums(-dev, k[judged], zero))
    return float((s / band[judged]).max())


def training_limit(pod, arrays: list[np.ndarray], k: np.ndarray, band: np.ndarray,
                   judged: np.ndarray, window: int, factor: float) -> float:
    """The limit of the statistic (band × samples) from the training campaigns (absolute
    readings): ``factor`` × the largest statistic over the campaigns and over held-out blocks
    (the campaigns, or with fewer than 3 each cut in 4, every block referenced to its first
    row and predicted by a basis of the same r fitted on the others: a basis fitted on a
    whole 40 h column predicts it 1.4 band × samples close, its own held-out quarters 66, its
    healthy test 3 and more)."""
    def errors(a: np.ndarray, basis) -> np.ndarray:
        M, lev = basis.operator(np.ones(a.shape[1], dtype=bool), pod.n_modes_)
        d = a - a[0]
        return (d - d @ M.T) / (1 - lev)

    top = max((_largest(errors(a, pod), k, band, judged, window) for a in arrays), default=0.0)
    blocks = arrays if len(arrays) >= 3 else [b for a in arrays for b in np.array_split(a, 4)]
    for i, b in enumerate(blocks):
        rest = [x - x[0] for j, x in enumerate(blocks) if j != i]
        if len(b) <= window + 1 or not rest:
            continue
        basis = ThermalPOD(modes=pod.n_modes_).fit(np.vstack(rest))
        top = max(top, _largest(errors(b, basis), k, band, judged, window))
    return max(factor * top, CUSUM_FLOOR)


class LevelCusum:
    """Mixin of :class:`~.monitor.SensorMonitor` (its state): the CUSUM of each judged sensor's
    departure from its level at the campaign's start (module doc)."""

    cusum_k, cusum_limit = None, None     # a monitor pickled before the rule: off

    def _cusum_setup(self) -> None:
        """The full-set operator and the references ``k`` (°C); off without a learned limit."""
        self._cs_live = self.cusum_k is not None and self.cusum_limit is not None
        if self._cs_live:
            M, lev = self.pod.operator(self._true)
            self._cs_M, self._cs_div = M, 1.0 - lev
            self._cs_k = float(self.cusum_k) * self.warning_c
            self._cs_judged = self._predictable.copy()

    def _cusum_reset(self) -> None:
        n = len(self.names)
        self._cs_sum = np.zeros(n)            # the baseline's sum, then its mean
        self._cs_n = 0                        # samples in the baseline so far
        self._cs_up, self._cs_down = np.zeros(n), np.zeros(n)
        self._cs_out = np.zeros(n, dtype=bool)    # excluded on this evidence

    def _cusum_watching(self, d: np.ndarray) -> bool:
        """Whether the sums run at the referenced sample ``d``: every sensor in, no new thermal
        state, and every reading within its training range -- beyond it every error grows with
        the distance from training (a line warmed 16 °C along its two trained modes: T_6
        persistently off its level at 6 °C beyond, read as a drift)."""
        return self._cs_live and self._all_active and not self._novel and not self._beyond(d)

    def _beyond(self, d: np.ndarray) -> np.ndarray:
        """Per row of referenced readings ``d``: a reading beyond its training range."""
        x = d + self._ref
        with np.errstate(invalid="ignore"):
            return ((x < self.lo_c) | (x > self.hi_c)).any(axis=-1)

    def _cusum_errors(self, D: np.ndarray) -> np.ndarray:
        """Full-set leave-one-out errors of referenced readings ``D`` ((m, n) or (n,))."""
        return (D - D @ self._cs_M.T) / self._cs_div

    def _cusum_statistic(self, up: np.ndarray, down: np.ndarray) -> np.ndarray:
        return np.where(self._cs_judged, np.maximum(up, down) / self.warning_c, 0.0)

    def _cusum_next(self, d: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
        """``(up, down)`` after the referenced sample ``d`` (the sample after the reference);
        ``None``: the baseline is still being taken, or a reading is missing (the sums stay)."""
        if self._cs_n < self.window or not np.isfinite(d).all():
            return None
        dev = self._cusum_errors(d) - self._cs_sum
        return (np.maximum(self._cs_up + dev - self._cs_k, 0.0),
                np.maximum(self._cs_down - dev - self._cs_k, 0.0))

    def _cusum_step(self, d: np.ndarray, sums: tuple | None = None) -> None:
        """Take the sample ``d`` (not the reference) into the baseline or the sums (``sums``:
        :meth:`_cusum_next` of it, where already computed)."""
        if not self._cs_live or not np.isfinite(d).all():
            return
        if self._cs_n < self.window:
            self._cs_n += 1
            self._cs_sum += self._cusum_errors(d)
            if self._cs_n == self.window:
                self._cs_sum /= self.window
            return
        if not self._cusum_watching(d):
            self._cs_up[:], self._cs_down[:] = 0.0, 0.0
            return
        self._cs_up, self._cs_down = sums or self._cusum_next(d)

    def _cusum_due(self, up: np.ndarray, down: np.ndarray) -> bool:
        """Whether a sensor's statistic is past the limit (the full path then judges it)."""
        return bool((self._cusum_statistic(up, down) > self.cusum_limit).any())

    def _cusum_block(self, d: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
        """``(ok, up, down)`` per row of the complete referenced rows ``d`` (every sensor active,
        the baseline taken): a row is ok while no statistic passes the limit; ``None``: the
        rule is off or the baseline is still being taken (the rows go one by one)."""
        if not self._cs_live:
            return np.ones(len(d), dtype=bool), None, None
        if self._cs_n < self.window or self._novel:
            return None
        dev = self._cusum_errors(d) - self._cs_sum
        up = cusum_sums(dev, self._cs_k, self._cs_up)
        down = cusum_sums(-dev, self._cs_k, self._cs_down)
        ok = ~(self._cusum_statistic(up, down) > self.cusum_limit).any(axis=1)
        beyond = self._beyond(d)
        if beyond.any():             # the sums drop to 0 there (row by row)
            ok &= np.cumsum(beyond) == 0
        return ok, up, down

    def _exclude_by_cusum(self, level, err, time, events) -> None:
        """Exclude the lone sensor past the limit (module doc), as a drift."""
        if not (self.adaptive and self._cs_live and self._all_active and not self._novel) \
                or self._active.sum() <= self.min_active_:
            return
        s = self._cusum_statistic(self._cs_up, self._cs_down)
        near = s >= 0.5 * self.cusum_limit
        if s.max() <= self.cusum_limit or int(near.sum()) > 2:
            return
        # of the (at most two) at half the limit, paper 002's culprit, as the bands pick it: the
        # largest departure of the residual with every sensor in (the deleted one × (1 - h)).
        # A drift on T_motor2 leaves the larger statistic on its coupled partner T_motor1,
        # whose deleted residual leans on it (0.111 against 0.080 °C over the window; x (1 - h):
        # 0.041 against 0.050)
        size = np.abs(self._cusum_departure()) * self._cs_div
        j = int(np.argmax(np.where(near & self._cs_judged, size, -1.0)))
        if self._drift_vetoed(j, level, err, time, events):
            return
        side = "+" if self._cs_up[j] >= self._cs_down[j] else "-"
        self._exclude(j, f"drift: self-prediction error persistently {side} off its level at the "
                         f"campaign's start (CUSUM {s[j]:.3g} band x samples, limit "
                         f"{self.cusum_limit:.3g})", time, events, by_field=True)
        self._since[j] = self._count
        self._cs_out[j] = True
        # a partner off its level too (its sums above 0) that no other sensor predicts once j is
        # out cannot be vouched for (a coupled pair looks alike to self-prediction: the pick
        # between them is a near tie): out too, as the bands take such a pair
        partner = (s > 0) & self._active & ~self._observable & self._cs_judged
        for i in np.flatnonzero(partner):
            if self._active.sum() > self.min_active_:
                self._exclude(int(i), f"drift: self-prediction error persistently off its level "
                                      f"at the campaign's start (CUSUM {s[i]:.3g}) and no other "
                                      f"sensor predicts it once {self.names[j]} is out", time,
                              events, by_field=True)
                self._since[i] = self._count
                self._cs_out[i] = True
        self._cs_up[:], self._cs_down[:] = 0.0, 0.0

    def _cusum_departure(self) -> np.ndarray:
        """Each sensor's full-set error over the window's complete samples, less its baseline
        (their mean)."""
        H = self._hist
        complete = np.isfinite(H).all(axis=1)
        if not complete.any():
            return np.zeros(len(self.names))
        return self._cusum_errors(H[complete]).mean(axis=0) - self._cs_sum

    def _cusum_calm(self) -> np.ndarray:
        """Per sensor: not out on this evidence, or its error's mean over the window within
        ``k_j`` of its baseline (back at its level: it may return)."""
        if not self._cs_out.any():
            return np.ones(len(self.names), dtype=bool)
        return ~self._cs_out | (np.abs(self._cusum_departure()) <= self._cs_k)
