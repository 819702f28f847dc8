"""Two more machines nobody has tuned on, end to end as a stranger (issue 34, session 57).

    .venv/bin/python benchmarks/bench_new_machines57.py write DIR   # the lab's files only
    .venv/bin/python benchmarks/bench_new_machines57.py all DIR     # write, init, run, diagnose,
                                                                    # monitor, table
    (or one step: init | run | diagnose | monitor | table | forensics DIR, on what the steps
    before wrote)

The physics below was written down before any model ran on these records; nothing was tuned on
them (seeds 5771 / 5772 fixed beforehand, every command run once).  Both differ from ``apps/sim``
(VMC, Swiss lathe, large mill, climate room, column, year-round spindle), ``bench_other_machine.py``
(a lathe heated by its spindle, a room-level factor) and ``bench_new_machines56.py`` (a grinder whose
coolant flow switches the network, a gantry yawed by its two columns x the Y position).  The
helpers are those two modules' (the records' programmes) and ``new_machine_steps.py``'s (the
steps, the table, ``bench_monitor_healthy.py``'s monitor summary).

``boring_mill`` -- a horizontal boring mill whose RAM bends with its own top-bottom gradient
---------------------------------------------------------------------------------------------
A ram (quill) W slides out of the headstock towards the part; its extension ``S_ram_W`` (mm,
0-700) is a logged state.  Lumped network (C J/K, hA W/K to the hall): spindle ``motor`` on top of
the headstock (3e4, 6), ``gearbox`` (1.2e5, 8), ``headstock`` (4e5, 14), the ram's upper half
``ram_top`` and lower half ``ram_bot`` (1.2e5, 3 each: inside the headstock's guides), spindle
bearings in the ram ``nose`` (8e3, 2), ``column`` (2e6, 30) and its unmeasured ``column_core``
(2e6, 0), the hydraulic unit's ``oil`` (100 l and the pump, 2e5, 10), the ``bed`` (5e6, 45).  Links
(W/K): motor-gearbox 5, gearbox-headstock 8, gearbox-ram_top 4, headstock-ram_top 5,
headstock-ram_bot 5, ram_top-ram_bot 3 (through the ram's section), nose-ram_top 2.5,
nose-ram_bot 2.5, oil-ram_bot 6 (the hydrostatic pads under the ram), oil-headstock 2,
headstock-column 10, column-column_core 30, column-bed 12, oil-bed 1.  Heat: motor
80 + 40 k + 5 k^2 W while turning (k = krpm, 0-2.5 krpm), gearbox 25 k W, nose 10 k W; the oil
pump charges an accumulator with a DUTY CYCLE (logged ``Pompa idraulica [-]``): on for 2-4 min,
off for 4-14 min, and on at every ram move; 900 W into the oil while on, 60 W while off.  So the
ram is heated from above by the motor and gearbox and from below by the oil, independently.
Bending: a gradient dT = T_top - T_bot over the ram's height h = 400 mm curves it
(kappa = alpha dT / h, alpha 11.5e-6/K); the tip drops by kappa W^2 / 2: 1.4375e-5 µm/(K mm^2)
x dT x W^2, 7.0 µm per K at W = 700 mm -- a PRODUCT of the gradient and the extension squared.
Errors (µm, rises since the run's start; the machine soaked at the hall's first value, so the
gradient starts at 0):
``E_Y`` (vertical, + up) = 4.5 column + 1.5 headstock - 2 column_core - 1.4375e-5 (r_top - r_bot) W^2;
``E_Z`` (along the ram, + towards the part) = 11.5e-3 (900 + W) (r_top + r_bot) / 2 + 3 nose
+ 1 headstock - 1 column_core (the ram's heated length grows with its extension: a product too).
The programme: blocks of 10-60 min at 0 / 400 / 800 / 1500 / 2500 rpm, the ram at a W drawn in
0-700 mm (5 mm steps; retracted to 0 while idle).  The hall: a run's base level 16-26 °C (the
season), +-1.5 K a day (runs start 5:00-13:00), 0-3 openings of the hall gate per run (the air
2.5 K colder at once, recovering with 15 min), a slow random walk.  20 sensors at 60 s (0.02 K
noise, 0.01 K steps): ram top rear / front (with the nose), ram bottom rear / front, nose, motor,
gearbox x2, headstock x3, column x3, oil tank, oil return (0.6 oil + 0.4 ram_bot), bed x2, the
electrics cabinet (0.3 motor + 0.7 column), the hall air; 0.3 µm probe noise, 0.1 µm steps.
10 runs of 6-12 h, a folder ``Prova_01.csv`` ... without a manifest, Italian headers with units,
``;`` and decimal commas; the last 3 runs test (``data.test_fraction=0.3``).

``twin_lathe`` -- a twin-spindle turning centre on a common bed, a shop with a night setback
--------------------------------------------------------------------------------------------
Main spindle (``m1`` motor 2.5e4 / 5, ``b1`` bearings 6e3 / 1.5, headstock ``hs1`` 1.5e5 / 9) on the
left of the bed, the sub spindle (``m2`` 1.5e4 / 4, ``b2`` 4e3 / 1.2, ``hs2`` 8e4 / 6) on a Z2 slide
on its right; the bed ``bed_L`` (1.5e6, 20), ``bed_R`` (1.2e6, 16) and its unmeasured ``bed_core``
(2e6, 0); the ``turret`` (3e4, 5) on a cross-slide over both halves; the chuck hydraulics ``hyd``
(8e4, 8) in the base; the BAR in the main spindle's liner (``bar``, 3 m x 40 mm steel,
1.4e4 J/K, 0.5 W/K to the air), unmeasured.  Links (W/K): m1-hs1 5, b1-hs1 6, bar-b1 2.5,
bar-hs1 1, hs1-bed_L 10, m2-hs2 4, b2-hs2 5, hs2-bed_R 5, bed_L-bed_R 8 (the common bed),
bed_L-bed_core 18, bed_R-bed_core 18, turret-bed_L 2, turret-bed_R 2, hyd-bed_L 6, hyd-bed_R 2.
Heat: m1 50 + 30 k + 3 k^2 W (0-5 krpm), b1 8 k W, m2 30 + 20 k + 2 k^2 W (0-6 krpm), b2 5 k W,
turret 25 W and hydraulics 150 W on shift (Mon-Fri 6-22 h, Sat 6-12 h).  The programme on
shift: blocks of 10-60 min, the main spindle at 0 (set-up) / 1500 / 2500 / 3500 / 5000 rpm, the
sub spindle (taking parts over) with p 0.7 at 2000-6000 rpm while the main one cuts.  The BAR
FEEDER: a bar is consumed at 20-60 mm/min (drawn per block) while the main spindle cuts; at a
300 mm remnant a new 3 m bar is pushed in from the magazine, which stands in the hall: the bar
node is set to the hall air (a cold bar cools the spindle's bore); logged ``Bar remaining [%]``.
The shop's heating: set-point 21.5 °C by day (5:00-22:00, Mon-Sat) and a NIGHT SETBACK of 4 K
(22:00-5:00, and Sunday all day); the air follows it with 25 min heating up and 50 min cooling
down (real air steps, not a ramp), +0.6 K sun at 14 h, a slow random walk.  The SEASON: two
files a month apart, Mon 00:00 - Sun 00:00 (6 days each), October (day 21.5, night 17.5) and
November (the heating short: day 20.5, night 16.5, the gate's draughts: 3 a day, 1.5 K for
~10 min); the machine soaked at the first value of each file (Sunday's setback).  Errors (µm,
rises since each file's start, the probes zeroed on Monday):
``E_Z1`` (main spindle, its part's face vs the turret) = 4 hs1 + 3 b1 - 1.2 bed_L - 1 bed_core
+ 0.8 turret; ``E_Z2`` (sub spindle) = 3.5 hs2 + 2.5 b2 + 1.5 bed_R - 0.6 bed_L - 1 bed_core.
20 sensors at 60 s: main motor, main bearing front / rear (0.7 b1 + 0.3 hs1), main headstock x3
(pure, with the motor, with the bed), sub motor, sub bearing, sub headstock x2, bed left x2,
bed right x2, bed middle (0.5 / 0.5), turret x2, hydraulics, the cabinet (0.3 m1 + 0.7 bed_L), the
hall air.  English headers with units, ``,``, a ``Date`` and a ``Time`` column; files
``2026-10_wk41.csv`` (train), ``2026-11_wk45.csv`` (test: ``data.test_fraction=0.5``).

What the ``left out`` variants withhold (diagnose only): ``boring_mill-noW`` ignores the ram's
extension (the bending's lever); ``twin_lathe-noair`` ignores the hall air (the night setback's
only direct measurement).

Measured (2026-11-30, each command once, 2 shared cores at load 2-4; ``write``, ``init``, ``run``,
``diagnose``, ``monitor``, ``table``).  Test RMSE (µm) per target, ratio to MLR's, CPU s (user +
sys of one ``thermocomp run``, ~2 s of it start-up), simulation mode, the defaults, ``init``'s
config::

    boring_mill (E_Errore_Y / E_Errore_Z)           twin_lathe (E_Z1_error / E_Z2_error)
      mlr            5.43 / 8.51  1.00 / 1.00   2.1     0.377 / 0.374  1.00 / 1.00   2.3
      pcr            5.19 / 8.80  0.96 / 1.03   2.2     3.47  / 2.64   9.22 / 7.05   2.3
      arx            5.34 / 8.30  0.99 / 0.97   2.5     0.447 / 0.410  1.19 / 1.10   2.4
      lagbank        4.74 / 6.86  0.87 / 0.81   3.0     0.343 / 0.432  0.91 / 1.15   3.7
      hammerstein    2.66 / 4.23  0.49 / 0.50   4.3     0.326 / 0.432  0.86 / 1.15   6.4
      lstm           5.41 / 9.33  1.00 / 1.10  13.8     0.377 / 0.375  1.00 / 1.00  28.6
      auto           2.63 / 4.23  0.49 / 0.50   9.4     0.339 / 0.382  0.90 / 1.02  19.3
      mlr ati=cmeans 6.16 / 9.40  1.14 / 1.10   2.8     0.377 / 0.374  1.00 / 1.00   2.2
      persistence    1.37 / 2.24  0.25 / 0.26           0.476 / 0.469  1.26 / 1.25

``auto`` against MLR and the best single family: boring_mill E_Y 2.63 vs hammerstein 2.66, E_Z
4.23 = hammerstein (its blend: hammerstein 0.97 / lagbank 0.01 / mlr 0.01 on E_Y, hammerstein 1.0
on E_Z; "blocked forward" validation, hammerstein 2.50 / 4.45 against MLR's 4.31 / 8.04): better
than MLR, the best on both.  twin_lathe E_Z1 0.339 (blend mlr 0.67 / hammerstein 0.33; best single
hammerstein 0.326, +4 %); **E_Z2 0.382 against MLR's 0.374: auto loses to MLR by 2.1 %** (within
10 % of the best single family, MLR itself).  ``mlr ati=cmeans``: boring_mill one interval (the
elbow; 7 train runs at 15.2-25.0 °C) with the ambient interaction, worse on the test (+14 / +10 %;
no ambient law is planted: as the grinder of ``bench_new_machines56``); twin_lathe one interval,
MLR's figures (one train file; ``auto`` skipped ATI: "1 ambient level(s), fewer than 3").

``diagnose`` (MLR; primary target = largest CV RMSE; test RMSE before -> after; CPU s):

* ``boring_mill``: E_Z 8.51 -> 0.37 (``S_ram_W`` x the rise of the ram's bottom rear sensor, then x
  its top rear one: the planted (900 + W) x mean ram rise; CV 8.36 -> 0.37, forward blocks), E_Y
  5.43 -> 1.56 (W x the ram bottom's rise: part of the planted W^2 x gradient).  5.7 s.
* ``boring_mill-noW`` (the lever withheld): accepts nothing, both targets unchanged.  4.9 s.
* ``twin_lathe``: E_Z1 0.377 -> 0.319: "sensor_fault" removes T_Bed_left_rear and
  T_Chuck_hydraulics (healthy), then a 4 h lag of the inputs (the unmeasured bed core);
  **E_Z2 0.374 -> 0.551, +47 %** (the same exclusions and its own 4 h lag).  7.7 s.
* ``twin_lathe-noair``: the same three steps; E_Z1 0.379 -> 0.322, E_Z2 0.377 -> 0.352.  7.6 s.

``monitor`` (the model fitted on the train split, the defaults; healthy test part):
boring_mill (24.4 h, 3 runs) mlr and lagbank: 0 events, RMSE fixed = adaptive (5.43 / 8.51,
4.74 / 6.86).  **twin_lathe (144 h) mlr and lagbank: 36 events, 18 exclusions of T_amb**, no
warning / alarm / new state / guard event; RMSE fixed -> adaptive mlr 0.377 -> 0.372, 0.374 ->
0.372, lagbank 0.343 -> 0.334, 0.432 -> 0.434 (+0.4 %).

Forensics.

(1) The monitor's 18 exclusions are the 18 gate draughts of the November file (3 a day x 6 days,
the air -1.5 K in one minute): "jump: -1.45 °C in one sample (largest step in training 0.29 °C);
... held at its last good reading: no other sensor predicts it", re-admitted after 10 samples
with the jump undone.  The train file (October) has no draught, and the night setback's own steps
(the air following with 25 / 50 min) raise nothing.  A real air step unseen in training against an
offset of the air sensor that nothing predicts: ``bench_ambient_step55.py`` measured the rules that
would tell them apart from what the structure does after the jump and refused each (offsets taken
for air at up to 10-36 % of the rows).  Not a defect with a general mend here: no src change; the
harm is nil for MLR (adaptive better) and +0.4 % on one target of the lag bank.

(2) ``diagnose``'s E_Z2 harm: the one train campaign (a week) gives forward chaining over its
second half (16 blocks of 5.4 h); the 4 h lag of the 18 inputs gains 26 % of CV RMSE there
(p 6e-5 family-wise 3e-4, the 95 % bound of the gain positive, in-range gain 22 %, shrink 1e-6: the
CV asked for none), every bar cleared.  On November it fails.  Least squares on the same 18
rises without and with their 4 h lags (``forensics``: no shrink, test 0.382 -> 0.914, against
thermocomp's 0.374 -> 0.551) shows how: the lagged model carries large
coefficients of opposite signs (lag of T_Sub_headstock -10.4 µm/K, lag of T_Main_headstock_top
-7.5, lag of T_Bed_right_front +4.8, of the air +4.3), the residual's mean moves from +0.01 to
+0.86 µm on every one of the 6 test days alike (not at the draughts: near them 0.94, elsewhere
0.91 µm rms), and the moves are those coefficients times a different operating mix (the sub
spindle ran more: its motor's lag 1.15 K higher on average in November; the sum of the features'
mean shifts x coefficients +2.0 µm).  A week's programme is one draw of the mix; blocks inside it
cannot show that the lagged combination does not carry over to another month.  The same root for
``auto``'s E_Z2: its validation (5 forward folds of the October week) had ARX 0.418 against MLR's
0.460, the votes blended ARX 0.51 / MLR 0.46 / lagbank 0.04; on the test ARX is 0.410 against
MLR's 0.374.  ARX's lead is fold 5's (0.568 against 0.711: the week's last block, Saturday after
the shift ended at noon, a state no earlier fold trained on) and fold 1's (0.433 / 0.450); MLR
won folds 3 and 4 (``run model=mlr`` / ``arx``: validation per_unit).  Neither is a defect with
a general mend found in this session (no bar at hand tells a week's mix from a law without a
second train campaign): no src change.  Traced further in ``bench_diagnose_lag57.py``: the CV error is
flat over the penalties 0-1e-3 (0.3098-0.3114 µm) while the test goes 0.91 -> 0.32; the lag at
the one-standard-error penalty (1e-3) gives 0.324, but that rule harms four position products
elsewhere and is refused.

(3) The "sensor_fault" exclusions on the twin lathe are healthy sensors: T_Chuck_hydraulics
(the hydraulics alone; 150 W switched with the shift) and T_Bed_left_rear (0.9 bed + 0.1
hydraulics), worst in the last health block of the week (Saturday afternoon: the shift ended at
12 h, a state no earlier block had), jump ratios 4.6 and 5.5 >= 3; removal is accepted because no
target needs them (CV gain -0.02 % and +2.7 %).  The exclusions alone on the test
(``diagnose.families=[sensor_fault]``): E_Z1 0.377 -> 0.383 (+1.5 %), E_Z2 0.374 -> 0.382
(+2.0 %).  A new thermal state read as two faults (the monitor's ``new_state`` rule has no
counterpart in diagnose's health check); noted, not mended.

What a stranger met on the way in (``init DIR data.test_fraction=...``): the twin lathe's English
export gave every role (``Date`` + ``Time``, ``Hall air`` the ambient, the errors and states from
the units).  The boring mill's Italian one was refused: ``'Tempo [s]': unit 's' is not a
temperature's`` (``tempo`` is no time header; ``temps``, ``tiempo`` are); with
``data.roles.time=Tempo`` init proposed ``Corsa slittone W [mm]`` (the ram's travel) as a third
error and ``Aria capannone`` (the hall's air) as a plain temperature: the stranger gives
``data.roles.state=['Corsa slittone*']`` and ``data.roles.ambient=['Aria capannone*']``; the
figures above are on that config.  Mended since (init57: ``tempo`` a time header; ``posizione``,
``posición``, ``corsa`` position words; ``ambiente``, ``ambiante``, ``capannone`` the air's words;
``tests/core/test_init_italian57.py``): ``init DIR data.test_fraction=0.3`` alone proposes the same
roles (MLR test RMSE the same to every digit, 5.4252 / 8.5131; ``diagnose`` of boring_mill and
boring_mill-noW on that config: the figures above).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).parent))
from bench_new_machines56 import rounded, simulate  # noqa: E402
from bench_other_machine import thermocomp  # noqa: E402, F401 (bench_diagnose_faults58, _lag57 call it here)
from new_machine_steps import Machines  # noqa: E402
from new_machine_steps import main as steps_main  # noqa: E402

from thermocomp.apps.sim.network import Link, Node, ThermalNetwork  # noqa: E402

SEEDS = {"boring_mill": 5771, "twin_lathe": 5772}
STEP = 60.0


def network(nodes: dict, links) -> ThermalNetwork:
    return ThermalNetwork([Node(n, c, h) for n, (c, h) in nodes.items()],
                          [Link(a, b, g) for a, b, g in links])


def sensors(frame: dict, nodes: np.ndarray, ix: dict, layout, rng) -> None:
    """``T_01`` ... of ``layout`` ``(name, node a, node b, weight of a)``: 0.02 K noise, 0.01 K steps."""
    n = len(nodes)
    for j, (_, a, b, w) in enumerate(layout):
        frame[f"T_{j + 1:02d}"] = rounded(w * nodes[:, ix[a]] + (1 - w) * nodes[:, ix[b]]
                                          + rng.normal(0, 0.02, n), 0.01)


def probe(value: np.ndarray, rng) -> np.ndarray:
    return rounded(value + rng.normal(0, 0.3, len(value)), 0.1)


# --- boring mill ----------------------------------------------------------------------------

B_NODES = {"motor": (3e4, 6.0), "gearbox": (1.2e5, 8.0), "headstock": (4e5, 14.0),
           "ram_top": (1.2e5, 3.0), "ram_bot": (1.2e5, 3.0), "nose": (8e3, 2.0),
           "column": (2e6, 30.0), "column_core": (2e6, 0.0), "oil": (2e5, 10.0), "bed": (5e6, 45.0)}
B_LINKS = (("motor", "gearbox", 5.0), ("gearbox", "headstock", 8.0), ("gearbox", "ram_top", 4.0),
           ("headstock", "ram_top", 5.0), ("headstock", "ram_bot", 5.0), ("ram_top", "ram_bot", 3.0),
           ("nose", "ram_top", 2.5), ("nose", "ram_bot", 2.5), ("oil", "ram_bot", 6.0),
           ("oil", "headstock", 2.0), ("headstock", "column", 10.0), ("column", "column_core", 30.0),
           ("column", "bed", 12.0), ("oil", "bed", 1.0))
B_SENSORS = [("Slittone sopra post.", "ram_top", "ram_top", 1.0),
             ("Slittone sopra ant.", "ram_top", "nose", 0.85),
             ("Slittone sotto post.", "ram_bot", "ram_bot", 1.0),
             ("Slittone sotto ant.", "ram_bot", "nose", 0.85), ("Naso mandrino", "nose", "nose", 1.0),
             ("Motore mandrino", "motor", "motor", 1.0), ("Riduttore", "gearbox", "gearbox", 1.0),
             ("Riduttore olio", "gearbox", "headstock", 0.7), ("Testa sx", "headstock", "headstock", 1.0),
             ("Testa dx", "headstock", "ram_bot", 0.85), ("Testa sopra", "headstock", "gearbox", 0.8),
             ("Montante basso", "column", "bed", 0.8), ("Montante medio", "column", "column", 1.0),
             ("Montante alto", "column", "headstock", 0.85), ("Olio centralina", "oil", "oil", 1.0),
             ("Olio ritorno", "oil", "ram_bot", 0.6), ("Basamento ant.", "bed", "bed", 1.0),
             ("Basamento post.", "bed", "column", 0.9), ("Quadro elettrico", "motor", "column", 0.3)]
SAG_UM_PER_K_MM2 = 11.5e-6 / (2 * 400.0) * 1000.0      # alpha / (2 h), h = 400 mm, in µm
RAM_CLAMPED_MM = 900.0


def mill_programme(rng, n):
    """Per sample: rpm, ram extension W (mm), oil pump on (blocks of 10-60 min)."""
    rpm, ram, pump = np.zeros(n), np.zeros(n), np.zeros(n)
    k = 0
    while k < n:
        length = int(rng.uniform(600, 3600) / STEP) + 1
        speed = rng.choice([0, 400, 800, 1500, 2500])
        rpm[k:k + length] = speed
        ram[k:k + length] = 5 * np.round(rng.uniform(0, 700) / 5) if speed else 0.0
        k += length
    k = 0
    moved = np.flatnonzero(np.diff(ram) != 0) + 1
    while k < n:                         # the accumulator's duty cycle, and a charge at each move
        on = int(rng.uniform(2, 4) * 60 / STEP) + 1
        pump[k:k + on] = 1
        off = int(rng.uniform(4, 14) * 60 / STEP) + 1
        nxt = moved[(moved > k + on) & (moved < k + on + off)]
        k = int(nxt[0]) if len(nxt) else k + on + off
    return rpm, ram, pump


def hall(rng, n, base, start_h, gate_count, gate_k, gate_tau_min):
    """A hall's air: ``base`` +- 1.5 K a day, ``gate_count`` gate openings (``gate_k`` colder,
    recovering with ``gate_tau_min``), a slow random walk."""
    hours = start_h + np.arange(n) * STEP / 3600
    air = base + 1.5 * np.sin((hours - 9.0) / 24 * 2 * np.pi) + rng.normal(0, 0.03, n).cumsum() * 0.1
    for at in rng.integers(0, n, gate_count):
        air[at:] -= gate_k * np.exp(-np.arange(n - at) * STEP / 60 / gate_tau_min)
    return air


def mill_run(net, rng, n):
    ix = net.index
    room = hall(rng, n, rng.uniform(16.0, 26.0), rng.uniform(5.0, 13.0), int(rng.integers(0, 4)), 2.5, 15.0)
    rpm, ram, pump = mill_programme(rng, n)
    k = rpm / 1000.0
    heat = np.zeros((n, net.n_nodes))
    heat[:, ix["motor"]] = np.where(rpm > 0, 80 + 40 * k + 5 * k**2, 0.0)
    heat[:, ix["gearbox"]] = 25.0 * k
    heat[:, ix["nose"]] = 10.0 * k
    heat[:, ix["oil"]] = np.where(pump > 0, 900.0, 60.0)
    nodes = simulate([(net, net.propagator(STEP))], np.zeros(n), room, heat, room[0])
    frame = {"time": np.arange(n) * STEP}
    sensors(frame, nodes, ix, B_SENSORS, rng)
    frame["T_amb"] = rounded(room + rng.normal(0, 0.05, n), 0.01)
    r = {name: nodes[:, i] - nodes[0, i] for name, i in ix.items()}
    gradient, mean = r["ram_top"] - r["ram_bot"], (r["ram_top"] + r["ram_bot"]) / 2
    frame["E_Y"] = probe(4.5 * r["column"] + 1.5 * r["headstock"] - 2 * r["column_core"]
                         - SAG_UM_PER_K_MM2 * gradient * ram**2, rng)
    frame["E_Z"] = probe(11.5e-3 * (RAM_CLAMPED_MM + ram) * mean + 3 * r["nose"] + r["headstock"]
                         - r["column_core"], rng)
    frame["S_W"], frame["S_rpm"], frame["S_pump"] = ram, rpm, pump
    return pd.DataFrame(frame)


def write_boring_mill(folder: Path, seed: int) -> None:
    rng = np.random.default_rng(seed)
    net = network(B_NODES, B_LINKS)
    names = {"time": "Tempo [s]", "E_Y": "Errore Y [µm]", "E_Z": "Errore Z [µm]",
             "T_amb": "Aria capannone [°C]", "S_W": "Corsa slittone W [mm]",
             "S_rpm": "Giri mandrino [1/min]", "S_pump": "Pompa idraulica [-]"}
    names.update({f"T_{j + 1:02d}": f"{s[0]} [°C]" for j, s in enumerate(B_SENSORS)})
    folder.mkdir(parents=True, exist_ok=True)
    for r in range(10):
        n = int(rng.uniform(6, 12) * 3600 / STEP)
        mill_run(net, rng, n).rename(columns=names).to_csv(
            folder / f"Prova_{r + 1:02d}.csv", sep=";", decimal=",", index=False, float_format="%.6g")


# --- twin-spindle lathe -----------------------------------------------------------------------

L_NODES = {"m1": (2.5e4, 5.0), "b1": (6e3, 1.5), "hs1": (1.5e5, 9.0), "bar": (1.4e4, 0.5),
           "m2": (1.5e4, 4.0), "b2": (4e3, 1.2), "hs2": (8e4, 6.0), "bed_L": (1.5e6, 20.0),
           "bed_R": (1.2e6, 16.0), "bed_core": (2e6, 0.0), "turret": (3e4, 5.0), "hyd": (8e4, 8.0)}
L_LINKS = (("m1", "hs1", 5.0), ("b1", "hs1", 6.0), ("bar", "b1", 2.5), ("bar", "hs1", 1.0),
           ("hs1", "bed_L", 10.0), ("m2", "hs2", 4.0), ("b2", "hs2", 5.0), ("hs2", "bed_R", 5.0),
           ("bed_L", "bed_R", 8.0), ("bed_L", "bed_core", 18.0), ("bed_R", "bed_core", 18.0),
           ("turret", "bed_L", 2.0), ("turret", "bed_R", 2.0), ("hyd", "bed_L", 6.0), ("hyd", "bed_R", 2.0))
L_SENSORS = [("Main motor", "m1", "m1", 1.0), ("Main bearing front", "b1", "b1", 1.0),
             ("Main bearing rear", "b1", "hs1", 0.7), ("Main headstock", "hs1", "hs1", 1.0),
             ("Main headstock top", "hs1", "m1", 0.85), ("Main headstock base", "hs1", "bed_L", 0.7),
             ("Sub motor", "m2", "m2", 1.0), ("Sub bearing", "b2", "b2", 1.0),
             ("Sub headstock", "hs2", "hs2", 1.0), ("Sub slide", "hs2", "bed_R", 0.7),
             ("Bed left front", "bed_L", "bed_L", 1.0), ("Bed left rear", "bed_L", "hyd", 0.9),
             ("Bed right front", "bed_R", "bed_R", 1.0), ("Bed right rear", "bed_R", "hs2", 0.9),
             ("Bed middle", "bed_L", "bed_R", 0.5), ("Turret", "turret", "turret", 1.0),
             ("Turret slide", "turret", "bed_R", 0.8), ("Chuck hydraulics", "hyd", "hyd", 1.0),
             ("Cabinet", "m1", "bed_L", 0.3)]
SEASONS = {"2026-10_wk41": ("2026-10-05", 21.5, 0), "2026-11_wk45": ("2026-11-02", 20.5, 3)}


def shop_air(rng, hours, day_c, draughts_per_day):
    """Set-point ``day_c`` 5-22 h Mon-Sat, 4 K less otherwise; the air follows with 25 min up,
    50 min down; sun at 14 h; ``draughts_per_day`` gate draughts; a slow random walk."""
    n = len(hours)
    day, hour = (hours // 24).astype(int), hours % 24
    setpoint = np.where((day % 7 < 6) & (hour >= 5) & (hour < 22), day_c, day_c - 4.0)
    air = np.empty(n)
    air[0] = setpoint[0]
    for i in range(1, n):
        tau = 25.0 if setpoint[i] > air[i - 1] else 50.0
        air[i] = setpoint[i] + (air[i - 1] - setpoint[i]) * np.exp(-STEP / 60 / tau)
    air += 0.6 * np.exp(-((hour - 14.0) / 3.0) ** 2) + rng.normal(0, 0.03, n).cumsum() * 0.05
    for at in rng.integers(0, n, int(draughts_per_day * n * STEP / 86400)):
        air[at:] -= 1.5 * np.exp(-np.arange(n - at) * STEP / 600)
    return air


def lathe_programme(rng, shift):
    """Per sample: main rpm, sub rpm, bar consumption mm per sample."""
    n = len(shift)
    main, sub, feed = np.zeros(n), np.zeros(n), np.zeros(n)
    k = 0
    while k < n:
        length = int(rng.uniform(600, 3600) / STEP) + 1
        main[k:k + length] = m = rng.choice([0, 1500, 2500, 3500, 5000])
        sub[k:k + length] = rng.choice([2000, 3000, 4500, 6000]) if m and rng.random() < 0.7 else 0.0
        feed[k:k + length] = rng.uniform(20, 60) * STEP / 60 if m else 0.0
        k += length
    return main * shift, sub * shift, feed * shift


def lathe_file(net, rng, day_c, draughts):
    ix = net.index
    n = int(6 * 86400 / STEP)
    hours = np.arange(n) * STEP / 3600
    day, hour = (hours // 24).astype(int), hours % 24
    shift = ((day < 5) & (hour >= 6) & (hour < 22)) | ((day == 5) & (hour >= 6) & (hour < 12))
    room = shop_air(rng, hours, day_c, draughts)
    main, sub, feed = lathe_programme(rng, shift)
    k1, k2 = main / 1000.0, sub / 1000.0
    heat = np.zeros((n, net.n_nodes))
    heat[:, ix["m1"]] = np.where(main > 0, 50 + 30 * k1 + 3 * k1**2, 0.0)
    heat[:, ix["b1"]] = 8.0 * k1
    heat[:, ix["m2"]] = np.where(sub > 0, 30 + 20 * k2 + 2 * k2**2, 0.0)
    heat[:, ix["b2"]] = 5.0 * k2
    heat[:, ix["turret"]] = 25.0 * shift
    heat[:, ix["hyd"]] = 150.0 * shift
    prop = net.propagator(STEP)
    nodes = np.empty((n, net.n_nodes))
    nodes[0] = net.steady_state(room[0], np.zeros(net.n_nodes))
    remaining = np.empty(n)
    bar = 3000.0
    for i in range(n):
        if i:
            nodes[i] = prop.step(nodes[i - 1], room[i - 1], heat[i - 1])
        bar -= feed[i]
        if bar < 300.0:                  # a new bar from the magazine in the hall
            bar = 3000.0
            nodes[i, ix["bar"]] = room[i]
        remaining[i] = bar
    frame = {"time": np.arange(n) * STEP}
    sensors(frame, nodes, ix, L_SENSORS, rng)
    frame["T_amb"] = rounded(room + rng.normal(0, 0.05, n), 0.01)
    r = {name: nodes[:, i] - nodes[0, i] for name, i in ix.items()}
    frame["E_Z1"] = probe(4 * r["hs1"] + 3 * r["b1"] - 1.2 * r["bed_L"] - r["bed_core"]
                          + 0.8 * r["turret"], rng)
    frame["E_Z2"] = probe(3.5 * r["hs2"] + 2.5 * r["b2"] + 1.5 * r["bed_R"] - 0.6 * r["bed_L"]
                          - r["bed_core"], rng)
    frame["S_main"], frame["S_sub"] = main, sub
    frame["S_bar"] = np.round(100 * remaining / 3000.0, 1)
    return pd.DataFrame(frame)


def write_twin_lathe(folder: Path, seed: int) -> None:
    rng = np.random.default_rng(seed)
    net = network(L_NODES, L_LINKS)
    names = {"E_Z1": "Z1 error [µm]", "E_Z2": "Z2 error [µm]", "T_amb": "Hall air [°C]",
             "S_main": "Main spindle [rpm]", "S_sub": "Sub spindle [rpm]", "S_bar": "Bar remaining [%]"}
    names.update({f"T_{j + 1:02d}": f"{s[0]} [°C]" for j, s in enumerate(L_SENSORS)})
    folder.mkdir(parents=True, exist_ok=True)
    for file, (monday, day_c, draughts) in SEASONS.items():
        out = lathe_file(net, rng, day_c, draughts).rename(columns=names)
        stamp = pd.Timestamp(monday) + pd.to_timedelta(out.pop("time"), unit="s")
        out.insert(0, "Time", stamp.dt.strftime("%H:%M:%S"))
        out.insert(0, "Date", stamp.dt.strftime("%Y-%m-%d"))
        out.to_csv(folder / f"{file}.csv", index=False, float_format="%.6g")


def write(root: Path) -> None:
    write_boring_mill(root / "boring_mill", SEEDS["boring_mill"])
    write_twin_lathe(root / "twin_lathe", SEEDS["twin_lathe"])



# --- the pipeline -------------------------------------------------------------------------

FAMILIES = ("mlr", "pcr", "arx", "lagbank", "hammerstein", "lstm", "auto")
# what a stranger adds to `init DIR`: the test share (the boring mill's time, travel and air
# were spelled out too before init57: the docstring's "way in")
INIT_ARGS = {"boring_mill": ("data.test_fraction=0.3",), "twin_lathe": ("data.test_fraction=0.5",)}
# (a header both ignored and given a role is refused: the states' patterns are given again)
LEFT_OUT = {"boring_mill-noW": ["data.roles.ignore=['Corsa slittone*']",
                                "data.roles.state=['Giri mandrino','Pompa idraulica']"],
            "twin_lathe-noair": ["data.roles.ignore=['Hall air*']", "data.roles.ambient=[]"]}
MONITORED = ("mlr", "lagbank")


def data_args(root: Path, name: str) -> list[str]:
    """``init``'s config (the lab's folder), plus the variant's ignored columns."""
    base, _, variant = name.partition("-")
    return [f"hydra.searchpath=[file://{root}/init-{base}/conf]", f"data={base}",
            *(LEFT_OUT[name] if variant else [])]


def lag_forensics(root: Path) -> None:
    """Why the 4 h lag ``diagnose`` accepted on the twin lathe's E_Z2 failed on the test file:
    least squares (intercept, no shrink) on the 18 rises it keeps, without and with their 4 h
    first-order lags, fitted on the October file, scored on November's."""
    folder, dropped = root / "twin_lathe", ("Bed left rear [°C]", "Chuck hydraulics [°C]")

    def load(file):
        d = pd.read_csv(folder / file)
        temps = d[[c for c in d.columns if "°C" in c and c not in dropped]]
        y = d["Z2 error [µm]"]
        return (temps - temps.iloc[0]).to_numpy(), (y - y.iloc[0]).to_numpy(), list(temps.columns), d

    def lagged(x, tau=14400.0):
        a, out = np.exp(-STEP / tau), np.zeros_like(x)
        for i in range(1, len(x)):
            out[i] = a * out[i - 1] + (1 - a) * x[i]
        return np.hstack([x, out])

    def design(x):
        return np.column_stack([x, np.ones(len(x))])

    xa, ya, cols, _ = load("2026-10_wk41.csv")
    xb, yb, _, db = load("2026-11_wk45.csv")
    fa, fb = lagged(xa), lagged(xb)
    w0 = np.linalg.lstsq(design(xa), ya, rcond=None)[0]
    w1 = np.linalg.lstsq(design(fa), ya, rcond=None)[0]
    r0, r1 = yb - design(xb) @ w0, yb - design(fb) @ w1
    print(f"test RMSE {np.sqrt(np.mean(r0**2)):.3f} -> {np.sqrt(np.mean(r1**2)):.3f}; mean residual "
          f"{r0.mean():+.2f} -> {r1.mean():+.2f}")
    names = cols + [f"lag {c}" for c in cols]
    print("largest coefficients:", [(names[i], round(w1[i], 1)) for i in np.argsort(-np.abs(w1[:-1]))[:5]])
    shift = (fb.mean(0) - fa.mean(0)) * w1[:-1]
    print(f"mean shift x coefficient, sum {shift.sum():+.2f}:",
          [(names[i], round(shift[i], 2), round(fb[:, i].mean() - fa[:, i].mean(), 2))
           for i in np.argsort(-np.abs(shift))[:5]])
    air = db["Hall air [°C]"].to_numpy()
    near = np.zeros(len(air), bool)
    for i in np.flatnonzero(np.diff(air) < -0.8) + 1:       # the draughts, 30 min after each
        near[i:i + 30] = True
    print(f"{near.sum()} rows near a draught: RMS {np.sqrt(np.mean(r1[near] ** 2)):.2f}, elsewhere "
          f"{np.sqrt(np.mean(r1[~near] ** 2)):.2f}")
    day = np.arange(len(yb)) * STEP // 86400
    print("per day RMSE:", [(round(float(np.sqrt(np.mean(r0[day == k] ** 2))), 3),
                             round(float(np.sqrt(np.mean(r1[day == k] ** 2))), 3)) for k in range(6)])


MACHINES = Machines(doc=__doc__, write=write, records=list(SEEDS), families=FAMILIES,
                    init_args=INIT_ARGS, data_args=data_args, variants=LEFT_OUT,
                    ati_records=list(SEEDS), monitored=MONITORED, forensics=lag_forensics)


def main(argv=None) -> int:
    return steps_main(MACHINES, argv)


if __name__ == "__main__":
    raise SystemExit(main())
