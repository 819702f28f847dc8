"""hbm75: a table-type horizontal boring mill with an NC rotary table (stranger75).

The column stands on its own bed beside the table's X bed; the headstock rides up the column
(Y, 0-2000 mm), its guides' friction heating the column where it stands; the spindle is driven
through a two-stage gearbox by a motor on the headstock's back; the rotary table (B) is turned
by a torque motor when a part is indexed; a lube/hydraulic unit beside the column feeds the
gearbox and the guides. Errors at the spindle nose against a test mandrel on the table.

Nodes (C J/K, hA W/K to the hall air): xbed (the table's X bed), saddle, rtable (the rotary
table), bdrive (its torque motor), colfoot, colhead (the column's lower and upper half),
headstock, quill (spindle and its bearings), gearbox, lube. 22 sensors; 60 s cadence; six runs
of 22 h (06:00 to 04:00 local time, the machine standing the 2 h between), one a day from Wed
2027-10-27: Saturday's run crosses the end of daylight saving time (Sun 31 Oct, 03:00 CEST ->
02:00 CET). States: the spindle speed S_n_rpm, the headstock's height S_Y_mm, the table
indexing S_B_turn (0/1). A run: jobs of 40-200 min at one speed and height (set-ups at 0 rpm),
the table indexed for 3-12 min now and then; from 22:00 the machine idles (no spindle, no
table, the lube unit off).
"""
from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime, timedelta
from zoneinfo import ZoneInfo

import numpy as np

from thermocomp.apps.sim.ambient import AmbientModel
from thermocomp.apps.sim.campaign import Machine
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.scenario import CampaignPlan, DeclaredScenario
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import ConstantWhileRunning, MovingSource, SpeedLosses

SPEED, HEIGHT, INDEX = "S_n_rpm", "S_Y_mm", "S_B_turn"
LOCAL = ZoneInfo("Europe/Berlin")
FIRST_RUN = datetime(2027, 10, 27, 6, tzinfo=LOCAL)        # a Wednesday, 06:00 CEST
RUN_H, RUNS = 22.0, 6
SHIFT_END_H = 16.0                                          # 22:00: the machine idles
SPEEDS = (0.0, 400.0, 900.0, 1500.0, 2200.0, 3000.0)        # rpm of a job (0: a set-up)


def network() -> ThermalNetwork:
    nodes = (Node("xbed", 2.6e6, 26.0), Node("saddle", 4.5e5, 7.0), Node("rtable", 7.0e5, 11.0),
             Node("bdrive", 2.5e4, 2.5), Node("colfoot", 1.3e6, 15.0), Node("colhead", 9.0e5, 13.0),
             Node("headstock", 3.5e5, 8.0), Node("quill", 4.5e4, 2.5), Node("gearbox", 1.4e5, 4.5),
             Node("lube", 2.2e5, 8.5))
    links = (Link("xbed", "saddle", 9.5), Link("saddle", "rtable", 13.0), Link("bdrive", "rtable", 5.5),
             Link("xbed", "colfoot", 7.0), Link("colfoot", "colhead", 10.5),
             Link("headstock", "colhead", 4.5), Link("headstock", "quill", 7.5),
             Link("gearbox", "headstock", 6.5), Link("lube", "gearbox", 5.0), Link("lube", "xbed", 2.0))
    return ThermalNetwork(nodes, links)


def sensors() -> list[TemperatureSensor]:
    s = TemperatureSensor
    return [
        s("T_air_floor", {AMBIENT: 1.0}, 0.2, 90.0), s("T_air_top", {AMBIENT: 1.0}, 0.6, 150.0),
        s("T_foundation", {AMBIENT: 0.55, "xbed": 0.45}, -0.4, 2400.0),
        s("T_xbed_front", {"xbed": 1.0}, 0.1, 700.0),
        s("T_xbed_rear", {"xbed": 0.85, AMBIENT: 0.15}, -0.1, 1000.0),
        s("T_saddle", {"saddle": 0.9, "xbed": 0.1}, 0.0, 500.0),
        s("T_table_top", {"rtable": 0.8, AMBIENT: 0.2}, 0.0, 350.0),
        s("T_table_rim", {"rtable": 0.65, "bdrive": 0.35}, 0.0, 250.0),
        s("T_bmotor", {"bdrive": 1.0}, 0.3, 45.0),
        s("T_col_foot", {"colfoot": 1.0}, 0.0, 650.0),
        s("T_col_mid", {"colfoot": 0.5, "colhead": 0.5}, 0.0, 800.0),
        s("T_col_head", {"colhead": 0.95, AMBIENT: 0.05}, 0.0, 600.0),
        s("T_hs_left", {"headstock": 0.85, "colhead": 0.15}, 0.0, 300.0),
        s("T_hs_right", {"headstock": 0.75, "gearbox": 0.25}, 0.0, 300.0),
        s("T_quill_front", {"quill": 0.9, "headstock": 0.1}, 0.0, 110.0),
        s("T_quill_rear", {"quill": 0.55, "headstock": 0.45}, 0.0, 160.0),
        s("T_quill_sleeve", {"quill": 0.75, AMBIENT: 0.25}, 0.0, 200.0),
        s("T_gearbox", {"gearbox": 1.0}, 0.0, 90.0),
        s("T_lube_tank", {"lube": 1.0}, 0.0, 70.0),
        s("T_lube_return", {"lube": 0.6, "gearbox": 0.4}, 0.0, 80.0),
        s("T_cabinet", {AMBIENT: 0.75, "lube": 0.25}, 0.5, 500.0),
        s("T_coolant", {AMBIENT: 0.65, "rtable": 0.35}, 0.0, 260.0),
    ]


def machine() -> Machine:
    from thermocomp.apps.sim.thermoelastic import ThermoelasticMap
    sources = [
        SpeedLosses("spindle_drive", {"quill": 0.5, "headstock": 0.2, "gearbox": 0.3}, signal=SPEED,
                    idle_W=55.0, linear_W_per_krpm=70.0, quadratic_W_per_krpm2=28.0),
        MovingSource("y_guides", path=("colfoot", "colhead"), positions_mm=(0.0, 2000.0),
                     signal=HEIGHT, when=SPEED, power_W=140.0),
        ConstantWhileRunning("b_torque_motor", {"bdrive": 0.75, "rtable": 0.25}, power_W=260.0,
                             when=INDEX),
        ConstantWhileRunning("lube_unit", {"lube": 1.0}, power_W=110.0, when="S_on"),
    ]
    errors = ThermoelasticMap(
        linear={"E_X": {"rtable": 2.2, "saddle": 1.6, "colfoot": -0.9, "xbed": 1.1},
                "E_Y": {"colfoot": 3.6, "colhead": 5.2, "headstock": 2.3, "rtable": -1.3},
                "E_Z": {"quill": -6.5, "headstock": -3.2, "gearbox": -1.1, "colhead": -1.4,
                        "xbed": 0.7, "rtable": 1.2}},
        reference_c=20.0)
    return Machine(network(), sources, sensors(), errors)


def run_programme(rng: np.random.Generator, period: float) -> dict:
    """The run's states as functions of the time since its start (s): jobs until 22:00, then idle."""
    shift = SHIFT_END_H * 3600.0
    edges, speed, height, t = [0.0], [], [], 0.0
    while t < shift:
        speed.append(float(rng.choice(SPEEDS, p=[.2, .1, .2, .2, .2, .1])))
        height.append(float(np.round(rng.uniform(150.0, 1850.0), -1)))
        t = min(shift, t + period * round(rng.uniform(40.0, 200.0) * 60.0 / period))
        edges.append(t)
    turns = []                      # (start, end) of each indexing of the table
    t = float(rng.uniform(0.5, 1.5)) * 3600.0
    while t < shift:
        turns.append((t, t + rng.uniform(3.0, 12.0) * 60.0))
        t += rng.uniform(0.7, 2.5) * 3600.0
    job_edges = np.asarray(edges)

    def job(values):
        vals = np.asarray(values + [0.0])

        def at(t_rel):
            return vals[np.clip(np.searchsorted(job_edges, np.asarray(t_rel, float), side="right") - 1,
                                0, len(vals) - 1)]
        return at
    starts = np.array([a for a, _ in turns])
    ends = np.array([b for _, b in turns])

    def indexing(t_rel):
        t_arr = np.asarray(t_rel, float)
        k = np.searchsorted(starts, t_arr, side="right") - 1
        return ((k >= 0) & (t_arr < ends[np.clip(k, 0, len(ends) - 1)])).astype(float)

    return {SPEED: job(speed), HEIGHT: _held(job_edges, height),
            INDEX: indexing, "S_on": lambda t_rel: (np.asarray(t_rel, float) < shift).astype(float)}


def _held(edges: np.ndarray, values: list):
    """The headstock stays where the last job left it."""
    vals = np.asarray(values)

    def at(t_rel):
        return vals[np.clip(np.searchsorted(edges, np.asarray(t_rel, float), side="right") - 1,
                            0, len(vals) - 1)]
    return at


def run_starts() -> list[datetime]:
    """Each run's start, 06:00 local time on six days in a row (aware datetimes)."""
    return [(FIRST_RUN.replace(tzinfo=None) + timedelta(days=k)).replace(tzinfo=LOCAL)
            for k in range(RUNS)]


@dataclass(eq=False, repr=False, kw_only=True)
class Hbm75(DeclaredScenario):
    name = "hbm75"
    year: int = 2027
    sample_period_s: float = 60.0
    run_h: float = RUN_H

    def machine(self):
        return machine()

    def plans(self, rng):
        period = float(self.sample_period_s)
        hall = AmbientModel(annual_mean_c=17.5, annual_amplitude_c=0.0, daily_amplitude_c=1.8,
                            daily_peak_hour=14.5, drift_sd_c=0.7, drift_tau_h=9.0)
        year0 = datetime(int(self.year), 1, 1, tzinfo=ZoneInfo("UTC"))
        plans = []
        for k, start in enumerate(run_starts()):
            r = np.random.default_rng([int(self.seed), 75, k])
            plans.append(CampaignPlan(
                cid=f"run{k + 1}", split="train", start_s=(start - year0).total_seconds(),
                duration_s=float(self.run_h) * 3600.0 - period, rng=r, ambient=hall, programme=None,
                states=run_programme(r, period), written=(SPEED, HEIGHT, INDEX),
                sample_period_s=period, error_period_s=None, cooldown_s=2 * 3600.0,
                notes=f"run {k + 1}"))
        return plans


def local_clock(start: datetime, seconds) -> list[str]:
    """The lab PC's wall clock (Europe/Berlin, no offset written) ``seconds`` after ``start``."""
    utc = start.astimezone(ZoneInfo("UTC"))
    return [(utc + timedelta(seconds=float(s))).astimezone(LOCAL).strftime("%Y-%m-%d %H:%M:%S")
            for s in seconds]
