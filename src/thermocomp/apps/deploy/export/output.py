"""What surrounds the linear system in the exported code: the time rule, the correction guard and
the reference update (pure core).

* **time** (:mod:`thermocomp.core.timerule`, every form's): a missing time (``substitute_time``:
  or one not after the last time read) is the previous time plus
  ``time_period``; a campaign's first, 0 of the stream's clock, the first time read counting from it;
  (restart66) a time after such a backward one, still not after the last read: a clock started
  again, counted on from the backward one.
* **guard** (:class:`~..guard.CorrectionGuard` of the adaptive compensator): static limits
  ``guard_lo``, ``guard_hi`` (µm of predicted error) and ``guard_rate`` (µm/s; null: none) per
  target, and one state, the previous guarded output.  A campaign's first output is bounded
  only; every later one is first held within ``guard_rate * dt`` of the previous one (``dt`` the
  time since the previous sample, at least ``guard_period``, the training period: also when no
  later time is given; rate71), then bounded.
  With ``guard_inputs`` (the clamp's training pattern in the code) the bound widens on each side
  by ``guard_gain . d`` at a sample on the pattern whose referenced inputs lie beyond their
  training range ``[guard_in_lo, guard_in_hi]`` by ``d`` (the guard's own rule, guard.py).
  (cmon82b) While the code's monitor declares a new thermal state, the bound is
  ``[guard_lo_new, guard_hi_new]`` (exported where ``monitor.new_state_margin`` makes it differ).
* **adapt** (``adapt.method=bias|rls``, :class:`~..adapt.ReferenceAdapter`): the correction is
  ``-(gain * y + bias)``; a reference measurement ``e`` of a target, taken where the guarded
  output was ``y``, updates ``bias`` and its variance (``bias``), or ``(gain, bias)`` and their
  covariance (``rls``), by the bounded recursive filter of ``adapt.py`` (``adapt_forgetting``,
  ``adapt_max_bias``, ``adapt_max_gain_change``, ``adapt_var_cap``).  What was learned
  survives a new campaign; the exported values are those the model was served with.

The served model's sensor monitor (exclusions, reconstruction of a sensor from the others) is
not in the code: :func:`not_in_code` names it.  A missing machine state is held in the code as
the served model holds it (``held``, :mod:`.statespace`).
"""

from __future__ import annotations

import math
import sys

import numpy as np

from ..adaptive import AdaptiveCompensator
from ..guard import rate_span, widening
from .errors import NotExportable

UNBOUNDED = sys.float_info.max   # a machine state's range: never beyond it

EXPORTED_ADAPT = ("none", "bias", "rls")


def guard_fields(deployed, n_states: int = 0, pattern: bool = False) -> dict:
    """The guard's fields of the exported system (none for a plain stream); its bound follows
    the inputs (``guard_inputs``) where the code has the training ``pattern`` (the clamp's), as
    the adaptive compensator's does with the clamp; ``n_states``: machine states after the
    inputs (never beyond a range)."""
    g = deployed.guard if isinstance(deployed, AdaptiveCompensator) else None
    if g is None:
        return {}
    rate = [None if math.isinf(r) else float(r) for r in g.max_rate_per_s]
    out = {"guard": True, "guard_lo": g.lo.tolist(), "guard_hi": g.hi.tolist(),
           "guard_rate": rate, "guard_period": float(g.period_s)}
    if g.lo_new is not None and not (np.array_equal(g.lo_new, g.lo) and np.array_equal(g.hi_new, g.hi)):
        # (cmon82b) the bound in a new thermal state, where it differs (monitor.new_state_margin)
        out.update(guard_lo_new=g.lo_new.tolist(), guard_hi_new=g.hi_new.tolist())
    if pattern and g.in_gain is not None:
        pad = [UNBOUNDED] * n_states
        out.update(guard_inputs=True,
                   guard_gain=np.hstack([g.in_gain, np.zeros((len(g.in_gain), n_states))]).tolist(),
                   guard_in_lo=g.in_lo.tolist() + [-u for u in pad], guard_in_hi=g.in_hi.tolist() + pad)
    return out


def time_fields(deployed, lag_period: float) -> dict:
    """Every stream's rule for a bad ``time`` (missing, or not after the last one read): taken as
    the previous time plus ``time_period`` (:mod:`thermocomp.core.timerule`): the adaptive
    compensator's sample period, a plain stream's its lag bank's ``lag_period``; and (dup99)
    ``skip_repeats``, the adaptive compensator's: a row written again is skipped."""
    adaptive = isinstance(deployed, AdaptiveCompensator)
    period = deployed.period_s if adaptive else lag_period
    # (dup99) a row written again skipped where the served stream skips it: the adaptive one's
    return {"substitute_time": True, "time_period": float(period), "skip_repeats": adaptive}


def adapt_fields(deployed) -> dict:
    """The reference update's fields (none when the model does not learn: ``adapt.method=none``);
    :class:`NotExportable` for a method the code lacks."""
    adapt = getattr(deployed, "adapt_", None)
    if adapt is None or adapt.method == "none":
        return {}
    if adapt.method not in EXPORTED_ADAPT:
        raise NotExportable(f"adapt.method={adapt.method} is not in the code; adapt.method=bias "
                            "or rls exports (or none: the frozen model)")
    a = adapt.adapter
    rls = a.method == "rls"
    return {"adapt": a.method, "adapt_gain": a.gain_.tolist(), "adapt_bias": a.bias_.tolist(),
            "adapt_var": None if rls else [float(p[0, 0]) for p in a._P],
            "adapt_cov": [p.tolist() for p in a._P] if rls else None,
            "adapt_forgetting": a.forgetting, "adapt_max_bias": a.max_bias_um,
            "adapt_max_gain_change": a.max_gain_change, "adapt_var_cap": float(np.trace(a._prior))}


class Output:
    """The guard and the reference update in numpy (part of the reference
    :class:`~.statespace.Simulator`)."""

    def __init__(self, ss):
        m = len(ss.targets)
        self.ss = ss
        if ss.guard:
            self.lo, self.hi = np.asarray(ss.guard_lo, float), np.asarray(ss.guard_hi, float)
            self.rate = np.array([np.inf if r is None else r for r in ss.guard_rate], float)
            self.lo_new, self.hi_new = (np.asarray(v if v is not None else w, float) for v, w in (
                (ss.guard_lo_new, ss.guard_lo), (ss.guard_hi_new, ss.guard_hi)))
        if ss.guard and ss.guard_inputs:
            self.in_gain = np.asarray(ss.guard_gain, float).reshape(m, -1)
            self.in_lo, self.in_hi = np.asarray(ss.guard_in_lo, float), np.asarray(ss.guard_in_hi, float)
        self.gain = np.asarray(ss.adapt_gain or [1.0] * m, float)
        self.bias = np.asarray(ss.adapt_bias or [0.0] * m, float).copy()
        self.var = np.asarray(ss.adapt_var or [0.0] * m, float).copy()
        self.cov = np.asarray(ss.adapt_cov or np.zeros((m, 2, 2)), float).copy()
        self.y = np.zeros(m)

    def allowance(self, x: np.ndarray, envelope) -> np.ndarray | None:
        """How far the guard's bound widens for the referenced inputs ``x`` (``guard_inputs``):
        ``guard_gain . d`` on the training pattern of ``envelope`` (the clamp's), else None."""
        if not (self.ss.guard and self.ss.guard_inputs):
            return None
        return widening(x, self.in_lo, self.in_hi, self.in_gain, envelope)

    def step(self, y: np.ndarray, first: bool, dt: float,
             allowance: np.ndarray | None = None, novel: bool = False) -> np.ndarray:
        """Correction (µm) of the model's predicted error ``y``; ``dt``: s since the previous
        sample (NaN: ``guard_period``); ``allowance``: the bound widened by it (:meth:`allowance`);
        ``novel``: a new thermal state declared (the bound ``guard_lo_new``, ``guard_hi_new``)."""
        if self.ss.guard:
            if not first:
                lim = self.rate * rate_span(dt, self.ss.guard_period)
                d = y - self.y
                y = np.where(d > lim, self.y + lim, np.where(d < -lim, self.y - lim, y))
            lo, hi = (self.lo_new, self.hi_new) if novel else (self.lo, self.hi)
            if allowance is not None:
                lo, hi = lo - allowance, hi + allowance
            y = np.minimum(np.maximum(y, lo), hi)
        self.y = y
        return -(self.gain * y + self.bias) if self.ss.adapt != "none" else -y

    def reference(self, measured) -> None:
        """A measured error per target (NaN: none) where the last output was given."""
        if self.ss.adapt == "none":
            return
        lam, cap = self.ss.adapt_forgetting, self.ss.adapt_var_cap
        for i, e in enumerate(np.asarray(measured, float)):
            if not np.isfinite(e):
                continue
            if self.ss.adapt == "rls":
                self._rls(i, e, lam, cap)
                continue
            p = self.var[i]
            k = p / (lam + p)
            b = self.bias[i] + k * (e - self.gain[i] * self.y[i] - self.bias[i])
            p = (p - k * p) / lam
            self.var[i] = p / max(1.0, p / cap) if cap > 0 else p
            self.bias[i] = min(max(b, -self.ss.adapt_max_bias), self.ss.adapt_max_bias)

    def _rls(self, i: int, e: float, lam: float, cap: float) -> None:
        """``(gain, bias)`` of target ``i`` by recursive least squares on ``phi = (y, 1)``."""
        y, P = self.y[i], self.cov[i]
        phi = np.array([y, 1.0])
        k = P @ phi / (lam + phi @ P @ phi)
        theta = np.array([self.gain[i], self.bias[i]]) + k * (e - (y * self.gain[i] + self.bias[i]))
        P = (P - np.outer(k, phi @ P)) / lam
        self.cov[i] = P / max(1.0, float(np.trace(P)) / cap) if cap > 0 else P
        g = self.ss.adapt_max_gain_change
        self.gain[i] = min(max(theta[0], 1 - g), 1 + g)
        self.bias[i] = min(max(theta[1], -self.ss.adapt_max_bias), self.ss.adapt_max_bias)
