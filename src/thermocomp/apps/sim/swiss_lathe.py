r"""Scenario ``swiss_lathe_door``: a Swiss-type lathe whose door lets cool air in.

After paper 004 (stacked ARX-random forest compensation of a Swiss-type lathe):
12 temperatures (7 external sensors, 5 internal NC temperatures ``T_nc_*``),
X and Y errors between main spindle and tool holder measured every ~5 min,
the door state ``S_door`` and the speeds logged every minute; an 80 h
calibration cycle of varying spindle and driven-tool speeds with door
openings, and a production-like validation run (~60 s part cycles, i.e. a
steady load at the 1-min logging rate) interrupted by door openings and breaks.
The hall is air-conditioned by day (on/off cycling, the noise paper 004 removes
with EMD) and left free at night.

Data layout: one row per minute; the probes measure every 5 min and the
logger repeats the last probe reading in between (``error_gaps='hold'``; set
``sim.generator.error_gaps=nan`` for empty cells, then read with
``data.max_gap_samples=4``).

The machine
-----------
==============  =======  =========================================================
node            C (J/K)  what
==============  =======  =========================================================
frame           3.7e5    ~800 kg cast-iron bed; hA 15 W/K
headstock       2.8e4    moving headstock (Z1), ~60 kg
spindle         5.5e3    main spindle shaft and bearings, ~12 kg
spindle_motor   7.0e3    built-in motor, ~15 kg
guide_bush      9.2e3    guide-bush support, ~20 kg
tool_post       1.15e4   X1/Y1 slide and tool holder with the probes, ~25 kg
tool_motor      3.7e3    driven-tool motor, ~8 kg
tool_holder     1.5e3    holder plate with the tools and the probe brackets, ~3 kg,
                         in the enclosure air (unmeasured: the holder sensors sit on
                         the slide behind it and respond in ~10 min)
workspace_air   1.5e4    enclosure air and sheet-metal guards; 15 W/K through the guards
==============  =======  =========================================================

Inner nodes exchange with ``workspace_air`` (links of 1-5 W/K), not with the
shop: the enclosure runs a few kelvin above the hall (60 W of pumps, conveyor and
lights plus part of the motor losses).
An open door adds
40 W/K between the enclosure air and the shop (the door's air exchange) and
forced convection on the tool post and guide bush (built-in ``door`` effect),
so the tool holder cools by kelvins within minutes and X/Y shift by several µm.
Errors (µm/K): X = 1.6 tool_post + 2.5 tool_holder + 0.9 guide_bush - 0.5
headstock + 0.6 spindle - 0.3 frame; Y = 1.1 tool_post + 1.8 tool_holder +
0.8 headstock - 0.6 guide_bush + 0.4 frame (lengths of 50-200 mm of steel).
"""

from __future__ import annotations

import numpy as np

from thermocomp.apps.sim.ambient import DAY_S, HallClimate
from thermocomp.apps.sim.campaign import Machine, Programme
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.scenario import CampaignPlan, Scenario
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import SPINDLE, ConstantWhileRunning, SpeedLosses, StateConvection
from thermocomp.apps.sim.thermoelastic import ThermoelasticMap
from thermocomp.base.params import POSITIVE, choice, numbers, samples_in, span

SCENARIO = "swiss_lathe_door"
TOOL = "S_tool_rpm"
AXES = "_axes_moving"

NODES = (
    Node("frame", 3.7e5, 15.0), Node("headstock", 2.8e4, 1.0), Node("spindle", 5.5e3, 0.2),
    Node("spindle_motor", 7.0e3, 1.0), Node("guide_bush", 9.2e3, 0.2), Node("tool_post", 1.15e4, 0.2),
    Node("tool_motor", 3.7e3, 0.5), Node("workspace_air", 1.5e4, 15.0), Node("tool_holder", 1.5e3, 0.0),
)
LINKS = (
    Link("headstock", "frame", 8.0), Link("spindle", "headstock", 6.0),
    Link("spindle_motor", "spindle", 4.0), Link("spindle_motor", "headstock", 5.0),
    Link("guide_bush", "frame", 10.0), Link("tool_post", "frame", 10.0), Link("tool_motor", "tool_post", 3.0),
    Link("headstock", "workspace_air", 2.0), Link("spindle", "workspace_air", 1.0),
    Link("guide_bush", "workspace_air", 3.0), Link("tool_post", "workspace_air", 4.0),
    Link("frame", "workspace_air", 5.0), Link("tool_motor", "workspace_air", 1.0),
    Link("tool_holder", "tool_post", 1.0), Link("tool_holder", "workspace_air", 2.0),
)


def heat_sources():
    return [
        SpeedLosses("main_spindle", {"spindle_motor": 0.6, "spindle": 0.3, "workspace_air": 0.1},
                    signal=SPINDLE, idle_W=20.0, linear_W_per_krpm=8.0, quadratic_W_per_krpm2=1.2),
        SpeedLosses("driven_tools", {"tool_motor": 0.6, "tool_post": 0.2, "workspace_air": 0.2},
                    signal=TOOL, idle_W=10.0, linear_W_per_krpm=6.0, quadratic_W_per_krpm2=0.8),
        ConstantWhileRunning("axis_drives", {"tool_post": 0.5, "headstock": 0.5}, power_W=25.0, when=AXES),
        # Coolant and lubrication pumps, chip conveyor, lights: the enclosure stays warm.
        ConstantWhileRunning("auxiliaries", {"workspace_air": 1.0}, power_W=60.0, when=AXES),
    ]


def convection_rules():
    return [StateConvection("spindle", 0.8, exponent=0.6)]


def sensors():
    """Seven external sensors and five NC temperatures (internal, fast, close to the windings)."""
    return [
        TemperatureSensor("T_amb", {AMBIENT: 0.97, "frame": 0.03}, -0.05, lag_s=120.0),
        TemperatureSensor("T_headstock", {"headstock": 0.9, "spindle": 0.1}, 0.04, lag_s=300.0),
        TemperatureSensor("T_guidebush", {"guide_bush": 0.8, "frame": 0.2}, -0.03, lag_s=300.0),
        TemperatureSensor("T_toolholder1", {"tool_post": 0.8, "tool_holder": 0.1, "tool_motor": 0.1}, 0.02,
                          lag_s=600.0),
        TemperatureSensor("T_toolholder2", {"tool_post": 0.7, "frame": 0.3}, 0.06, lag_s=600.0),
        TemperatureSensor("T_frame1", {"frame": 1.0}, -0.02, lag_s=600.0),
        TemperatureSensor("T_frame2", {"frame": 0.85, "guide_bush": 0.15}, 0.05, lag_s=600.0),
        TemperatureSensor("T_nc_spindle_motor", {"spindle_motor": 1.0}, 0.8, lag_s=60.0),
        TemperatureSensor("T_nc_tool_motor", {"tool_motor": 1.0}, -0.6, lag_s=60.0),
        TemperatureSensor("T_nc_x1_drive", {"tool_post": 0.6, "frame": 0.4}, 0.3, lag_s=120.0),
        TemperatureSensor("T_nc_z1_drive", {"headstock": 0.6, "frame": 0.4}, -0.2, lag_s=120.0),
        TemperatureSensor("T_nc_cabinet", {AMBIENT: 0.8, "frame": 0.2}, 1.5, lag_s=300.0),
    ]


def thermoelastic_map():
    return ThermoelasticMap(
        linear={"E_X": {"tool_post": 1.6, "tool_holder": 2.5, "guide_bush": 0.9, "headstock": -0.5,
                        "spindle": 0.6, "frame": -0.3},
                "E_Y": {"tool_post": 1.1, "tool_holder": 1.8, "headstock": 0.8, "guide_bush": -0.6,
                        "frame": 0.4}},
        quadratic={"E_X": {"spindle": 0.02}},
        reference_c=20.0)


def swiss_lathe() -> Machine:
    return Machine(ThermalNetwork(NODES, LINKS), heat_sources(), sensors(), thermoelastic_map(),
                   convection_rules())


SWISS_LATHE_EFFECTS = {
    # Built in: the door exchanges the enclosure air with the hall and blows on tool post and bush.
    "door": {"nodes": {"workspace_air": 60.0, "tool_holder": 6.0, "guide_bush": 1.5}, "air_offset_c": 0.0,
             "rate_per_h": 0.5, "duration_min": [3.0, 15.0], "targets": ["E_X", "E_Y"]},
    # A rotary union / clamping cylinder behind the spindle with its own hydraulic circuit.
    "hidden_source": {"anchor": "spindle", "power_W": 400.0, "capacity_J_per_K": 2.0e4,
                      "conductance_W_per_K": 6.0, "on_min": [30.0, 120.0], "off_min": [30.0, 120.0],
                      "targets": ["E_X"]},
    "lag_node": {"parent": "spindle_motor", "capacity_J_per_K": 8.0e4, "conductance_W_per_K": 8.0,
                 "convection_W_per_K": 0.5, "sensitivity_um_per_K": {"E_X": 4.0}, "targets": ["E_X"]},
    "axis_position": {"axis": "Z", "travel_mm": [0.0, 200.0], "home_mm": 0.0, "dwell_min": [5.0, 30.0],
                      "tilt_nodes": {"headstock": 1.0, "frame": -1.0}, "gain_um_per_K_per_m": 60.0,
                      "targets": ["E_Y"]},
    "sensor_drift": {"column": "T_toolholder1", "rate_K_per_h": 0.1, "onset_fraction": 0.3,
                     "splits": ["test"], "targets": ["E_X", "E_Y"]},
    "ambient_law": {"level_node": "ambient", "level_lag_h": 1.0, "threshold_c": 21.3, "gain": 0.5,
                    "targets": ["E_X", "E_Y"]},
}


class SwissLatheDoor(Scenario):
    """Generator of the ``swiss_lathe_door`` dataset: an 80 h calibration and a production run.

    Parameters
    ----------
    calibration_hours, production_hours : float
        Lengths of the calibration cycle (train) and of the production run (test).
    sample_period_s, error_period_s : float
        Logger period (1 min: temperatures, speeds, door) and probe period (5 min).
    error_gaps : {'hold', 'nan'}
        Probe cells between measurements: last reading repeated, or empty.
    spindle_rpm, tool_rpm : sequence of float
        Speeds of the calibration segments (drawn per segment).
    segment_h : (float, float)
        Range of calibration segment lengths.
    production_rpm : (float, float)
        Mean spindle and driven-tool speeds of the production cycle.
    temp_noise_c, temp_quantum_c, error_noise_um, error_quantum_um : float
    effects, effect_params, clean, seed
        See :class:`~thermocomp.apps.sim.scenario.Scenario`; ``door`` is built in.
    """

    name = SCENARIO
    param_rules = {**Scenario.param_rules, "calibration_hours": POSITIVE, "production_hours": POSITIVE,
                   "sample_period_s": POSITIVE, "error_period_s": POSITIVE,
                   "error_gaps": choice("hold", "nan"), "spindle_rpm": numbers(0.0),
                   "tool_rpm": numbers(0.0), "segment_h": span(open_lo=True),
                   "production_rpm": numbers(0.0, length=2)}

    def param_relations(self) -> list[tuple[str, str]]:
        return samples_in(self, ("calibration_hours", "production_hours"), "sample_period_s")
    builtin_effects = ("door",)

    def __init__(self, calibration_hours=80.0, production_hours=24.0, sample_period_s=60.0,
                 error_period_s=300.0, error_gaps="hold", spindle_rpm=(0, 2000, 4000, 6000, 8000),
                 tool_rpm=(0, 1500, 3000, 4500, 6000), segment_h=(1.0, 4.0), production_rpm=(5000, 3000),
                 temp_noise_c=0.03, temp_quantum_c=0.01, error_noise_um=0.2, error_quantum_um=0.1,
                 effects=(), effect_params=None, clean=False, seed=0):
        self.calibration_hours = calibration_hours
        self.production_hours = production_hours
        self.sample_period_s = sample_period_s
        self.error_period_s = error_period_s
        self.error_gaps = error_gaps
        self.spindle_rpm = spindle_rpm
        self.tool_rpm = tool_rpm
        self.segment_h = segment_h
        self.production_rpm = production_rpm
        super().__init__(temp_noise_c, temp_quantum_c, error_noise_um, error_quantum_um, effects,
                         effect_params, clean, seed)

    def machine(self):
        return swiss_lathe()

    def effect_defaults(self):
        return SWISS_LATHE_EFFECTS

    def _grid(self, t):
        return self.error_period_s * max(1, round(t / self.error_period_s))

    def _climate(self, start_s):
        return HallClimate(setpoints=((start_s - 5 * DAY_S, 22.0),), hvac_hours=(6.0, 20.0), free_c=20.5,
                           daily_amplitude_c=0.8, daily_peak_hour=15.0, cycling_amplitude_c=0.25,
                           cycling_period_min=24.0, room_tau_h=0.7, drift_sd_c=0.15)

    def _calibration(self, rng, duration_s):
        """Segments of random spindle / driven-tool speeds (ZOH on the probe grid)."""
        lo, hi = (3600.0 * float(h) for h in self.segment_h)
        spindle, tool, t = [], [], 0.0
        while t < duration_s:
            spindle.append((t, float(rng.choice(self.spindle_rpm))))
            tool.append((t, float(rng.choice(self.tool_rpm))))
            t += self._grid(rng.uniform(lo, hi))
        return Programme(tuple(spindle)), Programme(tuple(tool))

    def _production(self, rng, duration_s):
        """Steady part cycles, a lunch break and an evening stop (1-min logging averages the cycle)."""
        n, tool = (float(v) for v in self.production_rpm)
        stops = sorted(self._grid(duration_s * f) for f in (rng.uniform(0.2, 0.3), rng.uniform(0.55, 0.65)))
        spindle = [(0.0, n)]
        tools = [(0.0, tool)]
        for stop in stops:
            length = self._grid(3600.0 * rng.uniform(0.75, 1.5))
            spindle += [(stop, 0.0), (stop + length, n)]
            tools += [(stop, 0.0), (stop + length, tool)]
        return Programme(tuple(spindle)), Programme(tuple(tools))

    def plans(self, rng):
        calibration, production = rng.spawn(2)
        plans = []
        for cid, split, child, day, hours, kind in (
                ("calibration", "train", calibration, 65, self.calibration_hours, "calibration cycle"),
                ("production", "test", production, 79, self.production_hours, "production run")):
            start = DAY_S * day + 7 * 3600.0
            duration = self._grid(3600.0 * float(hours))
            spindle, tool = (self._calibration if split == "train" else self._production)(child, duration)
            plans.append(CampaignPlan(
                cid=cid, split=split, start_s=start, duration_s=duration, rng=child,
                ambient=self._climate(start),
                programme=spindle, states={TOOL: tool.rpm_at, AXES: np.ones_like},
                written=(SPINDLE, TOOL), sample_period_s=float(self.sample_period_s),
                error_period_s=float(self.error_period_s), cooldown_s=2 * DAY_S,
                notes=f"{kind}, {hours:g} h", manifest={"duration_h": float(hours)},
                truth={"spindle_programme": [list(map(float, s)) for s in spindle.steps],
                       "tool_programme": [list(map(float, s)) for s in tool.steps]}))
        return plans


__all__ = ["SwissLatheDoor", "swiss_lathe"]
