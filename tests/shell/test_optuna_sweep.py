"""`thermocomp run -m hydra/sweeper=optuna ...`: Optuna proposes each job, minimises the validation
score `promote` chooses by (never the test split), logs every trial as a child run, and its best
trial is the run `promote` registers."""

from __future__ import annotations

import json

import numpy as np
import pytest
from omegaconf import OmegaConf

from conftest import poisoned_copy, refused, thermocomp
from test_deploy import LIGHT_EVAL, mlflow_store, write_small_dataset
from thermocomp.shell.cli import main
from thermocomp.shell.sweeps import objective
from thermocomp.shell.tracking import SWEEP_TAG

# three trials (five before ci104e; each an in-process run, twice): all of them Optuna's random
# start-up trials either way (TPE samples its first 10 at random), their variances and
# objectives still distinct
N_TRIALS = 3
SEARCH = ("hydra/sweeper=optuna", f"hydra.sweeper.n_trials={N_TRIALS}", "hydra.sweeper.sampler.seed=0",
          "model=pcr", "model.estimator.variance=interval(0.3,0.999)")


@pytest.fixture(scope="session")
def datasets(tmp_path_factory):
    root = tmp_path_factory.mktemp("optuna")
    clean = write_small_dataset(root / "small")
    return clean, poisoned_copy(clean, root / "poisoned")


def _search(root, data):
    uri, sweep_dir = mlflow_store(root), root / "sweep"
    thermocomp("run", "-m", f"data.path={data}", f"tracking_uri={uri}", *LIGHT_EVAL,
               f"hydra.sweep.dir={sweep_dir}", *SEARCH)
    import mlflow

    mlflow.set_tracking_uri(uri)
    runs = mlflow.search_runs(experiment_names=["thermocomp"])
    parents = runs[runs[f"tags.{SWEEP_TAG}"] == "parent"]
    children = runs[runs["tags.mlflow.parentRunId"].notna()].sort_values("params.out")
    jobs = [json.loads((sweep_dir / str(j) / "metrics.json").read_text()) for j in range(N_TRIALS)]
    return uri, sweep_dir, parents, children, jobs


@pytest.mark.slow
def test_optuna_minimises_the_validation_score_and_its_best_trial_is_promoted(tmp_path, datasets):
    clean, poisoned = datasets
    uri, sweep_dir, parents, children, jobs = _search(tmp_path / "clean", clean)
    assert len(parents) == 1 and len(children) == N_TRIALS             # every trial logged
    assert parents["tags.sweeper"].iloc[0] == "OptunaSweeper"
    assert (children["tags.mlflow.parentRunId"] == parents["run_id"].iloc[0]).all()
    assert (children["status"] == "FINISHED").all()
    variances = children["params.model.estimator.variance"].astype(float)
    assert variances.between(0.3, 0.999).all() and variances.nunique() == N_TRIALS
    # each trial's objective is its mean validation RMSE over targets, as MLflow logged it
    values = [objective(m) for m in jobs]
    logged = children[["metrics.E_X.val.rmse", "metrics.E_Z.val.rmse"]].mean(axis=1).to_numpy()
    np.testing.assert_allclose(values, logged, rtol=1e-9)
    assert len({round(v, 9) for v in values}) > 1                       # the search space matters
    best = OmegaConf.load(sweep_dir / "optimization_results.yaml")
    assert best.best_value == pytest.approx(min(values), rel=1e-12)
    assert parents["metrics.sweep.best_value"].iloc[0] == pytest.approx(min(values), rel=1e-12)
    best_job = int(np.argmin(values))
    assert float(best.best_params["model.estimator.variance"]) == pytest.approx(
        float(children["params.model.estimator.variance"].iloc[best_job]))

    # `promote` takes the best trial: the same criterion, from the same runs
    out = tmp_path / "promote"
    assert main(["promote", f"tracking_uri={uri}", f"compare.sweep={sweep_dir}",
                 f"data.path={clean}", f"out={out}"]) == 0
    promoted = json.loads((out / "promote.json").read_text())
    assert promoted["run_id"] == children["run_id"].iloc[best_job]

    # Garbage in the test split changes nothing Optuna sees: same proposals, same objectives.
    _, _, _, poisoned_children, poisoned_jobs = _search(tmp_path / "poisoned", poisoned)
    np.testing.assert_allclose([objective(m) for m in poisoned_jobs], values, rtol=1e-12)
    assert list(poisoned_children["params.model.estimator.variance"]) == list(
        children["params.model.estimator.variance"])
    poisoned_rmse = poisoned_jobs[0]["targets"]["E_Z"]["test"]["rmse"]
    assert poisoned_rmse > 100 * jobs[0]["targets"]["E_Z"]["test"]["rmse"]


def test_objective_is_the_promote_criterion_and_nan_without_validation():
    metrics = {"targets": {"E_X": {"validation": {"rmse": 1.0, "rsd_mean": 0.5}, "test": {"rmse": 9.0}},
                           "E_Z": {"validation": {"rmse": 3.0, "rsd_mean": 1.5}, "test": {"rmse": 9.0}}}}
    assert objective(metrics) == pytest.approx(2.0)
    assert objective(metrics, "val_rsd_mean", "E_Z") == pytest.approx(1.5)
    no_val = {"targets": {"E_X": {"test": {"rmse": 9.0}}}}
    assert np.isnan(objective(no_val))


def test_a_test_criterion_cannot_drive_a_search(tmp_path, capsys):
    data = write_small_dataset(tmp_path / "small")
    refused(["run", "-m", f"data.path={data}", "track=false", *LIGHT_EVAL, *SEARCH,
             f"hydra.sweep.dir={tmp_path / 'sweep'}", "promote.criterion=rmse"], capsys,
            "promote.criterion='rmse'", "validation")
    assert not (tmp_path / "sweep" / "0").exists()
