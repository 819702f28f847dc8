"""`dvc repro pipelines/volumetric/dvc.yaml` (the README's volumetric pipeline) in a scratch copy
of the project, the venv not on PATH: its four stage commands as committed, on shorter weeks and
a smaller Monte Carlo, without figures (the scratch copy's params files), then nothing to rerun.
The figures cost 60 % of the run stage (two per error parameter) and are checked where they
are drawn (test_volumetric_run, test_newcomer's design figures), not DVC's concern."""

import json
from pathlib import Path

import pytest

from conftest import copy_project, dvc

pytestmark = pytest.mark.slow
STAGES = ("simulate", "calibrate", "run", "design")
PIPELINE = "pipelines/volumetric/dvc.yaml"


def _shrink(path: Path, **values) -> None:
    text = path.read_text()
    for key, value in values.items():
        old = next(line for line in text.splitlines() if line.strip().startswith(f"{key}:"))
        indent = old[:len(old) - len(old.lstrip())]
        text = text.replace(old, f"{indent}{key}: {value}")
    path.write_text(text)


def test_the_volumetric_pipeline_runs_its_four_stages_then_nothing(tmp_path):
    dest, env = copy_project(tmp_path / "proj")
    _shrink(dest / "conf/sim/large_mill_volumetric.yaml", train_hours=30.0, test_hours=20.0)
    _shrink(dest / "conf/design/default.yaml", n_machines=4, grid="[6, 4, 4]")
    _shrink(dest / "conf/common.yaml", plots="none")
    proc = dvc("repro", PIPELINE, cwd=dest, env=env)
    log = proc.stdout + proc.stderr
    assert {s for s in STAGES if f"Running stage '{PIPELINE}:{s}'" in log} == set(STAGES), log
    reports = dest / "reports/volumetric_large_mill"
    calibration = json.loads((reports / "calibrate/calibration.json").read_text())
    assert calibration["roundtrip"]["n_parameters"] == len(calibration["parameters"]) > 0
    run = json.loads((reports / "run/metrics.json").read_text())["volumetric"]
    assert run["distance_error"]["rms_after"] < run["distance_error"]["rms_before"]
    assert set(run["parameters"]) == set(calibration["parameters"])
    assert json.loads((reports / "run/headline/volumetric.json").read_text())
    design = json.loads((reports / "design/design.json").read_text())
    assert design["n_machines"] == 4 and design["strategies"]
    proc = dvc("repro", PIPELINE, cwd=dest, env=env)
    again = proc.stdout + proc.stderr
    assert "Running stage" not in again and "up to date" in again
