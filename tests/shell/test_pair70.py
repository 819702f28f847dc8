"""Two loggers per run rounded out (pair70; test_twolog70's lathe runs, a few rows): ``init``
detects the error files' own marks and time since the start as it does the temperature files',
and a manifest names a run's error file (``error_file``) where the two are named apart."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, refused
from test_twolog70 import CFG, _error, _folder
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main


def _init(folder: Path, out: Path, *args: str) -> list[str]:
    """``thermocomp init`` on ``folder``; the data config's override pair for ``run``."""
    assert main(["init", str(folder), "data.roles.error=[dX]", *args, f"out={out}"]) == 0
    return [f"hydra.searchpath=[file://{out / 'conf'}]", f"data={folder.name}"]


def _as_elapsed(seconds) -> list[str]:
    return [f"{int(s // 3600)}:{int(s % 3600 // 60):02d}:{int(s % 60):02d}" for s in seconds]


def test_init_reads_the_marks_the_error_files_write_out_of_range(tmp_path, capsys):
    """The probe software writes '---' (or 'n.a.') where a probe was out of range: before,
    init scanned the temperature files alone and refused the record at '---'."""
    folder = _folder(tmp_path / "runs")
    for run, row, mark in ((1, 5, "---"), (2, 9, "n.a.")):
        path = folder / f"run{run:02d}_disp.csv"
        lines = path.read_text().splitlines()
        lines[row] = lines[row].split(";")[0] + f";{mark}"
        path.write_text("\n".join(lines) + "\n")
    data = _init(folder, tmp_path / "init")
    said = capsys.readouterr().out
    assert "'---' in 1 cell of number column 'dX [µm]'" in said
    conf = (tmp_path / "init" / "conf" / "data" / "runs.yaml").read_text(encoding="utf-8")
    assert "missing_values:\n- '---'\n- n.a.\nmax_gap_samples: 1" in conf
    assert main(["run", *data, "model=mlr", *FAST, f"out={tmp_path / 'out'}"]) == 0
    report = json.loads((tmp_path / "out" / "metrics.json").read_text())
    assert report["targets"]["E_dX"]["test"]["rmse"] < 0.05     # (1.44 uncompensated)


def _elapsed_runs(root: Path, temp_header: str | None) -> Path:
    """The probe software's time since its start, ``h:mm:ss`` under 'Zeit'; the DAQ's too under
    ``temp_header`` (None: its timestamps kept)."""
    folder = _folder(root)
    for run in (1, 2, 3):
        disp = pd.read_csv(folder / f"run{run:02d}_disp.csv", sep=";", dtype=str)
        disp.insert(0, "Zeit", _as_elapsed(np.arange(len(disp)) * 60.0))
        disp.drop(columns="Zeitstempel").to_csv(folder / f"run{run:02d}_disp.csv", sep=";",
                                                index=False)
        if temp_header is not None:
            temp = pd.read_csv(folder / f"run{run:02d}_temp.csv", dtype=str)
            temp["Time"] = _as_elapsed(np.arange(len(temp)) * 10.0)
            temp.rename(columns={"Time": temp_header}).to_csv(
                folder / f"run{run:02d}_temp.csv", index=False)
    return folder


def test_init_reads_both_loggers_time_since_their_start_as_elapsed(tmp_path, capsys):
    """The DAQ's 'Elapsed time' read as elapsed by its header, the probes' 'Zeit' refused as a
    time of day: init writes data.time=elapsed, which reads both."""
    folder = _elapsed_runs(tmp_path / "runs", "Elapsed time")
    data = _init(folder, tmp_path / "init")
    assert ("run01_temp.csv and run01_disp.csv: 'Zeit' h:mm:ss as the temperatures' time: read "
            "as data.time='elapsed'") in capsys.readouterr().out
    ds = read_dataset(folder, {**CFG, "time": "elapsed"})[0]
    np.testing.assert_allclose(ds.campaigns["run01"]["E_dX"],
                               _error(np.arange(0.0, 1200.0 + 1e-9, 60.0), 1), atol=1e-4)
    assert main(["run", *data, "model=mlr", *FAST, f"out={tmp_path / 'out'}"]) == 0


def test_init_refuses_the_probes_elapsed_time_beside_the_daqs_timestamps(tmp_path, capsys):
    """Before: refused as a time of day, naming data.time=elapsed, which refuses the DAQ's
    timestamps in turn; now one line naming both files' times."""
    folder = _elapsed_runs(tmp_path / "runs", None)
    refused(["init", str(folder), "data.roles.error=[dX]", f"out={tmp_path / 'init'}"], capsys,
            f"file {folder / 'run01_disp.csv'}, column 'Zeit': its time 'Zeit' ('0:00:00') is "
            "h:mm:ss, a logger's time since its start, and run01_temp.csv's 'Time' timestamps",
            "export both files with timestamps")
    assert not (tmp_path / "init").exists()


def _named_apart(root: Path, error_files: list[str]) -> Path:
    """The runs' files renamed as two loggers name them (``daq_01.csv``, ``laser_01.csv``), a
    manifest naming each run's error file."""
    folder = _folder(root)
    for run in (1, 2, 3):
        (folder / f"run{run:02d}_temp.csv").rename(folder / f"daq_{run:02d}.csv")
        (folder / f"run{run:02d}_disp.csv").rename(folder / f"laser_{run:02d}.csv")
    rows = [f"{cid},daq_{run:02d}.csv,{split},{name}" for run, (cid, split, name)
            in enumerate(zip("ABC", ("train", "train", "test"), error_files), 1)]
    (folder / "campaigns.csv").write_text("campaign,file,split,error_file\n" + "\n".join(rows)
                                          + "\n")
    return folder


def test_a_manifest_names_each_runs_error_file(tmp_path, capsys):
    folder = _named_apart(tmp_path / "runs", ["laser_01.csv", "laser_02.csv", "laser_03.csv"])
    ds, report = read_dataset(folder, {**CFG, "test_fraction": None})
    assert list(ds.campaigns["C"].columns) == ["time", "T_Spindle", "T_Bed", "E_dX", "S_Door"]
    assert report["campaigns"]["B"]["paired"]["errors"] == "laser_02.csv"
    data = _init(folder, tmp_path / "init")
    assert "A: two loggers, daq_01.csv (every 10 s) + laser_01.csv" in capsys.readouterr().out
    assert main(["run", *data, "model=mlr", *FAST, f"out={tmp_path / 'out'}"]) == 0
    run = json.loads((tmp_path / "out" / "metrics.json").read_text())["targets"]["E_dX"]
    assert main(["replay", *data, f"replay.model={tmp_path / 'out' / 'model.pkl'}",
                 "promote.envelope.policy=off", "track=false", f"out={tmp_path / 'replay'}"]) == 0
    replay = json.loads((tmp_path / "replay" / "replay.json").read_text())["targets"]["E_dX"]
    assert replay["rmse"] == pytest.approx(run["test"]["rmse"], rel=1e-9, abs=1e-12)
    # ingest writes the runs joined: no error file beside them to name
    assert main(["ingest", *data, f"data.interim={tmp_path / 'interim'}", "track=false",
                 f"out={tmp_path / 'ingest'}"]) == 0
    written = pd.read_csv(tmp_path / "interim" / "campaigns.csv")
    assert "error_file" not in written.columns
    assert read_dataset(tmp_path / "interim")[0].campaigns["C"].equals(ds.campaigns["C"])


@pytest.mark.parametrize("name, says", [
    ("laser_3.csv", "error file 'laser_3.csv' not found in"),
    ("daq_01.csv", "error file 'daq_01.csv' is the campaign file of row 1")])
def test_a_manifests_error_file_that_is_no_run_file_is_refused_naming_its_row(tmp_path, capsys,
                                                                               name, says):
    folder = _named_apart(tmp_path / "runs", ["laser_01.csv", "laser_02.csv", name])
    refused(["run", f"data.path={folder}", "data.roles.error=[dX]", "data.roles.state=[Door]",
             *FAST, f"out={tmp_path / 'out'}"], capsys,
            f"file {folder / 'campaigns.csv'}, column 'error_file', data row 3", says)
    assert not (tmp_path / "out").exists()
