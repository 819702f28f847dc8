"""A run logged by two loggers (twolog70): the temperatures in ``<run>_temp.csv`` (a DAQ, every
10 s, its clock the reference), the displacements in ``<run>_disp.csv`` (the probe software, every
60 s, ``;`` and decimal commas, its clock 7 s ahead), read as one campaign on the errors' times
(``benchmarks/bench_twolog70.py`` writes a lathe's full record so; these are a few rows)."""

from __future__ import annotations

import datetime as dt
import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, refused
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

AHEAD_S = 7.0          # the probe PC's clock minus the DAQ's
START = dt.datetime(2027, 3, 1, 6, 0)


def _spindle(t: np.ndarray, run: int) -> np.ndarray:
    return 20.0 + np.sin(t / 300.0 + 0.2 * (run % 2))


def _bed(t: np.ndarray, run: int) -> np.ndarray:
    return 20.0 + (1.0 + 0.1 * (run == 2)) * t / 3600.0     # (the test run's like run 1's)


def _error(t: np.ndarray, run: int) -> np.ndarray:
    """The tool's drift (µm): linear in the two temperatures at the probe's true time."""
    return 2.0 * (_spindle(t, run) - 20.0) + 5.0 * (_bed(t, run) - 20.0)


def _run(folder: Path, run: int, late_s: float = 0.0, stop_early_s: float = 0.0,
         ahead_s: float = AHEAD_S, stamped: bool = True, pause: tuple = ()) -> None:
    """Run ``run`` as its two loggers wrote it (``late_s``: the DAQ started so late;
    ``stop_early_s``: the probes stopped so early; ``stamped``: the DAQ's time a timestamp,
    else seconds from its start; ``pause``: the DAQ logged nothing between these times)."""
    start = START + dt.timedelta(days=run)
    t = np.arange(0.0, 1200.0 + 1e-9, 10.0)
    paused = (t > pause[0]) & (t < pause[1]) if pause else np.zeros(len(t), bool)
    t = t[(t >= late_s) & ~paused]
    temp = pd.DataFrame({
        "Time": [(start + dt.timedelta(seconds=s)).strftime("%Y-%m-%d %H:%M:%S") for s in t]
        if stamped else t - t[0],
        "Spindle [°C]": np.round(_spindle(t, run), 5), "Bed [°C]": np.round(_bed(t, run), 5),
        "Door [-]": (t // 200) % 2})
    temp.to_csv(folder / f"run{run:02d}_temp.csv", index=False)
    te = np.arange(0.0, 1200.0 - stop_early_s + 1e-9, 60.0)
    disp = pd.DataFrame({
        "Zeitstempel": [(start + dt.timedelta(seconds=s + ahead_s)).strftime("%d.%m.%Y %H:%M:%S")
                        for s in te],
        "dX [µm]": [f"{v:.4f}".replace(".", ",") for v in _error(te, run)]})
    disp.to_csv(folder / f"run{run:02d}_disp.csv", index=False, sep=";")


def _folder(root: Path, **first) -> Path:
    root.mkdir()
    for run in (1, 2, 3):
        _run(root, run, **(first if run == 1 else {}))
    return root


CFG = {"roles": {"error": ["dX"], "state": ["Door"]}, "test_fraction": 0.34}


def test_two_loggers_files_are_one_campaign_on_the_errors_times(tmp_path):
    folder = _folder(tmp_path / "runs", late_s=120.0, stop_early_s=300.0)
    ds, report = read_dataset(folder, {**CFG, "join": {"offset_s": AHEAD_S}})
    assert list(ds.manifest.index) == ["run01", "run02", "run03"]     # one campaign per pair
    assert list(ds.manifest["split"]) == ["train", "train", "test"]
    frame = ds.campaigns["run01"]
    assert list(frame.columns) == ["time", "T_Spindle", "T_Bed", "E_dX", "S_Door"]
    # the probes' samples from the DAQ's first (120 s; 0 and 60 s cut) to their last (900 s)
    te = np.arange(120.0, 900.0 + 1e-9, 60.0)
    np.testing.assert_array_equal(frame["time"], te - te[0])
    np.testing.assert_allclose(frame["E_dX"], _error(te, 1), atol=1e-4)
    # temperatures interpolated at the probes' times on the DAQ's clock (10 s steps: 1e-4 K)
    np.testing.assert_allclose(frame["T_Spindle"], _spindle(te, 1), atol=2e-4)
    np.testing.assert_array_equal(frame["S_Door"], (te // 200) % 2)    # held, not interpolated
    pair = report["campaigns"]["run01"]["paired"]
    assert pair["temperatures"] == "run01_temp.csv" and pair["errors"] == "run01_disp.csv"
    assert pair["cut"] == {"before": 2, "after": 0, "gaps": 0}
    assert report["campaigns"]["run01"]["time_origin"] == "2027-03-02T06:02:00"


def test_the_clock_offset_moves_the_error_samples_on_the_temperature_clock(tmp_path):
    folder = _folder(tmp_path / "runs")
    ds, report = read_dataset(folder, CFG)
    frame = ds.campaigns["run02"]
    te = np.arange(0.0, 1200.0 - 60.0 + 1e-9, 60.0)  # its last, 1207 s on the DAQ's clock: cut
    # at te + 7 s on the DAQ's clock: its sample at te held (rate83: interpolated towards the
    # one at te + 10 s, a sample 3 s after the error's time)
    np.testing.assert_array_equal(frame["T_Spindle"], np.round(_spindle(te, 2), 5))
    assert report["campaigns"]["run02"]["paired"]["cut"] == {"before": 0, "after": 1, "gaps": 0}


def test_error_samples_in_a_pause_of_the_temperature_logger_are_cut_unless_tolerated(tmp_path):
    folder = _folder(tmp_path / "runs", pause=(400.0, 700.0))     # 5 min without a DAQ row
    cfg = {**CFG, "join": {"offset_s": AHEAD_S}}
    ds, report = read_dataset(folder, cfg)
    assert report["campaigns"]["run01"]["paired"]["cut"] == {"before": 0, "after": 0, "gaps": 5}
    np.testing.assert_array_equal(ds.campaigns["run01"]["time"],
                                  [0, 60, 120, 180, 240, 300, 360, 720, 780, 840, 900, 960, 1020,
                                   1080, 1140, 1200])
    ds, report = read_dataset(folder, {**cfg, "join": {"offset_s": AHEAD_S, "tolerance_s": 400}})
    assert report["campaigns"]["run01"]["paired"]["cut"]["gaps"] == 0
    assert len(ds.campaigns["run01"]) == 21


def test_init_says_what_it_paired_and_run_replay_fit_the_joined_runs(tmp_path, capsys):
    folder = _folder(tmp_path / "runs", late_s=120.0)
    assert main(["init", str(folder), "data.join.offset_s=7", f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert ("run01: two loggers, run01_temp.csv (every 10 s) + run01_disp.csv (every 60 s): one "
            "run, its rows the errors' times, the temperatures' last sample at or before each "
            "(data.join.offset_s=7); 19 rows, 2 error sample(s) cut (2 before)") in said
    assert ("run01_temp.csv: delimiter ',', decimal '.'; run01_disp.csv: delimiter ';', "
            "decimal ','") in said
    assert "dX [µm]       error        E_dX" in said
    conf = (tmp_path / "init" / "conf" / "data" / "runs.yaml").read_text()
    assert "delimiter: auto" in conf and "offset_s: 7" in conf      # (each file's detected)
    data = [f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=runs"]
    assert main(["run", *data, "model=mlr", *FAST, f"out={tmp_path / 'out'}"]) == 0
    run = json.loads((tmp_path / "out" / "metrics.json").read_text())["targets"]["E_dX"]
    assert run["test"]["rmse"] < 0.01          # (the drift is linear in the temperatures)
    assert main(["replay", *data, f"replay.model={tmp_path / 'out' / 'model.pkl'}",
                 "promote.envelope.policy=off", "track=false", f"out={tmp_path / 'replay'}"]) == 0
    replay = json.loads((tmp_path / "replay" / "replay.json").read_text())["targets"]["E_dX"]
    assert replay["rmse"] == pytest.approx(run["test"]["rmse"], rel=1e-9, abs=1e-12)


def test_a_two_logger_run_is_scored_on_what_a_control_is_fed(tmp_path):
    """(rate83) A control fed the DAQ's samples alone has at each probe's time the correction the
    run scored there, a lag bank's too (it commits a step once a training period, cadence72).
    Before: the temperatures were interpolated between the samples around the probe (7 s after
    one on the DAQ's clock), reading the next, 3 s later: the scored rows were no stream's."""
    from thermocomp.apps.deploy.streaming import StreamingCompensator, batch_prediction
    from thermocomp.shell.model_store import load_model

    folder = _folder(tmp_path / "runs")
    out = tmp_path / "out"
    assert main(["run", f"data.path={folder}", "data.roles.error=[dX]", "data.roles.state=[Door]",
                 "data.test_fraction=0.34", "model=lagbank", *FAST, "track=false",
                 f"out={out}"]) == 0
    comp = load_model(out / "model.pkl")
    joined = read_dataset(folder, CFG)[0].campaigns["run03"]
    scored = batch_prediction(comp, joined)["E_dX"].to_numpy()
    daq = pd.read_csv(folder / "run03_temp.csv")
    t = (pd.to_datetime(daq["Time"]) - pd.to_datetime(daq["Time"][0])).dt.total_seconds()
    scans = pd.DataFrame({"time": t, "T_Spindle": daq["Spindle [°C]"], "T_Bed": daq["Bed [°C]"],
                          "S_Door": daq["Door [-]"]})
    streaming = StreamingCompensator(comp, None, "off")
    streaming.reset()
    fed = streaming.predict(scans)["E_dX"].to_numpy()
    probes = np.arange(0.0, 1200.0 - 60.0 + 1e-9, 60.0) + AHEAD_S    # on the DAQ's clock
    held = np.searchsorted(t.to_numpy(), probes, side="right") - 1
    np.testing.assert_allclose(fed[held], scored, rtol=0, atol=1e-9)


def test_a_manifest_lists_the_temperature_file_and_the_error_file_is_joined(tmp_path):
    folder = _folder(tmp_path / "runs")
    (folder / "campaigns.csv").write_text(
        "campaign,file,split\nA,run01_temp.csv,train\nB,run02_temp.csv,train\n"
        "C,run03_temp.csv,test\n")
    ds, report = read_dataset(folder, {**CFG, "test_fraction": None})
    assert list(ds.campaigns["C"].columns) == ["time", "T_Spindle", "T_Bed", "E_dX", "S_Door"]
    assert report["campaigns"]["C"]["paired"]["errors"] == "run03_disp.csv"


def test_loggers_whose_times_do_not_overlap_are_refused_naming_the_files(tmp_path, capsys):
    folder = _folder(tmp_path / "runs")
    _run(folder, 2, ahead_s=86400.0)           # the probe PC's date a day ahead
    refused(["run", f"data.path={folder}", "data.roles.error=[dX]", "data.roles.state=[Door]",
             "data.test_fraction=0.34", *FAST, f"out={tmp_path / 'out'}"], capsys,
            f"file {folder / 'run02_temp.csv'}", "and run02_disp.csv's (2027-03-04T06:00:00",
            "have 0 error sample(s) in common", "data.join.offset_s")
    assert not (tmp_path / "out").exists()


def test_timestamps_in_one_file_and_seconds_in_the_other_are_refused(tmp_path, capsys):
    folder = _folder(tmp_path / "runs")
    _run(folder, 3, stamped=False)
    refused(["run", f"data.path={folder}", "data.roles.error=[dX]", "data.roles.state=[Door]",
             "data.test_fraction=0.34", *FAST, f"out={tmp_path / 'out'}"], capsys,
            f"file {folder / 'run03_temp.csv'}", "only run03_disp.csv has timestamps")


def test_files_of_two_loggers_named_apart_are_refused_saying_how_to_name_them(tmp_path, capsys):
    folder = tmp_path / "runs"
    folder.mkdir()
    _run(folder, 1)
    (folder / "run01_disp.csv").rename(folder / "laser.csv")
    (folder / "run01_temp.csv").rename(folder / "daq.csv")
    refused(["run", f"data.path={folder}", "data.roles.error=[dX]", "data.roles.state=[Door]",
             *FAST, f"out={tmp_path / 'out'}"], capsys,
            "laser.csv beside it holds errors", "run03_temp.csv and run03_disp.csv")
