"""Scenario ``yearround_spindle``: spindle tests on a VMC spread over one year.

After Wei et al. (2022): campaigns at 2000/4000/6000 rpm (some with speed
steps), 10 Pt sensors, 5-min sampling, 4-8 h each after a 2-day cool-down,
initial ambient 5-32 °C following the season.  Campaign ids ``K01..`` follow
the calendar; every ``test_every``-th campaign is held out as ``test``, so the
test set samples every season.
"""

from __future__ import annotations

import math

import numpy as np

from thermocomp.apps.sim.ambient import DAY_S, AmbientModel
from thermocomp.apps.sim.campaign import Programme
from thermocomp.apps.sim.scenario import CampaignPlan, Scenario, single_threaded_blas  # noqa: F401
from thermocomp.apps.sim.vmc import VMC_EFFECTS, vertical_machining_centre
from thermocomp.base.params import FRACTION, NON_NEGATIVE, POSITIVE, integer, numbers, overrides, span

SCENARIO = "yearround_spindle"


class YearRoundSpindle(Scenario):
    """Generator of the year-round spindle dataset (sklearn style: ``__init__`` only stores).

    Parameters
    ----------
    n_campaigns : int
        Number of campaigns ``K01..``, spread evenly over the year.
    sample_period_s : float
        Sampling period (s).
    duration_h : (float, float)
        Range of campaign lengths (h), drawn uniformly, rounded to the sampling period.
    speeds_rpm : sequence of float
        Spindle speeds of the programmes.
    step_fraction : float
        Share of campaigns that run a step programme (a staircase over all
        speeds, or one speed then a stop) instead of one constant speed.
    temp_noise_c, temp_quantum_c : float
        Temperature sensor noise (s.d.) and resolution (°C).
    error_noise_um, error_quantum_um : float
        Displacement probe noise (s.d.) and resolution (µm).
    test_every : int
        Every ``test_every``-th campaign by date is ``test``, the rest ``train``.
    year : int
        Calendar year of the ``start`` timestamps.
    start_hours : (float, float)
        Range of start times of day (h); tests start in the morning.
    ambient : dict or None
        Overrides of :class:`~thermocomp.apps.sim.ambient.AmbientModel` fields.
    summer_air_gain, air_movement_sd : float
        Convection of the whole machine is scaled per campaign by
        ``(1 + summer_air_gain * warmth) * exp(air_movement_sd * z)``: open gates
        and fans in summer, draughts from day to day (``warmth`` 0 in the coldest,
        1 in the warmest season).
    effects : list of str
        Undeclared effects to plant (:mod:`thermocomp.apps.sim.effects`).
    effect_params : dict
        Effect name -> parameter overrides (defaults: :data:`~thermocomp.apps.sim.vmc.VMC_EFFECTS`).
    clean : bool
        Errors exactly linear in the measured sensor rises + white noise.
    seed : int
        Seed of :func:`numpy.random.default_rng`; the same seed gives the same data.
    """

    name = SCENARIO
    param_rules = {**Scenario.param_rules, "n_campaigns": integer(1), "sample_period_s": POSITIVE,
                   "duration_h": span(open_lo=True), "speeds_rpm": numbers(0.0),
                   "step_fraction": FRACTION, "test_every": integer(1), "year": integer(1, 9998),
                   "start_hours": span(0.0, 24.0), "ambient": overrides(AmbientModel),
                   "summer_air_gain": NON_NEGATIVE, "air_movement_sd": NON_NEGATIVE}

    def param_relations(self) -> list[tuple[str, str]]:
        if 3600.0 * float(self.duration_h[0]) < 2 * float(self.sample_period_s):
            return [("duration_h", "the shortest campaign must hold two samples of "
                                   f"sim.generator.sample_period_s={self.sample_period_s}")]
        if not 2 <= int(self.test_every) <= int(self.n_campaigns):
            # else a split is empty: no test campaign (run refused it, pointing at the manifest)
            # or, with 1, no train campaign
            return [("test_every", "must be an integer in [2, sim.generator.n_campaigns="
                                   f"{self.n_campaigns}] (every test_every-th campaign is test: "
                                   "both splits need one)")]
        return []

    def __init__(self, n_campaigns=24, sample_period_s=300.0, duration_h=(4.0, 8.0),
                 speeds_rpm=(2000, 4000, 6000), step_fraction=0.4, temp_noise_c=0.03,
                 temp_quantum_c=0.01, error_noise_um=0.4, error_quantum_um=0.1, test_every=3,
                 year=2023, start_hours=(7.0, 10.0), ambient=None, summer_air_gain=0.4,
                 air_movement_sd=0.15, effects=(), effect_params=None, clean=False, seed=0):
        self.n_campaigns = n_campaigns
        self.sample_period_s = sample_period_s
        self.duration_h = duration_h
        self.speeds_rpm = speeds_rpm
        self.step_fraction = step_fraction
        self.test_every = test_every
        self.year = year
        self.start_hours = start_hours
        self.ambient = ambient
        self.summer_air_gain = summer_air_gain
        self.air_movement_sd = air_movement_sd
        super().__init__(temp_noise_c, temp_quantum_c, error_noise_um, error_quantum_um, effects,
                         effect_params, clean, seed)

    def effect_defaults(self) -> dict:
        return VMC_EFFECTS

    def truth_extra(self) -> dict:
        return {"ambient": self.ambient_model().to_dict()}

    def machine(self):
        """The twin under test (a fresh :class:`~thermocomp.apps.sim.campaign.Machine`)."""
        return vertical_machining_centre()

    def ambient_model(self) -> AmbientModel:
        return AmbientModel(**dict(self.ambient or {}))

    def _programme(self, rng, duration_s, speed, stepped: bool) -> tuple[Programme, str]:
        """A constant ``speed``; stepped: a staircase over all speeds (up or down), or
        ``speed`` then a stop, which shows the cooling half of the dynamics."""
        if not stepped:
            return Programme(((0.0, speed),)), "constant"
        if rng.random() < 0.5:
            order = sorted((float(s) for s in self.speeds_rpm), reverse=bool(rng.random() < 0.3))
            share = self._on_grid(duration_s / len(order))
            return Programme(tuple((i * share, s) for i, s in enumerate(order))), "steps"
        run = self._on_grid(duration_s * rng.uniform(0.5, 0.7))
        return Programme(((0.0, speed), (run, 0.0))), "run-stop"

    def _air_movement(self, rng, start_s: float, ambient: AmbientModel) -> float:
        """Factor on all convection: gates, windows and fans open as the hall warms, plus day-to-day spread.

        :math:`f = (1 + g\\,w)\\,e^{\\sigma z}`, :math:`z \\sim N(0, 1)`, with the season's
        warmth :math:`w \\in [0, 1]` (0 in the coldest, 1 in the warmest week).
        """
        warmth = float(ambient.warmth(start_s))
        spread = np.exp(self.air_movement_sd * rng.standard_normal())
        return float((1.0 + self.summer_air_gain * warmth) * spread)

    def _on_grid(self, t_s: float) -> float:
        return self.sample_period_s * max(1, round(t_s / self.sample_period_s))

    def _calendar(self, rng) -> list[float]:
        """Start times (s since 1 January) evenly over the year, jittered, in the morning."""
        n = int(self.n_campaigns)
        spacing = 365.0 / n
        days = 10.0 + spacing * np.arange(n) + rng.uniform(-0.2, 0.2, n) * spacing
        hours = rng.uniform(*self.start_hours, n)
        starts = np.floor(days) * DAY_S + np.round(hours * 12) / 12 * 3600.0
        return sorted(float(s) for s in starts)

    def plans(self, rng) -> list[CampaignPlan]:
        """One plan per campaign: calendar, speeds, programmes and air movement."""
        ambient = self.ambient_model()
        starts = self._calendar(rng)
        n = len(starts)
        width = max(2, len(str(n)))
        speeds = [float(s) for s in self.speeds_rpm]
        # Each block of len(speeds) consecutive campaigns runs every speed once, so
        # every season (and the test split) sees low and high speeds.
        block_speeds = np.concatenate([rng.permutation(speeds) for _ in range(math.ceil(n / len(speeds)))])
        stepped = set(rng.choice(n, size=int(round(self.step_fraction * n)), replace=False).tolist())
        lo, hi = (float(h) * 3600.0 for h in self.duration_h)
        plans = []
        for k, (start_s, child) in enumerate(zip(starts, rng.spawn(n))):
            duration_s = self._on_grid(child.uniform(lo, hi))
            programme, kind = self._programme(child, duration_s, float(block_speeds[k]), k in stepped)
            air = self._air_movement(child, start_s, ambient)
            plans.append(CampaignPlan(
                cid=f"K{k + 1:0{width}d}", split="test" if (k + 1) % int(self.test_every) == 0 else "train",
                start_s=start_s, duration_s=duration_s, rng=child, ambient=ambient, programme=programme,
                air_movement=air, sample_period_s=float(self.sample_period_s),
                notes=f"{kind}: {programme.describe()}",
                manifest={"spindle_rpm": max(r for _, r in programme.steps), "programme": kind,
                          "duration_h": duration_s / 3600.0},
                truth={"air_movement": air, "programme": [list(map(float, s)) for s in programme.steps]}))
        return plans
