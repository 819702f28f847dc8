"""A jump of the air's sensor: the real air or the sensor's offset, told by the heat the others
take in (mon105b).

At the instant the two are one jump of ``T_amb``; over the window that follows, a real step
drives the machine (every structure sensor takes in heat from the new air), an offset drives
nothing.  The others' field is modelled as a linear system driven by the air,
``z[t+1] - z[t] = F z[t] + b A[t] + c + e[t]`` (``z``: their absolute readings on their first
``r`` principal directions), fitted by least squares on the train campaigns; the innovations'
covariance there is mostly the spindle's unobserved heat, so weighting by its inverse counts the
spindle's directions little.  Read under the offset hypothesis (air = reading - J), the air
step the innovations call for is the GLS estimate ``s``; the jump is real when ``s`` follows
``J`` (same sign, more than a quarter of it) beyond every window of the train campaigns."""

from __future__ import annotations

import numpy as np

SHARE = 0.25     # the least share of the jump the others must call for


class AirInput:
    """The others' field driven by the sensor ``j`` (the air), fitted on training ``arrays``
    (absolute readings, (samples, sensors) each) over ``window``-sample windows."""

    def __init__(self, arrays, j: int, modes: int, window: int):
        self.j, self.window = int(j), int(window)
        others = np.ones(arrays[0].shape[1], dtype=bool)
        others[self.j] = False
        self.others = others
        T = np.vstack([a[:, others] for a in arrays])
        self.mu = T.mean(0)
        self.V = np.linalg.svd(T - self.mu, full_matrices=False)[2][:max(1, min(modes, others.sum()))]
        X = np.vstack([self._design(a[:-1]) for a in arrays])
        Y = np.vstack([np.diff(self._z(a), axis=0) for a in arrays])
        self.M = np.linalg.lstsq(X, Y, rcond=None)[0]
        E = Y - X @ self.M
        Sinv = np.linalg.pinv(np.atleast_2d(np.cov(E.T)))
        self.b = self.M[len(self.V)]
        self.w = Sinv @ self.b / (self.b @ Sinv @ self.b)     # s = mean_t w' e_t
        bound = [np.abs(self.called_for(a[k:k + self.window])) for a in arrays
                 for k in range(len(a) - self.window + 1)]
        self.bound = float(max(bound)) if bound else np.inf

    def _z(self, a: np.ndarray) -> np.ndarray:
        return (a[:, self.others] - self.mu) @ self.V.T

    def _design(self, a: np.ndarray) -> np.ndarray:
        return np.c_[self._z(a), a[:, self.j], np.ones(len(a))]

    def called_for(self, rows: np.ndarray) -> float:
        """The air step (°C) the others' innovations over ``rows`` (absolute readings, the air
        as read) call for beyond the air read; NaN with a missing reading."""
        e = np.diff(self._z(rows), axis=0) - self._design(rows[:-1]) @ self.M
        return float((e @ self.w).mean())

    def real(self, rows: np.ndarray, jump: float) -> tuple[bool, float]:
        """``(taken as real, s)`` for ``rows`` read under the offset hypothesis after a jump."""
        s = self.called_for(rows)
        return bool(np.isfinite(s) and s * np.sign(jump) > max(SHARE * abs(jump), self.bound)), s


def air_inputs(arrays, names, is_air, modes: int, window: int) -> dict:
    """An :class:`AirInput` per sensor of ``names`` that ``is_air`` names, where training has
    two campaigns or more and enough rows to fit it."""
    rows = sum(len(a) - 1 for a in arrays)
    out = {}
    for j, name in enumerate(names):
        if is_air(name) and len(arrays) >= 2 and len(names) > 2 and rows > 4 * (modes + 2):
            out[j] = AirInput(arrays, j, modes, window)
    return out
