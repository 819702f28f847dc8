"""gantry76: a 5-axis gantry milling machine, its gantry moving over a long bed (stranger76).

Two uprights ride the bed on linear guides (X, 0-3000 mm), driven each by a linear motor at its
foot; the cross beam joins them at the top, the carriage runs along it (Y) and carries the ram
(Z) with a motor spindle and its fork head (A/C, their motors in the head). Errors of the tool
centre point against a laser tracker's reflector at the spindle nose (dX, dY, dZ).

Nodes (C J/K, hA W/K to the hall air): bed1 / bed2 / bed3 (the bed's three segments, 0-1000 /
1000-2000 / 2000-3000 mm), xdrive (both linear motors), uprl / uprr (the left and right
upright), beam, carriage, ram, spindle, head (the fork head and its A/C motors), coolant (the
coolant tank). 26 sensors; 10 s cadence; the tracker measures every 5 min. Six runs of 16 h
(06:00-22:00 local), three weeks apart from Mon 2027-02-15: the hall (no air conditioning)
from ~12 to ~20 °C between the first and the last, so the runs span ambient levels. States:
the spindle speed S_n_rpm, the gantry's position S_X_mm, the fork head working S_AC_on (0/1).
A run: jobs of 30-150 min at one speed, gantry position and head use; from 20:00 idle.
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

SPEED, XPOS, HEAD = "S_n_rpm", "S_X_mm", "S_AC_on"
LOCAL = ZoneInfo("Europe/Berlin")
FIRST_RUN = datetime(2027, 2, 15, 6, tzinfo=LOCAL)          # a Monday, 06:00 CET
RUN_H, RUNS, EVERY_DAYS = 16.0, 6, 21
SHIFT_END_H = 14.0                                          # 20:00: the machine idles
SPEEDS = (0.0, 2000.0, 6000.0, 10000.0, 15000.0, 20000.0)   # rpm of a job (0: a set-up)
TRACKER_PERIOD_S = 300.0


def network() -> ThermalNetwork:
    nodes = (Node("bed1", 1.6e6, 16.0), Node("bed2", 1.6e6, 16.0), Node("bed3", 1.6e6, 16.0),
             Node("xdrive", 6.0e4, 4.0), Node("uprl", 8.0e5, 12.0), Node("uprr", 8.0e5, 12.0),
             Node("beam", 1.2e6, 18.0), Node("carriage", 2.2e5, 5.0), Node("ram", 1.8e5, 5.5),
             Node("spindle", 3.0e4, 2.0), Node("head", 6.0e4, 2.8), Node("coolant", 3.0e5, 9.0))
    links = (Link("bed1", "bed2", 6.0), Link("bed2", "bed3", 6.0), Link("xdrive", "uprl", 2.5),
             Link("xdrive", "uprr", 2.5), Link("xdrive", "bed2", 1.5), Link("uprl", "beam", 5.0),
             Link("uprr", "beam", 5.0), Link("beam", "carriage", 4.5), Link("carriage", "ram", 6.0),
             Link("ram", "spindle", 5.0), Link("spindle", "head", 3.0), Link("coolant", "spindle", 1.2),
             Link("coolant", "bed2", 1.0))
    return ThermalNetwork(nodes, links)


def sensors() -> list[TemperatureSensor]:
    s = TemperatureSensor
    return [
        s("T_air_floor", {AMBIENT: 1.0}, 0.0, 90.0), s("T_air_roof", {AMBIENT: 1.0}, 1.6, 200.0),
        *[s(f"T_{seg}_{side}", {seg: 1.0} if side == "front" else {seg: 0.85, AMBIENT: 0.15},
            0.0, 800.0 if side == "front" else 900.0)
          for seg in ("bed1", "bed2", "bed3") for side in ("front", "rear")],
        s("T_xmotor_l", {"xdrive": 0.9, "uprl": 0.1}, 0.0, 60.0),
        s("T_xmotor_r", {"xdrive": 0.9, "uprr": 0.1}, 0.2, 60.0),
        s("T_upl_low", {"uprl": 0.8, "xdrive": 0.2}, 0.0, 400.0), s("T_upl_mid", {"uprl": 1.0}, 0.0, 500.0),
        s("T_upl_top", {"uprl": 0.7, "beam": 0.3}, 0.0, 500.0),
        s("T_upr_low", {"uprr": 0.8, "xdrive": 0.2}, 0.0, 400.0), s("T_upr_mid", {"uprr": 1.0}, 0.0, 500.0),
        s("T_upr_top", {"uprr": 0.7, "beam": 0.3}, 0.0, 500.0),
        s("T_beam_left", {"beam": 0.8, "uprl": 0.2}, 0.0, 600.0), s("T_beam_mid", {"beam": 1.0}, 0.0, 700.0),
        s("T_beam_right", {"beam": 0.8, "uprr": 0.2}, 0.0, 600.0),
        s("T_carriage", {"carriage": 0.9, "beam": 0.1}, 0.0, 300.0),
        s("T_ram_top", {"ram": 0.7, "carriage": 0.3}, 0.0, 250.0),
        s("T_ram_low", {"ram": 0.8, "spindle": 0.2}, 0.0, 200.0),
        s("T_spindle_front", {"spindle": 1.0}, 0.0, 60.0),
        s("T_spindle_rear", {"spindle": 0.7, "ram": 0.3}, 0.0, 90.0),
        s("T_head", {"head": 1.0}, 0.0, 80.0), s("T_coolant", {"coolant": 1.0}, 0.0, 150.0),
    ]


def machine() -> Machine:
    from thermocomp.apps.sim.thermoelastic import ThermoelasticMap
    sources = [
        SpeedLosses("motor_spindle", {"spindle": 0.8, "ram": 0.2}, signal=SPEED,
                    idle_W=40.0, linear_W_per_krpm=8.0, quadratic_W_per_krpm2=0.3),
        MovingSource("x_guides", path=("bed1", "bed2", "bed3"), positions_mm=(0.0, 1500.0, 3000.0),
                     signal=XPOS, when="S_on", power_W=120.0),
        ConstantWhileRunning("x_linear_motors", {"xdrive": 1.0}, power_W=160.0, when="S_on"),
        ConstantWhileRunning("fork_head", {"head": 0.8, "spindle": 0.2}, power_W=90.0, when=HEAD),
        ConstantWhileRunning("coolant_pump", {"coolant": 1.0}, power_W=70.0, when=SPEED),
    ]
    errors = ThermoelasticMap(
        linear={"E_X": {"uprl": 2.4, "uprr": 1.6, "bed2": 1.4, "beam": -0.8, "ram": 0.9},
                "E_Y": {"beam": 6.5, "carriage": 1.8, "uprl": -1.2, "uprr": 1.2, "head": 1.1},
                "E_Z": {"ram": -5.5, "spindle": -3.8, "head": -1.6, "uprl": 2.1, "uprr": 2.3,
                        "beam": 1.1}},
        reference_c=20.0)
    return Machine(network(), sources, sensors(), errors)


def run_programme(rng: np.random.Generator, period: float) -> dict:
    """The run's states as functions of the time since its start (s): jobs until 20:00, then idle."""
    shift = SHIFT_END_H * 3600.0
    edges, speed, xpos, head, t = [0.0], [], [], [], 0.0
    while t < shift:
        speed.append(float(rng.choice(SPEEDS, p=[.15, .15, .2, .2, .2, .1])))
        xpos.append(float(np.round(rng.uniform(100.0, 2900.0), -1)))
        head.append(float(rng.random() < 0.4))
        t = min(shift, t + period * round(rng.uniform(30.0, 150.0) * 60.0 / period))
        edges.append(t)
    job_edges = np.asarray(edges)

    def job(values, after):
        vals = np.asarray(values + [after])

        def at(t_rel):
            return vals[np.clip(np.searchsorted(job_edges, np.asarray(t_rel, float), side="right") - 1,
                                0, len(vals) - 1)]
        return at
    return {SPEED: job(speed, 0.0), XPOS: job(xpos, xpos[-1]), HEAD: job(head, 0.0),
            "S_on": lambda t_rel: (np.asarray(t_rel, float) < shift).astype(float)}


def run_starts() -> list[datetime]:
    """Each run's start, 06:00 local time, three weeks apart (aware datetimes)."""
    return [(FIRST_RUN.replace(tzinfo=None) + timedelta(days=EVERY_DAYS * k)).replace(tzinfo=LOCAL)
            for k in range(RUNS)]


@dataclass(eq=False, repr=False, kw_only=True)
class Gantry76(DeclaredScenario):
    name = "gantry76"
    year: int = 2027
    sample_period_s: float = 10.0
    run_h: float = RUN_H

    def machine(self):
        return machine()

    def plans(self, rng):
        period = float(self.sample_period_s)
        hall = AmbientModel(annual_mean_c=15.5, annual_amplitude_c=7.0, coldest_day=25.0,
                            daily_amplitude_c=1.5, daily_peak_hour=15.0, drift_sd_c=0.6, drift_tau_h=8.0)
        year0 = datetime(int(self.year), 1, 1, tzinfo=ZoneInfo("UTC"))
        plans = []
        for k, start in enumerate(run_starts()):
            r = np.random.default_rng([int(self.seed), 76, k])
            plans.append(CampaignPlan(
                cid=f"run{k + 1}", split="train", start_s=(start - year0).total_seconds(),
                duration_s=float(self.run_h) * 3600.0 - period, rng=r, ambient=hall, programme=None,
                states=run_programme(r, period), written=(SPEED, XPOS, HEAD),
                sample_period_s=period, error_period_s=None, cooldown_s=8 * 3600.0,
                notes=f"run {k + 1}"))
        return plans
