"""A broken wire in the exported C (cdrop77): a monitored sensor's missing reading after a
campaign's first sample is excluded, rebuilt from the others and re-admitted by the code's sensor
monitor as the served adaptive model's monitor does it; where the code cannot rebuild it (the
first sample) the row is refused, the rule named; (dep105b) every sensor missing at once is held
as served: its last field read, the sensors re-admitted together.

On test_export's three-sensor record (MLR, deployed adaptive): ``T_b`` empty for four rows of a
test campaign.  Before, the C refused the first of them (``stream`` exit 2) and the pack cut the
campaign there; now the compiled code (gcc -Wall -Wextra -Werror) gives the served corrections on
every row, and so on the dropout the pack plants."""

from __future__ import annotations

import io
import subprocess

import numpy as np
import pandas as pd
import pytest

from cbuild import compiled
from test_export import adaptive_mlr, built_stream, needs_cc
from thermocomp.apps.deploy.export import Simulator, exported_files, not_in_code, state_space
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
from thermocomp.apps.deploy.report import stream_rows

LOST = list(range(4, 8))        # rows of T_b left empty (lines 6-9 of the CSV)


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """``(adaptive MLR as replay deploys it, its system with the monitor, a test campaign)``."""
    deployed, ds, test_ids = adaptive_mlr(tmp_path_factory.mktemp("cdrop77") / "data")
    return deployed, state_space(deployed, monitor=True), ds.campaigns[test_ids[1]].reset_index(
        drop=True)


def _lost(frame, rows, sensors=("T_b",), value=np.nan):
    out = frame.copy()
    out.loc[rows, list(sensors)] = value
    return out


@needs_cc
def test_a_missing_reading_is_excluded_rebuilt_and_readmitted_by_the_code_as_served(served,
                                                                                    tmp_path):
    deployed, ss, campaign = served
    faulty = _lost(campaign, LOST)
    done = stream_rows(deployed, faulty, "K06")
    moves = [(e["to"], e["reason"].split(":")[0]) for e in done.events if e.get("sensor") == "T_b"]
    assert moves == [("excluded", "dropout"), ("ok", "re-admitted")]
    files, summary = conformance_pack(deployed, ss, {"K06": faulty})
    # kept whole (before: cut at row 21, 'T_b has no value there, which the code refuses'), and
    # a dropout planted on the first monitored sensor beside the jump and the freeze (and, cmon80,
    # a reading beyond its range and a common step)
    assert [(e["campaign"], e["rows"], e["cut"]) for e in summary["campaigns"]] == [
        ("K06", 40, None), ("K06.jump.T_a", 40, None), ("K06.freeze.T_a", 40, None),
        ("K06.dropout.T_a", 40, None), ("K06.range.T_a", 40, None), ("K06.common.step", 40, None)]
    assert summary["campaigns"][3]["planted"] == ("T_a missing (an empty cell) in rows 21-25 (a "
                                                  "dropout), read again after")
    built_stream(tmp_path, {**exported_files(deployed, "c"), **files})
    script = subprocess.run(["sh", "check/check.sh"], cwd=tmp_path, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr
    assert "check: 6 campaign(s) within tolerance" in script.stdout
    # said on stderr at the served monitor's rows (a CSV line: the row + 2)
    line = {e["to"]: int(np.flatnonzero(faulty["time"] == e["time"])[0]) + 2
            for e in done.events if e.get("sensor") == "T_b"}
    said = script.stderr
    assert f"line {line['excluded']}: monitor: T_b: dropout: no finite value, excluded" in said
    assert f"line {line['ok']}: monitor: T_b: re-admitted" in said
    assert line["excluded"] == LOST[0] + 2 and line["ok"] > LOST[-1] + 2
    assert "line 22: monitor: T_a: dropout: no finite value, excluded" in said    # the planted one
    # an overload mark the reader lets through (tc_step's API) is what a missing reading is
    for value in (np.inf, 9.9e37):
        sim, same = Simulator(ss), Simulator(ss)
        for a, b in zip(faulty[ss.inputs].to_numpy(float),
                        _lost(campaign, LOST, value=value)[ss.inputs].to_numpy(float)):
            assert np.array_equal(sim.step(a), same.step(b)) and not same.refused
    # the rebuilt reading is what the model read: the readings as the plain code reads them part
    kept = corrections(ss, done.y)
    plain = corrections(ss, stream_rows(deployed.streaming, campaign, "K06").y)
    assert np.max(np.abs(plain[LOST] - kept[LOST])) > 0.01


@needs_cc
def test_where_the_code_cannot_rebuild_a_reading_it_refuses_the_row_and_names_why(served,
                                                                                 tmp_path):
    deployed, ss, campaign = served
    # (dep101) two of the three missing in one sample are held as served; (dep105b) all three too
    first, two = _lost(campaign, [0]), _lost(campaign, [20], ("T_a", "T_b"))
    every = _lost(campaign, [20], ss.inputs)
    _, summary = conformance_pack(deployed, ss, {"first": first, "two": two, "every": every})
    cuts = {e["campaign"]: e["cut"] for e in summary["campaigns"]}
    assert cuts["two"] is None and cuts["every"] is None     # (dep105b: before, cut at row 21)
    assert cuts["first"] == {"row": 1, "why": "T_b has no value there, which the code refuses (a "
                             "missing reading at a campaign's first sample; stream.c stops; the "
                             "served model rebuilds it)"}
    for name, text in exported_files(deployed, "c").items():
        (tmp_path / name).write_text(text)
    compiled(tmp_path)
    cols = ["time", *ss.inputs]
    run = subprocess.run([str(tmp_path / "stream")], capture_output=True, text=True,
                         input=every[cols].to_csv(index=False, float_format="%.17g"))
    # (dep105b) served holds its last field at row 20 (none left in to rebuild from), reads the
    # readings back from row 21 and re-admits all three a window on: the C the same, every row
    # (before: exit 2 at line 22, 'a missing reading with another sensor out or missing')
    done = stream_rows(deployed, every, "K06")
    back = {e["sensor"]: int(np.flatnonzero(every["time"] == e["time"])[0])
            for e in done.events if e.get("to") == "ok"}
    assert back == {"T_a": 30, "T_b": 30, "T_amb": 30}, done.events
    assert run.returncode == 0, run.stderr
    got = pd.read_csv(io.StringIO(run.stdout)).to_numpy(float)
    want = corrections(ss, done.y)
    assert got.shape == want.shape and np.max(np.abs(got - want)) < 1e-9
    # (the stream names a sample's first event: T_a's, at both lines)
    assert run.stderr.splitlines() == [
        "stream: line 22: monitor: T_a: dropout: no finite value, excluded",
        "stream: line 32: monitor: T_a: re-admitted: within half its warning band for a window "
        "(its whole band after a dropout, or out as a culprit within it)"]
    assert "a missing reading at a campaign's first sample" in not_in_code(deployed, "c")[0]
