"""A lab's raw export as a stranger brings it (issue 34, item 1): hand-written files off the
happy path.  Each is read to the values it holds, or refused in one line naming the file and the
column (and row), never read silently wrong."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

from conftest import refused
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.core.io.detect import proposed_roles
from thermocomp.core.io.options import ReadOptions
from thermocomp.core.io.roles import contract_columns
from thermocomp.core.io.source import open_dataset
from thermocomp.core.io.stdin import stream_seconds
from thermocomp.shell.cli import main

ROWS = 30


def _record():
    """A warming machine, one sample a minute: time (s), two temperatures (°C), an error (µm)."""
    rng = np.random.default_rng(4)
    t = np.arange(ROWS) * 60.0
    t1 = 20 + 6 * (1 - np.exp(-t / 600)) + rng.normal(0, 0.02, ROWS)
    t2 = 21 + 3 * (1 - np.exp(-t / 900)) + rng.normal(0, 0.02, ROWS)
    return t, t1, t2, 4.0 * (t1 - t1[0]) - t2 + rng.normal(0, 0.1, ROWS)


def _write(path: Path, header: list[str], columns, sep: str = ",", end: str = "") -> Path:
    rows = [sep.join(f"{v:.6g}" for v in row) + end for row in zip(*columns)]
    path.write_text("\n".join([sep.join(header) + end, *rows]) + "\n", encoding="utf-8")
    return path


def _read(path: Path, **cfg):
    ds, _ = read_dataset(path, cfg)
    (frame,) = ds.campaigns.values()
    return frame


def test_a_unit_written_quantity_slash_unit_is_read_as_the_unit_not_as_part_of_the_name(tmp_path):
    # ISO 80000 headers: before, 'delta L / um' was a temperature T_delta_L_um (an error read
    # as a model input, silently) and 'Zeit / s' no time column
    t, t1, t2, e = _record()
    path = _write(tmp_path / "lab.csv", ["Zeit / s", "T1 / °C", "T2 / K", "delta L / um",
                                         "dZ/mm"], [t, t1, t2 + 273.15, e, e / 1000])
    header = path.read_text(encoding="utf-8").splitlines()[0].split(",")
    roles = proposed_roles(header, {h: "1" for h in header}, ReadOptions())
    assert roles["error"] == ["delta L", "dZ"]             # what `thermocomp init` proposes
    frame = _read(path, roles=roles)
    assert list(frame.columns) == ["time", "T_T1", "T_T2", "E_delta_L", "E_dZ"]
    np.testing.assert_allclose(frame["time"], t)
    np.testing.assert_allclose(frame["T_T2"], t2, atol=1e-3)      # kelvin converted
    np.testing.assert_allclose(frame["E_dZ"], e, atol=1e-3)       # mm converted
    np.testing.assert_allclose(frame["E_delta_L"], e, atol=1e-3)


@pytest.mark.parametrize("header", ["Datum/Zeit", "on/off"])
def test_a_slash_inside_a_name_is_no_unit(header):
    from thermocomp.core.io.roles import split_unit

    assert split_unit(header) == (header, None)


def _excel(path: Path, cells: list[str] | None = None) -> Path:
    """``;``-separated, decimal commas, a separator closing every line (Excel's empty last
    column); ``cells``: what that column holds row by row (empty by default)."""
    t, t1, t2, e = _record()
    _write(path, ["Zeit [s]", "T1 [°C]", "T2 [°C]", "dX [µm]"], [t, t1, t2, e], sep=";", end=";")
    lines = path.read_text(encoding="utf-8").replace(".", ",").splitlines()
    lines[1:] = [ln + cell for ln, cell in zip(lines[1:], cells or [""] * ROWS)]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_an_empty_last_column_without_header_is_left_out(tmp_path, capsys):
    # before: refused ("'' gives no name"), and no data.roles pattern could name it
    path = _excel(tmp_path / "excel.csv")
    t, t1, t2, e = _record()
    frame = _read(path, roles={"error": ["dX"]})
    assert list(frame.columns) == ["time", "T_T1", "T_T2", "E_dX"]
    np.testing.assert_allclose(frame[["T_T1", "T_T2"]], np.c_[t1, t2], atol=1e-3)
    out = tmp_path / "init"
    assert main(["init", str(path), f"out={out}"]) == 0
    assert "(no header)" in capsys.readouterr().out


def test_a_column_without_header_that_holds_values_is_refused_naming_its_row(tmp_path, capsys):
    path = _excel(tmp_path / "excel.csv", [""] * 6 + ["Müller"] + [""] * (ROWS - 7))
    out = tmp_path / "init"
    refused(["init", str(path), f"out={out}"], capsys, str(path), "row 7", "column 5",
            "'Müller'")
    assert not out.exists()


def _stamped(path: Path, header: str, fmt: str, start: str = "2026-10-31 23:45:00",
             sep: str = ";") -> Path:
    """The record with its time as timestamps written in ``fmt`` (crossing a day and a month)."""
    t, t1, t2, e = _record()
    stamps = (pd.Timestamp(start) + pd.to_timedelta(t, unit="s")).strftime(fmt)
    _write(path, ["T1 [°C]", "T2 [°C]", "dX [µm]"], [t1, t2, e], sep=sep)
    lines = path.read_text(encoding="utf-8").splitlines()
    path.write_text("\n".join(f"{s}{sep}{ln}" for s, ln in zip([header, *stamps], lines)) + "\n",
                    encoding="utf-8")
    return path


def test_day_first_timestamps_are_the_time_read_day_first(tmp_path):
    # before: 'Datum/Zeit' holding 31.10.2026 23:45:00 was no time column ("set
    # data.sample_period_s"), and data.roles.time could not read it
    path = _stamped(tmp_path / "logger.csv", "Datum/Zeit", "%d.%m.%Y %H:%M:%S")
    ds, report = read_dataset(path, {"roles": {"error": ["dX"]}})
    (cid,) = ds.ids()
    np.testing.assert_allclose(ds.campaigns[cid]["time"], _record()[0])
    assert report["campaigns"][cid]["time_origin"] == "2026-10-31T23:45:00"


def test_timestamps_with_slashes_are_refused_naming_data_time_and_read_with_its_format(
        tmp_path, capsys):
    # (a day past 12 says the order since newmachine58: 10/31/2026 is read month first; here
    # every day and month is 12 or less, either order)
    ambiguous = _stamped(tmp_path / "either.csv", "Date Time", "%m/%d/%Y %H:%M:%S",
                         start="2026-11-01 10:00:00", sep=",")
    out = tmp_path / "init"
    refused(["init", str(ambiguous), f"out={out}"], capsys, str(ambiguous), "row 1", "data.time=")
    assert not out.exists()
    path = _stamped(tmp_path / "us.csv", "Date Time", "%m/%d/%Y %H:%M:%S", sep=",")
    ds, report = read_dataset(path, {"roles": {"error": ["dX"]}, "time": "%m/%d/%Y %H:%M:%S"})
    (cid,) = ds.ids()
    np.testing.assert_allclose(ds.campaigns[cid]["time"], _record()[0])
    assert report["campaigns"][cid]["time_origin"] == "2026-10-31T23:45:00"


def test_a_cell_out_of_the_time_format_is_refused_naming_its_row(tmp_path):
    path = _stamped(tmp_path / "logger.csv", "Datum/Zeit", "%d.%m.%Y %H:%M:%S")
    lines = path.read_text(encoding="utf-8").splitlines()
    lines[7] = "2026-11-01 00:51:00" + lines[7][len("01.11.2026 00:51:00"):]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    with pytest.raises(ContractError) as refusal:
        read_dataset(path, {"roles": {"error": ["dX"]}})
    assert (refusal.value.row, refusal.value.column) == (7, "time")
    assert "'%d.%m.%Y %H:%M:%S'" in str(refusal.value)


def test_a_streamed_record_reads_day_first_timestamps_as_a_file_does():
    stamps = pd.Series(["31.10.2026 23:59:00", "01.11.2026 00:01:00"])
    assert list(stream_seconds(stamps, "auto")) == [0.0, 120.0]


def test_a_time_in_ms_without_unit_is_said_and_read_with_data_units(tmp_path, capsys):
    # before: read as seconds without a word, and no setting could say its unit short of
    # editing the lab's file
    t, t1, t2, e = _record()
    path = _write(tmp_path / "ms.csv", ["time", "T1", "dX [µm]"], [t * 1000, t1, e])
    assert main(["init", str(path), f"out={tmp_path / 'guess'}"]) == 0
    said = capsys.readouterr()
    assert "time: 'time', in seconds: no unit in the header" in said.out
    assert f"{path}, column 'time'" in said.err and "milliseconds?" in said.err
    frame = _read(path, roles={"error": ["dX"]}, units={"time": "ms"})
    np.testing.assert_allclose(frame["time"], t)
    assert main(["init", str(path), "data.units={time: ms}", f"out={tmp_path / 'ms'}"]) == 0
    said = capsys.readouterr()
    assert "time: 'time', in ms" in said.out and "milliseconds?" not in said.err


def test_data_units_converts_an_error_whose_header_says_no_unit(tmp_path, capsys):
    t, t1, t2, e = _record()
    path = _write(tmp_path / "mm.csv", ["t", "T1", "T2", "dX"], [t, t1, t2, e / 1000])
    frame = _read(path, roles={"error": ["dX"]}, units={"dX": "mm"})
    np.testing.assert_allclose(frame["E_dX"], e, atol=1e-3)
    out = tmp_path / "init"
    refused(["init", str(path), "data.roles.error=[dX]", "data.units={dx: mm, T2: furlong}",
             f"out={out}"], capsys, str(path), "data.units names 'dx', no header",
            "'T2': unit 'furlong' is not a temperature's")
    assert not out.exists()


def test_a_footer_under_the_data_is_left_out_and_said(tmp_path, capsys):
    # before: refused, "row 31: expected 4 fields, got 1"
    t, t1, t2, e = _record()
    path = _write(tmp_path / "footer.csv", ["time", "T1", "T2", "dX [µm]"], [t, t1, t2, e])
    text = path.read_text(encoding="utf-8") + "End of data\n\nRows: 30\n"
    path.write_bytes(text.replace("\n", "\r\n").encode("utf-8"))
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    assert f"{path}: footer left out (2 line(s) under the data: 'End of data')" in \
        capsys.readouterr().err
    frame = _read(path, roles={"error": ["dX"]})
    np.testing.assert_allclose(frame[["time", "T_T1"]], np.c_[t, t1], atol=1e-3)


@pytest.mark.parametrize("tail, row", [("1740,25.1\n", 31), ("Pause\n" + "1740,25.1,21.0,3.5\n", 31)])
def test_a_row_cut_short_or_text_above_data_is_no_footer(tmp_path, tail, row):
    t, t1, t2, e = _record()
    path = _write(tmp_path / "cut.csv", ["time", "T1", "T2", "dX [µm]"], [t, t1, t2, e])
    path.write_text(path.read_text(encoding="utf-8") + tail, encoding="utf-8")
    with pytest.raises(ContractError) as refusal:
        read_dataset(path, {"roles": {"error": ["dX"]}})
    assert refusal.value.row == row


def test_a_unit_written_quantity_in_unit_is_read_as_the_unit(tmp_path):
    # before: 'dX in mm' was a temperature T_dX_in_mm, in mm, and 'Zeit in s' no time
    t, t1, t2, e = _record()
    path = _write(tmp_path / "lab.csv", ["Zeit in s", "T1 in °C", "dX in mm"], [t, t1, e / 1000])
    header = path.read_text(encoding="utf-8").splitlines()[0].split(",")
    roles = proposed_roles(header, {h: "1" for h in header}, ReadOptions())
    frame = _read(path, roles=roles)
    assert list(frame.columns) == ["time", "T_T1", "E_dX"]
    np.testing.assert_allclose(frame[["time", "E_dX"]], np.c_[t, e], atol=1e-3)


def test_a_labs_mark_for_a_value_not_measured_is_named_and_read_as_missing(tmp_path, capsys):
    # before: '-' and 'n/a' were refused as text and no setting read them as missing
    t, t1, t2, e = _record()
    path = _write(tmp_path / "marks.csv", ["time", "T1", "T2", "dX [µm]"], [t, t1, t2, e])
    lines = path.read_text(encoding="utf-8").splitlines()
    lines[9] = ",".join([*lines[9].split(",")[:2], "-", lines[9].split(",")[3]])
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    with pytest.raises(ContractError) as exc:          # the reader names the cell and the key
        read_dataset(path, {"roles": {"error": ["dX"]}})
    assert all(s in str(exc.value) for s in (
        str(path), "'T_T2'", "row 9", "value '-'", "data.missing_values")), exc.value
    # (initone65) init lists the mark itself, said, and writes the gap that reads it
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    assert "a mark for a value not measured" in capsys.readouterr().out
    written = yaml.safe_load(next((tmp_path / "init" / "conf" / "data").glob("*.yaml"))
                             .read_text())
    assert written["missing_values"] == ['-'] and written["max_gap_samples"] == 1
    lines[20] = ",".join([*lines[20].split(",")[:1], "n/a", *lines[20].split(",")[2:]])
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    ds, report = read_dataset(path, {"roles": {"error": ["dX"]}, "max_gap_samples": 1,
                                     "missing_values": ["-", "n/a"]})
    (frame,) = ds.campaigns.values()
    assert report["repairs"] == {"T_T1": 1, "T_T2": 1}
    np.testing.assert_allclose(frame["T_T2"][8], (t2[7] + t2[9]) / 2, atol=1e-3)


def test_a_record_streamed_has_its_train_part_repaired_as_a_batch_reads_it(tmp_path):
    # replay / monitor of a one-file record with a gap in its train part: before, refused
    # with "<record>/<record>: campaign file not found" (the part has no file of its own)
    t, t1, t2, e = _record()
    path = _write(tmp_path / "gap.csv", ["time", "T1", "T2", "dX [µm]"], [t, t1, t2, e])
    lines = path.read_text(encoding="utf-8").splitlines()
    lines[5] = ",".join(["240", "", *lines[5].split(",")[2:]])
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    cfg = {"roles": {"error": ["dX"]}, "test_fraction": 0.2, "max_gap_samples": 1}
    streamed = open_dataset(path, cfg, stream=True)
    batch, _ = read_dataset(path, cfg)
    pd.testing.assert_frame_equal(streamed.campaigns["gap_train"], batch.campaigns["gap_train"])
    assert streamed.campaigns["gap_train"]["T_T1"].notna().all()


@pytest.mark.parametrize("dead", ["T2", "dX [µm]"])
def test_a_dead_channel_of_a_record_is_said(tmp_path, capsys, dead):
    # before: a one-file record's constant error column was not said (only a folder's
    # campaigns were looked at), nor a constant temperature anywhere
    t, t1, t2, e = _record()
    columns = {"time": t, "T1": t1, "T2": t2, "dX [µm]": e, "dZ [µm]": -e}
    columns[dead] = np.full(ROWS, 21.5)
    path = _write(tmp_path / "dead.csv", list(columns), list(columns.values()))
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    name = {"T2": "T_T2", "dX [µm]": "E_dX"}[dead]
    assert f"{path}, column '{name}': constant over the whole campaign" in capsys.readouterr().err


def _logger_export(path: Path, preamble: list[str], units: list[str] | None,
                   error_scale: float = 1.0) -> Path:
    """``;``-separated, decimal commas, under a logger's preamble, with a unit row or not; the
    error (µm) written times ``error_scale`` (1e-3: in mm)."""
    t, t1, t2, e = _record()
    _write(path, ["Zeit", "T1", "T2", "dX"], [t, t1, t2, e * error_scale], sep=";")
    lines = path.read_text(encoding="utf-8").replace(".", ",").splitlines()
    lines[1:1] = [";".join(units)] if units else []
    path.write_text("\n".join([*preamble, *lines]) + "\n", encoding="utf-8")
    return path


def test_a_unit_row_under_the_header_gives_the_units(tmp_path, capsys):
    # before: refused, "no E_ column" (the units were read as the first row)
    # the error in mm as a lab writes it (0.02 mm: a length spanning more than 5 mm is an
    # axis' travel, proposed as a state, stranger64)
    path = _logger_export(tmp_path / "units.csv", [], ["s", "°C", "K", "mm"], error_scale=1e-3)
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "units from line 2; rows counted from line 3" in said and "E_dX" in said
    t, t1, t2, e = _record()
    frame = _read(path, roles={"error": ["dX"]})
    np.testing.assert_allclose(frame[["time", "T_T1", "T_T2"]], np.c_[t, t1, t2 - 273.15],
                               atol=1e-3)
    np.testing.assert_allclose(frame["E_dX"], e, rtol=1e-5, atol=1e-3)  # mm -> µm


def test_a_loggers_preamble_above_the_header_is_left_out_and_rows_count_from_the_data(tmp_path):
    # before: the preamble broke the separator's detection and was read as the header
    preamble = ["Logger: XY-200", "Datum: 28.11.2026", ""]
    path = _logger_export(tmp_path / "log.csv", preamble, ["s", "°C", "°C", "µm"])
    t, t1, t2, e = _record()
    frame = _read(path, roles={"error": ["dX"]})
    np.testing.assert_allclose(frame[["time", "T_T1", "E_dX"]], np.c_[t, t1, e], atol=1e-3)
    lines = path.read_text(encoding="utf-8").splitlines()
    lines[len(preamble) + 2 + 6] = lines[len(preamble) + 2 + 6].replace(";", ";x", 1)
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    with pytest.raises(ContractError) as refusal:
        read_dataset(path, {"roles": {"error": ["dX"]}})
    assert (refusal.value.row, refusal.value.column) == (7, "T_T1")


def test_a_title_line_excel_padded_to_the_tables_width_is_no_header(tmp_path):
    # before: 'Messprotokoll Spindel 3;;;' split into the table's 4 fields and was taken for the
    # header ("no E_ column"): Excel pads every row of a sheet to its widest
    path = _logger_export(tmp_path / "titled.csv", ["Messprotokoll Spindel 3;;;"], None)
    t, t1, t2, e = _record()
    frame = _read(path, roles={"error": ["dX"]})
    np.testing.assert_allclose(frame[["time", "T_T1", "E_dX"]], np.c_[t, t1, e], atol=1e-3)


def test_a_header_short_of_a_field_is_never_a_data_row_taken_for_the_header(tmp_path):
    path = _excel(tmp_path / "short.csv")
    lines = path.read_text(encoding="utf-8").splitlines()
    path.write_text("\n".join([lines[0][:-1], *lines[1:]]) + "\n", encoding="utf-8")
    with pytest.raises(ContractError):
        read_dataset(path, {"roles": {"error": ["dX"]}})


def test_an_error_column_never_measured_is_refused_naming_the_setting_that_leaves_it_out(
        tmp_path, capsys):
    t, t1, t2, e = _record()
    path = _write(tmp_path / "dy.csv", ["time", "T1", "dX [µm]", "dY [µm]"],
                  [t, t1, e, np.full(ROWS, np.nan)])
    out = tmp_path / "init"
    refused(["init", str(path), f"out={out}"], capsys, str(path), "column 'E_dY'",
            "data.roles.ignore")
    assert not out.exists()
    assert main(["init", str(path), "data.roles.error=[dX]", "data.roles.ignore=[dY]",
                 f"out={out}"]) == 0


def test_init_proposes_the_air_sensor_as_the_ambient(tmp_path):
    # before: 'Raumtemperatur [°C]' was a temperature T_Raumtemperatur, not the ambient T_amb
    # the ATI models and the diagnosis read
    header = ["time [s]", "Raumtemperatur [°C]", "Luftlager [°C]", "T_amb_x", "dX [µm]"]
    roles = proposed_roles(header, {h: "1" for h in header}, ReadOptions())
    assert roles["ambient"] == ["Raumtemperatur"]
    t, t1, t2, e = _record()
    path = _write(tmp_path / "hall.csv", header, [t, t1, t2, t2, e])
    assert list(_read(path, roles=roles).columns) == ["time", "T_amb", "T_Luftlager", "T_amb_x",
                                                      "E_dX"]


def test_a_loggers_text_export_goes_through_init_as_csv_does(tmp_path, capsys):
    # before: init read a .txt record as Parquet (a traceback); run read it as CSV
    t, t1, t2, e = _record()
    path = _write(tmp_path / "log.txt", ["time", "T1", "T2", "dX [um]"], [t, t1, t2, e], sep="\t")
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    assert "E_dX" in capsys.readouterr().out
    frame = _read(path, roles={"error": ["dX*"]})
    np.testing.assert_allclose(frame[["time", "T_T1", "E_dX"]], np.c_[t, t1, e], atol=1e-3)


@pytest.mark.parametrize("command", ["init", "run"])
def test_an_excel_workbook_is_refused_in_one_line_saying_to_save_it_as_csv(tmp_path, capsys,
                                                                           command):
    # before: init crashed in the Parquet reader; run said "file has a header but no data rows"
    # (session 48: a workbook is read, tests/shell/test_workbook48.py; one that is not: refused)
    book = tmp_path / "campaign.xlsx"
    book.write_bytes(b"PK\x03\x04" + bytes(60))
    args = [str(book)] if command == "init" else [f"data.path={book}", "track=false"]
    refused([command, *args, f"out={tmp_path / 'out'}"], capsys, "campaign.xlsx",
            "save it as an Excel workbook (.xlsx), or its sheet as CSV")
    assert not (tmp_path / "out").exists()


def test_a_folder_of_runs_without_a_manifest_is_read_file_by_file_in_natural_order(tmp_path,
                                                                                  capsys):
    # before: refused, "manifest not found (a dataset folder needs campaigns.csv)": a lab with
    # dozens of runs had to write the manifest by hand
    t, t1, t2, e = _record()
    runs = tmp_path / "runs"
    runs.mkdir()
    for k in (1, 2, 10):        # run_10 is the last run, though it sorts before run_2 as text
        _write(runs / f"run_{k}.csv", ["time [s]", "T1 [°C]", "T2 [°C]", "dX [um]"],
               [t, t1 + k, t2 + k, e * k])
    ds, _ = read_dataset(runs, {"test_fraction": 0.2, "roles": {"error": ["dX*"]}})
    assert list(ds.manifest.index) == ["run_1", "run_2", "run_10"]
    assert list(ds.manifest["split"]) == ["train", "train", "test"]
    np.testing.assert_allclose(ds.campaigns["run_10"]["E_dX"], 10 * e, atol=1e-3)
    assert main(["init", str(runs), "data.test_fraction=0.2", f"out={tmp_path / 'init'}"]) == 0
    assert "campaign run_10: test" in capsys.readouterr().out
    assert sorted(p.name for p in runs.iterdir()) == ["run_1.csv", "run_10.csv", "run_2.csv"]
    empty = tmp_path / "empty"
    empty.mkdir()
    with pytest.raises(ContractError, match="manifest not found"):
        read_dataset(empty)


def test_init_detects_a_windows_encoding_in_a_folder_of_runs_without_a_manifest(tmp_path):
    t, t1, t2, e = _record()
    runs = tmp_path / "runs"
    runs.mkdir()
    for k in (1, 2, 3):
        text = _write(tmp_path / "tmp.csv", ["time [s]", "T1 [°C]", "T2 [°C]", "dX [µm]"],
                      [t, t1, t2, e]).read_text(encoding="utf-8")
        (runs / f"run_{k}.csv").write_bytes(text.encode("cp1252"))
    assert main(["init", str(runs), "data.test_fraction=0.3", f"out={tmp_path / 'init'}"]) == 0
    assert "encoding: cp1252" in (tmp_path / "init" / "conf" / "data" / "runs.yaml").read_text()


def test_several_ambient_sensors_keep_their_own_names_once(tmp_path):
    # before: 'amb left' became T_amb_amb_left (the header's own 'amb' prefixed again)
    header = ["time [s]", "amb left [°C]", "Ambient_right [°C]", "Halle [°C]", "T1 [°C]", "dX [µm]"]
    names = contract_columns(header, {"ambient": ["amb*", "Ambient*", "Halle"], "error": ["dX"]},
                             first={h: "1" for h in header})
    assert [names[h] for h in header[1:4]] == ["T_amb_left", "T_amb_right", "T_amb_Halle"]
