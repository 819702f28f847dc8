"""`thermocomp promote` and the served champion.

A weak model (one sensor, MLR), a strong one (all sensors, a test-local ARX with
the streaming protocol): promoting them in the order weak, strong, weak moves
``champion`` twice and then leaves it; ``mlflow models serve -m
models:/<name>@champion`` answers over HTTP exactly as the model in process.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import TEST_PATH, free_port, stop_process_group, wait_until_up
from test_deploy import LIGHT_EVAL, mlflow_store, write_small_dataset
from thermocomp.shell.cli import main

pytestmark = pytest.mark.slow
NAME = "thermocomp-compensator"


@pytest.fixture(scope="session")
def project(tmp_path_factory):
    root = tmp_path_factory.mktemp("promote")
    data = write_small_dataset(root / "small")
    uri = mlflow_store(root)
    common = [f"data.path={data}", f"tracking_uri={uri}", *LIGHT_EVAL]
    import mlflow

    def run(name, *overrides) -> str:
        assert main(["run", *common, f"name={name}", f"out={root / name}", *overrides]) == 0
        mlflow.set_tracking_uri(uri)
        runs = mlflow.search_runs(experiment_names=["thermocomp"],
                                  filter_string=f"tags.run_name = '{name}'")
        return runs["run_id"].iloc[0]

    weak = run("weak", "data.inputs=[T_1]")
    strong = run("strong", "model.name=ar_stub", "~model.estimator.fit_intercept",
                 "model.estimator._target_=test_deploy.ARStub")
    return root, common, uri, weak, strong


def _promote(project, run_id, tag, capsys):
    root, common, *_ = project
    code = main(["promote", *common, f"promote.run_id={run_id}", f"out={root / tag}"])
    out = capsys.readouterr()
    assert code == 0, out.err
    import json

    return json.loads((root / tag / "promote.json").read_text()), out.out


def test_promote_moves_champion_only_for_a_better_model(project, capsys):
    root, common, uri, weak, strong = project
    from mlflow import MlflowClient

    client = MlflowClient(uri)
    first, _ = _promote(project, weak, "p1", capsys)
    assert first["moved"] and first["reason"] == "no champion yet"
    second, said = _promote(project, strong, "p2", capsys)
    assert second["moved"] and "beats" in second["reason"] and "promoted to @champion" in said
    assert second["candidate"]["score"] < second["champion"]["score"]
    third, said = _promote(project, weak, "p3", capsys)
    assert not third["moved"] and "does not beat" in third["reason"] and "not promoted" in said
    assert third["version"] == first["version"] and not third["registered"]   # weak: already v1
    # the gate compares validation scores; the champion's is the one it was promoted with
    assert third["champion"]["score"] == pytest.approx(second["candidate"]["score"], rel=1e-5)
    assert third["candidate"]["score"] == pytest.approx(first["candidate"]["score"], rel=1e-12)
    assert second["candidate"]["score"] == second["candidate"]["validation"]["val_rmse"]
    assert "rmse" in second["candidate"]["test_reported"]
    # monitor.adaptive (default): the adaptive compensator is registered; its POD needs >= 3 sensors
    assert first["adaptive"] and first["pod"] is None                    # weak: T_1 only
    assert second["adaptive"] and second["pod"]["n_sensors"] == 3 and second["pod"]["n_modes"] >= 1

    champion = client.get_model_version_by_alias(NAME, "champion")
    assert str(champion.version) == second["version"] == "2"
    assert sorted(str(v.version) for v in client.search_model_versions(f"name='{NAME}'")) == ["1", "2"]
    tags = champion.tags
    assert tags["source_run_id"] == strong and tags["model"] == "ar_stub"
    assert tags["test_campaigns"] == "K04,K05" and tags["promoted"] == "True"
    assert len(tags["dataset_hash"]) == 64
    assert tags["dataset_hash"] == client.get_model_version(NAME, "1").tags["dataset_hash"]
    assert len(tags["model_digest"]) == 64
    assert tags["git_commit"] == "unknown" or len(tags["git_commit"]) == 40
    assert float(tags["metric.val_rmse"]) == pytest.approx(second["candidate"]["score"], rel=1e-5)
    assert float(tags["metric.rsd_mean"]) == pytest.approx(          # test: reported beside it
        second["candidate"]["test_reported"]["rsd_mean"], rel=1e-5)
    assert tags["criterion"] == "val_rmse" and tags["eval_mode"] == "simulation"
    assert tags["adaptive"] == "True" and tags["outputs"] == "C_X,C_Z,n_clamped,excluded_inputs,events"
    assert tags["pod_modes"] == str(second["pod"]["n_modes"]) and len(tags["deploy_config"]) == 12
    assert "does not beat" in client.get_model_version(NAME, "1").tags["decision"]
    assert champion.current_stage in (None, "None")             # aliases only, no stages
    model = client.get_registered_model(NAME)
    assert {k: str(v) for k, v in model.aliases.items()} == {"champion": "2"}


def test_promoting_the_champion_again_registers_nothing(project, capsys):
    root, common, uri, weak, strong = project
    from mlflow import MlflowClient

    client = MlflowClient(uri)
    _promote(project, strong, "q1", capsys)
    before = {v.version for v in client.search_model_versions(f"name='{NAME}'")}
    champion = client.get_model_version_by_alias(NAME, "champion").version
    again, said = _promote(project, strong, "q2", capsys)
    assert f"already champion: version {champion}" in said
    assert (again["version"], again["registered"], again["moved"]) == (str(champion), False, False)
    assert {v.version for v in client.search_model_versions(f"name='{NAME}'")} == before
    # the same configuration run again: another run id, the same model and figures
    assert main(["run", *common, "name=strong_again", f"out={root / 'strong_again'}",
                 "model.name=ar_stub", "~model.estimator.fit_intercept",
                 "model.estimator._target_=test_deploy.ARStub"]) == 0
    [rerun] = client.search_runs([client.get_run(strong).info.experiment_id],
                                 filter_string="tags.run_name = 'strong_again'")
    third, said = _promote(project, rerun.info.run_id, "q3", capsys)
    assert f"already champion: version {champion}" in said and not third["registered"]
    assert {v.version for v in client.search_model_versions(f"name='{NAME}'")} == before


def test_promote_refuses_a_tampered_run_model_without_unpickling_it(project, capsys, tmp_path):
    root, common, uri, weak, strong = project
    from mlflow import MlflowClient

    from test_signing import evil_pickle

    client = MlflowClient(uri)
    assert main(["run", *common, "name=victim", f"out={root / 'victim'}"]) == 0
    [victim] = client.search_runs([client.get_run(weak).info.experiment_id],
                                  filter_string="tags.run_name = 'victim'")
    stored = Path(victim.info.artifact_uri.removeprefix("file://")) / "model.pkl"
    marker = tmp_path / "marker"
    evil_pickle(stored, marker)                   # the store was written to behind our back
    capsys.readouterr()
    assert main(["promote", *common, f"promote.run_id={victim.info.run_id}",
                 f"out={root / 'pv'}"]) == 2
    assert "signature mismatch" in capsys.readouterr().err
    assert not marker.exists() and not (root / "pv" / "promote.json").exists()


def test_promote_without_run_or_sweep_is_a_config_error(project, capsys):
    _, common, *_ = project
    assert main(["promote", *common]) == 2
    said = capsys.readouterr().err
    assert "no sweep" in said and "promote.run_id=<its MLflow run id>" in said   # runs made one at a time


@pytest.mark.parametrize("override, says", [
    # each was read as given: a truthy text forced the alias, a negative bar let a worse model in
    ("promote.force=maybe", "promote.force='maybe': must be true or false"),
    ("promote.min_improvement=-1", "promote.min_improvement=-1: must be a number >= 0"),
    ("promote.envelope.policy=ignore", "promote.envelope.policy='ignore': must be one of clamp"),
    ("promote.envelope.margin=-0.5", "promote.envelope.margin=-0.5: must be a number >= 0"),
    ("promote.max_stream_deviation_um=-1", "promote.max_stream_deviation_um=-1:"),
    # MlflowException tracebacks (exit 1) or a wrong reason before
    ("promote.alias='has space'", "promote.alias='has space': must be letters, digits"),
    ("promote.alias=v3", "not v<number>"),
    ("promote.criterion=bogus", "promote.criterion=bogus is not a figure"),
    ("promote.run_id=deadbeef", "promote.run_id=deadbeef: no such run"),
])
def test_promote_refuses_bad_settings_before_reading_a_run(project, capsys, override, says):
    import mlflow

    _, common, uri, weak, _ = project
    mlflow.set_tracking_uri(uri)
    before = len(mlflow.search_registered_models())
    assert main(["promote", *common, f"promote.run_id={weak}", override]) == 2
    assert says in capsys.readouterr().err
    assert len(mlflow.search_registered_models()) == before


def test_promote_refuses_to_choose_by_a_test_figure(project, capsys):
    _, common, _, weak, _ = project
    assert main(["promote", *common, f"promote.run_id={weak}", "promote.criterion=rsd_mean"]) == 2
    assert "test figure" in capsys.readouterr().err


def _post(port, frame: pd.DataFrame, reset: bool):
    import requests

    body = {"dataframe_split": frame.to_dict(orient="split"), "params": {"reset": reset}}
    body["dataframe_split"].pop("index")
    return requests.post(f"http://127.0.0.1:{port}/invocations", json=body, timeout=60)


@pytest.mark.full
def test_served_champion_answers_http_exactly_as_in_process(project, capsys):
    """``full``: MLflow's own ``mlflow models serve`` of the champion.  test_serve's
    test_thermocomp_serve_answers_as_in_process_without_an_activated_venv serves the champion
    (MLflow's scoring server, the user's route) and asserts the same: the answers of blocks
    that carry the stream on equal the in-process stream's, the same columns, a 400 naming a
    missing column (a server start is ~10 s of CPU)."""
    root, common, uri, weak, strong = project
    import mlflow

    if not _champion_exists(uri):
        _promote(project, strong, "p_serve", capsys)
    port = free_port()
    bin_dir = str(Path(sys.executable).parent)            # uvicorn lives next to mlflow
    env = {**os.environ, "MLFLOW_TRACKING_URI": uri,
           "PATH": os.pathsep.join([bin_dir, os.environ.get("PATH", "")]),
           "PYTHONPATH": os.pathsep.join([TEST_PATH, os.environ.get("PYTHONPATH", "")])}
    cmd = [str(Path(bin_dir) / "mlflow"), "models", "serve", "-m",
           f"models:/{NAME}@champion", "--env-manager", "local", "-h", "127.0.0.1", "-p", str(port)]
    log = open(root / "serve.log", "w")
    server = subprocess.Popen(cmd, env=env, stdout=log, stderr=subprocess.STDOUT,
                              start_new_session=True)
    try:
        wait_until_up(port, server, root / "serve.log", timeout_s=120)
        test = pd.read_csv(Path(common[0].split("=", 1)[1]) / "K05.csv")
        frame = test[["time", "T_1", "T_2", "T_amb"]].astype(float)
        local = mlflow.pyfunc.load_model(f"models:/{NAME}@champion")
        expected = [local.predict(frame.iloc[:70], params={"reset": True}),
                    local.predict(frame.iloc[70:])]            # the stream goes on
        got = [_post(port, frame.iloc[:70], True), _post(port, frame.iloc[70:], False)]
        for exp, resp in zip(expected, got):
            assert resp.status_code == 200, resp.text
            served = pd.DataFrame(resp.json()["predictions"])
            assert list(served.columns) == ["C_X", "C_Z", "n_clamped", "excluded_inputs", "events"]
            np.testing.assert_allclose(served[["C_X", "C_Z"]].to_numpy(),
                                       exp[["C_X", "C_Z"]].to_numpy(), rtol=0, atol=1e-9)
        # The memory matters: restarting the stream at row 70 would answer differently.
        restarted = local.predict(frame.iloc[70:], params={"reset": True})
        assert np.abs(restarted["C_Z"].to_numpy() - expected[1]["C_Z"].to_numpy()).max() > 0.1

        bad = frame.iloc[:5].drop(columns="T_amb")
        resp = _post(port, bad, True)
        assert resp.status_code == 400 and "T_amb" in resp.text
    finally:
        stop_process_group(server)
        log.close()


def _champion_exists(uri) -> bool:
    from mlflow import MlflowClient

    try:
        MlflowClient(uri).get_model_version_by_alias(NAME, "champion")
        return True
    except Exception:
        return False


def test_monitor_adaptive_false_registers_the_plain_stream_once(project, capsys):
    """The monitor group decides what is deployed: the same run deployed plain is another
    version (another deploy_config), registered once; the champion's alias stays."""
    import json

    import mlflow
    from mlflow import MlflowClient

    from thermocomp.apps.deploy import StreamingCompensator

    root, common, uri, weak, strong = project
    client = MlflowClient(uri)
    if not _champion_exists(uri):       # run alone: no earlier test promoted one (lead73)
        _promote(project, strong, "champion", capsys)
    champion = client.get_model_version_by_alias(NAME, "champion").version
    reports = []
    for tag in ("plain1", "plain2"):
        assert main(["promote", *common, f"promote.run_id={strong}", "monitor.adaptive=false",
                     f"out={root / tag}"]) == 0
        reports.append(json.loads((root / tag / "promote.json").read_text()))
    capsys.readouterr()
    first, again = reports
    assert first["registered"] and not first["adaptive"] and first["pod"] is None
    assert (again["version"], again["registered"]) == (first["version"], False)
    assert client.get_model_version_by_alias(NAME, "champion").version == champion != first["version"]
    tags = client.get_model_version(NAME, first["version"]).tags
    assert tags["adaptive"] == "False" and tags["outputs"] == "C_X,C_Z,n_clamped"
    assert tags["source_run_id"] == strong
    assert tags["deploy_config"] != client.get_model_version(NAME, champion).tags["deploy_config"]
    mlflow.set_tracking_uri(uri)
    model = mlflow.pyfunc.load_model(first["model_uri"])
    assert type(model.unwrap_python_model().streaming) is StreamingCompensator
    assert model.metadata.get_output_schema().input_names() == ["C_X", "C_Z", "n_clamped"]
