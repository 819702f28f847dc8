""":class:`SensorMonitor`: one sample at a time, the field the model should see (the package doc).

Its detectors live beside it, one concern each: the instant faults (:mod:`.faults`), the
judgement of the self-prediction errors and the new thermal state (:mod:`.judgement`), the
re-admission of an excluded sensor (:mod:`.readmission`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from ....core.io.contract import is_ambient
from ..pod import ThermalPOD, windowed_mean
from .excursion import Excursion
from .faults import InstantFaults
from .frozen_hold import held_until, kept, push_row
from .judgement import Judgement
from .readmission import Readmission
from .settled import Settled, largest_separation
from .states import (
    ALARM,
    COMMON_MIN,
    DITHER,
    EXCLUDED,
    EXCURSION_TAU_S,
    MAX_BACKOFF,
    OK,
    SPREAD_FACTOR,
    STATES,
    TREND_ROWS,
    WARNING,
)


class SensorMonitor(InstantFaults, Judgement, Readmission, Excursion, Settled):
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
    max_bend_c : array, optional
        Largest change of each sensor's one-sample change from one sample to the next in
        training (°C): ``jump_factor`` times it bounds the step of a sensor no other predicts
        against its own last step (:meth:`~.faults.InstantFaults._bent`).  ``None``: no bound.
    max_settle_c : array, optional
        Largest separation of two successive windows of each sensor in training (°C,
        :func:`~.settled.separation`): ``jump_factor`` times it bounds the level shift of a
        sensor no other predicts (:mod:`.settled`).  ``None``: no bound.
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
    rounding_c : float or array
        The most rounding the readings to their resolution moves each sensor's self-prediction
        error (°C; :meth:`from_training` fits it): a culprit beyond its band by less, whose
        excursion hovers, is a regime (:meth:`~.judgement.Judgement._within_rounding`).
    floor_c : float or array
        The floor of each sensor's warning band set by its training spread with every sensor in
        (°C; the alarm band's is twice it; :meth:`from_training` fits it, 0: none).
    moment : array, optional
        Second moment of training's windowed referenced snapshots (n × n): scales ``floor_c``
        to the set a sensor is judged in (:meth:`_bands_of`).  ``None``: the bands of the whole
        set judge every set.
    drift_warn_only : array of bool, optional
        Sensors whose self-prediction error is judged and warned but never excludes them (nor
        names them as explaining the others'); every other detector still excludes them.
        :meth:`from_training` marks the ambient sensors of a training that holds one campaign
        (quiet94).  ``None``: none.
    dithered : array of bool, optional
        Sensors whose reading's noise spans its resolution in training (:meth:`from_training`:
        the median absolute second difference at least ``DITHER`` times the smallest step): a
        constant run of one longer than ``blind_run`` is a freeze whatever the field did
        (mon97; a frozen ambient the slow field moves less than the warning band).  ``None``: none.
    """

    new_state, new_state_others = False, 2   # a monitor pickled before them judged as before

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state)
        if "_since" not in state:      # pickled before the new-state rule: its state, idle
            self._novel, self._calm_field = False, 0
            self._since = np.full(len(self.names), -1, dtype=np.int64)
        if "_slow" not in state:       # pickled before mon73: no memory of the field, no hover
            self._slow_reset()
            self._slow_ok = False
        if "rounding_c" not in state:  # pickled before mon83: judged as before
            self.rounding_c = np.zeros(len(self.names))
        if "floor_c" not in state:     # pickled before mon86: the whole set's bands judge
            self.floor_c, self.moment, self._q_full = np.zeros(len(self.names)), None, None
            self._warn, self._alarm = self.warning_c.copy(), self.alarm_c.copy()
        if "_froze" not in state:      # pickled before freeze84: nobody out for a freeze alone
            self._froze = np.zeros(len(self.names), dtype=bool)
            self._held, self._off = np.zeros(len(self.names)), np.zeros(len(self.names), int)
        if "drift_warn_only" not in state:   # pickled before quiet94: every sensor excludable
            self.drift_warn_only = np.zeros(len(self.names), dtype=bool)
        if "max_bend_c" not in state:  # pickled before step93: no step judged by its bend
            self.max_bend_c = np.full(len(self.names), np.inf)
            self._bend_lim, self._bends = self.max_bend_c.copy(), False
            self._last_step = np.full(len(self.names), np.nan)
        if "dithered" not in state:    # pickled before mon97: a predicted sensor's freeze by the field
            self.dithered = np.zeros(len(self.names), dtype=bool)
            self._dither_run = np.full(len(self.names), np.inf)
        if "_perm" not in state:       # pickled before wires100: the readings in their order
            self._perm = None
        if "max_settle_c" not in state:   # pickled before jump94b: no level shift judged
            self.max_settle_c = np.full(len(self.names), np.inf)
            self._set_settle_lim()
            self._settle_reset()
        if not {"_past", "_past_n"} <= state.keys():   # pickled before mon105c's ring / dep106's
            self._past_reset()

    def __init__(self, pod: ThermalPOD, names: Sequence[str], *, warning_c=0.4, alarm_c=0.8,
                 window: int = 10, confirm: int = 2, adaptive: bool = True,
                 exclude_at: str = "warning", max_step_c=None, max_bend_c=None, max_settle_c=None,
                 longest_run=None,
                 lo_c=None, hi_c=None, first_c=None, jump_factor: float = 3.0,
                 freeze_factor: float = 2.0, range_margin_c: float = 10.0,
                 new_state: bool = True, new_state_others: int = 2, rounding_c=0.0,
                 floor_c=0.0, moment=None, drift_warn_only=None, dithered=None):
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
        self.rounding_c = np.broadcast_to(np.asarray(rounding_c, float), (n,)).copy()
        self.floor_c = np.broadcast_to(np.asarray(floor_c, float), (n,)).copy()
        self.moment = None if moment is None else np.asarray(moment, float).reshape(n, n).copy()
        self.drift_warn_only = (np.zeros(n, dtype=bool) if drift_warn_only is None
                                else np.broadcast_to(np.asarray(drift_warn_only, bool), (n,)).copy())
        self._q_full = None if self.moment is None else self._error_moment(*pod.operator(
            np.ones(n, dtype=bool)), np.ones(n, dtype=bool))

        def arr(v, default):
            return np.full(n, default, float) if v is None else np.asarray(v, float).copy()

        self.max_step_c = arr(max_step_c, np.inf)
        self.max_bend_c = arr(max_bend_c, np.inf)
        self.max_settle_c = arr(max_settle_c, np.inf)
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
        # (mon97) a reading that dithers over its resolution repeats itself by chance only in
        # short runs, on a still field as on a moving one: past blind_run it is stuck (a frozen
        # ambient the slow field moved 0.16 °C, short of the band); a noiseless logger's reading
        # is not dithered (flat for hours on a settled machine, rounding83)
        self.dithered = (np.zeros(n, dtype=bool) if dithered is None
                         else np.broadcast_to(np.asarray(dithered, bool), (n,)).copy())
        self._dither_run = np.where(self.dithered, self._blind_run, np.inf)
        self._true = np.ones(n, dtype=bool)
        # which sensors the others can predict with every sensor in (re-admission check)
        self._predictable = pod.operator(self._true)[1] < pod.max_leverage
        # a sensor no other predicts: its step judged against its own last step too (_bent)
        self._bend_lim = np.where(self._predictable, np.inf, self.jump_factor * self.max_bend_c)
        self._bends = bool(np.isfinite(self._bend_lim).any())
        self._set_settle_lim()
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
        bends = np.vstack([np.abs(np.diff(a, n=2, axis=0)) for a in arrays if len(a) > 2]
                          or [np.full((1, len(names)), np.inf)])
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
            floor = 4 * spread
            warn = np.maximum(floor, 0.5 * warn)
            alarm = 2 * warn
        else:
            # never within `spread_factor` × the spread: a sensor the others predict loosely in
            # training does so on a healthy campaign of another season too (fl T_9: 0.24 °C in
            # training, past the 0.4 °C band on the test campaign, and the culprit pick then
            # excluded T_13 21 times); the others keep the configured bands
            floor = factor * spread
            warn, alarm = np.maximum(warn, floor), np.maximum(alarm, 2 * floor)
        # the windowed snapshots' second moment: the spread in any set of sensors (_bands_of)
        W = windowed_mean(snaps, groups, pod.window)
        # one campaign: the ambient's co-trend with the machine is that day's (the air warms
        # while the machine heats), no physics; it breaks once the stream leaves the rows the
        # POD was fitted on (quiet93: a healthy T_amb's forward spread 5.4x its in-sample one,
        # out by drift on 7 of 15 short records), so its error is warned, not acted on
        warn_only = [is_ambient(c) for c in names] if len(arrays) < 2 else None
        # (mon97) the reading's noise against its resolution; bends: its second differences
        # (no resolution seen: a sensor that never moved, or too short a training to tell)
        quantum, bend = _quantum(steps), np.median(bends, axis=0)
        dithered = (quantum > 0) & np.isfinite(bend) & (bend >= DITHER * quantum)
        options = {"rounding_c": _rounding(pod, steps), "floor_c": floor, "dithered": dithered,
                   "moment": W.T @ W / len(W), "drift_warn_only": warn_only, **options,
                   "warning_c": warn, "alarm_c": alarm}
        settle = largest_separation(arrays, int(options.get("window", 10)), len(names))
        return cls(pod, names, max_step_c=steps.max(0), max_bend_c=bends.max(0),
                   max_settle_c=settle, longest_run=runs,
                   lo_c=lo, hi_c=hi,
                   first_c=first, **options)

    # -- state ------------------------------------------------------------------------------
    _STATE = ("_ref", "_active", "_state", "_hist", "_err", "_pos", "_count", "_prev",
              "_prev_e", "_run", "_run_pred", "_clean", "_quiet", "_calm", "_prev_other",
              "_last_good", "_by_field", "_jumps", "_ref0", "_dropped", "_gap", "_gapped", "_dwell",
              "_outs", "_explains", "_novel", "_calm_field", "_since", "_slow", "_slow_t",
              "_slow_ok", "_ranged", "_froze", "_held", "_off", "_hid", "_last_step", "_settle",
              "_settle_age", "_perm", "_past", "_past_t", "_past_n", "_past_pos", "_past_rows",
              "_hold_to")

    def _set_settle_lim(self) -> None:
        # a sensor no other predicts: a level shift told by two windows (.settled)
        self._settle_lim = np.where(self._predictable, np.inf, self.jump_factor * self.max_settle_c)
        self._settle_cols = np.flatnonzero(np.isfinite(self._settle_lim))
        self._settles = bool(len(self._settle_cols))

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
        self._last_step = np.full(n, np.nan)   # each sensor's last one-sample change (_bent)
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
        self._hid = np.zeros(n, dtype=bool)          # ... as a culprit within its band (readmission.py)
        self._dropped = np.zeros(n, dtype=bool)      # its last detector to fire was a dropout
        self._ranged = np.zeros(n, dtype=bool)       # ... was out of range (readmission.py)
        self._froze = np.zeros(n, dtype=bool)        # out for a freeze alone (readmission.py)
        self._held = np.zeros(n)                     # ... the reading it held then
        self._off = np.zeros(n, dtype=np.int64)      # ... its readings in a row off that since
        # samples the next step spans (1 + missing ones since the last reading): the jump limit
        # is per sample (a warm-up across 6 missing rows read as a 4 °C jump, re-referenced away)
        self._gap = np.ones(n)
        self._gapped = False
        self._jumps = np.zeros(n, dtype=np.int64)    # jumps since it was last admitted
        self._ref0 = np.full(n, np.nan)              # its reference before the first of them
        self._run_pred = np.full(n, np.nan)
        self._perm = None            # (wires100) the readings' order where wires were exchanged
        self._clean = np.zeros(n)
        self._quiet = False          # every sensor active and ok: the fast path may run
        self._novel = False          # a new thermal state is declared (module doc)
        self._calm_field = 0         # samples since a judged sensor was last out of band
        self._since = np.full(n, -1, dtype=np.int64)   # sample count at its drift exclusion
        self._slow_reset()
        self._settle_reset()
        self._past_reset()
        self._set_operator()

    def _past_reset(self) -> None:
        """(mon105c) No readings kept yet; no held value read for a frozen sensor."""
        self._past = np.full((TREND_ROWS, len(self.names)), np.nan)   # referenced readings, ring
        self._past_t = np.full(TREND_ROWS, np.nan)                   # ... their times (s)
        self._past_n = np.full(TREND_ROWS, np.nan)      # ... their samples' numbers (dep106)
        self._past_pos, self._past_rows = 0, 0          # (rows seen, kept or not)
        self._hold_to = np.full(len(self.names), -np.inf)   # time until its held value is read

    def _past_push(self, D: np.ndarray, times) -> None:
        """Keep the rows ``D`` (referenced) taken at ``times`` (None: unknown) in the ring, those
        :func:`~.frozen_hold.kept` keeps (the ring where they one by one leave it)."""
        t = np.full(len(D), np.nan) if times is None else np.asarray(times, float)
        keep = np.flatnonzero(kept(t, self._past_t[(self._past_pos - 1) % TREND_ROWS], EXCURSION_TAU_S))
        n, keep = len(keep), keep[-TREND_ROWS:]
        where = (self._past_pos + n - len(keep) + np.arange(len(keep))) % TREND_ROWS
        self._past[where], self._past_t[where] = D[keep], t[keep]
        self._past_n[where] = self._past_rows + keep
        self._past_pos = int((self._past_pos + n) % TREND_ROWS)
        self._past_rows += len(D)

    def _hold_until(self, j: int) -> float:
        """(mon105c) Until when (s) the model reads sensor ``j``'s held value, just excluded for a
        freeze, instead of its stand-in: its rate fitted to its own readings over the
        ``EXCURSION_TAU_S`` before its constant run began, the drift that rate projects, over
        at least the span fitted, within the stand-in's training spread (-inf: never; a still
        ambient's held reading beat its drifting stand-in, a falling structure sensor's did not)."""
        return held_until(self._past_t, self._past[:, j], self._past_n, self._past_pos,
                          self._past_rows - int(self._run[j]), EXCURSION_TAU_S,
                          self.floor_c[j] / SPREAD_FACTOR)

    def _read_held(self, time: float) -> np.ndarray:
        """Sensors out for a freeze alone whose held value the model reads (:meth:`_hold_until`)."""
        return self._froze & ~self._active & (self._off == 0) & (time <= self._hold_to)

    def _operator(self, subset: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The POD operator of the sensors ``subset`` and every sensor's leverage in it (1, no
        prediction, outside it)."""
        M, h = self.pod.operator(subset)
        lev = np.ones(len(self.names))
        lev[subset] = h
        return M, lev

    def _error_moment(self, M: np.ndarray, h: np.ndarray, subset: np.ndarray) -> np.ndarray:
        """Each sensor of ``subset``'s windowed leave-one-out error's second moment in training,
        ``a' C a`` (``a`` its row of the error's linear map of the readings, ``C`` the
        ``moment``); NaN outside ``subset`` and where no other sensor predicts it."""
        n = len(self.names)
        A = np.zeros((n, n))
        A[:, subset] = -M
        A[np.arange(n), np.arange(n)] += 1.0
        seen = np.zeros(n, dtype=bool)
        seen[subset] = h < self.pod.max_leverage
        q = np.full(n, np.nan)
        S = A[seen] / (1 - h[seen[subset]])[:, None]
        q[seen] = np.einsum("ij,jk,ik->i", S, self.moment, S)
        return q

    def _bands_of(self, subset: np.ndarray, M=None, h=None) -> tuple[np.ndarray, np.ndarray]:
        """``(warning, alarm)`` bands of the sensors judged in ``subset`` (mon86): the floor of
        each, its training spread's, scaled by its windowed error's RMS in ``subset`` against the
        whole set's (at least 1), never narrower than the whole set's bands.  A set without a
        coupled partner predicts a sensor worse (fl_thermal's ``T_t14`` without ``T_t12``:
        training spread 0.112 -> 0.166 °C); judged against the whole set's band it warned 15
        times, healthy.  ``M`` / ``h``: ``pod.operator(subset)``, when at hand."""
        subset = np.asarray(subset, dtype=bool)
        if self.moment is None or subset.all() or not subset.any() or not self.floor_c.any():
            return self.warning_c, self.alarm_c
        if M is None:
            M, h = self.pod.operator(subset)
        with np.errstate(divide="ignore", invalid="ignore"):
            g = np.sqrt(self._error_moment(M, h, subset) / self._q_full)
        g = np.where(np.isfinite(g) & (g > 1), g, 1.0)
        return (np.maximum(self.warning_c, self.floor_c * g),
                np.maximum(self.alarm_c, 2 * self.floor_c * g))

    def _set_bands(self, M=None, lev=None) -> None:
        """The bands the active sensors are judged against: those of the active set with every
        culprit out within its own band (``_hid``) counted in (mon86: out on the monitor's guess,
        it loosens no band; the drift it hid, its coupled partner, would be hidden further).
        ``M`` / ``lev``: the active set's operator, when that is the set."""
        s = self._active | self._hid
        if not self._active.any():
            self._warn, self._alarm = self.warning_c, self.alarm_c
        elif (s != self._active).any() or M is None:
            self._warn, self._alarm = self._bands_of(s)
        else:
            self._warn, self._alarm = self._bands_of(s, M, lev[s])

    def _set_operator(self) -> None:
        """Operator, leverages, error scale and bands of the active set; the window's errors
        redone."""
        active = self._active
        self._all_active = bool(active.all())
        M, lev = self._operator(active) if active.any() else (None, np.ones(len(self.names)))
        self._M = M
        self._lev = lev
        self._set_bands(M, lev)
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
    def _judging(self) -> np.ndarray:
        """The judged sensors whose error is the drift rule's evidence (judgement.py): a
        ``drift_warn_only`` one's is judged and warned, not acted on."""
        return self._judged & ~self.drift_warn_only

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
        return (a >= self._warn).view(np.int8) + (a >= self._alarm), err

    def skipped(self, periods: float) -> None:
        """The next sample comes ``periods`` sampling periods after the last one (a gap in the
        record's time): each sensor may have moved by that many one-sample steps, as over its
        own missing samples (a machine that warmed while nothing was logged is no jump, nor the
        logger's common step)."""
        if periods > 1:
            self._gap = np.maximum(self._gap, float(periods))
            self._gapped = True

    def update(self, reading, time: float = float("nan")) -> tuple[np.ndarray, list[dict]]:
        """One sample (absolute °C, order of ``names``) -> (referenced field for the model,
        events).  Never NaN unless every sensor has been missing since the start."""
        x = np.asarray(reading, dtype=float)
        settled: list[dict] = []
        with np.errstate(invalid="ignore"):    # NaN (missing, unobservable) compares False
            x = self._exchanged(x, time, settled)     # (wires100) before every check
            if self._settles:
                self._settled(x, time, settled)
                ref = None if self._ref is None else self._ref.copy()
            clean = self._fast(x, time) if self._quiet else None
            out = (clean, []) if clean is not None else self._update(x, time)
        if self._settles:
            self._settle_push(ref)
        self._slow_step(self._hist[(self._pos - 1) % self.window], float(time))
        self._past_pos, self._past_rows = push_row(       # the row, where _past_push keeps it
            self._past, self._past_t, self._past_n, self._past_pos, self._past_rows,
            self._hist[(self._pos - 1) % self.window], time, EXCURSION_TAU_S)
        if clean is None:    # a new thermal state counts its calm samples on the full path
            self._quiet = self._rebuilds and not self._novel and not self._state[self._active].any()
        if settled:          # the next sample on the full path
            self._quiet = False
            return out[0], settled + out[1]
        return out

    @property
    def last_error_(self) -> np.ndarray:
        """Error per sensor over the last ``confirm`` samples (NaN: not judged)."""
        k = min(self._count, self.confirm)
        if not k:
            return np.full(len(self.names), np.nan)
        err = self._err[self._recent[self._pos, :k]].sum(axis=0) / k
        return np.where(self._judged | ~self._active, err, np.nan)

    def _fast(self, x: np.ndarray, time: float = float("nan")):
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
                or (np.abs(step) > (self._jump_lim * self._gap if self._gapped else self._jump_lim)).any()
                or (self._bends and (np.abs(step - self._last_step) > self._bend_lim).any())):
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
            if (judged & ((ae >= self._alarm) | (a >= self._warn))).any():
                return None
            if ((self._calm + 1 >= self.window) & ~self._active).any():
                return None                  # an excluded sensor may be due for re-admission
            if (self._froze & ((d != self._held) | (self._off > 0))).any():
                return None                  # one out for a freeze reads off its held value
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
        self._last_step = (step if self._all_active and not self._gapped   # none of one out
                           else np.where(self._active & (self._gap == 1), step, np.nan))
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
            self._active, d, np.where(self._predictable & ~self._read_held(time), pred, self._last_good))
        if self._all_active:
            self._last_good = d
        else:
            self._last_good = np.where(self._active, d, self._last_good)
        self._clean = clean
        return clean

    def update_block(self, X: np.ndarray, times=None) -> np.ndarray:
        """The referenced field of the first rows of ``X`` (absolute °C, (m, order of ``names``))
        that :meth:`update` takes on its fast path (:meth:`_fast`: every sensor active and ok,
        every reading there, nothing firing), in one go; the rows after them are for
        :meth:`update`.  Returns as many rows as it took (none: the next row needs the full
        path).  The state is the one :meth:`update` leaves row by row (the ring of readings and
        errors, the runs of equal readings, the calm counts): a lead-in of a year is read at
        once (warm59), each detector judged on every row as :meth:`_fast` judges it.  ``times``:
        the rows' times (s), for the memory of the field (:mod:`.excursion`; none: unknown)."""
        n = len(self.names)
        X = np.asarray(X, dtype=float)
        if self._perm is not None:      # (wires100) two wires read exchanged
            X = X[:, self._perm]
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
            if self._bends:
                last = np.vstack([self._last_step, step[:-1]])
                ok &= ~(np.abs(step - last) > self._bend_lim).any(axis=1)
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
            if self._settles:
                ok &= ~self._settle_block(d)
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
        last = step[m - 1] if m > 1 or not self._gapped else np.where(
            self._gap == 1, step[0], np.nan)           # none over a gap
        self._last_step = last if self._all_active else np.where(self._active, last, np.nan)
        if self._gapped:
            self._gap, self._gapped = np.ones(n), False
        self._last_good = self._clean = d[m - 1]
        self._slow_block(d[:m], None if times is None else np.asarray(times, float)[:m])
        self._past_push(d[:m], None if times is None else np.asarray(times, float)[:m])
        if self._settles:
            self._settle_commit(d[:m])
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
        was_in = self._active.copy()
        if self._bends:
            step, big = self._bent(d, step, big, rng | ~finite, pos, time, events)
        if (big & ~self._active).any() and not (rng | ~np.isfinite(d)).any():
            big = self._spike_back(x, d, big, pos, time, events)
        if not all_finite or (rng | big).any():
            instant = self._instant(x, d, step, finite, rng, big & ~rng)
            for j, why in instant.items():
                self._froze[j] = False       # out for another reason now: judged as such
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
        self._off = np.where(self._froze & finite & (d != self._held), self._off + 1, 0)
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
        # the change each sensor read took (after any re-reference); none over a gap of its own,
        # of a jump, of a sensor out or back this sample (a return's undo is no step: step93b)
        self._last_step = np.where(finite & (self._gap == 1) & ~big & was_in & self._active,
                                   d - self._prev, np.nan)
        self._prev = np.where(finite, d, self._prev)
        self._gap = np.where(finite, 1.0, self._gap + 1)
        self._gapped = bool((self._gap > 1).any())
        self._prev_e = e
        for j in instant:
            self._dropped[j] = not np.isfinite(x[j])
            self._ranged[j] = bool(rng[j])
        good = self._active & finite
        self._last_good = np.where(good, d, self._last_good)
        if not self._rebuilds:
            # too few sensors in to rebuild the field: a sensor out only for a dropout whose
            # reading is back feeds the model while it waits out its window, nearer the truth
            # than a held value (10 held samples of a warm-up doubled the adaptive error)
            good = good | (self._dropped & finite & (self._run == 0))
        # an excluded sensor: rebuilt from the field, or held where the others cannot predict it
        clean = d if (self._all_active and all_finite) else np.where(
            good, d, np.where(self._predictable & ~self._read_held(time), pred, self._last_good))
        if not np.isfinite(clean.sum()):
            clean = np.where(np.isfinite(clean), clean, self._clean)   # nothing to rebuild from
        self._clean = clean
        return clean, events




















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
            band = (self._warn if level == WARNING else self._alarm)[j]
            return f", all beyond ±{band:.3g} °C (the smallest {smallest:.3g})"
        return f", the smallest {smallest:.3g} within ±{self._warn[j]:.3g} °C"





    def _exclude(self, j: int, reason: str, time: float, events: list, by_field: bool = False) -> None:
        if not self.adaptive:
            self._set_state(j, ALARM, time, reason, events)
            return
        if not self._predictable[j]:   # say so: for a frozen sensor the exclusion changes nothing
            reason += "; held at its last good reading: no other sensor predicts it"
        self._active[j] = False
        self._hid[j] = False
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


def _rounding(pod: ThermalPOD, steps: np.ndarray) -> np.ndarray:
    """The most rounding the readings to their resolution moves each sensor's self-prediction
    error, every sensor in: ``(q / 2) · sum_k |(I - M)_jk| / (1 - h_j)``, ``q_k`` sensor ``k``'s
    smallest non-zero one-sample step in training (``steps``; a logger's 0.1 K, about none on a
    continuous reading); 0 where no other sensor predicts it (mon82c's bound)."""
    n = pod.n_features_in_
    M, h = pod.operator(np.ones(n, dtype=bool))
    q = _quantum(steps)
    S = (np.eye(n) - M) / np.maximum(1 - h, 1e-12)[:, None]
    return np.where(h < pod.max_leverage, 0.5 * np.abs(S) @ q, 0.0)


def _quantum(steps: np.ndarray) -> np.ndarray:
    """Each sensor's resolution as training shows it: its smallest non-zero one-sample step
    (``steps``, absolute; a logger's 0.1 K, about none on a continuous reading), 0 for a sensor
    that never moved."""
    q = np.array([np.min(s[s > 0], initial=np.inf) for s in steps.T])
    q[~np.isfinite(q)] = 0.0
    return q
