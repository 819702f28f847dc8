"""A run counter told from a temperature logged in whole degrees (session 53): both are whole
numbers stepping by one, held for many rows; a counter's value changes where a run ends (the
time restarts or jumps, the other sensors jump), a sensor's in the middle of a run."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from test_run_column52 import _runs
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.shell.cli import main


def _whole_degrees(path):
    """One two-hour record, ``T5`` (no unit) logged in whole degrees: 20, 21, 22 held for tens
    of rows each, rising slowly as the machine warms."""
    rng = np.random.default_rng(53)
    t = np.arange(120) * 60.0
    heat = 20 + 3 * (1 - np.exp(-t / 2400))
    pd.DataFrame({"Zeit [s]": t, "T0 [°C]": heat + rng.normal(0, 0.02, t.size),
                  "T5": np.floor(20 + 2.9 * (1 - np.exp(-t / 1800))).astype(int),
                  "dX [µm]": 3 * (heat - 20) + rng.normal(0, 0.05, t.size)}
                 ).to_csv(path, sep=";", decimal=",", index=False)
    return path


def _counted(path, going_on: bool):
    """Four runs, numbered 1..4 under ``Block`` (no run word); the time restarting at 0 in each,
    or going on from the last run's end one period later (only the sensors jump)."""
    runs = _runs()
    for k, run in enumerate(runs):
        run.insert(0, "Block", k + 1)
        run["Zeit [s]"] += 1800.0 * k if going_on else 0.0
    pd.concat(runs).to_csv(path, sep=";", decimal=",", index=False)
    return path


def test_a_sensor_in_whole_degrees_is_no_run_counter(tmp_path, caplog, capsys):
    # before: init proposed `campaign: T5` (three "runs" T5_20, T5_21, T5_22) and run warned
    # "column 'T5' looks like a run number"
    caplog.set_level(logging.INFO)
    path = _whole_degrees(tmp_path / "t5.csv")
    assert sorted(set(pd.read_csv(path, sep=";")["T5"])) == [20, 21, 22]
    ds, report = read_dataset(path, {"roles": {"error": ["dX"]}})
    assert "run number" not in caplog.text
    assert report["column_map"]["T5"] == "T_T5" and len(ds.campaigns) == 1
    assert main(["init", str(path), f"out={tmp_path / 'init'}", "data.roles.error=[dX]"]) == 0
    config = (tmp_path / "init" / "conf" / "data" / "t5.yaml").read_text()
    assert "campaign:" not in config and "each run a campaign" not in capsys.readouterr().out


@pytest.mark.parametrize("going_on", [False, True], ids=["time-restarts", "time-goes-on"])
def test_a_run_counter_without_a_run_word_is_still_pointed_out(tmp_path, caplog, capsys,
                                                               going_on):
    caplog.set_level(logging.INFO)
    path = _counted(tmp_path / "alle.csv", going_on)
    if going_on:       # read as one campaign, the counter said
        read_dataset(path, {"roles": {"error": ["dX"]}})
        assert "'Block' looks like a run number" in caplog.text
    else:
        with pytest.raises(ContractError, match=r"time decreases.*data.roles.campaign=Block"):
            read_dataset(path, {"roles": {"error": ["dX"]}})
    assert main(["init", str(path), f"out={tmp_path / 'init'}", "data.roles.error=[dX]"]) == 0
    assert "campaign: Block" in (tmp_path / "init" / "conf" / "data" / "alle.yaml").read_text()
