"""The guard's gain for a model whose step gain needs a stream state (guard111).

The correction guard's bound follows the inputs past training by ``|gain| @ d``
(:meth:`.guard.CorrectionGuard.allowance`), the gain asked with no state
(:func:`.adaptive.input_gains`).  Some models have none there, and their row of 0 kept the bound
as trained while a hotter day's right correction was cut to it (bench_guard111):

* any model without an analytic gain (``lstm``; guard111b: any wrapper or blend holding one,
  ``arx_rf``): :func:`stepped_gain` reads it off the model: from each training campaign's last
  state (its hottest operating point), each input held one unit higher for the envelope's
  horizon; the largest |change| over those states, per input (guard111c: from the stream state,
  the prefix once, for a model that streams a block from a state; else its batch ``predict``);
* a diagnosed ``inputs_product`` (a state ``c`` times the inputs' rises): its gain is linear in
  the held ``c``; :func:`held_factor_gain` takes the largest |gain| at the ends of ``c``'s
  training range (the largest of a linear function on an interval is at an end).

Either is one fixed gain, carried by the exported code's ``GUARD_GAIN`` as any other.
"""

from __future__ import annotations

import itertools

import numpy as np
import pandas as pd

from ...core.context import (
    AMBIENT_C0,
    CAMPAIGN,
    TIME,
    groups_of,
    row_context,
    step_gain,
    stream_branches,
    stream_steps,
)


def held_factor_gain(est, context: pd.DataFrame | None, ambients, horizon_s: float) -> np.ndarray | None:
    """Largest |step gain| of a diagnosed model over its ``inputs_product`` states held at the
    ends of their training range (``context``: the training's stacked context), at each
    training ambient (``ambients``; none: A0 unknown); None without such a state or a gain."""
    ranges = getattr(est, "held_ranges", None)
    if not callable(ranges) or context is None:
        return None
    ends = ranges(context)
    if not ends:
        return None
    gains = []
    for values in itertools.product(*ends.values()):
        for a0 in (ambients if len(ambients) else [np.nan]):
            state = {"state_of": dict(zip(ends, values)), AMBIENT_C0: float(a0)}
            gain = step_gain(est, state, horizon_s)
            if gain is None:
                return None
            gains.append(np.abs(gain))
    return np.max(gains, axis=0)


def stepped_gain(est, X: np.ndarray, context: pd.DataFrame | None, horizon_s: float,
                 period_s: float) -> np.ndarray | None:
    """Largest |response| per input of ``est`` (any model with a batch ``predict(X, context)`` over
    campaigns) to a unit step held for ``horizon_s`` from each training campaign's last row (``X``:
    its training inputs as the model reads them, ``context``: their stacked context).  The one
    fallback of every model without an analytic gain (guard111b: an ATI or blend of lstm,
    ``arx_rf``, a diagnosed lstm had a row of 0).

    (guard111c) A model whose own ``stream_steps`` starts a block from a state streams each
    campaign's prefix once and holds the p + 1 steps from copies of its last state
    (:func:`_from_states`); any other re-predicts the prefix with every step (:func:`_by_predict`):
    the prefix was 25 of the lathe's 26 passes (per-interval lstm 3.2 -> 15.4 s CPU)."""
    if not callable(getattr(est, "predict", None)) or context is None or not len(X):
        return None
    X = np.asarray(X, dtype=float)
    groups = groups_of(context)
    groups = np.zeros(len(X)) if groups is None else groups
    ends = np.r_[np.flatnonzero(groups[1:] != groups[:-1]), len(X) - 1]
    starts = np.r_[0, ends[:-1] + 1]
    held = max(1, int(np.ceil(horizon_s / period_s)) if np.isfinite(horizon_s)
               else int(np.max(ends - starts + 1)))
    steps = np.vstack([np.zeros(X.shape[1]), np.eye(X.shape[1])])     # row 0: the inputs as they are
    last_of = _from_states if callable(getattr(est, "stream_steps", None)) else _by_predict
    last = last_of(est, X, context, zip(starts, ends), held, period_s, steps)
    gain = np.max(np.abs(last[:, 1:] - last[:, :1]), axis=0)
    return gain if np.isfinite(gain).all() else None


def _from_states(est, X, context, campaigns, held: int, period_s: float, steps) -> np.ndarray:
    """(campaigns, steps) last outputs: each campaign's prefix streamed once, then every held
    step from a copy of the state at its last row (one batch for a model that branches at once)."""
    cols = {c: context[c].to_numpy() for c in context.columns}
    out = []
    for s, e in campaigns:
        state = est.stream_init(row_context(cols, s, len(X)))
        state = stream_steps(est, X[s:e + 1], state, {c: v[s:e + 1] for c, v in cols.items()})[1]
        after = {c: np.full(held, v[e]) for c, v in cols.items()}     # the last row's, held
        if TIME in after:
            after[TIME] = float(cols[TIME][e]) + period_s * np.arange(1, held + 1)
        blocks = np.repeat((X[e] + steps)[:, None, :], held, axis=1)
        out.append(stream_branches(est, blocks, state, after)[:, -1])
    return np.asarray(out, dtype=float)


def _by_predict(est, X, context, campaigns, held: int, period_s: float, steps) -> np.ndarray:
    """(campaigns, steps) last outputs of one batch ``predict``: every campaign's prefix and a
    held step, each its own campaign (the stream's result to rounding)."""
    blocks, ctx = [], []
    for s, e in campaigns:
        for j, step in enumerate(steps):
            blocks.append(np.vstack([X[s:e + 1], np.tile(X[e] + step, (held, 1))]))
            rows = context.iloc[np.r_[np.arange(s, e + 1), np.full(held, e)]].reset_index(drop=True)
            rows = rows.assign(**{CAMPAIGN: f"step{s}:{j - 1}"})
            if TIME in rows:
                t = rows[TIME].to_numpy(float)
                rows[TIME] = np.r_[t[:e - s + 1], t[e - s] + period_s * np.arange(1, held + 1)]
            ctx.append(rows)
    y = np.asarray(est.predict(np.vstack(blocks), context=pd.concat(ctx, ignore_index=True)), float)
    return y[np.cumsum([len(b) for b in blocks]) - 1].reshape(-1, len(steps))
