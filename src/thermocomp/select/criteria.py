"""Information criteria for the number of inputs of a least-squares model.

With ``n`` samples, ``p`` estimated coefficients (intercept included) and
residual sum of squares ``rss`` (Gaussian likelihood, constants dropped):

* AIC  = n ln(rss/n) + 2 p
* BIC  = n ln(rss/n) + p ln(n)
* BICc = n ln(rss/n) + n p ln(n) / (n - p - 2)   (McQuarrie 1999, small-sample corrected BIC)

Lower is better.  Thermal records are strongly autocorrelated, so ``n``
overstates the independent information and the criteria lean towards more
inputs on long records; ``k_max`` bounds them (1..10 in paper 000).
"""

from __future__ import annotations

import numpy as np

CRITERIA = ("aic", "bic", "bicc")


def information_criterion(rss: float, n: int, p: int, kind: str = "bicc") -> float:
    """AIC, BIC or BICc of a least-squares fit (see module docstring)."""
    if kind not in CRITERIA:
        raise ValueError(f"criterion must be one of {CRITERIA}, got {kind!r}")
    fit = n * np.log(max(rss, np.finfo(float).tiny) / n)
    if kind == "aic":
        return float(fit + 2 * p)
    if kind == "bic":
        return float(fit + p * np.log(n))
    if n - p - 2 <= 0:
        return float("inf")
    return float(fit + n * p * np.log(n) / (n - p - 2))


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
    return np.array([information_criterion(ols_rss(X[:, list(cols)], y), n, len(cols) + 1, kind)
                     for cols in orders])
