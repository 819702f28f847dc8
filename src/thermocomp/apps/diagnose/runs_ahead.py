"""The train runs ahead: a low-pass copy of the inputs must not lose where a whole run is predicted
(diag112c).

Forward chaining's validation blocks may all lie in the last train run (fresh 10247: 2 train runs,
its 16 blocks all in C02), so a low-pass copy of every input is scored on a run it has partly seen:
a 4 h copy of 12 inputs gained 43 % there and beat all 99 time shifts of its copies (p .01), yet
fitted on C01 it predicted C02 at 31.0 µm against the base's 10.2 (and the test run 4.28 -> 8.62 µm).
So each train run after the first is predicted by the fit on the runs before it, whole, with and
without the copy; the copy must not raise that squared error.
"""

from __future__ import annotations

import numpy as np

from ...core.context import for_target
from .cv import CrossValidator
from .shrink import PartialRidgePath


def ahead_sse(cv: CrossValidator, inputs, effects, alpha: float | None) -> float | None:
    """Squared error of every train run after the first, each predicted by the closed-form MLR
    fitted on the runs before it (penalty ``alpha`` on the effect features); None with one run or
    another base (its refit is the search's own: not repeated here)."""
    p = cv.problem
    labels = np.asarray(p.campaigns, dtype=object)
    order = list(dict.fromkeys(labels.tolist()))          # calendar order: the stacked one
    if len(order) < 2 or not cv.closed_form:
        return None
    names = cv.selection(tuple(inputs), None)
    fit_intercept = for_target(cv.estimator, p.target).fit_intercept
    total = 0.0
    for j in range(1, len(order)):
        train, test = np.isin(labels, order[:j]), (labels == order[j]) & p.measured
        Z = cv.design(names, effects, rows=train)
        fit = train & p.measured
        path = PartialRidgePath(Z[fit], p.y[fit], len(names), fit_intercept)
        total += float(np.sum((p.y[test] - path.predict(Z[test], [alpha or 0.0])[:, 0]) ** 2))
    return total


def loses_ahead(cv: CrossValidator, inputs, kept, tested) -> bool:
    """True where ``tested`` added to ``kept`` (at the penalty its CV chooses) predicts the train
    runs ahead worse than ``kept`` alone."""
    alpha = cv.run(inputs, list(kept) + list(tested)).alpha
    kept_alpha = cv.run(inputs, list(kept)).alpha if kept else None
    after = ahead_sse(cv, inputs, list(kept) + list(tested), alpha)
    before = ahead_sse(cv, inputs, list(kept), kept_alpha)
    return after is not None and before is not None and after > before
