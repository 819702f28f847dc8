r"""``trunnion63``: a 5-axis trunnion mill nobody tuned on (stranger63), as an own machine class.

Built through the documented path for a machine of one's own nodes (docs/simulation.md, "Your
own machine"): a :class:`~thermocomp.apps.sim.scenario.Scenario` subclass on ``PYTHONPATH``, a
yaml ``benchmarks/conf63/sim/trunnion63.yaml``, and

    THERMOCOMP_TARGETS=trunnion63. PYTHONPATH=src:benchmarks .venv/bin/python -m thermocomp \
        simulate "hydra.searchpath=[file://$PWD/benchmarks/conf63]" sim=trunnion63 seed=6301

Written down and committed before any model ran on it; seeds 6301 and 6302 fixed beforehand.

The machine
-----------
A vertical 5-axis mill with a trunnion (A cradle) carrying a rotary table (C), both turned by
torque motors; a 15,000 rpm motor spindle whose cartridge is cooled by a coolant jacket held by
a CHILLER (a proportional controller, cooling only: it removes ``gain (T_coolant - setpoint)``
W, at most ``max_W``, and nothing when the coolant is below its absolute setpoint, so a cold
Monday morning runs uncooled); the enclosure air is measured by no sensor.

============  =======  =====  ==========================================================
node          C (J/K)  hA     what
============  =======  =====  ==========================================================
spindle_motor 1.5e4    2      the motor spindle's stator and rotor
spindle       8e3      0.5    the cartridge and bearings
coolant       3e4      1      the jacket's coolant loop
headstock     1.2e5    3      the Z slide (ram) carrying the spindle
column        6e5      10     the column
bed           2.5e6    25     the bed
trunnion      2e5      5      the A cradle
rotary_table  6e4      2      the C table the master ball stands on
torque_motors 1.5e4    1      the A and C torque motors
enclosure     2e4      20     the enclosure air and guards (no sensor)
============  =======  =====  ==========================================================

Links (W/K): spindle_motor-spindle 5, spindle-coolant 15, spindle_motor-coolant 10,
spindle-headstock 6, headstock-column 8, column-bed 15, trunnion-bed 10, torque_motors-trunnion
6, torque_motors-rotary_table 4, rotary_table-trunnion 8; to the enclosure: headstock 3,
trunnion 3, rotary_table 2, spindle 1.
Heat (W): the spindle 40 + 10 n + 1.0 n^2 (n in krpm; 0.6 motor, 0.4 cartridge) while it turns;
while the machine is powered (weekdays 6-22 h): axis drives 60 (headstock / column halves),
torque motors 80, auxiliaries 80 into the enclosure, the chiller -clip(150 (T_coolant - 21.0),
0, 800) on the coolant.  Errors at the master ball on the C table (µm/K of the node rises; a
quadratic -0.05 µm/K^2 of the cartridge on Z):

    E_X =  1.2 column - 0.8 bed + 2.0 trunnion - 1.5 rotary_table + 0.5 headstock
    E_Y =  2.5 headstock - 1.2 column + 1.8 trunnion + 0.8 rotary_table
    E_Z = -8.0 spindle - 2.0 spindle_motor - 4.0 headstock + 5.5 column - 2.5 trunnion - 1.0 bed

Sensors (Pt100, 0.03 K noise, 0.01 K steps; lags in s): T_spindle_front (0.8 spindle + 0.2
headstock, 120), T_spindle_motor (60), T_coolant_return (60), T_ram (0.8 headstock + 0.2 column,
300), T_column (0.85 column + 0.15 headstock, 600), T_bed (600), T_trunnion (0.8 trunnion + 0.2
torque motors, 300), T_table (0.7 rotary table + 0.3 trunnion, 300), T_amb (0.97 air + 0.03 bed,
120); the spindle's speed ``S_spindle_rpm`` logged.

The programme and the hall
--------------------------
Three weeks from Monday 2026-11-02 00:00, one campaign a week (``W1``, ``W2`` train, ``W3``
test), logged every 60 s; the machine shut down from Friday 22:00 to Monday 6:00 (a weekend:
each week starts cold, the twin's 2-day rest).  Weekdays 6-22 h: jobs of 0.5-2 h at one speed
(3000 / 6000 / 9000 / 12000 / 15000 rpm), cutting 5-25 min, parted by 1-6 min part changes (the
spindle stopped), 5-20 min of set-up between jobs.  The hall: heated to 20 °C from 5 to 22 h,
17.5 °C free at night (± 1.0 K a day, peak 15 h), the heating's 0.2 K on/off cycling, a
0.2 K drift; and a HALL DOOR a worker opens on weekdays 6-22 h (4 a day on average, 5-25 min
open): the air at the machine falls by 2.5-4.5 K towards the November outside (6 min in, 20 min
back after it closes); the door's state is logged nowhere.  The probe: a master-ball cycle every
10 min (``error_period_s=600``, empty cells between, 0.2 µm noise, 0.1 µm steps).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from datetime import datetime

import numpy as np
from scenario_tail import merge, weekday_shift

from thermocomp.apps.sim.ambient import DAY_S, HallClimate
from thermocomp.apps.sim.campaign import Machine, Programme
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.scenario import CampaignPlan, DeclaredScenario
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import SPINDLE, ConstantWhileRunning, HeatSource, SpeedLosses
from thermocomp.apps.sim.thermoelastic import ThermoelasticMap

POWERED = "_powered"                # weekdays 6-22 h (not written)
START = datetime(2026, 11, 2)       # a Monday
SHIFT_H = (6.0, 22.0)

NODES = (Node("spindle_motor", 1.5e4, 2.0), Node("spindle", 8e3, 0.5), Node("coolant", 3e4, 1.0),
         Node("headstock", 1.2e5, 3.0), Node("column", 6e5, 10.0), Node("bed", 2.5e6, 25.0),
         Node("trunnion", 2e5, 5.0), Node("rotary_table", 6e4, 2.0),
         Node("torque_motors", 1.5e4, 1.0), Node("enclosure", 2e4, 20.0))
LINKS = (Link("spindle_motor", "spindle", 5.0), Link("spindle", "coolant", 15.0),
         Link("spindle_motor", "coolant", 10.0), Link("spindle", "headstock", 6.0),
         Link("headstock", "column", 8.0), Link("column", "bed", 15.0), Link("trunnion", "bed", 10.0),
         Link("torque_motors", "trunnion", 6.0), Link("torque_motors", "rotary_table", 4.0),
         Link("rotary_table", "trunnion", 8.0), Link("headstock", "enclosure", 3.0),
         Link("trunnion", "enclosure", 3.0), Link("rotary_table", "enclosure", 2.0),
         Link("spindle", "enclosure", 1.0))


@dataclass
class Chiller(HeatSource):
    """The coolant jacket's chiller: removes ``gain (T - setpoint)`` W (at most ``max_W``) from
    ``node`` while ``when`` is on; nothing below the setpoint (it only cools)."""

    node: str = "coolant"
    gain_W_per_K: float = 150.0
    setpoint_c: float = 21.0
    max_W: float = 800.0
    when: str = POWERED
    depends_on_temperature = True

    def power(self, state, temperature_of):
        if state.get(self.when, 0.0) == 0.0:
            return 0.0
        excess = temperature_of(self.node) - self.setpoint_c
        return -float(np.clip(self.gain_W_per_K * excess, 0.0, self.max_W))


def machine() -> Machine:
    sources = [
        SpeedLosses("spindle", {"spindle_motor": 0.6, "spindle": 0.4}, signal=SPINDLE, idle_W=40.0,
                    linear_W_per_krpm=10.0, quadratic_W_per_krpm2=1.0),
        ConstantWhileRunning("axis_drives", {"headstock": 0.5, "column": 0.5}, power_W=60.0,
                             when=POWERED),
        ConstantWhileRunning("torque_motors", {"torque_motors": 1.0}, power_W=80.0, when=POWERED),
        ConstantWhileRunning("auxiliaries", {"enclosure": 1.0}, power_W=80.0, when=POWERED),
        Chiller("chiller", {"coolant": 1.0}),
    ]
    sensors = [
        TemperatureSensor("T_spindle_front", {"spindle": 0.8, "headstock": 0.2}, 0.0, lag_s=120.0),
        TemperatureSensor("T_spindle_motor", {"spindle_motor": 1.0}, 0.0, lag_s=60.0),
        TemperatureSensor("T_coolant_return", {"coolant": 1.0}, 0.0, lag_s=60.0),
        TemperatureSensor("T_ram", {"headstock": 0.8, "column": 0.2}, 0.0, lag_s=300.0),
        TemperatureSensor("T_column", {"column": 0.85, "headstock": 0.15}, 0.0, lag_s=600.0),
        TemperatureSensor("T_bed", {"bed": 1.0}, 0.0, lag_s=600.0),
        TemperatureSensor("T_trunnion", {"trunnion": 0.8, "torque_motors": 0.2}, 0.0, lag_s=300.0),
        TemperatureSensor("T_table", {"rotary_table": 0.7, "trunnion": 0.3}, 0.0, lag_s=300.0),
        TemperatureSensor("T_amb", {AMBIENT: 0.97, "bed": 0.03}, 0.0, lag_s=120.0),
    ]
    errors = ThermoelasticMap(
        linear={"E_X": {"column": 1.2, "bed": -0.8, "trunnion": 2.0, "rotary_table": -1.5,
                        "headstock": 0.5},
                "E_Y": {"headstock": 2.5, "column": -1.2, "trunnion": 1.8, "rotary_table": 0.8},
                "E_Z": {"spindle": -8.0, "spindle_motor": -2.0, "headstock": -4.0, "column": 5.5,
                        "trunnion": -2.5, "bed": -1.0}},
        quadratic={"E_Z": {"spindle": -0.05}}, reference_c=20.0)
    return Machine(ThermalNetwork(NODES, LINKS), sources, sensors, errors)


def on_shift(t_rel) -> np.ndarray:
    """Campaign time -> 1 on weekdays 6-22 h (every campaign starts on a Monday 00:00)."""
    return weekday_shift(t_rel, SHIFT_H)


@dataclass(frozen=True)
class HallWithDoor:
    """A :class:`HallClimate` plus the hall door's cold dips: ``openings`` ((start s, end s,
    depth K), ...) in absolute time; the air falls with ``tau_in_s``, recovers with ``tau_out_s``."""

    climate: HallClimate
    openings: tuple = ()
    tau_in_s: float = 360.0
    tau_out_s: float = 1200.0
    extra: dict = field(default_factory=dict)

    def dip(self, t_s) -> np.ndarray:
        t = np.asarray(t_s, float)
        out = np.zeros_like(t)
        for a, b, depth in self.openings:
            inside = (t >= a) & (t < b)
            out[inside] -= depth * (1 - np.exp(-(t[inside] - a) / self.tau_in_s))
            after = t >= b
            out[after] -= (depth * (1 - np.exp(-(b - a) / self.tau_in_s))
                           * np.exp(-(t[after] - b) / self.tau_out_s))
        return out

    def sample(self, t_s, rng) -> np.ndarray:
        return self.climate.sample(t_s, rng) + self.dip(t_s)

    def to_dict(self) -> dict:
        return {"climate": self.climate.to_dict(),
                "door_openings": [list(map(float, o)) for o in self.openings]}


def door_openings(rng, start_s: float, days: int = 5, per_day: float = 4.0) -> tuple:
    out = []
    for day in range(days):
        t = start_s + day * DAY_S + SHIFT_H[0] * 3600 + rng.exponential(DAY_S * 16 / 24 / per_day)
        while t < start_s + day * DAY_S + SHIFT_H[1] * 3600:
            out.append((t, t + rng.uniform(5, 25) * 60, rng.uniform(2.5, 4.5)))
            t += rng.exponential(DAY_S * 16 / 24 / per_day)
    return tuple(out)


def programme(rng, period_s: float) -> Programme:
    """One week's spindle speeds (weekdays 6-22 h), on the logger's grid."""
    def grid(t):
        return period_s * round(t / period_s)

    steps = [(0.0, 0.0)]
    for day in range(5):
        t, end = (day * DAY_S + h * 3600 for h in SHIFT_H)
        while t < end:
            job_end = min(end, t + rng.uniform(0.5, 2.0) * 3600)
            rpm = float(rng.choice([3000, 6000, 9000, 12000, 15000]))
            while t < job_end:
                cut = min(job_end, t + rng.uniform(5, 25) * 60)
                steps += [(grid(t), rpm), (grid(cut), 0.0)]
                t = cut + rng.uniform(1, 6) * 60
            t += rng.uniform(5, 20) * 60
    return Programme(tuple(merge(steps)))    # rounding may merge two steps: keep the later


@dataclass(eq=False, repr=False, kw_only=True)
class Trunnion63(DeclaredScenario):
    """Three weekly records of the trunnion mill (``W1``, ``W2`` train, ``W3`` test)."""

    name = "trunnion63"
    year = 2026

    weeks: int = 3
    sample_period_s: float = 60.0
    error_period_s: float = 600.0
    error_gaps: str = "nan"

    def machine(self):
        return machine()

    def plans(self, rng):
        first = (START - datetime(self.year, 1, 1)).total_seconds()
        plans = []
        for w, child in enumerate(rng.spawn(int(self.weeks))):
            start = first + w * 7 * DAY_S
            openings = door_openings(child, start)
            climate = HallClimate(setpoints=((0.0, 20.0),), hvac_hours=(5.0, 22.0), free_c=17.5,
                                  daily_amplitude_c=1.0, daily_peak_hour=15.0,
                                  cycling_amplitude_c=0.2, cycling_period_min=25.0,
                                  room_tau_h=1.0, drift_sd_c=0.2)
            spindle = programme(child, float(self.sample_period_s))
            plans.append(CampaignPlan(
                cid=f"W{w + 1}", split="test" if w == int(self.weeks) - 1 else "train",
                start_s=start, duration_s=7 * DAY_S - float(self.sample_period_s), rng=child,
                ambient=HallWithDoor(climate, openings), programme=spindle,
                states={POWERED: on_shift}, written=(SPINDLE,),
                sample_period_s=float(self.sample_period_s),
                error_period_s=float(self.error_period_s), cooldown_s=2 * DAY_S,
                notes=f"week {w + 1}", manifest={},
                truth={"door_openings": [list(map(float, o)) for o in openings]}))
        return plans


__all__ = ["Trunnion63", "machine"]
