"""What every model family shares: the side-input and streaming protocol (:mod:`thermocomp.core.context`)."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from sklearn.base import BaseEstimator, clone
from sklearn.utils.validation import check_consistent_length, check_is_fitted, column_or_1d, validate_data

from ...base.errors import ContractError
from ..context import SideInputs, for_target
from ..gains import held


class LinearStreamMixin(SideInputs):
    """Prediction of a static linear law ``y = x·coef_ + intercept_``, batch and streamed (one dot
    product a sample): the law's families (MLR, PCR) differ only in how they fit it."""

    def predict(self, X, context=None):
        check_is_fitted(self)
        X = validate_data(self, X, reset=False)
        return X @ self.coef_ + self.intercept_

    def stream_step(self, x_row, state, context: Mapping | None = None):
        return float(np.asarray(x_row, dtype=float) @ self.coef_ + self.intercept_), state

    def stream_steps(self, X, state, context: Mapping | None = None):
        """A block of rows at once (:func:`thermocomp.core.context.stream_steps`): no state."""
        return np.asarray(X, dtype=float) @ self.coef_ + self.intercept_, state

    def step_gain(self, state=None, horizon_s: float = np.inf) -> np.ndarray:
        """Gain per input (:func:`thermocomp.core.context.step_gain`): the coefficients."""
        return np.asarray(self.coef_, float)

    def lagged_step_gain(self, lead_taus, horizon_s: float = np.inf, period_s: float = 1.0) -> np.ndarray:
        """:meth:`step_gain` where column ``j`` is a first-order lag of tau ``lead_taus[j]`` of the
        held step (``nan``: the step itself; a diagnosed low-pass copy of the inputs): each
        coefficient times that lag's response, ``1 - exp(-h / tau)`` (:func:`thermocomp.core.gains.held`)."""
        return np.asarray(self.coef_, float) * held(lead_taus, horizon_s)


class PerTarget(BaseEstimator):
    """``estimator`` with per-target parameters: ``for_target(t)`` is an unfitted copy with
    ``params[t]`` set (the hyper-parameters a fit on more data chose, see
    :func:`thermocomp.core.compensator.with_chosen_hyperparameters`)."""

    def __init__(self, estimator, params: Mapping | None = None):
        self.estimator = estimator
        self.params = params

    def for_target(self, target: str):
        return clone(for_target(self.estimator, target)).set_params(**(self.params or {}).get(target, {}))


class ForTargets(BaseEstimator):
    """A ``model=auto`` candidate for some targets only: ``for_target(t)`` is an unfitted copy
    of ``by_target[t]``, None for a target it does not name (no candidate there).  Never fitted
    itself (:meth:`thermocomp.core.models.auto.AutoRegressor.for_target` replaces it).
    ``about``: ``{target: entry}``, what ``metrics.json`` says of the candidate for a target
    (``targets.<t>.auto.<name>``, :func:`~thermocomp.core.models.auto.add_choices`; effects99:
    the effects the ``diagnosed`` search accepted, or that it accepted none)."""

    def __init__(self, by_target: Mapping | None = None, about: Mapping | None = None):
        self.by_target = by_target
        self.about = about

    def for_target(self, target: str):
        est = (self.by_target or {}).get(target)
        return None if est is None else clone(est)


def measured_rows(est, X, y) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``X`` validated (``est``'s features set, as ``validate_data(est, X, y)`` does), ``y`` as
    floats with its NaN kept, and the mask of the rows where ``y`` was measured.

    A target measured now and then (a probe cycle on a dense log, ``data.sparse_targets``) is
    NaN between its measurements: a family computes its inputs' dynamics (lags, filters,
    states) on every row and fits on the measured ones only; never on an interpolated ``y``.
    """
    X = validate_data(est, X)
    y = column_or_1d(np.asarray(y, dtype=float), warn=True)
    check_consistent_length(X, y)
    if np.isinf(y).any():
        raise ValueError("Input y contains infinity")
    measured = np.isfinite(y)
    if not measured.any():
        raise ContractError(f"{type(est).__name__}: the target is measured on no row")
    return X, y, measured
