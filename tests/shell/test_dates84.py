"""Day or month first, decided from a lab file itself (dates84): a catman export's T0 and a Scope
View export's date-times with slashes were read month first, so an en-GB PC's ``03/05/2027`` (the
3rd of May) was read as the 5th of March without a word (bench_stranger84)."""

from __future__ import annotations

import datetime as dt
import re

import numpy as np
import pandas as pd
import pytest

from conftest import refused
from test_scope77 import ROWS, scope
from test_stranger84 import START, export
from thermocomp.core.io import read_dataset

ROLES = {"roles": {"error": ["MCS*"]}, "encoding": "cp1252", "test_fraction": 0.5}


def _day_first(path, start: dt.datetime):
    """The export as an en-GB PC writes it: its T0 day first."""
    text = path.read_bytes().replace(f"{start:%m/%d/%Y}".encode(), f"{start:%d/%m/%Y}".encode())
    path.write_bytes(text)


def _gb_folder(root, days=(0, 1)):
    for run, day in enumerate(days, start=1):
        path = export(root, run)
        _day_first(path, START + dt.timedelta(days=run - 1))
        if day != run - 1:          # (the run on another day: its T0's date moved)
            text = path.read_bytes().decode("cp1252")
            moved = f"{START + dt.timedelta(days=day):%d/%m/%Y}"
            path.write_bytes(re.sub(r"\d\d/\d\d/\d{4}", moved, text).encode("cp1252"))
    return root


def test_a_t0_either_order_could_read_is_refused_naming_file_line_and_the_key(tmp_path, capsys):
    """(Before: read month first, the 5th of March.)"""
    _gb_folder(tmp_path / "rig")
    said = refused(["init", str(tmp_path / "rig"), f"out={tmp_path / 'init'}"], capsys,
                   "column 'T0'", "'03/05/2027 07:00:00' is day or month first",
                   "data.dayfirst=true", "data.dayfirst=false")
    assert str(tmp_path / "rig" / "SP_T1.TXT") in said and "line 9" in said


@pytest.mark.parametrize("dayfirst, start", [(True, START), (False, dt.datetime(2027, 3, 5, 7))])
def test_data_dayfirst_says_the_order(tmp_path, dayfirst, start):
    ds, _ = read_dataset(_gb_folder(tmp_path / "rig"), {**ROLES, "dayfirst": dayfirst})
    assert ds.manifest["start"].iloc[0] == pd.Timestamp(start)


def test_a_day_past_12_fixes_the_order_of_its_file(tmp_path):
    """(Before: '13/05/2027 07:00:00' refused as no date and time.)"""
    ds, _ = read_dataset(_gb_folder(tmp_path / "rig", days=(10, 12)), ROLES)
    assert list(ds.manifest["start"]) == [pd.Timestamp(2027, 5, 13, 7), pd.Timestamp(2027, 5, 15, 7)]


def _slashed_scope(path, start):
    """A Scope View export with absolute times, its date-times ``dd/mm/yyyy HH:MM:SS.fff``."""
    scope(path, start)
    text = path.read_bytes().decode("cp1252")
    path.write_bytes(re.sub(r"(\d\d)\.(\d\d)\.(\d{4}) (\d\d:\d\d:\d\d),(\d{3})", r"\1/\2/\3 \4.\5",
                            text).encode("cp1252"))


def test_a_scope_run_across_midnight_tells_its_order(tmp_path):
    """01/02 23:59:50 then 02/02 00:00:00: 10 s day first, a month month first (before: read
    month first, a month's jump in the run)."""
    root = tmp_path / "runs"
    root.mkdir()
    starts = [dt.datetime(2027, 2, day, 23, 55) for day in (1, 3, 5)]
    for run, start in enumerate(starts, start=1):
        _slashed_scope(root / f"Scope_{run}.csv", start)
    ds, _ = read_dataset(root, {"roles": {"error": ["Tracker*"]}, "encoding": "cp1252",
                                "test_fraction": 0.34, "max_gap_samples": 1})
    assert list(ds.manifest["start"]) == [pd.Timestamp(s) for s in starts]
    assert ds.campaigns["Scope_1"]["time"].max() < ROWS * 10.0


def test_a_labview_date_day_first_is_read_by_data_dayfirst_not_guessed(tmp_path, capsys):
    """An en-GB LabVIEW's ``Date 06/09/2027`` (its segments' too): refused, then read by the key
    (before: month first, the 9th of June)."""
    from test_stranger69 import CFG, _folder

    folder = _folder(tmp_path / "runs")
    for path in folder.iterdir():
        text = path.read_bytes().decode("cp1252")
        path.write_bytes(re.sub(r"(\d{4})/(\d\d)/(\d\d)", r"\3/\2/\1", text).encode("cp1252"))
    refused(["init", str(folder), f"out={tmp_path / 'init'}"], capsys, "column 'Date'",
            "'06/09/2027' is day or month first", "data.dayfirst=true")
    ds, _ = read_dataset(folder, {**CFG, "dayfirst": True})
    assert list(ds.manifest["start"]) == [pd.Timestamp(2027, 9, d, 6) for d in (6, 8, 10)]


def test_a_folder_is_one_record_read_in_the_order_one_of_its_files_says(tmp_path, capsys):
    """The 3rd's test read day first as the 13th's says, in init (written to the config) and in a
    read (before: the 13th refused as no date and time)."""
    root = _gb_folder(tmp_path / "rig", days=(0, 10))
    ds, _ = read_dataset(root, ROLES)
    assert list(ds.manifest["start"]) == [pd.Timestamp(2027, 5, 3, 7), pd.Timestamp(2027, 5, 13, 7)]
    from thermocomp.shell.cli import main

    assert main(["init", str(root), f"out={tmp_path / 'init'}"]) == 0
    assert "dates with slashes read day first, as SP_T2.TXT's '13/05/2027' says" in capsys.readouterr().out
    assert "dayfirst: true" in (tmp_path / "init" / "conf" / "data" / "rig.yaml").read_text()


def test_files_saying_both_orders_are_refused_naming_both(tmp_path, capsys):
    root = _gb_folder(tmp_path / "rig", days=(10, 11))
    second = root / "SP_T2.TXT"                   # its T0 written month first: 05/14/2027
    second.write_bytes(second.read_bytes().replace(b"14/05/2027", b"05/14/2027"))
    said = refused(["init", str(root), f"out={tmp_path / 'init'}"], capsys,
                   "'13/05/2027' is day first", "'05/14/2027' month first", "data.dayfirst=true|false")
    assert str(root / "SP_T1.TXT") in said and str(second) in said


def _csv_folder(root, days):
    """Two runs of a CSV table, its time ``dd/mm/yyyy HH:MM:SS`` (an en-GB PC's)."""
    root.mkdir()
    for run, day in enumerate(days, start=1):
        t = pd.date_range(dt.datetime(2027, 5, day, 7), periods=40, freq="60s")
        heat = (t - t[0]).total_seconds().to_numpy() / 2400.0
        pd.DataFrame({"time": t.strftime("%d/%m/%Y %H:%M:%S"), "T_a": 20 + heat,
                      "T_b": 20 + heat ** 2, "T_c": 20 + np.sin(3 * heat + run),
                      "E_x": 3.0 * heat}).to_csv(root / f"run_{run}.csv", index=False)
    return root


def test_a_csv_tables_slashed_dates_read_by_data_dayfirst_too(tmp_path, capsys):
    """One key for every reader (before: a CSV's either-way date named data.time alone)."""
    root = _csv_folder(tmp_path / "csv", (3, 4))
    opts = {"test_fraction": 0.5, "dayfirst": True}
    ds, _ = read_dataset(root, opts)
    assert list(ds.manifest["start"]) == [pd.Timestamp(2027, 5, 3, 7), pd.Timestamp(2027, 5, 4, 7)]
    refused(["init", str(root), f"out={tmp_path / 'init'}"], capsys, "day or month first",
            "data.dayfirst=true|false")
    later = _csv_folder(tmp_path / "later", (3, 13))
    with pytest.raises(Exception, match=r"'13/05/2027 07:00:00' says .* day first, but "
                                        r"data.dayfirst=false"):
        read_dataset(later, {**opts, "dayfirst": False})


def piped_as_its_file(tmp_path, monkeypatch, root, *keys: str) -> list[dict]:
    """``monitor`` on the record ``root`` (its test run ``run_2.csv``) read from its file and
    piped in (``monitor.input=-``): E_x's figures, each."""
    import io as _io
    import json

    from conftest import FAST
    from thermocomp.shell.cli import main

    common = ["monitor", f"data.path={root}", "data.test_fraction=0.5", *keys, *FAST]
    assert main([*common, f"out={tmp_path / 'file'}"]) == 0
    monkeypatch.setattr("sys.stdin", _io.StringIO((root / "run_2.csv").read_text()))
    assert main([*common, "monitor.input=-", f"out={tmp_path / 'pipe'}"]) == 0
    return [json.loads((tmp_path / k / "monitor.json").read_text())["targets"]["E_x"]
            for k in ("file", "pipe")]


def test_a_stream_of_such_rows_reads_in_data_dayfirsts_order(tmp_path, monkeypatch):
    """The test run piped in (``monitor.input=-``) scores as its file does (before: refused,
    "day or month first? set data.time ...", the key read by the file's reader alone)."""
    said = piped_as_its_file(tmp_path, monkeypatch, _csv_folder(tmp_path / "csv", (3, 4)),
                             "data.dayfirst=true")
    assert said[1]["n_samples"] == 40
    assert said[1]["rmse_fixed"] == pytest.approx(said[0]["rmse_fixed"], rel=1e-12)
