"""Data in (stop 86, data86b): ``monitor`` of a registered model reads a PLC status word by the
model's own declaration, as ``replay`` does since data86.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_data86b.py bits ROOT     # seeds 9071 / 9072

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
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

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


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"bits": bits}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
