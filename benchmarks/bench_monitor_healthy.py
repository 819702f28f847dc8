"""A healthy record the monitor must stay quiet on (session 53): false alarms on healthy records
nobody tuned the monitor on, and detection of faults planted in the same records.

    .venv/bin/python benchmarks/bench_monitor_healthy.py ROOT [--jobs 2] [--records ...]

Builds the records in ``ROOT`` (fresh seeds 5301..5306 of the shipped scenarios, cut small; the
measured ``fl_thermal``; ``bench_other_machine.py``'s machines that are not ours, seed 53), then per
record and model (``mlr``, ``lagbank``): ``run`` (its ``model.pkl`` at ``model_path``), and
``monitor monitor.model=<that pkl>`` on the healthy test campaigns: adaptive and plain
(``monitor.adaptive=false``) from the files, adaptive from stdin (``monitor.input=-``, the first
test campaign).  Then the same test part with a fault from half of each test campaign on the
judged sensor whose undetected offset costs most (that model's healthy ``monitor.json``): a drift of
1 K/h, a +3 °C step, a stuck sensor (its value at the onset), a dropout (empty cells).
Prints the tables (and writes ``ROOT/results.json``).

Measured (session 54, on session 53's records, 2 shared cores; 21 min of CPU for everything,
user + sys; docs/monitoring.md reads it).  Against session 53's run, only the culprit rule's mend
changed anything: the Swiss lathe's T_guidebush drift (708 -> 51 min; MLR 541 -> 5.56 µm²,
lagbank 317 -> 3.38), yearround s5301 lagbank's T_box1 drift (35.35 -> 21.21, the same delays),
and the column's stuck / dropped T_right2 (49.94 -> 59.00, 46.45 -> 55.50: its healthy T_left1 at
its band goes out, with T_left3, where T_right3 had gone).
Counts are events / warnings / alarms / exclusions / new thermal states / guard events;
``stdin`` streams only the first test campaign (``fl_thermal``'s without ``monitor.continues``).
Re-run whole 2026-11-30 (stop 56, after the guard following the inputs, the monitor on a hotter
machine and the common step; 463 s user + 81 s sys CPU, ``--jobs 2``, fresh records): the healthy
table below to every printed digit on all 22 record x model pairs; the faults' delays, exclusions,
other sensors and adaptive ΣRMSE² likewise; seven FIXED-stream figures of the lag bank moved in the
last digits (large_mill step 115.35 -> 115.77, the others by 0.01).
Re-run whole after jumps57 (several sensors jumping in one sample re-referenced against those that
did not; 521 s user + 91 s sys CPU, ``--jobs 1``, fresh records): results.json byte-identical to the
code before it on all 22 pairs, healthy and faulted.
The false alarms: ``large_mill`` (48 h of March training) and ``column no Q3`` (30 h); with the
shipped 40 h of the column, or 120 h of the mill, the same seeds are silent.  ``long_record``'s
exclusion is a spike the simulator plants::

    healthy: events/warnings/alarms/exclusions/new states/guard events per mode; exclusions
    per 100 h; sum over targets of RMSE² (µm²) fixed -> adaptive; worst adaptive/fixed
    record             model       h         file        plain        stdin /100h  ΣRMSE² fixed/adapt. worst
    yearround s5301    mlr      21.0  0/0/0/0/0/0  0/0/0/0/0/0  0/0/0/0/0/0  0.00    25.69 ->    25.69 1.000
    yearround s5301    lagbank  21.0  0/0/0/0/0/0  0/0/0/0/0/0  0/0/0/0/0/0  0.00    20.43 ->    20.43 1.000
    yearround s5302    mlr      26.9  0/0/0/0/0/0  0/0/0/0/0/0  0/0/0/0/0/0  0.00    16.88 ->    16.88 1.000
    yearround s5302    lagbank  26.9  0/0/0/0/0/0  0/0/0/0/0/0  0/0/0/0/0/0  0.00    10.95 ->    10.95 1.000
    large_mill s5303   mlr      24.0  2/0/0/1/0/0 10/4/0/0/1/0  2/0/0/1/0/0  4.17    10.10 ->     9.54 1.015
    large_mill s5303   lagbank  24.0  2/0/0/1/0/0 10/4/0/0/1/0  2/0/0/1/0/0  4.17    41.14 ->    43.10 1.100
    swiss_lathe s5304  mlr      24.0  0/0/0/0/0/0  0/0/0/0/0/0  0/0/0/0/0/0  0.00     4.75 ->     4.75 1.000
    swiss_lathe s5304  lagbank  24.0  0/0/0/0/0/0  0/0/0/0/0/0  0/0/0/0/0/0  0.00     2.08 ->     2.08 1.000
    column no Q3 s5305 mlr      20.0  2/0/0/1/0/0  2/1/0/0/0/0  2/0/0/1/0/0  4.99    43.80 ->    44.61 1.078
    column no Q3 s5305 lagbank  20.0  2/0/0/1/0/0  2/1/0/0/0/0  2/0/0/1/0/0  4.99  1120.17 ->  1122.58 1.006
    long_record s5306  mlr      24.0  2/0/0/1/0/0  4/0/2/0/0/0  2/0/0/1/0/0  4.17     0.35 ->     0.35 0.995
    long_record s5306  lagbank  24.0  2/0/0/1/0/0  4/0/2/0/0/0  2/0/0/1/0/0  4.17     0.24 ->     0.25 1.019
    fl_thermal         mlr       4.6  0/0/0/0/0/0  0/0/0/0/0/0  0/0/0/0/0/0  0.00    83.90 ->    83.90 1.000
    fl_thermal         lagbank   4.6  0/0/0/0/0/0  0/0/0/0/0/0  2/0/0/0/0/2  0.00   120.31 ->   120.31 1.000
    lathe43            mlr       7.0  0/0/0/0/0/0  0/0/0/0/0/0  0/0/0/0/0/0  0.00     3.37 ->     3.37 1.000
    lathe43            lagbank   7.0  0/0/0/0/0/0  0/0/0/0/0/0  0/0/0/0/0/0  0.00     3.46 ->     3.46 1.000
    lathe43m           mlr      12.1  0/0/0/0/0/0  0/0/0/0/0/0  0/0/0/0/0/0  0.00     1.84 ->     1.84 1.000
    lathe43m           lagbank  12.1  0/0/0/0/0/0  0/0/0/0/0/0  0/0/0/0/0/0  0.00     1.49 ->     1.49 1.000
    rig40              mlr      77.4  0/0/0/0/0/0  0/0/0/0/0/0  0/0/0/0/0/0  0.00     1.61 ->     1.61 1.000
    rig40              lagbank  77.4  0/0/0/0/0/0  0/0/0/0/0/0  0/0/0/0/0/0  0.00     1.53 ->     1.53 1.000
    vendor5            mlr       1.9  0/0/0/0/0/0  0/0/0/0/0/0  0/0/0/0/0/0  0.00     4.01 ->     4.01 1.000
    vendor5            lagbank   1.9  0/0/0/0/0/0  0/0/0/0/0/0  0/0/0/0/0/0  0.00     6.52 ->     6.52 1.000

    faulted, on the sensor named from half of each test campaign: minutes from the onset
    to its first flag, per campaign (- never); ΣRMSE² fixed -> adaptive; exclusions; other
    sensors out (healthy adaptive ΣRMSE² beside the sensor)
    yearround s5301    mlr     T_bearing_f2  (healthy 25.69)
        drift    30 30 35 30              963.56 ->    29.88  excl 4 others -
        step     0 0 0 0                 3822.17 ->    27.87  excl 4 others -
        stuck    30 15 30 25              898.62 ->    36.08  excl 4 others -
        dropout  0 0 0 0                   85.00 ->    26.76  excl 4 others -
    yearround s5301    lagbank T_box1  (healthy 20.43)
        drift    40 30 30 30               54.60 ->    21.21  excl 5 others T_box2
        step     0 0 0 0                  183.04 ->    21.33  excl 4 others -
        stuck    30 115 35 30              28.41 ->    19.18  excl 4 others -
        dropout  0 0 0 0                   56.35 ->    20.07  excl 4 others -
    yearround s5302    mlr     T_nose  (healthy 16.88)
        drift    35 40 35 35             1335.11 ->    22.68  excl 4 others -
        step     0 0 0 0                 3724.36 ->    14.58  excl 4 others -
        stuck    25 35 25 30             1533.43 ->    24.69  excl 4 others -
        dropout  0 0 0 0                   85.15 ->    17.77  excl 4 others -
    yearround s5302    lagbank T_nose  (healthy 10.95)
        drift    35 40 35 35              976.41 ->    13.71  excl 4 others -
        step     0 0 0 0                 2919.43 ->     9.81  excl 4 others -
        stuck    25 35 25 30             1056.95 ->    14.93  excl 4 others -
        dropout  0 0 0 0                   85.02 ->    11.80  excl 4 others -
    large_mill s5303   mlr     T_col_10  (healthy 9.54)
        drift    55                       994.52 ->   332.33  excl 2 others T_col_01,T_col_02,+8
        step     0                        841.03 ->     9.95  excl 2 others T_col_05
        stuck    14                        34.28 ->    20.37  excl 2 others T_col_05
        dropout  0                        146.19 ->    20.27  excl 2 others T_col_05
    large_mill s5303   lagbank T_col_11  (healthy 43.10)
        drift    22                       340.98 ->    41.16  excl 2 others T_col_05
        step     0                        115.35 ->    42.41  excl 2 others T_col_05
        stuck    17                        52.46 ->    43.49  excl 2 others T_col_05
        dropout  0                        167.27 ->    42.79  excl 2 others T_col_05
    swiss_lathe s5304  mlr     T_guidebush  (healthy 4.75)
        drift    51                       329.83 ->     5.56  excl 1 others -
        step     0                        336.04 ->     4.27  excl 1 others -
        stuck    371                       72.72 ->    10.85  excl 1 others -
        dropout  0                         40.54 ->     4.96  excl 1 others -
    swiss_lathe s5304  lagbank T_guidebush  (healthy 2.08)
        drift    51                       297.07 ->     3.38  excl 1 others -
        step     0                         81.30 ->     2.03  excl 1 others -
        stuck    371                       17.31 ->     4.61  excl 1 others -
        dropout  0                         48.28 ->     2.64  excl 1 others -
    column no Q3 s5305 mlr     T_right2  (healthy 44.61)
        drift    32                      3686.88 ->    49.49  excl 1 others -
        step     0                       4774.78 ->    43.54  excl 1 others -
        stuck    150                     1701.91 ->    59.00  excl 3 others T_left1,T_left3
        dropout  0                       3586.16 ->    55.50  excl 3 others T_left1,T_left3
    column no Q3 s5305 lagbank T_left4  (healthy 1122.58)
        drift    27                      9818.62 ->  1091.82  excl 1 others -
        step     0                       5258.67 ->  1148.28  excl 1 others -
        stuck    103                      478.77 ->  1089.04  excl 2 others T_right3
        dropout  0                       5719.69 ->  1085.75  excl 2 others T_right3
    long_record s5306  mlr     T_bed_right  (healthy 0.35)
        drift    24                       183.26 ->     0.39  excl 2 others T_col_front_top
        step     0                        183.13 ->     0.33  excl 2 others T_col_front_top
        stuck    298                        9.13 ->     0.55  excl 2 others T_col_front_top
        dropout  0                         41.64 ->     0.34  excl 2 others T_col_front_top
    long_record s5306  lagbank T_spindle_rear  (healthy 0.25)
        drift    44                       203.16 ->     0.35  excl 2 others T_col_front_top
        step     0                         41.15 ->     0.16  excl 2 others T_col_front_top
        stuck    269                       13.97 ->     0.39  excl 2 others T_col_front_top
        dropout  0                         40.90 ->     0.26  excl 2 others T_col_front_top
    fl_thermal         mlr     T_t11  (healthy 83.90)
        drift    58                       774.60 ->   111.03  excl 1 others -
        step     0                       1250.00 ->    78.54  excl 1 others -
        stuck    -                        119.99 ->   119.99  excl 0 others -
        dropout  0                        186.42 ->    64.76  excl 1 others -
    fl_thermal         lagbank T_t8  (healthy 120.31)
        drift    38                        94.20 ->   104.70  excl 1 others T_t11,T_t13,+2
        step     0                        688.64 ->   123.56  excl 1 others -
        stuck    101                      198.32 ->   172.46  excl 1 others -
        dropout  0                        167.24 ->   134.80  excl 1 others -
    lathe43            mlr     T_Pt02  (healthy 3.37)
        drift    24 21 22 22               13.68 ->     4.00  excl 4 others -
        step     0 0 0 0                  180.56 ->     3.47  excl 4 others -
        stuck    12 15 7 6                 21.60 ->     3.45  excl 4 others -
        dropout  0 0 0 0                   36.70 ->     3.41  excl 4 others -
    lathe43            lagbank T_Pt21  (healthy 3.46)
        drift    26 24 22 21                3.84 ->     3.36  excl 4 others -
        step     0 0 0 0                   35.71 ->     3.39  excl 4 others -
        stuck    - - - 21                   6.21 ->     3.79  excl 1 others -
        dropout  0 0 0 0                   35.86 ->     3.29  excl 4 others -
    lathe43m           mlr     T_02  (healthy 1.84)
        drift    25 26 23 24 28 24 22       9.46 ->     1.96  excl 7 others -
        step     0 0 0 0 0 0 0            161.85 ->     2.01  excl 7 others -
        stuck    47 - 33 50 15 8 7          9.88 ->     2.56  excl 6 others -
        dropout  0 0 0 0 0 0 0             12.53 ->     1.86  excl 7 others -
    lathe43m           lagbank T_18  (healthy 1.49)
        drift    24 24 22 23 24 21 -        3.95 ->     1.45  excl 6 others -
        step     0 0 0 0 0 0 0             24.55 ->     1.52  excl 7 others -
        stuck    - - - - - - -              1.51 ->     1.51  excl 0 others -
        dropout  0 0 0 0 0 0 0             12.48 ->     1.48  excl 7 others -
    rig40              mlr     T_29  (healthy 1.61)
        drift    30 28 24                 500.26 ->     1.65  excl 3 others -
        step     0 0 0                    134.09 ->     1.66  excl 3 others -
        stuck    36 26 54                  36.14 ->     1.61  excl 3 others -
        dropout  0 0 0                     92.62 ->     1.59  excl 3 others -
    rig40              lagbank T_29  (healthy 1.53)
        drift    30 28 24                 533.81 ->     1.58  excl 3 others -
        step     0 0 0                    126.46 ->     1.50  excl 3 others -
        stuck    36 26 54                  33.91 ->     1.57  excl 3 others -
        dropout  0 0 0                     93.45 ->     1.55  excl 3 others -
    vendor5            mlr     T_17  (healthy 4.01)
        drift    27                         2.96 ->     3.20  excl 1 others -
        step     0                         97.66 ->     4.12  excl 1 others -
        stuck    26                         4.82 ->     4.47  excl 1 others -
        dropout  0                         13.37 ->     3.76  excl 1 others -
    vendor5            lagbank T_23  (healthy 6.52)
        drift    27                         7.54 ->     3.87  excl 1 others -
        step     0                        192.92 ->     6.51  excl 1 others -
        stuck    -                          8.02 ->     8.02  excl 0 others -
        dropout  0                         14.83 ->     4.94  excl 1 others -
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
QUIET = ("track=false", "plots=none")
# name -> simulate overrides (None: not simulated), extra overrides of every command
SIM = {
    "yearround s5301": (["sim=yearround_spindle", "seed=5301", "sim.generator.n_campaigns=12"], []),
    "yearround s5302": (["sim=yearround_spindle", "seed=5302", "sim.generator.n_campaigns=12"], []),
    "large_mill s5303": (["sim=large_mill_week", "seed=5303", "sim.generator.train_hours=48",
                          "sim.generator.test_hours=24"], []),
    "swiss_lathe s5304": (["sim=swiss_lathe_door", "seed=5304", "sim.generator.calibration_hours=40"],
                          []),
    "column no Q3 s5305": (["sim=column_moving_source", "seed=5305", "sim.generator.q3=false",
                            "sim.generator.train_hours=30", "sim.generator.test_hours=20"], []),
    "long_record s5306": (["sim=long_record", "seed=5306", "sim.generator.duration_days=4",
                           "sim.generator.test_fraction=0.25"], ["sim=long_record"]),
}
OTHER = ("lathe43", "lathe43m", "rig40", "vendor5")
FAULTS = ("drift", "step", "stuck", "dropout")


def thermocomp(*args, stdin: Path | None = None) -> subprocess.CompletedProcess:
    with open(stdin, "rb") if stdin else open("/dev/null", "rb") as feed:
        return subprocess.run([sys.executable, "-m", "thermocomp", "-q", *args], cwd=ROOT,
                              stdin=feed, capture_output=True)


def build(root: Path) -> dict:
    """``{record: (data overrides, folder or file to fault)}``, the records written."""
    records = {}
    for name, (sim, extra) in SIM.items():
        path = root / "data" / name.replace(" ", "_")
        if not (path / "campaigns.csv").exists():
            assert thermocomp("simulate", *sim, f"data.path={path}", *QUIET).returncode == 0, name
        records[name] = ([f"data.path={path}", *extra], path)
    records["fl_thermal"] = (["data=fl_thermal"], ROOT / "datasets/fl_thermal/spindle_test.csv")
    other = root / "data" / "other"
    if not (other / "rig40").exists():
        subprocess.run([sys.executable, str(ROOT / "benchmarks/bench_other_machine.py"), "write",
                        str(other), "--seed", "53"], check=True, capture_output=True)
        assert thermocomp("init", str(other / "lathe43"), "data.max_gap_samples=2",
                          f"out={other}/init").returncode == 0
    records["lathe43"] = ([f"hydra.searchpath=[file://{other}/init/conf]", "data=lathe43"],
                          other / "lathe43")
    for name in OTHER[1:]:
        records[name] = ([f"data.path={other / name}"], other / name)
    return records


# --- one monitor run and what it says -------------------------------------------------------
def summary(report: dict, sensor: str | None = None, onset: dict | None = None) -> dict:
    ev = [e for e in report["events"] if e.get("sensor")]
    row = {"hours": report["alarms"]["hours"],
           "events": len(report["events"]),
           "warnings": sum(e["to"] == "warning" for e in ev),
           "alarms": sum(e["to"] == "alarm" for e in ev),
           "exclusions": sum(e["to"] == "excluded" for e in ev),
           "new_states": report["alarms"]["new_thermal_states"],
           "guard": sum(1 for e in report["events"] if e.get("target")),
           "by_sensor": sorted({e["sensor"] for e in ev if e["to"] != "ok"}),
           "rmse": {t: (r["rmse_fixed"], r["rmse_adaptive"]) for t, r in report["targets"].items()}}
    if sensor is not None:           # the first flag on the faulted sensor after its onset, per campaign
        delays = []
        for cid, t0 in (onset or {}).items():
            hit = [e["time"] - t0 for e in ev if e["campaign"] == cid and e["sensor"] == sensor
                   and e["to"] in ("warning", "alarm", "excluded") and e["time"] >= t0]
            delays.append(min(hit) if hit else None)
        row["delays_s"] = delays
        row["others_flagged"] = sorted({e["sensor"] for e in ev if e["sensor"] != sensor
                                        and e["to"] in ("alarm", "excluded")})
    return row


def monitor(args: list, out: Path, stdin: Path | None = None, sensor=None, onset=None) -> dict:
    proc = thermocomp("monitor", *args, *QUIET, f"out={out}", stdin=stdin)
    if proc.returncode:
        return {"error": proc.stderr.decode(errors="replace").strip().splitlines()[-1:]}
    return summary(json.loads((out / "monitor.json").read_text()), sensor, onset)


# --- faults in a record's own format ----------------------------------------------------------
def _read(path: Path) -> tuple[pd.DataFrame, dict]:
    text = path.read_text(encoding="utf-8")
    fmt = {"sep": ";", "decimal": ","} if text.split("\n", 1)[0].count(";") > 2 else {"sep": ","}
    return pd.read_csv(path, **fmt), fmt


def _header(df: pd.DataFrame, sensor: str) -> str:
    """The file's header of a contract name ``T_x`` (``Pt01 [°C]``, ``t1(°C)``, ``T_01``)."""
    for h in df.columns:
        bare = re.sub(r"\s*[\[(].*$", "", str(h))
        if sensor in (bare, f"T_{bare}"):
            return h
    raise KeyError(sensor)


def _seconds(col: pd.Series) -> np.ndarray:
    if pd.api.types.is_numeric_dtype(col):
        return col.to_numpy(float)
    return (pd.to_datetime(col) - pd.to_datetime(col.iloc[0])).dt.total_seconds().to_numpy()


def plant(df: pd.DataFrame, rows: slice, sensor: str, kind: str) -> float:
    """The fault ``kind`` on ``sensor`` over ``rows`` of ``df`` from their middle (in place);
    the onset in s after the first of ``rows``."""
    col, t = _header(df, sensor), _seconds(df.iloc[:, 0])
    idx = np.arange(len(df))[rows]
    start = idx[len(idx) // 2]
    on = idx[idx >= start]
    x = df[col].to_numpy(float).copy()
    if kind == "drift":
        x[on] += (t[on] - t[start]) / 3600.0
    elif kind == "step":
        x[on] += 3.0
    elif kind == "stuck":
        x[on] = x[start - 1]
    else:
        x[on] = np.nan
    df[col] = x
    return float(t[start] - t[idx[0]])


def faulted(src: Path, dst: Path, campaigns: list, sensor: str, kind: str,
            test_fraction: float = 0.1) -> dict:
    """A copy of the record at ``dst`` with the fault in its test part: ``{campaign: onset s}``."""
    onset = {}
    if src.is_file():                        # one record: its test part is its last share
        df, fmt = _read(src)
        n = len(df)
        onset[campaigns[0]] = plant(df, slice(n - round(test_fraction * n), n), sensor, kind)
        dst.parent.mkdir(parents=True, exist_ok=True)
        df.to_csv(dst, index=False, float_format="%.10g", **fmt)
        return onset
    shutil.copytree(src, dst, dirs_exist_ok=True)
    for cid in campaigns:
        file = dst / f"{cid}.csv"
        df, fmt = _read(file)
        onset[cid] = plant(df, slice(0, len(df)), sensor, kind)
        df.to_csv(file, index=False, float_format="%.10g", **fmt)
    return onset


def worst_sensor(report: dict) -> str:
    """The judged sensor whose undetected offset moves a target most (train campaigns only)."""
    def cost(r):
        return max((v for v in r["undetected_offset_um"].values() if v is not None), default=0)
    judged = {n: r for n, r in report["sensors"].items() if r.get("observable")}
    return max(judged, key=lambda n: cost(judged[n]))


# --- the pipeline ------------------------------------------------------------------------------
def record_rows(root: Path, name: str, args: list, src: Path, models=("mlr", "lagbank")) -> list:
    rows, key = [], name.replace(" ", "_")
    for model in models:
        out = root / "out" / f"{key}-{model}"
        pkl = out / "run" / "model.pkl"
        proc = thermocomp("run", *args, f"model={model}", f"model_path={pkl}", *QUIET, f"out={out / 'run'}")
        if proc.returncode:
            rows.append({"record": name, "model": model, "error": proc.stderr.decode()[-300:]})
            continue
        margs = [*args, f"model={model}", f"monitor.model={pkl}"]
        healthy = monitor(margs, out / "adaptive")
        report = json.loads((out / "adaptive" / "monitor.json").read_text())
        campaigns = report["campaigns"]
        first = src if src.is_file() else src / f"{campaigns[0]}.csv"
        if src.is_file():                    # stdin: the test part's rows, the header first
            df, fmt = _read(src)
            first = out / "stdin.csv"
            df.iloc[len(df) - round(0.1 * len(df)):].to_csv(first, index=False, **fmt)
        row = {"record": name, "model": model, "adaptive": healthy,
               "plain": monitor([*margs, "monitor.adaptive=false"], out / "plain"),
               "stdin": monitor([*margs, "monitor.input=-"], out / "stdin", stdin=first),
               "faults": {}}
        sensor = row["sensor"] = worst_sensor(report)
        for kind in FAULTS:
            dst = root / "faults" / f"{key}-{model}-{kind}" / (src.name if src.is_file() else "")
            onset = faulted(src, dst, campaigns, sensor, kind)
            row["faults"][kind] = monitor([*margs, f"data.path={dst}"], out / kind, sensor=sensor,
                                          onset=onset)
            row["faults"][kind]["onset_s"] = onset
        rows.append(row)
        print(json.dumps(row), flush=True)
    return rows


def _ratio(r: dict) -> str:
    """Worst target's adaptive / fixed RMSE."""
    q = [a / f for f, a in r["rmse"].values() if f and a is not None]
    return f"{max(q):.3f}" if q else "-"


def _sq(r: dict, k: int) -> float:
    return sum(v[k] ** 2 for v in r["rmse"].values() if v[k] is not None)


def _names(names: list, most: int = 2) -> str:
    return ",".join(names[:most]) + (f",+{len(names) - most}" if len(names) > most else "") or "-"


def tables(rows: list) -> str:
    lines = ["healthy: events/warnings/alarms/exclusions/new states/guard events per mode; exclusions",
             "per 100 h; sum over targets of RMSE² (µm²) fixed -> adaptive; worst adaptive/fixed",
             f"{'record':<18} {'model':<7} {'h':>5} {'file':>12} {'plain':>12} {'stdin':>12} "
             f"{'/100h':>5} {'ΣRMSE² fixed/adapt.':>20} {'worst':>5}"]

    def counts(r):
        return ("error" if "error" in r else
                f"{r['events']}/{r['warnings']}/{r['alarms']}/{r['exclusions']}/{r['new_states']}"
                f"/{r['guard']}")
    for row in rows:
        a = row.get("adaptive", row)
        if "error" in a:
            lines.append(f"{row['record']:<18} {row['model']:<7} error: {str(a['error'])[-70:]}")
            continue
        lines.append(f"{row['record']:<18} {row['model']:<7} {a['hours']:5.1f} {counts(a):>12} "
                     f"{counts(row['plain']):>12} {counts(row['stdin']):>12} "
                     f"{100 * a['exclusions'] / a['hours']:5.2f} "
                     f"{_sq(a, 0):8.2f} -> {_sq(a, 1):8.2f} {_ratio(a):>5}")
    lines += ["", "faulted, on the sensor named from half of each test campaign: minutes from the onset",
              "to its first flag, per campaign (- never); ΣRMSE² fixed -> adaptive; exclusions; other",
              "sensors out (healthy adaptive ΣRMSE² beside the sensor)"]
    for row in rows:
        if "faults" not in row:
            continue
        lines.append(f"{row['record']:<18} {row['model']:<7} {row['sensor']}  "
                     f"(healthy {_sq(row['adaptive'], 1):.2f})")
        for kind, r in row["faults"].items():
            if "error" in r:
                lines.append(f"    {kind:<8} error: {r['error']}")
                continue
            d = " ".join("-" if x is None else f"{x / 60:.0f}" for x in r["delays_s"])
            lines.append(f"    {kind:<8} {d:<22} {_sq(r, 0):8.2f} -> {_sq(r, 1):8.2f}  "
                         f"excl {r['exclusions']} others {_names(r['others_flagged'])}")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("root")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--records", nargs="+", default=None)
    a = parser.parse_args(argv)
    root = Path(a.root).resolve()
    records = build(root)
    names = [n for n in records if a.records is None or n in a.records]
    with ThreadPoolExecutor(a.jobs) as pool:
        rows = [r for rs in pool.map(lambda n: record_rows(root, n, *records[n]), names) for r in rs]
    (root / "results.json").write_text(json.dumps(rows, indent=1))
    print(tables(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
