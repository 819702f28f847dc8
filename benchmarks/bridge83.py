"""bridge83: a double-column (bridge) milling machine whose TCP drift a probing cycle measures
(stranger83).

Not the project's simulator: its own lumped network (implicit Euler, numpy) and kinematics.
A double-column machining centre: the table moves in X on the bed, a crossrail spans the two
columns (3.2 m apart, 2.5 m high), the saddle moves in Y along the crossrail, the ram in Z
carries a motor spindle; the hydraulic unit (the ram's counterbalance) stands against the RIGHT
column and warms it, the LEFT column stands by the hall's gate, in the afternoon sun through its
windows: the two columns are heated unequally.  The hall has no air conditioning (18.5-22.5 °C
over the day, the weather's drift).

The lab's test: day runs of 10 h from 06:00, the machine cutting the shop's parts; every 15 min
the NC runs a probing cycle on one of three spheres on the table (Y = -1200, 0, +1200 mm, in
turn): the TCP's dX / dY / dZ measured then, nothing in between.

Errors (µm, 20 °C reference; the sphere at Y): the ram's and the spindle's growth, the columns'
mean against the bed's (dZ); PLANTED: the crossrail tilted by the columns' unequal growth,
``Y / span x (right - left)`` column growth on dZ, and the crossrail's growth from its right end
(where the Y screw is fixed) ``(Y + 1600) x the rail's rise`` on dY; the saddle's and the
ram's gradient and the table's growth on dX.
"""
from __future__ import annotations

from datetime import datetime

import numpy as np
from _lumped import lagged_readings, laplacian
from _runs import day_runs

ALPHA = 11.5e-6
STEP_S = 60.0
PROBE_EVERY = 15                        # samples between probing cycles (15 min)
SPHERES_Y = (-1200.0, 0.0, 1200.0)      # mm, probed in turn
FIRST_DAY = datetime(2027, 9, 13)       # Monday, local time
DAYS, SPIN_UP_DAYS = 19, 3
RUN_DAYS = (0, 1, 2, 3, 4, 7, 8, 10, 14, 15, 16, 17)
RUN_HOURS = (6.0, 16.0)
SPAN, HEIGHT, RAM, HALF_RAIL = 3200.0, 2500.0, 900.0, 1600.0     # mm
NODES = ("bed", "table", "col_l", "col_r", "rail", "saddle", "ram", "spindle", "motor",
         "hydraulic", "x_drive")
C = np.array([6.0e7, 8.0e6, 1.6e7, 1.6e7, 1.2e7, 1.5e6, 8.0e5, 5.0e4, 8.0e4, 6.0e5, 3.0e4])
H_AIR = np.array([80.0, 20.0, 30.0, 30.0, 25.0, 6.0, 6.0, 0.6, 2.0, 8.0, 1.0])
LINKS = (("bed", "table", 15.0), ("bed", "col_l", 25.0), ("bed", "col_r", 25.0),
         ("col_l", "rail", 10.0), ("col_r", "rail", 10.0), ("rail", "saddle", 8.0),
         ("saddle", "ram", 6.0), ("ram", "spindle", 3.0), ("spindle", "motor", 4.0),
         ("hydraulic", "col_r", 12.0), ("bed", "x_drive", 2.0), ("table", "x_drive", 2.0))
SENSORS = (("AIR", "air", 90.0), ("AIR_GATE", "gate", 90.0), ("BED", {"bed": 1.0}, 900.0),
           ("TABLE", {"table": 1.0}, 600.0), ("COL_L", {"col_l": 1.0}, 900.0),
           ("COL_R", {"col_r": 1.0}, 900.0), ("RAIL", {"rail": 1.0}, 900.0),
           ("SADDLE", {"saddle": 1.0}, 600.0), ("RAM", {"ram": 1.0}, 400.0),
           ("SPINDLE", {"spindle": 0.7, "ram": 0.3}, 150.0), ("MOTOR", {"motor": 1.0}, 120.0),
           ("HYD_OIL", {"hydraulic": 1.0}, 120.0), ("X_NUT", {"x_drive": 0.8, "table": 0.2}, 150.0))


def _i(name: str) -> int:
    return NODES.index(name)


def hall_air(t_s: np.ndarray, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """The hall's air (°C: 18.5 at 05:00, 22.5 at 15:00, over a drift) and the air by the gate
    (the afternoon sun through its windows, more on clear days, up to 4 K more)."""
    hour = (t_s % 86400.0) / 3600.0
    day = 20.5 + 2.0 * np.sin(2 * np.pi * (hour - 9.0) / 24.0)
    ou = np.exp(-STEP_S / (3.0 * 86400.0))
    z, drift = 0.0, np.empty_like(t_s)
    for k, e in enumerate(rng.standard_normal(t_s.size)):
        z = z * ou + np.sqrt(1 - ou**2) * e
        drift[k] = z
    air = day + 0.8 * drift
    clear = rng.uniform(0.2, 1.0, int(t_s[-1] // 86400.0) + SPIN_UP_DAYS + 2)
    sun = np.clip(np.sin(np.pi * (hour - 11.0) / 7.0), 0.0, None)
    return air, air + 4.0 * sun * clear[(t_s // 86400.0).astype(int) + SPIN_UP_DAYS]


def programme(t_s: np.ndarray, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """States a step: on (run days 06:00-16:00, other weekdays 06:00-14:00 unlogged), the spindle's
    speed (rpm), the axes' motion (0..1), the sphere probed (its Y, mm, at each cycle)."""
    n = t_s.size
    out = {k: np.zeros(n) for k in ("on", "speed", "xmove", "ymove", "zmove")}
    day = np.floor(t_s / 86400.0)
    hour = (t_s % 86400.0) / 3600.0
    k = 0
    while k < n:
        d, h = int(day[k]), hour[k]
        on = (d in RUN_DAYS and RUN_HOURS[0] <= h < RUN_HOURS[1]) or (
            d not in RUN_DAYS and d % 7 < 5 and 6.0 <= h < 14.0)
        if not on:
            k += 1
            continue
        stop = min(k + int(rng.uniform(20.0, 90.0) * 60.0 / STEP_S), n)
        out["on"][k:stop] = 1.0
        if rng.random() < 0.8:
            out["speed"][k:stop] = np.round(rng.uniform(500.0, 6000.0), -2)
            for key in ("xmove", "ymove", "zmove"):
                out[key][k:stop] = rng.uniform(0.05, 0.6)
        k = max(stop, k + 1)
    cycle = np.floor(t_s / (PROBE_EVERY * STEP_S)).astype(int)
    out["y"] = np.asarray(SPHERES_Y)[cycle % len(SPHERES_Y)]
    return out


def simulate(seed: int) -> dict[str, np.ndarray]:
    """The record at STEP_S, spin-up dropped: ``t``, ``air``, ``T``, ``sensors``, states, and the
    TCP errors ``E_dX`` / ``E_dY`` / ``E_dZ`` (µm, the probe's noise, every sample at the sphere
    of its cycle: the bench keeps the probing cycles' rows)."""
    rng = np.random.default_rng([seed, 83])
    t = np.arange(-SPIN_UP_DAYS * 86400.0, DAYS * 86400.0, STEP_S)
    air, gate = hall_air(t, rng)
    st = programme(t, rng)
    g = laplacian(list(NODES), LINKS, H_AIR)
    inv = np.linalg.inv(np.diag(C / STEP_S) + g)
    s = st["speed"] / 6000.0
    q = np.zeros((t.size, len(NODES)))
    q[:, _i("spindle")] = 80.0 * s ** 1.5
    q[:, _i("motor")] = 40.0 * st["on"] + 200.0 * s
    q[:, _i("x_drive")] = 30.0 * st["xmove"]
    q[:, _i("saddle")] = 40.0 * st["ymove"]
    q[:, _i("ram")] = 25.0 * st["zmove"]
    q[:, _i("hydraulic")] = 120.0 * st["on"] + 80.0
    air_of = np.tile(air[:, None], (1, len(NODES)))
    air_of[:, _i("col_l")] = gate                 # the left column by the gate, in the sun
    temp = np.full(len(NODES), air[0])
    temps = np.empty((t.size, len(NODES)))
    for k in range(t.size):
        temp = inv @ (C / STEP_S * temp + q[k] + H_AIR * air_of[k])
        temps[k] = temp
    keep = t >= 0
    t, air, gate, temps = t[keep], air[keep], gate[keep], temps[keep]
    st = {k: v[keep] for k, v in st.items()}
    sensors = lagged_readings(temps, {"air": air, "gate": gate}, SENSORS, list(NODES), STEP_S,
                              0.02, 3, rng)
    return {"t": t, "air": air, "T": temps, **st, "sensors": sensors, **_errors(temps, st, rng)}


def _errors(temps: np.ndarray, st: dict, rng: np.random.Generator) -> dict[str, np.ndarray]:
    d = temps - 20.0
    n = {name: d[:, _i(name)] for name in NODES}
    y = st["y"]
    tilt = ALPHA * HEIGHT * (n["col_r"] - n["col_l"]) * y / SPAN
    dx = 1e3 * (ALPHA * 600.0 * (n["ram"] - n["saddle"]) + ALPHA * 400.0 * n["table"]
                - ALPHA * 200.0 * n["bed"])
    dy = 1e3 * (ALPHA * (y + HALF_RAIL) * n["rail"] * 0.5
                + ALPHA * HEIGHT * 0.05 * (n["col_r"] - n["col_l"]))
    dz = 1e3 * (-ALPHA * RAM * n["ram"] - ALPHA * 150.0 * n["spindle"]
                + ALPHA * HEIGHT * 0.5 * (n["col_l"] + n["col_r"]) - ALPHA * 600.0 * n["bed"]
                + tilt)
    noise = 0.3
    return {f"E_d{k}": v + noise * rng.standard_normal(v.size)
            for k, v in (("X", dx), ("Y", dy), ("Z", dz))}


def run_windows() -> list[tuple[datetime, slice]]:
    """Per run: its local start and its slice of ``simulate``'s rows."""
    return day_runs(FIRST_DAY, RUN_DAYS, RUN_HOURS, STEP_S)
