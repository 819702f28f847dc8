r"""Ridge on the diagnosed effects only: the model inputs stay unpenalised.

A diagnosed linear model :math:`\hat y = c + b^\top x + w^\top \phi` adds
many regressors :math:`\phi` (a lag of every input, products ...) that are
strongly correlated with the inputs and with each other.  On one long,
drifting record their least-squares coefficients grow large and of opposite
signs, and the model extrapolates badly.  The penalty acts on them alone, on
their standardised scale:

.. math:: \min_{c, b, w}\ \lVert y - c - X b - \Phi_s w\rVert^2 + \alpha\, n\, \lVert w\rVert^2

(:math:`\Phi_s` the effect features centred and scaled by their standard
deviation, :math:`n` the number of rows), so :math:`\alpha = 0` is ordinary
least squares and the input coefficients are those of a regression on what
the effects leave.  By Frisch-Waugh-Lovell, :math:`w` is the ridge solution
of the residuals of :math:`y` and :math:`\Phi_s` on :math:`[1, X]`, and
:math:`(c, b)` the least-squares fit of :math:`y - \Phi_s w` on :math:`[1, X]`.
One eigendecomposition of the residual Gram matrix gives the whole path over
:math:`\alpha`, which is how the cross-validation picks it.

Which penalty on the path: the search weighs every candidate at its penalty of
least CV error (:func:`least_error`).  The deployed model takes the largest
penalty within one standard error of it (:func:`one_standard_error`) when every
effect it carries has several features: the CV of one record can be flat over
decades of penalty on a bank of correlated features (a lag of every input),
whose ill-determined directions the least-error penalty leaves free for a new
operating mix to read.  A one-feature effect (a product, a square) is one
well-determined direction, which the larger penalty only biases towards zero;
with one among the effects the least-error penalty stays
(``benchmarks/bench_diagnose_lag57.py``).
"""

from __future__ import annotations

import numpy as np

from ...core.models._campaign_ls import at_cutoff

ALPHAS = np.r_[0.0, np.logspace(-7, 1, 17)]   # penalties tried by the CV (0 = least squares)
_RANK_TOL = 1e-10                             # relative eigenvalue floor of the residual Gram


def least_error(mse) -> int:
    """Index of the penalty of least CV MSE (ties: the smallest penalty)."""
    return int(np.argmin(mse))


def one_standard_error(mse, block_mse) -> int:
    """Index of the largest penalty whose CV MSE is within one standard error of the least.

    The simplest fit the CV cannot tell from the best (ESL 7.10, glmnet's
    ``lambda.1se``); the standard error is that of the mean over the test
    blocks of their MSE at the least-error penalty.

    Parameters
    ----------
    mse : ndarray (n_alphas,)
        CV MSE per penalty, in the order of increasing penalty.
    block_mse : ndarray (n_blocks, n_alphas)
        Each test block's MSE per penalty.
    """
    mse, block_mse = np.asarray(mse, float), np.asarray(block_mse, float)
    best, n = least_error(mse), block_mse.shape[0]
    if n < 2:
        return best
    se = block_mse[:, best].std(ddof=1) / np.sqrt(n)
    return int(np.flatnonzero(mse <= mse[best] + se).max())


class InputsFit:
    """The least squares on the centred inputs of some rows, factored once (their SVD, lstsq's
    cut-off): every fit of the same rows with other effect features shares it.  The refit null's
    99 permutations refit each fold with only the candidate's moved columns new, and the inputs'
    lstsq was the largest share of their CPU (diag111c).  ``None`` from :meth:`of` when a singular
    value lies within a factor 100 of the cut-off (then only lstsq itself decides the rank)."""

    @classmethod
    def of(cls, X) -> "InputsFit | None":
        A = np.asarray(X, float)
        if not A.size:
            return None
        A = A - A.mean(axis=0)
        U, s, Vt = np.linalg.svd(A, full_matrices=False)
        rcond = np.finfo(float).eps * max(A.shape)      # lstsq's rcond=None
        if at_cutoff(s, rcond, 100.0):
            return None
        keep = s > rcond * (s[0] if s.size else 0.0)
        self = cls.__new__(cls)
        self.U, self.s, self.Vt = U[:, keep], s[keep], Vt[keep]
        return self

    def solve(self, B) -> np.ndarray:
        """The minimum-norm least-squares coefficients of every column of ``B`` (lstsq's)."""
        return self.Vt.T @ ((self.U.T @ B) / self.s[:, None])


class PartialRidgePath:
    """The fits of ``y`` on ``Z = [X, Phi]`` for every penalty on ``Phi``, on some rows.

    Parameters
    ----------
    Z : ndarray (n, p + q)
        The first ``n_free`` columns are the unpenalised inputs ``X``.
    y : ndarray (n,)
    n_free : int
    fit_intercept : bool, default True
    inputs : InputsFit, optional
        The centred inputs' factor on these rows (with an intercept), when already computed.
    """

    def __init__(self, Z, y, n_free: int, fit_intercept: bool = True, inputs: InputsFit | None = None):
        Z, y = np.asarray(Z, float), np.asarray(y, float)
        self.n_free, self.fit_intercept, self.n = int(n_free), fit_intercept, len(y)
        # centred on these rows with an intercept (the least-squares part then matches
        # LinearRegression's minimum-norm solution, also for collinear inputs)
        self.z_mean = Z.mean(axis=0) if fit_intercept else np.zeros(Z.shape[1])
        self.y_mean = float(y.mean()) if fit_intercept else 0.0
        Zc = Z - self.z_mean
        A, F = Zc[:, :self.n_free], Zc[:, self.n_free:]
        self._solve(A, F, F.std(axis=0), y - self.y_mean, None, inputs if fit_intercept else None)

    @classmethod
    def from_triangle(cls, R, n: int, mean, n_free: int) -> "PartialRidgePath | None":
        """The path (with intercept) from ``R``, the triangular factor of ``[Z, y]`` centred on
        the ``n`` rows (``CampaignLeastSquares.union``: ``Q^T [Z_c, y_c]``), and their means
        ``mean`` of ``[Z, y]``: the same least squares and Gram matrices as on the rows, so the
        same path up to rounding.  ``None`` when a singular value of the inputs' part lies within
        a factor 100 of lstsq's cut-off (only the rows then decide the rank)."""
        self = cls.__new__(cls)
        self.n_free, self.fit_intercept, self.n = int(n_free), True, int(n)
        self.z_mean, self.y_mean = np.asarray(mean[:-1], float), float(mean[-1])
        A, F = R[:, :self.n_free], R[:, self.n_free:-1]
        # the rows' rcond=None: eps * max(rows, columns) of the inputs' block
        rcond = np.finfo(float).eps * max(self.n, self.n_free)
        sd = np.sqrt(np.sum(F ** 2, axis=0) / self.n)     # Q is orthogonal: the centred norms
        return self if self._solve(A, F, sd, R[:, -1], rcond) else None

    def _solve(self, A, F, sd, yc, rcond, inputs: InputsFit | None = None) -> bool:
        """Fill the path from the centred inputs ``A``, effect features ``F`` (their standard
        deviations ``sd``) and target ``yc`` -- on the rows, or rotated by ``Q^T`` (``rcond``
        given: then False, nothing filled, where a singular value is at the cut-off).  ``inputs``:
        ``A``'s factor, computed before."""
        self.f_scale = np.where(sd > 0, sd, 1.0)
        Fs = F / self.f_scale
        # least squares of y and of every standardised feature on the inputs
        if inputs is not None:
            coef = inputs.solve(np.column_stack([yc, Fs]))
        else:
            coef, _, _, s = np.linalg.lstsq(A, np.column_stack([yc, Fs]), rcond=rcond)
            if rcond is not None and at_cutoff(s, rcond, 100.0):
                return False
        self.b_y, self.B_f = coef[:, 0], coef[:, 1:]
        ry, RF = yc - A @ self.b_y, Fs - A @ self.B_f
        if Fs.shape[1]:
            lam, V = np.linalg.eigh(RF.T @ RF)
        else:
            lam, V = np.zeros(0), np.zeros((0, 0))
        keep = lam > _RANK_TOL * max(float(lam.max()) if lam.size else 0.0, 1e-300)
        self.lam, self.V = lam[keep], V[:, keep]
        self.u = self.V.T @ (RF.T @ ry)
        return True

    def _weights(self, alphas) -> np.ndarray:
        """Standardised effect coefficients ``(q, n_alphas)``."""
        alphas = np.atleast_1d(np.asarray(alphas, float))
        return self.V @ (self.u[:, None] / (self.lam[:, None] + alphas[None, :] * self.n))

    def predict(self, Z, alphas) -> np.ndarray:
        """Predictions ``(m, n_alphas)`` of the rows ``Z`` for every penalty."""
        Zc = np.asarray(Z, float) - self.z_mean
        A, Fs = Zc[:, :self.n_free], Zc[:, self.n_free:] / self.f_scale
        return self.y_mean + (A @ self.b_y)[:, None] + (Fs - A @ self.B_f) @ self._weights(alphas)

    def coefficients(self, alpha: float) -> tuple[np.ndarray, float]:
        """``(coef over Z's columns, intercept)`` of the fit with penalty ``alpha``."""
        w = self._weights([alpha])[:, 0]
        coef = np.r_[self.b_y - self.B_f @ w, w / self.f_scale]
        return coef, self.y_mean - float(self.z_mean @ coef)
