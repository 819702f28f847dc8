"""CPU of ``thermocomp diagnose ati=cmeans`` against plain ``diagnose`` (stop 59).

Usage::

    python benchmarks/bench_diagnose_speed59.py [--out DIR] [CASE ...]

Cases (seeds fixed before any run): ``climate16`` -- ``sim=climate_room`` with 16 runs
(``sim.generator.n_runs=16``, 14 train), target ``E_X`` (stop 58's measurement: 107.0 + 6.7 s
against 2.5 + 0.4 s); ``yearround`` -- ``sim=yearround_spindle`` (24 campaigns), every target.
Each is simulated into ``--out`` (default ``/tmp/diagspeed59-bench``), then diagnosed twice in
a child process, plain and with ``ati=cmeans`` (``track=false plots=none``); printed: the CPU
of each child (user + sys, from ``RUSAGE_CHILDREN``), the ratio, and the accepted effects.  The children
import the ``thermocomp`` this checkout's ``src`` holds, after any ``PYTHONPATH`` given (so
``PYTHONPATH=<old checkout>/src`` measures the code before).

Measured (2 shared cores; user + sys s; plain / ati=cmeans / ratio), the elbow's MLR folds
fitted on their rows (before: 09ad50a's ``src`` first on ``PYTHONPATH``) and from the campaigns'
QR factors (after, ``core/models/_campaign_ls.py``)::

    climate16   before  2.8 / 75.5 / 26.9x    after  2.7 / 13.3 / 4.9x
    yearround   before  2.9 / 69.6 / 23.6x    after  2.9 / 12.0 / 4.2x

(an earlier pair, with other jobs running: 2.7 / 86.7 and 3.0 / 73.9 before, 2.9 / 15.1 and
3.2 / 13.6 after.)  ``diagnosis.json`` of the ATI runs identical before and after (every
figure), of the plain runs within 2.3e-10 relative (their closed-form CV from row pieces); the
elbow's SM/SD of all 274 ATI fits of climate16 within 6.5e-11 relative, the same counts chosen.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PY = [sys.executable, "-m", "thermocomp"]
CASES = {  # name: (simulate overrides, diagnose overrides)
    "climate16": (["sim=climate_room", "sim.generator.n_runs=16"],
                  ["sim=climate_room", "diagnose.targets=[E_X]"]),
    "yearround": (["sim=yearround_spindle"], ["sim=yearround_spindle"]),
}


def _env() -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (env.get("PYTHONPATH"), str(ROOT / "src")) if p)
    return env


def run(args: list[str]) -> float:
    """Run ``thermocomp args`` in a child: its user + sys CPU seconds (exit on failure)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.run([*PY, *args], env=_env(), capture_output=True, text=True)
    if proc.returncode:
        sys.exit(f"thermocomp {' '.join(args)} failed:\n{proc.stderr[-3000:]}")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)   # the child is reaped: its CPU is in
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def accepted(path: Path) -> str:
    """The effects each target accepted, from ``diagnosis.json``."""
    d = json.loads((path / "diagnosis.json").read_text())
    per = {d["target"]: [s["effect"] for s in d["steps"] if s["effect"]]}
    per.update({t: list(v["accepted"]) for t, v in d["other_targets"].items()})
    return "; ".join(f"{t}: {', '.join(map(str, e)) or 'none'}" for t, e in per.items())


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("/tmp/diagspeed59-bench"))
    parser.add_argument("cases", nargs="*", default=list(CASES))
    opts = parser.parse_args(argv)
    for name in opts.cases:
        sim, diag = CASES[name]
        data = opts.out / name / "data"
        if not data.exists():
            run(["-q", "simulate", *sim, f"data.path={data}", "track=false"])
        cpu = {}
        for label, extra in (("plain", []), ("ati", ["ati=cmeans"])):
            out = opts.out / name / label
            cpu[label] = run(["-q", "diagnose", *diag, *extra, f"data.path={data}", f"out={out}",
                              "track=false", "plots=none"])
            print(f"{name} {label:5s} CPU {cpu[label]:6.1f} s   accepted: {accepted(out)}", flush=True)
        print(f"{name} diagnose ati=cmeans / plain CPU ratio: {cpu['ati'] / cpu['plain']:.1f}x "
              f"({cpu['ati']:.1f} / {cpu['plain']:.1f} s)", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
