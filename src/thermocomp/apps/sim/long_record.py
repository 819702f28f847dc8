r"""Scenario ``long_record``: one long, non-stationary record, as measured on a shop floor.

What measured data look like, as opposed to tidy campaigns: one machining
centre logged for two to four weeks at 1 min (default 21 days, ~30 k rows) in
a hall whose air drifts with the weather and swings day and night, under a
workload that changes from shift to shift and stops at weekends.  Part of
the error ``E_Z`` is driven by *internal* temperatures -- the cores of the
headstock, column and bed castings -- that no sensor sees: the sensors sit on
the skins and follow the air and the heat within minutes, the cores follow the
skins hours later.  A static regression on the measured temperatures therefore
leaves a dynamic residual that a model with first-order lags of the inputs
(time constants of hours) can remove.  Sensor noise, 0.01 °C quantisation and
a few spikes (in temperatures and in the error) complete the picture.

Layout and split
----------------
The data contract splits by campaign, so the one record is cut in time into
two manifest rows: ``R1a`` (``train``, the first ``1 - test_fraction`` of the
samples) and ``R1b`` (``test``, the last ``test_fraction``, default 10 %).
Both files come from one simulation (no rest, no restart between them); the
``time`` of ``R1b`` restarts at 0; its ``start`` and the extra manifest
columns ``record`` (``R1``), ``record_offset_s`` (where it sits in the
record) and ``continues`` (``R1a``: the campaign whose last sample precedes
its first by one period) say how the two fit together.  ``E_Z`` is the drift
since the record start (not re-zeroed at the cut), so the scenario config sets
``data.reference: none`` (DATA_FORMAT.md: "for one long record split into
campaigns"): temperatures and errors are used absolute, as a measured record
is run.  Dynamics of a model (lags, AR terms) restart at ``R1b``'s first
sample, as they would for a user's record cut the same way, unless the model
carries its state over from ``R1a`` (which ``continues`` allows): started
from a steady state at the cut, a lag of hours is wrong for hours, because the
cores are not in equilibrium with the skins at the cut.

Undeclared effects act on the whole record (one simulated campaign, split
``train`` while it runs), before the cut; their times in
``truth["record"]["effects"]`` are record times (``R1b``'s time plus
``record_offset_s``).

The machine (C = m · 460 J/(kg K); hA in W/K)
----------------------------------------------
==============  =======  =====  ======================================================
node            C (J/K)  hA     what
==============  =======  =====  ======================================================
motor           2.0e4    6      spindle motor, finned housing with its fan
shaft           1.15e4   1 (+)  spindle shaft (unmeasured; the bearing sensors are close)
bearings        4.0e3    1      front bearing set and inner housing
head_skin       6.0e4    10     headstock walls (~130 kg) with the head sensors
head_core       3.0e5    0.5    cartridge seat and thick flange (unmeasured), tau 2.7 h
column_front    1.2e5    8      front wall of the column, Z guideways (enclosure side)
column_back     1.2e5    20     back wall, ribbed, open to the shop
column_core     1.4e6    0      ~3 t of ribs and inner walls (unmeasured), tau 5.6 h
bed_skin        3.0e5    30     bed top and sides, X guideways
bed_core        4.6e6    40     ~10 t bed body on its foundation (unmeasured), tau 7.1 h
table           1.4e5    6      table and fixture
x_drive         2.0e4    3      X servo motor, screw nut and bearing block
z_drive         1.5e4    2      Z servo motor and screw bearing at the column top
==============  =======  =====  ======================================================

(+) a rotating shaft drags air: :math:`\Delta hA = 1.5 (n/1000)^{0.6}` W/K.
The cores hang on their skins through the casting walls (``head_skin``-
``head_core`` 25 W/K, each column wall-``column_core`` 25 W/K, ``bed_skin``-
``bed_core`` 120 W/K) and on each other (column base on the bed, 20 W/K),
weakly against the skins' own convection, so the skins follow the air and the
heat and the cores follow the skins;
:meth:`~thermocomp.apps.sim.network.ThermalNetwork.local_time_constants` gives
their time constants (in the truth, ``internal_nodes``): hours, against
minutes for the skins.  The slowest mode of the machine is ~20 h.

Heat: spindle motor losses :math:`25 + 15 n_k + 2 n_k^2` W (75 % motor, 25 %
shaft), Palmgren bearing friction (viscous 60 W, load 15 W at 6000 rpm, with
the oil viscosity of :mod:`~thermocomp.apps.sim.network`), X and Z drives (60 W and
30 W while a job runs, on the drive, guideway and screw nodes).

Errors (µm/K of node rises, :mod:`~thermocomp.apps.sim.thermoelastic`): ``E_Z`` =
2.0 shaft + 0.8 bearings + 1.0 head_skin + 5.0 head_core (Z growth of the head
between the Z nut and the spindle nose) - 1.5 column_front - 1.5 column_back -
11.0 column_core (the column grows and lifts the head) + 4.0 bed_core + 1.5
table (the bed and table lift the part); 0.04 µm/K² on the bearings,
:math:`\beta_Z` = 0.005 /K.  Over the default record the cores' part of
``E_Z`` has an s.d. of ~4.5 µm, the whole error ~15 µm (the spindle's fast
heating dominates the variance); of what a static regression on the measured
temperatures misses (0.69 µm RMS of the noise-free error), the cores alone
leave 0.53 µm, the minutes-fast shaft and the nonlinear terms 0.50 µm.

Sensors (14, Pt100 with 2-10 min contact lag): ``T_amb`` (air), on the
spindle (``T_spindle_front``, ``T_spindle_rear``, ``T_motor``), the headstock
(``T_head_left``, ``T_head_right``), the column (``T_col_front_top``,
``T_col_front_low``, ``T_col_back``), the bed (``T_bed_left``,
``T_bed_right``), the table (``T_table``) and the drives (``T_xdrive``,
``T_zdrive``).

Hall climate (:class:`WorkshopClimate`)
---------------------------------------
The air follows a target through a first-order lag (``room_tau_h``): on
working days during the HVAC hours a setpoint that leaks a share of the
outside (``hvac_leak``), otherwise the free level; the free level is a mean
plus a slow Ornstein-Uhlenbeck weather drift (s.d. ``weather_sd_c``, ``weather_tau_h``,
days) plus a day/night swing peaking mid-afternoon; a fast drift (neighbours,
doors) on top.

Workload (:func:`workload`)
---------------------------
Weekdays run two shifts (06-14, 14-22 h), a third (22-06 h) on some nights,
Saturday morning sometimes, Sunday never.  Each shift draws its utilisation;
jobs (10-90 min at one of ``speeds_rpm``, axes moving) alternate with idle
spells so that the shift's share of cutting time matches it.  ``S_spindle_rpm``
is written; the axis duty is not (the drives' heat is seen by ``T_xdrive``
and ``T_zdrive``).

Outliers
--------
After the measurement chain, ``n_temperature_outliers`` spikes (1-3 samples,
:math:`\pm` 1-5 °C, a loose contact or EMI) on random sensors and
``n_error_outliers`` spikes (1-2 samples, :math:`\pm` 3-10 µm, a chip on the
probe) are added, quantised like the data, from their own generator (the
record is otherwise identical with and without them); each is listed in
``truth["outliers"]`` with its campaign, time, column and offset.  They are
glitches of the logger and the probe, not physics, so ``clean=true`` keeps
them too: its linear law holds everywhere else.
"""

from __future__ import annotations

import math
import zlib
from dataclasses import asdict, dataclass

import numpy as np
import pandas as pd

from thermocomp.apps.sim.ambient import DAY_S, AmbientModel, room_response
from thermocomp.apps.sim.campaign import Machine, Programme
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.scenario import CampaignPlan, Scenario, assemble, campaign_entry, check_size, plain
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor, quantise
from thermocomp.apps.sim.sources import (
    SPINDLE,
    BearingFriction,
    ConstantWhileRunning,
    SpindleMotorLosses,
    StateConvection,
)
from thermocomp.apps.sim.thermoelastic import ThermoelasticMap
from thermocomp.base.errors import ConfigError
from thermocomp.base.params import FRACTION, POSITIVE, integer, number, numbers, overrides, span

SCENARIO = "long_record"
AXES = "_axes_moving"
RECORD = "R1"
HOUR = 3600.0

NODES = (
    Node("motor", 2.0e4, 6.0), Node("shaft", 1.15e4, 1.0), Node("bearings", 4.0e3, 1.0),
    Node("head_skin", 6.0e4, 10.0), Node("head_core", 3.0e5, 0.5),
    Node("column_front", 1.2e5, 8.0), Node("column_back", 1.2e5, 20.0), Node("column_core", 1.4e6, 0.0),
    Node("bed_skin", 3.0e5, 30.0), Node("bed_core", 4.6e6, 40.0), Node("table", 1.4e5, 6.0),
    Node("x_drive", 2.0e4, 3.0), Node("z_drive", 1.5e4, 2.0),
)
LINKS = (
    Link("motor", "shaft", 3.0), Link("motor", "head_skin", 8.0), Link("shaft", "bearings", 6.0),
    Link("bearings", "head_skin", 15.0), Link("head_skin", "head_core", 25.0),
    Link("head_skin", "column_front", 20.0), Link("head_core", "column_front", 5.0),
    Link("column_front", "column_core", 25.0), Link("column_back", "column_core", 25.0),
    Link("column_core", "bed_core", 20.0), Link("column_front", "bed_skin", 10.0),
    Link("column_back", "bed_skin", 10.0), Link("bed_skin", "bed_core", 120.0),
    Link("bed_skin", "table", 5.0), Link("x_drive", "bed_skin", 4.0), Link("x_drive", "table", 2.0),
    Link("z_drive", "column_front", 5.0), Link("z_drive", "head_skin", 2.0),
)
INTERNAL = {   # unmeasured core -> the skins it hangs on (what the sensors see)
    "head_core": ["head_skin"],
    "column_core": ["column_front", "column_back"],
    "bed_core": ["bed_skin"],
}


def heat_sources():
    return [
        SpindleMotorLosses("spindle_motor", {"motor": 0.75, "shaft": 0.25}),
        BearingFriction("front_bearings", {"bearings": 0.8, "shaft": 0.2}, bearing_node="bearings"),
        ConstantWhileRunning("x_drive", {"x_drive": 0.6, "bed_skin": 0.3, "table": 0.1}, 60.0, AXES),
        ConstantWhileRunning("z_drive", {"z_drive": 0.6, "column_front": 0.4}, 30.0, AXES),
    ]


def convection_rules():
    return [StateConvection("shaft", 1.5, exponent=0.6)]


def sensors():
    """14 sensors: air, spindle, headstock, column, bed, table, drives (skins only)."""
    return [
        TemperatureSensor("T_amb", {AMBIENT: 0.97, "column_back": 0.03}, -0.04, lag_s=120.0),
        TemperatureSensor("T_spindle_front", {"bearings": 0.8, "head_skin": 0.2}, 0.05, lag_s=300.0),
        TemperatureSensor("T_spindle_rear", {"shaft": 0.3, "head_skin": 0.7}, -0.03, lag_s=300.0),
        TemperatureSensor("T_motor", {"motor": 0.9, "head_skin": 0.1}, 0.08, lag_s=300.0),
        TemperatureSensor("T_head_left", {"head_skin": 1.0}, 0.02, lag_s=480.0),
        TemperatureSensor("T_head_right", {"head_skin": 0.85, "column_front": 0.15}, -0.06, lag_s=480.0),
        TemperatureSensor("T_col_front_top", {"column_front": 0.8, "z_drive": 0.2}, 0.04, lag_s=600.0),
        TemperatureSensor("T_col_front_low", {"column_front": 0.7, "bed_skin": 0.3}, -0.02, lag_s=600.0),
        TemperatureSensor("T_col_back", {"column_back": 0.95, AMBIENT: 0.05}, 0.07, lag_s=600.0),
        TemperatureSensor("T_bed_left", {"bed_skin": 1.0}, -0.05, lag_s=600.0),
        TemperatureSensor("T_bed_right", {"bed_skin": 0.8, "x_drive": 0.2}, 0.03, lag_s=600.0),
        TemperatureSensor("T_table", {"table": 0.9, AMBIENT: 0.1}, 0.01, lag_s=600.0),
        TemperatureSensor("T_xdrive", {"x_drive": 1.0}, -0.08, lag_s=300.0),
        TemperatureSensor("T_zdrive", {"z_drive": 1.0}, 0.06, lag_s=300.0),
    ]


def thermoelastic_map():
    return ThermoelasticMap(
        linear={"E_Z": {"shaft": 2.0, "bearings": 0.8, "head_skin": 1.0, "head_core": 5.0,
                        "column_front": -1.5, "column_back": -1.5, "column_core": -11.0,
                        "bed_core": 4.0, "table": 1.5}},
        quadratic={"E_Z": {"bearings": 0.04}},
        ambient_beta={"E_Z": 0.005},
        reference_c=20.0)


def long_record_machine() -> Machine:
    return Machine(ThermalNetwork(NODES, LINKS), heat_sources(), sensors(), thermoelastic_map(),
                   convection_rules())


LONG_RECORD_EFFECTS = {
    "door": {"nodes": {"table": 40.0, "column_front": 30.0}, "air_offset_c": -6.0, "rate_per_h": 0.2,
             "duration_min": [5.0, 20.0], "targets": ["E_Z"]},
    "hidden_source": {"anchor": "column_back", "power_W": 300.0, "conductance_W_per_K": 12.0,
                      "on_min": [60.0, 240.0], "off_min": [60.0, 240.0], "targets": ["E_Z"]},
    "lag_node": {"parent": "head_skin", "capacity_J_per_K": 6.0e5, "conductance_W_per_K": 40.0,
                 "convection_W_per_K": 1.0, "sensitivity_um_per_K": {"E_Z": 5.0}, "targets": ["E_Z"]},
    "axis_position": {"axis": "Z", "travel_mm": [0.0, 600.0], "home_mm": 300.0, "dwell_min": [15.0, 60.0],
                      "tilt_nodes": {"column_back": 1.0, "column_front": -1.0},
                      "gain_um_per_K_per_m": 40.0, "targets": ["E_Z"]},
    # One record is one simulated campaign (split "train" while it runs): the drift starts late in it.
    "sensor_drift": {"column": "T_head_left", "rate_K_per_h": 0.02, "onset_fraction": 0.8,
                     "splits": ["train"], "targets": ["E_Z"]},
    "ambient_law": {"level_node": "ambient", "level_lag_h": 2.0, "threshold_c": 21.0, "gain": 0.3,
                    "targets": ["E_Z"]},
}


@dataclass(frozen=True)
class WorkshopClimate:
    r"""Hall air: HVAC on working days, free drift otherwise, weather over days (°C).

    .. math::

        \tau_r \dot T_a = T_{tgt}(t) - T_a, \qquad
        T_{free} = \bar T + w(t) + A_d\cos(2\pi(h - h_{peak})/24), \qquad
        T_{tgt} = \begin{cases} s + \lambda\,(T_{free} - s) & \text{HVAC on} \\
                                  T_{free} & \text{off}\end{cases}

    :math:`w` is the weather, an Ornstein-Uhlenbeck drift (s.d.
    ``weather_sd_c``, correlation ``weather_tau_h``); the HVAC runs on weekdays
    (Monday-Friday) during ``hvac_hours`` and lets a share :math:`\lambda` =
    ``hvac_leak`` of the outside through; a fast drift (``drift_sd_c``,
    ``drift_tau_h``: neighbours, gates) rides on top.  ``sample`` takes
    absolute times (s since 1 January 00:00 of a year starting on a
    ``first_weekday``, 0 = Monday) on any increasing grid.
    """

    setpoint_c: float = 21.0
    hvac_hours: tuple = (5.0, 22.0)
    hvac_leak: float = 0.3
    free_mean_c: float = 18.0
    daily_amplitude_c: float = 2.0
    daily_peak_hour: float = 15.0
    weather_sd_c: float = 2.0
    weather_tau_h: float = 72.0
    room_tau_h: float = 1.5
    drift_sd_c: float = 0.15
    drift_tau_h: float = 2.0
    first_weekday: int = 6          # 1 January 2023 was a Sunday

    def working_day(self, t_s) -> np.ndarray:
        day = np.floor(np.asarray(t_s, dtype=float) / DAY_S).astype(int)
        return (day + self.first_weekday) % 7 < 5

    def target(self, t_s, weather) -> np.ndarray:
        t_s = np.asarray(t_s, dtype=float)
        hour = (t_s / DAY_S % 1.0) * 24.0
        free = (self.free_mean_c + weather
                + self.daily_amplitude_c * np.cos(2 * np.pi * (hour - self.daily_peak_hour) / 24.0))
        on = self.working_day(t_s) & (hour >= self.hvac_hours[0]) & (hour < self.hvac_hours[1])
        return np.where(on, self.setpoint_c + self.hvac_leak * (free - self.setpoint_c), free)

    def sample(self, t_s, rng: np.random.Generator) -> np.ndarray:
        t_s = np.asarray(t_s, dtype=float)
        weather = AmbientModel(drift_sd_c=self.weather_sd_c, drift_tau_h=self.weather_tau_h).drift(t_s, rng)
        level = room_response(t_s, self.target(t_s, weather), self.room_tau_h)
        fast = AmbientModel(drift_sd_c=self.drift_sd_c, drift_tau_h=self.drift_tau_h).drift(t_s, rng)
        return level + fast

    def to_dict(self) -> dict:
        return {**asdict(self), "hvac_hours": list(map(float, self.hvac_hours))}


def workload(rng: np.random.Generator, start_s: float, duration_s: float, grid_s: float,
             speeds_rpm, utilisation=(0.2, 0.95), third_shift_p: float = 0.3,
             saturday_p: float = 0.4, first_weekday: int = 6):
    """Spindle programme and job intervals of a shop over ``duration_s`` from absolute ``start_s``.

    Shifts 06-14 and 14-22 h on weekdays, 22-06 h on a share ``third_shift_p``
    of weekday nights, 06-14 h on a share ``saturday_p`` of Saturdays.  A shift
    draws its utilisation :math:`u` in ``utilisation``; jobs of 10-90 min at a
    speed of ``speeds_rpm`` follow idle spells of mean length
    :math:`\\bar j (1-u)/u`.  Times are on the ``grid_s`` grid, relative to the
    record start.  Returns ``(Programme, job intervals, shifts)`` where
    ``shifts`` lists ``(start, end, utilisation)``.
    """
    speeds = np.asarray(speeds_rpm, dtype=float)
    shifts = []
    first_day = math.floor(start_s / DAY_S) - 1        # a night shift may run into the record
    last_day = math.ceil((start_s + duration_s) / DAY_S)
    for day in range(first_day, last_day + 1):
        weekday = (day + first_weekday) % 7
        blocks = []
        if weekday < 5:
            blocks += [(6.0, 14.0), (14.0, 22.0)]
            if rng.uniform() < third_shift_p:
                blocks.append((22.0, 30.0))
        elif weekday == 5 and rng.uniform() < saturday_p:
            blocks.append((6.0, 14.0))
        for a, b in blocks:
            shifts.append((day * DAY_S + a * HOUR - start_s, day * DAY_S + b * HOUR - start_s,
                           float(rng.uniform(*utilisation))))
    steps, jobs, kept = [(0.0, 0.0)], [], []
    for a, b, u in shifts:
        if b <= 0 or a >= duration_s:
            continue
        kept.append((a, b, u))
        t = a + grid_s * round(rng.exponential(20.0 * 60.0) / grid_s)    # setting up
        while t < b:
            length = grid_s * max(1, round(rng.uniform(10.0, 90.0) * 60.0 / grid_s))
            end = min(t + length, b)
            if end > max(t, 0.0):
                jobs.append((max(t, 0.0), end))
            t = end + grid_s * max(1, round(rng.exponential(50.0 * 60.0 * (1 - u) / u) / grid_s))
    for a, b in jobs:
        rpm = float(rng.choice(speeds))
        a = grid_s * round(a / grid_s)
        b = grid_s * round(b / grid_s)
        if a == steps[-1][0]:
            steps[-1] = (a, rpm)
        elif a > steps[-1][0]:
            steps.append((a, rpm))
        if b > a:
            steps.append((b, 0.0))
    return Programme(tuple(_merged(steps))), jobs, kept


def _merged(steps):
    """Drop steps that repeat the previous speed (and keep the first at t = 0)."""
    out = [steps[0]]
    for t, rpm in steps[1:]:
        if t == out[-1][0]:
            out[-1] = (t, rpm)
        elif rpm != out[-1][1]:
            out.append((t, rpm))
    return out


def jobs_signal(jobs):
    """1 while a job runs (axes moving), 0 otherwise, as a function of record time."""
    starts = np.array([a for a, _ in jobs], dtype=float)
    ends = np.array([b for _, b in jobs], dtype=float)

    def signal(t):
        t = np.asarray(t, dtype=float)
        k = np.searchsorted(starts, t + 1e-6, side="right") - 1
        if not len(starts):
            return np.zeros(t.shape)
        return ((k >= 0) & (t < ends[np.clip(k, 0, None)] - 1e-6)).astype(float)
    return signal


class LongRecord(Scenario):
    """Generator of the ``long_record`` dataset: one record of weeks, cut 90/10 in time.

    Parameters
    ----------
    duration_days : float
        Length of the record (2-4 weeks in the measured records it mimics).
    sample_period_s : float
        Logger period of temperatures, error and spindle speed.
    test_fraction : float
        Share of the samples, at the end of the record, written as the ``test``
        campaign ``R1b``; the rest is ``R1a`` (``train``).
    start_day, start_hour : float
        Record start (day of the year, 0 = 1 January 2023, a Sunday; hour).
    speeds_rpm : sequence of float
        Spindle speeds of the jobs.
    utilisation : (float, float)
        Range of a shift's share of cutting time.
    third_shift_p, saturday_p : float
        Probability of a night shift on a weekday, of a Saturday morning shift.
    climate : dict or None
        Overrides of :class:`WorkshopClimate` fields.
    n_temperature_outliers, n_error_outliers : int
        Spikes added to random sensors and to the error.
    temp_noise_c, temp_quantum_c, error_noise_um, error_quantum_um : float
        Measurement chain.
    effects, effect_params, clean, seed
        See :class:`~thermocomp.apps.sim.scenario.Scenario`; the effects act on the
        whole record (one simulated campaign), before the cut.
    """

    name = SCENARIO
    param_rules = {**Scenario.param_rules, "duration_days": POSITIVE, "sample_period_s": POSITIVE,
                   "test_fraction": number(0.0, 1.0, open_lo=True, open_hi=True),
                   "start_day": integer(0, 364), "start_hour": number(0.0, 24.0, open_hi=True),
                   "speeds_rpm": numbers(0.0), "utilisation": span(0.0, 1.0),
                   "third_shift_p": FRACTION, "saturday_p": FRACTION,
                   "n_temperature_outliers": integer(0), "n_error_outliers": integer(0),
                   "climate": overrides(WorkshopClimate)}
    year = 2023

    def __init__(self, duration_days=21.0, sample_period_s=60.0, test_fraction=0.1, start_day=74,
                 start_hour=8.0, speeds_rpm=(1500, 3000, 4500, 6000, 8000), utilisation=(0.2, 0.95),
                 third_shift_p=0.3, saturday_p=0.4, climate=None, n_temperature_outliers=4,
                 n_error_outliers=3, temp_noise_c=0.03, temp_quantum_c=0.01, error_noise_um=0.2,
                 error_quantum_um=0.01, effects=(), effect_params=None, clean=False, seed=0):
        self.duration_days = duration_days
        self.sample_period_s = sample_period_s
        self.test_fraction = test_fraction
        self.start_day = start_day
        self.start_hour = start_hour
        self.speeds_rpm = speeds_rpm
        self.utilisation = utilisation
        self.third_shift_p = third_shift_p
        self.saturday_p = saturday_p
        self.climate = climate
        self.n_temperature_outliers = n_temperature_outliers
        self.n_error_outliers = n_error_outliers
        super().__init__(temp_noise_c, temp_quantum_c, error_noise_um, error_quantum_um, effects,
                         effect_params, clean, seed)

    def machine(self):
        return long_record_machine()

    def effect_defaults(self):
        return LONG_RECORD_EFFECTS

    def _climate(self) -> WorkshopClimate:
        return WorkshopClimate(**dict(self.climate or {}))

    def _duration_s(self) -> float:
        period = float(self.sample_period_s)
        return period * round(float(self.duration_days) * DAY_S / period)

    def plans(self, rng):
        (child,) = rng.spawn(1)
        start = DAY_S * float(self.start_day) + HOUR * float(self.start_hour)
        duration = self._duration_s()
        # refused before the workload is planned (a day at a time: 15 s for 1e5 days)
        check_size(duration / float(self.sample_period_s), 1)
        climate = self._climate()
        programme, jobs, shifts = workload(
            child, start, duration, float(self.sample_period_s), self.speeds_rpm, tuple(self.utilisation),
            float(self.third_shift_p), float(self.saturday_p), climate.first_weekday)
        return [CampaignPlan(
            cid=RECORD, split="train", start_s=start, duration_s=duration, rng=child, ambient=climate,
            programme=programme, states={AXES: jobs_signal(jobs)}, written=(SPINDLE,),
            sample_period_s=float(self.sample_period_s), cooldown_s=2 * DAY_S,
            truth={"shifts_s": [list(map(float, s)) for s in shifts],
                   "jobs_s": [list(map(float, j)) for j in jobs], "climate": climate.to_dict()})]

    def truth_extra(self):
        network = self.machine().network
        taus = network.local_time_constants()
        te = thermoelastic_map()
        return {"internal_nodes": {
            node: {"measured": False, "skins": skins, "time_constant_s": taus[node],
                   "time_constant_h": taus[node] / HOUR,
                   "sensitivity_um_per_K": {t: c.get(node, 0.0) for t, c in te.linear.items()},
                   "description": "core of a casting: follows its skins (which the sensors see) hours later"}
            for node, skins in INTERNAL.items()},
            "modal_time_constants_s": [float(v) for v in network.modal_time_constants()]}

    # --- one record -> outliers -> two campaigns ---------------------------------------------------
    def _generate(self):
        dataset, truth = super()._generate()
        frame = dataset.campaigns[RECORD]
        outliers = self._outliers(frame)
        return self._cut(dataset, frame, truth, outliers)

    def _outliers(self, frame: pd.DataFrame) -> list[dict]:
        """Spikes added in place to ``frame`` (own generator, quantised); their list for the truth."""
        rng = np.random.default_rng([int(self.seed), zlib.crc32(b"long_record/outliers")])
        sensors = [c for c in frame.columns if c.startswith("T_")]
        targets = [c for c in frame.columns if c.startswith("E_")]
        n = len(frame)
        out = []
        for count, columns, widths, size, quantum in (
                (self.n_temperature_outliers, sensors, (1, 3), (1.0, 5.0), self.temp_quantum_c),
                (self.n_error_outliers, targets, (1, 2), (3.0, 10.0), self.error_quantum_um)):
            for _ in range(int(count)):
                column = str(rng.choice(columns))
                width = int(rng.integers(widths[0], widths[1] + 1))
                row = int(rng.integers(1, n - width))
                offset = float(quantise(rng.choice([-1.0, 1.0]) * rng.uniform(*size), quantum))
                j = frame.columns.get_loc(column)
                frame.iloc[row:row + width, j] = quantise(frame.iloc[row:row + width, j].to_numpy() + offset,
                                                          quantum)
                out.append({"column": column, "row": row, "samples": width, "offset": offset,
                            "record_time_s": float(frame["time"].iloc[row])})
        return sorted(out, key=lambda o: o["row"])

    def _cut(self, dataset, frame, truth, outliers):
        n = len(frame)
        n_test = int(round(float(self.test_fraction) * n))
        if not 0 < n_test < n:
            raise ConfigError(f"sim.generator.test_fraction={self.test_fraction} leaves no train or no "
                              f"test sample in a record of {n}")
        cut = n - n_test
        cut_s = float(frame["time"].iloc[cut])
        row = dataset.manifest.loc[RECORD]
        start = pd.Timestamp(row["start"])
        parts = {f"{RECORD}a": ("train", frame.iloc[:cut].reset_index(drop=True), 0.0, 0),
                 f"{RECORD}b": ("test", frame.iloc[cut:].reset_index(drop=True), cut_s, cut)}
        simulated = []
        record_truth = {k: v for k, v in truth["campaigns"][RECORD].items() if k != "split"}
        air = self.node_temperatures_[RECORD]["ambient"]
        previous = ""
        for cid, (split, part, offset, first) in parts.items():
            part = part.assign(time=part["time"] - offset)
            share = "first" if split == "train" else "last"
            duration_s = float(part["time"].iloc[-1])
            simulated.append(campaign_entry(
                cid, split, start + pd.Timedelta(seconds=offset),
                f"{share} {len(part) / n:.0%} of the one record {RECORD} ({split})", part,
                {"record": RECORD, "record_offset_s": offset, "continues": previous,
                 "duration_h": duration_s / HOUR},
                {"record": RECORD, "record_offset_s": offset, "rows": [first, first + len(part)],
                 "duration_s": duration_s, "continues": previous or None,
                 "ambient_start_c": float(air.iloc[first])}))
            previous = cid
        nodes = self.node_temperatures_.pop(RECORD)
        for cid, (_, part, _, first) in parts.items():
            self.node_temperatures_[cid] = nodes.iloc[first:first + len(part)].reset_index(drop=True)
        for o in outliers:
            cid = f"{RECORD}a" if o["row"] < cut else f"{RECORD}b"
            o.update(campaign=cid, time_s=o["record_time_s"] - parts[cid][2])
        cut_dataset, campaigns = assemble(self.name, dataset.meta, simulated)
        truth = {**truth, **campaigns,
                 "record": {"campaign": RECORD, **record_truth, "n_samples": n,
                            "sample_period_s": float(self.sample_period_s)},
                 "split": {"method": "one record cut in time: train = the first samples, test = the last "
                                     f"{float(self.test_fraction):.0%} (R1b continues R1a, no gap)",
                           "test_fraction": float(self.test_fraction), "cut_row": cut,
                           "cut_record_time_s": cut_s, "train": f"{RECORD}a", "test": f"{RECORD}b",
                           "recommended_reference": "none"},
                 "outliers": outliers}
        return cut_dataset, plain(truth)


__all__ = ["LongRecord", "WorkshopClimate", "long_record_machine", "workload"]
