"""Today's merges together, on a machine nobody tuned on (session 62, stranger62).

    .venv/bin/python benchmarks/bench_stranger62.py write DIR     # the lab's files only
    .venv/bin/python benchmarks/bench_stranger62.py all DIR       # write, init, run, diagnose,
                                                                  # replay, monitor, export, table
    (or one step: init | run | diagnose | replay | monitor | export | replay-each | table DIR)

The physics below was written down and committed before any model ran on this record; nothing
was tuned on it (seeds 6221 and 6222 fixed beforehand, 6222 a second draw; every command run
once).  It differs from ``apps/sim`` and every bench machine so far: a CNC GEAR-HOBBING MACHINE
whose hob head rides on a moving column, its workpiece table turned by a direct-drive torque
motor, the cutting oil cooled by an air/oil HEAT EXCHANGER whose FAN switches on/off (a
thermostat, a machine state the log carries), the drift measured only by an in-machine probe
on a master gear's reference bore (a probe cycle now and then).

``hobber`` -- a gear-hobbing machine, an oil cooler's fan switching
-------------------------------------------------------------------
Lumped network (C J/K, hA W/K to the hall air): hmotor (the hob spindle's motor, 2e4, 5), hhead
(the hob head, 1.5e5, 6), column (8e5, 14), tmotor (the table's torque motor, 6e4, 4), table
(4e5, 8), oil (2.5e5, 10), bed (3e6, 30).  Links (W/K): hmotor-hhead 8, hhead-column 10,
column-bed 12, tmotor-table 9, table-bed 10, oil-table 8, oil-hhead 4, oil-bed 3.  Heat (W):
while hobbing (a job's cutting passes) hmotor 40 + 0.08 n_hob (rpm: 400 / 700 / 1000 per job),
hhead 12 + 0.02 n_hob, tmotor 35, oil +300 (the cutting power); oil +70 (its pump) on shift; the
cooler's FAN removes 12 (oil - air) + 250 W from the oil while on (thermostat: on at oil 3.0 K
above the hall air, off at 1.0 K above, checked every 10 s; never below the air: the removal
clipped at 0).  The programme: 3 weeks from Mon 2026-11-02 00:00 (the machine soaked at the
hall's first value); shifts Mon-Fri 6-22 h; jobs of 1-2.5 h at one hob speed, hobbing 60-90 %
of it in passes of 4-12 min parted by a part change (1-3 min, the hob stopped); between jobs
5-15 min of set-up.  The hall (°C): 20 + 1.2 sin(2 pi (h - 10) / 24) + 0.7 on shift (through a
40 min lag) + a slow walk.  Errors (µm, at the master gear's bore; rises r since the record's
start): ``E_X`` (the centre distance) = 0.0115 * 350 (column) - 2.2 hhead + 1.1 table - 0.4 bed;
``E_Z`` (the hob's axial position) = 5.5 hhead + 1.8 hmotor - 0.0115 * 600 * table + 2.0 oil.
Sensors (Pt100, 0.02 K noise, 0.01 K steps; hall air 0.05 K): Hob motor (hmotor), Hob head (0.8
hhead + 0.2 hmotor), Column (0.85 column + 0.15 hhead), Table motor (tmotor), Table (0.8 table +
0.2 oil), Oil (oil), Bed (bed), Hall; the hob's speed (rpm, 0 stopped) and the fan's relay (0/1).
The probe: 0.3 µm repeatability, 0.1 µm steps; a cycle every 12-18 min of the shift, 8 % skipped.

Draw 6221 (``hobber``, separate TEST RUNS, the first-sample frame): the lab runs the machine
6:00-14:00 on every weekday of the 3 weeks (15 runs) and logs each run on its own: the logger
starts at 6:00 (the machine switched on), every 30 s; the probe cycle's FIRST reading comes
10-25 min later (the warm-up part's first pass: a LATE FIRST PROBE), then every 12-18 min; the
probe zeroed at the run's start by the lab's macro (the rise since the logger's start), so its
first reading is already E(m) - E(0) != 0.  Exported by the lab's MATLAB script: one v5 .mat,
``hobber/hobber_runs.mat``, a struct array ``runs`` (one element per run): ``name``, ``t``
(seconds since the run's start), ``T_hob_motor``... as MATLAB fields (``Thobmotor``, ``Thead``,
``Tcolumn``, ``Ttmotor``, ``Ttable``, ``Toil``, ``Tbed``, ``Thall``), ``nhob`` (rpm), ``fan``
(0/1), ``dX``, ``dZ`` (µm, NaN between the probe's cycles).  Test share:
``data.test_fraction=0.3``.

Draw 6222 (``hobber_b``, CONTINUED WEEKLY FILES, the none frame): the edge PC logs every 30 s
all week (nights and weekends too), one CSV per calendar week (``GH22_KW45.csv``...), German
Excel style (``;`` separated, decimal comma, ``Zeitstempel`` ``02.11.2026 00:00:30``), headers
with units (``Hobmotor [°C]``, ``Lüfter``, ``Fräserdrehzahl [1/min]``, ``Sonde X [µm]``), the
probe's last result written on its next row, empty between cycles; the probe never re-zeroed
(the rises since the record's start).  The last week is the test (``data.test_fraction=0.34``).

Measured (2026-12-01, every step once, 2 shared cores; ``write`` 4.0 s CPU; ``init`` 1.9 s
each): test RMSE (µm), simulation, and ``eval.mode=one_step`` (from the last probe reading, a
cycle ahead: 30 rows), persistence (its label completed by each model's y_hat(m): it differs
per model on hobber), CPU s of one ``run``::

    hobber (6221, first-sample frame, 15 MATLAB runs, 5 test)  E_dX / E_dZ
      mlr          0.46 / 0.56   1-step 0.40 / 0.45   pers. 0.51 / 3.15   2.6
      pcr          0.63 / 1.24          0.43 / 0.63         0.59 / 3.41   2.8
      arx          0.44 / 0.56          0.38 / 0.45         0.52 / 3.16   2.9
      lagbank      0.49 / 0.56          0.40 / 0.45         0.50 / 3.21   3.6
      hammerstein  0.49 / 0.69          0.40 / 0.66         0.50 / 3.20   5.6
      auto         0.46 / 0.55          0.40 / 0.44         0.51 / 3.17  56.4
    hobber_b (6222, none frame, 3 weekly German CSVs, the last test)  E_Sonde_X / E_Sonde_Z
      mlr          0.30 / 0.35   1-step 0.30 / 0.35   pers. 0.48 / 3.26   3.0
      pcr          0.61 / 1.12          0.41 / 0.67                       3.0
      arx          0.30 / 0.35          0.30 / 0.35                       3.4
      lagbank      0.28 / 0.32          0.28 / 0.33                       4.5
      hammerstein  0.28 / 0.32          0.29 / 0.33                       6.4
      auto         0.29 / 0.34          0.29 / 0.34                      78.3

(hammerstein: E_dX took no state, = lagbank; E_dZ S_nhob, S_fan.)  One-step on hobber BEFORE
the mend (stranger62): mlr 0.44 / 5.58, pcr 1.08 / 10.46, arx 0.45 / 5.65, lagbank 0.40 / 4.12
(the law fed the label E(t) - E(m) against a simulation and a scored label E(t) - E(0)).
Validation (blocked forward, mlr) on hobber before / after the mend: E_dX 0.93 / 0.47, E_dZ
8.85 / 0.72 (test 0.56); auto 9.11 / 0.73; sweep's val_rmse (mean) 4.89 / 0.60.  hobber_b
unchanged to the last digit.  ``replay-each`` (12 models): |stream - batch| <= 1.14e-13 µm,
stream = batch = run, 0 events.  ``deploy`` (mlr, arx, lagbank, hammerstein: run, replay,
promote of the run, export C with the check pack, ``check.sh``): every pack passed (<= 1.2e-13
µm); promote's mean = run's mean (hobber_b: run = replay = promote = the pack's RMSE within
2e-14); on hobber the pack scored against the raw probe (zeroed at the run's start: the TRUE
E(t) - E(0)) gives mlr 0.49 / 0.60, lagbank 0.41 / 0.49 against run's frame figures 0.46 /
0.56, 0.49 / 0.56: not a mismatch, the error before the first probe no lab measures.
``monitor`` (mlr, the healthy test part, 40 h / 168 h): 0 events, fixed = adaptive.
``diagnose`` (mlr): before = run's test on both; hobber nothing accepted; hobber_b E_Sonde_Z
0.352 -> 0.316 (a 7200 s first-order lag), its ``rerun`` gives 0.31600 = after.  ``export``
C: the .mat fed to ``stream`` refused as binary (convert to CSV), the test runs as read
streamed: |C - replay| 1.4e-14 µm; hobber_b's German CSV fed as it is: 20,160 rows,
|C - replay| 7.8e-14.  ``sweep`` (mlr, lagbank) + compare + promote + export champion: check
passed on both.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).parent))
from bench_new_machines56 import rounded  # noqa: E402
from bench_new_machines57 import network  # noqa: E402
from new_machine_steps import Machines  # noqa: E402
from new_machine_steps import main as steps_main  # noqa: E402

SEEDS = {"hobber": 6221, "hobber_b": 6222}
STEP = 10.0
LOG_EVERY = 3                                  # 30 s rows
START = pd.Timestamp("2026-11-02 00:00:00")
WEEKS = 3
NODES = {"hmotor": (2e4, 5.0), "hhead": (1.5e5, 6.0), "column": (8e5, 14.0),
         "tmotor": (6e4, 4.0), "table": (4e5, 8.0), "oil": (2.5e5, 10.0), "bed": (3e6, 30.0)}
LINKS = (("hmotor", "hhead", 8.0), ("hhead", "column", 10.0), ("column", "bed", 12.0),
         ("tmotor", "table", 9.0), ("table", "bed", 10.0), ("oil", "table", 8.0),
         ("oil", "hhead", 4.0), ("oil", "bed", 3.0))
FAN_ON_K, FAN_OFF_K = 3.0, 1.0
# (csv name, MATLAB field, node a, node b, weight of a)
SENSORS = [("Hobmotor", "Thobmotor", "hmotor", "hmotor", 1.0),
           ("Fraeskopf", "Thead", "hhead", "hmotor", 0.8),
           ("Staender", "Tcolumn", "column", "hhead", 0.85),
           ("Tischmotor", "Ttmotor", "tmotor", "tmotor", 1.0),
           ("Tisch", "Ttable", "table", "oil", 0.8),
           ("Oel", "Toil", "oil", "oil", 1.0), ("Bett", "Tbed", "bed", "bed", 1.0)]
RUN_HOURS = (6.0, 14.0)


# --- the physics ----------------------------------------------------------------------------

def on_shift(n):
    hours = np.arange(n) * STEP / 3600
    day, hour = (hours // 24).astype(int), hours % 24
    return ((day % 7) < 5) & (hour >= 6) & (hour < 22), hours


def programme(rng, n):
    """Per 10 s step: the hob's speed (rpm, 0 stopped), hobbing (0/1), on shift (0/1)."""
    on, _ = on_shift(n)
    rpm, cut = np.zeros(n), np.zeros(n, int)
    k = 0
    while k < n:
        if not on[k]:
            k += 1
            continue
        job_end = min(n, k + int(rng.uniform(1, 2.5) * 3600 / STEP))
        speed, duty = float(rng.choice([400, 700, 1000])), rng.uniform(0.6, 0.9)
        while k < job_end and on[k]:
            length = int(rng.uniform(4, 12) * 60 * duty / STEP)
            block = np.arange(k, min(job_end, k + length))
            block = block[on[block]]
            rpm[block], cut[block] = speed, 1
            k += length + int(rng.uniform(1, 3) * 60 / STEP)
        k += int(rng.uniform(5, 15) * 60 / STEP)
    return rpm, cut, on.astype(int)


def hall(rng, on, n):
    hours = np.arange(n) * STEP / 3600
    lag, a = np.empty(n), STEP / 2400
    lag[0] = on[0]
    for i in range(1, n):
        lag[i] = lag[i - 1] + a * (on[i - 1] - lag[i - 1])
    return (20.0 + 1.2 * np.sin(2 * np.pi * (hours % 24 - 10) / 24) + 0.7 * lag
            + np.cumsum(rng.normal(0, 0.002, n)))


def simulate(rng):
    """Every node at every 10 s step, the air, the hob's speed, the fan's relay, the shift."""
    n = int(WEEKS * 7 * 86400 / STEP)
    rpm, cut, on = programme(rng, n)
    air = hall(rng, on, n)
    net = network(NODES, LINKS)
    step = net.propagator(STEP)
    ix = net.index
    temps = np.empty((n, net.n_nodes))
    temps[0] = net.steady_state(air[0], np.zeros(net.n_nodes))
    fan = np.zeros(n, int)
    for i in range(1, n):
        prev = temps[i - 1]
        excess = prev[ix["oil"]] - air[i - 1]
        fan[i] = 1 if excess > FAN_ON_K else 0 if excess < FAN_OFF_K else fan[i - 1]
        heat = np.zeros(net.n_nodes)
        if cut[i - 1]:
            heat[ix["hmotor"]] += 40 + 0.08 * rpm[i - 1]
            heat[ix["hhead"]] += 12 + 0.02 * rpm[i - 1]
            heat[ix["tmotor"]] += 35.0
            heat[ix["oil"]] += 300.0
        heat[ix["oil"]] += 70.0 * on[i - 1] - fan[i] * max(0.0, 12 * excess + 250.0)
        temps[i] = step.step(prev, air[i - 1], heat)
    return temps, ix, air, rpm, fan, on


def errors(rises: dict) -> list[np.ndarray]:
    """``E_X``, ``E_Z`` (µm) at the master gear's bore from the rises ``rises``."""
    r = rises
    e_x = 0.0115 * 350 * r["column"] - 2.2 * r["hhead"] + 1.1 * r["table"] - 0.4 * r["bed"]
    e_z = 5.5 * r["hhead"] + 1.8 * r["hmotor"] - 0.0115 * 600 * r["table"] + 2.0 * r["oil"]
    return [e_x, e_z]


def probe_steps(rng, first: int, last: int, lead_min=(0.0, 0.0)) -> np.ndarray:
    """The 10 s steps of the probe's cycles in ``[first, last)``: the first ``lead_min``
    minutes after ``first``, then every 12-18 min, 8 % skipped."""
    out = []
    t = first + int(rng.uniform(*lead_min) * 60 / STEP)
    while t < last:
        if rng.random() >= 0.08:
            out.append(t)
        t += int(rng.uniform(12, 18) * 60 / STEP)
    return np.array(out, int)


def sensed(rng, temps, ix, air, rows) -> dict:
    t = temps[rows]
    out = {}
    for name, _, a, b, w in SENSORS:
        out[name] = rounded(w * t[:, ix[a]] + (1 - w) * t[:, ix[b]]
                            + rng.normal(0, 0.02, len(rows)), 0.01)
    out["Halle"] = rounded(air[rows] + rng.normal(0, 0.05, len(rows)), 0.01)
    return out


# --- draw 6221: the lab's test runs, a MATLAB struct array ----------------------------------

def runs_6221(seed: int) -> list[dict]:
    rng = np.random.default_rng(seed)
    temps, ix, air, rpm, fan, _ = simulate(rng)
    runs = []
    for day in (w * 7 + d for w in range(WEEKS) for d in range(5)):
        first = int((day * 24 + RUN_HOURS[0]) * 3600 / STEP)
        last = int((day * 24 + RUN_HOURS[1]) * 3600 / STEP)
        rows = np.arange(first, last, LOG_EVERY)
        probes = probe_steps(rng, first, last, lead_min=(10.0, 25.0))
        rises = {k: temps[probes, j] - temps[first, j] for k, j in ix.items()}
        values = [rounded(e + rng.normal(0, 0.3, len(probes)), 0.1) for e in errors(rises)]
        at = np.minimum((probes - first + LOG_EVERY - 1) // LOG_EVERY, len(rows) - 1)
        run = {"name": f"Lauf {(START + pd.Timedelta(days=day)):%d-%b-%Y}",
               "t": (rows - first) * STEP}
        s = sensed(rng, temps, ix, air, rows)
        for name, field, *_ in SENSORS:
            run[field] = s[name]
        run["Thall"] = s["Halle"]
        run["nhob"] = rpm[rows]
        run["fan"] = fan[rows].astype(float)
        for axis, v in zip(("dX", "dZ"), values):
            column = np.full(len(rows), np.nan)
            column[at] = v
            run[axis] = column
        runs.append(run)
    return runs


def save_v5(runs: list[dict], path: Path) -> None:
    import scipy.io as sio

    fields = list(runs[0])
    array = np.empty((1, len(runs)), dtype=[(f, object) for f in fields])
    for k, run in enumerate(runs):
        array[0, k] = tuple(v if isinstance(v, str) else np.asarray(v, float)[:, None]
                            for v in run.values())
    path.parent.mkdir(parents=True, exist_ok=True)
    sio.savemat(path, {"runs": array})


# --- draw 6222: the edge PC's weekly CSVs ---------------------------------------------------

def write_weeks(folder: Path, seed: int) -> None:
    rng = np.random.default_rng(seed)
    temps, ix, air, rpm, fan, on = simulate(rng)
    folder.mkdir(parents=True, exist_ok=True)
    week = int(7 * 86400 / STEP)
    starts = np.flatnonzero(np.diff(np.r_[0, on]) == 1)
    ends = np.flatnonzero(np.diff(np.r_[on, 0]) == -1) + 1
    probes = np.concatenate([probe_steps(rng, s, e, lead_min=(10.0, 25.0))
                             for s, e in zip(starts, ends)])
    for w in range(WEEKS):
        first, last = w * week, (w + 1) * week
        rows = np.arange(first, last, LOG_EVERY)
        mine = probes[(probes >= first) & (probes < last)]
        rises = {k: temps[mine, j] - temps[0, j] for k, j in ix.items()}
        values = [rounded(e + rng.normal(0, 0.3, len(mine)), 0.1) for e in errors(rises)]
        at = np.minimum((mine - first + LOG_EVERY - 1) // LOG_EVERY, len(rows) - 1)
        frame = {"Zeitstempel": (START + pd.to_timedelta(rows * STEP, unit="s")).strftime(
            "%d.%m.%Y %H:%M:%S")}
        s = sensed(rng, temps, ix, air, rows)
        for name in [x[0] for x in SENSORS] + ["Halle"]:
            frame[f"{name} [°C]"] = s[name]
        frame["Fräserdrehzahl [1/min]"] = rpm[rows]
        frame["Lüfter"] = fan[rows]
        for axis, v in zip("XZ", values):
            column = np.full(len(rows), np.nan)
            column[at] = v
            frame[f"Sonde {axis} [µm]"] = column
        kw = (START + pd.Timedelta(days=7 * w)).isocalendar().week
        pd.DataFrame(frame).to_csv(folder / f"GH22_KW{kw}.csv", sep=";", decimal=",",
                                   index=False, float_format="%.6g")


def write(root: Path) -> None:
    save_v5(runs_6221(SEEDS["hobber"]), root / "hobber" / "hobber_runs.mat")
    write_weeks(root / "hobber_b", SEEDS["hobber_b"])


# --- the pipeline -------------------------------------------------------------------------

FAMILIES = ("mlr", "pcr", "arx", "lagbank", "hammerstein", "auto")
# hobber: what the stranger added after init's two refusals (a MATLAB field carries no unit)
INIT_ARGS = {"hobber": ("data.test_fraction=0.3", "data.roles.error=[dX,dZ]", "data.roles.state=[nhob]"),
             "hobber_b": ("data.test_fraction=0.34",)}
FOLDERS = {"hobber": "hobber/hobber_runs.mat", "hobber_b": "hobber_b"}
CONFIGS = {"hobber": "hobber_runs", "hobber_b": "hobber_b"}


def data_args(root: Path, name: str) -> list[str]:
    return [f"hydra.searchpath=[file://{root}/init-{name}/conf]", f"data={CONFIGS[name]}"]


def lab_file(root: Path, name: str) -> Path:
    return (root / FOLDERS[name] if name == "hobber"
            else sorted((root / name).glob("*.csv"))[-1])


MACHINES = Machines(doc=__doc__, write=write, records=list(SEEDS), families=FAMILIES,
                    init_args=INIT_ARGS, data_args=data_args, folders=FOLDERS,
                    monitored=("mlr",), replayed="mlr", lab_file=lab_file)


def one_step(root: Path, names) -> None:
    """Every family's ``run`` with ``eval.mode=one_step`` (the last probe reading an input)."""
    import json

    from new_machine_steps import run_models

    for name in names:
        rows = run_models(root, name, FAMILIES, ("eval.mode=one_step",), args_of=data_args)
        (root / f"families-onestep-{name}.json").write_text(json.dumps(rows, indent=1))


def deploy(root: Path, names, families=("mlr", "arx", "lagbank", "hammerstein")) -> None:
    """Per family: ``run`` (tracked), ``replay``, ``promote`` of that run, ``export`` of its
    version as C with the check pack, compiled, ``check/check.sh``, the pack scored
    (``bench_frames62``'s chain, on this bench's records)."""
    import json

    import bench_frames62

    bench_frames62.data_args = data_args      # its chain reads the record through data_args
    rows = [bench_frames62.one(root, name, family) for name in names for family in families]
    for row in rows:
        print(json.dumps(row, default=str)[:1500], flush=True)
    (root / f"deploy-{'-'.join(names)}.json").write_text(json.dumps(rows, indent=1, default=str))


def sweep(root: Path, names) -> None:
    """``run -m model=mlr,lagbank`` (tracked, its comparison), ``promote`` the best, ``export``
    the champion as C with its pack, ``check/check.sh`` (``bench_probe61``'s chain)."""
    import json

    import bench_probe61

    bench_probe61.data_args = data_args
    rows = [bench_probe61.sweep_promote_export(root, name) for name in names]
    (root / f"sweep-{'-'.join(names)}.json").write_text(json.dumps(rows, indent=1, default=str))


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    extra = {"one_step": one_step, "deploy": deploy, "sweep": sweep}
    if argv and argv[0] in extra:
        extra[argv[0]](Path(argv[1]).resolve(), argv[2:] or list(SEEDS))
        return 0
    return steps_main(MACHINES, argv)


if __name__ == "__main__":
    raise SystemExit(main())
