"""Honest residuals: cross-validation on the train split, and its test.

Two schemes (``diagnose.cv``, chosen by
:func:`~thermocomp.core.model_selection.cv_scheme`: ``auto`` takes the first for
several train campaigns, the second for one):

* **campaigns** -- the *unit* of cross-validation is a campaign: every campaign
  is held out once and predicted by a model that never saw it.  Units go to
  ``n_folds`` folds in turn (unit ``i`` -> fold ``i mod K``), so with campaigns
  in calendar order every fold spans the seasons
  (:class:`~thermocomp.core.model_selection.LeaveCampaignsOut`).  A single campaign
  forced into this scheme is cut into contiguous time blocks.
* **forward** -- one long record (or campaigns taken as one time line): the
  last ``1 - min_train_fraction`` of the rows are cut into ``n_blocks``
  validation blocks; block ``k`` is predicted by a model trained on every row
  before it less a ``gap`` (the longest lag tried), as the deployed model
  predicts what follows its training data
  (:class:`~thermocomp.core.model_selection.ForwardChaining`).  A block held out in
  the middle of a drifting record would be an extrapolation in both
  directions, scored far worse than the deployed model ever is.  The model
  runs through the whole record up to the block (its lags and AR states carry
  over, as on the machine); only the block's rows are scored.  The units of
  the sign-flip test are then runs of validation blocks at least as long as
  the residual takes to decorrelate (:mod:`~thermocomp.core.model_selection.blocks`).

Everything works on the stacked train matrices: the selector and the
estimator are refitted in every fold exactly as the
:class:`~thermocomp.core.compensator.Compensator` fits them, without re-reading
or re-referencing the campaigns for each fit (that is what makes a search
over dozens of candidates affordable).  An :class:`~thermocomp.core.models.MLR`
base is fitted in closed form, with the penalty on the effect features that
minimises the CV error (:mod:`.shrink`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np
import pandas as pd
from sklearn.base import clone

from ...core.context import CAMPAIGN, Y_MEASURED, for_target
from ...core.model_selection import ForwardChaining, LeaveCampaignsOut
from ...core.model_selection.blocks import cut_blocks, decorrelation_length
from ...core.model_selection.extrapolation import within_range
from ...core.models._campaign_ls import CampaignLeastSquares, FixedHead
from ...core.models._memo import BoundedCache
from ...core.models.linear import MLR
from ...core.select import AllInputs
from .features import (
    Effect,
    effect_features,
    in_frame,
    initial_offsets,
    level_weights,
    principal_directions,
    transient,
)
from .shrink import ALPHAS, InputsFit, PartialRidgePath, least_error, one_standard_error

# Every candidate screened keeps its features (a column or a few per train row): on a year at
# 1 min that grew past 6 GB in diagnose (scale58). Past this bound the least recently used
# are computed again when asked (the same numbers); a small record keeps them all.
FEATURE_CACHE_BYTES = 1e9


@dataclass
class Problem:
    """The train rows of one target, stacked, with their CV structure.

    ``campaigns`` drives the features (lags run over whole campaigns);
    ``units`` are what CV holds out and what the model sees as ``groups``
    (the campaigns themselves, or blocks of a single campaign) in the
    ``campaigns`` scheme.  In the ``forward`` scheme the units are the
    validation blocks (the rows before the first one are never scored), and
    the model sees the real campaigns.
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
    scheme: str = "campaigns"     # or "forward"
    n_blocks: int = 8             # forward: validation blocks
    gap: int = 0                  # forward: rows left out before each validation block
    min_train_fraction: float = 0.5
    unit_names: list = field(init=False)
    unit_index: np.ndarray = field(init=False)
    folds: np.ndarray = field(init=False)

    def __post_init__(self):
        n = len(self.y)
        if self.scheme == "forward":
            splitter = ForwardChaining(int(self.n_blocks), int(self.gap),
                                       min_train_fraction=self.min_train_fraction)
            self.folds = np.full(n, -1)
            self._train_end = []
            for k, (tr, te) in enumerate(splitter.split(np.empty((n, 1)))):
                self.folds[te] = k
                self._train_end.append(int(tr[-1]) + 1)
            # one unit per block, named after the campaign it starts in (a block may run on
            # into the next campaign of the time line: still one fold, one unit of the test)
            labels = np.asarray(self.campaigns, dtype=object)
            first = {k: labels[np.argmax(self.folds == k)] for k in set(self.folds.tolist()) if k >= 0}
            self.units = np.array([f"{first[k]}#{k + 1}" if k >= 0 else str(c)
                                   for c, k in zip(labels, self.folds)], dtype=object)
        elif self.scheme == "campaigns":
            self.folds = LeaveCampaignsOut(self.n_folds).fold_index(self.units)
        else:
            raise ValueError(f"unknown CV scheme {self.scheme!r}")
        # an error measured on 1 row in N (a probe cycle, data.sparse_targets) is NaN between
        # its measurements: every row runs through the model (the inputs' dynamics), only the
        # measured ones fit and score; a unit or fold without one is no unit, no fold
        self.measured = np.isfinite(np.asarray(self.y, float))
        self.validated = (self.folds >= 0) & self.measured
        self.unit_names = list(dict.fromkeys(self.units[self.validated]))
        pos = {u: i for i, u in enumerate(self.unit_names)}
        self.unit_index = np.array([pos.get(u, -1) if k >= 0 else -1
                                    for u, k in zip(self.units, self.folds)])
        self.held_out = self.unit_index >= 0     # the scored units' rows, measured or not
        self.block_index = np.where(self.validated, self.unit_index, -1)   # the test's units
        self.block_samples = None                                           # (below)
        self.penalty_index = self.block_index      # the deployed penalty's standard error's

    @property
    def sparse(self) -> bool:
        """True when the error is not measured at every row (a probe cycle)."""
        return not bool(self.measured.all())

    def set_test_blocks(self, length: int, penalty_length: int | None = None) -> None:
        """Test the gains on time blocks of ``length`` samples within the units: as long as the
        model's CV residual takes to decorrelate (:mod:`~thermocomp.core.model_selection.blocks`).
        With an error measured now and then, ``length`` counts measured samples (the residual's
        decorrelation is measured on the measured series at its own spacing).
        ``penalty_length`` (default ``length``): the blocks over which the deployed penalty's
        one-standard-error rule takes its standard error (:meth:`CrossValidator.run`)."""
        self.block_samples = int(length)
        self.penalty_samples = self.block_samples if penalty_length is None else int(penalty_length)
        self.block_index = self._cut(self.block_samples)
        self.penalty_index = (self.block_index if self.penalty_samples == self.block_samples
                              else self._cut(self.penalty_samples))

    def recut_test_blocks(self, residual: np.ndarray) -> bool:
        """Re-cut the test blocks (not the penalty's) as long as ``residual`` takes to
        decorrelate, as :meth:`set_test_blocks` was on the starting one; True when they changed.
        A search re-cuts them each round on its current residual: once an effect is taken the
        rest may stay correlated longer, and blocks cut on the starting residual then test
        dependent gains (planted 8282's E_Y: 13 samples cut, 24 after the position effect, a
        random walk cleared every check; bench_diag82e / bench_diag82f).  Never longer than the
        shared design's (the penalty's) blocks: no round tests on fewer blocks than the shipped
        design did (vtl78's dX re-cut to 9 blocks of its 15 lost the ram's effect; diag82g)."""
        if self.block_samples is None:
            return False
        length = min(decorrelation_length(residual, self.campaigns, self.validated, self.held_out),
                     self.penalty_samples)
        if length == self.block_samples:
            return False
        self.cut_to(length)
        return True

    def cut_to(self, length: int) -> None:
        """The test blocks cut anew, ``length`` samples each."""
        self.block_samples = int(length)
        self.block_index = self._cut(self.block_samples)

    def _cut(self, length: int) -> np.ndarray:
        return cut_blocks(self.unit_index, self.campaigns, length, timeline=self.forward,
                          scored=self.measured)

    @property
    def shared_ranked(self) -> bool:
        """True when the shared design -- every target on the slowest target's blocks, the
        penalty's (:meth:`set_test_blocks`), what one design for the whole diagnosis cut until
        diag82 -- has blocks finer than the units.  The checks a design with one block per unit
        asks (:meth:`~.search.Search.saturates`, the "over the air" form) follow it, not the
        target's own blocks (diag82e)."""
        ok = self.validated
        return bool(ok.any() and int(self.penalty_index[ok].max()) + 1 > self.n_units)

    @property
    def n_blocks_tested(self) -> int:
        """Units of the acceptance test (time blocks within the CV units)."""
        return int(self.block_index.max()) + 1 if self.validated.any() else 0

    @property
    def in_range(self) -> np.ndarray:
        """Scored rows where the fold that scores them does not extrapolate in the declared
        inputs (:func:`~thermocomp.core.model_selection.extrapolation.within_range`)."""
        if "_in_range" not in self.__dict__:
            X = self.X.to_numpy(float)
            out = np.zeros(len(self.y), bool)
            for k in self.fold_ids:
                out |= within_range(X, self.train_rows(k) & self.measured, self.test_rows(k))
            self._in_range = out & self.validated
        return self._in_range

    def varies(self, column: str) -> bool:
        """True when context ``column`` changes within the train data (in the target's frame)."""
        cache = self.__dict__.setdefault("_varies", {})
        if column not in cache:
            framed = in_frame(self.context[column].to_numpy(float), self.campaigns, self.reference)
            cache[column] = bool(np.nanstd(framed) > 1e-12)
        return cache[column]

    @property
    def forward(self) -> bool:
        return self.scheme == "forward"

    @property
    def n_units(self) -> int:
        """Units that are scored (validated)."""
        return len(self.unit_names)

    @property
    def units_trained(self) -> int | None:
        """Fewest CV units a fold trains on (``campaigns`` scheme; None for ``forward``, whose
        units are blocks of one time line, not campaigns each with an offset of its own)."""
        if self.forward:
            return None
        units = np.asarray(self.units, dtype=object)
        return min(len(set(units[self.train_rows(k) & self.measured].tolist())) for k in self.fold_ids)

    @property
    def fold_ids(self) -> list[int]:
        return sorted(set(self.folds[self.validated].tolist()))

    def train_rows(self, fold: int | None) -> np.ndarray:
        """Rows fold ``fold`` trains on (all rows for None)."""
        if fold is None:
            return np.ones(len(self.y), bool)
        if self.forward:
            return np.arange(len(self.y)) < self._train_end[fold]
        return self.folds != fold

    def test_rows(self, fold: int) -> np.ndarray:
        """Rows fold ``fold`` scores."""
        return self.folds == fold

    def predict_rows(self, fold: int) -> np.ndarray:
        """Rows fold ``fold``'s model runs through: its test rows, or (forward) the record up to
        the end of its block, so that its states carry over as on the machine."""
        if not self.forward:
            return self.test_rows(fold)
        return np.arange(len(self.y)) <= np.flatnonzero(self.folds == fold)[-1]

    @property
    def splits(self) -> list[tuple[np.ndarray, np.ndarray]]:
        """``(train rows, test rows)`` of every fold."""
        return [(self.train_rows(k), self.test_rows(k)) for k in self.fold_ids]


@dataclass
class CVResult:
    """Cross-validated prediction of the train rows and its error per unit.

    Rows that no fold scores (forward: before the first validation block)
    hold NaN in ``prediction`` and ``residual``.
    """

    prediction: np.ndarray
    residual: np.ndarray
    rmse: float
    unit_mse: np.ndarray      # mean squared residual of each held-out unit
    alpha: float | None = None   # penalty on the effect features (MLR base; None: none)
    block_mse: np.ndarray | None = None   # ... of each test block (the acceptance test's units)
    in_range_rmse: float = float("nan")   # RMSE on the rows no fold extrapolates to


class CrossValidator:
    """Held-out predictions of a Compensator-like model with extra effects.

    Parameters
    ----------
    problem : Problem
    estimator : regressor
        The configured estimator (cloned per fold, for the problem's target);
        it gets the fold's context, whose ``campaign`` is the CV unit in the
        ``campaigns`` scheme (a time block of a single campaign is a campaign
        of its own: no lag reaches across a held-out block), and in one-step
        mode the measured target.
    selector : selector or None
        Refitted per fold on the declared inputs left after exclusions.
    shrink : bool, default True
        With an :class:`~thermocomp.core.models.MLR` base, penalise the effect
        features (ridge, :mod:`.shrink`) with the penalty among
        :data:`~thermocomp.apps.diagnose.shrink.ALPHAS` of least CV error.
    """

    def __init__(self, problem: Problem, estimator, selector=None, shrink: bool = True):
        self.problem, self.estimator = problem, estimator
        self.selector = selector if selector is not None else AllInputs()
        self.shrink = shrink
        self._selection: dict = {}
        self._features = BoundedCache(max_bytes=FEATURE_CACHE_BYTES)
        self._ctx: dict = {}
        # what fits on other features of the same rows share: each fold's inputs factored once
        # (names, fold) -> InputsFit, the pieces' head factors (:meth:`_head`); None: nothing
        # shared (the search's own CV, as before; the refit null's permutations share: .refit_null)
        self._fixed: dict | None = None

    @property
    def closed_form(self) -> bool:
        """True when the base is a plain MLR (fitted here in closed form, with the penalty path)."""
        return type(for_target(self.estimator, self.problem.target)) is MLR

    # -- building blocks --------------------------------------------------------------------
    def selection(self, inputs: tuple, fold: int | None) -> list[str]:
        """Selected inputs among ``inputs`` on the rows of ``fold``'s training (all rows for None)."""
        key = (tuple(inputs), fold)
        if key not in self._selection:
            p = self.problem
            if isinstance(self.selector, AllInputs):
                names = list(inputs)
            else:
                rows = p.train_rows(fold) & p.measured     # what the selector's y scores
                Xf = p.X.loc[rows, list(inputs)].reset_index(drop=True)
                names = list(clone(self.selector).fit(Xf, p.y[rows]).selected_)
            self._selection[key] = names
        return self._selection[key]

    def inputs_matrix(self, names) -> np.ndarray:
        key = ("X", tuple(names))
        if key not in self._features:
            self._features[key] = self.problem.X[list(names)].to_numpy(float)
        return self._features[key]

    def features(self, effect: Effect, names: list[str], fold: int | None = None,
                 rows: np.ndarray | None = None) -> np.ndarray:
        """Features of ``effect`` on all train rows (cached; input effects per input set).

        An effect that ``learns`` (initial directions) learns from the training
        rows of ``fold`` (all rows for None), as the fitted model would; ``rows`` (a mask): from
        those rows instead (:meth:`forward_within`'s fits; not cached).
        """
        if rows is not None and effect.learns:
            return (self._scaled_features(effect, names, rows) if effect.transform == "ambient_scaled"
                    else self._start_features(effect, names, rows))
        fold = fold if effect.learns else None
        key = (effect, tuple(names) if effect.uses_inputs else None, fold)
        if key not in self._features:
            p = self.problem
            if effect.transform == "ambient_scaled":   # its direction learned on the fold's rows
                self._features[key] = self._scaled_features(effect, names,
                                                            weights=self.fold_level_weights(names, fold))
            elif effect.initial_state:     # the lag (cached once) + the initial-state transient
                self._features[key] = self._start_features(
                    effect, names, p.train_rows(fold) if effect.learns else None)
            else:
                X = self.inputs_matrix(names) if effect.uses_inputs else np.empty((len(p.y), 0))
                self._features[key] = effect_features(effect, X, p.context, p.campaigns, p.reference)
        return self._features[key]

    def _scaled_features(self, effect: Effect, names: list[str], rows: np.ndarray | None = None,
                         weights: np.ndarray | None = None) -> np.ndarray:
        """The level law on the inputs' least-squares fit, its weights learned on ``rows``
        (or given)."""
        p, X = self.problem, self.inputs_matrix(names)
        if weights is None:
            weights = level_weights(X[rows], np.asarray(p.y, float)[rows])
        return effect_features(effect, X, p.context, p.campaigns, p.reference, weights)

    def fold_level_weights(self, names: list[str], fold: int | None) -> np.ndarray:
        """``ambient_scaled``'s weights learned on ``fold``'s training rows (cached: they read the
        inputs and the target only, not the context)."""
        key = ("level", tuple(names), fold)
        if key not in self._features:
            rows = self.problem.train_rows(fold)
            self._features[key] = level_weights(self.inputs_matrix(names)[rows],
                                                np.asarray(self.problem.y, float)[rows])
        return self._features[key]

    def _start_features(self, effect: Effect, names: list[str], rows: np.ndarray | None) -> np.ndarray:
        """A lag from the initial state: its lag (cached once) and the transient, its initial
        directions learned from ``rows`` (None: one column per sensor)."""
        p = self.problem
        lag = self.features(replace(effect, initial_state=None, initial_directions=None), names)
        offsets = self._offsets(effect.initial_state)
        weights = (None if rows is None
                   else principal_directions(offsets[rows], p.campaigns[rows], effect.initial_directions))
        start = transient(offsets, weights, p.context["time"].to_numpy(float), p.campaigns, effect.tau_s)
        return np.hstack([lag, start])

    def _offsets(self, columns: tuple) -> np.ndarray:
        key = ("offsets", columns)
        if key not in self._features:
            p = self.problem
            self._features[key] = initial_offsets(p.context, columns, p.campaigns)
        return self._features[key]

    def design(self, names: list[str], effects, fold: int | None = None,
               rows: np.ndarray | None = None) -> np.ndarray:
        return np.hstack([self.inputs_matrix(names)] + [self.features(e, names, fold, rows) for e in effects])

    def forward_within(self, inputs, effects, alpha: float | None) -> np.ndarray:
        """The closed-form MLR's within-campaign squared error on the later half of the train
        campaigns, forward: each such campaign (in their stacked order, the calendar's) scored by
        the fit on the campaigns before it (learned initial directions too) at penalty ``alpha``
        on the effect features, its residual less its own mean; one sum per scored campaign
        (empty with fewer than 4 campaigns).  :meth:`~.search.Search._forward_within_gain`."""
        p = self.problem
        labels = np.asarray(p.campaigns, dtype=object)
        order = list(dict.fromkeys(labels[p.validated].tolist()))
        names = self.selection(tuple(inputs), None)
        fit_intercept = for_target(self.estimator, p.target).fit_intercept
        out = []
        for j in range(len(order) // 2, len(order) if len(order) >= 4 else 0):
            train, test = np.isin(labels, order[:j]), (labels == order[j]) & p.validated
            Z = self.design(names, effects, rows=train)
            fit = train & p.measured
            path = PartialRidgePath(Z[fit], p.y[fit], len(names), fit_intercept)
            r = p.y[test] - path.predict(Z[test], [alpha or 0.0])[:, 0]
            out.append(float(np.sum((r - r.mean()) ** 2)))
        return np.array(out)

    def _context(self, fold: int, train: bool) -> pd.DataFrame:
        key = (fold, train)
        if key not in self._ctx:
            p = self.problem
            rows = p.train_rows(fold) if train else p.predict_rows(fold)
            ctx = p.context.loc[rows].reset_index(drop=True)
            ctx[CAMPAIGN] = (p.campaigns if p.forward else p.units)[rows]
            if p.mode == "one_step" and not train:
                ctx[Y_MEASURED] = p.y[rows]
            self._ctx[key] = ctx
        return self._ctx[key]

    # -- cross-validation -------------------------------------------------------------------
    def run(self, inputs, effects=(), one_se: bool = False) -> CVResult:
        """CV prediction with declared ``inputs`` (after exclusions) and extra ``effects``.

        ``one_se``: with the closed-form MLR, the penalty on the effect features is the
        largest within one standard error of the least CV error (the deployed model's, when
        every effect has several features: :mod:`.shrink`), not the least-error one.
        """
        p = self.problem
        effects = [e for e in effects if e.transform != "remove"]
        if self.closed_form:
            return self._run_closed_form(inputs, effects, one_se)
        pred = np.full(len(p.y), np.nan)
        for k in p.fold_ids:
            tr, te, run = p.train_rows(k), p.test_rows(k), p.predict_rows(k)
            Z = self.design(self.selection(tuple(inputs), k), effects, k)
            est = clone(for_target(self.estimator, p.target))
            est.fit(Z[tr], p.y[tr], context=self._context(k, True))
            out = np.asarray(est.predict(Z[run], context=self._context(k, False)), dtype=float)
            pred[te] = out[te[run]]
        return self._result(pred)

    def _run_closed_form(self, inputs, effects, one_se: bool = False) -> CVResult:
        """MLR on the design, the effect features penalised by each of the alphas; the one of
        least CV error (``one_se``: the largest within one standard error of it)."""
        p = self.problem
        base = for_target(self.estimator, p.target)
        shrink = self.shrink and bool(effects)
        alphas = ALPHAS if shrink else np.zeros(1)
        pred = np.full((len(p.y), alphas.size), np.nan)
        pieces = self._pieces(inputs, effects) if base.fit_intercept else None
        for k in p.fold_ids:
            tr, te = p.train_rows(k) & p.measured, p.test_rows(k)
            names = self.selection(tuple(inputs), k)
            path = None
            if pieces is not None:           # every fold's design is the pieces' (not rebuilt)
                ls, members = pieces
                Z = ls.Z
                path = PartialRidgePath.from_triangle(*ls.union(members[k]), len(names))
            else:
                Z = self.design(names, effects, k)
            if path is None:
                path = PartialRidgePath(Z[tr], p.y[tr], len(names), base.fit_intercept,
                                        self._inputs_fit(names, k, Z, tr) if base.fit_intercept else None)
            pred[te] = path.predict(Z[te], alphas)
        err = (p.y[:, None] - pred) ** 2
        mse = np.nanmean(err, axis=0)
        best = least_error(mse)              # ties: the smallest penalty (least squares first)
        if one_se and shrink:
            best = one_standard_error(mse, self._block_mse(err))
        # a copy: as a view the column kept every penalty's predictions (18 x the rows) alive
        # in each result the search keeps (a year's diagnose: 5.3 GiB peak RSS, now 3.7)
        return self._result(pred[:, best].copy(), float(alphas[best]) if shrink else None)

    def _inputs_fit(self, names, fold: int, Z: np.ndarray, rows: np.ndarray) -> InputsFit | None:
        """The fold's inputs (``Z``'s first columns on ``rows``) factored once, where shared."""
        if self._fixed is None:
            return None
        key = ("inputs", tuple(names), fold)
        if key not in self._fixed:
            self._fixed[key] = InputsFit.of(Z[rows][:, :len(names)])
        return self._fixed[key]

    def _pieces(self, inputs, effects) -> tuple[CampaignLeastSquares, dict] | None:
        """The rows cut where any fold's training starts or stops, each piece's QR factor of
        ``[1, Z, y]``, and each fold's pieces -- when every fold's design is the same (all inputs
        kept, no effect that learns from its fold): a fold's least squares is then the QR of its
        pieces' factors, not of its rows (forward chaining's 16 nested folds refitted the record's
        first half 16 times: 35 % of ``diagnose`` on a week at 10 s).  ``None`` otherwise."""
        p = self.problem
        folds = p.fold_ids
        if not isinstance(self.selector, AllInputs) or any(e.learns for e in effects) \
                or not folds or len(folds) > 62:
            return None
        # each row's set of training folds, as bits: rows of one set are one piece
        code = np.zeros(len(p.y), np.int64)
        for bit, k in enumerate(folds):
            code |= p.train_rows(k).astype(np.int64) << bit
        sets, which = np.unique(code, return_inverse=True)
        order = np.argsort(which, kind="stable")
        rows = np.split(order, np.cumsum(np.bincount(which, minlength=sets.size))[:-1])
        rows = [r[p.measured[r]] for r in rows]     # the least squares of the measured rows
        names = self.selection(tuple(inputs), None)
        Z = self.design(names, effects, None)
        members = {k: [i for i, c in enumerate(sets.tolist()) if c >> bit & 1]
                   for bit, k in enumerate(folds)}
        head = self._head(names, effects)
        return CampaignLeastSquares(Z, p.y, rows, fit_intercept=True, head=head), members

    def _head(self, names, effects) -> FixedHead | None:
        """The pieces' factors of the design's columns that the fits sharing :attr:`_fixed` keep
        (:class:`~.refit_null.MovedDrivers`: the inputs and the kept effects); None: none shared."""
        return None

    def _block_mse(self, err: np.ndarray) -> np.ndarray:
        """Each penalty block's mean of ``err`` (rows x columns): blocks x columns (the one-SE
        rule's; :meth:`Problem.set_test_blocks`)."""
        p, ok = self.problem, self.problem.validated
        index = p.penalty_index[ok]
        n = int(index.max()) + 1 if index.size else 0
        counts = np.maximum(np.bincount(index, minlength=n), 1)
        return np.stack([np.bincount(index, weights=e, minlength=n) / counts
                         for e in err[ok].T], axis=1)

    def _result(self, pred: np.ndarray, alpha: float | None = None) -> CVResult:
        p = self.problem
        r = p.y - pred
        ok = p.validated
        sums = np.bincount(p.unit_index[ok], weights=r[ok] ** 2, minlength=p.n_units)
        counts = np.bincount(p.unit_index[ok], minlength=p.n_units)
        n_blocks = p.n_blocks_tested
        block_sums = np.bincount(p.block_index[ok], weights=r[ok] ** 2, minlength=n_blocks)
        block_mse = block_sums / np.maximum(np.bincount(p.block_index[ok], minlength=n_blocks), 1)
        inside = p.in_range
        in_range = float(np.sqrt(np.mean(r[inside] ** 2))) if inside.any() else float("nan")
        return CVResult(pred, r, float(np.sqrt(np.mean(r[ok] ** 2))), sums / np.maximum(counts, 1),
                        alpha, block_mse, in_range)


@lru_cache(maxsize=8)
def _sign_patterns(n: int) -> np.ndarray:
    return 1.0 - 2.0 * ((np.arange(2**n)[:, None] >> np.arange(n)) & 1)


EXACT_UNITS = 16      # sign patterns enumerated up to this many units (2^16), Monte Carlo beyond
RESAMPLES = 20000     # Monte Carlo sign patterns
CHUNK_CELLS = 1 << 22     # sign patterns taken as float this many cells at a time (32 MB)


@lru_cache(maxsize=2)
def _drawn_signs(n: int, n_resamples: int, seed: int) -> np.ndarray:
    """The Monte Carlo sign patterns (``n_resamples`` x ``n``, int8, read-only), drawn once per
    ``(n, n_resamples, seed)``: the search tests every candidate over the same units, and over
    a long record's 15,840 units one draw as float64 was 2.5 GB, freshly zeroed by the kernel at
    each of the search's calls (perf87: 147 s of system CPU of a 34,560-row diagnose)."""
    signs = np.random.default_rng(seed).choice(np.array([-1, 1], np.int8), size=(n_resamples, n))
    signs.flags.writeable = False
    return signs


def _sign_chunks(n: int, n_resamples: int, seed: int):
    """The sign patterns of ``n`` units (every one exact up to :data:`EXACT_UNITS`, else
    :func:`_drawn_signs`) as float64 row blocks of at most :data:`CHUNK_CELLS` cells, one
    buffer reused (the same values as ``rng.choice([-1.0, 1.0], ...)`` whole)."""
    if n <= EXACT_UNITS:
        yield _sign_patterns(n)
        return
    signs = _drawn_signs(n, n_resamples, seed)
    rows = max(1, CHUNK_CELLS // n)
    buffer = np.empty((min(rows, len(signs)), n))
    for start in range(0, len(signs), rows):
        block = buffer[:len(signs[start:start + rows])]
        np.copyto(block, signs[start:start + rows])
        yield block


def smallest_p(n_units: int, n_resamples: int = RESAMPLES) -> float:
    """The smallest p-value the sign-flip tests here can give with ``n_units`` units (every
    unit's gain positive): :math:`1/2^n` exact up to 16 units, :math:`1/(R+1)` by Monte Carlo
    beyond; family-wise it can only be larger.  No effect is accepted when it exceeds alpha."""
    if n_units < 2:
        return 1.0
    return 2.0 ** -n_units if n_units <= EXACT_UNITS else 1.0 / (n_resamples + 1)


def units_needed(alpha: float) -> int:
    """Fewest units with which the sign-flip test can reach ``alpha`` even when one of them
    goes against the candidate (:math:`2 / 2^n \\le \\alpha`): with fewer, a real effect is
    refused whatever its size (5 campaigns: p >= 1/32)."""
    return int(np.ceil(1.0 + np.log2(1.0 / float(alpha)) - 1e-9))


def sign_flip_pvalue(d, n_resamples: int = RESAMPLES, seed: int = 0) -> float:
    """One-sided p-value of ``mean(d) > 0`` by flipping the signs of the paired differences.

    ``d`` holds one value per CV unit (campaign): under the null the candidate
    does not help, each unit's gain is as likely negative as positive.  Exact
    over all :math:`2^n` patterns up to ``n = 16`` units, Monte Carlo beyond.
    (Written out rather than :func:`scipy.stats.permutation_test`, which gives
    the same p-value but enumerates the 65 536 patterns of 16 units ~20x slower,
    and the search calls it for every shortlisted candidate.)
    """
    return float(sign_flip_pvalues([d], n_resamples, seed)[0])


def sign_flip_pvalues(D, n_resamples: int = RESAMPLES, seed: int = 0) -> np.ndarray:
    """:func:`sign_flip_pvalue` of each row of ``D`` (equal lengths), each over the same sign
    patterns, drawn once: the same p-values as one call per row (the Monte Carlo patterns
    depend on ``seed`` and the length only), at one draw's cost (margin67: the search asks
    it of a candidate's gains and of its margin's ``e_i``, and over the jig grinder's 2,112
    blocks the draw is ~0.6 s of CPU).  A column non-finite in any row is dropped."""
    D = np.atleast_2d(np.asarray(D, dtype=float))
    D = D[:, np.isfinite(D).all(axis=0)]
    n = D.shape[1]
    if n == 0:
        return np.ones(D.shape[0])
    bars = [d.mean() - 1e-12 * max(np.abs(d).sum(), 1e-300) for d in D]
    hits, count = np.zeros(D.shape[0], dtype=np.int64), 0
    for signs in _sign_chunks(n, n_resamples, seed):
        count += len(signs)
        for k, d in enumerate(D):
            hits[k] += np.sum(signs @ d / n >= bars[k])
    return hits / count if n <= EXACT_UNITS else (1 + hits) / (n_resamples + 1)


def sign_flip_maxt(D, n_resamples: int = RESAMPLES, seed: int = 0) -> np.ndarray:
    r"""Family-wise one-sided p-values of ``mean(D[c]) > 0`` for every row ``c`` of ``D``.

    ``D`` holds one gain per unit (campaign, validation block) for every candidate of a round
    (candidates × units).  The step-down max-T of Westfall & Young (1993, Alg. 4.1): the signs
    of whole units are flipped alike for every candidate (their correlation is kept); the
    candidate of the largest t of the mean gain is compared with the largest t over all
    candidates of every flipped pattern, the next one with the largest over the candidates
    from it down, and so on (p-values kept monotone).  Tested one by one at ``alpha``, the
    shortlist of a round (~14 candidates) accepted a false effect far more often than
    ``alpha``: 6 of 30 targets of noise-free null data at 0.01, one making the test error
    2.3x worse (1 of 30 with this, on the gains of :meth:`~.search.Search._family_bar`).
    Step-down, so that a real effect found by several candidates does not hide another one.
    Exact up to 16 units, Monte Carlo beyond.
    """
    D = np.nan_to_num(np.atleast_2d(np.asarray(D, dtype=float)))
    k, n = D.shape
    if n < 2 or k == 0:
        return np.ones(k)

    def t(mean, square):      # t of the mean; a flip keeps every unit's square
        return mean / np.sqrt(np.maximum(square - n * mean ** 2, 1e-300) / ((n - 1) * n))

    order = np.argsort(-t(D.mean(axis=1), (D ** 2).sum(axis=1)))
    D = D[order]                                   # best observed first
    square = (D ** 2).sum(axis=1)
    observed = t(D.mean(axis=1), square)
    bar = observed - 1e-9 * np.maximum(np.abs(observed), 1.0)
    hits, count = np.zeros(k, dtype=np.int64), 0
    for signs in _sign_chunks(n, n_resamples, seed):
        count += len(signs)
        flipped = t(signs @ D.T / n, square)       # patterns × candidates
        tail_max = np.maximum.accumulate(flipped[:, ::-1], axis=1)[:, ::-1]
        hits += (tail_max >= bar).sum(axis=0)
    p = hits / count if n <= EXACT_UNITS else (1 + hits) / (count + 1)
    out = np.empty(k)
    out[order] = np.maximum.accumulate(p)
    return out
