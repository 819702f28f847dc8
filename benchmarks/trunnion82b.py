"""trunnion82b: a 5-axis trunnion machining centre whose TCP drift a probing cycle measures
(stranger82b).

Not the project's simulator: its own lumped network (implicit Euler, numpy) and kinematics.
A vertical machining centre with a swivelling trunnion (A, -30..+110 deg) carrying a rotary
table (C), both driven by torque motors; a motor spindle on a Z ram in a column; X / Y / Z on
ball screws (their nuts heating them while an axis moves); the spindle's coolant jacket held by
a chiller; a hall without air conditioning (19-23 °C over the day, the weather's drift).

The lab's test: day runs of 10 h from 06:00, the machine cutting the shop's parts at programmed
A / C poses; every 15 min the NC runs a probing cycle (a calibrated sphere on the table, touched
by the spindle's probe at the current A / C): the TCP's dX / dY / dZ (µm) measured then, and
nothing in between.

Errors (µm, 20 °C reference): the spindle's and the ram's growth (dZ), the column's tilt (dY),
the X / Y screws' growth with their position (dX: X x the X screw's rise, planted); the A
pivot's height grows with the trunnion's rise and shows on the sphere as its A-angle's
projection (dY: sin A, dZ: cos A x the trunnion's rise, planted); the C table's growth moves the
sphere radially (dX: cos C, dY: sin C x the table's rise).
"""
from __future__ import annotations

from datetime import datetime

import numpy as np
from _lumped import lagged_readings, laplacian
from _runs import day_runs

ALPHA = 11.5e-6
STEP_S = 20.0
PROBE_EVERY = 45                        # samples between probing cycles (15 min)
FIRST_DAY = datetime(2027, 9, 6)        # Monday, local time
DAYS, SPIN_UP_DAYS = 19, 3
RUN_DAYS = (0, 1, 2, 3, 7, 8, 9, 11, 14, 15, 16, 17)
RUN_HOURS = (6.0, 16.0)
NODES = ("bed", "column", "ram", "spindle", "motor", "coolant", "xscrew", "yscrew", "zscrew",
         "trunnion", "a_motor", "table", "c_motor", "cabinet")
C = np.array([3.0e7, 8.0e6, 6.0e5, 4.0e4, 6.0e4, 3.0e5, 1.2e4, 1.5e4, 1.0e4, 6.0e5, 5.0e4,
              2.0e5, 4.0e4, 3.0e5])
H_AIR = np.array([45.0, 25.0, 5.0, 0.5, 1.5, 4.0, 1.0, 1.2, 0.8, 6.0, 1.0, 3.0, 1.0, 8.0])
LINKS = (("bed", "column", 30.0), ("column", "ram", 8.0), ("ram", "spindle", 3.0),
         ("spindle", "motor", 4.0), ("motor", "coolant", 6.0), ("spindle", "coolant", 3.0),
         ("bed", "xscrew", 1.0), ("column", "yscrew", 1.0), ("ram", "zscrew", 1.0),
         ("bed", "trunnion", 10.0), ("trunnion", "a_motor", 3.0), ("trunnion", "table", 4.0),
         ("table", "c_motor", 3.0), ("column", "cabinet", 0.5))
PIVOT, RADIUS, RAM, COLUMN = 180.0, 150.0, 400.0, 900.0     # mm
SENSORS = (("HALLE", "air", 90.0), ("BETT", {"bed": 1.0}, 900.0),
           ("STAENDER_V", {"column": 0.9, "bed": 0.1}, 700.0), ("STAENDER_H", {"column": 1.0}, 900.0),
           ("PINOLE", {"ram": 1.0}, 400.0), ("SPINDEL", {"spindle": 0.7, "ram": 0.3}, 150.0),
           ("MOTOR", {"motor": 1.0}, 120.0), ("KUEHLUNG", {"coolant": 1.0}, 90.0),
           ("MUTTER_X", {"xscrew": 0.8, "bed": 0.2}, 150.0),
           ("MUTTER_Y", {"yscrew": 0.8, "column": 0.2}, 150.0),
           ("MUTTER_Z", {"zscrew": 0.8, "ram": 0.2}, 150.0),
           ("WIEGE", {"trunnion": 1.0}, 400.0), ("A_ANTRIEB", {"a_motor": 1.0}, 120.0),
           ("RUNDTISCH", {"table": 0.9, "trunnion": 0.1}, 300.0),
           ("C_ANTRIEB", {"c_motor": 1.0}, 120.0), ("SCHALTSCHRANK", {"cabinet": 1.0}, 300.0))


def _i(name: str) -> int:
    return NODES.index(name)


def hall_air(t_s: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """The hall's air (°C): the day's swing (19 °C at 05:00, 23 °C at 15:00) over a drift."""
    hour = (t_s % 86400.0) / 3600.0
    day = 21.0 + 2.0 * np.sin(2 * np.pi * (hour - 9.0) / 24.0)
    ou = np.exp(-STEP_S / (3.0 * 86400.0))
    z, drift = 0.0, np.empty_like(t_s)
    for k, e in enumerate(rng.standard_normal(t_s.size)):
        z = z * ou + np.sqrt(1 - ou**2) * e
        drift[k] = z
    return day + 0.8 * drift


def programme(t_s: np.ndarray, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """States a step: on (run days 06:00-16:00, other weekdays 06:00-14:00 unlogged), speed
    (rpm), X / Y mm, A / C deg, the axes' motion (0..1)."""
    n = t_s.size
    keys = ("on", "speed", "x", "y", "a", "c", "xmove", "ymove", "zmove", "amove", "cmove")
    out = {k: np.zeros(n) for k in keys}
    day = np.floor(t_s / 86400.0)
    hour = (t_s % 86400.0) / 3600.0
    k = 0
    while k < n:
        d, h = int(day[k]), hour[k]
        on = (d in RUN_DAYS and RUN_HOURS[0] <= h < RUN_HOURS[1]) or (
            d not in RUN_DAYS and d % 7 < 5 and 6.0 <= h < 14.0)
        if not on:
            for key in ("x", "y", "a", "c"):
                out[key][k] = out[key][k - 1] if k else 0.0
            k += 1
            continue
        stop = min(k + int(rng.uniform(20.0, 80.0) * 60.0 / STEP_S), n)
        span = slice(k, stop)
        out["on"][span] = 1.0
        out["x"][span] = np.round(rng.uniform(-300.0, 300.0), -1)
        out["y"][span] = np.round(rng.uniform(-250.0, 250.0), -1)
        out["a"][span] = np.round(rng.uniform(-30.0, 110.0), -1)
        out["c"][span] = np.round(rng.uniform(0.0, 360.0), -1)
        if rng.random() < 0.85:
            out["speed"][span] = np.round(rng.uniform(2000.0, 15000.0), -2)
            for key in ("xmove", "ymove", "zmove"):
                out[key][span] = rng.uniform(0.05, 0.6)
            out["amove"][span] = rng.uniform(0.0, 0.4)
            out["cmove"][span] = rng.uniform(0.0, 0.8)
        k = max(stop, k + 1)
    return out


def simulate(seed: int) -> dict[str, np.ndarray]:
    """The record at STEP_S, spin-up dropped: ``t``, ``air``, ``T``, ``sensors``, states, and the
    TCP errors ``E_dX`` / ``E_dY`` / ``E_dZ`` (µm, the probe's noise, every sample: the bench
    keeps the probing cycles' rows)."""
    rng = np.random.default_rng([seed, 822])
    t = np.arange(-SPIN_UP_DAYS * 86400.0, DAYS * 86400.0, STEP_S)
    air = hall_air(t, rng)
    st = programme(t, rng)
    inv = np.linalg.inv(np.diag(C / STEP_S) + laplacian(NODES, LINKS, H_AIR))
    s = st["speed"] / 10000.0
    q = np.zeros((t.size, len(NODES)))
    q[:, _i("spindle")] = 90.0 * s ** 1.5
    q[:, _i("motor")] = 40.0 * st["on"] + 250.0 * s
    q[:, _i("xscrew")] = 18.0 * st["xmove"]
    q[:, _i("yscrew")] = 18.0 * st["ymove"]
    q[:, _i("zscrew")] = 14.0 * st["zmove"]
    q[:, _i("a_motor")] = 15.0 * st["on"] + 60.0 * st["amove"]
    q[:, _i("c_motor")] = 10.0 * st["on"] + 45.0 * st["cmove"]
    q[:, _i("cabinet")] = 250.0 * st["on"] + 200.0
    temp = np.full(len(NODES), air[0])
    temps = np.empty((t.size, len(NODES)))
    chill = _i("coolant")
    for k in range(t.size):
        qk = q[k].copy()
        qk[chill] -= min(400.0, max(0.0, 150.0 * (temp[chill] - 21.0))) * st["on"][k]
        temp = inv @ (C / STEP_S * temp + qk + H_AIR * air[k])
        temps[k] = temp
    keep = t >= 0
    t, air, temps = t[keep], air[keep], temps[keep]
    st = {k: v[keep] for k, v in st.items()}
    return {"t": t, "air": air, "T": temps, **st,
            "sensors": lagged_readings(temps, {"air": air}, SENSORS, NODES, STEP_S, 0.02, 1, rng),
            **_errors(temps, st, rng)}


def _errors(temps: np.ndarray, st: dict, rng: np.random.Generator) -> dict[str, np.ndarray]:
    d = temps - 20.0
    n = {name: d[:, _i(name)] for name in NODES}
    a, c = np.radians(st["a"]), np.radians(st["c"])
    pivot = ALPHA * PIVOT * n["trunnion"]
    table = ALPHA * RADIUS * n["table"]
    dx = 1e3 * (ALPHA * (st["x"] + 400.0) * n["xscrew"] + table * np.cos(c)
                - ALPHA * 300.0 * n["bed"])
    dy = 1e3 * (ALPHA * (st["y"] + 300.0) * n["yscrew"] * 0.3 + pivot * np.sin(a)
                + table * np.sin(c) + ALPHA * COLUMN * 0.25 * (n["column"] - n["bed"]))
    dz = 1e3 * (-ALPHA * RAM * n["ram"] - ALPHA * 120.0 * n["spindle"] + pivot * np.cos(a)
                + ALPHA * COLUMN * 0.4 * n["column"] - ALPHA * 500.0 * n["bed"])
    noise = 0.25
    return {f"E_d{k}": v + noise * rng.standard_normal(v.size)
            for k, v in (("X", dx), ("Y", dy), ("Z", dz))}


def run_windows() -> list[tuple[datetime, slice]]:
    """Per run: its local start and its slice of ``simulate``'s rows."""
    return day_runs(FIRST_DAY, RUN_DAYS, RUN_HOURS, STEP_S)
