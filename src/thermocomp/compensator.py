"""The compensation model as one object: declared inputs -> selector -> estimator, per target.

Pure core: takes campaign DataFrames (contract columns), returns predictions.
Stages pickle it to ``models/<name>/model.pkl``; deployment wraps it.
"""

from __future__ import annotations

import inspect
from collections.abc import Mapping

import numpy as np
import pandas as pd
from sklearn.base import clone

from .denoise import denoise_campaigns, fit_denoiser
from .frame import resolve_columns, stack
from .select import AllInputs

MODES = ("simulation", "one_step")


def _accepts(method, name: str) -> bool:
    return name in inspect.signature(method).parameters


def _side_inputs(method, m) -> dict:
    """``groups``/``context`` for the estimator methods that take them."""
    side = {"groups": m.groups, "context": m.context}
    return {k: v for k, v in side.items() if _accepts(method, k)}


class Compensator:
    """Per-target thermal error model on a campaign dataset.

    Parameters
    ----------
    estimator : regressor
        Cloned once per target.  Its ``fit``/``predict`` get, when their
        signature accepts them, ``groups`` (campaign of each row, so dynamic
        models never cross campaigns) and ``context`` (a per-row DataFrame with
        ``campaign``, ``time``, ``ambient_c0``; see :class:`thermocomp.frame.Matrices`);
        ``fit`` also gets ``target`` (the ``E_`` column) when it accepts it.
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
        :class:`thermocomp.denoise.EMDDenoiser`).

    Attributes
    ----------
    inputs_ : list of str        declared input columns found in the data
    denoiser_ : fitted denoiser or None
    targets_ : list of str
    selected_ : dict target -> list of str
    estimators_ : dict target -> fitted estimator
    """

    def __init__(self, estimator, selector=None, inputs=("T_*",), targets=None,
                 reference: str = "first_sample", denoiser=None):
        self.estimator = estimator
        self.selector = selector
        self.inputs = inputs
        self.targets = targets
        self.reference = reference
        self.denoiser = denoiser

    def fit(self, campaigns: Mapping[str, pd.DataFrame], denoised: bool = False,
            selected: Mapping[str, list] | None = None) -> "Compensator":
        """Fit per target.  ``denoised=True``: ``campaigns`` already went through
        ``denoiser``, which is then used as fitted (the ``denoise`` stage's output);
        ``selected``: inputs per target chosen beforehand (the ``select`` stage),
        used instead of refitting the selector."""
        columns = list(dict.fromkeys(c for df in campaigns.values() for c in df.columns))
        self.inputs_, self.targets_ = resolve_columns(columns, self.inputs, self.targets)
        self.denoiser_, campaigns = fit_denoiser(self.denoiser, campaigns, self.inputs_, denoised)
        m = stack(campaigns, self.inputs_, self.targets_, self.reference)
        selector = self.selector if self.selector is not None else AllInputs()
        self.selected_, self.estimators_ = {}, {}
        for target in self.targets_:
            y = m.Y[target].to_numpy()
            names = list(selected[target]) if selected is not None else \
                list(clone(selector).fit(m.X, y, groups=m.groups).selected_)
            est = clone(self.estimator)
            X = m.X[names].to_numpy()
            side = _side_inputs(est.fit, m)
            if _accepts(est.fit, "target"):  # per-target settings (diagnosed effects)
                side["target"] = target
            est.fit(X, y, **side)
            self.selected_[target], self.estimators_[target] = names, est
        return self

    def predict(self, campaigns: Mapping[str, pd.DataFrame], mode: str = "simulation"
                ) -> dict[str, pd.DataFrame]:
        """Predicted error per campaign (columns = targets), in the reference frame.

        ``mode='simulation'`` never uses a measured target; ``'one_step'`` hands
        the measured previous error to models that have an autoregressive part.
        """
        if mode not in MODES:
            raise ValueError(f"eval.mode must be one of {MODES}, got {mode!r}")
        campaigns = denoise_campaigns(getattr(self, "denoiser_", None), campaigns)
        m = stack(campaigns, self.inputs_, self.targets_, self.reference)
        out = pd.DataFrame(index=m.X.index, columns=self.targets_, dtype=float)
        for target, est in self.estimators_.items():
            X = m.X[self.selected_[target]].to_numpy()
            kwargs = _side_inputs(est.predict, m)
            if mode == "one_step" and _accepts(est.predict, "y_measured"):
                kwargs["y_measured"] = m.Y[target].to_numpy()
            out[target] = np.asarray(est.predict(X, **kwargs), dtype=float)
        return {cid: out[m.rows_of(cid)].reset_index(drop=True) for cid in campaigns}

    def measured(self, campaigns: Mapping[str, pd.DataFrame]) -> dict[str, pd.DataFrame]:
        """Measured targets per campaign in the same reference frame as ``predict``."""
        m = stack(campaigns, self.inputs_, self.targets_, self.reference)
        return {cid: m.Y[m.rows_of(cid)].reset_index(drop=True) for cid in campaigns}
