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

from collections.abc import Callable, Mapping

import numpy as np

from ...core.compensator import Compensator
from ...core.continuation import lead_ins
from ...core.guarded import summed_frames
from ...core.io.contract import Dataset
from ...core.metrics import split_scores
from ...core.scoring.evaluation import sample_period

CLAMPED = "n_clamped"       # the replayed frame's count of inputs clamped in the row


def deployed_scores(comp: Compensator, ds: Dataset, ids, measured: Mapping, stream_of: Callable,
                    train: Mapping, statistic: str, points) -> tuple[dict, dict, int, dict]:
    """``({target: {"test": ...}}, {campaign: predicted}, rows clamped, {target: rows guarded})``
    of ``comp`` deployed (rows guarded: whose correction the guard bounded, rate-limited or held;
    ``{}`` for the plain stream).

    ``stream_of(comp, train)`` gives ``replay(campaign, lead_in)``: the campaign streamed from
    its start through what ``promote`` registers (the plain stream, its envelope fitted on
    ``train``, and with ``monitor.adaptive`` the adaptive compensator around it), warmed on
    ``lead_in``; a frame of the targets' predictions and
    ``n_clamped``.  (A callable, not the stream: the deploy app imports this one.)  Each
    campaign of ``ids`` is warmed on the campaigns it continues as ``promote`` warms it, and
    scored against ``measured`` (``{campaign: frame}``, the batch scoring's, so that only the
    prediction differs)."""
    ids = list(ids)
    replay = stream_of(comp, train)
    leads = lead_ins(comp, ds, ids)
    predicted = {c: replay(ds.campaigns[c], leads.get(c)) for c in ids}
    clamped = int(sum(int(np.count_nonzero(p[CLAMPED].to_numpy())) for p in predicted.values()
                      if CLAMPED in p))
    guarded = summed_frames(predicted.values(), comp.targets_) or {}
    dt = sample_period(ds, ids)
    out = {}
    for t in comp.targets_:
        y = {c: measured[c][t].to_numpy() for c in ids}
        r = {c: y[c] - predicted[c][t].to_numpy() for c in ids}
        out[t] = {"test": split_scores(y, r, dt, statistic, points, with_before_after=True)}
    return out, predicted, clamped, guarded
