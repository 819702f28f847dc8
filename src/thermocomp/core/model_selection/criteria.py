r"""Information criteria of a Gaussian least-squares fit: the one implementation.

With :math:`N` samples, :math:`k` estimated coefficients (intercept
included), residual sum of squares RSS and :math:`L = N \ln(\mathrm{RSS}/N)`
(constants common to all models dropped):

* AIC  :math:`= L + 2k`
* AICc :math:`= \mathrm{AIC} + 2k(k+1)/(N-k-1)`
* BIC  :math:`= L + k \ln N`
* BICc :math:`= L + N k \ln N/(N-k-2)`, the small-sample corrected Schwarz
  criterion of McQuarrie (1999), used by paper 000.

Lower is better.  A criterion whose correction is undefined (too few
samples) is +inf.  Thermal records are strongly autocorrelated, so :math:`N`
overstates the independent information and the criteria lean towards more
inputs on long records; the callers bound the size (1..10 in paper 000).

Floor: an RSS below ``RSS_FLOOR`` times the target's total sum of squares
``tss`` is rounding noise of a perfect fit, not information; it counts as that
floor, so every perfect fit ties and the smallest model wins the tie.
"""

from __future__ import annotations

import numpy as np

CRITERIA = ("aic", "aicc", "bic", "bicc")
LABELS = {"aic": "AIC", "aicc": "AICc", "bic": "BIC", "bicc": "BICc"}
RSS_FLOOR = 1e-15   # relative to tss: a few ulps of double precision


def information_criteria(rss: float, n_obs: int, n_params: int, *, tss: float) -> dict[str, float]:
    """AIC, AICc, BIC and BICc of a least-squares fit (see the module docstring).

    Parameters
    ----------
    rss : float
        Residual sum of squares.
    n_obs : int
        Number of samples :math:`N`.
    n_params : int
        Number of estimated coefficients :math:`k`, intercept included.
    tss : float
        Total sum of squares of the target (about its mean when the model has
        an intercept); sets the floor of ``rss``.

    Returns
    -------
    dict
        ``{"aic", "aicc", "bic", "bicc"} -> float``; +inf where undefined.
    """
    n, k = float(n_obs), float(n_params)
    rss = max(float(rss), RSS_FLOOR * max(float(tss), np.finfo(float).tiny))
    if n <= 0:
        return dict.fromkeys(CRITERIA, np.inf)
    fit = n * np.log(rss / n)
    out = {"aic": fit + 2 * k,
           "aicc": fit + 2 * k + (2 * k * (k + 1) / (n - k - 1) if n - k - 1 > 0 else np.inf),
           "bic": fit + k * np.log(n),
           "bicc": fit + (n * k * np.log(n) / (n - k - 2) if n - k - 2 > 0 else np.inf)}
    return {name: float(v) if np.isfinite(v) else np.inf for name, v in out.items()}


def information_criterion(rss: float, n_obs: int, n_params: int, kind: str = "bicc", *,
                          tss: float) -> float:
    """One criterion of :func:`information_criteria` (``kind`` in :data:`CRITERIA`)."""
    if kind not in CRITERIA:
        raise ValueError(f"criterion must be one of {CRITERIA}, got {kind!r}")
    return information_criteria(rss, n_obs, n_params, tss=tss)[kind]


def ols_rss(X: np.ndarray, y: np.ndarray) -> float:
    """Residual sum of squares of ``y`` on ``X`` plus an intercept."""
    A = np.column_stack([np.ones(len(y)), X])
    coef = np.linalg.lstsq(A, y, rcond=None)[0]
    r = y - A @ coef
    return float(r @ r)


def ic_path(X: np.ndarray, y: np.ndarray, orders, kind: str) -> np.ndarray:
    """Criterion of the OLS model (with intercept) on each candidate column set.

    ``orders`` is a list of column-index lists; returns one value per set.
    """
    n = len(y)
    tss = float(np.sum((y - np.mean(y)) ** 2))
    return np.array([information_criterion(ols_rss(X[:, list(cols)], y), n, len(cols) + 1, kind,
                                           tss=tss)
                     for cols in orders])
