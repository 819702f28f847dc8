"""The test figures of a diagnosed model as it is deployed, not as ``run`` scores it (diagafter60).

``run`` scores a model in batch (:meth:`Compensator.predict`); ``promote``, ``replay`` and the
exported code run it as a stream (by default inside the adaptive compensator: its sensor monitor
and correction guard, matrix61) whose inputs are held to the training envelope
(``promote.envelope``: a sample that leaves the training pattern beyond the envelope is clamped,
:class:`~thermocomp.apps.deploy.streaming.StreamingCompensator`).  Where no test sample is
clamped, no sensor excluded and no correction guarded the two are one computation (within
rounding); where one is, they part: a lag bank
on a planted ambient law (``yearround_spindle`` seed 6003) was diagnosed at 0.66 µm on E_Z
and deployed at 0.688, the last sample of test campaign K03 clamped (``bench_diagnosed_to_code59``);
on ``fl_thermal``'s 60/20/20 split no input is clamped but the guard bounds MLR's correction of
E_ch1 / E_ch2 to the training error range widened by ``monitor.guard.margin`` (depl70: 9.53 /
7.77 µm deployed, 9.57 / 7.95 in batch).
``diagnose`` reports the deployed figures; the batch ones stay beside them (``*_as_run``,
what ``thermocomp run`` of the written config puts in ``metrics.json``), with the rows clamped
and, per target, the rows guarded.
"""

from __future__ import annotations

from collections.abc import Callable

from ...core.compensator import Compensator


def deployed_scores(comp: Compensator, ids, scored_of: Callable, train) -> tuple[dict, int, dict]:
    """``({target: {"test": ...}}, rows clamped, {target: rows guarded})`` of ``comp`` deployed
    (rows guarded: whose correction the guard bounded, rate-limited or held; ``{}`` for the
    plain stream).

    ``scored_of(comp, train, ids)`` is promote's own computation of its "as deployed" test
    figures (:func:`~thermocomp.apps.deploy.streaming.stream_scores` of what it registers:
    the plain stream, its envelope fitted on ``train``, with ``monitor.adaptive`` the adaptive
    compensator around it, with ``adapt.method`` learning from the references as ``replay``
    does; each campaign warmed on the campaigns it continues): its ``{target: {"test",
    "clamped_samples", "guarded_samples"}}``.  (A callable: the deploy app imports this one.)"""
    scores = scored_of(comp, train, list(ids))
    first = next(iter(scores.values()))
    guarded = ({} if first["guarded_samples"] is None
               else {t: s["guarded_samples"] for t, s in scores.items()})
    return {t: {"test": s["test"]} for t, s in scores.items()}, first["clamped_samples"], guarded
