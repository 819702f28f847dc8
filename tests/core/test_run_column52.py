"""One long file holding a lab's runs, numbered by a column (issue 34 item 1, session 52):
``data.roles.campaign`` splits it into campaigns as a folder of the runs reads, and a column that
counts runs is pointed out (init proposes it) instead of read as a temperature."""

from __future__ import annotations

import json
import logging
import re

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, refused
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.shell.cli import main

ROLES = {"error": ["dX"], "campaign": "Lauf"}


def _runs(count: int = 4, rows: int = 30) -> list[pd.DataFrame]:
    """Runs heating by a different amount each, the error following the heat through a lag; the
    time restarts at 0 in each (a lab's logger started per run)."""
    rng = np.random.default_rng(52)
    out = []
    for k in range(count):
        t = np.arange(rows) * 60.0
        heat = 20 + (2 + k) * (1 - np.exp(-t / 900)) + rng.normal(0, 0.02, rows)
        lagged = 20 + (2 + k) * (1 - np.exp(-t / 2400))
        error = 3 * (lagged - 20) + 0.5 * (heat - 20) + rng.normal(0, 0.05, rows)
        other = 20 + 0.1 * k + rng.normal(0, 0.02, rows)
        out.append(pd.DataFrame({"Zeit [s]": t, "T0 [°C]": heat, "T1 [°C]": other,
                                 "dX [µm]": error}))
    return out


def _long(path, runs, numbers=None):
    """The runs in one file, ``;`` and decimal commas, ``Lauf`` first (1, 2, ... or ``numbers``)."""
    numbers = numbers or range(1, len(runs) + 1)
    pd.concat([r.assign(Lauf=n)[["Lauf", *r.columns]] for n, r in zip(numbers, runs)]).to_csv(
        path, sep=";", decimal=",", index=False)
    return path


def _folder(root, runs):
    root.mkdir()
    for k, run in enumerate(runs, 1):
        run.to_csv(root / f"Lauf_{k}.csv", sep=";", decimal=",", index=False)
    return root


def test_a_long_file_split_by_its_run_column_reads_as_the_folder_of_its_runs(tmp_path, caplog):
    # before: data.roles.campaign was an unknown role; the only read was one record whose time
    # restarts at each run ("time decreases"), or, with ignore, one campaign of all the runs
    caplog.set_level(logging.INFO)
    runs = _runs()
    long_ds, report = read_dataset(_long(tmp_path / "alle.csv", runs),
                                   {"roles": ROLES, "test_fraction": 0.25})
    folder_ds, _ = read_dataset(_folder(tmp_path / "runs", runs),
                                {"roles": {"error": ["dX"]}, "test_fraction": 0.25})
    assert long_ds.ids() == folder_ds.ids() == ["Lauf_1", "Lauf_2", "Lauf_3", "Lauf_4"]
    assert long_ds.ids("test") == folder_ds.ids("test") == ["Lauf_4"]   # the last run, held out
    assert "held out in file order (no start time for each): test ['Lauf_4']" in caplog.text
    for cid in long_ds.ids():
        pd.testing.assert_frame_equal(long_ds.campaigns[cid], folder_ds.campaigns[cid])
    assert report["campaigns"]["Lauf_2"]["record_rows"] == [30, 60]
    assert "Lauf" not in report["column_map"]     # no column of a campaign: nothing to serve


def test_runs_with_wall_clock_times_are_held_out_by_their_start(tmp_path):
    runs = _runs(3)
    starts = pd.to_datetime(["2023-03-01 08:00", "2023-03-09 08:00", "2023-03-05 08:00"])
    for run, start in zip(runs, starts):   # the file lists run 2, which ran last, before 3
        run.insert(0, "Zeit", (start + pd.to_timedelta(run.pop("Zeit [s]"), unit="s"))
                   .dt.strftime("%d.%m.%Y %H:%M:%S"))
    ds, _ = read_dataset(_long(tmp_path / "alle.csv", runs, ["A1", "B2", "C3"]),
                         {"roles": ROLES, "test_fraction": 0.34})
    assert ds.ids() == ["A1", "B2", "C3"]        # a value with a letter is the id as it is
    assert ds.ids("test") == ["B2"]
    assert ds.campaigns["C3"]["time"].iloc[0] == 0.0            # seconds from its own start
    assert str(ds.manifest.at["C3", "start"]) == "2023-03-05 08:00:00"


def test_a_run_coming_back_and_a_bad_row_in_a_later_run_are_named_by_their_row(tmp_path):
    runs = _runs(3, rows=25)
    path = _long(tmp_path / "alle.csv", runs, [1, 2, 1])
    with pytest.raises(ContractError) as err:
        read_dataset(path, {"roles": ROLES})
    assert "run '1' comes back after '2'" in str(err.value) and err.value.row == 51
    # a time going back inside run 2: the file's row and line, not the run's
    runs = _runs(3, rows=25)
    runs[1].loc[5, "Zeit [s]"] = 0.0
    with pytest.raises(ContractError) as err:
        read_dataset(_long(tmp_path / "b.csv", runs), {"roles": ROLES})
    assert (err.value.row, err.value.line) == (31, 32) and "time decreases" in str(err.value)
    for wrong, said in (("Run", "names no header"), ("T*", "matches 'T0 [°C]' and 'T1 [°C]'")):
        with pytest.raises(ContractError, match=re.escape(said)):
            read_dataset(path, {"roles": {**ROLES, "campaign": wrong}})
    with pytest.raises(ContractError, match="a folder"):
        read_dataset(_folder(tmp_path / "runs", _runs(2)), {"roles": ROLES})


def test_a_run_counter_not_named_is_pointed_out_not_read_silently_as_a_temperature(
        tmp_path, caplog):
    runs = _runs()
    path = _long(tmp_path / "alle.csv", runs)
    with pytest.raises(ContractError) as err:      # the time restarts at each run
        read_dataset(path, {"roles": {"error": ["dX"]}})
    assert "time decreases" in str(err.value) and "data.roles.campaign=Lauf" in str(err.value)
    for k, run in enumerate(runs):                 # a time that goes on: read, and said
        run["Zeit [s]"] += k * 3600.0
    read_dataset(_long(path, runs), {"roles": {"error": ["dX"]}})
    assert "'Lauf' looks like a run number" in caplog.text
    caplog.clear()
    # a temperature logged in whole degrees, rising, is no run number: its header has a unit
    for run in runs:
        run["T1 [°C]"] = np.repeat(np.arange(20, 23), 10)
    read_dataset(_long(path, runs), {"roles": {"error": ["dX"], "ignore": ["Lauf"]}})
    assert "run number" not in caplog.text


def test_init_proposes_the_run_column_and_run_scores_the_runs_as_the_folder(tmp_path, capsys):
    runs = _runs()
    path = _long(tmp_path / "alle.csv", runs)
    assert main(["init", str(path), f"out={tmp_path / 'init'}", "data.roles.error=[dX]"]) == 0
    config = (tmp_path / "init" / "conf" / "data" / "alle.yaml").read_text()
    assert "campaign: Lauf" in config and "test_fraction: 0.1" in config
    out = capsys.readouterr().out
    assert "(each run a campaign)" in out and "campaign Lauf_4: test" in out
    common = ["model=mlr", "data.roles.error=[dX]", "data.test_fraction=0.25", *FAST]
    assert main(["run", f"data.path={path}", "data.roles.campaign=Lauf",
                 f"out={tmp_path / 'long'}", *common]) == 0
    assert main(["run", f"data.path={_folder(tmp_path / 'runs', runs)}",
                 f"out={tmp_path / 'folder'}", *common]) == 0
    long_m, folder_m = (json.loads((tmp_path / d / "metrics.json").read_text())
                        for d in ("long", "folder"))
    assert long_m["targets"]["E_dX"]["test"]["rmse"] == pytest.approx(
        folder_m["targets"]["E_dX"]["test"]["rmse"], rel=1e-12)
    refused(["run", f"data.path={path}", "data.roles.campaign=Lauf", "data.roles.ignore=[Lauf]",
             f"out={tmp_path / 'no'}", *common], capsys, "'Lauf' is matched by "
            "data.roles.campaign and data.roles.ignore")


def test_a_split_override_naming_no_run_of_a_long_file_says_what_the_runs_are(tmp_path):
    # before: "..., which the manifest does not list": a long file has no manifest
    path = _long(tmp_path / "alle.csv", _runs(count=3))
    with pytest.raises(ContractError) as err:
        read_dataset(path, {"roles": ROLES, "split_overrides": {"Lauf_9": "test"}})
    text = str(err.value)
    assert "'Lauf_9'" in text and "run column (data.roles.campaign)" in text, text
    assert "Lauf_1, Lauf_2, Lauf_3" in text and "manifest" not in text, text
