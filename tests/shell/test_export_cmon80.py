"""A reading beyond its range and a common step in the exported C (cmon80, issue 34): the code's
sensor monitor reads the first as missing (the sensor excluded, rebuilt from the others, its
return stepped from its last reading, re-admitted) and re-references the second (every sensor
that took it, kept in), as the served adaptive model's monitor does.

On test_export's three-sensor record (MLR, deployed adaptive): ``T_b`` +30 °C for three rows and
+8 °C to the end, all three sensors +2 °C from the middle row, and ``T_b`` at 36 °C (beyond its
range) while a warmer ``T_a`` predicts it beyond the same edge (a machine hotter than training:
read, a jump).  Before, the C flagged both
(``TC_MON_NOT_IN_CODE``) and parted from the served corrections from row 21 (by 1.16 and 4.23 µm);
now the compiled code (gcc -Wall -Wextra -Werror) gives them on every row, and the pack, not cut,
passes with the range reading and the common step it plants."""

from __future__ import annotations

import subprocess

import numpy as np
import pandas as pd
import pytest

from test_export import adaptive_mlr, built_stream, needs_cc
from thermocomp.apps.deploy.export import Simulator, exported_files, not_in_code, state_space
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
from thermocomp.apps.deploy.export.served import ServedStreams
from thermocomp.apps.deploy.export.watch import CodeMonitor
from thermocomp.apps.deploy.report import stream_rows

HALF = 20


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """``(adaptive MLR as replay deploys it, its system with the monitor, a test campaign)``."""
    deployed, ds, test_ids = adaptive_mlr(tmp_path_factory.mktemp("cmon80") / "data")
    return deployed, state_space(deployed, monitor=True), ds.campaigns[test_ids[1]].reset_index(
        drop=True)


def _faulty(frame, kind):
    out = frame.copy()
    if kind == "spike":             # +30 degC for three rows: beyond T_b's range (+-10 degC)
        out.loc[HALF:HALF + 2, "T_b"] += 30.0
    elif kind == "beyond":          # +8 degC to the end
        out.loc[HALF:, "T_b"] += 8.0
    elif kind == "common":          # a logger's reference: every sensor +2 degC at once
        out.loc[HALF:, ["T_a", "T_b", "T_amb"]] += 2.0
    elif kind == "hotter":          # T_a warms (within its range) and T_b reads 36 degC, beyond
        out["T_a"] += np.clip(np.arange(len(out)) - 10, 0, 9) * 0.33      # its range, where T_a
        out.loc[HALF + 1:, "T_b"] = 36.0                                   # predicts it: a jump
    elif kind == "second":          # T_b beyond its range while T_a is out (a dropout)
        out.loc[HALF - 2:HALF - 1, "T_a"] = np.nan
        out.loc[HALF - 1, "T_b"] += 30.0
    return out


def _streamed(binary, frame, inputs):
    run = subprocess.run([str(binary)], capture_output=True, text=True, check=True,
                         input=frame[["time", *inputs]].to_csv(index=False, float_format="%.17g"))
    return pd.read_csv(pd.io.common.StringIO(run.stdout)).to_numpy(float), run.stderr


def streamed_as_served(folder, deployed, ss, campaign: str, frame, want,
                       served: ServedStreams | None = None) -> tuple[dict, str]:
    """``frame``'s conformance pack (as test campaign ``campaign``) not cut, and the compiled C
    (built in ``folder``) = ``want`` (the served corrections) on every row with nothing flagged
    as not in the code: the pack's summary and what the code said on stderr, for a test's own
    assertions on them.  ``served``: the served streams of ``deployed`` made so far, if any."""
    files, summary = conformance_pack(deployed, ss, {campaign: frame}, served=served)
    assert summary["campaigns"][0]["cut"] is None
    stream = built_stream(folder, {**exported_files(deployed, "c"), **files})
    c, said = _streamed(stream, frame, ss.inputs)
    assert c.shape == want.shape and np.max(np.abs(c - want)) < 1e-9        # every row
    assert "not in the code" not in said
    return summary, said


def assert_packed_as_served(folder, deployed, ss, campaign: str, frame, want,
                            served: ServedStreams | None = None) -> None:
    """:func:`streamed_as_served`, the pack whole (every row of ``frame``), and ``check.sh``
    passing."""
    summary, _ = streamed_as_served(folder, deployed, ss, campaign, frame, want, served)
    assert summary["campaigns"][0]["rows"] == len(frame)
    script = subprocess.run(["sh", "check/check.sh"], cwd=folder, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr


@needs_cc
def test_a_reading_beyond_its_range_and_a_common_step_are_what_the_code_does_as_served(served,
                                                                                       tmp_path):
    deployed, ss, campaign = served
    faults = {k: _faulty(campaign, k) for k in ("spike", "beyond", "common", "hotter")}
    moves = {k: [(e["sensor"], e["to"], e["reason"].split(":")[0])
                 for e in stream_rows(deployed, f, "K06").events if e.get("sensor")]
             for k, f in faults.items()}
    assert moves["spike"] == [("T_b", "excluded", "out of range"), ("T_b", "ok", "re-admitted")]
    assert moves["beyond"] == [("T_b", "excluded", "out of range")]      # out to the end
    assert moves["common"] == [(s, "re-referenced", "common step") for s in ("T_a", "T_b", "T_amb")]
    # a machine hotter than training: read, a jump (the others predict it beyond the same edge);
    # out, its readings beyond the range are missing ones
    assert moves["hotter"] == [("T_b", "excluded", "jump")]
    files, summary = conformance_pack(deployed, ss, faults)
    # kept whole (before: cut at row 21, 'a reading beyond its training range' / 'several sensors
    # jumping in one sample'); the copies planted on the first campaign are cut where its own
    # spike on T_b comes while the planted sensor is out (a second sensor out), or (the common
    # step) with it: two sensors jumping beside one beyond its range are no common step; the
    # freeze (cmon85) kept whole: T_a's freeze seen while T_b is out is a second sensor out the
    # code holds (before: cut at row 31); and (cmon88) the jump: T_a's jump in the row T_b goes
    # beyond its range is a second sensor out for a jump the code holds, its change judged by
    # the set in before T_b's exclusion, as served (before: cut at row 21); (dep99) T_a beyond
    # its range while T_b is out for its own: a second out for a range reading the code holds
    # where the field is not rebuilt without both, as served (before: cut at row 21)
    assert [(e["campaign"], e["rows"], e["cut"] is None) for e in summary["campaigns"]] == [
        ("spike", 40, True), ("beyond", 40, True), ("common", 40, True), ("hotter", 40, True),
        ("spike.jump.T_a", 40, True), ("spike.freeze.T_a", 40, True),
        ("spike.dropout.T_a", 20, False), ("spike.range.T_a", 40, True),
        ("spike.common.step", 20, False)]
    stream = built_stream(tmp_path, {**exported_files(deployed, "c"), **files})
    for k, f in faults.items():
        want = corrections(ss, stream_rows(deployed, f, "K06").y)
        got, said = _streamed(stream, f, ss.inputs)
        assert got.shape == want.shape and np.max(np.abs(got - want)) < 1e-9, k   # every row
        if k == "common":
            assert "line 22: monitor: T_a: common step: re-referenced, kept in" in said
        elif k == "hotter":
            assert "line 23: monitor: T_b: jump: re-referenced and excluded" in said
            assert "out of range" not in said
        else:
            assert "line 22: monitor: T_b: out of range: read as missing, excluded" in said
        assert "not in the code" not in said
        # the monitor is what the code does: the model fed the readings parts from the served
        fed = corrections(ss, stream_rows(deployed.streaming, f, "K06").y)
        assert np.max(np.abs(fed - want)) > 0.5, k
    script = subprocess.run(["sh", "check/check.sh"], cwd=tmp_path, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr
    left = not_in_code(deployed, "c")[0]
    assert "a reading beyond its training range, a common step, one sensor out" in left
    assert "several sensors jumping at once that are no common step" in left


@needs_cc
def test_the_pack_plants_a_reading_beyond_its_range_and_a_common_step(served, tmp_path):
    deployed, ss, campaign = served
    files, summary = conformance_pack(deployed, ss, {"K06": campaign})
    planted = {e["campaign"]: (e["rows"], e["cut"], e["planted"]) for e in summary["campaigns"]
               if "planted" in e}
    assert planted["K06.range.T_a"][:2] == (40, None)
    assert planted["K06.range.T_a"][2].startswith("T_a reads 47.34 degC (beyond its range) in "
                                                  "rows 21-25")
    assert planted["K06.common.step"][:2] == (40, None)
    assert planted["K06.common.step"][2].startswith("every monitored sensor +3.097 degC from row 21")
    built_stream(tmp_path, {**exported_files(deployed, "c"), **files})
    script = subprocess.run(["sh", "check/check.sh"], cwd=tmp_path, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr
    assert "check: 6 campaign(s) within tolerance" in script.stdout
    assert "line 22: monitor: T_a: out of range: read as missing, excluded" in script.stderr
    assert "line 22: monitor: T_a: common step: re-referenced, kept in" in script.stderr


def test_a_reading_beyond_its_range_with_another_sensor_out_is_held_as_served(served):
    """(dep99) T_b beyond its range while T_a is out for a dropout: the second out where the
    field is not rebuilt without both (before: cut at row 20, not in the code); T_a's returned
    reading read meanwhile, as served (``_rebuilds``)."""
    deployed, ss, campaign = served
    frame = _faulty(campaign, "second")
    _, summary = conformance_pack(deployed, ss, {"K06": frame})
    assert summary["campaigns"][0]["cut"] is None
    want = corrections(ss, stream_rows(deployed, frame, "K06").y)
    sim = Simulator(ss)
    sim.reset()
    U, t = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
    assert np.max(np.abs(np.array([sim.step(U[i], t[i]) for i in range(len(frame))]) - want)) < 1e-9


def test_a_machine_hotter_than_training_is_read_as_the_served_monitor_reads_it(served):
    """The served monitor's ``_hotter`` (the others predict the reading beyond the same training
    edge, and it reads near that prediction) and the code's, on readings built around it."""
    deployed, ss, _ = served
    mon, code = deployed.monitor, CodeMonitor(ss.monitor)
    n = len(mon.names)
    assert n - 1 >= mon.min_active_
    rng = np.random.default_rng(80)
    seen = set()
    for _ in range(200):
        j = int(rng.integers(n))
        ref = mon.first_c + rng.normal(0, 1, n)
        d = rng.normal(0, 15, n)
        M, _ = mon._operator(np.arange(n) != j)
        p = ref[j] + M[j] @ d[np.arange(n) != j]
        x = ref + d
        x[j] = p + rng.normal(0, 4)
        d[j] = x[j] - ref[j]
        beyond = (x < mon._lo_lim) | (x > mon._hi_lim)
        if beyond.sum() != 1 or not beyond[j]:
            continue
        mon.reset()
        mon._count = 1
        kept = bool(mon._hotter(x, d, beyond)[j])
        code.reset()
        code.ref = ref.copy()
        got = code._beyond(x, d, beyond)
        assert got is not None and bool(got[j]) != kept
        seen.add(kept)
    assert seen == {True, False}          # both outcomes met
