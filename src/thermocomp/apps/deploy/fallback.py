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
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd

from ...core.compensator import refit_as_chosen
from .streaming import StreamingCompensator

CHOICES = ("unobservable", "none")


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
    stream.unclamped_ = streaming.unclamped_      # the model's targets, as its envelope
    return stream if stream.columns_ == streaming.columns_ else None


def sensor_fallbacks(streaming: StreamingCompensator, monitor,
                     campaigns: Mapping[str, pd.DataFrame], which: str = "unobservable"
                     ) -> dict[str, StreamingCompensator]:
    """``{sensor: fallback}`` for each monitored sensor the others cannot predict (``which`` =
    ``unobservable``; ``none``: no fallback)."""
    if which not in CHOICES:
        raise ValueError(f"monitor.fallbacks must be one of {CHOICES}, got {which!r}")
    if which == "none":
        return {}
    _, leverage = monitor.pod.operator(np.ones(len(monitor.names), dtype=bool))
    out = {}
    for sensor, h in zip(monitor.names, leverage):
        if h >= monitor.pod.max_leverage:
            fallback = without_sensor(streaming, campaigns, sensor)
            if fallback is not None:
                out[sensor] = fallback
    return out
