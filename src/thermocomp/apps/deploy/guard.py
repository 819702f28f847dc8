"""A bound and a rate limit on the correction the compensator sends to the CNC (pure core).

Whatever the inputs do, the correction stays finite, inside the training error
range widened by ``margin`` × its width, and changes by at most
``(1 + rate_margin)`` × the fastest change in training, per second, of the measured error or of
the model's own correction (a model fed noisy sensors moves faster than the error it follows: a
rate taken from the error alone clips a healthy stream, a measured spindle record 226 times in
4.6 h), over a step or one training period, whichever is longer (:func:`rate_span`).  Each
target's state (``free``, ``bounded``, ``rate_limited``, ``held``) changes with an event; it is
reported ``free`` again only after :data:`CALM` samples within bound and rate, so a jumpy episode
is one event pair.  A target is reported ``rate_limited`` only where the model's own correction,
before the envelope clamp took its share out (``take``), moved beyond the limit: a step the
clamp made by switching on or off is paced all the same, without an event (guard96: a room
ramped past training, the clamp's pattern gate on its threshold, 36 events in 9 healthy cells).
While the sensor monitor declares a new thermal state (a source training never saw), the bound
is the training range widened by ``new_state_margin`` instead (``None``: the same bound).

The bound follows the inputs on the training pattern (:meth:`CorrectionGuard.allowance`): at a
sample whose inputs, as the model reads them, lie beyond their training range while moving
together as in training (:meth:`~.streaming.Envelope.leaves_pattern` false: a hotter machine,
which the stream passes as measured), both ends move out by ``sum_j |gain_tj| * d_j``, ``d_j``
input ``j``'s distance beyond its training range and ``gain`` the model's step gain at the
envelope's horizon (the clamp's).  A sample off the pattern (one sensor leaving the others: a
fault the monitor missed) keeps the bound as trained.  On the ``long_record`` overspeeds
(benchmarks/bench_guard56.py) the fixed bound had cut the right correction of a real state (true
error 115.9 µm, bound 90.3): the adaptive compensator was 1.2-6.8 x the plain stream's Σ² vs
truth; now 0.74-1.06 x (3.7 x for long4253's lag bank: the monitor's hold of a hot sensor), and
no injected fault of benchmarks/bench_deploy_faults.py moves.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ...core.timerule import median_step

FREE, BOUNDED, RATE, HELD = "free", "bounded", "rate_limited", "held"
CALM = 5   # samples within bound and rate before a target is reported free again


class CorrectionGuard:
    """Bound (``lo``, ``hi``, µm) and rate limit (µm/s) per target."""

    lo_new = hi_new = None   # bound in a new thermal state (None: lo, hi; older pickles)
    # the bound following the inputs on the training pattern (None: fixed; older pickles):
    # |step gain| (targets, inputs) and the inputs' training range, in the model's frame
    in_gain = in_lo = in_hi = None
    # per target, the rows whose correction it changed (bounded, rate-limited, held) since the
    # last reset: why a deployed figure leaves the model's batch one with no input clamped
    # (depl70; None: older pickles until their first reset)
    changed_ = None
    _raw = None   # the model's own correction at the last row, before the clamp (older pickles)

    def __init__(self, targets: Sequence[str], lo, hi, max_rate_per_s, period_s: float,
                 lo_new=None, hi_new=None):
        self.targets = list(targets)
        self.lo, self.hi = np.asarray(lo, float), np.asarray(hi, float)
        if lo_new is not None:
            self.lo_new, self.hi_new = np.asarray(lo_new, float), np.asarray(hi_new, float)
        self.max_rate_per_s = np.asarray(max_rate_per_s, float)
        self.period_s = float(period_s)
        self.reset()

    @classmethod
    def from_training(cls, targets: Sequence[str], measured: Sequence[np.ndarray],
                      times: Sequence[np.ndarray], margin: float = 0.2, rate_margin: float = 1.0,
                      predicted: Sequence[np.ndarray] | None = None,
                      new_state_margin: float | None = None) -> "CorrectionGuard":
        """``measured``: referenced training errors per campaign (n, k); ``times`` in s;
        ``predicted``: the model's corrections on the same campaigns (its rate counts too);
        ``new_state_margin``: the bound's margin in a new thermal state (``None``: ``margin``)."""
        if margin < 0 or rate_margin < 0 or (new_state_margin or 0) < 0:
            raise ValueError("guard margins must be >= 0")
        Y = np.vstack(measured)
        lo, hi = np.nanmin(Y, axis=0), np.nanmax(Y, axis=0)
        width = np.maximum(hi - lo, 1e-9)
        rates = []
        for k, t in enumerate(times):
            if len(t) > 1:
                for y in (measured[k], *([predicted[k]] if predicted is not None else [])):
                    rates.append(_fastest(np.asarray(y, float), np.asarray(t, float)))
        rate = np.nanmax(rates, axis=0) if rates else np.full(Y.shape[1], np.inf)
        rate = np.where(np.isnan(rate), np.inf, rate)      # (no two measurements: no limit)
        wide = margin if new_state_margin is None else float(new_state_margin)
        return cls(targets, lo - margin * width, hi + margin * width, (1 + rate_margin) * rate,
                   median_step(list(times)) or 1.0,
                   lo - wide * width, hi + wide * width)

    def follow_inputs(self, gain, lo, hi) -> "CorrectionGuard":
        """The bound widens by ``|gain| @ d`` beyond the inputs' training range ``[lo, hi]``
        (:meth:`allowance`); ``gain``: (targets, inputs) step gains, a row of 0 for a target
        without one."""
        self.in_gain = np.abs(np.asarray(gain, float))
        self.in_lo, self.in_hi = np.asarray(lo, float), np.asarray(hi, float)
        return self

    def allowance(self, x: np.ndarray, envelope) -> np.ndarray | None:
        """How far the bound widens (µm per target) for the inputs ``x`` the model reads
        (referenced): ``|gain| @ d``, ``d`` their distance beyond the training range, when
        ``x`` is on the envelope's training pattern; ``None`` within the range, off the pattern,
        without a pattern or a following bound."""
        if self.in_gain is None or envelope is None or envelope.basis is None:
            return None
        return widening(x, self.in_lo, self.in_hi, self.in_gain, envelope)

    def reset(self) -> None:
        self._prev = self._raw = None
        self._state = [FREE] * len(self.targets)
        self._free = True
        self._calm = np.zeros(len(self.targets), dtype=np.int64)
        self.changed_ = np.zeros(len(self.targets), dtype=np.int64)

    def snapshot(self) -> tuple:
        return (None if self._prev is None else self._prev.copy(), list(self._state),
                self._calm.copy(), None if self._raw is None else self._raw.copy())

    def restore(self, snap: tuple) -> None:
        self._prev, self._state = (None if snap[0] is None else snap[0].copy()), list(snap[1])
        self._calm = snap[2].copy()
        self._raw = snap[3].copy() if len(snap) > 3 and snap[3] is not None else None
        self._free = all(s == FREE for s in self._state)

    def step_block(self, Y: np.ndarray, dt: np.ndarray, new_state: np.ndarray,
                   takes: np.ndarray | None = None) -> int:
        """How many of the first rows of ``Y`` (model corrections, (m, targets)) :meth:`step`
        passes as they are on its fast path (every target free, finite, within rate and bound;
        no allowance: the inputs within their training range), taken in one go; the rows after
        them are for :meth:`step`; ``takes``: each row's ``take`` (:meth:`step`; None: none)."""
        if not self._free or self._prev is None or not len(Y):
            return 0
        with np.errstate(invalid="ignore"):
            lim = self.max_rate_per_s * rate_span(dt, self.period_s)[:, None]
            wide = (new_state & (self.lo_new is not None))[:, None]
            lo = np.where(wide, self.lo if self.lo_new is None else self.lo_new, self.lo)
            hi = np.where(wide, self.hi if self.hi_new is None else self.hi_new, self.hi)
            ok = (np.isfinite(Y).all(axis=1)
                  & (np.abs(Y - np.vstack([self._prev, Y[:-1]])) <= lim).all(axis=1)
                  & (Y >= lo).all(axis=1) & (Y <= hi).all(axis=1))
        m = len(Y) if ok.all() else int(np.argmin(ok))
        if m:
            self._prev = Y[m - 1].copy()
            self._raw = self._prev + (0.0 if takes is None else takes[m - 1])
        return m

    def step(self, y: np.ndarray, dt: float, time: float, new_state: bool = False,
             allowance: np.ndarray | None = None, take: np.ndarray | None = None
             ) -> tuple[np.ndarray, list[dict]]:
        """Guarded correction for the model's ``y`` (NaN: held at the previous one);
        ``new_state``: the monitor declares a new thermal state (the bound ``lo_new``, ``hi_new``);
        ``allowance``: the bound widened by it at this sample (:meth:`allowance`); ``take``: what
        the envelope clamp took out of the model's correction to give ``y`` (None: nothing).

        The output's rate is limited as ever; a target is reported ``rate_limited`` (an event)
        only where the model's own correction, ``y + take``, moved beyond the limit: a step made
        by the clamp switching on or off (the deployment's own act, not the model's) is paced
        without one (guard96), and counted in :attr:`changed_`."""
        y = np.asarray(y, dtype=float)
        raw, self._raw = self._raw, y if take is None else y + take
        prev = self._prev
        lo, hi = (self.lo_new, self.hi_new) if new_state and self.lo_new is not None else (
            self.lo, self.hi)
        if allowance is not None:
            lo, hi = lo - allowance, hi + allowance
        if self._free and prev is not None and np.isfinite(y.sum()):   # the usual case, fast
            lim = self.max_rate_per_s * rate_span(dt, self.period_s)
            if (np.abs(y - prev) <= lim).all() and (y >= lo).all() and (y <= hi).all():
                self._prev = y
                return y, []
        held = ~np.isfinite(y)
        prev = self._prev if self._prev is not None else np.zeros_like(y)
        out = np.where(held, prev, y)
        state = np.where(held, HELD, FREE).astype(object)
        if self._prev is not None:
            lim = self.max_rate_per_s * rate_span(dt, self.period_s)
            fast = np.abs(out - prev) > lim
            out = np.where(fast, prev + np.sign(out - prev) * lim, out)
            with np.errstate(invalid="ignore"):     # (a held target's NaN: not the model's step)
                own = fast if raw is None else fast & ~(np.abs(self._raw - raw) <= lim)
            state[own & ~held] = RATE
            paced = fast & ~own
        else:
            paced = np.zeros(len(y), dtype=bool)
        outside = (out < lo) | (out > hi)
        out = np.minimum(np.maximum(out, lo), hi)
        state[outside & ~held] = BOUNDED
        events = []
        self.changed_ = (0 if self.changed_ is None else self.changed_) + ((state != FREE) | paced)
        self._calm = np.where(state == FREE, self._calm + 1, 0)
        for k, new in enumerate(state):
            if new == FREE and self._calm[k] < CALM:
                continue     # free again only after CALM samples: one event per episode
            if new != self._state[k]:
                events.append({"time": float(time), "sensor": None, "target": self.targets[k],
                               "from": self._state[k], "to": str(new),
                               "reason": _reason(str(new), y[k], lo[k], hi[k])})
                self._state[k] = str(new)
        self._free = all(s == FREE for s in self._state)
        self._prev = out
        return out, events


def rate_span(dt, period_s: float):
    """Seconds the rate limit spans over a step of ``dt`` s (scalar or array): ``dt``, but at least
    one training period ``period_s`` (also where no later time is given).  The rate is learnt from
    rows one period apart: it says how far a correction moves in a period, nothing within one; a
    correction's sample-to-sample jitter does not shrink with a faster stream (rate71: a lag bank
    trained on 300 s rows and fed 60 s rows was rate-limited 88 times on a healthy run).  The one
    rule of the guard, of the exported code (:mod:`.export.output`, the C, the ST) and of the
    offsets ``connect`` writes (:class:`thermocomp.apps.machine.offsets.OffsetLimiter`, connect72)."""
    if isinstance(dt, float):       # one step's (ci101b): the same choice, no array made
        return np.float64(dt if math.isfinite(dt) and dt > period_s else period_s)
    with np.errstate(invalid="ignore"):
        return np.where(np.isfinite(dt) & (np.asarray(dt) > period_s), dt, period_s)


def guard_changes(deployed) -> np.ndarray | None:
    """A copy of the rows per target whose correction ``deployed``'s guard changed since its
    reset (:attr:`CorrectionGuard.changed_`); None without a guard (the plain stream)."""
    guard = getattr(deployed, "guard", None)
    if guard is None:
        return None
    return np.zeros(len(guard.targets), np.int64) if guard.changed_ is None else guard.changed_.copy()


def widening(x: np.ndarray, lo: np.ndarray, hi: np.ndarray, gain: np.ndarray,
             envelope) -> np.ndarray | None:
    """``gain @ d``, ``d`` the distance of the inputs ``x`` beyond their training range ``[lo,
    hi]``, when ``x`` is on ``envelope``'s training pattern; None within the range or off the
    pattern.  The one rule of the guard and of the exported code's Simulator (:mod:`.export.output`)."""
    d = x - hi
    np.maximum(d, lo - x, out=d)
    if not d.max() > 0.0 or envelope.leaves_pattern(x):      # (the usual case: in range)
        return None
    return gain @ np.maximum(d, 0.0, out=d)


def _reason(state: str, y: float, lo: float, hi: float) -> str:
    if state == BOUNDED:
        return f"correction bounded: model gave {y:.4g} µm, bound [{lo:.3g}, {hi:.3g}] µm"
    if state == RATE:
        return f"correction rate-limited: model gave {y:.4g} µm"
    if state == HELD:
        return "correction held: the model gave no finite value"
    return "correction within bound and rate again"


def _fastest(y: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Largest rate of change of each column of ``y`` (n, k) at times ``t``, between its
    consecutive finite values: every sample's, or a target measured now and then
    (``data.sparse_targets``) between two measurements; NaN with fewer than two."""
    out = np.full(y.shape[1], np.nan)
    for j in range(y.shape[1]):
        ok = np.isfinite(y[:, j])
        if ok.sum() > 1:
            out[j] = np.max(np.abs(np.diff(y[ok, j])) / np.diff(t[ok]))
    return out
