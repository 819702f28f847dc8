"""The weighted laws a per-target estimator is: what the export writes down for one target.

``model=auto`` (:class:`~thermocomp.core.models.auto.AutoRegressor`) predicts and streams as the
estimator it kept (``estimator_``): one family's, or a :class:`~thermocomp.core.models.blend.Blend`
``sum_i w_i * member_i`` whose members stream side by side.  A linear blend is the weighted sum
of its members' laws, so a target's law is the list of ``(name, weight, estimator)`` here.
"""

from __future__ import annotations

from ....core.models.ati import ATIRegressor
from ....core.models.auto import AutoRegressor
from ....core.models.blend import Blend


def one_model(est):
    """The one model of an ATI wrapper that kept one interval and no ambient interaction (too
    few ambient levels in training: what ati=none fits, and streams as it does), else ``est``."""
    if isinstance(est, ATIRegressor) and est.n_intervals_ == 1 and not est.interactions_[0]:
        return est.estimators_[0]
    return est


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


def described(laws: list) -> str:
    """``'lagbank'`` or ``'blend mlr 0.62 + arx 0.38'`` of ``members``' list."""
    if len(laws) == 1:
        return str(laws[0][0])
    return "blend " + " + ".join(f"{name} {w:.4g}" for name, w, _ in laws)
