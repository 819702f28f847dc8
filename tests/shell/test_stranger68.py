"""A lab's Excel macro export of a turn-mill centre's runs (stranger68): one workbook, a cover
sheet then a sheet per run, a two-row header whose time column is merged down over the group
row, a unit row giving the B axis' ``°``, an empty row and a ``Maximum`` row under each table
(``benchmarks/bench_stranger68.py`` writes the lab's full record; these are a few rows of it)."""

from __future__ import annotations

import datetime as dt
import json
from pathlib import Path

import numpy as np
import openpyxl
import pandas as pd
import pytest

from conftest import FAST, refused
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

CFG = {"roles": {"error": ["d*"], "state": ["B axis"]}, "test_fraction": 0.34}
NAMES = ["Air", "Column", "B head", "dX", "dZ", "B axis"]
UNITS = ["°C", "°C", "°C", "µm", "µm", "°"]
ROWS = 120


def linear_run(seed: int, run: int) -> np.ndarray:
    """A run's ``ROWS`` rows of three temperatures and two errors their linear map (dX, dZ)."""
    rng = np.random.default_rng(seed + run)
    t = np.arange(ROWS) / ROWS
    temps = 20 + np.column_stack([0.5 * np.sin(6 * t + run), 2 * t + 0.1 * run, 4 * t ** 0.5])
    temps += rng.normal(0, 0.02, temps.shape)
    dx = 3 * (temps[:, 2] - temps[0, 2]) - 2 * (temps[:, 1] - temps[0, 1])
    dz = 5 * (temps[:, 2] - temps[0, 2]) + (temps[:, 0] - temps[0, 0])
    return np.column_stack([temps, dx, dz])


def _values(run: int) -> np.ndarray:
    """A run's rows: :func:`linear_run`'s, B at 0 / 90 degrees."""
    b = np.where((np.arange(ROWS) // 30) % 2, 90.0, 0.0)
    return np.round(np.column_stack([linear_run(6853, run), b]), 3)


def _run_sheet(sheet, run: int, start: dt.datetime) -> None:
    width = 1 + len(NAMES)
    sheet.append([f"MTC 800 - thermal test, run {run}"])
    sheet.merge_cells(start_row=1, start_column=1, end_row=1, end_column=width)
    sheet.append([])
    sheet.append(["Date / time", "Temperatures", None, None, "Displacement", None, "NC"])
    sheet.append([None, *NAMES])
    sheet.append([None, *UNITS])
    sheet.merge_cells(start_row=3, start_column=1, end_row=4, end_column=1)
    sheet.merge_cells(start_row=3, start_column=2, end_row=3, end_column=4)
    sheet.merge_cells(start_row=3, start_column=5, end_row=3, end_column=6)
    values = _values(run)
    for k, row in enumerate(values):
        sheet.append([start + dt.timedelta(minutes=k), *map(float, row)])
    sheet.append([])
    sheet.append(["Maximum", *map(float, values.max(axis=0))])


def _cover(book, runs: int) -> None:
    info = book.active
    info.title = "Info"
    for row in (("Thermal test", "MTC 800 turn-mill centre"), ("Runs", runs),
                ("Sample period", "60 s"), (), ("Sensor", "Position", "Type"),
                ("Air", "beside the machine", "Pt100"), ("B head", "B-axis head", "Pt100")):
        info.append(list(row))


def _workbook(path: Path, runs: int = 3) -> Path:
    book = openpyxl.Workbook()
    _cover(book, runs)
    for run in range(1, runs + 1):
        _run_sheet(book.create_sheet(f"Run {run}"), run, dt.datetime(2027, 6, 12 + 2 * run, 6))
    book.save(path)
    return path


def test_a_workbook_of_run_sheets_behind_a_cover_reads_each_sheet_as_a_campaign(tmp_path):
    book = _workbook(tmp_path / "MTC800.xlsx")
    ds, report = read_dataset(book, CFG)
    assert list(ds.manifest.index) == ["Run_1", "Run_2", "Run_3"]
    assert list(ds.manifest["split"]) == ["train", "train", "test"]
    for run in (1, 2, 3):
        frame = ds.campaigns[f"Run_{run}"]
        # the merged 'Date / time' names the time; the unit row's '°' makes B a state; the
        # 'Maximum' row under the empty row is no sample
        assert list(frame.columns) == ["time", "T_Air", "T_Column", "T_B_head", "E_dX", "E_dZ",
                                       "S_B_axis"]
        assert len(frame) == ROWS and frame["time"].iloc[-1] == (ROWS - 1) * 60.0
        np.testing.assert_allclose(frame.iloc[:, 1:].to_numpy(), _values(run))
    assert report["campaigns"]["Run_2"]["sheet"] == "Run 2"


def test_init_and_run_on_the_workbook_say_the_sheets_read_and_left_out(tmp_path, capsys):
    book = _workbook(tmp_path / "MTC800.xlsx")
    assert main(["init", str(book), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr()
    assert ("its 3 sheets of one table ('Run 1', 'Run 2', 'Run 3') read as campaigns, one run a "
            "sheet; left out: 'Info'") in said.err
    assert "MTC800.xlsx: sheet 'Run 1', header on row 4 (3 row(s) above it left out)" in said.out
    assert "campaign Run_3: test" in said.out
    assert main(["run", f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=MTC800",
                 "model=mlr", *FAST, f"out={tmp_path / 'out'}"]) == 0
    metrics = json.loads((tmp_path / "out" / "metrics.json").read_text())
    assert set(metrics["targets"]) == {"E_dX", "E_dZ"}
    assert metrics["targets"]["E_dX"]["test"]["rmse"] < 0.2        # (the map is linear)


def test_a_folder_of_workbooks_each_behind_its_cover_reads_each_ones_table(tmp_path):
    folder = tmp_path / "runs"
    folder.mkdir()
    for run in (1, 2, 3):
        book = openpyxl.Workbook()
        _cover(book, 1)
        _run_sheet(book.create_sheet("Data"), run, dt.datetime(2027, 7, 4 + run, 6))
        book.save(folder / f"Run_{run:02d}.xlsx")
    ds, _ = read_dataset(folder, CFG)
    assert list(ds.manifest["split"]) == ["train", "train", "test"]
    np.testing.assert_allclose(ds.campaigns["Run_02"].iloc[:, 1:].to_numpy(), _values(2))


def test_a_folders_workbook_of_several_run_sheets_is_refused_naming_what_reads_it(tmp_path,
                                                                                   capsys):
    folder = tmp_path / "runs"
    folder.mkdir()
    _workbook(folder / "week1.xlsx")
    _workbook(folder / "week2.xlsx")
    refused(["run", f"data.path={folder}", "data.roles.error=[d*]", "data.test_fraction=0.5",
             *FAST, f"out={tmp_path / 'out'}"], capsys,
            f"{folder / 'week1.xlsx'}: 3 runs in one workbook, a sheet each ('Run 1', 'Run 2', "
            "'Run 3'): a folder's file is one campaign; give this workbook as data.path")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("unit", ["°", "deg"])
def test_a_csv_unit_row_with_an_axis_angle_gives_the_headers_their_units(tmp_path, unit):
    """The unit row under the header holds ``°`` (the B axis'): a unit row (it was read as a
    row of data, every unit a mark for a value not measured, and no error column was found)."""
    values = _values(1)
    lines = ["Zeit;" + ";".join(NAMES), ";" + ";".join([*UNITS[:-1], unit])]
    lines += [f"{k * 60};" + ";".join(f"{v:g}" for v in row) for k, row in enumerate(values)]
    path = tmp_path / "run.csv"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    ds, _ = read_dataset(path, {"roles": {"time": "Zeit", "error": ["d*"]}, "test_fraction": 0.25})
    frame = pd.concat(ds.campaigns.values())
    assert list(frame.columns)[1:] == ["T_Air", "T_Column", "T_B_head", "E_dX", "E_dZ",
                                       "S_B_axis"]
    np.testing.assert_allclose(frame["S_B_axis"].to_numpy(), values[:, -1])


def test_a_summary_row_under_an_empty_row_of_cells_is_left_out(tmp_path, capsys):
    """Excel's CSV export writes the sheet's empty row as a line of separators: the ``Maximum``
    row under it is a summary, left out (it was read as a sample, its time refused)."""
    values = _values(2)
    lines = ["time [s],dX [µm],T1 [°C]"]
    lines += [f"{k * 60},{row[3]:g},{row[0]:g}" for k, row in enumerate(values)]
    lines += [",,", f"Maximum,{values[:, 3].max():g},{values[:, 0].max():g}"]
    path = tmp_path / "run.csv"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    ds, _ = read_dataset(path, {"roles": {"error": ["dX"]}, "test_fraction": 0.25})
    assert sum(len(f) for f in ds.campaigns.values()) == ROWS


def test_a_name_merged_down_over_the_group_row_names_its_column(tmp_path):
    """One sheet, no cover, no angle: the time's name stands in the cell merged down over the
    group row and the names row (the names row's cell is empty as openpyxl reads it)."""
    book = openpyxl.Workbook()
    _run_sheet(book.active, 1, dt.datetime(2027, 6, 14, 6))
    book.active.cell(row=5, column=1 + NAMES.index("B axis") + 1, value="-")    # (not '°')
    book.active.delete_rows(book.active.max_row - 1, 2)                          # no 'Maximum'
    book.save(tmp_path / "run.xlsx")
    ds, report = read_dataset(tmp_path / "run.xlsx", CFG)
    frame = pd.concat(ds.campaigns.values())
    assert frame["time"].iloc[-1] == (ROWS - 1) * 60.0
    assert report["column_map"]["Date / time"] == "time"
