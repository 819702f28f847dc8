"""The envelope clamp's step gain, split by what a campaign's initial ambient switches (gain61).

A model's gain (:func:`thermocomp.core.context.step_gain`) may depend on the campaign's initial
ambient ``A0``: an ATI model's interval and ambient interaction, a diagnosed model's ambient law
``x (A0 - 20)`` and step ``x [A0 > A_thr]``.  :func:`gain_terms` writes it as a list of
:class:`GainTerm`, each a gain over the model's inputs that counts ``(A0 - 20) ** power`` where
``lo < A0 <= hi``: the stream's gain for a campaign is their sum there (:func:`gain_at`), and
the exported code carries one term per law of the same factor.  The one computation both ask.

A model splits its gain this way with ``gain_terms(horizon_s, lead, period_s)``; any other
gives one term that always counts: its ``step_gain``, or with ``lead`` (per input the tau of a
first-order lag of the held step, ``nan``: the step itself, a diagnosed low-pass copy of the
inputs) its ``lagged_step_gain(lead, horizon_s, period_s)``.  A term whose gain is ``None``:
the model has none in those campaigns (the stream then clamps it outright).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

AMBIENT_CENTRE_C = 20.0   # ISO 1 reference temperature: an ambient law's and interaction's centre


class GainTerm(NamedTuple):
    """``gain`` (over the model's inputs; ``None``: no gain) counting ``(A0 - 20) ** power``
    where ``lo < A0 <= hi``."""

    lo: float
    hi: float
    power: int
    gain: np.ndarray | None

    @property
    def always(self) -> bool:
        """Counts whatever ``A0`` (also when it is unknown)."""
        return self.lo == -np.inf and self.hi == np.inf and self.power == 0


def gain_terms(estimator, horizon_s: float = np.inf, lead=None, period_s: float = 1.0) -> list[GainTerm]:
    """The step gain of ``estimator`` at ``horizon_s`` as terms (module doc); ``lead``: per input
    the tau (s) of a first-order lag of the held step (``nan``: none), updated every ``period_s``."""
    method = getattr(estimator, "gain_terms", None)
    if callable(method):
        return [GainTerm(t.lo, t.hi, t.power, _finite(t.gain))
                for t in method(horizon_s, lead, period_s)]
    if lead is None:
        method = getattr(estimator, "step_gain", None)
        gain = method(None, horizon_s) if callable(method) else None
    else:
        method = getattr(estimator, "lagged_step_gain", None)
        gain = method(np.asarray(lead, float), horizon_s, period_s) if callable(method) else None
    return [GainTerm(-np.inf, np.inf, 0, _finite(gain))]


def gain_at(terms: list[GainTerm], a0: float) -> np.ndarray | None:
    """The gain in a campaign of initial ambient ``a0`` (°C; ``nan``: unknown): the terms that
    count there, summed; ``None`` when one of them has no gain, or one depends on an unknown ``a0``."""
    total = np.zeros(next((t.gain.size for t in terms if t.gain is not None), 0))
    for t in terms:
        if not t.always:
            if not np.isfinite(a0):
                return None
            if not t.lo < a0 <= t.hi:
                continue
        if t.gain is None or t.gain.size != total.size:
            return None
        total = total + (a0 - AMBIENT_CENTRE_C) ** t.power * t.gain if t.power else total + t.gain
    return total if terms else None


def within(terms: list[GainTerm], lo: float, hi: float, power: int = 0, scale: float = 1.0) -> list[GainTerm]:
    """``terms`` counting only where ``lo < A0 <= hi`` too, times ``(A0 - 20) ** power`` and
    ``scale`` more (an ATI interval's, its interaction's half, a blend member's weight)."""
    return [GainTerm(max(t.lo, lo), min(t.hi, hi), t.power + power,
                     None if t.gain is None else scale * t.gain) for t in terms]


def held(lead, horizon_s: float) -> np.ndarray:
    """Per input, a first-order lag of tau ``lead`` (s; ``nan``: none, 1) of a unit step held for
    ``horizon_s``: ``1 - exp(-h / tau)``, the stream's discrete lag at its samples."""
    lead = np.asarray(lead, float)
    if not np.isfinite(horizon_s):
        return np.ones(lead.shape)
    return np.where(np.isnan(lead), 1.0, 1.0 - np.exp(-horizon_s / np.where(np.isnan(lead), 1.0, lead)))


def _finite(gain) -> np.ndarray | None:
    return None if gain is None or not np.isfinite(gain).all() else np.asarray(gain, float)
