"""Re-admission of an excluded sensor in :class:`~.monitor.SensorMonitor` (hysteresis, judged
together; a jump the other sensors followed taken as measured)."""

from __future__ import annotations

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from .states import OK, READMIT


def course_slopes(rows: np.ndarray) -> np.ndarray:
    """Least-squares slope (per sample) of each column of ``rows`` (chronological, one a
    sample); NaN where a column has a missing reading."""
    t = np.arange(len(rows)) - (len(rows) - 1) / 2
    return t @ rows / (t @ t)


def course_kinks(a: np.ndarray, window: int) -> np.ndarray:
    """Each sensor's change of course at every row ``k`` of ``a`` ((samples, sensors)) that has
    room: its slope over the ``window`` rows after ``k`` minus its slope over the ``window - 1``
    rows before it, the rows the monitor's ring holds around a jump at ``k``."""
    a = np.asarray(a, float)
    w = int(window)
    if w < 3 or len(a) < 2 * w + 1:
        return np.empty((0, a.shape[1]))
    slopes = {m: np.einsum("knm,m->kn", sliding_window_view(a, m, axis=0),
                           (np.arange(m) - (m - 1) / 2) / ((np.arange(m) - (m - 1) / 2) ** 2).sum())
              for m in (w - 1, w)}
    k = np.arange(w - 1, len(a) - w)
    return slopes[w][k + 1] - slopes[w - 1][k - w + 1]


def followed_bars(arrays, window: int) -> np.ndarray:
    """Per sensor ``j``, (up, down): the largest, over the rows of the training ``arrays``, of
    the smallest kink (:func:`course_kinks`) of the other sensors in that direction -- how far
    the whole machine but ``j`` ever turned its course together (inf: no row to tell)."""
    n = arrays[0].shape[1]
    kinks = [k for k in (course_kinks(a, window) for a in arrays) if len(k)]
    if not kinks or n < 3:
        return np.full((n, 2), np.inf)
    K = np.vstack(kinks)
    bars = np.empty((n, 2))
    for side, signed in enumerate((K, -K)):
        low = np.sort(signed, axis=1)
        worst = signed.argmin(axis=1)
        for j in range(n):     # the smallest of the others: the second smallest where j's is
            bars[j, side] = np.where(worst == j, low[:, 1], low[:, 0]).max()
    return bars


class Readmission:
    """Mixin of :class:`~.monitor.SensorMonitor` (its state): who comes back."""

    def course_kinks(self, a: np.ndarray) -> np.ndarray:
        """:func:`course_kinks` of the absolute readings ``a`` over this monitor's window."""
        return course_kinks(a, self.window)

    def _course_before(self, j: int) -> None:
        """At sensor ``j``'s first jump of an outage: every sensor's slope over the ring's rows
        before the jump's row (NaN with the ring not yet full)."""
        if self._count < self.window:
            self._course[j] = np.nan
            return
        order = (self._pos + np.arange(self.window)) % self.window   # oldest first; the last: now
        self._course[j] = course_slopes(self._hist[order[:-1]])

    def _watch_followed(self) -> None:
        """A window after the last jump of a sensor no other predicts: the smallest change of
        course, in the jumps' direction, of the other active sensors with a reading
        (``_followed``; NaN with fewer than r + 1 of them).  The machine follows a real step
        of the air, every part of it; an offset of the air's sensor moves nothing, and a
        source of heat (a spindle speeding up) turns the sensors near it, not the far ones."""
        watch = ~self._active & ~self._predictable & (self._jumps > 0) & (self._calm == self.window)
        for j in np.flatnonzero(watch):
            order = (self._pos + np.arange(self.window)) % self.window
            kink = np.sign(self._ref[j] - self._ref0[j]) * (
                course_slopes(self._hist[order]) - self._course[j])
            others = self._active & np.isfinite(kink)
            others[j] = False
            self._followed[j] = kink[others].min() if others.sum() >= self.min_active_ else np.nan

    def _taken_as_measured(self, j: int) -> bool:
        """The others' course turned with ``j``'s jump beyond anything training shows at once."""
        side = 0 if self._ref[j] >= self._ref0[j] else 1
        return bool(self._followed[j] > max(self.follow_c[j, side], 0.0))

    def _readmit(self, d, finite, instant, time, events) -> bool:
        """Re-admission: back within the warning band for a whole window, no detector firing
        (checked against the field where the others can predict it, else calm is enough).
        Whether any sensor came back."""
        self._watch_followed()
        due = ~self._active & finite & (self._run == 0) & (self._calm >= self._dwell)
        due[list(instant)] = False
        back = self._returning(due) if due.any() else due
        for j in np.flatnonzero(back):
            why = f"re-admitted: within ±{self._readmit_c()[j]:.3g} °C for {self._calm[j]} samples"
            shift = self._ref[j] - self._ref0[j]
            if self._jumps[j] and self._taken_as_measured(j):
                # a real step (the air's): the others followed it, so its reading is the
                # temperature; re-referenced, the model read the air stepped back for good
                side = 0 if shift >= 0 else 1
                self._ref[j] = self._ref0[j]
                d[j] += shift
                self._hist[:, j] += shift
                why = (f"re-admitted as measured: every other sensor's course turned with its "
                       f"{self._jumps[j]} jump(s), by {self._followed[j]:.3g} °C per sample at "
                       f"least (in training at most {self.follow_c[j, side]:.3g} at once); "
                       f"the jump(s) undone ({shift:+.3g} °C)")
            elif not self._predictable[j] and (self._jumps[j] > 1 or (
                    self._jumps[j] and abs(d[j] + shift - self._last_good[j])
                    < abs(d[j] - self._last_good[j]))):
                # a sensor no other predicts: its outage's jumps were re-referenced one by
                # one, which is right for a step (an offset that stays) and wrong for noise
                # (a loose contact: the reading returns, and a noisy step kept was an offset
                # for good: 6.7x the healthy error on T_amb).  Several jumps are noise or a
                # spike; of one, the reading (with it or without) closer to the value
                # before the outage is taken: this temperature cannot be seen to move
                self._ref[j] = self._ref0[j]
                d[j] += shift
                self._hist[:, j] += shift
                why += f"; its {self._jumps[j]} jump(s) undone: the reading returned ({shift:+.3g} °C)"
            self._set_state(j, OK, time, why, events)
            self._jumps[j] = 0
            self._followed[j] = np.nan
            self._active[j] = True
            self._by_field[j] = False
            self._explains[j] = False
            self._set_operator()
        return bool(back.any())

    def _returning(self, due: np.ndarray) -> np.ndarray:
        """Which of the ``due`` sensors come back: those that pass their own judgement in the
        set of the active sensors and every due one, the worst failing one left out until the
        rest pass.  Judged together, not one at a time: a sensor whose coupled partner is out
        too, or any sensor after a total dropout, has no set to pass in on its own."""
        trial = self._active | due
        while True:
            ok, worst = self._pass_once_back(trial)
            failing = due & trial & ~ok
            if not failing.any():
                return due & trial
            trial[int(np.argmax(np.where(failing, worst, -1.0)))] = False

    def _readmit_c(self) -> np.ndarray:
        """Each sensor's re-admission band (°C): ``READMIT`` of its warning band (the hysteresis of
        one out by its error), its whole warning band for one out only for a dropout: it had passed
        its judgement until its reading went missing, the band that kept it in (the half band kept a
        healthy lathe sensor whose error sits at 0.9 of its band out for an hour after one empty
        logger row: adaptive 1.14x fixed)."""
        lost = self._dropped & ~self._by_field & (self._jumps == 0)
        return np.where(lost, 1.0, READMIT) * self.warning_c

    def _pass_once_back(self, trial: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(passes, worst error)`` of the sensors of the set ``trial``: their leave-one-out
        error in it over the whole window within the re-admission band (not their error against
        a set that a coupled partner may have left blind to them).  A sensor the others in
        ``trial`` cannot predict passes where no other predicts it at all (calm is enough then)."""
        n = len(self.names)
        if trial.sum() < self.min_active_:
            return np.zeros(n, dtype=bool), np.full(n, np.inf)
        M, lev = self._operator(trial)
        blind = lev >= self.pod.max_leverage
        H = np.where(np.isfinite(self._hist), self._hist, 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            worst = np.abs((H - H[:, trial] @ M.T) / (1 - lev)).max(axis=0)
        worst[blind] = np.inf
        ok = np.where(blind, ~self._predictable, worst < self._readmit_c()) & trial
        # one out for explaining the others' errors is vouched for by them: back only if they
        # stay within the warning band with it in (calm alone let a drifting T_table flap)
        explains = trial & blind & self._explains
        if explains.any():
            judged = trial & ~blind
            ok[explains] = bool((worst[judged] < self.warning_c[judged]).all())
        return ok, worst
