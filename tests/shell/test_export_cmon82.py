"""A drifting sensor in the exported C (cmon82, issue 34): the code's sensor monitor excludes it
by judgement as the served adaptive model's monitor does (the culprit whose exclusion leaves the
others within their bands, rebuilt from them), instead of flagging it and reading on.

On test_export's three-sensor record (MLR, deployed adaptive): ``T_b`` +0.2 °C a row and
``T_amb`` +0.1 °C a row from the middle row to the end.  Before, the C flagged the served drift
exclusion (``TC_MON_NOT_IN_CODE``) and read the drifting sensor on, and the pack was cut there;
now the compiled code (gcc -Wall -Wextra -Werror) excludes it at the same row, gives the served
corrections on every row, and the pack, not cut, passes."""

from __future__ import annotations

import dataclasses
import subprocess

import numpy as np
import pytest

from test_export import adaptive_mlr, built_stream, needs_cc
from test_export_cmon80 import _streamed
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
from thermocomp.apps.deploy.export.watch import DRIFT_OUT, EXCLUDED, NOT_IN_CODE
from thermocomp.apps.deploy.report import stream_rows

HALF = 20
DRIFTS = {"T_b": 0.2, "T_amb": 0.1}     # degC a row from the middle row


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """``(adaptive MLR as replay deploys it, its system with the monitor, a test campaign)``."""
    deployed, ds, test_ids = adaptive_mlr(tmp_path_factory.mktemp("cmon82") / "data")
    return deployed, state_space(deployed, monitor=True), ds.campaigns[test_ids[1]].reset_index(
        drop=True)


def _drifting(frame, sensor):
    out = frame.copy()
    out.loc[HALF:, sensor] += DRIFTS[sensor] * np.arange(len(out) - HALF)
    return out


def _code_exclusions(ss, frame) -> list[tuple[int, str]]:
    """The rows (1-based) and sensors the numpy mirror of the code excludes for drift; it must
    flag nothing it does not hold."""
    sim = Simulator(ss)
    sim.reset()
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    out = []
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
        sim.step(u, t)
        assert not sim.watch.flags & NOT_IN_CODE, (i + 1, sim.watch.missed)
        if sim.watch.flags & EXCLUDED and sim.watch.rule == DRIFT_OUT:
            out.append((i + 1, names[sim.watch.sensor]))
    return out


@needs_cc
def test_a_drifting_sensor_is_excluded_by_the_code_as_served(served, tmp_path):
    deployed, ss, campaign = served
    faults = {s: _drifting(campaign, s) for s in DRIFTS}
    times = campaign["time"].to_numpy(float)
    for sensor, frame in faults.items():
        moves = [(int(np.searchsorted(times, e["time"])) + 1, e["sensor"], e["to"],
                  e["reason"].split(":")[0])
                 for e in stream_rows(deployed, frame, "K06").events if e.get("sensor")]
        assert len(moves) == 1 and moves[0][1:] == (sensor, "excluded", "drift"), moves
        assert _code_exclusions(ss, frame) == [moves[0][:2]]          # the same row, the same sensor
    files, summary = conformance_pack(deployed, ss, faults)
    # kept whole (before: cut at the served drift exclusion, 'a drift beyond the band')
    assert [(e["campaign"], e["rows"], e["cut"]) for e in summary["campaigns"][:2]] == [
        ("T_b", 40, None), ("T_amb", 40, None)]
    stream = built_stream(tmp_path, {**exported_files(deployed, "c"), **files})
    for sensor, frame in faults.items():
        want = corrections(ss, stream_rows(deployed, frame, "K06").y)
        got, said = _streamed(stream, frame, ss.inputs)
        assert got.shape == want.shape and np.max(np.abs(got - want)) < 1e-9, sensor   # every row
        assert f"monitor: {sensor}: drift: its self-prediction error explains" in said
        assert "not in the code" not in said
        # the exclusion is what the code does: the model fed the drifting reading parts from it
        fed = corrections(ss, stream_rows(deployed.streaming, frame, "K06").y)
        assert np.max(np.abs(fed - want)) > 0.5, sensor
    script = subprocess.run(["sh", "check/check.sh"], cwd=tmp_path, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr


def test_an_export_before_cmon82_flags_the_drift_as_before(served):
    """Arrays without the judgement's constants (an export before cmon82): flagged, not held."""
    deployed, ss, campaign = served
    old = {k: v for k, v in ss.monitor.items() if k not in ("drift", "pairs")}
    sim = Simulator(dataclasses.replace(ss, monitor=old))
    sim.reset()
    frame = _drifting(campaign, "T_b")
    flagged = []
    for u, t in zip(frame[ss.inputs].to_numpy(float), frame["time"]):
        sim.step(u, t)
        flagged.append(bool(sim.watch.flags & NOT_IN_CODE))
    assert any(flagged) and not any(flagged[:HALF])
