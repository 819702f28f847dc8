"""A precision lathe's Graphtec GL840 CSV files, a file a run (stranger82): a header block, the
``Amp settings`` table naming each channel (``CH3`` is ``T_BETT``), then ``Data``: ``NO.``,
``Time``, ``ms``, the channels, the alarms, a unit row, signed values and ``BURNOUT`` for a
broken thermocouple (``benchmarks/bench_stranger82.py`` writes the lab's full record; these are
a few rows of test_stranger68's linear runs)."""

from __future__ import annotations

import datetime as dt
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, refused
from test_export import checked_pack, needs_cc
from test_stranger68 import ROWS, linear_run
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

# (signal name, unit) per channel: three thermocouples, the two probes, the carriage's Z
CHANNELS = [("T_HALLE", "degC"), ("T_SPINDEL", "degC"), ("T_BETT", "degC"), ("DX_DORN", "um"),
            ("DZ_DORN", "um"), ("Z_ISTWERT", "mm")]
START = dt.datetime(2027, 6, 7, 7)


def gl840(folder: Path, run: int, burnout: int = 0) -> Path:
    """``<yyMMdd>-070000.CSV``: linear_run's rows every 60 s, Z at 0 / 300 mm; ``burnout``
    samples of ``T_SPINDEL`` from row 40 written ``BURNOUT``."""
    folder.mkdir(parents=True, exist_ok=True)
    values = np.column_stack([linear_run(8211, run), np.where(np.arange(ROWS) % 40 < 20, 0, 300)])
    start = START + dt.timedelta(days=run - 1)
    n = len(CHANNELS)
    lines = ['"Model","GL840"', f'"Title","LAUF {run}"', f'"Trigger Time","\'{start:%Y/%m/%d %H:%M:%S}"',
             "", '"Amp settings"', '"CH","Signal name","Input","Range","Filter","Span","Unit"']
    lines += [f'"CH{i}","{name}","TEMP","TC_K","Off","0.0,100.0","{unit}"'
              for i, (name, unit) in enumerate(CHANNELS, start=1)]
    lines += ["", '"Data"',
              '"NO.","Time","ms",' + ",".join(f'"CH{i}"' for i in range(1, n + 1))
              + ',"Alarm1-10","AlarmOut"',
              '"","","",' + ",".join(f'"{u}"' for _, u in CHANNELS) + ',"",""']
    for k, row in enumerate(values):
        cells = [f"{v:+.5f}" for v in row]
        if 40 <= k < 40 + burnout:
            cells[1] = "BURNOUT"
        when = start + dt.timedelta(seconds=60 * k)
        lines.append(f"{k + 1},{when:%Y/%m/%d %H:%M:%S},0," + ",".join(cells) + ",LLLLLL,LLLL")
    path = folder / f"{start:%y%m%d-%H%M%S}.CSV"
    path.write_text("\r\n".join(lines) + "\r\n", encoding="ascii")
    return path


def test_a_folder_of_gl840_files_reads_its_channels_by_their_signal_names(tmp_path):
    """(Before: init refused the folder, "no column reads as a measured error ...; the numeric
    columns: none": its table starts below 31 lines of the logger's header block, its columns
    named CH1 ...)  The names are the Amp settings' signal names, the time the logger's
    date-time, a BURNOUT a missing value."""
    for run in (1, 2):
        gl840(tmp_path / "lathe", run, burnout=3 * (run == 2))
    ds, _ = read_dataset(tmp_path / "lathe", {"roles": {"error": ["D?_DORN"], "state": ["Z_*"]},
                                              "test_fraction": 0.5, "max_gap_samples": 3})
    assert list(ds.campaigns) == ["270607-070000", "270608-070000"]
    frame = ds.campaigns["270608-070000"]
    names = ["T_HALLE", "T_SPINDEL", "T_BETT", "E_DX_DORN", "E_DZ_DORN"]
    assert sorted(frame.columns) == sorted(["time", *names, "S_Z_ISTWERT"])
    np.testing.assert_array_equal(frame["time"], np.arange(ROWS) * 60.0)
    expected = linear_run(8211, 2)
    kept = np.r_[0:40, 43:ROWS]
    np.testing.assert_allclose(frame[names].to_numpy()[kept], expected[kept], atol=1e-5)
    gap = frame["T_SPINDEL"].to_numpy()[40:43]       # interpolated over the BURNOUT
    assert np.all((gap > min(expected[39, 1], expected[43, 1]) - 1e-9)
                  & (gap < max(expected[39, 1], expected[43, 1]) + 1e-9))
    assert str(ds.manifest["start"].iloc[1]) == "2027-06-08 07:00:00"


def test_init_proposes_a_gl840_folders_roles_and_gap(tmp_path, capsys):
    for run in (1, 2, 3):
        gl840(tmp_path / "lathe", run, burnout=4 * (run == 2))
    assert main(["init", str(tmp_path / "lathe"), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "a Graphtec logger's CSV" in said and "data.max_gap_samples=4" in said, said
    conf = (tmp_path / "init" / "conf" / "data" / "lathe.yaml").read_text()
    assert "error:\n  - DX_DORN\n  - DZ_DORN" in conf and "- Z_ISTWERT" in conf, conf


def test_a_gl840_file_piped_into_monitor_streams_as_the_file_does(tmp_path, monkeypatch, capsys):
    """(Before: "stdin is not a CSV table with a header, data.delimiter=',' (Error tokenizing
    data ...)": the logger's header block read as the table.)  The test run piped in as the
    logger wrote it streams to the RMSE its file streams to."""
    import io as _io
    import json

    for run in (1, 2):
        path = gl840(tmp_path / "lathe", run)
    common = ["monitor", f"data.path={tmp_path / 'lathe'}", "data.roles.error=[D?_DORN]",
              "data.roles.state=[Z_*]", "data.test_fraction=0.5", *FAST]
    assert main([*common, f"out={tmp_path / 'file'}"]) == 0
    monkeypatch.setattr("sys.stdin", _io.TextIOWrapper(_io.BytesIO(path.read_bytes())))
    assert main([*common, "monitor.input=-", f"out={tmp_path / 'pipe'}"]) == 0, capsys.readouterr().err
    said = [json.loads((tmp_path / k / "monitor.json").read_text())["targets"] for k in ("file", "pipe")]
    for target in ("E_DX_DORN", "E_DZ_DORN"):
        assert said[1][target]["n_samples"] == ROWS
        assert said[1][target]["rmse_fixed"] == pytest.approx(said[0][target]["rmse_fixed"], rel=1e-12)


def test_two_channels_given_one_signal_name_are_both_read(tmp_path):
    """(Before: one column was written for both, the second channel's values lost without a word:
    the lab file's channels laid into a table keyed by their header.)  The second is read as a
    CSV header written twice is, ``T_BETT#2``."""
    path = gl840(tmp_path / "lathe", 1)
    path.write_text(path.read_text().replace('"CH3","T_BETT"', '"CH3","T_SPINDEL"'))
    ds, _ = read_dataset(path, {"roles": {"error": ["D?_DORN"], "state": ["Z_*"]}})
    frame = pd.concat(ds.campaigns.values())
    assert {"T_SPINDEL", "T_SPINDEL_2"} <= set(frame.columns)
    expected = linear_run(8211, 1)
    np.testing.assert_allclose(frame[["T_SPINDEL", "T_SPINDEL_2"]], expected[:, 1:3], atol=1e-5)


def test_a_graphtec_binary_record_is_refused_saying_its_csv_is_read(tmp_path, capsys):
    """(Before: "its files, .gbd (2), are no kind read as a run (...)" alone: that the logger's
    CSV of the same runs is read, not said.)  A folder of them, and one given alone."""
    folder = tmp_path / "gl"
    folder.mkdir()
    for run in (1, 2):
        (folder / f"27060{run}-070000.GBD").write_bytes(bytes(range(256)) * 4)
    for path in (folder, folder / "270601-070000.GBD"):
        said = refused(["init", str(path), f"out={tmp_path / 'init'}"], capsys,
                       "a Graphtec logger's binary record: save its runs as CSV, which is read")
        assert str(path) in said


@needs_cc
def test_the_compiled_stream_refuses_a_gl840_file_naming_the_command_that_converts_it(
        tmp_path, capsys):
    """(Before: "the header (line 7 ...) lacks input column T_SPINDEL (the lab's header ...)", an
    Amp settings row taken for the header, while the file holds the channel.)  Refused at its first line, the
    command named; the rows it writes stream."""
    for run in (1, 2):
        path = gl840(tmp_path / "lathe", run)
    common = [f"data.path={tmp_path / 'lathe'}", "data.roles.error=[D?_DORN]",
              "data.roles.state=[Z_*]", "data.test_fraction=0.5"]
    assert main(["run", *common, *FAST, "model=mlr", f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, "track=false", "export.format=c",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 0
    checked_pack(tmp_path / "code")
    stream = str(tmp_path / "code" / "stream")
    done = subprocess.run([stream], capture_output=True, input=path.read_bytes())
    assert done.returncode == 2 and done.stdout == b""
    assert (b"stream: line 1 is a Graphtec logger's header block (\"Model\",\"GL...\"): its channels "
            b"are named in its Amp settings, its columns CH1 ...; convert it to the rows the served "
            b"model reads it as: `thermocomp rows FILE") in done.stderr, done.stderr
    capsys.readouterr()
    assert main(["rows", str(path), *common[1:3]]) == 0
    rows = capsys.readouterr().out
    streamed = subprocess.run([stream], capture_output=True, input=rows.encode())
    assert streamed.returncode == 0, streamed.stderr
    assert len(streamed.stdout.decode().splitlines()) == ROWS + 1
