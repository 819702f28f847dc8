"""A replay or monitor of a given model, tracked (journey63): the MLflow run names the model streamed."""

from __future__ import annotations

import pytest

from conftest import thermocomp
from test_deploy import LIGHT_EVAL, mlflow_store, write_small_dataset


@pytest.fixture(scope="module")
def lagbank(tmp_path_factory):
    """``(dataset, model.pkl)``: one untracked lag bank run, streamed by both tests (each tracks
    its own stage in a store of its own)."""
    root = tmp_path_factory.mktemp("run63")
    dataset = write_small_dataset(root / "small")
    thermocomp("run", "model=lagbank", f"data.path={dataset}", "track=false", *LIGHT_EVAL,
               "eval.validation=false", f"out={root / 'run'}", f"model_path={root / 'run/model.pkl'}")
    return dataset, root / "run" / "model.pkl"


def test_a_replay_of_a_given_model_is_tracked_under_that_models_name(lagbank, tmp_path):
    """`replay replay.model=<a lag bank>` was tracked as 'mlr' (the config's default model, which
    it never fitted): a lab's MLflow listed a lag bank's check as an MLR run."""
    import mlflow

    dataset, model = lagbank
    uri = mlflow_store(tmp_path)
    thermocomp("replay", f"replay.model={model}", f"data.path={dataset}",
               f"tracking_uri={uri}", f"out={tmp_path / 'replay'}")
    mlflow.set_tracking_uri(uri)
    run = mlflow.search_runs(experiment_names=["thermocomp"]).iloc[0]
    assert run["tags.mlflow.runName"] == "replay-lagbank" and run["tags.replay.model_name"] == "lagbank"
    assert run.get("params.model.name") is None          # it was 'mlr', a model never fitted here


def test_a_monitor_of_a_given_model_is_tracked_under_that_models_name(lagbank, tmp_path):
    """`monitor monitor.model=<a lag bank's model.pkl>` was tracked as 'mlr' too."""
    import mlflow

    dataset, model = lagbank
    uri = mlflow_store(tmp_path)
    thermocomp("monitor", f"monitor.model={model}", f"data.path={dataset}",
               "plots=none", f"tracking_uri={uri}", f"out={tmp_path / 'monitor'}")
    mlflow.set_tracking_uri(uri)
    run = mlflow.search_runs(experiment_names=["thermocomp"]).iloc[0]
    assert run["tags.mlflow.runName"] == "monitor-lagbank" and run["tags.monitor.model_name"] == "lagbank"
    assert run.get("params.model.name") is None
