"""grinder77: a precision surface grinder with a coolant tank and its chiller (stranger77).

Not the project's simulator: its own lumped network (implicit Euler, numpy) and kinematics.
A horizontal-spindle surface grinder: a cast-iron bed on a foundation, a table reciprocating
on oil-fed ways (its hydraulic unit's tank in the base), a column (front and rear walls) with
the wheelhead riding it (Z, the wheel's height), a motor spindle along Y, a 400 l coolant tank
held by an on/off chiller (19.5-21 °C) while the machine is on.  The hall is heated on working
days 06:00-20:00, not at the weekend.  Two shifts (06:00-22:00) Monday to Friday; jobs of
20-120 min grinding at one wheel speed and height, set-ups between; off at the weekend.

Errors of the wheel against the table (capacitive probes on a reference ring, µm) from the
machine's kinematics, not a map of temperatures: the gap dZ grows with the bed and the column
(over the wheelhead's height), shrinks with the wheelhead housing and the table; the column's
front-rear difference bends it (curvature alpha*dT/depth), tipping the wheel's overhang (dZ)
and moving the wheelhead back by kappa*h^2/2 (dY), h the wheelhead's height (a state: the same
temperatures give another error at another height); the spindle grows along Y.
"""
from __future__ import annotations

from datetime import datetime, timedelta, timezone

import numpy as np
from _lumped import laplacian

ALPHA = 11.0e-6                     # cast iron, 1/K
PERIOD_S = 60.0
FIRST_DAY = datetime(2027, 3, 1, tzinfo=timezone(timedelta(hours=1)))   # Monday 00:00 CET
DAYS, SPIN_UP_DAYS = 12, 4
NODES = ("bed", "table", "col_front", "col_rear", "wheelhead", "spindle", "oil", "coolant",
         "foundation")
C = np.array([4.0e6, 6.0e5, 8.0e5, 8.0e5, 1.5e5, 3.0e4, 3.5e5, 1.6e6, 2.0e7])     # J/K
H_AIR = np.array([25.0, 8.0, 6.0, 8.0, 5.0, 9.0, 12.0, 10.0, 40.0])               # W/K
LINKS = (("bed", "table", 15.0), ("bed", "col_front", 10.0), ("bed", "col_rear", 10.0),
         ("col_front", "col_rear", 6.0), ("col_front", "wheelhead", 5.0),
         ("wheelhead", "spindle", 6.0), ("bed", "foundation", 30.0), ("oil", "bed", 4.0))
OIL_ON = (("oil", "table", 10.0),)                       # the ways' oil while the table moves
COOLANT_ON = (("coolant", "table", 60.0), ("coolant", "wheelhead", 8.0), ("coolant", "bed", 15.0))
CHILLER_W, CHILL_ON, CHILL_OFF = 2000.0, 21.0, 19.5
SPEEDS = (1450.0, 1800.0, 2200.0)                        # wheel rpm
# sensors: (name, {node: weight} or "air", lag s); the air's sensors read the hall
SENSORS = (("hall air north", "air", 120.0), ("hall air south", "air", 300.0),
           ("bed left", {"bed": 0.9, "oil": 0.1}, 600.0), ("bed right", {"bed": 1.0}, 600.0),
           ("table", {"table": 1.0}, 300.0), ("column front low", {"col_front": 0.8, "bed": 0.2}, 400.0),
           ("column front top", {"col_front": 0.8, "wheelhead": 0.2}, 400.0),
           ("column rear low", {"col_rear": 0.8, "bed": 0.2}, 400.0),
           ("column rear top", {"col_rear": 1.0}, 400.0), ("wheelhead", {"wheelhead": 1.0}, 200.0),
           ("spindle front bearing", {"spindle": 1.0}, 60.0),
           ("spindle motor", {"spindle": 0.7, "wheelhead": 0.3}, 60.0),
           ("hydraulic oil", {"oil": 1.0}, 120.0), ("coolant tank", {"coolant": 1.0}, 120.0),
           ("foundation", {"foundation": 0.7, "bed": 0.3}, 900.0))


def _index(name: str) -> int:
    return NODES.index(name)


def hall_air(t_s: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """The hall (°C) at ``t_s`` (s since FIRST_DAY): heated on working days 06:00-20:00 (a
    first-order approach), a day's swing peaking at 15:00, a slow random drift."""
    day = np.floor(t_s / 86400.0)
    hour = (t_s % 86400.0) / 3600.0
    weekday = np.mod(day, 7)                      # 0: Monday (negative days: the spin-up)
    heated = (weekday < 5) & (hour >= 6.0) & (hour < 20.0)
    target = 15.5 + 4.0 * heated
    air = np.empty_like(t_s)
    level, tau = target[0], 2.5 * 3600.0
    drift, ou = 0.0, np.exp(-PERIOD_S / (10 * 3600.0))
    for k, tgt in enumerate(target):
        level += (tgt - level) * (1.0 - np.exp(-PERIOD_S / tau))
        drift = drift * ou + 0.5 * np.sqrt(1 - ou**2) * rng.standard_normal()
        air[k] = level + drift
    return air + 1.2 * np.sin(2 * np.pi * (hour - 9.0) / 24.0)


def programme(t_s: np.ndarray, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """States per sample: on (06:00-22:00 working days), grinding, wheel rpm, wheelhead Z mm,
    grinding power W."""
    n = t_s.size
    on, grind = np.zeros(n), np.zeros(n)
    rpm, z, power = np.zeros(n), np.full(n, 250.0), np.zeros(n)
    k = 0
    while k < n:
        day, hour = np.floor(t_s[k] / 86400.0), (t_s[k] % 86400.0) / 3600.0
        if np.mod(day, 7) >= 5 or hour < 6.0 or hour >= 22.0:
            z[k] = z[k - 1] if k else 250.0
            k += 1
            continue
        length = int(rng.uniform(20.0, 120.0) * 60.0 / PERIOD_S)
        setup = int(rng.uniform(10.0, 30.0) * 60.0 / PERIOD_S)
        height = float(np.round(rng.uniform(60.0, 420.0), -1))
        speed, watts, grinds = float(rng.choice(SPEEDS)), rng.uniform(500.0, 1600.0), rng.random() < 0.8
        end = k + setup + length
        span = slice(k, min(end, n))
        on[span] = 1.0
        z[span] = height
        job = slice(min(k + setup, n), min(end, n))
        if grinds:
            grind[job], rpm[job], power[job] = 1.0, speed, watts
        k = end
    # a job running past 22:00 ends there
    hour = (t_s % 86400.0) / 3600.0
    late = hour >= 22.0
    on[late] = grind[late] = rpm[late] = power[late] = 0.0
    return {"on": on, "grind": grind, "rpm": rpm, "z": z, "power": power}


def simulate(seed: int) -> dict[str, np.ndarray]:
    """The whole record, spin-up dropped: ``t`` (s since FIRST_DAY), ``air``, node
    temperatures ``T`` (n x nodes), the sensors' ``sensors`` (n x len(SENSORS)), states and
    the errors ``E_dZ`` / ``E_dY`` (µm, measured with the probes' noise)."""
    rng = np.random.default_rng([seed, 77])
    t = np.arange(-SPIN_UP_DAYS * 86400.0, DAYS * 86400.0, PERIOD_S)
    air = hall_air(t, rng)
    st = programme(t, rng)
    mats = {}
    for oil in (0, 1):
        for cool in (0, 1):
            g = laplacian(NODES, (*LINKS, *(OIL_ON if oil else ()), *(COOLANT_ON if cool else ())), H_AIR)
            mats[oil, cool] = np.linalg.inv(np.diag(C / PERIOD_S) + g)
    temp = np.full(len(NODES), air[0])
    temps = np.empty((t.size, len(NODES)))
    chilling = False
    for k in range(t.size):
        q = np.zeros(len(NODES))
        if st["rpm"][k] > 0:
            p = 150.0 + 0.12 * st["rpm"][k]
            q[_index("spindle")] += 0.7 * p
            q[_index("wheelhead")] += 0.3 * p
        if st["grind"][k]:
            q[_index("coolant")] += 0.8 * st["power"][k] + 150.0       # (the pump's own)
            q[_index("table")] += 0.2 * st["power"][k]
        if st["on"][k]:
            q[_index("oil")] += 300.0
            tc = temp[_index("coolant")]
            chilling = tc > CHILL_ON or (chilling and tc > CHILL_OFF)
            if chilling:
                q[_index("coolant")] -= CHILLER_W
        else:
            chilling = False
        rhs = C / PERIOD_S * temp + q + H_AIR * air[k]
        temp = mats[int(st["on"][k]), int(st["grind"][k])] @ rhs
        temps[k] = temp
    keep = t >= 0
    t, air, temps = t[keep], air[keep], temps[keep]
    st = {k: v[keep] for k, v in st.items()}
    return {"t": t, "air": air, "T": temps, **st, "sensors": _sensors(temps, air, rng),
            **_errors(temps, st["z"], rng)}


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


def _errors(temps: np.ndarray, z_mm: np.ndarray, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """dZ, dY (µm) of the wheel against the table from the parts' growths (20 °C reference)."""
    d = temps - 20.0
    n = {name: d[:, _index(name)] for name in NODES}
    h = 600.0 + z_mm                                     # wheelhead's height over the bed, mm
    depth, overhang = 500.0, 550.0
    kappa = ALPHA * (n["col_front"] - n["col_rear"]) / depth        # 1/mm, front longer: tips back
    column = ALPHA * h * 0.5 * (n["col_front"] + n["col_rear"])
    dz = (ALPHA * 400.0 * n["bed"] + column - ALPHA * 180.0 * n["wheelhead"]
          - ALPHA * 120.0 * n["table"] + kappa * h * overhang)
    dy = -kappa * h**2 / 2.0 + ALPHA * 260.0 * n["spindle"] + ALPHA * 90.0 * n["wheelhead"]
    noise = 0.15
    return {"E_dZ": 1e3 * dz + noise * rng.standard_normal(dz.size),
            "E_dY": 1e3 * dy + noise * rng.standard_normal(dy.size)}


def day_starts() -> list[datetime]:
    return [FIRST_DAY + timedelta(days=k) for k in range(DAYS)]
