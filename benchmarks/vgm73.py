"""vgm73: a vertical grinding machine with a rotary table and a hydrostatic oil unit (stranger73;
copied from its scratch for bench_auto73).

Nodes: base, column, wheelhead, wheel_bearing, table, oil (hydrostatic table bearing oil), hall
air. Five sensors (no air sensor on the machine's own list but the hall's), 15 s cadence, one
record of 36 h (a lab's single export), state: the wheel speed S_n_rpm and the table speed S_tab_rpm.
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

N, TAB = "S_n_rpm", "S_tab_rpm"
START = datetime(2027, 2, 1, 6)

NODES = (Node("base", 2.0e6, 18.0), Node("column", 8e5, 10.0), Node("wheelhead", 2e5, 5.0),
         Node("wheel_bearing", 3e4, 1.5), Node("table", 4e5, 6.0), Node("oil", 3e5, 8.0))
LINKS = (Link("base", "column", 12.0), Link("column", "wheelhead", 6.0),
         Link("wheelhead", "wheel_bearing", 4.0), Link("base", "table", 10.0),
         Link("table", "oil", 25.0), Link("oil", "base", 8.0))


def machine() -> Machine:
    from thermocomp.apps.sim.thermoelastic import ThermoelasticMap
    sources = [
        SpeedLosses("wheel", {"wheel_bearing": 0.6, "wheelhead": 0.4}, signal=N,
                    idle_W=50.0, linear_W_per_krpm=60.0, quadratic_W_per_krpm2=20.0),
        SpeedLosses("table_drive", {"oil": 0.8, "table": 0.2}, signal=TAB,
                    idle_W=30.0, linear_W_per_krpm=2000.0, quadratic_W_per_krpm2=0.0),
        ConstantWhileRunning("pump", {"oil": 1.0}, power_W=150.0, when=TAB),
    ]
    sensors = [
        TemperatureSensor("T_hall", {AMBIENT: 1.0}, 0.0, lag_s=120.0),
        TemperatureSensor("T_spindle", {"wheel_bearing": 0.7, "wheelhead": 0.3}, 0.0, lag_s=200.0),
        TemperatureSensor("T_column", {"column": 1.0}, 0.0, lag_s=600.0),
        TemperatureSensor("T_oil", {"oil": 1.0}, 0.0, lag_s=60.0),
        TemperatureSensor("T_base", {"base": 0.8, "table": 0.2}, 0.0, lag_s=900.0),
    ]
    errors = ThermoelasticMap(
        linear={"E_Z": {"wheel_bearing": -6.0, "wheelhead": -4.0, "column": -5.0, "table": 3.0,
                        "oil": 2.0},
                "E_X": {"column": 2.5, "base": -1.0, "wheelhead": 1.5}},
        reference_c=20.0)
    return Machine(ThermalNetwork(NODES, LINKS), sources, sensors, errors)


def steps(rng, period, duration, values):
    def grid(t):
        return period * round(t / period)
    out, t = [(0.0, 0.0)], 0.0
    while t < duration:
        length = rng.uniform(0.5, 3.0) * 3600
        out.append((grid(t), float(rng.choice(values))))
        t += length
    return out


def held(step_list):
    times = np.array([s for s, _ in step_list])
    vals = np.array([v for _, v in step_list])

    def at(t_rel):
        idx = np.searchsorted(times, np.asarray(t_rel, float), side="right") - 1
        return vals[np.clip(idx, 0, len(vals) - 1)]
    return at


@dataclass(eq=False, repr=False, kw_only=True)
class Vgm73(DeclaredScenario):
    name = "vgm73"
    record_h: float = 36.0
    sample_period_s: float = 15.0

    def machine(self):
        return machine()

    def plans(self, rng):
        period = float(self.sample_period_s)
        duration = float(self.record_h) * 3600.0 - period
        hall = AmbientModel(annual_mean_c=19.0, annual_amplitude_c=0.0, daily_amplitude_c=1.5,
                            daily_peak_hour=14.0, drift_sd_c=0.5, drift_tau_h=12.0)
        r = np.random.default_rng([int(self.seed), 73])
        n = held(steps(r, period, duration, [0, 1500, 2500, 3500, 4500]))
        tab = held(steps(r, period, duration, [0, 0.02, 0.05, 0.1]))
        return [CampaignPlan(cid="rec", split="train",
                             start_s=(START - datetime(2027, 1, 1)).total_seconds(),
                             duration_s=duration, rng=r, ambient=hall, programme=None,
                             states={N: n, TAB: tab}, written=(N, TAB), sample_period_s=period,
                             error_period_s=None, cooldown_s=86400.0, notes="one record")]


def lab_record(seed: int):
    """Seed ``seed``'s record as the lab exports carry it (their noise and quantisation)."""
    ds, _ = Vgm73(seed=seed, temp_noise_c=0.03, temp_quantum_c=0.01, error_noise_um=0.2,
                  error_quantum_um=0.1).generate()
    return ds.campaigns["rec"]
