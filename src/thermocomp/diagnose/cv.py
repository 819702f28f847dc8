"""Honest residuals: leave-campaigns-out cross-validation on the train split, and its test.

The *unit* of cross-validation is a campaign: every campaign is held out once
and predicted by a model that never saw it.  When the train split is a single
campaign (one long record) the units are contiguous time blocks of it (CLI.md).
Units go to ``n_folds`` folds in turn (unit ``i`` -> fold ``i mod K``), so with
campaigns in calendar order every fold spans the seasons
(:class:`~thermocomp.model_selection.LeaveCampaignsOut`).

Everything works on the stacked train matrices: the selector and the
estimator are refitted in every fold exactly as the
:class:`~thermocomp.compensator.Compensator` fits them, without re-reading
or re-referencing the campaigns for each fit (that is what makes a search
over dozens of candidates affordable).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np
import pandas as pd
from sklearn.base import clone

from ..context import CAMPAIGN, Y_MEASURED, for_target
from ..model_selection import LeaveCampaignsOut
from ..select import AllInputs
from .features import Effect, effect_features, in_frame, initial_offsets, principal_directions, transient


@dataclass
class Problem:
    """The train rows of one target, stacked, with their CV structure.

    ``campaigns`` drives the features (lags run over whole campaigns);
    ``units`` are what CV holds out and what the model sees as ``groups``
    (the campaigns themselves, or blocks of a single campaign).
    """

    X: pd.DataFrame               # declared inputs, reference frame
    y: np.ndarray
    context: pd.DataFrame
    campaigns: np.ndarray
    units: np.ndarray
    target: str
    mode: str = "simulation"
    reference: str = "first_sample"
    n_folds: int = 10
    unit_names: list = field(init=False)
    unit_index: np.ndarray = field(init=False)
    folds: np.ndarray = field(init=False)

    def __post_init__(self):
        self.unit_names = list(dict.fromkeys(self.units))
        pos = {u: i for i, u in enumerate(self.unit_names)}
        self.unit_index = np.array([pos[u] for u in self.units])
        self.folds = LeaveCampaignsOut(self.n_folds).fold_index(self.units)

    def varies(self, column: str) -> bool:
        """True when context ``column`` changes within the train data (in the target's frame)."""
        cache = self.__dict__.setdefault("_varies", {})
        if column not in cache:
            framed = in_frame(self.context[column].to_numpy(float), self.campaigns, self.reference)
            cache[column] = bool(np.nanstd(framed) > 1e-12)
        return cache[column]

    @property
    def n_units(self) -> int:
        return len(self.unit_names)

    @property
    def fold_ids(self) -> list[int]:
        return sorted(set(self.folds.tolist()))


@dataclass
class CVResult:
    """Cross-validated prediction of the train rows and its error per unit."""

    prediction: np.ndarray
    residual: np.ndarray
    rmse: float
    unit_mse: np.ndarray      # mean squared residual of each held-out unit


class CrossValidator:
    """Leave-units-out predictions of a Compensator-like model with extra effects.

    Parameters
    ----------
    problem : Problem
    estimator : regressor
        The configured estimator (cloned per fold, for the problem's target);
        it gets the fold's context, whose ``campaign`` is the CV unit (a time
        block of a single campaign is a campaign of its own: no lag reaches
        across a held-out block), and in one-step mode the measured target.
    selector : selector or None
        Refitted per fold on the declared inputs left after exclusions.
    """

    def __init__(self, problem: Problem, estimator, selector=None):
        self.problem, self.estimator = problem, estimator
        self.selector = selector if selector is not None else AllInputs()
        self._selection: dict = {}
        self._features: dict = {}
        self._ctx: dict = {}

    # -- building blocks --------------------------------------------------------------------
    def selection(self, inputs: tuple, fold: int | None) -> list[str]:
        """Selected inputs among ``inputs`` on the rows outside ``fold`` (all rows for None)."""
        key = (tuple(inputs), fold)
        if key not in self._selection:
            p = self.problem
            if isinstance(self.selector, AllInputs):
                names = list(inputs)
            else:
                rows = np.ones(len(p.y), bool) if fold is None else p.folds != fold
                Xf = p.X.loc[rows, list(inputs)].reset_index(drop=True)
                names = list(clone(self.selector).fit(Xf, p.y[rows]).selected_)
            self._selection[key] = names
        return self._selection[key]

    def inputs_matrix(self, names) -> np.ndarray:
        key = ("X", tuple(names))
        if key not in self._features:
            self._features[key] = self.problem.X[list(names)].to_numpy(float)
        return self._features[key]

    def features(self, effect: Effect, names: list[str], fold: int | None = None) -> np.ndarray:
        """Features of ``effect`` on all train rows (cached; input effects per input set).

        An effect that ``learns`` (initial directions) learns from the rows
        outside ``fold`` (all rows for None), as the fitted model would.
        """
        fold = fold if effect.learns else None
        key = (effect, tuple(names) if effect.uses_inputs else None, fold)
        if key not in self._features:
            p = self.problem
            if effect.initial_state:     # the lag (cached once) + the initial-state transient
                lag = self.features(replace(effect, initial_state=None, initial_directions=None), names)
                offsets = self._offsets(effect.initial_state)
                weights = None
                if effect.learns:
                    rows = np.ones(len(p.y), bool) if fold is None else p.folds != fold
                    weights = principal_directions(offsets[rows], p.campaigns[rows],
                                                   effect.initial_directions)
                start = transient(offsets, weights, p.context["time"].to_numpy(float), p.campaigns,
                                  effect.tau_s)
                self._features[key] = np.hstack([lag, start])
            else:
                X = self.inputs_matrix(names) if effect.uses_inputs else np.empty((len(p.y), 0))
                self._features[key] = effect_features(effect, X, p.context, p.campaigns, p.reference)
        return self._features[key]

    def _offsets(self, columns: tuple) -> np.ndarray:
        key = ("offsets", columns)
        if key not in self._features:
            p = self.problem
            self._features[key] = initial_offsets(p.context, columns, p.campaigns)
        return self._features[key]

    def design(self, names: list[str], effects, fold: int | None = None) -> np.ndarray:
        return np.hstack([self.inputs_matrix(names)] + [self.features(e, names, fold) for e in effects])

    def _context(self, fold: int, train: bool) -> pd.DataFrame:
        key = (fold, train)
        if key not in self._ctx:
            p = self.problem
            rows = (p.folds != fold) if train else (p.folds == fold)
            ctx = p.context.loc[rows].reset_index(drop=True)
            ctx[CAMPAIGN] = p.units[rows]
            if p.mode == "one_step" and not train:
                ctx[Y_MEASURED] = p.y[rows]
            self._ctx[key] = ctx
        return self._ctx[key]

    # -- cross-validation -------------------------------------------------------------------
    def run(self, inputs, effects=()) -> CVResult:
        """CV prediction with declared ``inputs`` (after exclusions) and extra ``effects``."""
        p = self.problem
        effects = [e for e in effects if e.transform != "remove"]
        pred = np.empty(len(p.y))
        for k in p.fold_ids:
            tr, te = p.folds != k, p.folds == k
            Z = self.design(self.selection(tuple(inputs), k), effects, k)
            est = clone(for_target(self.estimator, p.target))
            est.fit(Z[tr], p.y[tr], context=self._context(k, True))
            pred[te] = np.asarray(est.predict(Z[te], context=self._context(k, False)), dtype=float)
        return self._result(pred)

    def _result(self, pred: np.ndarray) -> CVResult:
        p = self.problem
        r = p.y - pred
        sums = np.bincount(p.unit_index, weights=r**2, minlength=p.n_units)
        counts = np.bincount(p.unit_index, minlength=p.n_units)
        return CVResult(pred, r, float(np.sqrt(np.mean(r**2))), sums / np.maximum(counts, 1))


@lru_cache(maxsize=8)
def _sign_patterns(n: int) -> np.ndarray:
    return 1.0 - 2.0 * ((np.arange(2**n)[:, None] >> np.arange(n)) & 1)


def sign_flip_pvalue(d, n_resamples: int = 20000, seed: int = 0) -> float:
    """One-sided p-value of ``mean(d) > 0`` by flipping the signs of the paired differences.

    ``d`` holds one value per CV unit (campaign): under the null the candidate
    does not help, each unit's gain is as likely negative as positive.  Exact
    over all :math:`2^n` patterns up to ``n = 16`` units, Monte Carlo beyond.
    (Written out rather than :func:`scipy.stats.permutation_test`, which gives
    the same p-value but enumerates the 65 536 patterns of 16 units ~20x slower,
    and the search calls it for every shortlisted candidate.)
    """
    d = np.asarray(d, dtype=float)
    d = d[np.isfinite(d)]
    n = d.size
    if n == 0:
        return 1.0
    observed = d.mean()
    tol = 1e-12 * max(np.abs(d).sum(), 1e-300)
    if n <= 16:
        means = _sign_patterns(n) @ d / n
        return float(np.mean(means >= observed - tol))
    rng = np.random.default_rng(seed)
    signs = rng.choice([-1.0, 1.0], size=(n_resamples, n))
    means = signs @ d / n
    return float((1 + np.sum(means >= observed - tol)) / (n_resamples + 1))
