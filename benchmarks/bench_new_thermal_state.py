"""The monitor's new-thermal-state rule and the guard's bound in it, on records not used to design it.

Run (after ``--prepare``, which simulates and fits under ``/tmp/m48``)::

    PYTHONPATH=src .venv/bin/python benchmarks/bench_new_thermal_state.py [--prepare] [--only cms5003]

Per record, family and configuration it prints the deployed RMSE (``replay``,
``promote.envelope.policy=off``) against the batch RMSE of ``run``, the sensor exclusions, the
"new thermal state" events and, for a planted fault, the first exclusion of the faulty sensor
(delay after the onset).  Configurations: ``before`` (``monitor.new_state.enabled=false``, the
monitor of session 47), ``after`` (the rule, guard as shipped), ``wide1`` / ``wide100`` (the rule,
and the bound's margin 1.0 / 100 while a new state is declared: ``monitor.guard.new_state_margin``).

Measured (2026-11-29; Σ² the sum over the six targets of the squared RMSE, µm², scored by ``run``
/ deployed ``before`` → ``after`` (``wide1``); CPU 19-51 s per record on the shared machine)::

  record   model    Σ² run / before → after (wide1)   E_X run / before → after (wide1)
  cms5003  mlr       8312 / 10253 → 5901 (8085)        2.11 / 49.40 → 7.48 (2.10)
           arx        274 /  6337 →  286  (244)        5.28 / 50.00 → 8.42 (5.28)
           lagbank   1508 /  4398 → 1342 (1420)       25.08 / 40.02 → 25.73 (25.73)
  cms6007  mlr       1390 /  1176 → 1376 (1340)        1.29 / 16.92 → 10.16 (1.29)
           arx        943 /   728 → 1024  (931)        3.90 / 17.73 → 10.56 (3.90)
           lagbank   1027 /  1118 → 1117 (1079)       14.29 / 19.83 → 14.38 (12.96)
  cms4253  mlr        529 /   524 →  546  (530)        2.29 / 19.36 → 7.89 (2.32)
           arx       5954 /   988 → 5805 (5956)        2.21 / 19.03 → 7.88 (2.24)
           lagbank    549 /   862 →  567  (552)       13.32 / 18.05 → 13.80 (13.33)
  cms3141  mlr       1614 /  1071 → 1401 (1614)        1.67 / 28.82 → 8.29 (1.72)   (designed on)
           arx      11925 /  1074 → 9827 (11923)       3.56 / 28.99 → 8.66 (3.59)
           lagbank    972 /  1188 → 1000  (970)       16.23 / 29.54 → 17.12 (16.22)

Exclusions / new states before → after: 4-8 / 0 → 1-2 / 1 on every cms record and model.
``wide100`` = ``wide1`` to the printed digits.  Healthy (yearround seed 5003, swiss4253,
cms2718q3off; three models; mill4253, mlr): 0 exclusions and 0 new states under every
configuration, RMSE identical.  Planted faults on yearround (T_bearing_f1) and cms2718q3off
(T_right3): the same first exclusion (jump +0, drift +35, freeze +40 / +65 min) and RMSE under
every configuration.
cms5003 T_left2 from 24 h (during the new state): jump +0 → +0 min, freeze +5 → +7 min, drift
+633 → +633 min; Σ² (mlr) 10467 → 5640, 20824 → 6181, 10461 → 5637.
long9191, mill9191 (stranger48, seeds never used; mlr): healthy 0 exclusions, 0 new states, RMSE
identical (E_Z 0.80; 1.81/1.20/2.02); T_col_front_low / T_col_05 jump +0 / +0 min, drift +29 / +26
min, freeze +37 / +57 min under before and after alike, same RMSE.  The measured fl_thermal:
bench_new_state_measured.py.
Re-measured 2026-11-30 (session 54, after the culprit rule's change for a sensor it would leave
unjudged): ``--only cms5003 --no-faults`` (the fits of /tmp/m48), every family and configuration
as in the table (E_X and exclusions / new states to the printed digit), 21.5 s CPU.
Read in docs/monitoring.md ("A new thermal state").
"""

from __future__ import annotations

import contextlib
import io
import json
import subprocess
import sys
from pathlib import Path

from thermocomp.shell.cli import main as thermocomp_main

sys.path.insert(0, str(Path(__file__).parent))
from bench_monitor_novel_state import faulty_copy  # noqa: E402  (the fault planting of session 47)

ROOT = Path("/tmp/m48")
FAMILIES = ("mlr", "arx", "lagbank")
# record -> its `thermocomp simulate` overrides; cms3141 designed the rule, the others did not
RECORDS = {
    "cms3141": ["sim=column_moving_source", "seed=3141"],
    "cms4253": ["sim=column_moving_source", "seed=4253"],
    "cms5003": ["sim=column_moving_source", "seed=5003"],
    "cms6007": ["sim=column_moving_source", "seed=6007"],
    "yearround": ["sim=yearround_spindle", "seed=5003"],
    "swiss4253": ["sim=swiss_lathe_door", "seed=4253"],
    "cms2718q3off": ["sim=column_moving_source", "seed=2718", "sim.generator.q3=false"],
    "mill4253": ["sim=large_mill_week", "seed=4253"],     # its June test outside March's envelope
    "long9191": ["sim=long_record", "seed=9191"],         # 21 days at 1 min, test continues train
    "mill9191": ["sim=large_mill_week", "seed=9191"],
}
# record -> (faulty sensor, onset as a share of each test campaign); cms5003: during the new state
FAULTS = {"cms2718q3off": ("T_right3", 0.5), "yearround": ("T_bearing_f1", 0.5),
          "cms5003": ("T_left2", 0.6), "long9191": ("T_col_front_low", 0.5),
          "mill9191": ("T_col_05", 0.5)}
KINDS = {"jump": {"kind": "jump", "magnitude_c": 3.0}, "drift": {"kind": "drift"},
         "freeze": {"kind": "freeze"}}
CONFIGS = {"before": ["monitor.new_state.enabled=false"], "after": [],
           "wide1": ["monitor.guard.new_state_margin=1.0"],
           "wide100": ["monitor.guard.new_state_margin=100"]}


def cli(*args) -> None:
    subprocess.run([sys.executable, "-m", "thermocomp", *args, "track=false"], check=True,
                   capture_output=True)


def prepare(families) -> None:
    for tag, sim in RECORDS.items():
        data = ROOT / tag
        if not data.exists():
            cli("simulate", *sim, f"data.path={data}")
        for fam in families:
            if not (ROOT / f"run-{tag}-{fam}" / "model.pkl").exists():
                cli("run", f"data.path={data}", f"model={fam}", f"out={ROOT / f'run-{tag}-{fam}'}",
                    "plots=none", "eval.mutual_prediction=false")


def replay(data: Path, model: Path, overrides: list[str], out: Path) -> dict:
    with contextlib.redirect_stdout(io.StringIO()):
        thermocomp_main(["-q", "replay", f"data.path={data}", f"replay.model={model}",
                         "promote.envelope.policy=off", "track=false", f"out={out}", *overrides])
    return json.loads((out / "replay.json").read_text())


def summary(rep: dict, column: str | None, onsets: dict | None) -> str:
    events = rep["events"]
    excl = [e for e in events if e.get("sensor") and e["to"] == "excluded"]
    novel = sum(e["to"] == "new thermal state" for e in events)
    mine = [e for e in excl if column is None or e["sensor"] == column]
    first = f"{mine[0]['time'] / 3600:.2f} h {mine[0]['sensor']}" if mine else "never"
    if mine and onsets:
        first += f" (+{(mine[0]['time'] - onsets[mine[0]['campaign']]) / 60:.0f} min)"
    rmse = " ".join(f"{t} {v['rmse']:.2f}/{v['rmse_batch']:.2f}" for t, v in rep["targets"].items())
    return f"excl {len(excl):2d} new {novel} | first {first:<30} | {rmse}"


def main() -> None:
    families = [f for f in FAMILIES if f"--{f}" in sys.argv] or list(FAMILIES)
    if "--prepare" in sys.argv:
        prepare(families)
    only = sys.argv[sys.argv.index("--only") + 1] if "--only" in sys.argv else ""
    faults = "--no-faults" not in sys.argv
    for tag in (t for t in RECORDS if only in t):
        data = ROOT / tag
        cases = [(tag, data, None, None)]
        if tag in FAULTS and faults:
            column, share = FAULTS[tag]
            for kind, params in KINDS.items():
                dst = ROOT / "faulty" / f"{tag}-{kind}"
                onsets = faulty_copy(data, dst, column, {**params, "onset_fraction": share})
                cases.append((f"{tag} {kind} {column}", dst, column, onsets))
        for fam in families:
            model = ROOT / f"run-{tag}-{fam}" / "model.pkl"
            for label, path, column, onsets in cases:
                for name, overrides in CONFIGS.items():
                    out = ROOT / "out" / f"{path.name}-{fam}-{name}"
                    print(f"{label:<30} {fam:<8} {name:<8} "
                          f"{summary(replay(path, model, overrides, out), column, onsets)}", flush=True)


if __name__ == "__main__":
    main()
