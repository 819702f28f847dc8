"""Top-k sensors by absolute Pearson correlation with the error (paper 003, Sect. 2.2)."""

from __future__ import annotations

import numpy as np

from .base import TSPSelector


def abs_correlation(A: np.ndarray, y: np.ndarray) -> np.ndarray:
    """|Pearson r| of each column of ``A`` with ``y`` (0 for a constant column)."""
    Ac, yc = A - A.mean(axis=0), y - y.mean()
    den = np.sqrt((Ac * Ac).sum(axis=0) * (yc @ yc))
    with np.errstate(invalid="ignore", divide="ignore"):
        r = np.where(den > 0, (Ac.T @ yc) / den, 0.0)
    return np.abs(r)


class PearsonSelector(TSPSelector):
    r"""Keep the ``k`` sensors most correlated with the error (``select=pearson``).

    .. math:: \rho_{x_i y} = \frac{\mathrm{Cov}(x_i, y)}{\sqrt{\mathrm{Var}(x_i)\,\mathrm{Var}(y)}}

    Sensors are ranked by :math:`|\rho|`; paper 003 keeps two and leaves
    collinearity to PCR.

    Parameters
    ----------
    k : int or None, default 2
        Number of sensors; ``None`` chooses it in ``1..k_max`` by ``criterion``.
    criterion : {'aic', 'aicc', 'bic', 'bicc'}, default 'bicc'
    k_max : int, default 10

    Attributes
    ----------
    selected_ : list of str
    scores_ : pandas.Series
        :math:`|\rho|` of every candidate.
    ic_ : pandas.Series or None
    """

    score_label = "|r| with the error"

    def __init__(self, k: int | None = 2, criterion: str = "bicc", k_max: int = 10):
        self.k = k
        self.criterion = criterion
        self.k_max = k_max

    def _rank(self, A, y, groups):
        scores = abs_correlation(A, y)
        return np.argsort(-scores, kind="stable"), scores
