"""A lab's LabVIEW Measurement Files of a gear grinder's runs (stranger69): one ``.lvm`` per run as
NI's "Write To Measurement File" writes it, a German LabVIEW's (Windows-1252, decimal commas)
with an ``X_Value`` column in one segment, or without an X column in a segment per hour, the
time then only in the segment headers; a chiller's set point logged in ``Deg C``
(``benchmarks/bench_stranger69.py`` writes the lab's full record; these are a few rows of it)."""

from __future__ import annotations

import datetime as dt
import json
from pathlib import Path

import numpy as np
import pytest

from conftest import FAST, refused
from test_stranger68 import ROWS, linear_run
from thermocomp.core.io import read_dataset
from thermocomp.core.io.units import role_by_unit
from thermocomp.shell.cli import main

NAMES = ["Luft", "Ständer", "Rundtisch", "dX", "dZ", "X-Achse", "Sollwert Ölkühler"]
UNITS = ["Deg C", "Deg C", "Deg C", "um", "um", "mm", "Deg C"]
CFG = {"roles": {"error": ["d*"], "state": ["X-Achse", "Sollwert*"]}, "encoding": "cp1252",
       "test_fraction": 0.34}


def _values(run: int) -> np.ndarray:
    """A run's rows: test_stranger68's three temperatures and two errors, X and the set point."""
    x = np.where((np.arange(ROWS) // 30) % 2, 450.0, 150.0)
    set_c = np.where(np.arange(ROWS) < 70, 21.0, 22.0)
    return np.round(np.column_stack([linear_run(6903, run), x, set_c]), 3)


def _lvm(path: Path, start: dt.datetime, values: np.ndarray, decimal: str = ",",
         x_column: bool = True, segment_rows: int | None = None, skip: tuple = ()) -> Path:
    """``values`` as the Express VI writes them (``skip``: segments not written, an hour the VI
    did not log); CRLF, Windows-1252."""
    def num(v: float, digits: int = 6) -> str:
        return f"{v:.{digits}f}".replace(".", decimal)

    def clock(at: dt.datetime) -> tuple[str, str]:
        return at.strftime("%Y/%m/%d"), f"{at:%H:%M:%S}{decimal}0000000000"

    k = len(NAMES)
    date, time = clock(start)
    lines = ["LabVIEW Measurement\t", "Writer_Version\t2", "Reader_Version\t2", "Separator\tTab",
             f"Decimal_Separator\t{decimal}", "Multi_Headings\tNo",
             f"X_Columns\t{'One' if x_column else 'No'}",
             f"Time_Pref\t{'Relative' if x_column else 'Absolute'}", "Operator\tM. Brandt",
             f"Date\t{date}", f"Time\t{time}", "***End_of_Header***\t", ""]
    rows = segment_rows or len(values)
    for s, first in enumerate(range(0, len(values), rows)):
        if s in skip:
            continue
        at = start + dt.timedelta(minutes=first)
        d, t = clock(at)
        x0 = first * 60.0 if x_column else 3.9e9 + first * 60.0      # (1904's seconds)
        lines += [f"Channels\t{k}\t", "Samples\t" + f"{rows}\t" * k, "Date\t" + f"{d}\t" * k,
                  "Time\t" + f"{t}\t" * k, "Y_Unit_Label\t" + "\t".join(UNITS) + "\t",
                  "X_Dimension\t" + "Time\t" * k, "X0\t" + f"{num(x0, 4)}E+0\t" * k,
                  "Delta_X\t" + f"{num(60.0)}\t" * k, "***End_of_Header***\t",
                  "\t".join((["X_Value"] if x_column else []) + NAMES + ["Comment"])]
        for i, row in enumerate(values[first:first + rows]):
            lines.append("\t".join(([num((first + i) * 60.0)] if x_column else [])
                                   + [num(v) for v in row]))
        lines.append("")
    path.write_bytes("\r\n".join(lines).encode("cp1252"))
    return path


def _folder(root: Path, **kw) -> Path:
    root.mkdir()
    for run in (1, 2, 3):
        _lvm(root / f"ZP1200_Lauf_{run:02d}.lvm", dt.datetime(2027, 9, 4 + 2 * run, 6),
             _values(run), **kw)
    return root


def test_a_folder_of_german_lvm_files_reads_each_as_a_campaign_timed_by_its_header(tmp_path):
    folder = _folder(tmp_path / "runs")
    ds, _ = read_dataset(folder, CFG)
    assert list(ds.manifest["split"]) == ["train", "train", "test"]
    assert list(ds.manifest["start"]) == [np.datetime64(f"2027-09-{d:02d}T06:00") for d in
                                          (6, 8, 10)]
    frame = ds.campaigns["ZP1200_Lauf_02"]
    assert list(frame.columns) == ["time", "T_Luft", "T_Ständer", "T_Rundtisch", "E_dX", "E_dZ",
                                   "S_X-Achse", "S_Sollwert_Ölkühler"]
    assert frame["time"].iloc[-1] == (ROWS - 1) * 60.0
    np.testing.assert_allclose(frame.iloc[:, 1:].to_numpy(), _values(2))


def test_segments_without_an_x_column_are_timed_by_their_own_headers(tmp_path):
    """No ``X_Value`` column, a segment per 30 rows, the second not written (the VI stopped for
    half an hour): the rows after it are read at their segment's Date and Time, not one
    ``Delta_X`` after the rows before."""
    path = _lvm(tmp_path / "Lauf.lvm", dt.datetime(2027, 9, 27, 6), _values(1), decimal=".",
                x_column=False, segment_rows=30, skip=(1,))
    ds, _ = read_dataset(path, {**CFG, "test_fraction": None, "max_gap_samples": 0})
    frame = ds.campaigns["Lauf"]
    expected = np.r_[np.arange(30), np.arange(60, ROWS)] * 60.0
    np.testing.assert_array_equal(frame["time"].to_numpy(), expected)
    np.testing.assert_allclose(frame["E_dX"].to_numpy(), np.r_[_values(1)[:30, 3],
                                                              _values(1)[60:, 3]])


def test_init_and_run_on_the_lvm_folder(tmp_path, capsys):
    folder = _folder(tmp_path / "runs")
    assert main(["init", str(folder), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    # an axis named alone, in mm, spanning 300 mm: its position (it was refused as either)
    assert "'X-Achse [mm]' spans 300 mm: more than a thermal error does (5 mm)" in said
    assert "X-Achse [mm]               state        S_X-Achse" in said
    # the file's own text said, not the temporary CSV's (',' and '.')
    assert ("ZP1200_Lauf_01.lvm: a LabVIEW Measurement File (its channels as columns), encoding "
            "cp1252 (not UTF-8), Separator Tab, Decimal_Separator ','") in said
    assert "timestamps from 2027-09-06T06:00:00" in said
    # a set point in the temperature's unit is told the control, no sensor: a state
    assert "Sollwert Ölkühler [Deg C]  state        S_Sollwert_Ölkühler" in said
    conf = (tmp_path / "init" / "conf" / "data" / "runs.yaml").read_text(encoding="utf-8")
    assert "encoding: cp1252" in conf
    assert main(["run", f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=runs",
                 "model=mlr", *FAST, f"out={tmp_path / 'out'}"]) == 0
    metrics = json.loads((tmp_path / "out" / "metrics.json").read_text())
    assert metrics["targets"]["E_dX"]["test"]["rmse"] < 0.2        # (the map is linear)


def test_a_cell_that_is_no_number_is_refused_naming_file_channel_and_line(tmp_path, capsys):
    folder = _folder(tmp_path / "runs")
    path = folder / "ZP1200_Lauf_02.lvm"
    lines = path.read_bytes().split(b"\r\n")
    cells = lines[30].split(b"\t")
    cells[4] = b"Overflow"                       # (the X column first: 'dX')
    lines[30] = b"\t".join(cells)
    path.write_bytes(b"\r\n".join(lines))
    refused(["run", f"data.path={folder}", "data.roles.error=[d*]",
             "data.roles.state=[X-Achse,Sollwert*]", "data.encoding=cp1252",
             "data.test_fraction=0.34", *FAST, f"out={tmp_path / 'out'}"], capsys,
            f"file {path}, column 'dX', line 31: cell 'Overflow' is no number (the file's "
            "Decimal_Separator is ',')")
    assert not (tmp_path / "out").exists()


def test_a_file_named_lvm_that_is_no_labview_measurement_file_is_refused(tmp_path, capsys):
    folder = tmp_path / "runs"
    folder.mkdir()
    (folder / "run1.lvm").write_text("t;T1;dX\n0;20;0\n60;20.1;0.2\n", encoding="utf-8")
    refused(["init", str(folder), f"out={tmp_path / 'init'}"], capsys,
            f"file {folder / 'run1.lvm'}, line 1: not a LabVIEW Measurement File: its first line "
            "is not 'LabVIEW Measurement'")


@pytest.mark.parametrize("name, unit", [("Sollwert Ölkühler", "Deg C"), ("Oil set point", "°C"),
                                        ("Chiller setpoint", "degC"), ("Solltemperatur Öl", "°C")])
def test_a_name_saying_a_set_point_is_a_state_whatever_its_unit(name, unit):
    assert role_by_unit(name, unit) == "state"
    assert role_by_unit("Schleiföl", unit) is None               # (a sensor: a temperature)


def test_a_folder_of_files_of_no_kind_read_is_refused_naming_what_it_holds(tmp_path, capsys):
    folder = tmp_path / "runs"
    folder.mkdir()
    for name in ("Lauf_01.xyz", "Lauf_02.xyz", "Notiz.docx"):
        (folder / name).write_text("x\n")
    refused(["init", str(folder), f"out={tmp_path / 'init'}"], capsys,
            "manifest not found (a dataset folder needs campaigns.csv); its files, .xyz (2), "
            ".docx (1), are no kind read as a run (.csv, .dat")


def test_x_columns_multi_times_each_channel_by_its_own_x_column(tmp_path):
    """``X_Columns Multi``: an ``X_Value`` column before each channel, here the second channel's
    X 30 s after the first's: each channel read at its own times (onto the 30 s grid)."""
    lines = ["LabVIEW Measurement\t", "Separator\tTab", "Decimal_Separator\t.",
             "X_Columns\tMulti", "Date\t2027/09/06", "Time\t06:00:00.0000000000",
             "***End_of_Header***\t", "", "Channels\t2\t", "Samples\t4\t4\t",
             "Date\t2027/09/06\t2027/09/06\t", "Time\t06:00:00.00\t06:00:30.00\t",
             "Y_Unit_Label\tDeg C\tum\t", "X0\t0.0\t30.0\t", "Delta_X\t60.0\t60.0\t",
             "***End_of_Header***\t", "X_Value\tLuft\tX_Value\tdX\tComment"]
    lines += [f"{k * 60.0}\t{20 + 0.1 * k}\t{k * 60.0 + 30}\t{0.5 * k}" for k in range(4)]
    path = tmp_path / "Lauf.lvm"
    path.write_text("\r\n".join(lines) + "\r\n", encoding="utf-8")
    ds, _ = read_dataset(path, {"roles": {"error": ["dX"]}, "resample_s": 30})
    frame = ds.campaigns["Lauf"]
    luft = dict(zip(frame["time"], frame["T_Luft"]))
    dx = dict(zip(frame["time"], frame["E_dX"]))
    assert luft[120.0] == pytest.approx(20.2) and dx[150.0] == pytest.approx(1.0)
