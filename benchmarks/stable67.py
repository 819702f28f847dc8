r"""``stable67``: a thermally stable grinder -- is compensation worth deploying? (stable67)

Built through the documented own-machine route (docs/simulation.md, "Your own machine"): this
:class:`~thermocomp.apps.sim.scenario.Scenario` subclass on ``PYTHONPATH`` and the yaml
``benchmarks/conf67/sim/stable67.yaml``::

    THERMOCOMP_TARGETS=stable67. PYTHONPATH=src:benchmarks .venv/bin/python -m thermocomp \
        simulate "hydra.searchpath=[file://$PWD/benchmarks/conf67]" sim=stable67 seed=6711

Written down and committed before any model ran on it; seeds fixed beforehand: 6711 the machine
as built (``spindle_um=0``: no real thermal effect worth a correction), 6712 the variant with ONE
real but small effect (``spindle_um=1.5``: the wheel spindle's axial growth on E_Z).  The lab's
export is written by ``benchmarks/bench_stable67.py write``.

The machine
-----------
A hydrostatic precision cylindrical grinder: a polymer-concrete BED, the wheelhead on hydrostatic
X slides, the table (Z) on hydrostatic guideways, the wheel spindle in hydrostatic bearings.  The
hydrostatic oil and the grinding coolant are held by a chiller that follows the bed (room-tracking,
modelled as a strong link of the oil and the coolant to the air: hA 600 and 400 W/K).  The room is
a measuring-room-grade hall held at 20 °C +- 0.3 K a day (peak 14 h), a drift of 0.1 K (12 h).

===============  =======  =====  ======================================================
node             C (J/K)  hA     what
===============  =======  =====  ======================================================
bed              6e6      30     the polymer-concrete bed (thermally sluggish)
column           8e5      8      the wheelhead's cross slide carrier
wheelhead        2.5e5    5      the wheelhead housing
spindle          3e4      1      the wheel spindle (shaft and bearing sleeves)
oil              4e5      600    the hydrostatic oil in its circuit (chilled)
table            4e5      8      the table on its hydrostatic guideways
workhead         1e5      3      the workhead with its motor
coolant          5e5      400    the grinding coolant (chilled)
===============  =======  =====  ======================================================

Links (W/K): bed-column 20, column-wheelhead 10, wheelhead-spindle 3, spindle-oil 120 (the oil flows
through the bearing pockets),
wheelhead-oil 6, bed-table 15, table-oil 10, table-workhead 4, bed-coolant 5, table-coolant 6.
Heat (W): the wheel spindle ``S_n_rpm`` (0-3000): 30 + 40 n + 10 n^2 (n in krpm), 0.7 into the
spindle (hydrostatic shear), 0.3 into the oil; the workhead 25 while the wheel turns; the grinding
60 into the coolant while the wheel turns.
Errors (µm/K of the node's rise from the run's first sample; a capacitive probe pair at a test
mandrel between centres, every sample, probe noise 0.4 µm, 0.05 µm steps)::

    E_X = 0.05 column - 0.05 bed                  (thermo-symmetric: essentially none)
    E_Y = 0.6 column - 0.5 table - 0.1 bed       (small: the column against the table)
    E_Z = 0.3 wheelhead + ``spindle_gain`` spindle

and a probe-mount creep on E_X (not thermal, no sensor sees it): a straight ramp from 0 to
``creep_um`` (0.2 µm, its sign drawn per run) over each run.  ``spindle_gain`` is
``spindle_um`` / 1.0 µm/K (``spindle_um`` in µm: the spindle node rises about 1 K above the oil at
2500 rpm steady; 0 on seed 6711, 1.5 on seed 6712).

Sensors (Pt100, 0.02 K noise, 0.01 K steps; lags in s): T_amb (the air, 120), T_bed (600),
T_bed2 (the bed's other end, 600), T_column (300), T_wheelhead (300), T_spindle (the front
bearing sleeve, 0.8 spindle + 0.2 wheelhead, 120), T_oil_return (60), T_oil_supply (0.3 oil +
0.7 air: after the chiller, 60), T_table (300), T_workhead (240), T_coolant (60), T_cabinet (the
electrics cabinet: 0.5 air + 0.5 column, 300): 12 temperatures and the wheel speed ``S_n_rpm``.

The programme
-------------
14 runs at 60 s, each 8-24 h (drawn per run, whole hours), starting 06:00 on working days from
Monday 2027-04-05 (one run a day, each its own clock, independent: a night's cool-down before).
Grinding jobs through the run: each 20-90 min at one wheel speed (1500-3000 rpm, steps of 100), a
pause of 5-40 min between them.  The last runs are held out by ``data.test_fraction``.
"""

from __future__ import annotations

from datetime import datetime, timedelta

import numpy as np
from scenario_tail import held, merge

from thermocomp.apps.sim.ambient import DAY_S, AmbientModel
from thermocomp.apps.sim.campaign import Machine
from thermocomp.apps.sim.effects import UndeclaredEffect
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.scenario import CampaignPlan, Scenario
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import ConstantWhileRunning, SpeedLosses

N = "S_n_rpm"
START = datetime(2027, 4, 5, 6)          # a Monday, 06:00
RUNS = 14
CREEP_UM = 0.2

NODES = (Node("bed", 6e6, 30.0), Node("column", 8e5, 8.0), Node("wheelhead", 2.5e5, 5.0),
         Node("spindle", 3e4, 1.0), Node("oil", 4e5, 600.0), Node("table", 4e5, 8.0),
         Node("workhead", 1e5, 3.0), Node("coolant", 5e5, 400.0))
LINKS = (Link("bed", "column", 20.0), Link("column", "wheelhead", 10.0),
         Link("wheelhead", "spindle", 3.0), Link("spindle", "oil", 120.0),
         Link("wheelhead", "oil", 6.0), Link("bed", "table", 15.0), Link("table", "oil", 10.0),
         Link("table", "workhead", 4.0), Link("bed", "coolant", 5.0),
         Link("table", "coolant", 6.0))


def machine(spindle_um: float = 0.0) -> Machine:
    from thermocomp.apps.sim.thermoelastic import ThermoelasticMap

    sources = [
        SpeedLosses("wheel_spindle", {"spindle": 0.7, "oil": 0.3}, signal=N, idle_W=30.0,
                    linear_W_per_krpm=40.0, quadratic_W_per_krpm2=10.0),
        ConstantWhileRunning("workhead_motor", {"workhead": 1.0}, power_W=25.0, when=N),
        ConstantWhileRunning("grinding", {"coolant": 1.0}, power_W=60.0, when=N),
    ]
    sensors = [
        TemperatureSensor("T_amb", {AMBIENT: 1.0}, 0.0, lag_s=120.0),
        TemperatureSensor("T_bed", {"bed": 1.0}, 0.0, lag_s=600.0),
        TemperatureSensor("T_bed2", {"bed": 1.0}, 0.0, lag_s=600.0),
        TemperatureSensor("T_column", {"column": 1.0}, 0.0, lag_s=300.0),
        TemperatureSensor("T_wheelhead", {"wheelhead": 1.0}, 0.0, lag_s=300.0),
        TemperatureSensor("T_spindle", {"spindle": 0.8, "wheelhead": 0.2}, 0.0, lag_s=120.0),
        TemperatureSensor("T_oil_return", {"oil": 1.0}, 0.0, lag_s=60.0),
        TemperatureSensor("T_oil_supply", {"oil": 0.3, AMBIENT: 0.7}, 0.0, lag_s=60.0),
        TemperatureSensor("T_table", {"table": 1.0}, 0.0, lag_s=300.0),
        TemperatureSensor("T_workhead", {"workhead": 1.0}, 0.0, lag_s=240.0),
        TemperatureSensor("T_coolant", {"coolant": 1.0}, 0.0, lag_s=60.0),
        TemperatureSensor("T_cabinet", {AMBIENT: 0.5, "column": 0.5}, 0.0, lag_s=300.0),
    ]
    z = {"wheelhead": 0.3}
    if spindle_um:
        z["spindle"] = float(spindle_um) / 1.0
    errors = ThermoelasticMap(
        linear={"E_X": {"column": 0.05, "bed": -0.05},
                "E_Y": {"column": 0.6, "table": -0.5, "bed": -0.1},
                "E_Z": z},
        reference_c=20.0)
    return Machine(ThermalNetwork(NODES, LINKS), sources, sensors, errors)


class ProbeCreep(UndeclaredEffect):
    """The E_X probe mount creeps: a straight ramp to +-creep_um over each run (no sensor sees it)."""

    name, kind = "probe_creep", "drift"
    defaults = {"creep_um": CREEP_UM, "targets": ["E_X"]}

    def modify_errors(self, ctx, errors):
        errors = errors.copy()
        k = ctx.machine.thermoelastic.targets.index("E_X")
        sign = 1.0 if self.rng(ctx).random() < 0.5 else -1.0
        n = errors.shape[0]
        errors[:, k] += sign * float(self.params["creep_um"]) * np.linspace(0.0, 1.0, n)
        return errors


def programme(rng, period_s: float, duration_s: float):
    """Step list (start s, value) of the wheel speed."""
    def grid(t):
        return period_s * round(t / period_s)

    n = [(0.0, 0.0)]
    t = rng.uniform(5.0, 30.0) * 60.0
    while t < duration_s:
        stop = min(t + rng.uniform(20.0, 90.0) * 60.0, duration_s)
        n.append((grid(t), float(rng.integers(15, 31) * 100)))
        n.append((grid(stop), 0.0))
        t = stop + rng.uniform(5.0, 40.0) * 60.0
    return merge(n)


class Stable67(Scenario):
    """14 runs of 8-24 h of the chiller-held hydrostatic grinder (one campaign each)."""

    name = "stable67"
    year = 2027

    def __init__(self, runs=RUNS, spindle_um=0.0, creep_um=CREEP_UM, sample_period_s=60.0,
                 temp_noise_c=0.02, temp_quantum_c=0.01, error_noise_um=0.4,
                 error_quantum_um=0.05, effects=(), effect_params=None, clean=False, seed=0):
        self.runs = runs
        self.spindle_um = spindle_um
        self.creep_um = creep_um
        self.sample_period_s = sample_period_s
        self.error_gaps = "hold"
        super().__init__(temp_noise_c, temp_quantum_c, error_noise_um, error_quantum_um, effects,
                         effect_params, clean, seed)

    def machine(self):
        return machine(self.spindle_um)

    def effects_list(self):
        return [*super().effects_list(), ProbeCreep(int(self.seed), creep_um=float(self.creep_um))]

    def generate(self):
        dataset, truth = super().generate()
        truth["stable67"] = {"spindle_um": float(self.spindle_um), "creep_um": float(self.creep_um)}
        truth["undeclared_effects"] = [e for e in truth["undeclared_effects"]
                                       if e["name"] != ProbeCreep.name]
        return dataset, truth

    def plans(self, rng):
        period = float(self.sample_period_s)
        room = AmbientModel(annual_mean_c=20.0, annual_amplitude_c=0.0, daily_amplitude_c=0.3,
                            daily_peak_hour=14.0, drift_sd_c=0.1, drift_tau_h=12.0)
        plans, day = [], 0
        for k in range(int(self.runs)):
            while (START + timedelta(days=day)).weekday() >= 5:
                day += 1
            start = START + timedelta(days=day)
            day += 1
            run_rng = np.random.default_rng([int(self.seed), k])
            hours = float(run_rng.integers(8, 25))
            duration = hours * 3600.0 - period
            n = held(programme(run_rng, period, duration))
            plans.append(CampaignPlan(
                cid=f"run{k + 1:02d}", split="train",
                start_s=(start - datetime(self.year, 1, 1)).total_seconds(), duration_s=duration,
                rng=run_rng, ambient=room, programme=None, states={N: n}, written=(N,),
                sample_period_s=period, error_period_s=None, cooldown_s=DAY_S / 2,
                notes=f"run {k + 1}, {hours:g} h from {start:%a %Y-%m-%d %H:%M}", manifest={}))
        return plans


__all__ = ["Stable67", "machine"]
