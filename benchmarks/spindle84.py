"""spindle84: a motor spindle on an ISO 230-3 thermal test rig, five capacitive probes at a test
mandrel (stranger84).

Not the project's simulator: its own lumped network (implicit Euler, numpy) and probe geometry.
A spindle maker's test rig: a motor spindle (max 18000 rpm, oil-air lubricated angular contact
bearings, its stator cooled by a water jacket fed by a chiller that follows the room) clamped
horizontally in a housing flange on a cast fixture plate; a test mandrel in the spindle; a
probe nest on the fixture holds five capacitive probes (ISO 230-3, 5.4 and figure 2): X1 / Y1
20 mm from the nose, X2 / Y2 120 mm from it (their difference over 100 mm: the tilts B / A),
Z against the mandrel's end face.  The lab's room is held at 20 +- 1 °C (a daily swing and a
drift).

Nodes: ``base`` (the fixture plate and the nest), ``housing``, ``front`` / ``rear`` (the
bearings' outer rings), ``motor`` (the stator), ``rotor`` (the shaft and the rotor: NO sensor
sees it), ``coolant`` (the jacket's water, pulled toward the room by the chiller), ``oil`` (the
oil-air unit's reservoir and lines).  Heat (n in krpm): front 2 n + 0.15 n^2, rear 1.5 n +
0.1 n^2, stator 30 + 4 n while on, rotor 0.12 n^2 W; the oil-air unit 15 W while on.

Errors (µm, each probe's reading: the mandrel's displacement toward it from the run's first
sample's zero, steel 11.5e-6 /K): Z the housing's and the shaft's growth against the nest's;
A (about X, µrad) the jacket's side colder than the stator's (4 µrad/K of stator - coolant), B
(about Y) the front against the rear bearing (1 µrad/K); Y / X at the nose the housing's centre
against the nest.  PLANTED (what no temperature sees): the shaft's centrifugal and preload pull
of the nose, ``E_Z -= 2.5 (n / 10 krpm)^2`` µm at once with the speed (-8.1 µm at 18000 rpm).

The programme (ISO 230-3, 6.2 / 6.3): ten tests of 8 h from 07:00 on the working days of two
weeks from Monday 2027-05-03 (the rig at rest between them); a test with p 0.3 runs a constant
speed (50 % or 75 % of max) for 4 h, else a speed spectrum: 4-6 steps of 30-60 min, speeds
drawn from 3000 ... 18000 rpm, one step a varying speed (a new speed each 1-3 min); then the
spindle stops and the rig cools for the rest of the 8 h.
"""
from __future__ import annotations

from datetime import datetime

import numpy as np
from _lumped import lagged_readings, laplacian
from _runs import day_runs

ALPHA = 11.5e-6
STEP_S = 10.0
FIRST_DAY = datetime(2027, 5, 3)        # a Monday
DAYS, SPIN_UP_DAYS = 12, 2
RUN_DAYS = (0, 1, 2, 3, 4, 7, 8, 9, 10, 11)
RUN_HOURS = (7.0, 15.0)
N_MAX = 18000.0
SPEEDS = np.arange(3000.0, N_MAX + 1, 1500.0)
L_PIVOT, H1, H2 = 350.0, 20.0, 120.0    # mm: the rear bearing to the nose; the probes' distances
NODES = ("base", "housing", "front", "rear", "motor", "rotor", "coolant", "oil")
C = np.array([8.0e5, 1.2e5, 1.5e4, 1.2e4, 4.0e4, 2.5e4, 3.0e4, 6.0e4])
H_AIR = np.array([12.0, 5.0, 0.5, 0.5, 1.0, 0.3, 40.0, 3.0])      # coolant: the chiller
LINKS = (("base", "housing", 4.0), ("housing", "front", 6.0), ("housing", "rear", 5.0),
         ("housing", "motor", 5.0), ("motor", "coolant", 12.0), ("housing", "coolant", 4.0),
         ("rotor", "front", 2.5), ("rotor", "rear", 2.0), ("rotor", "motor", 1.5),
         ("front", "oil", 2.0), ("rear", "oil", 2.0))
# (name, truth, lag s): type-K thermocouples on a QuantumX MX1609
SENSORS = (("T_AIR", "air", 120.0), ("T_BASE", {"base": 1.0}, 600.0),
           ("T_HOUSING", {"housing": 0.8, "front": 0.2}, 200.0), ("T_FRONT", {"front": 1.0}, 40.0),
           ("T_REAR", {"rear": 1.0}, 40.0), ("T_STATOR", {"motor": 1.0}, 60.0),
           ("T_COOLANT", {"coolant": 1.0}, 30.0), ("T_OIL", {"oil": 1.0}, 90.0))
QUICK = ("T_HOUSING", "T_FRONT", "T_REAR", "T_STATOR", "T_COOLANT")
PROBES = ("X1", "Y1", "X2", "Y2", "Z")
PULL_UM = 2.5                           # PLANTED: the nose's pull at 10 krpm (µm)


def _i(name: str) -> int:
    return NODES.index(name)


def room_air(t_s: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """The lab's air (°C): 20 +- 0.6 over the day (warmest at 15:00), a drift of 0.4 K."""
    hour = (t_s % 86400.0) / 3600.0
    ou = np.exp(-STEP_S / (2.0 * 86400.0))
    z, drift = 0.0, np.empty_like(t_s)
    for k, e in enumerate(rng.standard_normal(t_s.size)):
        z = z * ou + np.sqrt(1 - ou**2) * e
        drift[k] = z
    return 20.0 + 0.6 * np.sin(2 * np.pi * (hour - 9.0) / 24.0) + 0.4 * drift


def _test(n: int, rng: np.random.Generator) -> np.ndarray:
    """One test's speed (rpm) over ``n`` samples (module docstring)."""
    speed = np.zeros(n)
    per_min = int(60 / STEP_S)
    if rng.random() < 0.3:
        speed[:240 * per_min] = N_MAX * rng.choice([0.5, 0.75])
        return speed
    k, steps = 0, int(rng.integers(4, 7))
    varying = int(rng.integers(steps))
    for s in range(steps):
        length = int(rng.integers(30, 61)) * per_min
        if s == varying:
            j = k
            while j < k + length:
                hold = int(rng.integers(1, 4)) * per_min
                speed[j:min(j + hold, k + length)] = rng.choice(SPEEDS)
                j += hold
        else:
            speed[k:k + length] = rng.choice(SPEEDS)
        k += length
    return speed


def simulate(seed: int, planted: float = PULL_UM, quick: bool = False) -> dict[str, np.ndarray]:
    """The record at STEP_S, spin-up dropped: ``t``, ``air``, ``T``, ``speed``, ``sensors`` and
    the probes' ``E_<probe>`` (µm, before each run's zero); ``planted``: the centrifugal pull
    at 10 krpm (0: the clean control, every draw the same); ``quick``: the spindle's own
    thermocouples (housing, bearings, stator, coolant) lagging 1 s, not 30-200 s."""
    rng = np.random.default_rng([seed, 84])
    t = np.arange(-SPIN_UP_DAYS * 86400.0, DAYS * 86400.0, STEP_S)
    air = room_air(t, rng)
    speed = np.zeros(t.size)
    for start, rows in day_runs(FIRST_DAY, RUN_DAYS, RUN_HOURS, STEP_S):
        k0 = rows.start + int(SPIN_UP_DAYS * 86400.0 / STEP_S)
        speed[k0:k0 + rows.stop - rows.start] = _test(rows.stop - rows.start, rng)
    n = speed / 1000.0
    on = (speed > 0).astype(float)
    q = np.zeros((t.size, len(NODES)))
    q[:, _i("front")] = 2.0 * n + 0.15 * n**2
    q[:, _i("rear")] = 1.5 * n + 0.1 * n**2
    q[:, _i("motor")] = (30.0 + 4.0 * n) * on
    q[:, _i("rotor")] = 0.12 * n**2
    q[:, _i("oil")] = 15.0 * on
    g = laplacian(list(NODES), LINKS, H_AIR)
    inv = np.linalg.inv(np.diag(C / STEP_S) + g)
    temp = np.full(len(NODES), air[0])
    temps = np.empty((t.size, len(NODES)))
    for k in range(t.size):
        temp = inv @ (C / STEP_S * temp + q[k] + H_AIR * air[k])
        temps[k] = temp
    keep = t >= 0
    t, air, temps, speed = t[keep], air[keep], temps[keep], speed[keep]
    laid = tuple((n, w, 1.0 if quick and n in QUICK else lag) for n, w, lag in SENSORS)
    sensors = lagged_readings(temps, {"air": air}, laid, list(NODES), STEP_S, 0.02, 2, rng)
    return {"t": t, "air": air, "T": temps, "speed": speed, "sensors": sensors,
            **_probes(temps, speed, rng, planted)}


def _probes(temps: np.ndarray, speed: np.ndarray, rng: np.random.Generator, planted: float) -> dict:
    d = temps - 20.0
    n = {name: d[:, _i(name)] for name in NODES}
    tilt_a = 4.0e-6 * (n["motor"] - n["coolant"]) + 1.0e-6 * (n["front"] - n["housing"])
    tilt_b = 1.0e-6 * (n["front"] - n["rear"])
    y0 = 1e3 * ALPHA * 60.0 * (n["housing"] - n["base"])
    x0 = 1e3 * ALPHA * 30.0 * (n["base"] - n["housing"])
    z = (1e3 * ALPHA * (250.0 * n["housing"] + 150.0 * n["rotor"] + 80.0 * n["front"]
                        - 300.0 * n["base"]) - planted * (speed / 1e4) ** 2)
    out = {"E_X1": x0 + 1e3 * tilt_b * (L_PIVOT + H1), "E_X2": x0 + 1e3 * tilt_b * (L_PIVOT + H2),
           "E_Y1": y0 + 1e3 * tilt_a * (L_PIVOT + H1),
           "E_Y2": y0 + 1e3 * tilt_a * (L_PIVOT + H2), "E_Z": z}
    return {k: np.round(v + 0.05 * rng.standard_normal(v.size), 2) for k, v in out.items()}


def run_windows() -> list[tuple[datetime, slice]]:
    """Per run: its local start and its slice of ``simulate``'s rows."""
    return day_runs(FIRST_DAY, RUN_DAYS, RUN_HOURS, STEP_S)
