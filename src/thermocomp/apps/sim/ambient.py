"""Workshop air temperature over the year.

.. math::

    T_a(t) = \\bar T - A_y\\cos\\!\\left(2\\pi\\frac{d(t) - d_{cold}}{365}\\right)
             + A_d\\cos\\!\\left(2\\pi\\frac{h(t) - h_{peak}}{24}\\right) + \\delta(t)

:math:`d` is the (fractional) day of the year, :math:`h` the hour of the day and
:math:`\\delta` an Ornstein-Uhlenbeck drift (stationary s.d. ``drift_sd_c``,
correlation time ``drift_tau_h``), sampled exactly on any time grid.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, replace

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


def room_response(t_s, target, room_tau_h: float) -> np.ndarray:
    """Air of a hall following its ``target`` temperature as a first-order lag of ``room_tau_h``
    (exact for any sampling; starts at the target)."""
    decay = np.exp(-np.diff(t_s) / (3600.0 * room_tau_h))
    level = np.empty(len(t_s))
    level[0] = target[0]
    for k, a in enumerate(decay, start=1):
        level[k] = a * level[k - 1] + (1.0 - a) * target[k - 1]
    return level


@dataclass(frozen=True)
class HallClimate:
    """A climate-controlled hall: setpoint programme, HVAC hours, cycling, drift (°C).

    The room air follows its target through a first-order lag ``room_tau_h``
    (exact for a target held between grid points):

    .. math::

        \\tau_r \\dot T_a = T_{tgt}(t) - T_a, \\qquad
        T_{tgt} = \\begin{cases} s(t) + c(t) & \\text{HVAC on} \\\\
                                  T_{free} + A_d\\cos(2\\pi(h - h_{peak})/24) & \\text{off}\\end{cases}

    plus an Ornstein-Uhlenbeck drift :math:`\\delta(t)`.  :math:`s(t)` is the
    piecewise-constant setpoint ``setpoints`` ((absolute start s, °C), ...),
    forced heating or cooling included; :math:`c(t)` the on/off cycling of the
    controller (a square wave of ``cycling_amplitude_c``, period
    ``cycling_period_min``) that paper 004 removes with EMD.

    Parameters
    ----------
    setpoints : tuple of (float, float)
    hvac_hours : (float, float)
        Hours of the day with the HVAC on; ``(0, 24)`` = always.
    free_c : float
        Level the hall drifts to with the HVAC off (warm summer nights: 27 °C).
    """

    setpoints: tuple = ((0.0, 22.0),)
    room_tau_h: float = 1.5
    hvac_hours: tuple = (0.0, 24.0)
    free_c: float = 22.0
    daily_amplitude_c: float = 1.0
    daily_peak_hour: float = 16.0
    cycling_amplitude_c: float = 0.0
    cycling_period_min: float = 20.0
    drift_sd_c: float = 0.2
    drift_tau_h: float = 6.0

    def target(self, t_s) -> np.ndarray:
        t_s = np.asarray(t_s, dtype=float)
        starts = np.array([s for s, _ in self.setpoints], dtype=float)
        values = np.array([v for _, v in self.setpoints], dtype=float)
        setpoint = values[np.clip(np.searchsorted(starts, t_s, side="right") - 1, 0, None)]
        hour = (t_s / DAY_S % 1.0) * 24.0
        on = (hour >= self.hvac_hours[0]) & (hour < self.hvac_hours[1])
        if self.cycling_amplitude_c:
            phase = (t_s / (60.0 * self.cycling_period_min)) % 1.0
            setpoint = setpoint + np.where(phase < 0.5, self.cycling_amplitude_c, -self.cycling_amplitude_c)
        free = self.free_c + self.daily_amplitude_c * np.cos(2 * np.pi * (hour - self.daily_peak_hour) / 24.0)
        return np.where(on, setpoint, free)

    def sample(self, t_s, rng: np.random.Generator) -> np.ndarray:
        t_s = np.asarray(t_s, dtype=float)
        level = room_response(t_s, self.target(t_s), self.room_tau_h)
        drift = AmbientModel(drift_sd_c=self.drift_sd_c, drift_tau_h=self.drift_tau_h).drift(t_s, rng)
        return level + drift

    def to_dict(self) -> dict:
        return {**asdict(self), "setpoints": [list(map(float, s)) for s in self.setpoints]}


@dataclass(frozen=True)
class SinusoidalAmbient:
    """:math:`T_a = \\bar T + A\\sin(2\\pi (t - t_0)/P + \\phi)` (the FE case study of paper 002)."""

    mean_c: float = 20.0
    amplitude_c: float = 2.0
    period_h: float = 24.0
    phase_rad: float = 0.0

    def sample(self, t_s, rng=None) -> np.ndarray:
        t_s = np.asarray(t_s, dtype=float)
        phase = 2 * np.pi * t_s / (3600.0 * self.period_h) + self.phase_rad
        return self.mean_c + self.amplitude_c * np.sin(phase)

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass(frozen=True)
class SteppedAmbient:
    """``base``'s air plus ``step_c`` from ``on_s`` on, reached linearly over ``ramp_s`` (a door to
    another hall, an HVAC set-point): a real change the machine follows, unlike a sensor's offset.
    ``base`` draws the same random numbers, so only the air after ``on_s`` differs."""

    base: object
    on_s: float
    step_c: float
    ramp_s: float = 0.0

    def sample(self, t_s, rng=None) -> np.ndarray:
        t_s = np.asarray(t_s, dtype=float)
        share = (np.clip((t_s - self.on_s) / self.ramp_s, 0.0, 1.0) if self.ramp_s > 0
                 else (t_s >= self.on_s).astype(float))
        return self.base.sample(t_s, rng) + self.step_c * share

    def to_dict(self) -> dict:
        return {"base": self.base.to_dict(), "on_s": self.on_s, "step_c": self.step_c,
                "ramp_s": self.ramp_s}


def step_air(plans: list, cid: str, step_c: float, ramp_s: float = 0.0) -> list:
    """``plans`` with campaign ``cid``'s air stepped by ``step_c`` at its middle row (a real
    ambient change, :class:`SteppedAmbient`; the other campaigns as they were)."""
    out = []
    for p in plans:
        if p.cid == cid:
            rows = int(round(p.duration_s / p.sample_period_s)) + 1
            on = p.start_s + (rows // 2) * p.sample_period_s - 1.0      # the middle row reads it
            p = replace(p, ambient=SteppedAmbient(p.ambient, on, step_c, ramp_s))
        out.append(p)
    return out
