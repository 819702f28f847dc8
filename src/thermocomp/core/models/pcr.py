"""Principal component regression (paper 003, Sect. 2.1)."""

from __future__ import annotations

from sklearn.base import BaseEstimator, RegressorMixin
from sklearn.decomposition import PCA
from sklearn.linear_model import LinearRegression
from sklearn.preprocessing import StandardScaler

from ...base.params import check_estimator, number
from .base import LinearStreamMixin, measured_rows


class PCR(LinearStreamMixin, RegressorMixin, BaseEstimator):
    r"""Principal component regression mapped back onto the sensors.

    Inputs are standardised, :math:`x^*_i = (x_i - \bar x_i)/s_i`; principal
    components :math:`Z_j = e_j^\top x^*` of their correlation matrix are kept
    up to a cumulative explained variance of ``variance``; the error is
    regressed on them, :math:`\hat y = a_0 + \sum_{j\le g} a_j Z_j`; and the
    fit is mapped back to the original sensors

    .. math:: \hat y = b_0 + \sum_{i=1}^{p} b_i x_i,\qquad
              b_i = \frac{1}{s_i}\sum_{j\le g} a_j e_{ij},\qquad
              b_0 = a_0 - \sum_i b_i \bar x_i

    so the deployed model is a plain linear law in °C (``coef_``,
    ``intercept_``).  Dropping the low-variance components suppresses the
    collinearity of neighbouring temperatures.  Static: ``simulation`` and
    ``one_step`` predictions coincide.

    Parameters
    ----------
    variance : float in (0, 1], default 0.95
        Cumulative explained variance of the kept components (paper 003: 95 %).

    Attributes
    ----------
    coef_ : ndarray of shape (n_features,)
        Coefficients on the original (unstandardised) inputs.
    intercept_ : float
    n_components_ : int
        Number of kept components *g*.
    explained_variance_ratio_ : ndarray of shape (n_components_,)
    """

    param_rules = {"variance": number(0.0, 1.0, open_lo=True)}

    def __init__(self, variance: float = 0.95):
        self.variance = variance

    def fit(self, X, y, context=None):
        check_estimator(self)
        X, y, measured = measured_rows(self, X, y)      # (a static law: the measured rows)
        X, y = X[measured], y[measured]
        scaler = StandardScaler().fit(X)
        Xs = scaler.transform(X)
        n_comp = self.variance if self.variance < 1 else min(X.shape)
        pca = PCA(n_components=n_comp, svd_solver="full").fit(Xs)
        lr = LinearRegression().fit(pca.transform(Xs), y)
        self.coef_ = (pca.components_.T @ lr.coef_) / scaler.scale_
        # PCA centres the (already centred) scores; its mean_ is ~0 but kept exact here.
        self.intercept_ = float(lr.intercept_ - pca.mean_ @ (pca.components_.T @ lr.coef_)
                                - scaler.mean_ @ self.coef_)
        self.n_components_ = int(pca.n_components_)
        self.explained_variance_ratio_ = pca.explained_variance_ratio_
        self.context_columns_ = []
        return self
