"""A lab's data scientist sweeps, compares and runs the DVC study on a lab's own file (sweep57).

- A sweep over two of a lab's records ranked their runs in one list, as if figures scored on
  different data compared, and printed one unnamed ``persistence (baseline)`` row per record:
  now a ``dataset`` column, runs ranked within each dataset, each baseline named.
- MLflow held each run's test RMSE but not its MAE (in ``metrics.json`` only), the figure a
  paper's comparison (fl_thermal's authors) reports: now ``<target>.test.mae`` beside it.
- ``pipelines/thermocomp`` (what every DVC stage calls) ran the venv's install, whose project
  root is the checkout it was installed from: in a copy of the project whose ``.venv`` links to
  another checkout's (docs/dvc.md's scratch copy), ``dvc repro`` wrote the study into that
  checkout and failed "output 'data/raw/yearround_spindle' does not exist".
- The DVC study on a lab's file: a changed ``test_fraction`` or roles pattern reran ingest and
  what reads its output, not ``diagnose`` (it reads ``data.path`` itself), whose figures stayed
  those of the old split; ``units``, ``sheet``, ``encoding``, ``timezone``, ... reran nothing; the
  sweep pipeline declared no data key at all.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from dataclasses import fields

import pandas as pd
import pytest
import yaml
from mlflow import MlflowClient

from conftest import FAST, ROOT, thermocomp
from test_deploy import mlflow_store
from thermocomp.core.io.options import ReadOptions
from thermocomp.core.scoring.leaderboard import rank

RECORD = ROOT / "datasets" / "fl_thermal" / "spindle_test.csv"
ROLES = ("data.roles.error=[ch*]", "data.roles.state=[spindle*]", "data.test_fraction=0.2",
         "data.delimiter=;", "data.decimal=,")


def _lab_file(path, start: int, rows: int = 400):
    """A stretch of the measured record as a lab exports it: `;` and decimal commas."""
    part = pd.read_csv(RECORD, skiprows=range(1, start + 1), nrows=rows)
    part.iloc[:, 0] -= part.iloc[0, 0]
    part.to_csv(path, sep=";", decimal=",", index=False)
    return path


@pytest.fixture(scope="module")
def two_records_swept(tmp_path_factory):
    root = tmp_path_factory.mktemp("lab57")
    a, b = _lab_file(root / "Lauf_A.csv", 0), _lab_file(root / "Lauf_B.csv", 6000)
    uri = mlflow_store(root)
    proc = thermocomp("run", "-m", f"data.path={a},{b}", "model=mlr,pcr", *ROLES,
                      f"tracking_uri={uri}", f"hydra.sweep.dir={root / 'sweep'}",
                      *[o for o in FAST if o not in ("track=false", "eval.validation=false")])
    return root, uri, proc


def test_a_sweep_over_two_records_is_ranked_within_each_with_its_baseline(two_records_swept):
    root, _, proc = two_records_swept
    table = pd.read_csv(root / "sweep" / "compare.csv")
    assert sorted(set(table["dataset"])) == ["Lauf_A.csv", "Lauf_B.csv"]
    first = table["dataset"].iloc[0]
    # one dataset's runs, then the other's: each ranked by its own validation
    assert list(table["dataset"]) == [first] * 2 + [next(d for d in table["dataset"] if d != first)] * 2
    for _, runs in table.groupby("dataset"):
        assert list(runs["val_rmse"]) == sorted(runs["val_rmse"])
    doc = json.loads((root / "sweep" / "compare.json").read_text())
    assert sorted(b["dataset"] for b in doc["baselines"]) == ["Lauf_A.csv", "Lauf_B.csv"]
    assert set(doc["best_per_dataset"]) == {"Lauf_A.csv", "Lauf_B.csv"}
    assert "4 runs on 2 datasets, ranked within each" in proc.stdout


def test_mlflow_holds_the_test_mae_beside_the_rmse_and_the_labs_roles(two_records_swept):
    root, uri, _ = two_records_swept
    client = MlflowClient(uri)
    runs = client.search_runs([client.get_experiment_by_name("thermocomp").experiment_id],
                              filter_string="tags.mlflow.parentRunId != ''")
    job = json.loads((root / "sweep" / "0" / "metrics.json").read_text())
    [run] = [r for r in runs if r.data.metrics.get("E_ch1.test.rmse") == pytest.approx(
        job["targets"]["E_ch1"]["test"]["rmse"], rel=1e-12)]
    for t, m in job["targets"].items():
        assert run.data.metrics[f"{t}.test.mae"] == pytest.approx(m["test"]["mae"])
    assert run.data.params["data.roles.error"] == "['ch*']"
    assert run.data.tags["dataset_hash"]


def test_the_dvc_launcher_runs_on_the_project_it_is_in(tmp_path):
    """A copy whose .venv is this checkout's: the stage reads and writes the copy."""
    copy = tmp_path / "copy"
    shutil.copytree(ROOT / "pipelines", copy / "pipelines", ignore=shutil.ignore_patterns("*/"))
    shutil.copytree(ROOT / "conf", copy / "conf")
    os.symlink(ROOT / "src", copy / "src")
    os.symlink(ROOT / ".venv", copy / ".venv")
    env = {k: v for k, v in os.environ.items() if k not in ("THERMOCOMP_ROOT", "PYTHONPATH")}
    proc = subprocess.run([str(copy / "pipelines" / "thermocomp"), "ingest", "track=false",
                           "data.path=data/raw/none57"], cwd=copy, env=env,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 2, proc.stderr
    assert str(copy / "data" / "raw" / "none57") in proc.stderr, proc.stderr


def _params(stage: dict, conf: str) -> list | None:
    """The keys ``stage`` declares of ``conf`` ([] for the whole file), None when it declares none."""
    for entry in stage.get("params", []):
        if isinstance(entry, dict) and conf in entry:
            return entry[conf] or []
    return None


def test_every_stage_reading_the_data_reruns_when_a_data_key_changes():
    """A lab's study (docs/dvc.md) edits conf/data/default.yaml: a new roles pattern, test_fraction,
    units or sheet must rerun ingest, and diagnose and the sweep, which read data.path themselves."""
    conf = "conf/data/default.yaml"
    names = {f.name for f in fields(ReadOptions)}
    # a key read as a group of fields (data.join: join_offset_s, join_tolerance_s) counts too
    read = {k for k in yaml.safe_load((ROOT / conf).read_text())
            if k in names or any(n.startswith(f"{k}_") for n in names)}
    stages = yaml.safe_load((ROOT / "dvc.yaml").read_text())["stages"]
    assert read - set(_params(stages["ingest"], conf)) == set()
    assert "data/interim/default" in stages["diagnose"]["deps"]   # ingest's output: every read key
    sweep = yaml.safe_load((ROOT / "pipelines/sweep/dvc.yaml").read_text())["stages"]["sweep"]
    assert _params(sweep, conf) == []


def test_every_pickle_a_stage_outputs_has_its_signature_beside_it_in_the_cache():
    """`dvc exp run` after test_fraction 0.1 -> 0.2 -> 0.1 checked train's model.pkl out of the
    run cache beside the .sig of the 0.2 fit: evaluate refused it ("signature mismatch")."""
    for path in (ROOT / "dvc.yaml", *sorted((ROOT / "pipelines").glob("*/dvc.yaml"))):
        for name, stage in yaml.safe_load(path.read_text())["stages"].items():
            outs = [next(iter(o)) if isinstance(o, dict) else o for o in stage.get("outs", [])]
            for pkl in (o for o in outs if o.endswith(".pkl")):
                assert f"{pkl}.sig" in outs, (path.name, name, pkl)


def test_compare_sorts_by_a_figure_and_names_the_figures_it_sorts_by():
    """`compare.sort_by=mae` (fl_thermal's figure) was refused listing every column, run_id and
    model among them, as if they ranked; `sort_by=model` ranked the runs by their names."""
    rows = [{"run_id": "a", "model": "mlr", "val_rmse": 1.0, "rmse": 2.0, "fit_time_s": 0.1},
            {"run_id": "b", "model": "arx", "val_rmse": 0.5, "rmse": 3.0, "fit_time_s": 0.2}]
    with pytest.raises(KeyError) as said:
        rank(rows, "mae")
    assert "val_rmse" in str(said.value) and "test:<name>): rmse" in str(said.value)
    assert "run_id" not in str(said.value)
    with pytest.raises(KeyError):
        rank(rows, "model")
    assert list(rank(rows, "test:rmse")["run_id"]) == ["a", "b"]
