"""The refit null of the ``forward`` scheme: the candidate's drivers shifted in time (diag112b).

Forward chaining has one time line, no campaigns to permute (:mod:`.refit_null`), and its sign
flips over validation blocks let clean records through at about twice alpha (bench_diag111d
``forward``: 5 of 200 at p <= .01, 4 taken).  So the candidate a round would take is refitted with
its drivers -- the context columns :func:`drivers` names -- shifted circularly along the train time
line (time and campaign labels stay, and so do the base's inputs): the drivers keep their own
autocorrelation and lose their alignment with the error.  Its p is the share of those refits whose
forward CV RMSE is at most its own, the observed counted once.

Offsets are whole samples at least one test block (the residual's decorrelation length) away from
the identity either way, so ``n - 2 * length + 1`` distinct shifts: offsets of whole blocks would give
22-29 on an 80 h record (floor ~.04, above alpha).  :data:`SHIFTS` are drawn without replacement
(floor 0.01), all of them where fewer; where the floor is above ``alpha``: None, the flips alone.
"""

from __future__ import annotations

import numpy as np

from .cv import CrossValidator
from .features import Effect
from .refit_null import PERMUTATIONS, MovedDrivers, moved_p
from .refit_null import drivers as campaign_drivers

SHIFTS = PERMUTATIONS      # p floor 0.01 = the default alpha


def drivers(effect: Effect, columns) -> list[str]:
    """:func:`.refit_null.drivers`, and for a lag of a model input read from the context (kind
    ``dynamics``, e.g. ``T_6``'s lag) its own column: the base reads the inputs matrix, untouched.
    Moved among campaigns such a lag kept the warm-up shape they share; shifted in time it does not,
    and on clean records the forward scheme took three such lags of four (bench_diag112b)."""
    if effect.kind != "dynamics":
        return campaign_drivers(effect, columns)
    return [c for c in effect.context_columns if c in columns]


def offsets(n: int, length: int, n_shifts: int, seed: int) -> np.ndarray:
    """The shifts of a time line of ``n`` rows at least ``length`` rows from the identity both ways:
    all of them where at most ``n_shifts``, else ``n_shifts`` drawn without replacement (seeded)."""
    allowed = np.arange(max(int(length), 1), n - max(int(length), 1) + 1)
    if len(allowed) <= n_shifts:
        return allowed
    return np.sort(np.random.default_rng(seed).choice(allowed, n_shifts, replace=False))


def block_length(problem) -> int:
    """The test blocks' length in rows (set on the residual's decorrelation), else the validated
    rows over the test blocks."""
    if problem.block_samples:
        return int(problem.block_samples)
    return max(1, int(problem.validated.sum()) // max(problem.n_blocks_tested, 1))


def shift_pvalue(cv: CrossValidator, inputs, kept, tested, observed_rmse: float, seed: int = 0,
                 alpha: float = 1.0, n_shifts: int = SHIFTS) -> float | None:
    """p of ``tested`` (effects added together to ``kept``) reaching forward CV RMSE
    ``observed_rmse``: the share of refits with the tested effects' drivers shifted by one offset
    (:func:`offsets`) that do as well, the observed counted once.  None where no tested effect has
    a driver or the shifts cannot resolve ``alpha``.  Stops once p exceeds ``alpha`` for sure."""
    p = cv.problem
    columns = list(dict.fromkeys(c for e in tested for c in drivers(e, p.context.columns)))
    shifts = offsets(len(p.y), block_length(p), n_shifts, seed)
    total = len(shifts) + 1                      # the observed, counted once
    if not columns or alpha * total < 1:
        return None
    values, fits = {c: p.context[c].to_numpy(float) for c in columns}, {}

    def shifted(shift: int):
        context = p.context.copy(deep=False)
        for c in columns:
            context[c] = np.roll(values[c], int(shift))
        return MovedDrivers(cv, context, kept, fits)

    return moved_p((shifted(s) for s in shifts), cv, inputs, kept, tested, observed_rmse, total, alpha)
