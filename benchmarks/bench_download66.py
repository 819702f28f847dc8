"""CPU of loading a registered model, and of the commands that load one (download66).

Usage::

    python benchmarks/bench_download66.py OLD_SRC [repeats] [scratch]   # default 5, /tmp/download66-bench

``OLD_SRC``: the ``src`` folder of the tree to compare with (``git archive <base> src | tar -x -C
/tmp/x``: ``/tmp/x/src``); this tree's ``src`` is the new one.  Both are run alternately, each
call a fresh Python process (``PYTHONPATH`` set to one tree), on the same two stores made once by
this tree: a small simulated dataset (6 campaigns), ``run`` + ``promote`` of the default model and
of ``model=auto plots=all`` (a run with figures).  Each promoted model folder holds 270 files
(the package source of ``code_paths``, 261 of them, 3.1 MB); a load reads 3 (MLmodel, the signed pickle,
its signature).

Measured, CPU = user + sys, median over the repeats:

* ``load``: one ``load_deployed("models:/thermocomp-compensator@champion")`` in a warm process
  (after a first load), and the number of files it copied out of the store (counted in
  MLflow's local artifact repository);
* ``replay`` / ``export`` (``export.format=json``) of the registered champion: the whole
  command, a fresh interpreter (RUSAGE_CHILDREN around it);
* ``serve``: ``thermocomp serve`` from its start until ``/ping`` answers 200, then SIGTERM, its
  server child included (it waits for it): start to ready plus a stop.

Adoption bar, written before scoring: the file-by-file load is kept if (1) the deployed
compensator it loads is unpickled from the same bytes (the signed pickle, SHA-256 of what its
signature check let through) as the one loaded from the whole download, and
``replay``'s ``replay.json`` is identical on both trees, timing aside (every figure: RMSE,
stream minus batch, ranges, events); (2) a load copies 3 files
instead of 270; (3) the median CPU of a load is lower on the new tree for both stores.  The
command figures are reported, not a bar (a command's CPU is mostly its imports and its data).

Measured on the shared 2-core machine (load 7-10, others' tests running), main d4ed328b ->
fix/download66, 5 repeats alternated, two runs of the script; medians, s of CPU (load: ms)::

    store        files   load ms        replay s             export s             serve s
    arx   old     270    192 | 120    2.90 | 3.11         2.79 | 2.97          5.18 | 5.38
    arx   new       3     12 |  12    2.78 | 2.92         2.84 | 2.90          5.21 | 5.09
    auto  old     270    139 | 267    4.04 | 4.08         4.49 | 4.26          7.76 | 7.48
    auto  new       3     13 |  12    4.03 | 3.79         4.19 | 4.19          7.45 | 7.28

A load's range: 97-312 ms before, 11-16 ms after.  Both stores: the signed pickle loaded
the same bytes (SHA-256) on both trees and ``replay.json`` identical: the bar is met, adopted.
The commands' medians moved by +0.05 to -0.31 s (of 2.8-7.8 s; a load saves ~0.1-0.25 s),
inside their spread between repeats (0.3-0.9 s): not resolved as a command figure at this load.
"""

from __future__ import annotations

import hashlib
import json
import os
import resource
import signal
import socket
import statistics
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

HERE = Path(__file__).resolve().parents[1]
NEW_SRC = HERE / "src"
PY = sys.executable
MODEL = "models:/thermocomp-compensator@champion"

SETUP = """
import sys, mlflow
sys.path[:0] = [{tests!r}, {apps!r}]
from pathlib import Path
from test_deploy import write_small_dataset
from thermocomp.shell.cli import main
root = Path({root!r}); root.mkdir(parents=True, exist_ok=True)
data = write_small_dataset(root / "small")
uri = f"sqlite:///{{root}}/mlruns/mlflow.db"
common = [f"data.path={{data}}", f"tracking_uri={{uri}}", *{extra!r}]
assert main(["run", *common, f"out={{root / 'run'}}"]) == 0
mlflow.set_tracking_uri(uri)
run_id = mlflow.search_runs(experiment_names=["thermocomp"])["run_id"].iloc[0]
assert main(["promote", *common, f"promote.run_id={{run_id}}", f"out={{root / 'p'}}"]) == 0
"""

LOAD = """
import hashlib, resource, sys, mlflow
from mlflow.store.artifact.local_artifact_repo import LocalArtifactRepository
uri = sys.argv[1]
mlflow.set_tracking_uri(uri); mlflow.set_registry_uri(uri)
copied = [0]
original = LocalArtifactRepository._download_file
def counted(self, *a, **k):
    copied[0] += 1
    return original(self, *a, **k)
LocalArtifactRepository._download_file = counted
from thermocomp.base import signing
from thermocomp.apps.deploy.pyfunc import load_deployed
verified = []
checked = signing.verified_bytes
def kept(*a, **k):
    data = checked(*a, **k)
    verified.append(hashlib.sha256(data).hexdigest())
    return data
signing.verified_bytes = kept
def cpu():
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime
first = load_deployed({model!r})
files = copied[0]
times = []
for _ in range(int(sys.argv[2])):
    t = cpu(); load_deployed({model!r}); times.append(cpu() - t)
print(files, sorted(times)[len(times) // 2], verified[0])
"""


def replayed(path: Path) -> str:
    """SHA-256 of ``replay.json`` without its timing (``us_per_sample``): every number replayed."""
    found = json.loads(path.read_text())
    for row in found["targets"].values():
        row.pop("us_per_sample")
    return hashlib.sha256(json.dumps(found, sort_keys=True).encode()).hexdigest()


def children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def env_for(src: Path) -> dict:
    return {**os.environ, "PYTHONPATH": str(src), "MLFLOW_ENABLE_ARTIFACTS_PROGRESS_BAR": "false",
            "PYTHONHASHSEED": "0"}


def make_store(root: Path, extra: list[str]) -> str:
    uri = f"sqlite:///{root}/mlruns/mlflow.db"
    if not (root / "p").is_dir():
        code = SETUP.format(tests=str(HERE / "tests"), apps=str(HERE / "tests" / "apps"),
                            root=str(root), extra=extra)
        subprocess.run([PY, "-c", code], env=env_for(NEW_SRC), check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return uri


def load(src: Path, uri: str, repeats: int) -> tuple[int, float, str]:
    out = subprocess.run([PY, "-c", LOAD.format(model=MODEL), uri, str(repeats)], env=env_for(src),
                         check=True, capture_output=True, text=True).stdout.split()
    return int(out[0]), float(out[1]), out[2]


def command(src: Path, args: list[str]) -> float:
    before = children_cpu()
    subprocess.run([PY, "-m", "thermocomp", *args], env=env_for(src), check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return children_cpu() - before


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def serve(src: Path, uri: str) -> float:
    port = free_port()
    before = children_cpu()
    proc = subprocess.Popen([PY, "-m", "thermocomp", "serve", f"tracking_uri={uri}",
                             f"serve.port={port}"], env=env_for(src),
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        for _ in range(1200):
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{port}/ping", timeout=1) as r:
                    if r.status == 200:
                        break
            except OSError:
                time.sleep(0.05)
        else:
            raise RuntimeError("serve never answered /ping")
    finally:
        proc.send_signal(signal.SIGTERM)
        proc.wait(60)
    return children_cpu() - before


def main() -> None:
    old_src = Path(sys.argv[1]).resolve()
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    scratch = Path(sys.argv[3] if len(sys.argv) > 3 else "/tmp/download66-bench")
    stores = {"arx": (scratch / "plain", []), "auto": (scratch / "auto", ["model=auto", "plots=all"])}
    trees = {"old": old_src, "new": NEW_SRC}
    figures: dict = {}
    for store, (root, extra) in stores.items():
        uri = make_store(root, extra)
        data = root / "small"
        for i in range(repeats):
            for tree, src in (trees.items() if i % 2 == 0 else reversed(trees.items())):
                f = figures.setdefault((store, tree), {"load": [], "replay": [], "export": [],
                                                        "serve": [], "files": set(), "pickle": set(),
                                                        "replayed": set()})
                files, cpu, digest = load(src, uri, repeats)
                f["files"].add(files)
                f["pickle"].add(digest)
                f["load"].append(cpu)
                out = scratch / f"replay-{store}-{tree}-{i}"
                f["replay"].append(command(src, ["replay", f"replay.model={MODEL}",
                                                 f"data.path={data}", f"tracking_uri={uri}",
                                                 "track=false", "plots=none", f"out={out}"]))
                f["replayed"].add(replayed(out / "replay.json"))
                f["export"].append(command(src, ["export", f"export.model={MODEL}",
                                                 "export.format=json", f"tracking_uri={uri}",
                                                 f"out={scratch / f'export-{store}-{tree}-{i}'}"]))
                f["serve"].append(serve(src, uri))
    print(f"{'store':6} {'tree':4} {'files':>5} {'load ms':>8} {'replay s':>9} {'export s':>9} "
          f"{'serve s':>8}")
    for (store, tree), f in figures.items():
        med = {k: statistics.median(f[k]) for k in ("load", "replay", "export", "serve")}
        print(f"{store:6} {tree:4} {'/'.join(map(str, sorted(f['files']))):>5} "
              f"{1000 * med['load']:8.0f} {med['replay']:9.2f} {med['export']:9.2f} "
              f"{med['serve']:8.2f}   ranges: " + json.dumps(
                  {k: [round(min(f[k]), 3), round(max(f[k]), 3)] for k in med}))
    for store in stores:
        same_pickle = figures[(store, "old")]["pickle"] == figures[(store, "new")]["pickle"]
        same_replay = figures[(store, "old")]["replayed"] == figures[(store, "new")]["replayed"]
        print(f"{store}: signed pickle loaded identical {same_pickle} "
              f"({len(figures[(store, 'new')]['pickle'])} digest), replay.json identical {same_replay}")


if __name__ == "__main__":
    main()
