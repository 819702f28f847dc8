"""Temperature-sensitive point (TSP) selectors.

A selector is a scikit-learn-style object: ``fit(X, y)`` with ``X`` a DataFrame
of candidate inputs, learned ``selected_`` (column names, in order).
"""

from .base import AllInputs

__all__ = ["AllInputs"]
