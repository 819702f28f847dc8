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
* ``out of range`` — outside the training range widened by ``range_margin_c``, unless the active
  sensors within range predict it beyond the same training edge too (a machine hotter than
  training, :meth:`SensorMonitor._hotter`);
* ``jump`` — a one-sample step larger than ``jump_factor`` × the largest step
  seen in training (across missing samples, the step since the last reading
  against that limit times the samples it spans), or a self-prediction error
  that steps past the alarm band in one sample; a jumping sensor is re-referenced by its step
  less its change as the other active sensors predict it -- several jumping in one sample, as
  the sensors that did not jump predict it (:meth:`SensorMonitor._unjumped_change`);
* ``common step`` — a one-sample step on most active sensors at once (at least ``COMMON_MIN``
  of them jumping, more than half of the active ones within ``COMMON_SPREAD`` × the median
  jump, same sign): the logger's fault, every
  sensor that took it re-referenced by its own step, none excluded
  (:meth:`SensorMonitor._common_step`);
* ``freeze`` — the reading does not change, for longer than its longest constant
  run in training (capped at ``window``), while its prediction from the other
  sensors moves by the warning band (for a sensor no other predicts: no change
  for longer than ``freeze_factor`` × that run);
* ``drift`` — the windowed self-prediction error leaves the band gradually.

Adaptive mode (paper 002, 2.3): the worst sensor (largest self-prediction error
of the paper's Eq. 7, the sensor against the field fitted to all active sensors;
a one-sample step blames the largest standardised step, always the faulty
sensor for a single fault) is excluded and the operator recomputed, while more than
``r + 1`` sensors remain active (the first at ``exclude_at``, any further one while
a sensor is out by its error only beyond the alarm band:
:meth:`SensorMonitor._field_level`); before it, a sensor no other predicts whose drift has
leaked onto the judged ones is excluded when it explains them
(:meth:`SensorMonitor._explaining`); an excluded sensor whose reading returns
within the warning band for a whole window is re-admitted, the sensors due back
at once judged together (:meth:`SensorMonitor._returning`: after a total dropout
none could pass alone).  While too few sensors are in to rebuild the field, a
sensor out only for a dropout gives its reading as it waits.  Every change of
state is an event ``{"time", "sensor", "from", "to", "reason"}``.

A new thermal state (``new_state``, :meth:`SensorMonitor._drift_vetoed`): a
source training never saw moves several sensors away from the field at once,
which self-prediction cannot pin on one of them.  A sensor is excluded for drift
only if, with it out of the fit, every other judged sensor is within its warning
band (when the largest error's sensor does not explain the others, another sensor out
of band that does, and is itself off the others' field by more than any error now, is
excluded as a lone fault: :meth:`SensorMonitor._lone_fault`, a drifting sensor behind
its coupled neighbour's larger error; a sensor within its band whose exclusion leaves one out
of band unjudged gives way to one out of band that explains the others and is the likelier
single fault); otherwise no exclusion and an event
``"to": "new thermal state"`` (sensor ``None``, the sensors out of band in ``sensors``).
A drift-excluded sensor (by the largest error, a lone fault or as explaining the others) is
re-admitted when, within ``window`` samples of its exclusion, ``new_state_others``
other judged sensors leave their warning band (the field followed it), which
calls the new state too; while it lasts no sensor is excluded for drift (the
fault signatures -- dropout, range, jump, freeze -- still exclude), and it ends,
with an event ``"to": "trained"``, once every judged sensor has been within its
warning band for a whole window.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from .pod import ThermalPOD, windowed_mean

OK, WARNING, ALARM, EXCLUDED = 0, 1, 2, 3
SPREAD_FACTOR = 3.0   # bands never within this × a sensor's training spread (from_training)
MAX_BACKOFF = 10      # a sensor excluded again waits at most window × 2**MAX_BACKOFF to return
READMIT = 0.5   # hysteresis: back in when within this share of the warning band for a window
STATES = ("ok", "warning", "alarm", "excluded")
COMMON_MIN = 3        # jumping sensors, at least, that a common step (a logger's fault) needs
COMMON_SPREAD = 2.0   # ... each within this factor of their median step (about the same size)
NEW_STATE, TRAINED = "new thermal state", "trained"   # the field's states (events, sensor None)


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
    exclude_at : {"warning", "alarm"}
        Band whose crossing excludes the first sensor by its self-prediction error (any
        further one while it is out: the alarm band).
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
    new_state : bool
        Tell a new thermal state from a drifting sensor (module doc); ``False``: every drift
        beyond the band excludes its culprit.
    new_state_others : int
        Other judged sensors out of their warning band, soon after a drift exclusion, that
        re-admit it and call a new thermal state.
    """

    new_state, new_state_others = False, 2   # a monitor pickled before them judged as before

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state)
        if "_since" not in state:      # pickled before the new-state rule: its state, idle
            self._novel, self._calm_field = False, 0
            self._since = np.full(len(self.names), -1, dtype=np.int64)

    def __init__(self, pod: ThermalPOD, names: Sequence[str], *, warning_c=0.4, alarm_c=0.8,
                 window: int = 10, confirm: int = 2, adaptive: bool = True,
                 exclude_at: str = "warning", max_step_c=None, longest_run=None,
                 lo_c=None, hi_c=None, first_c=None, jump_factor: float = 3.0,
                 freeze_factor: float = 2.0, range_margin_c: float = 10.0,
                 new_state: bool = True, new_state_others: int = 2):
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
        if int(new_state_others) < 1:
            raise ValueError(f"new_state_others must be >= 1, got {new_state_others}")
        self.new_state, self.new_state_others = bool(new_state), int(new_state_others)
        self._lo_lim = self.lo_c - self.range_margin_c
        self._hi_lim = self.hi_c + self.range_margin_c
        self._jump_lim = self.jump_factor * self.max_step_c
        self._blind_run = np.maximum(self.freeze_factor * self.longest_run, self.window)
        # a run no longer than training's longest is no freeze, whatever the field did (a noisy
        # partner moved the field 0.55 °C while a quantised sensor read 3 equal samples)
        self._seen_run = np.minimum(self.longest_run, self.window)
        self._true = np.ones(n, dtype=bool)
        # which sensors the others can predict with every sensor in (re-admission check)
        self._predictable = pod.operator(self._true)[1] < pod.max_leverage
        self._zero_run = np.zeros(n, dtype=np.int64)
        self._mid, self._half = (self._lo_lim + self._hi_lim) / 2, (self._hi_lim - self._lo_lim) / 2
        # ring rows of the `confirm - 1` samples before each write position
        # ring positions of the last `confirm` samples before each write position
        self._recent = (np.arange(self.window)[:, None] - 1 - np.arange(self.confirm)) % self.window
        self.r_ = pod.n_modes_
        self.min_active_ = self.r_ + 1
        self.reset()

    @classmethod
    def from_training(cls, pod: ThermalPOD | None, names: Sequence[str],
                      campaigns: Mapping[str, np.ndarray], learned_bands: bool = False,
                      **options) -> "SensorMonitor":
        """Fit the POD (when not fitted; ``None``: the default one) and the detectors' limits on
        training campaigns (absolute readings, (n_samples, n_sensors) per campaign, complete)."""
        arrays = [np.asarray(a, float) for a in campaigns.values()]
        for cid, a in zip(campaigns, arrays):
            if not np.isfinite(a).all():
                raise ValueError(f"training campaign {cid} has missing values: the monitor is "
                                 "fitted on complete records")
        snaps = np.vstack([a - a[0] for a in arrays])
        groups = np.concatenate([np.full(len(a), k) for k, a in enumerate(arrays)])
        if pod is None:   # the default basis fits the training field within half the warning band
            pod = ThermalPOD(fit_band_c=0.5 * float(np.min(options.get("warning_c", 0.4))),
                             window=int(options.get("window", 10)))
        if not hasattr(pod, "n_modes_"):
            pod.fit(snaps, groups=groups)
        steps = np.vstack([np.abs(np.diff(a, axis=0)) for a in arrays if len(a) > 1]
                          or [np.zeros((1, len(names)))])
        runs = np.max([_longest_runs(a) for a in arrays], axis=0)
        lo = np.min([a.min(0) for a in arrays], axis=0)
        hi = np.max([a.max(0) for a in arrays], axis=0)
        first = np.mean([a[0] for a in arrays], axis=0)
        # the training spread of each sensor: 99.5th percentile of its windowed leave-one-out error
        E = pod.deleted_residuals(snaps)
        spread = np.nanquantile(np.abs(windowed_mean(np.nan_to_num(E), groups, pod.window)),
                                0.995, axis=0)
        warn = np.asarray(options.get("warning_c", 0.4), float)
        alarm = np.asarray(options.get("alarm_c", 0.8), float)
        factor = float(options.pop("spread_factor", SPREAD_FACTOR))
        if learned_bands:
            # bands from the training spread: 4× it, never below the configured bands' half
            warn = np.maximum(4 * spread, 0.5 * warn)
            alarm = 2 * warn
        else:
            # never within `spread_factor` × the spread: a sensor the others predict loosely in
            # training does so on a healthy campaign of another season too (fl T_9: 0.24 °C in
            # training, past the 0.4 °C band on the test campaign, and the culprit pick then
            # excluded T_13 21 times); the others keep the configured bands
            floor = factor * spread
            warn, alarm = np.maximum(warn, floor), np.maximum(alarm, 2 * floor)
        options = {**options, "warning_c": warn, "alarm_c": alarm}
        return cls(pod, names, max_step_c=steps.max(0), longest_run=runs, lo_c=lo, hi_c=hi,
                   first_c=first, **options)

    # -- state ------------------------------------------------------------------------------
    _STATE = ("_ref", "_active", "_state", "_hist", "_err", "_pos", "_count", "_prev",
              "_prev_e", "_run", "_run_pred", "_clean", "_quiet", "_calm", "_prev_other",
              "_last_good", "_by_field", "_jumps", "_ref0", "_dropped", "_gap", "_gapped", "_dwell",
              "_outs", "_explains", "_novel", "_calm_field", "_since")

    def reset(self) -> None:
        """New campaign: the next sample is the reference; every sensor active and ok."""
        n = len(self.names)
        self._ref = None
        self._active = np.ones(n, dtype=bool)
        self._state = np.zeros(n, dtype=np.int8)
        self._hist = np.full((self.window, n), np.nan)   # referenced readings, ring buffer
        self._err = np.full((self.window, n), np.nan)    # their errors under the current operator
        self._pos = 0
        self._count = 0
        self._prev = np.full(n, np.nan)
        self._prev_e = np.full(n, np.nan)
        self._run = np.zeros(n, dtype=np.int64)
        self._calm = np.zeros(n, dtype=np.int64)   # samples since a detector last fired
        # calm samples an excluded sensor needs to return: a window, doubled at each exclusion
        # by its error after the first in a campaign (hysteresis: a sensor cannot flap)
        self._dwell = np.full(n, self.window, dtype=np.int64)
        self._outs = np.zeros(n, dtype=np.int64)     # its exclusions by its error
        self._prev_other = np.full(n, np.nan)       # each sensor as the others predict it
        self._last_good = np.zeros(n)               # last reading while the sensor was in
        self._by_field = np.zeros(n, dtype=bool)     # excluded by its self-prediction error
        self._explains = np.zeros(n, dtype=bool)     # excluded as explaining the others' errors
        self._dropped = np.zeros(n, dtype=bool)      # its last detector to fire was a dropout
        # samples the next step spans (1 + missing ones since the last reading): the jump limit
        # is per sample (a warm-up across 6 missing rows read as a 4 °C jump, re-referenced away)
        self._gap = np.ones(n)
        self._gapped = False
        self._jumps = np.zeros(n, dtype=np.int64)    # jumps since it was last admitted
        self._ref0 = np.full(n, np.nan)              # its reference before the first of them
        self._run_pred = np.full(n, np.nan)
        self._clean = np.zeros(n)
        self._quiet = False          # every sensor active and ok: the fast path may run
        self._novel = False          # a new thermal state is declared (module doc)
        self._calm_field = 0         # samples since a judged sensor was last out of band
        self._since = np.full(n, -1, dtype=np.int64)   # sample count at its drift exclusion
        self._set_operator()

    def _operator(self, subset: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The POD operator of the sensors ``subset`` and every sensor's leverage in it (1, no
        prediction, outside it)."""
        M, h = self.pod.operator(subset)
        lev = np.ones(len(self.names))
        lev[subset] = h
        return M, lev

    def _set_operator(self) -> None:
        """Operator, leverages and error scale of the active set; the window's errors redone."""
        active = self._active
        self._all_active = bool(active.all())
        M, lev = self._operator(active) if active.any() else (None, np.ones(len(self.names)))
        self._M = M
        self._lev = lev
        self._observable = lev < self.pod.max_leverage
        # enough sensors in to rebuild the others (a total dropout leaves none)
        self._rebuilds = int(active.sum()) >= self.min_active_
        self._judged = active & self._observable
        self._scale = np.where(self._judged, 1.0 / np.maximum(1 - lev, 1e-12), 1.0)
        self._scale[active & ~self._observable] = np.nan
        self._std = np.sqrt(np.abs(1 - lev))
        if self._count:
            H = np.where(np.isfinite(self._hist), self._hist, 0.0)
            pred = H[:, active] @ M.T if M is not None else np.full_like(H, np.nan)
            self._err = (self._hist - pred) * self._scale

    @property
    def new_state_(self) -> bool:
        """A new thermal state is declared (module doc)."""
        return self._novel

    @property
    def excluded(self) -> list[str]:
        return [n for n, a in zip(self.names, self._active) if not a]

    @property
    def states(self) -> np.ndarray:
        """State code per sensor (see :data:`STATES`)."""
        return self._state.copy()

    def snapshot(self) -> tuple:
        return tuple(np.copy(getattr(self, k)) if isinstance(getattr(self, k), np.ndarray)
                     else getattr(self, k) for k in self._STATE)

    def restore(self, snap: tuple) -> None:
        for k, v in zip(self._STATE, snap):
            setattr(self, k, np.copy(v) if isinstance(v, np.ndarray) else v)
        count = self._count
        self._count = 0          # the window's errors are restored, not recomputed
        self._set_operator()
        self._count = count

    # -- one sample ---------------------------------------------------------------------------
    def _errors(self, d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(prediction, error)`` of every sensor from the active ones (leave-one-out for the
        judged sensors, NaN for active unobservable ones)."""
        if self._M is None:
            nan = np.full_like(d, np.nan)
            return nan, nan
        pred = self._M @ (d if self._all_active else np.where(self._active, d, 0.0)[self._active])
        return pred, (d - pred) * self._scale

    def _judge(self) -> tuple[np.ndarray, np.ndarray]:
        """``(level, error)`` per sensor: the band (0 ok, 1 warning, 2 alarm) that the last
        ``confirm`` errors all exceed, and their mean."""
        k = min(self._count, self.confirm)
        last = self._err[self._recent[self._pos, :k]]
        err = last.sum(axis=0) / k
        if k < self.confirm:
            return np.zeros(len(err), dtype=np.int8), err
        a = np.abs(last).min(axis=0)          # NaN (unobservable) compares False
        return (a >= self.warning_c).view(np.int8) + (a >= self.alarm_c), err

    def update(self, reading, time: float = float("nan")) -> tuple[np.ndarray, list[dict]]:
        """One sample (absolute °C, order of ``names``) -> (referenced field for the model,
        events).  Never NaN unless every sensor has been missing since the start."""
        x = np.asarray(reading, dtype=float)
        with np.errstate(invalid="ignore"):    # NaN (missing, unobservable) compares False
            if self._quiet:
                clean = self._fast(x)
                if clean is not None:
                    return clean, []
            out = self._update(x, time)
        # a new thermal state counts its calm samples on the full path
        self._quiet = self._rebuilds and not self._novel and not self._state[self._active].any()
        return out

    @property
    def last_error_(self) -> np.ndarray:
        """Error per sensor over the last ``confirm`` samples (NaN: not judged)."""
        k = min(self._count, self.confirm)
        if not k:
            return np.full(len(self.names), np.nan)
        err = self._err[self._recent[self._pos, :k]].sum(axis=0) / k
        return np.where(self._judged | ~self._active, err, np.nan)

    def _fast(self, x: np.ndarray):
        """The usual sample, every sensor active and ok, nothing firing: the field as read.
        ``None`` (nothing changed) when any check needs the full path of :meth:`_update`."""
        if self._count < self.confirm:
            return None
        d = x - self._ref
        step = d - self._prev
        complete = bool(np.isfinite(d.sum()))
        finite = self._true if complete else np.isfinite(d)
        if ((not complete and ((self._active & ~finite).any()   # a sensor in use went missing
                               or (np.isfinite(x) & ~finite).any()))   # or one comes, unreferenced
                or (np.abs(x - self._mid) > self._half).any()
                or (np.abs(step) > (self._jump_lim * self._gap if self._gapped else self._jump_lim)).any()):
            return None
        pred = self._M @ (d if self._all_active else d[self._active])
        e = (d - pred) * self._scale
        ae = np.abs(e)
        pos = self._pos
        before = self._recent[pos, :self.confirm - 1]     # the sample being read is the last one
        a = np.minimum(np.abs(self._err[before]).min(axis=0), ae) if len(before) else ae
        if self._all_active:
            if (ae >= self.alarm_c).any() or (a >= self.warning_c).any():
                return None
        else:
            judged = self._judged
            if (judged & ((ae >= self.alarm_c) | (a >= self.warning_c))).any():
                return None
            if ((self._calm + 1 >= self.window) & ~self._active).any():
                return None                  # an excluded sensor may be due for re-admission
        same = step == 0
        if same.any():
            other = np.where(self._judged, d - e, pred)
            run_pred = np.where(same & (self._run == 0), other, self._run_pred)
            run = np.where(same, self._run + 1, 0)
            moved = np.abs(other - run_pred)
            if self._frozen(same, run, moved).any():
                return None
            self._run, self._run_pred = run, run_pred
        else:
            self._run = self._zero_run
        self._hist[pos] = d
        self._err[pos] = e
        self._pos = (pos + 1) % self.window
        self._count += 1
        self._calm += 1
        self._prev_other = np.where(self._judged, d - e, np.nan)
        if complete:
            self._prev = d
            if self._gapped:
                self._gap, self._gapped = np.ones(len(d)), False
        else:                            # an excluded sensor still missing: not calm
            self._calm[~finite] = 0
            self._prev = np.where(finite, d, self._prev)
            self._gap, self._gapped = np.where(finite, 1.0, self._gap + 1), True
        self._prev_e = e
        clean = d if self._all_active else np.where(
            self._active, d, np.where(self._predictable, pred, self._last_good))
        if self._all_active:
            self._last_good = d
        else:
            self._last_good = np.where(self._active, d, self._last_good)
        self._clean = clean
        return clean

    def update_block(self, X: np.ndarray) -> np.ndarray:
        """The referenced field of the first rows of ``X`` (absolute °C, (m, order of ``names``))
        that :meth:`update` takes on its fast path (:meth:`_fast`: every sensor active and ok,
        every reading there, nothing firing), in one go; the rows after them are for
        :meth:`update`.  Returns as many rows as it took (none: the next row needs the full
        path).  The state is the one :meth:`update` leaves row by row (the ring of readings and
        errors, the runs of equal readings, the calm counts): a lead-in of a year is read at
        once (warm59), each detector judged on every row as :meth:`_fast` judges it."""
        n = len(self.names)
        X = np.asarray(X, dtype=float)
        if (not self._quiet or not self._all_active or self._M is None
                or self._count < self.confirm or not len(X)):
            return np.empty((0, n))
        c, window = self.confirm, self.window
        with np.errstate(invalid="ignore"):     # NaN (unobservable, a missing limit) compares False
            d = X - self._ref
            step = d - np.vstack([self._prev, d[:-1]])
            lim = np.broadcast_to(self._jump_lim, d.shape).copy()
            if self._gapped:
                lim[0] = self._jump_lim * self._gap
            ok = (np.isfinite(d).all(axis=1) & ~(np.abs(X - self._mid) > self._half).any(axis=1)
                  & ~(np.abs(step) > lim).any(axis=1))
            pred = d @ self._M.T
            e = (d - pred) * self._scale
            ae = np.abs(e)
            # each row's smallest |error| over the last `confirm` samples, the ring's before it
            before = self._recent[self._pos, :c - 1][::-1]
            past = np.abs(np.vstack([self._err[before], e]))
            a = past[c - 1:]
            for o in range(c - 1):
                a = np.minimum(a, past[o:o + len(e)])
            ok &= ~((ae >= self.alarm_c).any(axis=1) | (a >= self.warning_c).any(axis=1))
            # the runs of equal readings and the field at each run's start (the freeze rule)
            same = step == 0
            rows = np.arange(len(d))[:, None]
            broke = np.maximum.accumulate(np.where(same, -1, rows), axis=0)
            run = np.where(same, np.where(broke >= 0, rows - broke, self._run + rows + 1), 0)
            run_before = np.vstack([self._run, run[:-1]])
            other = np.where(self._judged, d - e, pred)
            begun = np.maximum.accumulate(np.where(same & (run_before == 0), rows, -1), axis=0)
            run_pred = np.where(begun >= 0, np.take_along_axis(other, np.maximum(begun, 0), axis=0),
                                self._run_pred)
            ok &= ~self._frozen(same, run, np.abs(other - run_pred)).any(axis=1)
        m = len(d) if ok.all() else int(np.argmin(ok))
        if not m:
            return np.empty((0, n))
        last = np.arange(max(0, m - window), m)
        where = (self._pos + last) % window
        self._hist[where], self._err[where] = d[last], e[last]
        self._pos = (self._pos + m) % window
        self._count += m
        self._calm = self._calm + m
        self._run, self._run_pred = run[m - 1].astype(np.int64), run_pred[m - 1]
        self._prev_other = np.where(self._judged, d[m - 1] - e[m - 1], np.nan)
        self._prev, self._prev_e = d[m - 1], e[m - 1]
        if self._gapped:
            self._gap, self._gapped = np.ones(n), False
        self._last_good = self._clean = d[m - 1]
        return d[:m]

    def _update(self, x: np.ndarray, time: float) -> tuple[np.ndarray, list[dict]]:
        """One sample through every check, in order: reference, instant detectors, late
        reference, freeze, a stepped error, exclusion by judgement, re-admission, states."""
        events: list[dict] = []
        rng = (x < self._lo_lim) | (x > self._hi_lim)
        if self._ref is None:       # an out-of-range reference is no reference (as if missing)
            self._ref = np.where(np.isfinite(x) & ~rng, x, np.nan)
        d = x - self._ref
        if rng.any() and self._count:
            rng = rng & ~self._hotter(x, d, rng)
        all_finite = bool(np.isfinite(d.sum()))
        finite = np.isfinite(d) if not all_finite else self._true
        pos = self._pos
        self._hist[pos] = d
        self._pos = (pos + 1) % self.window
        self._count += 1

        # instant detectors on the raw reading (vectorised check, details only when one fires)
        step = d - self._prev
        big = np.abs(step) > self._jump_lim * self._gap
        same = step == 0
        instant: dict[int, str] = {}
        if big.sum() >= COMMON_MIN:
            step, big = self._common_step(d, step, big & ~rng & finite, pos, time, events)
        if self._count == 2 and big.any():
            step, big = self._reference_glitch(d, step, big & ~rng, pos, time, events)
        if not all_finite or (rng | big).any():
            instant = self._instant(x, d, step, finite, rng, big & ~rng)
            for j, why in instant.items():
                if self._active[j]:
                    self._exclude(j, why, time, events)
            if rng.any():
                # an out-of-range reading is no measurement: read as missing from here on, so it
                # is neither the previous value of the next step (a +50 °C spike on T_amb then
                # read its return as a -50 °C jump and re-referenced the sensor by it) nor in the
                # window that decides re-admission
                d[rng] = np.nan
                finite = finite & ~rng
                all_finite = False
            self._hist[pos] = d             # a jump re-referenced the sensor
        self._run = np.where(same, self._run + 1, 0)
        self._calm += 1
        for j in instant:
            self._calm[j] = 0
        pred, e = self._errors(d)
        if not all_finite:
            self._reference_late(x, d, e, pred, finite, rng, pos)
        self._err[pos] = e
        self._check_freeze(x, d, e, pred, same, instant, time, events)
        self._check_stepped(e, instant, time, events)
        level, err = self._exclude_by_judgement(time, events)
        if self.adaptive and not self._all_active and self._count >= self.window:
            if self._readmit(d, finite, instant, time, events):
                level, err = self._judge()
        pred, e = self._errors(d)
        self._set_states(level, err, instant, time, events)
        self._prev_other = np.where(self._judged, d - e, np.nan)
        self._prev = np.where(finite, d, self._prev)
        self._gap = np.where(finite, 1.0, self._gap + 1)
        self._gapped = bool((self._gap > 1).any())
        self._prev_e = e
        for j in instant:
            self._dropped[j] = not np.isfinite(x[j])
        good = self._active & finite
        self._last_good = np.where(good, d, self._last_good)
        if not self._rebuilds:
            # too few sensors in to rebuild the field: a sensor out only for a dropout whose
            # reading is back feeds the model while it waits out its window, nearer the truth
            # than a held value (10 held samples of a warm-up doubled the adaptive error)
            good = good | (self._dropped & finite & (self._run == 0))
        # an excluded sensor: rebuilt from the field, or held where the others cannot predict it
        clean = d if (self._all_active and all_finite) else np.where(
            good, d, np.where(self._predictable, pred, self._last_good))
        if not np.isfinite(clean.sum()):
            clean = np.where(np.isfinite(clean), clean, self._clean)   # nothing to rebuild from
        self._clean = clean
        return clean, events

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
            why = (f"freeze: {x[j]:.4g} °C for {self._run[j] + 1} samples while the field "
                   f"moved {moved[j]:.2g} °C" if self._observable[j] else
                   f"freeze: {x[j]:.4g} °C for {self._run[j] + 1} samples (longest constant "
                   f"run in training {self.longest_run[j]:.0f})")
            instant[j] = why
            if self._active[j]:
                self._exclude(j, why, time, events)

    def _check_stepped(self, e, instant, time, events) -> None:
        """A self-prediction error that steps past the alarm band in one sample."""
        de = e - self._prev_e
        stepped = self._judged & (np.abs(e) >= self.alarm_c) & (np.abs(de) >= self.alarm_c)
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

    def _exclude_by_judgement(self, time, events) -> tuple[np.ndarray, np.ndarray]:
        """Judgement over the last ``confirm`` samples, worst first, redone after every
        exclusion; ``(level, error)`` of :meth:`_judge` after it."""
        level, err = self._judge()
        while (self.adaptive and (self._judged & (level >= self._field_level())).any()
               and self._active.sum() > self.min_active_):
            # a drift exclusion too: none in a new thermal state, and its field may follow it
            u = None if self.new_state and self._novel else self._explaining(level)
            if u is not None:
                out = np.flatnonzero(self._judged & (level >= self._field_level()))
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
            z = np.where(self._judged, np.abs(np.nan_to_num(err)) * self._std ** 2, -1)
            j, resolves = self._lone_fault(int(np.argmax(z)), z, level, err)
            if self._drift_vetoed(j, level, err, time, events, resolves):
                break
            self._exclude(j, f"drift: self-prediction error {err[j]:+.2g} °C over the last "
                             f"{self.confirm} samples", time, events, by_field=True)
            self._since[j] = self._count
            # a sensor out of band that no other can predict once j is out cannot be
            # vouched for (two coupled sensors look alike to self-prediction): out too
            blind = self._active & ~self._observable & (z >= 0.7 * z[j])
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
        others = self._judged & (level >= WARNING)
        others[j] = False
        if not (self._resolves(j) if resolves is None else resolves):
            self._declare(f"with {self.names[j]} out the others stay out of band",
                          others | (np.arange(len(others)) == j), err, time, events)
            return True
        return int(others.sum()) >= self.new_state_others

    def _lone_fault(self, j: int, z: np.ndarray, level: np.ndarray,
                    err: np.ndarray) -> tuple[int, bool | None]:
        """``(sensor, whether with it out the others are within band)`` (None: not asked):
        the single fault that explains the bands.  An exclusion explains them when, with the
        sensor out of the fit, every other judged sensor is within its warning band and, unless
        the sensor is out of band itself, every one out of band is still judged (a coupled pair
        out of band goes out together; a sensor within its band that leaves one out of band
        unjudged hides its error).  In order: ``j`` (paper 002's largest error); the
        sensor out of band (largest error first) that one fault explains, off the field the
        others make by more than any other sensor's error now (a fault's own deviation is the
        largest), and, where ``j``'s exclusion explains the bands only by leaving one out of
        them unjudged, also the largest standardised residual ``|E|·sqrt(1 - h)`` (the likelier
        single fault, as in :meth:`_explaining`); else ``j``, if it explains them at all (a
        coupled pair: :meth:`_exclude_by_judgement` takes the partner out too).  ``j``'s coupled
        neighbour can show the largest error (fl_thermal's t12 drifting, T_t14 then T_t15
        picked, and the drift read as a new thermal state that never ended); and a lathe's
        healthy T_nc_x1_drive (-0.58 °C, 0.48 standardised), excluded for a drifting
        T_guidebush (+0.93, 0.51) whose leverage that raised past judging (0.71 -> 0.96), had
        hidden the drift, until a new thermal state did."""
        if not self.new_state or self._novel:
            return j, None
        out = self._judged & (level >= WARNING)
        # a sensor out of band itself may leave its coupled partner out of band unjudged (the
        # partner follows it out); one within its band that does so hides, not explains
        if self._resolves(j, out if level[j] < WARNING else None):
            return j, True
        # j explains the bands only by hiding a sensor out of them (j out of band itself: the
        # same question as above, answered no)
        hides = bool(level[j] < WARNING) and self._resolves(j)
        size = np.abs(np.where(self._judged, np.nan_to_num(err), 0.0))
        # the likelier single fault, where j is one too: the largest standardised residual
        likelier = np.argmax(size * self._std) if hides else None
        for k in np.argsort(-z):
            if (k != j and z[k] >= 0 and level[k] >= WARNING and (likelier is None or likelier == k)
                    and self._resolves(int(k), out,
                                       alone=float(np.max(np.delete(size, k), initial=0.0)))):
                return int(k), True
        return j, hides

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
        judged = trial & (lev < self.pod.max_leverage)
        if seen is not None and (seen & trial & ~judged).any():
            return False
        rows = self._hist[self._recent[self._pos, :min(self._count, self.confirm)]]
        X = np.where(np.isfinite(rows), rows, 0.0)
        E = ((X[:, judged] - X[:, trial] @ M[judged].T) / (1 - lev[judged])).mean(axis=0)
        if not (np.abs(E) < self.warning_c[judged]).all():
            return False
        # (alone: and j itself off the others' field by that much at least, as a fault is)
        return alone is None or bool(abs((X[:, j] - X[:, trial] @ M[j]).mean()) >= alone)

    def _follow_field(self, level, err, time, events) -> tuple[np.ndarray, np.ndarray]:
        """A drift-excluded sensor whose exclusion the field followed (``new_state_others``
        other judged sensors out of band within a window of it) comes back, as a new state;
        the new state ends after a window with every judged sensor within band.
        ``(level, error)`` after it."""
        leaving = self._judged & (level >= WARNING)
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
                leaving = self._judged & (level >= WARNING)
                out = int(leaving.sum())
        self._end_when_calm(out, time, events)
        return level, err

    def _name_state(self, level, err, time, events) -> None:
        """Judge only (``adaptive=False``): the new thermal state the adaptive monitor would
        declare where it would exclude a sensor for drift (with the largest error's sensor, or
        a lone fault, out, the others stay out of band), and its end; nothing is excluded
        either way.  Without it, a source training never saw read as several sensors in
        alarm with no word of why."""
        if not self._novel and (self._judged & (level >= self._field_level())).any():
            z = np.where(self._judged, np.abs(np.nan_to_num(err)) * self._std ** 2, -1)
            j, resolves = self._lone_fault(int(np.argmax(z)), z, level, err)
            self._drift_vetoed(j, level, err, time, events, resolves)
        self._end_when_calm(int((self._judged & (level >= WARNING)).sum()), time, events)

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
        out = self._judged & (level >= self._field_level())
        band = self.warning_c if self._field_level() == WARNING else self.alarm_c
        rows = self._hist[self._recent[self._pos, :min(self._count, self.confirm)]]
        X = np.where(np.isfinite(rows), rows, 0.0)
        # every active sensor's residual in the current fit, standardised: the likelihood ratio
        # of a fault on it alone; a sensor no other predicts is blamed only as the best of all
        r = (X - X[:, self._active] @ self._M.T).mean(axis=0)
        z = np.where(self._active, np.abs(r) / np.sqrt(np.maximum(1 - self._lev, 1e-12)), -1.0)
        best, best_z = None, float(np.max(np.where(self._judged, z, -1.0)))
        for u in np.flatnonzero(self._active & ~self._observable & (z > best_z)):
            trial = self._active.copy()
            trial[u] = False
            if trial.sum() < self.min_active_:
                continue
            M, lev = self._operator(trial)
            judged = trial & (lev < self.pod.max_leverage)
            if (out & ~judged).any():
                continue
            E = (X[:, judged] - X[:, trial] @ M[judged].T) / (1 - lev[judged])
            if (np.abs(E).min(axis=0) >= band[judged]).any():
                continue
            if z[u] > best_z:
                best, best_z = int(u), float(z[u])
        return best

    def _readmit(self, d, finite, instant, time, events) -> bool:
        """Re-admission: back within the warning band for a whole window, no detector firing
        (checked against the field where the others can predict it, else calm is enough).
        Whether any sensor came back."""
        due = ~self._active & finite & (self._run == 0) & (self._calm >= self._dwell)
        due[list(instant)] = False
        back = self._returning(due) if due.any() else due
        for j in np.flatnonzero(back):
            why = f"re-admitted: within ±{self._readmit_c()[j]:.3g} °C for {self._calm[j]} samples"
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

    def _set_states(self, level, err, instant, time, events) -> None:
        """States of the sensors still active (monitor-only mode: a firing detector holds alarm)."""
        new = np.where(self._judged, level, OK).astype(np.int8)
        for j, why in instant.items():
            if self._active[j]:
                new[j] = ALARM
        changed = self._active & (new != self._state)
        for j in (np.flatnonzero(changed) if changed.any() else ()):
            self._set_state(j, int(new[j]), time, instant.get(j) or (
                f"self-prediction error {err[j]:+.2g} °C over the last {self.confirm} samples"
                + self._against_band(j, int(new[j]))
                if np.isfinite(err[j]) and self._judged[j] else
                "no longer judged: no other active sensor predicts it"), events)

    def _against_band(self, j: int, level: int) -> str:
        """How the last ``confirm`` errors of sensor ``j`` stand against the band its new
        state ``level`` turns on (:meth:`_judge`: a band is left when all are beyond it): a
        return to ok said only their mean, beyond the band as often as not ('-0.52 °C' against
        a 0.51 °C band, a mill's 700 warnings and returns in 12 h all read alike)."""
        k = min(self._count, self.confirm)
        smallest = float(np.abs(self._err[self._recent[self._pos, :k], j]).min())
        if level > OK:
            band = (self.warning_c if level == WARNING else self.alarm_c)[j]
            return f", all beyond ±{band:.3g} °C (the smallest {smallest:.3g})"
        return f", the smallest {smallest:.3g} within ±{self.warning_c[j]:.3g} °C"

    def _frozen(self, same: np.ndarray, run: np.ndarray, moved: np.ndarray) -> np.ndarray:
        """The freeze rule (module doc), for :meth:`_fast` and :meth:`_update` alike: ``same``
        unchanged readings, ``run`` their constant-run lengths, ``moved`` the field's change."""
        return same & ((self._observable & (moved >= self.warning_c) & (run >= self._seen_run))
                       | (~self._observable & (run > self._blind_run)))

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

    def _unjumped_change(self, d, finite, rng, big) -> np.ndarray:
        """The change since the last sample of each of the ``big`` sensors (jumping in the same
        sample) as the active sensors that did not jump predict it, NaN where they cannot (its
        leverage among them at the POD's limit).  Predicted from the others, each jumping sensor's
        prediction leaned on its jumping partners: two +3 K jumps on yearround's T_motor2 and
        T_bearing_f2 were re-referenced by 3.108 / 3.076 K, their own 0.11 / 0.09 K of true change
        taken with the offset for good (E_3 1.53x the healthy error on K09)."""
        expected = np.full(len(d), np.nan)
        base = self._active & finite & ~rng & ~big & np.isfinite(self._prev)
        if base.sum() < self.min_active_:
            return expected
        M, _ = self._operator(base)
        for j in np.flatnonzero(big):
            with_j = base.copy()
            with_j[j] = True
            if self._operator(with_j)[1][j] < self.pod.max_leverage:
                expected[j] = M[j] @ (d[base] - self._prev[base])
        return expected

    def _field_level(self) -> int:
        """Band whose crossing excludes a sensor by its self-prediction error: ``exclude_at``
        while no sensor is out by it, the alarm band while one is.  One sensor out of band is
        what a single fault looks like, and excluding it early spares the correction; sensors
        still leaving the band once the worst is out mean a field that training never saw (paper
        002: a new source), which self-prediction cannot pin on a sensor -- the paper excludes
        a sensor then only beyond its tolerance (the alarm band)."""
        return ALARM if (self._by_field & ~self._active).any() else self.exclude_level

    def _exclude(self, j: int, reason: str, time: float, events: list, by_field: bool = False) -> None:
        if not self.adaptive:
            self._set_state(j, ALARM, time, reason, events)
            return
        if not self._predictable[j]:   # say so: for a frozen sensor the exclusion changes nothing
            reason += "; held at its last good reading: no other sensor predicts it"
        self._active[j] = False
        self._calm[j] = 0            # back in only after a whole window inside the band
        if by_field:      # out by its error again since its first return: it waits longer
            self._dwell[j] = self.window * 2 ** min(self._outs[j], MAX_BACKOFF)
            self._outs[j] += 1
        self._by_field[j] = by_field
        self._set_state(j, EXCLUDED, time, reason, events)
        self._set_operator()

    def _set_state(self, j: int, new: int, time: float, reason: str, events: list) -> None:
        if new == self._state[j]:
            return
        events.append({"time": float(time), "sensor": self.names[j], "from": STATES[self._state[j]],
                       "to": STATES[new], "reason": reason})
        self._state[j] = new



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
