"""A stepped self-prediction error with two sensors already out in the exported C (step99, issue
34: deployed as scored; benchmarks/bench_step99.py, dl9902's ambient row 994).  Served's stepped
check takes a sensor the others predict out whatever the set out (here the third).  The C held a
stepped error (``STEP_OUT``) beside those out only where a place was free (the second): it
flagged ``SECOND`` and fed the stepped reading to the model.  Now it is held beside any number
out where the set solves, as dep99 holds a range reading and dep99b a jump: the numpy mirror and
the compiled C give served's corrections on every row.

test_export_dep99b's eight-sensor machine and faults (``T_e`` and ``T_f`` in kelvin, both out),
but ``T_c`` stepped +0.85 °C for good while they are out: below its jump limit (+0.95 is a jump),
its self-prediction error stepped past the alarm band.  Fails on 4b0de502 (the mirror flags
``SECOND`` at the step and parts from served by 0.175 µm on 45 rows)."""

from __future__ import annotations

import numpy as np
import pytest

import test_export
from conftest import deployed_as_replay
from test_export import built_stream, needs_cc
from test_export_cmon80 import _streamed
from test_export_dep99b import K_ROWS, ONSET, SPIKE, _machine
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.export.watch import NOT_IN_CODE, STEP_OUT
from thermocomp.apps.deploy.report import stream_rows

STEP = 0.85


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """``(adaptive MLR as replay deploys it, its system with the monitor, the faulted campaign)``."""
    folder = _machine(tmp_path_factory.mktemp("step99") / "data")
    deployed, ds, test_ids = deployed_as_replay(test_export._compose(
        f"data.path={folder}", "track=false", "monitor.adaptive=true", "monitor.fallbacks=none"))
    frame = ds.campaigns[test_ids[-1]].reset_index(drop=True)
    frame.loc[ONSET:ONSET + K_ROWS - 1, ["T_e", "T_f"]] += 273.15
    frame.loc[SPIKE:, "T_c"] += STEP
    return deployed, state_space(deployed, monitor=True), frame


@needs_cc
def test_a_stepped_error_with_two_out_is_held_as_served(served, tmp_path):
    deployed, ss, frame = served
    run = stream_rows(deployed, frame, "K06")
    want = corrections(ss, run.y)
    times = frame["time"].to_numpy(float) - frame["time"].iloc[0]
    moves = [(int(np.searchsorted(times, e["time"])), e["sensor"], e["to"], e["reason"])
             for e in run.events if e.get("sensor")]
    # served: the two out by range, then T_c out by its stepped error as the third
    assert [m for m in moves if m[:3] == (SPIKE, "T_c", "excluded")][0][3].startswith(
        "jump: self-prediction error stepped")
    assert {s for r, s, to, _ in moves if to == "excluded" and r < SPIKE} == {"T_e", "T_f"}
    assert not any(s in ("T_e", "T_f") and to == "ok" for r, s, to, _ in moves if r <= SPIKE)
    sim = Simulator(ss)
    sim.reset()
    U, t = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
    mirror = []
    for i in range(len(frame)):
        mirror.append(sim.step(U[i], t[i]))
        w = sim.watch
        assert not w.flags & NOT_IN_CODE, (i, w.missed)          # 4b0de502: SECOND at the step
        if i == SPIKE:
            assert (w.rule, len(w.gone)) == (STEP_OUT, 3)
    assert np.max(np.abs(np.array(mirror) - want)) < 1e-9                    # every row
    got, said = _streamed(built_stream(tmp_path, exported_files(deployed, "c")), frame, ss.inputs)
    assert got.shape == want.shape and np.max(np.abs(got - want)) < 1e-9     # every row
    assert "not in the code" not in said
