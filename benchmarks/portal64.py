r"""``portal64``: a double-column portal (bridge) mill nobody tuned on (stranger64).

Built through the documented own-machine route (docs/simulation.md, "Your own machine"): this
:class:`~thermocomp.apps.sim.scenario.Scenario` subclass on ``PYTHONPATH`` and the yaml
``benchmarks/conf64/sim/portal64.yaml``::

    THERMOCOMP_TARGETS=portal64. PYTHONPATH=src:benchmarks .venv/bin/python -m thermocomp \
        simulate "hydra.searchpath=[file://$PWD/benchmarks/conf64]" sim=portal64 seed=6401

Written down and committed before any model ran on it; seeds 6401 and 6402 fixed beforehand
(6401: three weekly campaigns; 6402: ``one_record=true``, the same three weeks as one record).
The lab's exports of both are written by ``benchmarks/bench_stranger64.py write``.

The machine
-----------
A double-column portal mill: the table and the bed run in X under a bridge of two columns and
a cross-rail along Y; the saddle runs along the rail and carries a long Z ram with the motor
spindle at its end.  It stands in an UNCLIMATISED hall: skylights put the afternoon sun on
the right column's outer face (``col_R_skin``, seen by no sensor; the right column's sensor
sits on its shaded inner face), the hall air follows the weather, and the hall heating
switches on at 05:00 on weekdays.

=============  =======  =====  ========================================================
node           C (J/K)  hA     what
=============  =======  =====  ========================================================
bed            6e6      40     bed and table
col_L          1.2e6    12     the left column
col_R          1.2e6    12     the right column (its core and shaded inner face)
col_R_skin     1.5e5    8      the right column's sunlit outer face (no sensor)
crossrail      8e5      10     the cross-rail (Y guideways)
rail_drives    2e4      2      the Y drives' motors and gearboxes on the rail
saddle         2e5      4      the saddle (Y carriage and ram housing)
ram            1.5e5    3      the Z ram
spindle        1.5e4    1      the spindle cartridge and bearings
spindle_motor  1.5e4    1.5    the motor spindle's stator and rotor
=============  =======  =====  ========================================================

Links (W/K): bed-col_L 20, bed-col_R 20, col_L-crossrail 10, col_R-crossrail 10,
col_R_skin-col_R 30, rail_drives-crossrail 8, crossrail-saddle 6, saddle-ram 8, ram-spindle 6,
spindle-spindle_motor 5.
Heat (W): the spindle 50 + 12 n + 0.8 n^2 (n in krpm; 0.6 motor, 0.4 cartridge) while it
turns; while powered (weekdays 6-22 h) the Y drives 120 on the rail drives, 80 more while the
spindle cuts, the Z drive and the ram's hydraulic balancing 50 on the saddle; the sun
700 x s(t) on ``col_R_skin``, s(t) in [0, 1]: the afternoon through the skylights,
sin(pi (h - 12) / 6) between 12 and 18 h, times the day's cloud factor (clear 0.85-1.0 with
p 0.4, broken 0.3-0.7 with p 0.3, each 10 min block x U(0.2, 1), overcast 0.03-0.12), held
in 10-min blocks in steps of 0.05.  The sun also warms the hall air: + 1.2 s(t) K.
Errors at the tool (µm/K of the node rises; ``p``: the ram's extension in m, the logged
``S_pos_Z`` / 1000, 0 retracted)::

    E_X =  4.0 col_R_skin - 2.5 col_R + 1.5 col_L + 1.0 saddle - 0.8 bed
    E_Y =  3.5 crossrail + 2.0 rail_drives + 1.5 saddle - 1.0 bed
           + 9.0 (ram - saddle) p                        (the ram bends, its lever p)
    E_Z =  2.5 col_L + 2.5 col_R + 1.5 col_R_skin - 1.5 crossrail - 3.0 ram - 2.0 bed
           - 6.0 spindle - 2.0 spindle_motor - 0.04 spindle^2
           - 11.7 ram p                                  (the extended ram's own growth)

Sensors (Pt100, 0.03 K noise, 0.01 K steps; lags in s): T_col_L (600), T_col_R (0.9 col_R + 0.1
col_R_skin, 600), T_rail (0.9 crossrail + 0.1 rail_drives, 600), T_rail_drive (120), T_saddle
(300), T_ram (0.7 ram + 0.3 saddle, 300), T_spindle (0.8 spindle + 0.2 ram, 120), T_motor (60),
T_bed (900), T_hall (the air, 120); the spindle speed and the ram's extension ``S_pos_Z`` logged.

The programme and the hall
--------------------------
From Monday 2027-03-01 00:00, three weeks logged every 60 s; the machine powered weekdays 6-22
h and off at the weekend; jobs of 0.5-2 h at one speed (1000 / 2000 / 3000 / 4500 / 6000 rpm),
cutting 5-30 min, 1-6 min between cuts, 5-20 min set-up between jobs; within a job the ram
works at one extension (100-800 mm, 10 mm steps), retracted (0) between jobs and when off.
The hall (March): 9.5 °C free at night (outside ± 2.5 K a day, peak 15 h, a 1.2 K weather
drift of 36 h), the heating on weekdays 05:00-20:00 towards 18 °C (the room's lag 2 h),
its 0.3 K on/off cycling.  The probe: a touch cycle every 5 min (``error_period_s=300``,
empty cells between; 0.3 µm noise, 0.1 µm steps), zeroed at each campaign's start.
``one_record=true``: the three weeks as ONE campaign (the lab's long record, cut by
``data.test_fraction``); otherwise one campaign a week (``W1``, ``W2`` train, ``W3`` test),
each after a 2-day rest (the weekend).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from datetime import datetime

import numpy as np
from scenario_tail import LoggedStateEffect, PlantedScenario, merge, weekday_shift

from thermocomp.apps.sim.ambient import DAY_S, AmbientModel, room_response
from thermocomp.apps.sim.campaign import Machine, Programme
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.scenario import CampaignPlan
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import SPINDLE, ConstantWhileRunning, HeatSource, SpeedLosses
from thermocomp.apps.sim.thermoelastic import ThermoelasticMap

POWERED = "_powered"                 # weekdays 6-22 h (not written)
SUN = "_sun"                         # the skylights' sun on the right column, 0..1 (not written)
RAM = "S_pos_Z"                      # the ram's extension (mm), written
START = datetime(2027, 3, 1)         # a Monday
SHIFT_H = (6.0, 22.0)
HEATING_H = (5.0, 20.0)
SUN_PEAK_W = 700.0
SUN_AIR_K = 1.2
SUN_BLOCK_S = 600.0

NODES = (Node("bed", 6e6, 40.0), Node("col_L", 1.2e6, 12.0), Node("col_R", 1.2e6, 12.0),
         Node("col_R_skin", 1.5e5, 8.0), Node("crossrail", 8e5, 10.0),
         Node("rail_drives", 2e4, 2.0), Node("saddle", 2e5, 4.0), Node("ram", 1.5e5, 3.0),
         Node("spindle", 1.5e4, 1.0), Node("spindle_motor", 1.5e4, 1.5))
LINKS = (Link("bed", "col_L", 20.0), Link("bed", "col_R", 20.0), Link("col_L", "crossrail", 10.0),
         Link("col_R", "crossrail", 10.0), Link("col_R_skin", "col_R", 30.0),
         Link("rail_drives", "crossrail", 8.0), Link("crossrail", "saddle", 6.0),
         Link("saddle", "ram", 8.0), Link("ram", "spindle", 6.0),
         Link("spindle", "spindle_motor", 5.0))
# the ram's extension as a lever: target -> (gain µm/(K m), {node: weight of its rise})
RAM_LEVER = {"E_Y": (9.0, {"ram": 1.0, "saddle": -1.0}), "E_Z": (-11.7, {"ram": 1.0})}


@dataclass
class Sun(HeatSource):
    """``peak_W`` times the state ``signal`` (the skylights' sun, 0..1) on its node."""

    peak_W: float = SUN_PEAK_W
    signal: str = SUN

    def power(self, state, temperature_of):
        return self.peak_W * state.get(self.signal, 0.0)


def machine() -> Machine:
    sources = [
        SpeedLosses("spindle", {"spindle_motor": 0.6, "spindle": 0.4}, signal=SPINDLE, idle_W=50.0,
                    linear_W_per_krpm=12.0, quadratic_W_per_krpm2=0.8),
        ConstantWhileRunning("y_drives", {"rail_drives": 1.0}, power_W=120.0, when=POWERED),
        ConstantWhileRunning("y_drives_cutting", {"rail_drives": 1.0}, power_W=80.0, when=SPINDLE),
        ConstantWhileRunning("z_drive", {"saddle": 1.0}, power_W=50.0, when=POWERED),
        Sun("sun", {"col_R_skin": 1.0}),
    ]
    sensors = [
        TemperatureSensor("T_col_L", {"col_L": 1.0}, 0.0, lag_s=600.0),
        TemperatureSensor("T_col_R", {"col_R": 0.9, "col_R_skin": 0.1}, 0.0, lag_s=600.0),
        TemperatureSensor("T_rail", {"crossrail": 0.9, "rail_drives": 0.1}, 0.0, lag_s=600.0),
        TemperatureSensor("T_rail_drive", {"rail_drives": 1.0}, 0.0, lag_s=120.0),
        TemperatureSensor("T_saddle", {"saddle": 1.0}, 0.0, lag_s=300.0),
        TemperatureSensor("T_ram", {"ram": 0.7, "saddle": 0.3}, 0.0, lag_s=300.0),
        TemperatureSensor("T_spindle", {"spindle": 0.8, "ram": 0.2}, 0.0, lag_s=120.0),
        TemperatureSensor("T_motor", {"spindle_motor": 1.0}, 0.0, lag_s=60.0),
        TemperatureSensor("T_bed", {"bed": 1.0}, 0.0, lag_s=900.0),
        TemperatureSensor("T_hall", {AMBIENT: 1.0}, 0.0, lag_s=120.0),
    ]
    errors = ThermoelasticMap(
        linear={"E_X": {"col_R_skin": 4.0, "col_R": -2.5, "col_L": 1.5, "saddle": 1.0, "bed": -0.8},
                "E_Y": {"crossrail": 3.5, "rail_drives": 2.0, "saddle": 1.5, "bed": -1.0},
                "E_Z": {"col_L": 2.5, "col_R": 2.5, "col_R_skin": 1.5, "crossrail": -1.5,
                        "ram": -3.0, "bed": -2.0, "spindle": -6.0, "spindle_motor": -2.0}},
        quadratic={"E_Z": {"spindle": -0.04}}, reference_c=20.0)
    return Machine(ThermalNetwork(NODES, LINKS), sources, sensors, errors)


class RamLever(LoggedStateEffect):
    """The ram's extension as a lever on E_Y and E_Z (declared: its position is logged)."""

    name, state = "ram_lever", RAM
    defaults = {"lever": RAM_LEVER, "targets": ["E_Y", "E_Z"]}

    def modify_errors(self, ctx, errors):
        index = ctx.machine.network.index
        rise = ctx.node_temps - ctx.node_temps[0]
        lever_m = self.logged(ctx) / 1000.0
        errors = errors.copy()
        targets = ctx.machine.thermoelastic.targets
        for target, (gain, weights) in self.params["lever"].items():
            tilt = sum(w * rise[:, index[n]] for n, w in weights.items())
            errors[:, targets.index(target)] += gain * tilt * lever_m
        return errors


def on_shift(t_rel) -> np.ndarray:
    """Campaign time -> 1 on weekdays 6-22 h (every campaign starts on a Monday 00:00)."""
    return weekday_shift(t_rel, SHIFT_H)


def cloud_factors(rng, days: int) -> np.ndarray:
    """Per day and 10-min block: the share of the clear-sky sun that reaches the column."""
    blocks = int(DAY_S / SUN_BLOCK_S)
    out = np.empty((days, blocks))
    for d in range(days):
        kind = rng.choice(3, p=[0.4, 0.3, 0.3])
        if kind == 0:
            out[d] = rng.uniform(0.85, 1.0)
        elif kind == 1:
            out[d] = rng.uniform(0.3, 0.7) * rng.uniform(0.2, 1.0, blocks)
        else:
            out[d] = rng.uniform(0.03, 0.12)
    return out


def sun_signal(clouds: np.ndarray):
    """Campaign time -> the sun's share (0..1), in 10-min blocks and steps of 0.05."""
    def sun(t_rel):
        t = np.asarray(t_rel, float)
        block = np.floor(t / SUN_BLOCK_S)
        hour = (block * SUN_BLOCK_S + SUN_BLOCK_S / 2) / 3600.0 % 24
        clear = np.where((hour > 12) & (hour < 18), np.sin(np.pi * (hour - 12) / 6), 0.0)
        day = np.clip((t // DAY_S).astype(int), 0, len(clouds) - 1)
        blocks = np.clip((block % (DAY_S / SUN_BLOCK_S)).astype(int), 0, clouds.shape[1] - 1)
        return np.round(clear * clouds[day, blocks] / 0.05) * 0.05
    return sun


@dataclass(frozen=True)
class UnclimatisedHall:
    """The hall air (°C): the free level with the outside's day cycle, the heating from 05:00
    on weekdays (towards ``heated_c``, its on/off cycling), the room's lag, a weather drift, and
    the skylights' sun; ``start_s`` is a Monday 00:00 (absolute s), ``sun`` a campaign-time
    signal."""

    start_s: float
    sun: object
    free_c: float = 9.5
    daily_amplitude_c: float = 2.5
    daily_peak_hour: float = 15.0
    heated_c: float = 18.0
    cycling_c: float = 0.3
    cycling_min: float = 30.0
    room_tau_h: float = 2.0
    drift_sd_c: float = 1.2
    drift_tau_h: float = 36.0
    extra: dict = field(default_factory=dict)

    def target(self, t_s) -> np.ndarray:
        t = np.asarray(t_s, float)
        hours = (t - self.start_s) / 3600.0
        day, hour = np.floor(hours / 24) % 7, hours % 24
        heating = (day < 5) & (hour >= HEATING_H[0]) & (hour < HEATING_H[1])
        free = self.free_c + self.daily_amplitude_c * np.cos(
            2 * np.pi * (hour - self.daily_peak_hour) / 24)
        cycling = np.where((t / (60 * self.cycling_min)) % 1 < 0.5, self.cycling_c, -self.cycling_c)
        return np.where(heating, self.heated_c + cycling, free)

    def sample(self, t_s, rng) -> np.ndarray:
        t = np.asarray(t_s, float)
        level = room_response(t, self.target(t), self.room_tau_h)
        drift = AmbientModel(drift_sd_c=self.drift_sd_c, drift_tau_h=self.drift_tau_h).drift(t, rng)
        sun = np.where(t >= self.start_s, self.sun(np.maximum(t - self.start_s, 0.0)), 0.0)
        return level + drift + SUN_AIR_K * sun

    def to_dict(self) -> dict:
        return {"free_c": self.free_c, "heated_c": self.heated_c, "heating_hours": HEATING_H,
                "daily_amplitude_c": self.daily_amplitude_c, "drift_sd_c": self.drift_sd_c}


def programme(rng, period_s: float, days: int) -> tuple[Programme, object]:
    """``days`` of spindle speeds and ram extensions (weekdays 6-22 h), on the logger's grid."""
    def grid(t):
        return period_s * round(t / period_s)

    steps, ram = [(0.0, 0.0)], [(0.0, 0.0)]
    for day in range(days):
        if day % 7 >= 5:
            continue
        t, end = (day * DAY_S + h * 3600 for h in SHIFT_H)
        while t < end:
            job_end = min(end, t + rng.uniform(0.5, 2.0) * 3600)
            rpm = float(rng.choice([1000, 2000, 3000, 4500, 6000]))
            ram.append((grid(t), float(rng.integers(10, 81) * 10)))
            while t < job_end:
                cut = min(job_end, t + rng.uniform(5, 30) * 60)
                steps += [(grid(t), rpm), (grid(cut), 0.0)]
                t = cut + rng.uniform(1, 6) * 60
            ram.append((grid(t), 0.0))
            t += rng.uniform(5, 20) * 60
    return Programme(tuple(merge(steps))), Programme(tuple(merge(ram))).rpm_at


@dataclass(eq=False, repr=False, kw_only=True)
class Portal64(PlantedScenario):
    """Three weeks of the portal mill: weekly campaigns, or one record (``one_record``)."""

    name = "portal64"
    year = 2027
    planted = RamLever

    weeks: int = 3
    one_record: bool = False
    sample_period_s: float = 60.0
    error_period_s: float = 300.0
    error_gaps: str = "nan"
    error_noise_um: float = 0.3

    def machine(self):
        return machine()

    def planted_truth(self):
        return {t: {"gain_um_per_K_per_m": g, "rise_weights": w} for t, (g, w) in RAM_LEVER.items()}

    def plans(self, rng):
        first = (START - datetime(self.year, 1, 1)).total_seconds()
        period = float(self.sample_period_s)
        blocks = [(0, int(self.weeks))] if self.one_record else [(w, 1) for w in range(int(self.weeks))]
        plans = []
        for (week, n_weeks), child in zip(blocks, rng.spawn(len(blocks))):
            start, days = first + week * 7 * DAY_S, 7 * n_weeks
            clouds = cloud_factors(child, days)
            sun = sun_signal(clouds)
            spindle, ram = programme(child, period, days)
            last = not self.one_record and week == int(self.weeks) - 1
            plans.append(CampaignPlan(
                cid="record" if self.one_record else f"W{week + 1}",
                split="test" if last else "train", start_s=start,
                duration_s=days * DAY_S - period, rng=child,
                ambient=UnclimatisedHall(start, sun), programme=spindle,
                states={POWERED: on_shift, SUN: sun, RAM: ram}, written=(SPINDLE, RAM),
                sample_period_s=period, error_period_s=float(self.error_period_s),
                cooldown_s=2 * DAY_S, notes=f"{n_weeks} week(s) from week {week + 1}",
                manifest={}, truth={"cloud_factor_day_mean": clouds.mean(axis=1).round(3).tolist()}))
        return plans


__all__ = ["Portal64", "machine"]
