"""edm81: a wire EDM with its dielectric chiller in a shop without air conditioning (stranger81).

Not the project's simulator: its own lumped network (implicit Euler, numpy) and kinematics.
A wire-cut EDM: a cast base on a foundation, a Y saddle and an X table on ball screws (each
screw heated by its nut while its axis moves, grown from a fixed bearing at its zero end), a
work tank on the table filled with de-ionised water, the lower arm reaching into the tank
through its wall (under water while the tank is full), a C-frame column behind carrying the
upper arm and its Z head (the upper guide's height set per job to the part's height, 0-200 mm),
a generator cabinet beside the machine and the dielectric unit: a reservoir whose chiller holds
the water at 20.0 °C by on/off control (hysteresis +-0.3 K, 3.5 kW of cooling while on).  The
shop has no air conditioning: its air follows the day (morning 18 °C, afternoon 23 °C) and the
weather (a few days' drift).  Unattended cutting: jobs run through the night on the days the
lab measured (24 h runs), the machine off at weekends.

Errors of the wire against a reference pin in the tank (µm, 20 °C reference), from the
kinematics: the X and Y screws grow from their fixed bearings (dX: X * dT_xscrew, dY: Y *
dT_yscrew: the planted position effects); the upper arm (along Y, 420 mm) grows with its own
temperature and the lower arm (400 mm) with the water's: their difference moves the wire in Y
(and tilts it, the tilt times the upper guide's height Z: a second position effect, on dY);
the column's front-rear difference bends the C-frame (dY, with the Z head's height); the table
and base grow in X from the reference pin's line.
"""
from __future__ import annotations

from datetime import datetime

import numpy as np
from _lumped import lagged_readings, laplacian
from _runs import day_runs

ALPHA = 11.5e-6                        # cast iron / steel, 1/K
STEP_S = 10.0                          # the network's step and the trace's period
FIRST_DAY = datetime(2027, 5, 10)      # Monday 00:00 local time (CEST all along)
DAYS, SPIN_UP_DAYS = 19, 3
RUN_DAYS = (0, 1, 3, 4, 7, 8, 9, 11, 14, 15, 16, 17)     # each a 22 h run from 07:00
RUN_HOURS = (7.0, 29.0)
NODES = ("foundation", "base", "saddle", "yscrew", "table", "xscrew", "water", "reservoir",
         "lowerarm", "col_front", "col_rear", "upperarm", "zhead", "generator")
C = np.array([6.0e7, 2.0e7, 2.5e6, 3.0e4, 2.0e6, 4.0e4, 1.4e6, 2.5e6, 4.0e5, 4.0e6, 4.0e6,
              1.2e6, 3.0e5, 4.0e5])                                               # J/K
H_AIR = np.array([70.0, 45.0, 14.0, 2.0, 12.0, 2.5, 12.0, 10.0, 2.0, 16.0, 16.0, 10.0, 4.0,
                  25.0])                                                          # W/K
LINKS = (("base", "foundation", 60.0), ("base", "saddle", 12.0), ("saddle", "yscrew", 2.5),
         ("base", "yscrew", 1.5), ("saddle", "table", 10.0), ("table", "xscrew", 3.0),
         ("saddle", "xscrew", 1.2), ("table", "water", 30.0), ("water", "lowerarm", 25.0),
         ("base", "col_front", 10.0), ("base", "col_rear", 10.0), ("col_front", "col_rear", 12.0),
         ("col_front", "upperarm", 8.0), ("upperarm", "zhead", 6.0), ("base", "lowerarm", 4.0),
         ("generator", "col_rear", 3.0))
UPPER_ARM, LOWER_ARM, COL_DEPTH, COL_H = 420.0, 400.0, 600.0, 900.0      # mm
SET_C, BAND_K, CHILL_W = 20.0, 0.3, 3500.0
# sensors: (the PLC's variable the lab traced, {node: weight} or "air"/"floor", lag s)
SENSORS = (("T_HALLE", "air", 90.0), ("T_BODEN", "floor", 300.0),
           ("T_FUNDAMENT", {"foundation": 0.8, "base": 0.2}, 1200.0),
           ("T_BETT_L", {"base": 1.0}, 600.0), ("T_BETT_R", {"base": 0.9, "generator": 0.1}, 600.0),
           ("T_SCHLITTEN_Y", {"saddle": 1.0}, 400.0),
           ("T_MUTTER_Y", {"yscrew": 0.8, "saddle": 0.2}, 150.0),
           ("T_TISCH_X", {"table": 1.0}, 400.0), ("T_MUTTER_X", {"xscrew": 0.8, "table": 0.2}, 150.0),
           ("T_DIELEKTRIKUM", {"water": 1.0}, 60.0), ("T_VORRAT", {"reservoir": 1.0}, 120.0),
           ("T_UNTERARM", {"lowerarm": 1.0}, 200.0),
           ("T_STAENDER_V", {"col_front": 0.8, "base": 0.2}, 500.0),
           ("T_STAENDER_H", {"col_rear": 1.0}, 500.0),
           ("T_OBERARM", {"upperarm": 1.0}, 300.0), ("T_Z_KOPF", {"zhead": 1.0}, 200.0),
           ("T_GENERATOR", {"generator": 1.0}, 150.0))


def _index(name: str) -> int:
    return NODES.index(name)


def shop_air(t_s: np.ndarray, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """The shop's air (°C) at the machine's head and at its floor: the day's swing (18 °C at 05:00,
    23 °C at 15:00) over the weather's drift, the floor lagging 30 min and 0.8 K cooler."""
    hour = (t_s % 86400.0) / 3600.0
    day = 20.5 + 2.5 * np.sin(2 * np.pi * (hour - 9.0) / 24.0)
    drift, ou = np.empty_like(t_s), np.exp(-STEP_S / (2.5 * 86400.0))
    z = 0.0
    for k in range(t_s.size):
        z = z * ou + np.sqrt(1 - ou**2) * rng.standard_normal()
        drift[k] = z
    air = day + 1.2 * drift
    floor = np.empty_like(air)
    a = 1.0 - np.exp(-STEP_S / 1800.0)
    floor[0] = air[0] - 0.8
    for k in range(1, air.size):
        floor[k] = floor[k - 1] + a * (air[k] - 0.8 - floor[k - 1])
    return air, floor


def programme(t_s: np.ndarray, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """States per step: on (the machine and its pumps, on a run day 07:00 to 05:00 the next
    morning, any other weekday 07:00-16:00: the shop cut parts the lab did not log), the
    generator's power (kW, while cutting), X / Y / Z mm, X and Y moving (0..1)."""
    n = t_s.size
    out = {k: np.zeros(n) for k in ("on", "power", "x", "y", "z", "xmove", "ymove", "flush")}
    out["x"][:], out["y"][:], out["z"][:] = 200.0, 150.0, 60.0
    day = np.floor(t_s / 86400.0)
    hour = (t_s % 86400.0) / 3600.0
    k = 0
    while k < n:
        d, h = int(day[k]), hour[k]
        on_run = d in RUN_DAYS and h >= 7.0 or (d - 1) in RUN_DAYS and h < 5.0
        on_shop = d % 7 < 5 and 7.0 <= h < 16.0
        if not (on_run or on_shop):
            for key in ("x", "y", "z"):
                out[key][k] = out[key][k - 1] if k else out[key][k]
            k += 1
            continue
        length = int(rng.uniform(40.0, 180.0) * 60.0 / STEP_S)
        setup = int(rng.uniform(8.0, 25.0) * 60.0 / STEP_S)
        stop = min(k + setup + length, n)
        span, job = slice(k, stop), slice(min(k + setup, stop), stop)
        out["on"][span] = 1.0
        out["x"][span] = np.round(rng.uniform(20.0, 380.0), -1)
        out["y"][span] = np.round(rng.uniform(20.0, 280.0), -1)
        out["z"][span] = np.round(rng.uniform(20.0, 200.0), -1)
        if rng.random() < 0.9:
            out["power"][job] = np.round(rng.uniform(0.6, 3.0), 1)
            out["xmove"][job] = rng.uniform(0.1, 0.6)
            out["ymove"][job] = rng.uniform(0.1, 0.6)
            out["flush"][job] = np.round(rng.uniform(2.0, 14.0), 0)
        k = max(stop, k + 1)
    return out


def simulate(seed: int) -> dict[str, np.ndarray]:
    """The whole record at STEP_S, spin-up dropped: ``t`` (s since FIRST_DAY, local clock),
    ``air``, node temperatures ``T``, the sensors' ``sensors``, the states, ``chiller`` (0/1)
    and the errors ``E_dX`` / ``E_dY`` (µm, with the measurement's noise)."""
    rng = np.random.default_rng([seed, 81])
    t = np.arange(-SPIN_UP_DAYS * 86400.0, DAYS * 86400.0, STEP_S)
    air, floor = shop_air(t, rng)
    st = programme(t, rng)
    inv = np.linalg.inv(np.diag(C / STEP_S) + laplacian(NODES, LINKS, H_AIR))
    low = np.array([n in ("foundation", "base", "reservoir") for n in NODES])
    temp = np.full(len(NODES), air[0])
    temps = np.empty((t.size, len(NODES)))
    chiller = np.zeros(t.size)
    q = np.zeros((t.size, len(NODES)))
    q[:, _index("water")] = 450.0 * st["power"] + 15.0 * st["flush"]
    q[:, _index("generator")] = 120.0 * st["on"] + 180.0 * st["power"]
    q[:, _index("xscrew")] = 30.0 * st["xmove"]
    q[:, _index("yscrew")] = 25.0 * st["ymove"]
    q[:, _index("zhead")] = 12.0 * st["on"]
    w, r = _index("water"), _index("reservoir")
    cooling = False
    for k in range(t.size):
        amb = np.where(low, floor[k], air[k])
        qk = q[k].copy()
        if st["on"][k]:                  # the pumps exchange the tank's water with the reservoir
            qk[w] += 400.0 * (temp[r] - temp[w])
            qk[r] += 400.0 * (temp[w] - temp[r])
        cooling = temp[r] > SET_C + BAND_K or (cooling and temp[r] > SET_C - BAND_K)
        chiller[k] = float(cooling)
        qk[r] -= CHILL_W * cooling
        temp = inv @ (C / STEP_S * temp + qk + H_AIR * amb)
        temps[k] = temp
    keep = t >= 0
    t, air, floor, temps, chiller = t[keep], air[keep], floor[keep], temps[keep], chiller[keep]
    st = {k: v[keep] for k, v in st.items()}
    return {"t": t, "air": air, "floor": floor, "T": temps, "chiller": chiller, **st,
            "sensors": lagged_readings(temps, {"air": air, "floor": floor}, SENSORS, NODES, STEP_S,
                                       0.015, 2, rng),
            **_errors(temps, st, rng)}


def _errors(temps: np.ndarray, st: dict, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """dX, dY (µm) of the wire against the reference pin (module docstring)."""
    d = temps - 20.0
    n = {name: d[:, _index(name)] for name in NODES}
    kappa = ALPHA * (n["col_front"] - n["col_rear"]) / COL_DEPTH       # 1/mm: bends the C-frame
    tilt = ALPHA * (UPPER_ARM * n["upperarm"] - LOWER_ARM * n["lowerarm"]) / 300.0   # rad/mm-ish
    dx = (1e3 * ALPHA * st["x"] * n["xscrew"] + 1e3 * ALPHA * 250.0 * (n["table"] - n["base"])
          + 1e3 * ALPHA * 80.0 * n["zhead"])
    dy = (1e3 * ALPHA * st["y"] * n["yscrew"]
          - 1e3 * ALPHA * (UPPER_ARM * n["upperarm"] - LOWER_ARM * n["lowerarm"])
          + 1e3 * tilt * st["z"] - 1e3 * kappa * COL_H ** 2 / 2
          + 1e3 * ALPHA * 150.0 * (n["col_front"] - n["saddle"]))
    noise = 0.15
    return {f"E_d{a}": v + noise * rng.standard_normal(v.size) for a, v in (("X", dx), ("Y", dy))}


def run_windows() -> list[tuple[datetime, slice]]:
    """Per run: its local start and the slice of ``simulate``'s rows it holds."""
    return day_runs(FIRST_DAY, RUN_DAYS, RUN_HOURS, STEP_S)
