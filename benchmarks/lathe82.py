"""lathe82: a precision CNC lathe with a chuck and a tailstock in a tempered shop (stranger82).

Not the project's simulator: its own lumped network (implicit Euler, numpy) and kinematics.
A flat-bed precision lathe: a cast bed, a headstock on its left end holding a spindle in a front
and a rear bearing set (the bearings heated by the speed, the belt-driven motor behind), a Z
carriage on a ball screw (its nut heating the screw while Z moves, the screw fixed at the
headstock end), an X cross slide on its own screw (fixed at the rear) carrying the turret, a
tailstock at the bed's right end (its quill's bearing heated while it holds a part), a coolant
tank in the chip conveyor's trough and a hydraulic unit for the chuck.  The shop is tempered
(20.5 +- 1 K over the day, a slow drift of the weather through the walls).  The lab's test:
ISO 230-3-like day runs, a test mandrel between chuck and tailstock, two eddy-current probes on
the turret (dX radial, dZ axial), the spindle run at a programme of speeds, the carriage at
the job's Z.

Errors (µm, 20 °C reference) from the kinematics: the X screw grows from its rear bearing
(dX: X * dT_xscrew), the Z screw from the headstock end (dZ: Z * dT_zscrew: planted position
effects); the mandrel's axis at the probe, Z along the 800 mm between centres, tilts with the
headstock's and the tailstock's rises ((1 - Z/800) * rise_head + Z/800 * rise_tail on dX: a
third position effect); the spindle grows from its rear bearing (dZ); the turret grows (dX).
"""
from __future__ import annotations

from datetime import datetime

import numpy as np
from _lumped import lagged_readings, laplacian
from _runs import day_runs

ALPHA = 11.5e-6                        # cast iron / steel, 1/K
STEP_S = 20.0                          # the network's step and the logger's interval
FIRST_DAY = datetime(2027, 6, 7)       # Monday 00:00 local time (CEST all along)
DAYS, SPIN_UP_DAYS = 19, 3
RUN_DAYS = (0, 1, 2, 4, 7, 8, 10, 11, 14, 15, 16, 17)    # each a 10 h run from 07:00
RUN_HOURS = (7.0, 17.0)
NODES = ("bed", "headstock", "bearing_f", "bearing_r", "motor", "zscrew", "carriage", "xscrew",
         "turret", "tailstock", "quill", "coolant", "hydraulic")
C = np.array([4.0e7, 6.0e6, 1.5e5, 1.5e5, 3.0e5, 2.5e4, 2.0e6, 1.2e4, 8.0e5, 1.5e6, 1.0e5,
              1.2e6, 6.0e5])                                                      # J/K
H_AIR = np.array([55.0, 18.0, 1.0, 1.0, 12.0, 1.5, 10.0, 1.0, 6.0, 8.0, 1.5, 9.0, 10.0])  # W/K
LINKS = (("bed", "headstock", 25.0), ("headstock", "bearing_f", 6.0),
         ("headstock", "bearing_r", 6.0), ("bearing_f", "bearing_r", 1.5),
         ("headstock", "motor", 2.0), ("bed", "zscrew", 1.0), ("bed", "carriage", 12.0),
         ("carriage", "zscrew", 1.5), ("carriage", "xscrew", 1.0), ("carriage", "turret", 8.0),
         ("xscrew", "turret", 1.0), ("bed", "tailstock", 10.0), ("tailstock", "quill", 4.0),
         ("bed", "coolant", 5.0), ("headstock", "hydraulic", 1.5))
HEAD_H, TAIL_H, CENTRES, SPINDLE, TURRET = 250.0, 230.0, 800.0, 320.0, 160.0   # mm
# sensors: (the thermocouple's signal name, {node: weight} or "air"/"floor", lag s)
SENSORS = (("LUFT_OBEN", "air", 90.0), ("LUFT_BODEN", "floor", 300.0),
           ("BETT_L", {"bed": 0.9, "headstock": 0.1}, 900.0), ("BETT_R", {"bed": 1.0}, 900.0),
           ("SPINDELKASTEN", {"headstock": 1.0}, 500.0),
           ("LAGER_V", {"bearing_f": 0.85, "headstock": 0.15}, 120.0),
           ("LAGER_H", {"bearing_r": 0.85, "headstock": 0.15}, 120.0),
           ("MOTOR", {"motor": 1.0}, 200.0), ("MUTTER_Z", {"zscrew": 0.8, "carriage": 0.2}, 150.0),
           ("SCHLITTEN", {"carriage": 1.0}, 400.0),
           ("MUTTER_X", {"xscrew": 0.8, "turret": 0.2}, 150.0),
           ("REVOLVER", {"turret": 1.0}, 300.0), ("REITSTOCK", {"tailstock": 1.0}, 500.0),
           ("PINOLE", {"quill": 0.8, "tailstock": 0.2}, 200.0),
           ("KUEHLMITTEL", {"coolant": 1.0}, 120.0), ("HYDRAULIK", {"hydraulic": 1.0}, 150.0))


def _index(name: str) -> int:
    return NODES.index(name)


def shop_air(t_s: np.ndarray, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """The shop's air (°C) at the spindle's height and at the floor: the day's swing (19.5 °C at
    05:00, 21.5 °C at 15:00) over the weather's drift, the floor lagging 40 min and 0.6 K cooler."""
    hour = (t_s % 86400.0) / 3600.0
    day = 20.5 + 1.0 * np.sin(2 * np.pi * (hour - 9.0) / 24.0)
    ou = np.exp(-STEP_S / (3.0 * 86400.0))
    z, drift = 0.0, np.empty_like(t_s)
    noise = rng.standard_normal(t_s.size)
    for k in range(t_s.size):
        z = z * ou + np.sqrt(1 - ou**2) * noise[k]
        drift[k] = z
    air = day + 0.6 * drift
    a = 1.0 - np.exp(-STEP_S / 2400.0)
    floor = np.empty_like(air)
    floor[0] = air[0] - 0.6
    for k in range(1, air.size):
        floor[k] = floor[k - 1] + a * (air[k] - 0.6 - floor[k - 1])
    return air, floor


def programme(t_s: np.ndarray, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """States per step: on (a run day 07:00-17:00, any other weekday 06:00-14:00: the shop turned
    parts the lab did not log), the spindle's speed (rpm), X / Z mm, X and Z moving (0..1), the
    tailstock holding a part (0/1), the coolant pump (0/1)."""
    n = t_s.size
    out = {k: np.zeros(n) for k in ("on", "speed", "x", "z", "xmove", "zmove", "tail", "coolant")}
    out["x"][:], out["z"][:] = 120.0, 400.0
    day = np.floor(t_s / 86400.0)
    hour = (t_s % 86400.0) / 3600.0
    k = 0
    while k < n:
        d, h = int(day[k]), hour[k]
        on = (d in RUN_DAYS and 7.0 <= h < 17.0) or (d not in RUN_DAYS and d % 7 < 5
                                                     and 6.0 <= h < 14.0)
        if not on:
            for key in ("x", "z"):
                out[key][k] = out[key][k - 1] if k else out[key][k]
            k += 1
            continue
        length = int(rng.uniform(20.0, 90.0) * 60.0 / STEP_S)
        stop = min(k + length, n)
        span = slice(k, stop)
        out["on"][span] = 1.0
        out["x"][span] = np.round(rng.uniform(10.0, 200.0), -1)
        out["z"][span] = np.round(rng.uniform(0.0, 600.0), -1)
        if rng.random() < 0.85:
            out["speed"][span] = np.round(rng.uniform(300.0, 4000.0), -2)
            out["xmove"][span] = rng.uniform(0.05, 0.5)
            out["zmove"][span] = rng.uniform(0.1, 0.7)
            out["coolant"][span] = float(rng.random() < 0.7)
        out["tail"][span] = float(rng.random() < 0.5)
        k = max(stop, k + 1)
    return out


def simulate(seed: int) -> dict[str, np.ndarray]:
    """The whole record at STEP_S, spin-up dropped: ``t`` (s since FIRST_DAY, local clock),
    ``air``, node temperatures ``T``, the sensors' ``sensors``, the states and the errors
    ``E_dX`` / ``E_dZ`` (µm, with the probes' noise)."""
    rng = np.random.default_rng([seed, 82])
    t = np.arange(-SPIN_UP_DAYS * 86400.0, DAYS * 86400.0, STEP_S)
    air, floor = shop_air(t, rng)
    st = programme(t, rng)
    inv = np.linalg.inv(np.diag(C / STEP_S) + laplacian(NODES, LINKS, H_AIR))
    low = np.array([n in ("bed", "coolant", "hydraulic") for n in NODES])
    q = np.zeros((t.size, len(NODES)))
    s = st["speed"] / 1000.0
    q[:, _index("bearing_f")] = 14.0 * s ** 1.5
    q[:, _index("bearing_r")] = 9.0 * s ** 1.5
    q[:, _index("motor")] = 60.0 * st["on"] + 70.0 * s
    q[:, _index("zscrew")] = 22.0 * st["zmove"]
    q[:, _index("xscrew")] = 14.0 * st["xmove"]
    q[:, _index("quill")] = 3.0 * st["tail"] * s
    q[:, _index("coolant")] = 180.0 * st["coolant"] * (0.3 + s)
    q[:, _index("turret")] = 40.0 * st["coolant"] * s
    q[:, _index("hydraulic")] = 150.0 * st["on"]
    temp = np.full(len(NODES), air[0])
    temps = np.empty((t.size, len(NODES)))
    for k in range(t.size):
        amb = np.where(low, floor[k], air[k])
        temp = inv @ (C / STEP_S * temp + q[k] + H_AIR * amb)
        temps[k] = temp
    keep = t >= 0
    t, air, floor, temps = t[keep], air[keep], floor[keep], temps[keep]
    st = {k: v[keep] for k, v in st.items()}
    return {"t": t, "air": air, "floor": floor, "T": temps, **st,
            "sensors": lagged_readings(temps, {"air": air, "floor": floor}, SENSORS, NODES, STEP_S,
                                       0.02, 1, rng),
            **_errors(temps, st, rng)}


def _errors(temps: np.ndarray, st: dict, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """dX, dZ (µm) of the mandrel at the probes (module docstring)."""
    d = temps - 20.0
    n = {name: d[:, _index(name)] for name in NODES}
    head = ALPHA * HEAD_H * (0.7 * n["headstock"] + 0.15 * (n["bearing_f"] + n["bearing_r"]))
    tail = ALPHA * TAIL_H * (0.8 * n["tailstock"] + 0.2 * n["quill"])
    w = st["z"] / CENTRES
    dx = 1e3 * (ALPHA * st["x"] * n["xscrew"] + (1.0 - w) * head + w * tail
                - ALPHA * TURRET * n["turret"] - ALPHA * 120.0 * n["bed"])
    dz = 1e3 * (ALPHA * st["z"] * n["zscrew"] + ALPHA * SPINDLE * (0.6 * n["bearing_f"]
                + 0.4 * n["headstock"]) - ALPHA * 200.0 * (n["carriage"] - n["bed"]))
    noise = 0.12
    return {f"E_d{a}": v + noise * rng.standard_normal(v.size) for a, v in (("X", dx), ("Z", dz))}


def run_windows() -> list[tuple[datetime, slice]]:
    """Per run: its local start and the slice of ``simulate``'s rows it holds."""
    return day_runs(FIRST_DAY, RUN_DAYS, RUN_HOURS, STEP_S)
