r"""``tsc66``: a twin-spindle turning centre, nobody tuned on (stranger66).

Built through the documented own-machine route (docs/simulation.md, "Your own machine"): this
:class:`~thermocomp.apps.sim.scenario.Scenario` subclass on ``PYTHONPATH`` and the yaml
``benchmarks/conf66/sim/tsc66.yaml``::

    THERMOCOMP_TARGETS=tsc66. PYTHONPATH=src:benchmarks .venv/bin/python -m thermocomp \
        simulate "hydra.searchpath=[file://$PWD/benchmarks/conf66]" sim=tsc66 seed=6601

Written down and committed before any model ran on it; seeds 6601 and 6602 fixed beforehand
(6601: the lab's six test runs, one file each; 6602: the same machine, another six runs, kept
for a second look).  The lab's export is written by ``benchmarks/bench_stranger66.py write``.

The machine
-----------
A twin-spindle turning centre on one slant BED (shared): the MAIN spindle (left, fixed
headstock) with the upper turret 1 (X1/Z1), the COUNTER spindle (right, its headstock slides on
the bed's Z2 guideways) with the lower turret 2 (X2/Z2).  The counter spindle is used only in
some operations (back-working of a transferred part); between them it is parked at the right
end (Z2 = 650 mm).  The coolant (a 150 l tank, water-based) takes the cutting heat and runs
over the bed through the chip trough.  The hall: 21 °C +- 2 K a day (peak 15 h), a weather
drift of 0.6 K (24 h).

===============  =======  =====  ======================================================
node             C (J/K)  hA     what
===============  =======  =====  ======================================================
bed              2.5e6    20     the shared slant bed
main_head        3e5      6      the main headstock housing
main_bearing     4e4      2      the main spindle's front bearings
counter_head     1.5e5    4      the counter headstock (slides on the bed)
counter_bearing  2e4      1      the counter spindle's front bearings
turret1          1.2e5    4      the upper turret with its X1/Z1 slides
turret2          1.2e5    4      the lower turret with its X2/Z2 slides
coolant          6e5      10     the coolant in the tank and the chip trough
===============  =======  =====  ======================================================

Links (W/K): bed-main_head 15, main_head-main_bearing 5, bed-counter_head 8,
counter_head-counter_bearing 3, bed-turret1 10, bed-turret2 10, coolant-bed 40,
coolant-turret1 5, coolant-turret2 5.
Heat (W): the main spindle ``S_n1_rpm`` (0-3500): 60 + 80 n + 15 n^2 (n in krpm), half into its
bearings, half into the headstock; the counter spindle ``S_n2_rpm`` (0-4500, only in
back-working jobs): 40 + 50 n + 10 n^2, half bearings, half headstock; turret 1's drives 80
while the main spindle turns, turret 2's 60 while the counter spindle turns; the cut 500 into
the coolant while either spindle turns.
Errors at the tool against the part (µm/K of the node rises from the run's first sample; the
lab's capacitive probes at a test bar in each spindle, every sample)::

    E_X1 = 3.0 main_head - 2.5 turret1 + 0.5 bed + 1.0 main_bearing
    E_Z1 = 8.0 main_bearing + 4.0 main_head - 3.0 turret1 - 2.0 bed
    E_X2 = 2.5 counter_head - 2.0 turret2 + 0.5 bed + 1.0 counter_bearing
    E_Z2 = 6.0 counter_bearing + 3.0 counter_head - 2.5 turret2 - 1.5 bed

PLANTED (the effect the default model lacks): the counter headstock stands at Z2 (logged,
``S_Z2_mm``) on the bed; the bed's growth between turret 2's slide and the counter headstock
scales with that distance: E_Z2 += 0.0115 * S_Z2_mm * rise(bed) (steel, 11.5 µm/m/K).  A
linear map of the temperatures and of S_Z2_mm cannot carry a product; diagnose should find
``S_Z2_mm`` x the bed's (or its inputs') rise.

Sensors (Pt100, 0.03 K noise, 0.01 K steps; lags in s): T_amb (the air, 120), T_bed (900),
T_main_head (0.7 main_head + 0.3 main_bearing, 300), T_counter_head (0.8 counter_head + 0.2
counter_bearing, 300), T_turret1 (240), T_turret2 (240), T_coolant (60); the spindle speeds
``S_n1_rpm``, ``S_n2_rpm`` and the counter headstock's position ``S_Z2_mm`` logged.

The programme
-------------
Six runs, 40 h each at 60 s, starting 06:00 on Monday 2027-03-08, Wednesday, Friday, the next
Monday, Wednesday, Friday (each after a 2-day cool-down: independent runs, each its own
clock).  Jobs from 06:00 to 22:00, idle through the night: each job 30-150 min at one main
speed (800-3500 rpm, steps of 100), with p 0.4 a back-working job (counter spindle 1000-4500
rpm, Z2 at 80-350 mm; else parked at 650 mm and still), a pause of 5-30 min between jobs.
The last run(s) are held out by ``data.test_fraction``.
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime, timedelta

import numpy as np
from scenario_tail import LoggedStateEffect, PlantedScenario, either, held, merge, working

from thermocomp.apps.sim.ambient import DAY_S, AmbientModel
from thermocomp.apps.sim.campaign import Machine
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.scenario import CampaignPlan
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import ConstantWhileRunning, SpeedLosses

N1, N2, Z2 = "S_n1_rpm", "S_n2_rpm", "S_Z2_mm"
CUTTING = "_cutting"                     # not written: either spindle turns
START = datetime(2027, 3, 8, 6)          # a Monday, 06:00
RUN_DAYS = (0, 2, 4, 7, 9, 11)           # the runs' first days from START
RUN_H = 40.0
PARKED_MM = 650.0
LEVER_UM_PER_MM_K = 0.0115               # the planted bed lever (steel)

NODES = (Node("bed", 2.5e6, 20.0), Node("main_head", 3e5, 6.0), Node("main_bearing", 4e4, 2.0),
         Node("counter_head", 1.5e5, 4.0), Node("counter_bearing", 2e4, 1.0),
         Node("turret1", 1.2e5, 4.0), Node("turret2", 1.2e5, 4.0), Node("coolant", 6e5, 10.0))
LINKS = (Link("bed", "main_head", 15.0), Link("main_head", "main_bearing", 5.0),
         Link("bed", "counter_head", 8.0), Link("counter_head", "counter_bearing", 3.0),
         Link("bed", "turret1", 10.0), Link("bed", "turret2", 10.0), Link("coolant", "bed", 40.0),
         Link("coolant", "turret1", 5.0), Link("coolant", "turret2", 5.0))


def machine() -> Machine:
    from thermocomp.apps.sim.thermoelastic import ThermoelasticMap

    sources = [
        SpeedLosses("main_spindle", {"main_bearing": 0.5, "main_head": 0.5}, signal=N1,
                    idle_W=60.0, linear_W_per_krpm=80.0, quadratic_W_per_krpm2=15.0),
        SpeedLosses("counter_spindle", {"counter_bearing": 0.5, "counter_head": 0.5}, signal=N2,
                    idle_W=40.0, linear_W_per_krpm=50.0, quadratic_W_per_krpm2=10.0),
        ConstantWhileRunning("turret1_drives", {"turret1": 1.0}, power_W=80.0, when=N1),
        ConstantWhileRunning("turret2_drives", {"turret2": 1.0}, power_W=60.0, when=N2),
        ConstantWhileRunning("cut", {"coolant": 1.0}, power_W=500.0, when=CUTTING),
    ]
    sensors = [
        TemperatureSensor("T_amb", {AMBIENT: 1.0}, 0.0, lag_s=120.0),
        TemperatureSensor("T_bed", {"bed": 1.0}, 0.0, lag_s=900.0),
        TemperatureSensor("T_main_head", {"main_head": 0.7, "main_bearing": 0.3}, 0.0, lag_s=300.0),
        TemperatureSensor("T_counter_head", {"counter_head": 0.8, "counter_bearing": 0.2}, 0.0,
                          lag_s=300.0),
        TemperatureSensor("T_turret1", {"turret1": 1.0}, 0.0, lag_s=240.0),
        TemperatureSensor("T_turret2", {"turret2": 1.0}, 0.0, lag_s=240.0),
        TemperatureSensor("T_coolant", {"coolant": 1.0}, 0.0, lag_s=60.0),
    ]
    errors = ThermoelasticMap(
        linear={"E_X1": {"main_head": 3.0, "turret1": -2.5, "bed": 0.5, "main_bearing": 1.0},
                "E_Z1": {"main_bearing": 8.0, "main_head": 4.0, "turret1": -3.0, "bed": -2.0},
                "E_X2": {"counter_head": 2.5, "turret2": -2.0, "bed": 0.5, "counter_bearing": 1.0},
                "E_Z2": {"counter_bearing": 6.0, "counter_head": 3.0, "turret2": -2.5,
                         "bed": -1.5}},
        reference_c=20.0)
    return Machine(ThermalNetwork(NODES, LINKS), sources, sensors, errors)


class BedLever(LoggedStateEffect):
    """The bed's growth between turret 2 and the counter headstock at Z2 (S_Z2_mm is logged)."""

    name, state = "bed_lever", Z2
    defaults = {"gain": LEVER_UM_PER_MM_K, "targets": ["E_Z2"]}

    def modify_errors(self, ctx, errors):
        errors = errors.copy()
        k = ctx.machine.thermoelastic.targets.index("E_Z2")
        errors[:, k] += float(self.params["gain"]) * self.logged(ctx) * self.rise(ctx, "bed")
        return errors


def programme(rng, period_s: float, duration_s: float):
    """Step lists (start s, value) of the main speed, the counter speed and Z2."""
    def grid(t):
        return period_s * round(t / period_s)

    n1, n2, z2 = [(0.0, 0.0)], [(0.0, 0.0)], [(0.0, PARKED_MM)]
    t = 0.0
    while t < duration_s:
        if not working(t):
            t = grid(t + period_s)
            continue
        stop = t + rng.uniform(30.0, 150.0) * 60.0
        shift_end = (np.floor(t / DAY_S) * DAY_S) + 16 * 3600.0
        stop = min(stop, shift_end)
        n1.append((grid(t), float(rng.integers(8, 36) * 100)))
        back = rng.random() < 0.4
        n2.append((grid(t), float(rng.integers(10, 46) * 100) if back else 0.0))
        z2.append((grid(t), float(np.round(rng.uniform(80.0, 350.0))) if back else PARKED_MM))
        n1.append((grid(stop), 0.0))
        n2.append((grid(stop), 0.0))
        z2.append((grid(stop), PARKED_MM))
        t = stop + rng.uniform(5.0, 30.0) * 60.0
    return merge(n1), merge(n2), merge(z2)


@dataclass(eq=False, repr=False, kw_only=True)
class Tsc66(PlantedScenario):
    """Six 40 h runs of the twin-spindle turning centre (one campaign each)."""

    name = "tsc66"
    year = 2027
    planted = BedLever

    runs: int = 6
    run_h: float = RUN_H
    sample_period_s: float = 60.0

    def machine(self):
        return machine()

    def planted_truth(self):
        return {"E_Z2_um_per_mm_K": LEVER_UM_PER_MM_K, "position": Z2, "node": "bed"}

    def plans(self, rng):
        period = float(self.sample_period_s)
        duration = float(self.run_h) * 3600.0 - period
        hall = AmbientModel(annual_mean_c=21.0, annual_amplitude_c=0.0, daily_amplitude_c=2.0,
                            daily_peak_hour=15.0, drift_sd_c=0.6, drift_tau_h=24.0)
        plans = []
        for k in range(int(self.runs)):
            first_day = RUN_DAYS[k % len(RUN_DAYS)] + 14 * (k // len(RUN_DAYS))
            start = START + timedelta(days=first_day)
            run_rng = np.random.default_rng([int(self.seed), k])
            n1, n2, z2 = (held(s) for s in programme(run_rng, period, duration))
            plans.append(CampaignPlan(
                cid=f"run{k + 1:02d}", split="train",
                start_s=(start - datetime(self.year, 1, 1)).total_seconds(), duration_s=duration,
                rng=run_rng, ambient=hall, programme=None,
                states={N1: n1, N2: n2, Z2: z2, CUTTING: either(n1, n2)},
                written=(N1, N2, Z2), sample_period_s=period, error_period_s=None,
                cooldown_s=2 * DAY_S, notes=f"run {k + 1}, {self.run_h:g} h from "
                f"{start:%a %Y-%m-%d %H:%M}", manifest={}))
        return plans


__all__ = ["Tsc66", "machine"]
