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
        ``campaign``, ``time``, ``ambient_c0``; see :class:`thermocomp.frame.Matrices`).
    selector : selector, optional
        Chooses inputs among the declared ones, per target (default: all).
    inputs : list of glob patterns
        Declared inputs (``data.inputs``).
    targets : list of str, optional
        ``E_`` columns to model (default: all in the training data).
    reference : {'first_sample', 'none'}
        Frame of ``T_``/``E_`` columns (see ``DATA_FORMAT.md``).

    Attributes
    ----------
    inputs_ : list of str        declared input columns found in the data
    targets_ : list of str
    selected_ : dict target -> list of str
    estimators_ : dict target -> fitted estimator
    """

    def __init__(self, estimator, selector=None, inputs=("T_*",), targets=None,
                 reference: str = "first_sample"):
        self.estimator = estimator
        self.selector = selector
        self.inputs = inputs
        self.targets = targets
        self.reference = reference

    def fit(self, campaigns: Mapping[str, pd.DataFrame]) -> "Compensator":
        columns = list(dict.fromkeys(c for df in campaigns.values() for c in df.columns))
        self.inputs_, self.targets_ = resolve_columns(columns, self.inputs, self.targets)
        m = stack(campaigns, self.inputs_, self.targets_, self.reference)
        selector = self.selector if self.selector is not None else AllInputs()
        self.selected_, self.estimators_ = {}, {}
        for target in self.targets_:
            y = m.Y[target].to_numpy()
            sel = clone(selector).fit(m.X, y, groups=m.groups)
            est = clone(self.estimator)
            X = m.X[sel.selected_].to_numpy()
            est.fit(X, y, **_side_inputs(est.fit, m))
            self.selected_[target], self.estimators_[target] = list(sel.selected_), est
        return self

    def predict(self, campaigns: Mapping[str, pd.DataFrame], mode: str = "simulation"
                ) -> dict[str, pd.DataFrame]:
        """Predicted error per campaign (columns = targets), in the reference frame.

        ``mode='simulation'`` never uses a measured target; ``'one_step'`` hands
        the measured previous error to models that have an autoregressive part.
        """
        if mode not in MODES:
            raise ValueError(f"eval.mode must be one of {MODES}, got {mode!r}")
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
