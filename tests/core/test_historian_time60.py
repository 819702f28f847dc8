"""A historian's long file reads its time column as a wide file's is (histtime60): the same
parser (:func:`thermocomp.core.io.tables.time_of_text`), so every form a wide file's time takes
a long file's takes too.  Before histtime60 the historian had rules of its own: epoch
milliseconds and Excel's serial days were read as seconds whatever ``data.units`` said (the grid
of ``data.resample_s`` then 1000 or 86400 times too fine or too coarse), and a date with slashes
was refused even where its day, past 12, says the order."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from test_historian60 import AIR, BEARING, CFG, PROBE, held, samples, write
from thermocomp.core.io import ContractError, read_dataset

NAMES = ((PROBE, "E_MC07.Probe.Z"), (BEARING, "T_MC07.Spindle.Bearing.Temp"),
         (AIR, "T_MC07.Hall.Air.Temp"))


def _stamps(frame: pd.DataFrame) -> pd.Series:
    return pd.to_datetime(frame["Timestamp"], format="%d.%m.%Y %H:%M:%S")


def _read_as_written(frame: pd.DataFrame, stamps, path, cfg, first=None) -> None:
    """The long file with its time column written as ``stamps`` reads onto the 10 s grid, each
    tag's value its last sample's (the grid's seconds since the ``first`` stamp; None: the
    time is a number, the seconds since its first)."""
    write(frame.assign(Timestamp=stamps), path)
    ds, report = read_dataset(path, cfg)
    grids = []
    for cid in ds.ids():
        campaign = ds.campaigns[cid]
        origin = report["campaigns"][cid].get("time_origin")
        since = 0.0 if first is None else (pd.Timestamp(origin).tz_localize(None)
                                           - first).total_seconds()
        grid = since + campaign["time"].to_numpy()
        grids.append(grid)
        for tag, name in NAMES:
            got, expected = campaign[name].to_numpy(), held(frame, tag, grid)
            assert np.allclose(got - got[0], expected - expected[0], atol=1e-9), (cid, name)
    grid = np.concatenate(grids)
    assert np.allclose(np.diff(grid), 10.0)
    last = (_stamps(frame).max() - _stamps(frame).min()).total_seconds()
    assert grid[0] == 7.0 and len(grid) == int((last - 7) // 10) + 1


def test_epoch_milliseconds_are_read_in_the_unit_data_units_gives(tmp_path):
    frame = samples()
    ms = ((_stamps(frame) - pd.Timestamp("1970-01-01")).dt.total_seconds() * 1000).astype("int64")
    _read_as_written(frame, ms, tmp_path / "pi.csv", {**CFG, "units": {"Timestamp": "ms"}})


def test_excel_serial_days_are_read_as_days(tmp_path):
    frame = samples()
    days = (_stamps(frame) - pd.Timestamp("1899-12-30")) / pd.Timedelta(days=1)
    _read_as_written(frame, days, tmp_path / "pi.csv", {**CFG, "units": {"Timestamp": "d"}})


def test_a_date_with_slashes_whose_day_says_the_order_is_read(tmp_path):
    frame = samples()      # (the 15th: past 12, the day; a wide file's is read so)
    later = _stamps(frame) + pd.Timedelta(days=13)
    slashed = later.dt.strftime("%d/%m/%Y %H:%M:%S")
    assert slashed.iloc[0].startswith("15/11/2026")
    _read_as_written(frame, slashed, tmp_path / "pi.csv", CFG, first=later.min())


def test_a_time_of_day_without_its_date_is_refused_with_a_long_files_way(tmp_path):
    """The wide reader's advice (a date column beside it, data.sample_period_s) does not hold
    for a long file, whose samples need their own times: the refusal says what does (lead60)."""
    frame = samples()
    write(frame.assign(Timestamp=_stamps(frame).dt.strftime("%H:%M:%S")), tmp_path / "pi.csv")
    with pytest.raises(ContractError) as caught:
        read_dataset(tmp_path / "pi.csv", CFG)
    text = str(caught.value)
    assert "column 'Timestamp', data row 1" in text and "historian's long file" in text
    assert "data.time=elapsed" in text and "sample_period_s" not in text
