"""Selector base and the trivial selector."""

from __future__ import annotations

import pandas as pd
from sklearn.base import BaseEstimator


class AllInputs(BaseEstimator):
    """Select every declared input (``select=all``)."""

    def fit(self, X: pd.DataFrame, y=None, groups=None):
        self.selected_ = list(X.columns)
        return self
