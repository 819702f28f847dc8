"""Data in (stop 86, data86b): ``monitor`` of a registered model reads a PLC status word by the
model's own declaration, as ``replay`` does since data86; a LabVIEW record end to end, its
``.lvm`` piped into ``monitor`` too.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_data86b.py bits ROOT     # seeds 9071 / 9072
    python benchmarks/bench_data86b.py lvm ROOT      # seed 9073

``bits``: bench_bits85's machine (``Status``: 128 a ready flag + bit 0 on + bit 1 spindle +
bit 2 coolant), two runs (seeds 9071, 9072; 360 rows of 10 s), the second held out; ``run
model=hammerstein`` with ``data.bits`` declared, ``promote``; the registered model replayed with
the key (what was scored), then ``monitor monitor.model=models:/...`` (and its pyfunc folder,
downloaded) on three data configs: the key, none, the key with bits 1 and 2 swapped; on the file
(the held-out run) and on stdin (``monitor.input=-``, the held-out run's CSV piped in).

No bar (a refusal turned into the model's own reading, as replay's): each outcome before (main
170e766b) and after (fix/data86b).

Scored (2026-12-04, main 170e766b -> fix/data86b 1ecf9349, ``bits /tmp/data86b/<tree>``): run
test RMSE E_dX 0.7834 µm (both trees); replay of the registered model with the key 0.7834
(both).  ``monitor``, each of the 12 (models:/ and the pyfunc folder; key, none, swapped; the
file and stdin):

* main: every one exit 2 -- models:/ "monitor.model=models:/thermocomp-compensator/1: a
  model.pkl file (run's or train's); a registered model replays through replay.model=...", the
  folder "file .../pyfunc: no trained model; run `thermocomp train` first".
* here, the key and no key: exit 0, RMSE fixed E_dX 0.7834 on the file and on stdin, from
  models:/ and from the folder (the figure replay scores: the stream monitored is the one
  promoted).
* here, swapped: exit 2, "data.bits={Status: {0: machine_on, 1: coolant_on, 2: spindle_on}} is
  not the declaration monitor.model=models:/thermocomp-compensator/1 (the folder: its path) was
  fitted with, data.bits={Status: {0: machine_on, 1: spindle_on, 2: coolant_on}}: a status word
  is read as the model reads it; leave data.bits out (the model's is read) or give the model's",
  on the file and on stdin.

Verdict (no bar): KEPT -- one mechanism (``builders.with_model_bits``) for replay, export and
monitor.
``lvm``: three runs (seed 9073; 360 rows a minute apart, a spindle warm-up) as an en-GB LabVIEW
writes them (``Date 06/09/2027``, decimal commas, an ``X_Value`` column, cp1252), from the 6th,
the 8th and the 13th of September 06:00, the 13th's held out; ``init`` (no key), ``run
model=lagbank`` by its config, ``promote``; ``monitor`` of the run's model.pkl and of the
registered model on the file, on the 13th's ``.lvm`` piped in and on the 6th's (its dates say no
order) piped in.  No bar (a refusal turned into the file's reading).

Scored (2026-12-04, main 170e766b -> fix/data86b, ``lvm /tmp/data86b/lvm_<tree>``): init exit 0,
``dayfirst: true`` (both trees); run test RMSE E_dX 0.7466 µm (both); model.pkl on the file
0.7466 (both).

* model.pkl, the 13th piped in: exit 2, "file <stdin>: stdin is not a CSV table with a header,
  data.delimiter=',' (Error tokenizing data ...)" -> exit 0, 0.7466 (the file's figure); the 6th
  piped in: the same exit 2 -> exit 0, 0.1954 (a train run), read day first as its record
  settled.
* models:/ (file, the 13th, the 6th): exit 2, "a model.pkl file ..." -> exit 0, 0.7466, 0.7466,
  0.1954 (the model.pkl's figures).

Verdict (no bar): KEPT.  (``lvm_as_csv``: a file of two sessions piped in is exit 2, "stream one
run".)
"""

from __future__ import annotations

import datetime as dt
import json
import os
import sys
from pathlib import Path

import numpy as np
from _cli import made_folder, run_commands
from bench_data86 import BITS, LIGHT, SWAPPED, _cli, _said


def _rmse(path: Path, key: str) -> str:
    return f"{json.loads(path.read_text())['targets']['E_dX'][key]:.4f}"


def bits(root: str) -> None:
    """``ROOT/runs`` (seeds 9071, 9072), run, promote, replay with the key, then ``monitor`` of
    the registered model (and its pyfunc folder) with the key, none and the swapped key, on the
    file and on stdin."""
    import bench_bits85
    import mlflow

    base = made_folder(root)
    bench_bits85.write(base / "runs", [9071, 9072])
    data = [f"data.path={base / 'runs'}", "data.roles.error=[dX*]", "data.roles.state=[Status]",
            "data.test_fraction=0.5"]
    keyed = {"key": BITS, "no key": {}, "swapped": SWAPPED}
    given = {k: [*data, *(f"++data.bits.Status.{b}={n}" for b, n in named.items())]
             for k, named in keyed.items()}
    light = ["model=hammerstein", *LIGHT]
    uri = f"sqlite:///{base / 'mlflow.db'}"
    done = _cli("run", *given["key"], *light, f"tracking_uri={uri}", f"out={base / 'run'}")
    assert done.returncode == 0, done.stderr[-2000:]
    mlflow.set_tracking_uri(uri)
    run_id = mlflow.search_runs(experiment_names=["thermocomp"])["run_id"].iloc[0]
    done = _cli("promote", *given["key"], *light, f"tracking_uri={uri}",
                f"promote.run_id={run_id}", f"out={base / 'promote'}")
    assert done.returncode == 0, done.stderr[-2000:]
    model = json.loads((base / "promote" / "promote.json").read_text())["model_uri"]
    os.environ["MLFLOW_ENABLE_ARTIFACTS_PROGRESS_BAR"] = "false"
    folder = mlflow.artifacts.download_artifacts(artifact_uri=model, dst_path=str(base / "pyfunc"))
    test = json.loads((base / "run" / "metrics.json").read_text())["targets"]["E_dX"]["test"]
    print(f"run: hammerstein test RMSE E_dX {test['rmse']:.4f} µm; promoted {model}")
    out = base / "replay"
    done = _cli("replay", *given["key"], f"replay.model={model}", f"tracking_uri={uri}",
                f"out={out}")
    print(f"replay, key: exit {done.returncode}"
          + (f", RMSE E_dX {_rmse(out / 'replay.json', 'rmse')}" if done.returncode == 0 else
             f", {_said(done)}"))
    piped = (base / "runs" / "run1.csv").read_bytes()
    for source, label in ((model, "models:/"), (folder, "pyfunc folder")):
        for key, keys in given.items():
            for where, extra, stdin in (("file", [], None),
                                        ("stdin", ["monitor.input=-"], piped)):
                out = base / f"monitor-{label[:6]}-{key.replace(' ', '')}-{where}"
                done = _cli("monitor", *keys, f"monitor.model={source}", f"tracking_uri={uri}",
                            *LIGHT[:1], f"out={out}", *extra, stdin=stdin)
                print(f"monitor {label}, {key}, {where}: exit {done.returncode}, " + (
                    f"RMSE fixed E_dX {_rmse(out / 'monitor.json', 'rmse_fixed')}"
                    if done.returncode == 0 else _said(done)))


LVM_STARTS = (dt.datetime(2027, 9, 6, 6), dt.datetime(2027, 9, 8, 6), dt.datetime(2027, 9, 13, 6))


def lvm_file(path: Path, rng: np.random.Generator, start: dt.datetime, rows: int = 360) -> None:
    """One run as an en-GB German-channel LabVIEW writes it (``Date 06/09/2027``, decimal commas,
    an ``X_Value`` column, one segment, cp1252, CRLF): a spindle warm-up every minute."""
    spin = (np.arange(rows) // 60) % 2 == 0
    heat = np.zeros(rows)
    for i in range(1, rows):
        heat[i] = heat[i - 1] + (8.0 * spin[i] - heat[i - 1]) / 50
    chans = {"Luft": 20 + rng.normal(0, 0.02, rows), "Ständer": 20.5 + heat / 20 + rng.normal(
        0, 0.02, rows), "Spindel": 21 + heat + rng.normal(0, 0.02, rows)}
    chans["dX"] = 2.0 * heat - 3.0 * (chans["Luft"] - 20) + rng.normal(0, 0.2, rows)
    units = ["Deg C"] * 3 + ["um"]

    def num(v: float) -> str:
        return f"{v:.6f}".replace(".", ",")
    date, time = f"{start:%d/%m/%Y}", f"{start:%H:%M:%S},0000000000"
    k = len(chans)
    lines = ["LabVIEW Measurement\t", "Writer_Version\t2", "Reader_Version\t2", "Separator\tTab",
             "Decimal_Separator\t,", "Multi_Headings\tNo", "X_Columns\tOne",
             "Time_Pref\tRelative", f"Date\t{date}", f"Time\t{time}", "***End_of_Header***\t", "",
             f"Channels\t{k}\t", "Samples\t" + f"{rows}\t" * k, "Date\t" + f"{date}\t" * k,
             "Time\t" + f"{time}\t" * k, "Y_Unit_Label\t" + "\t".join(units) + "\t",
             "X_Dimension\t" + "Time\t" * k, "X0\t" + "0,0000E+0\t" * k,
             "Delta_X\t" + f"{num(60.0)}\t" * k, "***End_of_Header***\t",
             "\t".join(["X_Value", *chans, "Comment"])]
    lines += ["\t".join([num(i * 60.0), *(num(v[i]) for v in chans.values())])
              for i in range(rows)]
    path.write_bytes(("\r\n".join(lines) + "\r\n").encode("cp1252"))


def lvm(root: str) -> None:
    """``ROOT/rig``: three runs (seed 9073) as an en-GB LabVIEW writes them, from the 6th, the
    8th and the 13th of September 06:00 (the 13th's says day first), the 13th's held out;
    ``init``, ``run model=lagbank`` by init's config, ``promote``; ``monitor`` of the run's
    model.pkl and of the registered model on the file, on the 13th's ``.lvm`` piped in and on
    the 6th's (its dates say no order) piped in."""
    import mlflow

    base = made_folder(root)
    rig = base / "rig"
    rig.mkdir(exist_ok=True)
    rng = np.random.default_rng(9073)
    for k, start in enumerate(LVM_STARTS, start=1):
        lvm_file(rig / f"Lauf_{k:02d}.lvm", rng, start)
    done = _cli("init", str(rig), f"out={base / 'init'}")
    conf = base / "init" / "conf" / "data" / "rig.yaml"
    print(f"init: exit {done.returncode}; " + (" ".join(
        ln.strip() for ln in conf.read_text(encoding="utf-8").splitlines() if "dayfirst" in ln)
        if done.returncode == 0 else _said(done)))
    uri = f"sqlite:///{base / 'mlflow.db'}"
    common = [f"hydra.searchpath=[file://{base / 'init' / 'conf'}]", "data=rig", "model=lagbank",
              *LIGHT, f"tracking_uri={uri}"]
    done = _cli("run", *common, f"out={base / 'run'}")
    assert done.returncode == 0, done.stderr[-2000:]
    test = json.loads((base / "run" / "metrics.json").read_text())["targets"]["E_dX"]["test"]
    mlflow.set_tracking_uri(uri)
    run_id = mlflow.search_runs(experiment_names=["thermocomp"])["run_id"].iloc[0]
    done = _cli("promote", *common, f"promote.run_id={run_id}", f"out={base / 'promote'}")
    assert done.returncode == 0, done.stderr[-2000:]
    model = json.loads((base / "promote" / "promote.json").read_text())["model_uri"]
    print(f"run: lagbank test RMSE E_dX {test['rmse']:.4f} µm; promoted {model}")
    for label, source in (("model.pkl", base / "run" / "model.pkl"), ("models:/", model)):
        for where, piped in (("file", None), ("stdin 13th", rig / "Lauf_03.lvm"),
                             ("stdin 6th", rig / "Lauf_01.lvm")):
            out = base / f"monitor-{label[:6]}-{where.replace(' ', '')}"
            done = _cli("monitor", *common, f"monitor.model={source}", f"out={out}",
                        *(["monitor.input=-"] if piped else []),
                        stdin=piped.read_bytes() if piped else None)
            print(f"monitor {label}, {where}: exit {done.returncode}, " + (
                f"RMSE fixed E_dX {_rmse(out / 'monitor.json', 'rmse_fixed')}"
                if done.returncode == 0 else _said(done)))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"bits": bits, "lvm": lvm}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
