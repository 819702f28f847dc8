"""Re-admission of an excluded sensor in :class:`~.monitor.SensorMonitor` (hysteresis, judged together).

A sensor no other predicts is judged by no band of its own; what its reading does to the others'
field is its *leak*: of every sensor judged with it and without it, the change of its
leave-one-out error, as a share of its warning band.  Back only where its leak is within half
their band, or, out for explaining their errors, where the leak hovers against the field's rise
(no larger a share of it than the slow memory's leak of its rise, within ``EXCURSION_GROWTH``, as
:mod:`.excursion` judges an excursion): a drift's leak grows where the field does not (mon82)."""

from __future__ import annotations

import numpy as np

from .states import EXCURSION_GROWTH, OK, READMIT


class Readmission:
    """Mixin of :class:`~.monitor.SensorMonitor` (its state): who comes back."""

    def _readmit(self, d, finite, instant, time, events) -> bool:
        """Re-admission: back within the warning band for a whole window, no detector firing
        (checked against the field where the others can predict it, else calm is enough).
        Whether any sensor came back."""
        due = ~self._active & finite & (self._run == 0) & (self._calm >= self._dwell)
        due[list(instant)] = False
        back = self._returning(due) if due.any() else due
        for j in np.flatnonzero(back):
            why = self._why_back(j)
            shift = self._ref[j] - self._ref0[j]
            if not self._predictable[j] and (self._jumps[j] > 1 or (
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
            self._active[j] = True
            self._by_field[j] = False
            self._explains[j] = False
            self._set_operator()
        return bool(back.any())

    def _why_back(self, j: int) -> str:
        """The re-admission's reason, as it was judged: a sensor no other predicts is judged by
        no band (calm, or the others' bands where it was out for explaining their errors:
        :meth:`_pass_once_back`), and its reason said "within ±10.4 °C" (stranger80: a screw
        nut's thermocouple after a dropout, its warning band a figure nothing compared)."""
        calm = self._calm[j]
        if self._predictable[j]:
            return f"re-admitted: within ±{self._readmit_c()[j]:.3g} °C for {calm} samples"
        if self._explains[j]:
            return (f"re-admitted: the others within their warning bands with it in for {calm} "
                    "samples (no other sensor predicts it)")
        return (f"re-admitted: no detector fired for {calm} samples (no other sensor predicts "
                "it: no band judges its reading)")

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
        return np.where(self._lost(), 1.0, READMIT) * self.warning_c

    def _lost(self) -> np.ndarray:
        """The sensors out only for a dropout (their last detector a missing reading)."""
        return self._dropped & ~self._by_field & (self._jumps == 0)

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
        # one no other predicts, out for anything but a dropout: its leak onto the others judged
        # too (the Hydraulik Tank drifting 1 K/h came back by the band it had left by and went
        # out again 40 s later; a gearbox out of range came back 14.8 K off on calm alone)
        for u in np.flatnonzero(ok & ~self._active & ~self._predictable & ~self._lost()):
            ok[u] = self._leak_passes(u, trial, H, M, lev)
        return ok, worst

    def _leak_passes(self, u: int, trial: np.ndarray, H: np.ndarray, M: np.ndarray,
                     lev: np.ndarray) -> bool:
        """Whether the leak of ``u`` onto the sensors judged in ``trial`` with it and without it
        lets it back (module doc): within ``READMIT`` of their bands over the window, or, out for
        explaining them, its window's mean share of the field's rise (the others' RMS referenced
        reading) within ``EXCURSION_GROWTH`` of the slow memory's, for every judged sensor.  True
        where too few sensors are left without ``u`` to judge (the test it passed stands)."""
        rest = trial.copy()
        rest[u] = False
        if rest.sum() < self.min_active_:
            return True
        M2, lev2 = self._operator(rest)
        both = rest & (lev < self.pod.max_leverage) & (lev2 < self.pod.max_leverage)
        if not both.any():
            return True

        def leak(X: np.ndarray) -> np.ndarray:
            with np.errstate(divide="ignore", invalid="ignore"):
                e_in = (X[:, both] - X[:, trial] @ M[both].T) / (1 - lev[both])
                e_out = (X[:, both] - X[:, rest] @ M2[both].T) / (1 - lev2[both])
            return np.abs(e_in - e_out) / self.warning_c[both]

        now = leak(H)
        if now.max() < READMIT:
            return True
        if not (self._explains[u] and self._slow_ok and np.isfinite(self._slow_t)):
            return False     # out of range or for a jump: an offset hovers too (vtl78's 14.8 K)
        then = leak(self._slow[None])[0]
        rise_now = np.sqrt(np.mean(H[:, rest] ** 2))
        rise_then = np.sqrt(np.mean(self._slow[rest] ** 2))
        return bool(np.all(now.mean(axis=0) * rise_then <= EXCURSION_GROWTH * then * rise_now))
