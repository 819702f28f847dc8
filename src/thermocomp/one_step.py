r"""One-step prediction, the same law for every model family, and the persistence baseline.

The CLI contract's ``eval.mode=one_step``: the previous *measured* error is an
input too.  Every family is fitted for simulation (its own free run, no
measured error: what a machine can deploy); :class:`OneStepLaw` turns its
simulation output :math:`\hat s` into a one-step predictor

.. math:: \hat y(t) = y(t-1) + k\,\big(\hat s(t) - \hat s(t-1)\big)

-- persistence of the measured error plus the change the model expects since
the last sample, scaled by one gain :math:`k` fitted by least squares on the
*training* rows' one-step increments :math:`y(t) - y(t-1)`.  One scalar per
target is hard to overfit, needs no CV, and puts every family on the same
footing (its one-step skill is exactly how well its simulation tracks
changes); with :math:`k = 0` it is persistence.  There is no intercept: a
constant drift per sample fitted on the train record is not a property of the
machine worth extrapolating.

At a campaign's first sample there is no previous measurement: the law
predicts :math:`\hat s(t)` (the model's own simulation value).  In the
``first_sample`` reference frame the measured error is 0 there by
definition, so nothing is lost; with ``data.reference=none`` the first
sample is predicted as in simulation, never from its own measurement.  A
campaign that continues another one (a record cut in two files) does have a
previous measurement: :mod:`thermocomp.continuation` predicts it joined to its
predecessor, so the law sees that sample.

Families with their own one-step model (ARX with an AR term, ARX+RF, LagBank
with ``ar``) still provide it when *they* are handed ``y_measured``, but the
:class:`~thermocomp.compensator.Compensator` uses this law for all of them:
one definition, fitted on the train split only, comparable across families.
"""

from __future__ import annotations

import numpy as np
from sklearn.base import BaseEstimator, RegressorMixin
from sklearn.utils.validation import check_is_fitted, validate_data

from .context import Y_MEASURED, SideInputs, groups_of, require, values
from .models._dynamics import previous, segment_starts


def persistence(y_measured, groups=None) -> np.ndarray:
    """Previous measured error as the prediction: ``y(t-1)``, 0 at each campaign start.

    0 is the first-sample frame's error at a campaign start (the frame's
    origin); NaN measurements carry the last valid value forward.
    """
    y = np.asarray(y_measured, dtype=float)
    if np.isnan(y).any():   # a gap in the measurement: hold the last valid value
        y = y.copy()
        for start, stop in zip(*_bounds(groups, len(y))):
            last = 0.0
            for t in range(start, stop):
                if np.isnan(y[t]):
                    y[t] = last
                last = y[t]
    return previous(y, groups)


def _bounds(groups, n):
    starts = segment_starts(groups, n)
    return starts, np.r_[starts[1:], n].astype(int)


class OneStepLaw(SideInputs, RegressorMixin, BaseEstimator):
    r"""One-step predictor from a model's simulation output and the measured previous error.

    .. math:: \hat y(t) = y(t-1) + k\,\big(\hat s(t) - \hat s(t-1)\big),
              \qquad \hat y(t_0) = \hat s(t_0) \text{ at a campaign start}

    ``X`` is the one column :math:`\hat s` (the model's simulation prediction
    of the same rows); ``y_measured`` comes from the context (side-input
    protocol, :mod:`thermocomp.context`), as does ``campaign``.  ``fit``
    estimates :math:`k` by least squares on the increments of the rows that
    have a previous sample in their campaign.  A missing measured value
    (NaN) is replaced by the law's own previous prediction.

    Attributes
    ----------
    k_ : float
        Gain on the model's expected change (0 when the model's output never
        changes: persistence).
    n_rows_ : int
        Rows the gain was fitted on.
    """

    def fit(self, X, y, context=None):
        X, y = validate_data(self, X, y, y_numeric=True)
        s, y = np.asarray(X, float)[:, 0], np.asarray(y, float)
        groups = groups_of(context)
        rows = np.ones(len(y), dtype=bool)
        rows[segment_starts(groups, len(y))] = False
        ds = (s - previous(s, groups))[rows]
        dy = (y - previous(y, groups))[rows]
        ok = np.isfinite(dy)
        ds, dy = ds[ok], dy[ok]
        denom = float(ds @ ds)
        # a tiny relative tolerance: an output that never changes leaves persistence alone
        self.k_ = float(ds @ dy) / denom if denom > 1e-24 * max(len(ds), 1) else 0.0
        self.n_rows_ = int(ds.size)
        self.context_columns_ = []
        return self

    def predict(self, X, context=None):
        """One-step prediction; needs ``y_measured`` in ``context``."""
        check_is_fitted(self)
        X = validate_data(self, X, reset=False)
        s = np.asarray(X, float)[:, 0]
        n = len(s)
        require(context, Y_MEASURED, "one-step prediction")
        y = values(context, Y_MEASURED, n)
        groups = groups_of(context)
        starts = segment_starts(groups, n)
        step = s - previous(s, groups)
        out = previous(y, groups) + self.k_ * step
        out[starts] = s[starts]
        gaps = np.flatnonzero(np.isnan(out))
        for t in gaps:   # measurement gap: continue from the law's own previous prediction
            out[t] = out[t - 1] + self.k_ * step[t]
        return out
