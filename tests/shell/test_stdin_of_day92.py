"""A stream on stdin under ``data.time=of_day`` reads its time by the file's one function
(data92, :func:`thermocomp.core.io.timestamps.seconds_of_day`): a value outside a day,
[0, 86400) s, is refused with its row, exit 2, in the file's words.  Before, stdin unwrapped the
column by ``past_midnight`` alone: 86460 s was taken as a time (a sample 1.5 h out of place), a
negative one refused as a clock stepping 22 h forward."""

from __future__ import annotations

import io
import sys

import numpy as np
import pytest

from conftest import refused
from test_data91 import DAY_S, _headerless, _record
from thermocomp.core.io import ContractError, ReadOptions, read_dataset
from thermocomp.core.io.stdin import read_stream, stream_campaigns

NAMES = ["T_a", "T_b", "T_c"]


def _night(seed: int, row: int, value: float):
    """A record's rows, its time as seconds since midnight under ``time`` (past midnight),
    data row ``row`` (1-based) holding ``value``."""
    lab = _headerless(_record(seed)).rename(columns={"t": "time"})
    lab.loc[row - 1, "time"] = value
    return lab


@pytest.mark.parametrize("value", [DAY_S + 60, -5.0])
def test_stdin_refuses_a_value_outside_a_day_as_the_file_does(tmp_path, value):
    lab = _night(921, 13, value)
    lab.to_csv(tmp_path / "night.csv", index=False)
    with pytest.raises(ContractError) as from_file:
        read_dataset(tmp_path / "night.csv", {"time": "of_day"})
    with pytest.raises(ContractError) as from_stdin:
        read_stream(lab.to_csv(index=False), NAMES, ReadOptions.from_cfg({"time": "of_day"}))
    assert (from_stdin.value.row, from_stdin.value.column) == (13, "time")
    assert from_stdin.value.reason == from_file.value.reason
    assert "no second of a day" in from_stdin.value.reason


def test_monitor_on_stdin_exits_2_naming_stdin_column_and_row(tmp_path, monkeypatch, capsys):
    _headerless(_record(922)).rename(columns={"t": "time"}).to_csv(tmp_path / "night.csv", index=False)
    args = [f"data.path={tmp_path / 'night.csv'}", "data.time=of_day", "data.test_fraction=0.25",
            "plots=none", "track=false"]
    from thermocomp.shell.cli import main
    assert main(["run", *args, "model=mlr", f"out={tmp_path / 'run'}"]) == 0
    bad = _night(922, 40, DAY_S + 60)
    monkeypatch.setattr(sys, "stdin", io.StringIO(bad.to_csv(index=False)))
    refused(["monitor", *args, f"monitor.model={tmp_path / 'run' / 'model.pkl'}",
             "monitor.input=-", f"out={tmp_path / 'mon'}"], capsys,
            "<stdin>", "column 'time'", "data row 40", "no second of a day")
    assert not (tmp_path / "mon" / "monitor.json").exists()


@pytest.mark.parametrize("written", ["seconds", "h:mm:ss"])
def test_a_blank_line_before_midnights_step_back_starts_a_campaign_as_stream_c_does(written):
    """con109: a blank line before the row where a time of day passes midnight (23:55 then
    00:00) starts a campaign in ``stream.c`` (its ``day_passed``), as the data contract says
    (dep108d: "... or starts where a blank line stands before the row"); stdin, carrying the time
    of day on a day there (dep108d), read it as a stray blank line within a run: one campaign,
    the lag bank 2.91 um off the C from that row (``benchmarks/bench_con109.py blank``)."""
    lab = _headerless(_record(923)).rename(columns={"t": "time"})
    day = int(np.flatnonzero(np.diff(lab["time"]) < 0)[0]) + 1    # the first row after midnight
    if written == "h:mm:ss":
        lab["time"] = [f"{s // 3600}:{s // 60 % 60:02d}:{s % 60:02d}" for s in lab["time"].astype(int)]
    lines = lab.to_csv(index=False).splitlines()
    text = "\n".join([*lines[:day + 1], "", *lines[day + 1:]]) + "\n"
    parts, _ = stream_campaigns(text, NAMES, ReadOptions.from_cfg({"time": "of_day"}))
    assert [len(p) for p in parts.values()] == [day, len(lab) - day]
