"""Static linear models."""

from __future__ import annotations

from sklearn.base import BaseEstimator, RegressorMixin
from sklearn.linear_model import LinearRegression

from ...base.params import BOOLEAN, check_estimator
from .base import LinearStreamMixin, measured_rows


class MLR(LinearStreamMixin, RegressorMixin, BaseEstimator):
    r"""Multiple linear regression of the error on the inputs.

    .. math:: \hat y(t) = b_0 + \sum_{i=1}^{p} b_i\, x_i(t)

    fitted by ordinary least squares.  Static: ``simulation`` and ``one_step``
    predictions coincide.

    Parameters
    ----------
    fit_intercept : bool, default True

    Attributes
    ----------
    coef_ : ndarray of shape (n_features,)
    intercept_ : float
    """

    param_rules = {"fit_intercept": BOOLEAN}

    def __init__(self, fit_intercept: bool = True):
        self.fit_intercept = fit_intercept

    def fit(self, X, y, context=None):
        check_estimator(self)
        X, y, measured = measured_rows(self, X, y)      # (a static law: the measured rows)
        lr = LinearRegression(fit_intercept=self.fit_intercept).fit(X[measured], y[measured])
        self.coef_ = lr.coef_
        self.intercept_ = lr.intercept_
        self.context_columns_ = []
        return self
