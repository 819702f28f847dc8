"""A new thermal state in the exported C (cmon82b, issue 34): where the field follows a drift
exclusion, the code's sensor monitor re-admits the sensor and declares a new thermal state as
the served adaptive model's monitor does (no drift exclusion while it lasts, the guard's bound
``lo_new`` / ``hi_new``), instead of flagging it.

On test_export's three-sensor record (MLR, deployed adaptive): ``T_amb`` +0.1 °C a row from the
middle row, excluded for drift; from the row after, ``T_a`` -1 °C and ``T_b`` +0.6 °C a row (both
out of their bands with ``T_amb`` out: the field followed it).  Before, the C flagged the served
re-admission (``TC_MON_NOT_IN_CODE``) and the pack was cut there; now the compiled code (gcc
-Wall -Wextra -Werror) gives the served corrections on every row and the pack, not cut, passes."""

from __future__ import annotations

import copy
import dataclasses
import subprocess

import numpy as np
import pytest

from test_export import adaptive_mlr, built_stream, needs_cc
from test_export_cmon80 import _streamed
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
from thermocomp.apps.deploy.export.watch import FOLLOWED, NOT_IN_CODE, NOVEL, READMITTED
from thermocomp.apps.deploy.report import stream_rows
from thermocomp.apps.deploy.surveillance import NEW_STATE

HALF = 20
FOLLOW = {"T_a": -1.0, "T_b": 0.6}     # degC a row from the row after T_amb's exclusion


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """``(adaptive MLR as replay deploys it, its system with the monitor, the record with the
    field following T_amb's exclusion, the row of that exclusion)``."""
    deployed, ds, test_ids = adaptive_mlr(tmp_path_factory.mktemp("cmon82b") / "data")
    frame = ds.campaigns[test_ids[1]].reset_index(drop=True)
    frame.loc[HALF:, "T_amb"] += 0.1 * np.arange(len(frame) - HALF)
    times = frame["time"].to_numpy(float)
    out = [e for e in stream_rows(deployed, frame, "K06").events
           if e.get("sensor") == "T_amb" and e["to"] == "excluded"]
    row = int(np.searchsorted(times, out[0]["time"])) + 1          # 1-based
    for sensor, rate in FOLLOW.items():
        frame.loc[row:, sensor] += rate * np.arange(1, len(frame) - row + 1)
    return deployed, state_space(deployed, monitor=True), frame, row


def _served_states(deployed, frame) -> list[tuple[int, str | None, str]]:
    times = frame["time"].to_numpy(float)
    return [(int(np.searchsorted(times, e["time"])) + 1, e.get("sensor"), e["to"])
            for e in stream_rows(deployed, frame, "K06").events
            if e.get("sensor") == "T_amb" or e.get("to") == NEW_STATE]


def _code_states(ss, frame) -> tuple[list, list]:
    """``(rows re-admitted as the field followed, rows in a new thermal state)`` of the numpy
    mirror of the code (1-based); it must flag nothing it does not hold."""
    sim = Simulator(ss)
    sim.reset()
    back, novel = [], []
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
        sim.step(u, t)
        assert not sim.watch.flags & NOT_IN_CODE, (i + 1, sim.watch.missed)
        if sim.watch.flags & READMITTED and sim.watch.rule == FOLLOWED:
            back.append(i + 1)
        if sim.watch.flags & NOVEL:
            novel.append(i + 1)
    return back, novel


@needs_cc
def test_a_new_thermal_state_is_what_the_code_does_as_served(served, tmp_path):
    deployed, ss, frame, row = served
    moves = _served_states(deployed, frame)
    # served: T_amb out for drift, back when the field follows, a new thermal state declared
    assert [m for m in moves if m[2] in ("ok", NEW_STATE)] and moves[0] == (row, "T_amb", "excluded")
    back = [r for r, s, to in moves if s == "T_amb" and to == "ok"]
    declared = [r for r, s, to in moves if to == NEW_STATE]
    assert len(back) == 1 and declared == back, moves
    code_back, code_novel = _code_states(ss, frame)
    assert code_back == back and code_novel == list(range(back[0], len(frame) + 1))
    files, summary = conformance_pack(deployed, ss, {"K06": frame})
    assert (summary["campaigns"][0]["rows"], summary["campaigns"][0]["cut"]) == (len(frame), None)
    stream = built_stream(tmp_path, {**exported_files(deployed, "c"), **files})
    want = corrections(ss, stream_rows(deployed, frame, "K06").y)
    got, said = _streamed(stream, frame, ss.inputs)
    assert got.shape == want.shape and np.max(np.abs(got - want)) < 1e-9        # every row
    assert "the field followed its exclusion" in said and "not in the code" not in said
    script = subprocess.run(["sh", "check/check.sh"], cwd=tmp_path, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr


@needs_cc
def test_the_guard_bound_of_a_new_thermal_state_is_in_the_code(served, tmp_path):
    """The bound ``monitor.guard.new_state_margin=0`` gives (the training error range, the guard's
    default margin 0.2 taken off) bounds the served corrections from the declaration on; the C
    does the same."""
    deployed, _, frame, _ = served
    narrow = copy.deepcopy(deployed)
    g = narrow.guard
    inward = 0.2 * (g.hi - g.lo) / 1.4          # lo - 0.2 w, hi + 0.2 w: w = (hi - lo) / 1.4
    g.lo_new, g.hi_new = g.lo + inward, g.hi - inward
    ss = state_space(narrow, monitor=True)
    want = corrections(ss, stream_rows(narrow, frame, "K06").y)
    wide = corrections(ss, stream_rows(deployed, frame, "K06").y)
    assert np.max(np.abs(want - wide)) > 0.5          # the new state's bound bites
    got, _ = _streamed(built_stream(tmp_path, exported_files(narrow, "c")), frame, ss.inputs)
    assert np.max(np.abs(got - want)) < 1e-9


def test_an_export_before_cmon82b_flags_the_new_thermal_state_as_before(served):
    """Arrays without ``novel`` (an export before cmon82b): flagged where the field follows."""
    deployed, ss, frame, row = served
    old = {k: v for k, v in ss.monitor.items() if k != "novel"}
    sim = Simulator(dataclasses.replace(ss, monitor=old))
    sim.reset()
    flagged = []
    for u, t in zip(frame[ss.inputs].to_numpy(float), frame["time"]):
        sim.step(u, t)
        flagged.append(bool(sim.watch.flags & NOT_IN_CODE))
    assert any(flagged) and not any(flagged[:row])
