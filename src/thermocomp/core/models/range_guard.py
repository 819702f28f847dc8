"""A kept model guarded by its training range: MLR's correction where an input leaves it.

``model=auto``'s dynamic and nonlinear families can extrapolate badly where a test campaign goes
past the train campaigns (an unseen heat source +6 K over the train maximum: col5791 E_Z_mid, the
lag-bank blend 0.73 x MLR inside the range and 3.08 x outside, ``benchmarks/bench_auto81b.py``),
while elsewhere they hold (tsc_a2 E_dZ1: 0.06 x MLR outside).  So the switch is one
:class:`~thermocomp.core.models.auto.AutoRegressor` turns on per target only where its own
validation folds say MLR extrapolates better (``range_guard='folds'``), and this is what it keeps
then: both models run side by side (their states advance on every sample), and each sample takes
MLR's correction where any input lies outside the train rows' per-input [min, max] widened by a
share of its width (:func:`outside`), the kept model's elsewhere.
"""

from __future__ import annotations

import numpy as np
from sklearn.base import BaseEstimator, RegressorMixin
from sklearn.utils.validation import check_is_fitted

from ..context import SideInputs, context_columns, merge_columns, step_gain, stream_steps
from ..gains import gain_terms

MARGIN = 0.1   # the box widened by this share of each input's width: the edge's noise does not fire it


def box(X: np.ndarray, margin: float = MARGIN) -> tuple[np.ndarray, np.ndarray]:
    """``(lo, hi)``: per column of ``X`` its [min, max] over the finite values, widened by
    ``margin`` of the width on both sides (a column without a finite value: unbounded)."""
    X = np.asarray(X, float)
    seen = np.isfinite(X).any(axis=0)
    lo = np.where(seen, np.min(np.where(np.isfinite(X), X, np.inf), axis=0), -np.inf)
    hi = np.where(seen, np.max(np.where(np.isfinite(X), X, -np.inf), axis=0), np.inf)
    w = np.where(seen, hi - lo, 0.0)
    return lo - margin * w, hi + margin * w


def outside(X: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Rows of ``X`` with any input below ``lo`` or above ``hi`` (a missing value is not outside)."""
    X = np.atleast_2d(np.asarray(X, float))
    return ((X < lo) | (X > hi)).any(axis=1)


class RangeGuard(SideInputs, RegressorMixin, BaseEstimator):
    """``kept``'s prediction inside the box ``[lo, hi]`` of the inputs, ``base``'s (MLR) outside.

    Built from two estimators already fitted on the same rows (``AutoRegressor`` fits them); it
    has no fit of its own.  Streams as a :class:`~thermocomp.core.models.blend.Blend` does (both
    states side by side), so replay equals run.

    Parameters
    ----------
    kept, base : fitted estimators
    lo, hi : arrays, one value per input
    """

    def __init__(self, kept=None, base=None, lo=None, hi=None):
        self.kept = kept
        self.base = base
        self.lo = lo
        self.hi = hi

    def __sklearn_is_fitted__(self) -> bool:
        return self.kept is not None and self.base is not None

    @property
    def context_columns_(self) -> list[str]:
        return merge_columns(context_columns(self.kept), context_columns(self.base))

    def predict(self, X, context=None):
        check_is_fitted(self)
        inside = np.asarray(self.kept.predict(X, context=context), float)
        base = np.asarray(self.base.predict(X, context=context), float)
        return np.where(outside(X, self.lo, self.hi), base, inside)

    def stream_init(self, context=None):
        check_is_fitted(self)
        return self.kept.stream_init(context), self.base.stream_init(context)

    def stream_step(self, x_row, state, context=None):
        (yk, sk), (yb, sb) = (self.kept.stream_step(x_row, state[0], context),
                              self.base.stream_step(x_row, state[1], context))
        return float(yb if outside(x_row, self.lo, self.hi)[0] else yk), (sk, sb)

    def stream_steps(self, X, state, context=None):
        (yk, sk), (yb, sb) = (stream_steps(self.kept, X, state[0], context),
                              stream_steps(self.base, X, state[1], context))
        return np.where(outside(X, self.lo, self.hi), yb, yk), (sk, sb)

    def step_gain(self, state=None, horizon_s: float = np.inf):
        """The kept model's (inside the box, where it answers)."""
        return step_gain(self.kept, None if state is None else state[0], horizon_s)

    def gain_terms(self, horizon_s: float = np.inf, lead=None, period_s: float = 1.0) -> list:
        """The kept model's (:mod:`thermocomp.core.gains`)."""
        return gain_terms(self.kept, horizon_s, lead, period_s)

    def chosen_params(self) -> dict:
        """The kept model's own choice."""
        own = getattr(self.kept, "chosen_params", None)
        return dict(own()) if callable(own) else {}
