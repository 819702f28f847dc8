"""Every "as deployed" figure says how many rows the correction guard changed (guard70).

depl70 made ``replay`` and ``diagnose`` count the test rows whose correction the guard
(``monitor.guard``) bounded or rate-limited; ``promote``'s test figures and ``monitor``'s
adaptive RMSE, streamed through the same guard, still left ``run``'s figure without a word.
The record is depl70's (tests/shell/test_deployed_guarded.py: 400 samples cut 60/20/20, the
test correction leaving the training error range, no input clamped); ``monitor`` needs three
temperature inputs, so its copy gains a slow sensor within its training range that the error
does not follow.
"""

from __future__ import annotations

import json
from pathlib import Path

import mlflow
import numpy as np
import pandas as pd
import pytest

from conftest import FAST, LIGHT
from test_deploy import mlflow_store
from test_deployed_guarded import TEST_ROWS, record  # noqa: F401 (record: depl70's fixture)
from thermocomp.shell.cli import main

SPLIT = ("data.split_order=[train,test,val]", "data.test_fraction=0.2", "data.val_fraction=0.2")
OUTPUT = {"run": "metrics", "replay": "replay", "monitor": "monitor", "promote": "promote"}


def _stage(stage: str, record: Path, out: Path, *overrides: str, fast=FAST) -> dict:  # noqa: F811
    assert main([stage, f"data.path={record}", f"out={out}", *SPLIT, *fast, *overrides]) == 0
    return json.loads((out / f"{OUTPUT[stage]}.json").read_text())


def _guarded_line(target: str, n: int) -> str:
    return f"guarded: {target} {n} of {TEST_ROWS} samples had the correction bounded or rate-limited"


def test_promote_says_how_many_test_rows_its_guard_changed(record, tmp_path, capsys):  # noqa: F811
    replayed = _stage("replay", record, tmp_path / "replay")["targets"]["E_X"]
    uri = mlflow_store(tmp_path)
    tracked = (f"tracking_uri={uri}", *LIGHT)        # promote needs a tracked run with validation
    run = _stage("run", record, tmp_path / "run", fast=tracked)["targets"]["E_X"]["test"]["rmse"]
    mlflow.set_tracking_uri(uri)
    run_id = mlflow.search_runs(experiment_names=["thermocomp"])["run_id"].iloc[0]
    capsys.readouterr()
    report = _stage("promote", record, tmp_path / "promote", f"promote.run_id={run_id}", fast=tracked)
    cand = report["candidate"]
    # the "as deployed" figure is replay's guarded stream, far from run's; promote says why
    assert cand["test_reported"]["rmse"] == pytest.approx(replayed["rmse"], rel=1e-9)
    assert cand["test_reported"]["rmse"] > 10 * run
    assert 0 < replayed["guarded_samples"] < TEST_ROWS
    assert cand["test_rows_guarded"] == {"E_X": replayed["guarded_samples"]}
    assert _guarded_line("E_X", replayed["guarded_samples"]) in capsys.readouterr().out


@pytest.fixture(scope="module")
def record3(record, tmp_path_factory) -> Path:  # noqa: F811
    """depl70's record plus ``T_3``: a slow swing within its training range, no part of the error."""
    rec = pd.read_csv(record)
    rec.insert(3, "T_3", (20 + 0.3 * np.sin(np.arange(len(rec)) / 40)).round(4))
    path = tmp_path_factory.mktemp("guarded3") / "rec3.csv"
    rec.to_csv(path, index=False)
    return path


def test_monitor_says_how_many_rows_its_guard_changed(record3, tmp_path, capsys):
    replayed = _stage("replay", record3, tmp_path / "replay")["targets"]["E_X"]
    run = _stage("run", record3, tmp_path / "run")["targets"]["E_X"]["test"]["rmse"]
    capsys.readouterr()
    mon = _stage("monitor", record3, tmp_path / "monitor")["targets"]["E_X"]
    assert mon["n_samples"] == TEST_ROWS and mon["clamped_samples"] == 0
    assert mon["rmse_fixed"] == pytest.approx(run, rel=1e-6)          # no guard: run's
    assert mon["rmse_adaptive"] == pytest.approx(replayed["rmse"], rel=1e-9)
    assert mon["rmse_adaptive"] > 10 * run
    assert 0 < replayed["guarded_samples"] < TEST_ROWS
    assert mon["guarded_samples"] == replayed["guarded_samples"]
    out = capsys.readouterr().out
    assert _guarded_line("E_X", mon["guarded_samples"]) + " by the guard (monitor.guard); " \
        "RMSE adaptive is the guarded stream's" in out
    # the guard is the whole difference: bound wide, no row guarded, no line, adaptive = fixed
    wide = _stage("monitor", record3, tmp_path / "wide", "monitor.guard.margin=1000")["targets"]["E_X"]
    assert wide["guarded_samples"] == 0
    assert wide["rmse_adaptive"] == pytest.approx(wide["rmse_fixed"], rel=1e-9)
    assert "guarded:" not in capsys.readouterr().out
