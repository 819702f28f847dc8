"""A diagnosed model's effects the code computes from its inputs: its *derived inputs*.

``thermocomp diagnose`` adds to a base model features of its accepted effects
(:class:`~thermocomp.apps.diagnose.AugmentedRegressor`); the stream's model computes them per sample
from its context, the raw value of each column it reads (a declared input denoised, a signal as
read; missing: held).  A lag, a product, a square or a raw signal of those columns is a feature
the code computes the same way from its inputs (``derived`` of :class:`~.statespace.StateSpace`),
a lag a lag-bank channel on it; a low-pass of the model inputs is a channel on each input.  A
product whose temperature is taken over the air (``over``, planted72) is that product, its second
factor less the air's in the same frame, ``r_a (r_b - r_c)`` (``derived_over``, overexport72).  A
state times the rises of all the inputs, ``c (x_i - x_i(0))`` (``inputs_product``, diagpos61), is
one derived input per input (export62), its second factor the model's input ``x_i`` itself, the
clamped one in the code's excess channel as the stream's model reads it (``derived_clamped``).  A
lag's initial-state transient ``w . (c(0) - A0) (1 - exp(-(t - t0)/tau))`` is a derived input of
its own (``initial``, exportrest60): ``c(0)`` the sensors' values at the first sample of the
campaign that has one of them, ``A0`` the campaign's initial ambient, ``t0`` its first sample's
time, as :meth:`~thermocomp.apps.diagnose.AugmentedRegressor.stream_step` computes it.  The
inputs' ambient law ``x (A0 - 20)`` and an ambient step ``x [A0 > A_thr]`` are laws on ``x`` the
campaign's initial ambient switches (:mod:`.laws`).  The base model's coefficients on them are
the law's.  A lean level law (diag107b) is one column ``(A0 - 20) x . w`` (``ambient_scaled``: ``w``
learned at fit; ``ambient_mean``: ``w = 1/k``): it is written as the ambient law's block, its k
coefficients the base's one times ``w`` (:func:`canonical_order`'s factors), so the code holds it
as it holds ``x (A0 - 20)``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

# what the code holds of diagnose's effects (the refusal names them)
DERIVED_TRANSFORMS = ("first_order_lag", "product", "square", "raw", "inputs_product")
AMBIENT_TRANSFORMS = ("ambient_linear", "ambient_step")     # laws on x the campaign's A0 switches
# one column (A0 - 20) x . w: the ambient law's block, its coefficients the column's times w
LEAN_TRANSFORMS = ("ambient_mean", "ambient_scaled")
EXPORTED_EFFECTS = ("a sensor's removal, the inputs' ambient law x (A0 - 20) (its lean reads, "
                    "the inputs' mean or fit x (A0 - 20), too) and ambient step "
                    "x [A0 > A_thr], a first-order lag of a signal or input and of all the inputs "
                    "(with or without its initial-state transient), a product of two columns "
                    "(the second's rise over the air's too), a state times the rises of all the "
                    "inputs (inputs_product), a square of one and a signal as read (raw)")


def is_derived(e) -> bool:
    """True for an effect whose feature is a derived input of the code (its initial-state
    transient too)."""
    return e.transform in DERIVED_TRANSFORMS


def exports(e) -> bool:
    """True for an effect the code holds (:data:`EXPORTED_EFFECTS`), around a plain base or an
    ATI model (an ``inputs_product`` around one too since exportprod65)."""
    return is_derived(e) or e.transform in (*AMBIENT_TRANSFORMS, *LEAN_TRANSFORMS, "lowpass_inputs")


@dataclass
class Feature:
    """One derived input of a diagnosed model: its effect's own term (``initial`` None), or one
    direction of its initial-state transient (``initial``: the weights over the effect's
    ``initial_state`` sensors)."""

    effect: object
    initial: np.ndarray | None = None
    input: int | None = None        # inputs_product: the model input whose rise it multiplies

    @property
    def title(self) -> str:
        return self.effect.title


def features(est) -> tuple[list[Feature], list[int]]:
    """``(derived inputs, initial-state directions per effect)`` of a fitted diagnosed model
    ``est``, in the order of its feature columns (:func:`canonical_order`): an effect's own term,
    then its transient's directions (the learned ``initial_weights_``, else one per sensor); an
    ``inputs_product`` one per model input."""
    out, counts = [], []
    for e, w in zip(est.effects_, est.initial_weights_):
        if e.transform == "inputs_product":
            out += [Feature(e, input=i) for i in range(int(est.n_features_in_))]
        elif is_derived(e):
            out.append(Feature(e))
        rows = [] if not e.initial_state else (
            np.asarray(w, float) if w is not None else np.eye(len(e.initial_state)))
        out += [Feature(e, np.asarray(row, float)) for row in rows]
        counts.append(len(rows))
    return out, counts


@dataclass
class Derived:
    """A diagnosed model's effects the code computes from its inputs (:func:`derived_inputs`):
    ``features`` in their column order, the model's ``reference`` and the sample period of its
    lags (a sample without time is one period after the previous one)."""

    features: list = field(default_factory=list)
    reference: str = "first_sample"
    period: float = 1.0
    order: list | None = None       # the model's feature columns in ``[x, ambient blocks, derived,
                                    # low-pass blocks]``
    lowpass: list = field(default_factory=list)     # the taus of the inputs' low-pass copies
    # the blocks of x the campaign's A0 switches, after x: ("ambient", None) x (A0 - 20),
    # ("step", A_thr) x [A0 > A_thr]; None: an ATI interval's (its interaction or none)
    blocks: list | None = None
    # per place of ``order``, the factor of its model column there (a lean law's w); None: all 1
    factor: list | None = None

    @property
    def widened(self) -> int:
        """The places a lean law's one column takes beyond it: the canonical columns less the
        model's."""
        return len(self.order) - (max(self.order) + 1) if self.order else 0

    def canonical(self, b0, delayed: dict, lags: list) -> tuple:
        """``(b0, delayed, lags)`` of the base model fitted on the features in the effects'
        order, its columns put in the order ``[x, ambient blocks, derived inputs, powers]``."""
        if self.order is None:
            return b0, delayed, lags
        model = self.model_columns(len(b0))
        factor = self._factors(len(model))
        # a lag of a lean law's column is the lag of x . w times (A0 - 20): one per place, times w
        return (self.columns(b0), {d: self.columns(r) for d, r in delayed.items()},
                [(tau, int(p), g * factor[p]) for tau, j, g in lags for p in np.flatnonzero(model == j)])

    def columns(self, row: np.ndarray | None) -> np.ndarray | None:
        """``row`` over the model's columns in the canonical order (:meth:`canonical`), a lean
        law's column times its direction ``w`` on its block's places."""
        if self.order is None or row is None:
            return row
        out = np.asarray(row)[self.model_columns(len(row))]
        return out if self.factor is None else out * self._factors(len(out))

    def model_columns(self, n: int) -> np.ndarray:
        """The canonical place's model column, of ``n`` model columns (none given: the same)."""
        order = self.order or []
        return np.r_[order, np.arange(len(order) - self.widened, n)].astype(int)

    def _factors(self, n: int) -> np.ndarray:
        """Per canonical place of ``n``, its column's factor (1 but a lean law's block)."""
        out = np.ones(n)
        if self.factor is not None:
            out[:len(self.factor)] = self.factor
        return out


def canonical_order(effects: list, k: int, initial: list[int],
                    weights: list | None = None) -> tuple[list[int], list[float] | None]:
    """``(order, factor)``: the model's feature columns (``k`` inputs, then each effect's, in
    the effects' order: :meth:`~thermocomp.apps.diagnose.AugmentedRegressor.stream_step`;
    ``initial[i]`` the transient's directions after effect i's own) in the order ``[x, ambient
    blocks, derived inputs, low-pass blocks]`` the laws are written in.  A lean level law's one
    column is an ambient block's k places, each times its direction's weight (``weights[i]``,
    the fitted ``initial_weights_``: ``ambient_scaled``'s ``w``; ``ambient_mean``'s ``1/k``):
    ``factor`` per place, None where no lean law is (every factor 1)."""
    at, wide, derived, lowpass = k, [], [], []
    for e, q, w in zip(effects, initial, weights or [None] * len(effects)):
        if e.transform in LEAN_TRANSFORMS:
            wide.extend(zip([at] * k, lean_direction(e, w, k)))
            at += 1
            continue
        own = k if e.transform in (*AMBIENT_TRANSFORMS, "lowpass_inputs", "inputs_product") else 1
        group = wide if e.transform in AMBIENT_TRANSFORMS else (
            lowpass if e.transform == "lowpass_inputs" else derived)
        group.extend((j, 1.0) for j in range(at, at + own))
        derived.extend((j, 1.0) for j in range(at + own, at + own + q))
        at += own + q
    places = [*((j, 1.0) for j in range(k)), *wide, *derived, *lowpass]
    lean = any(e.transform in LEAN_TRANSFORMS for e in effects)
    return [j for j, _ in places], [float(f) for _, f in places] if lean else None


def lean_direction(e, w, k: int) -> np.ndarray:
    """The direction ``w`` of a lean level law over the ``k`` inputs: the fitted one of
    ``ambient_scaled``, the mean's ``1/k`` (as ``AugmentedRegressor`` streams them)."""
    return np.full(k, 1.0 / k) if e.transform == "ambient_mean" else np.asarray(w, float)


def ambient_blocks(effects: list) -> list[tuple]:
    """The blocks of x the campaign's initial ambient switches, in the effects' order (a lean
    level law's: the ambient law's)."""
    return [("step", float(e.threshold_c)) if e.transform == "ambient_step" else ("ambient", None)
            for e in effects if e.transform in (*AMBIENT_TRANSFORMS, *LEAN_TRANSFORMS)]


def derived_inputs(derived: Derived, inputs: list, powers: dict,
                   cols=None) -> list[tuple[int, float | None]]:
    """Per derived input, ``(its place among the registered features, the lag's tau or None)``:
    each effect's term, registered in ``powers`` as ``(DERIVED, a, b, ra, rb)``: the product
    ``r_a r_b`` (``b`` = -1: ``r_a`` alone) of ``r_j = v_j - ra v_j(0)``, the input as the
    stream's model reads it from its context (a declared input denoised, a state raw; its change
    since the campaign's first sample where ``ra``: the effect's frame, whatever the inputs'
    reference); a lag is its lag bank channel on ``r_a``.  A product over the air ``c`` as
    ``(DERIVED, a, b, ra, rb, OVER, c)``: ``r_a (r_b - r_c)``, ``r_c`` in ``r_b``'s frame.  An
    ``inputs_product``'s, one per model input ``i`` (the code's input ``cols[i]``), as
    ``(DERIVED, a, cols[i], ra, 1, CLAMPED)``:
    ``r_b`` is the model's input's rise ``x_i - x_i(0)``, which the clamp moves (its excess
    channel: ``r_a (e_i - e_i(0))``), not the context's value.  A transient's direction is registered
    as ``(INITIAL, sensors, weights, tau)`` (no lag channel: a static input of the laws)."""
    from ...diagnose.features import frames  # loaded: the model is a diagnosed one
    out = []
    for f in derived.features:
        e = f.effect
        if f.initial is not None:
            sensors = tuple(inputs.index(c) for c in e.initial_state)
            key = (INITIAL, sensors, tuple(float(w) for w in f.initial), float(e.tau_s))
            out.append((powers.setdefault(key, len(powers)), None))
            continue
        own, other = (int(fr == "first_sample") for fr in frames(e, derived.reference))
        a = inputs.index(e.column)
        if f.input is not None:             # c (x_i - x_i(0)): the model's input, clamped
            key = (DERIVED, a, int(cols[f.input]), own, 1, CLAMPED)
            out.append((powers.setdefault(key, len(powers)), None))
            continue
        b, rb = -1, 0                       # a lag: r_a alone
        if e.transform == "product":
            b, rb = inputs.index(e.other), other
        elif e.transform == "square":
            b, rb = a, own
        over = (OVER, inputs.index(e.over)) if getattr(e, "over", None) is not None else ()
        key = (DERIVED, a, b, own, rb, *over)
        out.append((powers.setdefault(key, len(powers)), e.tau_s))
    return out


DERIVED = "derived"     # the key of a derived input among the registered features
INITIAL = "initial"     # the key of an initial-state transient's direction
CLAMPED = "clamped"     # a derived input's second factor is the model's (clamped) input
OVER = "over"           # a derived input's second factor is taken over the air's (planted72)
