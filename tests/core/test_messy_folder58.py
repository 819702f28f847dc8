"""A lab's folder of many runs, messy as real loggers make them (messy58): runs sorted into
sub-folders, a channel renamed from some run on, runs logged at other periods, a logger's clock
reset inside a run, summary rows under the data."""

from __future__ import annotations

import pytest

from test_sample_rate56 import said
from thermocomp.core.io import read_dataset
from thermocomp.core.io.contract import ContractError


def run_file(path, rows: int = 30, period: float = 60.0, level: float = 20.0,
             names=("T_spindle", "T_bed"), tail: str = ""):
    """One run, ``rows`` samples ``period`` s apart: two temperatures warming, the error
    following the first (contract names, or ``names`` the file's own)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    lines = [f"time,{names[0]},{names[1]},E_X"]
    for i in range(rows):
        t = i * period
        lines.append(f"{t:g},{level + 0.001 * t:.3f},{level + 0.0004 * t:.3f},{0.003 * t:.2f}")
    path.write_text("\n".join(lines) + "\n" + tail, encoding="utf-8")
    return path


def test_runs_in_a_sub_folder_beside_the_folders_runs_are_said_not_read(tmp_path, caplog):
    # half the lab's runs in a month folder were left out without a word (16 of 32 read)
    for i in range(1, 4):
        run_file(tmp_path / f"run_{i}.csv")
    for i in range(4, 6):
        run_file(tmp_path / "2023-02" / f"run_{i}.csv")
    text = said(caplog, tmp_path)
    assert "its sub-folders hold 2 more run files (2023-02/ (2)), not read" in text


def test_a_folder_whose_runs_are_all_in_sub_folders_names_them(tmp_path):
    # it was refused as "manifest not found" alone
    for i in range(1, 3):
        run_file(tmp_path / "2023-01" / f"run_{i}.csv")
        run_file(tmp_path / "2023-02" / f"run_{i + 2}.csv")
    with pytest.raises(ContractError, match=r"its sub-folders hold 4 \(2023-01/ \(2\), 2023-02/ "
                                            r"\(2\)\), not read: .*2023-01/<run>.csv"):
        read_dataset(tmp_path)


def stamped(path, stamps):
    """A run whose time column holds ``stamps`` as written."""
    path.write_text("time,T_spindle,E_X\n" + "".join(
        f"{t},{20 + 0.1 * i:.2f},{0.2 * i:.1f}\n" for i, t in enumerate(stamps)), encoding="utf-8")
    return path


def minutes(start: str, first: int, count: int) -> list[str]:
    """``count`` timestamps a minute apart from minute ``first`` after ``start``."""
    import pandas as pd

    return [(pd.Timestamp(start) + pd.Timedelta(minutes=first + k)).isoformat()
            for k in range(count)]


def test_a_loggers_clock_reset_to_its_default_date_is_not_said_to_be_sorted(tmp_path):
    # was "the rows are not in time order; sort them by their time": sorted, the run would
    # start in 2000 and last 23 years (refused then as longer than data.max_duration_days)
    path = stamped(tmp_path / "run.csv", minutes("2023-01-27T10:00", 0, 20)
                   + minutes("2000-01-01T00:00", 0, 20))
    with pytest.raises(ContractError) as refused:
        read_dataset(path)
    assert refused.value.row == 21
    assert "(23.1 years back): the logger's clock set back" in refused.value.reason
    assert "cut the file at this row into two runs" in refused.value.reason
    assert "sort them" not in refused.value.reason


def test_a_clock_set_back_into_the_runs_own_span_is_not_said_to_be_sorted(tmp_path):
    # set back 88.5 min into the run's own three hours (a clock set by hand, not daylight
    # saving time): sorting would interleave the stretches before and after
    path = stamped(tmp_path / "run.csv", minutes("2023-01-27T10:00", 0, 180)
                   + [f"{t[:-2]}30" for t in minutes("2023-01-27T10:00", 90, 20)])
    with pytest.raises(ContractError, match=r"\(88.5 min back\): .*would mix its stretches"):
        read_dataset(path)
    # two exports pasted the wrong way round are still to be sorted
    pasted = stamped(tmp_path / "pasted.csv", minutes("2023-01-27T10:00", 90, 90)
                     + minutes("2023-01-27T10:00", 0, 90))
    with pytest.raises(ContractError, match="sort them by their time"):
        read_dataset(pasted)


def test_runs_logged_at_other_periods_than_the_others_are_said(tmp_path, caplog):
    # read without a word: a 10 s run weighed six times a 60 s one in the fit and the scores
    # (lagbank on the climate room's 32 runs, 9 of them at 10 s: test RMSE E_X 1.68 -> 2.07 µm)
    for i in range(1, 5):
        run_file(tmp_path / f"run_{i}.csv", rows=30 if i % 2 else 180, period=60 if i % 2 else 10)
    text = said(caplog, tmp_path)
    assert ("its campaigns are logged at different sample periods (10 s: 2 (run_2, run_4); "
            "60 s: 2 (run_1, run_3))") in text
    assert "data.resample_s=60 puts them on one grid" in text
    assert "different sample periods" not in said(caplog, tmp_path, {"resample_s": 60})
    for i in (2, 4):
        run_file(tmp_path / f"run_{i}.csv", rows=30, period=60)
    assert "different sample periods" not in said(caplog, tmp_path)


def test_summary_rows_under_a_runs_data_are_left_out_and_said(tmp_path, caplog):
    # refused: "column 'time' ... value 'Mittelwert' is not a number", naming no fix
    path = run_file(tmp_path / "run.csv", tail="Mittelwert,20.9,20.4,2.6\nMax,21.7,20.7,5.2\n")
    text = said(caplog, path)
    assert "footer left out (2 line(s) under the data: 'Mittelwert,20.9,20.4,2.6')" in text
    ds, report = read_dataset(path)
    assert report["rows"] == 30
    # a logger's status column of words: its last rows are rows like every other, not a summary
    lines = ["Status,time,T1 [°C],dX [µm]"] + [
        f"{'run' if i < 25 else 'cool'},{60 * i},{20 + 0.01 * i:.2f},{0.1 * i:.1f}"
        for i in range(30)]
    path = tmp_path / "run.csv"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    ds, report = read_dataset(path, {"roles": {"error": ["dX"], "ignore": ["Status"]}})
    assert report["rows"] == 30


def test_a_header_only_run_among_a_folders_runs_is_said_to_be_left_out(tmp_path):
    # "file has a header but no data rows" alone: the file named, not what to do with it
    for i in range(1, 4):
        run_file(tmp_path / f"run_{i}.csv")
    (tmp_path / "run_4.csv").write_text("time,T_spindle,T_bed,E_X\n", encoding="utf-8")
    with pytest.raises(ContractError, match="no data rows: a run not recorded.*leave the file "
                                            "out of the folder") as refused:
        read_dataset(tmp_path)
    assert refused.value.file.name == "run_4.csv"


def test_a_clock_resynchronised_by_minutes_is_no_daylight_saving_time(tmp_path):
    # set back 6.5 min (a clock resync): it was said "set back by up to an hour, daylight saving
    # time ending? set data.timezone", which cannot read it (lead58); an hour less a period is
    path = stamped(tmp_path / "resync.csv", minutes("2023-06-01T08:00", 0, 60)
                   + [f"{t[:-2]}30" for t in minutes("2023-06-01T08:00", 52, 60)])
    with pytest.raises(ContractError) as refused:
        read_dataset(path)
    assert "(6.5 min back): the logger's clock set back" in refused.value.reason
    assert "daylight saving" not in refused.value.reason
    autumn = stamped(tmp_path / "autumn.csv", minutes("2023-10-29T01:00", 0, 120)
                     + minutes("2023-10-29T02:00", 0, 60))        # 02:59 -> 02:00
    with pytest.raises(ContractError, match="daylight saving time ending"):
        read_dataset(autumn)
