"""(deploy74) ``data.clock_sets`` where ``replay``'s reader did not find a set: a log thinned or
rotated between the set's two sample instants (the set found by the rows around it, not rows at
them), and the rows ``monitor monitor.input=-`` and a restarted ``connect`` (``connect.warm``)
stream, which read no clock set before (their time kept the step)."""

from __future__ import annotations

import json
from datetime import datetime, timedelta, timezone

import numpy as np
import pandas as pd
import pytest
from asyncua import ua

from thermocomp.core.io import ReadOptions, read_dataset
from thermocomp.core.io.stdin import TIME_ORIGIN, read_stream, stream_campaigns

EPOCH = datetime(2026, 3, 2, 6, 0, tzinfo=timezone.utc)
ROWS, SET_AT, HOUR = 40, 20, 3600.0


def _stamps(step: float, rows=range(ROWS)) -> list[str]:
    """A minute apart, the server's clock set by ``step`` before row SET_AT (the machine ran on)."""
    return [(EPOCH + timedelta(seconds=60.0 * k + step * (k >= SET_AT))).isoformat() for k in rows]


def _sets(path, step: float):
    """connect.json telling the set at SET_AT (the client's samples a minute apart)."""
    stamps = _stamps(step)
    event = {"event": "clock_set", "sample": SET_AT - 1, "step_s": step,
             "from_utc": stamps[SET_AT - 1], "at_utc": stamps[SET_AT]}
    path.write_text(json.dumps({"events": [{"event": "connected"}, event]}))
    return path


def _record(root, files: dict, step: float):
    """A record of the log's rows ``files`` ({campaign: rows}), each file continuing the last."""
    root.mkdir()
    stamps = _stamps(step)
    for cid, rows in files.items():
        pd.DataFrame({"time": [stamps[k] for k in rows], "T_a": [20 + k / 10 for k in rows],
                      "E_X": [k / 5 for k in rows]}).to_csv(root / f"{cid}.csv", index=False)
    ids = list(files)
    pd.DataFrame({"campaign": ids, "file": [f"{c}.csv" for c in ids], "split": "train",
                  "continues": [""] + ids[:-1]}).to_csv(root / "campaigns.csv", index=False)
    return root, _sets(root / "connect.json", step)


@pytest.mark.parametrize("step", [-HOUR, HOUR])
def test_a_set_is_found_in_a_log_thinned_between_its_two_samples(tmp_path, step):
    """Rows SET_AT-2 .. SET_AT+1 not logged (a log thinned to every 5th row, a logger down): no
    row at the set's instants.  Before, the set back was refused as a time going back and the
    set forward read as a pause of an hour; now undone, the times as connect streamed them."""
    rows = [k for k in range(ROWS) if not SET_AT - 2 <= k <= SET_AT + 1]
    root, sets = _record(tmp_path / "log", {"P1": rows}, step)
    ds, report = read_dataset(root, {"clock_sets": str(sets)})
    np.testing.assert_array_equal(ds.campaigns["P1"]["time"].to_numpy(), np.array(rows) * 60.0)
    assert report["clock_sets_undone"] == 1


def test_a_log_rotated_at_the_set_starts_its_next_file_on_connects_clock(tmp_path, caplog):
    """The log rotated at the set forward: P2's first row is the first after it, no row of P2
    follows one at the set's from_utc.  Before, P2 started an hour late (a pause between the
    two files it continues); now its start moves back by the step.  A set that no file shows
    is named in the warning."""
    root, sets = _record(tmp_path / "log", {"P1": range(SET_AT), "P2": range(SET_AT, ROWS)}, HOUR)
    told = json.loads(sets.read_text())
    told["events"].append({**told["events"][-1], "from_utc": "2026-03-01T06:00:00+00:00",
                           "at_utc": "2026-03-01T06:30:00+00:00"})
    sets.write_text(json.dumps(told))
    with caplog.at_level("WARNING"):
        _, report = read_dataset(root, {"clock_sets": str(sets)})
    starts = {c: pd.Timestamp(r["time_origin"]) for c, r in report["campaigns"].items()}
    assert (starts["P2"] - starts["P1"]).total_seconds() == SET_AT * 60.0
    assert report["clock_sets_undone"] == 1
    said = [r.getMessage() for r in caplog.records if "data.clock_sets" in r.getMessage()]
    assert len(said) == 1 and "not found: 2026-03-01T06:30:00+00:00 (+3600 s" in said[0], said


def _csv(step: float, rows) -> str:
    stamps = _stamps(step)
    return "time,T_a\n" + "".join(f"{stamps[k]},{20 + k / 10}\n" for k in rows)


@pytest.mark.parametrize("step", [-HOUR, HOUR])
def test_the_rows_streamed_on_stdin_have_the_set_undone(tmp_path, step):
    """``monitor monitor.input=-`` of the machine's log with ``data.clock_sets``: the stream's
    time as connect streamed it (before: the step kept, an hour's pause or a time going back)."""
    opts = ReadOptions.from_cfg({"clock_sets": str(_sets(tmp_path / "connect.json", step))})
    streamed, _ = stream_campaigns(_csv(step, range(ROWS)), ["T_a"], opts)
    np.testing.assert_array_equal(streamed["stdin"]["time"].to_numpy(), np.arange(ROWS) * 60.0)


def test_a_stream_that_starts_after_the_set_is_placed_on_connects_clock(tmp_path):
    """The rows on stdin continue a campaign of the record, the set forward between its last row
    and stdin's first: the stream's first instant (where it is placed on the campaign's clock)
    moves back by the step; before, an hour late, said as an hour of rows missing."""
    opts = ReadOptions.from_cfg({"clock_sets": str(_sets(tmp_path / "connect.json", HOUR))})
    streamed, _ = stream_campaigns(_csv(HOUR, range(SET_AT, ROWS)), ["T_a"], opts)
    assert streamed["stdin"].attrs[TIME_ORIGIN] == pd.Timestamp(EPOCH) + timedelta(minutes=SET_AT)


@pytest.mark.parametrize("logged", [ROWS - 10, SET_AT - 5])
def test_a_restarted_connect_places_its_sample_after_a_set_told_before(tmp_path, monkeypatch, logged):
    """``connect.warm`` (the log up to row ``logged``), the server's clock set forward an hour
    at row SET_AT (in the log, or after its last row), the client restarted at row 35: the
    sample's time is 35 minutes into the program, as the log read whole with the set undone;
    before, an hour more (the set read as a pause)."""
    from conftest import offline_connection
    from thermocomp.apps.machine import client
    from thermocomp.apps.machine.client import _Plan

    opts = ReadOptions.from_cfg({"clock_sets": str(_sets(tmp_path / "connect.json", HOUR))})
    warm, _ = read_stream(_csv(HOUR, range(logged)), ["T_a"], opts)
    monkeypatch.setattr(client, "own_clock", lambda: 0.0, raising=False)
    conn = offline_connection(clock="server", period_s=60.0, warm=warm)
    plan = _Plan(inputs=[object(), None], labels=["T_a", "time"], status={}, clock=object(),
                 offsets=[], types=[], answered=None, watched=[], registers=np.zeros(0))
    at = datetime.fromisoformat(_stamps(HOUR)[35])
    _, row, _, sample = conn._sample(plan, [ua.DataValue(ua.Variant(23.5, ua.VariantType.Float)),
                                            ua.DataValue(ua.Variant(at))])
    assert (row[1], sample) == (35 * 60.0, 35)
