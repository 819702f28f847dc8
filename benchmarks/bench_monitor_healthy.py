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


def tables(rows: list) -> str:
    lines = ["healthy: events / warnings / alarms / exclusions / new states / guard events; per 100 h "
             "of exclusions; sum over targets of RMSE² (µm²) fixed -> adaptive; worst adaptive/fixed",
             f"{'record':<20} {'model':<8} {'h':>6} {'adaptive (file)':>18} {'plain':>14} {'stdin':>14}"
             f" {'excl/100h':>9} {'ΣRMSE² fixed -> adaptive':>26} {'worst':>6}"]
    def counts(r):
        return ("error" if "error" in r else
                f"{r['events']}/{r['warnings']}/{r['alarms']}/{r['exclusions']}/{r['new_states']}"
                f"/{r['guard']}")
    for row in rows:
        if "error" in row:
            lines.append(f"{row['record']:<20} {row['model']:<8} error: {row['error'][-80:]!r}")
            continue
        a = row["adaptive"]
        if "error" in a:
            lines.append(f"{row['record']:<20} {row['model']:<8} monitor error: {a['error']}")
            continue
        lines.append(f"{row['record']:<20} {row['model']:<8} {a['hours']:6.1f} {counts(a):>18} "
                     f"{counts(row['plain']):>14} {counts(row['stdin']):>14} "
                     f"{100 * a['exclusions'] / a['hours']:9.2f} "
                     f"{_sq(a, 0):11.2f} -> {_sq(a, 1):11.2f} {_ratio(a):>6}"
                     + (f"  flagged: {','.join(a['by_sensor'])}" if a["by_sensor"] else ""))
    lines += ["", "faulted (on the sensor named, from half of each test campaign): first flag of it "
              "after the onset (min, per campaign; - never); ΣRMSE² fixed -> adaptive (healthy adaptive)"]
    for row in rows:
        if "faults" not in row:
            continue
        lines.append(f"{row['record']:<20} {row['model']:<8} {row['sensor']}  "
                     f"(healthy {_sq(row['adaptive'], 1):.2f})")
        for kind, r in row["faults"].items():
            if "error" in r:
                lines.append(f"    {kind:<8} error: {r['error']}")
                continue
            d = " ".join("-" if x is None else f"{x / 60:.0f}" for x in r["delays_s"])
            lines.append(f"    {kind:<8} delay min {d:<18} {_sq(r, 0):11.2f} -> {_sq(r, 1):11.2f}  "
                         f"excl {r['exclusions']} others {','.join(r['others_flagged']) or '-'}")
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
