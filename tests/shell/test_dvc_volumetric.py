"""`dvc repro pipelines/volumetric/dvc.yaml` (the README's volumetric pipeline) in a scratch copy
of the project, the venv not on PATH: its four stage commands as committed, on shorter weeks and
a smaller Monte Carlo in one process, without figures (the scratch copy's params files), then
nothing to rerun.  The figures cost 60 % of the run stage (two per error parameter) and are
checked where they are drawn (test_volumetric_run, test_newcomer's design figures), not DVC's
concern; nor are the design's worker processes (each imports the stack again; the result does not
depend on them: test_design) or the creation of the MLflow store (Alembic migrations, seconds of
CPU: test_tracking, test_hostile_procs), which starts here as a copy of a migrated one.

Marked ``full`` (`make test-all`, not CI's `make test`: ~31 s of CPU): in `make test` the
pipeline's four commands compose and pass the stage checks (test_pipeline_commands), `simulate`
writes the volumetric dataset (test_volumetric_sim), `calibrate` its calibration
(test_calibrate), `run` its volumetric section, as the separate stages do (test_volumetric_run),
`design` its study (test_design), and DVC runs a study then nothing (test_dvc_metrics)."""

import json

import pytest

from conftest import copy_project, dvc, set_keys
from test_deploy import mlflow_store

pytestmark = [pytest.mark.slow, pytest.mark.full]
STAGES = ("simulate", "calibrate", "run", "design")
PIPELINE = "pipelines/volumetric/dvc.yaml"


def test_the_volumetric_pipeline_runs_its_four_stages_then_nothing(tmp_path):
    dest, env = copy_project(tmp_path / "proj")
    set_keys(dest / "conf/sim/large_mill_volumetric.yaml", train_hours=30.0, test_hours=20.0)
    set_keys(dest / "conf/design/default.yaml", n_machines=4, grid="[6, 4, 4]", n_jobs=1)
    set_keys(dest / "conf/common.yaml", plots="none")
    mlflow_store(dest)                                  # the default store, sqlite:///mlruns/mlflow.db
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
