"""Temperature sensors and the measurement chain (noise, quantisation).

A sensor is glued to a housing between lumped masses, so it reads a weighted
mean of node temperatures (``"ambient"`` stands for the air):

.. math::

    T_s = \\mathrm{round}_q\\Big(\\sum_j w_{sj} T_j + o_s + \\varepsilon\\Big),
    \\qquad \\varepsilon \\sim N(0, \\sigma_T^2)

with a fixed calibration offset :math:`o_s` and quantum :math:`q`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import solve_banded

AMBIENT = "ambient"


def quantise(values: np.ndarray, quantum: float) -> np.ndarray:
    """Round to multiples of ``quantum`` (no rounding when ``quantum`` <= 0)."""
    if not quantum or quantum <= 0:
        return values
    # Round the ratio first, then clean the float so 0.1-steps print as 0.1, not 0.30000000000000004.
    return np.round(np.round(values / quantum) * quantum, 10)


@dataclass(frozen=True)
class TemperatureSensor:
    """A temperature sensor in the contract's column ``column`` (``T_...``).

    Parameters
    ----------
    column : str
    weights : dict
        Node name (or ``"ambient"``) -> weight; weights sum to 1.
    offset_c : float
        Calibration offset in °C (cancels once referenced to the first sample).
    lag_s : float
        Time constant (s) of the sensor's first-order response: a magnet-mounted
        Pt100 behind a contact resistance follows its surface with a delay.
    """

    column: str
    weights: dict
    offset_c: float = 0.0
    lag_s: float = 0.0

    @property
    def main_node(self) -> str:
        """The node the sensor mostly sees (the ground truth's sensor -> node map)."""
        return max(self.weights, key=self.weights.get)


class SensorArray:
    """Sensors bound to a network's node order.

    Parameters
    ----------
    sensors : sequence of TemperatureSensor
    node_names : sequence of str
    """

    def __init__(self, sensors, node_names):
        self.sensors = tuple(sensors)
        self.columns = [s.column for s in self.sensors]
        columns = list(node_names) + [AMBIENT]
        position = {name: i for i, name in enumerate(columns)}
        self.weights = np.zeros((len(self.sensors), len(columns)))
        for row, sensor in enumerate(self.sensors):
            if not sensor.column.startswith("T_"):
                raise ValueError(f"sensor column {sensor.column!r} must start with 'T_'")
            if not np.isclose(sum(sensor.weights.values()), 1.0):
                raise ValueError(f"sensor {sensor.column!r}: weights must sum to 1")
            for node, w in sensor.weights.items():
                if node not in position:
                    raise ValueError(f"sensor {sensor.column!r} sees unknown node {node!r}")
                self.weights[row, position[node]] = w
        self.offsets = np.array([s.offset_c for s in self.sensors])
        self.lags = np.array([s.lag_s for s in self.sensors], dtype=float)

    def true_readings(self, node_temperatures: np.ndarray, ambient: np.ndarray,
                      step_s: float | None = None) -> np.ndarray:
        """Noise-free readings (times x sensors) from node (times x nodes) and air temperatures.

        With ``step_s`` (the uniform spacing of the rows) each reading follows
        its local temperature :math:`x` through :math:`\\tau\\dot y = x - y`,
        integrated exactly for :math:`x` linear over a step, from :math:`y(0) = x(0)`.
        """
        local = np.column_stack([node_temperatures, ambient]) @ self.weights.T
        if step_s is not None and np.any(self.lags > 0):
            local = first_order_lag(local, self.lags, step_s)
        return local + self.offsets

    def measure(self, true: np.ndarray, rng: np.random.Generator,
                noise_c: float, quantum_c: float) -> np.ndarray:
        """Measured readings: true value + N(0, ``noise_c``²), quantised to ``quantum_c``."""
        return quantise(true + noise_c * rng.standard_normal(true.shape), quantum_c)

    def to_dict(self) -> dict:
        return {s.column: {"node": s.main_node, "weights": dict(s.weights), "offset_c": s.offset_c,
                           "lag_s": s.lag_s} for s in self.sensors}


def first_order_lag(x: np.ndarray, tau_s: np.ndarray, step_s: float) -> np.ndarray:
    """Columns of ``x`` (uniform rows, ``step_s`` apart) through lags ``tau_s`` (0 = none).

    Exact for input linear between rows (first-order hold), starting at rest
    (:math:`y_0 = x_0`):
    :math:`y_{k+1} = a y_k + (1-a-c)\\,x_{k+1} + c\\,x_k`, :math:`a = e^{-h/\\tau}`,
    :math:`c = \\tau(1-a)/h - a`.

    The recursion is a lower bidiagonal system, solved by LAPACK in one pass: SciPy's linear
    algebra, which the simulator loads anyway, not ``scipy.signal.lfilter``, whose package
    would double the start-up of ``thermocomp simulate`` (~0.6 s of CPU).
    """
    x = np.asarray(x, dtype=float)
    y = x.copy()
    for j, tau in enumerate(np.asarray(tau_s, dtype=float)):
        if tau > 0:
            a = np.exp(-step_s / tau)
            c = tau * (1 - a) / step_s - a
            rhs = np.concatenate([x[:1, j], (1 - a - c) * x[1:, j] + c * x[:-1, j]])
            bands = np.ones((2, len(rhs)))     # y_k - a y_{k-1} = rhs_k, with y_0 = x_0
            bands[1] = -a
            y[:, j] = solve_banded((1, 0), bands, rhs, check_finite=False)   # NaN: as lfilter
    return y
