"""(mon103) The warning band of a sensor the model leans on, priced by what its drift costs.

A slow drift of one sensor is read as temperature until its self-prediction error leaves the
warning band; until then the correction moves by the model's gain on that sensor times the drift.
The default scenario's MLR leans on ``T_motor2`` by -24.6 µm/°C on ``E_Z`` (5.6 × training's
residual RMS of 4.38 µm per °C): the 0.4 °C band let 9.9 µm through before the drift was named,
and a +0.2 K/h drift cost 1.85× the healthy error (``benchmarks/bench_mon103.py``).  Priced, the
band of a sensor ``s`` is at most ``LEAN_HARM`` / ``lean_s``, ``lean_s`` the largest over targets
of the model's gain on ``s`` over that target's training residual RMS: the drift it lets through
costs at most ``LEAN_HARM`` training residuals.  It is never tightened below ``LEAN_FLOOR`` of the
band's training-spread floor (the healthy spread of the sensor's error in training), nor for an
ambient sensor (its error is the season's, not the machine's), and a sensor the model barely uses
keeps its band.  The bands are the monitor's own (``warning_c``): the export carries them as it
carries every band.
"""

from __future__ import annotations

import numpy as np

from .states import LEAN_FLOOR, LEAN_HARM


def leans(gains: np.ndarray, residual_rms: np.ndarray) -> np.ndarray:
    """Per input, the largest over targets of ``|gain|`` (µm/°C, targets × inputs) over the
    target's training residual RMS (µm): the residuals a 1 °C offset moves the correction by
    (0 where no target has a residual to price it by)."""
    rms = np.asarray(residual_rms, float)[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        per = np.where(rms > 0, np.abs(np.asarray(gains, float)) / rms, 0.0)
    return per.max(axis=0) if per.size else np.zeros(np.shape(gains)[1])


def priced_bands(warning_c: np.ndarray, floor_c: np.ndarray, lean: np.ndarray,
                 ambient: np.ndarray) -> np.ndarray:
    """The warning bands with each non-ambient sensor's at most ``LEAN_HARM / lean``, never below
    ``LEAN_FLOOR × floor_c`` nor above its band as fitted."""
    warning_c = np.asarray(warning_c, float)
    with np.errstate(divide="ignore"):
        price = np.where(lean > 0, LEAN_HARM / np.asarray(lean, float), np.inf)
    priced = np.maximum(np.minimum(warning_c, price), LEAN_FLOOR * np.asarray(floor_c, float))
    return np.where(np.asarray(ambient, bool), warning_c, np.minimum(warning_c, priced))
