"""A gantry mill's Beckhoff TwinCAT Scope exports (stranger76): one CSV per run as a German
Windows' Scope View writes it (Windows-1252, ``;``, decimal commas), a preamble (``StartTime``
in Windows FILETIME ticks), a row per channel property, then every channel its own ``Time``
(ms) and value columns, a laser tracker's channels (mm) every 6th sample, empty below their
last (``benchmarks/bench_stranger76.py`` writes the lab's full record; these are a few rows of
test_stranger68's linear runs)."""

from __future__ import annotations

import datetime as dt
import io
import json
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, refused
from test_export import checked_pack, needs_cc, own_expected
from test_stranger68 import ROWS, linear_run
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

NAMES = ["Temp Luft", "Temp Ständer", "Temp Spindel", "Tracker dX", "Tracker dZ"]
UNITS = ["°C", "°C", "°C", "mm", "mm"]
EVERY = 6                           # the tracker's samples: every 6th of the temperatures'
PERIOD_MS = 10000


def _filetime(at: dt.datetime) -> int:
    return int((at - dt.datetime(1601, 1, 1)).total_seconds() * 10**7)


def _scope(path: Path, start: dt.datetime, values: np.ndarray) -> Path:
    """``values`` (°C, µm) as the Scope exports them: the errors in mm, every ``EVERY``th row."""
    def num(v: float, digits: int) -> str:
        return f"{v:.{digits}f}".replace(".", ",")

    samples = []
    for j, unit in enumerate(UNITS):
        rows = range(0, ROWS, EVERY if unit == "mm" else 1)
        samples.append([(i * PERIOD_MS, num(values[i, j] / 1000, 6) if unit == "mm"
                         else num(values[i, j], 3)) for i in rows])
    props = [("Name", NAMES), ("Data-Type", ["REAL64"] * 5),
             ("SampleTime[ms]", [str(PERIOD_MS * (EVERY if u == "mm" else 1)) for u in UNITS]),
             ("SymbolName", [f"MAIN.fValue[{j}]" for j in range(5)]), ("Unit", UNITS)]
    lines = ["Name;Portal;", r"File;C:\TwinCAT\Scope\Portal.tcscopex;",
             f"StartTime;{_filetime(start)};{start:%d.%m.%Y %H:%M:%S},000", ""]
    lines += [";".join(f"{key};{v};" for v in cells) for key, cells in props]
    lines += ["", ";".join("Time;Value;" for _ in NAMES)]
    for i in range(ROWS):
        lines.append(";".join(f"{s[i][0]};{s[i][1]};" if i < len(s) else ";;" for s in samples))
    path.write_bytes("\r\n".join(lines).encode("cp1252") + b"\r\n")
    return path


def _folder(root: Path) -> Path:
    root.mkdir()
    for run in (1, 2, 3):
        _scope(root / f"Scope_Portal_{run}.csv", dt.datetime(2027, 2, 1 + 7 * run, 5),
               linear_run(7671, run))
    return root


def test_a_folder_of_scope_exports_reads_each_channel_at_its_own_time(tmp_path):
    ds, _ = read_dataset(_folder(tmp_path / "runs"),
                         {"roles": {"error": ["Tracker*"]}, "encoding": "cp1252",
                          "test_fraction": 0.34})
    assert list(ds.manifest["split"]) == ["train", "train", "test"]
    # StartTime's FILETIME ticks are UTC: the run started 05:00 UTC
    assert ds.manifest["start"].iloc[1] == pd.Timestamp("2027-02-15 05:00", tz="UTC")
    frame = ds.campaigns["Scope_Portal_2"]
    assert list(frame.columns) == ["time", "T_Luft", "T_Ständer", "T_Spindel",
                                   "E_Tracker_dX", "E_Tracker_dZ"]
    np.testing.assert_array_equal(frame["time"], np.arange(ROWS) * 10.0)
    want = linear_run(7671, 2)
    np.testing.assert_allclose(frame.iloc[:, 1:4], want[:, :3], atol=5e-4)
    # the tracker's mm read as µm on its own rows, empty between them (never held)
    measured = np.arange(ROWS) % EVERY == 0
    np.testing.assert_allclose(frame["E_Tracker_dX"][measured], want[measured, 3], atol=5e-4)
    assert frame["E_Tracker_dX"][~measured].isna().all()


def test_init_reads_the_exports_and_its_config_runs(tmp_path, capsys):
    folder = _folder(tmp_path / "runs")
    assert main(["init", str(folder), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert ("Scope_Portal_1.csv: a TwinCAT Scope export (its channels as columns), encoding "
            "cp1252 (not UTF-8), delimiter ';', decimal ','") in said
    assert any(line.split() == ["Tracker", "dX", "[mm]", "error", "E_Tracker_dX"]
               for line in said.splitlines())
    assert main(["run", f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=runs",
                 "model=mlr", *FAST, f"out={tmp_path / 'out'}"]) == 0
    metrics = json.loads((tmp_path / "out" / "metrics.json").read_text())
    assert metrics["targets"]["E_Tracker_dX"]["test"]["rmse"] < 0.2     # (the map is linear)


def test_a_cell_that_is_no_number_is_refused_naming_file_channel_and_line(tmp_path, capsys):
    folder = _folder(tmp_path / "runs")
    path = folder / "Scope_Portal_2.csv"
    lines = path.read_bytes().split(b"\r\n")
    cells = lines[20].split(b";")
    cells[4] = b"Overflow"                      # (the second channel's value)
    lines[20] = b";".join(cells)
    path.write_bytes(b"\r\n".join(lines))
    refused(["run", f"data.path={folder}", "data.roles.error=[Tracker*]", "data.encoding=cp1252",
             "data.test_fraction=0.34", *FAST, f"out={tmp_path / 'out'}"], capsys,
            f"file {path}, column 'Temp Ständer', line 21: cell 'Overflow' is no number "
            "(decimal ',')")
    assert not (tmp_path / "out").exists()


def test_the_export_piped_into_monitor_streams_as_the_file_is_read(tmp_path, monkeypatch, capsys):
    """The test run's export as written on stdin (it ended in a traceback, 'The truth value of
    a Series is ambiguous', reading the preamble as a header)."""
    folder = _folder(tmp_path / "runs")
    monitor = ["monitor", f"data.path={folder}", "data.roles.error=[Tracker*]",
               "data.encoding=cp1252", "data.test_fraction=0.34", *FAST]
    assert main([*monitor, f"out={tmp_path / 'file'}"]) == 0
    text = (folder / "Scope_Portal_3.csv").read_bytes().decode("cp1252")
    monkeypatch.setattr("sys.stdin", io.StringIO(text))
    assert main([*monitor, "monitor.input=-", f"out={tmp_path / 'piped'}"]) == 0
    from_file, piped = (json.loads((tmp_path / name / "monitor.json").read_text())["targets"]
                        for name in ("file", "piped"))
    for target in ("E_Tracker_dX", "E_Tracker_dZ"):
        assert piped[target]["rmse_fixed"] == pytest.approx(from_file[target]["rmse_fixed"],
                                                            rel=1e-9)


@needs_cc
def test_the_compiled_stream_refuses_a_scope_export_naming_the_command_that_converts_it(
        tmp_path, capsys):
    """Before stranger76: it took the row of channel names for its header, read the property
    rows under it as samples, printed a correction of 'VariableSize;8;...' and stopped at
    'True'.  Before lab77: refused, told to stream 'the samples as one CSV table' with no way
    to write one; lab77 named a module (``python -m thermocomp.shell.scope_rows``), which wrote
    the lab's headers.  lab78: it names ``thermocomp rows``, which reads the export with the
    model's data config and writes its rows under the model's names, streamed as the pack's
    rows are; the export as a new run's file (no split), its corrections the pack's."""
    folder = _folder(tmp_path / "runs")
    config = ["data.roles.error=[Tracker*]", "data.encoding=cp1252"]
    common = [f"data.path={folder}", *config, "data.test_fraction=0.34"]
    assert main(["run", *common, *FAST, "model=mlr", f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, "track=false", "export.format=c",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 0
    checked_pack(tmp_path / "code")
    done = subprocess.run([str(tmp_path / "code" / "stream")], capture_output=True,
                          input=(folder / "Scope_Portal_3.csv").read_bytes())
    assert done.returncode == 2 and done.stdout == b""
    assert (b"stream: line 5 is a TwinCAT Scope export's row of channel names (Name;<channel>;;"
            b"Name;...): the export is not read here; convert it to the rows the served model "
            b"reads it as: `thermocomp rows FILE [its data config: data=<name> that thermocomp "
            b"init wrote, data.*] > rows.csv`") in done.stderr
    capsys.readouterr()
    assert main(["rows", str(folder / "Scope_Portal_3.csv"), *config]) == 0
    rows = capsys.readouterr().out
    assert rows.splitlines()[0] == "time,T_Luft,T_Ständer,T_Spindel"
    streamed = subprocess.run([str(tmp_path / "code" / "stream")], capture_output=True,
                              input=rows.encode(), check=True).stdout
    got = pd.read_csv(io.BytesIO(streamed))
    want = pd.read_csv(own_expected(tmp_path / "code")[0])
    assert list(got.columns) == list(want.columns) and len(got) == len(want)
    np.testing.assert_allclose(got.to_numpy(float), want.to_numpy(float), rtol=0, atol=1e-9)
    # a broken export: refused naming file, channel and line, nothing on stdout
    path = folder / "Scope_Portal_2.csv"
    lines = path.read_bytes().split(b"\r\n")
    cells = lines[20].split(b";")
    cells[4] = b"Overflow"
    lines[20] = b";".join(cells)
    path.write_bytes(b"\r\n".join(lines))
    assert main(["rows", str(path), *config]) == 2
    broken = capsys.readouterr()
    assert broken.out == ""
    assert (f"file {path}, column 'Temp Ständer', line 21: cell 'Overflow' is no number "
            "(decimal ',')") in broken.err
