"""While a sensor no other predicts is out: the same family fitted without it (sub71).

The adaptive compensator feeds the model an excluded sensor's POD reconstruction from the healthy
ones, or, for a sensor the others cannot predict (its leverage in the monitor's POD at least
``max_leverage``: its own mode), its last good reading.  Held, a spindle thermocouple unplugged
mid-run on a trunnion mill (keysight70's ``dmu_a``) left the model 93.6 µm RMS off after the
fault (mlr; lagbank 52.1).  A *fallback* is the model's family refitted on the training campaigns
with that sensor out of every target's inputs, streamed beside the model from the campaign's
start; while the sensor is excluded the correction (before the guard) is its fallback's (7.6 and
6.4 µm there).  Fallbacks are fitted at deploy build, for the unpredictable sensors the model
reads only: where the others predict a sensor its reconstruction did better than a fallback
(``benchmarks/bench_sub71.py``).  Under ``model=auto`` the family (or blend) auto chose per target
is refitted with the hyper-parameters it chose, not the candidates' validation again
(``benchmarks/bench_autofb72.py``).  A healthy stream never reads a fallback: its corrections are
the model's, to the bit.

A fallback gives the correction only once its sensor has been out for a delay priced on training
(range73, :func:`switch_delay`): for minutes, the held reading is the better stand-in; a fallback
never worth its switch is dropped.  On a grinder whose spindle carries the error (9.34 µm/°C), the
fallback fitted without it was 79.3 µm RMS in sample against the model's 3.85, and 40 missing
samples cost 22.1 µm with it against 9.71 held.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd

from ...core.compensator import refit_as_chosen
from .streaming import StreamingCompensator

CHOICES = ("unobservable", "none")
OUTAGES = 8       # the priced outages start at each 1/8 of every training campaign, to its end


def _squared_errors(comp, campaigns: Mapping[str, pd.DataFrame]) -> dict[str, np.ndarray]:
    """Per campaign, per row: ``comp``'s squared simulation error summed over its targets."""
    predicted = comp.predict(campaigns, mode="simulation")
    measured = comp.measured(campaigns, predicted=predicted)
    return {c: np.nansum((measured[c][comp.targets_] - predicted[c][comp.targets_])
                         .to_numpy(float) ** 2, axis=1) for c in campaigns}


def switch_delay(streaming: StreamingCompensator, fallback: StreamingCompensator,
                 campaigns: Mapping[str, pd.DataFrame], sensor: str) -> int | None:
    """Samples ``sensor`` must have been out before ``fallback`` gives the correction: of 0 and
    powers of 2, the delay that minimises the squared error, summed over targets and rows, of
    outages simulated on ``campaigns`` (the sensor held from each 1/:data:`OUTAGES` of every
    campaign to its end; the model fed the held reading before the delay, the fallback after
    it); ``None`` where holding throughout is as cheap (no switch worth it).  In sample the
    fallback is fitted on these rows: the price favours it, never holding."""
    own = _squared_errors(fallback.compensator, campaigns)
    held_cost, fall_cost = [], []
    for k in range(1, OUTAGES):
        starts = {c: int(k * len(df) / OUTAGES) for c, df in campaigns.items()}
        held = {}
        for c, df in campaigns.items():
            v = df[sensor].to_numpy(float).copy()
            v[starts[c]:] = v[starts[c]]
            held[c] = df.assign(**{sensor: v})
        errors = _squared_errors(streaming.compensator, held)
        held_cost += [errors[c][starts[c]:] for c in campaigns]
        fall_cost += [own[c][starts[c]:] for c in campaigns]
    longest = max(len(h) for h in held_cost)
    delays = [0, *(2 ** p for p in range(int(np.log2(max(longest, 1))) + 1)), longest]
    costs = [sum(h[:d].sum() + f[d:].sum() for h, f in zip(held_cost, fall_cost)) for d in delays]
    best = int(np.argmin(costs))
    return None if delays[best] >= longest else delays[best]


def without_sensor(streaming: StreamingCompensator, campaigns: Mapping[str, pd.DataFrame],
                   sensor: str) -> StreamingCompensator | None:
    """The model's family refitted on ``campaigns`` with ``sensor`` out of every target's inputs,
    as a stream with the model's envelope; ``None`` where the model does not read it or a target
    would read nothing else.  Under ``auto``, per target the family (or blend) it chose with the
    hyper-parameters it chose (:func:`~thermocomp.core.compensator.refit_as_chosen`): its whole
    choice again (every candidate's folds) took replay of make run's record 2.8 -> 10.3 s CPU."""
    comp = streaming.compensator
    selection = {t: [c for c in comp.selected_[t] if c != sensor] for t in comp.targets_}
    template = refit_as_chosen(comp)
    if (template is None or not all(selection.values())
            or selection == {t: list(comp.selected_[t]) for t in comp.targets_}):
        return None
    fitted = template.set_params(selection=selection).fit(campaigns)
    if list(fitted.inputs_) != list(comp.inputs_):
        return None
    stream = StreamingCompensator(fitted, streaming.envelope, streaming.policy,
                                  streaming.ambient_columns)
    return stream if stream.columns_ == streaming.columns_ else None


def sensor_fallbacks(streaming: StreamingCompensator, monitor,
                     campaigns: Mapping[str, pd.DataFrame], which: str = "unobservable"
                     ) -> dict[str, StreamingCompensator]:
    """``{sensor: fallback}`` for each monitored sensor the others cannot predict (``which`` =
    ``unobservable``; ``none``: no fallback), each with its ``switch_after_`` (samples out,
    :func:`switch_delay`); none where no switch is worth it."""
    if which not in CHOICES:
        raise ValueError(f"monitor.fallbacks must be one of {CHOICES}, got {which!r}")
    if which == "none":
        return {}
    _, leverage = monitor.pod.operator(np.ones(len(monitor.names), dtype=bool))
    out = {}
    for sensor, h in zip(monitor.names, leverage):
        if h >= monitor.pod.max_leverage:
            fallback = without_sensor(streaming, campaigns, sensor)
            delay = None if fallback is None else switch_delay(streaming, fallback, campaigns,
                                                               sensor)
            if delay is not None:
                fallback.switch_after_ = delay
                out[sensor] = fallback
    return out
