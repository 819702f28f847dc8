"""A replay or monitor of a given model, tracked (journey63): the MLflow run names the model streamed."""

from __future__ import annotations

from conftest import thermocomp
from test_deploy import LIGHT_EVAL, mlflow_store, write_small_dataset


def test_a_replay_of_a_given_model_is_tracked_under_that_models_name(tmp_path):
    """`replay replay.model=<a lag bank>` was tracked as 'mlr' (the config's default model, which
    it never fitted): a lab's MLflow listed a lag bank's check as an MLR run."""
    import mlflow

    dataset = write_small_dataset(tmp_path / "small")
    uri = mlflow_store(tmp_path)
    thermocomp("run", "model=lagbank", f"data.path={dataset}", "track=false", *LIGHT_EVAL,
               "eval.validation=false", f"out={tmp_path / 'run'}", f"model_path={tmp_path / 'run/model.pkl'}")
    thermocomp("replay", f"replay.model={tmp_path / 'run/model.pkl'}", f"data.path={dataset}",
               f"tracking_uri={uri}", f"out={tmp_path / 'replay'}")
    mlflow.set_tracking_uri(uri)
    run = mlflow.search_runs(experiment_names=["thermocomp"]).iloc[0]
    assert run["tags.mlflow.runName"] == "replay-lagbank" and run["tags.replay.model_name"] == "lagbank"
    assert run.get("params.model.name") is None          # it was 'mlr', a model never fitted here


def test_a_monitor_of_a_given_model_is_tracked_under_that_models_name(tmp_path):
    """`monitor monitor.model=<a lag bank's model.pkl>` was tracked as 'mlr' too."""
    import mlflow

    dataset = write_small_dataset(tmp_path / "small")
    uri = mlflow_store(tmp_path)
    thermocomp("run", "model=lagbank", f"data.path={dataset}", "track=false", *LIGHT_EVAL,
               "eval.validation=false", f"out={tmp_path / 'run'}", f"model_path={tmp_path / 'run/model.pkl'}")
    thermocomp("monitor", f"monitor.model={tmp_path / 'run/model.pkl'}", f"data.path={dataset}",
               "plots=none", f"tracking_uri={uri}", f"out={tmp_path / 'monitor'}")
    mlflow.set_tracking_uri(uri)
    run = mlflow.search_runs(experiment_names=["thermocomp"]).iloc[0]
    assert run["tags.mlflow.runName"] == "monitor-lagbank" and run["tags.monitor.model_name"] == "lagbank"
    assert run.get("params.model.name") is None
