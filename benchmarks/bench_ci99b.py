"""CI time (issue 34; stop 99, ci99b): where the slowest non-C test modules spend, traced.

tests/durations.json (idle seconds per unit) put test_dvc_metrics (80 s), test_calibrate (59),
apps/test_deployed_as_scored44 (56) and test_monitor_cli (51) first after test_readme.  The
brief: profile them, cut what is exact (shared fixtures, in-process calls, smaller data where the
premise holds), BAR >= 30 % summed CPU of the modules touched (>= 15 % kept as exact below it).

Verdict: TRACED, no test or src change.  The structural cuts the brief lists are already made in
these modules (every fixture shared at module or session scope, every command in process through
``conftest.thermocomp``/``main`` but where the process is the point -- DVC's stage processes;
Hydra's composition cached, tests/hydra_cache.py; the DVC study shortened, stages untracked and
figure-free).  What is left is spread over many small costs, none of them 30 %:

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci99b.py cpu TREE OUT MODULE...   # each module alone: OUT/cpu.txt lines
    python benchmarks/bench_ci99b.py profile TREE OUT MODULE  # py-spy (40 Hz) of it: OUT/<stem>.txt
    python benchmarks/bench_ci99b.py shares OUT               # per profile: where its samples are
    python benchmarks/bench_ci99b.py wide RAW                 # a wide (volumetric) read and edit

``cpu``: ``/usr/bin/time`` of ``pytest -q -n 0 -p no:cacheprovider MODULE`` in TREE (user + sys of
pytest and the processes it waited for).  ``profile`` needs py-spy in the venv.  ``shares``: the
share of samples whose stack holds each frame of ``PARTS`` (inclusive: the parts overlap), and the
five test functions with the most.  ``wide``: CPU of ``read_dataset`` and ``calibrate_folder`` on a
volumetric dataset RAW (test_calibrate's ``raw``: LargeMillVolumetric 6 h + 4 h, seed 0; 1483
columns, 19 + 13 rows) and of test_calibrate's ``edit`` (pandas read + write of one file).

Measured (2026-12-06, 4fafc59a, 2 cores shared by up to 8 helpers, load 2-12; one run each)::

  CPU s user + sys, pytest -n 0 alone (with --durations; wall is load, not the module)
    test_calibrate 41.9 (34.1 + 7.7)     test_deployed_as_scored44 31.6 (29.5 + 2.1)
    test_monitor_cli 27.8 (26.8 + 0.9)   test_dvc_metrics 64.3 (56.4 + 7.9; with its dvc processes)
  test_dvc_metrics, wall under load 12: the fixture's two `dvc repro` 177 s, the sweep pipeline
    97 s, the changed parameter's repro 48 s, the six dvc show calls 4.6-13 s each

  py-spy shares (% of samples, inclusive)   calibrate  scored44  monitor_cli
    the CLI's main (in-process commands)       60.4      80.6       81.2
    Hydra compose (cached tree, values)        4.1       12.7        6.0
    deep copies, all                           4.8        8.9        7.8
    ... of them in Hydra's run_job (2/command) 4.0        6.1        6.3
    imports (first use of each library)        9.6       18.8       10.1
    read_dataset                               22.4       7.4        8.3
    pandas to_parquet (the tests' edits)       10.5        -          -
    calibrate_folder / Compensator.fit         38.8      15.3        4.2
    stream_campaign / simulate (monitor_cli)    -          -     15.3 / 14.7

  test_calibrate, per call on RAW (CPU s, quiet machine moments): read_dataset 0.24-0.34,
  calibrate_folder 0.30-0.39 (its read most of it), edit 0.18-0.21; 67 calibrate_folder calls and
  34 edits in the module.  The read is spread over 1483 columns: pyarrow's read 18.5 % of it,
  the role naming 17.4 %, to_pandas 12.4 %, gap repair 9.3 %, unit steps 7.9 %, value checks 6.8 %.
  One deep copy of a run's composed config (model=mlr, its hydra node in): 0.016 s CPU (20 copies).

Against the bar, what an exact cut would give: (1) test_calibrate's ``edit`` through the file's
own arrow schema, only the changed columns converted -- the same table (``Table.equals``, metadata
checked), 0.18-0.22 s against 0.18-0.19 s: nothing (to_pandas and the schema's pandas metadata
dominate, not the column conversion); (2) a smaller set-up (fewer balls or poses): its tests name
balls 1-11 ('numbered 1 to 11', B11), poses of S1-S3 and counts ('all 33 parameters ... (11 not
seen'), so their premises do not hold on it; (3) the read of a wide file made 2x faster in src
would be ~11 % of test_calibrate (read_dataset 22.4 %); (4) scored44's 24 cells are a run and a
replay each, already FAST and SMALL; its served fixture is one fit and one MLflow save and load.
No exact cut reaches 15 %, so nothing was changed.  The one lever shared by every in-process
module is Hydra's per-command cost (the compose of the values and run_job's two deep copies of the
whole config: 18.8 % of scored44, 12.3 % of monitor_cli, 8.1 % of test_calibrate); cutting
run_job's copies means a job runner of thermocomp's own in ``shell/cli._run_job`` (Hydra's
callbacks, logging, run folder and saved configs kept), a src change with a bar of its own, not a
test cut.
"""
from __future__ import annotations

import collections
import os
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import made_folder, run_commands  # noqa: E402

THREADS = {k: "1" for k in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")}
# frame (function, file) -> what the share names
PARTS = {
    "main cli.py": "the CLI's main",
    "compose overrides.py": "Hydra compose",
    "deepcopy ": "deep copies",
    "_find_and_load ": "imports",
    "read_dataset read.py": "read_dataset",
    "DataFrame.to_parquet frame.py": "pandas to_parquet",
    "calibrate_folder calibration.py": "calibrate_folder",
    "Compensator.fit compensator.py": "Compensator.fit",
    "stream_campaign report.py": "stream_campaign",
    "simulate simulate.py": "simulate",
}


def _pytest(tree: Path, module: str) -> list[str]:
    return [sys.executable, "-m", "pytest", "-q", "-n", "0", "-p", "no:cacheprovider", module]


def _env(tree: Path) -> dict:
    return {**os.environ, **THREADS, "PYTHONPATH": str(tree / "src")}


def cpu(tree: str, out: str, *modules: str) -> None:
    """Each module alone under ``nice``: a line ``module user sys wall status`` in OUT/cpu.txt."""
    root, folder = Path(tree).resolve(), made_folder(out)
    for module in modules:
        cmd = ["nice", "/usr/bin/time", "-f", "%U %S %e", *_pytest(root, module)]
        proc = subprocess.run(cmd, cwd=root, env=_env(root), capture_output=True, text=True)
        line = f"{module} {proc.stderr.strip().splitlines()[-1]} {proc.returncode}"
        with (folder / "cpu.txt").open("a") as f:
            print(line, file=f)
        print(line)


def profile(tree: str, out: str, module: str) -> None:
    """py-spy's raw samples (40 Hz) of the module's pytest: OUT/<module stem>.txt."""
    root, folder = Path(tree).resolve(), made_folder(out)
    spy = Path(sys.executable).parent / "py-spy"
    target = folder / f"{Path(module).stem}.txt"
    subprocess.run(["nice", str(spy), "record", "-r", "40", "-f", "raw", "-o", str(target), "--",
                    *_pytest(root, module)], cwd=root, env=_env(root), check=True,
                   capture_output=True)
    print(target)


def _frame(entry: str) -> str:
    """``function file`` of a py-spy frame ``function (path:line)``."""
    name, _, where = entry.partition(" (")
    return f"{name} {where.rsplit('/', 1)[-1].split(':')[0] if '/' in where else ''}"


def shares(out: str) -> None:
    """Per raw profile in OUT: the share of samples under each frame of PARTS, and per test."""
    for raw in sorted(Path(out).glob("*.txt")):
        if raw.name == "cpu.txt":
            continue
        total, parts, tests = 0, collections.Counter(), collections.Counter()
        for line in raw.read_text().splitlines():
            stack, _, n = line.rpartition(" ")
            frames = {_frame(f) for f in stack.split(";")}
            total += int(n)
            for key in PARTS:
                if any(f.startswith(key) for f in frames):
                    parts[key] += int(n)
            for f in frames:
                if f.startswith("test_"):
                    tests[f.split(" ")[0]] += int(n)
        print(f"{raw.stem}: {total} samples")
        for key, what in PARTS.items():
            if parts[key]:
                print(f"  {100 * parts[key] / total:5.1f} %  {what}")
        for name, n in tests.most_common(5):
            print(f"  {100 * n / total:5.1f} %  {name}")


def wide(raw: str) -> None:
    """CPU of a wide dataset's read, its calibration and one pandas edit of a file (3 times)."""
    import shutil
    import tempfile

    import pandas as pd

    from thermocomp.apps.volumetric.calibration import calibrate_folder
    from thermocomp.core import io

    root = Path(raw).resolve()
    io.read_dataset(root, {}, missing="keep_errors")          # the imports, once
    for _ in range(3):
        start = time.process_time()
        io.read_dataset(root, {}, missing="keep_errors")
        read = time.process_time() - start
        start = time.process_time()
        calibrate_folder(root, {})
        folder = time.process_time() - start
        with tempfile.TemporaryDirectory() as tmp:
            copy = Path(tmp) / "f.parquet"
            shutil.copy(root / "train_week.parquet", copy)
            start = time.process_time()
            pd.read_parquet(copy).to_parquet(copy, index=False)
            edit = time.process_time() - start
        print(f"read_dataset {read:.3f}  calibrate_folder {folder:.3f}  edit {edit:.3f}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"cpu": cpu, "profile": profile, "shares": shares, "wide": wide},
                        argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
