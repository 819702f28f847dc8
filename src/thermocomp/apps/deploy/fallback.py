"""While a sensor is out: the same family fitted without it, where its reconstruction costs more.

The adaptive compensator feeds the model an excluded sensor's POD reconstruction from the healthy
ones.  Where no other sensor follows it (a spindle thermocouple on a trunnion mill, sub71) the
reconstruction is wrong and a model that leans on the sensor goes far off (E_Z 4.84 -> 66 µm).
A *fallback* is the model's family refitted on the training campaigns with that sensor left out
of every target's inputs, streamed beside the model; while the sensor is excluded its correction
is the fallback's.  Which sensors get one is decided at deploy build on the training campaigns:
the fallback's RMSE against the model's with the sensor replaced by its reconstruction (the
monitor's operator, from the other sensors); a fallback is kept only where it is lower
(:func:`priced_fallbacks`).  A healthy stream never reads a fallback: its corrections are the
model's, to the bit.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd
from sklearn.base import clone

from .streaming import StreamingCompensator


def without_sensor(streaming: StreamingCompensator, campaigns: Mapping[str, pd.DataFrame],
                   sensor: str) -> StreamingCompensator | None:
    """The model's family refitted on ``campaigns`` with ``sensor`` out of every target's inputs,
    as a stream with the model's envelope; ``None`` where the model does not read it or a target
    would read nothing else."""
    comp = streaming.compensator
    selection = {t: [c for c in comp.selected_[t] if c != sensor] for t in comp.targets_}
    if selection == {t: list(comp.selected_[t]) for t in comp.targets_} or not all(selection.values()):
        return None
    fitted = clone(comp).set_params(selection=selection).fit(campaigns)
    if list(fitted.inputs_) != list(comp.inputs_):
        return None
    stream = StreamingCompensator(fitted, streaming.envelope, streaming.policy,
                                  streaming.ambient_columns)
    return stream if stream.columns_ == streaming.columns_ else None


def _rmse(comp, campaigns: Mapping[str, pd.DataFrame]) -> float:
    """RMSE over targets and rows of ``comp``'s simulation on ``campaigns``."""
    predicted = comp.predict(campaigns, mode="simulation")
    measured = comp.measured(campaigns, predicted=predicted)
    r = np.concatenate([(measured[c][comp.targets_] - predicted[c][comp.targets_]).to_numpy(float)
                        for c in campaigns])
    return float(np.sqrt(np.nanmean(r ** 2)))


def reconstructed(monitor, campaigns: Mapping[str, pd.DataFrame], sensor: str
                  ) -> dict[str, pd.DataFrame]:
    """``campaigns`` with ``sensor`` replaced by the monitor's reconstruction from the others
    (each campaign referenced to its first sample, as the monitor reads a stream)."""
    names = list(monitor.names)
    j = names.index(sensor)
    active = np.ones(len(names), dtype=bool)
    active[j] = False
    M, _ = monitor.pod.operator(active)
    out = {}
    for cid, df in campaigns.items():
        T = df[names].to_numpy(float)
        d = T - T[0]
        out[cid] = df.assign(**{sensor: T[0, j] + d[:, active] @ M[j]})
    return out


def priced_fallbacks(streaming: StreamingCompensator, monitor,
                     campaigns: Mapping[str, pd.DataFrame]) -> dict[str, StreamingCompensator]:
    """``{sensor: fallback}`` for each monitored sensor whose fallback's training RMSE is below
    the model's fed the sensor's reconstruction (module doc)."""
    comp = streaming.compensator
    out = {}
    for sensor in monitor.names:
        fallback = without_sensor(streaming, campaigns, sensor)
        if fallback is None:
            continue
        if _rmse(fallback.compensator, campaigns) < _rmse(comp, reconstructed(monitor, campaigns,
                                                                               sensor)):
            out[sensor] = fallback
    return out
