"""The refit null: a second acceptance gate that moves a candidate's drivers among the campaigns.

The sign flips of :meth:`~.search.Search._family_bar` assume each held-out campaign's gain is
symmetric about 0 when the effect is absent.  A candidate fitted on the same campaigns is not: on
200 clean rooms (8 train campaigns, nothing planted) round 1's best candidate reached p <= .01 on 12
(bench_diag109 ``first``), the lean level law fitting the campaigns' chance offsets through their
starting ambients.  So a candidate that clears the flips is refitted with its per-campaign drivers
-- the context columns its features read, with the initial ambient for a level law or a start
lag -- moved among the train campaigns (each campaign takes another's values at the same elapsed
time; its own inputs stay), :data:`PERMUTATIONS` times.  Its p is the share of those refits whose
CV RMSE is at most its own, the observed counted once: floor ``1 / (PERMUTATIONS + 1)`` = 0.01
(every permutation up to 5 campaigns: 1/120).  Fewer campaigns than resolve alpha
(4: 24 orders) have no refit null: the flips alone, as before.
Under "no effect" the drivers are exchangeable among campaigns, whatever chance structure the
flips miss (``benchmarks/bench_diag111.py``).
"""

from __future__ import annotations

import copy
import itertools
import math

import numpy as np

from ...core.models._campaign_ls import FixedHead
from .cv import CrossValidator
from .features import Effect

PERMUTATIONS = 99      # p floor 0.01 = the default alpha
EXACT_ORDERS = 120     # up to 5 campaigns every order is refitted (drawn, the identity would recur)
AMBIENT = "ambient_c0"


def drivers(effect: Effect, columns) -> list[str]:
    """The per-campaign context columns ``effect``'s features read; [] for a lag of the model
    inputs (kind ``dynamics``), whose driver is what the base itself reads: moved among campaigns it
    keeps the warm-up shape every campaign shares, and a real lag does not lose to its moves
    (scenario ``axis_position`` read absolute: two start lags refused at p 0.02, test RMSE 1.73 ->
    3.21 µm)."""
    if effect.kind == "dynamics":
        return []
    own = [c for c in effect.context_columns if c in columns]
    if (effect.kind == "ambient_interval" or effect.initial_state) and AMBIENT in columns:
        own.append(AMBIENT)
    return list(dict.fromkeys(own))


class Mover:
    """Called with an order: the context with ``columns`` of campaign ``names[i]`` taken from
    ``names[order[i]]`` at the same elapsed time (held at the source's last sample past its end).
    Its campaigns' rows and elapsed times are found once (per order they were a fifth of the gate's
    CPU: diag111c); the context's other columns are not copied."""

    def __init__(self, context, campaigns, columns: list[str], names: list):
        labels = np.asarray(campaigns, dtype=object)
        time = context["time"].to_numpy(float)
        self.context, self.columns = context, list(columns)
        self.rows = [np.flatnonzero(labels == c) for c in names]
        self.elapsed = [time[r] - time[r[0]] for r in self.rows]
        self.values = {c: context[c].to_numpy(float) for c in self.columns}

    def __call__(self, order: np.ndarray):
        new = {c: v.copy() for c, v in self.values.items()}
        for i, j in enumerate(order):
            dst, src = self.rows[i], self.rows[j]
            at = np.searchsorted(self.elapsed[j], self.elapsed[i], side="right") - 1
            take = src[np.clip(at, 0, len(src) - 1)]
            for c in self.columns:
                new[c][dst] = self.values[c][take]
        out = self.context.copy(deep=False)
        for c in self.columns:
            out[c] = new[c]
        return out


class MovedDrivers(CrossValidator):
    """``base``'s cross-validation on a context whose drivers were moved; the ``kept`` effects (the
    search's accepted ones) keep ``base``'s features, the others are built on the moved context."""

    def __init__(self, base: CrossValidator, context, kept, fixed: dict | None = None):
        problem = copy.copy(base.problem)
        problem.context = context
        problem.__dict__.pop("_varies", None)
        super().__init__(problem, base.estimator, base.selector, base.shrink)
        self.base, self.kept = base, set(kept)
        self._selection = base._selection          # selection reads X and y only: shared
        # and so do the folds' inputs and level-law weights: every permutation's refit moves the
        # tested effects' columns only (diag111c); ``fixed``: the dict the refits share
        self._fixed = {} if fixed is None else fixed

    def inputs_matrix(self, names) -> np.ndarray:
        return self.base.inputs_matrix(names)

    def _head(self, names, effects) -> FixedHead | None:
        if self._fixed is None:
            return None
        kept = list(itertools.takewhile(lambda e: e in self.kept, effects))
        n = len(names) + sum(self.base.features(e, names).shape[1] for e in kept)
        return self._fixed.setdefault(("head", tuple(names), n), FixedHead(n))

    def fold_level_weights(self, names, fold) -> np.ndarray:
        return self.base.fold_level_weights(names, fold)

    def features(self, effect, names, fold=None, rows=None) -> np.ndarray:
        if effect in self.kept:
            return self.base.features(effect, names, fold, rows)
        return super().features(effect, names, fold, rows)


def refit_pvalue(cv: CrossValidator, inputs, kept, tested, observed_rmse: float, seed: int = 0,
                 alpha: float = 1.0, n_permutations: int = PERMUTATIONS) -> float | None:
    """p of ``tested`` (effects added together to ``kept``) reaching CV RMSE ``observed_rmse``: the
    share of refits with the tested effects' drivers moved among the campaigns (one permutation
    for all of them) that do as well, the observed counted once.  None where no tested effect has
    a context driver or the campaigns' permutations cannot resolve ``alpha`` (n! < 1 / alpha:
    4 campaigns give 24).  Stops once p exceeds
    ``alpha`` for sure: the p returned is then a lower bound, above ``alpha``."""
    p = cv.problem
    columns = list(dict.fromkeys(c for e in tested for c in drivers(e, p.context.columns)))
    names = list(dict.fromkeys(np.asarray(p.campaigns, dtype=object).tolist()))
    if not columns or math.factorial(len(names)) * alpha < 1:
        return None
    orders = _orders(len(names), n_permutations, seed)
    total = len(orders) + 1                      # the observed, counted once
    mover, fits = Mover(p.context, p.campaigns, columns, names), {}
    refits = (MovedDrivers(cv, mover(order), kept, fits) for order in orders)
    return moved_p(refits, cv, inputs, kept, tested, observed_rmse, total, alpha)


def moved_p(refits, cv: CrossValidator, inputs, kept, tested, observed_rmse: float,
            total: int, alpha: float) -> float:
    """``(1 + hits) / total``: a hit is a refit of ``kept`` and ``tested`` (each of ``refits``, made
    as asked) whose CV RMSE is at most ``observed_rmse``; it stops once the p is above ``alpha``.
    The one count of the campaigns' moves and of forward's shifts (:mod:`.shift_null`)."""
    effects, hits, limit = list(kept) + list(tested), 0, alpha * total - 1
    for refit in refits:
        # a move that leaves the features as they were (a drawn identity, ambients kept on their
        # side of a step's threshold) refits the observed: a hit, as it was when every refit
        # factored its folds anew (it had the observed RMSE to the last bit; shared factors
        # round it otherwise, 1e-14 relative: bench_diag111 first's room 68, diag111c)
        hits += unmoved(refit, cv, inputs, tested) or bool(refit.run(inputs, effects).rmse <= observed_rmse)
        if hits > limit:
            break
    return (1 + hits) / total


def unmoved(refit: MovedDrivers, cv: CrossValidator, inputs, tested) -> bool:
    """True when every tested effect's features (each fold's, for one that learns) are the same
    after the move as before it."""
    for fold in [None] + list(cv.problem.fold_ids):
        names = cv.selection(tuple(inputs), fold)
        for e in tested:
            if e.transform != "remove" and (fold is None or e.learns) and \
                    not np.array_equal(refit.features(e, names, fold), cv.features(e, names, fold)):
                return False
    return True


def _orders(n: int, n_permutations: int, seed: int) -> list[np.ndarray]:
    """Every permutation of ``n`` campaigns but the identity where they are at most
    :data:`EXACT_ORDERS` (the exact null: 5 campaigns, floor 1/120), else ``n_permutations``
    drawn (seeded; the identity may recur, as a drawn permutation test allows)."""
    if math.factorial(n) <= EXACT_ORDERS:
        return [np.array(o) for o in itertools.permutations(range(n)) if o != tuple(range(n))]
    rng = np.random.default_rng(seed)
    return [rng.permutation(n) for _ in range(n_permutations)]
