"""jig80: a jig borer with a quill (W axis) and an NC rotary table in a climate room (stranger80).

Not the project's simulator: its own lumped network (implicit Euler, numpy) and kinematics.
A single-column jig borer (Koordinatenbohrmaschine): a bed on a foundation, a saddle (Y) on
the bed and a cross table (X) on the saddle, each driven by a ball screw from a fixed bearing at
its zero end (the nut's friction heats the screw while its axis moves), an NC rotary table (B,
a torque motor beside it) on the cross table; the column (front and rear walls) behind, the
headstock on its front (its height a fixed set-up of the test week), the motor spindle in a
quill that extends down out of the headstock (W, 0-250 mm), a hydraulic / lube unit by the
column's rear.  The room is air-conditioned on working days 06:00-19:00 local time (20 °C, the
unit's on/off swing of +-0.25 K every ~35 min); at night and at weekends it drifts towards the
building.  One shift; the lab's runs 07:00-17:00 on the days it measured (gaps: days without
a run, the weekends), the machine warm from the day before or cold after a gap.

Errors of the spindle nose (a test mandrel in the quill) against a probe nest on the rotary
table, at the job's pose (µm, 20 °C reference), from the kinematics, not a map of
temperatures: the X and Y screws grow from their fixed bearings, moving the table by the
screw's rise times the axis' position (dX: X * dT_xscrew, dY: Y * dT_yscrew: the planted
position effects); the column's front-rear difference bends it (curvature alpha*dT/depth): the
headstock moves back by kappa*h^2/2 and tips, its nose moving by the tilt times the quill's
length below it (L0 + W: dY) and by the tilt times the overhang (dZ); the quill grows down over
its length out of the headstock (dZ: (L0 + W) * dT_quill, the second position effect); the
column lifts the headstock, the bed, saddle, table and rotary table lift the nest.
"""
from __future__ import annotations

from datetime import datetime, timedelta, timezone

import numpy as np
from _lumped import lagged_readings, laplacian
from _runs import day_runs

ALPHA = 11.5e-6                        # cast iron / steel, 1/K
STEP_S = 10.0                          # the network's step and the probes' period
FIRST_DAY = datetime(2027, 3, 15)      # Monday 00:00 local time (CET; CEST from Sun 28 Mar)
DAYS, SPIN_UP_DAYS = 21, 3
# the days the lab measured (0 = Mon 15 Mar): gaps of a day, the weekends; Mon 29 Mar after the change
RUN_DAYS = (0, 1, 2, 4, 7, 8, 10, 11, 14, 15, 16, 17, 18)
RUN_HOURS = (7.0, 17.0)
NODES = ("foundation", "bed", "saddle", "yscrew", "table", "xscrew", "rtable", "bmotor",
         "col_front", "col_rear", "headstock", "spindle", "quill", "motor", "hyd")
C = np.array([6.0e7, 1.6e7, 2.5e6, 3.0e4, 2.0e6, 4.0e4, 9.0e5, 1.2e5, 5.0e6, 5.0e6, 1.8e6,
              1.5e5, 8.0e4, 1.5e5, 6.0e5])                                        # J/K
H_AIR = np.array([70.0, 40.0, 14.0, 2.0, 14.0, 2.5, 8.0, 2.5, 18.0, 18.0, 12.0, 2.5, 1.5, 3.5,
                  9.0])                                                           # W/K
LINKS = (("bed", "foundation", 60.0), ("bed", "saddle", 12.0), ("saddle", "yscrew", 2.5),
         ("bed", "yscrew", 1.5), ("saddle", "table", 10.0), ("table", "xscrew", 3.0),
         ("saddle", "xscrew", 1.2), ("table", "rtable", 7.0), ("rtable", "bmotor", 6.0),
         ("bed", "col_front", 10.0), ("bed", "col_rear", 10.0), ("col_front", "col_rear", 14.0),
         ("col_front", "headstock", 8.0), ("headstock", "spindle", 6.0), ("spindle", "quill", 5.0),
         ("headstock", "quill", 3.0), ("headstock", "motor", 3.0), ("hyd", "col_rear", 5.0),
         ("hyd", "bed", 3.0))
# the geometry (mm)
HEAD_H, COL_DEPTH, OVERHANG, QUILL_L0 = 1100.0, 650.0, 420.0, 180.0
SPEEDS = (800.0, 1500.0, 2500.0, 4000.0, 6000.0)   # spindle rpm
# sensors: (lab's name, unit written, {node: weight} or "air"/"floor", lag s)
SENSORS = (("Raumluft oben", "air", 90.0), ("Raumluft Boden", "floor", 300.0),
           ("Fundament", {"foundation": 0.8, "bed": 0.2}, 1200.0),
           ("Bett links", {"bed": 1.0}, 600.0), ("Bett rechts", {"bed": 0.9, "hyd": 0.1}, 600.0),
           ("Saddle Y", {"saddle": 1.0}, 400.0), ("Mutter Y", {"yscrew": 0.8, "saddle": 0.2}, 150.0),
           ("Kreuztisch", {"table": 1.0}, 400.0), ("Mutter X", {"xscrew": 0.8, "table": 0.2}, 150.0),
           ("Rundtisch", {"rtable": 1.0}, 300.0), ("Torquemotor B", {"bmotor": 1.0}, 120.0),
           ("Ständer vorne unten", {"col_front": 0.7, "bed": 0.3}, 500.0),
           ("Ständer vorne oben", {"col_front": 0.8, "headstock": 0.2}, 500.0),
           ("Ständer hinten unten", {"col_rear": 0.7, "bed": 0.3}, 500.0),
           ("Ständer hinten oben", {"col_rear": 1.0}, 500.0),
           ("Spindelkasten", {"headstock": 1.0}, 300.0),
           ("Spindle bearing front", {"spindle": 1.0}, 60.0),
           ("Pinole", {"quill": 0.8, "spindle": 0.2}, 120.0),
           ("Spindle motor", {"motor": 1.0}, 90.0), ("Hydraulik Tank", {"hyd": 1.0}, 200.0))


def _index(name: str) -> int:
    return NODES.index(name)


def local_hours(t_s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(day index, hour of the day) on the local clock, ``t_s`` seconds since FIRST_DAY local."""
    return np.floor(t_s / 86400.0), (t_s % 86400.0) / 3600.0


def room_air(t_s: np.ndarray, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """The room (°C) at the machine's head and at its floor: conditioned on working days
    06:00-19:00 (20 °C, the on/off swing), else drifting (4 h) to the building's 17-19 °C."""
    day, hour = local_hours(t_s)
    on = (np.mod(day, 7) < 5) & (hour >= 6.0) & (hour < 19.0)
    building = 18.0 + 1.0 * np.sin(2 * np.pi * (hour - 10.0) / 24.0)
    air = np.empty_like(t_s)
    level, swing, phase = 18.0, 0.0, 0.0
    drift, ou = 0.0, np.exp(-STEP_S / (6 * 3600.0))
    for k in range(t_s.size):
        target, tau = (20.0, 1800.0) if on[k] else (building[k] + 0.4 * drift, 4 * 3600.0)
        level += (target - level) * (1.0 - np.exp(-STEP_S / tau))
        drift = drift * ou + np.sqrt(1 - ou**2) * rng.standard_normal()
        phase += STEP_S / (35 * 60.0 * (1.0 + 0.1 * np.sin(k / 997.0)))
        swing = 0.25 * (2 * np.abs(2 * (phase % 1.0) - 1.0) - 1.0) if on[k] else 0.0
        air[k] = level + swing + 0.08 * drift
    floor = np.empty_like(air)
    a = 1.0 - np.exp(-STEP_S / 1800.0)
    floor[0] = air[0] - 0.6
    for k in range(1, air.size):
        floor[k] = floor[k - 1] + a * (air[k] - 0.6 - floor[k - 1])
    return air, floor


def programme(t_s: np.ndarray, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """States per step: on (the machine, 06:30-17:30 on a run day or any working day 06:30-15:00
    when the lab did not measure: the shop used it), spindle rpm, X / Y / W mm, X and Y moving
    (0..1, the hole pattern's traverse), the table indexing (0/1)."""
    n = t_s.size
    out = {k: np.zeros(n) for k in ("on", "rpm", "x", "y", "w", "xmove", "ymove", "index")}
    out["x"][:], out["y"][:] = 400.0, 300.0
    day, hour = local_hours(t_s)
    k = 0
    while k < n:
        d, h = int(day[k]), hour[k]
        working = d % 7 < 5
        end = 17.5 if d in RUN_DAYS else 15.0
        if not working or h < 6.5 or h >= end:
            for key in ("x", "y", "w"):
                out[key][k] = out[key][k - 1] if k else out[key][k]
            k += 1
            continue
        length = int(rng.uniform(30.0, 120.0) * 60.0 / STEP_S)
        setup = int(rng.uniform(10.0, 30.0) * 60.0 / STEP_S)
        stop = min(k + setup + length, n, int((d * 24 + end) * 3600.0 / STEP_S)
                   + int(-t_s[0] / STEP_S))
        span, job = slice(k, stop), slice(min(k + setup, stop), stop)
        out["on"][span] = 1.0
        out["x"][span] = np.round(rng.uniform(40.0, 760.0), -1)
        out["y"][span] = np.round(rng.uniform(30.0, 570.0), -1)
        out["w"][span] = np.round(rng.uniform(0.0, 250.0), -1)
        if rng.random() < 0.85:
            out["rpm"][job] = rng.choice(SPEEDS)
            out["xmove"][job] = rng.uniform(0.2, 1.0)
            out["ymove"][job] = rng.uniform(0.2, 1.0)
            idx = rng.random(stop - job.start) < rng.uniform(0.0, 0.15)
            out["index"][job] = idx.astype(float)
        k = max(stop, k + 1)
    return out


def simulate(seed: int) -> dict[str, np.ndarray]:
    """The whole record at STEP_S, spin-up dropped: ``t`` (s since FIRST_DAY, local clock),
    ``air``, node temperatures ``T``, the sensors' ``sensors``, the states and the errors
    ``E_dX`` / ``E_dY`` / ``E_dZ`` (µm, with the probes' noise)."""
    rng = np.random.default_rng([seed, 80])
    t = np.arange(-SPIN_UP_DAYS * 86400.0, DAYS * 86400.0, STEP_S)
    air, floor = room_air(t, rng)
    st = programme(t, rng)
    inv = np.linalg.inv(np.diag(C / STEP_S) + laplacian(NODES, LINKS, H_AIR))
    h_air = H_AIR.copy()
    low = np.array([n in ("foundation", "bed", "hyd") for n in NODES])
    temp = np.full(len(NODES), air[0])
    temps = np.empty((t.size, len(NODES)))
    q = np.zeros((t.size, len(NODES)))
    rpm = st["rpm"]
    q[:, _index("spindle")] = 16.0 * (rpm / 1000.0) ** 1.5
    q[:, _index("quill")] = 4.0 * (rpm / 1000.0) ** 1.5
    q[:, _index("motor")] = st["on"] * 30.0 + 0.025 * rpm
    q[:, _index("xscrew")] = 45.0 * st["xmove"]
    q[:, _index("yscrew")] = 35.0 * st["ymove"]
    q[:, _index("bmotor")] = 120.0 * st["index"] + 8.0 * st["on"]
    q[:, _index("hyd")] = 260.0 * st["on"]
    q[:, _index("headstock")] = 15.0 * st["on"]
    for k in range(t.size):
        amb = np.where(low, floor[k], air[k])
        temp = inv @ (C / STEP_S * temp + q[k] + h_air * amb)
        temps[k] = temp
    keep = t >= 0
    t, air, floor, temps = t[keep], air[keep], floor[keep], temps[keep]
    st = {k: v[keep] for k, v in st.items()}
    return {"t": t, "air": air, "floor": floor, "T": temps, **st,
            "sensors": lagged_readings(temps, {"air": air, "floor": floor}, SENSORS, NODES, STEP_S,
                                       0.015, 3, rng),
            **_errors(temps, st, rng)}


def _errors(temps: np.ndarray, st: dict, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """dX, dY, dZ (µm) of the spindle nose against the nest (module docstring)."""
    d = temps - 20.0
    n = {name: d[:, _index(name)] for name in NODES}
    kappa = ALPHA * (n["col_front"] - n["col_rear"]) / COL_DEPTH      # 1/mm, front longer: bends back
    below = QUILL_L0 + st["w"]                                        # mm of quill under the head
    dx = (1e3 * ALPHA * st["x"] * n["xscrew"] + 1e3 * ALPHA * 120.0 * (n["rtable"] - n["table"])
          + 1e3 * ALPHA * 60.0 * n["headstock"])
    dy = (1e3 * ALPHA * st["y"] * n["yscrew"] - 1e3 * kappa * HEAD_H ** 2 / 2
          + 1e3 * kappa * HEAD_H * below + 1e3 * ALPHA * 200.0 * (n["col_front"] - n["saddle"]))
    dz = (1e3 * ALPHA * HEAD_H * 0.5 * (n["col_front"] + n["col_rear"])
          - 1e3 * ALPHA * below * n["quill"] - 1e3 * ALPHA * 140.0 * n["spindle"]
          - 1e3 * ALPHA * 260.0 * n["headstock"] - 1e3 * kappa * HEAD_H * OVERHANG
          - 1e3 * ALPHA * (350.0 * n["bed"] + 110.0 * n["saddle"] + 90.0 * n["table"]
                           + 120.0 * n["rtable"]))
    noise = 0.12
    return {f"E_d{a}": v + noise * rng.standard_normal(v.size)
            for a, v in (("X", dx), ("Y", dy), ("Z", dz))}


BERLIN_DST = datetime(2027, 3, 28, 2, 0)     # local 02:00 CET -> 03:00 CEST


def utc_of_local(local: datetime) -> datetime:
    """The UTC instant of the lab's local clock (CET / CEST; no ambiguous hour in March)."""
    offset = 2 if local >= BERLIN_DST else 1
    return (local - timedelta(hours=offset)).replace(tzinfo=timezone.utc)


def run_windows() -> list[tuple[datetime, slice]]:
    """Per run: its local start and the slice of ``simulate``'s rows it holds."""
    return day_runs(FIRST_DAY, RUN_DAYS, RUN_HOURS, STEP_S)
