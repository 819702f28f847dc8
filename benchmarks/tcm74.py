"""tcm74: a travelling-column milling machine on a 6 m bed, pendulum machining in two work zones
(stranger74).

Nodes: four bed segments (bed1 .. bed4 along X), the travelling column, the ram, the spindle, the
X linear motor, the hydraulic unit; hall air. 22 sensors (two per bed segment, column top and
bottom, ram front and rear, spindle front and rear, motor, hydraulic oil, hall air at both ends,
floor, coolant return, cabinet), 30 s cadence, one 48 h record. States: the spindle speed
S_n_rpm and the work zone (S_zone1 over bed1/bed2, S_zone2 over bed3/bed4; the column's X drive
heats the segments it runs over).
"""
from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime

import numpy as np

from thermocomp.apps.sim.ambient import AmbientModel
from thermocomp.apps.sim.campaign import Machine
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.scenario import CampaignPlan, DeclaredScenario
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import ConstantWhileRunning, SpeedLosses

N, Z1, Z2 = "S_n_rpm", "S_zone1", "S_zone2"
START = datetime(2027, 3, 8, 6)

NODES = (Node("bed1", 1.5e6, 12.0), Node("bed2", 1.5e6, 12.0), Node("bed3", 1.5e6, 12.0),
         Node("bed4", 1.5e6, 12.0), Node("column", 9e5, 25.0), Node("ram", 2.5e5, 15.0),
         Node("spindle", 4e4, 25.0), Node("motor", 6e4, 20.0), Node("hydraulic", 3e5, 15.0))
LINKS = (Link("bed1", "bed2", 8.0), Link("bed2", "bed3", 8.0), Link("bed3", "bed4", 8.0),
         Link("bed2", "column", 4.0), Link("bed3", "column", 4.0), Link("column", "ram", 6.0),
         Link("ram", "spindle", 10.0), Link("motor", "column", 5.0), Link("hydraulic", "column", 3.0),
         Link("motor", "bed2", 2.0), Link("motor", "bed3", 2.0))


def machine() -> Machine:
    from thermocomp.apps.sim.thermoelastic import ThermoelasticMap
    sources = [
        SpeedLosses("spindle", {"spindle": 0.7, "ram": 0.3}, signal=N,
                    idle_W=40.0, linear_W_per_krpm=30.0, quadratic_W_per_krpm2=6.0),
        ConstantWhileRunning("x_drive_zone1", {"motor": 0.5, "bed1": 0.25, "bed2": 0.25},
                             power_W=500.0, when=Z1),
        ConstantWhileRunning("x_drive_zone2", {"motor": 0.5, "bed3": 0.25, "bed4": 0.25},
                             power_W=500.0, when=Z2),
        ConstantWhileRunning("hydraulics", {"hydraulic": 1.0}, power_W=250.0, when=N),
    ]
    s = TemperatureSensor
    sensors = [
        s("T_bed1a", {"bed1": 1.0}, 0.1, 600.0), s("T_bed1b", {"bed1": 0.9, AMBIENT: 0.1}, -0.2, 900.0),
        s("T_bed2a", {"bed2": 1.0}, 0.0, 600.0), s("T_bed2b", {"bed2": 0.9, AMBIENT: 0.1}, 0.1, 900.0),
        s("T_bed3a", {"bed3": 1.0}, 0.2, 600.0), s("T_bed3b", {"bed3": 0.9, AMBIENT: 0.1}, 0.0, 900.0),
        s("T_bed4a", {"bed4": 1.0}, -0.1, 600.0), s("T_bed4b", {"bed4": 0.9, AMBIENT: 0.1}, 0.0, 900.0),
        s("T_col_top", {"column": 0.8, "ram": 0.2}, 0.0, 400.0),
        s("T_col_bot", {"column": 0.7, "motor": 0.3}, 0.0, 400.0),
        s("T_ram_front", {"ram": 0.8, "spindle": 0.2}, 0.0, 200.0),
        s("T_ram_rear", {"ram": 0.9, "column": 0.1}, 0.0, 300.0),
        s("T_sp_front", {"spindle": 0.9, "ram": 0.1}, 0.0, 120.0),
        s("T_sp_rear", {"spindle": 0.6, "ram": 0.4}, 0.0, 150.0),
        s("T_motor", {"motor": 1.0}, 0.0, 60.0),
        s("T_hyd", {"hydraulic": 1.0}, 0.0, 60.0),
        s("T_hall_left", {AMBIENT: 1.0}, 0.3, 120.0), s("T_hall_right", {AMBIENT: 1.0}, -0.3, 120.0),
        s("T_floor", {AMBIENT: 0.5, "bed1": 0.25, "bed4": 0.25}, 0.0, 1800.0),
        s("T_coolant", {"spindle": 0.2, AMBIENT: 0.8}, 0.0, 300.0),
        s("T_cabinet", {AMBIENT: 0.7, "hydraulic": 0.3}, 0.0, 600.0),
        s("T_hall_mid", {AMBIENT: 1.0}, 0.0, 200.0),
    ]
    errors = ThermoelasticMap(
        linear={"E_X": {"bed1": 3.0, "bed2": 3.0, "bed3": 3.0, "bed4": 3.0, "column": -1.0},
                "E_Y": {"column": 2.0, "ram": -1.5, "motor": 1.0},
                "E_Z": {"ram": -4.0, "spindle": -2.0, "column": -3.0, "bed2": 1.0, "bed3": 1.0}},
        reference_c=20.0)
    return Machine(ThermalNetwork(NODES, LINKS), sources, sensors, errors)


def _steps(rng, period, duration, values):
    out, t = [(0.0, values[0])], 0.0
    while t < duration:
        out.append((period * round(t / period), values[int(rng.integers(len(values)))]))
        t += rng.uniform(0.5, 3.0) * 3600
    times = np.array([a for a, _ in out])
    vals = np.array([b for _, b in out])

    def at(t_rel):
        idx = np.searchsorted(times, np.asarray(t_rel, float), side="right") - 1
        return vals[np.clip(idx, 0, len(vals) - 1)]
    return at


@dataclass(eq=False, repr=False, kw_only=True)
class Tcm74(DeclaredScenario):
    name = "tcm74"
    record_h: float = 48.0
    sample_period_s: float = 30.0

    def machine(self):
        return machine()

    def plans(self, rng):
        period = float(self.sample_period_s)
        duration = float(self.record_h) * 3600.0 - period
        hall = AmbientModel(annual_mean_c=20.0, annual_amplitude_c=0.0, daily_amplitude_c=2.0,
                            daily_peak_hour=15.0, drift_sd_c=0.6, drift_tau_h=10.0)
        r = np.random.default_rng([int(self.seed), 74])
        n = _steps(r, period, duration, [0, 2000, 4000, 6000, 8000])
        zone = _steps(r, period, duration, [0, 1, 2])
        return [CampaignPlan(cid="rec", split="train",
                             start_s=(START - datetime(2027, 1, 1)).total_seconds(),
                             duration_s=duration, rng=r, ambient=hall, programme=None,
                             states={N: n, Z1: lambda t: (zone(t) == 1).astype(float),
                                     Z2: lambda t: (zone(t) == 2).astype(float)},
                             written=(N, Z1, Z2), sample_period_s=period,
                             error_period_s=None, cooldown_s=86400.0, notes="one record")]
