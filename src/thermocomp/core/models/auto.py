"""``model=auto``: every candidate family validated in free run, blended (or the best kept) per target.

The :class:`~thermocomp.core.compensator.Compensator` clones its estimator once per
target, so this one estimator choosing among its candidates is the per-target
composite: each target keeps its own family, and scoring, the saved model,
streaming (replay, serve, promote) and figures see one estimator of the usual
protocol (:mod:`thermocomp.core.context`), the chosen one's.
"""

from __future__ import annotations

import logging
import time
from pathlib import Path

import numpy as np
from sklearn.base import BaseEstimator, RegressorMixin, clone
from sklearn.utils.validation import check_is_fitted

from ...base.errors import ConfigError, ParameterError
from ...base.log import logger, once_per_run
from ...base.params import check_estimator, choice, integer, number
from ..context import (
    AMBIENT_C0,
    SideInputs,
    context_columns,
    for_target,
    groups_of,
    step_gain,
    stream_steps,
    subset,
)
from ..gains import gain_terms
from ..metrics import PERSISTENCE, rmse
from ..model_selection import BlockedForward, LeaveBlockOut, LeaveCampaignsOut
from ..model_selection.extrapolation import within_range
from .blend import FOLD_MARGIN, Blend, fold_ratios, one_se_mean, vote_weights, zero_margin
from .hedge import hedge_weight
from .one_step import persistence

ATI = "ati"              # a candidate name: the ATI wrapper (conf/ati/cmeans.yaml) of a family
BASELINE = "mlr"         # always validated beside the candidates, with persistence
AUTO = "auto"            # the model that chooses: no candidate of its own
NONE = "none"            # no correction: validated beside them, kept where nothing beats it
FORWARD_ONE = "forward-chaining (one record)"
MIN_IN_RANGE_ROWS = 20   # validation_rows='in_range': a fold with fewer in-range rows is scored whole
BLOCKS_ONE = {"blocks": "leave-block-out (one record)", "late_blocks": "leave-late-block-out (one record)"}
CAMPAIGN_FOLDS = ("blocked forward", "leave-campaigns-out")   # folds holding out whole campaigns
# hedge: a weight of W against MLR is chosen on 2 folds by one fold alone (auto105: iso_b, tsc_a2
# lost their wins); 3 campaigns are the fewest whose nested choice is made on 2 or more
MIN_HEDGE_FOLDS = 3

# a candidate that does not apply (ATI over fewer ambient levels) is said once a run, not once
# per target each fit of auto tells it (notes100)
once_per_run(Path(__file__))


class AutoRegressor(SideInputs, RegressorMixin, BaseEstimator):
    """Fit every candidate that applies, blend them by their free-run validation (or keep the best).

    Validation holds training campaigns out the way the test split is held out
    of the data (``scheme``), on the training rows only (the test split never
    reaches ``fit``), always in simulation (no measured error enters), whatever
    ``eval.mode`` scores the run in: ``forward``
    (:class:`~thermocomp.core.model_selection.BlockedForward`) where the test
    campaigns come after the train ones, or for one record: the later
    campaigns (or the later part of the record) validate models fitted on the
    earlier ones; ``interleaved`` where the test campaigns lie among the train
    ones (every third by date): leave-campaigns-out, folds spread over the
    campaigns.  On year-round campaigns with every third held out, blocked
    forward folds ranked the five families against their test order
    (Spearman -0.63), interleaved ones with it (+0.17).  With a ``val`` split
    in the manifest the stage scores each candidate on it instead
    (``val_scores``), as the run's validation does.  A candidate that cannot
    fit these data (an ATI wrapper with campaigns at one ambient level, a
    family refusing them) is skipped with its reason.  MLR is validated as the baseline even
    when it is no candidate, and persistence (the previous measured error) is
    reported beside it.

    ``combine='vote'`` keeps a :class:`~thermocomp.core.models.blend.Blend` of the
    candidates weighted by bootstrap votes over the validation folds (each
    fold's error relative to MLR's there, :func:`~thermocomp.core.models.blend.vote_weights`):
    the share of fold resamples each candidate wins, MLR (a candidate) taking the part of a
    candidate's votes that the resamples do not back by beating MLR; with fewer folds than
    ``n_folds`` each drawn fold is resampled by its blocks too (``vote_weights``'s ``min_folds``:
    one fold alone gave its winner every vote).  ``'best'`` keeps the one
    candidate with the lowest pooled validation RMSE.  Picking one misranked:
    validation and test orders of the families agreed with a Spearman of 0.2
    to 0.4 on the simulated records and the spindle record.  A val split gives
    one score per candidate, no folds: there the best is kept either way.

    ``fallback='one_se'`` (extension, auto80) then keeps MLR alone where the folds are not surely
    in favour of the blend: its summed squared error over MLR's per fold has a mean r and a
    standard error se with r + se >= 1 (k >= 2 folds; the one-SE rule of CV model choice).  On
    the 22 records of ``benchmarks/bench_automore69.py`` it fired on 23 targets of 9 records; auto
    worse than MLR on the new campaigns went 10 -> 8, better 12 -> 13, no record worse than before
    by more than 1.5 % (iso_b), col5791 1.330 -> 1.258 x MLR; ``fl_thermal`` unchanged (90/10
    2.481 µm, MLR 4.060; ``benchmarks/bench_auto80.py``).

    Parameters
    ----------
    candidates : dict name -> estimator
        The families to choose among (``model.candidates``, built by the config).
    scheme : {'auto', 'forward', 'interleaved'}, default 'auto'
        How validation folds hold campaigns out; the stages set it from the dataset's
        split (:func:`thermocomp.core.scoring.evaluation.holdout_scheme`), ``auto`` alone is ``forward``.
    n_folds : int, default 5
    min_train_fraction : float in (0, 1), default 0.5
        Validate on the last ``1 - min_train_fraction`` of the training units.
    gap_blocks : float, default 0.5
        One record: rows left out before each validation block, in blocks.
    one_record : {'forward', 'blocks', 'late_blocks'}, default 'forward'
        The folds of one record: ``forward`` chaining over its last ``1 - min_train_fraction``
        (:class:`~thermocomp.core.model_selection.BlockedForward`); ``blocks``: each of
        ``n_folds`` blocks of the whole record held out, the fit on the rest less ``gap_blocks``
        on both sides, the record predicted from its start
        (:class:`~thermocomp.core.model_selection.LeaveBlockOut`: interpolation, as a separate
        test campaign inside the record's range is); ``late_blocks``: those blocks over its last
        ``1 - min_train_fraction`` only.
    validation_rows : {'all', 'in_range'}, default 'all'
        The out-of-fold rows ``combine='vote'`` scores: all, or only those where the fold does not
        extrapolate (:func:`~thermocomp.core.model_selection.extrapolation.within_range` of its fit
        rows, ``oof_in_range_``: None under ``'all'`` unless ``keep_oof``; :func:`in_range_rows`).
        On 12 tuning and 10 fresh simulated records it moved one record per group within 10 % of
        the best family and changed no record's side against MLR; ``fl_thermal`` 90/10 went
        2.483 -> 2.551 µm (``benchmarks/bench_auto_rules.py``): not the default.
    max_seconds : float or None
        A candidate whose folds take longer than this is not validated further
        (skipped, its time recorded): a time budget for the slow families.
    combine : {'vote', 'best'}, default 'vote'
    keep_oof : bool, default False
        Pickle the candidates' out-of-fold predictions with the model (``oof_``, ``oof_y_``,
        ``oof_fold_``, ``oof_folds_``, ``oof_in_range_``, ``oof_campaign_``: the campaign code of
        each row where the folds hold out campaigns, else None; 1.4 MB on ``fl_thermal``).  The fitted
        model holds them either way: the run's validation scores the choice from them (:meth:`out_of_fold`).
    fallback : {'one_se', 'none'}, default 'one_se'
        ``combine='vote'`` (extension): keep MLR alone where the blend's per-fold squared error
        over MLR's (:func:`~thermocomp.core.models.blend.fold_ratios`, k >= 2 folds among the
        voting rows, MLR a candidate) has mean + standard error >= 1, the reason saying so;
        ``'none'``: the blend the votes give (a model pickled before the key refits so).  The
        zero rule (``uncompensated``) then judges what is kept.
    min_gain_pct : float, default 1.0
        ``combine='best'``: MLR, when a candidate, is kept unless the best candidate's validation
        RMSE is lower
        by more than this share: a tie goes to the simplest family (on ``swiss_lathe_door``
        E_X the LSTM, whose early stopping kept the linear law, validated 2.16 as MLR and
        tested 3.43 against 3.38).
    val_scores : dict target -> {candidate: RMSE or the reason it could not fit}, optional
        Each candidate's free-run RMSE on the manifest's ``val`` split (fitted on the train
        split; :func:`thermocomp.core.scoring.auto_validation.val_split_scores`), used instead
        of folds, as the run's validation uses the val split when there is one.
    given_scores : dict candidate -> RMSE or the reason it could not fit, optional
        One target's ``val_scores`` (:meth:`for_target` sets it).
    chosen : dict target -> candidate name or {candidate: weight}, optional
        The choice already made (:meth:`for_target` then gives that candidate or blend): the
        run's validation refits the chosen families, not the whole choice (nested,
        candidates x folds² fits), so it is the chosen family's, optimistic by the
        selection (on auto's own folds it scores :meth:`out_of_fold` instead: the same).

    Attributes
    ----------
    estimator_ : the chosen candidate, fitted on all training rows
    family_ : str
        The chosen candidate (of a blend, the heaviest member).
    chosen_ : str or dict name -> weight
        The chosen candidate, or the blend's weights.
    validation_ : dict name -> validation RMSE of every validated candidate (and baseline)
    skipped_ : dict name -> why it was not validated
    reason_ : str
    scheme_ : str
        The folds used: ``blocked forward``, ``leave-campaigns-out``, ``forward-chaining (one record)``
        or (``one_record``) ``leave-block-out (one record)`` / ``leave-late-block-out (one record)``.
    fit_seconds_ : dict name -> seconds of its validation folds
    """

    param_rules = {"scheme": choice("auto", "forward", "interleaved"), "n_folds": integer(1, at_most=100),
                   "min_train_fraction": number(0.0, 1.0, open_lo=True, open_hi=True),
                   "gap_blocks": number(0.0, 10.0), "one_record": choice("forward", "blocks", "late_blocks"),
                   "min_gain_pct": number(0.0, 100.0),
                   "combine": choice("vote", "best"), "keep_oof": choice(True, False),
                   "uncompensated": choice("zero", "keep"), "fallback": choice("one_se", "none"),
                   "hedge": choice("none", "campaigns"), "validation_rows": choice("all", "in_range")}

    uncompensated = "keep"   # a model pickled before the key: refitted as it was fitted
    fallback = "none"        # likewise
    hedge = "none"           # likewise

    def __init__(self, candidates=None, scheme: str = "auto", n_folds: int = 5,
                 min_train_fraction: float = 0.5, gap_blocks: float = 0.5,
                 max_seconds: float | None = None, min_gain_pct: float = 1.0, chosen=None,
                 val_scores=None, given_scores=None, combine: str = "vote", keep_oof: bool = False,
                 one_record: str = "forward", validation_rows: str = "all",
                 uncompensated: str = "zero", fallback: str = "one_se", hedge: str = "campaigns"):
        self.hedge = hedge
        self.fallback = fallback
        self.uncompensated = uncompensated
        self.validation_rows = validation_rows
        self.one_record = one_record
        self.combine = combine
        self.keep_oof = keep_oof
        self.candidates = candidates
        self.val_scores = val_scores
        self.given_scores = given_scores
        self.min_gain_pct = min_gain_pct
        self.chosen = chosen
        self.scheme = scheme
        self.n_folds = n_folds
        self.min_train_fraction = min_train_fraction
        self.gap_blocks = gap_blocks
        self.max_seconds = max_seconds

    def fit(self, X, y, context=None):
        check_estimator(self)
        if not self.candidates:
            raise ParameterError("model.candidates is empty: name at least one model family")
        X, y = np.asarray(X, dtype=float), np.asarray(y, dtype=float)
        groups = groups_of(context)
        self.validated_as_ = {}
        if self.given_scores is not None:      # the val split's, computed by the stage
            self.scheme_ = "val split"
            return self._keep_best(X, y, context, dict(self.given_scores), "the val split")
        self.scheme_ = _scheme(self.scheme, groups)
        if self.scheme_ == FORWARD_ONE:
            self.scheme_ = BLOCKS_ONE.get(self.one_record, FORWARD_ONE)
        # a target measured now and then (NaN between measurements): every fold scores its
        # measured rows (the candidates fit on theirs, their dynamics run over every row)
        folds = [(fit, pred, score & np.isfinite(y)) for fit, pred, score in self._folds(groups, len(y))]
        self.validation_, self.skipped_, self.fit_seconds_, self.oof_ = {}, {}, {}, {}
        runs = dict(self.candidates)
        if BASELINE not in runs:
            from .linear import MLR

            runs[BASELINE] = MLR()
        for name, est in runs.items():
            why = _not_applicable(name, context, groups)
            if why is not None:    # (notes100: said in metrics.json's `skipped` alone before)
                logger.info("auto: %s skipped: %s", name, why)
            why = why or _same_as(name, est, runs, context, len(y))
            if why is None:
                why = self._validate(name, est, X, y, context, folds)
                _said(name, self.fit_seconds_.get(name, 0.0), self.validation_.get(name), why)
            if why is not None:
                self.skipped_[name] = why
        self.validated_as_ = _validated_as(self.oof_, context, groups, folds)
        held = np.any([score for *_, score in folds], axis=0)
        last = persistence(y, groups)
        self.validation_[PERSISTENCE] = rmse(y[held] - last[held])
        how = f"{len(folds)} {self.scheme_} fold(s)"
        self.oof_y_ = np.concatenate([y[score] for *_, score in folds])
        self.validation_[NONE] = rmse(self.oof_y_)     # no correction, on the candidates' rows
        self.oof_fold_ = np.concatenate([np.full(score.sum(), k) for k, (*_, score) in enumerate(folds)])
        self.oof_folds_ = (len(y), [(np.flatnonzero(fit), np.flatnonzero(score)) for fit, _, score in folds])
        self.oof_campaign_ = None   # folds of whole campaigns: the campaign of each row (benches')
        if self.scheme_ in CAMPAIGN_FOLDS:
            codes = np.unique(np.asarray(groups, dtype=object).astype(str), return_inverse=True)[1]
            self.oof_campaign_ = np.concatenate([codes[score] for *_, score in folds])
        self.oof_in_range_ = None   # an SVD per fold: where it chooses the rows, or is kept
        if self.validation_rows == "in_range" or self.keep_oof:
            self.oof_in_range_ = np.concatenate([within_range(X, fit, score)[score]
                                                 for fit, _, score in folds])
        members = [n for n in self.candidates if n in self.oof_]
        if self.combine == "vote" and len(members) > 1 and BASELINE in self.oof_:
            return self._blend(X, y, context, members, how)
        return self._keep_best(X, y, context, None, how)

    def _blend(self, X, y, context, members: list, how: str):
        """Keep the blend of ``members`` the folds vote for.  MLR, a candidate, gets the votes
        of the resamples it wins and the doubted part of the others' (``vote_weights``'s
        ``base_column``), which is its tie-break here (min_gain_pct is ``best``'s: a gate on the
        pooled RMSE, which one fold dominates, cost column_moving_source 5.87 -> 6.49 µm mean
        test RMSE and bought large_mill_week 1.867 -> 1.856)."""
        preds = np.column_stack([self.oof_[n] for n in members])
        base = members.index(BASELINE) if BASELINE in members else None
        rows = self._voting_rows()
        w = vote_weights(preds[rows], self.oof_y_[rows], self.oof_fold_[rows], self.oof_[BASELINE][rows],
                         base_column=base, min_folds=int(self.n_folds))
        weights = {n: float(v) for n, v in zip(members, w) if v > 0}
        blended = rmse(self.oof_y_ - preds @ w)
        mix = ", ".join(f"{n} {v:.2f}" for n, v in sorted(weights.items(), key=lambda kv: -kv[1]))
        doubt = "" if base is None else ", each kept as far as its resamples beat MLR, the rest MLR's"
        where = ("" if self.validation_rows == "all" else f", on the {rows.sum()} of {rows.size} rows "
                 f"where the fold does not extrapolate, {np.unique(self.oof_fold_[rows]).size} fold(s)")
        lead = (f"blend by the folds' votes (share of bootstrap resamples of the folds each "
                f"candidate wins, mean squared errors relative to MLR's per fold{doubt}{where}): {mix}; "
                f"blended validation RMSE {blended:.4g}")
        self.weights_, self.combine_ = weights, "vote"
        self.family_ = max(weights, key=weights.get)
        self.chosen_ = self.family_ if len(weights) == 1 else weights
        self.reason_ = (f"{lead} ({how}); MLR {self.validation_[BASELINE]:.4g}, "
                        f"persistence {self.validation_[PERSISTENCE]:.4g}")
        predicted = preds @ w
        if self._one_se(predicted, rows, base):
            blended, predicted = self.validation_[BASELINE], self.oof_[BASELINE]
        elif self._hedged(preds, members, rows, base):
            predicted = preds @ np.array([self.weights_.get(n, 0.0) for n in members])
            blended = rmse(self.oof_y_ - predicted)
        self._none_unless_better(blended, predicted)
        return self._refit(X, y, context)

    def _one_se(self, predicted: np.ndarray, rows: np.ndarray, base: int | None) -> bool:
        """``fallback='one_se'``: keep MLR alone where the folds are not surely in favour of the
        blend (``predicted``, its out-of-fold prediction): with MLR among the candidates, a blend
        that is not MLR alone and k >= 2 folds among the voting ``rows``, the blend's summed squared
        error over MLR's per fold (:func:`~thermocomp.core.models.blend.fold_ratios`) has a mean
        r and a standard error se = std(ddof=1) / sqrt(k); r + se >= 1 keeps MLR (the one-SE rule
        of CV model choice: the simpler model unless the other is better by more than one SE).
        True where it kept MLR."""
        if self.fallback != "one_se" or base is None or self.weights_ == {BASELINE: 1.0}:
            return False
        r = fold_ratios((self.oof_y_[rows] - predicted[rows]) ** 2,
                        (self.oof_y_[rows] - self.oof_[BASELINE][rows]) ** 2, self.oof_fold_[rows])
        read = one_se_mean(r)
        if read is None:
            return False
        mean, se = read
        if not mean + se >= 1.0:
            return False
        self.reason_ += (f"; one-SE rule: the blend's mean fold MSE over MLR's {mean:.4g} ± "
                         f"{se:.4g} ({r.size} folds) is not surely below 1: MLR kept")
        self.weights_, self.family_, self.chosen_ = {BASELINE: 1.0}, BASELINE, BASELINE
        return True

    def _hedged(self, preds, members: list, rows, base: int | None) -> bool:
        """``hedge='campaigns'`` (auto105b): the kept blend W mixed with MLR, ``lam * W + (1 - lam)
        * MLR``, ``lam`` from :func:`~thermocomp.core.models.hedge.hedge_weight` (out-of-fold
        predictions of this choice made without each fold), only where the folds are at least
        ``MIN_HEDGE_FOLDS`` whole campaigns: one record's time blocks share its conditions and its
        drift, and a weight chosen on them cost the one-campaign records up to 12 % (auto105).
        True where it changed the weights."""
        if (self.hedge != "campaigns" or base is None or self.weights_ == {BASELINE: 1.0}
                or self.scheme_ not in CAMPAIGN_FOLDS
                or np.unique(self.oof_fold_[rows]).size < MIN_HEDGE_FOLDS):
            return False
        lam = hedge_weight(preds[rows], self.oof_y_[rows], self.oof_fold_[rows], base, int(self.n_folds))
        if lam >= 1.0:
            return False
        w = {n: lam * v for n, v in self.weights_.items()}
        w[BASELINE] = w.get(BASELINE, 0.0) + 1.0 - lam
        self.weights_ = {n: v for n, v in w.items() if v > 0}
        self.family_ = max(self.weights_, key=self.weights_.get)
        self.chosen_ = self.family_ if len(self.weights_) == 1 else self.weights_
        self.reason_ += (f"; hedged towards MLR by the nested weight {lam:.3g} "
                         f"({np.unique(self.oof_fold_[rows]).size} campaign folds)")
        return True

    def _none_unless_better(self, kept: float, predicted: np.ndarray | None = None) -> None:
        """``uncompensated='zero'``: where the kept model's pooled validation RMSE ``kept`` is not
        below no correction's on the same rows (``validation_['none']``), keep a zero correction:
        the kept model weighted 0, which streams, replays and exports as any blend does.

        With the kept model's out-of-fold ``predicted``, the zero is undone where the votes'
        measure (:func:`~thermocomp.core.models.blend.mean_fold_ratio`: each fold's squared error
        over MLR's there, averaged, so every fold counts alike) puts the kept model below
        1/``FOLD_MARGIN`` of no correction's: the pooled RMSE is ruled by a fold where every model
        extrapolates (iso67, the X-axis test predicted from spindle tests: MLR 22.5 µm on a 1.3 µm
        label, 0.41 against 2.05 on the other fold; the zero tested 1.40 against the blend's
        0.27 µm).  With one fold it never fires (both measures are that fold's pooled one)."""
        none = self.validation_.get(NONE)
        if self.uncompensated != "zero" or none is None or not kept >= none:
            return
        if predicted is not None and BASELINE in self.oof_:
            q_kept, q_none = zero_margin(self.oof_y_, predicted, self.oof_[BASELINE], self.oof_fold_)
            if FOLD_MARGIN * q_kept < q_none:
                self.reason_ += (f"; kept though its pooled validation RMSE {kept:.4g} is not below "
                                 f"no correction's {none:.4g}: fold by fold it is (mean fold MSE "
                                 f"over MLR's {q_kept:.4g} against {q_none:.4g})")
                return
        member = self.family_
        self.reason_ = (f"no correction: the kept model's validation RMSE {kept:.4g} is not below "
                        f"the uncompensated error's {none:.4g} on the same rows, so a zero "
                        f"correction is kept (model.estimator.uncompensated=keep keeps it); was: "
                        f"{self.reason_}")
        self.family_, self.chosen_, self.weights_ = NONE, {member: 0.0}, {member: 0.0}

    def _voting_rows(self) -> np.ndarray:
        """The out-of-fold rows the votes score: all, or (``validation_rows='in_range'``) those
        where the fold does not extrapolate (:func:`in_range_rows`)."""
        if self.validation_rows == "in_range":
            return in_range_rows(self.oof_in_range_, self.oof_fold_)
        return np.ones(len(self.oof_y_), bool)

    def _refit(self, X, y, context):
        self.estimator_ = self._estimator(self.chosen_).fit(X, y, context=context)
        self.context_columns_ = context_columns(self.estimator_)
        return self

    def _estimator(self, chosen):
        """The unfitted candidate named by ``chosen``, or the blend its weights make."""
        if isinstance(chosen, str):
            return clone(self.candidates[chosen])
        return Blend({n: self.candidates[n] for n in chosen}, dict(chosen))

    def _keep_best(self, X, y, context, given, how: str):
        """Choose among the validated candidates (``given``: scores from elsewhere) and refit."""
        if given is not None:
            self.fit_seconds_ = {}
            self.skipped_ = {n: v or "cannot fit these data" for n, v in given.items()
                             if v is None or isinstance(v, str)}
            self.skipped_.update({n: "not validated" for n in self.candidates if n not in given})
            self.validation_ = {n: float(v) for n, v in given.items() if n not in self.skipped_}
        ranked = sorted((v, n) for n, v in self.validation_.items() if n in self.candidates)
        if not ranked:
            raise ParameterError("model=auto: no candidate could be validated on these data ("
                                 + "; ".join(f"{n}: {w}" for n, w in self.skipped_.items()) + ")")
        best, self.family_ = ranked[0]
        runner = f", next {ranked[1][1]} {ranked[1][0]:.4g}" if len(ranked) > 1 else ""
        lead = f"lowest free-run validation RMSE {best:.4g}"
        base = self.validation_.get(BASELINE)
        if (BASELINE in self.candidates and self.family_ != BASELINE and base is not None
                and best > base * (1 - float(self.min_gain_pct) / 100)):
            lead = (f"{self.family_}'s validation RMSE {best:.4g} is not {self.min_gain_pct:g} % "
                    "below MLR's: the simpler family kept")
            self.family_, runner = BASELINE, ""
        self.reason_ = (f"{lead} ({how}){runner}; "
                        f"MLR {self.validation_.get(BASELINE, float('nan')):.4g}, "
                        f"persistence {self.validation_.get(PERSISTENCE, float('nan')):.4g}")
        self.chosen_, self.weights_, self.combine_ = self.family_, {self.family_: 1.0}, "best"
        if NONE in self.validation_:            # (val split scores made before it: none)
            self._none_unless_better(self.validation_[self.family_],
                                     None if given is not None else self.oof_.get(self.family_))
        return self._refit(X, y, context)

    def chosen_params(self) -> dict:
        """What the chosen family's own CV chose (its ``chosen_params``; none for a family
        without a choice of its own): with ``chosen``, a copy fits that family alone, as chosen
        (:func:`thermocomp.core.compensator.with_chosen_hyperparameters`)."""
        check_is_fitted(self)
        own = getattr(self.estimator_, "chosen_params", None)
        return dict(own()) if callable(own) else {}

    def for_target(self, target: str):
        """The estimator of ``target``: its chosen candidate once ``chosen`` names one, else self
        (:func:`thermocomp.core.context.for_target`), each candidate as it is for ``target``
        (:func:`_candidates_for`: a candidate for some targets only, e.g. ``diagnosed``)."""
        own = _candidates_for(self.candidates, target)
        est = self if own is None else clone(self).set_params(candidates=own)
        if est.chosen and target in est.chosen:
            return est._estimator(est.chosen[target])
        if est.val_scores is not None:
            return clone(est).set_params(val_scores=None, given_scores=est.val_scores.get(target, {}))
        return est

    def out_of_fold(self):
        """``(n_rows, [(fit rows, scored rows)] per fold, measured, predicted)`` of the kept
        model on the validation folds: its members' out-of-fold free-run predictions, weighted.
        A refit of the kept model on these folds predicts the same (each member fitted as in its
        validation), so the run's validation scores it from these, as optimistic by the choice
        (weights chosen on the same folds) as that refit; None without them (a val split)."""
        check_is_fitted(self, "estimator_")
        if not hasattr(self, "oof_folds_") or any(n not in self.oof_ for n in self.weights_):
            return None
        predicted = sum(w * self.oof_[n] for n, w in self.weights_.items())
        return (*self.oof_folds_, self.oof_y_, predicted)

    def __getstate__(self):
        """The pickled model: without the out-of-fold predictions unless ``keep_oof``."""
        state = super().__getstate__()
        if not self.keep_oof:
            state = {k: v for k, v in state.items() if not k.startswith("oof_")}
        return state

    def _folds(self, groups, n: int) -> list:
        """``(fit, predict, score)`` row masks: held out as the test split is (``scheme``)."""
        if self.scheme_ == "leave-campaigns-out":     # two or more campaigns (_scheme)
            return [(~held, held, held) for held in
                    (np.isin(np.arange(n), rows) for _, rows in
                     LeaveCampaignsOut(n_folds=self.n_folds).split(np.zeros(n), groups=groups))]
        if self.scheme_ in BLOCKS_ONE.values():
            start = self.min_train_fraction if self.one_record == "late_blocks" else 0.0
            return LeaveBlockOut(self.n_folds, start, self.gap_blocks).folds(n)
        return BlockedForward(self.n_folds, self.min_train_fraction, self.gap_blocks).folds(groups, n)

    def _validate(self, name, est, X, y, context, folds) -> str | None:
        """Record ``name``'s pooled validation RMSE; the reason when it cannot be validated."""
        residual, predicted, t0 = [], [], time.perf_counter()
        for fit, pred, score in folds:
            try:
                model = clone(est).fit(X[fit], y[fit], context=subset(context, fit))
                yhat = np.asarray(model.predict(X[pred], context=subset(context, pred)), float)
            except (ValueError, ArithmeticError, np.linalg.LinAlgError) as exc:
                return f"cannot fit: {' '.join(str(exc).split())}"
            predicted.append(yhat[score[pred]])
            residual.append(y[score] - predicted[-1])
            spent = time.perf_counter() - t0
            over = self.max_seconds is not None and spent > float(self.max_seconds)
            if over and len(residual) < len(folds):
                self.fit_seconds_[name] = spent
                return f"over the time budget: {spent:.1f} s > max_seconds={self.max_seconds}"
        self.fit_seconds_[name] = time.perf_counter() - t0
        self.validation_[name] = rmse(np.concatenate(residual))
        self.oof_[name] = np.concatenate(predicted)
        return None

    def predict(self, X, context=None):
        check_is_fitted(self, "estimator_")
        return self.estimator_.predict(X, context=context)

    def stream_init(self, context=None):
        check_is_fitted(self, "estimator_")
        return self.estimator_.stream_init(context)

    def stream_step(self, x_row, state, context=None):
        return self.estimator_.stream_step(x_row, state, context)

    def stream_steps(self, X, state, context=None):
        return stream_steps(self.estimator_, X, state, context)

    def step_gain(self, state=None, horizon_s: float = np.inf):
        check_is_fitted(self, "estimator_")
        return step_gain(self.estimator_, state, horizon_s)

    def gain_terms(self, horizon_s: float = np.inf, lead=None, period_s: float = 1.0) -> list:
        """The kept estimator's (:mod:`thermocomp.core.gains`)."""
        check_is_fitted(self, "estimator_")
        return gain_terms(self.estimator_, horizon_s, lead, period_s)

    def report(self) -> dict:
        """``{candidates, chosen, weights, reason, skipped, ...}`` for ``metrics.json``
        (``targets.<t>.auto``)."""
        check_is_fitted(self, "estimator_")
        return {"candidates": {n: float(v) for n, v in self.validation_.items()},
                "chosen": self.family_, "weights": {n: round(w, 4) for n, w in self.weights_.items()},
                "combine": self.combine_, "reason": self.reason_, "scheme": self.scheme_,
                "skipped": dict(self.skipped_),
                "validated_as": dict(getattr(self, "validated_as_", {})),
                "validation_s": {n: round(s, 3) for n, s in self.fit_seconds_.items()}}


# a candidate whose folds took this long is said at INFO (else DEBUG): on a year at 1 min the
# candidates' validation ran 13 minutes without a line (scale58)
SAY_AFTER_S = 10.0


def _said(name: str, seconds: float, score: float | None, why: str | None) -> None:
    """Log one candidate's validation: its time and RMSE, or why it was skipped."""
    what = f"skipped, {why}" if why is not None else f"validation RMSE {score:.4g}"
    logger.log(logging.INFO if seconds >= SAY_AFTER_S else logging.DEBUG,
               "auto: %s validated in %.0f s: %s", name, seconds, what)


def in_range_rows(in_range: np.ndarray, fold: np.ndarray, min_rows: int = MIN_IN_RANGE_ROWS,
                  thin: str = "all") -> np.ndarray:
    """Out-of-fold rows to score: those ``in_range`` (the fold does not extrapolate there) of
    every fold with at least ``min_rows`` of them.  A fold with fewer is scored on all its rows
    (``thin='all'``) or left out (``'drop'``); with fewer than two folds left, every row.
    Dropping them left the votes to the folds nearest the fit, where a lag family won by luck
    (``benchmarks/bench_auto_rules.py``: ``column_moving_source`` seed 303 15.2 µm against
    12.1 scored whole, MLR 14.9)."""
    keep = np.zeros(len(fold), bool)
    for f in np.unique(fold):
        rows = fold == f
        inside = rows & in_range
        if inside.sum() >= min_rows:
            keep |= inside
        elif thin == "all":
            keep |= rows
    if np.unique(fold[keep]).size < 2:
        return np.ones(len(fold), bool)
    return keep


def _not_applicable(name: str, context, groups) -> str | None:
    """Why candidate ``name`` does not apply to these training rows (None: it does)."""
    if not name.startswith(ATI):
        return None
    a0 = np.asarray(context[AMBIENT_C0], float) if context is not None and AMBIENT_C0 in context else None
    if a0 is None or not np.isfinite(a0).any():
        return "no campaign ambient (a T_amb sensor) to choose an interval by"
    from .ati import MIN_AMBIENTS  # here: ati's sklearn.cluster (OpenMP) kept off start-up

    levels = _ambient_levels(a0, groups)
    if levels < MIN_AMBIENTS:
        return (f"the train campaigns span {levels} ambient level(s), fewer than "
                f"{MIN_AMBIENTS}")
    return None


def _ambient_levels(a0: np.ndarray, groups, rows=None) -> int:
    """The distinct initial ambients of the campaigns of ``rows`` (all: None), counted as ATI
    counts them (:func:`~thermocomp.core.models.ati.ambient_levels`)."""
    from .ati import ambient_levels

    rows = np.arange(len(a0)) if rows is None else np.flatnonzero(rows)
    first = rows[np.unique(groups[rows], return_index=True)[1]] if groups is not None else rows[:1]
    return ambient_levels(a0[first])


def _validated_as(oof: dict, context, groups, folds) -> dict:
    """ATI candidate -> why its out-of-fold predictions are its base family's, row for row.

    Where no fold's fit campaigns span the ambient levels ATI's intervals and interaction need,
    every fold's ATI model is one model of its family, and so is what the votes score: a tie
    with that family (a tie's votes go to the first), while the fit on every train campaign,
    which spans them, may take the interaction that no fold scored (hbm75 seed 7601: each fold
    2 levels, the train split 3; ``benchmarks/bench_autoati75.py``).  Said, not changed."""
    out = {}
    for name, predicted in oof.items():
        base = candidate_family(name) if name.startswith(ATI) else None
        if base is None or base not in oof or not np.array_equal(predicted, oof[base], equal_nan=True):
            continue
        a0 = np.asarray(context[AMBIENT_C0], float)
        most = max(_ambient_levels(a0, groups, fit) for fit, *_ in folds)
        out[name] = (f"validated as {base}, row for row: every fold's ATI model was one {base} "
                     f"model (the folds' fit campaigns span at most {most} ambient level(s), the "
                     f"train split {_ambient_levels(a0, groups)}); what the fit on every train campaign "
                     "may add, no fold scored")
    return out


def _candidates_for(candidates, target: str) -> dict | None:
    """``candidates`` as they are for ``target``: each with per-target settings through its
    ``for_target`` (:class:`~.base.ForTargets`: None, nothing for that target, leaves it out);
    None where no candidate has any (the candidates as given)."""
    if not candidates or not any(callable(getattr(c, "for_target", None)) for c in candidates.values()):
        return None
    own = {n: for_target(c, target) for n, c in dict(candidates).items()}
    return {n: c for n, c in own.items() if c is not None}


def _same_as(name: str, est, runs: dict, context, n: int) -> str | None:
    """Why candidate ``name`` is not validated again: on these ``n`` rows it is the very model of
    another candidate of ``runs`` (a Hammerstein model into which no machine state can enter is
    the plain lag bank, ``lagbank``'s: validated twice, it split nothing and cost its folds
    again); None otherwise."""
    reduced = est.plain_lagbank(context, n) if hasattr(est, "plain_lagbank") else None
    if reduced is None:
        return None
    for other, candidate in runs.items():
        if other != name and _same_model(reduced, candidate):
            return (f"the same model as {other} on these data ({est.why_no_state(context)}): "
                    "validated once")
    return None


def _same_model(a, b) -> bool:
    """``a`` and ``b`` are unfitted estimators of one class with equal parameters."""
    return type(a) is type(b) and _plain(a.get_params(deep=False)) == _plain(b.get_params(deep=False))


def _plain(value):
    """``value`` with tuples, arrays and estimators made comparable lists and dicts (a config's
    list and a default's tuple of the same numbers are one parameter)."""
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_plain(v) for v in value]
    if hasattr(value, "get_params"):
        return (type(value).__name__, _plain(value.get_params(deep=False)))
    return value


def _scheme(scheme: str, groups) -> str:
    """What the folds were: over campaigns (as ``scheme`` holds them out) or one record."""
    if groups is None or len(set(groups)) < 2:
        return FORWARD_ONE
    return "leave-campaigns-out" if scheme == "interleaved" else "blocked forward"


def add_choices(comp, targets: dict) -> dict:
    """``targets[t]["auto"]``: each target's choice of a model=auto compensator, as
    ``metrics.json`` holds it (run's and each fleet group's); any other leaves ``targets`` as is."""
    given = getattr(getattr(comp, "estimator", None), "candidates", None) or {}
    for t, est in getattr(comp, "estimators_", {}).items():
        if hasattr(est, "family_"):
            targets[t]["auto"] = est.report()
            # a candidate's own entry for the target (ForTargets.about: the diagnosed effects)
            targets[t]["auto"].update({n: c.about[t] for n, c in dict(given).items()
                                       if t in (getattr(c, "about", None) or {})})
    return targets


def as_chosen(template, fitted):
    """``template`` (an unfitted compensator) fitting, per target, the family ``fitted`` (a
    model=auto compensator) chose: what its validation refits (the choice itself is not
    re-validated: candidates x folds² fits).  Any other ``template`` as it is."""
    chosen = {t: getattr(est, "chosen_", getattr(est, "family_", None))
              for t, est in getattr(fitted, "estimators_", {}).items()}
    if not chosen or None in chosen.values() or "chosen" not in template.estimator.get_params(deep=False):
        return template
    # a candidate ``fitted`` had beyond the config's (``diagnosed``, searched on its train rows)
    given = getattr(template.estimator, "candidates", None) or {}
    had = getattr(getattr(fitted, "estimator", None), "candidates", None) or {}
    if any(n not in given for n in had):
        template.set_params(estimator__candidates={**given, **{n: c for n, c in had.items()
                                                               if n not in given}})
    return template.set_params(estimator__chosen=chosen)


def check_candidates(candidates, params, defaults, sequence=(list, tuple), mapping=(dict,)
                     ) -> list:
    """The names of ``model.candidates``, it and ``model.candidate_params`` /
    ``model.candidate_defaults`` checked for shape (``sequence``, ``mapping``: the types a
    config's lists and mappings have)."""
    if not isinstance(candidates, sequence):
        raise ConfigError(f"model.candidates={candidates}: must be a list of model families, "
                          "e.g. [mlr,lagbank]")
    for key, value in (("candidate_params", params), ("candidate_defaults", defaults)):
        if not isinstance(value, mapping):
            what = "candidate" if key == "candidate_params" else "family"
            raise ConfigError(f"model.{key}={value}: must be a mapping {what} -> "
                              "its keys, e.g. {lstm:{max_epochs:30}}")
    names = list(candidates)
    if not names:
        raise ConfigError("model.candidates is empty: name at least one model family")
    for name in params:
        if name not in names:
            raise ConfigError(f"model.candidate_params.{name}: {name} is not among model.candidates "
                              f"{names}")
    return names


def candidate_family(name) -> str:
    """The model family of a candidate: itself, or for ``ati`` / ``ati+<family>`` (the ATI
    wrapper) MLR / that family."""
    wrapped = str(name).split("+", 1)
    family = BASELINE if wrapped == [ATI] else wrapped[-1]
    if len(wrapped) == 2 and wrapped[0] != ATI or family in (AUTO, ATI) or not str(name).strip():
        raise ConfigError(f"model.candidates: {name!r} is not a model family nor ati[+family]")
    return family
