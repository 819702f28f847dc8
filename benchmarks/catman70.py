r"""``catman70``: a motor spindle on an ISO 230-3 test rig, logged with HBM catman, nobody tuned on.

Built through the documented own-machine route (docs/simulation.md, "Your own machine"): this
:class:`~thermocomp.apps.sim.scenario.Scenario` subclass on ``PYTHONPATH`` and the yaml
``benchmarks/conf70/sim/catman70.yaml``::

    THERMOCOMP_TARGETS=catman70. PYTHONPATH=src:benchmarks .venv/bin/python -m thermocomp \
        simulate "hydra.searchpath=[file://$PWD/benchmarks/conf70]" sim=catman70 seed=7131

Written down and committed before any model ran on it; seeds 7131 and 7132 fixed beforehand
(7131: the lab's eight ISO 230-3 tests of one spindle, exported by catman Easy on a German PC,
one file per test; 7132: the same rig three weeks later, eight more tests, exported by catman AP
on an English PC into one file).  The lab's files are written by ``benchmarks/bench_catman70.py
write``.

The rig
-------
A spindle manufacturer's test stand: a motor SPINDLE (max 15000 rpm, grease-lubricated angular
contact bearings, no chiller) clamped vertically, nose down, in a HOUSING flange on a cast
COLUMN standing on the rig's BASE plate.  A test mandrel (Ø 40 mm) in the spindle; under it a
sensor nest on the base holds five capacitive probes: X1 / Y1 at 20 mm below the nose, X2 / Y2
100 mm lower (near the mandrel's end), Z against the mandrel's end face.  Lumped nodes (C J/K,
hA W/K to the hall air):

=============  =======  =====  ========================================================
node           C (J/K)  hA     what
=============  =======  =====  ========================================================
base           1.5e6    15     the rig's cast base plate with the sensor nest
column         4e5      6      the stand's column
housing        1e5      5      the spindle's housing and flange
front_bearing  2e4      2      the front bearing set (next to the nose)
motor          4e4      3      the built-in motor's stator and the rear bearings
=============  =======  =====  ========================================================

Links (W/K): base-column 10, column-housing 6, housing-front_bearing 5, housing-motor 6.
Heat (W): the spindle ``S_n_spindle_rpm``: 20 + 10 n + 0.6 n^2 (n in krpm), 0.5 into the front
bearings, 0.5 into the motor; nothing at rest.

The errors: the five probes' raw readings (µm, the mandrel's displacement toward each probe from
the run's first sample; linear in the node rises)::

    E_X1 = 1.5 column - 0.5 base + 0.8 housing
    E_X2 = 1.5 column - 0.5 base + 1.6 housing            (the housing's roll: B)
    E_Y1 = -1.2 column + 2.0 housing + 0.4 front_bearing
    E_Y2 = -1.2 column + 2.6 housing + 0.2 front_bearing  (A)
    E_Z  = 4.0 column - 1.0 base - 3.0 housing - 5.0 front_bearing - 2.0 motor

PLANTED (the effect the default model lacks): the ROTOR's axial growth, which no sensor sees
(the thermocouples sit on the stator side): its losses rise with the speed squared (windage,
the rotor's iron), its temperature follows them with its own time constant (20 min), and the
shaft grows toward the Z probe::

    E_Z += -0.07 lag_1200s((n / krpm)^2)   (µm; -15.75 at 15000 rpm held)

``lag_1200s``: a first-order lag of 1200 s of the logged speed's square, 0 at the run's start
(the rig rested).  A linear map of the temperatures and of ``S_n_spindle_rpm`` holds it only as
far as the front bearing's sensor follows the speed; ``diagnose`` might find the speed (its
square, lagged or not) on E_Z.

Sensors (type-K thermocouples on a QuantumX MX1609, 0.05 K noise, 0.01 K steps; lags in s):
T_amb (the air, 120), T_base (900), T_column (600), T_housing (0.7 housing + 0.3 front_bearing,
240), T_front (front_bearing, 60), T_rear (motor, 120).  The speed is logged from the drive's
analogue output (``S_n_spindle_rpm``).  The probes: 0.1 µm noise, 0.01 µm steps.

The programme (ISO 230-3 clause 6, spindle tests)
-------------------------------------------------
Eight tests of 12 h at 30 s, from 07:00 on Monday 2027-04-05, Wednesday, Friday, the next
Monday, ... (each after a 2-day rest: independent tests, each its own clock).  A test with p 0.3
runs the constant speed test (6.2: 50 % or 75 % of max, i.e. 7500 or 11250 rpm, for 4 h), else
a speed spectrum (6.3: four steps of 60-105 min, speeds drawn without repeat from {3000, 4500,
..., 15000} rpm, in the drawn order); then the spindle stops and the rig cools for the rest of
the 12 h (the drift's cool-down).  The last test(s) are held out by ``data.test_fraction``.
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime

import numpy as np
from scenario_tail import DayRunsScenario, LoggedStateEffect, day_runs, merge

from thermocomp.apps.sim.ambient import AmbientModel
from thermocomp.apps.sim.campaign import Machine
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import SpeedLosses

N_SPINDLE = "S_n_spindle_rpm"
START = datetime(2027, 4, 5, 7)          # a Monday, 07:00
RUN_DAYS = (0, 2, 4, 7, 9, 11, 14, 16)   # the tests' first days from START
ROTOR_UM_PER_KRPM2 = -0.07               # the planted rotor growth per (krpm)^2 held
ROTOR_TAU_S = 1200.0

NODES = (Node("base", 1.5e6, 15.0), Node("column", 4e5, 6.0), Node("housing", 1e5, 5.0),
         Node("front_bearing", 2e4, 2.0), Node("motor", 4e4, 3.0))
LINKS = (Link("base", "column", 10.0), Link("column", "housing", 6.0),
         Link("housing", "front_bearing", 5.0), Link("housing", "motor", 6.0))
ERRORS = {
    "E_X1": {"column": 1.5, "base": -0.5, "housing": 0.8},
    "E_X2": {"column": 1.5, "base": -0.5, "housing": 1.6},
    "E_Y1": {"column": -1.2, "housing": 2.0, "front_bearing": 0.4},
    "E_Y2": {"column": -1.2, "housing": 2.6, "front_bearing": 0.2},
    "E_Z": {"column": 4.0, "base": -1.0, "housing": -3.0, "front_bearing": -5.0, "motor": -2.0},
}


def machine() -> Machine:
    from thermocomp.apps.sim.thermoelastic import ThermoelasticMap

    sources = [SpeedLosses("spindle", {"front_bearing": 0.5, "motor": 0.5}, signal=N_SPINDLE,
                           idle_W=20.0, linear_W_per_krpm=10.0, quadratic_W_per_krpm2=0.6)]
    sensors = [
        TemperatureSensor("T_amb", {AMBIENT: 1.0}, 0.0, lag_s=120.0),
        TemperatureSensor("T_base", {"base": 1.0}, 0.0, lag_s=900.0),
        TemperatureSensor("T_column", {"column": 1.0}, 0.0, lag_s=600.0),
        TemperatureSensor("T_housing", {"housing": 0.7, "front_bearing": 0.3}, 0.0, lag_s=240.0),
        TemperatureSensor("T_front", {"front_bearing": 1.0}, 0.0, lag_s=60.0),
        TemperatureSensor("T_rear", {"motor": 1.0}, 0.0, lag_s=120.0),
    ]
    return Machine(ThermalNetwork(NODES, LINKS), sources, sensors,
                   ThermoelasticMap(linear=ERRORS, reference_c=20.0))


class RotorGrowth(LoggedStateEffect):
    """The rotor's axial growth: a first-order lag of the logged speed's square (krpm^2), 0 at
    the run's start, times ``gain`` µm, on E_Z."""

    name, state = "rotor_growth", N_SPINDLE
    defaults = {"gain": ROTOR_UM_PER_KRPM2, "tau_s": ROTOR_TAU_S, "targets": ["E_Z"]}

    def modify_errors(self, ctx, errors):
        errors = errors.copy()
        square = (self.logged(ctx) / 1000.0) ** 2
        keep = np.exp(-float(ctx.sample_period_s) / float(self.params["tau_s"]))
        lagged = np.zeros_like(square)
        for k in range(1, len(square)):
            lagged[k] = keep * lagged[k - 1] + (1.0 - keep) * square[k - 1]
        errors[:, ctx.machine.thermoelastic.targets.index("E_Z")] += (
            float(self.params["gain"]) * lagged)
        return errors


SPEEDS = tuple(range(3000, 15001, 1500))


def programme(rng, period_s: float, duration_s: float):
    """The speed's steps (start s, rpm): the constant speed test or a spectrum, then rest."""
    def grid(t):
        return period_s * round(t / period_s)

    if rng.random() < 0.3:
        steps = [(0.0, float(rng.choice([7500.0, 11250.0]))), (grid(4 * 3600.0), 0.0)]
    else:
        steps, t = [], 0.0
        for speed in rng.choice(SPEEDS, size=4, replace=False):
            steps.append((grid(t), float(speed)))
            t += rng.uniform(60.0, 105.0) * 60.0
        steps.append((grid(t), 0.0))
    return (merge(steps),)


@dataclass(eq=False, repr=False, kw_only=True)
class Catman70(DayRunsScenario):
    """Eight 12 h ISO 230-3 spindle tests on the rig (one campaign each)."""

    name = "catman70"
    year = 2027
    planted = RotorGrowth
    temp_noise_c: float = 0.05               # thermocouples, noisier than a Pt100
    error_noise_um: float = 0.1
    error_quantum_um: float = 0.01

    def machine(self):
        return machine()

    def planted_truth(self):
        return {"um_per_krpm2": ROTOR_UM_PER_KRPM2, "tau_s": ROTOR_TAU_S, "state": N_SPINDLE,
                "target": "E_Z"}

    def plans(self, rng):
        hall = AmbientModel(annual_mean_c=21.0, annual_amplitude_c=0.0, daily_amplitude_c=1.0,
                            daily_peak_hour=15.0, drift_sd_c=0.4, drift_tau_h=8.0)
        return day_runs(self, START, RUN_DAYS, hall, programme, (N_SPINDLE,))


__all__ = ["Catman70", "machine"]
