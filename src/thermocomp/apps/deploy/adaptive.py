"""The fault-tolerant deployable compensator: surveillance, adaptive inputs, guarded output.

:class:`AdaptiveCompensator` wraps a :class:`~thermocomp.apps.deploy.StreamingCompensator`
and puts in front of it a :class:`~.surveillance.SensorMonitor` (every
temperature the model reads is judged; an excluded or missing one is replaced
by its POD reconstruction from the healthy ones), and behind it a
:class:`~.guard.CorrectionGuard` (bounded, rate-limited correction).  It also
checks ``time`` (NaN, repeated or backwards: taken as the previous time plus
the sampling period, :mod:`thermocomp.core.timerule`) and holds a missing non-temperature
input (``S_`` signal) at its last value.  A correction is produced for every sample.  (dup99) A
row written again (its time not after the last read, every input as the last sample's:
:func:`~thermocomp.core.timerule.repeats`) is skipped before all of it, the last correction
given again, counted in ``n_repeated_`` (an event ``time`` -> ``repeated`` at a burst's first row):
a logger re-sending its last sample 12 times was ten sensors frozen.

It has the interface of the streaming compensator (``columns_``, ``targets_``,
``reset``, ``step``, ``predict``), so ``replay``, ``promote`` and the pyfunc use
either; :meth:`predict` adds ``excluded_inputs`` and ``events`` columns.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from contextlib import contextmanager

import numpy as np
import pandas as pd

from ...core.context import AMBIENT_C0, TIME, step_gain
from ...core.frame import context_record
from ...core.io.own_headers import as_named
from ...core.timerule import SampleClock, repeats
from .fallback import sensor_fallbacks
from .guard import CorrectionGuard
from .held_gains import held_factor_gain, stepped_gain
from .pod import ThermalPOD
from .streaming import STREAM_ID, OutOfEnvelopeError, StreamingCompensator, step_block
from .surveillance import SensorMonitor

INPUT_ROWS = 4096    # rows the monitor reads in one go at most (a failed try costs little per row)
# a sample this many sampling periods after the one before follows a gap in the record (a
# logger stopped; a continued chain whose campaign starts rows after its predecessor ended): the
# monitor judges its step as that many one-sample steps (probe61: the warm-up of 6.5 h between
# two weekly files, read as the logger's common step, re-referenced every sensor by it)
GAP_PERIODS = 1.5


class AdaptiveCompensator:
    """Streaming compensator + sensor monitor + correction guard (see module doc).

    Parameters
    ----------
    streaming : StreamingCompensator
    monitor : SensorMonitor, optional
        Over the ``T_`` columns of ``streaming.columns_`` (``monitor.names``).
    guard : CorrectionGuard, optional
    period_s : float
        Nominal sampling period (substitute for a bad ``time``).

    Attributes ``lab_names_``, ``slashed_``, ``end_states_`` and ``adapt_``: as
    :class:`StreamingCompensator`'s (the deployed object carries them; end states are of this
    adaptive stream).
    """

    lab_names_: dict = {}      # replaced, never mutated (older pickles have none)
    n_repeated_ = 0            # (dup99; older pickles have none of these three)
    _u_last = None
    _repeating = False
    lab_units_: dict = {}      # the lab's headers in another unit (naming.lab_units): likewise
    derived_: dict = {}        # data.derive's targets, computed from a block's errors: likewise
    bits_: dict = {}           # data.bits, a status word a served block decodes: likewise (bits85)
    slashed_ = None            # the record's order of dates with slashes (older pickles: none)
    day_seconds_ = None        # (dep108d) its time plain seconds of the day (None: its header says)
    missing_values_: list = []  # data.missing_values, a served block's marks: likewise (lab74)
    end_states_: dict = {}
    adapt_ = None
    # {sensor: the family fitted without it} (fallback.py): its correction while the sensor is out
    fallbacks_: dict = {}

    def __init__(self, streaming: StreamingCompensator, monitor: SensorMonitor | None = None,
                 guard: CorrectionGuard | None = None, period_s: float = 1.0):
        self.streaming, self.monitor, self.guard = streaming, monitor, guard
        self.period_s = float(period_s)
        cols = streaming.columns_
        if monitor is not None:
            unknown = [c for c in monitor.names if c not in cols]
            if unknown:
                raise ValueError(f"monitored sensors {unknown} are not inputs of the compensator")
        self._mon = np.array([cols.index(c) for c in monitor.names] if monitor else [], dtype=int)
        self._other = np.array([j for j, c in enumerate(cols) if j not in set(self._mon)], dtype=int)
        self._mon_all = len(self._mon) == len(cols) and bool(np.all(self._mon == np.arange(len(cols))))
        self.reset()

    @classmethod
    def from_training(cls, streaming: StreamingCompensator, campaigns: Mapping[str, pd.DataFrame],
                      *, monitor: dict | None = None, pod: dict | None = None,
                      guard: dict | None = None, learned_bands: bool = False,
                      fallbacks: str = "unobservable") -> "AdaptiveCompensator":
        """Fit the POD, the detectors' limits, the guard and (``fallbacks``, :mod:`.fallback`)
        the sensor fallbacks on the training campaigns."""
        comp = streaming.compensator
        names = [c for c in streaming.columns_ if c.startswith("T_")]
        mon = None
        if len(names) >= 3:
            raw = {c: df[names].to_numpy(float) for c, df in campaigns.items()}
            mon = SensorMonitor.from_training(ThermalPOD(**pod) if pod else None, names, raw,
                                              learned_bands=learned_bands, **(monitor or {}))
        predicted = comp.predict(campaigns, mode="simulation")
        measured = comp.measured(campaigns, predicted=predicted)
        times = [df[TIME].to_numpy(float) if TIME in df.columns else np.arange(len(df), dtype=float)
                 for df in campaigns.values()]
        guard = dict(guard or {})
        follow = bool(guard.pop("follow_inputs", True))
        g = CorrectionGuard.from_training(
            streaming.targets_, [measured[c][streaming.targets_].to_numpy(float) for c in campaigns],
            times, **guard,
            predicted=[predicted[c][streaming.targets_].to_numpy(float) for c in campaigns])
        if follow and streaming.envelope is not None:
            m = comp.stacked(campaigns, targets=[])     # the envelope's data, before its margin
            gains = input_gains(streaming, training_ambients(m), m, g.period_s)
            g.follow_inputs(gains, m.X.min().to_numpy(float), m.X.max().to_numpy(float))
        out = cls(streaming, mon, g, g.period_s)
        if mon is not None:
            out.fallbacks_ = sensor_fallbacks(streaming, mon, campaigns, fallbacks)
            out.reset()
        return out

    # -- the streaming-compensator interface ---------------------------------------------------
    @property
    def compensator(self):
        return self.streaming.compensator

    @property
    def columns_(self):
        return self.streaming.columns_

    @property
    def targets_(self):
        return self.streaming.targets_

    @property
    def time_required_(self):
        return self.streaming.time_required_

    @property
    def envelope(self):
        return self.streaming.envelope

    @property
    def policy(self):
        return self.streaming.policy

    @contextmanager
    def envelope_off(self):
        with self.streaming.envelope_off():
            yield self

    @property
    def _absolute(self) -> bool:
        """The model reads absolute temperatures (``data.reference=none``), not changes."""
        return self.streaming.compensator.reference != "first_sample"

    @property
    def clock_time_(self) -> float:
        """The last sample's time on the stream's clock (:mod:`thermocomp.core.timerule`): event
        times are on it."""
        return self._clock.t

    @property
    def excluded_inputs(self) -> list[str]:
        return self.monitor.excluded if self.monitor is not None else []

    def reset(self, ambient_c: float = float("nan")) -> None:
        """New campaign (see :meth:`StreamingCompensator.reset`)."""
        self.streaming.reset(ambient_c)
        for fallback in self.fallbacks_.values():
            fallback.reset(ambient_c)
        if self.monitor is not None:
            self.monitor.reset()
        if self.guard is not None:
            self.guard.reset()
        self._base = None
        self._late = None
        self._clock = SampleClock(self.period_s)
        self._held = np.full(len(self._other), np.nan)
        self._held_state = np.zeros(len(self._other), dtype=bool)
        self._time_bad = False
        self._y = None
        self.last_events_: list[dict] = []
        self.rows_events_: list[dict] = []
        self.n_samples_ = 0
        self.n_repeated_ = 0
        self._u_last = None       # (dup99) the inputs of the last sample stepped on, as read
        self._repeating = False   # the last row was one written again

    def __setstate__(self, state: dict) -> None:
        if "_clock" not in state:     # pickled before the time rule (timerule.py)
            state["_clock"] = SampleClock(state["period_s"])
            state["_clock"].restore(_clock_of(state.pop("_last_time", float("nan")),
                                              state.pop("_last_read", float("nan"))))
        self.__dict__.update(state)

    def _snapshot(self) -> tuple:
        return (self.streaming._snapshot(), self.monitor.snapshot() if self.monitor else None,
                self.guard.snapshot() if self.guard else None,
                None if self._base is None else self._base.copy(),
                None if self._late is None else self._late.copy(), self._clock.snapshot(),
                self._held.copy(), self._held_state.copy(), self._time_bad,
                None if self._y is None else self._y.copy(), self.n_samples_,
                {s: f._snapshot() for s, f in self.fallbacks_.items()},
                (self._u_last, self._repeating, self.n_repeated_))

    def _restore(self, snap: tuple) -> None:
        if not isinstance(snap[5], tuple):   # taken before the time rule (an older model's)
            snap = (*snap[:5], _clock_of(snap[5], snap[6]), *snap[7:])
        if len(snap) == 11:     # taken before the fallbacks (fallback.py): none to restore
            snap = (*snap, {})
        if len(snap) == 12:     # taken before dup99: no row to repeat yet
            snap = (*snap, (None, False, 0))
        (s, m, g, self._base, self._late, clock, self._held,
         self._held_state, self._time_bad, self._y, self.n_samples_, falls, repeat) = snap
        self._u_last, self._repeating, self.n_repeated_ = repeat
        for sensor, fallback in self.fallbacks_.items():
            if sensor in falls:
                fallback._restore(falls[sensor])
        self._clock.restore(clock)
        self.streaming._restore(s)
        if self.monitor is not None:
            self.monitor.restore(m)
        if self.guard is not None:
            self.guard.restore(g)

    # -- one sample -------------------------------------------------------------------------------
    def step(self, x_row, time: float = float("nan")) -> np.ndarray:
        """One sample (order of ``columns_``) -> guarded correction per target (µm of error)."""
        return self._step(np.asarray(x_row, dtype=float), time)[0]

    def _step(self, x: np.ndarray, time: float) -> tuple[np.ndarray, int]:
        self.last_events_: list[dict] = []    # a step that fails reports none, not the last ones
        events: list[dict] = []
        if self._repeated(x, float(time), events):
            self.last_events_ = events
            return self._y, 0
        t, dt = self._check_time(float(time), events)
        read = x if self._mon_all else x[self._mon]
        x = self._inputs(x, t, events, dt)
        take = None
        try:
            y, clamped = self.streaming._step(x, t, clocked=True)
            stepped, take = True, getattr(self.streaming, "last_take_", None)
        except ValueError as exc:    # OutOfEnvelopeError (policy=refuse) and its kin
            y, clamped, stepped = np.full(len(self.targets_), np.nan), 0, False
            events.append(_held_event(t, exc))
        if self.fallbacks_:
            out = self._fallen_back(read)
            falls = {}
            for sensor, fallback in self.fallbacks_.items():
                try:
                    falls[sensor] = fallback._step(x, t, clocked=True)[0]
                except ValueError:
                    pass
            if stepped and out in falls:
                y, take = falls[out], getattr(self.fallbacks_[out], "last_take_", None)
        self._output(y, dt, t, self._allowance(stepped), events, take)
        return self._y, clamped

    def _repeated(self, x: np.ndarray, time: float, events: list) -> bool:
        """(dup99) Whether the row is one written again (module doc), counted, its event added
        at a burst's first; else it is the last row read."""
        if self._u_last is None or not repeats(
                self._clock.snapshot(), time, x, self._u_last):
            self._u_last, self._repeating = np.array(x, dtype=float), False
            return False
        if not self._repeating:
            events.append({"time": self._clock.t, "sensor": TIME, "from": "ok", "to": "repeated",
                           "reason": f"row written again (time {time:.6g} s not after the last "
                                     "read, every input as the last sample's): skipped, the last "
                                     "correction given again"})
        self._repeating = True
        self.n_repeated_ += 1
        return True

    def _fallen_back(self, read: np.ndarray) -> str | None:
        """The excluded sensor whose fallback gives the correction (the first of the monitor's
        order with one), or ``None``: not while too few sensors are in to rebuild the field (the
        fallback would read stand-ins only; the correction is held), nor for a sensor out for a
        dropout that reads again (``read``: the monitored readings of the row) while it waits
        out its window (its held reading, a window old at most, is the better stand-in: one
        empty logger row cost 1.35 against 1.30 µm, tests/shell/test_monitor_lab57.py)."""
        mon = self.monitor
        if not self.fallbacks_ or mon is None or not mon._rebuilds:
            return None
        back = mon._dropped & np.isfinite(read)
        return next((s for s, out, b in zip(mon.names, ~mon._active, back)
                     if out and not b and s in self.fallbacks_), None)

    def _inputs(self, x: np.ndarray, t: float, events: list, dt: float | None = None
                ) -> np.ndarray:
        """The row the model reads: the monitored temperatures judged (an excluded one replaced),
        a missing other input held; ``dt`` (s) since the row before (a gap: :data:`GAP_PERIODS`)."""
        if self.monitor is not None:
            if dt is not None and dt > GAP_PERIODS * self.period_s:
                self.monitor.skipped(dt / self.period_s)
            clean, ev = self.monitor.update(x if self._mon_all else x[self._mon], t)
            events += ev
            ref = self.monitor._ref
            if self._base is None:
                self._base = np.where(np.isfinite(ref), ref, self.monitor.first_c)
                self._late = ~np.isfinite(ref)
            elif self._absolute and self._late.any():
                # a model of absolute readings sees a sensor missing at the start as read once it
                # is referenced (a model of changes keeps the stand-in: its reference is row 0)
                now = self._late & np.isfinite(ref)
                self._base[now] = ref[now]
                self._late &= ~now
            if self._mon_all:
                x = self._base + clean
            else:
                x = x.copy()
                x[self._mon] = self._base + clean
        if len(self._other):
            if self.monitor is None:
                x = x.copy()
            x[self._other] = self._hold(x[self._other], t, events)
        return x

    def _output(self, y: np.ndarray, dt: float, t: float, allowance, events: list,
                take: np.ndarray | None = None) -> None:
        """The guarded correction of the model's ``y`` (``self._y``; ``take``: the clamp's,
        :meth:`~.guard.CorrectionGuard.step`); the row counted, its events kept."""
        if self.guard is not None:
            y, ev = self.guard.step(y, dt, t, self.monitor is not None and self.monitor.new_state_,
                                    allowance, take)
            events += ev
        elif not np.all(np.isfinite(y)):
            y = np.where(np.isfinite(y), y, 0.0 if self._y is None else self._y)
        self._y = y
        self.n_samples_ += 1
        self.last_events_ = events

    def run_rows(self, X: np.ndarray, time: np.ndarray, on_refused=None
                 ) -> tuple[np.ndarray, np.ndarray]:
        """``(y, n_clamped)`` of the rows of ``X`` streamed one after the other, as :meth:`_step`
        gives them, in three passes (the model reads nothing of the monitor's or the guard's
        state, nor they of its): the time rule, the monitor and the hold; the plain stream over
        the rows they give (:meth:`StreamingCompensator.run_rows`); the guard.  Each pass takes
        in one go the rows its fast path takes as they are (the time read in order, every sensor
        ok and nothing firing, no missing input, a correction within rate and bound), the others
        row by row.  Each row's events are dropped but the last row's (``last_events_``).  A
        ``ValueError`` of the time rule or the monitor goes to ``on_refused(i, exc)`` (raised
        without it), as :meth:`_step` raises it."""
        n = len(X)
        xs = np.array(X, dtype=float, copy=True)
        ts, dts = np.empty(n), np.empty(n)
        novel = np.zeros(n, dtype=bool)
        fallen = np.full(n, None, dtype=object)     # the fallback each row reads (none: the model)
        events: dict[int, list] = {}
        done = np.ones(n, dtype=bool)
        skipped = np.zeros(n, dtype=bool)      # (dup99) rows written again
        given = self._y                        # the last correction given before the rows
        i = 0
        while i < n:
            m = self._inputs_block(X, time, i, xs, ts, dts, novel)
            if m:
                i += m
                continue
            events[i] = row_events = []
            if self._repeated(X[i], float(time[i]), row_events):
                skipped[i], done[i] = True, False
                i += 1
                continue
            try:
                ts[i], dts[i] = self._check_time(float(time[i]), row_events)
                xs[i] = self._inputs(xs[i], ts[i], row_events, dts[i])
                novel[i] = self.monitor is not None and self.monitor.new_state_
                fallen[i] = self._fallen_back(X[i] if self._mon_all else X[i, self._mon])
            except ValueError as exc:
                if on_refused is None:
                    raise
                done[i] = False
                on_refused(i, exc)
            i += 1
        refused = np.zeros(n, dtype=bool)

        def held(k: int, exc: ValueError) -> None:
            refused[rows[k]] = True
            events.setdefault(rows[k], []).append(_held_event(ts[rows[k]], exc))

        rows = np.flatnonzero(done)
        y, clamps, dx = self.streaming.run_rows(xs[rows], ts[rows], clocked=True, on_refused=held)
        takes = _takes(self.streaming, y)
        for sensor, fallback in self.fallbacks_.items():
            ys = fallback.run_rows(xs[rows], ts[rows], clocked=True,
                                   on_refused=lambda k, exc: None)[0]
            use = (fallen[rows] == sensor) & ~refused[rows] & np.isfinite(ys).all(axis=1)
            y[use], takes[use] = ys[use], _takes(fallback, ys)[use]
        out = np.full((n, len(self.targets_)), np.nan)
        clamped = np.zeros(n, dtype=np.int64)
        clamped[rows] = clamps
        self._guard_rows(rows, y, dx, dts, ts, novel, refused, events, out, takes)
        for i in np.flatnonzero(skipped):      # the last correction given again
            before = rows[rows < i]
            out[i] = out[before[-1]] if len(before) else (np.nan if given is None else given)
        self.last_events_ = events.get(n - 1, []) if n else []
        # every row's, in order: what the monitor did over a lead-in it was warmed on (deploy88)
        self.rows_events_ = [e for k in sorted(events) for e in events[k]]
        return out, clamped

    def _inputs_block(self, X, time, start: int, xs, ts, dts, novel) -> int:
        """The rows from ``start`` that the time rule, the monitor and the hold take on their fast
        paths, in one go (``xs``, ``ts``, ``dts``, ``novel`` filled in); how many (0: the next
        row goes row by row)."""
        mon = self.monitor
        if self._time_bad or (mon is not None and (
                self._base is None or (self._absolute and self._late.any()))):
            return 0
        if self._held_state.any():
            return 0
        first, t_prev, t_read, shift = self._clock.snapshot()[:4]
        if first or not np.isfinite(shift):
            return 0
        block = X[start:start + INPUT_ROWS]
        t = np.asarray(time[start:start + len(block)], dtype=float)
        with np.errstate(invalid="ignore"):          # a missing time compares False: not read
            ok = t > np.r_[t_read, t[:-1]]
            # a row after a gap in time (GAP_PERIODS) starts a block of its own: the monitor
            # judges its step over the gap
            gap = np.diff(np.r_[t_read, t]) > GAP_PERIODS * self.period_s
        ok[1:] &= ~gap[1:]
        if len(self._other):
            ok &= np.isfinite(block[:, self._other]).all(axis=1)
        m = len(block) if ok.all() else int(np.argmin(ok))
        if not m:
            return 0
        block = block[:m].copy()
        if mon is not None:
            if gap[0]:
                mon.skipped((t[0] - t_read) / self.period_s)
            clean = mon.update_block(block if self._mon_all else block[:, self._mon], t - shift)
            m = len(clean)
            if not m:
                return 0
            block = block[:m]
            if self._mon_all:
                block = self._base + clean
            else:
                block[:, self._mon] = self._base + clean
        rows = slice(start, start + m)
        now = t[:m] - shift                          # the clock's own subtraction
        xs[rows], ts[rows], dts[rows] = block, now, np.diff(np.r_[t_prev, now])
        novel[rows] = mon is not None and mon.new_state_
        self._clock.restore((False, float(now[-1]), float(t[m - 1]), shift))
        self._u_last, self._repeating = np.array(X[start + m - 1], dtype=float), False
        if len(self._other):
            self._held = block[-1, self._other].copy()
        return m

    def _guard_rows(self, rows, y, dx, dts, ts, novel, refused, events, out, takes) -> None:
        """The guard over the plain stream's ``y`` of ``rows`` (``out`` filled in, ``events``
        added to; ``takes``: the clamp's per row): in one go where its fast path takes them, else
        row by row as :meth:`_step`."""
        guard = self.guard
        # rows the guard may take in one go: stepped, no allowance (the inputs in their range)
        plain = ~refused[rows]
        env = self.envelope
        if (guard is not None and guard.in_gain is not None and self.policy == "clamp"
                and env is not None and env.basis is not None):   # a bound that follows them
            with np.errstate(invalid="ignore"):
                beyond = np.maximum(dx - guard.in_hi, guard.in_lo - dx).max(axis=1) > 0.0
            plain &= ~beyond
        nxt = np.minimum.accumulate(np.where(plain, len(rows), np.arange(len(rows)))[::-1])[::-1]
        k = 0
        while k < len(rows):
            if guard is not None and plain[k]:
                r = rows[k:nxt[k]]
                m = guard.step_block(y[k:nxt[k]], dts[r], novel[r], takes[k:nxt[k]])
                if m:
                    out[rows[k:k + m]] = y[k:k + m]
                    self._y = y[k + m - 1].copy()
                    self.n_samples_ += m
                    k += m
                    continue
            i = rows[k]
            row_events = events.setdefault(i, [])
            allowance = None if refused[i] or guard is None else \
                stream_allowance(guard, self.streaming, dx[k])
            if guard is not None:
                y_i, ev = guard.step(y[k], dts[i], ts[i], novel[i], allowance,
                                     None if refused[i] else takes[k])
                row_events += ev
            else:
                y_i = y[k]
                if not np.all(np.isfinite(y_i)):
                    y_i = np.where(np.isfinite(y_i), y_i, 0.0 if self._y is None else self._y)
            self._y = out[i] = y_i
            self.n_samples_ += 1
            k += 1

    def _allowance(self, stepped: bool) -> np.ndarray | None:
        return stream_allowance(self.guard, self.streaming) if stepped else None

    def _check_time(self, t: float, events: list) -> tuple[float, float]:
        # the time rule of every deployed form (timerule.py); a bad time is judged against the
        # last time *read*, not the last one used: after a swapped pair of rows the substitutes
        # run one period ahead of the record, and judging against them kept every later time
        # 'substituted' to the end of the stream
        t, dt, bad = self._clock.step(t)
        if bad is not None:
            if not self._time_bad:
                events.append({"time": t, "sensor": TIME, "from": "ok", "to": "substituted",
                               "reason": f"{bad}: taken as previous + {self.period_s:g} s"})
            self._time_bad = True
        elif self._time_bad:
            events.append({"time": t, "sensor": TIME, "from": "substituted", "to": "ok",
                           "reason": "time increases again"})
            self._time_bad = False
        return t, dt if np.isfinite(dt) else self.period_s

    def _hold(self, v: np.ndarray, t: float, events: list) -> np.ndarray:
        missing = ~np.isfinite(v)
        out = np.where(missing, np.where(np.isfinite(self._held), self._held, 0.0), v)
        for k in np.flatnonzero(missing != self._held_state):
            name = self.columns_[self._other[k]]
            events.append({"time": t, "sensor": name, "from": "ok" if missing[k] else "held",
                           "to": "held" if missing[k] else "ok",
                           "reason": ("dropout: no finite value, last value held" if missing[k]
                                      else "value again")})
        self._held_state = missing
        self._held = out
        return out

    # -- blocks -----------------------------------------------------------------------------------
    def predict(self, frame: pd.DataFrame) -> pd.DataFrame:
        """Guarded correction per target for consecutive samples, with ``n_clamped``,
        ``excluded_inputs`` (comma-separated) and ``events`` (JSON list of the row's events)."""
        missing = [c for c in self.columns_ if c not in frame.columns]
        if missing:
            raise OutOfEnvelopeError(f"input lacks column(s) {as_named(missing, self.lab_names_)} "
                                     f"(need {self.columns_})")
        X = np.column_stack([pd.to_numeric(frame[c], errors="coerce").to_numpy(dtype=float)
                             for c in self.columns_]) if self.columns_ else np.empty((len(frame), 0))
        time = (pd.to_numeric(frame[TIME], errors="coerce").to_numpy(float) if TIME in frame.columns
                else np.full(len(frame), np.nan))
        excluded, events = [], []

        def record_row():
            excluded.append(",".join(self.excluded_inputs))
            events.append(json.dumps(self.last_events_, ensure_ascii=False))

        y, clamps = step_block(self, X, time, record_row)
        out = pd.DataFrame(y, columns=self.targets_)
        out["n_clamped"] = clamps
        out["excluded_inputs"] = excluded
        out["events"] = events
        return out


def _held_event(t: float, exc: Exception) -> dict:
    """The event of a row the plain stream refused: the correction held."""
    return {"time": t, "sensor": None, "from": "running", "to": "held",
            "reason": f"correction held: {exc}"}


def _takes(streaming, y: np.ndarray) -> np.ndarray:
    """What ``streaming``'s clamp took out of each row of its last ``run_rows`` (``y``), zeros
    for a stream without one (:meth:`~.guard.CorrectionGuard.step`'s ``take``)."""
    takes = getattr(streaming, "takes_", None)
    return np.zeros_like(y) if takes is None or takes.shape != y.shape else takes


def stream_allowance(guard: CorrectionGuard, streaming: StreamingCompensator,
                     x: np.ndarray | None = None) -> np.ndarray | None:
    """How far ``guard``'s bound widens for the inputs ``streaming``'s model read at its last
    sample (or ``x``, a row's of a block; :meth:`~.guard.CorrectionGuard.allowance`): with the
    envelope's clamp, which carries the training pattern (so does the code); ``None`` before a
    sample or without a following bound."""
    x = getattr(streaming, "last_x_", None) if x is None else x
    if x is None or getattr(streaming, "policy", None) != "clamp":
        return None                           # (the guard says None without a following bound)
    return guard.allowance(x, streaming.envelope)


def input_gains(streaming: StreamingCompensator, ambients=(), training=None, period_s: float = 1.0
                ) -> np.ndarray:
    """(targets, inputs) step gains at the envelope's horizon, as the clamp's (0: a target
    without one).

    A model whose gain depends on the campaign's initial ambient ``A0`` (an ATI model's interval
    and interaction, a diagnosed ambient law: no gain without ``A0``) takes, per input, the largest
    |gain| at the training campaigns' ``ambients``: one fixed gain, which the exported code's
    ``GUARD_GAIN`` carries as it is.  With a row of 0 the bound stayed as trained while the
    inputs went past training (dep108c: climate room 10158 E_X, diagnosed, every test row cut to
    67.04 µm, deployed 1.955 µm against 1.089 unguarded; every ATI wrapper of mlr, pcr, arx and
    lagbank had 0).  The gain at each campaign's own ``A0`` would be the clamp's, but the C and
    the ST would have to compute it per campaign; within the training ambients the largest
    widens the bound at most by what another training campaign's model would.

    (guard111) With the stacked ``training`` (its inputs as the model reads them, sampled every
    ``period_s``): a diagnosed state times the inputs' rises takes its gain at the ends of the
    state's training range, any other model without an analytic gain a numerical one, by held
    steps (:mod:`.held_gains`; guard111b); without them a
    hotter day's correction was cut to the trained bound (climate room 10158, lstm E_X: 230 test
    rows guarded)."""
    n = len(streaming.envelope.lo)
    out = np.zeros((len(streaming.targets_), n))
    horizon = streaming.envelope.horizon_s
    for k, (_, est, idx) in enumerate(streaming._plan):
        gain = step_gain(est, None, horizon)
        if gain is None and len(ambients):
            at = [step_gain(est, est.stream_init(context_record(STREAM_ID, 0.0, a0, {})), horizon)
                  for a0 in ambients]
            at = [np.abs(g) for g in at if g is not None]
            gain = np.max(at, axis=0) if at else None
        if gain is None and training is not None:
            gain = _held_gain(est, idx, training, ambients, horizon, period_s)
        if gain is not None:
            out[k, np.arange(gain.size) if idx is None else np.asarray(idx)] = gain
    return out


def _held_gain(est, idx, m, ambients, horizon_s: float, period_s: float) -> np.ndarray | None:
    """:mod:`.held_gains`' gain of a model whose gain needs a stream state (None: none)."""
    gain = held_factor_gain(est, m.context, ambients, horizon_s)
    if gain is None:
        X = m.X.to_numpy(float)
        gain = stepped_gain(est, X if idx is None else X[:, np.asarray(idx)], m.context, horizon_s, period_s)
    return gain


def training_ambients(m) -> np.ndarray:
    """The distinct finite initial ambients (°C) of stacked training campaigns ``m``."""
    if m.context is None or AMBIENT_C0 not in m.context:
        return np.array([])
    a0 = m.context[AMBIENT_C0].to_numpy(float)
    return np.unique(a0[np.isfinite(a0)])


def _clock_of(last_time: float, last_read: float) -> tuple:
    """The clock's snapshot (:meth:`thermocomp.core.timerule.SampleClock.snapshot`) of a stream
    saved before the time rule, which kept its last time used and its last time read (on one clock)."""
    return (not np.isfinite(last_time), last_time, last_read,
            0.0 if np.isfinite(last_read) else float("nan"))
