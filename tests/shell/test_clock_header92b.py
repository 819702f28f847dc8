"""A lab's time-of-day column found by its header, in the languages labs write (data92b).

A dateless ``h:mm:ss`` under ``Uhrzeit`` (``Heure``, ``Hora``, ``Ora``, ``時刻``, ``time of
day``), no date column beside it, was no time column: ``init`` refused it as a time of day
without its date, and a stranger needed two keys, ``data.time=of_day data.roles.time=Uhrzeit``.
Its header now says what the key says: read as ``data.time=of_day``, ``init`` writing the key."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import yaml

from test_data88b import START, _record, _stamps
from test_lab_clock92 import _raw_clock
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.shell.cli import main


def test_init_reads_a_time_of_day_header_alone_as_of_day_and_writes_the_key(tmp_path, capsys):
    rows = _record(923)
    (tmp_path / "lab.csv").write_bytes(_raw_clock(rows).encode("utf-8"))
    # before: refused, "a time of day without its date", naming the two keys
    assert main(["init", str(tmp_path / "lab.csv"), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "'Uhrzeit' h:mm:ss" in said and "data.time='of_day'" in said
    config = yaml.safe_load(next((tmp_path / "init/conf/data").glob("*.yaml")).read_text())
    assert config["time"] == "of_day"
    ds, _ = read_dataset(tmp_path / "lab.csv", {k: config[k] for k in ("roles", "time",
                                                                        "delimiter", "decimal")})
    typed, _ = read_dataset(tmp_path / "lab.csv", {"roles": {"time": "Uhrzeit", "error": ["dX"]},
                                                    "time": "of_day", "delimiter": ";",
                                                    "decimal": ","})
    got, want = ds.campaigns["lab"], typed.campaigns["lab"]
    pd.testing.assert_frame_equal(got, want)       # the two keys typed, as data92 read it
    np.testing.assert_allclose(got["time"] - got["time"].iloc[0], rows["time"])   # past midnight


@pytest.mark.parametrize("header", ["Heure", "Hora", "Ora", "時刻", "time of day"])
def test_a_time_of_day_header_within_a_day_reads_its_rows_by_the_clock(tmp_path, header):
    # a clock that never passes midnight: refused under 'time' (a time of day without its
    # date); under these headers no time column at all (their rows had no role)
    rows = _record(924).iloc[:20]                          # 21:30 .. 23:05
    frame = rows.assign(time=_stamps(rows["time"], "%H:%M:%S")).rename(
        columns={"time": header, "E_X": "dX [µm]"})
    frame.to_csv(tmp_path / "day.csv", index=False)
    ds, _ = read_dataset(tmp_path / "day.csv", {"roles": {"error": ["dX"]}})
    time = ds.campaigns["day"]["time"]
    np.testing.assert_allclose(time - time.iloc[0], rows["time"])


def test_a_value_no_time_of_day_under_such_a_header_is_refused_with_its_row(tmp_path):
    rows = _record(925)
    frame = rows.assign(time=_stamps(rows["time"], "%H:%M:%S")).rename(
        columns={"time": "Uhrzeit", "E_X": "dX [µm]"})
    frame.loc[19, "Uhrzeit"] = "25:10:00"                   # (no hour of a day: an elapsed time?)
    frame.to_csv(tmp_path / "bad.csv", index=False)
    with pytest.raises(ContractError) as caught:
        read_dataset(tmp_path / "bad.csv", {"roles": {"error": ["dX"]}})
    assert caught.value.row == 20 and caught.value.column == "time"
    assert "'25:10:00' is no time of day" in str(caught.value) and "bad.csv" in str(caught.value)


def test_a_date_beside_it_still_makes_the_pair_one_timestamp(tmp_path, capsys):
    # a guard: the date column beside the time of day is the pair's, as before (no of_day key)
    rows = _record(926)
    stamps = [START + pd.Timedelta(seconds=float(t)) for t in rows["time"]]
    frame = rows.drop(columns="time").rename(columns={"E_X": "dX [µm]"})
    frame.insert(0, "Uhrzeit", [s.strftime("%H:%M:%S") for s in stamps])
    frame.insert(0, "Datum", [s.strftime("%d.%m.%Y") for s in stamps])
    frame.to_csv(tmp_path / "pair.csv", index=False, sep=";")
    assert main(["init", str(tmp_path / "pair.csv"), f"out={tmp_path / 'init'}"]) == 0
    assert "time: 'Datum' + 'Uhrzeit', timestamps from 2027-03-05T21:30:00" in capsys.readouterr().out
    config = yaml.safe_load(next((tmp_path / "init/conf/data").glob("*.yaml")).read_text())
    assert "time" not in config and config["roles"]["time"] == ["Datum", "Uhrzeit"]
