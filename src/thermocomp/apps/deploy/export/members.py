"""The weighted laws a per-target estimator is: what the export writes down for one target.

``model=auto`` (:class:`~thermocomp.core.models.auto.AutoRegressor`) predicts and streams as the
estimator it kept (``estimator_``): one family's, or a :class:`~thermocomp.core.models.blend.Blend`
``sum_i w_i * member_i`` whose members stream side by side.  A linear blend is the weighted sum
of its members' laws, so a target's law is the list of ``(name, weight, estimator)`` here.
"""

from __future__ import annotations

import sys

from ....core.models.ati import ATIRegressor
from ....core.models.auto import AutoRegressor
from ....core.models.blend import Blend


def one_model(est):
    """The one model of an ATI wrapper that kept one interval and no ambient interaction (too
    few ambient levels in training: what ati=none fits, and streams as it does), or of a
    diagnosed model without an effect feature (none accepted, or a sensor's removal only: its
    base model on the inputs kept), else ``est``."""
    if is_diagnosed(est) and not est.effects_:
        return one_model(est.estimator_)
    if isinstance(est, ATIRegressor) and est.n_intervals_ == 1 and not est.interactions_[0]:
        return est.estimators_[0]
    return est


def is_diagnosed(est) -> bool:
    """``est`` is ``diagnose``'s :class:`~thermocomp.apps.diagnose.AugmentedRegressor` (its module
    is loaded when such a model was unpickled: no other model pays for importing it)."""
    module = sys.modules.get(__name__.split(".apps.")[0] + ".apps.diagnose.augmented")
    return module is not None and isinstance(est, module.AugmentedRegressor)


def members(est) -> list[tuple[str | None, float, object]]:
    """``[(name, weight, estimator)]`` whose weighted sum streams as ``est``: of a ``model=auto``
    estimator the family it chose (weight 1) or its blend's members, named as its candidates
    (``auto``'s ``report``; a blend ``model.estimator.chosen`` names is fitted as it is, without
    the ``auto`` around it); any other ``[(None, 1, est)]``."""
    est = one_model(est)
    if not isinstance(est, (AutoRegressor, Blend)):
        return [(None, 1.0, est)]
    kept = est.estimator_ if isinstance(est, AutoRegressor) else est
    if isinstance(kept, Blend):
        return [(name, float(w), one_model(e))
                for (name, e), w in zip(kept.estimators_.items(), kept.weights_)]
    return [(str(est.family_), 1.0, one_model(kept))]


def described(laws: list) -> str | None:
    """``'lagbank'``, ``'blend mlr 0.62 + ati 0.38 (A0 <= 23.5 | A0 > 23.5 +interaction)'`` of
    ``members``' list; of a plain model ``None``, of a plain ATI model its intervals."""
    if laws[0][0] is None:
        ati = _ati(laws[0][2])
        return f"ati {intervals(ati)}" if ati is not None else None
    named = [f"{name} {intervals(_ati(e))}" if _ati(e) is not None else str(name)
             for name, _, e in laws]
    if len(laws) == 1:
        return named[0] if laws[0][1] else f"none (no correction: {named[0]} weighted 0)"
    return "blend " + " + ".join(f"{n} {w:.4g}" for n, (_, w, _) in zip(named, laws))


def _ati(est) -> ATIRegressor | None:
    """The ATI model ``est`` is, or that a diagnosed model's effects are around (exportrest60);
    None: neither."""
    est = est.estimator_ if is_diagnosed(est) else est
    return est if isinstance(est, ATIRegressor) else None


def intervals(est: ATIRegressor) -> str:
    """``'(A0 <= 23.5 | A0 > 23.5 +interaction)'``: an ATI model's intervals of the initial
    ambient (°C) and which take the ambient interaction -- what the code switches on."""
    edges = [f"{float(b):.4g}" for b in est.boundaries_]
    if not edges:
        spans = ["any A0"]
    else:
        spans = ([f"A0 <= {edges[0]}"] + [f"{lo} < A0 <= {hi}" for lo, hi in zip(edges, edges[1:])]
                 + [f"A0 > {edges[-1]}"])
    return "(" + " | ".join(s + (" +interaction" if inter else "")
                            for s, inter in zip(spans, est.interactions_)) + ")"
