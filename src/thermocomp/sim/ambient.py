"""Workshop air temperature over the year.

.. math::

    T_a(t) = \\bar T - A_y\\cos\\!\\left(2\\pi\\frac{d(t) - d_{cold}}{365}\\right)
             + A_d\\cos\\!\\left(2\\pi\\frac{h(t) - h_{peak}}{24}\\right) + \\delta(t)

:math:`d` is the (fractional) day of the year, :math:`h` the hour of the day and
:math:`\\delta` an Ornstein-Uhlenbeck drift (stationary s.d. ``drift_sd_c``,
correlation time ``drift_tau_h``), sampled exactly on any time grid.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

DAY_S = 86400.0
YEAR_DAYS = 365.0


@dataclass(frozen=True)
class AmbientModel:
    """Seasonal level + daily swing + slow random drift (°C).

    Parameters
    ----------
    annual_mean_c, annual_amplitude_c : float
        Daily-mean air temperature runs over ``mean ± amplitude`` in the year;
        18.5 ± 13.5 gives 5-32 °C, the unheated workshop of Wei et al. (2022).
    coldest_day : float
        Day of the year (0 = 1 January) of the coldest daily mean.
    daily_amplitude_c, daily_peak_hour : float
        Day/night swing inside the hall and the hour of its maximum.
    drift_sd_c, drift_tau_h : float
        Weather, doors and neighbouring machines as a random drift.
    """

    annual_mean_c: float = 18.5
    annual_amplitude_c: float = 13.5
    coldest_day: float = 15.0
    daily_amplitude_c: float = 3.0
    daily_peak_hour: float = 15.0
    drift_sd_c: float = 0.4
    drift_tau_h: float = 12.0

    def seasonal(self, t_s) -> np.ndarray:
        """Daily-mean air temperature (°C) at times ``t_s`` (s since 1 January 00:00)."""
        day = np.asarray(t_s, dtype=float) / DAY_S
        return self.annual_mean_c - self.annual_amplitude_c * np.cos(
            2 * np.pi * (day - self.coldest_day) / YEAR_DAYS)

    def warmth(self, t_s) -> np.ndarray:
        """Position in the season, 0 in the coldest and 1 in the warmest week."""
        return (self.seasonal(t_s) - self.annual_mean_c + self.annual_amplitude_c) / (
            2 * self.annual_amplitude_c)

    def deterministic(self, t_s) -> np.ndarray:
        """Seasonal + daily part at times ``t_s`` (s since 1 January 00:00)."""
        hour = (np.asarray(t_s, dtype=float) / DAY_S % 1.0) * 24.0
        daily = self.daily_amplitude_c * np.cos(2 * np.pi * (hour - self.daily_peak_hour) / 24.0)
        return self.seasonal(t_s) + daily

    def drift(self, t_s: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        """Exact OU sample on an increasing grid, started from its stationary law."""
        t_s = np.asarray(t_s, dtype=float)
        tau = self.drift_tau_h * 3600.0
        decay = np.exp(-np.diff(t_s) / tau)
        shocks = rng.standard_normal(len(t_s))
        out = np.empty(len(t_s))
        out[0] = self.drift_sd_c * shocks[0]
        for k, a in enumerate(decay, start=1):
            out[k] = a * out[k - 1] + self.drift_sd_c * np.sqrt(1.0 - a * a) * shocks[k]
        return out

    def sample(self, t_s: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        """Air temperature (°C) at times ``t_s`` (s since 1 January 00:00)."""
        return self.deterministic(t_s) + self.drift(t_s, rng)

    def to_dict(self) -> dict:
        return asdict(self)
