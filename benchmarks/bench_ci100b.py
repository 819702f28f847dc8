"""CI time margin (issue 34; stop 100, ci100b): where the docs-as-written, dvc, calibrate,
hostile, sweep/replay, volumetric, tracking and stranger modules spend their CPU; TRACED.

The project's CI ran stop 99's head in 935.98 s of pytest (over the 15-minute target).  This
bench measures the modules of task ci100b (tests/test_readme.py's pages, shell/test_dvc_metrics,
test_calibrate, test_monitor_cli, test_hostile_procs, test_hostile, test_sweep, test_replay,
test_opcua67, test_hostile_numeric, test_volumetric_run, test_tracking, test_stranger*) on
9bbbb214, to find what is computed twice.

Rule: none built (TRACED).  No src, test or docs change.
BAR (the brief's, written here before any after-measurement; none was made, since no rule was
built): the modules' summed CPU (user + sys incl. children, each module alone, ``-n 0``, ``nice``,
base and after paired back to back, 2 repetitions) down >= 25 %, every planted break caught;
kept below it only if exact and >= 12 %.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci100b.py cpu TREE TAG OUT SPEC...   # each spec alone: OUT/cpu.txt lines
    python benchmarks/bench_ci100b.py table OUT [BEFORE AFTER]    # per spec, the sum, the bar
    python benchmarks/bench_ci100b.py blocks OUT                  # each docs page block's CPU
    python benchmarks/bench_ci100b.py command [REPEAT]            # one small in-process command

``cpu``: ``/usr/bin/time`` of ``nice pytest -q -n 0 -p no:cacheprovider -m "not full"
--durations=0 tests/<SPEC>`` in TREE (a checkout; ``TAG`` names it: ``base``, ``after``); a SPEC
is a module path under tests/ with an optional ``::test[...]`` node (a docs page of test_readme).
Its pytest output (durations) goes to OUT/log/.  ``blocks``: the per-block lines of the
``readme_run.log`` files test_readme leaves under OUT's base folders.  ``command``: CPU of
three small in-process commands (test_hostile's dataset: an ingest, a refused run, a FAST run),
REPEAT times each after one warm-up, and what Hydra's per-command work takes of it: run_job's two
``copy.deepcopy`` (the task's config, the Hydra config), ``HydraConfig.set_config`` (twice a
command) and the composition (tests/hydra_cache.py on, as in the suite).

Measured (2026-12-06, base = 9bbbb214 as a git clone, 2 cores shared by 8 helpers, load 2-31;
CPU s user + sys incl. children, each module alone, one run; every module passed)::

  test_readme (9 tests, 7 pages)  148.5    test_sweep           38.4    test_volumetric_run  27.5
  shell/test_dvc_metrics           62.7    test_replay          32.0    test_tracking        22.1
  test_calibrate                   43.4    test_hostile         31.8    test_opcua67         16.2
  test_hostile_procs               34.5    test_hostile_numeric 27.7    19 test_stranger*   116.1
  test_monitor_cli                 29.6    sum over the 31 modules: 630.4 s

Where it goes:

- test_readme: the blocks' commands, each a process, are 133 of its 148.5 s (``blocks``):
  sweeps.md's sweep + compare + 2 promotes 25.0, its lathe simulate + replay 10.6;
  simulation.md's simulate + diagnose 16.0; diagnose.md 14.1 + 7.4; README's make run 9.1,
  fl_thermal run 6.7, export + cc 3.3, twin + connect 5.8; own-data.md 20.2 in 5 blocks;
  monitoring.md 7.5 + 5.7; the pages' PREPARE (simulate) 1.5 once; a fresh clone 0.5-0.8 each.
  No page runs another's command and none runs one twice: nothing is computed twice to share
  (the README's dataset already reaches the docs pages as a copy).
- test_dvc_metrics: the study's fixture (``dvc repro``, 7 stage processes) is 312 of its 557 s
  wall, the param rerun (3 stages) 89, the sweep pipeline (2 stage processes, 6 jobs) 79; a
  stage process pays the stack's imports (an untracked ``ingest`` on SHORT: 2.8 s CPU under
  ``-X importtime``; it
  imports sklearn and thermocomp.apps.volumetric.source), ``dvc version`` 0.56 s CPU.  The
  processes are the test's point (DVC as a user types it).
- test_calibrate: ``read_dataset`` of its 1483-column volumetric record 0.42 s CPU a read
  (cProfile: the parquet load ~50 %, the roles' naming ~21 %, the missing-value pass ~17 %);
  the residual-scatter test is 64 of the module's 465 s wall (14 %; 3 calibrations, a run).
- test_hostile (146 tests): 184 in-process commands, ``cli.main`` 23.1 of the process's 26.1 s
  CPU; in it Hydra's per-command work: run_job's two deep copies 3.3 s, ``set_config`` (twice a
  command, a masked copy each) 1.8 s, the composition 8.4 s (misses included) -- 13.5 s, 52 % of
  the process.  ``command`` (16:00, load ~30): an ingest 0.114-0.134 s CPU, a refused run
  0.096-0.098, a FAST run 0.146-0.165; deep copies 0.017-0.035, set_config 0.008-0.011, compose
  0.013-0.029 a command.  A pickle round trip of the default root config costs 0.0096 s against
  0.0167 for its deep copy.  test_hostile_numeric: 19 commands, ``cli.main`` 3.2 of 25.9 s.
- test_stranger*: 3.4-13.4 s each, of which ~1.7 s is pytest's start and collection
  (``--co`` of stranger47: 1.70 s CPU of its 3.91), paid per module only when run alone.

Against the bar: no rule built, nothing scored.  The cuts seen and why none was built:
(1) run_job's task-config copy as a pickle round trip (a tests/hydra_cache.py wrapper):
~0.007 s a command, ~1.3 s of test_hostile's 31.8 (-4 %); (2) a thermocomp run_job without
Hydra's two copies and second set_config: a src change under every command, at most the 5.1 s
of test_hostile (-16 %; 0.8 % of the 630 s; the other modules' in-process commands were not
counted); (3) the wide parquet read: ~11 % of test_calibrate at twice the speed (ci99b), ~0.8 %
of the sum; (4) the pages and DVC: their processes are the tests' point.  None reaches 12 % of
the 630 s; what was counted of (2) and (3) together is ~10 s (~1.6 %).
"""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import made_folder, run_commands  # noqa: E402
from cpu import cpu_seconds  # noqa: E402

THREADS = {k: "1" for k in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")}


def _key(spec: str) -> str:
    return spec.replace("/", "_").replace("::", "-").replace("[", "-").replace("]", "").replace(".", "_")


def cpu(tree: str, tag: str, out: str, *specs: str) -> None:
    """Each spec alone in ``tree``: ``TAG SPEC user sys wall result`` on OUT/cpu.txt; pytest's
    output (with its durations) on OUT/log/TAG-SPEC.txt."""
    folder, tree = made_folder(out), Path(tree).resolve()
    env = {**os.environ, **THREADS, "PYTHONPATH": str(tree / "src")}
    (folder / "log").mkdir(exist_ok=True)
    for spec in specs:
        base = folder / "bt" / f"{tag}-{_key(spec)}"
        subprocess.run(["rm", "-rf", str(base)], check=True)
        base.mkdir(parents=True)
        run = subprocess.run(["/usr/bin/time", "-f", "TIME %U %S %e", "nice", sys.executable, "-m",
                              "pytest", "-q", "-n", "0", "-p", "no:cacheprovider", "-m", "not full",
                              "--durations=0", f"--basetemp={base}", f"tests/{spec}"],
                             cwd=tree, env=env, capture_output=True, text=True)
        user, system, wall = next(line for line in run.stderr.splitlines()
                                  if line.startswith("TIME")).split()[1:]
        result = (run.stdout.strip().splitlines() or ["?"])[-1].replace(" ", "_")
        (folder / "log" / f"{tag}-{_key(spec)}.txt").write_text(run.stdout + run.stderr)
        line = f"{tag} {spec} {user} {system} {wall} {result}"
        print(line, flush=True)
        with open(folder / "cpu.txt", "a") as f:
            f.write(line + "\n")


def table(out: str, before: str = "base", after: str = "after", bar: float = 25.0) -> None:
    """Per spec the mean of the ``before`` and ``after`` CPU runs (user + sys; tags of ``cpu``),
    the sum over specs measured under both tags, and the bar (the sum down by ``bar`` %)."""
    bar = float(bar)
    seen: dict = {}
    for line in (Path(out) / "cpu.txt").read_text().splitlines():
        tag, spec, user, system = line.split()[:4]
        seen.setdefault((tag, spec), []).append(float(user) + float(system))
    specs = list(dict.fromkeys(s for (t, s) in seen if (before, s) in seen and (after, s) in seen))
    mean = {k: sum(v) / len(v) for k, v in seen.items()}
    for s in specs:
        b, a = mean[(before, s)], mean[(after, s)]
        runs = f"{len(seen[(before, s)])}/{len(seen[(after, s)])}"
        print(f"{s:60s} {b:6.1f} -> {a:6.1f}  {100 * (a / b - 1):+6.1f} %  ({runs} runs)")
    b, a = (sum(mean[(tag, s)] for s in specs) for tag in (before, after))
    cut = 100 * (1 - a / b) if b else 0.0
    print(f"sum {b:6.1f} -> {a:6.1f}  -{cut:.1f} % over {len(specs)} specs: "
          f"bar {'met' if cut >= bar else 'not met'} (>= {bar:g} %)")


def blocks(out: str) -> None:
    """Each docs page's blocks with their CPU, from the ``readme_run.log`` files test_readme
    writes (one per page, under OUT's pytest base folders)."""
    for log in sorted(Path(out).rglob("readme_run.log")):
        for line in log.read_text().splitlines():
            if line.startswith("--- ") and "CPU" in line:
                print(line[4:])


def command(repeat: str = "10") -> None:
    """CPU of one small in-process command (test_hostile's dataset) and what Hydra's per-command
    work takes of it: run_job's two deep copies, HydraConfig.set_config (twice a command) and
    the composition (tests/hydra_cache.py on, as in the suite)."""
    import contextlib
    import io
    import tempfile
    import time

    root = Path(__file__).resolve().parents[1]
    sys.path[:0] = [str(root / "tests"), str(root / "tests" / "shell")]
    import hydra.core.hydra_config as hydra_config
    import hydra.core.utils as hydra_utils

    import conftest
    from test_hostile import make_dataset
    from thermocomp.shell.cli import main
    from thermocomp.shell.config import overrides

    spent = dict.fromkeys(("deepcopy", "set_config", "compose"), 0.0)

    def timed(name, function):
        def call(*args, **kwargs):
            start = time.process_time()
            try:
                return function(*args, **kwargs)
            finally:
                spent[name] += time.process_time() - start
        return call

    class _Copy:          # run_job's module-level `copy`, its deepcopy timed
        deepcopy = staticmethod(timed("deepcopy", hydra_utils.copy.deepcopy))

    hydra_utils.copy = _Copy()
    hydra_config.HydraConfig.set_config = timed("set_config", hydra_config.HydraConfig.set_config)
    overrides.compose = timed("compose", overrides.compose)
    folder = Path(tempfile.mkdtemp(prefix="ci100b-"))
    ds = make_dataset(folder / "ds")
    cases = {"ingest": ["ingest", f"data.path={ds}", f"data.interim={folder / 'i'}", "track=false"],
             "run refused": ["run", f"data.path={ds}", f"out={folder / 'o'}", "track=false",
                             "data.resample_s=0.0001", *conftest.LIGHT],
             "run FAST": ["run", f"data.path={ds}", f"out={folder / 'o2'}", f"data.interim={folder / 'i2'}",
                          f"model_path={folder / 'm.pkl'}", *conftest.FAST]}
    n = int(repeat)
    for label, args in cases.items():
        for k in range(n + 1):                  # the first: imports, not measured
            if k == 1:
                spent.update(dict.fromkeys(spent, 0.0))
                start = cpu_seconds()
            with conftest.process_state(folder, {}), contextlib.redirect_stdout(io.StringIO()), \
                    contextlib.redirect_stderr(io.StringIO()):
                code = main(list(args))
        each = (cpu_seconds() - start) / n
        print(f"{label:12s} exit {code}: {each:.3f} s CPU a command; "
              + ", ".join(f"{k} {v / n:.3f}" for k, v in spent.items()))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"cpu": cpu, "table": table, "blocks": blocks, "command": command},
                        argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
