r"""``pde66``: a machine simulated by DISTRIBUTED physics (issue 34, "a simulated machine that is not
yours"; stop 66).

Every simulated record measured on before (conf/sim, bench_other_machine, new_machines5x,
trunnion63, portal64, edm65) is a lumped thermal network: a few nodes, first-order exchanges, the
structure of the lag bank / Hammerstein families.  This one is a finite-difference (method of
lines) model of a vertical machining centre on a grid of 194 nodes, integrated by an implicit
Euler written here (numpy only, 20 s steps, 3 per 60 s sample), the errors integrals of
alpha dT along the structural loop.  Written down (physics, parameters, sensors, campaigns,
records, the planted effect) and committed BEFORE any model ran on it; seeds 6611 and 6612
fixed beforehand.  ``python benchmarks/pde66.py ROOT`` writes the four datasets (the contract:
a folder + ``campaigns.csv``) under ROOT.

The structure (SI units; steel / cast iron: rho c = 3.61e6 J/(m^3 K), alpha = 11 µm/(m K))
------------------------------------------------------------------------------------------
* spindle SHAFT: a 1-D rod, 20 nodes of 20 mm (0.4 m, d 70 mm: C 278 J/K, axial G 8.7 W/K a
  node pair), node 0 the nose.  It points down: node k sits 1.3 + 0.02 k m above the floor.
* spindle HOUSING: a 1-D rod beside it, 20 nodes (C 1700 J/K, axial G 59 W/K).  Shaft node k
  exchanges with housing node k through the internal air, G = (20 + 10 n^0.8) x 4.4e-3 W/K
  (n in krpm: forced convection), and through the bearings (3 W/K) at node 2 (front) and 16
  (rear); the housing's outer face with the hall air at its height, (8 + 3 n^0.5) x 0.0126 W/K
  a node; the nose (shaft node 0) with the air, (10 + 15 n^0.8) x 0.004 W/K.
* BEARING friction while the spindle turns: front 1.1 n^1.8 W, rear 0.5 n^1.8 W (half into the
  shaft, half into the housing node); the built-in motor: rotor 0.8 n^1.5 W on shaft nodes
  8..12, stator 40 + 3 n W on housing nodes 8..12.
* COOLANT loop: housing nodes 4..16 exchange 4 W/K each with the tank node (the jacket, while
  the pump runs: whenever the machine is powered, the whole campaign; 0.3 W/K when off).
  The tank: C 2e5 J/K, 40 W pump heat, 4 W/K to the hall; a THERMOSTAT chiller with
  hysteresis (on above 20.4 °C, off below 19.6 °C, the state remembered) removes 500 W while on.
* COLUMN: a 2-D grid in its vertical plane of symmetry, 20 heights x 6 depths (0.1 m x 0.1 m
  cells, 0.6 m wide, a box of solidity 0.25: C 5400 J/K, G 7.5 W/K vertical and horizontal);
  row iz at 0.55 + 0.1 iz m (its foot on the bed at 0.5 m); depth iy = 0 the FRONT face (the
  spindle side), iy = 5 the back.  Front and back faces exchange with the air at their height,
  5 W/(m^2 K) x 0.06 m^2; the BACK face is blown by the HVAC outlet while the HVAC runs,
  12 W/(m^2 K); the sides 0.1 W/K a node.  The spindle housing's top node (19) is bolted to the
  column front at rows 11 and 12 (6 W/K each).  The foot row exchanges with bed nodes 1..5
  (4 W/K per column node, depth iy onto bed node 1 + iy // 1.25).
* the electrical CABINET on the column back: a node (C 3e4 J/K) with 150 W while powered,
  2 W/K to each of column back rows 14..16, 3 W/K to the air at 2.0 m.
* BED: a 1-D rod along X, 16 nodes of 0.1 m (C 21600 J/K, axial G 30 W/K), 4 W/K each to the
  floor, 0.5 W/K to the air at 0.5 m; the X drive 30 W at node 15 while powered.  The column
  foot stands on x 0.1-0.6 m, the table over x 1.0 m (node 10).
* Y BALL SCREW (in the bed under the table): a 1-D rod of 16 nodes of 50 mm (d 40 mm: C 227
  J/K, axial G 1.13 W/K, 0.063 W/K each to the air at 0.45 m), node 0 its fixed bearing
  (2 W while powered, 0.5 W/K to bed node 10).  The NUT is a MOVING heat source: 6 W into the
  node under it while the spindle cuts, and 1.5 J per mm travelled into the node it arrives at.

The hall (per campaign, from the seed)
-------------------------------------
Air T(t, z) = L + A cos(2 pi (h - 15) / 24) + c(t) + e(t) + g(t) (z - 1.0): level L ~ U(19, 23)
°C, day amplitude A ~ U(0.5, 1.5) K (h the hour of day), the HVAC's on/off cycling c(t) (+-0.25 K,
period U(25, 40) min, through a 5 min lag), an HVAC OUTAGE (p 0.6 a campaign, start U(1, H - 2)
h, U(1, 2.5) h long: the cycling and the back face's forced convection stop, the air goes
towards L + 1.5 K with a 1 h lag and back after), the vertical stratification g = 0.4 K/m (1.0
K/m during an outage).  The floor is L - 0.5 °C.  Each campaign starts at power-on after a
night: the steady state of the powered-off machine in the start's air.

The errors at the tool (µm; dT = T - 20 °C of each node; sums over cells of their length)
--------------------------------------------------------------------------------------------
::

  E_X = 11 sum_{bed i=3..9} dT_i 0.1                     (the bed between column and table)
  E_Z = 11 sum_{iz=0..11} mean_iy dT 0.1                 (the column's growth to the head)
        - 11 sum_{housing k=2..19} dT_k 0.02              (the housing, mount to front bearing)
        - 11 sum_{shaft k=0..1} dT_k 0.02                 (the shaft before the front bearing)
        - 11 0.5 mean_{bed i=8..12} dT_i                  (the bed's height under the table)
        + 0.35 theta                                      (the tilt x the head's overhang)
  E_Y = -(delta + 0.4 theta)                              (the column's bend, the tool below)
  kappa(z) = 11 (dT_front - dT_back) / 0.5 µm/m^2 per row, theta = sum_{iz=0..11} kappa 0.1,
  delta = sum_{iz=0..11} kappa (1.7 - z_iz) 0.1

The probe measures each every sample: noise 0.4 µm (sd), steps of 0.1 µm.

Sensors (16, at grid nodes; Pt100: 0.02 K noise, a 60 s lag, the air's 120 s)
--------------------------------------------------------------------------------
T_amb (air at 1.0 m), T_amb_top (air at 2.5 m), T_spindle_front / _mid / _rear (housing nodes 3,
10, 17), T_coolant (the tank; QUANTISED to 0.1 K), T_col_front_low / _mid / _top (column front
rows 2, 9, 17), T_col_back_low / _top (back rows 2, 17), T_cabinet, T_bed_left / _mid / _right
(bed nodes 1, 8, 14), T_yscrew (the screw's fixed bearing, node 0).  States: S_spindle_rpm,
S_pos_Y (the table's Y, mm).  Declared inputs are the default ``T_*``.

The campaigns and the records
-----------------------------
A campaign: H ~ U{6..12} h at 60 s, from U(6, 9) h on its day (campaign k on 2027-04-05 + k
days).  Its duty d ~ U(0.3, 0.9) and top speed from {6000, 9000, 12000} rpm; jobs U(10, 60) min
at 0.25 / 0.5 / 0.75 / 1 x the top speed (500 rpm steps), within a job cuts of U(3, 15) min and
pauses making the duty d; 2-15 min set-ups (spindle off) between jobs; with p 0.5 the last
U(1, 3) h idle (the machine powered, the spindle off: a cool-down).  Y: within a job around a
centre U(100, 700) mm (+-50 mm a sample while cutting), 0 (home) between jobs.

Records: ``pde6611`` (seed 6611) and ``pde6612`` (seed 6612), the same machine, 20 campaigns
each (C01..C20), the last 5 (1/4) ``split=test``, the rest train.

The planted effect (not in the declared inputs) and its clean copy
------------------------------------------------------------------
``pde66xx_planted``: the same record but the Y axis is SEMI-CLOSED LOOP (the rotary encoder
on the screw, no linear scale), so E_Y also holds the screw's thermal growth up to the nut:
``+ 11.5 sum_i dT_i overlap(i, [0, y]) µm`` (screw nodes, dT against the 20 °C of the pitch
calibration, y = S_pos_Y).  ``pde66xx`` (clean): the linear scale, no such term; the screw's
field and T_yscrew are computed and written in both.  ``diagnose`` should find S_pos_Y (with a
screw temperature) on E_Y of the planted copy, and nothing on S_pos_Y in the clean one.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

RHO_C = 3.61e6
ALPHA = 11.0                   # µm / (m K)
ALPHA_SCREW = 11.5
DT = 20.0                      # implicit Euler step (s)
SAMPLE = 60.0
SUB = int(SAMPLE / DT)
N_CAMPAIGNS, N_TEST = 20, 5
SEEDS = {"pde6611": 6611, "pde6612": 6612}

SHAFT, HOUSING = np.arange(0, 20), np.arange(20, 40)
COL0, NZ, NY = 40, 20, 6
BED, SCREW = np.arange(160, 176), np.arange(176, 192)
TANK, CAB = 192, 193
N = 194


def col(iz: int, iy: int) -> int:
    return COL0 + iz * NY + iy


def heights() -> np.ndarray:
    """Height (m) of each node's surroundings: the air it exchanges with."""
    z = np.zeros(N)
    z[SHAFT] = z[HOUSING] = 1.3 + 0.02 * np.arange(20)
    for iz in range(NZ):
        for iy in range(NY):
            z[col(iz, iy)] = 0.55 + 0.1 * iz
    z[BED], z[SCREW], z[TANK], z[CAB] = 0.5, 0.45, 0.5, 2.0
    return z


Z_AIR = heights()


def capacities() -> np.ndarray:
    c = np.empty(N)
    c[SHAFT], c[HOUSING] = 278.0, 1700.0
    c[COL0:COL0 + NZ * NY] = 5400.0
    c[BED], c[SCREW], c[TANK], c[CAB] = 21600.0, 227.0, 2e5, 3e4
    return c


def links(n_krpm: float, pump: bool, hvac: bool) -> tuple[list, np.ndarray, np.ndarray]:
    """(node-node links (i, j, G), G to the air per node, G to the floor per node)."""
    pairs = []
    for k in range(19):
        pairs += [(SHAFT[k], SHAFT[k + 1], 8.7), (HOUSING[k], HOUSING[k + 1], 59.0)]
    for k in range(20):
        pairs.append((SHAFT[k], HOUSING[k], (20 + 10 * n_krpm ** 0.8) * 4.4e-3))
    pairs += [(SHAFT[2], HOUSING[2], 3.0), (SHAFT[16], HOUSING[16], 3.0)]
    for k in range(4, 17):
        pairs.append((HOUSING[k], TANK, 4.0 if pump else 0.3))
    for iz in range(NZ):
        for iy in range(NY):
            if iz + 1 < NZ:
                pairs.append((col(iz, iy), col(iz + 1, iy), 7.5))
            if iy + 1 < NY:
                pairs.append((col(iz, iy), col(iz, iy + 1), 7.5))
    pairs += [(HOUSING[19], col(11, 0), 6.0), (HOUSING[19], col(12, 0), 6.0)]
    pairs += [(CAB, col(iz, NY - 1), 2.0) for iz in (14, 15, 16)]
    pairs += [(col(0, iy), BED[1 + int(iy / 1.25)], 4.0) for iy in range(NY)]
    for i in range(15):
        pairs += [(BED[i], BED[i + 1], 30.0), (SCREW[i], SCREW[i + 1], 1.13)]
    pairs.append((SCREW[0], BED[10], 0.5))
    air = np.zeros(N)
    air[HOUSING] = (8 + 3 * n_krpm ** 0.5) * 0.0126
    air[SHAFT[0]] = (10 + 15 * n_krpm ** 0.8) * 0.004
    for iz in range(NZ):
        for iy in range(NY):
            air[col(iz, iy)] += 0.1
        air[col(iz, 0)] += 5.0 * 0.06
        air[col(iz, NY - 1)] += (12.0 if hvac else 5.0) * 0.06
    air[BED], air[SCREW], air[TANK], air[CAB] = 0.5, 0.063, 4.0, 3.0
    floor = np.zeros(N)
    floor[BED] = 4.0
    return pairs, air, floor


def conductance(n_krpm: float, pump: bool, hvac: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    pairs, air, floor = links(n_krpm, pump, hvac)
    k = np.zeros((N, N))
    for i, j, g in pairs:
        k[i, i] += g
        k[j, j] += g
        k[i, j] -= g
        k[j, i] -= g
    k[np.diag_indices(N)] += air + floor
    return k, air, floor


class Stepper:
    """Implicit Euler: (C/dt + K) T+ = C/dt T + Q + G_air T_air + G_floor T_floor, the matrix
    inverted once per (speed, pump, HVAC) state."""

    def __init__(self):
        self.c = capacities()
        self.cache: dict = {}

    def system(self, n_krpm, pump, hvac):
        key = (round(n_krpm, 3), pump, hvac)
        if key not in self.cache:
            k, air, floor = conductance(n_krpm, pump, hvac)
            self.cache[key] = (np.linalg.inv(np.diag(self.c / DT) + k), air, floor, k)
        return self.cache[key]

    def step(self, t, n_krpm, pump, hvac, q, t_air, t_floor):
        inv, air, floor, _ = self.system(n_krpm, pump, hvac)
        return inv @ (self.c / DT * t + q + air * t_air + floor * t_floor)

    def steady(self, t_air, t_floor):
        _, air, floor, k = self.system(0.0, False, True)
        return np.linalg.solve(k, air * t_air + floor * t_floor)


def heat(n_krpm: float, cutting: bool, chiller: bool, nut_node: int | None, travel_mm: float,
         arrive_node: int) -> np.ndarray:
    """Heat (W) into each node while powered."""
    q = np.zeros(N)
    if n_krpm > 0:
        front, rear = 1.1 * n_krpm ** 1.8, 0.5 * n_krpm ** 1.8
        q[SHAFT[2]] += front / 2
        q[HOUSING[2]] += front / 2
        q[SHAFT[16]] += rear / 2
        q[HOUSING[16]] += rear / 2
        q[SHAFT[8:13]] += 0.8 * n_krpm ** 1.5 / 5
        q[HOUSING[8:13]] += (40 + 3 * n_krpm) / 5
    q[TANK] += 40.0 - (500.0 if chiller else 0.0)
    q[CAB] += 150.0
    q[BED[15]] += 30.0
    q[SCREW[0]] += 2.0
    if cutting and nut_node is not None:
        q[SCREW[nut_node]] += 6.0
    q[SCREW[arrive_node]] += 1.5 * travel_mm / SAMPLE
    return q


def hall(rng, hours: int, start_h: float):
    """The hall on a 20 s grid: (air at 1.0 m, stratification K/m, HVAC on) per step, the floor."""
    n = int(hours * 3600 / DT) + 1
    t = np.arange(n) * DT
    level, amp = rng.uniform(19, 23), rng.uniform(0.5, 1.5)
    period = rng.uniform(25, 40) * 60
    outage = np.zeros(n, bool)
    if rng.random() < 0.6:
        o0 = rng.uniform(1, hours - 2) * 3600
        outage = (t >= o0) & (t < o0 + rng.uniform(1, 2.5) * 3600)
    square = np.where((t / period) % 1 < 0.5, 0.25, -0.25)
    cyc, e = np.zeros(n), np.zeros(n)
    a5, a60 = 1 - np.exp(-DT / 300), 1 - np.exp(-DT / 3600)
    for i in range(1, n):
        cyc[i] = cyc[i - 1] + a5 * ((0.0 if outage[i] else square[i]) - cyc[i - 1])
        e[i] = e[i - 1] + a60 * ((1.5 if outage[i] else 0.0) - e[i - 1])
    hour = start_h + t / 3600
    air = level + amp * np.cos(2 * np.pi * (hour - 15) / 24) + cyc + e
    grad = np.where(outage, 1.0, 0.4)
    return air, grad, ~outage, level - 0.5, {"hall_c": round(level, 2), "outage": bool(outage.any())}


def programme(rng, hours: int):
    """Per sample: spindle speed (rpm), cutting (bool), Y (mm)."""
    n = hours * 60
    rpm, cut, y = np.zeros(n), np.zeros(n, bool), np.zeros(n)
    duty, top = rng.uniform(0.3, 0.9), rng.choice([6000, 9000, 12000])
    end = n - (int(rng.uniform(1, 3) * 60) if rng.random() < 0.5 else 0)
    i = 0
    while i < end:
        length = int(rng.uniform(10, 60))
        speed = round(top * rng.choice([0.25, 0.5, 0.75, 1.0]) / 500) * 500
        centre = rng.uniform(100, 700)
        j_end = min(end, i + length)
        while i < j_end:
            c = int(rng.uniform(3, 15))
            pause = int(round(c * (1 - duty) / duty))
            sl = slice(i, min(j_end, i + c))
            rpm[sl], cut[sl] = speed, True
            y[sl] = np.round(centre + rng.uniform(-50, 50, sl.stop - sl.start))
            ps = slice(sl.stop, min(j_end, sl.stop + pause))
            y[ps] = round(centre)
            i = ps.stop
        i += int(rng.uniform(2, 15))
    return rpm, cut, y, {"duty": round(duty, 3), "top_rpm": int(top)}


def lagged(x: np.ndarray, tau: float) -> np.ndarray:
    a = 1 - np.exp(-SAMPLE / tau)
    out = np.empty_like(x)
    out[0] = x[0]
    for i in range(1, len(x)):
        out[i] = out[i - 1] + a * (x[i] - out[i - 1])
    return out


SENSORS = {"T_spindle_front": HOUSING[3], "T_spindle_mid": HOUSING[10],
           "T_spindle_rear": HOUSING[17], "T_coolant": TANK,
           "T_col_front_low": col(2, 0), "T_col_front_mid": col(9, 0),
           "T_col_front_top": col(17, 0), "T_col_back_low": col(2, NY - 1),
           "T_col_back_top": col(17, NY - 1), "T_cabinet": CAB, "T_bed_left": BED[1],
           "T_bed_mid": BED[8], "T_bed_right": BED[14], "T_yscrew": SCREW[0]}


def errors(temps: np.ndarray, y_mm: np.ndarray) -> dict:
    """E_X, E_Y, E_Z (clean) and the screw's growth to the nut (µm) from the node temperatures."""
    d = temps - 20.0
    e_x = ALPHA * d[:, BED[3:10]].sum(1) * 0.1
    front = np.stack([d[:, col(iz, 0)] for iz in range(12)], 1)
    back = np.stack([d[:, col(iz, NY - 1)] for iz in range(12)], 1)
    mean = np.stack([d[:, [col(iz, iy) for iy in range(NY)]].mean(1) for iz in range(12)], 1)
    kappa = ALPHA * (front - back) / 0.5
    z = 0.55 + 0.1 * np.arange(12)
    theta = (kappa * 0.1).sum(1)
    delta = (kappa * (1.7 - z) * 0.1).sum(1)
    e_z = (ALPHA * mean.sum(1) * 0.1 - ALPHA * d[:, HOUSING[2:20]].sum(1) * 0.02
           - ALPHA * d[:, SHAFT[0:2]].sum(1) * 0.02 - ALPHA * 0.5 * d[:, BED[8:13]].mean(1)
           + 0.35 * theta)
    e_y = -(delta + 0.4 * theta)
    lo = 0.05 * np.arange(16)
    overlap = np.clip(y_mm[:, None] / 1000.0 - lo[None, :], 0.0, 0.05)
    screw = ALPHA_SCREW * (d[:, SCREW] * overlap).sum(1)
    return {"E_X": e_x, "E_Y": e_y, "E_Z": e_z, "screw": screw}


def campaign(rng, stepper: Stepper, start_h: float):
    hours = int(rng.integers(6, 13))
    air, grad, hvac, floor, meta = hall(rng, hours, start_h)
    rpm, cut, y, pmeta = programme(rng, hours)
    n = hours * 60
    temps = stepper.steady(air[0] + grad[0] * (Z_AIR - 1.0), floor)
    node = np.empty((n, N))
    chiller = False
    nut_prev = 0.0
    for s in range(n):
        node[s] = temps
        nut = int(np.clip(y[s] / 50.0, 0, 15))
        travel = abs(y[s] - nut_prev)
        nut_prev = y[s]
        for k in range(SUB):
            i = s * SUB + k
            chiller = temps[TANK] > 20.4 or (chiller and temps[TANK] > 19.6)
            q = heat(rpm[s] / 1000.0, bool(cut[s]), chiller, nut, travel, nut)
            t_air = air[i] + grad[i] * (Z_AIR - 1.0)
            temps = stepper.step(temps, rpm[s] / 1000.0, True, bool(hvac[i]), q, t_air, floor)
    a_lo = air[::SUB][:n] + grad[::SUB][:n] * (1.0 - 1.0)
    a_hi = air[::SUB][:n] + grad[::SUB][:n] * (2.5 - 1.0)
    frame = {"time": np.arange(n) * SAMPLE}
    noise = 0.02
    frame["T_amb"] = lagged(a_lo, 120) + rng.normal(0, noise, n)
    frame["T_amb_top"] = lagged(a_hi, 120) + rng.normal(0, noise, n)
    for name, idx in SENSORS.items():
        v = lagged(node[:, idx], 60) + rng.normal(0, noise, n)
        frame[name] = np.round(v, 1) if name == "T_coolant" else np.round(v, 3)
    frame["T_amb"], frame["T_amb_top"] = np.round(frame["T_amb"], 3), np.round(frame["T_amb_top"], 3)
    e = errors(node, y)
    probe = {k: rng.normal(0, 0.4, n) for k in ("E_X", "E_Y", "E_Z")}
    clean = {k: np.round(e[k] + probe[k], 1) for k in probe}
    planted = dict(clean, E_Y=np.round(e["E_Y"] + e["screw"] + probe["E_Y"], 1))
    states = {"S_spindle_rpm": rpm, "S_pos_Y": y}
    return (pd.DataFrame({**frame, **clean, **states}), pd.DataFrame({**frame, **planted, **states}),
            {**meta, **pmeta, "hours": hours})


def record(seed: int):
    rng = np.random.default_rng(seed)
    stepper = Stepper()
    rows, clean, planted = [], {}, {}
    for k in range(N_CAMPAIGNS):
        cid = f"C{k + 1:02d}"
        start_h = float(rng.uniform(6, 9))
        c, p, meta = campaign(rng, stepper, start_h)
        clean[cid], planted[cid] = c, p
        start = pd.Timestamp("2027-04-05") + pd.Timedelta(days=k) + pd.Timedelta(
            minutes=round(start_h * 60))
        rows.append({"campaign": cid, "file": f"{cid}.csv",
                     "split": "test" if k >= N_CAMPAIGNS - N_TEST else "train",
                     "start": start.isoformat(), **meta})
    return pd.DataFrame(rows), clean, planted


def write(root: Path) -> None:
    for name, seed in SEEDS.items():
        manifest, clean, planted = record(seed)
        for suffix, frames in (("", clean), ("_planted", planted)):
            folder = root / f"{name}{suffix}"
            folder.mkdir(parents=True, exist_ok=True)
            for cid, frame in frames.items():
                frame.to_csv(folder / f"{cid}.csv", index=False, float_format="%.6g")
            manifest.to_csv(folder / "campaigns.csv", index=False)


if __name__ == "__main__":
    write(Path(sys.argv[1]).resolve())
