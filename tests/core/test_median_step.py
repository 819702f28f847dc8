"""The sample period of a time column, one definition (:func:`thermocomp.core.timerule.median_step`):
the median of the finite positive steps within each campaign / segment."""

from __future__ import annotations

import numpy as np
import pytest

from thermocomp.base.log import logger
from thermocomp.core.io.timestamps import said_if_not_seconds
from thermocomp.core.timerule import median_step


def test_only_positive_finite_steps_within_a_campaign_count():
    # a run restarting at 0, a repeated time and a missing one make no step
    time = [0, 60, 120, 0, 60, 60, np.nan, 180, 240]
    assert median_step(time) == 60
    # without them, the 100 s steps would be the median
    assert median_step([0, 100, 200, 300, 360, 420]) == 100


def test_no_step_joins_two_campaigns_as_a_list_of_columns_or_by_groups():
    a, b = np.arange(5) * 60.0, 1000 + np.arange(3) * 300.0      # b starts 760 s after a ends
    groups = ["a"] * 5 + ["b"] * 3
    pooled = median_step(np.r_[a, b], groups)
    assert pooled == median_step([a, b]) == 60      # 4 steps of 60 s, 2 of 300 s, no 760 s
    assert median_step(np.r_[a, b, b], groups + ["c"] * 3) == pytest.approx(180)
    # a segment is a run of rows with the same label: 'a' again after 'b' is a new one
    assert median_step([0, 1, 50, 51, 100, 101], ["a", "a", "b", "b", "a", "a"]) == 1
    with pytest.raises(ValueError, match="groups has 2 rows, time 3"):
        median_step([0, 1, 2], ["a", "a"])


@pytest.mark.parametrize("time", [[], [5.0], [3.0, 3.0], [10.0, 5.0, 0.0], [np.nan, 1.0],
                                  [[0.0], [7.0]]])
def test_without_a_positive_step_there_is_no_period(time):
    assert median_step(time) is None


def test_a_time_in_ms_repeating_its_rows_is_still_said(caplog):
    # before: the median of every step, 0 when most rows repeat the previous time, hid a time
    # 1000 s (ms?) apart; the steps that advance are what the period is
    logger.addHandler(caplog.handler)
    try:
        said_if_not_seconds(np.repeat(np.arange(20) * 1000.0, 3), "f.csv", "t")
    finally:
        logger.removeHandler(caplog.handler)
    assert "samples 1000 s apart, in whole thousands: milliseconds?" in caplog.text


def test_a_clock_written_with_few_decimals_gives_its_period_not_one_rounded_step():
    # elapsed hours to four places (a lab's export, stranger64): a 60 s logger's steps are
    # 59.76 and 60.12 s, the median 60.12 (0.2 % long); the mean of the steps near it is 60
    hours = np.round(np.arange(2000) / 60.0, 4)
    steps = set(np.round(np.diff(hours * 3600.0), 2))
    assert steps == {59.76, 60.12}
    assert median_step(hours * 3600.0) == pytest.approx(60.0, abs=0.01)
    # a jittering PC clock (whole milliseconds) likewise: its mean step, not one rounded step
    rng = np.random.default_rng(3)
    jittered = np.round(np.arange(500) * 2.0 + rng.uniform(-0.004, 0.004, 500), 3)
    assert median_step(jittered) == pytest.approx(2.0, abs=5e-4)


@pytest.mark.parametrize("start", [0.0, 1.7e9])
def test_a_float_grid_keeps_its_median_bit_for_bit(start):
    # the rounding of a grid's float times (k * 0.1 s; epoch seconds) is no clock's resolution
    for period in (0.1, 60.0):
        time = start + np.arange(5000) * period
        steps = np.diff(time)
        assert median_step(time) == float(np.median(steps[steps > 0]))
