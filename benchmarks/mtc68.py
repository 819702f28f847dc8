r"""``mtc68``: a turn-mill centre with a B-axis milling head, nobody tuned on (stranger68).

Built through the documented own-machine route (docs/simulation.md, "Your own machine"): this
:class:`~thermocomp.apps.sim.scenario.Scenario` subclass on ``PYTHONPATH`` and the yaml
``benchmarks/conf68/sim/mtc68.yaml``::

    THERMOCOMP_TARGETS=mtc68. PYTHONPATH=src:benchmarks .venv/bin/python -m thermocomp \
        simulate "hydra.searchpath=[file://$PWD/benchmarks/conf68]" sim=mtc68 seed=6851

Written down and committed before any model ran on it; seeds 6851 and 6852 fixed beforehand
(6851: the lab's eight test runs, one workbook, one sheet per run; 6852: the same machine,
another eight runs, one workbook per run).  The lab's exports are written by
``benchmarks/bench_stranger68.py write``.

The machine
-----------
A multitasking turn-mill centre: the MAIN spindle in a fixed headstock on the slant bed turns
the part; a COLUMN travels in Z on the bed and carries, on its X/Y slides, the B-AXIS HEAD, a
swivelling milling head whose built-in TOOL spindle (max 12000 rpm) mills, drills and, locked,
holds the turning tools.  The head swivels the tool's axis from radial (B = 0°, along X) to
axial (B = 90°, along Z).  The coolant (a 300 l tank) takes the cutting heat and runs over the
bed.  The hall: 20.5 °C +- 1.5 K a day (peak 15 h), a weather drift of 0.5 K (12 h).

=============  =======  =====  ========================================================
node           C (J/K)  hA     what
=============  =======  =====  ========================================================
bed            3e6      25     the slant bed
head           3e5      6      the main headstock housing
main_bearing   4e4      2      the main spindle's front bearings
column         6e5      8      the travelling column with its X/Y slides
bhead          8e4      4      the B-axis head's housing (its torque motor, the clamp)
tool_spindle   2e4      2      the tool spindle's shaft, motor and bearings
coolant        4e5      8      the coolant in the tank and on the bed
=============  =======  =====  ========================================================

Links (W/K): bed-head 15, head-main_bearing 5, bed-column 10, column-bhead 6,
bhead-tool_spindle 4, coolant-bed 30, coolant-bhead 3.
Heat (W): the main spindle ``S_n_main_rpm`` (turning jobs, 800-4000 rpm): 40 + 40 n + 8 n^2
(n in krpm), half into its bearings, half into the headstock; the tool spindle ``S_n_tool_rpm``
(milling jobs, 2000-12000 rpm): 15 + 8 n + 0.5 n^2, 0.7 into the spindle, 0.3 into the head;
the column's drives 60 and the cut 400 into the coolant while either spindle turns.

Errors at the tool against the part (µm/K of the node rises from the run's first sample; the
lab's capacitive probes at a test bar clamped in the main spindle, read every sample)::

    E_X = 3.0 head + 1.0 main_bearing - 2.0 column + 0.5 bed + 1.0 bhead
    E_Y = 1.5 column - 1.2 bhead + 0.3 bed
    E_Z = 7.0 main_bearing + 3.5 head - 2.5 column - 1.5 bed - 1.0 bhead

PLANTED (the effect the default model lacks): the tool spindle's own axial growth (its shaft,
0.25 m from the front bearing to the gauge line: 11.5 µm/(m K) x 0.25 m, toward the part)
reaches the part along the tool's axis, which the B angle (logged, ``S_B_deg``) turns::

    E_X += -2.9 cos(B) rise(tool_spindle),   E_Z += -2.9 sin(B) rise(tool_spindle)   (µm)

A linear map of the temperatures and of ``S_B_deg`` cannot carry a product; diagnose should
find ``S_B_deg`` x a rise (the B head's sensor or the inputs') on E_X or on E_Z.

Sensors (Pt100, 0.03 K noise, 0.01 K steps; lags in s): T_amb (the air, 120), T_bed (900),
T_headstock (0.7 head + 0.3 main_bearing, 300), T_spindle_front (main_bearing, 120),
T_column (600), T_bhead (0.6 bhead + 0.4 tool_spindle, 120), T_coolant (60).  The main and
tool speeds and the B angle are logged (``S_n_main_rpm``, ``S_n_tool_rpm``, ``S_B_deg``).
The probes: 0.2 µm noise, 0.1 µm steps.

The programme
-------------
Eight runs of 24 h at 60 s, from 06:00 on Monday 2027-06-14, Wednesday, Friday, the next
Monday, Wednesday, Friday, the Monday and Wednesday after (each after a 2-day rest: the
simulator soaks the machine, independent runs, each its own clock).  Jobs from 06:00 to 22:00,
idle through the night: each job 20-120 min; with p 0.5 a turning job (the main spindle at
800-4000 rpm, steps of 100; the B head locked at B = 0°), else a milling job (the tool spindle
at 2000-12000 rpm, steps of 500, B drawn from {0°, 45°, 90°}); a pause of 5-30 min between
jobs, the head staying at the B of the last job (it swivels at the next job's start).  The
last run(s) are held out by ``data.test_fraction``.
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime

import numpy as np
from scenario_tail import DayRunsScenario, TurnedGrowth, day_runs, either, merge, working

from thermocomp.apps.sim.ambient import DAY_S, AmbientModel
from thermocomp.apps.sim.campaign import Machine
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import ConstantWhileRunning, SpeedLosses

N_MAIN, N_TOOL, B = "S_n_main_rpm", "S_n_tool_rpm", "S_B_deg"
CUTTING = "_cutting"                     # not written: either spindle turns
START = datetime(2027, 6, 14, 6)         # a Monday, 06:00
RUN_DAYS = (0, 2, 4, 7, 9, 11, 14, 16)   # the runs' first days from START
TOOL_UM_PER_K = -2.9                     # the planted axial growth of the tool spindle

NODES = (Node("bed", 3e6, 25.0), Node("head", 3e5, 6.0), Node("main_bearing", 4e4, 2.0),
         Node("column", 6e5, 8.0), Node("bhead", 8e4, 4.0), Node("tool_spindle", 2e4, 2.0),
         Node("coolant", 4e5, 8.0))
LINKS = (Link("bed", "head", 15.0), Link("head", "main_bearing", 5.0),
         Link("bed", "column", 10.0), Link("column", "bhead", 6.0),
         Link("bhead", "tool_spindle", 4.0), Link("coolant", "bed", 30.0),
         Link("coolant", "bhead", 3.0))
ERRORS = {
    "E_X": {"head": 3.0, "main_bearing": 1.0, "column": -2.0, "bed": 0.5, "bhead": 1.0},
    "E_Y": {"column": 1.5, "bhead": -1.2, "bed": 0.3},
    "E_Z": {"main_bearing": 7.0, "head": 3.5, "column": -2.5, "bed": -1.5, "bhead": -1.0},
}


def machine() -> Machine:
    from thermocomp.apps.sim.thermoelastic import ThermoelasticMap

    sources = [
        SpeedLosses("main_spindle", {"main_bearing": 0.5, "head": 0.5}, signal=N_MAIN,
                    idle_W=40.0, linear_W_per_krpm=40.0, quadratic_W_per_krpm2=8.0),
        SpeedLosses("tool_spindle", {"tool_spindle": 0.7, "bhead": 0.3}, signal=N_TOOL,
                    idle_W=15.0, linear_W_per_krpm=8.0, quadratic_W_per_krpm2=0.5),
        ConstantWhileRunning("column_drives", {"column": 1.0}, power_W=60.0, when=CUTTING),
        ConstantWhileRunning("cut", {"coolant": 1.0}, power_W=400.0, when=CUTTING),
    ]
    sensors = [
        TemperatureSensor("T_amb", {AMBIENT: 1.0}, 0.0, lag_s=120.0),
        TemperatureSensor("T_bed", {"bed": 1.0}, 0.0, lag_s=900.0),
        TemperatureSensor("T_headstock", {"head": 0.7, "main_bearing": 0.3}, 0.0, lag_s=300.0),
        TemperatureSensor("T_spindle_front", {"main_bearing": 1.0}, 0.0, lag_s=120.0),
        TemperatureSensor("T_column", {"column": 1.0}, 0.0, lag_s=600.0),
        TemperatureSensor("T_bhead", {"bhead": 0.6, "tool_spindle": 0.4}, 0.0, lag_s=120.0),
        TemperatureSensor("T_coolant", {"coolant": 1.0}, 0.0, lag_s=60.0),
    ]
    return Machine(ThermalNetwork(NODES, LINKS), sources, sensors,
                   ThermoelasticMap(linear=ERRORS, reference_c=20.0))


class ToolAxis(TurnedGrowth):
    """The tool spindle's axial growth along the tool's axis, turned by B (S_B_deg is logged)."""

    name, state, node, along_cos, along_sin = "tool_axis", B, "tool_spindle", "E_X", "E_Z"
    defaults = {"gain": TOOL_UM_PER_K, "targets": ["E_X", "E_Z"]}


def programme(rng, period_s: float, duration_s: float):
    """Step lists (start s, value) of the main speed, the tool speed and B."""
    def grid(t):
        return period_s * round(t / period_s)

    n_main, n_tool, b = [(0.0, 0.0)], [(0.0, 0.0)], [(0.0, 0.0)]
    t = 0.0
    while t < duration_s:
        if not working(t):
            t = grid(t + period_s)
            continue
        stop = min(t + rng.uniform(20.0, 120.0) * 60.0, np.floor(t / DAY_S) * DAY_S + 16 * 3600.0)
        if rng.random() < 0.5:                       # turning: the head locked at B = 0
            n_main.append((grid(t), float(rng.integers(8, 41) * 100)))
            b.append((grid(t), 0.0))
        else:                                        # milling at a drawn B
            n_tool.append((grid(t), float(rng.integers(4, 25) * 500)))
            b.append((grid(t), float(rng.choice([0.0, 45.0, 90.0]))))
        n_main.append((grid(stop), 0.0))
        n_tool.append((grid(stop), 0.0))
        t = stop + rng.uniform(5.0, 30.0) * 60.0
    return merge(n_main), merge(n_tool), merge(b)


@dataclass(eq=False, repr=False, kw_only=True)
class Mtc68(DayRunsScenario):
    """Eight 24 h runs of the turn-mill centre (one campaign each)."""

    name = "mtc68"
    year = 2027
    planted = ToolAxis

    def machine(self):
        return machine()

    def planted_truth(self):
        return {"um_per_K": TOOL_UM_PER_K, "angle": B, "node": "tool_spindle",
                "E_X": "cos(B)", "E_Z": "sin(B)"}

    def plans(self, rng):
        hall = AmbientModel(annual_mean_c=20.5, annual_amplitude_c=0.0, daily_amplitude_c=1.5,
                            daily_peak_hour=15.0, drift_sd_c=0.5, drift_tau_h=12.0)
        return day_runs(self, START, RUN_DAYS, hall, programme, (N_MAIN, N_TOOL, B),
                        lambda s: {CUTTING: either(s[N_MAIN], s[N_TOOL])})


__all__ = ["Mtc68", "machine"]
