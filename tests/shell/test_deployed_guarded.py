"""Deployed and batch figures that part with no input clamped: the correction guard (depl70).

On ``fl_thermal``'s 60/20/20 split ``diagnose``'s deployed "before" read E_ch1 9.53 µm against
``run``'s 9.57 with no row clamped: the adaptive compensator's guard (``monitor.guard``: the
training error range widened by 20 % of its width) bounded MLR's correction on 135 test rows,
which no output counted.  Both figures are right (the model's own prediction, what the machine
gets); the outputs now say which is which and why they part.

The record here: one file of 400 samples cut 60/20/20 (test = the middle part, continuing the
train part); two sensors that warm one after the other in train and together in test, both
within their training ranges (nothing to clamp), the error their sum, so the model's correction
in test leaves the training error range.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, thermocomp
from thermocomp.shell.cli import main

ROWS, TEST_ROWS = 400, 80
SPLIT = ("data.split_order=[train,test,val]", "data.test_fraction=0.2", "data.val_fraction=0.2")


@pytest.fixture(scope="module")
def record(tmp_path_factory) -> Path:
    i = np.arange(ROWS)

    def bump(centre):
        return 10 * np.exp(-0.5 * ((i - centre) / 25) ** 2)
    t1, t2 = 20 + bump(60) + bump(280), 20 + bump(170) + bump(280)
    error = (t1 - 20) + (t2 - 20) + np.random.default_rng(7).normal(0, 0.05, ROWS)
    path = tmp_path_factory.mktemp("guarded") / "rec.csv"
    pd.DataFrame({"time": 60.0 * i, "T_1": t1, "T_2": t2, "E_X": error}).round(4).to_csv(path, index=False)
    return path


def _stage(stage: str, record: Path, out: Path, *overrides: str) -> dict:
    assert main([stage, f"data.path={record}", f"out={out}", *SPLIT, *FAST, *overrides]) == 0
    name = {"run": "metrics", "replay": "replay", "diagnose": "diagnosis"}[stage]
    return json.loads((out / f"{name}.json").read_text())


@pytest.fixture(scope="module")
def run_rmse(record, tmp_path_factory) -> float:
    return _stage("run", record, tmp_path_factory.mktemp("run"))["targets"]["E_X"]["test"]["rmse"]


@pytest.fixture(scope="module")
def replayed(record, tmp_path_factory) -> tuple[dict, str]:
    """The default replay (the adaptive stream, its guard): E_X's figures and what it printed,
    read by both tests."""
    out = tmp_path_factory.mktemp("replay")
    printed = thermocomp("replay", f"data.path={record}", f"out={out}", *SPLIT, *FAST).stdout
    return json.loads((out / "replay.json").read_text())["targets"]["E_X"], printed


def test_replay_counts_the_rows_its_guard_bounded(record, run_rmse, replayed, tmp_path, capsys):
    r, out = replayed
    assert r["n_samples"] == TEST_ROWS and r["clamped_samples"] == 0
    assert r["rmse_batch"] == pytest.approx(run_rmse, rel=1e-9)   # run's, the stream warmed
    assert r["max_abs_stream_minus_batch"] < 1e-9
    assert 0 < r["guarded_samples"] < TEST_ROWS
    assert r["rmse"] > 10 * r["rmse_batch"]          # the guard cut a right correction here
    assert f"guarded: E_X {r['guarded_samples']} of {TEST_ROWS} samples" in out
    # the guard is the whole difference: bound wide, the deployed stream is the batch one
    wide = _stage("replay", record, tmp_path / "wide", "monitor.guard.margin=1000")["targets"]["E_X"]
    assert wide["guarded_samples"] == 0 and wide["rmse"] == pytest.approx(run_rmse, rel=1e-9)
    assert "guarded:" not in capsys.readouterr().out
    plain = _stage("replay", record, tmp_path / "plain", "monitor.adaptive=false")["targets"]["E_X"]
    assert plain["guarded_samples"] is None          # no guard in the plain stream


def test_diagnose_says_its_deployed_before_is_guarded_and_gives_run_s(record, run_rmse, replayed,
                                                                       tmp_path, capsys):
    replayed, _ = replayed
    before = _stage("diagnose", record, tmp_path / "diagnose")["before"]
    assert before["test_rmse"] == pytest.approx(replayed["rmse"], rel=1e-9)
    assert before["test_rmse_as_run"] == pytest.approx(run_rmse, rel=1e-9)
    assert before["test_rows_guarded"] == replayed["guarded_samples"]
    assert before["test_rows_clamped"] == 0
    out = capsys.readouterr().out
    assert (f"guard (monitor.guard) bounded or rate-limited the correction on E_X "
            f"{replayed['guarded_samples']}" in out)
    assert f"E_X {run_rmse:.3f} -> {run_rmse:.3f}" in out
