"""The judgement of :class:`~.monitor.SensorMonitor`: drift exclusions by the self-prediction
errors, and the new thermal state.  Its evidence is the errors of the sensors ``_judging``: the
judged ones but those ``drift_warn_only`` (an ambient trained on one campaign, quiet94), whose
error is warned but neither blames them, nor vetoes, nor holds another's exclusion."""

from __future__ import annotations

import numpy as np

from .states import ALARM, NEW_STATE, OK, TRAINED, WARNING


class Judgement:
    """Mixin of :class:`~.monitor.SensorMonitor` (its state): which sensor the bands blame, or a new
    thermal state."""

    def _exclude_by_judgement(self, time, events) -> tuple[np.ndarray, np.ndarray]:
        """Judgement over the last ``confirm`` samples, worst first, redone after every
        exclusion; ``(level, error)`` of :meth:`_judge` after it."""
        level, err = self._judge()
        while (self.adaptive and (self._judging & (level >= self._field_level())).any()
               and self._active.sum() > self.min_active_):
            # a drift exclusion too: none in a new thermal state, and its field may follow it
            u = None if self.new_state and self._novel else self._explaining(level)
            if u is not None:
                out = np.flatnonzero(self._judging & (level >= self._field_level()))
                named = ", ".join(f"{self.names[i]} {err[i]:+.2g} °C" for i in out)
                self._exclude(u, f"drift: its reading explains the others' self-prediction errors "
                                 f"({named} over the last {self.confirm} samples)", time, events,
                              by_field=True)
                self._explains[u] = True
                self._since[u] = self._count
                level, err = self._judge()
                continue
            # the culprit is the largest self-prediction error of paper 002 (Eq. 7: the sensor
            # against the field fitted to all active sensors, itself included: |E|(1-h) of the
            # leave-one-out error E), among all judged sensors, in alarm or not.  Not the
            # standardised |E|/sqrt(1-h), which is the right pick for one faulty sensor but not
            # for a new source spread over several: its high-leverage sensors near the source
            # pull the fit, and a well-predicted sensor far away then looks worst (measured on a
            # column with more nodes than sensors: the far T_left1 went out first on 3 of 5 runs)
            z = np.where(self._judging, np.abs(np.nan_to_num(err)) * self._std ** 2, -1)
            j, resolves = self._lone_fault(int(np.argmax(z)), z, level, err)
            if j < 0 or self._drift_vetoed(j, level, err, time, events, resolves):
                break
            # a culprit within its own band is blamed for another's excursion only while that
            # grows: one that reached its offset and hovers is a regime (module excursion.py);
            # so is one beyond it by less than its readings' rounding moves its error, its memory
            # within that of the band already (mon83: trunnion 8342's healthy table at -0.59 °C
            # against 0.576, its error -0.35 / -0.58 as its partner's 0.1 K logger flipped,
            # 0.196 its bound, its memory -0.431, a share of its rise 1.26x the memory's)
            if (self.new_state and (level[j] < WARNING or self._within_rounding(j))
                    and self._excursion_hovers(level, err)):
                break
            self._exclude(j, f"drift: self-prediction error {err[j]:+.2g} °C over the last "
                             f"{self.confirm} samples", time, events, by_field=True)
            self._since[j] = self._count
            self._hid[j] = bool(level[j] < WARNING)   # it passed its own band (readmission.py)
            self._set_bands()
            # a sensor out of band that no other can predict once j is out cannot be
            # vouched for (two coupled sensors look alike to self-prediction): out too
            blind = self._active & ~self._observable & ~self.drift_warn_only & (z >= 0.7 * z[j])
            for i in np.flatnonzero(blind):
                if self._active.sum() > self.min_active_:
                    if self._drift_vetoed(i, *self._judge(), time, events):
                        break
                    self._exclude(i, f"drift: self-prediction error {err[i]:+.2g} °C and no other "
                                     f"sensor predicts it once {self.names[j]} is out", time, events,
                                  by_field=True)
                    self._since[i] = self._count
            else:
                level, err = self._judge()
                continue
            break
        level, err = self._judge()
        if self.new_state and self.adaptive:
            level, err = self._follow_field(level, err, time, events)
        elif self.new_state:
            self._name_state(level, err, time, events)
        return level, err

    # -- a new thermal state (module doc) ------------------------------------------------------
    def _drift_vetoed(self, j: int, level, err, time, events, resolves: bool | None = None) -> bool:
        """Whether the drift exclusion of ``j`` is refused as a new thermal state: one is
        declared, or with ``j`` out the other judged sensors are not all within their warning
        band (declared then; ``resolves``: :meth:`_resolves` of ``j``, where already known), or
        ``new_state_others`` of them are out of it with ``j`` in."""
        if not self.new_state:
            return False
        if self._novel:
            return True
        others = self._judging & (level >= WARNING)
        others[j] = False
        if not (self._resolves(j) if resolves is None else resolves):
            self._declare(f"with {self.names[j]} out the others stay out of band",
                          others | (np.arange(len(others)) == j), err, time, events)
            return True
        return int(others.sum()) >= self.new_state_others

    def _lone_fault(self, j: int, z: np.ndarray, level: np.ndarray,
                    err: np.ndarray) -> tuple[int, bool | None]:
        """``(sensor, whether with it out the others are within band)`` (None: not asked; sensor -1: none
        yet, mon86b): the single fault that explains the bands.  An exclusion explains them when, with
        the sensor out of the fit, every other judged sensor is within its warning band and, unless
        the sensor is out of band itself, every one out of band is still judged (a coupled pair out of
        band goes out together; a sensor within its band that leaves one out of band unjudged hides
        its error).  In order: ``j`` (paper 002's largest error); the sensor out of band (largest
        error first) that one fault explains, off the field the others make by more than any other
        sensor's error now (a fault's own deviation is the largest), and the largest standardised
        residual ``|E|·sqrt(1 - h)`` (the likelier single fault, as in :meth:`_explaining`; mon84:
        asked always, before only where ``j``'s exclusion explains the bands by leaving one out of
        them unjudged), whose exclusion leaves every judged sensor judged (mon84b); else ``j``, if it
        explains them at all, within its band not by leaving the likelier single fault out of band in
        and unjudged (mon85; a coupled pair: :meth:`_exclude_by_judgement` takes the partner out too).
        ``j``'s coupled neighbour can show the largest error (fl_thermal's t12 drifting, T_t14 then
        T_t15 picked, and the drift read as a new thermal state that never ended); and a lathe's
        healthy T_nc_x1_drive (-0.58 °C, 0.48 standardised), excluded for a drifting T_guidebush
        (+0.93, 0.51) whose leverage that raised past judging (0.71 -> 0.96), had hidden the drift,
        until a new thermal state did.  ``j`` within its band that explains the bands is not taken
        where the likelier single fault is out of band (mon86b): that one if its own exclusion
        explains them, else none yet (-1: nothing excluded, nothing declared); unless the
        excursion hovers (mon87): ``j`` then, which the regime check holds as before."""
        if not self.new_state or self._novel:
            return j, None
        out = self._judging & (level >= WARNING)
        size = np.abs(np.where(self._judging, np.nan_to_num(err), 0.0))
        # the likelier single fault: the largest standardised residual |E|·sqrt(1 - h), the
        # likelihood ratio's pick for one faulty sensor (a fault on k gives no other a larger
        # one: Cauchy-Schwarz on the projector I - H).  Asked of every lone fault, not only
        # where j hides: a column's T_left1 (leverage 0.82), beyond its band at an unseen
        # source's onset, was taken over T_right4 on a residual 0.17 °C amplified 5.5x by the
        # leave-one-out division, 0.35 standardised against T_right4's 0.37 (mon84)
        likelier = np.argmax(size * self._std)
        # j within its band is no fault where the likelier one is out of band (mon86b: a short-
        # trained column's healthy T_right3, -0.17 °C for a 0.40 band, 0.135 standardised,
        # taken for T_left1's 0.4068 against 0.4052, 0.190): that one, or nothing yet; unless
        # the excursion hovers (mon87: the regime check kept whoever gets the pick: j then, held
        # by it as on main, not the lathe's healthy T_toolholder1 hovering past its band).
        # A sensor out of band itself may leave its coupled partner out of band unjudged (the
        # partner follows it out); one within its band that does so hides, not explains
        doubted = self._resolves(j, out if level[j] < WARNING else None)
        if doubted and not (level[j] < WARNING and out[likelier]
                            and not self._excursion_hovers(level, err)):
            return j, True
        # j explains the bands only by hiding a sensor out of them (j out of band itself: the
        # same question as above, answered no); not where the one it leaves in unjudged (not
        # its blind partner, z < 0.7 z[j]) is the likelier single fault (mon85: s8774's healthy
        # T_edge1 hid the frozen T_front1 7 rows; fl_thermal's T_t14 hiding the healthy T_t9,
        # less likely than itself, is let stand)
        hidden = out & (z < 0.7 * z[j]) & (np.arange(len(z)) == likelier)
        hides = bool(level[j] < WARNING) and self._resolves(j, hidden)
        # a lone fault is tested on every other judged sensor: one whose exclusion leaves a
        # judged sensor unjudged (its coupled partner past max_leverage) takes that partner
        # out with it on no evidence of the partner's own (mon84b: a column's T_left1, the
        # likelier fault at an unseen source's onset, blinded T_left3 within its band)
        for k in np.argsort(-z):
            if (k != j and z[k] >= 0 and level[k] >= WARNING and likelier == k
                    and self._resolves(int(k), self._judging,
                                       alone=float(np.max(np.delete(size, k), initial=0.0)))):
                return int(k), True
        return (-1, None) if doubted else (j, hides)

    def _resolves(self, j: int, seen: np.ndarray | None = None,
                  alone: float | None = None) -> bool:
        """With ``j`` out of the fit, every other judged sensor's leave-one-out error over the
        last ``confirm`` samples (their mean) within its warning band (``seen``: and each of
        these sensors but ``j`` still judged; ``alone``: the largest error of the others now, and
        ``j``'s own error against the others' field at least that, as a lone fault's)."""
        trial = self._active.copy()
        trial[j] = False
        if trial.sum() < self.min_active_:
            return True
        M, lev = self._operator(trial)
        judged = trial & (lev < self.pod.max_leverage) & ~self.drift_warn_only
        if seen is not None and (seen & trial & ~judged).any():
            return False
        rows = self._hist[self._recent[self._pos, :min(self._count, self.confirm)]]
        X = np.where(np.isfinite(rows), rows, 0.0)
        E = ((X[:, judged] - X[:, trial] @ M[judged].T) / (1 - lev[judged])).mean(axis=0)
        if not (np.abs(E) < self._warn[judged]).all():
            return False
        # (alone: and j itself off the others' field by that much at least, as a fault is)
        return alone is None or bool(abs((X[:, j] - X[:, trial] @ M[j]).mean()) >= alone)

    def _follow_field(self, level, err, time, events) -> tuple[np.ndarray, np.ndarray]:
        """A drift-excluded sensor whose exclusion the field followed (``new_state_others``
        other judged sensors out of band within a window of it) comes back, as a new state;
        the new state ends after a window with every judged sensor within band.
        ``(level, error)`` after it."""
        leaving = self._judging & (level >= WARNING)
        out = int(leaving.sum())
        for j in np.flatnonzero(self._since >= 0):
            if self._active[j] or self._count - self._since[j] > self.window:
                self._since[j] = -1
            elif out >= self.new_state_others:
                self._since[j] = -1
                self._active[j], self._by_field[j], self._dwell[j] = True, False, self.window
                self._explains[j] = False
                self._set_state(j, OK, time, f"re-admitted: {out} other sensors left the band "
                                "after its exclusion (the field followed it: a new thermal state)",
                                events)
                self._set_operator()
                leaving[j] = True
                self._declare(f"the field followed {self.names[j]}", leaving, err, time, events)
                level, err = self._judge()
                leaving = self._judging & (level >= WARNING)
                out = int(leaving.sum())
        self._end_when_calm(out, time, events)
        return level, err

    def _name_state(self, level, err, time, events) -> None:
        """Judge only (``adaptive=False``): the new thermal state the adaptive monitor would
        declare where it would exclude a sensor for drift (with the largest error's sensor, or
        a lone fault, out, the others stay out of band), and its end; nothing is excluded
        either way.  Without it, a source training never saw read as several sensors in
        alarm with no word of why."""
        if not self._novel and (self._judging & (level >= self._field_level())).any():
            z = np.where(self._judging, np.abs(np.nan_to_num(err)) * self._std ** 2, -1)
            j, resolves = self._lone_fault(int(np.argmax(z)), z, level, err)
            if j >= 0:
                self._drift_vetoed(j, level, err, time, events, resolves)
        self._end_when_calm(int((self._judging & (level >= WARNING)).sum()), time, events)

    def _end_when_calm(self, out: int, time, events) -> None:
        """Count the samples with no judged sensor out of band (``out``: how many are); the
        new state ends after a window of them."""
        self._calm_field = 0 if out else self._calm_field + 1
        if self._novel and self._calm_field >= self.window:
            self._novel = False
            again = "drift exclusions again" if self.adaptive else "drift judged again"
            events.append({"time": float(time), "sensor": None, "from": NEW_STATE,
                           "to": TRAINED, "sensors": [],
                           "reason": f"every judged sensor within its warning band for "
                                     f"{self.window} samples: {again}"})

    def _declare(self, why: str, involved: np.ndarray, err, time, events) -> None:
        """A new thermal state (one event while it lasts), ``involved`` the sensors out of band
        and the one whose exclusion did not explain them."""
        self._calm_field = 0
        if self._novel:
            return
        self._novel = True
        out = np.flatnonzero(involved)
        named = ", ".join(f"{self.names[i]} {err[i]:+.2g} °C" for i in out)
        events.append({"time": float(time), "sensor": None, "from": TRAINED, "to": NEW_STATE,
                       "sensors": [self.names[i] for i in out],
                       "reason": f"new thermal state: several sensors leave the field together "
                                 f"({why}: {named}); no exclusion for drift until they are back"})

    def _explaining(self, level: np.ndarray) -> int | None:
        """An active sensor no other predicts whose reading explains the judged sensors out of
        band: with it out of the fit, every judged sensor within the band and those out of it
        still judged.  Such a sensor still weighs a little in the others' predictions (its
        leverage is below 1: T_table at 0.998 weighs 0.054 in T_xdrive's), so its drift, unseen
        by itself, leaks onto them; the culprit rule below, blind to it, then took out a healthy
        sensor (T_bed_right, which only hid T_xdrive's error).  Of several, the best
        single-fault explanation: the largest standardised residual.  ``None`` if none does."""
        out = self._judging & (level >= self._field_level())
        band = self._warn if self._field_level() == WARNING else self._alarm
        rows = self._hist[self._recent[self._pos, :min(self._count, self.confirm)]]
        X = np.where(np.isfinite(rows), rows, 0.0)
        # every active sensor's residual in the current fit, standardised: the likelihood ratio
        # of a fault on it alone; a sensor no other predicts is blamed only as the best of all
        r = (X - X[:, self._active] @ self._M.T).mean(axis=0)
        z = np.where(self._active, np.abs(r) / np.sqrt(np.maximum(1 - self._lev, 1e-12)), -1.0)
        best, best_z = None, float(np.max(np.where(self._judging, z, -1.0)))
        for u in np.flatnonzero(self._active & ~self._observable & ~self.drift_warn_only
                                & (z > best_z)):
            trial = self._active.copy()
            trial[u] = False
            if trial.sum() < self.min_active_:
                continue
            M, lev = self._operator(trial)
            judged = trial & (lev < self.pod.max_leverage) & ~self.drift_warn_only
            if (out & ~judged).any():
                continue
            E = (X[:, judged] - X[:, trial] @ M[judged].T) / (1 - lev[judged])
            if (np.abs(E).min(axis=0) >= band[judged]).any():
                continue
            if z[u] > best_z:
                best, best_z = int(u), float(z[u])
        return best

    def _within_rounding(self, j: int) -> bool:
        """Whether sensor ``j``'s smallest error over the last ``confirm`` samples is beyond the
        band that excludes by less than ``rounding_c`` (the most the readings' rounding to their
        resolution moves its error) and the error of the field's memory (module excursion.py)
        was within that of the band already, on the same side: an offset standing within the
        logger's last digit of the band, a crossing that digit may make alone.  (Not the memory
        too, the turret of lathe 8513, healthy, that a drifting coolant's leak carried from
        -0.42 to -0.58 °C in 20 min, was held 23 min: mon83's first rule.)"""
        k = min(self._count, self.confirm)
        last = self._err[self._recent[self._pos, :k], j]
        band = (self._warn if self._field_level() == WARNING else self._alarm)[j]
        if not self._slow_ok or not float(np.abs(last).min()) < band + self.rounding_c[j]:
            return False
        past = (self._slow[j] - self._M[j] @ self._slow[self._active]) * self._scale[j]
        return bool(past * np.sign(last.sum()) >= band - self.rounding_c[j])

    def _field_level(self) -> int:
        """Band whose crossing excludes a sensor by its self-prediction error: ``exclude_at``
        while no sensor is out by it, the alarm band while one is.  One sensor out of band is
        what a single fault looks like, and excluding it early spares the correction; sensors
        still leaving the band once the worst is out mean a field that training never saw (paper
        002: a new source), which self-prediction cannot pin on a sensor -- the paper excludes
        a sensor then only beyond its tolerance (the alarm band)."""
        return ALARM if (self._by_field & ~self._active).any() else self.exclude_level
