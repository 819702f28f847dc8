"""``data.runs_at_pauses`` on a time of seconds since midnight (stop 90).

Before: the pauses were looked for in the raw seconds of the day, so a run after a pause across
midnight (79140 s, then 3600 s: back, not a long step forward) was joined to the run before it,
read as one campaign across a 3 h pause, and warned of as "a day lost".
"""
from __future__ import annotations

import logging

import numpy as np
import pandas as pd

from thermocomp.core.io import read_dataset

ROWS, PERIOD_S, DAY_S = 120, 60, 86400


def _runs(path, starts_h):
    """Runs of ``ROWS`` rows each starting at ``starts_h`` hours, under ``Seconds of day``."""
    rng = np.random.default_rng(90)
    frames = []
    for start in starts_h:
        t = start * 3600 + np.arange(ROWS) * PERIOD_S
        temp = 20 + np.cumsum(rng.normal(0, 0.05, (ROWS, 3)), axis=0)
        frames.append(pd.DataFrame({"Seconds of day": t % DAY_S, "T_a": temp[:, 0],
                                    "T_b": temp[:, 1], "T_c": temp[:, 2],
                                    "E_X": 2 * temp[:, 0] - temp[:, 1]}))
    pd.concat(frames, ignore_index=True).to_csv(path, index=False)
    return path


def test_runs_at_pauses_splits_seconds_of_day_at_a_pause_across_midnight(tmp_path, caplog):
    path = _runs(tmp_path / "week.csv", [20, 25, 34])        # 20:00, 01:00 the next day, 10:00
    with caplog.at_level(logging.WARNING):
        ds, _ = read_dataset(path, {"runs_at_pauses": True})
    assert list(ds.campaigns) == ["week_1", "week_2", "week_3"]
    for campaign in ds.campaigns.values():
        time = campaign["time"].to_numpy()
        assert len(time) == ROWS and np.allclose(np.diff(time), PERIOD_S)
    # the pauses it was told to split at are no "day lost"
    assert not [r for r in caplog.records if "a day lost" in r.getMessage()]


def test_without_the_key_the_pauses_are_still_warned_of(tmp_path, caplog):
    path = _runs(tmp_path / "week.csv", [20, 25, 34])
    with caplog.at_level(logging.WARNING):
        ds, _ = read_dataset(path)
    assert list(ds.campaigns) == ["week"]
    [said] = [r.getMessage() for r in caplog.records if "a day lost" in r.getMessage()]
    assert "2 such pauses" in said


def test_a_run_passing_midnight_stays_one_run_between_its_pauses(tmp_path):
    # (data90) 16:00; 23:00 to 01:00 the next day, midnight inside the run; 09:00
    ds, report = read_dataset(_runs(tmp_path / "week.csv", [16, 23, 33]), {"runs_at_pauses": True})
    assert list(ds.campaigns) == ["week_1", "week_2", "week_3"]
    for campaign in ds.campaigns.values():
        assert np.allclose(np.diff(campaign["time"].to_numpy()), PERIOD_S)
    assert report["campaigns"]["week_2"]["time"] == "seconds of day"
