"""A TwinCAT Scope export as Scope View's other options write it (lab77): the absolute time
format (a date-time per row, the PC's clock), channels on different clocks (each ``Time;Value``
pair its own sample times: the temperatures every 10 s, a tracker every 60 s 3.7 s after them,
another target's clock) and a ``BOOL`` channel written ``True`` / ``False``.  Before: refused at
the first date-time ("cell '08.02.2027 06:00:00,000' is no number"); with ms times the two
clocks went to the historian's grid (refused without ``data.resample_s``, then held)."""

from __future__ import annotations

import datetime as dt
import io
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

from conftest import FAST, refused
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

ROWS, PERIOD, EVERY, OFFSET = 60, 10.0, 6, 3.7        # the tracker: every 60 s, 3.7 s late
START = dt.datetime(2027, 2, 8, 6)


def truth(s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Two temperatures (°C) and the error (µm) at times ``s``: the error linear in them."""
    t1 = 20 + 0.002 * s + np.sin(s / 900.0)
    t2 = 21 + 0.001 * s
    return t1, t2, 3.0 * (t1 - 20) + 2.0 * (t2 - 21)


def scope(path: Path, start: dt.datetime, absolute: bool = True) -> Path:
    """One run as a German Scope View exports it: ``;``, decimal commas, cp1252."""
    def num(v: float, digits: int = 4) -> str:
        return f"{v:.{digits}f}".replace(".", ",")

    def when(s: float) -> str:
        return ((start + dt.timedelta(seconds=float(s))).strftime("%d.%m.%Y %H:%M:%S,%f")[:-3]
                if absolute else num(s * 1000, 1))

    fast = np.arange(ROWS) * PERIOD
    slow = np.arange(0, ROWS * PERIOD, EVERY * PERIOD) + OFFSET
    t1, t2, _ = truth(fast)
    on = (np.arange(ROWS) // 20) % 2 == 0
    chans = [("Temp Bett", "°C", "REAL64", [(when(s), num(v)) for s, v in zip(fast, t1)]),
             ("Temp Ständer", "°C", "REAL64", [(when(s), num(v)) for s, v in zip(fast, t2)]),
             ("Tracker dX", "mm", "REAL64",
              [(when(s), num(v / 1000, 7)) for s, v in zip(slow, truth(slow)[2])]),
             ("Spindel an", "", "BOOL", [(when(s), str(bool(v))) for s, v in zip(fast, on)])]
    filetime = int((start - dt.timedelta(hours=1) - dt.datetime(1601, 1, 1)).total_seconds() * 1e7)
    lines = ["Name;Portal;", f"StartTime;{filetime};{start:%d.%m.%Y %H:%M:%S},000", ""]
    props = [("Name", 0), ("Data-Type", 2), ("SampleTime[ms]", None), ("Unit", 1)]
    for key, k in props:
        cells = [c[k] if k is not None else ("60000" if c[0] == "Tracker dX" else "10000")
                 for c in chans]
        lines.append(";".join(f"{key};{v};" for v in cells))
    lines += ["", ";".join("Time;Value;" for _ in chans)]
    for r in range(ROWS):
        lines.append(";".join(f"{c[3][r][0]};{c[3][r][1]};" if r < len(c[3]) else ";;"
                              for c in chans))
    path.write_bytes("\r\n".join(lines).encode("cp1252") + b"\r\n")
    return path


def folder(root: Path, absolute: bool = True) -> Path:
    root.mkdir()
    for run in (1, 2, 3):
        scope(root / f"Scope_{run}.csv", START + dt.timedelta(days=7 * run), absolute)
    return root


OPTIONS = {"roles": {"error": ["Tracker*"]}, "encoding": "cp1252", "test_fraction": 0.34,
           "max_gap_samples": 1}


@pytest.mark.parametrize("absolute", [True, False])
def test_channels_on_two_clocks_are_read_on_the_union_of_their_times(tmp_path, absolute):
    ds, _ = read_dataset(folder(tmp_path / "runs", absolute), OPTIONS)
    frame = ds.campaigns["Scope_2"]
    assert list(frame.columns) == ["time", "T_Bett", "T_Ständer", "E_Tracker_dX",
                                   "S_Spindel_an"]
    fast = np.arange(ROWS) * PERIOD
    slow = np.arange(0, ROWS * PERIOD, EVERY * PERIOD) + OFFSET
    np.testing.assert_allclose(frame["time"], np.union1d(fast, slow), atol=1e-6)
    # the tracker on its own rows, at its own times, empty at the temperatures' (never held)
    measured = frame["E_Tracker_dX"].notna().to_numpy()
    np.testing.assert_allclose(frame["time"][measured], slow, atol=1e-6)
    np.testing.assert_allclose(frame["E_Tracker_dX"][measured], truth(slow)[2], atol=1e-3)
    # a temperature at the tracker's times: interpolated in time over its one-row gap
    np.testing.assert_allclose(frame["T_Bett"], truth(frame["time"].to_numpy())[0],
                               atol=2e-3)
    # the BOOL's True / False: 1 / 0, a state
    on = frame.loc[np.isin(frame["time"], fast), "S_Spindel_an"].to_numpy()
    np.testing.assert_array_equal(on, ((np.arange(ROWS) // 20) % 2 == 0).astype(float))
    start = ds.manifest["start"].iloc[1]
    if absolute:       # the PC's date-times: a clock the file does not say (no UTC)
        assert start == pd.Timestamp(START + dt.timedelta(days=14))
    else:              # StartTime's FILETIME ticks are UTC (written an hour before the local)
        assert start == pd.Timestamp(START + dt.timedelta(days=14, hours=-1), tz="UTC")


def test_init_proposes_the_bool_as_a_state_and_the_gap_the_clocks_leave(tmp_path, capsys):
    runs = folder(tmp_path / "runs")
    assert main(["init", str(runs), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert any(line.split() == ["Spindel", "an", "[-]", "state", "S_Spindel_an"]
               for line in said.splitlines()), said
    assert "data.max_gap_samples=1 interpolates such runs linearly" in said
    written = yaml.safe_load((tmp_path / "init" / "conf" / "data" / "runs.yaml").read_text())
    assert written["max_gap_samples"] == 1 and written["roles"]["state"] == ["Spindel an"]


@pytest.mark.parametrize(("at", "cell", "says"), [
    (10, "Maybe", "column 'Spindel an', line 12: cell 'Maybe' is no True / False (a BOOL "
                  "channel)"),
    (0, "15.02.2027 6h00", "column 'Temp Bett', line 12: cell '15.02.2027 6h00' is no date-time"),
])
def test_a_broken_bool_or_date_time_is_refused_naming_file_channel_and_line(tmp_path, capsys,
                                                                               at, cell, says):
    runs = folder(tmp_path / "runs")
    path = runs / "Scope_2.csv"
    lines = path.read_bytes().decode("cp1252").split("\r\n")
    cells = lines[11].split(";")
    cells[at] = cell
    lines[11] = ";".join(cells)
    path.write_bytes("\r\n".join(lines).encode("cp1252"))
    refused(["run", f"data.path={runs}", "data.roles.error=[Tracker*]", "data.encoding=cp1252",
             "data.test_fraction=0.34", "data.max_gap_samples=1", *FAST,
             f"out={tmp_path / 'out'}"], capsys, f"file {path}, {says}")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("titled", [True, False])
def test_an_export_without_its_header_blocks_is_refused_naming_file_line_and_columns(
        tmp_path, capsys, titled):
    """(lab78) Scope View's *Include header* off: no preamble, no property rows, with or
    without the ``Time;Value`` row.  Before: refused as a CSV of unnamed columns ("'Value' has
    no role, columns 2 and 5 have the same header 'Value' ...", or its first samples taken for
    headers, "'20,0000' has no role").  Now: said what it is, by ``init``, ``run`` and ``rows``
    alike, exit 2, nothing written."""
    lines = scope(tmp_path / "whole.csv", START).read_bytes().decode("cp1252").split("\r\n")
    at = next(i for i, line in enumerate(lines) if line.startswith("Time;Value")) + (not titled)
    path = tmp_path / "Scope_9.csv"
    path.write_bytes("\r\n".join(lines[at:]).encode("cp1252"))
    what = "'Time;Value' over each channel" if titled else "samples, a time and a value a channel"
    says = (f"file {path}, line 1: a TwinCAT Scope export without its header blocks (Scope "
            f"View's 'Include header' off): {what}, 4 channel(s) in columns 1-2, 4-5, 7-8, "
            "10-11, none named")
    refused(["rows", str(path), "data.encoding=cp1252"], capsys, says)
    refused(["init", str(path), f"out={tmp_path / 'init'}"], capsys, says)
    assert not (tmp_path / "init").exists()


def test_rows_writes_each_campaign_a_block_with_the_errors_on_request(tmp_path, capsys):
    """(lab78) ``thermocomp rows`` of a folder: every campaign its block (a blank line between:
    where ``stream.c`` starts a campaign), its cells the dataset's as read (``rows.errors``: the
    tracker's too, empty between its samples); ``rows.campaigns`` picks, one unknown refused."""
    runs = folder(tmp_path / "runs")
    given = ["data.roles.error=[Tracker*]", "data.encoding=cp1252", "data.max_gap_samples=1"]
    ds, _ = read_dataset(runs, {k: v for k, v in OPTIONS.items() if k != "test_fraction"})
    assert main(["rows", str(runs), *given, "rows.errors=true"]) == 0
    blocks = capsys.readouterr().out.split("\n\n")
    assert len(blocks) == 3
    header = blocks[0].splitlines()[0]
    assert header == "time,T_Bett,T_Ständer,E_Tracker_dX,S_Spindel_an"
    for cid, block in zip(["Scope_1", "Scope_2", "Scope_3"], blocks):
        got = pd.read_csv(io.StringIO(block if block.startswith("time") else f"{header}\n{block}"))
        pd.testing.assert_frame_equal(got, ds.campaigns[cid][got.columns].reset_index(drop=True),
                                      check_exact=True, check_dtype=False)
    assert main(["rows", str(runs), *given, "rows.campaigns=[Scope_2]"]) == 0
    only = capsys.readouterr().out
    assert "\n\n" not in only and only.splitlines()[0] == "time,T_Bett,T_Ständer,S_Spindel_an"
    assert len(only.splitlines()) == len(ds.campaigns["Scope_2"]) + 1
    refused(["rows", str(runs), *given, "rows.campaigns=[Scope_4]"], capsys,
            "rows.campaigns names 'Scope_4', no campaign of data.path (it has 'Scope_1', "
            "'Scope_2', 'Scope_3')")
