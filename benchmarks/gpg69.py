r"""``gpg69``: a gear profile grinding machine with a chilled grinding oil, nobody tuned on (stranger69).

Built through the documented own-machine route (docs/simulation.md, "Your own machine"): this
:class:`~thermocomp.apps.sim.scenario.Scenario` subclass on ``PYTHONPATH`` and the yaml
``benchmarks/conf69/sim/gpg69.yaml``::

    THERMOCOMP_TARGETS=gpg69. PYTHONPATH=src:benchmarks .venv/bin/python -m thermocomp \
        simulate "hydra.searchpath=[file://$PWD/benchmarks/conf69]" sim=gpg69 seed=6901

Written down and committed before any model ran on it; seeds 6901 and 6902 fixed beforehand
(6901: the lab's eight test runs; 6902: the same machine three weeks later, another eight runs,
written by another export setting).  The lab's LabVIEW files are written by
``benchmarks/bench_stranger69.py write``.

The machine
-----------
A vertical gear profile grinding machine: the workpiece stands on a heavy ROTARY TABLE (the C
axis, a torque motor, hydrostatic oil bearings) on a polymer-concrete BED; a COLUMN carries the
WHEELHEAD on its X (radial infeed) and Z (axial stroke) slides; the wheelhead's WHEEL SPINDLE
(a profiled grinding wheel, 3000-6000 rpm) grinds one tooth gap after the other while the table
indexes.  The grinding OIL (a 1500 l tank) floods the wheel and the work and runs back over the
table and the bed; an OIL CHILLER holds the tank at its set point (heating and cooling,
1500 W/K, at most 4 kW; off while the machine rests), and the lab logs that set point.  The
hall: 21 °C +- 1.2 K a day (peak 15 h), a weather drift of 0.5 K (12 h).

=============  =======  =====  ========================================================
node           C (J/K)  hA     what
=============  =======  =====  ========================================================
bed            4e6      30     the polymer-concrete bed
column         8e5      10     the column with its X/Z slides
wheelhead      2e5      8      the wheelhead housing and its drive
wheel_spindle  3e4      4      the grinding spindle's shaft, bearings and motor
table          6e5      6      the rotary table (C), its torque motor and bearings
oil            1.2e6    15     the grinding oil in the tank, on the table and the bed
=============  =======  =====  ========================================================

Links (W/K): bed-column 12, column-wheelhead 6, wheelhead-wheel_spindle 8, bed-table 10,
oil-table 10, oil-bed 15, oil-wheelhead 2.
Heat (W): the wheel spindle ``S_n_wheel_rpm``: 40 + 30 n + 4 n^2 (n in krpm), 0.6 into the
spindle, 0.4 into the wheelhead; while the wheel grinds the grinding power 1200 into the oil,
the work and the C axis' torque motor 150 into the table, the column's drives 60; the chiller
-1500 (T_oil - ``S_oil_set_C``), within +-4000, while its set point is on (> 0).

Errors at the wheel against the work (µm/K of the node rises from the run's first sample; the
lab's capacitive probes on the wheelhead at a master ring on the table, at the radius where the
head stands, read every sample)::

    E_X = 2.5 wheelhead + 1.0 wheel_spindle - 2.0 column + 0.5 bed - 1.5 table
    E_Y = 1.2 column - 0.8 wheelhead + 0.4 bed
    E_Z = 3.0 column + 2.0 wheelhead - 2.5 table - 1.0 bed

PLANTED (the effect the default model lacks): the table grows radially with its rise, so the
ring's surface at the head's radius (``S_X_mm``, logged: 150-450 mm by the gear ground, 500 mm
parked) comes toward the wheel by 11.5 µm/(m K) x the radius::

    E_X += -0.0115 S_X_mm rise(table)   (µm)

A linear map of the temperatures and of ``S_X_mm`` cannot carry a product; diagnose should
find ``S_X_mm`` x a rise (the table's sensor or the inputs') on E_X.

Sensors (Pt100, 0.03 K noise, 0.01 K steps; lags in s): T_amb (the air, 120), T_bed (900),
T_column (600), T_wheelhead (0.7 wheelhead + 0.3 wheel_spindle, 180), T_spindle
(wheel_spindle, 120), T_table (600), T_oil (60).  The wheel speed, the X position and the
chiller's set point are logged (``S_n_wheel_rpm``, ``S_X_mm``, ``S_oil_set_C``).  The probes:
0.2 µm noise, 0.1 µm steps.

The programme
-------------
Eight runs of 24 h at 60 s, from 06:00 on Monday 2027-09-06, Wednesday, Friday, the next
Monday, Wednesday, Friday, the Monday and Wednesday after (each after a 2-day rest: the
simulator soaks the machine, independent runs, each its own clock).  Jobs from 06:00 to 22:00,
idle through the night: each job 30-120 min grinding one gear (the wheel at 3000-6000 rpm,
steps of 250; the head at X 150-450 mm, steps of 10), a pause of 5-30 min between jobs (the
wheel stopped, the head parked at X = 500 mm).  The chiller's set point is 21.0 °C from the
run's start; in a run with p 0.5 the lab sets it to 20.0 or 22.0 °C (even odds) at a whole
hour from 10:00 to 16:00, kept to the run's end.  The last run(s) are held out by
``data.test_fraction``.
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime

import numpy as np
from scenario_tail import DayRunsScenario, LoggedStateEffect, day_runs, merge, working

from thermocomp.apps.sim.ambient import DAY_S, AmbientModel
from thermocomp.apps.sim.campaign import Machine
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import ConstantWhileRunning, HeatSource, SpeedLosses

N_WHEEL, X_MM, OIL_SET = "S_n_wheel_rpm", "S_X_mm", "S_oil_set_C"
START = datetime(2027, 9, 6, 6)          # a Monday, 06:00
RUN_DAYS = (0, 2, 4, 7, 9, 11, 14, 16)   # the runs' first days from START
PARKED_MM = 500.0
TABLE_UM_PER_MM_K = -0.0115              # the planted radial growth of the table

NODES = (Node("bed", 4e6, 30.0), Node("column", 8e5, 10.0), Node("wheelhead", 2e5, 8.0),
         Node("wheel_spindle", 3e4, 4.0), Node("table", 6e5, 6.0), Node("oil", 1.2e6, 15.0))
LINKS = (Link("bed", "column", 12.0), Link("column", "wheelhead", 6.0),
         Link("wheelhead", "wheel_spindle", 8.0), Link("bed", "table", 10.0),
         Link("oil", "table", 10.0), Link("oil", "bed", 15.0), Link("oil", "wheelhead", 2.0))
ERRORS = {
    "E_X": {"wheelhead": 2.5, "wheel_spindle": 1.0, "column": -2.0, "bed": 0.5, "table": -1.5},
    "E_Y": {"column": 1.2, "wheelhead": -0.8, "bed": 0.4},
    "E_Z": {"column": 3.0, "wheelhead": 2.0, "table": -2.5, "bed": -1.0},
}


@dataclass
class Chiller(HeatSource):
    """The oil chiller: ``-gain (T_oil - set)`` W within +-``cap_W`` while its set point (the
    state ``signal``) is on; off (0 W) at a set point of 0 (the machine at rest)."""

    signal: str = OIL_SET
    node: str = "oil"
    gain_W_per_K: float = 1500.0
    cap_W: float = 4000.0

    depends_on_temperature = True

    def power(self, state, temperature_of):
        set_c = state.get(self.signal, 0.0)
        if not set_c > 0.0:
            return 0.0
        return float(np.clip(-self.gain_W_per_K * (temperature_of(self.node) - set_c),
                             -self.cap_W, self.cap_W))


def machine() -> Machine:
    from thermocomp.apps.sim.thermoelastic import ThermoelasticMap

    sources = [
        SpeedLosses("wheel_spindle", {"wheel_spindle": 0.6, "wheelhead": 0.4}, signal=N_WHEEL,
                    idle_W=40.0, linear_W_per_krpm=30.0, quadratic_W_per_krpm2=4.0),
        ConstantWhileRunning("grinding", {"oil": 1.0}, power_W=1200.0, when=N_WHEEL),
        ConstantWhileRunning("table_drive", {"table": 1.0}, power_W=150.0, when=N_WHEEL),
        ConstantWhileRunning("column_drives", {"column": 1.0}, power_W=60.0, when=N_WHEEL),
        Chiller("chiller", {"oil": 1.0}),
    ]
    sensors = [
        TemperatureSensor("T_amb", {AMBIENT: 1.0}, 0.0, lag_s=120.0),
        TemperatureSensor("T_bed", {"bed": 1.0}, 0.0, lag_s=900.0),
        TemperatureSensor("T_column", {"column": 1.0}, 0.0, lag_s=600.0),
        TemperatureSensor("T_wheelhead", {"wheelhead": 0.7, "wheel_spindle": 0.3}, 0.0,
                          lag_s=180.0),
        TemperatureSensor("T_spindle", {"wheel_spindle": 1.0}, 0.0, lag_s=120.0),
        TemperatureSensor("T_table", {"table": 1.0}, 0.0, lag_s=600.0),
        TemperatureSensor("T_oil", {"oil": 1.0}, 0.0, lag_s=60.0),
    ]
    return Machine(ThermalNetwork(NODES, LINKS), sources, sensors,
                   ThermoelasticMap(linear=ERRORS, reference_c=20.0))


class TableRadius(LoggedStateEffect):
    """The table's radial growth at the head's radius (S_X_mm is logged) onto E_X."""

    name, state = "table_radius", X_MM
    defaults = {"gain": TABLE_UM_PER_MM_K, "targets": ["E_X"]}

    def modify_errors(self, ctx, errors):
        errors = errors.copy()
        targets = ctx.machine.thermoelastic.targets
        growth = float(self.params["gain"]) * self.logged(ctx) * self.rise(ctx, "table")
        errors[:, targets.index("E_X")] += growth
        return errors


def programme(rng, period_s: float, duration_s: float):
    """Step lists (start s, value) of the wheel speed, the X position and the set point."""
    def grid(t):
        return period_s * round(t / period_s)

    n_wheel, x_mm = [(0.0, 0.0)], [(0.0, PARKED_MM)]
    t = 0.0
    while t < duration_s:
        if not working(t):
            t = grid(t + period_s)
            continue
        stop = min(t + rng.uniform(30.0, 120.0) * 60.0, np.floor(t / DAY_S) * DAY_S + 16 * 3600.0)
        n_wheel.append((grid(t), float(rng.integers(12, 25) * 250)))
        x_mm.append((grid(t), float(rng.integers(15, 46) * 10)))
        n_wheel.append((grid(stop), 0.0))
        x_mm.append((grid(stop), PARKED_MM))
        t = stop + rng.uniform(5.0, 30.0) * 60.0
    oil_set = [(0.0, 21.0)]
    if rng.random() < 0.5:                    # the lab's chiller test: a new set point
        hour = float(rng.integers(10, 17))
        oil_set.append(((hour - 6.0) * 3600.0, 20.0 if rng.random() < 0.5 else 22.0))
    return merge(n_wheel), merge(x_mm), merge(oil_set)


@dataclass(eq=False, repr=False, kw_only=True)
class Gpg69(DayRunsScenario):
    """Eight 24 h runs of the gear profile grinding machine (one campaign each)."""

    name = "gpg69"
    year = 2027
    planted = TableRadius

    def machine(self):
        return machine()

    def planted_truth(self):
        return {"um_per_mm_K": TABLE_UM_PER_MM_K, "radius": X_MM, "node": "table",
                "E_X": "S_X_mm x rise(table)"}

    def plans(self, rng):
        hall = AmbientModel(annual_mean_c=21.0, annual_amplitude_c=0.0, daily_amplitude_c=1.2,
                            daily_peak_hour=15.0, drift_sd_c=0.5, drift_tau_h=12.0)
        return day_runs(self, START, RUN_DAYS, hall, programme, (N_WHEEL, X_MM, OIL_SET))


__all__ = ["Gpg69", "machine"]
