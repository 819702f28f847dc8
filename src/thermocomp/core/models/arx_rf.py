"""ARX stacked with a random forest on a logistic-smoothed machine-state signal (paper 004)."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd
from scipy.special import expit
from sklearn.base import BaseEstimator, RegressorMixin, clone
from sklearn.ensemble import RandomForestRegressor
from sklearn.utils.validation import check_is_fitted, validate_data

from ...base.errors import ParameterError
from ...base.params import POSITIVE, check_estimator, either, numbers, optional, text
from ..context import (
    TIME,
    Y_MEASURED,
    SideInputs,
    context_columns,
    groups_of,
    has,
    merge_columns,
    require,
    stream_branches,
    stream_steps,
    values,
    with_column,
)
from ._dynamics import segment_bounds
from .arx import ARX
from .base import measured_rows


def _taus(tau_s) -> np.ndarray:
    taus = np.atleast_1d(np.asarray(tau_s, dtype=float))
    if taus.size == 0 or not np.all(taus > 0):
        raise ParameterError(f"ARXRF tau_s={tau_s!r} must be one or more positive times (s)")
    return taus


def logistic_switching(state, time, groups=None, tau_s=60.0) -> np.ndarray:
    r"""Smooth a binary state signal (door 0 closed / 1 open) at its switching instants.

    Paper 004, Eq. 9, read as a logistic ramp from each status change at
    :math:`t_0` onwards:

    .. math:: s(t) = \frac{1}{1 + e^{-k (t - t_0)/\tau}}, \qquad
              k = +1 \text{ (0 → 1)},\; k = -1 \text{ (1 → 0)}

    with :math:`t_0` the last change at or before :math:`t`.  Before a
    campaign's first change ``s`` is the state itself.  (The printed equation
    multiplies by the raw state and has the sign of ``t0 - t`` flipped, which
    would zero the signal after every closing and make it fall while the door
    stays open; the ramp above is the reading that makes ``k = ±1`` meaningful.)
    The rate is per ``tau`` seconds (the paper's unit is not stated; its
    door signal is sampled every minute, hence the default 60 s).  Causal: the
    value at ``t`` uses samples up to ``t`` only, so it runs on a machine.

    Parameters
    ----------
    state : array (n,)
        Raw state; values > 0.5 count as 1, NaN holds the previous value (0 at a start).
    time : array (n,)
        Sample time (s).
    groups : array (n,), optional
        Campaign of each row; the smoothing restarts at each campaign.
    tau_s : float or sequence of float
        Time scale(s); one output column per value.

    Returns
    -------
    ndarray (n, len(tau_s))
    """
    taus = _taus(tau_s)
    state, time = np.asarray(state, dtype=float), np.asarray(time, dtype=float)
    n = len(state)
    out = np.empty((n, taus.size))
    for start, stop in segment_bounds(groups, n):
        on = pd.Series(state[start:stop]).ffill().fillna(0.0).to_numpy() > 0.5
        t = time[start:stop]
        idx = np.arange(stop - start)
        last = np.maximum.accumulate(np.where(np.r_[False, on[1:] != on[:-1]], idx, -1))
        t0 = t[np.maximum(last, 0)]
        k = np.where(on, 1.0, -1.0)
        ramp = expit(k[:, None] * (t - t0)[:, None] / taus[None, :])
        out[start:stop] = np.where((last >= 0)[:, None], ramp, on[:, None].astype(float))
    return out


def _flat_trees(forest) -> tuple:
    """Node arrays of every tree of a fitted forest, padded to one table (cached on the forest)."""
    cached = getattr(forest, "_thermocomp_flat", None)
    if cached is not None:
        return cached
    trees = [e.tree_ for e in getattr(forest, "estimators_", [])]
    width = max(t.node_count for t in trees)

    def table(get, fill, dtype):
        out = np.full((len(trees), width), fill, dtype=dtype)
        for i, t in enumerate(trees):
            out[i, :t.node_count] = get(t)
        return out

    flat = (table(lambda t: t.children_left, -1, np.int64), table(lambda t: t.children_right, -1, np.int64),
            table(lambda t: np.maximum(t.feature, 0), 0, np.int64),   # leaves: -2 -> any column
            table(lambda t: t.threshold, 0.0, float),
            table(lambda t: t.value[:, 0, 0], 0.0, float))
    forest._thermocomp_flat = flat
    return flat


def _distinct_rows_predict(forest, S: np.ndarray) -> np.ndarray:
    """``forest.predict(S)``, each distinct row of ``S`` predicted once (the same numbers: a
    row's prediction does not depend on the others).  The smoothed state repeats: a machine
    on or off holds 0 or 1 for minutes (707 distinct rows of 26 898 on a 43-run lathe record,
    predicted by each of mutual prediction's and validation's forests)."""
    if not np.isfinite(S).all():        # NaN rows are not told apart reliably: all of them
        return forest.predict(S)
    rows, inverse = np.unique(S, axis=0, return_inverse=True)
    return forest.predict(rows)[inverse.reshape(-1)]


def _one_row_predict(forest, x) -> float:
    """``forest.predict(x[None, :])[0]`` for one sample, all trees walked at once in NumPy.

    Written by hand because scikit-learn's ``predict`` spends ~80 µs per tree on
    validation and dispatch for a single row (8 ms for 100 trees, every sample
    of a stream); the walk below is the same comparison (features cast to
    float32 as the trees see them) and the same mean of the leaf values.
    Any other regressor goes through its own ``predict``.
    """
    if not hasattr(forest, "estimators_") or not all(hasattr(e, "tree_") for e in forest.estimators_):
        return float(forest.predict(np.asarray(x, float)[None, :])[0])
    left, right, feature, threshold, value = _flat_trees(forest)
    x32 = np.asarray(x, dtype=np.float32).astype(float)
    rows = np.arange(left.shape[0])
    node = np.zeros(left.shape[0], dtype=np.int64)
    while True:
        inner = left[rows, node] >= 0
        if not inner.any():
            break
        go_left = x32[feature[rows, node]] <= threshold[rows, node]
        node = np.where(inner, np.where(go_left, left[rows, node], right[rows, node]), node)
    return float(value[rows, node].mean())


class ARXRF(SideInputs, RegressorMixin, BaseEstimator):
    r"""Stacked ARX + random forest: the forest models what the ARX misses from a machine state.

    .. math:: \hat y(t) = \hat y_{\mathrm{ARX}}(t) + f_{\mathrm{RF}}\big(s(t)\big)

    where :math:`\hat y_{\mathrm{ARX}}` is an :class:`~thermocomp.core.models.arx.ARX`
    on the inputs ``X`` and :math:`s(t)` the state signal (default ``S_door``)
    smoothed by :func:`logistic_switching` (paper 004, Eq. 9).  The forest is
    trained on the ARX residual in simulation mode (free run) on the training
    campaigns, so it learns what the deployed ARX actually misses.  In one-step
    mode (``y_measured`` given) an ARX with an AR term uses a second forest,
    trained on its one-step residual.

    The state column is not a declared input: it reaches the estimator through
    ``context`` (the Compensator's per-row frame, which carries every ``S_``
    column of the campaigns, see :func:`thermocomp.core.frame.stack`), together
    with ``time``.  A campaign without the column counts as "door closed".

    Parameters
    ----------
    arx : ARX, optional
        The dynamic part (default ``ARX()``), cloned in ``fit``.
    forest : regressor, optional
        Residual model (default ``RandomForestRegressor(n_estimators=100,
        min_samples_leaf=5, random_state=0)``; paper 004 uses 100 trees).
    state_column : str or None, default 'S_door'
        Context column of the state signal.  ``None``: no state, the forest
        sees a constant (it then only learns the mean residual; this is the
        configuration scikit-learn's ``check_estimator`` can run, as it cannot
        pass a context).
    tau_s : float or sequence of float, default 60.0
        Time scale(s) of the logistic ramp (s); several give the forest one
        smoothed signal per scale.

    Attributes
    ----------
    arx_ : ARX
    forest_ : regressor
        Trained on the simulation-mode ARX residual.
    forest_one_step_ : regressor or None
        Trained on the one-step residual (None when the ARX has no AR term:
        both residuals coincide).
    """

    param_rules = {"state_column": optional(text()),
                   "tau_s": either(POSITIVE, numbers(0.0, open_lo=True))}

    def __init__(self, arx=None, forest=None, state_column: str | None = "S_door", tau_s=60.0):
        self.arx = arx
        self.forest = forest
        self.state_column = state_column
        self.tau_s = tau_s

    def _state_features(self, n: int, context) -> np.ndarray:
        taus = _taus(self.tau_s)
        if self.state_column is None:
            return np.zeros((n, 1))
        state = require(context, self.state_column, f"the ARX+RF model (machine-state signal "
                                                    f"{self.state_column!r})")
        if len(state) != n:
            raise ValueError(f"context has {len(state)} rows, X has {n}")
        time = values(context, TIME, n)
        return logistic_switching(np.asarray(state, dtype=float),
                                  time if time is not None else np.arange(n, dtype=float),
                                  groups_of(context), taus)

    def _new_forest(self):
        if self.forest is not None:
            return clone(self.forest)
        return RandomForestRegressor(n_estimators=100, min_samples_leaf=5, random_state=0)

    def fit(self, X, y, context=None):
        check_estimator(self)
        # a target measured now and then: the ARX (no AR term then) and the forest on the
        # measured rows, the state features on every row
        X, y, measured = measured_rows(self, X, y)
        S = self._state_features(len(y), context)
        self.arx_ = clone(self.arx if self.arx is not None else ARX()).fit(X, y, context=context)
        residual = y - self.arx_.predict(X, context=context)
        self.forest_ = self._new_forest().fit(S[measured], residual[measured])
        self.forest_one_step_ = None
        if self.arx_.ar_coef_ != 0.0:
            one_step = self.arx_.predict(X, context=with_column(context, Y_MEASURED, y, len(y)))
            self.forest_one_step_ = self._new_forest().fit(S, y - one_step)
        self.context_columns_ = merge_columns(
            [TIME, self.state_column] if self.state_column is not None else [],
            context_columns(self.arx_))
        return self

    def predict(self, X, context=None):
        """ARX prediction (free run, or one-step with ``y_measured`` in ``context``) + forest on the state."""
        check_is_fitted(self)
        X = validate_data(self, X, reset=False)
        S = self._state_features(X.shape[0], context)
        base = self.arx_.predict(X, context=context)
        one_step = has(context, Y_MEASURED) and self.forest_one_step_ is not None
        return base + _distinct_rows_predict(self.forest_one_step_ if one_step else self.forest_, S)

    # -- streaming (deployment) ---------------------------------------------------------
    def stream_init(self, context=None) -> dict:
        check_is_fitted(self)
        return {"arx": self.arx_.stream_init(context), "door": None, "t0": None}

    def stream_step(self, x_row, state: dict, context: Mapping | None = None) -> tuple[float, dict]:
        """One sample of simulation-mode ``predict``.

        ``context`` maps ``'time'`` (s) and ``state_column`` to this sample's
        values (the extension of the streaming protocol for models that use a
        machine state; static-input models take ``x_row`` only).
        """
        y_arx, arx_state = self.arx_.stream_step(x_row, state["arx"], context)
        features, door, t0 = self._stream_features(context, 1, state, "ARX+RF stream_step")
        y_hat = float(y_arx + _one_row_predict(self.forest_, features[0]))
        return y_hat, {"arx": arx_state, "door": door, "t0": t0}

    def stream_steps(self, X, state: dict, context: Mapping | None = None) -> tuple[np.ndarray, dict]:
        """A block of rows (:func:`thermocomp.core.context.stream_steps`; ``context``: arrays of
        one value per row): the ARX's block, the forest once per distinct state feature row."""
        y_arx, arx_state = stream_steps(self.arx_, X, state["arx"], context)
        features, door, t0 = self._stream_features(context, len(y_arx), state, "ARX+RF stream_steps")
        return y_arx + self._forest_rows(features), {"arx": arx_state, "door": door, "t0": t0}

    def stream_branches(self, blocks, state: dict, context: Mapping | None = None) -> np.ndarray:
        """Blocks (b, n, p) each from the same state (:func:`thermocomp.core.context.stream_branches`):
        the state features read only the context, so the forest's part is the same for all."""
        blocks = np.asarray(blocks, dtype=float)
        features = self._stream_features(context, blocks.shape[1], state, "ARX+RF stream_branches")[0]
        forest = self._forest_rows(features)
        return stream_branches(self.arx_, blocks, state["arx"], context) + forest[None, :]

    def _forest_rows(self, features: np.ndarray) -> np.ndarray:
        """The forest on each row of ``features`` as :meth:`stream_step` walks it, once per distinct row."""
        rows, inverse = np.unique(features, axis=0, return_inverse=True)
        return np.array([_one_row_predict(self.forest_, r) for r in rows])[inverse.reshape(-1)]

    def _stream_features(self, context, n: int, state: dict, who: str) -> tuple[np.ndarray, object, object]:
        """The forest's features of ``n`` streamed rows (``context``: a sample's values or arrays
        of ``n``) and the door state ``(door, t0)`` after them: the smoothed door from its last change."""
        door, t0 = state["door"], state["t0"]
        if self.state_column is None:
            return np.zeros((n, 1)), door, t0
        taus = _taus(self.tau_s)
        value = np.broadcast_to(np.asarray(require(context, self.state_column, who), float), n)
        t = np.broadcast_to(np.asarray(require(context, TIME, who), float), n)
        out = np.empty((n, taus.size))
        for i in range(n):
            on = (door if door is not None else False) if np.isnan(value[i]) else bool(value[i] > 0.5)
            if door is not None and on != door:
                t0 = float(t[i])
            door = on
            out[i] = float(on) if t0 is None else expit((1.0 if on else -1.0) * (t[i] - t0) / taus)
        return out, door, t0
