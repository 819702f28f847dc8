r"""``edm65``: a wire EDM with a dielectric chiller in a day-night hall, nobody tuned on (stranger65).

Built through the documented own-machine route (docs/simulation.md, "Your own machine"): this
:class:`~thermocomp.apps.sim.scenario.Scenario` subclass on ``PYTHONPATH`` and the yaml
``benchmarks/conf65/sim/edm65.yaml``::

    THERMOCOMP_TARGETS=edm65. PYTHONPATH=src:benchmarks .venv/bin/python -m thermocomp \
        simulate "hydra.searchpath=[file://$PWD/benchmarks/conf65]" sim=edm65 seed=6501

Written down and committed before any model ran on it; seeds 6501 and 6502 fixed beforehand
(6501: eight days as ONE record, the lab cuts it into one file per day; 6502: the same machine,
another eight days, one record, the second lab's single export).  The lab's exports are
written by ``benchmarks/bench_stranger65.py write``.

The machine
-----------
A wire EDM (C-frame: the column carries the upper arm with the upper wire guide, the lower arm
reaches into the work tank under the table).  The dielectric (deionised water, a 300 l tank)
is cooled by an on/off CHILLER: on above 20.4 °C, off below 19.6 °C (hysteresis, remembered
between steps), 1500 W of cooling while on, only while the machine is powered.  The
generator's spark energy goes into the water (85 %) and the lower arm (15 %) while it cuts;
the generator cabinet (300 W while powered) stands behind the column and warms its back.  The
hall is not climatised: 20 °C +- 2.5 K a day (peak 15 h), a weather drift of 0.8 K (24 h).

=============  =======  =====  ========================================================
node           C (J/K)  hA     what
=============  =======  =====  ========================================================
bed            3e6      25     the machine bed
table          4e5      6      the work table (in the tank)
water          1.25e6   15     the dielectric in the work tank and the reservoir
col_front      1e6      10     the column's front (upper arm side)
col_back       3e5      5      the column's back (towards the generator cabinet)
upper_arm      1e5      3      the upper arm with the upper guide
lower_arm      8e4      2      the lower arm with the lower guide (reaches into the tank)
cabinet        5e4      10     the generator cabinet (its fans)
=============  =======  =====  ========================================================

Links (W/K): bed-table 15, table-water 30, bed-col_front 12, col_front-col_back 8,
col_front-upper_arm 4, bed-lower_arm 4, lower_arm-water 20, cabinet-col_back 4, bed-water 6.
Heat (W): the generator ``S_gen_W`` (600-1800 W while it cuts, 0 else) 0.85 water + 0.15
lower arm; the cabinet 300 while powered; the chiller -1500 on the water while on.
Errors at the lower guide against the table (µm/K of the node rises from the campaign's first
sample; the lab's capacitive gauges, every sample)::

    E_X =  4.0 lower_arm - 3.0 table + 1.0 bed - 1.5 col_front + 2.0 col_back
    E_Y =  2.5 table - 2.0 bed + 3.0 col_back - 2.5 col_front + 1.0 upper_arm

PLANTED (the effect the default model lacks): the workpiece's clamping frame stands in the
tank; when the tank is FLOODED (submerged cutting, ``S_flooded`` = 1, logged) it takes the
water's temperature and its growth moves the workpiece: E_X += 10.0 * S_flooded * rise(water),
E_Y += -4.0 * S_flooded * rise(water) (drained: it rests on the table and is in the linear map
through it).

Sensors (Pt100, 0.03 K noise, 0.01 K steps; lags in s): T_hall (the air, 120), T_water (the
tank, 60), T_table (300), T_bed (900), T_col_front (600), T_col_back (600), T_upper_arm
(0.8 upper_arm + 0.2 col_front, 300), T_lower_arm (240), T_cabinet (120); the generator power
``S_gen_W`` and ``S_flooded`` logged.

The programme
-------------
From Monday 2027-06-07 00:00, eight days logged every 60 s.  The machine is powered from
Monday 06:00 to Saturday 12:00 (it cuts unattended through the nights) and again from the
second Monday 06:00; off at the weekend (chiller off: the water drifts with the hall).  Jobs of
1-6 h, each at one generator power (600-1800 W, steps of 100 W) and flooded with p 0.5, set-up
of 10-40 min between jobs.  The lab's files: one per day (00:00-23:59), the days continue each
other (one clock); the last ones are held out by ``data.test_fraction``.
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime

import numpy as np
from scenario_tail import LoggedStateEffect, PlantedScenario, held, merge

from thermocomp.apps.sim.ambient import DAY_S, AmbientModel
from thermocomp.apps.sim.campaign import Machine
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.scenario import CampaignPlan
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import ConstantWhileRunning, HeatSource

POWERED = "_powered"                 # not written
GEN = "S_gen_W"                      # the generator's power (W), written
FLOODED = "S_flooded"                # 1 while the tank is flooded, written
START = datetime(2027, 6, 7)         # a Monday
CHILLER = (19.6, 20.4, 1500.0)       # off below, on above (°C), cooling (W)

NODES = (Node("bed", 3e6, 25.0), Node("table", 4e5, 6.0), Node("water", 1.25e6, 15.0),
         Node("col_front", 1e6, 10.0), Node("col_back", 3e5, 5.0), Node("upper_arm", 1e5, 3.0),
         Node("lower_arm", 8e4, 2.0), Node("cabinet", 5e4, 10.0))
LINKS = (Link("bed", "table", 15.0), Link("table", "water", 30.0), Link("bed", "col_front", 12.0),
         Link("col_front", "col_back", 8.0), Link("col_front", "upper_arm", 4.0),
         Link("bed", "lower_arm", 4.0), Link("lower_arm", "water", 20.0),
         Link("cabinet", "col_back", 4.0), Link("bed", "water", 6.0))
# the submerged clamping frame: target -> gain (µm/K of the water's rise) while flooded
FRAME = {"E_X": 10.0, "E_Y": -4.0}


@dataclass
class StatePower(HeatSource):
    """The state ``signal``'s value as W on its nodes (the generator's logged power)."""

    signal: str = GEN

    def power(self, state, temperature_of):
        return float(state.get(self.signal, 0.0))


@dataclass
class Chiller(HeatSource):
    """On/off cooling of the water with hysteresis (its last switch remembered), while powered."""

    off_below_c: float = CHILLER[0]
    on_above_c: float = CHILLER[1]
    cooling_W: float = CHILLER[2]
    when: str = POWERED
    on: bool = False

    depends_on_temperature = True

    def power(self, state, temperature_of):
        if not state.get(self.when, 0.0):
            self.on = False
            return 0.0
        water = temperature_of("water")
        if water > self.on_above_c:
            self.on = True
        elif water < self.off_below_c:
            self.on = False
        return -self.cooling_W if self.on else 0.0


def machine() -> Machine:
    sources = [
        StatePower("generator", {"water": 0.85, "lower_arm": 0.15}),
        ConstantWhileRunning("cabinet", {"cabinet": 1.0}, power_W=300.0, when=POWERED),
        Chiller("chiller", {"water": 1.0}),
    ]
    sensors = [
        TemperatureSensor("T_hall", {AMBIENT: 1.0}, 0.0, lag_s=120.0),
        TemperatureSensor("T_water", {"water": 1.0}, 0.0, lag_s=60.0),
        TemperatureSensor("T_table", {"table": 1.0}, 0.0, lag_s=300.0),
        TemperatureSensor("T_bed", {"bed": 1.0}, 0.0, lag_s=900.0),
        TemperatureSensor("T_col_front", {"col_front": 1.0}, 0.0, lag_s=600.0),
        TemperatureSensor("T_col_back", {"col_back": 1.0}, 0.0, lag_s=600.0),
        TemperatureSensor("T_upper_arm", {"upper_arm": 0.8, "col_front": 0.2}, 0.0, lag_s=300.0),
        TemperatureSensor("T_lower_arm", {"lower_arm": 1.0}, 0.0, lag_s=240.0),
        TemperatureSensor("T_cabinet", {"cabinet": 1.0}, 0.0, lag_s=120.0),
    ]
    from thermocomp.apps.sim.thermoelastic import ThermoelasticMap

    errors = ThermoelasticMap(
        linear={"E_X": {"lower_arm": 4.0, "table": -3.0, "bed": 1.0, "col_front": -1.5,
                        "col_back": 2.0},
                "E_Y": {"table": 2.5, "bed": -2.0, "col_back": 3.0, "col_front": -2.5,
                        "upper_arm": 1.0}},
        reference_c=20.0)
    return Machine(ThermalNetwork(NODES, LINKS), sources, sensors, errors)


class SubmergedFrame(LoggedStateEffect):
    """The clamping frame in the flooded tank follows the water (declared: S_flooded is logged)."""

    name, state = "submerged_frame", FLOODED
    defaults = {"gains": FRAME, "targets": ["E_X", "E_Y"]}

    def modify_errors(self, ctx, errors):
        rise, flooded = self.rise(ctx, "water"), self.logged(ctx)
        errors = errors.copy()
        targets = ctx.machine.thermoelastic.targets
        for target, gain in self.params["gains"].items():
            errors[:, targets.index(target)] += gain * flooded * rise
        return errors


def powered(t_rel) -> np.ndarray:
    """Campaign time (from a Monday 00:00) -> 1 from Monday 06:00 to Saturday 12:00."""
    hours = np.asarray(t_rel, float) / 3600.0
    week_h = hours % (7 * 24)
    return ((week_h >= 6.0) & (week_h < 5 * 24 + 12.0)).astype(float)


def programme(rng, period_s: float, days: int):
    """Generator power and flooding steps (jobs while powered), on the logger's grid."""
    def grid(t):
        return period_s * round(t / period_s)

    gen, flood = [(0.0, 0.0)], [(0.0, 0.0)]
    t, end = 0.0, days * DAY_S
    while t < end:
        if not powered(t):
            t = grid(t + period_s)
            continue
        job = rng.uniform(1.0, 6.0) * 3600
        stop = t + job
        # a job ends where the machine goes off
        ends = t + period_s * np.argmin(powered(t + period_s * np.arange(int(job / period_s) + 1)))
        stop = ends if ends > t else stop
        gen.append((grid(t), float(rng.integers(6, 19) * 100)))
        flood.append((grid(t), float(rng.random() < 0.5)))
        gen.append((grid(stop), 0.0))
        flood.append((grid(stop), 0.0))
        t = stop + rng.uniform(10, 40) * 60
    return merge(gen), merge(flood)


@dataclass(eq=False, repr=False, kw_only=True)
class Edm65(PlantedScenario):
    """Eight days of the wire EDM as one record (the lab cuts it into day files)."""

    name = "edm65"
    year = 2027
    planted = SubmergedFrame

    days: int = 8
    sample_period_s: float = 60.0

    def machine(self):
        return machine()

    def planted_truth(self):
        return {"gains_um_per_K_water_rise_while_flooded": FRAME}

    def plans(self, rng):
        first = (START - datetime(self.year, 1, 1)).total_seconds()
        period = float(self.sample_period_s)
        days = int(self.days)
        gen, flood = programme(rng, period, days)
        hall = AmbientModel(annual_mean_c=20.0, annual_amplitude_c=0.0, daily_amplitude_c=2.5,
                            daily_peak_hour=15.0, drift_sd_c=0.8, drift_tau_h=24.0)
        return [CampaignPlan(
            cid="record", split="train", start_s=first, duration_s=days * DAY_S - period,
            rng=rng, ambient=hall, programme=None,
            states={POWERED: powered, GEN: held(gen), FLOODED: held(flood)},
            written=(GEN, FLOODED), sample_period_s=period, error_period_s=None,
            cooldown_s=2 * DAY_S, notes=f"{days} days from Monday", manifest={})]


__all__ = ["Edm65", "machine"]
