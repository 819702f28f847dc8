r"""Sensor faults by self-prediction: a sensor whose relation to its neighbours breaks.

Paper 002 (Sect. 2.2-2.3) predicts every measured temperature from the others
through the machine's thermal modes and watches the self-prediction error
:math:`E_s = T_s - \hat T_s`: a sensor whose :math:`E_s` leaves its tolerance
band behaves unlike the field it sits in (a heat source the training never saw,
a loose contact, a drifting element) and is dropped from the model.

Here each declared sensor :math:`j` is predicted from the other declared
sensors by least squares, fitted without the held-out campaigns (the same
folds as the residual): :math:`e_j = T_j - \hat T_j`.  A healthy thermal
field is smooth, so every sensor is well predicted by its neighbours and the
errors of all sensors are of one size; a faulty one jumps above it.  The
statistic is the *jump ratio*

.. math:: J_j = \frac{\max_u \mathrm{RMS}(e_{j,u})}{\operatorname{median}_k \max_u \mathrm{RMS}(e_{k,u})}

(worst held-out unit of sensor :math:`j` against the median sensor), and a
sensor with :math:`J_j` at or above the tolerance is a ``sensor_fault``
candidate: the search then tests the model *without* it.  Ambient sensors
(``T_amb*``) predict but are not judged: the ambient is the field's boundary
condition, not part of it, and no structure sensor predicts its daily swing.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .cv import Problem


def _ambient(column: str) -> bool:
    return column == "T_amb" or column.startswith("T_amb_")


def self_prediction(problem: Problem, inputs) -> pd.DataFrame:
    """Cross-validated self-prediction error of each sensor among ``inputs`` (°C).

    Returns a frame indexed by sensor with ``cv_rmse`` (pooled), ``worst_unit``,
    ``worst_unit_rmse`` and ``jump_ratio``.  Needs at least three sensors.
    """
    inputs = [c for c in inputs if c.startswith("T_")]
    field_sensors = [c for c in inputs if not _ambient(c)]
    if len(inputs) < 3 or not field_sensors:
        return pd.DataFrame(columns=["cv_rmse", "worst_unit", "worst_unit_rmse", "jump_ratio"])
    T = problem.X[inputs].to_numpy(float)
    E = np.empty_like(T)
    A = np.column_stack([np.ones(len(T)), T])
    for k in problem.fold_ids:
        tr, te = problem.folds != k, problem.folds == k
        for j in range(T.shape[1]):
            if _ambient(inputs[j]):
                continue
            cols = [0] + [i + 1 for i in range(T.shape[1]) if i != j]
            coef, *_ = np.linalg.lstsq(A[tr][:, cols], T[tr, j], rcond=None)
            E[te, j] = T[te, j] - A[te][:, cols] @ coef
    keep = [j for j, c in enumerate(inputs) if not _ambient(c)]
    E, inputs = E[:, keep], [inputs[j] for j in keep]
    T = T[:, keep]
    per_unit = np.vstack([np.sqrt(np.bincount(problem.unit_index, weights=E[:, j] ** 2,
                                              minlength=problem.n_units)
                                  / np.maximum(np.bincount(problem.unit_index,
                                                           minlength=problem.n_units), 1))
                          for j in range(T.shape[1])])          # (sensors, units)
    worst = per_unit.max(axis=1)
    scale = float(np.median(worst))
    out = pd.DataFrame({
        "cv_rmse": np.sqrt(np.mean(E**2, axis=0)),
        "worst_unit": [problem.unit_names[i] for i in per_unit.argmax(axis=1)],
        "worst_unit_rmse": worst,
        "jump_ratio": worst / scale if scale > 0 else np.full(len(inputs), np.inf),
    }, index=pd.Index(inputs, name="sensor"))
    return out.sort_values("jump_ratio", ascending=False)
