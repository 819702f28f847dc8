"""The compensation model as one estimator: declared inputs -> selector -> estimator, per target.

Pure core: takes campaign DataFrames (contract columns), returns predictions.
Stages pickle it to ``model.pkl``; deployment wraps it
(:class:`thermocomp.apps.deploy.StreamingCompensator`).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd
from sklearn.base import BaseEstimator, clone

from .choices import MODES
from .context import Y_MEASURED, between_steps, for_target, keeps_memory, with_column
from .denoise import denoise_campaigns, fit_denoiser
from .first_probe import REFITS, completed, frame_loss, late_starts
from .frame import Matrices, resolve_columns, stack
from .models.one_step import OneStepLaw
from .select import AllInputs
from .select.per_target import measured
from .shared_fits import fitted
from .timerule import grid_rows, median_step

OFFSETS = ("predict", "drop")


class Compensator(BaseEstimator):
    """Per-target thermal error model on a campaign dataset.

    Parameters
    ----------
    estimator : regressor
        Cloned once per target (through ``for_target`` when it has per-target
        settings).  It gets the per-row ``context`` of the campaigns
        (:mod:`thermocomp.core.context`): campaign, time, initial ambient, raw
        ``S_``/``T_`` columns and, in one-step mode, the measured target.
    selector : selector, optional
        Chooses inputs among the declared ones, per target (default: all).
    inputs : list of glob patterns
        Declared inputs (``data.inputs``).
    targets : list of str, optional
        ``E_`` columns to model (default: all in the training data).
    reference : {'first_sample', 'none'}
        Frame of ``T_``/``E_`` columns (see ``DATA_FORMAT.md``).
    denoiser : transformer, optional
        Applied per campaign to the declared input columns before stacking
        (so before referencing): offline on the training data, and in
        ``predict`` causally when its ``online`` is true (see
        :class:`thermocomp.core.denoise.EMDDenoiser`).  A fitted denoiser wrapped in
        :class:`sklearn.frozen.FrozenEstimator` is used as fitted (the
        ``denoise`` stage's output).
    selection : dict target -> list of str, optional
        Inputs chosen beforehand (the ``select`` stage's output), used
        instead of fitting ``selector``.
    offsets : {'predict', 'drop'}, default 'predict'
        ``'drop'``: a linear family's intercept is fitted, so that the gains
        are free of a constant offset of the targets, and then left out of
        every prediction (batch, streaming, exported code: they all read
        ``intercept_``).  For targets referenced to a noisy first sample -- the
        identified error parameters of a volumetric dataset, whose first
        cycle's identification error every row of the campaign shares -- the
        intercept is that error, not a thermal effect, and a compensation
        predicting it would apply it at every cycle.  A family without
        ``intercept_`` (ARX+RF, LSTM, the ATI wrapper) keeps its predictions.

    Attributes
    ----------
    inputs_ : list of str        declared input columns found in the data
    denoiser_ : fitted denoiser or None
    targets_ : list of str
    selected_ : dict target -> list of str
    estimators_ : dict target -> fitted estimator
    one_step_ : dict target -> fitted :class:`~thermocomp.core.models.one_step.OneStepLaw`
        The one-step law of each target, fitted on the training rows from the
        estimator's own simulation prediction (``eval.mode=one_step``).
    offsets_ : dict target -> float
        The intercepts left out (``offsets='drop'``), in the targets' unit.
    grid_period_s_ : float or None
        The training sample period where a model keeps a memory (cadence72): on rows closer
        together it steps once a period, on the row nearest each period on, and answers a row
        between from the state that row committed, not committing (between73; one-step mode
        holds; :func:`~thermocomp.core.timerule.on_grid`; every deployed form does the same);
        None (a static law, no time, an older pickle): every row.  (deploy73) Asked of the
        models (:func:`~thermocomp.core.context.keeps_memory`) when first read, not at every
        fit: a fit keeps the training period alone, and a prediction asks only where a row
        falls between two of its grid (3.4 % of MLR's fit CPU on make run's record, CV folds
        included, was the question asked at every fit).
    """

    def __init__(self, estimator, selector=None, inputs=("T_*",), targets=None,
                 reference: str = "first_sample", denoiser=None, selection=None,
                 offsets: str = "predict"):
        self.estimator = estimator
        self.selector = selector
        self.inputs = inputs
        self.targets = targets
        self.reference = reference
        self.denoiser = denoiser
        self.selection = selection
        self.offsets = offsets

    # -- matrices ---------------------------------------------------------------------------
    def stacked(self, campaigns: Mapping[str, pd.DataFrame], targets=None) -> Matrices:
        """The campaigns as the fitted model sees them: denoised (causally when online),
        stacked in the reference frame, with their context."""
        campaigns = denoise_campaigns(getattr(self, "denoiser_", None), campaigns)
        return stack(campaigns, self.inputs_, self.targets_ if targets is None else targets,
                     self.reference)

    def fit(self, campaigns: Mapping[str, pd.DataFrame], denoised: bool = False) -> "Compensator":
        """Fit the denoiser, the selector and the estimator of each target on ``campaigns``;
        ``denoised``: the campaigns are denoised already, by ``denoiser`` (fitted, frozen)."""
        columns = list(dict.fromkeys(c for df in campaigns.values() for c in df.columns))
        self.inputs_, self.targets_ = resolve_columns(columns, self.inputs, self.targets)
        self.denoiser_, campaigns = fit_denoiser(self.denoiser, campaigns, self.inputs_, denoised)
        return self.fit_stacked(stack(campaigns, self.inputs_, self.targets_, self.reference))

    def fit_stacked(self, m: Matrices) -> "Compensator":
        """Fit selector and estimators on already stacked matrices: the rows may be any subset
        of campaigns of one stack (its columns are the inputs and targets).  Without a fitted
        denoiser (``fit`` sets one) the matrices are taken as they are, so a configured
        denoiser is refused."""
        if not hasattr(self, "denoiser_"):
            if self.denoiser is not None:
                raise ValueError("fit_stacked takes matrices as they are: fit() a compensator "
                                 "with a denoiser")
            self.denoiser_ = None
        self.inputs_, self.targets_ = list(m.X.columns), list(m.Y.columns)
        if self.offsets not in OFFSETS:
            raise ValueError(f"offsets must be one of {OFFSETS}, got {self.offsets!r}")
        selector = self.selector if self.selector is not None else AllInputs()
        self.selected_, self.estimators_, self.one_step_, self.offsets_ = {}, {}, {}, {}
        context = _simulation(m.context)
        for target in self.targets_:
            y = m.Y[target].to_numpy()
            names = (list(self.selection[target]) if self.selection is not None  # (measured
                     else list(clone(selector).fit(measured(m.X, y), y[np.isfinite(y)]).selected_))
            X = m.X[names].to_numpy()
            est, y = self._fit_in_frame(for_target(self.estimator, target), X, y, m.groups,
                                        context)
            if self.offsets == "drop" and hasattr(est, "intercept_"):
                self.offsets_[target] = float(est.intercept_)
                est.intercept_ = 0.0
            # the one-step law: from the fitted model's simulation on these (training) rows only,
            # on the label in the frame it is scored and fed in (a late first probe: completed
            # by y_hat(m), as predict_stacked completes the measured error it is given)
            s = np.asarray(est.predict(X, context=context), dtype=float).reshape(-1, 1)
            self.one_step_[target] = OneStepLaw().fit(
                s, self.scored_label(m.Y[target].to_numpy(), m.groups, s[:, 0]), context=context)
            self.selected_[target], self.estimators_[target] = names, est
        self.__dict__.pop("_grid_period_s", None)
        self._sample_period_s = median_step(m.time, m.groups)    # the grid's, if it keeps memory
        return self

    @property
    def grid_period_s_(self) -> float | None:
        """The training grid's period (class doc), the models asked once, when first read."""
        known = self.__dict__
        if "_grid_period_s" not in known:
            period = known.get("_sample_period_s")
            memory = period and any(keeps_memory(e, len(self.selected_[t]))
                                    for t, e in self.estimators_.items())
            self._grid_period_s = period if memory else None
        return self._grid_period_s

    def _grid_candidate(self) -> float | None:
        """The period a grid would have (the training's; the grid itself once known): rows
        closer than half of it are held only where the models keep a memory."""
        known = self.__dict__
        return known["_grid_period_s"] if "_grid_period_s" in known else known.get("_sample_period_s")

    def __setstate__(self, state: dict) -> None:
        if "grid_period_s_" in state:       # pickled by cadence72's code: the grid as found then
            state["_grid_period_s"] = state.pop("grid_period_s_")
        super().__setstate__(state)

    def _fit_in_frame(self, template, X, y, groups, context):
        """``template`` cloned and fitted on ``(X, y)``, and the label it was fitted on: in the
        first-sample frame, where a campaign's first measurement comes after its first row
        (:mod:`thermocomp.core.first_probe`), refitted up to :data:`REFITS` times on the label
        completed by the model's own estimate of the unmeasured ``E(m) - E(0)``, so that it is
        fitted in the frame it is used in (the stream's, from the campaign's first row); the fit
        of the lowest :func:`~thermocomp.core.first_probe.frame_loss` on these rows is kept (a
        refit that moves away, as a Hammerstein's on a record of short campaigns, is not).
        Within :func:`~thermocomp.core.shared_fits.shared_fits` a fit already made is copied."""
        return fitted(lambda: self._fit_in_frame_now(template, X, y, groups, context),
                      template, X, y, groups, context, self.reference)

    def _fit_in_frame_now(self, template, X, y, groups, context):
        est = clone(template).fit(X, y, context=context)
        if self.reference != "first_sample" or not late_starts(y, groups):
            return est, y
        s = np.asarray(est.predict(X, context=context), dtype=float)
        best = (frame_loss(y, s, groups), est, y)
        for _ in range(REFITS):
            label = completed(y, s, groups, from_start=True)
            est = clone(template).fit(X, label, context=context)
            s = np.asarray(est.predict(X, context=context), dtype=float)
            loss = frame_loss(y, s, groups)
            if loss < best[0]:
                best = (loss, est, label)
        return best[1], best[2]

    # -- prediction -------------------------------------------------------------------------
    def predict_stacked(self, m: Matrices, mode: str = "simulation") -> np.ndarray:
        """Predicted error ``(n_rows, n_targets)`` of stacked matrices (see :meth:`stacked`)."""
        if mode not in MODES:
            raise ValueError(f"eval.mode must be one of {MODES}, got {mode!r}")
        period = self._grid_candidate()
        if period:      # rows closer than the training period: stepped on its grid
            stepped = grid_rows(m.time, m.groups, period)
            if not stepped.all() and self.grid_period_s_:
                out = self.predict_stacked(m.subset(stepped), mode)[np.cumsum(stepped) - 1]
                if mode == "simulation":   # a row between: from the committed state (between73)
                    context = _simulation(m.context)
                    for k, (target, est) in enumerate(self.estimators_.items()):
                        X = m.X[self.selected_[target]].to_numpy()
                        out[~stepped, k] = between_steps(est, X, context, stepped)
                return out
        out = np.empty((len(m.X), len(self.targets_)))
        laws = getattr(self, "one_step_", None)   # None: a model pickled before the law existed
        context = _simulation(m.context) if laws is not None else m.context
        for k, (target, est) in enumerate(self.estimators_.items()):
            X = m.X[self.selected_[target]].to_numpy()
            if mode == "simulation":
                out[:, k] = est.predict(X, context=context)
                continue
            # one-step: the measured error is a side input too (of the law, or of an old model)
            measured = with_column(context, Y_MEASURED, m.Y[target].to_numpy(), len(m.X))
            if laws is None:
                out[:, k] = est.predict(X, context=measured)
                continue
            s = np.asarray(est.predict(X, context=context), dtype=float).reshape(-1, 1)
            # the measured error in the frame of the simulation s, E(t) - E(0): a late first
            # probe's label E(t) - E(m) completed by y_hat(m), as it is scored (Compensator.
            # measured); fed as it is, every one-step prediction was off by E(m) - E(0)
            y = self.scored_label(m.Y[target].to_numpy(), m.groups, s[:, 0])
            measured = with_column(context, Y_MEASURED, y, len(m.X))
            out[:, k] = laws[target].predict(s, context=measured)
        return out

    def scored_label(self, label: np.ndarray, groups: np.ndarray, simulated) -> np.ndarray:
        """The stacked ``label`` (``(n,)`` or ``(n, k)``, campaigns ``groups``) as every scorer
        compares it with this model's prediction: in the first-sample frame, a campaign first
        measured after its first row completed by the model's simulation there
        (:mod:`thermocomp.core.first_probe`); else ``label`` itself.  ``simulated``: that
        simulation, or a function giving it (called only where a first measurement is late)."""
        if self.reference != "first_sample" or not late_starts(label, groups):
            return label
        return completed(label, simulated() if callable(simulated) else simulated, groups)

    def predict(self, campaigns: Mapping[str, pd.DataFrame], mode: str = "simulation"
                ) -> dict[str, pd.DataFrame]:
        """Predicted error per campaign (columns = targets), in the reference frame.

        ``mode='simulation'`` never uses a measured target; ``'one_step'``
        feeds the model's simulation and the measured previous error to the
        target's one-step law (:class:`~thermocomp.core.models.one_step.OneStepLaw`, the
        same for every family).
        """
        m = self.stacked(campaigns, self.targets_ if mode == "one_step" else [])
        out = pd.DataFrame(self.predict_stacked(m, mode), columns=self.targets_)
        return {cid: out[m.rows_of(cid)].reset_index(drop=True) for cid in campaigns}

    def measured(self, campaigns: Mapping[str, pd.DataFrame], predicted: Mapping | None = None
                 ) -> dict[str, pd.DataFrame]:
        """Measured targets per campaign in the same reference frame as ``predict``; a target
        a campaign did not record (a stream scored where it was measured) is NaN there.

        In the first-sample frame a target first measured after its campaign's first row is
        completed by the prediction there (:mod:`thermocomp.core.first_probe`): its residual
        compares ``y_hat(t) - y_hat(m)`` with the label.  ``predicted``: :meth:`predict`'s
        simulation of these campaigns when the caller has it (else predicted here, only then).
        """
        campaigns = {cid: df.assign(**{t: np.nan for t in self.targets_ if t not in df.columns})
                     for cid, df in campaigns.items()}
        m = stack(campaigns, [], self.targets_, self.reference)
        def simulated():
            frames = self.predict(campaigns) if predicted is None else predicted
            return np.concatenate([frames[cid][self.targets_].to_numpy(float) for cid in campaigns])

        Y = m.Y.to_numpy(float)
        label = self.scored_label(Y, m.groups, simulated)
        if label is not Y:
            m.Y = pd.DataFrame(label, columns=m.Y.columns)
        return {cid: m.Y[m.rows_of(cid)].reset_index(drop=True) for cid in campaigns}


def _simulation(context):
    """The context without a measured target: families are fitted and run in simulation."""
    if context is not None and Y_MEASURED in context:
        return context.drop(columns=[Y_MEASURED])
    return context


def with_chosen_hyperparameters(template: Compensator, fitted: Compensator) -> Compensator:
    """``template`` (unfitted) whose estimator takes, per target, the hyper-parameters that
    ``fitted``'s estimator chose by its own cross-validation (``chosen_params()``), so that its
    copies fit without one: the many small models of mutual prediction.  Families without
    ``chosen_params`` (and targets ``fitted`` does not have) are left as they are."""
    from .models.base import PerTarget

    chosen = {t: est.chosen_params() for t, est in getattr(fitted, "estimators_", {}).items()
              if callable(getattr(est, "chosen_params", None))}
    if not chosen:
        return template
    return clone(template).set_params(estimator=PerTarget(template.estimator, chosen))


def refit_as_chosen(fitted: Compensator) -> Compensator | None:
    """``fitted`` unfitted again, to refit without choosing again: under model=auto, per target
    the family or blend auto chose (:func:`~.models.auto.as_chosen`), each member with the
    hyper-parameters its own CV chose (:func:`with_chosen_hyperparameters`, as mutual
    prediction's single-campaign models are made), so no candidate is validated again; any other
    model as configured (its family's own CV, if any, runs).  None where model=auto chose but
    the estimator cannot be told its choice (a wrapper without ``chosen``)."""
    from .models.auto import as_chosen

    template = clone(fitted)
    # auto's mark is family_: an ARX's chosen_ (its order) is no choice of auto's (deploy87)
    if not any(hasattr(est, "family_") for est in getattr(fitted, "estimators_", {}).values()):
        return template
    template = as_chosen(template, fitted)
    if template.estimator.get_params(deep=False).get("chosen") is None:
        return None
    return with_chosen_hyperparameters(template, fitted)
