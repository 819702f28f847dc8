r"""``iso67``: a vertical machining centre under the three ISO 230-3 thermal tests (iso67).

Built through the documented own-machine route (docs/simulation.md, "Your own machine"): this
:class:`~thermocomp.apps.sim.scenario.Scenario` subclass on ``PYTHONPATH`` and the yaml
``benchmarks/conf67/sim/iso67.yaml``::

    THERMOCOMP_TARGETS=iso67. PYTHONPATH=src:benchmarks .venv/bin/python -m thermocomp \
        simulate "hydra.searchpath=[file://$PWD/benchmarks/conf67]" sim=iso67 seed=6701

Written down and committed before any model ran on it; seeds 6701 and 6702 fixed beforehand
(6701: the lab's test week, one file per test, tilts in µrad; 6702: the same machine, another
week, the software's other version writing the tilts in arcsec).  The lab's export is written by
``benchmarks/bench_iso67.py write``.

The machine
-----------
A vertical machining centre (C-frame: a fixed column on the bed, the spindle head riding the
column front's Z guides, the table on an X/Y cross slide), its spindle air-cooled (no chiller),
max 12000 rpm.  Lumped nodes (C J/K, hA W/K to the hall air):

===========  =======  =====  ========================================================
node         C (J/K)  hA     what
===========  =======  =====  ========================================================
bearing      3e4      2      the spindle's front bearings (the nose)
motor        6e4      4      the built-in motor and the rear bearings
head         1.2e5    10     the spindle head housing
col_front    6e5      6      the column's front wall (guides, the head's side)
col_back     6e5      12     the column's back wall (facing the hall's HVAC outlet)
bed          2e6      15     the bed
xdrive       8e4      3      the X ball screw, its nut and the saddle around it
===========  =======  =====  ========================================================

Links (W/K): bearing-head 6, motor-head 5, head-col_front 8, col_front-col_back 10,
col_front-bed 12, col_back-bed 12, xdrive-bed 4.
Heat (W): the spindle ``S_spindle_rpm`` (n in krpm, none at rest): 10 + 12 n + 1.2 n^2, 0.6
into the bearings, 0.4 into the motor; the X drive 90 while the X axis moves (``S_feed_X``,
mm/min, non-zero).  No heat while the machine rests (the ETVE).

The errors (the sensor nest: 5 capacitive probes on a test mandrel in the spindle, X1/X2 and
Y1/Y2 at two heights 100 mm apart, Z at the end; the software gives X, Y, Z at the lower
probes and the two tilts), linear in the node rises against 20 °C::

    E_X = 1.2 motor - 0.8 bearing + 3.0 xdrive - 0.5 bed                       (µm)
    E_Y = -9.9 col_front + 9.9 col_back + 1.0 head                             (µm)
    E_Z = -3.5 bearing - 5.5 head - 1.5 motor + 5.5 col_front + 5.5 col_back - 2 bed
                                                                               (µm)
    E_A = 22 col_front - 22 col_back + 3 bearing - 3 motor                     (µrad)
    E_B = 6 motor - 6 head + 2 xdrive - 2 bed                                  (µrad)

E_A, the tilt about X: the column's bend from its front/back gradient (alpha 11 µm/(m K) x
1.0 m high / 0.5 m deep = 22 µrad/K) and the head's pitch; E_Y carries the same bend through
the tool's 0.45 m below the column top (-9.9 µm/K); E_Z: the shaft (0.3 m) and the head (0.5 m)
growing down, the column (1 m) up.  E_B, the tilt about Y: the head's roll from
its motor side, the saddle's from the X screw.  Tilts are in µrad (= µm/m, the contract's unit
of an angular error); the probes' noise 0.1 µm, steps of 0.01 (the tilts alike: the simulator
has one measurement chain).

PLANTED (the effect the declared inputs, the default ``T_*``, do not carry): the spindle's
centrifugal shrink, instant with the speed, no temperature behind it (the logged state
``S_spindle_rpm``, not declared): ``E_Z += -0.04 (n / 1000 rpm)^2 µm`` (-5.8 µm at 12000 rpm).
``diagnose`` should find ``S_spindle_rpm`` (its square, or itself) on E_Z.

Sensors (Pt100, 0.02 K noise, 0.01 K steps; lags in s): T_amb (the air, 120), T_spindle_front
(0.7 bearing + 0.3 head, 60), T_spindle_rear (motor, 60), T_head (120), T_col_front (240),
T_col_back (240), T_bed (600), T_xdrive (120).  States logged: ``S_spindle_rpm`` and
``S_feed_X`` (mm/min).

The tests (as the lab runs them)
--------------------------------
The hall: 21 °C, +-1.5 K a day (peak 15 h), a weather drift of 0.5 K (6 h); each test starts
after a rest (the machine at the hall's steady state, 2 days).  Seed 6701's week, starting on a
Friday 2027-05-07 12:00; seed 6702's two weeks later (``sim.generator.weeks_later=2``: the same
plan, its own random draws):

1. ``ETVE`` (ISO 230-3 clause 5): the machine powered, at rest, 60 h from Friday 12:00 at a
   60 s period: the hall's variation alone.
2. ``SPINDLE-CS``: constant speed 6000 rpm (50 %) for 4 h, then 4 h stopped (the cool-down), 10 s.
3. ``SPINDLE-VS1``: a speed spectrum (ISO 230-3 clause 7, variable speed): 4 steps of 75-105
   min each, speeds drawn from {2000, 3000, ... 12000} rpm without repeat, ascending; then a
   3 h cool-down; 10 s.
4. ``AXIS-X``: the X axis to and fro at 10000 mm/min over its travel for 4 h, then 3 h at rest,
   10 s; the nest read once a cycle at the measuring position, every 60 s, the software writing
   that reading until the next (the other tests read every sample).
5. ``SPINDLE-VS2``: a spectrum as 3 but in random order, 5 steps of 60-90 min, 3 h cool-down.
6. ``SPINDLE-VS3``: as 5 (another draw): the last test, the one held out.

A test starts at 07:00 of the working days after the ETVE (Monday to Friday), two on a day
where they fit (the second 30 min after the first ends, when that is before 16:00).
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime, timedelta

import numpy as np
from scenario_tail import LoggedStateEffect, PlantedScenario, held, merge

from thermocomp.apps.sim.ambient import DAY_S, AmbientModel
from thermocomp.apps.sim.campaign import Machine
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.scenario import CampaignPlan
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import ConstantWhileRunning, SpeedLosses

RPM, FEED = "S_spindle_rpm", "S_feed_X"
START = datetime(2027, 5, 7, 12)          # a Friday, 12:00: the ETVE over the weekend
CENTRIFUGAL_UM_PER_KRPM2 = -0.04          # the planted shrink of the spindle nose

NODES = (Node("bearing", 3e4, 2.0), Node("motor", 6e4, 4.0), Node("head", 1.2e5, 10.0),
         Node("col_front", 6e5, 6.0), Node("col_back", 6e5, 12.0), Node("bed", 2e6, 15.0),
         Node("xdrive", 8e4, 3.0))
LINKS = (Link("bearing", "head", 6.0), Link("motor", "head", 5.0), Link("head", "col_front", 8.0),
         Link("col_front", "col_back", 10.0), Link("col_front", "bed", 12.0),
         Link("col_back", "bed", 12.0), Link("xdrive", "bed", 4.0))
ERRORS = {
    "E_X": {"motor": 1.2, "bearing": -0.8, "xdrive": 3.0, "bed": -0.5},
    "E_Y": {"col_front": -9.9, "col_back": 9.9, "head": 1.0},
    "E_Z": {"bearing": -3.5, "head": -5.5, "motor": -1.5, "col_front": 5.5, "col_back": 5.5,
            "bed": -2.0},
    "E_A": {"col_front": 22.0, "col_back": -22.0, "bearing": 3.0, "motor": -3.0},
    "E_B": {"motor": 6.0, "head": -6.0, "xdrive": 2.0, "bed": -2.0},
}
# (kind, hours running, hours cooling, sample period s, error period s or None)
TESTS = (("ETVE", 60.0, 0.0, 60.0, None), ("SPINDLE-CS", 4.0, 4.0, 10.0, None),
         ("SPINDLE-VS1", None, 3.0, 10.0, None), ("AXIS-X", 4.0, 3.0, 10.0, 60.0),
         ("SPINDLE-VS2", None, 3.0, 10.0, None), ("SPINDLE-VS3", None, 3.0, 10.0, None))


def machine() -> Machine:
    from thermocomp.apps.sim.thermoelastic import ThermoelasticMap

    sources = [
        SpeedLosses("spindle", {"bearing": 0.6, "motor": 0.4}, signal=RPM, idle_W=10.0,
                    linear_W_per_krpm=12.0, quadratic_W_per_krpm2=1.2),
        ConstantWhileRunning("x_drive", {"xdrive": 1.0}, power_W=90.0, when=FEED),
    ]
    sensors = [
        TemperatureSensor("T_amb", {AMBIENT: 1.0}, 0.0, lag_s=120.0),
        TemperatureSensor("T_spindle_front", {"bearing": 0.7, "head": 0.3}, 0.0, lag_s=60.0),
        TemperatureSensor("T_spindle_rear", {"motor": 1.0}, 0.0, lag_s=60.0),
        TemperatureSensor("T_head", {"head": 1.0}, 0.0, lag_s=120.0),
        TemperatureSensor("T_col_front", {"col_front": 1.0}, 0.0, lag_s=240.0),
        TemperatureSensor("T_col_back", {"col_back": 1.0}, 0.0, lag_s=240.0),
        TemperatureSensor("T_bed", {"bed": 1.0}, 0.0, lag_s=600.0),
        TemperatureSensor("T_xdrive", {"xdrive": 1.0}, 0.0, lag_s=120.0),
    ]
    return Machine(ThermalNetwork(NODES, LINKS), sources, sensors,
                   ThermoelasticMap(linear=ERRORS, reference_c=20.0))


class Centrifugal(LoggedStateEffect):
    """The spindle nose's centrifugal shrink, instant with the speed (S_spindle_rpm is logged)."""

    name, state = "centrifugal", RPM
    defaults = {"gain": CENTRIFUGAL_UM_PER_KRPM2, "targets": ["E_Z"]}

    def modify_errors(self, ctx, errors):
        errors = errors.copy()
        k = ctx.machine.thermoelastic.targets.index("E_Z")
        n_k = self.logged(ctx) / 1000.0
        errors[:, k] += float(self.params["gain"]) * (n_k ** 2 - n_k[0] ** 2)
        return errors


def spectrum(rng, steps: int, lo_min: float, hi_min: float, ascending: bool) -> list:
    """``steps`` speeds (rpm) from {2000 ... 12000} without repeat and their durations (s)."""
    speeds = rng.choice(np.arange(2000, 12001, 1000), size=steps, replace=False).astype(float)
    if ascending:
        speeds = np.sort(speeds)
    return [(float(s), float(rng.uniform(lo_min, hi_min)) * 60.0) for s in speeds]


def programme(kind: str, rng, period: float, run_h: float | None, cool_h: float):
    """The test's steps ``(start s, value)`` of the speed and of the X feed, its duration (s)."""
    def grid(t):
        return period * round(t / period)

    rpm, feed = [(0.0, 0.0)], [(0.0, 0.0)]
    if kind == "ETVE":
        return rpm, feed, run_h * 3600.0
    if kind == "AXIS-X":
        feed += [(grid(60.0), 10000.0), (grid(60.0 + run_h * 3600.0), 0.0)]
        return rpm, feed, 60.0 + (run_h + cool_h) * 3600.0
    if kind == "SPINDLE-CS":
        steps = [(6000.0, run_h * 3600.0)]
    elif kind == "SPINDLE-VS1":
        steps = spectrum(rng, 4, 75.0, 105.0, ascending=True)
    else:
        steps = spectrum(rng, 5, 60.0, 90.0, ascending=False)
    t = 60.0
    for speed, length in steps:
        rpm.append((grid(t), speed))
        t += length
    rpm.append((grid(t), 0.0))
    return merge(rpm), feed, t + cool_h * 3600.0


def calendar(durations: list) -> list:
    """The tests' start datetimes: the ETVE at START, then 07:00 of the next working days, two
    on a day where the second starts (30 min after the first ends) before 16:00."""
    starts = [START]
    day = START + timedelta(seconds=durations[0])
    day = datetime(day.year, day.month, day.day, 7)
    t = day if START + timedelta(seconds=durations[0]) <= day else day + timedelta(days=1)
    for length in durations[1:]:
        while t.weekday() >= 5:
            t += timedelta(days=1)
        starts.append(t)
        nxt = t + timedelta(seconds=length) + timedelta(minutes=30)
        t = nxt if nxt.date() == t.date() and nxt.hour < 16 else datetime(
            t.year, t.month, t.day, 7) + timedelta(days=1)
    return starts


@dataclass(eq=False, repr=False, kw_only=True)
class Iso67(PlantedScenario):
    """The ISO 230-3 test week of the vertical machining centre (one campaign per test)."""

    name = "iso67"
    year = 2027
    planted = Centrifugal

    # (its parameters declared once, as leftovers67's DeclaredScenario takes them: the
    # __init__ it had, merged beside that, refused every simulate)
    weeks_later: int = 0
    temp_noise_c: float = 0.02
    temp_quantum_c: float = 0.01
    error_noise_um: float = 0.1
    error_quantum_um: float = 0.01

    def machine(self):
        return machine()

    def planted_truth(self):
        return {"E_Z_um_per_krpm2": CENTRIFUGAL_UM_PER_KRPM2, "state": RPM}

    def plans(self, rng):
        hall = AmbientModel(annual_mean_c=21.0, annual_amplitude_c=0.0, daily_amplitude_c=1.5,
                            daily_peak_hour=15.0, drift_sd_c=0.5, drift_tau_h=6.0)
        drawn = []
        for k, (kind, run_h, cool_h, period, error_period) in enumerate(TESTS):
            test_rng = np.random.default_rng([int(self.seed), k])
            rpm, feed, duration = programme(kind, test_rng, period, run_h, cool_h)
            drawn.append((kind, test_rng, rpm, feed, period * np.floor(duration / period),
                          period, error_period))
        starts = calendar([d for _, _, _, _, d, _, _ in drawn])
        plans = []
        for k, ((kind, test_rng, rpm, feed, duration, period, error_period), start) in enumerate(
                zip(drawn, starts)):
            start = start + timedelta(weeks=int(self.weeks_later))
            plans.append(CampaignPlan(
                cid=f"T{k + 1:02d}", split="train",
                start_s=(start - datetime(self.year, 1, 1)).total_seconds(), duration_s=duration,
                rng=test_rng, ambient=hall, programme=None,
                states={RPM: held(rpm), FEED: held(feed)}, written=(RPM, FEED),
                sample_period_s=period, error_period_s=error_period, cooldown_s=2 * DAY_S,
                notes=f"{kind}, {duration / 3600:.2f} h from {start:%a %Y-%m-%d %H:%M}",
                manifest={"test": kind}))
        return plans


__all__ = ["Iso67", "machine"]
