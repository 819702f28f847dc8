"""A machine whose record comes from a process historian's LONG export (issue 34, session 60).

    .venv/bin/python benchmarks/bench_historian60.py write DIR     # the lab's files only
    .venv/bin/python benchmarks/bench_historian60.py all DIR --data vtl
    .venv/bin/python benchmarks/bench_historian60.py init DIR --data vtl_exact vtl_wide
    .venv/bin/python benchmarks/bench_historian60.py run DIR --data vtl_exact vtl_wide --families mlr
    (or one step: init | run | diagnose | replay | monitor | table DIR)

The physics below was written down before any model ran on this record; nothing was tuned on
it (seed 6001 fixed beforehand, every command run once).  It differs from ``apps/sim`` and every
bench machine so far (``bench_other_machine``'s lathe, ``56``'s grinder and gantry, ``57``'s
boring mill and twin lathe, ``58``'s trunnion and laser, ``59``'s pallet HMC and wire EDM): a
VERTICAL TURRET LATHE whose heavy parts SOAK on its table (each part a mass of its own, 2-8 t,
arriving cold from an unheated yard store and warming on the table it chills), and a record
that is no table at all but a historian's tag samples, each tag logged on change at its own
times.  The helpers are ``bench_new_machines56``'s (rounding), ``57``'s (the network, the probe)
and ``new_machine_steps``'s (the steps, the table).

``vtl`` -- a vertical turret lathe, its parts soaking on a 2.5 m table
-----------------------------------------------------------------------
A rotary table (2.5 m) on a large TABLE BEARING, driven by the main motor through a gearbox; two
columns carry the crossrail, on which the ram (the tool, vertical) moves in X.  Lumped network
(C J/K, hA W/K to the hall air): main ``motor`` (6e4, 60: its fan), ``gearbox`` (4e5, 30), the table
``bearing`` (5e5, 3), ``table`` (2.8e6, 25), the ``part`` (460 m J/K for m t, 3 + 1.5 m W/K),
the lube ``oil`` unit (3e5, 12), ``base`` (9e6, 60) and its unmeasured ``base_core`` (6e6, 0),
``col_L`` / ``col_R`` (1.6e6, 18 each), ``crossrail`` (1.3e6, 20), ``ram`` (2.2e5, 6).  Links
(W/K): motor-gearbox 6, gearbox-base 5, gearbox-bearing 8, bearing-table 30, bearing-base 15,
oil-base 2, base-base_core 30, base-col_L 10, base-col_R 10, col_L-crossrail 6,
col_R-crossrail 6, crossrail-ram 8; switched: table-part 45 while a part is clamped, oil-bearing
30 while the table turns (the lube flow), else 5.  Heat (W), P the cutting power (W), n the
table speed (rpm): motor 150 + 0.08 P while turning, gearbox 0.04 P + 5 n, bearing 12 n +
0.01 P, ram 40 while cutting, the part 0.03 P (the chips take the rest), the oil pump 300 into
the oil while turning, the oil cooler -150 x (oil - hall - 1) when positive (it follows the
hall + 1 K), and, while the hall door is open (the crane brings a part from the yard), -54 into
``col_R`` (its air 3 K colder: the door is on its side).  The programme, 3 weeks from Mon
2026-11-02 00:00 (the machine soaked at the hall's first value): shifts Mon-Fri 6-22 h; a part's
machining takes 3-10 h of shift time (a part left at 22 h stays clamped overnight and over the
weekend, soaking), in blocks of 10-40 min at n of 8 / 15 / 25 / 40 rpm and P 5-25 kW, between
blocks a 2-10 min stop (measuring, a tool change); a part change (on shift) 20-60 min with the
table stopped, no part on the table and the hall door open; a new part, m 2-8 t, arrives at the
yard store's temperature, the hall's less 4-9 K (November).  The hall: 17.5 °C + 1.5 K a day
(warmest at 15 h) + 1 K on shift (the machines), a slow random walk.  Errors (µm, rises since
the record's start; the displacement sensors of a test fixture read a reference on the table
rim, R 1200 mm): ``E_X`` = 6.9 crossrail - 13.8 table + 14.8 (col_L - col_R) - 2.0 base_core
(the rail's half length grows the ram out, the table grows the reference out, a column warmer
than the other leans the crossrail); ``E_Z`` = 34.5 (col_L + col_R) / 2 - 17.25 ram - 4.6 table -
2.9 bearing + 1.5 base - 1.0 base_core (the columns lift the rail, the ram grows down, the table
and bearing lift the reference).  So the parts act on the error only through the table they
chill, each with its own mass and start: a load the sensors see (the part's surface sensor),
not the model's inputs' usual pattern.  Sensors (0.02 K noise, 0.01 K steps): main motor,
gearbox (0.8 gearbox + 0.2 motor), table bearing (0.8 bearing + 0.2 base), table rim, table
centre (0.7 table + 0.3 bearing), the part's surface (a magnetic contact sensor: the part while
one is clamped, else parked on the table rim), oil supply, oil return (0.6 oil + 0.4 bearing),
base front, base rear (0.8 base + 0.2 col_R), column left, column right, crossrail, ram (0.85
ram + 0.15 crossrail), hall air (0.05 K noise); states: table speed (rpm), cutting power (kW),
part loaded (0 / 1), hall door (0 / 1); the displacement sensors 0.3 µm noise, 0.1 µm steps.

The historian (report by exception; every stamp its scan's time plus the collector's latency,
0-200 ms): the displacement sensors scanned every 10 s, logged when 0.1 µm or more from the last
logged value, 0.3 % of scans ``Bad`` (a chip on the target: value ``Bad Input``, quality
``Bad``); temperatures scanned every 30 s, logged at 0.05 K from the last (the hall air every
60 s at 0.1 K); states scanned every 10 s, logged on a change of 0.5 rpm, 0.2 kW or a flag's;
every tag logged at least every 15 min (the heartbeat).  ONE file, ``vtl/VTL01_history.csv``:
``TagName,Timestamp,Value,Quality``, sorted by tag then time (an archive export), timestamps on
the hall's clock ``2026-11-02 06:00:00.137``, tags ``VTL01.Table.Bearing.Temp``,
``VTL01.Fixture.X_um``, ``VTL01.Table.Speed_rpm`` ...; the last quarter test
(``data.test_fraction=0.25``).

Mended before any model ran (the first ``write``'s sensor ranges only): the motor's and the
gearbox's hA were 6 and 10 W/K, a motor at 169 °C and a gearbox at 89 °C under 25 kW (2 kW of
motor losses without its fan); now 60 and 30.

The wide check: the same simulation written twice more.  ``vtl_wide/VTL01_wide.csv``: every tag
at every 10 s step in one row (a Bad scan an empty cell); ``vtl_exact/VTL01_exact.csv``: its long
form, each tag logged at the exact 10 s stamp of every step where its value differs from the
step before (a Bad scan logged Bad), no latency.  Held onto a 10 s grid, the exact long file IS
the wide table cell for cell (every grid point is a stamp; a tag not logged there kept the value
the hold takes; a Bad scan is missing from its stamp to the next, one grid row, the wide file's
empty cell): MLR's test RMSE must agree to the last digit.

Measured (2026-11-30, each step once, 2 shared cores; ``write`` 12.6 s CPU).  Test RMSE (µm) per
target, ratio to MLR's, CPU s (user + sys of one ``thermocomp run``; the record read through a
temporary CSV grid then, since a Parquet one: mlr 15.2 -> 10.2 s, the same RMSE to the last
digit), the defaults, ``init``'s config (grid 10 s, 181,439 rows, the last quarter test)::

    vtl (E_VTL01.Fixture.X / E_VTL01.Fixture.Z)
      mlr              0.59 / 0.74     1.00 / 1.00    15.2
      pcr              4.50 / 6.17     7.69 / 8.37    15.1
      arx              0.54 / 0.80     0.92 / 1.08    15.9
      lagbank          0.34 / 0.39     0.58 / 0.53    33.4
      hammerstein      0.30 / 0.44     0.51 / 0.59    97.4
      auto             0.38 / 0.64     0.65 / 0.86   374.5
      persistence      0.41 / 0.41     0.69 / 0.55

MLR / best single / auto: **E_X 0.586 / 0.301 (hammerstein) / 0.379; E_Z 0.737 / 0.391
(lagbank) / 0.637**: auto beats MLR on both and loses to the best single on both (+26 %,
+63 %).  Its blends: E_X hammerstein 0.49 / arx 0.33 / mlr 0.18 (validated 0.453 in 5
forward-chaining folds; MLR 0.672); E_Z mlr 0.48 / lstm 0.33 / hammerstein 0.13 / lagbank 0.03 /
arx 0.03 (the folds rank hammerstein 0.899, lstm 0.940, lagbank 0.952, mlr 0.962: close; on the
test lagbank is far ahead).  Nothing tuned.

``diagnose`` (MLR; test RMSE before -> after): E_X 0.586 -> 0.342 (first-order lags of the
inputs, 1800 s and 14400 s: the soaking table and the columns), E_Z 0.737 -> 0.398 (a 900 s
lag); 33.4 s.  ``replay`` of mlr's ``model.pkl``: |stream - batch| <= 2.6e-13 µm, 0 events, RMSE
0.5859 / 0.7369 (the run's 0.5858 / 0.7367: a stream keeps the Bad scans' cells missing, not
scored; the batch interpolates them), 16.8 s.  ``monitor`` (mlr fitted on the train split, the
healthy test part, 126 h): **0 events** (no warning, alarm, exclusion, new state or guard
event), RMSE fixed = adaptive = 0.5859 / 0.7369; 18.4 s.

The wide check (``init`` of each, then mlr; every digit printed by the run): ``vtl_exact`` (long,
2,704,789 samples) 0.581806397769775 / 0.7187026528768222, ``vtl_wide`` the same digits: equal
by construction, as above.  The historian's record (``vtl``: deadbands, 15 min heartbeats, the
collector's latency) costs MLR 0.7 % / 2.5 % against them (0.5858 / 0.7367): a grid row just
before a late probe stamp holds the previous scan (the grid starts 0.181 s after the first
stamp, the latency is 0-0.2 s).  CPU: ``run`` mlr 24.3 s (the exact long file's 2.7 M rows),
5.0 s (wide); ``init`` 42.5 s / 3.3 s.

What a stranger met on the way in (``init <file> data.test_fraction=0.25``):

1. Before historian60: ``init`` "no column reads as a measured error (...) the numeric
   columns: 'Value'", ``run data.path=<file>`` "3 column(s) not read: 'TagName' has no role,
   'Value' has no role, 'Quality' has no role".  Mended: the long layout (``core/io/historian.py``).
2. The archive export is sorted by tag: its first 50 lines hold one tag, and the layout was
   not found (a tag column was told by its values coming back after one another).  Mended: a
   ``TagName`` / ``Tag`` / ``Name`` header says it too.
3. ``init`` proposed ``data.resample_s=10.01`` (the probe's median interval: the collector's
   latency and the deadband's skipped scans).  Mended: two digits, 10.
4. "gap of 2 missing values (grid rows 2139-2140) is longer than data.max_gap_samples=0" (the
   Bad scans), then, at 2, a gap of 3 further on, then of 4: refused one gap at a time.
   Mended: the refusal says the column's longest, "its longest gap is 4 values,
   data.max_gap_samples=4 interpolates every one of this column" (``INIT_ARGS``).
5. ``VTL01.Part.Loaded`` (0 / 1) proposed a temperature and ``VTL01.Hall.Door`` the hall's air
   (its word ``Hall``), each read as one.  Mended: ``init`` proposes a column of only two values
   one apart over the record as a state, said.
6. (said, not wrong) "the grid starts where every tag has a sample, 0.17 s after the first
   stamp": the first stamps of the tags differ by their latency.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).parent))
from bench_new_machines56 import rounded  # noqa: E402
from bench_new_machines57 import network, probe  # noqa: E402
from new_machine_steps import Machines  # noqa: E402
from new_machine_steps import main as steps_main  # noqa: E402

SEED = 6001
STEP = 10.0
START = pd.Timestamp("2026-11-02 00:00:00")
WEEKS = 3
NODES = {"motor": (6e4, 60.0), "gearbox": (4e5, 30.0), "bearing": (5e5, 3.0), "table": (2.8e6, 25.0),
         "part": (460.0 * 1000 * 5, 3 + 1.5 * 5), "oil": (3e5, 12.0), "base": (9e6, 60.0),
         "base_core": (6e6, 0.0), "col_L": (1.6e6, 18.0), "col_R": (1.6e6, 18.0),
         "crossrail": (1.3e6, 20.0), "ram": (2.2e5, 6.0)}    # (a part: its own mass, simulate_vtl)
LINKS = (("motor", "gearbox", 6.0), ("gearbox", "base", 5.0), ("gearbox", "bearing", 8.0),
         ("bearing", "table", 30.0), ("bearing", "base", 15.0), ("oil", "base", 2.0),
         ("base", "base_core", 30.0), ("base", "col_L", 10.0), ("base", "col_R", 10.0),
         ("col_L", "crossrail", 6.0), ("col_R", "crossrail", 6.0), ("crossrail", "ram", 8.0))
# tag, node a, node b, weight of a (the part's surface sensor: its own rule)
SENSORS = [("VTL01.Main.Motor.Temp", "motor", "motor", 1.0),
           ("VTL01.Gearbox.Temp", "gearbox", "motor", 0.8),
           ("VTL01.Table.Bearing.Temp", "bearing", "base", 0.8),
           ("VTL01.Table.Rim.Temp", "table", "table", 1.0),
           ("VTL01.Table.Centre.Temp", "table", "bearing", 0.7),
           ("VTL01.Oil.Supply.Temp", "oil", "oil", 1.0),
           ("VTL01.Oil.Return.Temp", "oil", "bearing", 0.6),
           ("VTL01.Base.Front.Temp", "base", "base", 1.0),
           ("VTL01.Base.Rear.Temp", "base", "col_R", 0.8),
           ("VTL01.Column.Left.Temp", "col_L", "col_L", 1.0),
           ("VTL01.Column.Right.Temp", "col_R", "col_R", 1.0),
           ("VTL01.Crossrail.Temp", "crossrail", "crossrail", 1.0),
           ("VTL01.Ram.Temp", "ram", "crossrail", 0.85)]
PART_TAG, AIR_TAG = "VTL01.Part.Surface.Temp", "VTL01.Hall.Air.Temp"
ERROR_TAGS = ("VTL01.Fixture.X_um", "VTL01.Fixture.Z_um")
STATE_TAGS = {"VTL01.Table.Speed_rpm": 0.5, "VTL01.Cut.Power_kW": 0.2, "VTL01.Part.Loaded": 0.5,
              "VTL01.Hall.Door": 0.5}
HEARTBEAT_S = 900.0
BAD_SHARE = 0.003


def schedule(rng, n):
    """Per sample: table speed (rpm), cutting power (W), part loaded (0/1), door open (0/1), the
    part's index (a new one at each load), and each part's mass (t) and store offset (K)."""
    hours = np.arange(n) * STEP / 3600
    day, hour = (hours // 24).astype(int), hours % 24
    on_shift = (day % 7 < 5) & (hour >= 6) & (hour < 22)
    rpm, power = np.zeros(n), np.zeros(n)
    loaded, door, part = np.ones(n, int), np.zeros(n, int), np.zeros(n, int)
    masses, offsets = [rng.uniform(2, 8)], [rng.uniform(4, 9)]
    k, left = 0, rng.uniform(3, 10) * 3600      # the first part: clamped at the start, cold
    while k < n:
        if not on_shift[k]:
            part[k] = len(masses) - 1
            k += 1
            continue
        if left <= 0:                            # a part change: table stopped, door open
            length = int(rng.uniform(20, 60) * 60 / STEP)
            stop = min(n, k + length)
            loaded[k:stop], door[k:stop], part[k:stop] = 0, 1, len(masses) - 1
            masses.append(rng.uniform(2, 8))
            offsets.append(rng.uniform(4, 9))
            left = rng.uniform(3, 10) * 3600
            k = stop
            continue
        length = int(rng.uniform(10, 40) * 60 / STEP)
        pause = int(rng.uniform(2, 10) * 60 / STEP)
        block = np.arange(k, min(n, k + length))
        block = block[on_shift[block]]
        speed, cut = rng.choice([8.0, 15.0, 25.0, 40.0]), rng.uniform(5e3, 25e3)
        rpm[block], power[block], part[block] = speed, cut, len(masses) - 1
        left -= len(block) * STEP
        stop = min(n, k + length + pause)
        part[k:stop] = len(masses) - 1
        k = stop
    return rpm, power, loaded, door, part, np.array(masses), np.array(offsets)


def hall_air(rng, n):
    hours = np.arange(n) * STEP / 3600
    day, hour = (hours // 24).astype(int), hours % 24
    on_shift = (day % 7 < 5) & (hour >= 6) & (hour < 22)
    walk = np.cumsum(rng.normal(0, 0.004, n))
    return 17.5 + 1.5 * np.sin((hours - 9.0) / 24 * 2 * np.pi) + 1.0 * on_shift + walk


def simulate_vtl(rng):
    """The record: a frame of every tag at every 10 s step (values), and the part index."""
    n = int(WEEKS * 7 * 24 * 3600 / STEP)
    rpm, power, loaded, door, part, masses, offsets = schedule(rng, n)
    room = hall_air(rng, n)
    nets = {}

    def net_of(p, turning, clamped):
        key = (p, turning, clamped)
        if key not in nets:
            nodes = dict(NODES, part=(460.0 * 1000 * masses[p], 3 + 1.5 * masses[p]))
            links = [*LINKS, ("oil", "bearing", 30.0 if turning else 5.0)]
            if clamped:
                links.append(("table", "part", 45.0))
            net = network(nodes, links)
            nets[key] = (net, net.propagator(STEP))
        return nets[key]

    net = net_of(0, False, True)[0]
    ix = net.index
    temps = np.empty((n, net.n_nodes))
    temps[0] = room[0]
    temps[0, ix["part"]] = room[0] - offsets[0]
    for i in range(1, n):
        prev = temps[i - 1].copy()
        if part[i] != part[i - 1] or (loaded[i] and not loaded[i - 1]):
            prev[ix["part"]] = room[i - 1] - offsets[part[i]]     # a new part from the store
        heat = np.zeros(net.n_nodes)
        turning, p = rpm[i - 1] > 0, power[i - 1]
        if turning:
            heat[ix["motor"]] = 150 + 0.08 * p
            heat[ix["oil"]] = 300.0
            heat[ix["ram"]] = 40.0
            heat[ix["part"]] = 0.03 * p
        heat[ix["gearbox"]] = 0.04 * p + 5 * rpm[i - 1]
        heat[ix["bearing"]] = 12 * rpm[i - 1] + 0.01 * p
        heat[ix["oil"]] -= 150 * max(0.0, prev[ix["oil"]] - room[i - 1] - 1.0)
        heat[ix["col_R"]] -= 54.0 * door[i - 1]
        if not loaded[i - 1]:        # no part: its node follows the hall, cut off from the table
            prev[ix["part"]] = room[i - 1]
        temps[i] = net_of(int(part[i - 1]), bool(turning), bool(loaded[i - 1]))[1].step(
            prev, room[i - 1], heat)
    r = {name: temps[:, j] - temps[0, j] for name, j in ix.items()}
    frame = {}
    for tag, a, b, w in SENSORS:
        frame[tag] = rounded(w * temps[:, ix[a]] + (1 - w) * temps[:, ix[b]]
                             + rng.normal(0, 0.02, n), 0.01)
    surface = np.where(loaded > 0, temps[:, ix["part"]], temps[:, ix["table"]])
    frame[PART_TAG] = rounded(surface + rng.normal(0, 0.02, n), 0.01)
    frame[AIR_TAG] = rounded(room + rng.normal(0, 0.05, n), 0.01)
    frame[ERROR_TAGS[0]] = probe(6.9 * r["crossrail"] - 13.8 * r["table"]
                                 + 14.8 * (r["col_L"] - r["col_R"]) - 2.0 * r["base_core"], rng)
    frame[ERROR_TAGS[1]] = probe(34.5 * (r["col_L"] + r["col_R"]) / 2 - 17.25 * r["ram"]
                                 - 4.6 * r["table"] - 2.9 * r["bearing"] + 1.5 * r["base"]
                                 - 1.0 * r["base_core"], rng)
    frame["VTL01.Table.Speed_rpm"] = rpm
    frame["VTL01.Cut.Power_kW"] = np.round(power / 1000, 1)
    frame["VTL01.Part.Loaded"] = loaded.astype(float)
    frame["VTL01.Hall.Door"] = door.astype(float)
    values = pd.DataFrame(frame)
    bad = pd.DataFrame(False, index=values.index, columns=values.columns)
    for tag in ERROR_TAGS:                      # a chip on the target: 1-2 scans Bad
        starts = rng.choice(n - 2, int(BAD_SHARE * n / 1.5), replace=False)
        bad.loc[starts, tag] = True
        bad.loc[starts[rng.random(starts.size) < 0.5] + 1, tag] = True
    return values, bad


def scan_plan(tag: str) -> tuple[int, float]:
    """(scan every so many steps, deadband) of a tag."""
    if tag in ERROR_TAGS:
        return 1, 0.1
    if tag in STATE_TAGS:
        return 1, STATE_TAGS[tag]
    if tag == AIR_TAG:
        return 6, 0.1
    return 3, 0.05


def exceptions(values: np.ndarray, bad: np.ndarray, every: int, deadband: float) -> np.ndarray:
    """The steps a report-by-exception collector logs: each scan whose value is ``deadband`` or
    more from the last logged one, a Bad scan and the first Good one after it, the heartbeat."""
    logged = np.zeros(len(values), bool)
    last, since, was_bad = None, 0.0, False
    beat = int(HEARTBEAT_S / STEP)
    for i in range(0, len(values), every):
        since += every
        if bad[i]:
            logged[i], was_bad = True, True
            continue
        if last is None or was_bad or abs(values[i] - last) >= deadband - 1e-9 or since >= beat:
            logged[i], last, since, was_bad = True, values[i], 0, False
    return logged


def long_rows(values: pd.DataFrame, bad: pd.DataFrame, rng, exact: bool) -> pd.DataFrame:
    """The historian's samples: per tag the logged steps (``exact``: every change, at the step's
    own stamp), the value, the quality."""
    parts = []
    seconds = np.arange(len(values)) * STEP
    for tag in values.columns:
        v, b = values[tag].to_numpy(), bad[tag].to_numpy()
        if exact:
            keep = np.ones(len(v), bool)
            keep[1:] = (v[1:] != v[:-1]) | b[1:] | b[:-1]
            latency = np.zeros(keep.sum())
        else:
            every, band = scan_plan(tag)
            keep = exceptions(v, b, every, band)
            latency = rng.uniform(0, 0.2, keep.sum())
        stamp = START + pd.to_timedelta(np.round((seconds[keep] + latency) * 1000), unit="ms")
        text = np.where(b[keep], "Bad Input", [f"{x:.6g}" for x in v[keep]])
        parts.append(pd.DataFrame({"TagName": tag, "Timestamp": stamp.strftime(
            "%Y-%m-%d %H:%M:%S.%f").str[:-3], "Value": text,
            "Quality": np.where(b[keep], "Bad", "Good")}))
    return pd.concat(parts, ignore_index=True)


def write(root: Path) -> None:
    rng = np.random.default_rng(SEED)
    values, bad = simulate_vtl(rng)
    for name in ("vtl", "vtl_exact", "vtl_wide"):
        (root / name).mkdir(parents=True, exist_ok=True)
    long_rows(values, bad, rng, exact=False).to_csv(root / "vtl" / "VTL01_history.csv",
                                                    index=False)
    long_rows(values, bad, rng, exact=True).to_csv(root / "vtl_exact" / "VTL01_exact.csv",
                                                   index=False)
    wide = values.map(lambda x: f"{x:.6g}").mask(bad, "")
    wide.insert(0, "Timestamp", (START + pd.to_timedelta(np.arange(len(values)) * STEP, unit="s")
                                 ).strftime("%Y-%m-%d %H:%M:%S"))
    wide.to_csv(root / "vtl_wide" / "VTL01_wide.csv", index=False)


# --- the pipeline -------------------------------------------------------------------------

FAMILIES = ("mlr", "pcr", "arx", "lagbank", "hammerstein", "auto")
# what a stranger adds to `init`: the test share, and what the refusal of the Bad scans said
INIT_ARGS = {name: ("data.test_fraction=0.25", "data.max_gap_samples=4")
             for name in ("vtl", "vtl_exact", "vtl_wide")}
FOLDERS = {"vtl": "vtl/VTL01_history.csv", "vtl_exact": "vtl_exact/VTL01_exact.csv",
           "vtl_wide": "vtl_wide/VTL01_wide.csv"}
CONFIGS = {"vtl": "VTL01_history", "vtl_exact": "VTL01_exact", "vtl_wide": "VTL01_wide"}
MONITORED = ("mlr",)
REPLAYED = "mlr"


def data_args(root: Path, name: str) -> list[str]:
    """``init``'s config for the lab's files."""
    return [f"hydra.searchpath=[file://{root}/init-{name}/conf]", f"data={CONFIGS[name]}"]


MACHINES = Machines(doc=__doc__, write=write, records=["vtl", "vtl_exact", "vtl_wide"],
                    families=FAMILIES, init_args=INIT_ARGS, data_args=data_args, folders=FOLDERS,
                    monitored=MONITORED, replayed=REPLAYED)


def main(argv=None) -> int:
    return steps_main(MACHINES, argv)


if __name__ == "__main__":
    raise SystemExit(main())
