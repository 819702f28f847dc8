"""A lab's data in (data89b): a time column of seconds since midnight (``Seconds of day``:
77400 ... 86100, 0, 300 ...) is read by the time of day's rule, a day added where the clock goes
back past midnight (it was not taken for the time, and named by ``data.roles.time`` it was
refused, "time decreases ... sort them by their time", the rows being in order); one pause of
a record is warned of once, suggesting what works for its time column (a dateless clock's was
warned twice, the second suggesting ``data.runs_at_pauses``, which cannot split it); an
ingest report's ``settings`` name the data config's keys as its ``ingested_with.settings`` do."""

from __future__ import annotations

import json
import logging

import numpy as np
import pandas as pd
import pytest

from conftest import FAST
from test_data88b import START, _record
from test_data89 import _paused
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.shell.cli import main

DAY_S = 86400


def _of_day(rows: pd.DataFrame, header: str) -> pd.DataFrame:
    """``rows`` with their ``time`` as a logger's seconds since midnight under ``header``."""
    of_day = (rows["time"] + (START - START.normalize()).total_seconds()) % DAY_S
    return rows.assign(time=of_day).rename(columns={"time": header})


@pytest.mark.parametrize("header, keys", [("Seconds of day", {}),               # the header says
                                          ("Logger [s]", {"roles": {"time": "Logger"}})])  # values
def test_seconds_of_day_past_midnight_read_as_a_continuing_time(tmp_path, header, keys):
    # before: no time column found ("set data.sample_period_s"); named, "time decreases from
    # 86100 s ... sort them by their time"
    rows = _record(8).drop(index=[9, 33]).reset_index(drop=True)    # (a skipped row stays one)
    lab = _of_day(rows, header)
    assert (np.diff(lab[header]) < -DAY_S / 2).sum() == 1             # the record passes midnight
    lab.to_csv(tmp_path / "daysec.csv", index=False)
    ds, report = read_dataset(tmp_path / "daysec.csv", keys)
    time = ds.campaigns["daysec"]["time"].to_numpy()
    np.testing.assert_allclose(time - time[0], rows["time"], atol=1e-9)
    assert report["campaigns"]["daysec"]["time"] == "seconds of day"


def test_a_time_started_again_after_half_a_day_is_no_midnight(tmp_path):
    # within a day and back by more than half a day, but 8.17 h without rows, a day added: a
    # logger's elapsed seconds started again (57000 s, then 0), not a clock passing midnight:
    # still refused, the refusal saying what reads seconds of the day
    rows = _record(9)
    restart = np.r_[np.arange(20) * 3000.0, np.arange(len(rows) - 20) * 3000.0]
    rows.assign(time=restart).to_csv(tmp_path / "restart.csv", index=False)
    with pytest.raises(ContractError, match="time decreases .* or seconds of the day past "
                       "midnight after 8.17 h without rows"):
        read_dataset(tmp_path / "restart.csv")
    # the same rows as seconds of the day past midnight: read
    _of_day(rows, "Seconds of day").to_csv(tmp_path / "daysec.csv", index=False)
    assert read_dataset(tmp_path / "daysec.csv")[0].campaigns["daysec"]["time"].is_monotonic_increasing


def _pause_warnings(caplog) -> list[str]:
    return [r.getMessage() for r in caplog.records
            if r.levelno == logging.WARNING and "pause" in r.getMessage()]


def test_a_dateless_clocks_pause_is_warned_of_once(tmp_path, caplog):
    # before: twice, the record's "one record, yet it pauses" beside it suggesting
    # data.runs_at_pauses=true, which refuses a time written as text
    with caplog.at_level(logging.WARNING):
        read_dataset(_paused(tmp_path))
    said = _pause_warnings(caplog)
    assert len(said) == 1 and "data row 42" in said[0] and "runs_at_pauses" not in said[0]


def test_an_elapsed_times_pause_is_warned_of_naming_what_splits_it(tmp_path, caplog):
    # before: "data.runs_at_pauses=true ... reads each as a campaign", which is then refused
    rows = _record(10)
    elapsed = rows["time"] + np.where(np.arange(len(rows)) > 30, 12 * 3600.0, 0.0)
    text = [f"{int(t // 3600)}:{int(t % 3600 // 60):02d}:{int(t % 60):02d}" for t in elapsed]
    rows.assign(time=text).rename(columns={"time": "Dauer"}).to_csv(tmp_path / "long.csv",
                                                                    index=False)
    with caplog.at_level(logging.WARNING):
        read_dataset(tmp_path / "long.csv")
    said = _pause_warnings(caplog)
    assert len(said) == 1 and "data row 32" in said[0]
    assert "data.roles.campaign" in said[0] and "data.runs_at_pauses=true" not in said[0]
    with pytest.raises(ContractError, match="data.runs_at_pauses"):
        read_dataset(tmp_path / "long.csv", {"runs_at_pauses": True})


def test_an_ingest_reports_settings_are_named_as_its_ingested_with(tmp_path):
    # before: settings said join_offset_s / join_tolerance_s, ingested_with data.join.offset_s
    _record(11).to_csv(tmp_path / "record.csv", index=False)
    assert main(["ingest", f"data.path={tmp_path / 'record.csv'}", "data.test_fraction=0.25",
                 f"data.interim={tmp_path / 'interim'}", "data.join.offset_s=2.5", *FAST]) == 0
    report = json.loads((tmp_path / "interim" / "ingest_report.json").read_text())
    ingested = {k.removeprefix("data."): v for k, v in report["ingested_with"]["settings"].items()
                if k != "data.path"}
    assert set(report["settings"]) == set(ingested)
    assert report["settings"]["join.offset_s"] == 2.5
