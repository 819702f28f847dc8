"""A fixed-weight blend of model families, and the weights ``model=auto`` gives it.

Choosing one family per target by a noisy validation misranks: the validation
folds of a record rank families against their held-out order with a Spearman
of 0.2 to 0.4, so the one picked is often not the best on test.  A convex
blend of the candidates' free-run predictions, weighted on the same folds,
does not hinge on that ranking: where families tie it averages their
independent errors, where one is clearly better it takes it alone.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import minimize
from sklearn.base import BaseEstimator, RegressorMixin, clone
from sklearn.utils.validation import check_is_fitted

from ..context import SideInputs, context_columns, merge_columns

MIN_WEIGHT = 0.01   # a member weighted less is dropped (refitting it would buy nothing)


class Blend(SideInputs, RegressorMixin, BaseEstimator):
    """``sum_i weights[i] * members[i].predict(X)``, each member fitted on the same rows.

    Streams as its members do (the state is theirs, side by side), so replay
    equals run as for any single family.

    Parameters
    ----------
    members : dict name -> unfitted estimator
    weights : dict name -> weight (non-negative, summing to 1; members without one are not used)
    member_params : dict name -> {param: value}, optional
        Parameters set on a member before its fit: what each member's own CV chose on more data
        (:meth:`chosen_params`, :func:`thermocomp.compensator.with_chosen_hyperparameters`).
    """

    def __init__(self, members=None, weights=None, member_params=None):
        self.members = members
        self.weights = weights
        self.member_params = member_params

    def fit(self, X, y, context=None):
        params = self.member_params or {}
        self.estimators_ = {n: clone(self.members[n]).set_params(**params.get(n, {}))
                            .fit(X, y, context=context) for n in self.weights}
        self.weights_ = np.array([float(self.weights[n]) for n in self.estimators_])
        self.context_columns_ = merge_columns(*map(context_columns, self.estimators_.values()))
        return self

    def predict(self, X, context=None):
        check_is_fitted(self, "estimators_")
        preds = [np.asarray(e.predict(X, context=context), float) for e in self.estimators_.values()]
        return np.column_stack(preds) @ self.weights_

    def stream_init(self, context=None):
        check_is_fitted(self, "estimators_")
        return tuple(e.stream_init(context) for e in self.estimators_.values())

    def stream_step(self, x_row, state, context=None):
        steps = [e.stream_step(x_row, s, context) for e, s in zip(self.estimators_.values(), state)]
        return float(np.dot(self.weights_, [y for y, _ in steps])), tuple(s for _, s in steps)

    def chosen_params(self) -> dict:
        """Each member's own choice (``member_params``): a copy fits the members as chosen."""
        check_is_fitted(self, "estimators_")
        own = {n: getattr(e, "chosen_params", None) for n, e in self.estimators_.items()}
        return {"member_params": {n: dict(f()) for n, f in own.items() if callable(f)}}


def stack_weights(predictions: np.ndarray, y: np.ndarray, fold: np.ndarray,
                  base: np.ndarray) -> np.ndarray:
    """Non-negative weights summing to 1 of the columns of ``predictions`` (out-of-fold free-run
    predictions of each candidate) that minimise the validation error, each fold's squared error
    relative to that of ``base`` (MLR's predictions) there: every fold counts alike, so one fold
    where every family fails (the first forward fold, fitted on the least data) does not decide."""
    k = predictions.shape[1]
    gram, cross = np.zeros((k, k)), np.zeros(k)
    for f in np.unique(fold):
        rows = fold == f
        p, t = predictions[rows], y[rows]
        scale = max(float(np.mean((t - base[rows]) ** 2)), 1e-12) * rows.sum()
        gram += p.T @ p / scale
        cross += p.T @ t / scale
    gram += np.eye(k) * 1e-9 * np.trace(gram) / k   # identical candidates: one optimum
    start = np.full(k, 1.0 / k)
    res = minimize(lambda w: w @ gram @ w - 2 * cross @ w, start, jac=lambda w: 2 * (gram @ w - cross),
                   bounds=[(0.0, 1.0)] * k, method="SLSQP",
                   constraints=[{"type": "eq", "fun": lambda w: w.sum() - 1.0,
                                 "jac": lambda w: np.ones_like(w)}])
    w = np.clip(res.x if res.success else start, 0.0, None)
    w[w < MIN_WEIGHT] = 0.0
    return w / w.sum()
