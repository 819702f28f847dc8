"""What every model family shares: the side-input and streaming protocol (:mod:`thermocomp.core.context`)."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from sklearn.base import BaseEstimator, clone
from sklearn.utils.validation import check_is_fitted, validate_data

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
