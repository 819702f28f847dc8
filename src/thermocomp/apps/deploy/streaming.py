"""A fitted compensator as a causal, stateful, sample-by-sample process (pure core).

:class:`StreamingCompensator` wraps a fitted :class:`~thermocomp.core.compensator.Compensator`
for the machine side.  It sees one sample at a time (or a block of consecutive
samples, streamed row by row), in time order, and keeps between calls
everything it needs, in the order :meth:`Compensator.predict` applies it:

1. the state of the **causal denoiser** (``denoiser_``, streamed on the raw
   declared inputs, as the Compensator denoises before referencing);
2. the **reference frame**: the first sample after :meth:`~StreamingCompensator.reset`
   is the campaign's first sample; later ``T_`` inputs are taken relative to it
   (``data.reference=first_sample``), as the machinist zeroes the error when
   setting up a workpiece; its ambient reading is ``ambient_c0`` (ATI models);
3. the **training envelope** check (clamp / refuse / off);
4. the state of every **model**, through the one streaming protocol of
   :mod:`thermocomp.core.context` (``stream_init(context)``, ``stream_step(x_row,
   state, context)``): ARX uses its own past predictions, never a measured
   error; wrappers forward it to the models they hold.

The clamp takes out of the prediction the model's response to the excess ``e`` of an input
over its bound, ``y(x) - y(clamp(x))``, but never more than the response to that excess held
for the longest training campaign, ``|gain @ e|`` (:func:`thermocomp.core.context.step_gain` at
``Envelope.horizon_s``): from the campaign's first excess on, each model is streamed on the
inputs as measured and on the clamped ones.  For a static model, or an input far out, this is
the prediction on the clamped inputs; a lag model's dynamics run on the measured signal, so
that the transients a flattened input injects into its lags are not passed on beyond what
the excess itself is worth (a lag bank's opposed weights on several time constants no longer
cancel on a flattened input: a spindle record whose ambient left its range by 0.1 °C was
deployed at 1.44 µm against 0.218 scored).  The horizon, not the steady state: no training
record shows a lag longer than itself, and a lag bank's level coefficients alone are then a
split the ridge made at will.  Taking the held response out alone (no clamped stream)
reversed the correction for hours after a sudden far excursion (-145 µm after a +40 K step
where the model's own response had barely begun).  Back in range after an excess, the bound
is the excess's last sample's (0 before the campaign's first): an excess that fades out ends
with a bound near 0 and the correction is the model's own again, as scored; one that ends at
once, which no temperature does (a one-row spike, a sensor's offset gone), keeps its bound,
so that what it left in the lags and the AR feedback is taken out as it decays (with the
sample's own bound, 0 in range, a one-row +50 °C spike on a ``yearround_spindle`` motor
sensor stayed in a lag bank's correction to the campaign's end: 261 µm the next row, 9 at
the end; now 41 and 1.4, the memory of the reading at the envelope's edge, which the clamp
gives for it; benchmarks/bench_deploy_faults.py).  The pattern gate ends an excess at once too
(a sample back on the training pattern): on the real excursions of
benchmarks/bench_envelope_policy.py a lag bank's Σ² moved by -0.3 % to +1.5 %, MLR's and ARX's
not at all.  A model without a step gain (LSTM,
ARX+RF, a blend or a diagnosed model around one) is streamed on the clamped inputs alone; a
diagnosed model's gain is its base's through its features (clampdiag60:
:meth:`~thermocomp.apps.diagnose.AugmentedRegressor.step_gain`; a low-pass copy of the inputs
over any linear base, gain61), split by what the campaign's initial ambient switches the way the
exported code's laws are (:mod:`thermocomp.core.gains`: the code asks the model the same).

:meth:`StreamingCompensator.run_rows` streams a block of rows as :meth:`~StreamingCompensator._step`
does row by row, the rows it takes as they are (in the envelope or along its pattern, finite, in
time order, no clamped stream yet) through each model in one go
(:func:`thermocomp.core.context.stream_steps`): :func:`warm` on a year's lead-in of 473,041 rows
(replay 60.8 s of CPU, 29.3 s so; benchmarks/bench_scale58.py, warm59).

The per-sample context is built by :func:`thermocomp.core.frame.context_record`,
the rule :func:`thermocomp.core.frame.stack` applies to a whole batch; the columns
it carries are what the fitted estimators declare in ``context_columns_``.
"""

from __future__ import annotations

import copy
import logging
from collections.abc import Mapping
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ...core.compensator import Compensator
from ...core.context import (
    AMBIENT_C0,
    RESERVED,
    TIME,
    context_columns,
    merge_columns,
    step_gain,
    stream_steps,
)
from ...core.continuation import campaign_period
from ...core.frame import ambient_c0, context_record
from ...core.guarded import mark_guarded, summed_frames
from ...core.io.contract import is_ambient, manifest_ambient
from ...core.io.own_headers import as_named
from ...core.io.values import MAX_ABS_T_C, reading_limit
from ...core.metrics import split_scores
from ...core.timerule import SampleClock, on_grid
from .guard import guard_changes

log = logging.getLogger(__name__)
POLICIES = ("clamp", "refuse", "off")
STREAM_ID = "stream"


class OutOfEnvelopeError(ValueError):
    """An input left the training envelope under ``policy='refuse'``, or is missing."""


class MissingValueError(OutOfEnvelopeError):
    """An input has no finite value (a sensor dropout): the row is refused, the state untouched."""


def has_stream_protocol(obj) -> bool:
    """True when ``obj`` implements ``stream_init``/``stream_step``."""
    return callable(getattr(obj, "stream_init", None)) and callable(getattr(obj, "stream_step", None))


@dataclass(frozen=True)
class Envelope:
    """Per-input bounds ``[lo, hi]`` of the training data, in the frame the model sees, and
    its ``horizon_s``: the longest training campaign (s; ``inf`` when unknown), for how long
    the clamp takes an excess over a bound to have been held (module doc).

    Built by :meth:`from_data` from the training matrix widened by ``margin`` ×
    range on each side (a constant column by ``margin`` × max(|value|, 1)).

    The training *pattern* (``pattern=True``): the clamp acts only on a sample that leaves it
    (:meth:`leaves_pattern`), so that a machine running hotter along the way its sensors moved
    together in training is streamed as ``run`` scores it, while an unseen heat source that
    moves them apart is clamped (benchmarks/bench_envelope_policy.py: Σ² pooled 905 against
    1300 with every excursion clamped on hotter tests, 13168 against 13156 on unseen sources).
    ``mean`` (training mean), ``scale`` (the training widths, before the margin: max(|value|, 1)
    for a constant input; the gate does not depend on the margin), ``basis`` (orthonormal
    columns: the principal subspace of the scaled, centred training inputs holding
    ``PATTERN_ENERGY`` of their variance) and ``tol`` (the largest residual of a training
    sample off it).  ``basis`` is None (every excursion clamped) when
    the pattern is off, in older pickles, and where the subspace is the whole input space (one
    input; inputs that training moved independently): no sample could leave it, so the gate
    would pass a sensor 30 K out as readily as a hotter machine; there the clamp acts on every
    excursion as before (the spindle workbook's three sensors: lagbank 0.373 µm² clamped
    against 0.048 scored, the price of that safety).
    """

    columns: tuple[str, ...]
    lo: np.ndarray
    hi: np.ndarray
    margin: float = 0.0
    horizon_s: float = float("inf")      # older pickles have none: the steady state
    mean: np.ndarray | None = None       # the training pattern (older pickles: none)
    scale: np.ndarray | None = None
    basis: np.ndarray | None = None
    tol: float = float("inf")

    @classmethod
    def from_data(cls, X: pd.DataFrame, margin: float = 0.1,
                  horizon_s: float = float("inf"), pattern: bool = True) -> "Envelope":
        if margin < 0:
            raise ValueError(f"envelope margin must be >= 0, got {margin}")
        lo, hi = X.min().to_numpy(float), X.max().to_numpy(float)
        # the training widths: what the margin is a fraction of, and the pattern's scale
        width = np.where(hi > lo, hi - lo, np.maximum(np.abs(hi), 1.0))
        lo, hi = lo - margin * width, hi + margin * width
        shape = _pattern(X.to_numpy(float), width) if pattern else {}
        return cls(tuple(X.columns), lo, hi, margin, float(horizon_s), **shape)

    def outside(self, X: np.ndarray) -> np.ndarray:
        """Boolean mask of values outside the bounds (same shape as ``X``)."""
        return (X < self.lo) | (X > self.hi)

    def excess(self, x: np.ndarray) -> np.ndarray:
        """The excess of the sample ``x`` (model frame) over the bounds, ``x - clip(x, lo, hi)``:
        the part the clamp acts on, zero within them and everywhere when ``x`` stays on the
        training pattern (:meth:`leaves_pattern`); the stream's and the exported code's."""
        e = x - np.minimum(np.maximum(x, self.lo), self.hi)
        return e if e.any() and self.leaves_pattern(x) else np.zeros_like(e)

    def leaves_pattern(self, x: np.ndarray) -> bool:
        """True when the sample ``x`` (model frame) is off the training pattern: its scaled,
        centred residual off ``basis`` exceeds ``tol`` (squared: the exported code has no
        square root); always True without a pattern (today's clamp of every excursion)."""
        if self.basis is None:
            return True
        z = (x - self.mean) / self.scale
        r = z - self.basis @ (self.basis.T @ z)
        return float(r @ r) > self.tol * self.tol


PATTERN_ENERGY = 0.999     # fixed before any measurement (bench_envelope_policy), never tuned
# a residual whose consecutive samples correlate less than this is white (white_targets): chosen on
# seen column records between the two groups their targets form (0.06-0.41 against 0.64-0.99)
WHITE_LAG1 = 0.5


def white_targets(compensator: Compensator, campaigns: Mapping[str, pd.DataFrame]) -> tuple:
    """The targets whose training residual is white: the measured error less the model's
    simulation on ``campaigns``, its lag-1 autocorrelation over consecutive samples within a
    campaign below :data:`WHITE_LAG1`; none where the campaigns do not carry every target.

    Such a model leaves nothing an unmeasured heat path would explain: its target's physics lies
    in the sensors (a column's E_X, left face against right, both measured), and it carries a
    source training never saw on as the physics does (the Q3 part of E_X predicted with slope
    0.98 on 19 column seeds), so the clamp would only freeze a true extrapolation.  A residual
    that keeps structure (E_Y, E_Z: the unmeasured back face and base, stood in for by sensors
    that follow them only in the training field) marks a model a new source misleads: clamped
    (benchmarks/bench_env93.py).
    """
    targets = list(compensator.targets_)
    if not all(t in df.columns for df in campaigns.values() for t in targets):
        return ()
    predicted = compensator.predict(campaigns)
    measured = compensator.measured(campaigns, predicted)
    # consecutive residuals (lag 1) within each campaign, pooled
    pairs = [(r[:-1], r[1:]) for r in (measured[cid][targets].to_numpy(float)
                                       - predicted[cid][targets].to_numpy(float) for cid in campaigns)]
    before, after = np.vstack([p[0] for p in pairs]), np.vstack([p[1] for p in pairs])
    out = []
    for k, t in enumerate(targets):
        a, b = before[:, k], after[:, k]
        ok = np.isfinite(a) & np.isfinite(b)
        if ok.sum() > 2 and np.std(a[ok]) > 0 and np.std(b[ok]) > 0 and \
                np.corrcoef(a[ok], b[ok])[0, 1] < WHITE_LAG1:
            out.append(t)
    return tuple(out)


def spread_excess(excess: np.ndarray | None) -> bool:
    """True when the sample's excess over the envelope (:meth:`Envelope.excess`) is shared by at
    least two inputs: what a heat source makes (it warms the sensors around it together), not one
    sensor alone (a drift, a jump, a sensor's own fault), for which a white target is clamped
    again (benchmarks/bench_env94.py: a +1 K/h drift of one sensor left unclamped cost up to
    1.60x the deployed Σ² of the shared clamp, env93b)."""
    return excess is not None and int(np.count_nonzero(excess)) >= 2


def _pattern(X: np.ndarray, scale: np.ndarray) -> dict:
    """``{mean, scale, basis, tol}`` of the training inputs ``X`` (:class:`Envelope`)."""
    mean = X.mean(axis=0)
    Z = (X - mean) / scale
    _, S, Vt = np.linalg.svd(Z, full_matrices=False)
    energy = S ** 2
    if not energy.sum() > 0:
        return {}
    rank = int(np.searchsorted(np.cumsum(energy) / energy.sum(), PATTERN_ENERGY) + 1)
    if rank >= X.shape[1]:      # every direction is the pattern: no gate (class doc)
        return {}
    basis = Vt[:rank].T
    tol = float(np.linalg.norm(Z - Z @ basis @ basis.T, axis=1).max())
    return {"mean": mean, "scale": scale, "basis": basis, "tol": tol}


def step_block(deployed, X: np.ndarray, time: np.ndarray, after_row=None) -> tuple[np.ndarray, np.ndarray]:
    """``(predictions, n_clamped)`` of ``deployed._step`` over the rows of ``X``, all or nothing:
    a row that raises restores the state the block found (a refused block leaves a stream where
    it was); ``after_row()`` runs after each accepted row."""
    y = np.empty((len(X), len(deployed.targets_)))
    clamps = np.zeros(len(X), dtype=np.int64)
    snap = deployed._snapshot()
    try:
        for i in range(len(X)):
            y[i], clamps[i] = deployed._step(X[i], time[i])
            if after_row is not None:
                after_row()
    except Exception:
        deployed._restore(snap)
        raise
    return y, clamps


def grid_times(saved) -> tuple[float, float]:
    """A stream's grid state as it keeps it: ``(the last stepped row's time, the last row's)``.
    A state saved before deploy74 held the last stepped row's output too, unread since
    between73 (whether a row was stepped its time says): dropped, so such a state (an end state
    in a registered model, a served session, a pickled stream) still restores."""
    return float(saved[0]), float(saved[1])


def lag_period(estimators) -> float | None:
    """The training sample period the models keep for their lags (a lag bank's, a Hammerstein
    model's lag bank's, a diagnosed model's): a sample without time is one period after the
    previous one; None where no model keeps one."""
    for est in estimators:
        period = getattr(getattr(est, "lagbank_", est), "sample_period_s_", None)
        if period:
            return float(period)
    return None


class StreamingCompensator:
    """Causal, stateful compensator for streaming use on the machine.

    Parameters
    ----------
    compensator : fitted Compensator
    envelope : Envelope, optional
        Bounds of the declared inputs (order of ``compensator.inputs_``) in the
        model's frame; ``None`` disables the check.  See :meth:`from_training`.
    policy : {'clamp', 'refuse', 'off'}
        An input outside the envelope is clamped where the sample leaves the training
        pattern (:class:`Envelope`; counted in ``n_clamped``; the models'
        response to its excess over the bound is taken out of the prediction, within the
        response to the excess held, see the module doc), refused with
        :class:`OutOfEnvelopeError`, or passed as is.
    ambient_columns : list of str, optional
        Absolute ambient sensors whose first-sample mean is ``ambient_c0``
        (default: the ``T_amb*`` declared inputs).  With none, a model that needs
        ``ambient_c0`` (ATI) takes the campaign's ambient given to :meth:`reset`
        (``ambient_given_``), as the batch takes the manifest's ``ambient_c``.

    Attributes
    ----------
    columns_ : list of str
        Columns every call needs (the pyfunc signature): declared inputs, extra
        ambient sensors, raw columns the models read from their context; plus
        ``time`` when ``time_required_``.
    targets_ : list of str
    n_samples_ : int
        Samples streamed since the last reset.

    lab_names_ : dict
        ``{contract name: the lab's name}`` of the columns (``data.columns``): the served
        model reads either (:mod:`thermocomp.apps.deploy.naming`); set by the stage that deploys.
    lab_units_ : dict
        ``{the lab's header: [contract name, scale, offset]}`` of the columns read in another
        unit (:func:`~thermocomp.apps.deploy.naming.lab_units`): the exported ``stream.c``
        converts them; set by the stage that deploys.
    derived_ : dict
        ``data.derive`` (extension, derive71): ``{derived target: its arithmetic of errors}``;
        a served block's reference measurements give them (:func:`.pyfunc.references`).
    slashed_ : str or None
        The strptime format of the record's dates with slashes (code71: ``data.time``, or the
        order its rows said, :func:`thermocomp.shell.source.slashed_time`): a served block's
        are read in that order (a block's first row alone decided); set by the stage that deploys.
    day_seconds_ : bool or None
        (dep108d) Its time is the time of day in plain seconds (``TC_DAY_SECONDS``,
        :func:`thermocomp.shell.builders.day_seconds`): a served session's carried past midnight,
        as the C's; None (older pickles): as the lab's header of the time says; set by the stage
        that deploys.
    end_states_ : dict
        ``{campaign: EndState}`` of the record it was deployed on (:func:`end_states`), from
        which a served stream may continue; set by ``promote``.
    adapt_ : Adaptation or None
        How the served model learns from reference measurements (:mod:`.adapt`, ``adapt.*``);
        set by the stage that deploys.

    Notes
    -----
    Each call continues the stream; :meth:`reset` starts a new campaign and the
    next sample becomes its reference.  Prediction is always in simulation
    mode: no measured error ever enters.  :meth:`predict` is the loop of
    :meth:`step` over the block's rows.
    """

    lab_names_: dict = {}      # replaced, never mutated (older pickles have none)
    lab_units_: dict = {}      # the lab's headers in another unit (naming.lab_units): likewise
    derived_: dict = {}        # data.derive's targets, computed from a block's errors: likewise
    bits_: dict = {}           # data.bits, a status word a served block decodes: likewise (bits85)
    slashed_ = None            # the record's order of dates with slashes (older pickles: none)
    day_seconds_ = None        # (dep108d) its time plain seconds of the day (None: its header says)
    missing_values_: list = []  # data.missing_values, a served block's marks: likewise (lab74)
    end_states_: dict = {}
    ambient_given_ = False
    ambient_optional_ = False  # older pickles: an ambient given is needed
    adapt_ = None
    unclamped_: tuple = ()     # targets the clamp leaves alone (white_targets; older pickles: none)
    last_take_ = None          # what the clamp took from the last row's correction (None: nothing)
    _held = None               # older pickles: no stream on the clamped inputs yet
    _gains: dict = {}
    _bounds: dict = {}         # replaced, never mutated (older pickles have none)
    _clock = None              # older pickles: the models' own rule for a missing time

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
        missing = [t for t, e in ests.items() if not has_stream_protocol(e)]
        if missing:
            raise ValueError(f"the estimator of {missing} has no streaming mode "
                             "(stream_init/stream_step): it cannot run on a machine")
        self.targets_ = list(compensator.targets_)
        needs = merge_columns(*(context_columns(e) for e in ests.values()))
        self.time_required_ = TIME in needs
        self.ambient_columns = (list(ambient_columns) if ambient_columns is not None
                                else [c for c in inputs if is_ambient(c)])
        # no ambient sensor: the campaign's ambient is given at reset (its manifest ambient_c)
        self.ambient_given_ = AMBIENT_C0 in needs and not self.ambient_columns
        # ... and where no model needs it (a diagnosed lag's initial state reads it if known, its
        # sensors' mean else: ``ambient_optional_``), a campaign without one still starts
        self.ambient_optional_ = all(getattr(e, "ambient_optional_", False)
                                     for e in ests.values() if AMBIENT_C0 in context_columns(e))
        raw = [c for c in needs if c not in RESERVED]
        extra = [c for c in self.ambient_columns if c not in inputs]
        self.columns_ = inputs + extra + [c for c in raw if c not in inputs and c not in extra]
        # raw context columns, as positions in the row vector (declared inputs: denoised value)
        self._raw = [(c, self.columns_.index(c)) for c in raw]
        self._n_inputs, self._n_checked = len(inputs), len(inputs) + len(extra)
        self._amb_idx = [self.columns_.index(c) for c in self.ambient_columns]
        referenced = compensator.reference == "first_sample"
        self._is_ref = np.array([referenced and c.startswith("T_") for c in inputs])
        idx = {t: [inputs.index(c) for c in compensator.selected_[t]] for t in self.targets_}
        # per target: estimator, input positions (None: all inputs in order)
        self._plan = [(t, ests[t], None if idx[t] == list(range(len(inputs))) else np.asarray(idx[t]))
                      for t in self.targets_]
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
                      margin: float = 0.1, policy: str = "clamp",
                      pattern: bool = True, per_target: bool = False) -> "StreamingCompensator":
        """Envelope from the training campaigns, in the frame the model sees (its horizon: the
        longest campaign's ``time`` span; ``pattern``: the clamp acts only off the training
        pattern, :class:`Envelope`; ``per_target``: the targets :func:`white_targets` finds
        stream unclamped, ``unclamped_``; the deploying stages read ``promote.envelope.
        per_target``, default false).

        Ambient sensors that are not declared inputs are added to the input
        columns when a model needs the initial ambient temperature (ATI).
        """
        m = compensator.stacked(campaigns, targets=[])
        ambient = None
        if AMBIENT_C0 in merge_columns(*(context_columns(e) for e in compensator.estimators_.values())):
            cols = dict.fromkeys(c for df in campaigns.values() for c in df.columns)
            ambient = [c for c in cols if is_ambient(c)]
        spans = [float(np.nanmax(t) - np.nanmin(t)) for t in
                 (df[TIME].to_numpy(float) for df in campaigns.values() if TIME in df.columns)
                 if np.isfinite(t).any()]
        horizon = max(spans) if spans else float("inf")
        out = cls(compensator, Envelope.from_data(m.X, margin, horizon, pattern), policy, ambient)
        if per_target and policy == "clamp":
            out.unclamped_ = white_targets(compensator, campaigns)
        return out

    # -- state ------------------------------------------------------------------------------

    def reset(self, ambient_c: float = float("nan")) -> None:
        """Start a new campaign: the next sample is the reference, every memory is cleared.
        ``ambient_c``: the campaign's ambient (°C) where no ambient sensor is read (its
        manifest ``ambient_c``); the sensors' first sample otherwise."""
        self._ref = None
        self._ambient_c0 = float(ambient_c)
        self._states: dict = {}
        self._held: dict | None = None    # states streamed on the clamped inputs (first excess on)
        self._gains: dict = {}
        self._bounds: dict = {}           # per target: |gain @ e| of the last sample out of range
        self._den_state = None
        self.n_samples_ = 0
        # the training grid (cadence72): the models commit a step once a training period; a row
        # between is answered from the committed state (between73)
        self._grid = getattr(self.compensator, "grid_period_s_", None)
        self._on_grid = (float("nan"), float("nan"))   # (last stepped row's time, last row's)
        period = lag_period(est for _, est, _ in self._plan) or self._grid
        # the time rule of every deployed form (timerule.py): the models see the stream's clock.
        # A time not after the last one read is taken as missing (a scored record's times always
        # increase, so batch and stream agree): as read, the lag bank's exp(-dt/tau) of a time set
        # back by an hour was ~1e12 µm of correction
        self._clock = SampleClock(period) if period else None

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state)
        if "_on_grid" in state:          # (a stream pickled before deploy74: grid_times)
            self._on_grid = grid_times(state["_on_grid"])

    @property
    def clock_time_(self) -> float | None:
        """The last sample's time on the stream's clock (NaN before a campaign's first); None
        without a clock (a static law: the models read the time as given)."""
        return None if self._clock is None else self._clock.t

    @contextmanager
    def envelope_off(self):
        """Within the block the envelope is off (the inputs reach the models as batch gets them);
        the policy is restored after, whatever happens."""
        saved, self.policy = self.policy, "off"
        try:
            yield self
        finally:
            self.policy = saved

    def _snapshot(self) -> tuple:
        return (self._ref, self._ambient_c0, copy.deepcopy(self._states),
                copy.deepcopy(self._den_state), self.n_samples_, copy.deepcopy(self._held),
                self._gains, self._clock and self._clock.snapshot(), dict(self._bounds),
                self._on_grid)

    def _restore(self, snap: tuple) -> None:
        (self._ref, self._ambient_c0, self._states, self._den_state, self.n_samples_, self._held,
         self._gains, *later) = snap      # (an older model's end states have no clock, no bounds)
        clock = later[0] if later else None
        self._bounds = dict(later[1]) if len(later) > 1 else {}
        self._on_grid = grid_times(later[2]) if len(later) > 2 else self._gridless()
        if self._clock is not None:
            if clock is not None:
                self._clock.restore(clock)
            else:                # the models' own times: a time read passes as it is
                self._clock.reset()

    def _gridless(self) -> tuple:
        """(deploy73) The grid of a state saved before cadence72 (none in it), for a model with a
        training grid: its stream stepped every row, so its last row was stepped, but where its
        grid stood was not saved: the next row is stepped and kept, the grid counting from it (a
        faster stream's first row after the state steps a fraction of a period; at the training
        period every row is stepped anyway).  Said once per stream, where the state is
        mid-campaign."""
        if self._grid and self._ref is not None and not getattr(self, "_said_gridless", False):
            self._said_gridless = True
            log.warning(f"a stream state saved before cadence72 (no training grid in it) restored "
                        f"into a model stepped on a {self._grid:g} s grid: the next sample is "
                        "stepped and kept, and the grid counts from it; deploy the model again "
                        "for end states with the grid")
        return float("nan"), float("nan")

    # -- prediction -------------------------------------------------------------------------

    def predict(self, frame: pd.DataFrame) -> pd.DataFrame:
        """Predicted error (µm, one column per target) for consecutive samples of the stream,
        and ``n_clamped`` (inputs of the row clamped to the envelope).

        The rows go through :meth:`step` one by one; the state advances only
        when the whole block is accepted.
        """
        return self._frame(*step_block(self, *self._rows(frame)))

    def _rows(self, frame: pd.DataFrame) -> tuple[np.ndarray, np.ndarray]:
        """``(X, time)`` of ``frame``'s rows, the columns :meth:`predict` reads."""
        need = self.columns_ + ([TIME] if self.time_required_ else [])
        missing = [c for c in need if c not in frame.columns]
        if missing:
            raise OutOfEnvelopeError(f"input lacks column(s) {as_named(missing, self.lab_names_)} "
                                     f"(need {need})")
        X = np.column_stack([frame[c].to_numpy(dtype=float) for c in self.columns_]) \
            if self.columns_ else np.empty((len(frame), 0))
        time = frame[TIME].to_numpy(float) if TIME in frame.columns else np.full(len(frame), np.nan)
        return X, time

    def _frame(self, y: np.ndarray, clamps: np.ndarray) -> pd.DataFrame:
        out = pd.DataFrame(y, columns=self.targets_)
        out["n_clamped"] = clamps
        return out

    def step(self, x_row, time: float = float("nan")) -> np.ndarray:
        """One sample (values in the order of ``columns_``) -> predicted error per target.

        The low-latency path for a CNC loop: no DataFrame, one array in, one out.
        """
        return self._step(np.asarray(x_row, dtype=float), time)[0]

    def _step(self, x: np.ndarray, time: float, clocked: bool = False) -> tuple[np.ndarray, int]:
        """``(prediction, n_clamped)`` of one sample; ``clocked``: ``time`` is on the stream's
        clock already (an adaptive compensator's, stepped by its own clock: one clock)."""
        checked = x[:self._n_checked]
        if not np.isfinite(checked.sum()):          # one reduction instead of a mask
            j = int(np.flatnonzero(~np.isfinite(checked))[0])
            raise MissingValueError(f"input {self.columns_[j]} has no finite value at row "
                                     f"{self.n_samples_} (sensor dropout?)")
        beyond = np.abs(checked) > self._limits()
        if np.count_nonzero(beyond):                # (ci101b: its index only where one is)
            j = int(np.flatnonzero(beyond)[0])
            raise MissingValueError(f"input {self.columns_[j]} reads {checked[j]:g} at row "
                                     f"{self.n_samples_}, beyond {MAX_ABS_T_C:g} °C, which no "
                                     "sensor reads (an overload or open-circuit mark?)")
        if self._clock is not None and not clocked:
            time = self._clock.step(float(time))[0]
        first = self._ref is None
        seen = x
        if self.denoiser is not None:
            den, self._den_state = self.denoiser.stream_step(
                x[:self._n_inputs], self.denoiser.stream_init() if first else self._den_state)
            seen = x.copy()
            seen[:self._n_inputs] = den
        if not first and self._grid and self._between(float(time)):
            # between two grid rows: the models' step from the committed state, not committed
            committed = (self._states, self._held, self._gains, self._bounds)
            self._states, self._held = copy.deepcopy(self._states), copy.deepcopy(self._held)
            try:
                return self._models(seen, time, first)
            finally:
                self._states, self._held, self._gains, self._bounds = committed
        y, n_clamped = self._models(seen, time, first)
        if self._grid:
            self._on_grid = (float(time), float(time))
        return y, n_clamped

    def _models(self, seen: np.ndarray, time: float, first: bool) -> tuple[np.ndarray, int]:
        """``(prediction, n_clamped)`` of the models on the (denoised) sample ``seen`` at the
        stream's ``time``, their states stepped."""
        if first:
            # refused before the stream starts: a half-started one (its reference set, no
            # model state) failed at the next row on a KeyError naming a target
            if not self._amb_idx and self.ambient_given_ and not self.ambient_optional_ and \
                    not np.isfinite(self._ambient_c0):
                raise OutOfEnvelopeError(
                    "the model needs the campaign's initial ambient temperature and reads no "
                    "T_amb / T_amb_* sensor: give the campaign's ambient_c (the manifest column; "
                    "served: params ambient_c)")
            self._ref = np.where(self._is_ref, seen[:self._n_inputs], 0.0)
            if self._amb_idx:
                self._ambient_c0 = ambient_c0(seen[self._amb_idx])
            start = context_record(STREAM_ID, time, self._ambient_c0, {})
            self._states = {t: est.stream_init(start) for t, est, _ in self._plan}
        dx = seen[:self._n_inputs] - self._ref
        self.last_x_ = dx                 # the inputs as the models read them (the guard's)
        n_clamped, excess = 0, None
        env = self.envelope
        if env is not None and self.policy != "off":
            out = (dx < env.lo) | (dx > env.hi)
            if np.count_nonzero(out):
                if self.policy == "refuse":
                    j = int(np.flatnonzero(out)[0])
                    frame = " (change since the first sample)" if self._is_ref[j] else ""
                    raise OutOfEnvelopeError(
                        f"input {self.columns_[j]} = {dx[j]:.4g}{frame} at row {self.n_samples_} is "
                        f"outside the training envelope [{env.lo[j]:.4g}, {env.hi[j]:.4g}]; "
                        "refused (policy=refuse)")
                e = env.excess(dx)
                if e.any():                     # along the training pattern: passed as is
                    excess, n_clamped = e, int(out.sum())
        context = context_record(STREAM_ID, time, self._ambient_c0,
                                 {c: seen[j] for c, j in self._raw})
        y = np.empty(len(self._plan))
        states = self._states
        # a white target streams unclamped only at a sample whose excess several inputs share
        # (spread_excess); at any other its clamped twin's bound holds, as for every target
        free = self.unclamped_ if spread_excess(excess) else ()
        if n_clamped and self._held is None:        # the campaign's first excess: fork
            self._gains = {t: step_gain(est, states[t], env.horizon_s) for t, est, _ in self._plan}
            # a white target's clamped twin too: the samples that are not a source's take it back
            self._held = {t: copy.deepcopy(states[t]) for t, g in self._gains.items() if g is not None}
        held = self._held
        take = np.zeros(len(self._plan))
        for k, (t, est, idx) in enumerate(self._plan):
            x = dx if idx is None else dx[idx]
            e = None if excess is None else excess if idx is None else excess[idx]
            if held is None or t not in held:     # in range so far, or no step gain: the clamp
                y[k], states[t] = est.stream_step(x if e is None or t in free else x - e,
                                                  states[t], context)
                continue
            y[k], states[t] = est.stream_step(x, states[t], context)
            clamped, held[t] = est.stream_step(x if e is None else x - e, held[t], context)
            if e is not None:
                self._bounds = {**self._bounds, t: abs(self._gains[t] @ e)}
            if t in free:       # a heat source's excess: carried on as run scores it
                continue
            # back in range the last excess's bound holds (module doc): an excess that ends at
            # once leaves its memory in the lags and the feedback, taken out as it decays
            bound = self._bounds.get(t, 0.0)
            take[k] = min(max(y[k] - clamped, -bound), bound)
            y[k] -= take[k]
        # what the clamp took out of the model's correction: the guard judges the model's own
        # step, not the clamp switching on or off (guard96)
        self.last_take_ = take
        self.n_samples_ += 1
        return y, n_clamped

    def _between(self, time: float) -> bool:
        """Whether a row lies between two of the training grid (between73), answered from the
        last committed state; False at a row the models step on
        (:func:`~thermocomp.core.timerule.on_grid`; a row without a time is one period on)."""
        stepped, last = self._on_grid
        if not (np.isfinite(time) and np.isfinite(stepped)):
            return False
        if on_grid(time - stepped, time - last, self._grid):
            return False
        self._on_grid = (stepped, time)
        return True

    # -- blocks of rows ---------------------------------------------------------------------
    def run_rows(self, X: np.ndarray, time: np.ndarray, clocked: bool = False, on_refused=None
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(y, n_clamped, dx)`` of the rows of ``X`` streamed one after the other, as
        :meth:`_step` gives them row by row (``dx``: each row's ``last_x_``, the inputs as the
        models read them).

        A run of rows the stream takes as they are -- the campaign started, no excess streamed
        yet (no clamped stream), no denoiser, every checked input finite and inside the
        envelope (or the policy off), each time read after the last one on a set clock -- goes
        through each model in one go (:func:`~thermocomp.core.context.stream_steps`, equal to
        the loop to rounding); any other row through :meth:`_step`, so that a refusal, a clamp
        or a substituted time is what it was.  A row :meth:`_step` refuses (``ValueError``)
        leaves the state as it found it and its ``y`` NaN: ``on_refused(i, exc)`` is called,
        or the error raised when there is none.
        """
        n = len(X)
        y = np.full((n, len(self.targets_)), np.nan)
        clamps = np.zeros(n, dtype=np.int64)
        dx = np.full((n, self._n_inputs), np.nan)
        self.takes_ = np.zeros_like(y)     # each row's last_take_ (a row in one go: none)
        i = 0
        while i < n:
            stop = self._run_batch(X, time, i, clocked, y, dx)
            if stop > i:
                i = stop
                continue
            try:
                y[i], clamps[i] = self._step(X[i], time[i], clocked)
                dx[i] = self.last_x_
                self.takes_[i] = self.last_take_
            except ValueError as exc:
                if on_refused is None:
                    raise
                on_refused(i, exc)
            i += 1
        return y, clamps, dx

    def _run_batch(self, X, time, start: int, clocked: bool, y, dx) -> int:
        """Stream the rows from ``start`` that :meth:`run_rows` may take in one go (at most
        ``BLOCK_ROWS``), their ``y`` and ``dx`` filled in; the row after them (``start``: none)."""
        if self._ref is None or self._held is not None or self.denoiser is not None:
            return start
        if not self._clock_set(clocked):
            return start
        # a few rows first: a stretch the loop must take costs little per row
        m = self._batchable(X, time, start, PROBE_ROWS, clocked)
        if m == PROBE_ROWS:
            m = self._batchable(X, time, start, BLOCK_ROWS, clocked)
        if m and self._grid:
            m = self._grid_rows(time, start, m, clocked)
        if not m:
            return start
        block = X[start:start + m]
        d = block[:, :self._n_inputs] - self._ref
        t = np.asarray(time[start:start + m], dtype=float)
        if self._clock is not None and not clocked:
            shift = self._clock.shift
            t = t - shift                            # the clock's own subtraction
            self._clock.restore((False, float(t[-1]), float(time[start + m - 1]), shift))
        context = context_record(STREAM_ID, t, self._ambient_c0,
                                 {c: block[:, j] for c, j in self._raw})
        rows = slice(start, start + m)
        for k, (target, est, idx) in enumerate(self._plan):
            y[rows, k], self._states[target] = stream_steps(
                est, d if idx is None else d[:, idx], self._states[target], context)
        dx[rows] = d
        self.last_x_, self.last_take_ = d[-1], None
        self.n_samples_ += m
        if self._grid:
            self._on_grid = (float(t[-1]), float(t[-1]))
        return start + m

    def _grid_rows(self, time, start: int, m: int, clocked: bool) -> int:
        """How many of the ``m`` rows from ``start`` the models step on one after the other
        (:func:`~thermocomp.core.timerule.on_grid`; a row between goes through :meth:`_step`)."""
        t = np.asarray(time[start:start + m], dtype=float)
        if self._clock is not None and not clocked:
            t = t - self._clock.shift
        stepped, last = self._on_grid
        steps = np.diff(np.r_[last, t])
        ok = on_grid(steps, steps, self._grid)     # after a stepped row its step is its elapsed
        ok[0] = not np.isfinite(stepped) or bool(on_grid(t[0] - stepped, steps[0], self._grid))
        return m if ok.all() else int(np.argmin(ok))

    def _clock_set(self, clocked: bool) -> bool:
        """The stream's clock reads a time as it is (its offset set by an earlier row)."""
        if self._clock is None or clocked:
            return True
        first, _, _, shift = self._clock.snapshot()[:4]
        return not first and bool(np.isfinite(shift))

    def _limits(self) -> np.ndarray:
        """The largest |value| of each checked input a sensor reads (faults71: a temperature
        within the reader's :data:`MAX_ABS_T_C`; a Keysight DAQ's +9.9E+37 overload mark in a
        lag bank's served plain stream gave corrections of 1e39 µm), inf for any other."""
        limits = getattr(self, "_limits_", None)
        if limits is None:        # (set on first use: a compensator pickled before has none)
            limits = self._limits_ = np.array([reading_limit(c)
                                               for c in self.columns_[:self._n_checked]])
        return limits

    def _batchable(self, X, time, start: int, size: int, clocked: bool) -> int:
        """How many rows from ``start`` (at most ``size``) :meth:`_step` would take as they are:
        every checked input finite, inside the envelope or (clamp) on its training pattern, each
        time read after the last one."""
        block = X[start:start + size]
        checked = block[:, :self._n_checked]
        with np.errstate(invalid="ignore"):
            ok = (np.isfinite(checked) & (np.abs(checked) <= self._limits())).all(axis=1)
        if self._clock is not None and not clocked:
            t = np.asarray(time[start:start + len(block)], dtype=float)
            with np.errstate(invalid="ignore"):      # a missing time compares False: not read
                ok &= t > np.r_[self._clock.t_read, t[:-1]]
        m = len(block) if ok.all() else int(np.argmin(ok))
        env = self.envelope
        if not m or env is None or self.policy == "off":
            return m
        d = block[:m, :self._n_inputs] - self._ref
        for i in np.flatnonzero(((d < env.lo) | (d > env.hi)).any(axis=1)):
            # passed as is along the training pattern (clamp), as _step decides it, row by row
            if self.policy != "clamp" or env.leaves_pattern(d[i]):
                return int(i)
        return m


PROBE_ROWS = 256
BLOCK_ROWS = 1 << 15     # rows streamed in one go at most: a lag bank's filtered block stays small


def warm(deployed, lead_in: pd.DataFrame | None = None, campaign: pd.DataFrame | None = None
         ) -> None:
    """Start a campaign: reset, then stream ``lead_in`` (the rows of the campaigns it continues,
    :func:`thermocomp.core.continuation.lead_in`; predictions discarded), so that the campaign starts
    from the state its predecessor left, as ``run`` predicts it joined to them.  ``deployed``:
    a :class:`StreamingCompensator` or an adaptive compensator around one.  The ambient of a
    model without an ambient sensor is the manifest's ``ambient_c`` of the chain's first
    campaign (``lead_in``'s, else ``campaign``'s), as ``run`` reads the joined campaign.

    A lead-in row with a missing value (a continued test campaign read as recorded) is passed
    over with the state held, as the stream holds it where that campaign itself is streamed
    (``monitor``; the adaptive compensator reconstructs or holds it on its own); any other
    refusal (``policy=refuse``) raises naming the row."""
    start = lead_in if lead_in is not None and len(lead_in) else campaign
    deployed.reset(float("nan") if start is None else manifest_ambient(start))
    if lead_in is None or not len(lead_in):
        return
    X = lead_in[deployed.columns_].to_numpy(float)
    t = lead_in[TIME].to_numpy(float) if TIME in lead_in.columns else np.full(len(X), np.nan)

    def refused(i: int, exc: ValueError) -> None:
        if isinstance(exc, MissingValueError):
            return                                   # passed over, the state held
        deployed.reset()
        raise OutOfEnvelopeError(f"warming the stream on the campaign(s) it continues, row "
                                 f"{i + 1} of {len(X)}: {exc}") from None

    # in one go where the rows allow it (run_rows): a year's lead-in was minutes row by row
    deployed.run_rows(X, t, on_refused=refused)


def batch_prediction(compensator: Compensator, campaign: pd.DataFrame,
                     lead_in: pd.DataFrame | None = None) -> pd.DataFrame:
    """:meth:`Compensator.predict` (simulation) of ``campaign`` joined to its ``lead_in``, sliced
    to its own rows: what ``run`` scores, and what a warmed stream must equal."""
    joined = campaign if lead_in is None else pd.concat([lead_in, campaign], ignore_index=True)
    if lead_in is not None:          # the chain's start: its manifest ambient_c, as run joins it
        joined.attrs = dict(lead_in.attrs)
    predicted = compensator.predict({STREAM_ID: joined})[STREAM_ID]
    return predicted.iloc[len(joined) - len(campaign):].reset_index(drop=True)


@dataclass(frozen=True)
class EndState:
    """Where a campaign left a deployed stream: the state after its last sample, that sample's
    ``time`` and the campaign's sample period (the next sample follows one period later)."""

    state: tuple
    time: float
    period: float


def end_states(deployed, campaigns: Mapping[str, pd.DataFrame],
               lead_ins: Mapping[str, pd.DataFrame] | None = None) -> dict[str, EndState]:
    """``{campaign: EndState}``: each campaign streamed to its end (warmed on its ``lead_ins``
    entry), so that a served stream may start where it left off (``continues``).  Empty
    unless the model reads absolute temperatures (``data.reference=none``): in the
    first-sample frame every campaign starts from its own reference."""
    if deployed.compensator.reference != "none":
        return {}
    lead_ins = lead_ins or {}
    out = {}
    for cid, df in campaigns.items():
        if len(df) < 2 or TIME not in df.columns:
            continue
        lead = lead_ins.get(cid)
        whole = df if lead is None else pd.concat([lead, df], ignore_index=True)
        if lead is not None:
            whole.attrs = dict(lead.attrs)
        warm(deployed, whole)
        out[cid] = EndState(deployed._snapshot(), float(df[TIME].iloc[-1]), campaign_period(df))
    deployed.reset()
    return out


def replay(streaming: StreamingCompensator, campaign: pd.DataFrame, chunk: int | None = None,
           lead_in: pd.DataFrame | None = None) -> pd.DataFrame:
    """Stream one whole campaign from its start (:func:`warm`), in blocks of ``chunk`` samples
    (all at once if None).  Of an adaptive compensator the frame's attrs hold, per target, the
    campaign's rows whose correction its guard changed (the lead-in's not;
    :func:`~thermocomp.core.guarded.mark_guarded`)."""
    warm(streaming, lead_in, campaign)
    warmed = guard_changes(streaming)
    lead = warm_events(streaming, lead_in)
    if lead and len(campaign):
        # the first row puts the campaign on the stream's clock: the lead-in's events count from it
        out = _streamed(streaming, campaign.iloc[:1], None)
        lead = on_campaign_clock(lead, streaming.clock_time_)
        if len(campaign) > 1:
            out = pd.concat([out, _streamed(streaming, campaign.iloc[1:], chunk)], ignore_index=True)
    else:
        out = _streamed(streaming, campaign, chunk)
    if warmed is not None:
        mark_guarded(out, streaming.targets_, guard_changes(streaming) - warmed)
    if lead:
        out.attrs["lead_in_events"] = lead
    return out


def warm_events(deployed, lead_in: pd.DataFrame | None) -> list[dict]:
    """What the sensor monitor of an adaptive compensator did while :func:`warm` streamed
    ``lead_in``: the campaign starts from the state that left (deploy88); none for the plain
    stream or without a lead-in."""
    return list(getattr(deployed, "rows_events_", [])) if lead_in is not None else []


def on_campaign_clock(events: list[dict], t0: float, cid: str | None = None) -> list[dict]:
    """``events`` with their ``time`` from the campaign's first row (``t0`` on the stream's
    clock; a lead-in's are < 0) and, given ``cid``, the ``campaign`` they belong to."""
    named = {} if cid is None else {"campaign": cid}
    return [{**named, **e, "time": e["time"] - t0} for e in events]


def _streamed(streaming, campaign: pd.DataFrame, chunk: int | None) -> pd.DataFrame:
    step = chunk or max(len(campaign), 1)
    if isinstance(streaming, StreamingCompensator):
        # predict's blocks on the arrays read once: a DataFrame per block of 7 rows was most of
        # the causality gate's CPU on a year (promote), the rows still stepped one by one
        X, time = streaming._rows(campaign)
        blocks = [step_block(streaming, X[i:i + step], time[i:i + step])
                  for i in range(0, len(campaign), step)]
        return streaming._frame(np.concatenate([y for y, _ in blocks]) if blocks else
                                np.empty((0, len(streaming.targets_))),
                                np.concatenate([c for _, c in blocks]) if blocks else
                                np.zeros(0, dtype=np.int64))
    parts = [streaming.predict(campaign.iloc[i:i + step]) for i in range(0, len(campaign), step)]
    return pd.concat(parts, ignore_index=True)


def streaming_deviation(streaming: StreamingCompensator, campaign: pd.DataFrame,
                        chunk: int = 7, lead_in: pd.DataFrame | None = None) -> float:
    """Largest |streamed - batch| prediction (µm) over one campaign.

    Batch is :func:`batch_prediction` (the campaign joined to its ``lead_in``, as ``run``
    scores it); the stream is warmed on the same ``lead_in`` and fed the campaign in blocks
    of ``chunk`` samples, envelope off.  A model with memory that lacks the streaming
    protocol, or breaks causality, shows up here; so does a stream that restarts where
    ``run`` carries the state over.
    """
    try:
        with streaming.envelope_off():
            streamed = replay(streaming, campaign, chunk, lead_in)
    finally:
        streaming.reset()
    batch = batch_prediction(streaming.compensator, campaign, lead_in)
    diff = streamed[streaming.targets_].to_numpy() - batch[streaming.targets_].to_numpy()
    return float(np.max(np.abs(diff))) if diff.size else 0.0


def stream_scores(streaming: StreamingCompensator, campaigns: Mapping[str, pd.DataFrame],
                  sample_period_s: float, statistic: str = "range", points: int | None = 200,
                  lead_ins: Mapping[str, pd.DataFrame] | None = None, adapt=None) -> dict:
    """Test figures of the *deployed* predictions, in the layout of ``metrics.json``.

    Each campaign is streamed from its start, as on the machine: from a reset, or warmed on
    its ``lead_ins`` entry (the campaigns it continues); returns ``{target: {"test": {...}}}``
    (see :func:`thermocomp.core.metrics.split_scores`).  With ``adapt`` (an
    :class:`~.adapt.Adaptation` with its schedule, ``adapt.method`` not ``none``) the
    corrections are adapted as ``replay`` adapts them: the campaigns in their order, what is
    learned from the references carried from one to the next.  Each target's
    ``guarded_samples`` (beside ``test``) counts the rows whose correction the guard changed, as
    ``replay.json``'s (:func:`~thermocomp.core.guarded.summed_frames`; None without a guard:
    the plain stream), ``clamped_samples`` the rows with an input clamped to the envelope and
    ``excluded_samples`` those with an input the sensor monitor excluded (stranger74: promote
    said the guard's 2 rows where 109 were clamped and a sensor excluded, its "as deployed"
    1.18 µm against run's 0.71), ``lead_in_events`` what the sensor monitor did while a test
    campaign's stream was warmed (``replay.json``'s, each with its ``campaign``).
    """
    lead_ins = lead_ins or {}
    predicted = {c: replay(streaming, df, lead_in=lead_ins.get(c)) for c, df in campaigns.items()}
    guarded = summed_frames(predicted.values(), streaming.targets_)
    clamped = sum(int((p["n_clamped"].to_numpy() > 0).sum()) for p in predicted.values())
    excluded = sum(int((p["excluded_inputs"].fillna("").astype(str) != "").sum())
                   for p in predicted.values() if "excluded_inputs" in p.columns)
    # what the sensor monitor did while a test campaign's stream was warmed, as replay says it
    lead_events = [{"campaign": c, **e} for c, p in predicted.items()
                   for e in p.attrs.get("lead_in_events", [])]
    streaming.reset()
    # (a probe's first reading after the first row: the deployed y_hat(m) completes the label)
    measured = streaming.compensator.measured(campaigns, predicted=predicted)
    if adapt is not None:
        # the model served with adapt.method learns from the probe; scored frozen, promote
        # tagged a model that adapts with the figures of one that does not
        targets = list(streaming.targets_)
        for c, df in campaigns.items():
            predicted[c][targets] = adapt.correct_recorded(predicted[c][targets].to_numpy(float), df,
                                                           measured[c][targets].to_numpy(float))
    out = {}
    for t in streaming.targets_:
        y = {c: measured[c][t].to_numpy() for c in campaigns}
        r = {c: y[c] - predicted[c][t].to_numpy() for c in campaigns}
        out[t] = {"test": split_scores(y, r, sample_period_s, statistic, points),
                  "guarded_samples": None if guarded is None else guarded[t],
                  "clamped_samples": clamped, "excluded_samples": excluded,
                  "lead_in_events": lead_events}
    return out
