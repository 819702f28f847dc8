r"""One-step prediction, the same law for every model family, and the persistence baseline.

The CLI contract's ``eval.mode=one_step``: the previous *measured* error is an
input too.  Every family is fitted for simulation (its own free run, no
measured error: what a machine can deploy); :class:`OneStepLaw` turns its
simulation output :math:`\hat s` into a one-step predictor, an
error-correction form

.. math:: \hat y(t) = y(t-1) + k\,\big(\hat s(t) - \hat s(t-1)\big)
                     - g\,\big(y(t-1) - \hat s(t-1)\big)

-- persistence of the measured error, plus the change the model expects since
the last sample, minus a share of the model's current miss.  The two gains
are fitted by least squares on the *training* rows' one-step increments
:math:`y(t) - y(t-1)`.  It contains persistence (:math:`k = g = 0`) and the
simulation itself (:math:`k = g = 1`), so the fit decides how far to trust the
measurement against the model: with sensor noise larger than the model's
error, :math:`g \to 1` (a noisy :math:`y(t-1)` is worse than the model); with
a drifting model, :math:`g \to 0`.  Two scalars per target are hard to
overfit and need no CV; there is no intercept (a constant drift per sample of
the train record is not worth extrapolating).  :math:`\hat s` on the training
rows is in-sample, so its miss there is somewhat smaller than on new data
and :math:`g` leans towards the model: negligible for models with few
parameters per sample (all families on records of thousands of samples).

At a campaign's first sample there is no previous measurement: the law
predicts :math:`\hat s(t)` (the model's own simulation value).  In the
``first_sample`` reference frame the measured error is 0 there by
definition, so nothing is lost; with ``data.reference=none`` the first
sample is predicted as in simulation, never from its own measurement.  A
campaign that continues another one (a record cut in two files) does have a
previous measurement: :mod:`thermocomp.core.continuation` predicts it joined to its
predecessor, so the law sees that sample.

Families with their own one-step model (ARX with an AR term, ARX+RF, LagBank
with ``ar``) still provide it when *they* are handed ``y_measured``, but the
:class:`~thermocomp.core.compensator.Compensator` uses this law for all of them:
one definition, fitted on the train split only, comparable across families,
and on ``sim=long_record`` about as good as the best family-specific one.
"""

from __future__ import annotations

import numpy as np
from sklearn.base import BaseEstimator, RegressorMixin
from sklearn.utils.validation import check_is_fitted, validate_data

from ..context import Y_MEASURED, SideInputs, groups_of, require, values
from ._dynamics import last_measured, previous, segment_starts
from .base import measured_rows


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

    .. math:: \hat y(t) = y(t-1) + k\,\big(\hat s(t) - \hat s(t-1)\big)
                         - g\,\big(y(t-1) - \hat s(t-1)\big),
              \qquad \hat y(t_0) = \hat s(t_0) \text{ at a campaign start}

    ``X`` is the one column :math:`\hat s` (the model's simulation prediction
    of the same rows); ``y_measured`` comes from the context (side-input
    protocol, :mod:`thermocomp.core.context`), as does ``campaign``.  ``fit``
    estimates :math:`(k, g)` by least squares on the increments of the rows
    that have a previous sample in their campaign.  A missing measured value
    (NaN) is bridged from the last measured one: :math:`t-1` above is the last row before
    :math:`t` whose error was measured (a probe cycle's previous reading, ``data.sparse_targets``).

    Attributes
    ----------
    k_ : float
        Gain on the model's expected change.
    g_ : float
        Share of the model's previous miss corrected (0: persistence plus
        changes, 1: back to the model's level).
    n_rows_ : int
        Rows the gains were fitted on.
    """

    def fit(self, X, y, context=None):
        X, y, _ = measured_rows(self, X, y)
        s = np.asarray(X, float)[:, 0]
        groups = groups_of(context)
        # the increments from the last measured row (the previous sample where y is measured
        # at every one; the previous probe reading of a target measured now and then)
        last = last_measured(y, groups)
        rows = last >= 0
        s_prev, y_prev = s[np.maximum(last, 0)], y[np.maximum(last, 0)]
        A = np.c_[s - s_prev, s_prev - y_prev][rows]
        dy = (y - y_prev)[rows]
        ok = np.isfinite(dy) & np.isfinite(A).all(axis=1)
        # lstsq: the minimum-norm answer when the model's output never changes (k = g = 0 there)
        theta = np.linalg.lstsq(A[ok], dy[ok], rcond=None)[0] if ok.any() else np.zeros(2)
        self.k_, self.g_ = float(theta[0]), float(theta[1])
        self.n_rows_ = int(ok.sum())
        # rows between two measurements (1: every sample measured): its one-step law spans them
        spans = (np.flatnonzero(rows) - last[rows])[ok]
        self.every_ = int(np.median(spans)) if spans.size else 1
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
        # from the last measured row, as fitted: the previous sample where every sample is
        # measured; the last probe reading of a target measured now and then (one probe
        # cycle ahead), or the last reading before a measurement gap
        last = last_measured(y, groups_of(context))
        seen = last >= 0
        out = s.copy()          # no measurement yet in the campaign: the model's own simulation
        out[seen] = self._law(y[last[seen]], s[seen], s[last[seen]])
        return out

    def _law(self, y_prev, s, s_prev):
        return y_prev + self.k_ * (s - s_prev) - self.g_ * (y_prev - s_prev)
