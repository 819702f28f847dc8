"""Contiguous time blocks about as long as a residual takes to forget itself.

The units a test or a bootstrap can treat as near-independent when the held-out
campaigns or folds are too few to be the units themselves: the diagnosis's
acceptance test (:mod:`thermocomp.apps.diagnose.blocks`, where the rule and its
measurements are described) and ``model=auto``'s votes with few validation folds
(:func:`thermocomp.core.models.blend.vote_weights`) cut them alike.
"""

from __future__ import annotations

import numpy as np

DECORRELATED = 0.2        # autocorrelation at which two samples count as near-independent


def decorrelation_length(residual, campaigns, scored) -> int:
    """Samples until the residual's autocorrelation within campaigns first falls to
    :data:`DECORRELATED` (the longest scored run when it never does)."""
    r = np.asarray(residual, float)
    ok = np.asarray(scored, bool) & np.isfinite(r)
    runs = _runs(np.asarray(campaigns, dtype=object), ok)
    if not runs:
        return 1
    centred = r - r[ok].mean()
    var = float(np.mean(centred[ok] ** 2))
    longest = max(len(run) for run in runs)
    if var <= 0.0:
        return 1
    series = [centred[run] for run in runs]     # copied once, not at every lag
    for lag in range(1, longest):
        num = cnt = 0.0
        for x in series:
            if len(x) > lag:
                num += float(x[:-lag] @ x[lag:])
                cnt += len(x) - lag
        if num / cnt / var <= DECORRELATED:       # cnt > 0: lag < the longest run
            return lag
    return longest


def _runs(campaigns: np.ndarray, ok: np.ndarray) -> list[np.ndarray]:
    """Row indices of each contiguous scored stretch of one campaign."""
    idx = np.flatnonzero(ok)
    if idx.size == 0:
        return []
    breaks = np.flatnonzero((np.diff(idx) != 1) | (campaigns[idx[1:]] != campaigns[idx[:-1]])) + 1
    return np.split(idx, breaks)


def cut_blocks(unit_index: np.ndarray, campaigns, length: int, timeline: bool = False) -> np.ndarray:
    """Test block of each row (-1: not scored): every contiguous scored stretch of one campaign
    (``timeline``: of the campaigns taken as one time line, as forward validation blocks run
    on into the next campaign) cut into ``len // length`` near-equal blocks (at least one).
    Neighbouring units shorter than ``length`` (time blocks of one record) thus share a test
    block: they are not independent of each other."""
    unit_index = np.asarray(unit_index)
    out = np.full(unit_index.shape, -1)
    ok = unit_index >= 0
    key = np.zeros(len(unit_index)) if timeline else np.asarray(campaigns, dtype=object)
    n = 0
    for run in _runs(key, ok):
        k = max(1, len(run) // max(int(length), 1))
        for part in np.array_split(run, k):
            out[part] = n
            n += 1
    return out
