"""Fuzzy C-means clusters of sensors, one representative per cluster by grey relational degree."""

from __future__ import annotations

import numpy as np

from ...base.params import integer, number
from .base import TSPSelector
from .pearson import abs_correlation


def grey_relational_degree(A: np.ndarray, y: np.ndarray, rho: float = 0.5) -> np.ndarray:
    r"""Deng's grey relational degree of each column of ``A`` with the reference ``y``.

    Sequences are sign-aligned with ``y`` (a sensor that falls while the error
    grows is as informative) and min-max normalised; then
    :math:`\xi_i(t) = (\Delta_{min} + \rho\Delta_{max}) / (\Delta_i(t) + \rho\Delta_{max})`
    with :math:`\Delta_i(t) = |y^*(t) - x_i^*(t)|` and the degree is the mean
    of :math:`\xi_i` over time.
    """
    def unit(v):
        lo, span = v.min(axis=0), np.ptp(v, axis=0)
        return (v - lo) / np.where(span > 0, span, 1.0)

    Ac, yc = A - A.mean(axis=0), y - y.mean()
    sign = np.where(Ac.T @ yc < 0, -1.0, 1.0)
    delta = np.abs(unit(y[:, None]) - unit(A * sign))
    dmin, dmax = delta.min(), delta.max()
    if dmax == 0:
        return np.ones(A.shape[1])
    return ((dmin + rho * dmax) / (delta + rho * dmax)).mean(axis=0)


def sensor_embedding(A: np.ndarray) -> np.ndarray:
    """Coordinates of each sensor (row) whose Euclidean distances equal those of the z-scored series.

    Distances between z-scored series measure how differently sensors move
    (:math:`d^2 = 2n(1-r)`); the SVD keeps them exactly in at most
    ``n_sensors`` dimensions, which spares fuzzy C-means the collapse of its
    centres in the thousands of dimensions of the raw record.
    """
    sd = A.std(axis=0)
    Z = (A - A.mean(axis=0)) / np.where(sd > 0, sd, 1.0)
    _, s, vt = np.linalg.svd(Z, full_matrices=False)
    return (vt.T * s) / np.sqrt(len(A))


def fuzzy_clusters(points: np.ndarray, c: int, m: float, seed: int) -> np.ndarray:
    """Hard labels (max membership) of scikit-fuzzy's C-means on ``points`` (one row per sensor)."""
    if c >= len(points):
        return np.arange(len(points))
    if c == 1:
        return np.zeros(len(points), dtype=int)
    import skfuzzy  # here: every command loads this module (the selectors), few use it

    _, u, *_ = skfuzzy.cluster.cmeans(points.T, c, m, error=1e-6, maxiter=1000, seed=seed)
    return np.argmax(u, axis=0)


class ClusterGreySelector(TSPSelector):
    r"""Fuzzy C-means of sensors, then the best sensor of each cluster (``select=cluster_grey``).

    Sensors are clustered by how they move (z-scored series, fuzzy exponent
    ``m``; scikit-fuzzy), each sensor going to the cluster of highest
    membership.  From each cluster the sensor with the highest grey relational
    degree with the error is kept, so the inputs are informative and mutually
    little collinear (the classic TSP method cited in paper 003).  ``k`` is the
    number of clusters; with ``k=None`` it is chosen in ``1..k_max`` by
    ``criterion`` on a joint OLS fit of the representatives.

    Parameters
    ----------
    k : int or None, default None
    criterion : {'aic', 'aicc', 'bic', 'bicc'}, default 'bicc'
    k_max : int, default 10
    m : float, default 2.0
        Fuzzy exponent.
    rho : float, default 0.5
        Distinguishing coefficient of the grey relational degree.
    random_state : int, default 0
        Seed of the C-means initialisation.

    Attributes
    ----------
    selected_ : list of str
        Representatives, by decreasing grey degree.
    scores_ : pandas.Series
        Grey relational degree of every candidate.
    clusters_ : dict str -> int
        Cluster of each candidate in the chosen clustering.
    ic_ : pandas.Series or None
    """

    score_label = "grey relational degree"
    # rho: the grey distinguishing coefficient, in (0, 1] (0.5 usual)
    param_rules = {**TSPSelector.param_rules, "m": number(1.0, open_lo=True),
                   "rho": number(0.0, 1.0, open_lo=True), "random_state": integer(0, 2 ** 32 - 1)}

    def __init__(self, k: int | None = None, criterion: str = "bicc", k_max: int = 10,
                 m: float = 2.0, rho: float = 0.5, random_state: int = 0):
        self.k = k
        self.criterion = criterion
        self.k_max = k_max
        self.m = m
        self.rho = rho
        self.random_state = random_state

    def _candidate_sets(self, A, y, groups):
        grey = grey_relational_degree(A, y, self.rho)
        # a constant sensor carries nothing: rank it last whatever its grey degree
        grey_rank = np.where(abs_correlation(A, y) > 0, grey, -np.inf)
        points = sensor_embedding(A)
        sets, self._labels = [], []
        for c in self._sizes(A.shape[1], len(y)):
            labels = fuzzy_clusters(points, c, self.m, self.random_state)
            reps = [max(np.flatnonzero(labels == g), key=lambda i: grey_rank[i])
                    for g in np.unique(labels)]
            sets.append(sorted(reps, key=lambda i: -grey_rank[i]))
            self._labels.append(labels)
        return sets, grey

    def fit(self, X, y, groups=None):
        super().fit(X, y, groups)
        best = 0 if self.ic_ is None else int(np.argmin(self.ic_.to_numpy()))
        labels = self._labels[-1 if self.ic_ is None else best]
        self.clusters_ = {n: int(g) for n, g in zip(self.scores_.index, labels)}
        del self._labels
        return self
