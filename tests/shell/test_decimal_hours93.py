"""A lab's time of day in decimal hours, and rows missing from a time of day without its date
(data93).

A numeric column under a time-of-day header (``Hora`` 21.5, 21.5833 ...) was read as seconds:
``init`` showed a 0.083 s sample period, and past midnight the record was refused at its row
("time decreases").  Read as seconds since midnight such a record lies within 24 s of midnight,
no thermal test: the reader refuses it naming the unit's key, and ``init`` writes
``data.units={Hora: h}`` with ``data.time=of_day`` where no fraction of a day (Excel's time,
all values within [0, 1]) is as likely.  A gap of fewer than 100 sample periods in a time of
day without its date was said as a logger's outage only: it reads as well a day longer."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest
import yaml

from test_data88b import START, _clock, _record
from test_lab_clock92 import _served_clock, _warned
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.core.io.stdin import seconds_and_origin
from thermocomp.shell.cli import main

KEYS = ("roles", "time", "units", "delimiter", "decimal")


def _hours(rows: pd.DataFrame, start: pd.Timestamp = START) -> list[str]:
    """``rows``' time as the wall clock's decimal hours from ``start`` (a decimal comma)."""
    stamps = [start + pd.Timedelta(seconds=float(t)) for t in rows["time"]]
    return [repr((s - s.normalize()).total_seconds() / 3600).replace(".", ",") for s in stamps]


def _raw_hours(rows: pd.DataFrame, start: pd.Timestamp = START, header: str = "Hora") -> str:
    """``rows`` as a lab's PC writes them, its time in decimal hours under ``header``."""
    head = [header, "T a [°C]", "T b [°C]", "T c [°C]", "dX [µm]"]
    body = [[h, *(repr(float(v)).replace(".", ",") for v in (r.T_a, r.T_b, r.T_c, r.E_X))]
            for h, r in zip(_hours(rows, start), rows.itertuples(index=False))]
    return "\ufeff" + "".join(";".join(cells) + "\r\n" for cells in [head, *body])


def _config(out) -> dict:
    return yaml.safe_load(next((out / "conf" / "data").glob("*.yaml")).read_text())


def test_init_reads_decimal_hours_past_midnight_and_writes_the_unit(tmp_path, capsys):
    # before: read as seconds, refused at midnight ("time decreases from 23.9 s")
    rows = _record(931)
    (tmp_path / "lab.csv").write_bytes(_raw_hours(rows).encode("utf-8"))
    assert main(["init", str(tmp_path / "lab.csv"), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "decimal hours" in said and "data.units={'Hora': h}" in said
    config = _config(tmp_path / "init")
    assert config["units"] == {"Hora": "h"} and config["time"] == "of_day"
    ds, _ = read_dataset(tmp_path / "lab.csv", {k: config[k] for k in KEYS})
    time = ds.campaigns["lab"]["time"]
    np.testing.assert_allclose(time - time.iloc[0], rows["time"], atol=1e-6)
    assert "sample period: 300 s" in said


def test_decimal_hours_without_their_unit_are_refused_naming_it(tmp_path):
    # before: accepted as seconds, a record of 1.9 s sampled every 0.083 s
    rows = _record(932).iloc[:20]                           # 21:30 .. 23:05, within a day
    (tmp_path / "day.csv").write_bytes(_raw_hours(rows).encode("utf-8"))
    with pytest.raises(ContractError) as caught:
        read_dataset(tmp_path / "day.csv", {"roles": {"error": ["dX"]}, "delimiter": ";",
                                             "decimal": ","})
    assert caught.value.row == 1 and caught.value.column == "time"
    said = str(caught.value)
    assert "day.csv" in said and "data.units={'Hora': h}" in said and "data.time=of_day" in said
    assert "{'Hora': d}" not in said                         # (21.5: no fraction of a day)


def test_hours_within_the_first_hour_may_be_a_days_fraction_refused_naming_both(tmp_path, capsys):
    # before: accepted as seconds.  0.0 .. 0.92: the hour after midnight in hours, or a whole
    # day as Excel's fraction of it: init guesses neither
    rows = _record(933).iloc[:12]
    (tmp_path / "night.csv").write_bytes(
        _raw_hours(rows, pd.Timestamp("2027-03-06 00:00:00")).encode("utf-8"))
    assert main(["init", str(tmp_path / "night.csv"), f"out={tmp_path / 'init'}"]) == 2
    said = capsys.readouterr().err
    assert "night.csv" in said and "data row 1" in said
    assert "data.units={'Hora': h}" in said and "data.units={'Hora': d}" in said


def test_an_hour_past_24_among_decimal_hours_is_refused_at_its_row(tmp_path, capsys):
    rows = _record(934)
    text = _raw_hours(rows).split("\r\n")
    text[20] = "25,25" + text[20][text[20].index(";"):]      # data row 20
    (tmp_path / "bad.csv").write_bytes("\r\n".join(text).encode("utf-8"))
    assert main(["init", str(tmp_path / "bad.csv"), f"out={tmp_path / 'init'}"]) == 2
    said = capsys.readouterr().err
    assert "bad.csv" in said and "data row 20" in said and "25.25 h is no hour of a day" in said


def test_seconds_of_the_day_under_such_a_header_read_as_before(tmp_path):
    # a guard: seconds since midnight under 'Hora' (77400 ...) are no hours
    rows = _record(935)
    frame = rows.assign(time=[(START + pd.Timedelta(seconds=float(t)) - START.normalize())
                              .total_seconds() % 86400 for t in rows["time"]])
    frame.rename(columns={"time": "Hora", "E_X": "dX [µm]"}).to_csv(tmp_path / "s.csv",
                                                                    index=False)
    ds, _ = read_dataset(tmp_path / "s.csv", {"roles": {"error": ["dX"]}})
    time = ds.campaigns["s"]["time"]
    np.testing.assert_allclose(time - time.iloc[0], rows["time"])


def test_rows_missing_from_a_dateless_clock_are_said_to_hide_a_day_maybe(tmp_path, caplog):
    # before: said as a logger's outage only; a day and 30 min read as 30 min
    rows = _record(936).drop(index=[10, 11, 12, 13, 14]).reset_index(drop=True)
    _clock(rows).rename(columns={"Time": "Uhrzeit"}).to_csv(tmp_path / "gap.csv", index=False)
    with caplog.at_level(logging.WARNING):
        read_dataset(tmp_path / "gap.csv", {"roles": {"error": ["E_X"]}})
    [said] = [r.getMessage() for r in caplog.records if "without rows" in r.getMessage()]
    assert "data row 11" in said and "as well a day longer (24.5 h or more" in said
    # the same rows with their date: a gap, no day to hide
    caplog.clear()
    stamped = rows.assign(time=[(START + pd.Timedelta(seconds=float(t))).isoformat()
                                for t in rows["time"]])
    stamped.to_csv(tmp_path / "dated.csv", index=False)
    with caplog.at_level(logging.WARNING):
        read_dataset(tmp_path / "dated.csv", {})
    [said] = [r.getMessage() for r in caplog.records if "without rows" in r.getMessage()]
    assert "a day longer" not in said


def test_stdin_under_of_day_says_rows_missing_may_hide_a_day(caplog):
    seconds = pd.Series(77400.0 + 300.0 * np.r_[0:10, 16:30])      # 5 rows missing
    with caplog.at_level(logging.WARNING):
        seconds_and_origin(seconds, "of_day")
    [said] = [r.getMessage() for r in caplog.records if "without rows" in r.getMessage()]
    assert "<stdin>" in said and "data row 11" in said and "a day longer" in said


def test_a_served_session_warns_of_a_short_pause_a_day_could_hide(caplog):
    # before: only a pause of 100 sample periods or more (10 h) was said; 30 min (6) was not
    [said] = _warned(_served_clock(1800.0), caplog)
    assert "data row 1 of the block" in said and "since the session's last block" in said
    assert not _warned(_served_clock(0.0), caplog)
