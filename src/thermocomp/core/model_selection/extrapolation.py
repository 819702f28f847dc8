"""Rows a validation fold extrapolates to: outside the region its fit rows cover.

A held-out row whose inputs leave the range of the rows the fold fitted on is an
extrapolation: there a model can look far better or worse than where its inputs have been
seen.  A row is within range when its leverage in the fit rows' design (centred inputs) is
at most the largest leverage of a fit row -- inside the ellipsoid that holds the fit data,
the classical check for hidden extrapolation (Montgomery, Peck & Vining, *Introduction to
Linear Regression Analysis*, 3.8).  ``diagnose`` asks a gain to hold on those rows
(:meth:`thermocomp.apps.diagnose.search.Search._clears`); ``model=auto`` can score its candidates there
(:class:`~thermocomp.core.models.auto.AutoRegressor`, ``validation_rows``).
"""

from __future__ import annotations

import numpy as np


def within_range(X: np.ndarray, train: np.ndarray, scored: np.ndarray) -> np.ndarray:
    """Rows of ``scored`` whose leverage in the design of the ``train`` rows is at most the
    largest leverage of a training row (the fold does not extrapolate there)."""
    Z = X[train]
    mean = Z.mean(axis=0)
    U, s, Vt = np.linalg.svd(Z - mean, full_matrices=False)
    keep = s > (s[0] * 1e-8 if s.size else 0.0)
    if not keep.any():
        return scored.copy()
    W = Vt[keep].T / s[keep]                   # whitening: leverage = |(x - mean) W|^2
    limit = float(np.max(np.sum((U[:, keep]) ** 2, axis=1)))
    lev = np.sum(((X[scored] - mean) @ W) ** 2, axis=1)
    out = np.zeros(len(X), bool)
    out[np.flatnonzero(scored)] = lev <= limit * (1.0 + 1e-9)
    return out
