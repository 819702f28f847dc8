"""A sweep on a lab's one-file record is promoted as the sweeps page says (deploy57).

``thermocomp init <file>`` writes a data config whose ``data.path`` is the lab's file itself;
docs/sweeps.md promotes a sweep on it with that config.  A tracked run tagged its dataset's
digest only when ``data.path`` was a folder, so every child of such a sweep was untagged and
``promote`` refused the file it was swept on ("was not scored by any run of sweep ... (datasets
seen: none)"): the lab's file could be swept but its best run not promoted.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd

from conftest import LIGHT
from test_deploy import mlflow_store
from thermocomp.base.files import folder_digest
from thermocomp.shell.cli import main

# the lab's headers, its roles given as `thermocomp init` writes them
ROLES = ("data.roles.error=[dX]", "data.test_fraction=0.2", "data.delimiter=;", "data.decimal=,")


def lab_file(path, rows: int = 240, seed: int = 57):
    """One record, `;` and decimal commas, the lab's own headers: the error follows a lagged
    spindle temperature and the bed's."""
    rng = np.random.default_rng(seed)
    t = np.arange(rows) * 60.0
    spindle = 20 + 4 * (1 - np.exp(-t / 3000.0)) + 0.5 * np.sin(t / 900.0)
    bed = 20 + 0.3 * np.sin(t / 5000.0) + rng.normal(0, 0.02, rows)
    error = 3.0 * (spindle - 20) - 5.0 * (bed - 20) + rng.normal(0, 0.1, rows)
    pd.DataFrame({"Zeit [s]": t, "Temp Spindel [°C]": spindle.round(3),
                  "Temp Bett [°C]": bed.round(3), "dX [µm]": error.round(2)}).to_csv(
        path, sep=";", decimal=",", index=False)
    return path


def lab_run(tmp_path, rows: int = 120) -> tuple[list[str], str, str]:
    """``(common overrides, tracking URI, run id)``: :func:`lab_file` run once (MLR) into a new
    MLflow store under ``tmp_path``."""
    data = lab_file(tmp_path / "messung.csv", rows=rows)
    uri = mlflow_store(tmp_path)
    common = [f"data.path={data}", *ROLES, f"tracking_uri={uri}"]
    assert main(["run", *common, *LIGHT, f"out={tmp_path / 'run'}"]) == 0
    from mlflow import MlflowClient

    client = MlflowClient(uri)
    exp = client.get_experiment_by_name("thermocomp").experiment_id
    return common, uri, client.search_runs([exp], max_results=1)[0].info.run_id

def test_a_sweep_on_a_labs_one_file_record_is_promoted(tmp_path):
    data = lab_file(tmp_path / "messung.csv")
    uri = mlflow_store(tmp_path)
    common = [f"data.path={data}", *ROLES, f"tracking_uri={uri}", *LIGHT]
    assert main(["run", "-m", *common, "model=mlr,pcr",
                 f"hydra.sweep.dir={tmp_path / 'sweep'}"]) == 0
    from mlflow import MlflowClient

    client = MlflowClient(uri)
    exp = client.get_experiment_by_name("thermocomp").experiment_id
    children = [r for r in client.search_runs([exp]) if "mlflow.parentRunId" in r.data.tags]
    assert len(children) == 2
    # each job names the file it was scored on, as a folder's jobs do
    assert {r.data.tags.get("dataset_hash") for r in children} == {folder_digest(data)}
    out = tmp_path / "promote"
    assert main(["promote", *common, f"out={out}"]) == 0
    report = json.loads((out / "promote.json").read_text())
    assert report["run_id"] in {r.info.run_id for r in children} and report["moved"]
