"""A PLC status word (``data.bits``, lab83) deployed as scored: each deployed path fed the lab's
own rows, the word in them (bits85).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_bits85.py paths ROOT [SEEDS]     # SEEDS: 8931-8934 (bits85's)

``paths``: a small record, ``ROOT/runs/run<k>.csv``, one run per seed (360 rows of 10 s, the
last run held out by ``data.test_fraction=0.25``): a machine whose PLC logs ``Status`` = 128
(a ready flag, undeclared) + bit 0 machine on + bit 1 spindle turning + bit 2 coolant on; the
spindle heats, the coolant cools, ``Spindel`` / ``Ständer`` follow the heat, ``Bett`` a walk;
``dX`` the heat plus a direct spindle / coolant step.  Declared ``data.bits={Status: {0:
machine_on, 1: spindle_on, 2: coolant_on}}``, ``data.roles.state=[Status]``, ``model=
hammerstein`` (it reads the states), ``run`` into a new MLflow store, ``promote``d; then, each
a child process of ``python -m thermocomp`` (``OMP_NUM_THREADS=1``): ``rows`` (the held-out
run as the reader decodes it), the registered model's pyfunc ``predict`` fed ``rows``' rows
and the lab's own (the word), ``replay replay.model=models:/...`` with the key and without,
``monitor`` of run's ``model.pkl`` on the file and on stdin (``monitor.input=-``), ``export
export.format=c`` of the registered model, built (``cc``), ``./stream`` fed ``rows``' rows
and the lab's own.  What each path does with the word: decodes it (corrections compared with
the served model's on ``rows``' rows), refuses it (exit code, the refusal's words) or
mis-reads it silently.  No test split chooses anything: the split is the files' order.

No bar (a refusal made clear and a path made to decode, not a rule scored): what is measured is
each path's outcome, before (main) and after (this tree), and whether served = replay = C.

Scored (2026-12-04; main 03c2007d = before, fix/bits85 = after; seeds 8931-8934; 2 cores shared
with five other helpers; CPU user + sys of the whole ``paths``, children included)
-----------------------------------------------------------------------------------------------
The model: hammerstein reads ``S_machine_on``, ``S_spindle_on``, ``S_coolant_on`` (and the three
``T_``); ``run`` test RMSE E_dX 0.9928 µm (run3, 360 rows), identical before and after.

Each path fed run3, before (main) -> after (fix/bits85):

- ``rows`` (the reader decodes): the three bits as columns -> same.
- served (registered pyfunc ``predict``), ``rows``' rows: RMSE 0.9928 -> same.
- served, the lab's rows (``Status``): refused, MLflow dropped ``Status`` (no input of the
  signature) and the model said "input lacks column(s) ['S_machine_on', 'S_spindle_on',
  'S_coolant_on']", the word unnamed -> decoded as the reader does, max |C - served on rows'
  rows| 0 (bit-identical); a word 130.5 is refused naming the column and the block's row
  (tests/shell/test_bits85.py).
- replay of the registered model, the key given: exit 0, RMSE 0.9928 -> same.
- replay, the key not given (``Status`` read as one number): exit 2 "test campaign run3 lacks 3
  columns the deployed model reads: S_machine_on, S_spindle_on, S_coolant_on" -> the same and
  "(bits of the PLC status word 'Status' the model was fitted with: give data.bits={Status: {0:
  machine_on, 1: spindle_on, 2: coolant_on}})" (``export`` alike).
- monitor (run's model.pkl) on the file, on stdin (``monitor.input=-``, lab83 decodes): exit 0,
  RMSE 0.9928 each -> same.
- ``stream.c`` fed ``rows``' rows: max |C - served| 2.4e-13 µm, RMSE 0.9928 -> same.
- ``stream.c`` fed the lab's rows: exit 2 "the header (line 1: CSV naming the inputs as ...)
  lacks input column S_machine_on", the word unnamed -> exit 2 "the header (line 1) lacks input
  column S_machine_on, bit 0 of the PLC status word 'Status' (data.bits; column 5): this code
  does not decode the word; give each bit as a column of its own, as thermocomp rows writes
  them"; ``export`` says so ("the word alone: refused by name, exit 2").

No path mis-read the word silently, before or after: each either decoded it as training did or
refused.  Served = replay = monitor = C on the record: RMSE 0.9928 µm each (the run's), the C's
corrections the served model's to 2.4e-13 µm.  CPU of ``paths`` (children, s; this process
3.1-3.7 more): before 24.0, 20.6; after 26.6 (before the replay's key was said), 23.5, 19.9 (in
the order run: before, after, after, before, after): no cost seen.

The C: refused by name rather than decoded.  ``stream.c`` maps each header to one input
(``TC_LAB_NAMES``, a scale and an offset per column), its check pack and ``--state`` file
follow that map; a word is one header for several inputs, a second path through the driver,
while ``thermocomp rows`` already decodes it with the reader's own code (the check above), and a
controller's rows give its flags as columns of their own.  Verdict (no bar): KEPT -- the served
model decodes the word it was fitted on; replay / export without the key and the C fed the word
name what to do.
"""
from __future__ import annotations

import io
import json
import os
import resource
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import made_folder, run_commands, seed_list  # noqa: E402

BITS = {0: "machine_on", 1: "spindle_on", 2: "coolant_on"}
ROWS = 360


def write(folder: Path, seeds: list[int]) -> None:
    """One run per seed under ``folder`` (the docstring's machine)."""
    folder.mkdir(parents=True, exist_ok=True)
    n = ROWS
    for k, seed in enumerate(seeds):
        rng = np.random.default_rng(seed)
        on = ((np.arange(n) // 60) % 3 != 2).astype(int)
        spin = on * (rng.random(n // 20).repeat(20) < 0.6)
        cool = spin * (rng.random(n // 30).repeat(30) < 0.5)
        heat = np.zeros(n)
        for i in range(1, n):
            heat[i] = 0.97 * heat[i - 1] + 1.2 * spin[i] - 0.5 * cool[i] + 0.2 * on[i]
        pd.DataFrame({"Zeit [s]": np.arange(n) * 10.0,
                      "Spindel [°C]": (20 + heat / 8 + rng.normal(0, 0.02, n)).round(3),
                      "Bett [°C]": (20 + np.cumsum(rng.normal(0, 0.01, n))).round(3),
                      "Ständer [°C]": (20.5 + heat / 20 + rng.normal(0, 0.02, n)).round(3),
                      "Status": 128 + on + 2 * spin + 4 * cool,
                      "dX [um]": (2.5 * heat / 8 + 0.8 * spin - 0.6 * cool
                                  + rng.normal(0, 0.1, n)).round(3)}
                     ).to_csv(folder / f"run{k}.csv", index=False)


def _cli(*args: str, stdin: str | None = None) -> subprocess.CompletedProcess:
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    return subprocess.run([sys.executable, "-m", "thermocomp", *args], input=stdin,
                          capture_output=True, text=True, env=env)


def _said(done: subprocess.CompletedProcess) -> str:
    """A refusal's line (the last of stderr that says error or refuses)."""
    lines = [ln for ln in done.stderr.splitlines() if "error" in ln.lower() or "lacks" in ln]
    return (lines[-1] if lines else done.stderr.strip()[-300:])[:400]


def _residual(measured: np.ndarray, correction: np.ndarray) -> float:
    """The test RMSE of a stream's corrections (``C = -E`` predicted; its first row, the
    reference, scored as run scores it)."""
    return float(np.sqrt(np.nanmean((measured - measured[0] + correction) ** 2)))


def _rmse(report: Path, key: str) -> float:
    return json.loads(report.read_text())["targets"]["E_dX"][key]


def _served(uri: str, model_uri: str, frame: pd.DataFrame):
    import mlflow

    mlflow.set_tracking_uri(uri)
    try:
        return mlflow.pyfunc.load_model(model_uri).predict(frame, params={"reset": True}), ""
    except Exception as exc:  # noqa: BLE001 (the outcome measured)
        return None, f"{type(exc).__name__}: {str(exc)[:300]}"


def paths(root: str, seeds: str = "8931-8934") -> None:
    """Each deployed path fed the held-out run, its word decoded by ``rows`` or as logged."""
    root_p = made_folder(root)
    folder = root_p / "runs"
    write(folder, seed_list(seeds))
    test = folder / f"run{len(seed_list(seeds)) - 1}.csv"
    uri = f"sqlite:///{root_p / 'mlflow.db'}"
    data = [f"data.path={folder}", "data.roles.error=[dX*]", "data.roles.state=[Status]",
            "data.test_fraction=0.25", *(f"++data.bits.Status.{b}={n}" for b, n in BITS.items())]
    light = ["model=hammerstein", "plots=none", "eval.mutual_prediction=false",
             "eval.ati_baselines=false", "eval.iso10791_a3=false"]
    done = _cli("run", *data, *light, f"tracking_uri={uri}", f"out={root_p / 'run'}")
    assert done.returncode == 0, done.stderr[-2000:]
    run_rmse = json.loads((root_p / "run" / "metrics.json").read_text())["targets"]["E_dX"][
        "test"]["rmse"]
    import mlflow

    mlflow.set_tracking_uri(uri)
    run_id = mlflow.search_runs(experiment_names=["thermocomp"])["run_id"].iloc[0]
    done = _cli("promote", *data, *light, f"tracking_uri={uri}", f"promote.run_id={run_id}",
                f"out={root_p / 'promote'}")
    assert done.returncode == 0, done.stderr[-2000:]
    model_uri = json.loads((root_p / "promote" / "promote.json").read_text())["model_uri"]
    print(f"run: hammerstein test RMSE E_dX {run_rmse:.4f} µm; promoted {model_uri}")
    done = _cli("rows", *data, f"rows.campaigns=[{test.stem}]")
    rows = pd.read_csv(io.StringIO(done.stdout))
    lab = pd.read_csv(test).astype(float)
    print(f"rows: exit {done.returncode}, columns {', '.join(rows.columns)}")
    reference, said = _served(uri, model_uri, rows)
    assert reference is not None, said
    c_ref = reference["C_dX"].to_numpy(float)
    measured = lab["dX [um]"].to_numpy(float)
    print(f"served, rows' rows: corrections given (max |C_dX| {np.abs(c_ref).max():.3f} µm), "
          f"RMSE E_dX {_residual(measured, c_ref):.4f}")
    served, said = _served(uri, model_uri, lab)
    print("served, the lab's rows (Status): " + (
        f"decoded, max |C - served on rows| {np.abs(served['C_dX'].to_numpy() - c_ref).max():.2g}"
        if served is not None else f"refused, {said}"))
    for label, keys in (("with the key", data), ("without it", data[:4])):
        out = root_p / f"replay-{label.split()[0]}"
        done = _cli("replay", *keys, f"replay.model={model_uri}", f"tracking_uri={uri}",
                    f"out={out}")
        print(f"replay of the registered model, {label}: " + (
            f"exit 0, RMSE E_dX {_rmse(out / 'replay.json', 'rmse'):.4f}"
            if done.returncode == 0 else f"exit {done.returncode}, {_said(done)}"))
    for label, extra, stdin in (("the file", [], None),
                                ("stdin", ["monitor.input=-"], test.read_text())):
        out = root_p / f"monitor-{label.split()[-1]}"
        done = _cli("monitor", *data, f"monitor.model={root_p / 'run' / 'model.pkl'}",
                    "track=false", f"out={out}", *extra, stdin=stdin)
        print(f"monitor on {label}: " + (
            f"exit 0, RMSE E_dX {_rmse(out / 'monitor.json', 'rmse_fixed'):.4f}"
            if done.returncode == 0 else f"exit {done.returncode}, {_said(done)}"))
    c_dir = root_p / "c"
    done = _cli("export", *data, f"export.model={model_uri}", f"tracking_uri={uri}",
                "export.format=c", "export.check=false", f"out={c_dir}")
    print(f"export c: exit {done.returncode}; says: "
          + "; ".join(ln for ln in done.stderr.splitlines() if "data.bits" in ln))
    if shutil.which("cc") is None or done.returncode:
        print("no C build (no cc, or the export refused)")
        return
    subprocess.run(["cc", "compensator.c", "stream.c", "-lm", "-o", "stream"], cwd=c_dir,
                   check=True)
    for label, frame in (("rows' rows", rows), ("the lab's rows (Status)", lab)):
        fed = subprocess.run(["./stream"], cwd=c_dir, input=frame.to_csv(index=False),
                             capture_output=True, text=True)
        if fed.returncode == 0:
            c = pd.read_csv(io.StringIO(fed.stdout))["C_dX"].to_numpy(float)
            print(f"stream.c, {label}: exit 0, max |C - served on rows| "
                  f"{np.abs(c - c_ref).max():.2g} µm, RMSE E_dX {_residual(measured, c):.4f}")
        else:
            print(f"stream.c, {label}: exit {fed.returncode}, {fed.stderr.strip()[:400]}")
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    print(f"CPU s of the children: {usage.ru_utime + usage.ru_stime:.1f}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"paths": paths}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
