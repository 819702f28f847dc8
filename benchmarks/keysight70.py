r"""``keysight70``: a 5-axis machining centre with a trunnion table, nobody tuned on (keysight70).

Built through the documented own-machine route (docs/simulation.md, "Your own machine"): this
:class:`~thermocomp.apps.sim.scenario.Scenario` subclass on ``PYTHONPATH`` and the yaml
``benchmarks/conf70/sim/keysight70.yaml``::

    THERMOCOMP_TARGETS=keysight70. PYTHONPATH=src:benchmarks .venv/bin/python -m thermocomp \
        simulate "hydra.searchpath=[file://$PWD/benchmarks/conf70]" sim=keysight70 seed=7041

Written down and committed before any model ran on it; seeds 7041 and 7042 fixed beforehand
(7041: the lab's eight test runs, exported by BenchLink Data Logger 3 from a 34970A; 7042: the
same machine three weeks later, another eight runs, exported from a DAQ970A on a German PC).
The lab's files are written by ``benchmarks/bench_keysight70.py write``.

The machine
-----------
A vertical 5-axis machining centre: a motor SPINDLE (max 18000 rpm) in a HEADSTOCK on the Z
slide of a moving COLUMN on the BED; the work sits on a rotary TABLE (C) carried by a TRUNNION
cradle that tilts about the A axis (0° flat, up to 90°: the table's face toward Y), both driven
by torque motors (the A motor's losses into the trunnion).  The chips and the coolant fall onto
the table and the trunnion's trough; the coolant (200 l) runs back to the bed's tank.  The
hall: 20.0 °C +- 1.5 K a day (peak 14 h), a weather drift of 0.4 K (12 h).

=============  =======  =====  ========================================================
node           C (J/K)  hA     what
=============  =======  =====  ========================================================
bed            3e6      25     the bed with the coolant tank under it
column         6e5      8      the moving column with its X/Y slides
headstock      1.5e5    4      the Z slide and the spindle's housing
spindle        2.5e4    2      the motor spindle's shaft, bearings and stator
trunnion       2.5e5    5      the A cradle and its torque motor
table          8e4      3      the C table and its riser the work stands on
coolant        3e5      8      the coolant on the trunnion, in the trough and the tank
=============  =======  =====  ========================================================

Links (W/K): bed-column 10, column-headstock 6, headstock-spindle 5, bed-trunnion 12,
trunnion-table 6, coolant-table 8, coolant-trunnion 6, coolant-bed 20.
Heat (W): the spindle ``S_n_spindle_rpm``: 30 + 5 n + 0.2 n^2 (n in krpm), 0.7 into the
spindle, 0.3 into the headstock; while the spindle cuts: the column's drives 50, the A motor
holding the tilted cradle 80 into the trunnion, the cut 200 into the coolant and 60 into the
table (the chips).

Errors at the tool against a master ball on the table (µm/K of the node rises from the run's
first sample; the lab's capacitive probes in the spindle at the ball, read every sample)::

    E_X = 1.5 column - 0.8 bed + 1.0 trunnion
    E_Y = 2.0 headstock - 1.0 column + 1.2 trunnion + 0.3 bed
    E_Z = -6.0 spindle - 3.0 headstock + 4.0 column - 1.5 trunnion - 1.0 bed

PLANTED (the effect the default model lacks): the ball stands 200 mm above the A axis on the
table and its riser; their growth, 11.5 µm/(m K) x 0.2 m = 2.3 µm/K of the table's rise, points
along the table's normal, which the tilt A (logged, ``S_pos_A``, degrees) turns from Z toward Y::

    E_Y += 2.3 sin(A) rise(table),   E_Z += 2.3 cos(A) rise(table)   (µm)

A linear map of the temperatures and of ``S_pos_A`` cannot carry the product on E_Y; diagnose
should find ``S_pos_A`` x a rise (the table's sensor or the inputs') on E_Y.

Sensors (type-T thermocouples on the DAQ, 0.05 K noise, 0.01 K steps; lags in s): T_amb (the
air, 120), T_bed (900), T_column (600), T_headstock (0.7 headstock + 0.3 spindle, 240),
T_spindle (spindle, 120), T_trunnion (trunnion, 600), T_table (table, 300), T_coolant (60).
The spindle's speed and the tilt are logged (``S_n_spindle_rpm``, ``S_pos_A``).  The probes:
0.2 µm noise, 0.1 µm steps.

The programme
-------------
Eight runs of 24 h at 60 s, from 06:00 on Monday 2027-03-01, Wednesday, Friday, the next
Monday, Wednesday, Friday, the Monday and Wednesday after (each after a 2-day rest: the
simulator soaks the machine, independent runs, each its own clock; so 7041's dates are all
at most the 17th, several of them ambiguous as day or month).  Jobs from 06:00 to 22:00, idle
through the night: each job 20-120 min at one speed (4000-18000 rpm, steps of 500) and one
tilt drawn from {0, 15, 30, 45, 60, 75, 90}°; between jobs a pause of 5-30 min, the spindle
stopped and the cradle back at A = 0°.  The last run(s) are held out by ``data.test_fraction``.
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime

import numpy as np
from scenario_tail import DayRunsScenario, TurnedGrowth, day_runs, merge, working

from thermocomp.apps.sim.ambient import DAY_S, AmbientModel
from thermocomp.apps.sim.campaign import Machine
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import ConstantWhileRunning, SpeedLosses

N_SPINDLE, A_DEG = "S_n_spindle_rpm", "S_pos_A"
START = datetime(2027, 3, 1, 6)          # a Monday, 06:00
RUN_DAYS = (0, 2, 4, 7, 9, 11, 14, 16)   # the runs' first days from START
TABLE_UM_PER_K = 2.3                     # the planted growth along the table's normal

NODES = (Node("bed", 3e6, 25.0), Node("column", 6e5, 8.0), Node("headstock", 1.5e5, 4.0),
         Node("spindle", 2.5e4, 2.0), Node("trunnion", 2.5e5, 5.0), Node("table", 8e4, 3.0),
         Node("coolant", 3e5, 8.0))
LINKS = (Link("bed", "column", 10.0), Link("column", "headstock", 6.0),
         Link("headstock", "spindle", 5.0), Link("bed", "trunnion", 12.0),
         Link("trunnion", "table", 6.0), Link("coolant", "table", 8.0),
         Link("coolant", "trunnion", 6.0), Link("coolant", "bed", 20.0))
ERRORS = {
    "E_X": {"column": 1.5, "bed": -0.8, "trunnion": 1.0},
    "E_Y": {"headstock": 2.0, "column": -1.0, "trunnion": 1.2, "bed": 0.3},
    "E_Z": {"spindle": -6.0, "headstock": -3.0, "column": 4.0, "trunnion": -1.5, "bed": -1.0},
}


def machine() -> Machine:
    from thermocomp.apps.sim.thermoelastic import ThermoelasticMap

    sources = [
        SpeedLosses("spindle", {"spindle": 0.7, "headstock": 0.3}, signal=N_SPINDLE,
                    idle_W=30.0, linear_W_per_krpm=5.0, quadratic_W_per_krpm2=0.2),
        ConstantWhileRunning("column_drives", {"column": 1.0}, power_W=50.0, when=N_SPINDLE),
        ConstantWhileRunning("a_motor", {"trunnion": 1.0}, power_W=80.0, when=N_SPINDLE),
        ConstantWhileRunning("cut", {"coolant": 200.0 / 260.0, "table": 60.0 / 260.0},
                             power_W=260.0, when=N_SPINDLE),
    ]
    sensors = [
        TemperatureSensor("T_amb", {AMBIENT: 1.0}, 0.0, lag_s=120.0),
        TemperatureSensor("T_bed", {"bed": 1.0}, 0.0, lag_s=900.0),
        TemperatureSensor("T_column", {"column": 1.0}, 0.0, lag_s=600.0),
        TemperatureSensor("T_headstock", {"headstock": 0.7, "spindle": 0.3}, 0.0, lag_s=240.0),
        TemperatureSensor("T_spindle", {"spindle": 1.0}, 0.0, lag_s=120.0),
        TemperatureSensor("T_trunnion", {"trunnion": 1.0}, 0.0, lag_s=600.0),
        TemperatureSensor("T_table", {"table": 1.0}, 0.0, lag_s=300.0),
        TemperatureSensor("T_coolant", {"coolant": 1.0}, 0.0, lag_s=60.0),
    ]
    return Machine(ThermalNetwork(NODES, LINKS), sources, sensors,
                   ThermoelasticMap(linear=ERRORS, reference_c=20.0))


class TableNormal(TurnedGrowth):
    """The table's growth along its normal, turned from Z toward Y by the tilt (S_pos_A logged)."""

    name, state, node, along_cos, along_sin = "table_normal", A_DEG, "table", "E_Z", "E_Y"
    defaults = {"gain": TABLE_UM_PER_K, "targets": ["E_Y", "E_Z"]}


def programme(rng, period_s: float, duration_s: float):
    """Step lists (start s, value) of the spindle speed and the tilt A."""
    def grid(t):
        return period_s * round(t / period_s)

    n_spindle, a_deg = [(0.0, 0.0)], [(0.0, 0.0)]
    t = 0.0
    while t < duration_s:
        if not working(t):
            t = grid(t + period_s)
            continue
        stop = min(t + rng.uniform(20.0, 120.0) * 60.0, np.floor(t / DAY_S) * DAY_S + 16 * 3600.0)
        n_spindle.append((grid(t), float(rng.integers(8, 37) * 500)))
        a_deg.append((grid(t), float(rng.integers(0, 7) * 15)))
        n_spindle.append((grid(stop), 0.0))
        a_deg.append((grid(stop), 0.0))
        t = stop + rng.uniform(5.0, 30.0) * 60.0
    return merge(n_spindle), merge(a_deg)


@dataclass(eq=False, repr=False, kw_only=True)
class Keysight70(DayRunsScenario):
    """Eight 24 h runs of the trunnion machining centre (one campaign each)."""

    name = "keysight70"
    year = 2027
    planted = TableNormal
    temp_noise_c: float = 0.05               # thermocouples on the DAQ, noisier than a Pt100

    def machine(self):
        return machine()

    def planted_truth(self):
        return {"um_per_K": TABLE_UM_PER_K, "angle": A_DEG, "node": "table",
                "E_Y": "sin(A)", "E_Z": "cos(A)"}

    def plans(self, rng):
        hall = AmbientModel(annual_mean_c=20.0, annual_amplitude_c=0.0, daily_amplitude_c=1.5,
                            daily_peak_hour=14.0, drift_sd_c=0.4, drift_tau_h=12.0)
        return day_runs(self, START, RUN_DAYS, hall, programme, (N_SPINDLE, A_DEG))


__all__ = ["Keysight70", "machine"]
