"""Re-admission of an excluded sensor in :class:`~.monitor.SensorMonitor` (hysteresis, judged together).

A sensor no other predicts is judged by no band of its own.  Out because its reading left the
training range, it is back only where its *leak* is within ``READMIT`` of the others' bands: of
every sensor judged with it and without it, the change of its leave-one-out error, as a share of
its warning band (a gearbox back inside the range's margin 14.8 K off had come back on calm
alone).  Out for anything else it is judged as before (mon81's and mon82's leak rules for every
such sensor held a healthy gantry's ``Gabelkopf`` stale, or let a drifting tank flap: mon82b).

Out for a freeze alone (no other detector fired on it since), a sensor is back once ``THAW``
readings in a row are off the value it held when it went out (freeze84): the freeze's own
evidence is gone, and the judgement takes it from there as an active sensor, the new-state veto
with it.  Its return judged against the field kept a healthy column sensor out for 496 rows
where an unseen heat source had moved the field off it (bench_freeze83b: E_Y 12.356 µm fixed,
20.102 served).  A held run broken by one sample that returns to the held value is still a
hold: a logger stuck but for one step every few samples, taken back on its first changed
reading, stayed in, stuck, between the freeze's runs (E_Y x1.6-2.9, bench_freeze83c).

One out by the field's judgement that no sensor left in predicts comes back, after its calm
window, where a partner out of the set is frozen by the rule for a sensor no other predicts and
would predict it (mon88): the error the pair shared is the frozen one's (cr9031's healthy
``T_nc_cabinet`` had stayed out behind a frozen ``T_amb`` to the campaign's end)."""

from __future__ import annotations

import numpy as np

from .states import OK, READMIT, THAW


class Readmission:
    """Mixin of :class:`~.monitor.SensorMonitor` (its state): who comes back."""

    def _readmit(self, d, finite, instant, time, events) -> bool:
        """Re-admission: back within the warning band for a whole window, no detector firing
        (checked against the field where the others can predict it, else calm is enough).
        Whether any sensor came back."""
        thawed = self._thawed(finite, instant, time, events)
        due = ~self._active & finite & (self._run == 0) & (self._calm >= self._dwell)
        due[list(instant)] = False
        back = self._returning(due) if due.any() else due
        band = self._readmit_c(self._active | back | self._hid) if back.any() else None
        blind = (self._operator(self._active | back)[1] >= self.pod.max_leverage) if back.any() else None
        for j in np.flatnonzero(back):
            why = self._why_back(j, band, bool(blind[j]))
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
            self._by_field[j] = self._froze[j] = False
            self._explains[j] = False
            self._ranged[j] = False
            self._set_operator()
        return bool(back.any()) or thawed

    def _thawed(self, finite, instant, time, events) -> bool:
        """Those out for a freeze alone, ``THAW`` readings in a row off the value they held,
        back at once (module doc)."""
        back = self._froze & ~self._active & finite & (self._off >= THAW)
        back[list(instant)] = False
        for j in np.flatnonzero(back):
            self._set_state(j, OK, time, f"re-admitted: {self._off[j]} readings in a row off "
                            "the value it held when frozen", events)
            self._active[j] = True
            self._froze[j] = self._explains[j] = self._ranged[j] = False
        if back.any():
            self._set_operator()
        return bool(back.any())

    def _why_back(self, j: int, band: np.ndarray | None = None, blind: bool = False) -> str:
        """The re-admission's reason, as it was judged: a sensor no other predicts is judged by
        no band (calm, or the others' bands where it was out for explaining their errors:
        :meth:`_pass_once_back`), and its reason said "within ±10.4 °C" (stranger80: a screw
        nut's thermocouple after a dropout, its warning band a figure nothing compared)."""
        calm = self._calm[j]
        if self._predictable[j] and blind:    # (mon88: _blind_for_frozen)
            return (f"re-admitted: no detector fired for {calm} samples; the others in do not "
                    "predict it without a partner that is out frozen, whose error it was")
        if self._predictable[j]:
            band = self._readmit_c() if band is None else band
            return f"re-admitted: within ±{band[j]:.3g} °C for {calm} samples"
        if self._explains[j]:
            return (f"re-admitted: the others within their warning bands with it in for {calm} "
                    "samples (no other sensor predicts it)")
        if self._ranged[j]:
            return (f"re-admitted: no detector fired for {calm} samples and its leak onto the "
                    f"others within {READMIT:g} of their warning bands (no other sensor predicts it)")
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

    def _readmit_c(self, trial: np.ndarray | None = None, warn=None) -> np.ndarray:
        """Each sensor's re-admission band (°C): ``READMIT`` of its warning band (the hysteresis of
        one out by its error), its whole warning band for one out only for a dropout: it had passed
        its judgement until its reading went missing, the band that kept it in (the half band kept a
        healthy lathe sensor whose error sits at 0.9 of its band out for an hour after one empty
        logger row: adaptive 1.14x fixed).  Its whole band too for a culprit taken out within it
        (mon85b): it passed its own judgement, out for another's error it hid (a drift pulling
        its field), and it passes again once that sensor is out; the half band kept fl_thermal's
        healthy ``T_t14`` out to the record's end, its error without the drifting ``T_t12`` (its
        partner: leverage 0.50 -> 0.73) at 0.83 of its band on the clean record too.  The warning
        band is that of the set ``trial`` it is judged in (its culprits out within band counted in;
        ``None``: the active set's; ``warn``: that band, when at hand), mon86."""
        lost = self._dropped & ~self._by_field & (self._jumps == 0)
        return np.where(lost | self._hid, 1.0, READMIT) * (
            warn if warn is not None else self._warn if trial is None
            else self._bands_of(trial | self._hid)[0])

    def _pass_once_back(self, trial: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(passes, worst error)`` of the sensors of the set ``trial``: their leave-one-out
        error in it over the whole window within the re-admission band (not their error against
        a set that a coupled partner may have left blind to them).  A sensor the others in
        ``trial`` cannot predict passes where no other predicts it at all (calm is enough then)."""
        n = len(self.names)
        if trial.sum() < self.min_active_:
            return np.zeros(n, dtype=bool), np.full(n, np.inf)
        M, lev = self._operator(trial)
        bands = trial | self._hid        # a culprit out within its band counts in (_set_bands)
        warn = self._bands_of(bands, *((M, lev[trial]) if (bands == trial).all() else ()))[0]
        blind = lev >= self.pod.max_leverage
        H = np.where(np.isfinite(self._hist), self._hist, 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            worst = np.abs((H - H[:, trial] @ M.T) / (1 - lev)).max(axis=0)
        worst[blind] = np.inf
        ok = np.where(blind, ~self._predictable, worst < self._readmit_c(warn=warn)) & trial
        # one out for explaining the others' errors is vouched for by them: back only if they
        # stay within the warning band with it in (calm alone let a drifting T_table flap)
        explains = trial & blind & self._explains
        if explains.any():
            judged = trial & ~blind
            ok[explains] = bool((worst[judged] < warn[judged]).all())
        # one out by the field's judgement, blind here only for want of a partner that is out
        # frozen by its own evidence: what it was blamed for is that partner's (mon88)
        for u in np.flatnonzero(trial & blind & self._by_field & ~self._explains & ~self._active):
            ok[u] = self._blind_for_frozen(u, trial)
        # one no other predicts, out of range: calm is no evidence its reading is true again
        for u in np.flatnonzero(ok & ~self._active & ~self._predictable & self._ranged):
            ok[u] = self._leak_passes(u, trial, H, M, lev)
        return ok, worst

    def _blind_for_frozen(self, u: int, trial: np.ndarray) -> bool:
        """Whether ``u``, no other in ``trial`` predicting it, would be predicted with a sensor
        out of ``trial`` that is frozen by the rule for a sensor no other predicts (its reading
        constant longer than ``_blind_run``: :meth:`~.faults.InstantFaults._frozen`).

        ``u`` was taken out by the field's judgement (as the culprit, or as a blind partner) for
        an error its coupled partner's fault may make alike; with the partner out too, ``u`` is
        judged by nothing, and a sensor the others predict with every sensor in never passes
        blind (:meth:`_pass_once_back`): cr9031's
        healthy ``T_nc_cabinet`` (-0.35 °C in its 0.40 band), taken for a frozen ``T_amb``
        (+0.43 °C, constant for 16 samples, the field 0.39 °C on: short of the freeze rule's
        0.40) and out to the campaign's end while ``T_amb`` read the same value 137 samples.
        The partner's own freeze clears it; the partner comes back as before (judged with it
        once its reading moves)."""
        frozen = ~trial & ~self._active & (self._run > self._blind_run)
        for k in np.flatnonzero(frozen):
            with_k = trial.copy()
            with_k[k] = True
            if self._operator(with_k)[1][u] < self.pod.max_leverage:
                return True
        return False

    def _leak_passes(self, u: int, trial: np.ndarray, H: np.ndarray, M: np.ndarray,
                     lev: np.ndarray) -> bool:
        """Whether the leak of ``u`` onto the sensors judged in ``trial`` with it and without it
        (module doc) is within ``READMIT`` of their bands on every sample of the window ``H``.
        True where too few sensors are left without ``u`` to judge (the test it passed stands)."""
        rest = trial.copy()
        rest[u] = False
        if rest.sum() < self.min_active_:
            return True
        M2, lev2 = self._operator(rest)
        both = rest & (lev < self.pod.max_leverage) & (lev2 < self.pod.max_leverage)
        if not both.any():
            return True
        with np.errstate(divide="ignore", invalid="ignore"):
            e_in = (H[:, both] - H[:, trial] @ M[both].T) / (1 - lev[both])
            e_out = (H[:, both] - H[:, rest] @ M2[both].T) / (1 - lev2[both])
        return bool((np.abs(e_in - e_out) / self.warning_c[both]).max() < READMIT)
