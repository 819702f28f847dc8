r"""Artefact calibration: error parameters from measured ball distances (papers 000 and 001).

Linearised, the deviation of the distance between balls i and j of a pose is

.. math::

    \Delta d_{ij} = -u_{ij}^T \, (e(q_j) - e(q_i)) + \nu_{ij}, \qquad e(q) = B(q)\, p,

with :math:`u_{ij}` the nominal unit vector from ball i to ball j, :math:`B` the small-angle
kinematic model's basis and :math:`\nu` the measurement noise.  The minus: the machine
reads a ball at the command :math:`q` whose actual TCP :math:`q + e(q)` is on it, so its
reading is the ball's centre minus the error there.  Every probed centre is off by
``probing_um`` per coordinate, every calibrated ball of the artefact by ``ball_um`` (the
same in every pose), plus a floor for what the linearisation leaves out.  The noise is
therefore correlated (distances share balls, poses share the artefact); the parameters are
found by generalised least squares, :math:`\hat p = (A^T \Sigma^{-1} A)^{-1} A^T \Sigma^{-1}
\Delta d`, with standard uncertainties from :math:`(A^T \Sigma^{-1} A)^{-1}`.

With a prior (``prior_sd``: what the machine's parameters are expected to be, zero mean and
standard deviation :math:`s`, e.g. the ranges a design study draws machines from) every
parameter is estimated by its posterior mean, :math:`\hat p = (A^T \Sigma^{-1} A + S^{-1})^{-1}
A^T \Sigma^{-1} \Delta d` with :math:`S = \mathrm{diag}(s^2)`: a combination the poses cannot
see, or see only faintly, is shared among its parameters as the prior expects instead of being
given to one of them in full (or amplified from the noise), which is what the volumetric error
of the identified model depends on.

What a pose set cannot see is found before fitting: the parameters are taken in priority
order and one whose whitened column is (numerically) a combination of those kept before
is dropped, reported with the kept parameters it is confounded with.  Distances whose
studentised residual exceeds ``outlier_z`` are flagged and the cycle is refitted without
them.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field

import numpy as np
from scipy import linalg

from .artefact import Setup, column, pairs

FLOOR_UM = 0.02          # what the linearisation leaves out (second order: ~0.01 µm at 50 µm errors)
DEPENDENT = 1e-6         # a column this close (relative) to the span of the kept ones is not seen
PARTIAL = 10.0           # a cycle knowing a parameter this many times worse than a full one cannot


class CycleError(ValueError):
    """A cycle whose measured distances cannot identify the parameters (``cycle`` 0-based)."""

    def __init__(self, cycle: int, missing: int, total: int, why: str = ""):
        if "cannot identify the parameters" in why:     # says nothing more than the message
            why = ""
        self.cycle, self.missing, self.total, self.why = cycle, missing, total, why
        super().__init__(f"cycle {cycle + 1}: the {total - missing} distances measured of {total} "
                         f"cannot identify the parameters{f' ({why})' if why else ''}")


@dataclass
class Design:
    """The linearised measurement model of a set-up: one row per (pose, ball pair)."""

    columns: list[str]
    rows: list[tuple[str, int, int]]
    A: np.ndarray                  # (m, p) distance deviation per unit parameter (µm per unit)
    cov: np.ndarray                # (m, m) noise covariance (µm²)


def design(setup: Setup, floor_um: float = FLOOR_UM) -> Design:
    """The measurement model of every pose and ball pair of ``setup``."""
    model, array = setup.model, setup.array
    nb = array.n_balls
    ball_pairs = pairs(nb)
    i, j = (np.array(b) - 1 for b in zip(*ball_pairs))          # 0-based, every pair at once
    n = np.arange(len(ball_pairs))

    def signed(vectors):
        """``(pairs, 3 * nb)``: each pair's unit vector at ball j, its opposite at ball i."""
        out = np.zeros((len(ball_pairs), nb, 3))
        out[n, j], out[n, i] = vectors, -vectors
        return out.reshape(len(ball_pairs), -1)

    w = array.centres()[j] - array.centres()[i]
    h = signed(w / np.linalg.norm(w, axis=1, keepdims=True))  # the artefact's frame: every pose alike
    rows, blocks, probing = [], [], []
    for pose in setup.poses:
        balls = pose.balls(array)
        basis = model.basis(balls - model.tool)               # commands that put the TCP on a ball
        d = balls[j] - balls[i]
        u = d / np.linalg.norm(d, axis=1, keepdims=True)
        rows += [(pose.name, a, b) for a, b in ball_pairs]
        blocks.append(-np.einsum("nc,ncp->np", u, basis[j] - basis[i]))   # reading = centre - error
        g = signed(u)                                          # this pose's probed centres
        probing.append(g @ g.T)
    H = np.tile(h, (len(setup.poses), 1))
    # poses share no probed centre: the probing part is block diagonal (one product per pose,
    # not of all the poses' centres at once: 1.7 GFlop for 26 poses of 11 balls)
    cov = (setup.probing_um ** 2) * linalg.block_diag(*probing) + (setup.ball_um ** 2) * H @ H.T
    cov[np.diag_indices_from(cov)] += floor_um ** 2
    return Design([column(*r) for r in rows], rows, np.vstack(blocks), cov)


@dataclass
class Identifiability:
    kept: list[int]
    dropped: dict = field(default_factory=dict)     # name -> names it is confounded with


def identifiability(A_white: np.ndarray, names: list[str]) -> Identifiability:
    """Which parameters a (whitened) design sees, in the given priority order."""
    norms = np.linalg.norm(A_white, axis=0)
    scale = norms.max() if norms.size and norms.max() > 0 else 1.0
    kept, dropped = [], {}
    for j, name in enumerate(names):
        col = A_white[:, j]
        if norms[j] <= DEPENDENT * scale:
            dropped[name] = []                            # no effect at all on these distances
            continue
        if kept:
            coef, *_ = np.linalg.lstsq(A_white[:, kept], col, rcond=None)
            residual = col - A_white[:, kept] @ coef
            if np.linalg.norm(residual) <= DEPENDENT * norms[j]:
                weight = np.abs(coef) * norms[kept]
                order = np.argsort(weight)[::-1]
                dropped[name] = [names[kept[k]] for k in order[:3] if weight[k] > 1e-3 * norms[j]]
                continue
        kept.append(j)
    return Identifiability(kept, dropped)


class ArtefactCalibration:
    """Identify the error parameters of every measurement cycle.

    Parameters
    ----------
    setup : Setup
        Machine model, artefact, poses and uncertainties.
    outlier_z : float
        A distance whose studentised residual exceeds this is flagged and left out of its cycle.
    prior_sd : array-like or None
        Prior standard deviation of every parameter of the model (µm, µm/m): then every
        parameter is estimated (posterior mean); None: generalised least squares of those
        the poses see.

    Attributes
    ----------
    design_ : Design
    names_ : list of str
        The estimated parameters in model order: those the poses see, or all with a prior.
    seen_ : list of str
        The parameters the distances alone identify.
    unidentifiable_ : dict
        Parameter -> the identified parameters it is confounded with ([] = no effect at all).
    uncertainty_ : ndarray
        Standard uncertainty of each estimated parameter (one cycle, all distances; with a
        prior, the posterior's).
    residual_sd_ : ndarray
        Standard deviation of each distance's residual that the declared uncertainties predict
        (one cycle, all distances).
    residual_dof_ : float
        Effective degrees of freedom of one cycle's residual sum of squares (Satterthwaite:
        a distance's noise is shared with the others of its balls, so far fewer than the
        distances less the parameters).
    """

    def __init__(self, setup: Setup, outlier_z: float = 6.0, prior_sd=None):
        self.setup = setup
        self.outlier_z = outlier_z
        self.prior_sd = prior_sd

    def fit(self) -> ArtefactCalibration:
        names = self.setup.model.names
        self._precision = 0.0
        if self.prior_sd is not None:
            sd = np.asarray(self.prior_sd, float)
            if sd.shape != (len(names),) or not np.all(np.isfinite(sd)) or np.any(sd <= 0):
                raise ValueError(f"prior_sd must be {len(names)} finite positive numbers, one per "
                                 f"parameter of the model, got shape {sd.shape}")
            self._precision = np.diag(1.0 / sd ** 2)
        self.design_ = design(self.setup)
        self._chol = linalg.cholesky(self.design_.cov, lower=True)
        self._whiteners = {}
        white = linalg.solve_triangular(self._chol, self.design_.A, lower=True)
        ident = identifiability(white, names)
        self.seen_ = [names[j] for j in ident.kept]
        self.kept_ = ident.kept if self.prior_sd is None else list(range(len(names)))
        self.names_ = [names[j] for j in self.kept_]
        self.unidentifiable_ = ident.dropped
        # every distance measured: the solver of that mask, from the factor computed above
        self._solvers = {}
        everything = np.ones(len(self.design_.rows), bool)
        self._solve, _, self.residual_sd_, self.param_cov_ = self._solver(everything, self._chol)
        self.uncertainty_ = np.sqrt(np.diag(self.param_cov_))
        A = self.design_.A[:, self.kept_]
        V = self.design_.cov - A @ self.param_cov_ @ A.T            # the residuals' covariance
        self.residual_dof_ = float(np.trace(V) ** 2 / np.sum(V ** 2))   # Satterthwaite
        return self

    def copy(self) -> ArtefactCalibration:
        """This fitted calibration, to be used apart: the same fit, caches of its own."""
        new = copy.copy(self)
        new._solvers, new._whiteners = dict(self._solvers), dict(self._whiteners)
        return new

    def full(self, estimates: np.ndarray) -> np.ndarray:
        """Identified parameters ``(..., k)`` -> the model's full vector (unseen ones at 0)."""
        out = np.zeros(estimates.shape[:-1] + (len(self.setup.model.names),))
        out[..., self.kept_] = estimates
        return out

    def predict(self, estimates: np.ndarray) -> np.ndarray:
        """Distance deviations ``(..., m)`` of identified parameters ``(..., k)``."""
        return estimates @ self.design_.A[:, self.kept_].T

    def identify(self, distances: np.ndarray) -> tuple[np.ndarray, list[dict]]:
        """Parameters ``(n_cycles, k)`` of distance deviations ``(n_cycles, m)`` (columns in
        ``design_.columns`` order, NaN = not measured), and the flagged outliers
        ``[{"cycle", "column", "residual_um", "z"}]``."""
        D = np.atleast_2d(np.asarray(distances, float))
        P = np.where(np.isfinite(D), D, 0.0) @ self._solve.T
        flagged = []
        for t in range(D.shape[0]):
            try:
                P[t], out = self._cycle(D[t], P[t])
            except ValueError as err:
                raise CycleError(t, int(np.isnan(D[t]).sum()), D.shape[1], str(err)) from err
            flagged += [{"cycle": t, **o} for o in out]
        return P, flagged

    def _cycle(self, d, p):
        """One cycle's estimate (``p``: the estimate from every distance) and its outliers."""
        mask = np.isfinite(d)
        if mask.all():
            z = (d - self.predict(p)) / self.residual_sd_
        else:                           # the same gaps in many cycles: one solver (cached)
            p, _, z = self._masked(d, mask)
        if np.max(np.abs(z)) <= self.outlier_z:
            return p, []
        p, out, _ = self._robust_cycle(d, mask)
        return p, out

    def screen(self, distances: np.ndarray) -> tuple[list[dict], bool]:
        """The outliers of one cycle (as :meth:`identify` flags them) and whether they reached
        the cap of a tenth of its distances: then the distances do not fit the set-up at all
        (an artefact or a machine described wrongly), which no outlier rule can mend."""
        d = np.asarray(distances, float)
        mask = np.isfinite(d)
        # where the search would stop at its first fit, without its whitener (the fit of a cycle
        # with gaps is cached for identify); a cycle that fit refuses is the search's to judge
        try:
            z = ((d - self.predict(self._solve @ d)) / self.residual_sd_ if mask.all()
                 else self._masked(d, mask)[2])
        except ValueError:
            z = None
        if z is not None and np.max(np.abs(z)) <= self.outlier_z:
            return [], False
        _, out, capped = self._robust_cycle(d, mask)
        return out, capped

    def _solver(self, mask, chol=None):
        """``(M, A, sd, cov)`` of the GLS (or posterior mean) from the distances in ``mask``: estimate
        ``M @ d[mask]``, model ``A``, standard deviation of each residual, covariance of the
        estimate; cached per mask (``chol``: the noise covariance's factor on ``mask``, if known)."""
        cache = self._solvers
        key = mask.tobytes()
        if key not in cache:
            A = self.design_.A[np.ix_(mask, self.kept_)]
            cov_d = self.design_.cov[np.ix_(mask, mask)]
            if chol is None:
                chol = linalg.cholesky(cov_d, lower=True)
            Aw = linalg.solve_triangular(chol, A, lower=True)
            try:
                cov = np.linalg.inv(Aw.T @ Aw + self._precision)
            except np.linalg.LinAlgError as err:
                raise ValueError("the distances left measured cannot identify the parameters") from err
            if self.prior_sd is None and not mask.all():
                self._check_seen(np.sqrt(np.clip(np.diag(cov), 0.0, None)))
            M = cov @ linalg.solve_triangular(chol, Aw, lower=True, trans="T").T     # cov A' S^-1
            sd = np.sqrt(np.clip(np.diag(cov_d) - np.einsum("ij,jk,ik->i", A, cov, A), 1e-12, None))
            if len(cache) >= 64:            # the gaps of a few dozen cycles
                cache.pop(next(iter(cache)))
            cache[key] = (M, A, sd, cov)
        return cache[key]

    def _check_seen(self, u) -> None:
        """A cycle whose measured distances know a parameter far worse than a full cycle
        (``PARTIAL`` times its uncertainty) cannot identify it: an outside probe's cycle with
        one pose of 16 measured gave E_XX1 = 2.6e16 µm and a 'compensated' VCE of 7e14 µm, exit
        0; inverting a nearly singular matrix raises nothing."""
        worse = u / np.maximum(self.uncertainty_, 1e-300)
        if np.any(~np.isfinite(worse) | (worse > PARTIAL)):
            j = int(np.argmax(np.where(np.isfinite(worse), worse, np.inf)))
            raise ValueError(f"the distances left measured know {self.names_[j]} to ±{u[j]:.3g}, "
                             f"{worse[j]:.3g} times a full cycle's")

    def _masked(self, d, mask):
        """GLS of one cycle from the distances in ``mask``: estimate, residuals, studentised."""
        M, A, sd, _ = self._solver(mask)
        p = M @ d[mask]
        r = d[mask] - A @ p
        return p, r, r / sd

    def _robust_cycle(self, d, mask):
        """Leave out the worst distance while any studentised residual exceeds ``outlier_z``, up
        to a tenth of the distances: ``(estimate, left out, whether the cap was reached)``.

        Many gross errors swamp that search (the good distances' residuals grow with them): it
        leaves out good distances with the bad (one whose offset, given the rest, is not beyond
        ``outlier_z``), or reaches the cap.  Then the cycle is searched again with the
        mean-shift test of :meth:`_closure_search`, and that result is kept when it leaves out
        fewer distances (or the first reached the cap), stays below the cap, and keeps every
        distance within ``outlier_z`` studentised: the closure test alone would
        accept distances the noise model can explain at any size (a mis-probed ball, a wrong
        machine or prior).
        """
        linv = self._whitener(mask)
        p, out, capped, swamped = self._marginal_search(d, mask, linv)
        if swamped:
            p2, out2, capped2 = self._closure_search(d, mask, linv)
            if not capped2 and (capped or len(out2) < len(out)):
                keep = mask.copy()
                keep[[self.design_.columns.index(o["column"]) for o in out2]] = False
                if np.max(np.abs(self._masked(d, keep)[2])) <= self.outlier_z:
                    return p2, out2, False
        return p, out, capped

    def _whitener(self, mask):
        """``L^-1`` of the noise covariance of the distances in ``mask``, cached per mask: a
        column excluded from every cycle gives every cycle's search the same gaps (a factor
        and an inverse of 1430 distances each, 1 s a cycle, before)."""
        key = mask.tobytes()
        if key not in self._whiteners:
            idx = np.flatnonzero(mask)
            chol = (self._chol if mask.all()
                    else linalg.cholesky(self.design_.cov[np.ix_(idx, idx)], lower=True))
            if len(self._whiteners) >= 4:           # (m, m) each: the all and a few sets of gaps
                self._whiteners.pop(next(iter(self._whiteners)))
            linv, info = linalg.lapack.dtrtri(chol, lower=1)    # a third of solving against I
            if info:
                raise np.linalg.LinAlgError(f"dtrtri: {info}")
            self._whiteners[key] = linv, linv @ self.design_.A[np.ix_(idx, self.kept_)]
        return self._whiteners[key][0]

    def _marginal_search(self, d, mask, linv):
        """The search on studentised residuals (each against its own standard deviation):
        ``(estimate, left out, capped, swamped)``, swamped when it reached the cap or left out
        a distance whose offset, given the rest, is within ``outlier_z`` of its uncertainty.

        A distance left out is given a free offset of its own, one more column of the whitened
        design (the same estimate as refitting without it): the noise covariance is inverted
        once (per set of gaps), not factorised again for every distance left out.  The offsets
        are projected out of the parameters' normal equations (their whitened columns kept
        orthonormal, Gram-Schmidt twice): each distance left out is a rank-one downdate of a
        k x k system, where inverting the whole (k + left out)² system at every step cost
        O(left out³) a step (3.1 of the 7 s of CPU the outlier searches of
        tests/shell/test_calibrate.py took); the offsets' own test is solved once, at the end.
        """
        idx, A, white, dw = self._whitened(d, mask, linv)
        cap = int(np.floor(0.1 * mask.size)) + 1
        info = white.T @ white + self._precision             # normal equations without the left out
        rhs = white.T @ dw
        U = np.empty((idx.size, cap))                        # the left out's whitened columns, orthonormal
        var = np.diag(self.design_.cov)[idx]
        left = np.zeros(idx.size, bool)
        out = []
        while True:
            try:
                cov = np.linalg.inv(info)
            except np.linalg.LinAlgError as err:
                raise ValueError("the distances left measured cannot identify the parameters") from err
            p = cov @ rhs
            r = d[idx] - A @ p
            sd = np.sqrt(np.clip(var - np.sum((A @ cov) * A, axis=1), 1e-12, None))
            z = np.where(left, 0.0, r / sd)
            worst = int(np.argmax(np.abs(z)))
            if abs(z[worst]) <= self.outlier_z:
                return p, out, False, self._shifts_within(white, dw, linv[:, left])
            if len(out) >= 0.1 * mask.size:
                return p, out, True, True
            out.append({"column": self.design_.columns[idx[worst]], "residual_um": float(r[worst]),
                        "z": float(z[worst])})
            q = len(out) - 1
            left[worst] = True
            u = linv[:, worst].copy()
            for _ in range(2):
                u -= U[:, :q] @ (U[:, :q].T @ u)
            u /= np.linalg.norm(u)
            U[:, q] = u
            v = white.T @ u
            info -= np.outer(v, v)
            rhs -= v * (u @ dw)

    def _shifts_within(self, white, dw, W) -> bool:
        """Whether a distance left out (whitened unit columns ``W``) has an offset, given the
        rest, within ``outlier_z`` of its uncertainty: its mean-shift test in the fit with a
        free offset for each."""
        if not W.shape[1]:
            return False
        X = np.hstack([white, W])
        gram = X.T @ X
        k = white.shape[1]
        gram[:k, :k] += self._precision
        try:
            cov = np.linalg.inv(gram)
        except np.linalg.LinAlgError as err:
            raise ValueError("the distances left measured cannot identify the parameters") from err
        beta = cov @ (X.T @ dw)
        shift = np.abs(beta[k:]) / np.sqrt(np.clip(np.diag(cov)[k:], 1e-300, None))
        return bool(np.any(shift <= self.outlier_z))

    def _whitened(self, d, mask, linv):
        """``(indices, design, whitened design, whitened distances)`` of the distances in
        ``mask`` over the estimated parameters, both searches' starting point."""
        idx = np.flatnonzero(mask)
        A = self.design_.A[np.ix_(idx, self.kept_)]
        cached, white = self._whiteners.get(mask.tobytes(), (None, None))
        return idx, A, white if cached is linv else linv @ A, linv @ d[idx]

    def _closure_search(self, d, mask, linv):
        """The search on the mean-shift test of every distance: its deviation from what the fit
        and the other distances (through the correlated noise: distances sharing a ball, poses
        sharing the artefact) predict, in its own standard deviation.

        Distances computed from probed centres agree with each other to the probing noise
        within a pose, so this test sees a lone gross error however many there are; but a
        mis-probed ball moves all its distances alike and is explained by the noise model,
        which is why it is the fallback of the studentised search, not its replacement.  The
        whitened design grows by one column per distance left out, kept orthonormal
        (Gram-Schmidt, twice) for a test that stays exact when the gross errors are 10^4
        standard deviations.
        """
        idx, A, X, dw = self._whitened(d, mask, linv)
        m, k = A.shape
        if self.prior_sd is not None:       # the prior as k pseudo-distances of value 0
            X = np.vstack([X, np.diag(1.0 / np.asarray(self.prior_sd, float)[self.kept_])])
            dw = np.append(dw, np.zeros(k))
        Q0, R0 = np.linalg.qr(X)
        n0, cap = Q0.shape[1], int(np.floor(0.1 * mask.size)) + 1
        Q = np.empty((Q0.shape[0], n0 + cap), order="F")   # grown a column per left out, not copied
        R = np.zeros((n0 + cap, n0 + cap))
        Q[:, :n0], R[:n0, :n0] = Q0, R0
        n = n0
        den = np.sum(linv ** 2, axis=0) - np.sum((linv.T @ Q0[:m]) ** 2, axis=1)
        coef = Q0.T @ dw
        g = linv.T @ (dw - Q0 @ coef)[:m]
        left = np.zeros(m, bool)
        out = []
        while True:
            p = linalg.solve_triangular(R[:n, :n], coef)[:k]
            t = np.where(left, 0.0, g / np.sqrt(np.clip(den, 1e-300, None)))
            worst = int(np.argmax(np.abs(t)))
            if abs(t[worst]) <= self.outlier_z:
                return p, out, False
            if len(out) >= 0.1 * mask.size:
                return p, out, True
            out.append({"column": self.design_.columns[idx[worst]],
                        "residual_um": float(d[idx[worst]] - A[worst] @ p), "z": float(t[worst])})
            left[worst] = True
            w = np.zeros(Q.shape[0])
            w[:m] = linv[:, worst]
            c = Q[:, :n].T @ w
            w -= Q[:, :n] @ c
            c2 = Q[:, :n].T @ w
            w -= Q[:, :n] @ c2
            rho = np.linalg.norm(w)
            Q[:, n] = w / rho
            R[:n, n], R[n, n] = c + c2, rho
            n += 1
            coef = Q[:, :n].T @ dw
            # two products with linv (m² each; two matrix-vector ones: 8x quicker than one of 2 columns)
            g = linv.T @ (dw - Q[:, :n] @ coef)[:m]
            den = den - (linv.T @ Q[:m, n - 1]) ** 2


def equivalent_truth(calibration: ArtefactCalibration, truth: np.ndarray) -> np.ndarray:
    """The identified parameters' values that reproduce the distances of a full true parameter
    vector (rows): the truth the estimates are to be compared with when a dropped parameter
    is confounded with kept ones."""
    A = calibration.design_.A
    full = np.atleast_2d(truth) @ A.T
    coef, *_ = np.linalg.lstsq(A[:, calibration.kept_], full.T, rcond=None)
    return coef.T
