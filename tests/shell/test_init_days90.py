"""init's Excel-days check reads the column's first rows, not its first cell (stop 90).

Before: a plain ``time`` of seconds since a logger started 8 h 20 min before the file's first
row (30000, 30060, ...) was proposed as Excel's serial days from its first cell alone, and
init's own read then refused a campaign of 2.4e4 days.
"""
from __future__ import annotations

import pandas as pd

from test_stranger64 import EXCEL_EPOCH, _config, lab_frame
from thermocomp.shell.cli import main


def _plain_time(path, first_s: float, days: bool):
    """``lab_frame``'s record under a plain ``time`` header: seconds from ``first_s``, or the
    same instants as Excel's serial days (``days``)."""
    frame = lab_frame(240).drop(columns=["Z ram [mm]"])
    seconds = first_s + frame.pop("t [s]")
    if days:
        start = (pd.Timestamp("2027-03-01") - EXCEL_EPOCH) / pd.Timedelta(days=1)
        seconds = (start + seconds / 86400.0).map(lambda d: f"{d:.10f}")
    frame.insert(0, "time", seconds)
    frame.to_csv(path, index=False)
    return path


def test_init_reads_elapsed_seconds_in_the_day_numbers_range_as_seconds(tmp_path, capsys):
    path = _plain_time(tmp_path / "late_start.csv", 30000.0, days=False)
    assert main(["init", str(path), "data.roles.error=[dZ]", f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "Excel's serial days" not in said and "sample period: 60 s, 240 rows" in said
    assert "d" not in (_config(tmp_path / "init").get("units") or {}).values()


def test_init_still_reads_a_plain_time_of_excel_days_as_days(tmp_path, capsys):
    path = _plain_time(tmp_path / "days.csv", 0.0, days=True)
    assert main(["init", str(path), "data.roles.error=[dZ]", f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "Excel's serial days" in said and "sample period: 60 s, 240 rows" in said
    assert _config(tmp_path / "init")["units"] == {"time": "d"}
