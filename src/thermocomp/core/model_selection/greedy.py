"""Greedy input search on a cross-product (Gram) matrix: the one implementation.

The split greedy search of paper 000 (Sect. 2.2, after Liu et al. 2018) and
classical forward selection both only need inner products of the centred
regressors and the target, so both run on one matrix ``M = A.T @ A`` per
target instead of one regression per candidate; partialling a regressor out
of ``M`` is the sweep operator.  :class:`~thermocomp.core.models.ARX` (lagged
copies, AR term, sensor groups) and
:class:`~thermocomp.core.select.GreedyResidualSelector` (static sensors) both use
:func:`greedy_path`.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

SEARCHES = ("residual", "forward")
COLLINEAR = 1e-10   # a candidate whose partialled variance falls below this share is collinear


class GreedyPath(NamedTuple):
    """Result of :func:`greedy_path` (in the units of the matrix it was given)."""

    order: list[int]
    """Selected indices, in order."""
    rss: list[float]
    """RSS of the joint least-squares fit of the forced terms + the first ``j`` selected inputs."""
    gain: np.ndarray
    """Per candidate (aligned with ``candidates``): its score when it entered; for the others,
    their score after the last step (0 for a constant or collinear candidate)."""


def scaled_gram(A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(A.T @ A / outer(s, s), s)`` with ``s`` the column norms: a unit diagonal.

    The unit diagonal keeps the sweeps well conditioned whatever the units of
    the columns; constant (all-zero) columns keep ``s = 1`` and stay 0.
    """
    M = A.T @ A
    scale = np.sqrt(np.diag(M))
    scale[scale == 0] = 1.0
    return M / np.outer(scale, scale), scale


def sweep(M: np.ndarray, k: int) -> None:
    """Partial column ``k`` out of the cross-product matrix ``M`` in place (the sweep operator)."""
    col = M[:, k].copy()
    M -= np.outer(col, col) / col[k]
    M[k, :] = 0.0
    M[:, k] = 0.0


def greedy_path(M: np.ndarray, y: int, candidates, sensor_of=None, forced=(), max_inputs: int = 10,
                search: str = "residual") -> GreedyPath:
    """Greedy input order and the joint least-squares RSS after each step, from a Gram matrix.

    Parameters
    ----------
    M : ndarray (q, q)
        Cross-product matrix of the (centred) regressors and the target
        (e.g. from :func:`scaled_gram`).
    y : int
        Index of the target in ``M``.
    candidates : sequence of int
        Indices of candidate inputs.
    sensor_of : sequence of int, optional
        Sensor of each index of ``M`` (delayed copies of one sensor share it;
        once a sensor is in, its other delays are out).  Default: every index
        its own sensor.
    forced : sequence of int
        Regressors always in the model (the autoregressive term), partialled out first.
    max_inputs : int
        Largest number of selected inputs.
    search : {'residual', 'forward'}
        ``residual``: the split greedy of paper 000 -- each step fits a one-input
        model of the current residual for every remaining candidate, keeps the
        one that removes most of the residual's sum of squares and subtracts its
        fit.  ``forward``: classical forward selection -- each step keeps the
        candidate that most lowers the RSS of the joint fit.

    Returns
    -------
    GreedyPath
        ``order``, ``rss`` and ``gain`` (the step's score: the residual sum of
        squares removed by the one-input fit for ``residual``, the drop of the
        joint RSS for ``forward``).

    Notes
    -----
    A candidate that is constant, or whose variance is explained by the forced
    and selected terms up to a share ``COLLINEAR``, is never selected; the
    search stops early when no candidate is left.  A forced term that is
    constant or collinear raises :class:`numpy.linalg.LinAlgError`.
    """
    if search not in SEARCHES:
        raise ValueError(f"search must be one of {SEARCHES}, got {search!r}")
    M = np.array(M, dtype=float, copy=True)
    base = np.diag(M).copy()
    for f in forced:
        if not M[f, f] > COLLINEAR * base[f]:
            raise np.linalg.LinAlgError("forced regressor is constant or collinear")
        sweep(M, f)
    partial = M.copy()              # Gram with only the forced terms partialled out
    resid = partial[:, y].copy()    # covariances of the candidates with the running residual
    cand = np.asarray(candidates, dtype=int)
    sensors = cand if sensor_of is None else np.asarray(sensor_of)[cand]
    free = np.ones(len(cand), dtype=bool)
    taken = np.zeros(len(cand), dtype=bool)
    gain = np.zeros(len(cand))
    order, rss = [], []
    for _ in range(max_inputs):
        joint_var = np.diag(M)[cand]
        ok = free & (joint_var > COLLINEAR * base[cand])
        if not ok.any():
            break
        if search == "forward":
            score = M[cand, y] ** 2 / np.where(ok, joint_var, 1.0)
        else:
            score = resid[cand] ** 2 / np.where(ok, np.diag(partial)[cand], 1.0)
        score[~ok] = -np.inf
        pos = int(np.argmax(score))
        j = int(cand[pos])
        gain[pos], taken[pos] = score[pos], True
        if search == "residual":
            resid -= resid[j] / partial[j, j] * partial[:, j]
        sweep(M, j)
        free &= sensors != sensors[pos]
        order.append(j)
        rss.append(max(float(M[y, y]), 0.0))
    if not taken.all():             # what the others would score after the last step
        top, var = (M[cand, y], np.diag(M)[cand]) if search == "forward" \
            else (resid[cand], np.diag(partial)[cand])
        with np.errstate(divide="ignore", invalid="ignore"):
            after = np.where(var > COLLINEAR * base[cand], top ** 2 / var, 0.0)
        gain[~taken] = after[~taken]
    return GreedyPath(order, rss, gain)
