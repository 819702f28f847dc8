"""A fitted compensator as a causal, stateful, sample-by-sample process (pure core).

:class:`StreamingCompensator` wraps a fitted :class:`~thermocomp.compensator.Compensator`
for the machine side.  It sees one sample (or a block of consecutive samples)
at a time, in time order, and keeps between calls everything it needs, in the
order :meth:`Compensator.predict` applies it:

1. the state of the **causal denoiser** (``denoiser_``, streamed on the raw
   declared inputs, as the Compensator denoises before referencing);
2. the **reference frame**: the first sample after :meth:`~StreamingCompensator.reset`
   is the campaign's first sample; later ``T_`` inputs are taken relative to it
   (``data.reference=first_sample``), as the machinist zeroes the error when
   setting up a workpiece; its ambient reading is ``ambient_c0`` (ATI models);
3. the **training envelope** check (clamp / refuse / off);
4. the state of every **model with memory**: ARX uses its own past
   predictions, never a measured error.

Models with memory implement the streaming protocol ``stream_init() -> state``
(ATI: ``stream_init(ambient_c0=...)``) and ``stream_step(x_row, state) ->
(y_hat, state)``; a model using a machine state outside its inputs (ARX+RF's
door) takes ``context={'time': t, <state_column>: value}`` per sample.  Static
models don't implement it and are evaluated on whole blocks.
"""

from __future__ import annotations

import inspect
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..compensator import Compensator
from ..denoise import denoise_campaigns
from ..frame import stack
from ..metrics import split_scores

POLICIES = ("clamp", "refuse", "off")
STREAM_ID = "stream"


class OutOfEnvelopeError(ValueError):
    """An input left the training envelope under ``policy='refuse'``, or is missing."""


def _accepts(method, name: str) -> bool:
    return name in inspect.signature(method).parameters


def has_stream_protocol(obj) -> bool:
    """True when ``obj`` implements ``stream_init``/``stream_step`` (a model with memory)."""
    return callable(getattr(obj, "stream_init", None)) and callable(getattr(obj, "stream_step", None))


def _is_ambient(column: str) -> bool:
    return column == "T_amb" or column.startswith("T_amb_")


def _needs_ambient(est) -> bool:
    init = getattr(est, "stream_init", None)
    if init is not None and (_accepts(init, "ambient_c0") or _accepts(init, "context")):
        return True
    return init is None and _accepts(est.predict, "context")


def _state_columns(est) -> list[str]:
    """Raw columns a model reads from ``context``: ARX+RF's ``state_column``, and the
    ``required_context_`` of a diagnosed model (:class:`thermocomp.diagnose.AugmentedRegressor`)."""
    col = getattr(est, "state_column", None)
    cols = [col] if isinstance(col, str) else []
    return cols + [c for c in getattr(est, "required_context_", []) if c not in cols]


@dataclass(frozen=True)
class Envelope:
    """Per-input bounds ``[lo, hi]`` of the training data, in the frame the model sees.

    Built by :meth:`from_data` from the training matrix widened by ``margin`` ×
    range on each side (a constant column by ``margin`` × max(|value|, 1)).
    """

    columns: tuple[str, ...]
    lo: np.ndarray
    hi: np.ndarray
    margin: float = 0.0

    @classmethod
    def from_data(cls, X: pd.DataFrame, margin: float = 0.1) -> "Envelope":
        if margin < 0:
            raise ValueError(f"envelope margin must be >= 0, got {margin}")
        lo, hi = X.min().to_numpy(float), X.max().to_numpy(float)
        width = np.where(hi > lo, hi - lo, np.maximum(np.abs(hi), 1.0))
        return cls(tuple(X.columns), lo - margin * width, hi + margin * width, margin)

    def outside(self, X: np.ndarray) -> np.ndarray:
        """Boolean mask of values outside the bounds (same shape as ``X``)."""
        return (X < self.lo) | (X > self.hi)


class StreamingCompensator:
    """Causal, stateful compensator for streaming use on the machine.

    Parameters
    ----------
    compensator : fitted Compensator
    envelope : Envelope, optional
        Bounds of the declared inputs (order of ``compensator.inputs_``) in the
        model's frame; ``None`` disables the check.  See :meth:`from_training`.
    policy : {'clamp', 'refuse', 'off'}
        An input outside the envelope is clamped to the bound (and counted in
        ``n_clamped``), refused with :class:`OutOfEnvelopeError`, or passed as is.
    ambient_columns : list of str, optional
        Absolute ambient sensors whose first-sample mean is ``ambient_c0``
        (default: the ``T_amb*`` declared inputs).

    Attributes
    ----------
    columns_ : list of str
        Columns every call needs (the pyfunc signature): declared inputs, extra
        ambient sensors, machine states read through ``context``; plus ``time``
        when ``time_required_``.
    targets_ : list of str
    n_samples_ : int
        Samples streamed since the last reset.

    Notes
    -----
    Each call continues the stream; :meth:`reset` starts a new campaign and the
    next sample becomes its reference.  Prediction is always in simulation
    mode: no measured error ever enters.
    """

    def __init__(self, compensator: Compensator, envelope: Envelope | None = None,
                 policy: str = "clamp", ambient_columns=None):
        if not hasattr(compensator, "estimators_"):
            raise ValueError("the compensator is not fitted; fit it before deploying")
        if policy not in POLICIES:
            raise ValueError(f"envelope policy must be one of {POLICIES}, got {policy!r}")
        self.compensator, self.envelope, self.policy = compensator, envelope, policy
        inputs = list(compensator.inputs_)
        if envelope is not None and list(envelope.columns) != inputs:
            raise ValueError(f"envelope columns {list(envelope.columns)} != model inputs {inputs}")
        ests = compensator.estimators_
        self.targets_ = list(compensator.targets_)
        self.ambient_columns = (list(ambient_columns) if ambient_columns is not None
                                else [c for c in inputs if _is_ambient(c)])
        self._stream = {t: has_stream_protocol(e) for t, e in ests.items()}
        self._ctx = {t: self._stream[t] and _accepts(e.stream_step, "context") for t, e in ests.items()}
        state_cols = [c for t, e in ests.items() if self._ctx[t] or not self._stream[t]
                      for c in _state_columns(e)]
        self.state_columns = [c for c in dict.fromkeys(state_cols) if c not in inputs]
        extra = [c for c in self.ambient_columns if c not in inputs]
        self.columns_ = inputs + extra + self.state_columns
        # Raw columns handed to models through ``context`` (may include declared inputs).
        self.context_columns = list(dict.fromkeys(state_cols))
        self.time_required_ = any(self._ctx.values())
        self._n_inputs, self._n_checked = len(inputs), len(inputs) + len(extra)
        self._amb_idx = [self.columns_.index(c) for c in self.ambient_columns]
        referenced = compensator.reference == "first_sample"
        self._is_ref = np.array([referenced and c.startswith("T_") for c in inputs])
        self._idx = {t: [inputs.index(c) for c in compensator.selected_[t]] for t in self.targets_}
        # step(): per target (estimator, input index or None for all inputs in order, streams, context)
        self._plan = [(ests[t], None if self._idx[t] == list(range(len(inputs)))
                       else np.asarray(self._idx[t]), self._stream[t], self._ctx[t])
                      for t in self.targets_]
        self._context_idx = [self.columns_.index(c) for c in self.context_columns]
        self.denoiser = getattr(compensator, "denoiser_", None)
        if self.denoiser is not None:
            if not has_stream_protocol(self.denoiser):
                raise ValueError(f"denoiser {type(self.denoiser).__name__} has no causal streaming "
                                 "mode (stream_init/stream_step): it cannot run on a machine")
            if not getattr(self.denoiser, "online", True):
                raise ValueError("the model was fitted and scored with offline denoising "
                                 "(online=false), which needs future samples; refit with the "
                                 "causal (online) denoiser to deploy it")
            names = list(getattr(self.denoiser, "feature_names_in_", inputs))
            if names != inputs:
                raise ValueError(f"the denoiser was fitted on {names}, the model's inputs are {inputs}")
        self.reset()

    @classmethod
    def from_training(cls, compensator: Compensator, campaigns: Mapping[str, pd.DataFrame],
                      margin: float = 0.1, policy: str = "clamp") -> "StreamingCompensator":
        """Envelope from the training campaigns, in the frame the model sees.

        Ambient sensors that are not declared inputs are added to the input
        columns when a model needs the initial ambient temperature (ATI).
        """
        den = getattr(compensator, "denoiser_", None)
        seen = denoise_campaigns(den, campaigns) if den is not None else campaigns
        m = stack(seen, compensator.inputs_, compensator.targets_, compensator.reference)
        ambient = None
        if any(_needs_ambient(e) for e in compensator.estimators_.values()):
            cols = dict.fromkeys(c for df in campaigns.values() for c in df.columns)
            ambient = [c for c in cols if _is_ambient(c)]
        return cls(compensator, Envelope.from_data(m.X, margin), policy, ambient)

    # -- state ------------------------------------------------------------------------------

    def reset(self) -> None:
        """Start a new campaign: the next sample is the reference, every memory is cleared."""
        self._ref = None
        self._ambient_c0 = float("nan")
        self._states: dict = {}
        self._den_state = None
        self.n_samples_ = 0

    def _init_states(self, ambient_c0: float) -> dict:
        states = {}
        for t, est in self.compensator.estimators_.items():
            if not self._stream[t]:
                continue
            if _accepts(est.stream_init, "ambient_c0"):
                states[t] = est.stream_init(ambient_c0=ambient_c0)
            elif _accepts(est.stream_init, "context"):
                states[t] = est.stream_init(context={"campaign": STREAM_ID, "ambient_c0": ambient_c0})
            else:
                states[t] = est.stream_init()
        return states

    # -- input ------------------------------------------------------------------------------

    def _matrix(self, frame: pd.DataFrame) -> np.ndarray:
        need = self.columns_ + (["time"] if self.time_required_ else [])
        missing = [c for c in need if c not in frame.columns]
        if missing:
            raise OutOfEnvelopeError(f"input lacks column(s) {missing} (need {need})")
        X = np.column_stack([frame[c].to_numpy(dtype=float) for c in self.columns_])
        bad = ~np.isfinite(X[:, :self._n_checked])
        if bad.any():
            i, j = np.argwhere(bad)[0]
            raise OutOfEnvelopeError(f"input {self.columns_[j]} has no finite value at row "
                                     f"{self.n_samples_ + i} (sensor dropout?)")
        return X

    def _apply_envelope(self, dX: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        clamps = np.zeros(len(dX), dtype=np.int64)
        if self.envelope is None or self.policy == "off":
            return dX, clamps
        out = self.envelope.outside(dX)
        if not out.any():
            return dX, clamps
        if self.policy == "refuse":
            i, j = np.argwhere(out)[0]
            frame = " (change since the first sample)" if self._is_ref[j] else ""
            raise OutOfEnvelopeError(
                f"input {self.columns_[j]} = {dX[i, j]:.4g}{frame} at row {self.n_samples_ + i} is "
                f"outside the training envelope [{self.envelope.lo[j]:.4g}, "
                f"{self.envelope.hi[j]:.4g}]; refused (policy=refuse)")
        return np.clip(dX, self.envelope.lo, self.envelope.hi), out.sum(axis=1)

    # -- prediction -------------------------------------------------------------------------

    def predict(self, frame: pd.DataFrame) -> pd.DataFrame:
        """Predicted error (µm, one column per target) for consecutive samples of the stream,
        and ``n_clamped`` (inputs of the row clamped to the envelope).

        The state advances only when the whole block is accepted.
        """
        X = self._matrix(frame)
        n = len(X)
        y = np.empty((n, len(self.targets_)))
        if n == 0:
            return self._frame(y, np.zeros(0, dtype=np.int64))
        # Work on copies: a refused block or a failing model leaves the stream as it was.
        seen = X.copy()
        den_state = self._den_state
        if self.denoiser is not None:
            if self._ref is None:
                den_state = self.denoiser.stream_init()
            for i in range(n):
                row, den_state = self.denoiser.stream_step(X[i, :self._n_inputs], den_state)
                seen[i, :self._n_inputs] = row
        ref, ambient_c0, states = self._ref, self._ambient_c0, dict(self._states)
        if ref is None:
            ref = np.where(self._is_ref, seen[0, :self._n_inputs], 0.0)
            amb = seen[0, self._amb_idx]
            ambient_c0 = float(amb.mean()) if amb.size else float("nan")
            states = self._init_states(ambient_c0)
        dX, clamps = self._apply_envelope(seen[:, :self._n_inputs] - ref)
        time = frame["time"].to_numpy(float) if "time" in frame.columns else np.full(n, np.nan)
        for k, (t, est) in enumerate(self.compensator.estimators_.items()):
            Xt = dX[:, self._idx[t]]
            if not self._stream[t]:
                y[:, k] = est.predict(Xt, **self._side(est.predict, n, time, X, ambient_c0))
                continue
            st = states[t]
            if self._ctx[t]:
                ctx = self._row_context(time, X)
                for i in range(n):
                    y[i, k], st = est.stream_step(Xt[i], st, context=ctx[i])
            else:
                for i in range(n):
                    y[i, k], st = est.stream_step(Xt[i], st)
            states[t] = st
        self._ref, self._ambient_c0, self._states, self._den_state = ref, ambient_c0, states, den_state
        self.n_samples_ += n
        return self._frame(y, clamps)

    def step(self, x_row, time: float = float("nan")) -> np.ndarray:
        """One sample (values in the order of ``columns_``) -> predicted error per target.

        The low-latency path for a CNC loop: no DataFrame, one array in, one out;
        same result as :meth:`predict` on that row.
        """
        x = np.asarray(x_row, dtype=float)
        checked = x[:self._n_checked]
        if not np.isfinite(checked.sum()):          # one reduction instead of a mask
            j = int(np.flatnonzero(~np.isfinite(checked))[0])
            raise OutOfEnvelopeError(f"input {self.columns_[j]} has no finite value at row "
                                     f"{self.n_samples_}")
        seen = x[:self._n_inputs]
        first = self._ref is None
        if self.denoiser is not None:
            seen, self._den_state = self.denoiser.stream_step(
                seen, self.denoiser.stream_init() if first else self._den_state)
            seen = np.asarray(seen, float)
        if first:
            self._ref = np.where(self._is_ref, seen, 0.0)
            amb = np.concatenate([seen, x[self._n_inputs:]])[self._amb_idx]
            self._ambient_c0 = float(amb.mean()) if amb.size else float("nan")
            self._states = self._init_states(self._ambient_c0)
        dx = seen - self._ref
        env = self.envelope
        if env is not None and self.policy != "off" and (
                (dx < env.lo).any() or (dx > env.hi).any()):
            if self.policy == "refuse":
                self._apply_envelope(dx[None, :])       # raises with the column and bounds
            dx = np.minimum(np.maximum(dx, env.lo), env.hi)
        y = np.empty(len(self._plan))
        states = self._states
        for k, (est, idx, streams, ctx) in enumerate(self._plan):
            xt = dx if idx is None else dx[idx]
            t = self.targets_[k]
            if streams:
                if ctx:
                    context = {"time": time, **{c: x[j] for c, j in
                                                zip(self.context_columns, self._context_idx)}}
                    y[k], states[t] = est.stream_step(xt, states[t], context=context)
                else:
                    y[k], states[t] = est.stream_step(xt, states[t])
            else:
                side = self._side(est.predict, 1, np.array([time]), x[None, :], self._ambient_c0)
                y[k] = est.predict(xt[None, :], **side)[0]
        self.n_samples_ += 1
        return y

    def _row_context(self, time: np.ndarray, X: np.ndarray) -> list[dict]:
        cols = {c: X[:, j] for c, j in zip(self.context_columns, self._context_idx)}
        for c in self.columns_[:self._n_inputs]:
            if c.startswith("S_"):
                cols.setdefault(c, X[:, self.columns_.index(c)])
        return [{"time": time[i], **{c: v[i] for c, v in cols.items()}} for i in range(len(time))]

    def _side(self, method, n: int, time: np.ndarray, X: np.ndarray, ambient_c0: float) -> dict:
        side = {}
        if _accepts(method, "groups"):
            side["groups"] = np.full(n, STREAM_ID, dtype=object)
        if _accepts(method, "context"):
            ctx = {"campaign": np.full(n, STREAM_ID, dtype=object), "time": time,
                   "ambient_c0": np.full(n, ambient_c0)}
            ctx.update({c: X[:, j] for j, c in enumerate(self.columns_) if c.startswith("S_")})
            side["context"] = pd.DataFrame(ctx)
        return side

    def _frame(self, y: np.ndarray, clamps: np.ndarray) -> pd.DataFrame:
        out = pd.DataFrame(y, columns=self.targets_)
        out["n_clamped"] = clamps
        return out


def replay(streaming: StreamingCompensator, campaign: pd.DataFrame, chunk: int | None = None
           ) -> pd.DataFrame:
    """Stream one whole campaign from a reset, in blocks of ``chunk`` samples (all at once if None)."""
    streaming.reset()
    step = chunk or max(len(campaign), 1)
    parts = [streaming.predict(campaign.iloc[i:i + step]) for i in range(0, len(campaign), step)]
    return pd.concat(parts, ignore_index=True)


def streaming_deviation(streaming: StreamingCompensator, campaign: pd.DataFrame,
                        chunk: int = 7) -> float:
    """Largest |streamed - batch| prediction (µm) over one campaign.

    Batch is :meth:`Compensator.predict` in simulation mode; streaming feeds the
    campaign in blocks of ``chunk`` samples, envelope off.  A model with memory
    that lacks the streaming protocol, or breaks causality, shows up here.
    """
    saved = streaming.policy
    streaming.policy = "off"
    try:
        streamed = replay(streaming, campaign, chunk)
    finally:
        streaming.policy = saved
        streaming.reset()
    batch = streaming.compensator.predict({STREAM_ID: campaign})[STREAM_ID]
    diff = streamed[streaming.targets_].to_numpy() - batch[streaming.targets_].to_numpy()
    return float(np.max(np.abs(diff))) if diff.size else 0.0


def stream_scores(streaming: StreamingCompensator, campaigns: Mapping[str, pd.DataFrame],
                  sample_period_s: float, statistic: str = "range", points: int | None = 200
                  ) -> dict:
    """Test figures of the *deployed* predictions, in the layout of ``metrics.json``.

    Each campaign is streamed from a reset, as on the machine; returns
    ``{target: {"test": {...}}}`` (see :func:`thermocomp.metrics.split_scores`).
    """
    measured = streaming.compensator.measured(campaigns)
    predicted = {c: replay(streaming, df) for c, df in campaigns.items()}
    streaming.reset()
    out = {}
    for t in streaming.targets_:
        y = {c: measured[c][t].to_numpy() for c in campaigns}
        r = {c: y[c] - predicted[c][t].to_numpy() for c in campaigns}
        out[t] = {"test": split_scores(y, r, sample_period_s, statistic, points)}
    return out
