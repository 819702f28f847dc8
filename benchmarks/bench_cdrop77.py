"""A broken wire in the exported C (cdrop77, issue 34): a monitored sensor's missing readings,
the served adaptive model against the compiled code with its sensor monitor.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_cdrop77.py dropouts [ROOT] [SEEDS]

For each seed (default 7736-7745) and dropout length (``10min``: 2 samples, ``2h``: 24 samples of
the default ``yearround_spindle``'s 300 s; the simulator's ``sensor_faults`` effect, ``kind=
dropout`` on ``T_motor2`` from the middle of every test campaign, empty cells), ``thermocomp
simulate`` into ``ROOT`` (default ``/tmp/cdrop77-bench``); MLR and lagbank fitted on the train
split and deployed adaptive as ``replay`` deploys it, exported as C with its monitor, compiled
``gcc -std=c99 -Wall -Wextra -Werror -O2``; every test campaign streamed through ``stream`` and
the served model (``stream_rows``).  Prints per record and target the test RMSE (µm, pooled over
the test campaigns) of the served adaptive model and of the C, the largest |C - served| over
every row, the rows where the code's monitor flagged a rule it does not hold (from there the two
may part), the conformance pack's rows kept of all and whether ``check/check.sh`` passes, and
how often ``stream`` said ``T_motor2`` excluded for a dropout and re-admitted.
Before cdrop77 the C refused the first missing row (``stream`` exit 2): printed as the row count
``stream`` reached without its monitor's dropout rule (the plain C, ``exported_files(monitor=
False)``, which refuses as the C did).

The bar (written before any scored run; the seeds 7736-7745 not used before): the C ports the
served monitor's dropout rule, it decides nothing of its own, so the bar is parity: on every
record (seed x length x model) the build compiles warning-free, ``stream`` streams every row of
every test campaign (exit 0), max |C - served| <= 1e-9 µm over every row before the code's
monitor first flags a rule not in the code, and the pack's ``check.sh`` passes (its planted
dropout copy among its campaigns).  A record that misses it is a failure of the port, reported
as such; the served monitor is as shipped (no rule of auto / diagnose / monitor changes).
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _ccode import built, deployed_on, rmse  # noqa: E402
from _cli import made_folder, run_commands, seed_list  # noqa: E402

SEEDS = "7736-7745"
LENGTHS = {"10min": 2, "2h": 24}         # samples of 300 s
MODELS = ("mlr", "lagbank")
SENSOR = "T_motor2"


def _streamed(binary: Path, frame: pd.DataFrame) -> tuple[np.ndarray, int, str]:
    """``(corrections, exit status, stderr)`` of ``binary`` fed ``frame`` as CSV."""
    text = frame.to_csv(index=False, float_format="%.17g", na_rep="")
    run = subprocess.run([str(binary)], input=text, text=True, capture_output=True)
    rows = [line.split(",") for line in run.stdout.splitlines()[1:]]
    return np.array(rows, dtype=float).reshape(len(rows), -1), run.returncode, run.stderr


def _dataset(root: Path, seed: int, length: str) -> Path:
    from thermocomp.shell.cli import main

    data = root / f"{length}-{seed}"
    fault = ("sim.generator.effects=[sensor_faults]",
             "sim.generator.effect_params.sensor_faults.kind=dropout",
             f"sim.generator.effect_params.sensor_faults.column={SENSOR}",
             f"sim.generator.effect_params.sensor_faults.duration_samples={LENGTHS[length]}")
    if not (data / "campaigns.csv").is_file():
        assert main(["-q", "simulate", *fault, f"seed={seed}", f"data.path={data}",
                     "track=false"]) == 0
    return data


def record(root: Path, seed: int, length: str, model: str) -> str:
    from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
    from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
    from thermocomp.apps.deploy.export.watch import NOT_IN_CODE
    from thermocomp.apps.deploy.report import stream_rows

    data = _dataset(root, seed, length)
    deployed, ds, test_ids = deployed_on(data, model)
    tests = {k: ds.campaigns[k].reset_index(drop=True) for k in test_ids}
    targets = deployed.targets_
    ss = state_space(deployed, monitor=True)
    cols = ["time", *ss.inputs]
    files, summary = conformance_pack(deployed, ss, tests)
    errors, served, code, worst, flagged, failed, before = [], [], [], 0.0, [], [], []
    said = {"dropout": 0, "re-admitted": 0}
    with tempfile.TemporaryDirectory(prefix="cdrop77-") as tmp:
        binary = built(Path(tmp) / "with", {**exported_files(deployed, "c"), **files})
        plain = built(Path(tmp) / "plain", exported_files(deployed, "c", monitor=False))
        check = subprocess.run(["sh", "check/check.sh"], cwd=Path(tmp) / "with",
                               capture_output=True, text=True)
        for k, df in tests.items():
            want = corrections(ss, stream_rows(deployed, df, k).y)
            got, status, stderr = _streamed(binary, df[cols])
            if status or len(got) != len(df):
                failed.append(f"{k}: exit {status}, {len(got)}/{len(df)} rows: {stderr[-200:]}")
                continue
            for what in said:        # the monitor's events stream.c says
                said[what] += sum(f"{SENSOR}: {what}" in line for line in stderr.splitlines())
            # the first row where the code's monitor flags a rule it does not hold
            sim = Simulator(ss)
            sim.reset()
            first = len(df)
            for i, (u, t) in enumerate(zip(df[ss.inputs].to_numpy(float), df["time"])):
                sim.step(u, t)
                if sim.watch.flags & NOT_IN_CODE or sim.refused:
                    first = i
                    break
            if first < len(df):
                flagged.append(f"{k}@{first + 1}")
            if first:
                worst = max(worst, float(np.max(np.abs(got[:first] - want[:first]))))
            errors.append(df[targets].to_numpy(float))
            served.append(want)
            code.append(got)
            before.append(len(_streamed(plain, df[cols])[0]))
    listed = [e for e in summary["campaigns"] if "planted" not in e]
    kept = sum(e["rows"] for e in listed)
    total = sum(len(df) for df in tests.values())
    plants = [f"{e['campaign'].split('.')[1]} {e['rows']} rows" for e in summary["campaigns"]
              if "planted" in e]
    ok = (not failed and worst <= 1e-9 and check.returncode == 0)
    lines = [f"{model} {length} s{seed}: {'PASS' if ok else 'FAIL'}  max|C - served| {worst:.2e} um"
             f" (before a flag); flags {', '.join(flagged) or 'none'}; pack rows {kept}/{total}, "
             f"check.sh exit {check.returncode}; planted {', '.join(plants)}; the plain C "
             f"streamed {sum(before)}/{total} rows; stream said {SENSOR} excluded for a dropout "
             f"{said['dropout']}x, re-admitted {said['re-admitted']}x"]
    lines += [f"  FAILED {f}" for f in failed]
    if served:
        for i, t in enumerate(targets):
            s, c = (rmse(errors, x)[i] for x in (served, code))
            lines.append(f"  {t}: served adaptive {s:.4f}  C with monitor {c:.4f}")
    return "\n".join(lines)


def dropouts(root: str = "/tmp/cdrop77-bench", seeds: str = SEEDS) -> None:
    folder = made_folder(root)
    for seed in seed_list(seeds):
        for length in LENGTHS:
            for model in MODELS:
                print(record(folder, seed, length, model), flush=True)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"dropouts": dropouts}, sys.argv[1:] if argv is None else argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
