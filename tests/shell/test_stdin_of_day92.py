"""A stream on stdin under ``data.time=of_day`` reads its time by the file's one function
(data92, :func:`thermocomp.core.io.timestamps.seconds_of_day`): a value outside a day,
[0, 86400) s, is refused with its row, exit 2, in the file's words.  Before, stdin unwrapped the
column by ``past_midnight`` alone: 86460 s was taken as a time (a sample 1.5 h out of place), a
negative one refused as a clock stepping 22 h forward."""

from __future__ import annotations

import io
import sys

import pytest

from conftest import refused
from test_data91 import DAY_S, _headerless, _record
from thermocomp.core.io import ContractError, ReadOptions, read_dataset
from thermocomp.core.io.stdin import read_stream

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
