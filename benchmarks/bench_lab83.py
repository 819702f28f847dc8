"""A PLC status word read as one number or as its declared bits (lab83, ``data.bits``).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_lab83.py write ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_lab83.py matrix ROOT SEED

The record is bench_stranger80's jig borer (``benchmarks/jig80.py``; its TDMS files, 13 runs of
10 h, the last held out), whose PLC logs ``Status`` (uint16): 1 machine on, 2 spindle turning,
4 table indexing, 128 probe ready.  ``write``: its files, ``ROOT/jig<SEED>/`` (bench_stranger80's
``write``; seeds 8571-8580 only).  ``matrix``: ``thermocomp init`` twice on the folder, with no
key (``Status`` proposed a state, read as one number 129-135) and with the bits declared
(``data.bits={Status: {0: machine_on, 1: spindle_on, 2: table_indexing, 7: probe_ready}}``, the
word no input), then ``run model=<f>`` for f in mlr, hammerstein, auto on each config
(``track=false plots=none``, ``OMP_NUM_THREADS=1``); the test RMSE per target, number -> bits.
No test run chooses anything: the split is init's (the last run held out), only scored.

No bar: a reader feature (the user declares what the bits say; nothing is decoded undeclared).
What is measured: whether the models change with the bits declared, and ``init``'s saying.

Also (not a command here: tests/shell/test_lab83.py): a historian's long TEXT export's gaps.
Main never scanned its cells (the file is read through the grid's converted copy, so
``Cells.longest``'s "slowest tag" rule never met it): ``init`` proposed no
``data.max_gap_samples`` and its own read refused six Bad samples of a 10 s probe, "gap of 6
missing values (grid rows 101-106) is longer than data.max_gap_samples=0" (exit 2): too strict.
Now each tag's runs are counted on the read's own grid: 6 for the probe, 30 for one Bad sample
of a 300 s air tag, said "of 'MC07.Probe.Z_um' (from data row 114 of pi.csv)", the read then
accepting it.

Scored (2026-12-04; ``OMP_NUM_THREADS=1``, 2 cores shared with five other helpers; CPU user +
sys of each child ``run``, seed 8571's before the bench printed it)
-----------------------------------------------------------------------------------------------
``init`` (no key) on each draw: "'Status' holds 3 whole numbers (129, 131, 135), each a sum of
few powers of two (bits 0, 1, 2, 7 set): a PLC's status word? ... data.bits={Status: {0:
<name>, 1: <name>, 2: <name>, 7: <name>}} ... (not written ...)"; with the key declared it says
nothing and writes it.  Bit 0 (machine on) and bit 7 (probe ready) are 1 on every logged row,
dropped as constants: hammerstein reads ``S_spindle_on`` and ``S_table_indexing`` in place of
``S_Status`` (its other states ``S_Drehzahl``, ``S_W_Pinole``, ``S_X-Pos``, ``S_Y-Pos`` alike).

Test RMSE dX / dY / dZ (µm, the last run), number -> bits:

- 8571: mlr 3.923 / 2.645 / 1.696 unchanged (MLR reads no state); hammerstein 2.653 / 1.838 /
  1.443 -> 2.687 / 1.844 / 1.519 (+1.3 / +0.3 / +5.2 %); auto 2.344 / 2.395 / 1.696 -> 2.390 /
  2.398 / 1.696 (+2.0 / +0.1 / 0 %; the same blend weights both ways, its hammerstein's
  change only).
- 8572: mlr 5.497 / 2.876 / 4.519 unchanged; hammerstein 5.201 / 2.036 / 2.787 -> 5.253 /
  2.028 / 2.839 (+1.0 / -0.4 / +1.8 %); auto 4.800 / 2.768 / 4.100 -> 4.586 / 2.475 / 4.237
  (-4.5 / -10.6 / +3.4 %: its votes moved, hammerstein 0.20 -> 0.42 on dX, 0.08 -> 0.32 on dY).
- 8573: mlr 6.265 / 4.740 / 1.867 unchanged; hammerstein 4.076 / 2.684 / 2.000 -> 4.024 /
  2.310 / 1.530 (-1.3 / -13.9 / -23.5 %); auto 4.507 / 3.805 / 1.746 -> 4.256 / 3.369 / 1.746
  (-5.6 / -11.4 / 0 %).

CPU per ``run`` (s, 8572 / 8573, number -> bits): mlr 11 -> 10 / 9 -> 10, hammerstein 23 -> 20
/ 23 -> 25, auto 50 -> 35 / 31 -> 35: no cost seen.  Verdict (no bar): the bits change only
the state-reading families; on two draws of three a few % either way, on one hammerstein dY
/ dZ 14 / 24 % better.  The number here is nearly a sum of the bits already (129 + 2 spindle
+ 4 indexing), so a linear reading of it was not meaningless on this machine; a word whose
bits' weights do not follow 1 : 2 : 4 is where declaring them matters.  Nothing is decoded
undeclared.
"""
from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import run_commands  # noqa: E402

FAMILIES = ("mlr", "hammerstein", "auto")
BITS = {0: "machine_on", 1: "spindle_on", 2: "table_indexing", 7: "probe_ready"}


def write(root: str, seed: str) -> None:
    """bench_stranger80's files of seed ``seed``: ``ROOT/jig<SEED>/``."""
    from bench_stranger80 import write as stranger_write

    stranger_write(root, seed)


def _init(folder: Path, out: Path, keys: list[str]) -> str:
    cli = [sys.executable, "-m", "thermocomp"]
    done = subprocess.run([*cli, "init", f"data.path={folder}", f"out={out}", *keys],
                          capture_output=True, text=True, check=True)
    return done.stdout


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _states(run: Path) -> list[str]:
    """The state columns a fitted model reads (hammerstein's, auto's hammerstein)."""
    import joblib

    found: set = set()
    for est in joblib.load(run / "model.pkl").estimators_.values():
        for part in [est, *getattr(est, "candidates_", {}).values()] if hasattr(
                getattr(est, "candidates_", None), "values") else [est]:
            found |= {c for c in getattr(part, "state_columns_", None) or [] if c.startswith("S_")}
    return sorted(found)


def _weights(run: Path) -> str:
    """auto's blend per target (its validation's votes)."""
    import joblib

    return "; ".join(f"{t} " + ", ".join(f"{f} {w:.2f}" for f, w in est.weights_.items())
                     for t, est in joblib.load(run / "model.pkl").estimators_.items())


def matrix(root: str, seed: str) -> None:
    """init (number / bits) -> run per family; the test RMSE per target, number -> bits."""
    root_p = Path(root).resolve()
    folder = root_p / f"jig{seed}"
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    declared = [f"++data.bits.Status.{b}={n}" for b, n in BITS.items()]
    scores: dict = {}
    for kind, keys in (("number", []), ("bits", declared)):
        out = root_p / f"lab83-{kind}"
        said = _init(folder, out, keys)
        print(f"{kind}: init says of Status: "
              + ("; ".join(ln for ln in said.splitlines() if "status word" in ln) or "nothing"))
        common = [f"hydra.searchpath=[file://{out / 'conf'}]", f"data=jig{seed}", "track=false",
                  "plots=none"]
        for family in FAMILIES:
            run = out / family
            before = _children_cpu()
            done = subprocess.run([sys.executable, "-m", "thermocomp", "run", *common,
                                   f"model={family}", f"out={run}"], capture_output=True,
                                  text=True, env=env)
            if done.returncode:
                print(f"{kind} {family}: run exit {done.returncode}: {done.stderr[-400:]}")
                continue
            targets = json.loads((run / "metrics.json").read_text())["targets"]
            scores[kind, family] = {t: v["test"]["rmse"] for t, v in targets.items()}
            states = _states(run) if family != "auto" else _weights(run)
            print(f"{kind} {family} ({_children_cpu() - before:.0f} s CPU): "
                  + " / ".join(f"{t} {r:.3f}" for t, r in scores[kind, family].items())
                  + (f" ({states})" if states else ""), flush=True)
    for family in FAMILIES:
        if ("number", family) in scores and ("bits", family) in scores:
            a, b = scores["number", family], scores["bits", family]
            print(f"{family}: " + "; ".join(f"{t} {a[t]:.3f} -> {b[t]:.3f} ({b[t] / a[t] - 1:+.1%})"
                                            for t in a if t in b))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "matrix": matrix}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
