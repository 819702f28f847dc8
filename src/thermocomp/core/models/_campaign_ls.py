r"""Ordinary least squares on unions of campaigns, from one QR factor per campaign.

The ATI elbow (:mod:`thermocomp.core.models.ati`) fits one MLR per held-out campaign and
number of intervals, each on a union of the other campaigns: on a climate-room record
(14 train runs, ``diagnose ati=cmeans``) 11,644 fits of ~6,000 rows.  ``diagnose``'s
closed-form CV (:mod:`thermocomp.apps.diagnose.cv`) fits each fold on a union of pieces of
rows (forward chaining: 16 nested prefixes of one record).  The union's least
squares problem is the stack of its campaigns' triangular factors: with
:math:`[\mathbf 1, Z_c, y_c] = Q_c R_c` per campaign :math:`c`,

.. math:: \min_b \|[\mathbf 1, Z_U] b - y_U\| \text{ over } U = \cup_c
          \iff \text{the QR of } [R_c]_{c \in U} \text{ stacked},

an orthogonal change of rows, so the solution is the same up to rounding and each fit
costs a QR of ``len(U)`` small squares instead of the rows.  The factor's block after the
intercept column is the factor of the centred design (the Householder step on the column of
ones centres the others), so :meth:`CampaignLeastSquares.fit` solves what
:class:`sklearn.linear_model.LinearRegression` solves -- ``scipy.linalg.lstsq`` of the
centred design with ``cond=tol``, the minimum-norm solution when the design is rank
deficient -- on a matrix with the same singular values.  Not the normal equations: those
square the condition number (a singular value 1e-6 of the largest, LinearRegression's cut-off,
would keep 4 of its digits there; the climate-room folds of full rank had condition numbers of
median 2.6e5, a third of them were rank deficient).  Where a singular value is so close to that
cut-off that rounding could put it on the other side, :meth:`~CampaignLeastSquares.fit` says
so (``None``) and the caller fits the rows themselves.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import lstsq
from sklearn.linear_model import LinearRegression

# LinearRegression's relative cut-off of the singular values (lstsq ``cond``)
LSTSQ_TOL = LinearRegression().tol
# singular values this close (relative) to the cut-off: rounding may decide their side
CUTOFF_BAND = 1e-6


def triangle(A: np.ndarray) -> np.ndarray:
    """The R of ``A = QR``, its ``min(A.shape)`` rows (scipy's ``mode='r'`` keeps all of A's,
    zeros below: stacked, they were most of the work; numpy's returns the triangle alone, in
    half scipy's time on a stack of twelve 62-column triangles)."""
    return np.linalg.qr(A, mode="r")


def at_cutoff(s: np.ndarray, rcond: float, band: float) -> bool:
    """Whether a singular value of ``s`` (largest first) is within a factor ``1 ± band`` (or,
    ``band >= 1``, a factor ``band``) of the cut-off ``rcond * s[0]``: which side of it the
    value falls on is then rounding's choice."""
    if not s.size or not s[0] > 0:
        return False
    cut = rcond * s[0]
    if band >= 1:
        return bool(np.any((s >= cut / band) & (s <= cut * band)))
    return bool(np.any(np.abs(s - cut) <= band * cut))


class FixedHead:
    """Each campaign's QR of the intercept and the design's first ``n`` columns (shifted), kept for
    fits whose later columns change on the same rows (the refit null's 99 permutations move only the
    tested effect's columns: diag111c); the later columns are then projected on it, not factored
    with it."""

    def __init__(self, n: int):
        self.n, self.factors = int(n), {}


class CampaignLeastSquares:
    """OLS fits of ``y`` on the design ``Z`` restricted to unions of campaigns.

    Parameters
    ----------
    Z : ndarray of shape (n_rows, n_features)
    y : ndarray of shape (n_rows,)
    rows : sequence of index arrays
        The rows of each campaign (campaign ``c`` is ``rows[c]``).
    fit_intercept : bool, default True
    tol : float
        Relative cut-off of the singular values (``LinearRegression.tol``).
    head : FixedHead, optional
        The campaigns' factors of ``Z``'s first columns, shared with fits that differ after them.
    """

    def __init__(self, Z, y, rows, fit_intercept: bool = True, tol: float = LSTSQ_TOL,
                 head: FixedHead | None = None):
        self.Z = np.asarray(Z, float)
        self.y = np.asarray(y, float)
        self.rows = list(rows)
        self.fit_intercept = fit_intercept
        self.tol, self.head = tol, head
        self._factors: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        # with an intercept the columns are factored less their means over all rows: the same
        # least squares, and its rounding scales with the columns' spread, not their level
        # (temperatures near 20 °C varying by tenths: 15x closer to the fits on the rows)
        n = sum(len(r) for r in self.rows)
        self.shift = np.zeros(self.Z.shape[1] + 1)
        if fit_intercept and n:
            self.shift[:-1] = sum(self.Z[r].sum(axis=0) for r in self.rows) / n
            self.shift[-1] = sum(self.y[r].sum() for r in self.rows) / n

    def _factor(self, c: int) -> tuple[np.ndarray, np.ndarray]:
        """The R of ``[1, Z_c, y_c]`` (``[Z_c, y_c]`` without intercept) and the column sums of
        ``[Z_c, y_c]``, computed once."""
        rows, first = self.rows[c], int(self.fit_intercept)
        if c not in self._factors and self.head is not None and len(rows) > first + self.Z.shape[1] + 1:
            self._factors[c] = self._factor_on_head(c)
        if c not in self._factors:
            # one array, in LAPACK's column order: a piece may be half a long record
            zy = np.empty((len(rows), first + self.Z.shape[1] + 1), order="F")
            zy[:, :first] = 1.0
            zy[:, first:-1] = self.Z[rows]
            zy[:, -1] = self.y[rows]
            zy[:, first:] -= self.shift
            self._factors[c] = triangle(zy), zy[:, first:].sum(axis=0)
        return self._factors[c]

    def _factor_on_head(self, c: int) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`_factor` from the head's ``Q1 R11`` of the first columns: the rest ``W`` (the later
        columns and y) projected out of ``Q1`` twice (twice is enough: Giraud et al. 2005), then
        factored alone, ``R = [[R11, Q1^T W], [0, R(W - Q1 Q1^T W)]]``: the same Gram matrix."""
        rows, first, n = self.rows[c], int(self.fit_intercept), self.head.n
        if c not in self.head.factors:
            A = np.empty((len(rows), first + n), order="F")
            A[:, :first] = 1.0
            A[:, first:] = self.Z[rows, :n] - self.shift[:n]
            Q, R = np.linalg.qr(A)
            self.head.factors[c] = Q, R, A[:, first:].sum(axis=0)
        Q, R11, sums = self.head.factors[c]
        W = np.empty((len(rows), self.Z.shape[1] - n + 1), order="F")
        W[:, :-1] = self.Z[rows, n:]
        W[:, -1] = self.y[rows]
        W -= self.shift[n:]
        sums = np.r_[sums, W.sum(axis=0)]
        R12 = Q.T @ W
        W -= Q @ R12
        again = Q.T @ W
        R12 += again
        W -= Q @ again
        R22 = triangle(W)
        top = np.hstack([R11, R12])
        bottom = np.hstack([np.zeros((R22.shape[0], R11.shape[1])), R22])
        return np.vstack([top, bottom]), sums

    def union(self, members) -> tuple[np.ndarray, int, np.ndarray]:
        """``(R, n, mean)`` of the rows of campaigns ``members``: the triangular factor of
        ``[Z, y]`` centred on these rows (uncentred without intercept), their number and the
        means of ``[Z, y]`` on them."""
        members = list(members)
        first = int(self.fit_intercept)
        R = triangle(np.vstack([self._factor(c)[0] for c in members]))
        n = sum(len(self.rows[c]) for c in members)
        return R[first:, first:], n, sum(self._factor(c)[1] for c in members) / n + self.shift

    def fit(self, members) -> tuple[np.ndarray, float] | None:
        """``(coef, intercept)`` of the OLS fit on the rows of campaigns ``members``, as
        ``LinearRegression(fit_intercept).fit`` gives them up to rounding; ``None`` when a
        singular value lies at the rank cut-off (then only a fit on the rows decides)."""
        R, _, mean = self.union(members)
        if not R.shape[0]:              # one row: nothing left to fit after the intercept
            return None
        coef, _, _, s = lstsq(R[:, :-1], R[:, -1], cond=self.tol, check_finite=False)
        if at_cutoff(s, self.tol, CUTOFF_BAND):
            return None
        if not self.fit_intercept:
            return coef, 0.0
        return coef, float(mean[-1] - mean[:-1] @ coef)

    def predict(self, fitted: tuple[np.ndarray, float], c: int) -> np.ndarray:
        """The fit ``fitted`` on campaign ``c``'s rows (``Z @ coef + intercept``, as MLR)."""
        coef, intercept = fitted
        return self.Z[self.rows[c]] @ coef + intercept
