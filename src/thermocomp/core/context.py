"""Side inputs: the one way per-row information besides ``X`` reaches an estimator.

Every estimator of thermocomp (model families, the ATI / augmented / ARX+RF
wrappers) has the signatures

* ``fit(X, y, context=None)`` and ``predict(X, context=None)`` -- batch;
* ``stream_init(context) -> state`` and ``stream_step(x_row, state, context)
  -> (y_hat, state)`` -- one sample at a time, causal, for deployment;
* optionally ``stream_steps(X, state, context) -> (y, state)``: a block of rows at once, equal
  to ``stream_step`` row after row to rounding (:func:`stream_steps`; a lead-in of a year is
  then one call, not 473,041);
* optionally ``step_gain(state, horizon_s) -> ndarray``: per input, the change of the
  prediction a unit step of that input held for ``horizon_s`` seconds makes (see
  :func:`step_gain`), for a model whose prediction is linear in its inputs; the training
  envelope takes the response to an input's excess over its bound out of the correction
  with it; a model whose gain the campaign's initial ambient switches splits it by that
  (``gain_terms``, :mod:`thermocomp.core.gains`), which the exported code carries per law.

``context`` is a DataFrame with one row per row of ``X`` (batch) or a mapping
for one sample (stream) with these columns, all optional:

``campaign``
    Campaign of the row: dynamics (lags, AR feedback, windows) never cross a
    campaign start.  Missing: the rows are one campaign.
``time``
    Seconds since the campaign start.
``ambient_c0``
    The campaign's initial absolute ambient temperature (°C), the key of
    ambient-interval models.
``y_measured``
    The measured target (one-step prediction only, ``eval.mode=one_step``).
``S_*``, ``T_*``
    Raw values of the campaign's machine states and sensors, for models that
    read a column outside their declared inputs (ARX+RF's door signal, the
    effects of a diagnosed model).

Callers always pass the whole context; an estimator reads what it needs and
says so after ``fit`` in ``context_columns_`` (the raw columns and the keys
``time``/``ambient_c0`` its *predictions* need), which wrappers forward, so a
deployment knows which columns to ask the machine for.  The context of a
batch is built by :func:`thermocomp.core.frame.stack`; the stream's rows by
:class:`thermocomp.core.frame.ContextBuilder`, the same rules.

The ``context`` parameter is requested by default under scikit-learn's
metadata routing (``__metadata_request__*``), so with
``sklearn.set_config(enable_metadata_routing=True)`` scikit-learn's own
cross-validation tools slice it per fold like ``X``.
"""

from __future__ import annotations

import copy
from collections.abc import Mapping

import numpy as np
import pandas as pd

from ..base.errors import ContractError

CAMPAIGN = "campaign"
TIME = "time"
AMBIENT_C0 = "ambient_c0"
Y_MEASURED = "y_measured"
RESERVED = (CAMPAIGN, TIME, AMBIENT_C0, Y_MEASURED)


def has(context, name: str) -> bool:
    """True when ``context`` (DataFrame, mapping or None) holds ``name``."""
    return context is not None and name in context


def groups_of(context) -> np.ndarray | None:
    """Campaign of each row (None: one campaign)."""
    return np.asarray(context[CAMPAIGN], dtype=object) if has(context, CAMPAIGN) else None


def values(context, name: str, n: int | None = None) -> np.ndarray | None:
    """Column ``name`` as a float array (None when absent)."""
    if not has(context, name):
        return None
    out = np.asarray(context[name], dtype=float)
    if n is not None and out.shape[0] != n:
        raise ValueError(f"context has {out.shape[0]} rows, X has {n}")
    return out


def require(context, name: str, who: str) -> np.ndarray:
    """Column ``name`` or a ContractError saying who needs it."""
    if not has(context, name):
        raise ContractError(f"{who} needs {name!r} in its context (a column of the campaigns the "
                            f"compensator hands to the model); it is missing", column=name)
    return np.asarray(context[name])


def subset(context, rows) -> pd.DataFrame | None:
    """The context of the rows ``rows`` (boolean mask or indices), index reset."""
    if context is None:
        return None
    return context.iloc[np.flatnonzero(rows) if np.asarray(rows).dtype == bool else rows] \
        .reset_index(drop=True)


def with_column(context, name: str, value, n: int) -> pd.DataFrame:
    """A copy of ``context`` (or a new one of ``n`` rows) with ``name`` set to ``value``."""
    out = pd.DataFrame(index=pd.RangeIndex(n)) if context is None else context.copy()
    out[name] = value
    return out


def scalar(context: Mapping | None, name: str, default=float("nan")) -> float:
    """One sample's value of ``name`` from a stream context mapping."""
    if context is None or name not in context:
        return default
    return float(context[name])


def context_columns(estimator) -> list[str]:
    """``context_columns_`` of a fitted estimator (``[]`` when it reads none)."""
    return list(getattr(estimator, "context_columns_", []))


def merge_columns(*lists) -> list[str]:
    """Union of column lists, first occurrence order."""
    return list(dict.fromkeys(c for cols in lists for c in cols))


def step_gain(estimator, state=None, horizon_s: float = np.inf) -> np.ndarray | None:
    """Step-response gain per input of ``estimator`` in stream ``state``: an input change
    ``dx`` held for ``horizon_s`` seconds (``inf``: until the steady state) has changed the
    prediction by ``gain @ dx``.  ``None`` when the estimator has none (not linear in its
    inputs, or an AR term without a steady state)."""
    method = getattr(estimator, "step_gain", None)
    if not callable(method):
        return None
    gain = method(state, horizon_s)
    return None if gain is None or not np.isfinite(gain).all() else np.asarray(gain, float)


def row_context(context: Mapping | None, i: int, n: int) -> dict | None:
    """Row ``i`` of a block's stream context (:func:`stream_steps`): an array of ``n`` values
    gives its ``i``-th, any other value (the campaign, ``ambient_c0``) is the row's as it is."""
    if context is None:
        return None
    return {k: v[i] if isinstance(v, np.ndarray) and v.ndim == 1 and len(v) == n else v
            for k, v in context.items()}


def stream_steps(estimator, X: np.ndarray, state, context: Mapping | None = None):
    """``(y, state)`` of the rows of ``X`` (n, p) streamed one after the other from ``state``:
    ``y`` (n,) the predictions ``stream_step`` gives, ``state`` the one after the last row.

    ``context`` maps each column to an array of ``n`` values (``time``, raw columns) or to one
    value for every row (``campaign``, ``ambient_c0``).  An estimator that defines
    ``stream_steps(X, state, context)`` computes the block in one go (its lag filters by
    :func:`scipy.signal.lfilter`, its feedback from the block's predictions), equal to the loop
    to rounding; any other is stepped row by row here (the one definition of the result)."""
    method = getattr(estimator, "stream_steps", None)
    if callable(method):
        return method(X, state, context)
    X = np.asarray(X, dtype=float)
    y = np.empty(len(X))
    for i in range(len(X)):
        y[i], state = estimator.stream_step(X[i], state, row_context(context, i, len(X)))
    return y, state


def stream_branches(estimator, blocks: np.ndarray, state, context: Mapping | None = None) -> np.ndarray:
    """``(b, n)`` outputs of each block of ``blocks`` (b, n, p) streamed from a copy of the same
    ``state`` with the same block ``context`` (:func:`stream_steps`'): branches of one history
    (the guard's held steps from a campaign's last row).  An estimator that defines
    ``stream_branches(blocks, state, context)`` computes them at once (a network: one batch);
    any other streams each block by :func:`stream_steps` from a deep copy (``state`` untouched)."""
    method = getattr(estimator, "stream_branches", None)
    if callable(method):
        return np.asarray(method(blocks, state, context), dtype=float)
    return np.stack([stream_steps(estimator, block, copy.deepcopy(state), context)[0] for block in blocks])


def between_steps(estimator, X: np.ndarray, context, stepped: np.ndarray) -> np.ndarray:
    """The batch's answer at the rows not ``stepped`` (between two rows of the training grid,
    :func:`thermocomp.core.timerule.grid_rows`), as the stream gives it (between73): the
    estimator's own step from the state its last stepped row committed, with the row's inputs
    and ``context`` (a DataFrame, one row per row of ``X``), that state kept.  The stepped rows
    of each campaign are streamed from ``stream_init`` at its first row (always stepped).
    Returns one value per row not stepped, in row order."""
    X = np.asarray(X, dtype=float)
    n = len(X)
    cols = {} if context is None else {c: context[c].to_numpy() for c in context.columns}
    groups = groups_of(context)
    start = np.r_[True, groups[1:] != groups[:-1]] if groups is not None and n \
        else np.r_[True, np.zeros(max(n - 1, 0), bool)]
    out, state, i = [], None, 0
    while i < n:
        if start[i]:      # a campaign's first row stepped alone, as the stream steps it
            ctx = row_context(cols, i, n)
            state = estimator.stream_step(X[i], estimator.stream_init(ctx), ctx)[1]
            i += 1
            continue
        if not stepped[i]:
            ctx = row_context(cols, i, n)
            out.append(estimator.stream_step(X[i], copy.deepcopy(state), ctx)[0])
            i += 1
            continue
        j = i + 1
        while j < n and stepped[j] and not start[j]:
            j += 1
        block = {k: v[i:j] for k, v in cols.items()}
        state = stream_steps(estimator, X[i:j], state, block)[1]
        i = j
    return np.asarray(out, dtype=float)


def keeps_memory(estimator, n_inputs: int) -> bool:
    """Whether a fitted estimator's stream carries a memory from sample to sample (a lag, a
    history, a feedback, a cell state): what the training grid paces (cadence72,
    :func:`thermocomp.core.timerule.on_grid`).  Asked of the stream itself: a ramp of four
    samples streamed answers otherwise than each sample from a fresh start (a static law, an
    ARX that kept no delay nor feedback, answer alike); a stream that cannot be asked without
    its raw columns counts as one with a memory (the safe side: held between grid rows)."""
    def at(i: int) -> dict:
        return {CAMPAIGN: "grid", TIME: 60.0 * i, AMBIENT_C0: 20.0}

    try:
        state = estimator.stream_init(at(0))
        for i in range(4):
            x = np.full(n_inputs, float(i))
            y, state = estimator.stream_step(x, state, at(i))
            alone, _ = estimator.stream_step(x, estimator.stream_init(at(i)), at(i))
            if not np.isclose(y, alone, rtol=1e-12, atol=1e-12):
                return True
    except Exception:  # noqa: BLE001
        return True
    return False


def feedback_gain(gain: np.ndarray, ar_coef: float) -> np.ndarray | None:
    """Steady-state gain of ``y(t) = a y(t-1) + gain . x``: ``gain / (1 - a)``, ``None`` when the
    feedback has no steady state (``|a| >= 1``)."""
    return np.asarray(gain, float) / (1.0 - ar_coef) if abs(ar_coef) < 1.0 else None


def for_target(estimator, target: str):
    """The estimator a model uses for ``target`` (per-target settings of a diagnosed model).

    An estimator with per-target parameters implements ``for_target(target)``
    returning an unfitted copy configured for that target; others are used as given.
    """
    method = getattr(estimator, "for_target", None)
    return method(target) if callable(method) else estimator


class SideInputs:
    """Mixin declaring the side-input protocol for scikit-learn metadata routing.

    ``context`` is requested by ``fit``, ``predict`` and ``score`` by default,
    and static models get a default streaming pair (one row through ``predict``).
    Put it first among the bases (its ``score`` routes the context).
    """

    __metadata_request__fit = {"context": True}
    __metadata_request__predict = {"context": True}
    __metadata_request__score = {"context": True}

    def score(self, X, y, sample_weight=None, context=None):
        """R² of ``predict(X, context=context)`` (scikit-learn's regressor score, routed context)."""
        from sklearn.metrics import r2_score

        return r2_score(y, self.predict(X, context=context), sample_weight=sample_weight)

    def stream_init(self, context: Mapping | None = None):
        """State before a campaign's first sample (static model: none)."""
        from sklearn.utils.validation import check_is_fitted

        check_is_fitted(self)
        return None

    def stream_step(self, x_row, state, context: Mapping | None = None):
        """One sample: ``(y_hat, state)``, equal to ``predict`` on that row."""
        x = np.asarray(x_row, dtype=float).reshape(1, -1)
        ctx = None if context is None else pd.DataFrame({k: [v] for k, v in context.items()})
        return float(np.asarray(self.predict(x, context=ctx)).ravel()[0]), state
