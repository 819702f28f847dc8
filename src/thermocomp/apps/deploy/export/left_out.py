"""What the exported code leaves to the served model (:func:`not_in_code`), and (st103b) the
fallback models the ST block holds beside the model's laws (:func:`with_st_fallbacks`).

Apart from :mod:`.output` and :mod:`.fallbacks`: it builds the fallbacks' state spaces
(:mod:`.statespace`, which imports both).
"""

from __future__ import annotations

from ..adaptive import AdaptiveCompensator
from .errors import NotExportable
from .fallbacks import with_fallbacks
from .statespace import state_space


def not_in_code(deployed, fmt: str | None = None) -> list[str]:
    """What the served model does that the exported code (of format ``fmt``) does not: its
    sensor monitor, of which the C holds a slice (:mod:`.watch`, cmon76)."""
    if not (isinstance(deployed, AdaptiveCompensator) and deployed.monitor is not None):
        return []
    if fmt == "c" and deployed.monitor.adaptive:
        # (quiet94c) the ambient of a one-campaign training, warned and not excluded by its
        # drift (quiet94), is held by the code too (``warn_only``): not named here any more
        return ["sensor monitor rules (the C holds the jump, the freeze, a missing reading, "
                "a reading beyond its training range, a common step, one sensor out "
                "reconstructed from the others and its re-admission, a drift exclusion while no "
                "sensor is out, of one sensor or of it and its blind partner, a new thermal "
                "state, a sensor no other predicts out for a dropout, a freeze or a jump, a stepped "
                "self-prediction error's culprit out, a second sensor out for a jump, two sensors "
                "jumping in one sample, one or two out, the drift of an ambient sensor of a "
                "one-campaign training warned and not excluded, a sensor no other predicts "
                "re-referenced when its level settles off its own): a missing "
                "reading at a campaign's first sample, with another sensor out or missing, or of a "
                "sensor the code does not hold out (the code refuses the row), a missing reading of "
                "a sensor out for a freeze (its re-admission band), a sample without its time "
                "while a frozen sensor's held value is read (mon105d: the code counts one period "
                "on, served reads its stand-in), a reading beyond its training "
                "range at a campaign's first sample, of every sensor at once or beside those out "
                "where the code does not hold it, several sensors jumping at once that are no "
                "common step (two or more the code cannot hold: a set it cannot solve), "
                "a jump at the sample after the reference, a stepped self-prediction "
                "error whose culprit would be a third out, a drift beyond the band with a "
                "sensor out, of a sensor no other predicts, of more than one blind partner, a "
                "second sensor out for another rule, a third out, a "
                "sensor no other predicts out for another rule, or with a fallback model (the "
                "model fitted without it) of a kind the code does not step beside the model "
                "(an lstm network of another shape, other inputs)"]
    if fmt == "st" and st_leaves_fallbacks(deployed):
        return ["sensor monitor (exclusion, reconstruction of a sensor from the others; a fallback "
                "model with a forest or a network, or any of a model with them: the ST serves the "
                "model's laws while it holds its sensor out)"]
    return ["sensor monitor (exclusion, reconstruction of a sensor from the others)"]


def _stepped_in_st(system) -> bool:
    """Whether the ST block steps ``system``'s laws beside another's: no forest, no network (its
    forest walk and networks count whatever set is served)."""
    return not (system.forest_target or system.lstm_target)


def st_leaves_fallbacks(deployed) -> bool:
    """(st103b) Whether the ST block leaves out a fallback model of ``deployed`` that has a forest
    or a network, or every one of a model with them (:func:`with_st_fallbacks`)."""
    falls = getattr(deployed, "fallbacks_", {}) or {}
    systems = []
    for fb in [deployed, *falls.values()] if falls else []:
        try:
            systems.append(state_space(fb))
        except NotExportable:
            continue
    return not all(_stepped_in_st(s) for s in systems)


def with_st_fallbacks(ss, deployed, watch: dict) -> None:
    """(st103b) The ST block's fallback models: :func:`with_fallbacks` into ``ss`` (made without
    a monitor) by the block's monitor ``watch``, which gets the ``fallback_set``; one with a
    forest or a network is left out, and every one where the model has them (the block's forest
    walk and networks count whatever set is served): the block serves the model's laws for their
    sensors, as before (``provenance.not_in_code``)."""
    if not watch:
        return
    watch["fallback_set"] = [0] * len(watch["inputs"])
    if not _stepped_in_st(ss):
        return

    def system(fb):
        out = state_space(fb)
        if not _stepped_in_st(out):
            raise NotExportable("a fallback with a forest or a network: not in the ST block")
        return out

    ss.monitor = watch
    try:
        with_fallbacks(ss, deployed, system)
    finally:
        ss.monitor = {}
