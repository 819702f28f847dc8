"""Held-out runs re-referenced at their first samples: the rule autorep65 measured for
``model=auto``'s votes and diagref65 for ``diagnose``'s CV, taken into neither (autocheck65:
over 10 fresh records it reaches, auto's test RMSE new / shipped 1.032, geometric mean; diagref65:
five targets > 2 % worse than shipped).  Kept here so that the three benches score it as they did;
``vote_weights(squared=...)`` takes its squares."""

from __future__ import annotations

import numpy as np

REREFERENCE_SHARE = 0.05   # a held-out run re-referenced at the samples of its first 5 %,
REREFERENCE_MAX = 10       # at most 10 (fixed before scoring, bench_autorep65)


def rereferenced_squares(residual: np.ndarray, y: np.ndarray, campaign: np.ndarray) -> np.ndarray:
    """Squared errors of the columns of ``residual`` (out-of-fold residuals, rows x columns), each
    held-out run referenced to its first sample re-referenced at its first k samples: at row ``t``
    of such a run the mean over ``j < k`` of ``(r(t) - r(t_j))^2``, ``t_j`` its j-th out-of-fold
    (measured) row, ``k`` the samples of its first :data:`REREFERENCE_SHARE` (at least 1, at
    most :data:`REREFERENCE_MAX`).  ``campaign``: the run of each row; a run whose first label is
    not exactly 0 (not referenced to that sample: ``reference=none``, a late first probe) keeps
    ``r(t)^2``.

    With ``data.reference=first_sample`` a held-out run's label is ``E(t) + n(t) - E(t0) -
    n(t0)``: the first sample's noise ``n(t0)`` is an offset of the whole run and entered every
    candidate's fold MSE through ``2 n(t0) mean(r)``, one draw that reordered the candidates
    (``hmc`` E_Y: auto 1.58 against MLR's 0.78, all on the Hammerstein model; 0.81 re-referenced).
    The first samples barely move from the run's start state, so the re-referenced residual keeps
    what each candidate gets wrong over the run while ``n(t0)`` weighs 1/k as much
    (``benchmarks/bench_autorep65.py``).
    """
    squared = residual ** 2
    for c in np.unique(campaign):
        rows = np.flatnonzero(campaign == c)
        if y[rows[0]] != 0.0:
            continue
        k = min(REREFERENCE_MAX, max(1, int(REREFERENCE_SHARE * rows.size)))
        ref = residual[rows[:k]]
        squared[rows] = (residual[rows] - ref.mean(axis=0)) ** 2 + ref.var(axis=0)   # mean over j
    return squared
