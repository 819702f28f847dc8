"""`thermocomp connect`: the server's clock set while the machine ran, told from a pause (connect71).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_clockset71.py measure DIR

The record is ``tests/shell/test_opcua67.py``'s small lathe (six programs of 50 rows a minute,
four sensors, errors lagging the spindle's heating), each model (``lagbank``, ``mlr``) fitted on
its four train programs; its two test programs are served, one NC program each, by
``tests/shell/vendor_machine.py``'s server (offsets as Doubles: as computed), ``connect`` in
this process with its own clock driven by the machine's time (the test's ``client_clock``: the
machine's time at the server's clock it read last), so that the server's clock runs at the
client's as a real control's does.  Runs per model:

- ``forward``: the server's clock set forward 3 h at the first program's row 20 (the machine ran
  on), the machine off 3 h at the second's row 30 (both clocks on);
- ``back``: the server's clock set back 1 h at the first program's row 20, the same pause;
- ``simulated``: no client clock (the real one: the lockstep server runs its clock ~1000s of
  times faster), the server's clock stepped 3 h at the first program's row 20.

The rule (``src/thermocomp/apps/machine/clockset.py``) and its bar, written before this bench
ran (the ``forward`` figures of the test's scenario were measured first by hand): a clock set
where the server's clock runs at the client's gives every offset the run's without the set
(``replay`` of the rows with the machine's own times: the largest difference <= 1e-12 µm), the
pause and the ``simulated`` run are kept as before (offsets ``replay``'s with the step in the
time), samples missed 0.  Measured per run and target: the largest |offset − replay of the rows
without the set| and |offset − replay with the step kept| per program, the RMS of (the error
from the program's first sample − the offset) over the first program's rows 20-49, the clock
events.  Run it on stop 70's code (its src first on PYTHONPATH) for the "before" figures.
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "tests" / "shell"), str(ROOT / "tests")]

from _cli import run_commands  # noqa: E402

SET_ROW, PAUSE_ROW, HOURS = 20, 30, 3600.0


def _scenario(programs: dict, run: str) -> tuple[dict, dict, tuple[int, float]]:
    """(the frames the machine runs, those of the set kept as a step, the server's clock set)."""
    frames = {p: df.copy() for p, df in programs.items()}
    first, second = list(frames)
    if run != "simulated":
        frames[second].loc[PAUSE_ROW:, "time"] += 3 * HOURS      # the machine off: both clocks
    step = -HOURS if run == "back" else 3 * HOURS
    kept = {p: df.copy() for p, df in frames.items()}
    kept[first].loc[SET_ROW:, "time"] += step
    return frames, kept, (SET_ROW, step)


def _one(t, data: Path, pkl: Path, out: Path, run: str) -> dict:
    from _pytest.monkeypatch import MonkeyPatch

    from conftest import free_port
    from vendor_machine import VendorMachine, as_published, connect_nodes

    frames, kept, clock_set = _scenario(t.programs(data), run)
    served = kept if run == "simulated" else frames           # simulated: the step in the record
    machine = VendorMachine(served, free_port(), offsets=t.DOUBLES,
                            clock_set=None if run == "simulated" else clock_set)
    patch = MonkeyPatch()
    if run != "simulated":
        t.client_clock(patch, machine)
    try:
        code, link = t.run_connect(data, pkl, out, machine, nodes=connect_nodes(offsets=t.DOUBLES))
    finally:
        patch.undo()
    held = np.vstack(machine.served.offsets)
    without = t.corrections(data, pkl, as_published(frames))
    with_step = t.corrections(data, pkl, as_published(kept))
    first = frames[next(iter(frames))]
    error = (first[["E_X", "E_Z"]] - first[["E_X", "E_Z"]].iloc[0]).to_numpy()
    n = len(first)

    def largest(ref):
        d = np.abs(held - ref)
        return {"first": d[:n].max(0).round(12).tolist(), "second": d[n:].max(0).round(12).tolist()}

    return {"code": code, "samples": link["samples"], "missed": link["samples_missed"],
            "vs_without_set": largest(without), "vs_step_kept": largest(with_step),
            "rms_rows_20_49": np.sqrt(np.mean((error - held[:n])[SET_ROW:] ** 2, 0)).round(4).tolist(),
            "rms_without_set": np.sqrt(np.mean((error - without[:n])[SET_ROW:] ** 2, 0)).round(4).tolist(),
            "events": [(e["event"], e["sample"], e.get("step_s"), e["detail"])
                       for e in link["events"] if e["event"].startswith("clock")]}


def lathe_models(root: Path):
    """``(test_opcua67, the record's folder, {model: model.pkl})``: the small lathe record and
    ``lagbank`` and ``mlr`` fitted on its train programs, under ``root`` (made once)."""
    import test_opcua67 as t
    from thermocomp.shell.cli import main

    root.mkdir(parents=True, exist_ok=True)
    data = root / "data"
    if not (data / "campaigns.csv").is_file():
        t.record(data)
    pkls = {}
    for model in ("lagbank", "mlr"):
        pkls[model] = pkl = root / model / "model.pkl"
        if not pkl.is_file():
            assert main(["run", f"data.path={data}", f"out={pkl.parent}", f"model_path={pkl}",
                         *t.FAST, f"model={model}", "eval.validation=false",
                         "eval.mutual_prediction=false"]) == 0
    return t, data, pkls


def measure(where: str) -> None:
    root = Path(where)
    t, data, pkls = lathe_models(root)
    results = {}
    for model, pkl in pkls.items():
        for run in ("forward", "back", "simulated"):
            out = Path(tempfile.mkdtemp(prefix=f"{model}-{run}-", dir=root))
            results[f"{model} {run}"] = _one(t, data, pkl, out, run)
            print(json.dumps({f"{model} {run}": results[f"{model} {run}"]}), flush=True)
    (root / "bench_clockset71.json").write_text(json.dumps(results, indent=1))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"measure": measure}, argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
