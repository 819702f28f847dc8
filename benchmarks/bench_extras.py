"""CPU time of ``thermocomp run`` on a lathe-sized record, split by phase (issue 34, item 5).

    .venv/bin/python benchmarks/bench_extras.py ROOT [--families mlr lagbank mlr+ati ...] [key=value ...]

``ROOT`` holds ``lathe43`` and its ``init`` config as ``benchmarks/bench_other_machine.py write
ROOT`` and ``thermocomp init ROOT/lathe43 data.max_gap_samples=2 out=ROOT/init`` leave them
(written here when missing): 43 runs x ~600 rows x 24 Pt100s, 10 s, two targets.  Each family
is run in a fresh process at the defaults (``plots=summary``, MLflow on, in a temp folder) with
the run's phase clock (``time (s): ...`` on stderr) counting CPU seconds of the process and its
reaped children (user + sys: the figure workers are counted when the run ends) instead of
wall seconds; the table is those phases, the total CPU, the wall time and the peak RSS of the
run's largest process (``ru_maxrss`` of the waited-for child).  ``mlr+ati`` is ``model=mlr
ati=cmeans``.

Measured 2026-11-30 (scale60; seed 0, load 1.3-4 on 2 shared cores), CPU s (user + sys) / peak
RSS, and the CPU ratio to ``mlr``'s; the families' code as at 3b634e7 (scale60's changes are in
the one-record path, which these campaigns do not take)::

    mlr 7.4 s / 410 MiB (1.00), pcr 7.5 / 421 (1.01), arx 8.5 / 418 (1.15),
    arx_rf 24.8 / 429 (3.35), lagbank 10.3 / 595 (1.39), hammerstein 13.6 / 762 (1.84),
    lstm 43.2 / 769 (5.84), auto 35.2 / 1038 (4.76), mlr+ati 11.0 / 444 (1.49)

(Measured again 2026-12-07 on de1b3055, paired with 6430c4be: ``bench_perf106.py``; lstm and
auto 44-46 % cheaper now, the others within 0-11 %.)

Every family fits in seconds: 7-43 s CPU, ~5 s of it start-up, reading and the figures.  The
largest ratios are the methods' own: ``lstm`` trains a network per target and fold (validation
19 s of its 43), ``auto`` fits every candidate's folds, ``arx_rf`` fits 100-tree forests
(cProfile: 67 of its run's 99 profiled s in scikit-learn's forest fit, 18 s of that building
each tree's estimator through ``get_params``/``inspect.signature``, scikit-learn's per-tree
overhead).

Measured 2026-11-29 (seed 0; 2 cores shared with three other sessions, load 3-13: the wall
column is mostly waiting; CPU s are user + sys).  ``other`` is scoring, ANOVA and the ATI
baselines; ``io`` reading, MLflow and writing; the rest of the total (~5 s) is start-up.
Before: main at 1193592; after: this branch (mutual prediction at most 24 single-campaign
models, ``eval.mutual_prediction_max_models``; a Hammerstein's single-campaign models fixed to
its choice; an ARX+RF forest predicting each distinct state once; an LSTM predicting campaigns
of like length in one batch), ``before / after``::

                          fit  validation       mutual     other   figures        io          CPU s     wall s
    mlr             0.2 / 0.3   0.2 / 0.4    1.0 / 0.7 0.6 / 0.7 3.0 / 3.2 4.1 / 4.7    14.4 / 16.4    23 / 57
    pcr             0.3 / 0.3   0.4 / 0.5    1.4 / 1.0 0.6 / 0.7 3.1 / 3.3 4.1 / 4.2    15.2 / 16.0    23 / 32
    arx             0.6 / 0.3   0.6 / 0.6    2.6 / 1.4 0.9 / 0.8 3.9 / 3.2 5.1 / 4.7    19.2 / 16.6    31 / 44
    arx_rf          3.9 / 3.7 12.7 / 13.7  33.1 / 18.0 2.4 / 2.7 3.1 / 3.4 4.5 / 4.7    66.0 / 52.1   130 / 78
    lagbank         1.7 / 1.5   3.5 / 3.7    4.7 / 3.1 1.0 / 1.0 3.1 / 3.2 4.9 / 4.2    24.7 / 22.4    53 / 76
    hammerstein     4.3 / 4.3 11.8 / 13.5   24.5 / 3.8 1.6 / 1.5 3.2 / 3.2 4.7 / 4.6    55.7 / 37.0   94 / 116
    lstm          17.5 / 12.8 65.4 / 51.5 101.1 / 22.8 3.8 / 1.8 3.2 / 2.4 4.9 / 4.6  206.4 / 105.6  657 / 162
    auto        124.3 / 113.8   0.0 / 0.0    5.8 / 2.4 9.0 / 8.9 2.9 / 2.4 6.3 / 4.4  159.6 / 141.4  325 / 388

``auto``'s validation reuses its candidates' out-of-fold predictions; its fit holds its LSTM
candidate's folds.  Phases this branch does not touch moved by the load alone (mlr's wall).
``run`` of ``lagbank`` over ``mlr`` (CPU): 1.72 / 1.37.  What is left is the validation score
(5 folds, each the whole fit with its own choices: ``model=auto``, ``compare`` and ``promote``
choose by it, so it is not cut) and, for ``arx_rf``, scikit-learn's per-tree cost of 100-tree
forests fitted on one smoothed state (24 models x 2 targets x 1-2 forests).
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from cpu import cpu_seconds  # noqa: E402

FAMILIES = ("mlr", "pcr", "arx", "arx_rf", "lagbank", "hammerstein", "lstm", "auto", "mlr+ati")
# a family name and the overrides it stands for beyond model=<name>
EXTRA = {"arx_rf": ["model.estimator.state_column=S_Drehzahl"], "mlr+ati": ["ati=cmeans"]}
PHASES = re.compile(r"time \(s\): [\d.]+ = (.*)$", re.M)
# what the run's phases are counted as in the table
COLUMNS = {"fit": ("fit",), "validation": ("validation",), "mutual": ("mutual_prediction",),
           "other extras": ("score", "anova", "ati"), "figures": ("figures",),
           "tracking/io": ("read", "log", "write")}


def child(argv: list[str]) -> int:
    """``thermocomp <argv>`` in this process, its phase clock counting CPU seconds."""
    from thermocomp.base import log
    from thermocomp.shell import cli

    def start(clock):
        clock.seconds, clock._last = {}, cpu_seconds(children=True)

    def lap(clock, name):
        now = cpu_seconds(children=True)
        clock.seconds[name] = clock.seconds.get(name, 0.0) + now - clock._last
        clock._last = now

    log.Clock.__init__, log.Clock.lap = start, lap   # the rest of the process keeps wall time
    return cli.main(argv)


def prepare(root: Path) -> None:
    if (root / "init" / "conf" / "data" / "lathe43.yaml").exists():
        return
    here = Path(__file__).resolve().parent
    subprocess.run([sys.executable, str(here / "bench_other_machine.py"), "write", str(root)], check=True)
    subprocess.run([sys.executable, "-m", "thermocomp", "init", str(root / "lathe43"),
                    "data.max_gap_samples=2", f"out={root}/init"], check=True, capture_output=True)


def run_family(root: Path, family: str, extra: list[str]) -> dict:
    with tempfile.TemporaryDirectory() as cwd, tempfile.TemporaryFile("w+") as err:
        args = ["run", f"hydra.searchpath=[file://{root}/init/conf]", "data=lathe43",
                f"model={family.split('+')[0]}", *EXTRA.get(family, []), *extra, f"out={cwd}/out"]
        t0 = time.perf_counter()
        child = subprocess.Popen([sys.executable, __file__, "--child", *args], cwd=cwd,
                                 stdout=subprocess.DEVNULL, stderr=err)
        # this child's own rusage: its CPU and the peak RSS of its largest process
        _, status, usage = os.wait4(child.pid, 0)
        wall = time.perf_counter() - t0
        err.seek(0)
        stderr = err.read()
    if os.waitstatus_to_exitcode(status) != 0:
        return {"family": family, "error": stderr.strip().splitlines()[-1]}
    cpu = usage.ru_utime + usage.ru_stime
    phases: dict[str, float] = {}
    for part in PHASES.findall(stderr)[-1].split(" + "):
        name, seconds = part.rsplit(" ", 1)
        phases[name] = phases.get(name, 0.0) + float(seconds)
    row = {"family": family, "cpu": cpu, "wall": wall, "rss": usage.ru_maxrss / 1024}
    for column, names in COLUMNS.items():
        row[column] = sum(phases.pop(n, 0.0) for n in names)
    row["tracking/io"] += sum(phases.values())  # any phase not named above (none so far)
    return row


def table(rows: list[dict]) -> str:
    head = ["family", *COLUMNS, "CPU s", "wall s", "peak MiB"]
    lines = ["  ".join(f"{h:>12}" for h in head)]
    for r in rows:
        if "error" in r:
            lines.append(f"{r['family']:>12}  {r['error']}")
            continue
        values = [r[c] for c in COLUMNS] + [r["cpu"], r["wall"], r["rss"]]
        lines.append(f"{r['family']:>12}  " + "  ".join(f"{v:12.1f}" for v in values))
    return "\n".join(lines)


def main(argv=None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv[:1] == ["--child"]:
        return child(argv[1:])
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("root")
    parser.add_argument("--families", nargs="+", default=list(FAMILIES))
    parser.add_argument("overrides", nargs="*", help="key=value for every run")
    args = parser.parse_args(argv)
    root = Path(args.root).resolve()
    prepare(root)
    print(f"load average: {' '.join(f'{v:.2f}' for v in os.getloadavg())}", flush=True)
    rows = []
    for family in args.families:
        rows.append(run_family(root, family, args.overrides))
        print(table(rows[-1:]), flush=True)
    print(table(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
