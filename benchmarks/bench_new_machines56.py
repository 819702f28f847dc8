"""Two machines nobody has tuned on, end to end as a stranger (issue 34, session 56).

    .venv/bin/python benchmarks/bench_new_machines56.py write DIR   # the lab's files only
    .venv/bin/python benchmarks/bench_new_machines56.py all DIR     # write, init, run, diagnose, table
    (or one step: init | run | diagnose | table | forensics DIR, on what the steps before wrote)

The physics below was written down before any model ran on these records; nothing was tuned on
them (seeds 5671 / 5672 fixed beforehand, every command run once).  Both differ from
``apps/sim`` (VMC, Swiss lathe, large mill, climate room) and ``bench_other_machine.py`` (a
lathe whose heat comes from its spindle, errors linear in the rises times a room-level factor).

``grinder`` -- a surface grinder whose dominant source is its COOLANT
----------------------------------------------------------------------
Lumped network (C J/K, hA W/K to the room): coolant ``tank`` (300 l of water-based coolant and
its steel tank, 1.4e6, 60 -- a wide open tank, evaporation), ``table`` with the chucked part
(2.5e5, 12), ``bed`` (1.5e6, 25) and its unmeasured ``bed_core`` (1.5e6, 0), ``column``
(6e5, 15), ``wheelhead`` (8e4, 6), wheel ``motor`` (2.5e4, 5), and ``bore``: a probe in a deep
bore of the column (2e4, 0; 8 W/K to the column: it lags the column by ~40 min).  Fixed links
(W/K): motor-wheelhead 4, wheelhead-column 5, column-bed 10, bed-table 3 (guideways),
bed-bed_core 25, column-bore 8, tank-bed 1.5 (floor, hoses).  While the coolant flows
(state ``S_coolant`` = 1) three more links exist: tank-table 80 (the flood over table and part,
back to the tank), tank-bed 15 (the return channel in the bed), tank-wheelhead 8 (splash on the
guard): the network switches between two propagators.  Heat: the wheel motor 80 W while the wheel
turns (+5 % of the grinding power), 40 W of spindle bearings into the wheelhead, the pump 250 W
into the tank while the coolant flows, the table's hydraulic drive 60 W into the bed while
grinding, and the grinding power P (0.3 / 0.6 / 1.0 kW, logged) 80 % into the coolant and 10 %
into the table and part (only with coolant: nobody grinds dry).  No chiller: the tank drifts with
the room and the load (steady rise ~10 K, ~6 h time constant).  The programme: blocks of 10-60 min
of idle (all off), set-up (wheel on, coolant off), dressing / spark-out (coolant on, P 0.3 kW),
grinding (coolant on, P 0.6 or 1.0 kW).  The room: a shop without air conditioning, a run's base
level 17-29 °C (the season), a day swing of +-1.5 K (runs start 6:00-14:00) and noise; the
machine (and the coolant) soaked at the room's first value.  Errors, linear in the node rises
since the run's start (µm/K): ``E_Y`` (wheel to table, the infeed: wheelhead growth)
= 6 column + 2.5 wheelhead + 0.8 motor - 5 table - 2 bed_core; ``E_Z`` (cross feed)
= 3 wheelhead - 2 column + 1.5 bed - 1.5 bed_core + 1 table.  16 Pt100s at 30 s (0.02 K noise,
0.01 K steps): the tank, the coolant return (0.7 table + 0.3 tank), table x3, bed x2, column x2,
the bore probe, wheelhead x3, motor, the electrics cabinet (0.5 motor + 0.5 column), the room.
12 runs of 4-10 h, a folder of ``Lauf_01.csv`` ... without a manifest, German headers with units,
``;`` and decimal commas; ``E_Z`` in mm; the last 3 runs test (``data.test_fraction=0.25``).

``gantry`` -- a 5-axis gantry whose two columns are heated unequally (a yaw)
------------------------------------------------------------------------------
The gantry travels along X on two columns (rails) 3 m apart; the crossbeam carries the head
across Y.  Nodes: ``col_L`` and ``col_R`` (7e5, 18 each), ``beam`` (6e5, 15), ``head``
(6e4, 6), spindle ``motor`` (2.5e4, 5), ``bearing`` (6e3, 1.5), ``bed`` (4e6, 40) and its
unmeasured ``bed_core`` (3e6, 0), the hydraulic unit ``hyd`` bolted to the LEFT column
(1.5e5, 10), the X drives ``xdrive_L`` (master, 1.5e4, 3) and ``xdrive_R`` (1.5e4, 3).  Links:
motor-head 4, bearing-head 6, head-beam 5, beam-col_L 6, beam-col_R 6, col_L-bed 12,
col_R-bed 12, bed-bed_core 40, hyd-col_L 15, xdrive_L-col_L 5, xdrive_R-col_R 5.  Heat: motor
40 + 25 k + 3 k^2 W (k = krpm, 0-8 krpm), bearing 8 k W, hydraulics 400 W while on (two shifts,
Mon-Fri 6-22 h), X drives 50 W (left, master) / 25 W (right) while on.  Room: 20 °C, +-2.5 K
day/night (the hall), 1 K cooler at the weekend; the second week 1.5 K warmer (spring).  The
left column runs warmer than the right: the columns grow unequally along X, the crossbeam yaws
by theta = alpha H (dT_L - dT_R) / span (alpha 11.5e-6/K, H = span), and the tool at Y (mm from
the beam's middle) moves in X by theta * Y: a PRODUCT of the columns' temperature difference and
the Y position (``S_Y``, logged), ~17 µm per K of difference at the beam's end.
``E_X`` = 3 head + 2 beam - 1.5 bed_core + 11.5e-3 (dT_L - dT_R) Y µm;
``E_Z`` = 3 (col_L + col_R) + 3 head + 2 bearing - 2 bed_core (rises since the record's start).
The programme: blocks of 10-90 min at 0/2/4/6/8 krpm at a Y position drawn in -1400..1400 mm;
off shift the head parks at Y = +1200.  30 sensors at 60 s: each column x5 (pure and mixed with
the beam or the bed), beam x5, head x4, motor, bearing, hydraulic unit, X drives x2, bed x4,
one mixed (0.5 col_L + 0.5 hyd), the room; ``E_X``/``E_Z`` in µm; states ``S_Y`` (mm),
spindle speed, hydraulics on.  Two contiguous weeks, two files (``week_47.csv``, ``week_48.csv``),
ISO time stamps, English headers with units, ``,``; the second file test (``test_fraction=0.5``).

What the ``left out`` variants withhold (diagnose only): ``grinder-nocoolant`` ignores the tank,
the coolant return and ``S_coolant`` (``data.roles.ignore``): the dominant source's only direct
measurements; ``gantry-noY`` ignores ``S_Y``: nothing then measures the yaw's lever.

Measured (2026-11-30, one run, 2 shared cores at load ~4.8; ``run`` then ``table``).  Test RMSE
(µm) per target, ratio to MLR's, CPU s (user + sys of one ``thermocomp run``, ~2 s of it start-up),
simulation mode, the defaults, ``init``'s config::

    grinder (E_Zustellung_dY / E_Querachse_dZ)      gantry (E_X_error / E_Z_error)
      mlr            0.63 / 0.35  1.00 / 1.00   2.3     27.33 / 0.38  1.00 / 1.00    2.5
      pcr            1.89 / 0.90  3.02 / 2.55   2.5     30.36 / 5.31  1.11 / 13.83   2.6
      arx            0.61 / 0.35  0.97 / 0.98   2.7     28.16 / 1.30  1.03 / 3.39    2.7
      lagbank        0.78 / 0.33  1.24 / 0.94   3.3     27.22 / 0.38  1.00 / 0.98    5.4
      hammerstein    0.78 / 0.35  1.24 / 0.99   4.6     13.95 / 0.52  0.51 / 1.34   11.2
      lstm           0.64 / 0.35  1.02 / 1.00  28.0     28.87 / 0.38  1.06 / 1.00   40.7
      auto           0.60 / 0.35  0.95 / 0.99  25.4     15.13 / 0.36  0.55 / 0.95   33.9
      mlr ati=cmeans 0.64 / 0.40  1.03 / 1.14   4.3     (skipped: one train record, one ambient level)
      persistence    0.43 / 0.43  0.68 / 1.22           6.30 / 0.47  0.23 / 1.23

``auto`` beats MLR on both records and both targets; against the best single family: grinder
E_Y 0.595 vs arx 0.607 (better), E_Z 0.351 vs lagbank 0.334 (+5 %), gantry E_X 15.13 vs
hammerstein 13.95 (+8.5 %), E_Z 0.364 vs lagbank 0.378 (better): within 10 % on all four.  Its
blends (``metrics.json`` targets.*.auto): grinder E_Y ati 0.49 / lstm 0.28 / mlr 0.19 / arx 0.04,
E_Z mlr 0.44 / ati 0.37 / arx 0.13; gantry E_X hammerstein 0.81 / lagbank 0.19 (5 forward folds
of the one train week; ATI skipped: 1 ambient level), E_Z lagbank 0.52 / mlr 0.42 / lstm 0.06.
No family but Hammerstein (its state inputs) sees the yaw: E_X stays at MLR's 27 µm, persistence
6.3.  ``mlr ati=cmeans`` on the grinder: one interval (the elbow), with the ambient interaction
(9 runs at 9 levels 18.9-29.1 °C); the grinder has no ambient law, the interaction's CV SM looked
better than MLR's (auto's folds: 0.405 vs 0.438 on E_Z) and the test was worse, mostly Lauf_12
at 29.0 °C, the warm edge of the train levels (0.52 vs the single model's 0.31 Rsd): a 9-run CV
that did not hold, no defect found; ``auto`` gave it 0.37 of E_Z and stayed at MLR's 0.35.

``diagnose`` (MLR; test RMSE before -> after; CPU s):

* ``grinder``: accepts nothing (E_Y 0.626, E_Z 0.354 unchanged); 5.2 s.
* ``gantry``: E_X 27.33 -> 1.55: ``S_Y_position`` x rise of T01 (left column) and x rise of T08
  (right column, 0.8 col_R + 0.2 bed): the planted yaw, both columns; E_Z 0.384 -> 0.343 (a 4 h
  lag of the inputs: the unmeasured bed core).  11.8 s.
* ``gantry-noY`` (the lever withheld): E_X unchanged (nothing to find it with; no harm), E_Z
  the same lag, 0.384 -> 0.343.  9.2 s.
* ``grinder-nocoolant`` (tank, return, ``S_coolant`` withheld): the coolant is not found (the
  grinding power's lags gain < 1 %); it accepts (dT_amb)^2 on E_Y: 0.644 -> 0.674, **+4.7 %,
  above the 2 % of issue 34**; E_Z unchanged.  5.7 s.

Forensics of that harm (``forensics``: least squares on the 13 kept temperatures reproduces
``run``'s MLR and the diagnosed model to 3 digits).  In CV every one of the 9 held-out runs
gained, 13-46 % of its MSE (p 1/512, the smallest 9 runs allow; family-wise 0.006; in-range gain
16 %; the 95 % bound of the gain positive).  On the test Lauf_11 / Lauf_12 gained as in CV (0.633
-> 0.537, 0.480 -> 0.381) and Lauf_10 lost (0.739 -> 0.917): its residual mean was +0.65 and
moved to +0.84.  The square's own term there is 0.09 µm rms; the prediction moved 0.25 µm rms,
through the refitted temperatures (coefficients changed by up to 0.93 against 5.0): the room's
change squared stood in, in those 9 runs, for the withheld tank, and Lauf_10 -- a heavy load
(tank +7.1 K) with a quiet room ((dT_amb)^2 <= 0.81, inside the train range 0.94-6.35, no
extrapolation) -- breaks the proxy.  No fold shows it; the bar's one stricter form at hand
(asking the ``1 - alpha`` Student-t bound of the gain to reach ``min_gain_pct`` also with one
block per unit, as with ranked blocks) would have refused it (bound -2 %) but also refuses
vendor5's real ambient law (``bench_other_machine``: bound -16 %, test 1.39 -> 0.74), while
lathe43 / lathe43m's pass (+17 / +11 %).  So: a proxy for a withheld dominant source that 9
runs cannot tell from an effect, not a defect with a general mend; no src change.
Corrected in session 57 (``bench_diagnose_proxy57.py``): not the tank -- its true rise beyond the
kept temperatures is -0.04..+0.03 K per run and as an input it moves the test RMSE 0.644 -> 0.639
-- but the runs' offsets: 64 % of the CV MSE is in the held-out runs' means, which follow each
run's first-sample probe noise (correlation -0.91); 92 % of the square's CV gain is there, and
Lauf_10's offset (+0.65) met its shift the wrong way.  Still no general mend.

What a stranger met on the way in (``init``), mended since (init56, ``core/io/units.py``): a
``[-]`` column (an on/off flag) was refused as "not a temperature's unit" (``Kühlmittel ein [-]``,
``Hydraulics on [-]``), and once ``data.roles.state`` named it, no role was proposed from the
units any more (the errors in µm / mm were then "no column reads as a measured error"): every
role had to be spelled out; ``Y position [mm]`` would have been proposed as an error (mm).  Now
``init DIR data.test_fraction=...`` alone proposes the roles the hand-spelled ones gave (the same
headers; MLR test RMSE the same to 4 digits: grinder 0.6261 / 0.3542, gantry 27.3341 / 0.3839;
``diagnose`` on init's config, the left-out variants too, gives the figures above).
A header both ignored and given a role is refused with a clear message.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).parent))
from bench_other_machine import thermocomp  # noqa: E402, F401 (bench_diagnose_lag57 calls it here)
from new_machine_steps import Machines  # noqa: E402
from new_machine_steps import main as steps_main  # noqa: E402

from thermocomp.apps.sim.network import Link, Node, ThermalNetwork  # noqa: E402

SEEDS = {"grinder": 5671, "gantry": 5672}


def rounded(x, step):
    return np.round(np.asarray(x) / step) * step


def simulate(nets, switch, room, heat, start):
    """Integrate ``nets[switch[i]]`` over each sample; the machine soaked at ``start`` °C."""
    n = len(room)
    nodes = np.empty((n, heat.shape[1]))
    nodes[0] = nets[0][0].steady_state(start, np.zeros(heat.shape[1]))
    for i in range(1, n):
        nodes[i] = nets[int(switch[i - 1])][1].step(nodes[i - 1], room[i - 1], heat[i - 1])
    return nodes


# --- grinder ------------------------------------------------------------------------------

G_NODES = {"tank": (1.4e6, 60.0), "table": (2.5e5, 12.0), "bed": (1.5e6, 25.0),
           "bed_core": (1.5e6, 0.0), "column": (6e5, 15.0), "wheelhead": (8e4, 6.0),
           "motor": (2.5e4, 5.0), "bore": (2e4, 0.0)}
G_LINKS = (("motor", "wheelhead", 4.0), ("wheelhead", "column", 5.0), ("column", "bed", 10.0),
           ("bed", "table", 3.0), ("bed", "bed_core", 25.0), ("column", "bore", 8.0),
           ("tank", "bed", 1.5))
G_FLOW = (("tank", "table", 80.0), ("tank", "bed", 15.0), ("tank", "wheelhead", 8.0))
G_GAINS = {"E_Y": {"column": 6.0, "wheelhead": 2.5, "motor": 0.8, "table": -5.0, "bed_core": -2.0},
           "E_Z": {"wheelhead": 3.0, "column": -2.0, "bed": 1.5, "bed_core": -1.5, "table": 1.0}}
G_SENSORS = [("Kühlmitteltank", "tank", "tank", 1.0), ("Kühlmittelrücklauf", "table", "tank", 0.7),
             ("Tisch links", "table", "table", 1.0), ("Tisch rechts", "table", "bed", 0.9),
             ("Werkstück", "table", "tank", 0.85), ("Bett vorn", "bed", "bed", 1.0),
             ("Bett hinten", "bed", "column", 0.8), ("Ständer vorn", "column", "wheelhead", 0.9),
             ("Ständer hinten", "column", "bed", 0.8), ("Ständer Bohrung", "bore", "bore", 1.0),
             ("Schleifkopf", "wheelhead", "wheelhead", 1.0), ("Schleifkopf oben", "wheelhead", "motor", 0.8),
             ("Schleifkopf hinten", "wheelhead", "column", 0.7), ("Motor", "motor", "motor", 1.0),
             ("Schaltschrank", "motor", "column", 0.5)]


def grinder_networks():
    """(network, propagator) with the coolant off (0) and flowing (1), 30 s."""
    nodes = [Node(n, c, h) for n, (c, h) in G_NODES.items()]
    off = ThermalNetwork(nodes, [Link(a, b, g) for a, b, g in G_LINKS])
    links = {(a, b): g for a, b, g in G_LINKS}
    for a, b, g in G_FLOW:
        links[(a, b)] = links.get((a, b), 0.0) + g
    on = ThermalNetwork(nodes, [Link(a, b, g) for (a, b), g in links.items()])
    return [(off, off.propagator(30.0)), (on, on.propagator(30.0))]


def grinder_programme(rng, n, step):
    """Per sample: wheel on, coolant on, grinding power kW (blocks of 10-60 min)."""
    modes = {"idle": (0, 0, 0.0), "setup": (1, 0, 0.0), "dress": (1, 1, 0.3),
             "rough": (1, 1, 1.0), "finish": (1, 1, 0.6)}
    out = np.zeros((n, 3))
    k = 0
    while k < n:
        length = int(rng.uniform(600, 3600) / step) + 1
        out[k:k + length] = modes[rng.choice(list(modes), p=[0.15, 0.1, 0.15, 0.35, 0.25])]
        k += length
    return out


def grinder_run(nets, rng, n, step=30.0):
    net = nets[0][0]
    base = rng.uniform(17.0, 29.0)
    hour0 = rng.uniform(6.0, 14.0)
    hours = hour0 + np.arange(n) * step / 3600
    room = base + 1.5 * np.sin((hours - 9.0) / 24 * 2 * np.pi) + rng.normal(0, 0.05, n).cumsum() * 0.05
    prog = grinder_programme(rng, n, step)
    wheel, coolant, power = prog.T
    heat = np.zeros((n, net.n_nodes))
    ix = net.index
    heat[:, ix["motor"]] = wheel * (80.0 + 50.0 * power)
    heat[:, ix["wheelhead"]] = wheel * 40.0
    heat[:, ix["tank"]] = coolant * (250.0 + 800.0 * power)
    heat[:, ix["table"]] = coolant * 100.0 * power
    heat[:, ix["bed"]] = (power > 0) * 60.0
    nodes = simulate(nets, coolant, room, heat, room[0])
    frame = {"time": np.arange(n) * step}
    for j, (name, a, b, w) in enumerate(G_SENSORS):
        frame[f"T_{j + 1:02d}"] = rounded(w * nodes[:, ix[a]] + (1 - w) * nodes[:, ix[b]]
                                          + rng.normal(0, 0.02, n), 0.01)
    frame["T_amb"] = rounded(room + rng.normal(0, 0.05, n), 0.01)
    rises = nodes - nodes[0]
    for e, gains in G_GAINS.items():
        frame[e] = rounded(sum(g * rises[:, ix[node]] for node, g in gains.items())
                           + rng.normal(0, 0.3, n), 0.1)
    frame["S_coolant"], frame["S_power"], frame["S_wheel"] = coolant, power, wheel * 1800.0
    return pd.DataFrame(frame)


def grinder_lab(frame):
    names = {"time": "Zeit [s]", "E_Y": "Zustellung dY [µm]", "E_Z": "Querachse dZ [mm]",
             "T_amb": "Hallentemperatur [°C]", "S_coolant": "Kühlmittel ein [-]",
             "S_power": "Schleifleistung [kW]", "S_wheel": "Scheibendrehzahl [1/min]"}
    names.update({f"T_{j + 1:02d}": f"{s[0]} [°C]" for j, s in enumerate(G_SENSORS)})
    out = frame.rename(columns=names)
    out["Querachse dZ [mm]"] = out["Querachse dZ [mm]"] / 1000.0
    return out


def write_grinder(folder: Path, seed: int) -> None:
    rng = np.random.default_rng(seed)
    nets = grinder_networks()
    folder.mkdir(parents=True, exist_ok=True)
    for r in range(12):
        n = int(rng.uniform(4, 10) * 120)
        grinder_lab(grinder_run(nets, rng, n)).to_csv(folder / f"Lauf_{r + 1:02d}.csv", sep=";",
                                                      decimal=",", index=False, float_format="%.6g")


# --- gantry -------------------------------------------------------------------------------

P_NODES = {"col_L": (7e5, 18.0), "col_R": (7e5, 18.0), "beam": (6e5, 15.0), "head": (6e4, 6.0),
           "motor": (2.5e4, 5.0), "bearing": (6e3, 1.5), "bed": (4e6, 40.0), "bed_core": (3e6, 0.0),
           "hyd": (1.5e5, 10.0), "xdrive_L": (1.5e4, 3.0), "xdrive_R": (1.5e4, 3.0)}
P_LINKS = (("motor", "head", 4.0), ("bearing", "head", 6.0), ("head", "beam", 5.0),
           ("beam", "col_L", 6.0), ("beam", "col_R", 6.0), ("col_L", "bed", 12.0),
           ("col_R", "bed", 12.0), ("bed", "bed_core", 40.0), ("hyd", "col_L", 15.0),
           ("xdrive_L", "col_L", 5.0), ("xdrive_R", "col_R", 5.0))
P_SENSORS = [("col_L", "col_L", 1.0), ("col_L", "beam", 0.8), ("col_L", "bed", 0.8), ("col_L", "col_L", 1.0),
             ("col_L", "xdrive_L", 0.85), ("col_R", "col_R", 1.0), ("col_R", "beam", 0.8),
             ("col_R", "bed", 0.8), ("col_R", "col_R", 1.0), ("col_R", "xdrive_R", 0.85),
             ("beam", "beam", 1.0), ("beam", "col_L", 0.8), ("beam", "col_R", 0.8), ("beam", "head", 0.85),
             ("beam", "beam", 1.0), ("head", "head", 1.0), ("head", "motor", 0.8), ("head", "bearing", 0.8),
             ("head", "beam", 0.8), ("motor", "motor", 1.0), ("bearing", "bearing", 1.0), ("hyd", "hyd", 1.0),
             ("xdrive_L", "xdrive_L", 1.0), ("xdrive_R", "xdrive_R", 1.0), ("bed", "bed", 1.0),
             ("bed", "col_L", 0.85), ("bed", "col_R", 0.85), ("bed", "bed", 1.0), ("col_L", "hyd", 0.5)]
YAW_UM_PER_K_MM = 11.5e-3      # alpha * H / span * 1000 µm/mm, H = span


def gantry_record(seed, weeks=2, step=60.0):
    rng = np.random.default_rng(seed)
    net = ThermalNetwork([Node(n, c, h) for n, (c, h) in P_NODES.items()],
                         [Link(a, b, g) for a, b, g in P_LINKS])
    ix = net.index
    n = int(weeks * 7 * 86400 / step)
    t = np.arange(n) * step
    hours = t / 3600.0
    day, hour = (hours // 24).astype(int), hours % 24
    weekday = (day % 7) < 5
    shift = weekday & (hour >= 6) & (hour < 22)
    room = (20.0 + 2.5 * np.sin((hour - 9.0) / 24 * 2 * np.pi) - 1.0 * ~weekday + 1.5 * (day >= 7)
            + rng.normal(0, 0.05, n).cumsum() * 0.02)
    rpm = np.zeros(n)
    y = np.full(n, 1200.0)
    k = 0
    while k < n:
        length = int(rng.uniform(600, 5400) / step) + 1
        rpm[k:k + length] = rng.choice([0, 2000, 4000, 6000, 8000])
        y[k:k + length] = rng.uniform(-1400, 1400)
        k += length
    rpm, y = np.where(shift, rpm, 0.0), np.where(shift, np.round(y), 1200.0)
    kr = rpm / 1000.0
    heat = np.zeros((n, net.n_nodes))
    heat[:, ix["motor"]] = np.where(rpm > 0, 40 + 25 * kr + 3 * kr**2, 0.0)
    heat[:, ix["bearing"]] = 8.0 * kr
    heat[:, ix["hyd"]] = 400.0 * shift
    heat[:, ix["xdrive_L"]], heat[:, ix["xdrive_R"]] = 50.0 * shift, 25.0 * shift
    nodes = simulate([(net, net.propagator(step))], np.zeros(n), room, heat, room[0])
    frame = {"time": t}
    for j, (a, b, w) in enumerate(P_SENSORS):
        frame[f"T_{j + 1:02d}"] = rounded(w * nodes[:, ix[a]] + (1 - w) * nodes[:, ix[b]]
                                          + rng.normal(0, 0.02, n), 0.01)
    frame["T_amb"] = rounded(room + rng.normal(0, 0.05, n), 0.01)
    r = nodes - nodes[0]
    yaw = YAW_UM_PER_K_MM * (r[:, ix["col_L"]] - r[:, ix["col_R"]]) * y
    frame["E_X"] = rounded(3 * r[:, ix["head"]] + 2 * r[:, ix["beam"]] - 1.5 * r[:, ix["bed_core"]] + yaw
                           + rng.normal(0, 0.3, n), 0.1)
    frame["E_Z"] = rounded(3 * (r[:, ix["col_L"]] + r[:, ix["col_R"]]) + 3 * r[:, ix["head"]]
                           + 2 * r[:, ix["bearing"]] - 2 * r[:, ix["bed_core"]] + rng.normal(0, 0.3, n), 0.1)
    frame["S_Y"], frame["S_rpm"], frame["S_hyd"] = y, rpm, shift.astype(float)
    return pd.DataFrame(frame), yaw


def write_gantry(folder: Path, seed: int) -> None:
    frame, _ = gantry_record(seed)
    names = {"E_X": "X error [µm]", "E_Z": "Z error [µm]", "T_amb": "Hall air [°C]",
             "S_Y": "Y position [mm]", "S_rpm": "Spindle speed [rpm]", "S_hyd": "Hydraulics on [-]"}
    names.update({f"T_{j + 1:02d}": f"T{j + 1:02d} [°C]" for j in range(len(P_SENSORS))})
    out = frame.rename(columns=names)
    out.insert(0, "Timestamp", (pd.Timestamp("2026-11-16 00:00") + pd.to_timedelta(out.pop("time"), unit="s")
                                ).dt.strftime("%Y-%m-%dT%H:%M:%S"))
    folder.mkdir(parents=True, exist_ok=True)
    half = len(out) // 2
    out.iloc[:half].to_csv(folder / "week_47.csv", index=False, float_format="%.6g")
    out.iloc[half:].to_csv(folder / "week_48.csv", index=False, float_format="%.6g")


def write(root: Path) -> None:
    write_grinder(root / "grinder", SEEDS["grinder"])
    write_gantry(root / "gantry", SEEDS["gantry"])


# --- the pipeline -------------------------------------------------------------------------

FAMILIES = ("mlr", "pcr", "arx", "lagbank", "hammerstein", "lstm", "auto")
# what a stranger adds: the test share (init proposes every role from the units since init56;
# before, each had to be spelled out: the docstring's "What a stranger met on the way in")
INIT_ARGS = {"grinder": ("data.test_fraction=0.25",), "gantry": ("data.test_fraction=0.5",)}

def data_args(root: Path, name: str) -> list[str]:
    """``init``'s config (the lab's folder), plus the variant's ignored columns."""
    base, _, variant = name.partition("-")
    args = [f"hydra.searchpath=[file://{root}/init-{base}/conf]", f"data={base}"]
    if variant:
        args += LEFT_OUT[name]
    return args


# (a header both ignored and given a role is refused: the state's patterns are given again)
LEFT_OUT = {"grinder-nocoolant": ["data.roles.ignore=['Kühlmitteltank*','Kühlmittelrücklauf*',"
                                  "'Kühlmittel ein*']",
                                  "data.roles.state=['Schleifleistung*','Scheibendrehzahl*']"],
            "gantry-noY": ["data.roles.ignore=['Y position*']",
                           "data.roles.state=['Spindle speed*','Hydraulics on*']"]}


def proxy_forensics(root: Path) -> None:
    """Why ``diagnose`` on ``grinder-nocoolant`` raised E_Y's test RMSE: least squares on the
    13 temperatures it keeps (rises since the run's start; the MLR ``run`` fits, to 3 digits),
    with and without (dT_amb)^2, left out per train run, then on the test runs."""
    runs = {}
    for f in sorted((root / "grinder").glob("Lauf_*.csv")):
        d = pd.read_csv(f, sep=";", decimal=",")
        temps = d[[c for c in d.columns if "°C" in c and not c.startswith("Kühlmittel")]]
        room = d["Hallentemperatur [°C]"] - d["Hallentemperatur [°C]"].iloc[0]
        y = d["Zustellung dY [µm]"] - d["Zustellung dY [µm]"].iloc[0]
        rises = (temps - temps.iloc[0]).to_numpy()
        runs[f.stem] = ((rises, np.column_stack([rises, room**2])), y.to_numpy())

    def design(key, extra):
        x = runs[key][0][extra]
        return np.column_stack([x, np.ones(len(x))])

    def fit(keys, extra):
        return np.linalg.lstsq(np.vstack([design(k, extra) for k in keys]),
                               np.concatenate([runs[k][1] for k in keys]), rcond=None)[0]

    def mse(key, w, extra):
        return float(np.mean((design(key, extra) @ w - runs[key][1]) ** 2))

    ids = list(runs)
    train, test = ids[:9], ids[9:]
    for k in train:
        rest = [j for j in train if j != k]
        before, after = mse(k, fit(rest, 0), 0), mse(k, fit(rest, 1), 1)
        print(f"CV  {k}: MSE {before:.3f} -> {after:.3f} (gain {100 * (before - after) / before:.0f} %)")
    w0, w1 = fit(train, 0), fit(train, 1)
    for k in test:
        p0, p1 = design(k, 0) @ w0, design(k, 1) @ w1
        square = w1[-2] * runs[k][0][1][:, -1]
        print(f"test {k}: RMSE {mse(k, w0, 0) ** 0.5:.3f} -> {mse(k, w1, 1) ** 0.5:.3f}; mean residual "
              f"{np.mean(runs[k][1] - p0):+.2f} -> {np.mean(runs[k][1] - p1):+.2f}; prediction moved "
              f"{np.sqrt(np.mean((p1 - p0) ** 2)):.2f} rms, the square's own term "
              f"{np.sqrt(np.mean(square**2)):.2f}")
    print(f"coefficient of (dT_amb)^2 {w1[-2]:.2f} µm/K^2; largest change of a temperature's "
          f"{np.abs(w1[:-2] - w0[:-1]).max():.2f} (largest coefficient {np.abs(w0[:-1]).max():.2f})")
    for k in ids:
        d = pd.read_csv(root / "grinder" / f"{k}.csv", sep=";", decimal=",")
        room = d["Hallentemperatur [°C]"] - d["Hallentemperatur [°C]"].iloc[0]
        tank = d["Kühlmitteltank [°C]"] - d["Kühlmitteltank [°C]"].iloc[0]
        print(f"{k}: max (dT_amb)^2 {float((room**2).max()):.2f}, tank rise {tank.max():.1f} K")


MACHINES = Machines(doc=__doc__, write=write, records=list(SEEDS), families=FAMILIES,
                    init_args=INIT_ARGS, data_args=data_args, variants=LEFT_OUT,
                    ati_records=("grinder",),    # the shop's seasons: a run's room level 17-29 °C
                    forensics=proxy_forensics, diagnose_file="diagnose.json")


def main(argv=None) -> int:
    return steps_main(MACHINES, argv)


if __name__ == "__main__":
    raise SystemExit(main())
