"""A lab's whole record at full size, through the documented commands: CPU and peak memory per step.

Usage::

    python benchmarks/bench_scale58.py [--small] [--out DIR] [--steps NAME ...] [--lstm]

Builds two records the way a lab exports them (one file each, German headers with units,
``;`` and decimal commas, a wall-clock ``Zeitstempel`` column), from ``thermocomp simulate
sim=long_record`` (seeds fixed below, chosen before any run):

* ``year``: 365 days at 1 min (525,601 rows), seed 58;
* ``month``: 30 days at 10 s (259,201 rows), seed 5810.

The simulated machine has 14 sensors; 20 more are added as a lab's extra thermocouples
would read: each a mix of two simulated sensors (weights drawn from the seed), lagged by a
first-order filter of 5-120 min, offset by up to 0.5 °C, with 0.03 °C noise and 0.01 °C
quantisation, so 34 temperature columns, ``Verlagerung Z [µm]`` and ``Drehzahl [1/min]``.
``--small`` builds 10 days at 1 min and 3 days at 10 s instead (a quick check).

Then, as a stranger would, each step runs in a child process: ``init``, ``ingest``, ``run``
with every family (``lstm`` only with ``--lstm``, capped by ``model.max_seconds``),
``ati=cmeans``, ``diagnose``, ``replay``, ``monitor`` (the test part, and the file on stdin),
``export`` (C, compiled with ``gcc`` and streamed), ``promote`` and ``compare``.  Per step it
prints the CPU time of the child tree (user+sys from ``os.wait4``), its peak RSS (the largest
process of the tree: ``ru_maxrss``), and the size of what the step wrote.  A step with a
process above 8 GiB RSS is stopped (the machine is shared).  Scratch goes to ``--out`` (default
``/tmp/scale58-bench``), never into the repository.

scale60 (``--records year --steps year_run_lagbank year_run_hammerstein year_run_auto``, one
step at a time, 2 shared cores at load 2-5; CPU user + sys and peak RSS of ``/usr/bin/time -v``;
before: 3b634e7, after: scale60's branch), ``before -> after`` (ratio)::

    run lagbank       153.6 s / 5.23 GiB  ->   90.9 s / 3.79 GiB   (1.69x CPU, 1.38x RSS)
    run hammerstein   421.8 s / 5.62 GiB  ->  219.6 s / 3.86 GiB   (1.92x, 1.45x)
    run auto          471.7 s / 5.65 GiB  ->  257.6 s / 4.02 GiB   (1.83x, 1.41x)
    run mlr (unchanged)                        23.1 s / 1.64 GiB

(``auto`` without ``lstm``, ``max_seconds=300``: it validated ``hammerstein`` in 384 s, then
217 s, of wall time, and chose it both times, test RMSE 0.27 µm; its first measurement, at
another load, had skipped it.)  Against ``mlr``'s CPU: ``lagbank`` 6.6x -> 3.9x,
``hammerstein`` 18.3x -> 9.5x.

The same fitted coefficients bit for bit, the same ``metrics.json`` (``auto``'s too); the CV
tables' MSE differ by at most 1.8e-8 (lagbank) and 1.4e-7 (hammerstein's lag bank) relative, at
the smallest penalties (the folds' Grams summed in another order), the same penalties and powers
chosen.  What went:
each forward-chaining fold's copy of its training rows and 3.5x the rows' Gram products (one
pass of 16 MB blocks, the prefixes' moments pooled), the refit's design standardised while the
CV's was still held, the lags written apart and copied into the features, scikit-learn's
``StandardScaler`` fit and transform on the whole design (its copies and checks: the same
numbers in blocks), and Hammerstein's three refits of the power sets it does not keep.  System
time fell with the copies (69.4 -> 29.3 s, 155.9 -> 52.8 s: fresh pages of GB-sized arrays).
Left: the features (1.2 GB, remembered) and one standardised copy at once.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np
import pandas as pd
import psutil

ROOT = Path(__file__).resolve().parents[1]
PY = [sys.executable, "-m", "thermocomp"]
RSS_LIMIT = 8 << 30
RECORDS = {  # name: (days, period s, seed); --small: (days, ...)
    "year": (365.0, 60.0, 58),
    "month": (30.0, 10.0, 5810),
}
SMALL_DAYS = {"year": 10.0, "month": 3.0}
EXTRA_SENSORS = 20
GERMAN = {
    "T_amb": "Umgebung [°C]", "T_spindle_front": "Spindel vorne [°C]",
    "T_spindle_rear": "Spindel hinten [°C]", "T_motor": "Motor [°C]",
    "T_head_left": "Kopf links [°C]", "T_head_right": "Kopf rechts [°C]",
    "T_col_front_top": "Ständer vorne oben [°C]", "T_col_front_low": "Ständer vorne unten [°C]",
    "T_col_back": "Ständer hinten [°C]", "T_bed_left": "Bett links [°C]",
    "T_bed_right": "Bett rechts [°C]", "T_table": "Tisch [°C]",
    "T_xdrive": "Antrieb X [°C]", "T_zdrive": "Antrieb Z [°C]",
    "E_Z": "Verlagerung Z [µm]", "S_spindle_rpm": "Drehzahl [1/min]",
}


def _env() -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "src") + os.pathsep + env.get("PYTHONPATH", "")
    return env


def run_step(args: list[str], *, stdin_path: Path | None = None, stdout_path: Path | None = None,
             cwd: Path | None = None, max_cpu_s: float = 600.0) -> dict:
    """Run ``args`` as a child: CPU s (user+sys of its tree), peak RSS (MiB), exit code, wall s;
    stopped past ``max_cpu_s`` of CPU (its main process) or ``RSS_LIMIT``.

    The child is reaped by ``os.wait4`` alone (its rusage is the measurement), so nothing else
    may wait for it: output goes to files, and the memory watch stops on a flag.
    """
    t0 = time.perf_counter()
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err, \
            open(stdin_path or os.devnull, "rb") as fin:
        child = subprocess.Popen(args, stdin=fin, stdout=out, stderr=err, env=_env(), cwd=cwd)
        done, killed = threading.Event(), []

        def watch():  # the machine is shared: stop a child whose process passes RSS_LIMIT
            try:
                proc = psutil.Process(child.pid)
                while not done.wait(0.2):
                    # per process: a forked worker's RSS counts the pages it shares with its parent
                    rss = max(p.memory_info().rss for p in [proc, *proc.children(recursive=True)])
                    times = proc.cpu_times()
                    if rss > RSS_LIMIT or times.user + times.system > max_cpu_s:
                        killed.append(rss)
                        os.kill(child.pid, signal.SIGKILL)
                        return
            except psutil.Error:
                return

        watcher = threading.Thread(target=watch, daemon=True)
        watcher.start()
        _, status, usage = os.wait4(child.pid, 0)
        child.returncode = os.waitstatus_to_exitcode(status)
        done.set()
        watcher.join()
        out.seek(0)
        err.seek(0)
        stdout, stderr = out.read(), err.read()
    if stdout_path:
        Path(stdout_path).write_bytes(stdout)
    return {"cpu_s": usage.ru_utime + usage.ru_stime, "rss_mib": usage.ru_maxrss / 1024,
            "rc": child.returncode, "wall_s": time.perf_counter() - t0,
            "killed_rss": killed[0] if killed else None,
            "stdout": stdout.decode(errors="replace"), "stderr": stderr.decode(errors="replace")}


def extra_sensors(frame: pd.DataFrame, seed: int, period_s: float) -> pd.DataFrame:
    """``EXTRA_SENSORS`` more thermocouples: lagged, offset mixes of two simulated sensors."""
    rng = np.random.default_rng([seed, 1])
    temps = [c for c in frame.columns if c.startswith("T_")]
    out = {}
    for k in range(EXTRA_SENSORS):
        a, b = rng.choice(len(temps), 2, replace=False)
        w = rng.uniform(0.3, 0.7)
        mix = w * frame[temps[a]].to_numpy() + (1 - w) * frame[temps[b]].to_numpy()
        alpha = period_s / (rng.uniform(5.0, 120.0) * 60.0 + period_s)
        lagged = pd.Series(mix).ewm(alpha=alpha, adjust=False).mean().to_numpy()
        value = lagged + rng.uniform(-0.5, 0.5) + rng.normal(0.0, 0.03, len(mix))
        out[f"Messstelle {k + 1:02d} [°C]"] = np.round(value, 2)
    return pd.DataFrame(out, index=frame.index)


def build(name: str, folder: Path, small: bool) -> Path:
    """Simulate record ``name`` and write it as a lab's one-file export ``<folder>/<name>.csv``."""
    days, period, seed = RECORDS[name]
    days = SMALL_DAYS[name] if small else days
    target = folder / f"{name}.csv"
    if target.exists():
        return target
    sim = folder / f"sim_{name}"
    res = run_step([*PY, "-q", "simulate", "sim=long_record", f"sim.generator.duration_days={days}",
                    f"sim.generator.sample_period_s={period}", f"seed={seed}", f"data.path={sim}"])
    if res["rc"]:
        sys.exit(res["stderr"][-3000:])
    manifest = pd.read_csv(sim / "campaigns.csv")
    parts = []
    for _, entry in manifest.iterrows():  # each part's time counts from its own start
        part = pd.read_csv(sim / entry["file"])
        part["time"] += float(entry["record_offset_s"])
        parts.append(part)
    frame = pd.concat(parts, ignore_index=True)
    start = pd.Timestamp(str(manifest["start"].iloc[0]))
    stamps = start + pd.to_timedelta(frame["time"].to_numpy(), unit="s")
    lab = pd.DataFrame({"Zeitstempel": stamps.strftime("%d.%m.%Y %H:%M:%S")})
    lab = pd.concat([lab, frame.drop(columns="time").rename(columns=GERMAN),
                     extra_sensors(frame, seed, period)], axis=1)
    lab.to_csv(target, sep=";", decimal=",", index=False)
    print(f"built {target}: {len(lab)} rows, {lab.shape[1]} columns, "
          f"{target.stat().st_size / 2**20:.1f} MiB ({res['cpu_s']:.1f} s CPU simulating)",
          flush=True)
    return target


def size_mib(path: Path) -> float:
    """Bytes under ``path`` (file or folder), MiB."""
    if path.is_file():
        return path.stat().st_size / 2**20
    return sum(p.stat().st_size for p in path.rglob("*") if p.is_file()) / 2**20 if path.exists() else 0.0


FAMILIES = ["mlr", "pcr", "arx", "lagbank", "hammerstein"]


def steps(name: str, work: Path, lab: Path, lstm: bool) -> list[tuple[str, list[str], dict]]:
    """``(label, thermocomp args, options)`` of every step on record ``name``, in order."""
    conf = f"hydra.searchpath=[file://{work}/init_{name}/conf]"
    common = [conf, f"data={name}", "track=false"]
    out = lambda label: f"out={work}/{label}"     # noqa: E731
    model = f"{work}/{name}_run_mlr/model.pkl"
    auto = [] if lstm else ["model.candidates=[mlr,pcr,arx,lagbank,hammerstein,ati]"]
    todo = [(f"{name}_init", ["init", str(lab), out(f"init_{name}")], {}),
            (f"{name}_ingest", ["ingest", *common, f"data.interim={work}/interim_{name}",
                                out(f"{name}_ingest")], {})]
    todo += [(f"{name}_run_{m}", ["run", *common, f"model={m}", out(f"{name}_run_{m}")], {})
             for m in FAMILIES]
    todo += [(f"{name}_run_mlr_plots_all", ["run", *common, "plots=all",
                                            out(f"{name}_run_mlr_plots_all")], {}),
             (f"{name}_run_auto", ["run", *common, "model=auto", *auto,
                                   "model.estimator.max_seconds=300", out(f"{name}_run_auto")], {}),
             (f"{name}_run_ati", ["run", *common, "ati=cmeans", out(f"{name}_run_ati")], {}),
             (f"{name}_diagnose", ["diagnose", *common, out(f"{name}_diagnose")], {}),
             (f"{name}_replay", ["replay", *common, f"replay.model={model}", out(f"{name}_replay")], {}),
             (f"{name}_monitor", ["monitor", *common, f"monitor.model={model}",
                                  out(f"{name}_monitor")], {}),
             (f"{name}_monitor_stdin", ["monitor", *common, f"monitor.model={model}", "monitor.input=-",
                                        out(f"{name}_monitor_stdin")], {"stdin": "test_rows"}),
             (f"{name}_export_c", ["export", *common, f"export.model={model}", "export.format=c",
                                   out(f"{name}_export")], {"then": "gcc"}),
             (f"{name}_sweep_mlflow", ["run", "-m", conf, f"data={name}", "model=mlr,pcr",
                                       f"tracking_uri=sqlite:///{work}/mlruns/mlflow.db",
                                       f"hydra.sweep.dir={work}/{name}_sweep"],
              {"size": work / "mlruns"}),   # the MLflow store: its database and artifacts
             (f"{name}_compare", ["compare", conf, f"data={name}", f"compare.sweep={work}/{name}_sweep",
                                  f"tracking_uri=sqlite:///{work}/mlruns/mlflow.db",
                                  f"compare.out={work}/{name}_compare"], {}),
             (f"{name}_promote", ["promote", conf, f"data={name}", f"compare.sweep={work}/{name}_sweep",
                                  f"tracking_uri=sqlite:///{work}/mlruns/mlflow.db",
                                  out(f"{name}_promote")], {})]
    if lstm:
        todo.insert(7, (f"{name}_run_lstm", ["run", *common, "model=lstm", out(f"{name}_run_lstm")], {}))
    return todo


def test_rows(lab: Path, work: Path, fraction: float = 0.1) -> Path:
    """The header and the last ``fraction`` of the rows of ``lab``: what a logger sends on stdin."""
    lines = lab.read_text(encoding="utf-8").splitlines(keepends=True)
    keep = int(round(fraction * (len(lines) - 1)))
    path = work / f"{lab.stem}_test_rows.csv"
    path.write_text(lines[0] + "".join(lines[-keep:]), encoding="utf-8")
    return path


def _compile_and_stream(folder: Path, lab: Path) -> dict:
    """``gcc`` the exported C and stream the whole record through it."""
    res = run_step(["gcc", "-O2", "compensator.c", "stream.c", "-lm", "-o", "stream"], cwd=folder)
    if res["rc"]:
        return {**res, "gcc_cpu_s": res["cpu_s"]}
    run = run_step([str(folder / "stream")], stdin_path=lab, stdout_path=folder / "corrections.csv",
                   cwd=folder)
    return {**run, "gcc_cpu_s": res["cpu_s"]}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--small", action="store_true", help="10 days at 1 min, 3 days at 10 s")
    parser.add_argument("--out", type=Path, help="scratch folder (default /tmp/scale58-bench[-small])")
    parser.add_argument("--records", nargs="*", default=list(RECORDS), choices=list(RECORDS))
    parser.add_argument("--steps", nargs="*", help="only the steps whose label holds one of these")
    parser.add_argument("--lstm", action="store_true", help="also model=lstm and auto with lstm")
    parser.add_argument("--max-cpu", type=float, default=600.0, help="CPU seconds per step")
    args = parser.parse_args()
    work = (args.out or Path("/tmp/scale58-bench" + ("-small" if args.small else ""))).resolve()
    work.mkdir(parents=True, exist_ok=True)
    rows = []
    print(f"{'step':34s} {'CPU s':>8s} {'RSS MiB':>8s} {'out MiB':>8s}  rc", flush=True)
    for name in args.records:
        lab = build(name, work, args.small)
        for label, cmd, opt in steps(name, work, lab, args.lstm):
            if args.steps and not any(s in label for s in args.steps):
                continue
            stdin = test_rows(lab, work) if opt.get("stdin") else None
            res = run_step([*PY, *cmd], stdin_path=stdin, max_cpu_s=args.max_cpu)
            target = re.search(r"out=(\S+)", " ".join(cmd))
            folder = Path(target.group(1)) if target else work / f"{name}_sweep"
            sized = opt.get("size", folder)
            extra = ""
            if opt.get("then") == "gcc" and not res["rc"]:
                c = _compile_and_stream(folder, lab)
                extra = (f"  (gcc {c['gcc_cpu_s']:.1f} s CPU; stream.c over the whole record: "
                         f"{c['cpu_s']:.1f} s CPU, {c['rss_mib']:.1f} MiB, rc {c['rc']})")
            if res["killed_rss"]:
                extra += f"  STOPPED (RSS {res['killed_rss'] / 2**30:.1f} GiB, or --max-cpu)"
            row = {"step": label, "cpu_s": round(res["cpu_s"], 1), "rss_mib": round(res["rss_mib"]),
                   "out_mib": round(size_mib(sized), 1), "rc": res["rc"]}
            rows.append(row)
            print(f"{label:34s} {row['cpu_s']:8.1f} {row['rss_mib']:8d} {row['out_mib']:8.1f}  "
                  f"{res['rc']}{extra}", flush=True)
            if res["rc"]:
                print("   " + res["stderr"].strip().splitlines()[-1][:300] if res["stderr"].strip()
                      else "   (no stderr)", flush=True)
    (work / "bench_scale58.json").write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
