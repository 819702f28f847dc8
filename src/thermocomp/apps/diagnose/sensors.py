r"""Sensor faults by self-prediction: a sensor whose relation to its neighbours breaks.

Paper 002 (Sect. 2.2-2.3) predicts every measured temperature from the others
through the machine's thermal modes and watches the self-prediction error
:math:`E_s = T_s - \hat T_s` while the machine runs: a sensor whose
:math:`E_s` leaves its tolerance band behaves unlike the field it sits in (a
heat source the training never saw, a loose contact, a drifting element) and
is dropped from the model.

Here each declared sensor :math:`j` is predicted from the other declared
sensors by least squares fitted on train campaigns: on each train campaign by
a fit without it (the folds of the residual), which is what the search acts on;
for the report only, also on every later campaign the compensator will face
(the test split's *temperatures* -- never its errors) by the fit on all train
campaigns: a sensor broken there is said, not removed (the test split chooses
nothing).  A healthy thermal field is smooth, so
every sensor is well predicted by its neighbours and the errors of all
sensors are of one size; a faulty one jumps above it.  The statistic is the
*jump ratio*

.. math:: J_j = \min\left(\frac{\max_u r_{j,u}}{\operatorname{median}_k \max_u r_{k,u}},\;
                           \frac{\max_u r_{j,u}}{Q_{25\%,u}\, r_{j,u}}\right),
          \qquad r_{j,u} = \mathrm{RMS}_u(e_j)

-- its worst campaign against the median sensor's *and* against its own
typical campaign: a sensor the field never explains well (a motor or a
cabinet sensor driven by the load) is not broken, one that was fine and then
jumps is.  A sensor with :math:`J_j` at or above the tolerance is a
``sensor_fault`` candidate: the search then tests the model *without* it.  A faulty sensor also spoils
the prediction of its close neighbours (it is one of their predictors), so
with a tolerance the ratios are computed twice, the second time predicting
each sensor without the *other* suspects (paper 002 likewise drops the
outlier before judging the rest).  Ambient sensors (``T_amb*``) predict but
are not judged: the ambient is the field's boundary condition, not part of
it, and no structure sensor predicts its daily swing.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .cv import Problem

COLUMNS = ["cv_rmse", "worst_unit", "worst_unit_rmse", "cross_ratio", "own_ratio", "jump_ratio"]


def is_ambient(column: str) -> bool:
    return column == "T_amb" or column.startswith("T_amb_")


HEALTH_BLOCKS = 8   # time blocks a sensor's self-prediction is judged on (see _health_units)


def _health_units(problem: Problem) -> tuple[np.ndarray, int, list[str]]:
    """``(index, count, names)`` of the units a sensor's jump is judged on: the campaigns, but
    time blocks of one record merged, adjacent ones together, into :data:`HEALTH_BLOCKS` (the lower quartile
    of many short blocks is a quiet stretch, not the sensor's usual error: with 16 blocks a
    healthy motor sensor of a long record passed the jump ratio of 3 and was removed)."""
    index, n, names = problem.unit_index, problem.n_units, list(problem.unit_names)
    blocks = problem.scheme == "forward" or len(set(np.asarray(problem.campaigns))) == 1
    if not blocks or n <= HEALTH_BLOCKS:
        return index, n, names
    group = np.arange(n) * HEALTH_BLOCKS // n                 # adjacent blocks together
    merged = np.where(index >= 0, group[np.maximum(index, 0)], -1)
    firsts = [names[int(np.flatnonzero(group == g)[0])] for g in range(HEALTH_BLOCKS)]
    return merged, HEALTH_BLOCKS, firsts


def _unit_rms(errors: np.ndarray, index: np.ndarray, n_units: int) -> np.ndarray:
    """RMS of each column of ``errors`` per unit: shape (columns, units); index -1: not scored."""
    ok = index >= 0
    counts = np.maximum(np.bincount(index[ok], minlength=n_units), 1)
    return np.vstack([np.sqrt(np.bincount(index[ok], weights=e[ok] ** 2, minlength=n_units) / counts)
                      for e in errors.T])


def _errors(problem: Problem, T, judged, predictors, L=None):
    """Held-out self-prediction errors on the train rows (and on ``L``, fitted on all rows)."""
    E = np.full((len(T), len(judged)), np.nan)     # rows no fold scores stay NaN
    folds = list(problem.splits)
    if L is not None:
        folds.append((np.ones(len(T), bool), None))
        EL = np.empty((len(L), len(judged)))
    for tr, te in folds:
        Tr = T[tr]
        mean = Tr.mean(axis=0)
        C = (Tr - mean).T @ (Tr - mean)
        for col, j in enumerate(judged):
            cols = predictors[j]
            coef, *_ = np.linalg.lstsq(C[np.ix_(cols, cols)], C[cols, j], rcond=None)
            if te is None:
                EL[:, col] = L[:, j] - mean[j] - (L[:, cols] - mean[cols]) @ coef
            else:
                E[te, col] = T[te, j] - mean[j] - (T[te][:, cols] - mean[cols]) @ coef
    return E, (EL if L is not None else None)


def self_prediction(problem: Problem, inputs, later: pd.DataFrame | None = None,
                    later_units=None, tolerance: float | None = None) -> pd.DataFrame:
    """Self-prediction error of each non-ambient sensor among ``inputs`` (°C).

    ``later``/``later_units``: temperatures (reference frame) and campaign of
    the rows the compensator will face after training (the test split).
    ``tolerance``: the jump ratio of a suspect; when given, suspects are left
    out of each other's predictors in a second pass.  Returns a frame indexed
    by sensor, worst first, with ``cv_rmse`` (pooled over the held-out train
    campaigns), ``worst_unit``, ``worst_unit_rmse``, ``cross_ratio`` (against
    the median sensor), ``own_ratio`` (against the sensor's own lower-quartile
    campaign) and ``jump_ratio`` (the smaller of the two).
    Empty with fewer than three sensors.
    """
    sensors = [c for c in inputs if c.startswith("T_")]
    judged = [j for j, c in enumerate(sensors) if not is_ambient(c)]
    if len(sensors) < 3 or not judged:
        return pd.DataFrame(columns=COLUMNS)
    T = problem.X[sensors].to_numpy(float)
    L = later[sensors].to_numpy(float) if later is not None and len(later) else None
    unit_index, n_units, names = _health_units(problem)
    index = None
    if L is not None:
        ids = list(dict.fromkeys(np.asarray(later_units, dtype=object)))
        pos = {u: i for i, u in enumerate(ids)}
        index = np.array([pos[u] for u in np.asarray(later_units, dtype=object)])
        names += ids

    def jumps(predictors):
        E, EL = _errors(problem, T, judged, predictors, L)
        per_unit = _unit_rms(E, unit_index, n_units)
        if EL is not None:
            per_unit = np.hstack([per_unit, _unit_rms(EL, index, len(names) - n_units)])
        worst = per_unit.max(axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):
            cross = worst / float(np.median(worst))
            own = worst / np.quantile(per_unit, 0.25, axis=1)
        return E, per_unit, worst, np.nan_to_num(cross, nan=0.0), np.nan_to_num(own, nan=0.0)

    everyone = {j: [i for i in range(len(sensors)) if i != j] for j in judged}
    E, per_unit, worst, cross, own = jumps(everyone)
    if tolerance is not None:
        suspects = {judged[col] for col in np.flatnonzero(np.minimum(cross, own) >= tolerance)}
        if suspects:
            apart = {j: [i for i in everyone[j] if i not in suspects - {j}] for j in judged}
            if all(apart[j] for j in judged):
                E, per_unit, worst, cross, own = jumps(apart)
    out = pd.DataFrame({
        "cv_rmse": np.sqrt(np.mean(E[problem.held_out] ** 2, axis=0)),
        "worst_unit": [names[i] for i in per_unit.argmax(axis=1)],
        "worst_unit_rmse": worst,
        "cross_ratio": cross,
        "own_ratio": own,
        "jump_ratio": np.minimum(cross, own),
    }, index=pd.Index([sensors[j] for j in judged], name="sensor"))
    return out.sort_values("jump_ratio", ascending=False)
