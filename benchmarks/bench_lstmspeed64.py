"""``model=lstm``'s CPU and test accuracy per record, before and after lstmspeed64, three seeds.

    .venv/bin/python benchmarks/bench_lstmspeed64.py DIR [--before REV] [--seeds 0 1 2]
                                                        [--records fl90 fl60 door lathe grinder]

``DIR`` holds the records (written when missing): ``lathe`` the lathe-sized set of issue 34
(``bench_extras.py``'s ``lathe43``: 43 runs x ~600 rows x 24 Pt100s), ``grinder`` the probe
grinder's joined train weeks (``bench_probe61.py``, seed 6131), ``door`` ``swiss_lathe_door``
(its default seed), ``fl90`` / ``fl60`` the shipped ``fl_thermal`` record on its 90/10 split and on
its authors' 60/20/20 (``split_order=[train,test,val]``).  Each record and seed is run once per
code (``thermocomp run model=lstm seed=S plots=none track=false``, its own process: CPU user +
sys of that process), the code of ``--before`` (``git archive REV src conf``) and this
checkout's; ``model=mlr`` once (seed 0) with this checkout for the ratio.  Prints CPU and test
MAE / RMSE per target; writes ``DIR/lstmspeed64.json``.

Where an lstm run's time went (cProfile of e67059c3 on ``lathe``, 105 s profiled): 60 lstm fits
(2 targets x the fit, 5 validation folds, 24 mutual-prediction models), 82 s; in them 24 s
torch's LSTM forward (oneDNN), 17 s backward, 12 s Adam, 7.5 s gradient clipping, 11 s the
per-epoch pass over whole campaigns (carried states and validation loss), ~4 s Python.  A step
costs nearly as much for 4 pieces as for 16 (the recurrence is sequential in time: a forward of
4 x 128 samples 0.4-0.8 ms, of 31 x 128 2.3 ms), so the cost is the number of Adam steps.
``np.linalg.lstsq`` of the skip path spun a second OpenBLAS thread: 0.29 s CPU per call on the
lathe's ~25,000 x 25 matrix, 0.02 s on one thread.  Cutting the pieces once per fit, the state
batches gathered at once and Adam's ``foreach`` changed nothing measurable (weights and
predictions of 12 replayed lathe fits identical, CPU within the load's noise) and are kept
(identical).

Measured 2026-12-01 (2 shared cores, load 4-6; each run once per seed), CPU s before (e67059c3)
-> after, mean of seeds 0-2, and test MAE (um, mean over targets) per seed: lathe 45.4 -> 19.6
(0.668 / 0.678 / 0.679 -> 0.665 / 0.669 / 0.686), fl90 71.4 -> 33.1 (2.75 / 3.13 / 3.19 ->
2.65 / 3.41 / 3.06), fl60 29.0 -> 15.3 (8.13 / 9.32 / 8.15 -> 9.07 / 9.81 / 8.71), door 12.8 ->
8.9 (0.901 / 0.904 / 0.913 -> 0.908 / 0.903 / 0.905), grinder 164.8 -> 101.7 (0.780 / 0.764 /
0.758 -> 0.759 / 0.770 / 0.758); mlr 3.2 / 2.1 / 2.0 / 2.1 / 3.0 s (docs/measured/models.md).  These
figures were taken with an equivalent shell loop over the same commands; this script repeats it.

lstmbatch64 (refused): ``--before b7fc1b0d --label lstmbatch64 --json lstmbatch64.json --no-mlr``
from 2d8c6dcf (``batch_size: auto``, 16 pieces a step unless an epoch would have < 10 steps, never
< 4, the rate 6e-3 x sqrt(batch/16)), fl60 fl90 in one process and lathe door in another, CPU s
mean of seeds 0-2 today -> auto and test MAE per seed: fl60 16.6 -> 20.6 (9.073 / 9.807 / 8.705 ->
9.070 / 9.728 / 8.217), fl90 36.6 -> 42.6 (2.649 / 3.405 / 3.063 -> 2.769 / 3.093 / 3.308), lathe
21.9 -> 23.3 (identical fits and MAE), door 9.5 -> 10.9 (0.908 / 0.903 / 0.905 -> 0.901 / 0.904 /
0.913); docs/measured/models.md.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from bench_autocpu63 import code_of  # noqa: E402  (a revision's src unpacked once)

REPO = Path(__file__).resolve().parents[1]
RECORDS = ("fl90", "fl60", "door", "lathe", "grinder")


def prepare(root: Path, records=RECORDS) -> None:
    """Write the records of ``records`` that ``root`` lacks."""
    py, env = [sys.executable], dict(os.environ, PYTHONPATH=str(REPO / "src"))
    here = REPO / "benchmarks"
    steps = []
    sys.path.insert(0, str(here))
    from bench_extras import prepare as lathe  # the lathe43 files and their init config
    if "lathe" in records:
        lathe(root / "lathe")
    if "grinder" in records and not (root / "init-grinder").exists():
        steps += [[*py, str(here / "bench_probe61.py"), "write", str(root)],
                  [*py, str(here / "bench_probe61.py"), "init", str(root)]]
    if "door" in records and not (root / "swiss_lathe_door").exists():
        steps.append([*py, "-m", "thermocomp", "simulate", "sim=swiss_lathe_door",
                      f"data.path={root / 'swiss_lathe_door'}", "track=false"])
    root.mkdir(parents=True, exist_ok=True)
    for step in steps:
        subprocess.run(step, cwd=root, env=env, check=True, capture_output=True)


def data_args(root: Path, record: str) -> list[str]:
    fl = ["data=fl_thermal"]
    return {"lathe": [f"hydra.searchpath=[file://{root}/lathe/init/conf]", "data=lathe43"],
            "grinder": [f"hydra.searchpath=[file://{root}/init-grinder/conf]", "data=grinder"],
            "door": [f"data.path={root / 'swiss_lathe_door'}"],
            "fl90": fl,
            "fl60": [*fl, "data.split_order=[train,test,val]", "data.test_fraction=0.2",
                     "data.val_fraction=0.2"]}[record]


def run(root: Path, record: str, src: Path, label: str, seed: int, model: str = "lstm") -> dict:
    """One ``thermocomp run``: its CPU s (user + sys) and test MAE / RMSE per target."""
    out = root / "out" / f"{label}-{model}-{record}-s{seed}"
    before = os.times()
    done = subprocess.run([sys.executable, "-m", "thermocomp", "run", *data_args(root, record),
                           f"model={model}", f"seed={seed}", "track=false", "plots=none",
                           f"out={out}"], env=dict(os.environ, PYTHONPATH=str(src)),
                          cwd=src.parent, capture_output=True, text=True)
    after = os.times()
    row = {"record": record, "code": label, "model": model, "seed": seed,
           "cpu_s": round(after.children_user - before.children_user
                          + after.children_system - before.children_system, 2)}
    if done.returncode:
        return {**row, "error": done.stderr.strip().splitlines()[-1]}
    targets = json.loads((out / "metrics.json").read_text())["targets"]
    return {**row, "test": {t: {k: v["test"][k] for k in ("mae", "rmse")} for t, v in targets.items()}}


def summary(rows: list[dict]) -> str:
    lines = []
    for record in dict.fromkeys(r["record"] for r in rows):
        mine = [r for r in rows if r["record"] == record and "test" in r]
        mlr = [r["cpu_s"] for r in mine if r["model"] == "mlr"]
        lines.append(f"{record}" + (f"  (mlr CPU {mlr[0]:.1f} s)" if mlr else ""))
        for code in dict.fromkeys(r["code"] for r in mine if r["model"] == "lstm"):
            runs = [r for r in mine if r["code"] == code and r["model"] == "lstm"]
            cpu = statistics.mean(r["cpu_s"] for r in runs)
            ratio = f", {cpu / mlr[0]:.2f} x mlr" if mlr else ""
            each = " / ".join(f"{r['cpu_s']:.1f}" for r in runs)
            lines.append(f"  {code}: CPU {each} s (mean {cpu:.1f}{ratio})")
            for t in runs[0]["test"]:
                mae = " / ".join(f"{r['test'][t]['mae']:.3f}" for r in runs)
                rmse = " / ".join(f"{r['test'][t]['rmse']:.3f}" for r in runs)
                lines.append(f"    {t}: MAE {mae}  RMSE {rmse}")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("root")
    parser.add_argument("--before", default="e67059c3")
    parser.add_argument("--seeds", nargs="+", type=int, default=[0, 1, 2])
    parser.add_argument("--records", nargs="+", default=list(RECORDS))
    parser.add_argument("--label", default="lstmspeed64", help="this checkout's name in the rows")
    parser.add_argument("--json", default="lstmspeed64.json", help="file name of the rows in DIR")
    parser.add_argument("--no-mlr", action="store_true", help="skip the mlr runs (the ratio)")
    args = parser.parse_args(argv)
    root = Path(args.root).resolve()
    prepare(root, args.records)
    codes = {args.before: code_of(root, args.before), args.label: REPO / "src"}
    rows = []
    for record in args.records:
        if not args.no_mlr:
            rows.append(run(root, record, REPO / "src", args.label, 0, model="mlr"))
        for label, src in codes.items():
            for seed in args.seeds:
                rows.append(run(root, record, src, label, seed))
                print(json.dumps(rows[-1]), flush=True)
    (root / args.json).write_text(json.dumps(rows, indent=1))
    print(summary(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
