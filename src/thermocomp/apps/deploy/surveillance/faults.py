"""The instant detectors of :class:`~.monitor.SensorMonitor`: dropout, range, jump, common step, freeze."""

from __future__ import annotations

import numpy as np

from .states import COMMON_MIN, COMMON_SPREAD, EXCHANGED, OK, STATES


class InstantFaults:
    """Mixin of :class:`~.monitor.SensorMonitor` (its state): one sample's instant faults."""

    def _hotter(self, x: np.ndarray, d: np.ndarray, rng: np.ndarray) -> np.ndarray:
        """Of the active sensors out of range (``rng``), those whose reading is a machine hotter
        (or colder) than training, not a fault: the active sensors within range predict it
        beyond the same training edge by more than its warning band (the prediction's own error
        scale), and the reading is nearer that prediction than half its distance from the edge.
        A spike, a unit change, a stuck or drifting sensor leave the others' prediction where
        the healthy field is: out of range.  Predicted from the sensors within range only, so
        that one faulty reading out of range does not move the prediction of another.
        (long4253's T_motor at twice the training speed, 10-19 °C above its training maximum,
        the others predicting 3.5 °C off it on average, had been held 9.5 °C below the reading.)"""
        kept = np.zeros(len(x), dtype=bool)
        inside = self._active & ~rng & np.isfinite(d)
        if inside.sum() < self.min_active_:
            return kept
        M, _ = self._operator(inside)
        cand = self._active & rng & np.isfinite(x)
        p = (x - d)[cand] + M[cand] @ d[inside]     # absolute °C, from the sensors within range
        up = x[cand] > self.hi_c[cand]
        edge = np.where(up, self.hi_c[cand], self.lo_c[cand])
        beyond = np.where(up, p - edge, edge - p) > self.warning_c[cand]
        kept[cand] = beyond & (np.abs(x[cand] - p) < 0.5 * np.abs(x[cand] - edge))
        return kept

    def _reference_glitch(self, d, step, big, pos, time, events) -> tuple[np.ndarray, np.ndarray]:
        """A jump right after the reference sample: the reference is the glitch (or the sensor
        took an offset at once: the same thing to a model of changes since the start), so the
        sensor is re-referenced and stays in.  ``(step, big)`` after it."""
        for j in np.flatnonzero(big):
            self._ref[j] += step[j]
            d[j] = self._hist[pos, j] = 0.0
            events.append({"time": float(time), "sensor": self.names[j], "from": STATES[self._state[j]],
                           "to": "re-referenced", "reason": f"reference glitch: {-step[j]:+.3g} °C "
                           "at the reference sample against the next one; re-referenced"})
        step = d - self._prev
        return step, np.abs(step) > self._jump_lim

    def _common_step(self, d, step, big, pos, time, events) -> tuple[np.ndarray, np.ndarray]:
        """A one-sample step shared by most active sensors, of about the same size: a fault of
        the logger (its reference, a shared supply), not of the machine -- a real air step
        moves the air alone at once, the structure lags.  Every active sensor that took it is
        re-referenced by its own step and stays in (one by one, each jump was judged against the
        others' prediction, which had taken the step too: 11 of 14 excluded on long_record 4253 at
        +2 K, too few left to rebuild the field, none back for 24 h).  A jump off the common step
        is judged as before.  ``(step, big)`` after it."""
        common = float(np.median(step[big])) if big.sum() >= COMMON_MIN else 0.0
        ratio = step / common if common else np.zeros_like(step)
        took = self._active & (ratio >= 1 / COMMON_SPREAD) & (ratio <= COMMON_SPREAD)
        jumped = took & big
        if jumped.sum() < COMMON_MIN or 2 * took.sum() <= (self._active & np.isfinite(d)).sum():
            return step, big
        for j in np.flatnonzero(took):
            self._ref[j] += step[j]
            d[j] -= step[j]
            self._hist[pos, j] = d[j]
            events.append({"time": float(time), "sensor": self.names[j], "from": STATES[self._state[j]],
                           "to": "re-referenced", "reason": f"common step: {step[j]:+.3g} °C in one "
                           f"sample on {int(took.sum())} sensors at once (median {common:+.3g} °C); "
                           "re-referenced"})
        step = np.where(took, 0.0, step)
        return step, big & ~took

    def _bent(self, d, step, big, gone, pos, time, events) -> tuple[np.ndarray, np.ndarray]:
        """A step of a sensor no other predicts, in, that departs from its own last step by more
        than its bound (``jump_factor`` x the largest such departure in training): a fault of the
        sensor (a contact, a recalibration), not heat -- a motor warms along a ramp whose steps
        change little from one sample to the next.  Its one-sample limit is 3 x its largest
        training step, taken while it warmed fastest (swiss's spindle motor: 0.73 °C, so a +2 °C
        step was read as heat, audit89); its step's change is far tighter (0.39 °C).  It is
        re-referenced by the departure, its step taken as its last one, and stays in: nobody
        predicts it, so held out it would be read at its last value and its heating meanwhile
        kept as an offset on its return (cr9431's spindle motor +1.5 °C: 8 % from the truth).
        It is kept in the jump bookkeeping (step93b): the reference before it is ``_ref0`` and it
        counts as a jump, so a second such step before the sensor is next admitted is a jump
        (re-referenced, out) and the return undoes both, as a blind sensor's jumps are undone
        (:meth:`~.readmission.Readmission._readmit`): a noise burst's steps, re-referenced one by
        one and kept, had left yearround's ``T_amb`` 16 °C off.  A sensor out, or back this
        sample, has no last step (``_last_step`` NaN): a return's undo is no step of its own.
        ``gone``: missing or beyond range (not judged); ``d``, the window's row ``pos``, changed in
        place.  ``(step, big)`` after it."""
        off = step - self._last_step              # NaN (no last step) compares False
        bent = ~big & ~gone & (self._gap == 1) & (np.abs(off) > self._bend_lim)
        again = bent & (self._jumps > 0)          # a second one since it was admitted: a jump
        big, bent = big | again, bent & ~again
        for j in np.flatnonzero(bent):
            self._ref0[j] = self._ref[j]
            self._jumps[j] = 1
            self._ref[j] += off[j]
            d[j] = self._hist[pos, j] = d[j] - off[j]
            events.append({"time": float(time), "sensor": self.names[j], "from": STATES[self._state[j]],
                           "to": "re-referenced", "reason": f"step off its own: {step[j]:+.3g} °C in "
                           f"one sample after {self._last_step[j]:+.3g} °C (no other sensor predicts "
                           f"it; largest change of its step in training {self.max_bend_c[j]:.3g} "
                           "°C); re-referenced"})
        return np.where(bent, step - off, step), big

    def _spike_back(self, x, d, big, pos, time, events) -> np.ndarray:
        """A sensor the others predict, out for a jump, whose next jump brings its reading back to
        the field on its reference before the first (``_ref0``) within a window of its last one:
        a spike (a loose contact, EMI), not an offset.  Its reference is put back and it is in
        again at once; only the samples it spent off the field were replaced by the field's
        prediction.  Re-referenced by the return's whole step instead (judged by no one while
        out), it kept the others' one-sample prediction noise as an offset for good and waited
        out a window: lr9211's ``T_head_left`` (a -3.85 °C sample, back 0.02 °C off the field)
        kept +0.12 °C for the record's last 4.7 h, the deployed lag models 16-23 % worse than
        run's.  A reading back only within the re-admission band of the set it returns to
        counts: a step that stays is re-referenced as before.  Called where every reading of the
        sample is there and in range; ``big`` (the jumping sensors) less those back after it;
        ``d``, the window's row ``pos``, changed in place."""
        cand = (big & ~self._active & self._predictable & (self._jumps > 0) & ~self._by_field
                & ~self._froze & ~self._dropped & (self._calm < self.window))
        if not cand.any() or not self._rebuilds or (big & self._active).any():
            return big   # no field to read the return against (a sensor it leans on jumps too)
        pred, _ = self._errors(d)
        for j in np.flatnonzero(cand):
            trial = self._active.copy()
            trial[j] = True
            if self._operator(trial)[1][j] >= self.pod.max_leverage:
                continue
            back = x[j] - self._ref0[j]
            band = self._readmit_c(trial)[j]
            if not abs(back - pred[j]) < band:
                continue
            shift = self._ref[j] - self._ref0[j]
            self._ref[j] = self._ref0[j]
            d[j] = self._hist[pos, j] = back
            big[j] = False
            self._jumps[j] = 0
            self._active[j] = True
            self._set_state(j, OK, time, f"re-admitted: a spike, its reading back {back - pred[j]:+.3g} °C "
                            f"off the field (within ±{band:.3g} °C) on its reference before the "
                            f"jump, {self._calm[j] + 1} sample(s) after it; the jump undone "
                            f"({-shift:+.3g} °C)", events)
            self._set_operator()
            pred, _ = self._errors(d)
        return big

    def _reference_late(self, x, d, e, pred, finite, rng, pos) -> None:
        """The first value of a sensor missing at the start (or out of range there): referenced
        to agree with the field where the others predict it, else to go on from the value the
        model was given meanwhile (its reference was NaN, so it stayed out for good)."""
        late = np.isfinite(x) & ~np.isfinite(self._ref) & ~rng
        for j in np.flatnonzero(late):
            by_field = bool(self._predictable[j] and np.isfinite(pred[j]))
            value = pred[j] if by_field else self._clean[j]
            self._ref[j] = x[j] - value
            d[j] = self._hist[pos, j] = value
            e[j] = 0.0 if by_field else np.nan
            finite[j] = True

    def _check_freeze(self, x, d, e, pred, same, instant, time, events) -> None:
        """Freeze: constant while the field (its prediction from the others) moves."""
        if not same.any():
            return
        other = d - np.where(np.isfinite(e), e, d - pred)
        start = same & (self._run == 1)
        self._run_pred[start] = other[start]
        moved = np.abs(other - self._run_pred)
        for j in np.flatnonzero(self._frozen(same, self._run, moved)):
            if j in instant:
                continue
            by_field = self._observable[j] and moved[j] >= self._warn[j]
            why = (f"freeze: {x[j]:.4g} °C for {self._run[j] + 1} samples while the field "
                   f"moved {moved[j]:.2g} °C" if by_field else
                   f"freeze: {x[j]:.4g} °C for {self._run[j] + 1} samples (longest constant "
                   f"run in training {self.longest_run[j]:.0f}"
                   + ("; its noise spans its resolution)" if self.dithered[j] else ")"))
            instant[j] = why
            if self._active[j]:
                self._exclude(j, why, time, events)
                # its return: readmission.py's _thawed, on readings off the value it held
                self._froze[j], self._held[j], self._off[j] = self.adaptive, d[j], 0
                # (mon105c) its held value read while its own past says it stood still; none
                # where the field moved past its band while it held (the field contradicts it)
                self._hold_to[j] = -np.inf if by_field or not self.adaptive else self._hold_until(j)

    def _check_stepped(self, e, instant, time, events) -> None:
        """A self-prediction error that steps past the alarm band in one sample."""
        de = e - self._prev_e
        stepped = self._judged & (np.abs(e) >= self._alarm) & (np.abs(de) >= self._alarm)
        if not stepped.any():
            return
        for j in np.flatnonzero(stepped):
            instant.setdefault(j, f"jump: self-prediction error stepped {de[j]:+.3g} °C in one sample")
        if self.adaptive:
            # the culprit by its standardised *step*: a step fault on j steps every other
            # error by less (the bound below), while the errors' levels carry each sensor's
            # own model error (a coupled partner's may exceed the faulty one's)
            j = int(np.argmax(np.where(stepped, np.abs(de) * self._std, -1)))
            self._exclude(j, instant[j], time, events, by_field=True)

    def _frozen(self, same: np.ndarray, run: np.ndarray, moved: np.ndarray) -> np.ndarray:
        """The freeze rule (module doc), for :meth:`_fast` and :meth:`_update` alike: ``same``
        unchanged readings, ``run`` their constant-run lengths, ``moved`` the field's change;
        a dithered reading (mon97) by its run alone, as one no other predicts."""
        return same & ((self._observable & (moved >= self._warn) & (run >= self._seen_run))
                       | (~self._observable & (run > self._blind_run)) | (run > self._dither_run))

    def _instant(self, x, d, step, finite, rng, big) -> dict[int, str]:
        """Reasons of the instant detectors that fire (dropout, out of range, jump)."""
        out: dict[int, str] = {}
        if big.sum() > 1:      # several at once: each as the sensors that did not jump see it
            expected = self._unjumped_change(d, finite, rng, big)
        elif big.any():   # the change of a jumping sensor as the other sensors see it
            pred, e = self._errors(np.where(finite, d, 0.0))
            other = np.where(self._judged, d - e, np.nan)
            expected = other - self._prev_other
        for j in np.flatnonzero(~finite):
            out[j] = "dropout: no finite value"
        for j in np.flatnonzero(rng):
            out[j] = (f"out of range: {x[j]:.4g} °C outside the training range "
                      f"[{self.lo_c[j]:.3g}, {self.hi_c[j]:.3g}] ± {self.range_margin_c:g} °C")
        for j in np.flatnonzero(big):
            # no temperature jumps: the offset is the sensor's, so it is re-referenced at once
            # (a model of changes since the start then sees its true changes again) and stays
            # out until it has been calm, and agrees with the field, for a window
            offset = step[j] - (expected[j] if np.isfinite(expected[j]) else 0.0)
            if not self._jumps[j]:
                self._ref0[j] = self._ref[j]
            self._jumps[j] += 1
            self._ref[j] += offset               # changes as the field says it changed
            d[j] -= offset
            out[j] = (f"jump: {step[j]:+.3g} °C in one sample (largest step in training "
                      f"{self.max_step_c[j]:.3g} °C); re-referenced")
        return out

    def _exchanged(self, x: np.ndarray, time, events: list) -> np.ndarray:
        """The reading ``x`` (order of ``names``) as read from two wires exchanged (wires100).
        Every sensor in and read, exactly two flagged at one sample (a step past the jump limit,
        or a reading beyond range), and each reading within the OTHER's jump limit of the reading
        the sensors without both predict for the other (its last reading plus the change they
        predict, :meth:`_change_seen`; its last reading where no other predicts it): no two
        offsets but two wires exchanged.  From that sample on the two readings are read
        exchanged (``_perm``), before every check, an event per sensor (``to`` ``exchanged``)
        naming the other.  Read as two jumps (re-referenced as offsets), the pair came back on
        each other's dynamics (wires99: pt9851 77.66 µm off the healthy corrections) or stayed
        out, rebuilt (9.497 µm)."""
        if self._perm is not None:
            x = x[self._perm]
        if not (self._count and self._all_active):
            return x
        d = x - self._ref
        flagged = ((np.abs(d - self._prev) > self._jump_lim * self._gap)
                   | (x < self._lo_lim) | (x > self._hi_lim))
        if flagged.sum() != 2 or not np.isfinite(d - self._prev).all():
            return x
        a, b = np.flatnonzero(flagged)
        seen = self._ref + self._prev + np.nan_to_num(self._change_seen(d, ~flagged, flagged))
        lim = self._jump_lim * self._gap
        if not (abs(x[b] - seen[a]) < lim[a] and abs(x[a] - seen[b]) < lim[b]):
            return x
        perm = np.arange(len(x)) if self._perm is None else self._perm.copy()
        perm[[a, b]] = perm[[b, a]]
        self._perm = perm
        for j, k in ((a, b), (b, a)):
            events.append({"time": float(time), "sensor": self.names[j], "from": STATES[self._state[j]],
                           "to": EXCHANGED, "reason": f"wires exchanged with {self.names[k]}: it read "
                           f"{x[j]:.4g} °C where the others predict {self.names[k]} ({seen[k]:.4g} °C), "
                           f"{self.names[k]} {x[k]:.4g} °C where they predict it ({seen[j]:.4g} °C); "
                           "read exchanged from here"})
        x = x.copy()
        x[[a, b]] = x[[b, a]]
        return x

    def _change_seen(self, d, base, which) -> np.ndarray:
        """The change since the last sample of each ``which`` sensor as the sensors ``base``
        predict it (one operator on that set), NaN where they cannot (its leverage with them at
        the POD's limit): the jump's expected change (:meth:`_unjumped_change`) and the
        exchanged wires' prediction (:meth:`_exchanged`) alike."""
        expected = np.full(len(d), np.nan)
        M, _ = self._operator(base)
        for j in np.flatnonzero(which):
            with_j = base.copy()
            with_j[j] = True
            if self._operator(with_j)[1][j] < self.pod.max_leverage:
                expected[j] = M[j] @ (d[base] - self._prev[base])
        return expected

    def _unjumped_change(self, d, finite, rng, big) -> np.ndarray:
        """The change since the last sample of each of the ``big`` sensors (jumping in the same
        sample) as the active sensors that did not jump predict it, NaN where they cannot (its
        leverage among them at the POD's limit).  Predicted from the others, each jumping sensor's
        prediction leaned on its jumping partners: two +3 K jumps on yearround's T_motor2 and
        T_bearing_f2 were re-referenced by 3.108 / 3.076 K, their own 0.11 / 0.09 K of true change
        taken with the offset for good (E_3 1.53x the healthy error on K09)."""
        base = self._active & finite & ~rng & ~big & np.isfinite(self._prev)
        if base.sum() < self.min_active_:
            return np.full(len(d), np.nan)
        return self._change_seen(d, base, big)
