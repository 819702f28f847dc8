"""The order of dates with slashes on a large Scope View export: the folder-wide check and the
read (stop 85, dates85).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dates85.py write ROOT [ROWS]   # two exports, seeds 8851 / 8852
    python benchmarks/bench_dates85.py check ROOT          # CPU of the check and of the read
    python benchmarks/bench_dates85.py stranger ROOT       # en-GB lab folders, seeds 8853 / 8854
    python benchmarks/bench_dates85.py table ROOT          # a 200 000-row CSV: the run test's CPU

``write``: two TwinCAT Scope View exports as an en-GB PC writes them (``;``, decimal commas,
cp1252, absolute times ``dd/mm/yyyy HH:MM:SS.fff``), four channels every second, ``ROWS`` rows
(default 50 000, ~14 h): ``night.csv`` (seed 8851) from the 3rd of May 23:00 into the 4th -- no
day or month past 12 anywhere, the run across midnight settles the order -- and ``day13.csv``
(seed 8852) from the 13th of May 07:00 (a day past 12 in every date).  ``check``: per export,
the CPU (user + sys, the least of 3) of the folder-wide check (``plain.lab_dayfirst``, a date
past 12 in any lab file of a record deciding for all: before, a Python look at every date of the
file's text; now one regex search each way), and of one ``read_dataset`` of it (the Scope
reader's own order: before, every time cell's fields matched and, where none is past 12, parsed
twice with ``datetime.strptime`` in Python; now the one mechanism of ``core/io/dayfirst.py``,
vectorized), with what each decided (the order, the start).

The bar (written before scoring): the check and the read decide the same (order, start) on main
and on this tree; the check's CPU on this tree at most that of main on each export; the read's
CPU at most 1.05 x main's on each.  Trees alternated, main first.

Scored (2026-12-04, main 39d6305f against fix/dates85, ``write /tmp/dates85/bench``, 50 000
rows, 7.2 MB each; two rounds alternated, main first; CPU s, user + sys)
------------------------------------------------------------------------------------------------
::

  export  decided (both trees)                     check main -> here   read main -> here
  night   no field past 12; start 05-03 23:00:00   0.173 0.172 -> 0.122 0.128   10.70 10.21 -> 2.69 2.85
  day13   day first ('13/05/2027'); 05-13 07:00    0.517 0.531 -> 0.119 0.121    1.99  1.94 -> 1.72 1.85

The same order and start on both trees; the check -30 % (night) and -77 % (day13: before, every
one of the ~200 000 dates past 12 looked at in Python), the read -73 % on the night export (its
50 000 time cells parsed twice with ``datetime.strptime`` before, with pandas now) and -9 % on
day13.  (A first cut, one regex search each way, took the night check to 0.24 s: worse than
main, replaced by the distinct dates of one ``findall`` before scoring the rows above.)
Re-scored on the final tree (the CSV run test on Arrow's strptime; two rounds, main first):
check night 0.179 0.182 -> 0.134 0.129, day13 0.522 0.535 -> 0.124 0.122; read night 10.41 10.72
-> 2.89 2.77, day13 1.93 2.39 -> 1.86 1.74.  Verdict: KEPT.

``table /tmp/dates85/bench`` (not in the bar: main refuses the table without the key), the least
of 3, two rounds: main refused in 0.18 / 0.20 s, with the key 0.28 / 0.28 s; here read by its run
in 0.43 / 0.44 s, with the key 0.27 / 0.40 s.  The run test, only where no row says the order,
costs ~0.16 s on 200 000 rows (0.6 s in a first cut parsing with pandas, replaced).

``stranger /tmp/dates85/str_<tree>`` (seeds 8853 night, 8854 day), main -> here:

* gb_night (run 1 from 03/05 22:00 into 04/05): ``init`` refused ("day or month first? set
  data.time ... or data.dayfirst") -> read day first, "the order its rows say (its run: its data
  row 121, '04/05/2027 00:00:00' ...)", ``data.time='%d/%m/%Y %H:%M:%S'`` written; ``run`` E_dX
  test RMSE 0.448 µm both (main with the key given by hand); ``export``: ``TC_SLASHED 0`` -> 1.
* gb_day (no night run): ``init`` refused both, now naming the file, column 'Date/Time', line 2 (data
  row 1) and ``data.dayfirst=true|false``; with the key 0.473 µm both; ``TC_SLASHED 0`` -> 1
  (before, the exported stream refused the lab's every row, the served model every block).
"""

from __future__ import annotations

import datetime as dt
import json
import sys
from pathlib import Path

import numpy as np
from _cli import run_commands
from cpu import cpu_seconds

STARTS = {"night": (8851, dt.datetime(2027, 5, 3, 23)), "day13": (8852, dt.datetime(2027, 5, 13, 7))}


def _export(path: Path, seed: int, start: dt.datetime, rows: int) -> None:
    rng = np.random.default_rng(seed)
    t = np.arange(rows, dtype=float)
    heat = 1 - np.exp(-t / (rows / 3))
    chans = [("Temp Bett", "°C", 20 + 4 * heat + rng.normal(0, 0.02, rows)),
             ("Temp Ständer", "°C", 20 + 2.5 * heat + rng.normal(0, 0.02, rows)),
             ("Temp Spindel", "°C", 21 + 6 * heat + rng.normal(0, 0.02, rows)),
             ("Tracker dX", "mm", (9 * heat + rng.normal(0, 0.3, rows)) / 1000)]
    base = np.datetime64(start, "ms") + (t * 1000).astype("timedelta64[ms]")
    stamps = [f"{s.day:02d}/{s.month:02d}/{s.year} {s:%H:%M:%S}.000"
              for s in base.astype(dt.datetime)]
    filetime = int((start - dt.timedelta(hours=1) - dt.datetime(1601, 1, 1)).total_seconds() * 1e7)
    lines = ["Name;Portal;", f"StartTime;{filetime};{start:%d/%m/%Y %H:%M:%S}.000", ""]
    for key, cells in (("Name", [c[0] for c in chans]), ("Data-Type", ["REAL64"] * len(chans)),
                       ("SampleTime[ms]", ["1000"] * len(chans)), ("Unit", [c[1] for c in chans])):
        lines.append(";".join(f"{key};{v};" for v in cells))
    lines += ["", ";".join("Time;Value;" for _ in chans)]
    values = [[f"{v:.7f}".replace(".", ",") for v in c[2]] for c in chans]
    lines += [";".join(f"{stamps[r]};{v[r]};" for v in values) for r in range(rows)]
    path.write_bytes("\r\n".join(lines).encode("cp1252") + b"\r\n")


def write(root: str, rows: str = "50000") -> None:
    out = Path(root)
    out.mkdir(parents=True, exist_ok=True)
    for name, (seed, start) in STARTS.items():
        _export(out / f"{name}.csv", seed, start, int(rows))
        print(f"{out / name}.csv: {(out / f'{name}.csv').stat().st_size / 1e6:.1f} MB")


LAB = {"gb_night": (8853, (dt.datetime(2027, 5, 3, 22), dt.datetime(2027, 5, 6, 8),
                         dt.datetime(2027, 5, 8, 8))),
       "gb_day": (8854, (dt.datetime(2027, 5, 3, 8), dt.datetime(2027, 5, 6, 8),
                         dt.datetime(2027, 5, 8, 8)))}


def _lab(root: Path, seed: int, starts) -> None:
    """Three runs of a spindle warm-up as an en-GB PC's logger exports them (``Date/Time``
    ``dd/mm/yyyy HH:MM:SS``, every minute, 6 h)."""
    rng = np.random.default_rng(seed)
    root.mkdir(parents=True, exist_ok=True)
    for run, start in enumerate(starts, start=1):
        t = np.arange(360) * 60.0
        speed = np.where((t // 3600) % 2 == 0, 1.0, 0.3 + 0.1 * run)
        spindle = 21 + np.cumsum(speed * 0.004 - 0.0006 * np.arange(360) / 360) * 3
        bed = 20.5 + 0.4 * (1 - np.exp(-t / 9000)) + rng.normal(0, 0.02, 360)
        column = 20.8 + 0.6 * (spindle - 21) ** 0.9 + rng.normal(0, 0.02, 360)
        ambient = 20 + 0.5 * np.sin(t / 20000 + run) + rng.normal(0, 0.02, 360)
        dx = 6.0 * (spindle - 21) - 2.0 * (bed - 20.5) + rng.normal(0, 0.3, 360)
        stamps = [f"{s:%d/%m/%Y %H:%M:%S}" for s in
                  (start + dt.timedelta(seconds=float(x)) for x in t)]
        frame = {"Date/Time": stamps, "Spindle [°C]": spindle, "Bed [°C]": bed,
                 "Column [°C]": column, "Ambient [°C]": ambient, "dX [um]": dx}
        lines = [",".join(frame)] + [",".join(f"{frame[k][i]:.4f}" if k != "Date/Time" else
                                              frame[k][i] for k in frame) for i in range(360)]
        (root / f"warmup_{run}.csv").write_text("\n".join(lines) + "\n", encoding="utf-8")


def stranger(root: str, python: str = sys.executable) -> None:
    """Each lab folder through ``thermocomp init``, ``run`` (with the key where init asks for it)
    and ``export export.format=c``, as a stranger would: what each said, the test RMSE, the
    exported stream's ``TC_SLASHED`` (1: its dates with slashes read day first)."""
    import subprocess

    for name, (seed, starts) in LAB.items():
        folder = Path(root) / name
        _lab(folder, seed, starts)
        for keys in ([], ["data.dayfirst=true"]):
            init = [python, "-m", "thermocomp", "init", str(folder),
                    f"out={Path(root) / ('init_' + name)}", *keys]
            done = subprocess.run(init, capture_output=True, text=True)
            said = [ln for ln in (done.stdout + done.stderr).splitlines()
                    if "slashes" in ln or "error" in ln or "first" in ln]
            print(f"{name} init {' '.join(keys) or '(no key)'}: exit {done.returncode}; "
                  + " | ".join(said)[:600])
            if done.returncode == 0:
                break
        run = [python, "-m", "thermocomp", "run",
               f"hydra.searchpath=[file://{Path(root) / ('init_' + name) / 'conf'}]",
               f"data={name}", "model=mlr", "track=false", "plots=none",
               f"out={Path(root) / ('run_' + name)}", *keys]
        done = subprocess.run(run, capture_output=True, text=True)
        metrics = Path(root) / f"run_{name}" / "metrics.json"
        if metrics.exists():
            rmse = json.loads(metrics.read_text())["targets"]["E_dX"]["test"]["rmse"]
            shown = f"E_dX test RMSE {rmse:.3f} um"
        else:
            shown = done.stderr[-600:]
        print(f"{name} run: exit {done.returncode}; {shown}")
        code = Path(root) / f"code_{name}"
        done = subprocess.run([python, "-m", "thermocomp", "export", *run[4:6], "track=false",
                               "export.format=c", f"export.model={Path(root) / f'run_{name}'}"
                               "/model.pkl", f"out={code}", *keys], capture_output=True, text=True)
        slashed = [ln for f in code.glob("*.[ch]") for ln in f.read_text().splitlines()
                   if ln.startswith("#define TC_SLASHED")]
        print(f"{name} export: exit {done.returncode}; {slashed or done.stderr[-300:]}")


def table(root: str) -> None:
    """A CSV table of 200 000 rows every second from the 3rd of May 07:00 (into the 5th, no day
    or month past 12), its time day first: read with ``data.dayfirst`` unset (the run test) and
    with it set, CPU each."""
    import pandas as pd

    from thermocomp.core.io import read_dataset

    path = Path(root) / "table.csv"
    if not path.exists():
        t = pd.date_range("2027-05-03 07:00", periods=200_000, freq="1s")
        h = np.arange(t.size) / t.size
        pd.DataFrame({"time": t.strftime("%d/%m/%Y %H:%M:%S"), "T_a": 20 + h, "T_b": 20 + h ** 2,
                      "T_c": 20 + np.sin(3 * h), "E_x": 3 * h}).to_csv(path, index=False)
    for keys in ({}, {"dayfirst": True}):
        times = []
        for _ in range(3):
            start = cpu_seconds()
            try:
                ds = read_dataset(path, {"test_fraction": 0.3, **keys})[0]
                said = ds.manifest["start"].iloc[0]
            except Exception as exc:       # (main: refused without the key)
                said = type(exc).__name__
            times.append(cpu_seconds() - start)
        print(f"table {keys or '(no key)'}: {said}, {min(times):.2f} s CPU (the least of 3)")


def check(root: str) -> None:
    from thermocomp.core.io import read_dataset
    from thermocomp.core.io.plain import lab_dayfirst

    for name in STARTS:
        path = Path(root) / f"{name}.csv"
        times = []
        for _ in range(3):
            start = cpu_seconds()
            said = lab_dayfirst([path], "cp1252")
            times.append(cpu_seconds() - start)
        start = cpu_seconds()
        ds, _ = read_dataset(path, {"roles": {"error": ["Tracker*"]}, "encoding": "cp1252",
                                    "test_fraction": 0.3})
        read = cpu_seconds() - start
        first = ds.manifest["start"].iloc[0]
        print(f"{name}: check {min(times):.3f} s CPU, said {said and (said[0], said[2])}; read "
              f"{read:.2f} s CPU, start {first}, {len(next(iter(ds.campaigns.values())))} rows")


def main(argv: list[str]) -> int:
    commands = {"write": write, "check": check, "stranger": stranger, "table": table}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
