"""A lab's Keysight DAQ exports of a 5-axis trunnion machining centre's runs (keysight70): one CSV
per run as BenchLink Data Logger (a 34970A) or a DAQ970A writes it: a block of ``key,value``
lines above the table, ``Scan``, ``Time`` as ``MM/DD/YYYY HH:MM:SS:mmm`` (the milliseconds after
a colon), each channel ``101 <Air> (C)`` followed by its ``Alarm 101``, a trailing separator;
a German PC's with ``;`` and decimal commas, the probes' channels scaled to µm by the logger's
Mx+B with their label left ``VDC`` (``benchmarks/bench_keysight70.py`` writes the lab's full
record; these are a few rows of it)."""

from __future__ import annotations

import copy
import datetime as dt
import io
import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, refused
from test_export import needs_cc
from test_stranger65 import _compiled_stream_equals_its_pack
from test_stranger68 import ROWS, linear_run
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

LABELS = ["Air", "Column", "Table", "DISP_X", "DISP_Z", "A axis"]
CHANNELS = [101, 102, 103, 201, 202, 205]
HEADER = ["Name,DMU thermal run", "Owner,Thermal lab", "Acquisition Date,{start}",
          "Instrument,34970A (Serial Number MY41012345) at GPIB0::9::INSTR",
          "Total Sweeps,{rows}", "Total Channels,6", ""]
VOLTS = ["'201 <DISP_X> (um)'", "'202 <DISP_Z> (um)'"]


def _values(run: int) -> np.ndarray:
    """A run's rows: test_stranger68's three temperatures and two errors, the tilt A."""
    a = np.where((np.arange(ROWS) // 30) % 2, 90.0, 0.0)
    return np.round(np.column_stack([linear_run(7043, run), a]), 3)


def _export(path: Path, start: dt.datetime, values: np.ndarray, sep: str = ",",
            decimal: str = ".", probe_unit: str = "um", day_first: bool = False) -> Path:
    """``values`` as the logger's software exports them (scans 13 ms late now and then: the
    milliseconds after a colon; an alarm above 21 °C on the table; ``day_first``: a European
    PC's date order)."""
    date = "%d/%m/%Y" if day_first else "%m/%d/%Y"
    units = ["C", "C", "C", probe_unit, probe_unit, "DEG"]
    names = ["Scan", "Time"]
    for channel, label, unit in zip(CHANNELS, LABELS, units):
        names += [f"{channel} <{label}> ({unit})", f"Alarm {channel}"]
    lines = [line.replace(",", sep).format(start=f"{start:%m/%d/%Y %H:%M:%S}", rows=len(values))
             for line in HEADER] + [sep.join(names) + sep]
    for k, row in enumerate(values):
        at = start + dt.timedelta(minutes=k, milliseconds=13 * (k % 3 == 1))
        cells = [str(k + 1), f"{at.strftime(date)} {at:%H:%M:%S}:{at.microsecond // 1000:03d}"]
        for i, v in enumerate(row):
            cells += [f"{v:.3f}".replace(".", decimal), "2" if i == 2 and v > 21 else "0"]
        lines.append(sep.join(cells) + sep)
    path.write_bytes("\r\n".join(lines).encode("utf-8") + b"\r\n")
    return path


def _folder(root: Path, **kw) -> Path:
    root.mkdir()
    for run in (1, 2, 3):      # March 1, 3 and 5: every date reads either way round
        _export(root / f"dmu_run{run:02d}.csv", dt.datetime(2027, 3, 2 * run - 1, 6),
                _values(run), **kw)
    return root


def test_a_benchlink_folder_reads_each_run_month_first_without_the_daqs_own_columns(tmp_path):
    ds, _ = read_dataset(_folder(tmp_path / "runs"), {"roles": {"error": ["*DISP*"]},
                                                      "test_fraction": 0.34})
    assert list(ds.manifest["split"]) == ["train", "train", "test"]
    # March, not January (a Keysight DAQ's Time is month first), to the millisecond
    assert list(ds.manifest["start"]) == [np.datetime64(f"2027-03-0{d}T06:00") for d in (1, 3, 5)]
    frame = ds.campaigns["dmu_run02"]
    assert list(frame.columns) == ["time", "T_101_Air", "T_102_Column", "T_103_Table",
                                   "E_201_DISP_X", "E_202_DISP_Z", "S_205_A_axis"]
    np.testing.assert_allclose(frame["time"].to_numpy()[:4], [0.0, 60.013, 120.0, 180.0])
    np.testing.assert_allclose(frame.iloc[:, 1:].to_numpy(), _values(2))


def test_init_and_run_on_the_benchlink_folder(tmp_path, capsys):
    folder = _folder(tmp_path / "runs")
    assert main(["init", str(folder), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert ("dmu_run01.csv: dates with slashes read as data.time='%m/%d/%Y %H:%M:%S', the order "
            "its rows say (a Keysight DAQ's Time, its ms after a colon: month first)") in said
    assert "timestamps from 2027-03-01T06:00:00" in said
    assert "  Scan                DAQ's own    - (left out: no measurement)" in said
    assert "  Alarm 103           DAQ's own    - (left out: no measurement)" in said
    assert "  201 <DISP_X> (um)   error        E_201_DISP_X" in said
    assert "  205 <A axis> (DEG)  state        S_205_A_axis" in said
    conf = (tmp_path / "init" / "conf" / "data" / "runs.yaml").read_text(encoding="utf-8")
    assert "Alarm" not in conf and "Scan" not in conf
    assert main(["run", f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=runs",
                 "model=mlr", *FAST, f"out={tmp_path / 'out'}"]) == 0
    metrics = json.loads((tmp_path / "out" / "metrics.json").read_text())
    assert metrics["targets"]["E_201_DISP_X"]["test"]["rmse"] < 0.2     # (the map is linear)
    assert set(metrics["targets"]) == {"E_201_DISP_X", "E_202_DISP_Z"}


def test_probes_left_at_vdc_are_refused_naming_the_patterns_that_give_their_unit(tmp_path,
                                                                                  capsys):
    """A DAQ970A's export on a German PC (``;``, decimal commas), the probes' Mx+B label left
    ``VDC``: init names the patterns that say µm (a map's key with brackets is not read on the
    command line, so ``data.units`` could not), and with them reads the values as written."""
    folder = _folder(tmp_path / "runs", sep=";", decimal=",", probe_unit="VDC")
    refused(["init", str(folder), f"out={tmp_path / 'init'}"], capsys,
            "no column reads as a measured error",
            f"data.roles.error=[{', '.join(VOLTS)}]; raw volts need the probe's scale applied")
    refused(["init", str(folder), "data.roles.error=['*DISP*']", f"out={tmp_path / 'init'}"],
            capsys, "'201 <DISP_X> (VDC)': unit 'VDC' is not an error's",
            f"data.roles.error=[{VOLTS[0]}]")
    assert main(["init", str(folder), f"data.roles.error=[{', '.join(VOLTS)}]",
                 f"out={tmp_path / 'init'}"]) == 0
    assert "  201 <DISP_X> (VDC)  error        E_201_DISP_X" in capsys.readouterr().out
    ds, _ = read_dataset(folder, {"roles": {"error": ["*DISP* (um)"]}, "delimiter": ";",
                                  "decimal": ","})
    np.testing.assert_allclose(ds.campaigns["dmu_run03"].iloc[:, 1:].to_numpy(), _values(3))


@pytest.mark.parametrize("pattern, unit", [("*DISP* [mm]", 1000.0), ("Kanal[*]", None)])
def test_a_role_patterns_own_unit_converts_and_a_glob_bracket_is_no_unit(tmp_path, pattern,
                                                                         unit):
    path = tmp_path / "lab.csv"
    path.write_text("time;Kanal*;DISP_X (VDC);Air\n0;1;0,001;20\n60;2;0,002;20,1\n"
                    "120;3;0,004;20,3\n", encoding="utf-8")
    roles = {"error": [pattern, "DISP_X (mm)"]} if unit else {"state": [pattern],
                                                               "error": ["DISP* (mm)"]}
    ds, _ = read_dataset(path, {"roles": roles, "delimiter": ";", "decimal": ","})
    frame = ds.campaigns["lab"]
    np.testing.assert_allclose(frame["E_DISP_X"], [1.0, 2.0, 4.0])   # mm -> µm
    if unit is None:
        np.testing.assert_allclose(frame["S_Kanal"], [1.0, 2.0, 3.0])


def test_a_time_cell_no_keysight_time_is_refused_naming_file_column_and_line(tmp_path, capsys):
    folder = _folder(tmp_path / "runs")
    path = folder / "dmu_run02.csv"
    lines = path.read_bytes().split(b"\r\n")
    lines[20] = lines[20].replace(b":000,", b":0x0,", 1)
    path.write_bytes(b"\r\n".join(lines))
    refused(["run", f"data.path={folder}", "data.roles.error=['*DISP*']", "data.test_fraction=0.34",
             *FAST, f"out={tmp_path / 'out'}"], capsys,
            f"file {path}, column 'time', line 21 (data row 13): value '03/03/2027 06:12:00:0x0' "
            "is not a time in data.time's format '%m/%d/%Y %H:%M:%S'")
    assert not (tmp_path / "out").exists()


@needs_cc
@pytest.mark.parametrize("sep, decimal, probe, time", [
    (",", ".", "um", ["data.time='%m/%d/%Y %H:%M:%S'"]),     # as init writes it
    (";", ",", "VDC", [])])                                  # data.time=auto: the file says it
def test_the_compiled_stream_reads_the_keysight_export_as_the_reader_does(tmp_path, sep, decimal,
                                                                          probe, time):
    """Before: the C export refused ('data.time=%m/%d/%Y %H:%M:%S, which stream.c cannot
    convert'), or, with data.time=auto, its stream refused the raw file's every time; a lag
    bank reads the time: the ms after a colon count."""
    path = _export(tmp_path / "run.csv", dt.datetime(2027, 3, 1, 6), _values(1), sep=sep,
                   decimal=decimal, probe_unit=probe)
    common = [f"data.path={path}", f"data.roles.error=[{', '.join(VOLTS)}]", *time,
              "data.test_fraction=0.3", "data.reference=none"]
    _compiled_stream_equals_its_pack(tmp_path, path, common)


def test_a_day_first_keysight_file_is_read_as_its_rows_past_the_12th_say(tmp_path, capsys):
    """A European PC's export writes its day first: a run from 12/03 22:00 into 13/03 is March
    the 12th and 13th, not December the 3rd (the Keysight month first is the order only where no
    row says one); before, init read it month first and refused the 13th's rows."""
    path, start = tmp_path / "dmu_eu.csv", dt.datetime(2027, 3, 12, 22, 0)
    _export(path, start, np.vstack([_values(1)] * 3), day_first=True)
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert ("dmu_eu.csv: dates with slashes read as data.time='%d/%m/%Y %H:%M:%S', the order its "
            "rows say (a day or month past 12)") in said
    ds, _ = read_dataset(path, {"roles": {"error": ["*DISP*"]}, "time": "%d/%m/%Y %H:%M:%S"})
    assert list(ds.manifest["start"]) == [np.datetime64("2027-03-12T22:00")]


def _two_runs(root: Path, first_from: int = 10, second_day_first: bool = True) -> Path:
    """A European PC's two runs (small71): the first from March ``first_from`` 06:00 (the 10th:
    no day past 12, either order reads), the second from 12/03 23:00 into 13/03 (its 61st row
    says day first), or, not ``second_day_first``, a US PC's (``03/13``: month first)."""
    root.mkdir()
    _export(root / "dmu_run01.csv", dt.datetime(2027, 3, first_from, 6), _values(1),
            day_first=True)
    _export(root / "dmu_run02.csv", dt.datetime(2027, 3, 12, 23), _values(2),
            day_first=second_day_first)
    return root


def test_a_later_file_past_the_12th_says_the_order_of_the_whole_folder(tmp_path, capsys):
    """Before: read by its first file (a Keysight Time: month first), the folder's second run
    was refused at its 13th's row (init and run alike); the first run was October the 3rd."""
    folder = _two_runs(tmp_path / "runs")
    ds, _ = read_dataset(folder, {"roles": {"error": ["*DISP*"]}})      # data.time=auto
    assert list(ds.manifest["start"]) == [np.datetime64("2027-03-10T06:00"),
                                          np.datetime64("2027-03-12T23:00")]
    np.testing.assert_allclose(ds.campaigns["dmu_run02"]["time"].to_numpy()[59:62],
                               [3540.0, 3600.0, 3660.013])         # past midnight, into the 13th
    assert main(["init", str(folder), f"out={tmp_path / 'init'}"]) == 0
    assert ("dmu_run01.csv: dates with slashes read as data.time='%d/%m/%Y %H:%M:%S', the order "
            "the rows of dmu_run02.csv say (a day or month past 12: its data row 61, "
            "'13/03/2027 00:00:00:000'), in every file") in capsys.readouterr().out
    conf = (tmp_path / "init" / "conf" / "data" / "runs.yaml").read_text(encoding="utf-8")
    assert "time: '%d/%m/%Y %H:%M:%S'" in conf


def test_a_one_file_record_takes_the_order_its_read_reads_once(tmp_path, monkeypatch, caplog):
    """A one file record's order is decided from the rows its read reads (small72): before, every
    row was read once for the order (slashed._said) and again for the record."""
    import thermocomp.core.io.slashed as slashed

    path = _export(tmp_path / "dmu_eu.csv", dt.datetime(2027, 3, 12, 23), _values(2),
                   day_first=True)           # its row 61 (13/03) says day first
    monkeypatch.setattr(slashed, "_said", lambda *a: pytest.fail("the file read for its order"))
    with caplog.at_level("INFO", logger="thermocomp"):
        ds, _ = read_dataset(path, {"roles": {"error": ["*DISP*"]}})     # data.time=auto
    assert list(ds.manifest["start"]) == [np.datetime64("2027-03-12T23:00")]
    np.testing.assert_allclose(ds.campaigns["dmu_eu"]["time"].to_numpy()[59:62],
                               [3540.0, 3600.0, 3660.013])         # past midnight, into the 13th
    assert ("dates with slashes read as data.time='%d/%m/%Y %H:%M:%S', the order dmu_eu.csv's "
            "data row 61 says ('13/03/2027 00:00:00:000')") in caplog.text


def test_files_that_contradict_each_other_are_refused_naming_both(tmp_path, capsys):
    """Day first by the first (13/03 from its first row), month first by the second (03/13 from
    its row 61): one data.time cannot read both.  Before, init wrote the first's order and the
    second was refused at its row 61 naming only that file; a run read each by its own first
    row, two orders in one record, without a word."""
    folder = _two_runs(tmp_path / "runs", first_from=13, second_day_first=False)
    first, second = folder / "dmu_run01.csv", folder / "dmu_run02.csv"
    for stage in (["init", str(folder)], ["run", f"data.path={folder}",
                                          "data.roles.error=['*DISP*']", *FAST]):
        refused([*stage, f"out={tmp_path / 'out'}"], capsys,
                f"file {first}, column 'Time', data row 1: value '13/03/2027 06:00:00:000' says "
                "its dates with slashes are day first",
                f"but file {second}, column 'Time', data row 61: '03/13/2027 00:00:00:000' says "
                "month first", "data.time")
        assert not (tmp_path / "out").exists()


def _monitored(tmp_path, monkeypatch, capsys, stream: Path, name: str) -> tuple[int, str]:
    """``monitor`` of the lab's export ``stream`` on stdin (``data.time=auto``, no init) with
    the model fitted on ``_two_runs``' folder (day first: its second run's row 61 says so)."""
    folder = tmp_path / "runs"
    if not folder.exists():
        _two_runs(folder)
    monkeypatch.setattr("sys.stdin", io.StringIO(stream.read_text(encoding="utf-8")))
    code = main(["monitor", f"data.path={folder}", "data.roles.error=['*DISP*']", "model=lagbank",
                 "monitor.input=-", f"out={tmp_path / name}", *FAST])
    return code, capsys.readouterr().err


def test_a_stream_reads_its_dates_in_the_order_its_training_record_decided(tmp_path, monkeypatch,
                                                                          capsys):
    """code71: the stream's first row alone decided (a Keysight Time: month first): the lab's
    next run from 10/03 23:00 into 11/03 (no day past 12) was read October 3rd, then November
    3rd, without a word (a lag bank's RMSE 3.24 / 6.66 µm against 0.036 / 0.061), and one into
    13/03 refused at its 61st row.  Now both are read day first, as the record was; a US PC's
    run (03/13 at row 61) is refused naming the row."""
    for start in (10, 12):                  # no row says the order / row 61 says day first
        stream = _export(tmp_path / f"next_{start}.csv", dt.datetime(2027, 3, start, 23),
                         _values(3), day_first=True)
        code, err = _monitored(tmp_path, monkeypatch, capsys, stream, f"m{start}")
        assert code == 0, err
        report = json.loads((tmp_path / f"m{start}" / "monitor.json").read_text())
        assert report["events"] == [] and report["targets"]["E_201_DISP_X"]["n_samples"] == ROWS
        assert report["targets"]["E_201_DISP_X"]["rmse_fixed"] < 0.1
    us = _export(tmp_path / "us.csv", dt.datetime(2027, 3, 12, 23), _values(3))
    monkeypatch.setattr("sys.stdin", io.StringIO(us.read_text(encoding="utf-8")))
    refused(["monitor", f"data.path={tmp_path / 'runs'}", "data.roles.error=['*DISP*']",
             "monitor.input=-", f"out={tmp_path / 'us'}", *FAST], capsys,
            "file <stdin>, column 'time', data row 61: value '03/13/2027 00:00:00:000' says its "
            "dates with slashes are month first, but the record the model was trained on says "
            "day first (data.time='%d/%m/%Y %H:%M:%S')")
    assert not (tmp_path / "us").exists()


def test_the_served_model_reads_a_blocks_dates_in_its_records_order(tmp_path):
    """code71: each served block's first row decided (a Keysight Time: month first): the lab's
    run from 10/03 23:00 into 11/03 was served as October 3rd, then November 3rd (a lag bank's
    corrections 9.46 µm off those of the same rows timed in seconds).  The deployed model
    carries the record's order (``slashed_``); a row saying the other order is a 400."""
    from mlflow.exceptions import MlflowException

    from test_export import _compose
    from thermocomp.apps.deploy.pyfunc import CompensatorModel
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    cfg = _compose(f"data.path={_two_runs(tmp_path / 'runs')}", "data.roles.error=['*DISP*']",
                   "model=lagbank", "track=false", "monitor.adaptive=false")
    ds, train, _, _ = read_streamed(cfg, test=False)
    deployed = deployable_model(cfg, ds, train, None, "serve.model")[0]
    block = pd.read_csv(_export(tmp_path / "next.csv", dt.datetime(2027, 3, 10, 23), _values(3),
                                day_first=True), skiprows=len(HEADER))
    seconds = block.assign(Time=np.arange(ROWS) * 60.0 + 0.013 * (np.arange(ROWS) % 3 == 1))
    served, timed = (CompensatorModel(copy.deepcopy(deployed)).predict(None, b, {"reset": True})
                     for b in (block, seconds))
    corrections = [c for c in served.columns if c.startswith("C_")]
    assert len(corrections) == 2
    np.testing.assert_array_equal(served[corrections], timed[corrections])
    us = pd.read_csv(_export(tmp_path / "us.csv", dt.datetime(2027, 3, 12, 23), _values(3)),
                     skiprows=len(HEADER))
    with pytest.raises(MlflowException, match="data row 61 of the block: value '03/13/2027 "
                       "00:00:00:000' says its dates with slashes are month first"):
        CompensatorModel(copy.deepcopy(deployed)).predict(None, us, {"reset": True})


def test_a_model_deployed_before_code71_says_it_reads_a_blocks_first_row_once(tmp_path, caplog,
                                                                             capsys):
    """small72: a model pickled before code71 has no ``slashed_``: its streams read dates with
    slashes by each block's first row, without a word before; loading it says so, naming it,
    once (serve's trusted copy of it does not say it again)."""
    import mlflow

    from test_export import _compose
    from thermocomp.apps.deploy.pyfunc import load_deployed, save_compensator
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    cfg = _compose(f"data.path={_two_runs(tmp_path / 'runs')}", "data.roles.error=['*DISP*']",
                   "model=mlr", "track=false", "monitor.adaptive=false")
    ds, train, _, _ = read_streamed(cfg, test=False)
    deployed = deployable_model(cfg, ds, train, None, "serve.model")[0]
    assert deployed.slashed_ == "%d/%m/%Y %H:%M:%S"
    del deployed.slashed_                                   # as pickled before code71
    old = save_compensator(deployed, tmp_path / "old")
    capsys.readouterr()

    def said() -> list[str]:     # (a serving process logs to stderr itself: load_context)
        lines = [r.getMessage() for r in caplog.records] + [
            line.removeprefix("[thermocomp] warning: ") for line in capsys.readouterr().err.splitlines()]
        caplog.clear()
        return sorted({line for line in lines if "before code71" in line})   # (each said once)

    with caplog.at_level("WARNING"):
        copied = save_compensator(load_deployed(str(old), old), tmp_path / "copy")
        first = said()
        assert len(first) == 1 and first[0].startswith(f"model {old} carries no order of its training")
        assert "(deployed before code71, or built outside thermocomp's deploy)" in first[0]
        assert "read in the order each block's first row says" in first[0]
        assert "promote its run's model.pkl again" in first[0]
        mlflow.pyfunc.load_model(str(old))                  # a serving process loads it
        assert len(said()) == 1
        mlflow.pyfunc.load_model(str(copied))
        load_deployed(str(copied), copied)
        assert said() == []
