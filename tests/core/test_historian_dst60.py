"""A historian's long file stamped on a local clock without an offset, read with
``data.timezone``: the hour repeated when daylight saving time ends is told apart by each tag's
own order (a tag logs through it in order; the tags' rows interleave), as a wide file's rows
tell it; the record is one 3-hour grid, not an hour of stamps read twice (before: the second
pass's samples sorted among the first's, a tag holding two values at one stamp refused)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from test_historian60 import AIR, PROBE, write
from thermocomp.core.io import ContractError, read_dataset

ZONE = "Europe/Berlin"
UTC_START = pd.Timestamp("2026-10-24T23:30:00Z")     # 01:30 summer time; clocks go back at 03:00


def across_the_repeated_hour() -> pd.DataFrame:
    """The probe every 10 min, the air every 30 min (offset 5 min), for 3 h on UTC's clock,
    written as Berlin's wall clock without an offset, sorted by the instant."""
    rows = [(m, PROBE, round(0.1 * m, 1)) for m in range(0, 180, 10)]
    rows += [(m, AIR, round(20 + 0.01 * m, 2)) for m in range(5, 180, 30)]
    frame = pd.DataFrame(rows, columns=["m", "TagName", "Value"]).sort_values("m", kind="stable")
    instants = UTC_START + pd.to_timedelta(frame.pop("m"), unit="min")
    frame.insert(0, "Timestamp", instants.dt.tz_convert(ZONE).dt.strftime("%Y-%m-%d %H:%M:%S"))
    frame["Quality"] = "Good"
    return frame.reset_index(drop=True)


CFG = {"roles": {"error": ["MC07.Probe.Z"]}, "resample_s": 600, "max_gap_samples": 0,
       "timezone": ZONE}


def test_the_repeated_hour_is_told_apart_by_each_tags_order(tmp_path):
    frame = across_the_repeated_hour()
    assert frame["Timestamp"].duplicated().any()          # the clock shows 02:00-02:59 twice
    write(frame, tmp_path / "pi.csv")
    ds, report = read_dataset(tmp_path / "pi.csv", CFG)
    (cid,) = ds.ids()
    campaign = ds.campaigns[cid]
    origin = pd.Timestamp(report["campaigns"][cid]["time_origin"])
    assert origin == UTC_START + pd.Timedelta(minutes=5)   # the air's first sample
    assert np.allclose(np.diff(campaign["time"].to_numpy()), 600.0)
    assert len(campaign) == 17                 # +5 .. +165 min (the last stamp +170), one grid
    # the probe's value is 0.1 x its minute on the UTC clock, held from its last sample
    minutes = 5 + campaign["time"].to_numpy() / 60
    assert np.allclose(campaign["E_MC07.Probe.Z"].to_numpy(), 0.1 * (minutes // 10 * 10))


def test_a_tag_that_does_not_run_through_the_repeated_hour_in_order_is_refused(tmp_path):
    frame = across_the_repeated_hour()
    probe = frame.index[frame["TagName"] == PROBE]
    frame.loc[probe, "Timestamp"] = frame.loc[probe[::-1], "Timestamp"].to_numpy()  # backwards
    write(frame, tmp_path / "pi.csv")
    with pytest.raises(ContractError, match=r"column 'Timestamp', data row \d+: .*data.timezone"):
        read_dataset(tmp_path / "pi.csv", CFG)
