"""A logger that wrote no row for a while inside a record (an IoT gateway's outage of 7 and 25
minutes on a wire EDM, newmachine59): said with the longest stretch's row, not refused; a model
whose lags count samples reads each stretch as one period."""

from __future__ import annotations

from test_sample_rate56 import CHANGED, PAUSED, record, said

STEADY = [60.0 * i for i in range(200)]
OUTAGES = [t for t in STEADY if not 3000 <= t < 3420 and not 7200 <= t < 8700]   # 7 and 25 rows
# (the longest ends at data row 114: 50 rows before 3000 s, 63 from 3420 s to 7140 s)
SAID = "stretch(es) without rows"


def test_rows_not_logged_are_said_with_the_longest_stretch_and_its_row(tmp_path, caplog):
    path = record(tmp_path / "edm.csv", OUTAGES)
    text = said(caplog, path)
    assert f"{path}, column 'time': 2 {SAID} (steps of 8, 26 sample periods of 60 s; the longest " \
           "26 min, before line 115 (data row 114))" in text, text
    assert "data.resample_s=60 fills them" in text


def test_a_steady_record_a_rate_change_a_pause_and_a_grid_are_not_said_as_rows_missing(
        tmp_path, caplog):
    assert SAID not in said(caplog, record(tmp_path / "steady.csv", STEADY))
    assert SAID not in said(caplog, record(tmp_path / "changed.csv", CHANGED))   # said as a rate
    assert SAID not in said(caplog, record(tmp_path / "paused.csv", PAUSED))     # a pause of hours
    assert SAID not in said(caplog, record(tmp_path / "grid.csv", OUTAGES), {"resample_s": 60})
