r"""A start block's effect on the campaigns' levels against the first reading's probe noise.

With ``reference=first_sample`` every campaign's error is measured from its first reading, so
each campaign's labels carry minus that reading's probe noise: a constant level per campaign,
:math:`a_c \sim N(0, \sigma^2)` with :math:`\sigma` the probe's per-sample noise, that no
temperature predicts.  A lag from the initial state (:attr:`~.features.Effect.initial_state`) adds
``k`` regressors that are nearly constant within a campaign once its transient has settled: on 8
train campaigns they can fit those ``k`` levels by chance and gain in CV, then miss on new
campaigns whose first readings are fresh noise (diag87c: 8075 E_Y, 8457 E_X, 8170 E_X, 8178 E_Z;
``benchmarks/bench_diag87c.py``, ``bench_diag88.py``).

The test here asks whether the start block moves the campaigns' levels by more than that noise
can.  Null model (train rows): :math:`y = Z\beta + D a + e`, ``Z`` the model without the start
block (intercept, inputs, the effects taken, the same lag without its start), ``D`` the campaign
indicators, :math:`a_c, e_t` independent :math:`N(0, \sigma^2)`.  With ``B`` an orthonormal basis
of the start block beyond ``Z``, its least-squares signal is :math:`s = B B^\top y` and
:math:`c = B^\top y = B^\top (D a + e) \sim N(0, \sigma^2 C)`, :math:`C = B^\top D D^\top B + I`
(exactly: :math:`B \perp Z`).  The statistic is the signal's campaign-level sum of squares,
:math:`T = \sum_c n_c \bar s_c^2 = c^\top G c`, :math:`G = B^\top D N^{-1} D^\top B`, so
:math:`T / \sigma^2` is distributed as :math:`\sum_i \lambda_i \chi^2_1`, the
:math:`\lambda_i` the eigenvalues of :math:`C^{1/2} G C^{1/2}` (``k`` of them; about
:math:`n_c + 1` each where the block is constant within campaigns of ``n_c`` rows).
:math:`\sigma` is estimated from the same residual's sample-to-sample differences within the
campaigns (von Neumann: :math:`E[(r_t - r_{t-1})^2] = 2\sigma^2` for white noise, a smooth misfit
adds little), so the first reading's noise is judged by the noise of every other reading.
"""

from __future__ import annotations

import numpy as np

from ...core.models._dynamics import segment_bounds

DRAWS = 20000   # Monte Carlo draws of the weighted chi-square (k <= a few terms)


def successive_difference_sigma(residual: np.ndarray, campaigns) -> float:
    """Per-sample noise sd from the residual's differences within the campaigns (von Neumann)."""
    r = np.asarray(residual, dtype=float)
    sq, n = 0.0, 0
    for start, stop in segment_bounds(campaigns, len(r)):
        d = np.diff(r[start:stop])
        d = d[np.isfinite(d)]
        sq, n = sq + float(d @ d), n + d.size
    return float(np.sqrt(sq / (2 * n))) if n else float("nan")


def start_level_pvalue(Q: np.ndarray, start: np.ndarray, y: np.ndarray, campaigns,
                       seed: int = 0) -> float:
    """p of the start block's campaign-level effect under first-reading noise alone.

    Parameters
    ----------
    Q : ndarray (n, q)
        Orthonormal basis of the model without the start block (intercept included).
    start : ndarray (n, k)
        The start block's regressors.
    y : ndarray (n,)
        The target (measured train rows, grouped by campaign in time order).
    campaigns : array-like (n,)
        Campaign of each row.
    seed : int
        Seed of the Monte Carlo draws of the null distribution.

    Returns
    -------
    float
        One-sided p (large: the levels moved no more than the first reading's noise moves them);
        0 where the residual has no noise to judge by, 1 where the block adds nothing beyond ``Q``.
    """
    residual = y - Q @ (Q.T @ y)
    sigma = successive_difference_sigma(residual, campaigns)
    S = start - Q @ (Q.T @ start)
    U, sv, _ = np.linalg.svd(S, full_matrices=False)
    B = U[:, sv > sv[0] * 1e-10] if sv.size and sv[0] > 0 else U[:, :0]
    if B.shape[1] == 0:
        return 1.0
    if not sigma > 0:
        return 0.0
    index, rows = np.unique(np.asarray(campaigns), return_inverse=True, return_counts=True)[1:]
    sums = np.stack([np.bincount(index, weights=b, minlength=rows.size) for b in B.T])   # B'D (k, n)
    c = B.T @ y
    G = (sums / rows) @ sums.T
    stat = float(c @ G @ c) / sigma ** 2
    C = sums @ sums.T + np.eye(B.shape[1])
    w, V = np.linalg.eigh(C)
    root = V @ np.diag(np.sqrt(np.maximum(w, 0.0))) @ V.T
    lam = np.maximum(np.linalg.eigvalsh(root @ G @ root), 0.0)
    null = (np.random.default_rng(seed).standard_normal((DRAWS, lam.size)) ** 2) @ lam
    return float((1 + np.count_nonzero(null >= stat)) / (DRAWS + 1))
