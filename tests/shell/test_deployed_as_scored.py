"""Deployed as scored (issue 34, item 2): a test campaign that continues the train one streams
from the state the train campaign left, as ``run`` scores it.

The record is the shipped spindle test (datasets/fl_thermal) cut in two inside a cool-down,
under the lab's own column names mapped with ``data.columns``: train = the first 1200
samples, test = the next 300 (``continues`` the train file), ``data.reference=none``.
Restarting a lag or AR state there is off by microns.  The envelope is off in the
comparisons (``promote.envelope.policy=off``): the clamp is the deployment's own choice,
reported apart (``clamped_samples``), and the comparison is about state.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from test_deploy import mlflow_store
from test_hostile import FAST
from thermocomp.shell.cli import main
from thermocomp.shell.config.commands import groups_of

RECORD = Path(__file__).resolve().parents[2] / "datasets" / "fl_thermal" / "spindle_test.csv"
TRAIN_ROWS, TEST_ROWS = 1200, 300
TEMPS = [f"T{i}" for i in range(8)]
LAB = ["secs", "rpm", "ch1", "ch3", *TEMPS]                  # the lab's headers
CONTRACT = ["time", "S_rpm", "E_ch1", "E_ch3", *(f"T_{i}" for i in range(8))]
COLUMNS = "data.columns={" + ",".join(f"{a}:{b}" for a, b in zip(LAB, CONTRACT)) + "}"
PLAIN = ["monitor.adaptive=false", "promote.envelope.policy=off", "data.reference=none", COLUMNS]


@pytest.fixture(scope="module")
def record(tmp_path_factory) -> Path:
    """The cut record: A.csv (train), B.csv (test, continues A), lab's names."""
    root = tmp_path_factory.mktemp("cut")
    rec = pd.read_csv(RECORD, nrows=TRAIN_ROWS + TEST_ROWS)
    rec = rec.iloc[:, [0, 1, 2, 4, *range(7, 15)]].set_axis(LAB, axis=1)
    rec.iloc[:TRAIN_ROWS].to_csv(root / "A.csv", index=False)
    rec.iloc[TRAIN_ROWS:].to_csv(root / "B.csv", index=False)
    pd.DataFrame({"campaign": ["A", "B"], "file": ["A.csv", "B.csv"], "split": ["train", "test"],
                  "continues": ["", "A"]}).to_csv(root / "campaigns.csv", index=False)
    return root


def _stage(stage: str, record: Path, out: Path, *overrides: str, fast=FAST) -> dict:
    plain = [o for o in PLAIN if o.split(".")[0] in groups_of(stage) or "." not in o.split("=")[0]]
    assert main([stage, f"data.path={record}", f"out={out}", *plain, *fast, *overrides]) == 0
    name = {"run": "metrics", "replay": "replay", "monitor": "monitor", "promote": "promote"}[stage]
    return json.loads((out / f"{name}.json").read_text())


def _run_rmse(record: Path, out: Path, model: str) -> dict:
    metrics = _stage("run", record, out, f"model={model}")
    assert metrics["carry_over"] == {"B": ["A", "B"]}
    return {t: m["test"]["rmse"] for t, m in metrics["targets"].items()}


@pytest.fixture(scope="module")
def run_rmse(record, tmp_path_factory):
    """``run_rmse(model)``: ``_run_rmse`` of a model, run once in the module (the replay case and
    the monitor test of the lag bank compare their streams with the same run)."""
    runs: dict = {}

    def rmse(model: str) -> dict:
        if model not in runs:
            runs[model] = _run_rmse(record, tmp_path_factory.mktemp(f"run_{model}"), model)
        return runs[model]
    return rmse


@pytest.mark.parametrize("model", ["mlr", "arx", "lagbank"])
def test_replay_of_a_continuing_campaign_scores_as_run(record, run_rmse, tmp_path, capsys, model):
    run = run_rmse(model)
    replay = _stage("replay", record, tmp_path / "replay", f"model={model}")["targets"]
    for t, rmse in run.items():
        assert replay[t]["rmse"] == pytest.approx(rmse, rel=0.01)
        # like with like: the batch side is `run`'s joined prediction, the stream is warmed
        assert replay[t]["rmse_batch"] == pytest.approx(rmse, rel=1e-9)
        assert replay[t]["max_abs_stream_minus_batch"] < 1e-6
    captured = capsys.readouterr()
    assert "B continues A" in captured.err
    # the printed table shows the streamed RMSE beside the batch one (run's figure)
    row = [line.split() for line in captured.out.splitlines() if line.startswith("E_ch1 ")][-1]
    assert float(row[3]) == pytest.approx(replay["E_ch1"]["rmse"], abs=1e-3)
    assert float(row[4]) == pytest.approx(run["E_ch1"], abs=1e-3)


def test_monitor_streams_a_continuing_campaign_as_run_scores_it(record, run_rmse, tmp_path):
    run = run_rmse("lagbank")
    monitor = _stage("monitor", record, tmp_path / "monitor", "model=lagbank")["targets"]
    for t, rmse in run.items():
        assert monitor[t]["rmse_fixed"] == pytest.approx(rmse, rel=0.01)


@pytest.fixture(scope="module")
def promoted(record, tmp_path_factory):
    """A lagbank run promoted from a tracking store: (run's test RMSE, promote.json, store)."""
    root = tmp_path_factory.mktemp("promoted")
    uri = mlflow_store(root)
    tracked = [f"tracking_uri={uri}", "model=lagbank"]
    fast = [o for o in FAST if not o.startswith(("track=", "eval.validation="))]
    run = _stage("run", record, root / "run", *tracked, fast=fast)
    import mlflow

    mlflow.set_tracking_uri(uri)
    run_id = mlflow.search_runs(experiment_names=["thermocomp"])["run_id"].iloc[0]
    report = _stage("promote", record, root / "promote", *tracked, f"promote.run_id={run_id}",
                    fast=fast)
    return {t: m["test"]["rmse"] for t, m in run["targets"].items()}, report, uri


def test_promote_reports_the_figures_of_the_stream_it_deploys(promoted):
    run, report, _ = promoted
    assert report["candidate"]["test_reported"]["rmse"] == pytest.approx(np.mean(list(run.values())),
                                                                         rel=0.01)
    assert report["continuable"] == ["A", "B"]


def _served(promoted):
    import mlflow

    _, report, uri = promoted
    mlflow.set_tracking_uri(uri)
    return mlflow.pyfunc.load_model(report["model_uri"])


def _test_file(record: Path) -> pd.DataFrame:
    """B.csv under the lab's names, as the machine sends it: doubles (the schema's type), its
    clock restarted with the file."""
    lab = pd.read_csv(record / "B.csv").astype(float)
    return lab.assign(secs=lab["secs"] - lab["secs"].iloc[0])


INPUTS = [c for c in LAB if not c.startswith("ch")]


def test_the_served_model_reads_the_labs_names_as_contract_names(promoted, record):
    model = _served(promoted)
    lab = _test_file(record)
    contract = lab.set_axis(CONTRACT, axis=1)
    by_lab = model.predict(lab[INPUTS], params={"session": "lab", "reset": True})
    by_contract = model.predict(contract[[c for c in CONTRACT if not c.startswith("E_")]],
                                params={"session": "contract", "reset": True})
    pd.testing.assert_frame_equal(by_lab, by_contract)


def test_the_served_model_continues_a_campaign_as_run_scores_it(promoted, record):
    run, _, _ = promoted
    model = _served(promoted)
    lab = _test_file(record)
    served = model.predict(lab[INPUTS], params={"session": "machine", "continues": "A"})
    for t in run:      # the correction C = -Ê: what it leaves of the measured error is run's RMSE
        left = lab[t[2:]].to_numpy() + served["C_" + t[2:]].to_numpy()
        assert np.sqrt(np.mean(left ** 2)) == pytest.approx(run[t], rel=0.01)
    restarted = model.predict(lab[INPUTS], params={"session": "restarted", "reset": True})
    assert not np.allclose(restarted["C_ch3"], served["C_ch3"], atol=0.1)


def test_the_served_model_refuses_a_column_named_twice_or_an_unknown_predecessor(promoted, record):
    from mlflow.exceptions import MlflowException

    model = _served(promoted)
    lab = pd.read_csv(record / "B.csv").head(3).drop(columns=["ch1", "ch3"]).astype(float)
    twice = lab.assign(T_0=lab["T0"])
    with pytest.raises(MlflowException, match="'T0' and 'T_0'"):
        model.predict(twice, params={"session": "twice"})
    with pytest.raises(MlflowException, match="continues='Z'.*holds: A, B"):
        model.predict(lab, params={"session": "unknown", "continues": "Z"})
