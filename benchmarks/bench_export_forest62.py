"""An arx_rf model's forest to code: its size, the export's CPU and |C - replay| (exportrest62).

``sim=swiss_lathe_door`` (paper 004's lathe: a door, 80 h of training, a 24 h test run, one
sample a minute) is simulated, ``model=arx_rf`` fitted with its default forest (100 trees,
``min_samples_leaf`` 5) as ``thermocomp run`` fits it (``n_estimators`` may be given) and
exported as C and as ST with the pack of the test run; the C is built (gcc -O2) and run through
``check/check.sh``.  Printed: the forests' trees, nodes and depth, each file's size, each
export's CPU (user + sys of the child) and the check's largest |difference|.  Everything in a
scratch root.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_export_forest62.py [n_estimators]
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
from pathlib import Path

from compiled_stream import checked

ROOT = Path(os.environ.get("BENCH_ROOT", "/tmp/exportrest62-bench"))
REPO = Path(__file__).resolve().parents[1]
PY = str(REPO / ".venv" / "bin" / "python")
FAST = ["track=false", "plots=none", "eval.mutual_prediction=false", "eval.ati_baselines=false",
        "eval.iso10791_a3=false", "eval.validation=false"]


def thermocomp(*args: str) -> tuple[float, str]:
    """Run a command in a child process: ``(its CPU seconds, user + sys; its stderr)``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    env = {**os.environ, "PYTHONPATH": str(REPO / "src")}
    run = subprocess.run([PY, "-m", "thermocomp", *args], cwd=REPO, env=env, check=True,
                         capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), run.stderr


def main(trees: str | None) -> None:
    data, model = ROOT / "lathe", ROOT / "model"
    if not data.exists():
        thermocomp("simulate", "sim=swiss_lathe_door", f"data.path={data}", "track=false")
    forest = [f"model.estimator.forest.n_estimators={trees}"] if trees else []
    thermocomp("run", "model=arx_rf", f"data.path={data}", f"out={model}", *FAST, *forest)
    for fmt in ("c", "st"):
        out = ROOT / f"code-{fmt}"
        cpu, said = thermocomp("export", f"data.path={data}", f"export.model={model / 'model.pkl'}",
                               f"export.format={fmt}", f"out={out}", "track=false")
        line = next(ln for ln in said.splitlines() if "forest:" in ln)
        sizes = {p.name: p.stat().st_size for p in sorted(out.iterdir()) if p.is_file()
                 and p.suffix in (".c", ".h", ".st", ".json")}
        print(f"{fmt}: export {cpu:.2f} s CPU; {line.split('] ', 1)[-1]}")
        print("   " + ", ".join(f"{k} {v / 1024:,.0f} KB" for k, v in sizes.items()))
        if fmt != "c":
            continue
        print("   " + checked(out))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
