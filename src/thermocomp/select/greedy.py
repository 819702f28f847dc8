"""Split unbiased greedy selection (paper 000, Sect. 2.2, after Liu et al. 2018)."""

from __future__ import annotations

import numpy as np

from .base import TSPSelector


def greedy_residual_path(A: np.ndarray, y: np.ndarray, steps: int) -> tuple[list[int], np.ndarray]:
    """Greedy order and the residual-variance reduction of every candidate.

    Each step fits ``r ≈ a + b x_n`` for every remaining sensor ``x_n`` on the
    current residual ``r`` (start: ``r = y``), keeps the one with the lowest
    mean squared error, subtracts its fit from ``r`` and repeats.  Returns the
    chosen column indices and, per candidate, the mean squared error it removed
    at the step it entered (for the others: what it would remove after the
    last step).  Vectorised: a one-input fit is closed form,
    ``SSE = Σr_c² - (Σx_c r_c)² / Σx_c²`` on centred data.
    """
    n, p = A.shape
    Ac = A - A.mean(axis=0)
    sxx = (Ac * Ac).sum(axis=0)
    r = y - y.mean()
    remaining = np.ones(p, dtype=bool)
    order, gain = [], np.zeros(p)
    for _ in range(min(steps, p)):
        sxr = Ac.T @ r
        with np.errstate(invalid="ignore", divide="ignore"):
            reduction = np.where(sxx > 0, sxr * sxr / sxx, 0.0) / n
        best = int(np.argmax(np.where(remaining, reduction, -np.inf)))
        order.append(best)
        gain[best] = reduction[best]
        remaining[best] = False
        if sxx[best] > 0:
            r = r - (sxr[best] / sxx[best]) * Ac[:, best]
    if remaining.any():
        sxr = Ac.T @ r
        with np.errstate(invalid="ignore", divide="ignore"):
            gain[remaining] = np.where(sxx > 0, sxr * sxr / sxx, 0.0)[remaining] / n
    return order, gain


class GreedyResidualSelector(TSPSelector):
    r"""Split unbiased greedy selection of temperature inputs (``select=greedy_residual``).

    At step *j* a one-input model :math:`r_{j-1} \approx a + b_n T_n` is fitted
    for every remaining sensor on the current residual (:math:`r_0 = E`), the
    sensor with the lowest mean squared error is kept, its fit is subtracted

    .. math:: r_j = r_{j-1} - \hat a - \hat b_{n_j} T_{n_j}

    and the search repeats on :math:`r_j`.  The number of sensors is ``k`` or,
    with ``k=None``, the size in ``1..k_max`` minimising ``criterion`` (BICc in
    paper 000) for a joint OLS fit on the first sensors of the greedy order.
    The one-input fits are static, so campaign boundaries (``groups``) do not
    matter; lagged (ARX) variants belong to :mod:`thermocomp.models.arx`.

    Parameters
    ----------
    k : int or None, default None
    criterion : {'aic', 'bic', 'bicc'}, default 'bicc'
    k_max : int, default 10

    Attributes
    ----------
    selected_ : list of str
        In greedy order.
    scores_ : pandas.Series
        Mean squared error (target unit²) each sensor removed at the step it
        entered; for unselected sensors, what it would remove after the last step.
    ic_ : pandas.Series or None
    """

    score_label = "MSE removed (target unit²)"

    def __init__(self, k: int | None = None, criterion: str = "bicc", k_max: int = 10):
        self.k = k
        self.criterion = criterion
        self.k_max = k_max

    def _rank(self, A, y, groups):
        steps = max(self._sizes(A.shape[1], len(y)))
        order, gain = greedy_residual_path(A, y, steps)
        return np.asarray(order, dtype=int), gain
