"""The train runs ahead: a low-pass copy of the inputs must gain where a whole run is predicted
(diag112c).

Forward chaining's validation blocks may all lie in the last train run (fresh 10247: 2 train runs,
its 16 blocks all in C02), so a low-pass copy of every input is scored on a run it has partly seen:
a 4 h copy of 12 inputs gained 43 % there and beat all 99 time shifts of its copies (p .01), yet
fitted on C01 it predicted C02 no better than the base at any penalty (RMSE 10.2-54 µm against
10.2), and the test run went 4.28 -> 8.62 µm.  So each train run after the first is predicted by
the fit on the runs before it, whole, with and without the copy.  The penalty is the one of least
error there, chosen on the runs it scores, so the copy must gain :data:`MIN_GAIN_PCT` at least:
a 1 h lag of the inputs planted into the same draw, 1 h copy fitted on C01 alone, loses at no
penalty (22 µm against 20) and gains 58 % at its best.
"""

from __future__ import annotations

import numpy as np

from ...core.context import for_target
from .cv import CrossValidator
from .shrink import ALPHAS, PartialRidgePath

MIN_GAIN_PCT = 5.0     # the search's bar (SearchOptions.min_gain_pct's default)


def ahead_sse(cv: CrossValidator, inputs, effects) -> np.ndarray | None:
    """Squared error of every train run after the first, each predicted by the closed-form MLR
    fitted on the runs before it, per penalty of :data:`~.shrink.ALPHAS` on the effect features;
    None with one run or another base (the estimators the search refits have no penalty path)."""
    p = cv.problem
    labels = np.asarray(p.campaigns, dtype=object)
    order = list(dict.fromkeys(labels.tolist()))          # calendar order: the stacked one
    if len(order) < 2 or not cv.closed_form:
        return None
    names = cv.selection(tuple(inputs), None)
    fit_intercept = for_target(cv.estimator, p.target).fit_intercept
    alphas = ALPHAS if effects else np.zeros(1)
    total = np.zeros(alphas.size)
    for j in range(1, len(order)):
        train, test = np.isin(labels, order[:j]), (labels == order[j]) & p.measured
        Z = cv.design(names, effects, rows=train)
        fit = train & p.measured
        path = PartialRidgePath(Z[fit], p.y[fit], len(names), fit_intercept)
        total += np.sum((p.y[test][:, None] - path.predict(Z[test], alphas)) ** 2, axis=0)
    return total


def loses_ahead(cv: CrossValidator, inputs, kept, tested) -> bool:
    """True where ``tested`` added to ``kept`` predicts the train runs ahead, at its best penalty,
    not :data:`MIN_GAIN_PCT` % better (RMSE) than ``kept`` alone at its own best."""
    after = ahead_sse(cv, inputs, list(kept) + list(tested))
    before = ahead_sse(cv, inputs, list(kept))
    if after is None or before is None:
        return False
    return bool(np.sqrt(after.min()) > (1 - MIN_GAIN_PCT / 100) * np.sqrt(before.min()))
