"""Two more machines nobody has tuned on, exported by a lab's data logger (issue 34, session 59).

    .venv/bin/python benchmarks/bench_new_machines59.py write DIR   # the lab's files only
    .venv/bin/python benchmarks/bench_new_machines59.py all DIR     # write, init, run, diagnose,
                                                                    # replay, monitor, table
    (or one step: init | run | diagnose | replay | monitor | table DIR, on what the steps before
    wrote)

The physics below was written down before any model ran on these records; nothing was tuned on
them (seeds 5991 / 5992 fixed beforehand, every command run once).  Both differ from ``apps/sim``
and every bench machine so far (``bench_other_machine``'s lathe, ``bench_new_machines56``'s
grinder and gantry, ``57``'s boring mill and twin lathe, ``58``'s trunnion and laser): a THERMAL
STATE THAT SWITCHES WITH A PALLET (two masses that take turns in the machine, each soaked at
another place), and a LIMIT CYCLE (a chiller on a hysteresis thermostat) driving the error.
The helpers are those modules' (``bench_new_machines56``: the integrator, rounding, the runs of
the families, the table; ``57``: the network, sensors, probe; ``58``: the monitor row;
``bench_other_machine``: the CLI call and ``diagnose``).

``hmc`` -- a horizontal machining centre whose two pallets take turns (a pallet shuttle)
----------------------------------------------------------------------------------------
A horizontal spindle (Z towards the part) in a head moving in Y on a travelling column, a rotary
B table with a pallet receiver, a linear two-pallet shuttle: pallet 1 parks on the LEFT station
(by the hall door: its air 2.5 K below the hall's), pallet 2 on the RIGHT one (over the chip
conveyor and the coolant tank: 3.0 K above the hall's).  Each pallet (steel pallet, tombstone and
parts, 330 kg) is a node of its own that is IN the machine half the time.  Lumped network
(C J/K, hA W/K): spindle ``motor`` (2.5e4, 5), ``bearing`` (6e3, 1.5), ``head`` (1.5e5, 8),
``column`` (1.0e6, 18), ``bed`` (3e6, 30) and its unmeasured ``bed_core`` (2e6, 0), the B
``table`` (2.5e5, 8), the coolant ``tank`` (8e5, 80: open tank, chip conveyor), ``pal1`` /
``pal2`` (1.5e5, 8 each, unmeasured).  Fixed links (W/K): motor-head 4, bearing-head 6,
head-column 6, column-bed 12, bed-bed_core 25, table-bed 6, tank-bed 2.  Switched links: the
pallet in the machine is clamped on the receiver (table-pallet 20); while cutting the flood
joins the tank to that pallet (40) and to the table (10): four networks (pallet 1 / 2 x coolant
on / off).  A pallet in its station exchanges with that station's air: its 8 W/K to the hall plus
8 x (station offset) W.  Heat while cutting: spindle motor 40 + 20 k + 2 k^2 W (k krpm,
4 / 6 / 8 / 10), bearing 5 k W, the coolant pump 400 W into the tank, the chips 0.15 x P into
the tank and 0.03 x P into the pallet in the machine (P = 300 k W of cutting power).  The
programme, lights-out runs of 18-40 h: blocks of 20-90 min, one pallet's cycle each (the pallets
alternate block by block, the run starting with pallet 1), a block idle (spindle and coolant
off: no operator) with p 0.15.  The hall: a run's base level 19-26 °C (autumn), +-2 K a day
(warmest at 15 h; runs start 6:00-14:00), a slow random walk; the machine soaked at the hall's
first value, pallet 1 at its station's (-2.5 K), pallet 2 at its (+3.0 K).  Errors (µm), the probe
nest on each pallet's tombstone (500 mm above the pallet face, 150 mm off the B axis along Z),
both nests zeroed at the run's start as pallet 1 then was (so pallet 2's first entry shows its
5.5 K), ``r`` the rise since the run's start, ``p`` the pallet in the machine (its temperature
less pallet 1's at the start):
``E_Y`` = 8.05 column + 1.5 head - 5.75 p - 2.0 table (the column lifts the spindle, the
tombstone lifts the nest); ``E_Z`` = -6 head - 3 bearing - 1.725 p + 1.5 bed - 1.0 bed_core (the
spindle grows towards the part and the tombstone towards the spindle).  So the error switches
with the pallet: a product of the pallet state and two unmeasured masses' temperatures.  14
thermocouples at 60 s (0.02 K noise, 0.01 K steps): spindle motor, front bearing, head (0.8 head
+ 0.2 motor), head rear (its connector loose: the logger writes ``+OVER`` on 0.2 % of its
samples in runs 3 and 6), column top (0.85 column + 0.15 head), column base (0.7 column + 0.3
bed), bed left, bed right (0.85 bed + 0.15 tank), B table, the pallet RECEIVER (0.7 table + 0.3
the pallet in the machine), the coolant tank, the coolant return (while the flood runs 0.6 tank
+ 0.4 the pallet in, else the tank), the cabinet (0.4 motor + 0.6 column), the hall air; spindle
speed (rpm, the drive's analog output), the pallet in the machine (1 / 2, a digital input), the
coolant (0 / 1); the probes 0.3 µm noise, 0.1 µm steps.  8 runs (from Mon 2026-09-07, each on
the working day after the one before ended), the logger's files ``HMC_2026-09-07.csv`` ...: an
instrument preamble (logger model, serial, start, interval, channel count), a header of channel
names (``CH01 Spindle motor`` ...), a SECOND row of units (``degC``, ``um``, ``rpm``, ``-``), an
elapsed ``Time`` ``h:mm:ss`` column that rolls past 24 h, ``,`` with a trailing ``,`` on every
line (an empty last column); the last 2 runs test (``data.test_fraction=0.25``).

``edm`` -- a wire EDM whose dielectric is held by an on/off chiller with hysteresis
-----------------------------------------------------------------------------------
A C-frame wire EDM: the upper and the lower wire-guide arms hang off the column; the work tank
(on the X/Y table) is flooded with deionised water, the LOWER arm submerged in it, the upper arm
in air.  The dielectric circulates between the work tank's ``bath`` and the ``reservoir``; a
chiller on the reservoir switches its compressor ON when the reservoir passes 20.6 °C and OFF
below 19.4 °C (its own thermostat; hysteresis 1.2 K): a LIMIT CYCLE whose period is set by the
load.  Lumped network (C J/K, hA W/K): ``bath`` (water 100 l, the part, the tank walls: 6e5,
15), ``reservoir`` (400 l: 1.7e6, 20), ``lower_arm`` (1.2e5, 2), ``upper_arm`` (1.2e5, 6),
``column`` (8e5, 16), ``base`` (2.5e6, 30) and its unmeasured ``base_core`` (2e6, 0), the X/Y
``xy_table`` (4e5, 10), the generator ``cabinet`` (1e5, 10).  Fixed links (W/K): lower_arm-bath
60, lower_arm-column 6, upper_arm-column 8, column-base 12, base-base_core 25, xy_table-base 10,
bath-xy_table 10, cabinet-base 1, bath-reservoir 2.  While flushing (cutting) the circulation
adds bath-reservoir 160 (0.04 kg/s of water).  Heat: while cutting the discharge power P (0.3 /
0.6 / 1.0 / 1.5 kW) 90 % into the bath, the drives 20 W into the X/Y table, the flushing pump
250 W into the reservoir; the generator cabinet 150 + 0.2 P W while the machine is on; the
chiller -2000 W into the reservoir while its compressor runs (it runs on the mains, weekends
too).  The programme: the machine runs 24 h a day Mon-Sat (wire EDM, unattended), blocks of
20-180 min of cutting at P, a block of 10-40 min idle (threading, part change: no flushing) with
p 0.25; off (nothing but the chiller) from Sun 0:00 to Mon 6:00.  The room: air-conditioned,
22 °C +- 1 K a day (warmest at 16 h), its compressor hunting +-0.3 K over ~40 min, a slow random
walk.  Errors (µm, rises since the record's start, the machine soaked at 22 °C and the dielectric
at 20 °C): the wire at the part's mid-height sits between the guides, the part is in the bath:
``E_X`` = 11.5e-3 x 500 (upper_arm + lower_arm) / 2 + 1.2 column - 11.5e-3 x 150 bath
- 11.5e-3 x 300 xy_table + 0.5 base - 0.8 base_core; the TAPER (the upper guide less the lower one
over the 500 mm arms) ``E_U`` = 5.75 (upper_arm - lower_arm).  So E_U follows the chiller's
sawtooth through the submerged arm against the air-side arm.  12 sensors at 60 s (0.02 K noise,
0.01 K steps): bath, reservoir, bath outlet (0.7 bath + 0.3 reservoir), upper arm, lower arm
(the arm's root above the water: 0.6 lower_arm + 0.4 column), column x2 (one 0.8 column + 0.2
upper_arm), base x2 (one 0.85 base + 0.15 xy_table), X/Y table, the generator cabinet, the room
air; the states: the discharge power (kW), the flushing (``true`` / ``false``), the chiller's
compressor (``true`` / ``false``), the probes 0.3 µm noise, 0.1 µm steps.  Three weeks (Mon
2026-09-07 06:00 UTC on) in ONE file written by an IoT gateway, ``edm01_export.csv``:
``timestamp`` ISO 8601 UTC with milliseconds and ``Z`` (the gateway polls every 60 s, each poll
late by 0-300 ms), snake_case tags with their unit as a suffix (``bath_temp_c``,
``wire_x_um``, ``taper_u_um``, ``discharge_power_kw``, ``flushing``, ``chiller_on``), two gateway
outages (the rows missing: 7 and 25 min); the last quarter test (``data.test_fraction=0.25``).

Measured (2026-11-30, each step once, on the code after the mends below, 2 shared cores;
``write`` 1.1 s CPU, ``init`` 1.8 / 1.7 s).  Test RMSE (µm) per target, ratio to MLR's, CPU s
(user + sys of one ``thermocomp run``, ~2 s of it start-up), simulation mode, the defaults,
``init``'s config::

    hmc (E_CH15_Disp_Y / E_CH16_Disp_Z)                   edm (E_wire_x / E_taper_u)
      mlr          0.78 / 0.41   1.00 / 1.00    2.2        0.33 / 0.38   1.00 / 1.00    2.4
      pcr          4.99 / 5.32   6.39 / 12.94   2.3        0.77 / 1.44   2.34 / 3.78    2.5
      arx          1.72 / 0.40   2.20 / 0.97    2.5        0.64 / 0.34   1.92 / 0.89    2.7
      lagbank      0.93 / 0.35   1.19 / 0.86    2.9        0.30 / 0.31   0.92 / 0.80    5.3
      hammerstein  1.26 / 0.35   1.61 / 0.86    4.2        0.30 / 0.31   0.92 / 0.80   10.4
      auto         1.26 / 0.34   1.61 / 0.84   11.8        0.30 / 0.34   0.92 / 0.88   50.3
      persistence  1.27 / 0.64   1.63 / 1.56               0.43 / 0.43   1.29 / 1.13

(Since autohmc59, ``hammerstein``'s states at rest start their lags at 0, ``state_start=rest``:
hmc E_Y hammerstein / auto 1.58 / 1.58, E_Z 0.37 / 0.35, ``bench_auto_hmc59.py``; the edm, whose
power and flags are such states, not re-run.  ``bench_auto_hmc60.py``: the E_Y loss is the
first-sample frame's reference noise; noise-free, MLR is exact and no family needs a lag.)

``auto`` against MLR and the best single family (its blend: ``metrics.json`` targets.*.auto):
**hmc E_Y 1.256 against MLR's 0.780 (+61 %), MLR the best single: auto loses to MLR and misses
"within 10 %"**.  Its blend: hammerstein 1.0, validated 0.812 against MLR's 1.387 (3 blocked
forward folds of the 6 train runs, hammerstein ahead in each: 1.15 / 0.59 / 0.50 against 2.07
/ 0.73 / 0.77); on the 2 test runs it is behind in each (1.14 / 1.38 against 0.89 / 0.63): the
folds fit on 3-5 runs, the test model on 6 (MLR's 17 inputs may need them; not checked).  hmc
E_Z 0.345, the best (lagbank 0.71 / ati 0.22 / mlr 0.07; MLR 0.411).  edm E_X 0.303, the best
(hammerstein 0.66 / lagbank 0.30 / mlr 0.02 / lstm 0.02; MLR 0.330); **edm E_U 0.336, better
than MLR's 0.380 (-12 %) but +10.1 % on the best single (lagbank 0.305): "within 10 %" missed
by 0.1 point**: its blend arx 0.79 / mlr 0.11 / lagbank 0.10, arx validated best (0.337
against lagbank's 0.391, forward chaining in the one train record), on the test 0.340.  (The
edm's families sit at the probes' noise, 0.3 µm: 0.336 is 0.15 µm above it in quadrature,
lagbank 0.06.)  hammerstein = lagbank on the edm to the last digit (no power of a state
chosen).  Nothing tuned.

``diagnose`` (MLR; test RMSE before -> after; CPU s): no harm anywhere.

* ``hmc``: nothing accepted (0.78 / 0.41 unchanged), and said: "16 CV units (forward) in 2
  test blocks: the sign-flip test cannot reach alpha=0.01 (min p 0.25 ...) so no effect can be
  accepted" (6 train runs).  5.1 s.
* ``edm``: E_U 0.380 -> 0.325 (a 30 min first-order lag of the inputs: the submerged arm behind
  the bath's sawtooth), E_X 0.330 unchanged.  112.1 s.

``replay`` of auto's ``model.pkl`` (the defaults): the stream equals the batch (|stream - batch|
<= 6e-14 µm), RMSE = the run's test figure, 0 events; 2.9 / 22.9 s.  ``monitor`` (the model
fitted on the train split, the defaults; healthy test part): hmc (41.4 h, 2 runs) and edm
(125.9 h), mlr and lagbank: **0 events** (no warning, alarm, exclusion, new state or guard
event), RMSE fixed = adaptive (the table's figures); 2.5 / 3.2 / 4.1 / 7.6 s.

What a stranger met on the way in (``init DIR data.test_fraction=0.25``; the hmc's first
``init`` was refused at 1., the rest found on a scratch copy with that row's time cell blanked):

1. hmc: "no column reads as a measured error (no length unit in a header ...); the numeric
   columns: none" -- the unit row (``h:mm:ss,degC,...,um,rpm,-,``) was not read as one (its
   time cell, the column's format, is no unit) and was taken for the first data row.  Mended:
   a time format (``h:mm:ss``, ``[h]:mm:ss``, ``yyyy/mm/dd hh:mm:ss``) is a cell of a unit row,
   joined to no header (``tests/core/test_logger_strangers59.py``).
2. hmc: "value '+OVER' is not a number: a mark for a value not measured? list it in
   data.missing_values (['+OVER'])", then "gap of 1 missing value (row 154) is longer than
   data.max_gap_samples=0": refusals with their fix, followed (``INIT_ARGS``).  Since, the first
   names both ("..., each then a gap: data.max_gap_samples=1 interpolates the longest run of
   them here").  The ingest report counts the 3 + 4 interpolated cells.
3. hmc: "value '0:00:00' is a time of day without its date ... data.time=elapsed" for
   ``HMC_2026-09-18.csv`` (a 19:52 h run) after ``init`` had read the first file's
   ``0:00:00 ... 36:32:00`` as elapsed.  Mended: ``init`` writes ``data.time: elapsed`` where a
   file of the record or folder holds an hour past 23 in its ``h:mm:ss`` column, said.
4. edm: ``flushing`` and ``chiller_on`` (``true`` / ``false``) proposed "ignore (left out)": the
   chiller, the limit cycle's switch, was dropped; named as a state, "value 'true' is not a
   number: a mark for a value not measured? list it in data.missing_values (['true'])" -- a
   remedy that would have read every ``true`` as missing.  Mended: a state column of
   ``true`` / ``false`` is read as 1 / 0 (a workbook's boolean cell already was) and ``init``
   proposes it as a state.
5. (said nowhere, not wrong) the edm gateway's two outages (rows missing for 7 and 25 min, both
   in the train part) pass without a word: the rows are read with their times; and the logger's
   preamble ``Start,2026/09/07 07:44:29`` is not read: the hmc's runs are held out in name
   order, said ("no start time for each"), which is their order here.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).parent))
from bench_new_machines56 import rounded  # noqa: E402
from bench_new_machines57 import STEP, network, probe, sensors  # noqa: E402
from new_machine_steps import Machines  # noqa: E402
from new_machine_steps import main as steps_main  # noqa: E402

SEEDS = {"hmc": 5991, "edm": 5992}
ALPHA_UM = 11.5e-3          # µm per K per mm, steel


# --- horizontal machining centre with a pallet shuttle -------------------------------------

H_NODES = {"motor": (2.5e4, 5.0), "bearing": (6e3, 1.5), "head": (1.5e5, 8.0), "column": (1.0e6, 18.0),
           "bed": (3e6, 30.0), "bed_core": (2e6, 0.0), "table": (2.5e5, 8.0), "tank": (8e5, 80.0),
           "pal1": (1.5e5, 8.0), "pal2": (1.5e5, 8.0)}
H_LINKS = (("motor", "head", 4.0), ("bearing", "head", 6.0), ("head", "column", 6.0),
           ("column", "bed", 12.0), ("bed", "bed_core", 25.0), ("table", "bed", 6.0), ("tank", "bed", 2.0))
STATION_K = {"pal1": -2.5, "pal2": 3.0}      # each station's air less the hall's
H_SENSORS = [("Spindle motor", "motor", "motor", 1.0), ("Front bearing", "bearing", "bearing", 1.0),
             ("Head", "head", "motor", 0.8), ("Head rear", "head", "head", 1.0),
             ("Column top", "column", "head", 0.85), ("Column base", "column", "bed", 0.7),
             ("Bed left", "bed", "bed", 1.0), ("Bed right", "bed", "tank", 0.85),
             ("B table", "table", "table", 1.0)]
# then the receiver and the coolant return (the pallet in the machine), tank, cabinet, hall
OVER_CHANNEL, OVER_RUNS, OVER_SHARE = "Head rear", (3, 6), 0.002


def hmc_networks():
    """Index ``2 * (pallet - 1) + coolant``: the four networks of the shuttle and the flood."""
    nets = []
    for pallet in ("pal1", "pal2"):
        for flood in (False, True):
            links = [*H_LINKS, ("table", pallet, 20.0)]
            if flood:
                links += [("tank", pallet, 40.0), ("tank", "table", 10.0)]
            net = network(H_NODES, links)
            nets.append((net, net.propagator(STEP)))
    return nets


def hmc_programme(rng, n):
    """Per sample: spindle rpm, the pallet in the machine (1 / 2), the coolant (0 / 1)."""
    rpm, pallet = np.zeros(n), np.ones(n, int)
    k, which = 0, 1
    while k < n:
        length = int(rng.uniform(1200, 5400) / STEP) + 1
        pallet[k:k + length] = which
        rpm[k:k + length] = 0.0 if rng.random() < 0.15 else rng.choice([4000, 6000, 8000, 10000])
        which = 3 - which
        k += length
    return rpm, pallet, (rpm > 0).astype(int)


def hmc_run(nets, rng, n, start_h):
    net = nets[0][0]
    ix = net.index
    hours = start_h + np.arange(n) * STEP / 3600
    room = (rng.uniform(19.0, 26.0) + 2.0 * np.sin((hours - 9.0) / 24 * 2 * np.pi)
            + rng.normal(0, 0.03, n).cumsum() * 0.1)
    rpm, pallet, coolant = hmc_programme(rng, n)
    k = rpm / 1000.0
    power = 300.0 * k * coolant
    heat = np.zeros((n, net.n_nodes))
    heat[:, ix["motor"]] = np.where(rpm > 0, 40 + 20 * k + 2 * k**2, 0.0)
    heat[:, ix["bearing"]] = 5.0 * k
    heat[:, ix["tank"]] = (400.0 + 0.15 * power) * coolant
    for p, name in ((1, "pal1"), (2, "pal2")):
        inside = pallet == p
        heat[:, ix[name]] = np.where(inside, 0.03 * power, 8.0 * STATION_K[name])
    switch = 2 * (pallet - 1) + coolant
    nodes = _soaked_run(nets, switch, room, heat, ix)
    loaded = np.where(pallet == 1, nodes[:, ix["pal1"]], nodes[:, ix["pal2"]])
    frame = {"time": np.arange(n) * STEP}
    sensors(frame, nodes, ix, H_SENSORS, rng)
    noise = lambda: rng.normal(0, 0.02, n)  # noqa: E731
    tank = nodes[:, ix["tank"]]
    frame["T_receiver"] = rounded(0.7 * nodes[:, ix["table"]] + 0.3 * loaded + noise(), 0.01)
    frame["T_tank"] = rounded(tank + noise(), 0.01)
    frame["T_return"] = rounded(np.where(coolant > 0, 0.6 * tank + 0.4 * loaded, tank) + noise(), 0.01)
    frame["T_cabinet"] = rounded(0.4 * nodes[:, ix["motor"]] + 0.6 * nodes[:, ix["column"]] + noise(), 0.01)
    frame["T_amb"] = rounded(room + rng.normal(0, 0.05, n), 0.01)
    r = {name: nodes[:, i] - nodes[0, i] for name, i in ix.items()}
    p = loaded - nodes[0, ix["pal1"]]
    frame["E_Y"] = probe(8.05 * r["column"] + 1.5 * r["head"] - 5.75 * p - 2.0 * r["table"], rng)
    frame["E_Z"] = probe(-6 * r["head"] - 3 * r["bearing"] - 1.725 * p + 1.5 * r["bed"] - r["bed_core"], rng)
    frame["S_rpm"], frame["S_pallet"], frame["S_coolant"] = rpm, pallet, coolant
    return pd.DataFrame(frame)


def _soaked_run(nets, switch, room, heat, ix):
    """:func:`simulate` from the machine soaked at the hall's first value, each pallet at its
    station's air."""
    n = len(room)
    nodes = np.empty((n, heat.shape[1]))
    nodes[0] = room[0]
    for name, offset in STATION_K.items():
        nodes[0, ix[name]] = room[0] + offset
    for i in range(1, n):
        nodes[i] = nets[int(switch[i - 1])][1].step(nodes[i - 1], room[i - 1], heat[i - 1])
    return nodes


def elapsed(seconds: np.ndarray) -> list[str]:
    """A logger's ``h:mm:ss`` since the start, hours past 24 as they come."""
    s = np.asarray(seconds, int)
    return [f"{v // 3600}:{v % 3600 // 60:02d}:{v % 60:02d}" for v in s]


def write_hmc(folder: Path, seed: int) -> None:
    rng = np.random.default_rng(seed)
    nets = hmc_networks()
    channels = [s[0] for s in H_SENSORS] + ["Pallet receiver", "Coolant tank", "Coolant return",
                                             "Cabinet", "Hall air"]
    units = ["degC"] * len(channels) + ["um", "um", "rpm", "-", "-"]
    names = channels + ["Disp Y", "Disp Z", "Spindle speed", "Pallet", "Coolant"]
    labels = [f"CH{j + 1:02d} {name}" for j, name in enumerate(names)]
    over = names.index(OVER_CHANNEL)
    folder.mkdir(parents=True, exist_ok=True)
    day = pd.Timestamp("2026-09-07")
    for run in range(1, 9):
        n = int(rng.uniform(18, 40) * 3600 / STEP)
        start_h = float(rng.uniform(6.0, 14.0))
        frame = hmc_run(nets, rng, n, start_h)
        start = day + pd.Timedelta(hours=start_h)
        cells = frame.drop(columns="time").astype(object)
        cells = cells.map(lambda v: f"{v:.6g}")
        if run in OVER_RUNS:
            rows = rng.choice(n, max(1, int(OVER_SHARE * n)), replace=False)
            cells.iloc[rows, over] = "+OVER"
        lines = ["Logger,TL-32 Thermal Logger,Firmware 2.14", "Serial No.,TL32-0918",
                 f"Start,{start:%Y/%m/%d %H:%M:%S}", f"Interval,{int(STEP)} s",
                 f"Channels,{len(names)}", "",
                 ",".join(["Time", *labels]) + ",", ",".join(["h:mm:ss", *units]) + ","]
        for t, row in zip(elapsed(frame["time"]), cells.itertuples(index=False)):
            lines.append(",".join([t, *row]) + ",")
        (folder / f"HMC_{day:%Y-%m-%d}.csv").write_text("\r\n".join(lines) + "\r\n", encoding="utf-8")
        day = (start + pd.Timedelta(seconds=n * STEP)).normalize() + pd.offsets.BDay(1)


# --- wire EDM with a chiller on a hysteresis thermostat --------------------------------------

W_NODES = {"bath": (6e5, 15.0), "reservoir": (1.7e6, 20.0), "lower_arm": (1.2e5, 2.0),
           "upper_arm": (1.2e5, 6.0), "column": (8e5, 16.0), "base": (2.5e6, 30.0), "base_core": (2e6, 0.0),
           "xy_table": (4e5, 10.0), "cabinet": (1e5, 10.0)}
W_LINKS = (("lower_arm", "bath", 60.0), ("lower_arm", "column", 6.0), ("upper_arm", "column", 8.0),
           ("column", "base", 12.0), ("base", "base_core", 25.0), ("xy_table", "base", 10.0),
           ("bath", "xy_table", 10.0), ("cabinet", "base", 1.0), ("bath", "reservoir", 2.0))
W_FLUSH = (("bath", "reservoir", 160.0),)
CHILLER_ON_C, CHILLER_OFF_C, CHILLER_W = 20.6, 19.4, 2000.0
W_SENSORS = [("bath_temp_c", "bath", "bath", 1.0), ("reservoir_temp_c", "reservoir", "reservoir", 1.0),
             ("bath_outlet_temp_c", "bath", "reservoir", 0.7),
             ("upper_arm_temp_c", "upper_arm", "upper_arm", 1.0),
             ("lower_arm_root_temp_c", "lower_arm", "column", 0.6),
             ("column_temp_c", "column", "column", 1.0),
             ("column_top_temp_c", "column", "upper_arm", 0.8), ("base_front_temp_c", "base", "base", 1.0),
             ("base_rear_temp_c", "base", "xy_table", 0.85), ("xy_table_temp_c", "xy_table", "xy_table", 1.0),
             ("generator_cabinet_temp_c", "cabinet", "cabinet", 1.0)]


def edm_programme(rng, hours):
    """Per sample: the discharge power (kW) and whether the machine is on (Sun 0:00 - Mon 6:00 off)."""
    n = len(hours)
    weekday, hour = (hours // 24).astype(int) % 7, hours % 24       # hours from a Monday 0:00
    on = ~((weekday == 6) | ((weekday == 0) & (hour < 6)))
    power = np.zeros(n)
    k = 0
    while k < n:
        idle = rng.random() < 0.25
        length = int(rng.uniform(600, 2400) / STEP) + 1 if idle else int(rng.uniform(1200, 10800) / STEP) + 1
        power[k:k + length] = 0.0 if idle else rng.choice([0.3, 0.6, 1.0, 1.5])
        k += length
    return power * on, on


def edm_record(rng, days=21):
    """Three weeks at 60 s from Mon 06:00: the frame, the nodes, the chiller's state."""
    flush_nets = [network(W_NODES, W_LINKS), network(W_NODES, (*W_LINKS, *W_FLUSH))]
    props = [net.propagator(STEP) for net in flush_nets]
    ix = flush_nets[0].index
    n = int(days * 86400 / STEP)
    hours = 6.0 + np.arange(n) * STEP / 3600
    power, on = edm_programme(rng, hours)
    flushing = power > 0
    hunting = 0.3 * np.sign(np.sin(hours * 60 / 40 * 2 * np.pi))      # the room's AC compressor
    room = (22.0 + np.sin((hours % 24 - 10.0) / 24 * 2 * np.pi) + hunting
            + rng.normal(0, 0.03, n).cumsum() * 0.05)
    heat = np.zeros((n, len(ix)))
    heat[:, ix["bath"]] = 900.0 * power
    heat[:, ix["xy_table"]] = 20.0 * flushing
    heat[:, ix["reservoir"]] = 250.0 * flushing
    heat[:, ix["cabinet"]] = (150.0 + 200.0 * power) * on
    nodes = np.empty((n, len(ix)))
    nodes[0] = 22.0
    nodes[0, ix["bath"]] = nodes[0, ix["reservoir"]] = 20.0
    chiller = np.zeros(n, bool)
    running = False
    for i in range(1, n):
        t = nodes[i - 1, ix["reservoir"]]
        running = t > CHILLER_ON_C or (running and t > CHILLER_OFF_C)     # the thermostat's hysteresis
        chiller[i - 1] = running
        q = heat[i - 1].copy()
        q[ix["reservoir"]] -= CHILLER_W * running
        nodes[i] = props[int(flushing[i - 1])].step(nodes[i - 1], room[i - 1], q)
    chiller[-1] = running
    frame = {}
    sensors(frame, nodes, ix, W_SENSORS, rng)
    frame["T_amb"] = rounded(room + rng.normal(0, 0.05, n), 0.01)
    r = {name: nodes[:, i] - nodes[0, i] for name, i in ix.items()}
    frame["E_X"] = probe(ALPHA_UM * 500 * (r["upper_arm"] + r["lower_arm"]) / 2 + 1.2 * r["column"]
                         - ALPHA_UM * 150 * r["bath"] - ALPHA_UM * 300 * r["xy_table"]
                         + 0.5 * r["base"] - 0.8 * r["base_core"], rng)
    frame["E_U"] = probe(ALPHA_UM * 500 * (r["upper_arm"] - r["lower_arm"]), rng)
    frame["S_P"], frame["S_flush"], frame["S_chiller"] = power, flushing, chiller
    return pd.DataFrame(frame)


def write_edm(folder: Path, seed: int) -> None:
    rng = np.random.default_rng(seed)
    frame = edm_record(rng)
    names = {f"T_{j + 1:02d}": s[0] for j, s in enumerate(W_SENSORS)}
    names.update(T_amb="room_air_temp_c", E_X="wire_x_um", E_U="taper_u_um", S_P="discharge_power_kw",
                 S_flush="flushing", S_chiller="chiller_on")
    frame = frame.rename(columns=names)
    n = len(frame)
    late = rng.uniform(0, 0.3, n)                           # each poll late by 0-300 ms
    stamp = pd.Timestamp("2026-09-07 06:00") + pd.to_timedelta(np.arange(n) * STEP + late, unit="s")
    frame.insert(0, "timestamp", stamp.strftime("%Y-%m-%dT%H:%M:%S.%f").str[:-3] + "Z")
    for col in ("flushing", "chiller_on"):
        frame[col] = np.where(frame[col], "true", "false")
    keep = np.ones(n, bool)
    for start, minutes in ((int(rng.integers(2000, 12000)), 7), (int(rng.integers(14000, 26000)), 25)):
        keep[start:start + minutes] = False                 # the gateway's outages
    folder.mkdir(parents=True, exist_ok=True)
    frame[keep].to_csv(folder / "edm01_export.csv", index=False, float_format="%.6g")


def write(root: Path) -> None:
    write_hmc(root / "hmc", SEEDS["hmc"])
    write_edm(root / "edm", SEEDS["edm"])


# --- the pipeline -------------------------------------------------------------------------

FAMILIES = ("mlr", "pcr", "arx", "lagbank", "hammerstein", "auto")
# what a stranger adds to `init`: the test share, and for the logger's overrange mark what the
# two refusals said to add (the docstring's "way in")
INIT_ARGS = {"hmc": ("data.test_fraction=0.25", "data.missing_values=['+OVER']", "data.max_gap_samples=1"),
             "edm": ("data.test_fraction=0.25",)}
FOLDERS = {"hmc": "hmc", "edm": "edm/edm01_export.csv"}
CONFIGS = {"hmc": "hmc", "edm": "edm01_export"}     # the names init gives them
MONITORED = ("mlr", "lagbank")
REPLAYED = "auto"                                   # the model a lab would deploy: auto's


def data_args(root: Path, name: str) -> list[str]:
    """``init``'s config for the lab's files."""
    return [f"hydra.searchpath=[file://{root}/init-{name}/conf]", f"data={CONFIGS[name]}"]


MACHINES = Machines(doc=__doc__, write=write, records=list(SEEDS), families=FAMILIES,
                    init_args=INIT_ARGS, data_args=data_args, folders=FOLDERS, monitored=MONITORED,
                    replayed=REPLAYED)


def main(argv=None) -> int:
    return steps_main(MACHINES, argv)


if __name__ == "__main__":
    raise SystemExit(main())
