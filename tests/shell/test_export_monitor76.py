"""The sensor monitor in the exported C (cmon76): the jump, the freeze, one sensor out rebuilt from
the others and its re-admission, as the served adaptive model's monitor does them; what the code
does not hold is flagged and named, and the conformance pack cuts a campaign there.

On test_export's three-sensor record (MLR, deployed adaptive): a +3 °C jump of ``T_b`` half-way
through a test campaign is excluded, rebuilt and re-admitted by the served monitor, and the
compiled code (gcc -Wall -Wextra -Werror) gives the served corrections on every row (the pack, not
cut, passes; before, it was cut at the jump), and so on a jump and a freeze the pack plants.  Two
sensors stepping +2 °C in one sample (too few for a common step: cmon80) is a rule the code flags
and does not hold: the pack cuts there and says which."""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest

from test_export import adaptive_mlr, built_stream, needs_cc
from test_export_cmon85 import without
from thermocomp.apps.deploy.export import exported_files, not_in_code, state_space
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
from thermocomp.apps.deploy.report import stream_rows


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """``(adaptive MLR as replay deploys it, healthy test campaign, the other test campaign)``."""
    deployed, ds, test_ids = adaptive_mlr(tmp_path_factory.mktemp("cmon76") / "data")
    healthy, other = (ds.campaigns[c].reset_index(drop=True) for c in test_ids)
    return deployed, healthy, other


def _stepped(frame, by_c):
    out = frame.copy()
    out.loc[len(out) // 2:, "T_b"] += by_c
    return out


@needs_cc
def test_a_jump_is_excluded_rebuilt_and_readmitted_by_the_code_as_served(served, tmp_path):
    deployed, healthy, other = served
    faulty = _stepped(other, 3.0)
    done = stream_rows(deployed, faulty, "K06")
    moves = [(e["to"], e["reason"].split(":")[0]) for e in done.events if e.get("sensor") == "T_b"]
    assert moves == [("excluded", "jump"), ("ok", "re-admitted")]
    ss = state_space(deployed, monitor=True)
    files, summary = conformance_pack(deployed, ss, {"K05": healthy, "K06": faulty})
    # (and a jump, a freeze, (cdrop77) a dropout, (cmon80) a reading beyond its range planted on
    # K05's first monitored sensor and a common step: every pack checks them)
    assert [(e["campaign"], e["rows"], e["cut"]) for e in summary["campaigns"]] == [
        ("K05", 40, None), ("K06", 40, None), ("K05.jump.T_a", 40, None),
        ("K05.freeze.T_a", 40, None), ("K05.dropout.T_a", 40, None),
        ("K05.range.T_a", 40, None), ("K05.common.step", 40, None)]
    assert summary["campaigns"][2]["planted"].startswith("T_a +3.097 degC from row 21")
    built_stream(tmp_path, {**exported_files(deployed, "c"), **files})
    script = subprocess.run(["sh", "check/check.sh"], cwd=tmp_path, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr
    said = script.stderr
    assert "line 22: monitor: T_b: jump: re-referenced and excluded" in said
    assert "line 32: monitor: T_b: re-admitted" in said
    assert "line 22: monitor: T_a: jump: re-referenced and excluded" in said      # the planted one
    assert "check: 7 campaign(s) within tolerance" in script.stdout
    # the monitor is what the code does: the plain arithmetic parts from the served corrections
    served_c = corrections(ss, done.y)
    plain = corrections(ss, stream_rows(deployed.streaming, faulty, "K06").y)
    assert np.max(np.abs(plain - served_c)) > 0.5


def test_a_rule_the_code_does_not_hold_is_named_and_the_pack_cut_there(served):
    deployed, healthy, other = served
    faulty = other.copy()       # two sensors +2 degC in one sample: several jumps, no common step
    faulty.loc[len(faulty) // 2:, ["T_a", "T_b"]] += 2.0
    event = next(e for e in stream_rows(deployed, faulty, "K06").events if e.get("sensor") == "T_b")
    assert event["reason"].startswith("jump")
    ss = state_space(deployed, monitor=True)
    # (cmon93: the code holds two jumping at once as served, so the pack runs whole; an export
    # before it, without monitor.pair_jump, flags them and the pack is cut there)
    assert conformance_pack(deployed, ss, {"K06": faulty})[1]["campaigns"][0]["cut"] is None
    _, summary = conformance_pack(deployed, without(ss, "pair_jump"), {"K06": faulty})
    assert summary["campaigns"][0]["cut"] == {
        "row": 21, "why": "the served model's sensor monitor acted there, which is not in the "
                          "code (several sensors jumping in one sample (no common step))"}
    left = not_in_code(deployed, "c")
    assert len(left) == 1 and "several sensors jumping at once that are no common step" in left[0]
    assert not_in_code(deployed, "st") == not_in_code(deployed)       # the ST holds none of it


def test_the_structured_text_and_json_carry_no_monitor(served):
    deployed = served[0]
    assert json.loads(exported_files(deployed, "c")["compensator.json"])["monitor"]["inputs"]
    for fmt in ("st", "json"):
        assert json.loads(exported_files(deployed, fmt)["compensator.json"])["monitor"] == {}
