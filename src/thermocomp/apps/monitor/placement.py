r"""Optimal sensor placement on a POD basis (paper 002, section 2.1; Benner et al. 2019).

Two rankings of the sensors, best first; the first ``s >= r`` of either are the
sensors to keep (or to install) so that the ``r`` mode coefficients stay well
determined:

* :func:`qr_sensors` — QR with column pivoting of :math:`\Phi_r^\top` (Q-DEIM),
  and of :math:`\Phi_r\Phi_r^\top` beyond ``r`` sensors (oversampling);
* :func:`covariance_sensors` — the sequential covariance method: pick the sensor
  whose temperature has the largest variance left unexplained by the sensors
  already chosen, under the field covariance :math:`\Phi\Sigma^2\Phi^\top / m`
  (a pivoted Cholesky factorisation).
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import qr


def qr_sensors(phi: np.ndarray, s: int | None = None) -> np.ndarray:
    """Sensor indices ranked by QR pivoting (first ``s``; all by default)."""
    n, r = phi.shape
    s = n if s is None else int(s)
    if not r <= s <= n:
        raise ValueError(f"need r={r} <= s={s} <= n={n} sensors")
    target = phi.T if s == r else phi @ phi.T
    _, _, piv = qr(target, pivoting=True, mode="economic")
    return np.asarray(piv[:s])


def covariance_sensors(phi: np.ndarray, singular_values: np.ndarray, n_instants: int,
                       s: int | None = None, noise_c: float = 0.0) -> np.ndarray:
    """Sensor indices chosen one by one by the largest remaining (conditional) variance."""
    n, r = phi.shape
    s = n if s is None else int(s)
    if not 1 <= s <= n:
        raise ValueError(f"need 1 <= s={s} <= n={n} sensors")
    lam = np.asarray(singular_values[:r], float) ** 2 / max(int(n_instants), 1)
    C = (phi * lam) @ phi.T + noise_c ** 2 * np.eye(n)
    chosen: list[int] = []
    left = np.diag(C).copy()
    for _ in range(s):
        left[chosen] = -np.inf
        j = int(np.argmax(left))
        chosen.append(j)
        if C[j, j] <= 1e-15:   # nothing left to explain: the rest by their own variance
            continue
        C = C - np.outer(C[:, j], C[j, :]) / C[j, j]
        left = np.diag(C).copy()
    return np.asarray(chosen)
