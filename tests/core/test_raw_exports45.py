"""A lab's raw export, round 2 (issue 34, item 1): more hand-written files off the happy path,
and the same export streamed on stdin.  Each is read to the values it holds, or refused in one
line naming the file and the column (and row), never read silently wrong."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

from conftest import refused
from test_raw_exports44 import ROWS, _read, _record, _write
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.core.io.detect import proposed_roles
from thermocomp.core.io.options import ReadOptions
from thermocomp.core.io.roles import split_unit
from thermocomp.core.io.stdin import read_stream, stream_seconds
from thermocomp.shell.cli import main


def _roles_of(path: Path, sep: str = ",") -> dict:
    """What ``thermocomp init`` proposes for the file's header."""
    header = path.read_text(encoding="utf-8").splitlines()[0].split(sep)
    return proposed_roles(header, {h: "1" for h in header}, ReadOptions())


def test_a_unit_as_the_headers_last_word_or_suffix_is_read_and_converted(tmp_path):
    # before: 'dZ mm' was no error for init (a temperature 'dZ mm' refused for its space) and,
    # named by data.roles.error, E_dZ_mm: millimetres read as µm without a word
    t, t1, t2, e = _record()
    path = _write(tmp_path / "lab.csv", ["time s", "T_spindle degC", "Spindel °C", "dX_um",
                                         "dZ mm"], [t, t1, t2, e, -e / 1000])
    roles = _roles_of(path)
    assert roles["error"] == ["dX", "dZ"]
    frame = _read(path, roles=roles)
    assert list(frame.columns) == ["time", "T_spindle", "T_Spindel", "E_dX", "E_dZ"]
    np.testing.assert_allclose(frame[["time", "T_Spindel", "E_dX"]], np.c_[t, t2, e], atol=1e-3)
    np.testing.assert_allclose(frame["E_dZ"], -e, atol=1e-3)                 # mm -> µm
    frame = _read(path, roles={"error": ["d*"]})          # the lab's own pattern, as before
    np.testing.assert_allclose(frame["E_dZ"], -e, atol=1e-3)


@pytest.mark.parametrize("header, split", [
    ("dZ um", ("dZ", "um")), ("Load %", ("Load", "%")), ("Zeit_s", ("Zeit", "s")),
    ("Zone C", ("Zone C", None)),                 # a single letter: a name as often as a unit
    ("T_spindle_degC", ("T_spindle_degC", None)),   # a contract name keeps its name
    ("T_min", ("T_min", None)),                     # a time's unit only after a time header
    ("dZ_mm", ("dZ", "mm")), ("[°C]", ("", "°C"))])
def test_which_last_words_are_units(header, split):
    assert split_unit(header) == split


def test_a_header_that_is_only_a_unit_is_refused_not_named_after_it(tmp_path, capsys):
    # before: '[°C]' became a temperature T_C
    t, t1, t2, e = _record()
    path = _write(tmp_path / "nameless.csv", ["time", "[°C]", "T2 [°C]", "dX [µm]"], [t, t1, t2, e])
    out = tmp_path / "init"
    refused(["init", str(path), f"out={out}"], capsys, str(path), "'[°C]' gives no name",
            "data.columns")
    assert not out.exists()


def test_two_columns_under_one_header_are_read_by_their_occurrence(tmp_path):
    # before (raw45): "duplicate column (after data.columns mapping)", which no mapping had made;
    # then (until init74) refused naming both, no setting telling them apart: the second is
    # read as 'T1#2' (test_init74), in a file and on stdin alike
    t, t1, t2, e = _record()
    path = _write(tmp_path / "twice.csv", ["time", "T1", "T1", "dX [µm]"], [t, t1, t2, e], sep=";")
    frame = _read(path, roles={"error": ["dX"]})
    assert list(frame.columns) == ["time", "T_T1", "T_T1_2", "E_dX"]
    stream = read_stream(path.read_text(encoding="utf-8"), ["T_T1_2"],
                         ReadOptions.from_cfg({"roles": {"error": ["dX"]}}))[0]
    np.testing.assert_allclose(stream["T_T1_2"], t2, atol=1e-4)


def test_a_time_of_day_alone_under_any_header_is_refused_saying_so(tmp_path, capsys):
    # before: init proposed 'ignore' for it and the run said only "no 'time' column ... set
    # data.sample_period_s": the lab's clock column, which wraps at midnight, not named
    t, t1, t2, e = _record()
    clock = (pd.Timestamp("2026-11-28 23:45") + pd.to_timedelta(t, unit="s")).strftime("%H:%M:%S")
    path = _write(tmp_path / "clock.csv", ["time", "T1", "dX [µm]"], [t, t1, e])
    lines = path.read_text(encoding="utf-8").splitlines()
    rows = [f"{c},{ln.split(',', 1)[1]}" for c, ln in zip(clock, lines[1:])]
    # (data92b: 'Uhrzeit' names a time of day, read as data.time=of_day: a header no time header names)
    path.write_text("\n".join(["Erfasst,T1,dX [µm]", *rows]) + "\n", encoding="utf-8")
    out = tmp_path / "init"
    refused(["init", str(path), f"out={out}"], capsys, str(path), "time of day without its date",
            "'Erfasst'", "data.sample_period_s")
    assert not out.exists()
    assert main(["init", str(path), "data.sample_period_s=60", f"out={out}"]) == 0


@pytest.mark.parametrize("step_ms, jitter", [(500, 0), (2500, 0), (1000, 3)])
def test_a_time_in_ms_off_whole_seconds_is_said(tmp_path, capsys, step_ms, jitter):
    # before: said only for steps of whole thousands >= 1000; 500 ms, 2500 ms or a logger's
    # 998-1003 ms were read as seconds without a word
    t, t1, t2, e = _record()
    ms = np.arange(ROWS) * step_ms + np.random.default_rng(1).integers(-jitter, jitter + 1, ROWS)
    path = _write(tmp_path / "ms.csv", ["time", "T1", "dX [µm]"], [np.sort(ms), t1, e])
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().err
    assert f"{path}, column 'time'" in said and "milliseconds?" in said
    assert main(["init", str(path), "data.units={time: s}", f"out={tmp_path / 's'}"]) == 0
    assert "milliseconds?" not in capsys.readouterr().err


@pytest.mark.parametrize("period", [60.0, 120.0, 1200.0, 0.5])
def test_a_time_in_seconds_at_a_loggers_period_is_not_suspected(tmp_path, capsys, period):
    t, t1, t2, e = _record()
    path = _write(tmp_path / "s.csv", ["time", "T1", "dX [µm]"], [t / 60 * period, t1, e])
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    assert "milliseconds?" not in capsys.readouterr().err


def test_a_unicode_minus_is_read_as_a_minus(tmp_path):
    # before: refused, "value '−0,249' is not a number": a word processor's or a localised
    # export's minus sign (U+2212) is no other number than '-'
    t, t1, t2, e = _record()
    path = _write(tmp_path / "minus.csv", ["Zeit [s]", "T1 [°C]", "dX [µm]"], [t, t1 - 30, e],
                  sep=";")
    path.write_text(path.read_text(encoding="utf-8").replace("-", "\u2212").replace(".", ","),
                    encoding="utf-8")
    frame = _read(path, roles={"error": ["dX"]})
    np.testing.assert_allclose(frame[["T_T1", "E_dX"]], np.c_[t1 - 30, e], atol=1e-3)
    lines = path.read_text(encoding="utf-8").splitlines()
    lines[5] = lines[5].replace("\u2212", "\u2212\u2212", 1)          # '−−8,3' is no number
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    with pytest.raises(ContractError) as refusal:
        _read(path, roles={"error": ["dX"]})
    assert (refusal.value.row, refusal.value.column) == (5, "T_T1")


def test_an_excel_error_cell_is_named_and_can_be_read_as_missing(tmp_path, capsys):
    # before: '#DIV/0!' was refused without a hint, and data.missing_values refused it (a mark
    # with a digit)
    t, t1, t2, e = _record()
    path = _write(tmp_path / "excel.csv", ["time", "T1", "T2", "dX [µm]"], [t, t1, t2, e])
    lines = path.read_text(encoding="utf-8").splitlines()
    cells = lines[9].split(",")
    lines[9] = ",".join([*cells[:2], "#DIV/0!", cells[3]])
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    with pytest.raises(ContractError) as exc:          # the reader names the cell and the key
        read_dataset(path, {"roles": {"error": ["dX"]}})
    assert all(s in str(exc.value) for s in (
        str(path), "'T_T2'", "row 9", "data.missing_values (['#DIV/0!'])")), exc.value
    # (initone65) init lists the mark itself, said, and writes the gap that reads it
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    assert "a mark for a value not measured" in capsys.readouterr().out
    written = yaml.safe_load(next((tmp_path / "init" / "conf" / "data").glob("*.yaml"))
                             .read_text())
    assert written["missing_values"] == ['#DIV/0!'] and written["max_gap_samples"] == 1
    ds, report = read_dataset(path, {"roles": {"error": ["dX"]}, "max_gap_samples": 1,
                                     "missing_values": ["#DIV/0!"]})
    assert report["repairs"] == {"T_T2": 1}
    with pytest.raises(ContractError, match="data.missing_values"):
        read_dataset(path, {"missing_values": ["1,5"]})           # a number is no mark


def _lab_export(path: Path, rows: int = 60) -> Path:
    """A lab's logger export: ';', decimal commas, the date and the time of day in two columns
    (crossing midnight), units after a space (one error in mm), four temperatures."""
    rng = np.random.default_rng(45)
    t = np.arange(rows) * 60.0
    temps = [20 + k + (3 + k) * (1 - np.exp(-t / (600 * (k + 1)))) + rng.normal(0, 0.02, rows)
             for k in range(4)]
    ex = 3 * (temps[0] - temps[0][0]) - temps[1] + rng.normal(0, 0.1, rows)
    ez = -2 * (temps[2] - temps[2][0]) + temps[3] + rng.normal(0, 0.1, rows)
    stamps = pd.Timestamp("2026-11-28 23:30") + pd.to_timedelta(t, unit="s")
    header = ["Datum", "Uhrzeit", "Spindel °C", "Bett °C", "Motor °C", "Raum °C", "dX um", "dZ mm"]
    lines = [";".join([s.strftime("%d.%m.%Y"), s.strftime("%H:%M:%S"),
                       *(f"{v:.4f}".replace(".", ",") for v in values)])
             for s, *values in zip(stamps, *temps, ex, ez / 1000)]
    path.write_text("\n".join([";".join(header), *lines]) + "\n", encoding="utf-8")
    return path


LAB_ROLES = {"error": ["d*"], "ambient": ["Raum"], "time": ["Datum", "Uhrzeit"]}


def test_a_labs_export_on_stdin_is_named_joined_and_converted_as_its_file_is(tmp_path):
    # before: a stream read no data.roles, joined no date and time of day and converted no
    # unit: 'stdin lacks a column the compensator reads' for the lab's own headers
    path = _lab_export(tmp_path / "lab.csv")
    cfg = {"roles": LAB_ROLES, "test_fraction": 0.2}
    ds, _ = read_dataset(path, cfg)
    test = ds.campaigns["lab_test"]
    lines = path.read_text(encoding="utf-8").splitlines()
    stream = "\n".join([lines[0], *lines[-len(test):]]) + "\n"
    df, missing = read_stream(stream, ["T_Spindel", "T_Bett", "T_Motor", "T_amb"],
                              ReadOptions.from_cfg(cfg))
    assert list(df.columns) == list(test.columns) and not missing
    np.testing.assert_allclose(df.drop(columns="time"), test.drop(columns="time"))
    np.testing.assert_allclose(df["time"], test["time"] - test["time"].iloc[0])   # its own clock


def test_monitor_streams_a_labs_export_from_stdin_with_the_config_it_was_fitted_with(
        tmp_path, monkeypatch, capsys):
    import io
    import json

    path = _lab_export(tmp_path / "lab.csv")
    lines = path.read_text(encoding="utf-8").splitlines()
    monkeypatch.setattr("sys.stdin", io.StringIO("\n".join([lines[0], *lines[-12:]]) + "\n"))
    out = tmp_path / "monitor"
    assert main(["monitor", "monitor.input=-", f"data.path={path}", "data.test_fraction=0.2",
                 "data.roles.error=[d*]", "data.roles.ambient=[Raum]",
                 "data.roles.time=[Datum,Uhrzeit]", f"out={out}", "track=false",
                 "plots=none"]) == 0, capsys.readouterr().err
    report = json.loads((out / "monitor.json").read_text())
    assert report["campaigns"] == ["stdin"] and set(report["targets"]) == {"E_dX", "E_dZ"}


def _local_clock(path: Path, start_utc: str, zone: str = "Europe/Berlin") -> Path:
    """The record with its time as a local clock's timestamps without an offset (a lab's PC)."""
    t, t1, t2, e = _record()
    utc = pd.Timestamp(start_utc, tz="UTC") + pd.to_timedelta(t * 4, unit="s")   # 2 hours
    stamps = utc.tz_convert(zone).strftime("%Y-%m-%d %H:%M:%S")
    _write(path, ["T1 [°C]", "dX [µm]"], [t1, e])
    lines = path.read_text(encoding="utf-8").splitlines()
    path.write_text("\n".join(f"{s},{ln}" for s, ln in zip(["time", *stamps], lines)) + "\n",
                    encoding="utf-8")
    return path


def test_a_local_clock_set_back_an_hour_is_refused_naming_data_timezone_which_reads_it(
        tmp_path, capsys):
    # before: refused "time decreases from 7140 s (row 31) to 3600 s", and no setting read it
    path = _local_clock(tmp_path / "autumn.csv", "2026-10-24T23:30:00")   # 01:30 CEST
    out = tmp_path / "init"
    refused(["init", str(path), f"out={out}"], capsys, str(path), "column 'time'",
            "daylight saving time ending on 2026-10-25 in ", "(e.g. data.timezone=Europe/Berlin)")
    assert not out.exists()
    ds, report = read_dataset(path, {"roles": {"error": ["dX"]}, "timezone": "Europe/Berlin"})
    np.testing.assert_allclose(ds.campaigns["autumn"]["time"], _record()[0] * 4)
    assert report["campaigns"]["autumn"]["time_origin"] == "2026-10-25T01:30:00+02:00"


def test_a_local_clock_that_skips_an_hour_is_said_and_read_with_data_timezone(tmp_path, caplog):
    # before: read as an hour without samples, without a word (caplog: run alone, the log's
    # stderr is not capsys's)
    path = _local_clock(tmp_path / "spring.csv", "2026-03-29T00:30:00")   # 01:30 CET
    frame = _read(path, roles={"error": ["dX"]})
    assert np.diff(frame["time"]).max() == 3600 + 240
    assert f"{path}, column 'time', line 10 (data row 9)" in caplog.text
    assert "data.timezone" in caplog.text
    caplog.clear()
    frame = _read(path, roles={"error": ["dX"]}, timezone="Europe/Berlin")
    np.testing.assert_allclose(frame["time"], _record()[0] * 4)
    assert "data.timezone" not in caplog.text


def test_a_time_the_zones_clock_never_showed_or_an_unknown_zone_is_refused(tmp_path, capsys):
    path = _local_clock(tmp_path / "spring.csv", "2026-03-29T00:30:00", zone="UTC")  # 02:xx
    with pytest.raises(ContractError) as refusal:
        _read(path, roles={"error": ["dX"]}, timezone="Europe/Berlin")
    first_skipped = int(np.argmax(_record()[0] * 4 >= 90 * 60)) + 1     # 02:00 or later
    assert (refusal.value.column, refusal.value.row) == ("time", first_skipped)
    assert "never shown by data.timezone=Europe/Berlin's clock" in str(refusal.value)
    refused(["init", str(path), "data.timezone=Europe/Berln", f"out={tmp_path / 'init'}"],
            capsys, "data.timezone", "'Europe/Berln'")


def test_a_stream_on_a_local_clock_is_read_with_data_timezone():
    utc = pd.Timestamp("2026-10-25 00:00", tz="UTC") + pd.to_timedelta(np.arange(12) * 900, "s")
    local = pd.Series(list(utc.tz_convert("Europe/Berlin").strftime("%Y-%m-%d %H:%M:%S")))
    np.testing.assert_allclose(stream_seconds(local, "auto", "Europe/Berlin"), np.arange(12) * 900)


def test_a_blank_line_inside_a_record_without_a_time_column_is_said(tmp_path, capsys):
    # before: left out without a word, every row after it a sample period earlier (a sample
    # not taken?), where the rows' positions are the time
    t, t1, t2, e = _record()
    path = _write(tmp_path / "blank.csv", ["T1", "dX [µm]"], [t1, e], sep=";")
    lines = path.read_text(encoding="utf-8").splitlines()
    path.write_text("\r\n".join([*lines[:13], "", *lines[13:]]) + "\r\n", encoding="utf-8")
    frame = _read(path, roles={"error": ["dX"]}, sample_period_s=60)
    np.testing.assert_allclose(frame["T_T1"], t1, atol=1e-3)
    assert f"{path}, line 13 (data row 12): a blank line under it" in capsys.readouterr().err
    timed = _write(tmp_path / "timed.csv", ["time", "T1", "dX [µm]"], [t, t1, e])
    lines = timed.read_text(encoding="utf-8").splitlines()
    timed.write_text("\n".join([*lines[:13], "", *lines[13:], "", ""]) + "\n", encoding="utf-8")
    np.testing.assert_allclose(_read(timed, roles={"error": ["dX"]})["time"], t)
    assert "blank line" not in capsys.readouterr().err        # its time says where it is


def test_a_line_the_csv_module_cannot_split_never_escapes_as_a_traceback(tmp_path):
    # before: a one-column header over a row holding a carriage return inside quotes raised
    # csv.Error out of the separator check ("new-line character seen in unquoted field")
    from thermocomp.core.io.csvline import EMPTY, SPLIT, split_line

    path = tmp_path / "cr.csv"
    path.write_bytes(b'time;T1;dX\r\n"0\r1";20,5;1,0\r\n60;20,6;1,1\r\n')
    with pytest.raises(ContractError, match="set data.delimiter=';'"):
        read_dataset(path, {"delimiter": ","})
    assert split_line('a;"b\rc";d', ";") == ["a", "b\rc", "d"]
    assert split_line("a;b\rc", ";", EMPTY) == [] and split_line("a;b\rc", ";", SPLIT) == [
        "a", "b\rc"]


def test_a_contract_files_time_every_100_s_is_seconds_by_the_contract(tmp_path, capsys):
    # the simulator's column_moving_source samples every 100 s: a contract file says seconds
    t, t1, t2, e = _record()
    path = _write(tmp_path / "sim.csv", ["time", "T_1", "E_X"], [t / 60 * 100, t1, e])
    assert _read(path)["time"].iloc[-1] == (ROWS - 1) * 100
    assert "milliseconds?" not in capsys.readouterr().err


def test_a_loggers_preamble_and_unit_row_stream_as_its_file_reads(tmp_path):
    # before: the preamble was read as the stream's header, the unit row as its first row
    from test_raw_exports44 import _logger_export
    path = _logger_export(tmp_path / "log.csv", ["Logger: XY-200", ""], ["s", "°C", "K", "mm"])
    cfg = {"roles": {"error": ["dX"]}}
    frame = _read(path, **cfg)
    df, _ = read_stream(path.read_text(encoding="utf-8"), ["T_T1", "T_T2"],
                        ReadOptions.from_cfg(cfg))
    np.testing.assert_allclose(df[list(frame.columns)], frame, rtol=1e-9)


def test_a_time_in_excels_serial_days_is_said_and_read_with_data_units(tmp_path, capsys):
    # before: read as seconds without a word (200 samples in a tenth of a second)
    t, t1, t2, e = _record()
    path = tmp_path / "serial.csv"            # 28.12.2025 12:00 as Excel counts days
    lines = [f"{46000.5 + s / 86400:.8f},{a:.4f},{b:.4f}" for s, a, b in zip(t, t1, e)]
    path.write_text("\n".join(["Zeit,T1,dX [µm]", *lines]) + "\n", encoding="utf-8")
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    # said by init and written as the unit (stranger64; before: only warned of, naming the column)
    said = capsys.readouterr().out
    assert "'Zeit' from 46000.50000000: Excel's serial days" in said and "read as the time" in said
    assert "Zeit: d" in next((tmp_path / "init").rglob("serial.yaml")).read_text(encoding="utf-8")
    frame = _read(path, roles={"error": ["dX"]}, units={"Zeit": "d"})
    np.testing.assert_allclose(frame["time"] - frame["time"].iloc[0], t, atol=1e-3)
    assert "Excel" not in capsys.readouterr().err


@pytest.mark.parametrize("space", ["\u00a0", "\u202f"])
def test_digits_grouped_by_a_no_break_space_are_named_and_read_with_data_thousands(
        tmp_path, space):
    # before: refused without a hint, and data.thousands refused a no-break space: a French
    # (or SI) export's '1 234,5' could not be read at all
    t, t1, t2, e = _record()
    path = tmp_path / "fr.csv"
    group = lambda v: f"{v:,.3f}".replace(",", space).replace(".", ",")   # noqa: E731
    lines = [";".join(map(group, row)) for row in zip(t, t1, 1000 * e)]
    path.write_text("\n".join(["Temps [s]", *lines]).replace("Temps [s]", "Temps [s];T1;dX [µm]")
                    + "\n", encoding="utf-8")
    with pytest.raises(ContractError, match=re.escape(f"set data.thousands={space!r}")) as refusal:
        _read(path, roles={"error": ["dX"]})
    # the earliest grouped cell of every column: dX's first (stranger65: the time's 1 020 s at
    # row 18, the first column Arrow's reader met)
    assert (refusal.value.column, refusal.value.row) == ("E_dX", 1)
    frame = _read(path, roles={"error": ["dX"]}, thousands=space)
    np.testing.assert_allclose(frame[["time", "T_T1", "E_dX"]], np.c_[t, t1, 1000 * e], atol=1e-3)


def test_an_excel_row_of_empty_cells_under_a_time_column_is_left_out_and_said(tmp_path, capsys):
    # before: refused, "missing time value" (';;;' is how Excel writes an empty row)
    t, t1, t2, e = _record()
    path = _write(tmp_path / "excel.csv", ["Zeit [s]", "T1", "dX [µm]"], [t, t1, e], sep=";")
    lines = path.read_text(encoding="utf-8").splitlines()
    path.write_text("\n".join([*lines[:11], ";;", *lines[11:]]) + "\n", encoding="utf-8")
    frame = _read(path, roles={"error": ["dX"]})
    np.testing.assert_allclose(frame[["time", "T_T1", "E_dX"]], np.c_[t, t1, e], atol=1e-3)
    assert f"{path}, line 12 (data row 11): 1 row(s) of empty cells left out" in (
        capsys.readouterr().err)
    lines[5] = ";" + lines[5].split(";", 1)[1]           # a time missing from a row of values
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    with pytest.raises(ContractError, match="missing time value") as refusal:
        _read(path, roles={"error": ["dX"]})
    assert refusal.value.row == 5


def test_init_proposes_a_torque_in_newton_metres_as_a_state_not_an_error_in_nanometres():
    # before: 'Spindel [Nm]' (or 'Spindel Nm') was proposed an error, read in nm
    header = ["time", "Spindel [Nm]", "Motor Nm", "dX nm", "T1"]
    roles = proposed_roles(header, {h: "1" for h in header}, ReadOptions())
    assert (roles["state"], roles["error"]) == (["Spindel", "Motor"], ["dX"])
