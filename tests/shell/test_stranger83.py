"""A bridge mill's runs, each two files (stranger83): the temperatures as BenchLink Data Logger
exports a Keysight 34970A's scans (a header block, ``Scan,Time,101 <AIR> (C),Alarm 101,...``,
``9/13/2027 6:00:00:013``, readings ``+2.13450000E+01``, an open thermocouple
``+9.90000000E+37``), the errors as the NC's probing macro logs them (``DATE,TIME,...,dX
[mm],dZ [mm]``, a row a cycle) (``benchmarks/bench_stranger83.py`` writes the lab's full record;
these are a few rows of test_stranger68's linear runs)."""

from __future__ import annotations

import datetime as dt
from pathlib import Path

import numpy as np
import yaml

from test_stranger68 import ROWS, linear_run
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

CHANNELS = ("AIR", "SPINDLE", "BED", "MOTOR")   # the motor warming 0.15 K a scan
START = dt.datetime(2027, 9, 13, 6)
PROBE = 10          # a probing cycle every PROBE scans


def _stamp(at: dt.datetime, german: bool = False) -> str:
    return f"{at:%d.%m.%Y %H:%M:%S}" if german else f"{at.month}/{at.day}/{at.year} {at.hour}:{at:%M:%S}"


def benchlink(folder: Path, run: int, open_scans: int = 0, german: bool = False) -> None:
    """``MCR_L<run>_daq.csv`` (linear_run's temperatures every 60 s; ``open_scans`` scans of
    ``SPINDLE`` from scan 41 read ``+9.90000000E+37``) and ``MCR_L<run>_probe.csv`` (its errors,
    in mm, every PROBE scans, 20 s after the scan); ``german``: the DAQ file as a German PC
    exports it (``;``, decimal commas, ``13.09.2027 06:00:00:000``), the probe log as before."""
    folder.mkdir(parents=True, exist_ok=True)
    values = linear_run(8556, run)
    temps = np.column_stack([values[:, :3], 20 + 0.15 * np.arange(ROWS)])
    start = START + dt.timedelta(days=run - 1)
    names = ["Scan", "Time"]
    for ch, name in enumerate(CHANNELS, start=101):
        names += [f"{ch} <{name}> (C)", f"Alarm {ch}"]
    sep = ";" if german else ","
    lines = [f"Name{sep}MCR run {run}", f"Owner{sep}Lab", f"Acquisition Date{sep}{_stamp(start, german)}",
             f"Instrument{sep}34970A (Serial Number: MY44054321) at GPIB0::9::INSTR",
             f"Total Sweeps{sep}{ROWS}", f"Total Channels{sep}{len(CHANNELS)}", "", sep.join(names) + sep]
    for k, v in enumerate(values):
        at = start + dt.timedelta(seconds=60 * k, milliseconds=k % 7)
        cells = [str(k + 1), f"{_stamp(at, german)}:{at.microsecond // 1000:03d}"]
        for j in range(len(CHANNELS)):
            broken = j == 1 and 40 <= k < 40 + open_scans
            reading = 9.9e37 if broken else temps[k, j]
            cells += [f"{reading:+.8E}".replace(".", "," if german else "."), "0"]
        lines.append(sep.join(cells) + sep)
    (folder / f"MCR_L{run:02d}_daq.csv").write_bytes(("\r\n".join(lines) + "\r\n").encode())
    probe = ["PROBE LOG", "DATE,TIME,Y [mm],dX [mm],dZ [mm]"]
    for k in range(0, ROWS, PROBE):
        at = start + dt.timedelta(seconds=60 * k + 20)
        probe.append(f"{at:%m/%d/%Y},{at:%H:%M:%S},{300.0 * (k // PROBE % 3):.3f},"
                     f"{values[k, 3] / 1e3:.6f},{values[k, 4] / 1e3:.6f}")
    (folder / f"MCR_L{run:02d}_probe.csv").write_bytes(("\r\n".join(probe) + "\r\n").encode())


def _init(tmp_path: Path, folder: Path, *keys: str) -> dict:
    assert main(["init", str(folder), f"out={tmp_path / 'init'}", *keys]) == 0
    return yaml.safe_load((tmp_path / "init" / "conf" / "data" / f"{folder.name}.yaml").read_text())


def test_init_reads_a_probe_logs_date_and_time_columns_as_its_time(tmp_path, capsys):
    """(Before: init proposed the probe log's ``DATE`` left out, then its own read refused
    ``TIME`` alone, "value '06:00:20' is not a time in data.time's format".)  The two columns
    are the error file's time: the runs join on it, every probe row kept."""
    for run in (1, 2, 3):
        benchlink(tmp_path / "mcr", run)
    conf = _init(tmp_path, tmp_path / "mcr")
    assert "DATE" not in conf["roles"].get("ignore", []), conf
    assert conf["roles"]["error"] == ["dX", "dZ"] and conf["roles"]["state"] == ["Y"], conf
    ds, _ = read_dataset(tmp_path / "mcr", {k: v for k, v in conf.items() if k != "defaults"})
    frame = ds.campaigns["MCR_L02"]
    assert len(frame) == ROWS // PROBE
    # (rate83) each row at its scan's time, the one at or before the probe's (20 s later; the
    # scans' ms after a colon kept): was the probe's time
    scans = np.arange(0, ROWS, PROBE)
    np.testing.assert_array_equal(frame["time"], scans * 60.0 + (scans % 7) / 1e3)
    expected = linear_run(8556, 2)[::PROBE]
    np.testing.assert_allclose(frame["E_dX"], expected[:, 3], atol=1e-3)
    np.testing.assert_allclose(frame["T_102_SPINDLE"], expected[:, 1], atol=0.02)


def test_init_reads_a_keysight_overload_as_a_missing_value_and_its_run_as_a_gap(tmp_path, capsys):
    """(Before: init wrote no key for an open thermocouple's ``+9.90000000E+37``, its read
    refused it as 9.9e+37 °C; given in ``data.missing_values``, its 3 scans were refused as a gap
    longer than ``data.max_gap_samples=0``.)"""
    for run in (1, 2, 3):
        benchlink(tmp_path / "mcr", run, open_scans=3 * (run == 2))
    conf = _init(tmp_path, tmp_path / "mcr")
    said = capsys.readouterr().out
    assert "a Keysight DAQ's overload" in said
    # the run's span in the DAQ's scans (60 s), not the probe's joined rows (before: 1800 s)
    assert "3 samples, 180 s of '102 <SPINDLE> (C)'" in said, said
    assert conf["missing_values"] == ["+9.90000000E+37"] and conf["max_gap_samples"] == 3, conf
    given = _init(tmp_path, tmp_path / "mcr", "data.missing_values=['9.9E+37']")
    assert given["missing_values"] == ["9.9E+37"] and given["max_gap_samples"] == 3, given
    ds, _ = read_dataset(tmp_path / "mcr", {k: v for k, v in conf.items() if k != "defaults"})
    assert np.abs(ds.campaigns["MCR_L02"]["T_102_SPINDLE"]).max() < 100


def test_init_reads_a_german_daq_export_beside_a_probe_log_with_decimal_points(tmp_path):
    """(Before: a DAQ970A's export on a German PC, ``;`` and ``+2,04390000E+01``, beside the NC's
    probe log in ``,`` and points, was refused by init, "11 column(s) not read: '102 <SPINDLE>
    (C)' is not numeric ('+2,04390000E+01')": its second look at the roles, once the probe's
    ``Y [mm]`` was proposed a state, read the first row with ``decimal: auto``.)"""
    for run in (1, 2, 3):
        benchlink(tmp_path / "mcr", run, german=True)
    conf = _init(tmp_path, tmp_path / "mcr")
    assert (conf["delimiter"], conf["decimal"]) == ("auto", "auto"), conf
    ds, _ = read_dataset(tmp_path / "mcr", {k: v for k, v in conf.items() if k != "defaults"})
    expected = linear_run(8556, 3)[::PROBE]
    np.testing.assert_allclose(ds.campaigns["MCR_L03"]["T_102_SPINDLE"], expected[:, 1], atol=0.02)
    np.testing.assert_allclose(ds.campaigns["MCR_L03"]["E_dZ"], expected[:, 4], atol=1e-3)


def test_rows_of_a_runs_daq_file_alone_writes_its_inputs(tmp_path, capsys):
    """(Before: ``thermocomp rows MCR_L03_daq.csv`` with the folder's data config was refused,
    "no E_ column: a campaign needs at least one measured error", its errors being in the probe's
    log: a control's inputs could not be written from the file a DAQ logs.)  Without
    ``rows.errors`` the file's scans are the rows, every one; with it, still refused."""
    for run in (1, 2, 3):
        benchlink(tmp_path / "mcr", run)
    _init(tmp_path, tmp_path / "mcr")
    capsys.readouterr()
    keys = [f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=mcr"]
    daq = tmp_path / "mcr" / "MCR_L03_daq.csv"
    assert main(["rows", str(daq), *keys]) == 0, capsys.readouterr().err
    lines = capsys.readouterr().out.splitlines()
    header = lines[0].split(",")
    assert header[:2] == ["time", "T_amb"] and not any(h.startswith("E_") for h in header)
    rows = np.array([[float(c) for c in line.split(",")] for line in lines[1:] if line])
    assert len(rows) == ROWS
    np.testing.assert_allclose(rows[:, header.index("T_102_SPINDLE")], linear_run(8556, 3)[:, 1],
                               atol=1e-6)
    assert main(["rows", str(daq), *keys, "rows.errors=true"]) == 2
    assert "no E_ column" in capsys.readouterr().err


def test_init_judges_a_daq_channel_on_its_own_scans_not_the_probes_rows(tmp_path, capsys):
    """(Before: a motor warming 0.15 K a scan, 1.5 K between two probe rows, was said to be "a
    number, a count or an index (a state)?": its steps judged on the joined rows.)  A column of
    the probe's log stepping by 1 (a sphere's number) is still warned."""
    for run in (1, 2, 3):
        benchlink(tmp_path / "mcr", run)
        probe = tmp_path / "mcr" / f"MCR_L{run:02d}_probe.csv"
        lines = probe.read_text().splitlines()
        lines[1] = lines[1].replace("DATE,TIME,", "DATE,TIME,SPHERE,")
        lines[2:] = [line.replace(",", f",{k % 3 + 1},", 2).replace(f",{k % 3 + 1},", ",", 1)
                     for k, line in enumerate(lines[2:])]
        probe.write_text("\r\n".join(lines) + "\r\n")
    _init(tmp_path, tmp_path / "mcr")
    said = capsys.readouterr().out
    assert "'104 <MOTOR> (C)' is proposed as a temperature" not in said, said
    assert "'SPHERE' is proposed as a temperature, but 100% of its steps" in said, said
