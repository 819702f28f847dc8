"""An arx_rf model's fallback in the exported C (cmon91, issue 34): while a sensor no other
predicts is out, the served correction is the arx_rf fitted without it, its ARX and its forest
on the door's switching; the code now holds that forest beside the model's and walks it only
while its set is served, as its laws (bench_deploy89's lr9212/arx_rf, cut at R1b row 765 before).

test_export_cmon82c's machine and ramp (``T_u``, a sensor no other predicts, excluded as
explaining ``T_b``'s band and re-admitted once back; ``S_door`` switching), deployed as
``model=arx_rf`` with its fallback models.  Before, the export left the fallback's forest out
(``fallback_set`` 0): the code flagged ``FALLBACK`` from the exclusion on and the pack was cut
there; now the numpy mirror and the compiled code (gcc -Wall -Wextra -Werror) give the served
corrections on every row and the pack, not cut, passes; the same export with no set for the
fallback (as before cmon91) still flags."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from test_export import needs_cc
from test_export_cmon80 import assert_packed_as_served
from test_export_cmon82c import _deployed, _machine, _served_moves
from test_export_cmon83 import _mirror, _plain
from thermocomp.apps.deploy.export import exported_files, not_in_code, state_space
from thermocomp.apps.deploy.export.fallbacks import _merge
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
from thermocomp.apps.deploy.export.watch import FALLBACK
from thermocomp.apps.deploy.report import stream_rows


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """``(adaptive arx_rf with T_u's fallback model, its system with the monitor, the ramped
    record)``."""
    deployed, frame = _deployed(_machine(tmp_path_factory.mktemp("cmon91") / "data"),
                                "unobservable", "arx_rf")
    return deployed, state_space(deployed, monitor=True), frame


def _sensor_set(ss, sensor: str) -> int:
    return ss.monitor["fallback_set"][[ss.inputs[i] for i in ss.monitor["inputs"]].index(sensor)]


@needs_cc
def test_the_code_serves_an_arx_rf_fallback_with_its_forest(served, tmp_path):
    deployed, ss, frame = served
    assert "T_u" in deployed.fallbacks_
    s = _sensor_set(ss, "T_u")
    # the fallback's forest in the system, counting by a law of its set
    assert s > 0 and len(ss.forest_target) > 1
    assert s in {ss.law_set[r] for r in ss.forest_law}
    moves = [(r, to) for r, to, _ in _served_moves(deployed, frame) if to in ("excluded", "ok")]
    assert [to for _, to in moves] == ["excluded", "ok"], moves
    (out, _), (back, _) = moves
    want = corrections(ss, stream_rows(deployed, frame, "K06").y)
    got, sets, missed = _mirror(ss, frame)
    assert sets == [0] * (out - 1) + [s] * (back - out) + [0] * (len(frame) - back + 1)
    assert not any(missed) and np.max(np.abs(got - want)) < 1e-9
    assert_packed_as_served(tmp_path, deployed, ss, "K06", frame, want)
    # the same system with no set for T_u's fallback (an export before cmon91: 0 there) flags
    # from the exclusion to the end, the pack cut there, as it did
    sets = list(ss.monitor["fallback_set"])
    sets[sets.index(s)] = 0
    old = dataclasses.replace(ss, monitor={**ss.monitor, "fallback_set": sets})
    _, old_sets, missed = _mirror(old, frame)
    assert missed == [0] * (out - 1) + [FALLBACK] * (len(frame) - out + 1) and not any(old_sets)
    _, summary = conformance_pack(deployed, old, {"K06": frame})
    cut = summary["campaigns"][0]["cut"]
    assert cut["row"] >= out and "model fitted without" in cut["why"], cut


def test_the_structured_text_leaves_an_arx_rf_fallback_out_and_says_so(served):
    """(st103b) The ST block serves a fallback model while it holds its sensor out, but not one
    with a forest (its forest walk counts whatever set is served): the model's laws alone, as
    before, and ``provenance.not_in_code`` says so (the C's message is as it was)."""
    deployed = served[0]
    assert "N_SETS : INT := 1;" in exported_files(deployed, "st")["compensator.st"]
    assert "a forest or a network" in not_in_code(deployed, "st")[0]
    assert "a forest or a network" not in not_in_code(deployed)[0]


@pytest.mark.parametrize("into", ["model", "fallback"])
def test_a_merged_arx_rf_fallback_steps_as_its_own_system(served, into):
    """An arx_rf model's fallback merged into the model's system, served, gives its own system's
    corrections (its forest walked, the model's not), and the model's merged into its
    fallback's its own."""
    deployed, _, frame = served
    own = dataclasses.replace(state_space(deployed), monitor={})
    fallback = state_space(deployed.fallbacks_["T_u"])
    assert own.forest_target and fallback.forest_target
    base, added = (own, fallback) if into == "model" else (fallback, own)
    merged = dataclasses.replace(base, **{k: list(getattr(base, k)) for k in (
        "powers", "taus", "lag_input", "lag_decay", "lag_of", "switch_input", "switch_feature")})
    _merge(merged, added, 1)
    assert len(merged.forest_target) == len(base.forest_target) + len(added.forest_target)
    assert len(merged.node_left) == len(base.node_left) + len(added.node_left)
    served_added = dataclasses.replace(merged, law_set=[1 - s for s in merged.law_set])
    rows, times = frame[own.inputs].to_numpy(float), frame["time"]
    assert np.max(np.abs(_plain(served_added, rows, times) - _plain(added, rows, times))) < 1e-9
    # the base's laws served: its own corrections, the added laws and forest stepping beside
    assert np.max(np.abs(_plain(merged, rows, times) - _plain(base, rows, times))) < 1e-9
