"""A lab's data in (data91): a time column of seconds since midnight under a header that does
not say so (``t``), its logger paused over midnight, read with ``data.time=of_day`` (it was
refused, "time decreases ... sort them", and no key said what the column holds); the refusal
names the key; a served model's session reads its blocks' dateless ``h:mm:ss`` on from the last
time it read, a day added past midnight (each block was refused, read alone)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from conftest import refused
from test_data88b import _clock, _record
from test_serve import _model
from thermocomp.core.io import ContractError, ReadOptions, read_dataset
from thermocomp.core.io.stdin import read_stream, stream_stamps
from thermocomp.shell.cli import main

DAY_S, START_S, PAUSE_S = 86400.0, 77400.0, 1800.0     # the record starts at 21:30:00


def _paused(rows: pd.DataFrame) -> pd.DataFrame:
    """``rows`` with the logger paused ``PAUSE_S`` at midnight: every time after it later."""
    return rows.assign(time=rows["time"] + PAUSE_S * (rows["time"] + START_S >= DAY_S))


def _headerless(rows: pd.DataFrame) -> pd.DataFrame:
    """``rows``' time as seconds since midnight under ``t`` (the step over midnight, a day
    added, longer than any other step: its values alone do not say a clock)."""
    return rows.assign(time=(rows["time"] + START_S) % DAY_S).rename(columns={"time": "t"})


def test_a_headerless_seconds_of_day_paused_at_midnight_reads_with_data_time_of_day(tmp_path):
    # before: data.time=of_day refused ("data.time must be one of auto, seconds, ..."), and
    # without it "time decreases from 86100 s (row 30) to 2100 s ... sort them by their time"
    rows = _paused(_record(91))
    lab = _headerless(rows)
    steps = np.diff(lab["t"])
    assert steps.min() + DAY_S > steps.max() > 0       # no step elsewhere as long as midnight's
    lab.to_csv(tmp_path / "night.csv", index=False)
    ds, report = read_dataset(tmp_path / "night.csv", {"time": "of_day"})
    time = ds.campaigns["night"]["time"].to_numpy()
    np.testing.assert_allclose(time - time[0], rows["time"], atol=1e-9)
    np.testing.assert_allclose(ds.campaigns["night"]["E_X"], rows["E_X"])
    assert report["campaigns"]["night"]["time"] == "seconds of day"


def test_without_the_key_the_refusal_names_it_and_init_writes_it_when_given(tmp_path, capsys):
    _headerless(_paused(_record(92))).to_csv(tmp_path / "night.csv", index=False)
    refused(["init", str(tmp_path / "night.csv"), f"out={tmp_path / 'a'}"], capsys, "night.csv",
            "column 'time'", "data row 31", "data.time=of_day")
    assert main(["init", str(tmp_path / "night.csv"), "data.time=of_day",
                 f"out={tmp_path / 'b'}"]) == 0
    out = capsys.readouterr().out
    assert "seconds of day" in out and "data.time=of_day" in out
    assert "time: of_day" in (tmp_path / "b" / "conf" / "data" / "night.yaml").read_text()


def test_of_day_refuses_a_value_outside_a_day_with_its_row(tmp_path):
    rows = _record(93)
    lab = _headerless(rows)
    lab.loc[12, "t"] = DAY_S + 60                 # no second of a day
    lab.to_csv(tmp_path / "night.csv", index=False)
    with pytest.raises(ContractError, match=r"no second of a day.*data row 13|data row 13.*no "
                                            r"second of a day"):
        read_dataset(tmp_path / "night.csv", {"time": "of_day"})


def test_a_sessions_blocks_of_a_dateless_clock_read_on_as_the_whole_night_does():
    # before: stream_stamps took no session's time (each served block read alone, refused)
    night = _clock(_record(94))["Time"]
    whole, _ = read_stream(pd.DataFrame({"time": night, "T_a": 1.0, "T_b": 1.0, "T_c": 1.0})
                           .to_csv(index=False), ["T_a", "T_b", "T_c"], ReadOptions.from_cfg({}))
    carried = [float("nan"), 0.0]
    blocks = [stream_stamps(night.iloc[a:a + 7].reset_index(drop=True), served=True,
                            carried=carried) for a in range(0, len(night), 7)]
    np.testing.assert_allclose(np.concatenate([b.to_numpy() for b in blocks]),
                               whole["time"].to_numpy(), atol=1e-9)


def test_a_served_session_passes_midnight_in_h_mm_ss_blocks_as_in_seconds():
    # before: each block refused, "a time of day without its date ... not in a served model's
    # block, read alone"
    model, camps = _model()
    run = camps[list(camps)[-1]]
    start = pd.Timestamp("2027-03-05 23:00:00")
    clock = run.assign(time=[(start + pd.Timedelta(seconds=float(t))).strftime("%H:%M:%S")
                             for t in run["time"] - run["time"].iloc[0]])
    assert clock["time"].iloc[0] > clock["time"].iloc[-1]            # it passes midnight
    want = model.predict(None, run.assign(time=run["time"] - run["time"].iloc[0] + 82800.0),
                         {"session": "seconds", "reset": True})
    got = pd.concat([model.predict(None, clock.iloc[a:a + 25], {"session": "clock",
                                                                 "reset": a == 0})
                     for a in range(0, len(clock), 25)], ignore_index=True)
    pd.testing.assert_frame_equal(got, want)


def test_a_stream_of_seconds_of_day_paused_at_midnight_reads_as_the_file_with_the_key():
    # (the stream's numbers under data.time=of_day were parsed as timestamps: AttributeError)
    rows = _paused(_record(95))
    text = _headerless(rows).rename(columns={"t": "time"}).to_csv(index=False)
    streamed, _ = read_stream(text, ["T_a", "T_b", "T_c"], ReadOptions.from_cfg({"time": "of_day"}))
    time = streamed["time"].to_numpy()
    np.testing.assert_allclose(time - time[0], rows["time"], atol=1e-9)


def test_a_dateless_clock_that_never_passes_midnight_reads_with_the_key(tmp_path):
    # before: refused under any data.time, "a time of day without its date"
    rows = _record(96).iloc[:20]                  # 21:30 to 23:05: no midnight
    _clock(rows).to_csv(tmp_path / "evening.csv", index=False)
    with pytest.raises(ContractError, match="time of day without its date.*data.time=of_day"):
        read_dataset(tmp_path / "evening.csv")
    ds, _ = read_dataset(tmp_path / "evening.csv", {"time": "of_day"})
    time = ds.campaigns["evening"]["time"].to_numpy()
    np.testing.assert_allclose(time - time[0], rows["time"], atol=1e-9)
