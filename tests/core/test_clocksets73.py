"""(deploy73) A server's clock set back while the machine ran, told by ``connect``
(``clock_set`` in its connect.json): the machine's log holds the step back in its timestamps,
which the reader refused as a time going back; with ``data.clock_sets`` it is undone, the times
continuous as ``connect`` streamed them."""

from __future__ import annotations

import json
from datetime import datetime, timedelta, timezone

import numpy as np
import pandas as pd
import pytest

from thermocomp.core.io import ContractError, read_dataset

EPOCH = datetime(2026, 3, 2, 6, 0, tzinfo=timezone.utc)
ROWS, SET_AT, BACK = 40, 20, -3600.0


def _log(root, sets_at=(SET_AT,)):
    """One campaign a minute apart, the server's clock set back an hour at row SET_AT (the
    machine ran on): its timestamps and connect.json's event of it."""
    root.mkdir()
    seconds = np.arange(ROWS) * 60.0 + BACK * (np.arange(ROWS) >= SET_AT)
    stamps = [(EPOCH + timedelta(seconds=float(s))).isoformat() for s in seconds]
    t = np.arange(ROWS) * 60.0
    pd.DataFrame({"time": stamps, "T_a": 20 + t / 600, "E_X": t / 300}).to_csv(root / "P1.csv", index=False)
    pd.DataFrame([("P1", "P1.csv", "train")], columns=["campaign", "file", "split"]).to_csv(
        root / "campaigns.csv", index=False)
    events = [{"event": "clock_set", "sample": k - 1, "step_s": BACK, "from_utc": stamps[k - 1],
               "at_utc": stamps[k]} for k in sets_at]
    (root / "connect.json").write_text(json.dumps({"events": [{"event": "connected"}, *events]}))
    return root


def test_a_clock_set_back_told_by_connect_is_undone_in_the_log(tmp_path):
    root = _log(tmp_path / "log")
    with pytest.raises(ContractError, match="time decreases") as refused:
        read_dataset(root)
    assert refused.value.row == SET_AT + 1
    ds, report = read_dataset(root, {"clock_sets": str(root / "connect.json")})
    np.testing.assert_array_equal(ds.campaigns["P1"]["time"].to_numpy(), np.arange(ROWS) * 60.0)
    assert report["campaigns"]["P1"]["clock_sets_undone"] == 1


def test_clock_sets_that_are_no_connect_json_are_refused_naming_the_file(tmp_path):
    root = _log(tmp_path / "log")
    (root / "other.json").write_text(json.dumps({"events": [{"event": "clock_set", "step_s": 1}]}))
    for name in ("other.json", "missing.json"):
        with pytest.raises(ContractError, match="data.clock_sets") as refused:
            read_dataset(root, {"clock_sets": str(root / name)})
        assert name in str(refused.value)


def test_a_clock_set_not_found_in_the_log_is_said(tmp_path, caplog):
    """(lead73) A set whose instants no row of the log holds (a log sampled at another rate,
    another clock) is left as the log has it and said (before: without a word)."""
    root = _log(tmp_path / "log")
    events = json.loads((root / "connect.json").read_text())
    events["events"].append({**events["events"][-1], "from_utc": "2026-03-03T06:00:00+00:00",
                             "at_utc": "2026-03-03T06:01:00+00:00"})
    (root / "connect.json").write_text(json.dumps(events))
    with caplog.at_level("WARNING"):
        _, report = read_dataset(root, {"clock_sets": str(root / "connect.json")})
    assert report["clock_sets_undone"] == 1
    said = [r.getMessage() for r in caplog.records if "data.clock_sets" in r.getMessage()]
    assert len(said) == 1 and "1 of the 2 clock set(s) found" in said[0], said
