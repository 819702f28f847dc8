r"""Candidate effects as feature families, built from the model inputs and the per-row context.

An :class:`Effect` names one missing piece of physics in a form a model can
take: a transform of a column (or of the model's inputs) that becomes extra
regressors.  :func:`effect_features` builds them for stacked campaign rows
from

* ``X``: the model's inputs (declared, selected, in the reference frame), and
* ``context``: the per-row frame the :class:`~thermocomp.core.compensator.Compensator`
  passes (``campaign``, ``time``, ``ambient_c0`` and every ``S_``/``T_``
  column, raw values; see :func:`thermocomp.core.frame.stack`).

Columns taken from the context are put in the target's frame first: with
``reference='first_sample'`` a ``T_`` or ``S_`` column becomes its change since
the campaign's first valid sample (DATA_FORMAT.md: the error is zeroed there,
so a state acts through its change).  A state signal may also be taken in a
frame of its own (``frame``): ``absolute`` (its raw value) or ``referenced``
(:math:`S(t) - S(0)`, its change since the campaign's first sample, like the
error), whatever the data's reference; a product with a ``frame`` multiplies
that state by the *rise* :math:`\Delta o(t) = o(t) - o(0)` of a temperature
(an axis position acts through its lever :math:`p - p(0)` on a thermal tilt
that grows from the campaign start).  ``inputs_product`` multiplies a state by the rise of
*every* model input at once: where an axis stands sets the lever through which each
structure's growth or bend reaches the tool, so a position scales the inputs' gains, as the
initial ambient does in ``ambient_linear`` (a rail that grows and bows by two sensors' rises
reaches the tool in proportion to where the saddle stands: one product of the position with
one sensor is half the law, and the search takes one effect a round).  A product may take the
temperature's rise *over the air's* (``over``: the ambient sensor): a tilt is a gradient across a
structure, one face heated, the other held by the air, so a sensor's rise less the air's reads it
where no sensor's rise alone does (planted72: the year-round VMC's column tilt, back less front,
unmeasured: the best single rise explains 82-85 % of it, ``T_box1``'s rise over ``T_amb``'s
94-96 %; tried where the bank of all the rises cannot be tested).  Every transform is causal (the value at
``t`` uses samples up to ``t`` of the same campaign), so it runs on a machine.

==================  ====================  =================================================
kind                transform             features
==================  ====================  =================================================
signal              ``raw``               :math:`\Delta c(t)`
signal              ``first_order_lag``   :math:`L_\tau[\Delta c](t)` (an unused column)
dynamics            ``first_order_lag``   :math:`L_\tau[\Delta c](t)` (a model input)
dynamics            ``lowpass_inputs``    :math:`L_\tau[x_i](t)` for every model input
(both lags)         ``initial_state``     also :math:`w_k^\top(c(0) - A_0)\,(1 - e^{-t/\tau})`
ambient_interval    ``ambient_linear``    :math:`x_i(t)\,(A_0 - 20\,°C)` for every input
ambient_interval    ``ambient_step``      :math:`x_i(t)\,[A_0 > A_{thr}]` for every input
ambient_interval    ``ambient_mean``      :math:`\bar x(t)\,(A_0 - 20\,°C)`, the inputs' mean: one
                                          regressor (diag106e: a room's level law 8 campaigns
                                          can test, where ``ambient_linear`` saturates them)
interaction         ``product``           :math:`\Delta c(t)\,\Delta o(t)`; with ``over``
                                          :math:`\Delta c(t)\,(\Delta o(t) - \Delta a(t))`
interaction         ``inputs_product``    :math:`c(t)\,(x_i(t) - x_i(0))` for every input
(signal, product)   ``frame``             :math:`c` absolute or :math:`c - c(0)` (then
                                          :math:`o - o(0)` in a product)
nonlinear           ``square``            :math:`\Delta c(t)^2`
sensor_fault        ``remove``            none: the declared sensor ``c`` leaves the inputs
==================  ====================  =================================================

:math:`L_\tau` is the first-order lag :math:`\tau\dot z + z = u` (a thermal mass
or a smoothed door), discretised exactly for any sampling,
:math:`z_k = a_k z_{k-1} + (1 - a_k) u_k`, :math:`a_k = e^{-\Delta t_k/\tau}`,
starting in steady state (:math:`z_0 = u_0`).  A first-order lag of all inputs
with a common :math:`\tau` is also what the autoregressive term
:math:`y_k = a\,y_{k-1} + b^\top x_k` of a simulation-mode ARX adds to a static
model (a common pole), so ``lowpass_inputs`` is the AR family too.

A campaign seldom starts in thermal equilibrium: an unmeasured mass with
memory starts off its steady state by an amount the referenced data cannot
see, and in the reference frame that offset decays as
:math:`(1 - e^{-t/\tau})` times an unknown per-campaign constant.  The
``initial_state`` block estimates it from what *is* measured at the first
sample -- how far each sensor :math:`c_j` sits from the initial ambient
:math:`A_0` (absolute °C) -- projected on a few directions :math:`w_k` (the
leading principal directions of those distances over the train campaigns;
sensors on one body move together): regressors
:math:`w_k^\top(c(0) - A_0)\,(1 - e^{-t/\tau})`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict, dataclass, fields

import numpy as np
import pandas as pd

from ...base.errors import ParameterError
from ...core.gains import AMBIENT_CENTRE_C  # ambient_linear's centre: the ATI interaction's
from ...core.io.contract import ContractError
from ...core.models._dynamics import first_order_lag, segment_bounds  # noqa: F401 (re-exported)

FRAMES = ("absolute", "referenced")   # frame of a state signal of its own (None: the data's)
KINDS = ("signal", "dynamics", "ambient_interval", "interaction", "nonlinear", "sensor_fault")
TRANSFORMS = ("raw", "first_order_lag", "lowpass_inputs", "ambient_linear", "ambient_step", "ambient_mean",
              "ambient_scaled",
              "product", "inputs_product", "square", "remove")


def _tuple(v):
    """Lists (from a config) -> nested tuples, so an Effect stays hashable."""
    return tuple(_tuple(x) for x in v) if isinstance(v, (list, tuple)) else v


@dataclass(frozen=True)
class Effect:
    """One candidate (or accepted) effect: a kind, a transform and its parameters.

    Parameters
    ----------
    kind : str
        One of :data:`KINDS` (``diagnosis.json`` vocabulary of CLI.md).
    transform : str
        One of :data:`TRANSFORMS`.
    column : str or None
        The column the effect is traced to (``None`` for effects of all inputs).
    other : str or None
        Second factor of a ``product``.
    tau_s : float or None
        Time constant of a lag (s).
    threshold_c : float or None
        Initial-ambient threshold of ``ambient_step`` (°C).
    initial_state : tuple of str or None
        Lags only: sensors whose initial distance to the ambient starts the
        lag's transient (see the module docstring).
    initial_directions : int or None
        Project the initial distances on their ``k`` leading principal
        directions over the training campaigns (sensors on one body carry one
        number, not one each); learned when the model is fitted
        (:func:`initial_weights`).  ``None`` keeps one regressor per sensor.
    frame : {'absolute', 'referenced'} or None
        ``raw``/``first_order_lag``/``square``/``product`` of a context column:
        take ``column`` absolute or as its change since the campaign's first
        sample, whatever the data's reference; a ``product`` then multiplies it
        by the rise of ``other`` since the first sample.  ``None``: both in the
        data's frame (``reference``).
    over : str or None
        A ``product`` only: take ``other`` over this column (the air), ``o - a`` in
        ``other``'s frame: a structure's gradient to the air.
    """

    kind: str
    transform: str
    column: str | None = None
    other: str | None = None
    tau_s: float | None = None
    threshold_c: float | None = None
    initial_state: tuple | None = None
    initial_directions: int | None = None
    frame: str | None = None
    over: str | None = None     # product: ``other``'s rise taken over this column's (the air's)

    def __post_init__(self):
        object.__setattr__(self, "initial_state", _tuple(self.initial_state))
        if self.kind not in KINDS:
            raise ParameterError(f"effect kind {self.kind!r} is not one of {list(KINDS)}")
        if self.transform not in TRANSFORMS:
            raise ParameterError(f"effect transform {self.transform!r} is not one of {list(TRANSFORMS)}")
        needs = {"first_order_lag": ("column", "tau_s"), "raw": ("column",), "square": ("column",),
                 "product": ("column", "other"), "lowpass_inputs": ("tau_s",),
                 "inputs_product": ("column",),
                 "ambient_step": ("threshold_c",), "remove": ("column",)}
        missing = [k for k in needs.get(self.transform, ()) if getattr(self, k) is None]
        if missing:
            raise ParameterError(f"effect {self.transform!r} needs {missing}")
        if self.tau_s is not None and not self.tau_s > 0:
            raise ParameterError(f"effect tau_s must be > 0 s, got {self.tau_s}")
        if self.initial_state and self.transform not in ("first_order_lag", "lowpass_inputs"):
            raise ParameterError("effect initial_state only goes with a lag")
        if self.frame is not None and (self.frame not in FRAMES or self.transform not in (
                "raw", "first_order_lag", "square", "product", "inputs_product")
                or self.kind == "dynamics"):
            raise ParameterError(f"effect frame {self.frame!r} must be one of {list(FRAMES)}, on a "
                                 "raw, first_order_lag, square, product or inputs_product of a signal")
        if self.over is not None and (self.transform != "product" or self.over == self.other):
            raise ParameterError("effect over (the air a product's temperature is taken over) only "
                                 "goes with a product, and names another column than its other")
        if self.initial_directions is not None and not (
                self.initial_state and 1 <= int(self.initial_directions) <= len(self.initial_state)):
            raise ParameterError("effect initial_directions must be 1 .. the number of initial_state sensors")

    @property
    def title(self) -> str:
        """``kind:column label`` (``-`` for no column): the one name of an accepted effect in the
        stage's table and in ``diagnosis.json`` (``steps``, ``other_targets``; there it was
        ``dynamics:None`` for a lag of the model inputs)."""
        return f"{self.kind}:{self.column or '-'} {self.label}".rstrip()

    @property
    def label(self) -> str:
        """The ``transform`` string of ``diagnosis.json``, e.g. ``first_order_lag(tau=240s)``."""
        tau = f"tau={self.tau_s:g}s" if self.tau_s is not None else ""
        start = ""
        if self.initial_state:
            k = self.initial_directions or len(self.initial_state)
            start = f", from the initial thermal state ({k} direction{'s' if k > 1 else ''})"
        frame = {"absolute": " (absolute)", "referenced": " (change since the first sample)",
                 None: ""}[self.frame]
        return {
            "raw": f"raw{frame}",
            "first_order_lag": f"first_order_lag({tau}){start}{frame}",
            "lowpass_inputs": f"first_order_lag({tau}) of the model inputs{start}",
            "ambient_linear": f"model inputs x (ambient_c0 - {AMBIENT_CENTRE_C:g}°C)",
            "ambient_mean": f"model inputs' mean x (ambient_c0 - {AMBIENT_CENTRE_C:g}°C)",
            "ambient_scaled": f"model inputs' least-squares fit x (ambient_c0 - {AMBIENT_CENTRE_C:g}°C)",
            "ambient_step": f"model inputs x [ambient_c0 > {self.threshold_c:.2f}°C]"
            if self.threshold_c is not None else "",
            "product": f"product({self.other}{' rise' if self.frame else ''}"
                       f"{f' over {self.over}' if self.over else ''}){frame}",
            "inputs_product": f"product(model inputs' rises){frame}",
            "square": f"square{frame}",
            "remove": "remove from the inputs",
        }[self.transform]

    @property
    def learns(self) -> bool:
        """True when the features hold a part learned from the training rows (initial directions)."""
        return (bool(self.initial_state) and self.initial_directions is not None) \
            or self.transform == "ambient_scaled"

    @property
    def uses_inputs(self) -> bool:
        """True when the features are built from the model inputs ``X``."""
        return self.transform in ("lowpass_inputs", "ambient_linear", "ambient_step", "ambient_mean",
                                  "ambient_scaled", "inputs_product")

    @property
    def context_columns(self) -> list[str]:
        """Context columns the features need (besides ``time``/``campaign``/``ambient_c0``)."""
        if self.transform == "remove":
            return []
        own = [c for c in (self.column, self.other, self.over) if c is not None] \
            if not self.uses_inputs or self.transform == "inputs_product" else []
        return list(dict.fromkeys(own + list(self.initial_state or ())))

    def to_dict(self) -> dict:
        """Plain dict without ``None`` values (the form written to the model config)."""
        def plain(v):
            return [plain(x) for x in v] if isinstance(v, tuple) else v
        return {k: plain(v) for k, v in asdict(self).items() if v is not None}

    @classmethod
    def from_dict(cls, d: Mapping) -> "Effect":
        known = {f.name for f in fields(cls)}
        unknown = set(d) - known
        if unknown:
            raise ParameterError(f"effect has unknown key(s) {sorted(unknown)} (known: {sorted(known)})")
        d = dict(d)
        for key in ("tau_s", "threshold_c"):
            if d.get(key) is not None:
                d[key] = float(d[key])
        if d.get("initial_directions") is not None:
            d["initial_directions"] = int(d["initial_directions"])
        return cls(**d)


def as_effect(e) -> Effect:
    return e if isinstance(e, Effect) else Effect.from_dict(e)


def frames(effect: Effect, reference: str) -> tuple[str, str]:
    """Reference of ``effect.column`` and of ``effect.other`` (``'first_sample'`` or ``'none'``)."""
    if effect.frame is None:
        return reference, reference
    return ("none" if effect.frame == "absolute" else "first_sample"), "first_sample"


def in_frame(values, groups, reference: str = "first_sample") -> np.ndarray:
    """A raw context column in the target's frame, gaps held, per segment.

    NaN is held from the previous sample (the first valid value before it);
    a campaign without the column gives zeros.  With ``first_sample`` the
    result is the change since the first valid sample.
    """
    v = np.asarray(values, dtype=float)
    out = np.zeros_like(v)
    for start, stop in segment_bounds(groups, len(v)):
        seg = v[start:stop]
        if np.isnan(seg).any():
            seg = pd.Series(seg).ffill().bfill().to_numpy()
        if np.isnan(seg).all():
            continue
        out[start:stop] = seg - seg[0] if reference == "first_sample" else seg
    return out


def rises(X: np.ndarray, groups) -> np.ndarray:
    """Each column of ``X`` minus its first sample, per segment: the inputs' rises whatever
    the data's reference (with ``first_sample`` they are already)."""
    X = np.asarray(X, dtype=float)
    out = X.copy()
    for start, stop in segment_bounds(groups, len(X)):
        out[start:stop] -= X[start]
    return out


def _context_column(context: pd.DataFrame | None, column: str) -> np.ndarray:
    if context is None or column not in context:
        raise ContractError(f"the diagnosed model needs column {column!r} (passed as context: "
                            "an S_ or T_ column of the campaigns); the data have none", column=column)
    return context[column].to_numpy(dtype=float)


def _groups(groups, context, n: int):
    if groups is not None:
        return groups
    if context is not None and "campaign" in context:
        return np.asarray(context["campaign"])
    return None


def _time(context, n: int) -> np.ndarray:
    if context is not None and "time" in context:
        return context["time"].to_numpy(dtype=float)
    return np.arange(n, dtype=float)


def _ambient(context, n: int) -> np.ndarray:
    if context is None or "ambient_c0" not in context:
        raise ContractError("an ambient-interval effect needs the campaigns' initial ambient "
                            "(ambient_c0, from a T_amb column)", column="T_amb")
    a0 = context["ambient_c0"].to_numpy(dtype=float)
    if not np.isfinite(a0).all():
        raise ContractError("an ambient-interval effect needs a T_amb column in every campaign",
                            column="T_amb")
    return a0


def initial_offsets(context: pd.DataFrame | None, columns, groups) -> np.ndarray:
    """``c_j(0) - A_0`` per row: each sensor's first valid absolute value minus the initial ambient.

    ``A_0`` is the campaign's ``ambient_c0`` (the mean of the ``c_j(0)`` when
    the data have no ambient sensor); a sensor without any value gives 0.
    """
    raw = np.column_stack([_context_column(context, c) for c in columns])
    n = raw.shape[0]
    a0 = context["ambient_c0"].to_numpy(float) if "ambient_c0" in context else np.full(n, np.nan)
    out = np.zeros_like(raw)
    for start, stop in segment_bounds(groups, n):
        first = raw[start]
        if np.isnan(first).any():
            first = pd.DataFrame(raw[start:stop]).bfill().iloc[0].to_numpy()
        ref = a0[start] if np.isfinite(a0[start]) else np.nanmean(first)
        out[start:stop] = np.nan_to_num(first - ref)[None, :]
    return out


def principal_directions(offsets: np.ndarray, groups, k: int) -> np.ndarray:
    """The ``k`` leading principal directions ``(k, m)`` of per-row ``offsets`` over the
    campaigns (one row each; centred SVD, sign fixed so the largest weight is positive)."""
    g = np.asarray(groups)
    starts = np.flatnonzero(np.r_[True, g[1:] != g[:-1]])
    centred = offsets[starts] - offsets[starts].mean(axis=0)
    _, _, Vt = np.linalg.svd(centred, full_matrices=True)
    W = Vt[:k]
    signs = np.sign(W[np.arange(len(W)), np.abs(W).argmax(axis=1)])
    return W * np.where(signs == 0, 1.0, signs)[:, None]


#: A direction the campaigns' starts spread over by no more than this many times the noise of the
#: readings that place them is no state (three sigma; diag95d's measure, diag107c's use).
SPAN_NOISE_FACTOR = 3.0


def spanned_directions(context: pd.DataFrame | None, columns, groups, k: int) -> int:
    """How many of the ``k`` leading principal directions of the initial distances ``c_j(0) - A_0``
    the campaigns span beyond the sensors' noise, counted from the first (bench_diag95d).

    Direction ``w`` is spanned when the s.d. of the campaigns' scores on it exceeds
    :data:`SPAN_NOISE_FACTOR` times one reading's noise projected on ``w``: the robust s.d.
    (1.4826 MAD) of the rows' first differences within the campaigns, over ``sqrt(2)`` (a
    difference holds two readings' noise), floored at the projected resolution
    ``sqrt(sum w_j^2 q_j^2 / 12)`` (``q_j`` the sensor's smallest step).
    """
    g = np.asarray(groups)
    offsets = initial_offsets(context, columns, g)
    starts = np.flatnonzero(np.r_[True, g[1:] != g[:-1]])
    if len(starts) < 2:
        return 0
    W = principal_directions(offsets, g, k)
    scores = (offsets[starts] - offsets[starts].mean(axis=0)) @ W.T
    raw = np.column_stack([_context_column(context, c) for c in columns])
    steps = np.diff(raw, axis=0)[g[1:] == g[:-1]]
    steps = steps[np.isfinite(steps).all(axis=1)]
    moved = np.abs(steps)
    quantum = np.array([np.min(m[m > 0]) if np.any(m > 0) else 0.0 for m in moved.T])
    spanned = 0
    for w, s in zip(W, scores.T):
        d = steps @ w
        noise = 1.4826 * np.median(np.abs(d - np.median(d))) / np.sqrt(2) if len(d) else 0.0
        floor = np.sqrt(np.sum(w ** 2 * quantum ** 2) / 12)
        if np.std(s, ddof=1) <= SPAN_NOISE_FACTOR * max(noise, floor):
            break
        spanned += 1
    return spanned


def initial_weights(context: pd.DataFrame | None, columns, groups, k: int) -> np.ndarray:
    """The ``k`` leading principal directions of the initial distances ``c_j(0) - A_0`` over
    the campaigns of these rows (what a model with ``initial_directions`` learns)."""
    return principal_directions(initial_offsets(context, columns, groups), groups, k)


def transient(offsets: np.ndarray, weights, time, groups, tau_s: float) -> np.ndarray:
    """``offsets (@ weights.T) * (1 - exp(-(t - t_0)/tau))`` per campaign."""
    if weights is not None:
        offsets = offsets @ np.asarray(weights, dtype=float).T
    time = np.asarray(time, dtype=float)
    decay = np.empty(len(offsets))
    for start, stop in segment_bounds(groups, len(offsets)):
        decay[start:stop] = 1.0 - np.exp(-(time[start:stop] - time[start]) / tau_s)
    return offsets * decay[:, None]


def initial_state(context: pd.DataFrame | None, columns, groups, tau_s: float,
                  weights=None) -> np.ndarray:
    """The initial disequilibrium's transient ``(c_j(0) - A_0)(1 - exp(-(t - t_0)/tau))``.

    One column per sensor, or per row of ``weights`` (projected distances).
    """
    offsets = initial_offsets(context, columns, groups)
    return transient(offsets, weights, _time(context, len(offsets)), groups, tau_s)


def _with_start(lag: np.ndarray, effect: Effect, context, groups, weights) -> np.ndarray:
    if not effect.initial_state:
        return lag
    if effect.learns and weights is None:
        weights = initial_weights(context, effect.initial_state, groups, effect.initial_directions)
    return np.hstack([lag, initial_state(context, effect.initial_state, groups, effect.tau_s, weights)])


def effect_features(effect: Effect, X, context: pd.DataFrame | None = None, groups=None,
                    reference: str = "first_sample", weights=None) -> np.ndarray:
    """Extra regressors of one effect, shape ``(n, q)`` (``q = 0`` for ``remove``).

    ``weights``: the learned initial directions (:func:`initial_weights`) of an
    effect that ``learns``; ``None`` learns them from these rows.
    """
    X = np.asarray(X, dtype=float)
    n = X.shape[0]
    g = _groups(groups, context, n)
    tr = effect.transform
    if tr == "remove":
        return np.empty((n, 0))
    own, other = frames(effect, reference)
    if tr in ("raw", "first_order_lag", "square"):
        c = in_frame(_context_column(context, effect.column), g, own)
        if tr == "first_order_lag":
            return _with_start(first_order_lag(c, _time(context, n), g, effect.tau_s)[:, None],
                               effect, context, g, weights)
        return (c**2 if tr == "square" else c)[:, None]
    if tr == "product":
        a = in_frame(_context_column(context, effect.column), g, own)
        b = in_frame(_context_column(context, effect.other), g, other)
        if effect.over is not None:
            b = b - in_frame(_context_column(context, effect.over), g, other)
        return (a * b)[:, None]
    if tr == "inputs_product":
        return in_frame(_context_column(context, effect.column), g, own)[:, None] * rises(X, g)
    if tr == "lowpass_inputs":
        return _with_start(first_order_lag(X, _time(context, n), g, effect.tau_s), effect, context, g,
                           weights)
    a0 = _ambient(context, n)
    if tr == "ambient_linear":
        return X * (a0 - AMBIENT_CENTRE_C)[:, None]
    if tr == "ambient_mean":
        return (X.mean(axis=1) * (a0 - AMBIENT_CENTRE_C))[:, None]
    if tr == "ambient_scaled":
        if weights is None:
            raise ParameterError("an ambient_scaled effect needs the inputs' least-squares weights "
                                 "(level_weights), learned where the model is fitted")
        return ((X @ np.asarray(weights, float)) * (a0 - AMBIENT_CENTRE_C))[:, None]
    return X * (a0 > effect.threshold_c)[:, None].astype(float)   # ambient_step


def level_weights(X, y) -> np.ndarray:
    """The inputs' least-squares coefficients on ``y`` (with an intercept, measured rows only):
    ``ambient_scaled``'s direction, the base's own fit, which a level law scales (diag106e)."""
    X, y = np.asarray(X, float), np.asarray(y, float)
    ok = np.isfinite(y)
    A = np.column_stack([np.ones(ok.sum()), X[ok]])
    return np.linalg.lstsq(A, y[ok], rcond=None)[0][1:]


def design(X, effects, context: pd.DataFrame | None = None, groups=None,
           reference: str = "first_sample", weights=None) -> np.ndarray:
    """Model inputs ``X`` followed by the features of every effect (``weights[i]`` of effect i)."""
    X = np.asarray(X, dtype=float)
    weights = weights or [None] * len(effects)
    blocks = [X] + [effect_features(as_effect(e), X, context, groups, reference, w)
                    for e, w in zip(effects, weights)]
    return np.hstack(blocks)
