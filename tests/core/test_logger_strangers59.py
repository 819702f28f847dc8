"""A lab's data logger and an IoT gateway through `init` and the reader (session 59,
benchmarks/bench_new_machines59.py).

The horizontal machining centre's logger writes an instrument preamble, a header of channel
names, a second row of units whose time cell is the column's format (``h:mm:ss``), an elapsed
time that rolls past 24 h and a trailing ``,``: `init` said "no column reads as a measured error
... the numeric columns: none" (the unit row, not read as one, taken for the first data row).
"""

from __future__ import annotations

import pytest
import yaml

from thermocomp.core.io import read_dataset
from thermocomp.core.io.contract import ContractError
from thermocomp.core.io.layout import is_unit_row, with_units
from thermocomp.shell.cli import main

PREAMBLE = ["Logger,TL-32 Thermal Logger,Firmware 2.14", "Serial No.,TL32-0918",
            "Start,2026/09/07 07:44:29", "Interval,60 s", ""]


def logger_file(path, rows=30, step_s=3600, time_unit="h:mm:ss"):
    """A logger's file: preamble, channel names, units, ``h:mm:ss`` since the start (past 24 h
    at the default ``step_s``), a trailing ``,``."""
    lines = [*PREAMBLE, "Time,CH01 Spindle motor,CH02 Hall air,CH03 Disp Y,CH04 Pallet,",
             f"{time_unit},degC,degC,um,-,"]
    for i in range(rows):
        s = step_s * i
        lines.append(f"{s // 3600}:{s % 3600 // 60:02d}:{s % 60:02d},{20 + 0.05 * i:.2f},"
                     f"{20 + 0.01 * i:.2f},{0.3 * i:.1f},{1 + i // 10 % 2},")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\r\n".join(lines) + "\r\n", encoding="utf-8")
    return path


def test_a_time_format_is_a_cell_of_a_unit_row_and_not_joined_to_its_header():
    for cell in ("h:mm:ss", "hh:mm:ss", "[h]:mm:ss", "hh:mm:ss.0", "HH:MM:SS",
                 "yyyy/mm/dd hh:mm:ss", "dd.mm.yyyy hh:mm"):
        assert is_unit_row([cell, "degC", "um", "-", ""]), cell
    assert not is_unit_row(["0:00:00", "degC"])            # a data row's time is no format
    assert with_units(["Time", "T1", "Disp Y"], ["h:mm:ss", "degC", "um"]) == [
        "Time", "T1 [degC]", "Disp Y [um]"]


def test_a_loggers_unit_row_under_its_channel_names_is_read(tmp_path):
    path = logger_file(tmp_path / "HMC_2026-09-07.csv")
    ds, report = read_dataset(path, {"roles": {"error": ["CH03*"], "state": ["CH04*"]}})
    (cid,) = ds.ids()
    df = ds.campaigns[cid]
    assert report["campaigns"][cid]["time"] == "elapsed"
    assert {"E_CH03_Disp_Y", "T_CH01_Spindle_motor", "S_CH04_Pallet"} <= set(df.columns)
    assert df["time"].iloc[-1] - df["time"].iloc[0] == 29 * 3600.0


def test_init_reads_a_loggers_file_with_a_time_format_in_its_unit_row(tmp_path, capsys):
    path = logger_file(tmp_path / "HMC_2026-09-07.csv")
    out = tmp_path / "init"
    assert main(["init", str(path), "data.test_fraction=0.5", f"out={out}"]) == 0
    said = capsys.readouterr().out
    assert "units from line 7" in said and "elapsed" in said
    config = yaml.safe_load((out / "conf" / "data" / "HMC_2026-09-07.yaml").read_text())
    assert config["roles"]["error"] == ["CH03 Disp Y"]


# The wire EDM's IoT gateway writes its on/off tags as `true` / `false` (the chiller's
# compressor, the flushing): `init` left both out as text, and naming them as states was refused
# "value 'true' is not a number: a mark for a value not measured? list it in
# data.missing_values (['true'])" -- a remedy that would have read every `true` as missing.

def gateway_file(path, rows=12):
    lines = ["timestamp,bath_temp_c,room_air_temp_c,wire_x_um,discharge_power_kw,chiller_on"]
    for i in range(rows):
        lines.append(f"2026-09-07T06:{i:02d}:00.{i * 20:03d}Z,{20 + 0.1 * i:.2f},22.0{i % 10},"
                     f"{0.2 * i:.1f},0.6,{'true' if i // 3 % 2 else 'false'}")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_a_state_of_true_and_false_is_read_as_one_and_zero(tmp_path):
    path = gateway_file(tmp_path / "edm01_export.csv")
    ds, _ = read_dataset(path, {"roles": {"error": ["wire_x_um"], "state": ["chiller_on"],
                                          "ambient": ["room_air*"]}})
    (cid,) = ds.ids()
    assert ds.campaigns[cid]["S_chiller_on"].tolist() == [0, 0, 0, 1, 1, 1] * 2


def test_init_proposes_an_on_off_column_of_true_and_false_as_a_state(tmp_path, capsys):
    path = gateway_file(tmp_path / "edm01_export.csv")
    out = tmp_path / "init"
    assert main(["init", str(path), "data.test_fraction=0.5", f"out={out}"]) == 0
    config = yaml.safe_load((out / "conf" / "data" / "edm01_export.yaml").read_text())
    assert "chiller_on" in config["roles"]["state"]
    assert "chiller_on" not in config["roles"]["ignore"]


# The logger's folder: a run of 36 h (its time past 24:00:00, read as elapsed) beside one of
# 20 h, whose 0:00:00 ... 19:52:00 was refused as "a time of day without its date" after init
# had read the first file's as elapsed.

def test_init_reads_every_file_of_a_folder_elapsed_where_one_runs_past_24_hours(tmp_path, capsys):
    folder = tmp_path / "hmc"
    logger_file(folder / "HMC_2026-09-07.csv")                  # 0:00:00 ... 29:00:00
    logger_file(folder / "HMC_2026-09-09.csv", step_s=60)       # 0:00:00 ... 0:29:00
    out = tmp_path / "init"
    assert main(["init", str(folder), "data.test_fraction=0.5", f"out={out}"]) == 0
    assert "data.time='elapsed'" in capsys.readouterr().out
    config = yaml.safe_load((out / "conf" / "data" / "hmc.yaml").read_text())
    assert config["time"] == "elapsed"


# The logger's overrange mark '+OVER' (a loose thermocouple, single samples): listed in
# data.missing_values as the first refusal said, the next refusal was its gap ("longer than
# data.max_gap_samples=0"): the first now says both.

def test_a_missing_value_mark_says_the_gap_setting_that_reads_its_runs(tmp_path):
    path = logger_file(tmp_path / "HMC_2026-09-14.csv")
    lines = path.read_text(encoding="utf-8").splitlines()
    for k in (10, 14, 15):                        # one mark, then two in a row
        cells = lines[k].split(",")
        cells[1] = "+OVER"
        lines[k] = ",".join(cells)
    path.write_text("\r\n".join(lines), encoding="utf-8")
    with pytest.raises(ContractError) as refused:
        read_dataset(path, {"roles": {"error": ["CH03*"], "state": ["CH04*"]}})
    assert "data.missing_values (['+OVER'])" in str(refused.value)
    assert "data.max_gap_samples=2" in str(refused.value)
    ds, report = read_dataset(path, {"roles": {"error": ["CH03*"], "state": ["CH04*"]},
                                     "missing_values": ["+OVER"], "max_gap_samples": 2})
    assert report["campaigns"][ds.ids()[0]]["repairs"] == {"T_CH01_Spindle_motor": 3}
