"""`dvc repro pipelines/sweep/dvc.yaml` (the README's DVC sweep) in a scratch copy of the project,
the venv not on PATH: the default study's simulate, the sweep's jobs as committed and the
comparison, then nothing to rerun.  (An arx_rf job in its grid failed on this dataset, which has
no door signal, and with it every `dvc repro` of this pipeline.)  The default MLflow store starts
as a copy of a migrated one: its creation (Alembic migrations, seconds of CPU) is tested where it
is the point (test_tracking, test_hostile_procs).  The jobs run as on a one-CPU machine
(``LOKY_MAX_CPU_COUNT=1``: the launcher's ``n_jobs=-1`` is one job at a time, in the stage's
process): two loky workers each importing the stack and opening the store cost ~19 of the test's
52 s of CPU, and a joblib sweep on two workers is test_sweep's (one parent, four children, the
table).  Not marked ``full``: the only test that runs every job of the committed grid on the
default data (test_pipeline_commands only composes them)."""

import json

import pandas as pd
import pytest

from conftest import SHORT_KEYS, copy_project, dvc, set_keys
from test_deploy import mlflow_store

pytestmark = pytest.mark.slow
PIPELINE = "pipelines/sweep/dvc.yaml"


def test_the_sweep_pipeline_runs_every_job_and_the_comparison_then_nothing(tmp_path):
    dest, env = copy_project(tmp_path / "proj")
    env["LOKY_MAX_CPU_COUNT"] = "1"
    set_keys(dest / "conf/sim/yearround_spindle.yaml", **SHORT_KEYS)   # what runs, not what scores
    mlflow_store(dest)
    proc = dvc("repro", PIPELINE, cwd=dest, env=env)
    log = proc.stdout + proc.stderr
    for stage in ("sweep", "compare"):
        assert f"Running stage '{PIPELINE}:{stage}'" in log, log
    sweep = json.loads((dest / "reports/sweep/sweep.json").read_text())
    jobs = [p for p in (dest / "reports/sweep").iterdir() if (p / "metrics.json").is_file()]
    assert len(jobs) == 6, sweep                      # 3 models x 2 selections
    ranked = pd.read_csv(dest / "reports/sweep_compare/compare_plot.csv")
    assert len(ranked) == 6 and ranked["val_rmse"].is_monotonic_increasing
    proc = dvc("repro", PIPELINE, cwd=dest, env=env)
    again = proc.stdout + proc.stderr
    assert "Running stage" not in again and "up to date" in again
