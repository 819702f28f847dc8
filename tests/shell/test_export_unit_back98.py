"""The exported C after a logger's unit comes back (dep98, issue 34: deployed as scored;
benchmarks/bench_dep98.py).  Every ``T_`` input read in kelvin for ``K_ROWS`` samples, then in °C
again: the served monitor reads the kelvin samples as missing (each sensor's step after them
spans them) and re-admits the sensors a window after the return; the C passes such samples by its
monitor (not in the code).  Its state stayed as it was, so the return read as one sample's
step: a common step on test_export_cmon82c's machine (every sensor re-referenced by the heat of
the 20 samples), a settled level shift of a sensor no other predicts on tr9828 (its ring took the
window's last row again for each passed sample) -- corrections parted from served's for good
(here 3.28 µm to the campaign's end).  Now a passed sample counts in each step's span and the
settled ring, as served: once served has re-admitted the sensors the numpy mirror and the
compiled C give its corrections again, to the end.  (From the return until served's re-admission
served holds the last field and the C reads the readings: not in the code, flagged.)

test_export_cmon82c's four-sensor machine (``T_u`` no other predicts; no fallback model), its
last test campaign as recorded.  Fails on 16d3b58d (the mirror 3.28 µm off served from the
return to the end)."""

from __future__ import annotations

import numpy as np
import pytest

import test_export
from conftest import deployed_as_replay
from test_export import built_stream, needs_cc
from test_export_cmon80 import _streamed
from test_export_cmon82c import _machine
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.report import stream_rows

ONSET, K_ROWS = 20, 20
KELVIN = 273.15


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """``(adaptive MLR as replay deploys it, its system with the monitor, the test campaign)``."""
    folder = _machine(tmp_path_factory.mktemp("unit_back98") / "data")
    deployed, ds, test_ids = deployed_as_replay(test_export._compose(
        f"data.path={folder}", "track=false", "monitor.adaptive=true", "monitor.fallbacks=none"))
    return deployed, state_space(deployed, monitor=True), ds.campaigns[test_ids[-1]].reset_index(
        drop=True)


@needs_cc
def test_after_the_unit_comes_back_the_code_serves_as_served(served, tmp_path):
    deployed, ss, campaign = served
    frame = campaign.copy()
    frame.loc[ONSET:ONSET + K_ROWS - 1, [c for c in frame.columns if c.startswith("T_")]] += KELVIN
    run = stream_rows(deployed, frame, "K06")
    want = corrections(ss, run.y)
    healthy = corrections(ss, stream_rows(deployed, campaign, "K06").y)
    times = frame["time"].to_numpy(float) - frame["time"].iloc[0]
    back = {int(np.searchsorted(times, e["time"])) for e in run.events if e.get("to") == "ok"}
    assert len(back) == 1 and (readmitted := back.pop()) > ONSET + K_ROWS    # all in at once
    # served back on its healthy corrections (its guard's rate-limit at the return spent)
    equal = readmitted + 5
    assert np.max(np.abs(want[equal:] - healthy[equal:])) < 1e-9
    sim = Simulator(ss)
    sim.reset()
    U, t = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
    mirror = np.array([sim.step(U[i], t[i]) for i in range(len(frame))])
    assert np.max(np.abs(mirror[:ONSET + K_ROWS] - want[:ONSET + K_ROWS])) < 1e-9   # (kelvin97)
    assert np.max(np.abs(mirror[equal:] - want[equal:])) < 1e-9   # 16d3b58d: 3.28 µm to the end
    stream = built_stream(tmp_path, exported_files(deployed, "c"))
    got, said = _streamed(stream, frame, ss.inputs)
    assert got.shape == want.shape
    assert np.max(np.abs(got[:ONSET + K_ROWS] - want[:ONSET + K_ROWS])) < 1e-9
    assert np.max(np.abs(got[equal:] - want[equal:])) < 1e-9
    assert "not in the code: a reading beyond its training range" in said
