"""Data in (stop 86, data86): the order a lab file settled and a status word, carried by the
model; the folder-wide date check without reading whole files.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_data86.py lab ROOT       # (a) an en-GB Scope View folder, seed 9006
    python benchmarks/bench_data86.py bits ROOT      # (b) a PLC status word, seeds 9007 / 9008
    python benchmarks/bench_data86.py write ROOT [ROWS]   # (c) two folders of large exports, 9009
    python benchmarks/bench_data86.py check ROOT     # (c) CPU of the folder-wide date check

``lab`` (a): ``ROOT/rig``, three runs of a spindle warm-up as an en-GB PC's TwinCAT Scope View
exports them (``;``, decimal commas, cp1252, absolute times ``dd/mm/yyyy HH:MM:SS.fff``; seed
9006, 6 h every 10 s, 2 160 rows): the first from the 3rd of May 22:00 across midnight, the
others from the 6th and the 10th at 07:00; no day or month past 12 anywhere, the night run alone
says day first.  Three records, each through the paths a stranger takes: ``folder`` (the three
files, the 10th's held out) and ``night`` (the night run's file alone, its last 30 % held out)
via ``thermocomp init`` (again with ``data.dayfirst=true`` where it refuses) and its config;
``night-keys``, the same file with ``data.path`` and the roles given by hand (no init).  Each:
``run model=lagbank`` (it reads the time), ``promote``; the registered model served the 10th's
lab rows (their dates with slashes) and the same rows timed in seconds; ``monitor`` of the
run's model.pkl on the record's test part and on the 10th's Scope export piped in
(``monitor.input=-``, as the PC wrote it); ``export export.format=c``'s ``TC_SLASHED``.

No bar (a gap closed, not a rule scored): each path's outcome before (main 14a3bd50) and after
(fix/data86).

Scored (2026-12-04, main 14a3bd50 -> fix/data86, ``lab /tmp/data86/<tree>_a``)
------------------------------------------------------------------------------
``folder``: ``init`` exit 2, "file .../Scope_2.csv, column 'StartTime', line 2: date
'06/05/2027 07:00:00.000' is day or month first? ... set data.dayfirst" (each file decided by
its own run: the 6th's and the 10th's mornings settle nothing) -> exit 0, "rig: dates with
slashes read day first, as Scope_1.csv's '04/05/2027' (its run: a day on read so, a month on or
back read the other way) says, in every file: data.dayfirst=true", written.  With the key (by
hand on main, by init here) every path as before: run test RMSE 2.2518 µm, served lab rows = the
rows in seconds (max |dC| 0 of max |C| 17.50 µm), monitor file 2.2511 = stdin 2.2511,
``TC_SLASHED 1``.

``night`` (init: no key written on main -> ``data.dayfirst: true`` written here), ``night-keys``
(no key either tree); main -> here:

* run: test RMSE 0.2967 / 0.3205 µm, the same on both trees (the file's reader settles its own).
* served, the 10th's lab rows: refused, "value '10/05/2027 07:00:00.000' is a date with slashes,
  day or month first? set data.time ... or data.dayfirst" -> read day first, the corrections
  the rows in seconds get (max |dC| 0, of max |C| 15.21 / 15.06 µm).
* monitor on the record's test part: 0.2967 / 0.3205 both trees; on the 10th's export piped in:
  exit 2, "file <stdin>, column 'StartTime', line 2: date '10/05/2027 07:00:00.000' is day or
  month first? ..." -> exit 0, RMSE 0.3484 / 0.3403 µm (another run than the file's test part).
* export: ``TC_SLASHED 0`` -> ``1``.

Verdict (no bar): KEPT -- the order the record's files settled is the one every deployed path
reads the lab's rows in, with no key given by hand.

``bits`` (b): bench_bits85's machine (``Status``: 128 a ready flag + bit 0 on + bit 1 spindle +
bit 2 coolant), two runs (seeds 9007, 9008; 360 rows of 10 s), the second held out; ``run
model=hammerstein`` with ``data.bits`` declared, ``promote``; the registered model replayed and
exported as C with its check pack (``export.check=true``) on three data configs: the key, none,
the key with bits 1 and 2 swapped.  No bar (a refusal turned into the model's own reading, a
silent mis-read into a refusal).

Scored (2026-12-04, main 14a3bd50 -> fix/data86, ``bits /tmp/data86/<tree>_b``): run test RMSE
E_dX 1.0141 µm (both).  With the key: replay 1.0141, the pack of run1's 360 rows (both).

* no key: replay exit 2 "test campaign run1 lacks 3 columns the deployed model reads:
  S_machine_on, S_spindle_on, S_coolant_on (... give data.bits={Status: {0: machine_on, 1:
  spindle_on, 2: coolant_on}})", export alike -> replay exit 0, RMSE 1.0141 (the keyed one's);
  export exit 0, its pack's expected corrections byte for byte the keyed export's.
* swapped: replay exit 0, RMSE 1.7320 (the spindle read as the coolant, without a word); export
  exit 0, a pack whose expected corrections are not the keyed one's -> each exit 2,
  "data.bits={Status: {0: machine_on, 1: coolant_on, 2: spindle_on}} is not the declaration
  replay.model=models:/thermocomp-compensator/1 was fitted with, data.bits={Status: {0:
  machine_on, 1: spindle_on, 2: coolant_on}}: a status word is read as the model reads it; leave
  data.bits out (the model's is read) or give the model's".

Verdict (no bar): KEPT.

``write`` / ``check`` (c): the folder-wide check (``plain.lab_dayfirst``, run by every read of a
folder with ``data.dayfirst`` unset, by ``init`` and now by ``slashed_time``) read each lab
file's whole text and looked at every date in it: 69 MB for ``may`` (24 exports of 20 000 rows,
2.9 MB each), 35 MB for ``early``.  The rule: a file's dates run forward (its reader refuses a
time that goes back), so a file whose first and last dates are one is that date throughout (its
head and its tail read, not its middle); any other file is read from its start only until its
dates say an order (a day past 12, or a run one order alone reads), where the folder's decision
can no longer change (an order impossible on a part of a file is impossible on all of it).

The bar (written before scoring): on both folders the check says the same (order, file, date,
run) as the whole-text check of 37409ee5 (this branch before the rule); its CPU (the least of
3) at most 0.2 x that check's on each folder.  Trees alternated, the whole-text one first.

Before (2026-12-04, measured before the rule was written; CPU s, the least of 3, two rounds):
main 14a3bd50: may 1.159 / 1.174 (said day first, Scope_13.csv's '13/05/2027'), early 0.590 /
0.595 (said nothing: main does not settle by a run); 37409ee5: may 1.200 / 1.190 (the same),
early 0.595 / 0.608 (day first, Scope_06.csv's '07/05/2027', its run).

Scored (2026-12-04, 37409ee5 -> fix/data86, ``write /tmp/data86/c`` (69 MB / 35 MB), ``check``;
two rounds, 37409ee5 first; CPU s, the least of 3)
---------------------------------------------------------------------------------------------
::

  folder  said (both trees)                                   whole text      -> read as needed
  may     day first, Scope_13.csv's '13/05/2027'              1.164  1.209    -> 0.109  0.105
  early   day first, Scope_06.csv's '07/05/2027' (its run)    0.594  0.607    -> 0.052  0.048

The same decision on both folders; the check's CPU 0.09 x (may) and 0.08 x (early) the
whole-text one's (main's: 1.16 / 0.59, the same reading without the run): bar met.  What
is read: of a morning's export (the 13th's and later alike, their one date past 12) its first
and last 64 KiB, one date at both ends; of the night run, its text a MiB at a time up to its
midnight (2 h into a 5.5 h file).  (A first cut left the file at its end where it was
no larger than 4 x 64 KiB: every small file said nothing; tests/shell/test_data86.py's small
records caught it before scoring.)  A catman or LabVIEW file, whose dates are in its header (and
a LabVIEW segment's), holds no date in its tail: read from its start until its dates say an
order, whole where they say none, as before.  tests/shell/test_data86.py counts what is read
(< 0.3 of the bytes of a morning and a 13th's / a night's export; before: every byte).
Re-scored on the final tree (c0dac26a: the head's and the tail's whole lines only; before, a
date cut in two at the tail's first byte could send a morning's file to the scan), 37409ee5
first, two rounds: may 1.189 1.164 -> 0.062 0.058 (0.05 x), early 0.631 0.604 -> 0.050 0.050
(0.08 x), the same decisions.  Verdict: KEPT.  ``lab`` and ``bits`` re-run on the final tree:
every line as scored above.
"""

from __future__ import annotations

import datetime as dt
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
from _cli import made_folder, run_commands
from cpu import cpu_seconds


def scope_export(path: Path, rng: np.random.Generator, start: dt.datetime, rows: int,
                 period_s: float = 10.0, run: int = 1) -> None:
    """A TwinCAT Scope View export as an en-GB PC writes it (``;``, decimal commas, cp1252,
    absolute times ``dd/mm/yyyy HH:MM:SS.fff``): three temperatures and a tracker's dX (mm),
    every ``period_s``, a spindle warm-up whose heat the error follows."""
    t = np.arange(rows) * period_s
    speed = np.where((t // 3600) % 2 == 0, 1.0, 0.3 + 0.1 * run)
    heat = np.zeros(rows)
    for i in range(1, rows):
        heat[i] = heat[i - 1] + (speed[i] * 8 - heat[i - 1]) * period_s / 3000
    bed = 20 + 0.3 * heat / 8 + rng.normal(0, 0.02, rows)
    column = 20.5 + 0.8 * heat / 8 + rng.normal(0, 0.02, rows)
    spindle = 21 + heat + rng.normal(0, 0.02, rows)
    dx = 2.2 * heat - 3.0 * (bed - 20) + rng.normal(0, 0.3, rows)
    chans = [("Temp Bett", "°C", bed), ("Temp Ständer", "°C", column),
             ("Temp Spindel", "°C", spindle), ("Tracker dX", "mm", dx / 1000)]
    base = np.datetime64(start, "ms") + (t * 1000).astype("timedelta64[ms]")
    stamps = [f"{s.day:02d}/{s.month:02d}/{s.year} {s:%H:%M:%S}.000"
              for s in base.astype(dt.datetime)]
    filetime = int((start - dt.timedelta(hours=1) - dt.datetime(1601, 1, 1)).total_seconds() * 1e7)
    lines = ["Name;Portal;", f"StartTime;{filetime};{start:%d/%m/%Y %H:%M:%S}.000", ""]
    for key, cells in (("Name", [c[0] for c in chans]), ("Data-Type", ["REAL64"] * len(chans)),
                       ("SampleTime[ms]", [f"{period_s * 1000:.0f}"] * len(chans)),
                       ("Unit", [c[1] for c in chans])):
        lines.append(";".join(f"{key};{v};" for v in cells))
    lines += ["", ";".join("Time;Value;" for _ in chans)]
    values = [[f"{v:.7f}".replace(".", ",") for v in c[2]] for c in chans]
    lines += [";".join(f"{stamps[r]};{v[r]};" for v in values) for r in range(rows)]
    path.write_bytes("\r\n".join(lines).encode("cp1252") + b"\r\n")


LAB_STARTS = (dt.datetime(2027, 5, 3, 22), dt.datetime(2027, 5, 6, 7), dt.datetime(2027, 5, 10, 7))
LIGHT = ["plots=none", "eval.mutual_prediction=false", "eval.ati_baselines=false",
         "eval.iso10791_a3=false"]


def _cli(*args: str, stdin: bytes | None = None) -> subprocess.CompletedProcess:
    """``python -m thermocomp ARGS`` (its output decoded as UTF-8), ``stdin`` piped in as the
    bytes the lab's PC wrote."""
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    done = subprocess.run([sys.executable, "-m", "thermocomp", *args], input=stdin,
                          capture_output=True, env=env)
    return subprocess.CompletedProcess(done.args, done.returncode,
                                       *(b.decode("utf-8", "replace") for b in (done.stdout,
                                                                               done.stderr)))


def _said(done: subprocess.CompletedProcess, words: tuple[str, ...] = ("error:",)) -> str:
    lines = [ln for ln in (done.stdout + done.stderr).splitlines()
             if any(w in ln.lower() for w in words)]
    return " | ".join(lines)[:500] or done.stderr.strip()[-300:]


def _figure(path: Path, *keys: str) -> str:
    said = json.loads(path.read_text())["targets"]["E_Tracker_dX"]
    for key in keys:
        said = said[key]
    return f"{said:.4f}"


def _served(uri: str, model_uri: str, block: pd.DataFrame):
    import mlflow

    mlflow.set_tracking_uri(uri)
    try:
        return mlflow.pyfunc.load_model(model_uri).predict(block, params={"reset": True}), ""
    except Exception as exc:  # noqa: BLE001 (the outcome measured)
        return None, f"{type(exc).__name__}: {str(exc)[:300]}"


def lab(root: str) -> None:
    """(a) ``ROOT/rig``: three runs of a spindle warm-up as an en-GB PC's Scope View exports them
    (seed 9006; 6 h every 10 s), the first from the 3rd of May 22:00 across midnight, the others
    from the 6th and the 10th 07:00 (no day or month past 12 anywhere; the run across midnight
    alone says day first).  Two records: the folder (its last run held out) and the night run's
    file alone (``data.test_fraction=0.3``).  As a stranger, each: ``init`` (again with
    ``data.dayfirst=true`` where it refuses), ``run`` by init's config (``model=lagbank``: it
    reads the time), ``promote``; the served model fed the 10th's lab rows (its dates with
    slashes) and the same rows timed in seconds; ``monitor`` of the run's model.pkl on the file
    and on stdin (``monitor.input=-``: the 10th's Scope export piped in); ``export
    export.format=c``'s ``TC_SLASHED``."""
    base = made_folder(root)
    rig = base / "rig"
    rig.mkdir(exist_ok=True)
    rng = np.random.default_rng(9006)
    for run, start in enumerate(LAB_STARTS, start=1):
        scope_export(rig / f"Scope_{run}.csv", rng, start, 2160, run=run)
    for name, path, init in (("folder", rig, True), ("night", rig / "Scope_1.csv", True),
                             ("night-keys", rig / "Scope_1.csv", False)):
        print(f"-- {name}: {path.relative_to(base)}" + ("" if init else ", no init: data.path"
                                                         " and the roles given by hand"))
        _lab_paths(base / name, path, rig / "Scope_3.csv", init)


def _lab_paths(base: Path, path: Path, test: Path, init: bool = True) -> None:
    """:func:`lab`'s paths of the record ``path``, the lab rows of ``test`` served and piped."""
    common = [f"data.path={path}", "data.roles.error=[Tracker*]", "data.encoding=cp1252",
              "data.test_fraction=0.3", "model=lagbank", *LIGHT]
    for keys in ([], ["data.dayfirst=true"]) if init else ():
        done = _cli("init", str(path), f"out={base / 'init'}", *keys)
        print(f"init {' '.join(keys) or '(no key)'}: exit {done.returncode}; "
              f"{_said(done, ('first', 'error'))}")
        if done.returncode == 0:
            conf = next((base / "init" / "conf" / "data").glob("*.yaml"))
            print("config: " + (" ".join(ln.strip() for ln in conf.read_text().splitlines()
                                         if "dayfirst" in ln) or "(no dayfirst)"))
            common = [f"hydra.searchpath=[file://{base / 'init' / 'conf'}]",
                      f"data={conf.stem}", *keys, "model=lagbank", *LIGHT]
            break
    uri = f"sqlite:///{base / 'mlflow.db'}"
    done = _cli("run", *common, f"tracking_uri={uri}", f"out={base / 'run'}")
    if done.returncode:
        print(f"run: exit {done.returncode}; {_said(done)}")
        return
    print(f"run: exit 0, test RMSE E_Tracker_dX {_figure(base / 'run' / 'metrics.json', 'test', 'rmse')}")
    import mlflow

    mlflow.set_tracking_uri(uri)
    run_id = mlflow.search_runs(experiment_names=["thermocomp"])["run_id"].iloc[0]
    done = _cli("promote", *common, f"tracking_uri={uri}", f"promote.run_id={run_id}",
                f"out={base / 'promote'}")
    model_uri = json.loads((base / "promote" / "promote.json").read_text())["model_uri"]
    frame = pd.read_csv(test, sep=";", decimal=",", skiprows=9, header=None, encoding="cp1252")
    block = pd.DataFrame({"time": frame[0], "Temp Bett [°C]": frame[1],
                          "Temp Ständer [°C]": frame[4], "Temp Spindel [°C]": frame[7]})
    seconds = block.assign(time=np.arange(len(block)) * 10.0)
    (served, said), (timed, _) = (_served(uri, model_uri, b) for b in (block, seconds))
    print("served, the lab's rows (dd/mm/yyyy): " + (
        f"max |C - C timed in s| {np.abs(served['C_Tracker_dX'] - timed['C_Tracker_dX']).max():.2g}"
        f" µm (of max |C| {np.abs(timed['C_Tracker_dX']).max():.2f})"
        if served is not None else f"refused, {said}"))
    for label, extra, stdin in (("the file", [], None),
                                ("stdin", ["monitor.input=-"], test.read_bytes())):
        out = base / f"monitor-{label.split()[-1]}"
        done = _cli("monitor", *common, f"monitor.model={base / 'run' / 'model.pkl'}",
                    "track=false", f"out={out}", *extra, stdin=stdin)
        print(f"monitor on {label}: " + (
            f"exit 0, RMSE E_Tracker_dX {_figure(out / 'monitor.json', 'rmse_fixed')}"
            if done.returncode == 0 else f"exit {done.returncode}, {_said(done)}"))
    code = base / "c"
    done = _cli("export", *common, "track=false", "export.format=c", "export.check=false",
                f"export.model={base / 'run' / 'model.pkl'}", f"out={code}")
    slashed = [ln for f in code.glob("*.[ch]") for ln in f.read_text().splitlines()
               if ln.startswith("#define TC_SLASHED")]
    print(f"export: exit {done.returncode}; {slashed or _said(done)}")


BITS = {0: "machine_on", 1: "spindle_on", 2: "coolant_on"}
SWAPPED = {0: "machine_on", 1: "coolant_on", 2: "spindle_on"}


def bits(root: str) -> None:
    """(b) ``ROOT/runs``: bench_bits85's machine (its PLC's ``Status``: a ready flag, bit 0 on,
    bit 1 spindle, bit 2 coolant), two runs, seeds 9007 and 9008, the second held out; ``run``
    (hammerstein, ``data.bits`` declared), ``promote``; the registered model replayed, and
    exported as C with its check pack (``export.check=true``), with the key, without it and with
    a key whose bits 1 and 2 are swapped."""
    import bench_bits85
    import mlflow

    base = made_folder(root)
    bench_bits85.write(base / "runs", [9007, 9008])
    data = [f"data.path={base / 'runs'}", "data.roles.error=[dX*]", "data.roles.state=[Status]",
            "data.test_fraction=0.5"]
    keyed = {"key": BITS, "no key": {}, "swapped": SWAPPED}
    given = {k: [*data, *(f"++data.bits.Status.{b}={n}" for b, n in named.items())]
             for k, named in keyed.items()}
    light = ["model=hammerstein", *LIGHT]
    uri = f"sqlite:///{base / 'mlflow.db'}"
    done = _cli("run", *given["key"], *light, f"tracking_uri={uri}", f"out={base / 'run'}")
    assert done.returncode == 0, done.stderr[-2000:]
    rmse = json.loads((base / "run" / "metrics.json").read_text())["targets"]["E_dX"]["test"]
    mlflow.set_tracking_uri(uri)
    run_id = mlflow.search_runs(experiment_names=["thermocomp"])["run_id"].iloc[0]
    done = _cli("promote", *given["key"], *light, f"tracking_uri={uri}",
                f"promote.run_id={run_id}", f"out={base / 'promote'}")
    assert done.returncode == 0, done.stderr[-2000:]
    model = json.loads((base / "promote" / "promote.json").read_text())["model_uri"]
    print(f"run: hammerstein test RMSE E_dX {rmse['rmse']:.4f} µm; promoted {model}")
    for label, keys in given.items():
        out = base / f"replay-{label.replace(' ', '')}"
        done = _cli("replay", *keys, f"replay.model={model}", f"tracking_uri={uri}", f"out={out}")
        if done.returncode == 0:
            said = json.loads((out / "replay.json").read_text())["targets"]["E_dX"]["rmse"]
            shown = f"exit 0, RMSE E_dX {said:.4f}"
        else:
            shown = f"exit {done.returncode}, {_said(done)}"
        print(f"replay, {label}: {shown}")
        out = base / f"c-{label.replace(' ', '')}"
        done = _cli("export", *keys, f"export.model={model}", f"tracking_uri={uri}",
                    "export.format=c", "export.check=true", f"out={out}")
        if done.returncode == 0:
            pack = json.loads((out / "check" / "check.json").read_text())["campaigns"][0]
            same = all(f.read_bytes() == (base / "c-key" / f.relative_to(out)).read_bytes()
                       for f in (out / "check").rglob("*.csv"))
            shown = (f"exit 0, pack: {pack['campaign']} {pack['rows']} rows, its expected "
                     f"corrections {'the same as' if same else 'not'} the keyed export's")
        else:
            shown = f"exit {done.returncode}, {_said(done)}"
        print(f"export c (check), {label}: {shown}")


FOLDERS = {"may": [dt.datetime(2027, 5, d, 7) for d in range(1, 25)],
           "early": [dt.datetime(2027, 5, d, 22 if d == 6 else 7) for d in range(1, 13)]}


def write(root: str, rows: str = "20000") -> None:
    """(c) Two folders of large Scope View exports (en-GB, as :func:`scope_export` writes them,
    every second, ``ROWS`` rows each; one generator, seed 9009): ``may``, 24 runs from the 1st
    to the 24th of May at 07:00 (the 13th's and later say day first by their day); ``early``,
    12 runs from the 1st to the 12th, the 6th's from 22:00 across midnight (no day or month past
    12: that run alone says the order)."""
    rng = np.random.default_rng(9009)
    for name, starts in FOLDERS.items():
        folder = made_folder(str(Path(root) / name))
        for k, start in enumerate(starts, start=1):
            scope_export(folder / f"Scope_{k:02d}.csv", rng, start, int(rows), period_s=1.0,
                         run=k % 4)
        size = sum(f.stat().st_size for f in folder.iterdir())
        print(f"{folder}: {len(starts)} files, {size / 1e6:.0f} MB")


def check(root: str) -> None:
    """(c) Per folder of :func:`write`, the CPU (user + sys, the least of 3) of the folder-wide
    check (``plain.lab_dayfirst``: the order one file's dates say for all), and what it said."""
    from thermocomp.core.io.plain import lab_dayfirst

    for name in FOLDERS:
        files = sorted((Path(root) / name).glob("*.csv"))
        times = []
        for _ in range(3):
            start = cpu_seconds()
            said = lab_dayfirst(files, "cp1252")
            times.append(cpu_seconds() - start)
        shown = "nothing" if said is None else (
            f"day first={said[0]}, {said[1].name}'s {said[2]!r}"
            + (" (its run)" if getattr(said, "run", False) else ""))
        print(f"{name}: check {min(times):.3f} s CPU (of {', '.join(f'{t:.3f}' for t in times)}),"
              f" said {shown}")


def main(argv: list[str]) -> int:
    commands = {"lab": lab, "bits": bits, "write": write, "check": check}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
