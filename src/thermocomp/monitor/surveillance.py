r"""Online surveillance of the temperature sensors and the adaptive sensor set (paper 002, 2.2–2.3).

:class:`SensorMonitor` sees one sample of the ``n`` monitored sensors at a
time (absolute °C; it references them to the campaign's first sample as the
POD snapshots were) and returns the field the compensation model should see:
the measured value of every *active* sensor, the POD reconstruction
:math:`\Phi_r\,\Phi_r[a]^+ T_a` from the active set :math:`a` for the others.

Each sensor is judged by its windowed self-prediction error: the trailing mean
over ``window`` samples of its reading minus what the *other* active sensors
predict for it (the leave-one-out form :math:`E_s/(1-h_{ss})` of paper 002's
:math:`E_s`; with the sensor in its own fit, a fault shows only by the factor
:math:`1-h_{ss}` and leaks onto the others).  Bands: ``warning_c``, ``alarm_c``.

Detectors, each named in the event's reason:

* ``dropout`` — no finite value;
* ``out of range`` — outside the training range widened by ``range_margin_c``;
* ``jump`` — a one-sample step larger than ``jump_factor`` × the largest step
  seen in training, or a self-prediction error that steps past the alarm band
  in one sample;
* ``freeze`` — the reading does not change while its prediction from the other
  sensors moves by the warning band (for a sensor no other predicts: no change
  for longer than ``freeze_factor`` × its longest constant run in training);
* ``drift`` — the windowed self-prediction error leaves the band gradually.

Adaptive mode (paper 002, 2.3): the worst sensor in alarm (largest standardised
error :math:`|E_s|/\sqrt{1-h_{ss}}`, which is always the faulty one for a
single fault) is excluded and the operator recomputed, while more than
``r + 1`` sensors remain active; an excluded sensor whose reading returns
within the warning band for a whole window is re-admitted.  Every change of
state is an event ``{"time", "sensor", "from", "to", "reason"}``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from .pod import ThermalPOD

OK, WARNING, ALARM, EXCLUDED = 0, 1, 2, 3
STATES = ("ok", "warning", "alarm", "excluded")


class SensorMonitor:
    """Stateful monitor of ``names`` (see module doc).

    Parameters
    ----------
    pod : fitted ThermalPOD
        On the referenced training snapshots of ``names`` (same order).
    names : list of str
    warning_c, alarm_c : float or array
        Bands of the windowed self-prediction error (°C), scalar or per sensor.
    window : int
        Samples of self-prediction error kept; an excluded sensor is re-admitted when all
        of them are within the warning band.
    confirm : int
        A band is left when the last ``confirm`` errors are all beyond it (one noisy
        sample is no fault); the reported error is their mean.
    adaptive : bool
        Exclude and re-admit sensors (otherwise only judge them).
    max_step_c : array
        Largest one-sample change of each sensor in training (°C).
    longest_run : array
        Longest run of identical readings of each sensor in training.
    lo_c, hi_c : array
        Absolute training range of each sensor (°C).
    first_c : array
        Mean first-sample reading in training (a stand-in reference for a sensor
        missing at the campaign's start).
    jump_factor, freeze_factor, range_margin_c : float
    """

    def __init__(self, pod: ThermalPOD, names: Sequence[str], *, warning_c=0.4, alarm_c=0.8,
                 window: int = 10, confirm: int = 3, adaptive: bool = True,
                 exclude_at: str = "warning", max_step_c=None, longest_run=None,
                 lo_c=None, hi_c=None, first_c=None, jump_factor: float = 3.0,
                 freeze_factor: float = 2.0, range_margin_c: float = 10.0):
        n = len(names)
        if pod.n_features_in_ != n:
            raise ValueError(f"POD has {pod.n_features_in_} sensors, names {n}")
        self.pod, self.names = pod, list(names)
        self.warning_c = np.broadcast_to(np.asarray(warning_c, float), (n,)).copy()
        self.alarm_c = np.broadcast_to(np.asarray(alarm_c, float), (n,)).copy()
        if np.any(self.alarm_c < self.warning_c) or np.any(self.warning_c <= 0):
            raise ValueError("bands need 0 < warning_c <= alarm_c")
        if int(window) < 1:
            raise ValueError(f"window must be >= 1, got {window}")
        if not 1 <= int(confirm) <= int(window):
            raise ValueError(f"confirm must be in [1, window={window}], got {confirm}")
        self.window, self.confirm, self.adaptive = int(window), int(confirm), bool(adaptive)
        if exclude_at not in ("warning", "alarm"):
            raise ValueError(f"exclude_at must be warning or alarm, got {exclude_at!r}")
        self.exclude_at = exclude_at
        self.exclude_level = WARNING if exclude_at == "warning" else ALARM

        def arr(v, default):
            return np.full(n, default, float) if v is None else np.asarray(v, float).copy()

        self.max_step_c = arr(max_step_c, np.inf)
        self.longest_run = arr(longest_run, np.inf)
        self.lo_c, self.hi_c = arr(lo_c, -np.inf), arr(hi_c, np.inf)
        self.first_c = arr(first_c, 0.0)
        self.jump_factor, self.freeze_factor = float(jump_factor), float(freeze_factor)
        self.range_margin_c = float(range_margin_c)
        self.r_ = pod.n_modes_
        self.min_active_ = self.r_ + 1
        self.reset()

    @classmethod
    def from_training(cls, pod: ThermalPOD | None, names: Sequence[str],
                      campaigns: Mapping[str, np.ndarray], learned_bands: bool = False,
                      **options) -> "SensorMonitor":
        """Fit the POD (when not fitted) and the detectors' limits on training campaigns
        (absolute readings, (n_samples, n_sensors) per campaign, complete)."""
        arrays = [np.asarray(a, float) for a in campaigns.values()]
        for cid, a in zip(campaigns, arrays):
            if not np.isfinite(a).all():
                raise ValueError(f"training campaign {cid} has missing values: the monitor is "
                                 "fitted on complete records")
        snaps = np.vstack([a - a[0] for a in arrays])
        groups = np.concatenate([np.full(len(a), k) for k, a in enumerate(arrays)])
        pod = pod if pod is not None else ThermalPOD()
        if not hasattr(pod, "n_modes_"):
            band = options.get("warning_c", 0.4)
            pod.set_params(fit_band_c=None if pod.fit_band_c is None else
                           min(pod.fit_band_c, 0.5 * float(np.min(band))),
                           window=int(options.get("window", pod.window)))
            pod.fit(snaps, groups=groups)
        steps = np.vstack([np.abs(np.diff(a, axis=0)) for a in arrays if len(a) > 1]
                          or [np.zeros((1, len(names)))])
        runs = np.max([_longest_runs(a) for a in arrays], axis=0)
        lo = np.min([a.min(0) for a in arrays], axis=0)
        hi = np.max([a.max(0) for a in arrays], axis=0)
        first = np.mean([a[0] for a in arrays], axis=0)
        if learned_bands:
            # bands from the training spread: 4× the 99.5th percentile of the windowed
            # leave-one-out error per sensor, never below the configured bands' half
            E = pod.deleted_residuals(snaps)
            from .pod import windowed_mean
            spread = np.nanquantile(np.abs(windowed_mean(np.nan_to_num(E), groups,
                                                         pod.window)), 0.995, axis=0)
            warn = np.maximum(4 * spread, 0.5 * np.asarray(options.get("warning_c", 0.4), float))
            options = {**options, "warning_c": warn, "alarm_c": 2 * warn}
        return cls(pod, names, max_step_c=steps.max(0), longest_run=runs, lo_c=lo, hi_c=hi,
                   first_c=first, **options)

    # -- state ------------------------------------------------------------------------------
    def reset(self) -> None:
        """New campaign: the next sample is the reference; every sensor active and ok."""
        n = len(self.names)
        self._ref = None
        self._active = np.ones(n, dtype=bool)
        self._state = np.zeros(n, dtype=np.int8)
        self._why = [""] * n               # the detector that excluded each sensor
        self._hist = np.full((self.window, n), np.nan)   # referenced readings, ring buffer
        self._pos = 0
        self._count = 0
        self._prev = np.full(n, np.nan)
        self._prev_e = np.full(n, np.nan)
        self._run = np.zeros(n, dtype=np.int64)
        self._run_pred = np.full(n, np.nan)
        self._prev_other = np.full(n, np.nan)
        self._clean = np.zeros(n)
        self._set_operator()

    def _set_operator(self) -> None:
        M, h = self.pod.operator(self._active) if self._active.any() else (None, None)
        self._M = M
        lev = np.ones(len(self.names))
        if h is not None:
            lev[self._active] = h
        self._lev = lev
        self._observable = lev < self.pod.max_leverage
        self._scale = np.where(self._active & self._observable, 1.0 / np.maximum(1 - lev, 1e-12), 1.0)
        self._scale[self._active & ~self._observable] = np.nan

    @property
    def excluded(self) -> list[str]:
        return [n for n, a in zip(self.names, self._active) if not a]

    @property
    def states(self) -> np.ndarray:
        """State code per sensor (see :data:`STATES`)."""
        return self._state.copy()

    def snapshot(self) -> tuple:
        return tuple(np.copy(v) if isinstance(v, np.ndarray) else
                     (list(v) if isinstance(v, list) else v)
                     for v in (self._ref, self._active, self._state, self._why, self._hist,
                               self._pos, self._count, self._prev, self._prev_e, self._run,
                               self._run_pred, self._prev_other, self._clean))

    def restore(self, snap: tuple) -> None:
        (self._ref, self._active, self._state, self._why, self._hist, self._pos, self._count,
         self._prev, self._prev_e, self._run, self._run_pred, self._prev_other, self._clean) = (
            np.copy(v) if isinstance(v, np.ndarray) else (list(v) if isinstance(v, list) else v)
            for v in snap)
        self._set_operator()

    # -- one sample ---------------------------------------------------------------------------
    def _residuals(self, d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(prediction, leave-one-out error)`` of every sensor from the active ones."""
        if self._M is None:
            return np.full_like(d, np.nan), np.full_like(d, np.nan)
        pred = self._M @ np.nan_to_num(d[self._active])
        E = d - pred
        return pred, E * self._scale

    def _window_errors(self) -> np.ndarray:
        """Leave-one-out errors of the samples in the window under the current operator,
        most recent first."""
        k = min(self._count, self.window)
        H = self._hist[(self._pos - 1 - np.arange(k)) % self.window]
        if self._M is None:
            return np.full_like(H, np.nan)
        pred = np.nan_to_num(H[:, self._active]) @ self._M.T
        return (H - pred) * self._scale

    def _judge(self, W: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(level, error)`` per sensor: the band (0 ok, 1 warning, 2 alarm) that the last
        ``confirm`` errors all exceed, and their mean."""
        last = W[:self.confirm]
        err = _nanmean(last, W.shape[1])
        if len(last) < self.confirm:
            return np.zeros(W.shape[1], dtype=np.int8), err
        a = np.abs(last)
        with np.errstate(invalid="ignore"):
            level = (np.all(a >= self.warning_c, axis=0).astype(np.int8)
                     + np.all(a >= self.alarm_c, axis=0))
        return level, err

    def update(self, reading, time: float = float("nan")) -> tuple[np.ndarray, list[dict]]:
        """One sample (absolute °C, order of ``names``) -> (referenced field for the model,
        events).  Never NaN unless every sensor has been missing since the start."""
        x = np.asarray(reading, dtype=float)
        finite = np.isfinite(x)
        events: list[dict] = []
        if self._ref is None:
            self._ref = np.where(finite, x, np.nan)
        late = finite & ~np.isfinite(self._ref)      # first value of a sensor missing at the start
        d = x - self._ref
        self._hist[self._pos] = d
        self._pos = (self._pos + 1) % self.window
        self._count += 1

        # instant detectors on the raw reading
        instant: dict[int, str] = {}
        for j in np.flatnonzero(~finite):
            instant[j] = "dropout: no finite value"
        rng = finite & ((x < self.lo_c - self.range_margin_c) | (x > self.hi_c + self.range_margin_c))
        for j in np.flatnonzero(rng):
            instant[j] = (f"out of range: {x[j]:.4g} °C outside the training range "
                          f"[{self.lo_c[j]:.3g}, {self.hi_c[j]:.3g}] ± {self.range_margin_c:g} °C")
        step = d - self._prev
        big = np.isfinite(step) & (np.abs(step) > self.jump_factor * self.max_step_c) & ~rng
        for j in np.flatnonzero(big):
            instant[j] = (f"jump: {step[j]:+.3g} °C in one sample (largest step in training "
                          f"{self.max_step_c[j]:.3g} °C)")
        same = finite & (step == 0)
        self._run = np.where(same, self._run + 1, 0)

        for j in list(instant):
            if self._active[j]:
                self._exclude(j, instant[j], time, events)
        pred, e = self._residuals(d)
        for j in np.flatnonzero(late):                 # referenced so that it agrees with the field
            if np.isfinite(pred[j]):
                self._ref[j] = x[j] - pred[j]
                d[j] = pred[j]
                self._hist[(self._pos - 1) % self.window, j] = d[j]
                e[j] = 0.0

        # freeze: constant while the field (its prediction from the others) moves
        other = np.where(np.isfinite(e), d - e, pred)   # what the other sensors say it reads
        start = same & (self._run == 1)
        self._run_pred[start] = self._prev_other[start]
        self._prev_other = other
        moved = np.abs(other - self._run_pred)
        frozen_obs = same & self._observable & (moved >= self.warning_c)
        frozen_blind = same & ~self._observable & (self._run > np.maximum(
            self.freeze_factor * self.longest_run, self.window))
        for j in np.flatnonzero(frozen_obs | frozen_blind):
            if j in instant:
                continue
            why = (f"freeze: {x[j]:.4g} °C for {self._run[j] + 1} samples while the field moved "
                   f"{moved[j]:.2g} °C" if frozen_obs[j] else
                   f"freeze: {x[j]:.4g} °C for {self._run[j] + 1} samples (longest constant run "
                   f"in training {self.longest_run[j]:.0f})")
            instant[j] = why
            if self._active[j]:
                self._exclude(j, why, time, events)
        # a self-prediction error that steps past the alarm band in one sample
        de = e - self._prev_e
        stepped = (self._active & self._observable & np.isfinite(de)
                   & (np.abs(e) >= self.alarm_c) & (np.abs(de) >= self.alarm_c))
        if stepped.any():
            for j in np.flatnonzero(stepped):
                if j not in instant:
                    instant[j] = f"jump: self-prediction error stepped {de[j]:+.3g} °C in one sample"
            if self.adaptive:
                j = int(np.argmax(np.where(stepped, np.abs(e) * np.sqrt(np.abs(1 - self._lev)), -1)))
                self._exclude(j, instant[j], time, events)
        if events:
            pred, e = self._residuals(d)

        # windowed judgement, worst first, re-evaluated after every exclusion
        for _ in range(len(self.names)):
            W = self._window_errors()
            level, err = self._judge(W)
            judged = self._active & self._observable
            if not (self.adaptive and (judged & (level >= self.exclude_level)).any()
                    and self._active.sum() > self.min_active_):
                break
            # the culprit is the largest *standardised* error |E|/sqrt(1-h) among all judged
            # sensors, in alarm or not: a fault on j gives every other sensor i a smaller one
            # (|H_ij| <= sqrt((1-h_ii)(1-h_jj))), while its leave-one-out error may be smaller
            # than a coupled neighbour's
            z = np.where(judged, np.abs(np.nan_to_num(err)) * np.sqrt(np.abs(1 - self._lev)), -1)
            j = int(np.argmax(z))
            self._exclude(j, f"drift: self-prediction error {err[j]:+.2g} °C over the last "
                             f"{self.confirm} samples", time, events)
            # a sensor out of band that no other can predict once j is out cannot be
            # vouched for (two coupled sensors look alike to self-prediction): out too
            blind = self._active & ~self._observable & judged & (z >= 0.7 * z[j])
            for i in np.flatnonzero(blind):
                if self._active.sum() > self.min_active_:
                    self._exclude(i, f"drift: self-prediction error {err[i]:+.2g} °C and no other "
                                     f"sensor predicts it once {self.names[j]} is out", time, events)
        pred, e = self._residuals(d)

        # re-admission: back within the warning band for a whole window, no detector firing
        if self.adaptive and (~self._active).any() and self._count >= self.window:
            back = (~self._active & finite & (self._run == 0)
                    & np.all(np.abs(W) < self.warning_c, axis=0) if len(W) == self.window else
                    np.zeros(len(d), bool))
            back &= np.array([j not in instant for j in range(len(d))])
            for j in np.flatnonzero(back):
                self._set_state(j, OK, time, f"re-admitted: within ±{self.warning_c[j]:g} °C "
                                              f"for {self.window} samples", events)
                self._active[j] = True
            if back.any():
                self._set_operator()
                pred, e = self._residuals(d)
                W = self._window_errors()
                level, err = self._judge(W)

        # states of the sensors still active
        for j in np.flatnonzero(self._active):
            if j in instant:      # monitor-only mode: a firing detector holds the alarm
                self._set_state(j, ALARM, time, instant[j], events)
                continue
            new = int(level[j]) if self._observable[j] else OK
            if new != self._state[j]:
                self._set_state(j, new, time, f"self-prediction error {err[j]:+.2g} °C over the "
                                              f"last {self.confirm} samples", events)
        self._prev = np.where(finite, d, self._prev)
        self._prev_e = e
        self.last_error_ = np.where(self._observable | ~self._active, err, np.nan)
        clean = np.where(self._active & finite, d, pred)
        clean = np.where(np.isfinite(clean), clean, self._clean)   # nothing to rebuild from: hold
        self._clean = clean
        return clean, events

    def _exclude(self, j: int, reason: str, time: float, events: list) -> None:
        if not self.adaptive:
            self._set_state(j, ALARM, time, reason, events)
            return
        self._active[j] = False
        self._why[j] = reason
        self._set_state(j, EXCLUDED, time, reason, events)
        self._set_operator()

    def _set_state(self, j: int, new: int, time: float, reason: str, events: list) -> None:
        if new == self._state[j]:
            return
        events.append({"time": float(time), "sensor": self.names[j], "from": STATES[self._state[j]],
                       "to": STATES[new], "reason": reason})
        self._state[j] = new


def _nanmean(W: np.ndarray, n: int) -> np.ndarray:
    """Column means over the finite values (NaN where none), without warnings."""
    ok = np.isfinite(W)
    count = ok.sum(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(count > 0, np.where(ok, W, 0.0).sum(axis=0) / count, np.nan) \
            if len(W) else np.full(n, np.nan)


def _longest_runs(a: np.ndarray) -> np.ndarray:
    """Longest run of identical consecutive values per column."""
    if len(a) < 2:
        return np.zeros(a.shape[1])
    same = np.diff(a, axis=0) == 0
    best = np.zeros(a.shape[1])
    run = np.zeros(a.shape[1])
    for row in same:
        run = np.where(row, run + 1, 0)
        best = np.maximum(best, run)
    return best
