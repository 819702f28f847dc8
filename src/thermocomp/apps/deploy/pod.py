r"""POD of the temperature field and reconstruction from any sensor subset (pure core).

Paper 002 (thermal mode shapes): the snapshot matrix :math:`T` (sensors ×
instants) is decomposed by SVD, :math:`T = U \Sigma V^\top`, and the first
:math:`r` left singular vectors form the reduced basis :math:`\Phi_r`.  From the
readings :math:`T_s` of any subset :math:`s` of at least :math:`r` sensors the
whole field is

.. math:: \hat T = \Phi_r\, \Phi_r[s]^{+}\, T_s = M_s\, T_s ,

and the measured sensors are *self-predicted*: :math:`E_s = T_s - \hat T_s`.

The snapshots are the temperature changes since each campaign's first sample
(the frame the compensation models see), so a campaign starts at the zero
field and ambient levels that differ between campaigns are no mode.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from sklearn.base import BaseEstimator


def windowed_mean(E: np.ndarray, groups: np.ndarray | None, window: int) -> np.ndarray:
    """Trailing mean over ``window`` rows (fewer at a campaign's start), per campaign."""
    out = np.empty_like(E, dtype=float)
    bounds = _group_bounds(groups, len(E))
    for a, b in bounds:
        c = np.cumsum(np.vstack([np.zeros((1, E.shape[1])), E[a:b]]), axis=0)
        n = np.arange(1, b - a + 1)
        lo = np.maximum(n - window, 0)
        out[a:b] = (c[n] - c[lo]) / (n - lo)[:, None]
    return out


def _group_bounds(groups, n: int) -> list[tuple[int, int]]:
    if groups is None:
        return [(0, n)]
    g = np.asarray(groups)
    cuts = np.flatnonzero(g[1:] != g[:-1]) + 1
    edges = np.concatenate([[0], cuts, [n]])
    return list(zip(edges[:-1], edges[1:]))


def leverage(phi_s: np.ndarray) -> np.ndarray:
    """Diagonal of the hat matrix :math:`\\Phi_s \\Phi_s^+` (how much each sensor predicts itself)."""
    q, _ = np.linalg.qr(phi_s)
    return np.einsum("ij,ij->i", q, q)


class ThermalPOD(BaseEstimator):
    r"""Reduced modal basis of the temperature field (paper 002, eqs. 1–7).

    Parameters
    ----------
    energy : float
        Captured energy :math:`\sum_{k\le r}\sigma_k^2 / \sum\sigma_k^2` that sets
        the smallest number of modes.
    modes : int, optional
        Fixed :math:`r` (overrides ``energy`` and ``fit_band_c``).
    fit_band_c : float, optional
        Raise :math:`r` above the energy's until the training field is
        self-predicted within this band (°C): the 99.5th percentile of the
        windowed leave-one-out self-prediction error of the observable sensors.
        A basis that cannot reproduce the field it was trained on would alarm on
        that very field, whatever the captured energy says.  ``None``: energy only.
    window : int
        Samples of the trailing mean used for ``fit_band_c``.
    max_leverage : float
        A sensor whose hat-matrix diagonal exceeds this is *unobservable*: the
        other sensors cannot predict it (it carries a mode of its own, as an
        ambient sensor does), so self-prediction cannot judge it.
    min_redundancy : int
        :math:`r` is kept at most ``n_sensors - min_redundancy``: a basis with as
        many modes as sensors predicts every sensor exactly and sees nothing.

    Attributes
    ----------
    basis_ : ndarray (n_sensors, n_sensors_or_instants)
        All left singular vectors (columns), most energetic first.
    singular_values_ : ndarray
    energy_ : ndarray
        Cumulative captured energy per number of modes.
    n_modes_ : int
        :math:`r`.
    n_modes_energy_ : int
        The :math:`r` of the energy criterion alone.
    train_band_c_ : float
        The training self-prediction error at ``n_modes_`` (same statistic as ``fit_band_c``).
    """

    def __init__(self, energy: float = 0.99, modes: int | None = None,
                 fit_band_c: float | None = 0.2, window: int = 10, max_leverage: float = 0.9,
                 min_redundancy: int = 2):
        self.energy = energy
        self.modes = modes
        self.fit_band_c = fit_band_c
        self.window = window
        self.max_leverage = max_leverage
        self.min_redundancy = min_redundancy

    def fit(self, X, y=None, groups=None) -> "ThermalPOD":
        """``X``: snapshots (n_instants, n_sensors), ``groups``: campaign of each row (the
        windows of ``fit_band_c`` do not cross campaigns)."""
        X = np.asarray(X, dtype=float)
        if X.ndim != 2 or X.shape[1] < 2:
            raise ValueError(f"POD needs at least 2 sensors, got shape {X.shape}")
        if not np.isfinite(X).all():
            raise ValueError("POD snapshots must be finite (training campaigns with missing values)")
        if not 0 < self.energy <= 1:
            raise ValueError(f"energy must be in (0, 1], got {self.energy}")
        u, s, _ = np.linalg.svd(X.T, full_matrices=False)
        self.basis_, self.singular_values_ = u, s
        total = float(np.sum(s ** 2)) or 1.0
        self.energy_ = np.cumsum(s ** 2) / total
        n = X.shape[1]
        r_max = max(1, min(len(s), n - int(self.min_redundancy)))
        if self.modes is not None:
            r = int(self.modes)
            if not 1 <= r <= r_max:
                raise ValueError(f"modes={r}: need 1 <= modes <= {r_max} for {n} sensors "
                                 f"(min_redundancy={self.min_redundancy})")
            self.n_modes_energy_ = r
        else:
            r = int(min(np.searchsorted(self.energy_, self.energy - 1e-12) + 1, r_max))
            self.n_modes_energy_ = r
            if self.fit_band_c is not None:
                while r < r_max and self._train_band(X, groups, r) > self.fit_band_c:
                    r += 1
        self.n_modes_ = r
        self.train_band_c_ = self._train_band(X, groups, r)
        self.n_features_in_ = n
        return self

    @property
    def phi_(self) -> np.ndarray:
        """:math:`\\Phi_r` (n_sensors, r)."""
        return self.basis_[:, :self.n_modes_]

    def _train_band(self, X, groups, r: int) -> float:
        phi = self.basis_[:, :r]
        h = leverage(phi)
        observable = h < self.max_leverage
        if not observable.any():
            return 0.0
        E = self.deleted_residuals(X, r=r)[:, observable]
        return float(np.quantile(np.abs(windowed_mean(E, groups, self.window)), 0.995))

    def operator(self, active: Sequence[bool] | np.ndarray, r: int | None = None
                 ) -> tuple[np.ndarray, np.ndarray]:
        r"""``(M, h)`` for the active sensors: :math:`\hat T = M\,T_{active}` (n × s) and the
        leverage of each active sensor.  Uses ``min(r, s)`` modes when fewer sensors remain."""
        active = np.asarray(active, dtype=bool)
        r = min(self.n_modes_ if r is None else r, int(active.sum()))
        phi = self.basis_[:, :r]
        pinv = np.linalg.pinv(phi[active])
        return phi @ pinv, leverage(phi[active])

    def reconstruct(self, T_subset, subset) -> np.ndarray:
        r"""Whole field from the sensors ``subset`` (indices or mask): :math:`\Phi_r\,\Phi_r[s]^+ T_s`.
        ``T_subset``: (n_instants, s) or (s,)."""
        mask = np.zeros(self.n_features_in_, dtype=bool)
        mask[subset] = True
        M, _ = self.operator(mask)
        return np.asarray(T_subset, dtype=float) @ M.T

    def self_prediction(self, X) -> np.ndarray:
        """Paper's :math:`E_s = T_s - \\hat T_s` with every sensor in the fit (n_instants, n)."""
        X = np.asarray(X, dtype=float)
        M, _ = self.operator(np.ones(self.n_features_in_, dtype=bool))
        return X - X @ M.T

    def deleted_residuals(self, X, r: int | None = None) -> np.ndarray:
        r"""Each sensor minus its prediction from the *other* sensors,
        :math:`E_s / (1 - h_{ss})`: a faulty sensor no longer pulls the fit toward itself
        (NaN where a sensor is unobservable)."""
        X = np.asarray(X, dtype=float)
        r = self.n_modes_ if r is None else r
        phi = self.basis_[:, :r]
        M = phi @ np.linalg.pinv(phi)
        h = np.diag(M)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(h < 1 - 1e-9, (X - X @ M.T) / (1 - h), np.nan)
