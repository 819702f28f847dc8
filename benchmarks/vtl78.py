"""vtl78: a large vertical turning lathe, a hydrostatic rotary table and a ram (stranger78).

Not the project's simulator: its own lumped network (implicit Euler, numpy) and kinematics.
A portal VTL (table 2.5 m): a base on a foundation, a rotary table floating on a hydrostatic
oil film (the film's shear heats the oil and the table by the square of the speed), its
hydraulic unit with an on/off oil cooler (21.5-23 °C while the machine is on), a table gearbox,
two columns (left, right) carrying a cross-rail, a saddle on it and a vertical ram with the tool
(turning: no spindle in the ram).  The hall follows the day (its heating on working days
05:00-21:00, not at the weekend, with a day's swing).  Two shifts (05:00-22:00) Monday to
Friday; jobs of 40-180 min at one radius, ram extension and cutting speed, set-ups between.

Errors of the tool against the table (a laser probe on a reference ring on the table, µm) from
the machine's kinematics, not a map of temperatures: the columns lift the cross-rail (dZ +),
the ram grows down over its whole length (dZ -), the table's top rises with the table and the
base, and sinks with the hot oil's thinner film (the film's height goes with the oil's
viscosity^(1/3): a nonlinear term); the columns' left-right difference tilts the cross-rail,
which moves the tool by the tilt times the ram's extension (dX) and by the tilt times the
tool's radius (dZ); along X the cross-rail grows from its middle by its temperature times the
tool's radius, the table's rim under it by the table's (states: the radius and the ram's
extension; the same temperatures give another error at another pose).
"""
from __future__ import annotations

from datetime import datetime, timedelta

import numpy as np
from _lumped import laplacian

ALPHA = 11.0e-6                     # cast iron / steel, 1/K
PERIOD_S = 60.0
FIRST_DAY = datetime(2027, 4, 5)   # Monday 00:00, the lab PC's clock (CEST, no zone written)
DAYS, SPIN_UP_DAYS = 12, 4
NODES = ("base", "table", "oil", "gearbox", "col_left", "col_right", "rail", "saddle", "ram",
         "foundation")
C = np.array([2.5e7, 6.0e6, 1.2e6, 4.0e5, 5.0e6, 5.0e6, 3.0e6, 6.0e5, 4.0e5, 8.0e7])  # J/K
H_AIR = np.array([60.0, 30.0, 15.0, 6.0, 25.0, 25.0, 22.0, 6.0, 5.0, 90.0])           # W/K
LINKS = (("base", "foundation", 80.0), ("base", "col_left", 20.0), ("base", "col_right", 20.0),
         ("col_left", "rail", 8.0), ("col_right", "rail", 8.0), ("rail", "saddle", 10.0),
         ("saddle", "ram", 12.0), ("gearbox", "base", 12.0), ("gearbox", "table", 6.0),
         ("oil", "base", 10.0), ("gearbox", "col_left", 5.0), ("oil", "col_right", 4.0))
# (the gearbox stands by the left column, the hydraulic unit by the right one)
FILM = (("oil", "table", 120.0),)           # the hydrostatic film while the pump runs
COOLER_W, COOL_ON, COOL_OFF = 6000.0, 23.0, 21.5
SPEED_M_MIN = (120.0, 180.0, 250.0)         # cutting speeds: the table's rpm from the radius
# sensors: (name, {node: weight} or "air", lag s); the air's sensors read the hall
SENSORS = (("Halle oben", "air", 120.0), ("Halle unten", "air", 400.0),
           ("Fundament", {"foundation": 0.7, "base": 0.3}, 900.0), ("Bett", {"base": 1.0}, 600.0),
           ("Tisch Rand", {"table": 1.0}, 300.0), ("Hydrostatik Vorlauf", {"oil": 1.0}, 60.0),
           ("Hydrostatik Rücklauf", {"oil": 0.7, "table": 0.3}, 120.0),
           ("Getriebe", {"gearbox": 1.0}, 120.0),
           ("Ständer links unten", {"col_left": 0.7, "base": 0.3}, 400.0),
           ("Ständer links oben", {"col_left": 0.8, "rail": 0.2}, 400.0),
           ("Ständer rechts unten", {"col_right": 0.7, "base": 0.3}, 400.0),
           ("Ständer rechts oben", {"col_right": 0.8, "rail": 0.2}, 400.0),
           ("Querbalken links", {"rail": 0.8, "col_left": 0.2}, 300.0),
           ("Querbalken Mitte", {"rail": 1.0}, 300.0),
           ("Querbalken rechts", {"rail": 0.8, "col_right": 0.2}, 300.0),
           ("Support", {"saddle": 1.0}, 200.0), ("Stößel oben", {"ram": 0.7, "saddle": 0.3}, 150.0),
           ("Stößel unten", {"ram": 1.0}, 150.0))


def _index(name: str) -> int:
    return NODES.index(name)


def hall_air(t_s: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """The hall (°C): heated on working days 05:00-21:00 (a first-order approach, 3 h), a day's
    swing peaking at 15:00 (the sun on the roof), a slow random drift."""
    day = np.floor(t_s / 86400.0)
    hour = (t_s % 86400.0) / 3600.0
    heated = (np.mod(day, 7) < 5) & (hour >= 5.0) & (hour < 21.0)
    target = 14.0 + 5.0 * heated
    air = np.empty_like(t_s)
    level, tau = target[0], 3.0 * 3600.0
    drift, ou = 0.0, np.exp(-PERIOD_S / (12 * 3600.0))
    for k, tgt in enumerate(target):
        level += (tgt - level) * (1.0 - np.exp(-PERIOD_S / tau))
        drift = drift * ou + 0.6 * np.sqrt(1 - ou**2) * rng.standard_normal()
        air[k] = level + drift
    return air + 1.5 * np.sin(2 * np.pi * (hour - 9.0) / 24.0)


def programme(t_s: np.ndarray, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """States per sample: on (05:00-22:00 working days), cutting, table rpm, tool radius mm,
    ram extension mm, cutting power W."""
    n = t_s.size
    on, cut = np.zeros(n), np.zeros(n)
    rpm, radius, ram, power = np.zeros(n), np.full(n, 800.0), np.full(n, 300.0), np.zeros(n)
    k = 0
    while k < n:
        day, hour = np.floor(t_s[k] / 86400.0), (t_s[k] % 86400.0) / 3600.0
        if np.mod(day, 7) >= 5 or hour < 5.0 or hour >= 22.0:
            radius[k], ram[k] = (radius[k - 1], ram[k - 1]) if k else (800.0, 300.0)
            k += 1
            continue
        length = int(rng.uniform(40.0, 180.0) * 60.0 / PERIOD_S)
        setup = int(rng.uniform(15.0, 45.0) * 60.0 / PERIOD_S)
        r = float(np.round(rng.uniform(250.0, 1200.0), -1))
        ext = float(np.round(rng.uniform(150.0, 1100.0), -1))
        v = float(rng.choice(SPEED_M_MIN))
        span, job = slice(k, min(k + setup + length, n)), slice(min(k + setup, n), min(k + setup + length, n))
        on[span], radius[span], ram[span] = 1.0, r, ext
        if rng.random() < 0.85:
            cut[job] = 1.0
            rpm[job] = min(v * 1e3 / (2 * np.pi * r), 60.0)
            power[job] = rng.uniform(8e3, 30e3)
        k += setup + length
    hour = (t_s % 86400.0) / 3600.0
    late = hour >= 22.0
    on[late] = cut[late] = rpm[late] = power[late] = 0.0
    return {"on": on, "cut": cut, "rpm": rpm, "radius": radius, "ram": ram, "power": power}


def simulate(seed: int) -> dict[str, np.ndarray]:
    """The whole record, spin-up dropped: ``t`` (s since FIRST_DAY), ``air``, node
    temperatures ``T``, the sensors' ``sensors``, states and the errors ``E_dX`` / ``E_dZ``
    (µm, with the probe's noise)."""
    rng = np.random.default_rng([seed, 78])
    t = np.arange(-SPIN_UP_DAYS * 86400.0, DAYS * 86400.0, PERIOD_S)
    air = hall_air(t, rng)
    st = programme(t, rng)
    mats = {on: np.linalg.inv(np.diag(C / PERIOD_S)
                              + laplacian(NODES, (*LINKS, *(FILM if on else ())), H_AIR)) for on in (0, 1)}
    temp = np.full(len(NODES), air[0])
    temps = np.empty((t.size, len(NODES)))
    cooling = False
    for k in range(t.size):
        q = np.zeros(len(NODES))
        if st["on"][k]:
            shear = 1500.0 * (st["rpm"][k] / 40.0) ** 2        # the film's shear, W
            q[_index("oil")] += 1200.0 + 0.6 * shear            # (the pump's own)
            q[_index("table")] += 0.4 * shear
            q[_index("gearbox")] += 0.01 * st["power"][k] + 4.0 * st["rpm"][k]
            q[_index("saddle")] += 60.0                         # the ram's drives
            q[_index("ram")] += 0.003 * st["power"][k]          # chips and the cut's heat
            to = temp[_index("oil")]
            cooling = to > COOL_ON or (cooling and to > COOL_OFF)
            if cooling:
                q[_index("oil")] -= COOLER_W
        else:
            cooling = False
        rhs = C / PERIOD_S * temp + q + H_AIR * air[k]
        temp = mats[int(st["on"][k])] @ rhs
        temps[k] = temp
    keep = t >= 0
    t, air, temps = t[keep], air[keep], temps[keep]
    st = {k: v[keep] for k, v in st.items()}
    return {"t": t, "air": air, "T": temps, **st, "sensors": _sensors(temps, air, rng),
            **_errors(temps, st, rng)}


def _sensors(temps: np.ndarray, air: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    out = np.empty((temps.shape[0], len(SENSORS)))
    for j, (_, where, lag) in enumerate(SENSORS):
        truth = air if where == "air" else sum(w * temps[:, _index(n)] for n, w in where.items())
        a = 1.0 - np.exp(-PERIOD_S / lag)
        read = np.empty_like(truth)
        read[0] = truth[0]
        for k in range(1, truth.size):
            read[k] = read[k - 1] + a * (truth[k] - read[k - 1])
        out[:, j] = np.round(read + 0.02 * rng.standard_normal(truth.size), 2)
    return out


def _errors(temps: np.ndarray, st: dict, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """dX, dZ (µm) of the tool against the table from the parts' growths (20 °C reference)."""
    d = temps - 20.0
    n = {name: d[:, _index(name)] for name in NODES}
    height, span, ram_len = 3200.0, 3600.0, 1800.0          # mm: rail over the base, columns apart
    tilt = ALPHA * height * (n["col_left"] - n["col_right"]) / span   # rad, left longer: tips right
    # the film (40 µm at 22 °C) thins as the oil's viscosity falls (about 3 %/K)
    film = 40.0 * np.exp(-0.03 * (temps[:, _index("oil")] - 22.0)) ** (1 / 3)
    dz = (1e3 * ALPHA * height * 0.5 * (n["col_left"] + n["col_right"])
          - 1e3 * ALPHA * ram_len * n["ram"] - 1e3 * ALPHA * 250.0 * n["saddle"]
          - 1e3 * ALPHA * 600.0 * n["base"] - 1e3 * ALPHA * 400.0 * n["table"]
          - (film - 40.0) + 1e3 * tilt * st["radius"])
    dx = (1e3 * ALPHA * st["radius"] * (n["rail"] - n["table"]) + 1e3 * tilt * st["ram"]
          + 1e3 * ALPHA * 200.0 * n["saddle"])
    noise = 0.2
    return {"E_dX": dx + noise * rng.standard_normal(dx.size),
            "E_dZ": dz + noise * rng.standard_normal(dz.size)}


def day_starts() -> list[datetime]:
    return [FIRST_DAY + timedelta(days=k) for k in range(DAYS)]
