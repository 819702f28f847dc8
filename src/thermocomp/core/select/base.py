"""Selector bases: the trivial selector and the machinery of the supervised ones."""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
from sklearn.base import BaseEstimator
from sklearn.feature_selection import SelectorMixin
from sklearn.utils.validation import check_is_fitted, validate_data

from ...base.params import check_estimator, choice, integer, optional
from ..model_selection.criteria import CRITERIA, ic_path


class AllInputs(BaseEstimator):
    """Select every declared input (``select=all``)."""

    def fit(self, X: pd.DataFrame, y=None, groups=None):
        self.selected_ = list(X.columns)
        return self


class TSPSelector(SelectorMixin, BaseEstimator):
    """Common machinery of the supervised TSP selectors.

    Subclasses implement ``_rank(X, y, groups) -> (order, scores)`` -- column
    indices in selection order and a score per candidate -- or override
    ``_candidate_sets`` when each size needs its own search.  With ``k`` an
    integer the first ``k`` are kept; with ``k=None`` the size in
    ``1..k_max`` that minimises ``criterion`` for an OLS fit (with intercept)
    on the kept sensors is used.

    Attributes
    ----------
    selected_ : list of str
        Selected columns, in selection order.
    scores_ : pandas.Series
        Per-candidate score used for the ranking (see the subclass).
    ic_ : pandas.Series or None
        Criterion per size ``k`` when ``k=None``.
    feature_names_in_ : ndarray of str (DataFrame input only)
    """

    _k_min = 1
    param_rules = {"k": optional(integer(1)), "criterion": choice(*CRITERIA), "k_max": integer(1)}

    def _names(self, n_features: int) -> np.ndarray:
        names = getattr(self, "feature_names_in_", None)
        return np.asarray(names if names is not None else [f"x{i}" for i in range(n_features)],
                          dtype=object)

    def check_params(self) -> None:
        """Raise :class:`~thermocomp.base.errors.ParameterError` (a ValueError) for a parameter
        outside its allowed values."""
        check_estimator(self)

    def fit(self, X, y, groups=None):
        """Select sensors for target ``y``; ``groups`` (campaign per row) is accepted for API
        uniformity -- the fits here are static, so campaign boundaries do not matter."""
        self.check_params()
        A, y = validate_data(self, X, y, y_numeric=True, dtype=np.float64)
        names = self._names(A.shape[1])
        sets, scores = self._candidate_sets(A, y, groups)
        if len(sets) == 1 or self.k is not None:
            self.ic_, best = None, sets[-1]
        else:
            ic = ic_path(A, y, sets, self.criterion)
            self.ic_ = pd.Series(ic, index=[len(s) for s in sets], name=self.criterion)
            best = sets[int(np.argmin(ic))]
        self.support_order_ = np.asarray(best, dtype=int)
        self.selected_ = [str(names[i]) for i in best]
        self.scores_ = pd.Series(scores, index=[str(n) for n in names], name="score")
        return self

    def _sizes(self, n_features: int, n_samples: int) -> list[int]:
        if self.k is not None:
            if int(self.k) > n_features:
                warnings.warn(f"select k={self.k}: only {n_features} candidate inputs, all taken",
                              UserWarning, stacklevel=3)
            return [min(int(self.k), n_features)]
        top = max(self._k_min, min(int(self.k_max), n_features, max(n_samples - 3, 1)))
        return list(range(self._k_min, top + 1))

    def _candidate_sets(self, A, y, groups):
        order, scores = self._rank(A, y, groups)
        # a ranking may be short: the greedy search never picks a constant or collinear sensor
        sizes = [k for k in self._sizes(A.shape[1], len(y)) if k <= len(order)] or [len(order)]
        return [list(order[:k]) for k in sizes], scores

    def _get_support_mask(self):
        check_is_fitted(self)
        mask = np.zeros(self.n_features_in_, dtype=bool)
        mask[self.support_order_] = True
        return mask

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.target_tags.required = True
        return tags
