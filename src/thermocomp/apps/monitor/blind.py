"""What a sensor fault inside the bands can cost: the correction's change for an offset the
self-prediction error does not flag.

The monitor sees a drifting sensor only once its self-prediction error leaves the exclusion
band; until then the model reads the drift as temperature.  A sensor's cost is the largest
change of the predicted error (per target, over the training campaigns) when its reading is
offset by that band from the first sample after the reference on: a model that leans hard on
one sensor (coupled, collinear inputs) turns a drift of a fraction of a degree into microns
before any alarm.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd


def undetected_offset_um(compensator, campaigns: Mapping[str, pd.DataFrame],
                         offsets_c: Mapping[str, float]) -> dict[str, dict[str, float]]:
    """Sensor -> target -> largest |change| of the prediction (µm) when the sensor reads
    ``offsets_c[sensor]`` °C more from the second sample of every campaign on (an offset
    present at the reference sample would be referenced away)."""
    base = compensator.predict(campaigns)
    out: dict[str, dict[str, float]] = {}
    for sensor, offset in offsets_c.items():
        moved = compensator.predict({
            cid: df.assign(**{sensor: df[sensor] + float(offset) * (np.arange(len(df)) > 0)})
            for cid, df in campaigns.items()})
        out[sensor] = {}
        for target in compensator.targets_:
            change = np.concatenate([np.abs(moved[c][target].to_numpy(float)
                                            - base[c][target].to_numpy(float)) for c in campaigns])
            out[sensor][target] = float(np.nanmax(change)) if np.isfinite(change).any() else None
    return out
