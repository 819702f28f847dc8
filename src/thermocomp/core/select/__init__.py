"""Temperature-sensitive point (TSP) selectors.

A selector is a scikit-learn-style object: ``fit(X, y, groups=None)`` with
``X`` a DataFrame of candidate inputs, learned ``selected_`` (column names, in
order) and, for the supervised ones, ``scores_`` (per candidate) and ``ic_``
(information criterion per size when the size is chosen by one; the criteria live
in :mod:`thermocomp.core.model_selection`).
"""

from .base import AllInputs, TSPSelector
from .cluster_grey import ClusterGreySelector
from .greedy import GreedyResidualSelector
from .pearson import PearsonSelector

__all__ = ["AllInputs", "ClusterGreySelector", "GreedyResidualSelector", "PearsonSelector",
           "TSPSelector"]
