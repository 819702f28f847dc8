"""A lab's data in (data89): a stream's time of day without its date that passes midnight is
read as a file's is (it was refused, "a stream's time is one column ..."; a served model's block,
read alone, is still refused, saying why); an ingest records its reading settings under the data
config's keys (``data.join.offset_s``; it named ``data.join_offset_s`` and internal fields such as
``data.skip_rows``), an ingest recorded under the old names refused once, saying so; a pause in a
dateless clock, which reads as well a day longer, is warned of with its row."""

from __future__ import annotations

import io
import json
import logging

import numpy as np
import pandas as pd
import pytest
import yaml

from conftest import FAST, ROOT, refused
from test_data88b import _clock, _record
from thermocomp.core.io import ContractError, ReadOptions, read_dataset
from thermocomp.core.io.stdin import read_stream, stream_stamps
from thermocomp.shell.cli import main


def _night(rows: pd.DataFrame) -> pd.DataFrame:
    """``rows`` with ``time`` the wall clock's ``hh:mm:ss``, no date (past midnight)."""
    return _clock(rows).rename(columns={"Time": "time"})


def test_a_streamed_time_of_day_past_midnight_is_read_as_the_files_time(tmp_path):
    # before: refused, "value '21:30:00' is a time of day without its date ... a stream's time
    # is one column, seconds or a timestamp with its date"
    rows = _record(3).drop(index=[7, 30]).reset_index(drop=True)     # (a skipped row stays one)
    text = _night(rows).to_csv(index=False)
    (tmp_path / "night.csv").write_text(text)
    filed = read_dataset(tmp_path / "night.csv")[0].campaigns["night"]["time"]
    streamed, _ = read_stream(text, ["T_a", "T_b", "T_c"], ReadOptions.from_cfg({}))
    np.testing.assert_array_equal(streamed["time"].to_numpy(), filed.to_numpy())
    np.testing.assert_array_equal(streamed["time"] - streamed["time"].iloc[0], rows["time"])


def test_the_monitor_streams_a_piped_night_as_the_same_rows_in_seconds(tmp_path, monkeypatch):
    rows = _record(4)
    rows.to_csv(tmp_path / "record.csv", index=False)
    common = ["monitor", f"data.path={tmp_path / 'record.csv'}", "data.test_fraction=0.25",
              *FAST]
    said = {}
    for name, piped in (("clock", _night(rows)), ("seconds", rows)):
        monkeypatch.setattr("sys.stdin", io.StringIO(piped.to_csv(index=False)))
        assert main([*common, "monitor.input=-", f"out={tmp_path / name}"]) == 0
        said[name] = json.loads((tmp_path / name / "monitor.json").read_text())["targets"]
    assert said["clock"]["E_X"]["n_samples"] == len(rows)
    for key in ("n_samples", "rmse_fixed", "rmse_adaptive"):
        assert said["clock"]["E_X"][key] == pytest.approx(said["seconds"]["E_X"][key], abs=1e-12)


def test_a_served_blocks_time_of_day_is_refused_saying_why():
    # a block is read alone: a day passing between two blocks cannot be told
    night = _clock(_record(5))["Time"]
    with pytest.raises(ContractError, match="served model's block, read alone"):
        stream_stamps(night, served=True)


@pytest.fixture
def study(tmp_path):
    _record(6).to_csv(tmp_path / "record.csv", index=False)
    return tmp_path, [f"data.path={tmp_path / 'record.csv'}", "data.test_fraction=0.25",
                      f"data.interim={tmp_path / 'interim'}", *FAST]


def test_an_ingest_records_its_settings_under_the_data_configs_keys(study):
    tmp_path, args = study
    assert main(["ingest", *args, "data.join.offset_s=2.5"]) == 0
    made = json.loads((tmp_path / "interim" / "ingest_report.json").read_text())["ingested_with"]
    conf = yaml.safe_load((ROOT / "conf" / "data" / "default.yaml").read_text())
    keys = {f"data.{k}" for k in conf if k != "join"} | {f"data.join.{k}" for k in conf["join"]}
    assert set(made["settings"]) <= keys
    assert made["settings"]["data.join.offset_s"] == 2.5


def test_an_ingest_recorded_under_the_old_names_is_refused_once_saying_so(study, capsys):
    from thermocomp.shell.fingerprint import CONFIG, json_hash

    tmp_path, args = study
    assert main(["ingest", *args]) == 0
    report = tmp_path / "interim" / "ingest_report.json"
    doc = json.loads(report.read_text())
    settings = doc["ingested_with"]["settings"]      # as the code before data89 wrote them
    settings["data.join_offset_s"] = settings.pop("data.join.offset_s")
    settings["data.skip_rows"] = 1
    doc["ingested_with"][CONFIG] = json_hash({k: v for k, v in settings.items() if k != "data.path"})
    report.write_text(json.dumps(doc))
    refused(["train", *args], capsys, "ingest_report.json", "recorded its settings under other "
            "names (data.join_offset_s, data.skip_rows", "ingest again, once")
    assert main(["ingest", *args]) == 0
    assert main(["train", *args]) == 0


def _paused(tmp_path):
    """A dateless clock past midnight whose logger pauses 9 h after data row 41 (00:50 -> 09:55)."""
    rows = _clock(_record(7))
    later = pd.to_datetime(rows["Time"].iloc[41:], format="%H:%M:%S") + pd.Timedelta(hours=9)
    rows.loc[41:, "Time"] = later.dt.strftime("%H:%M:%S").to_numpy()
    rows.to_csv(tmp_path / "paused.csv", index=False)
    return tmp_path / "paused.csv"


def test_a_pause_in_a_dateless_clock_is_warned_of_with_its_row(tmp_path, caplog):
    # before: read as 9 h without a word of the day (or more) it may as well be
    with caplog.at_level(logging.WARNING):
        ds, _ = read_dataset(_paused(tmp_path))
    said = [r.getMessage() for r in caplog.records if "a day lost" in r.getMessage()]
    assert len(said) == 1 and "data row 42" in said[0] and "data.roles.time=[<date" in said[0]
    time = ds.campaigns["paused"]["time"].to_numpy()
    assert time[41] - time[40] == pytest.approx(9 * 3600 + 300)      # read as the clock says


def test_runs_at_pauses_on_a_dateless_clock_is_refused_naming_the_keys(tmp_path):
    # before: ValueError "diff requires input that is at least one dimensional" (no file, no key)
    with pytest.raises(ContractError, match=r"data.roles.time=\[<date column>") as caught:
        read_dataset(_paused(tmp_path), {"runs_at_pauses": True})
    assert caught.value.file is not None and caught.value.column == "time"
