"""Simulated artefact measurement: the distance deviations a machine reads on the ball array.

The probe reads a ball where the machine believes its tool point is: the true centre minus the
TCP error there, plus probing noise.  The true centres are the calibrated ones off by the
artefact's ball errors (its own frame, the same in every pose).  The TCP error is taken at the
nominal centres through the full HTM form (a µm shift of the point changes it by far less than
a nm).  Used by the volumetric simulator and by the calibration design study.
"""

from __future__ import annotations

import numpy as np

from .artefact import Setup, pairs
from .kinematics import KinematicModel


def artefact_distances(machine: KinematicModel, setup: Setup, params, ball_error_um,
                       probe_noise_um) -> np.ndarray:
    """Measured minus calibrated distances ``(k, m)`` (µm, ``setup.columns()`` order).

    Parameters
    ----------
    machine : the true machine (its parameters ``params`` (k, p): one row per cycle or machine)
    setup : poses and artefact
    ball_error_um : (n_balls, 3) or (k, n_balls, 3) ball centres off their calibrated ones
    probe_noise_um : (k, n_poses, n_balls, 3) noise of every probed centre
    """
    params = np.atleast_2d(np.asarray(params, float))
    poses, nb = setup.poses, setup.array.n_balls
    nominal = np.stack([p.balls(setup.array) for p in poses])                 # (poses, nb, 3) mm
    frames = np.stack([p.frame() for p in poses])                             # (poses, 3, 3)
    err = machine.error(params, nominal.reshape(-1, 3) - machine.tool, form="htm")
    err = err.reshape(len(params), len(poses), nb, 3)                         # µm
    ball = np.broadcast_to(np.asarray(ball_error_um, float), (len(params), nb, 3))
    dev = np.einsum("kbi,pij->kpbj", ball, frames) - err + probe_noise_um     # µm off nominal
    i, j = np.array(pairs(nb)).T - 1
    a = nominal[:, j] - nominal[:, i]                                         # (poses, pairs, 3) mm
    b = 1e-3 * (dev[:, :, j] - dev[:, :, i])                                  # (k, poses, pairs, 3) mm
    # |a + b| - |a| without the cancellation of subtracting two ~1500 mm lengths
    delta = (2 * np.sum(a * b, axis=-1) + np.sum(b * b, axis=-1)) / (
        np.linalg.norm(a + b, axis=-1) + np.linalg.norm(a, axis=-1))
    return 1e3 * delta.reshape(len(params), -1)
