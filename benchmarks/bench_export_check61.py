"""The conformance pack on a measured record: its size, its CPU, and how far builds part from it
(feed61).

The vendored spindle record (``data=fl_thermal``: one CSV of 11,115 samples, 16 temperatures and
the spindle speed, five error channels) is fitted per family (``mlr``, ``lagbank``,
``hammerstein``, ``auto``) as ``thermocomp run`` fits it and exported as a lab exports it
(``export.format=c``, the default deployment: adaptive, guard on), the pack of the test split
and of the whole record (``export.campaigns``: both campaigns, 11,115 rows).  Each pack is then
run through ``stream --check`` of several builds: gcc ``-O0``, ``-O2``, ``-O3 -ffast-math``, and
a float32 build (every ``double`` of the three files made ``float``), the largest
``|C - expected|`` of each over every row and target read from the outputs.  Everything in a
scratch root.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_export_check61.py [family ...]
"""

from __future__ import annotations

import io
import json
import os
import re
import resource
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(os.environ.get("BENCH_ROOT", "/tmp/feed61-bench"))
REPO = Path(__file__).resolve().parents[1]
PY = str(REPO / ".venv" / "bin" / "python")
FAST = ["track=false", "plots=none", "eval.mutual_prediction=false", "eval.ati_baselines=false",
        "eval.iso10791_a3=false", "eval.validation=false"]
FAMILIES = ("mlr", "lagbank", "hammerstein", "auto")
# auto's exportable candidates: on this record its default set blends an LSTM (not in the code)
CANDIDATES = {"auto": ["model.candidates=[mlr,pcr,arx,lagbank,hammerstein]"]}
BUILDS = {"gcc -O0": ["-O0"], "gcc -O2": ["-O2"], "gcc -O3 -ffast-math": ["-O3", "-ffast-math"],
          "float32 -O2": ["-O2"]}


def thermocomp(*args: str) -> float:
    """Run a command in a child process; its CPU seconds (user + sys)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    env = {**os.environ, "PYTHONPATH": str(REPO / "src")}
    subprocess.run([PY, "-m", "thermocomp", *args], cwd=REPO, env=env, check=True,
                   capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def build(code: Path, name: str) -> Path:
    """``stream`` of ``code`` built as ``name`` says, in a folder of its own."""
    folder = ROOT / "builds" / f"{code.name}-{re.sub(r'[^a-z0-9]+', '_', name)}"
    folder.mkdir(parents=True, exist_ok=True)
    for f in ("compensator.h", "compensator.c", "stream.c"):
        text = (code / f).read_text()
        if name.startswith("float32"):
            text = re.sub(r"\bdouble\b", "float", text)
        (folder / f).write_text(text)
    subprocess.run(["gcc", "-std=c99", *BUILDS[name], "compensator.c", "stream.c", "-lm", "-o",
                    "stream"], cwd=folder, check=True, capture_output=True)
    return folder / "stream"


def deviation(binary: Path, pack: Path) -> float:
    """Largest |C - expected| over every campaign of ``pack`` (its rows streamed by ``binary``)."""
    worst = 0.0
    for entry in json.loads((pack / "check.json").read_text())["campaigns"]:
        if not entry["rows"]:
            continue
        folder = pack.parent / entry["folder"]
        run = subprocess.run([str(binary)], stdin=open(folder / "rows.csv", "rb"),
                             capture_output=True, check=True)
        got = pd.read_csv(io.BytesIO(run.stdout)).to_numpy(float)
        want = pd.read_csv(folder / "expected.csv").to_numpy(float)
        worst = max(worst, float(np.abs(got - want).max()))
    return worst


def size(pack: Path) -> int:
    return sum(p.stat().st_size for p in pack.rglob("*") if p.is_file())


def main(families) -> None:
    ROOT.mkdir(parents=True, exist_ok=True)
    for family in families:
        run = ROOT / "runs" / family
        fit = thermocomp("run", "data=fl_thermal", f"model={family}", *CANDIDATES.get(family, []),
                         *FAST, f"out={run}")
        for what, extra in (("test split", []),
                            ("whole record", ["export.campaigns=[spindle_test_train,spindle_test_test]"])):
            code = ROOT / "code" / f"{family}-{'test' if not extra else 'all'}"
            cpu = thermocomp("export", "data=fl_thermal", "export.format=c", "track=false",
                             f"export.model={run / 'model.pkl'}", *extra, f"out={code}")
            pack = code / "check"
            listed = json.loads((pack / "check.json").read_text())["campaigns"]
            rows = sum(e["rows"] for e in listed)
            cuts = [f"{e['campaign']}@{e['cut']['row']}" for e in listed if e["cut"]]
            laws = json.loads((code / "compensator.json").read_text())["provenance"].get("laws")
            line = (f"{family:<12} {what:<13} fit {fit:6.1f} s, export+pack {cpu:6.1f} s CPU, "
                    f"{rows:6d} rows, pack {size(pack) / 1e6:6.2f} MB"
                    + (f", cut {cuts}" if cuts else "") + (f", kept {laws}" if laws else ""))
            print(line, flush=True)
            for name in BUILDS:
                print(f"    {name:<22} max|C - expected| = {deviation(build(code, name), pack):.3g} um",
                      flush=True)


if __name__ == "__main__":
    main(sys.argv[1:] or FAMILIES)
