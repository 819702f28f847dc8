"""Split unbiased greedy selection (paper 000, Sect. 2.2, after Liu et al. 2018)."""

from __future__ import annotations

import numpy as np

from ..model_selection.greedy import greedy_path, scaled_gram
from .base import TSPSelector


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
    matter; lagged (ARX) variants belong to :mod:`thermocomp.core.models.arx`.  The
    search runs on the Gram matrix of the centred data
    (:func:`~thermocomp.core.model_selection.greedy_path`, shared with ARX): a sensor
    constant on the data, or collinear with those already kept, is never picked.

    Parameters
    ----------
    k : int or None, default None
    criterion : {'aic', 'aicc', 'bic', 'bicc'}, default 'bicc'
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
        n, p = A.shape
        steps = max(self._sizes(p, n))
        data = np.column_stack([A, y])
        M, scale = scaled_gram(data - data.mean(axis=0))
        path = greedy_path(M, p, range(p), max_inputs=steps, search="residual")
        if not path.order:
            raise ValueError(f"{type(self).__name__} found no usable sensor: every one of the {p} "
                             f"columns is constant on {n} sample(s)")
        # the path's gain is the residual sum of squares removed, in units of M: back to MSE
        return np.asarray(path.order, dtype=int), path.gain * scale[p] ** 2 / n
