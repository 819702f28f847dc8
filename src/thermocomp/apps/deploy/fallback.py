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


def _residuals(comp, campaigns: Mapping[str, pd.DataFrame]) -> np.ndarray:
    """Measured minus ``comp``'s simulation on ``campaigns`` (rows x targets)."""
    predicted = comp.predict(campaigns, mode="simulation")
    measured = comp.measured(campaigns, predicted=predicted)
    return np.concatenate([(measured[c][comp.targets_] - predicted[c][comp.targets_])
                           .to_numpy(float) for c in campaigns])


def _rmse(comp, campaigns: Mapping[str, pd.DataFrame]) -> float:
    """RMSE over targets and rows of ``comp``'s simulation on ``campaigns``."""
    return float(np.sqrt(np.nanmean(_residuals(comp, campaigns) ** 2)))


def _reads(comp, sensor: str) -> bool:
    return any(sensor in comp.selected_[t] for t in comp.targets_)


def _without(comp, sensor: str | None) -> dict:
    return {t: [c for c in comp.selected_[t] if c != sensor] for t in comp.targets_}


def heldout_fallbacks(streaming: StreamingCompensator, monitor,
                      campaigns: Mapping[str, pd.DataFrame]) -> dict[str, StreamingCompensator]:
    """``{sensor: fallback}`` for each monitored sensor whose fallback predicts the train
    campaigns held out one at a time (fitted on the others) with a smaller squared error than the
    model fitted on the others fed the sensor's reconstruction by a POD of the others; none with
    fewer than 3 train campaigns."""
    comp = streaming.compensator
    ids = list(campaigns)
    sensors = [s for s in monitor.names if _reads(comp, s) and all(_without(comp, s).values())]
    if len(ids) < 3 or not sensors:
        return {}
    names = list(monitor.names)
    cost = {s: np.zeros(2) for s in sensors}        # squared error: reconstruction, fallback
    for held in ids:
        rest = {c: campaigns[c] for c in ids if c != held}
        one = {held: campaigns[held]}
        model = clone(comp).set_params(selection=_without(comp, None)).fit(rest)
        raw = [df[names].to_numpy(float) for df in rest.values()]
        pod = clone(monitor.pod).fit(np.vstack([a - a[0] for a in raw]), groups=np.concatenate(
            [np.full(len(a), k) for k, a in enumerate(raw)]))
        for s in sensors:
            fallback = clone(comp).set_params(selection=_without(comp, s)).fit(rest)
            cost[s] += [np.nansum(_residuals(model, reconstructed(monitor, one, s, pod)) ** 2),
                        np.nansum(_residuals(fallback, one) ** 2)]
    out = {}
    for s in sensors:
        if cost[s][1] < cost[s][0]:
            fallback = without_sensor(streaming, campaigns, s)
            if fallback is not None:
                out[s] = fallback
    return out


def unobservable_fallbacks(streaming: StreamingCompensator, monitor,
                           campaigns: Mapping[str, pd.DataFrame]) -> dict[str, StreamingCompensator]:
    """``{sensor: fallback}`` for each monitored sensor the others cannot predict (its leverage
    in the monitor's POD at least ``max_leverage``: judged by its own detectors only)."""
    _, lev = monitor.pod.operator(np.ones(len(monitor.names), dtype=bool))
    out = {}
    for s, h in zip(monitor.names, lev):
        if h >= monitor.pod.max_leverage:
            fallback = without_sensor(streaming, campaigns, s)
            if fallback is not None:
                out[s] = fallback
    return out


def reconstructed(monitor, campaigns: Mapping[str, pd.DataFrame], sensor: str, pod=None
                  ) -> dict[str, pd.DataFrame]:
    """``campaigns`` with ``sensor`` replaced by its reconstruction from the others by ``pod``
    (the monitor's by default; each campaign referenced to its first sample, as the monitor reads
    a stream)."""
    names = list(monitor.names)
    j = names.index(sensor)
    active = np.ones(len(names), dtype=bool)
    active[j] = False
    M, _ = (pod or monitor.pod).operator(active)
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
