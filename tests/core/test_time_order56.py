"""A lab's record whose rows are out of time order or repeat a time (session 56)."""

from __future__ import annotations

import pandas as pd
import pytest

from thermocomp.core.io import read_dataset
from thermocomp.core.io.contract import ContractError


def record(path, stamps) -> None:
    path.write_text("time,T_spindle,E_X\n" + "".join(
        f"{t},{20 + 0.1 * i:.2f},{0.2 * i:.1f}\n" for i, t in enumerate(stamps)), encoding="utf-8")


def test_rows_out_of_time_order_are_refused_saying_to_sort_them_with_the_times_as_written(tmp_path):
    # two exports pasted in the wrong order were refused "time decreases from 4800 s (row 5) to
    # -6000 s": seconds the file does not hold (one negative), and no fix
    stamps = [f"2026-10-24T{19 + m // 60:02d}:{m % 60:02d}:00" for m in range(0, 200, 20)]
    record(tmp_path / "lab.csv", stamps[5:] + stamps[:5])
    with pytest.raises(ContractError) as refused:
        read_dataset(tmp_path / "lab.csv")
    assert refused.value.row == 6
    assert refused.value.reason == ("time decreases from 2026-10-24T22:00:00 (row 5) to "
                                    "2026-10-24T19:00:00: the rows are not in time order; sort "
                                    "them by their time")


def test_a_repeated_time_is_refused_saying_what_to_do(tmp_path):
    stamps = [f"2026-10-24T19:{m:02d}:00" for m in range(30, 40)]
    record(tmp_path / "lab.csv", stamps[:4] + stamps[3:9])
    with pytest.raises(ContractError) as refused:
        read_dataset(tmp_path / "lab.csv")
    assert refused.value.row == 5
    assert refused.value.reason == ("duplicate time 2026-10-24T19:33:00 (same as row 4): two "
                                    "samples at one time; delete the row written twice, or give "
                                    "it its own time")


def test_a_time_starting_again_is_refused_saying_the_logger_restarted(tmp_path):
    # refused "time decreases from 240 s (row 5) to 0 s" and no more: a logger whose elapsed
    # time starts again at 0 after a restart, one run per file the way to read it
    record(tmp_path / "lab.csv", [60 * i for i in range(5)] + [60 * i for i in range(5)])
    with pytest.raises(ContractError) as refused:
        read_dataset(tmp_path / "lab.csv")
    assert refused.value.row == 6
    assert refused.value.reason == ("time decreases from 240 s (row 5) to 0 s: the time starts "
                                    "again (the logger restarted, or runs joined in one file?): "
                                    "one file per run in a folder reads each as a campaign")


def test_a_row_written_out_of_place_is_to_be_sorted_not_cut_as_a_clock_set_back(tmp_path):
    # audit86: two adjacent rows swapped (a sample a gateway wrote late) were said "the logger's
    # clock set back ...; sorting the rows would mix its stretches before and after this row:
    # cut the file at this row into two runs": sorted, they are the logger's regular minutes
    seconds = [60 * i for i in range(40)]
    seconds[20], seconds[21] = seconds[21], seconds[20]
    record(tmp_path / "lab.csv", seconds)
    with pytest.raises(ContractError) as refused:
        read_dataset(tmp_path / "lab.csv")
    assert refused.value.row == 22
    assert refused.value.reason.endswith("the rows are not in time order; sort them by their time")
    # a clock set back by 30.5 min into a record's own span still is one (sorted, its samples
    # fall between the earlier ones)
    record(tmp_path / "lab.csv", [60 * i for i in range(60)] + [60 * i + 30 for i in range(29, 45)])
    with pytest.raises(ContractError, match="would mix its stretches"):
        read_dataset(tmp_path / "lab.csv")


def test_a_parquet_time_with_its_zone_is_named_on_that_zone_s_clock(tmp_path):
    # audit106: a lab's Parquet copy, its timestamps on Europe/Berlin's clock across the change to
    # summer time, a row written twice at 11:00+02:00; the refusal named "10:00:00+01:00" (the
    # first row's offset kept), a time that clock never showed
    import pyarrow as pa
    import pyarrow.parquet as pq

    stamps = pd.date_range("2027-03-28 01:00", periods=12, freq="30min", tz="Europe/Berlin").tolist()
    stamps = stamps[:8] + stamps[7:11]                       # the 8th (05:30+02:00) twice
    table = pa.table({"time": pa.array(stamps, pa.timestamp("ns", "Europe/Berlin")),
                      "T_spindle": [20.0 + 0.1 * i for i in range(12)],
                      "E_X": [0.2 * i for i in range(12)]})
    pq.write_table(table, tmp_path / "lab.parquet")
    with pytest.raises(ContractError) as refused:
        read_dataset(tmp_path / "lab.parquet")
    assert refused.value.row == 9
    assert refused.value.reason.startswith(
        "duplicate time 2027-03-28T05:30:00+02:00 = 2027-03-28 03:30:00 UTC (same as row 8)")
