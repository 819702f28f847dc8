"""A diagnosed model's effects the code computes from its inputs: its *derived inputs*.

``thermocomp diagnose`` adds to a base model features of its accepted effects
(:class:`~thermocomp.apps.diagnose.AugmentedRegressor`); the stream's model computes them per sample
from its context, the raw value of each column it reads (a declared input denoised, a signal as
read; missing: held).  A lag, a product, a square or a raw signal of those columns is a feature
the code computes the same way from its inputs (``derived`` of :class:`~.statespace.StateSpace`),
a lag a lag-bank channel on it; a low-pass of the model inputs is a channel on each input.  The
base model's coefficients on them are the law's (:mod:`.laws`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

# what the code holds of diagnose's effects (the refusal names them)
DERIVED_TRANSFORMS = ("first_order_lag", "product", "square", "raw")
EXPORTED_EFFECTS = ("a sensor's removal, the inputs' ambient law x (A0 - 20), a first-order lag "
                    "of a signal or input and of all the inputs (without an initial-state "
                    "transient), a product of two columns, a square of one and a signal as read "
                    "(raw)")


def is_derived(e) -> bool:
    return e.transform in DERIVED_TRANSFORMS and not e.initial_state


@dataclass
class Derived:
    """A diagnosed model's effects the code computes from its inputs (:func:`derived_inputs`):
    ``effects`` in their feature order, the model's ``reference`` and the sample period of its
    lags (a sample without time is one period after the previous one)."""

    effects: list = field(default_factory=list)
    reference: str = "first_sample"
    period: float = 1.0
    order: list | None = None       # the model's feature columns in ``[x, x (A0 - 20), derived,
                                    # low-pass blocks]``
    lowpass: list = field(default_factory=list)     # the taus of the inputs' low-pass copies

    def canonical(self, b0, delayed: dict, lags: list) -> tuple:
        """``(b0, delayed, lags)`` of the base model fitted on the features in the effects'
        order, its columns put in the order ``[x, x (A0 - 20), derived inputs, powers]``."""
        if self.order is None:
            return b0, delayed, lags
        place = np.argsort(self._order(len(b0)))     # a model column's canonical place
        return (self.columns(b0), {d: self.columns(r) for d, r in delayed.items()},
                [(tau, int(place[j]), g) for tau, j, g in lags])

    def columns(self, row: np.ndarray | None) -> np.ndarray | None:
        """``row`` over the model's columns in the canonical order (:meth:`canonical`)."""
        if self.order is None or row is None:
            return row
        return np.asarray(row)[self._order(len(row))]

    def _order(self, n: int) -> np.ndarray:
        return np.r_[self.order, np.arange(len(self.order), n)].astype(int)


def canonical_order(effects: list, k: int) -> list[int]:
    """The model's feature columns (``k`` inputs, then each effect's, in the effects' order:
    :meth:`~thermocomp.apps.diagnose.AugmentedRegressor.stream_step`) in the order ``[x, x (A0 -
    20), derived inputs]`` the laws are written in."""
    at, groups = k, {"ambient_linear": [], "lowpass_inputs": [], None: []}
    for e in effects:
        wide = e.transform in ("ambient_linear", "lowpass_inputs")
        groups[e.transform if wide else None].extend(range(at, at + (k if wide else 1)))
        at += k if wide else 1
    return [*range(k), *groups["ambient_linear"], *groups[None], *groups["lowpass_inputs"]]


def derived_inputs(derived: Derived, inputs: list, powers: dict) -> list[tuple[int, float | None]]:
    """Per effect feature, ``(its place among the registered features, the lag's tau or None)``:
    each effect's term, registered in ``powers`` as ``(DERIVED, a, b, ra, rb)``: the product
    ``r_a r_b`` (``b`` = -1: ``r_a`` alone) of ``r_j = v_j - ra v_j(0)``, the input as the
    stream's model reads it from its context (a declared input denoised, a state raw; its change
    since the campaign's first sample where ``ra``: the effect's frame, whatever the inputs'
    reference); a lag is its lag bank channel on ``r_a``."""
    from ...diagnose.features import frames  # loaded: the model is a diagnosed one
    out = []
    for e in derived.effects:
        own, other = (int(f == "first_sample") for f in frames(e, derived.reference))
        a = inputs.index(e.column)
        b, rb = -1, 0                       # a lag: r_a alone
        if e.transform == "product":
            b, rb = inputs.index(e.other), other
        elif e.transform == "square":
            b, rb = a, own
        key = (DERIVED, a, b, own, rb)
        out.append((powers.setdefault(key, len(powers)), e.tau_s))
    return out


DERIVED = "derived"     # the key of a derived input among the registered features

