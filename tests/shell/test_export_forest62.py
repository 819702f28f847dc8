"""An ``arx_rf`` model exports: its ARX a law, its forest walked as arrays (exportrest62).

``arx_rf`` (paper 004) streams as an ARX plus a random forest on a door's switching signal
(``S_door`` smoothed by a logistic ramp from its last change), and ``thermocomp export`` refused
it ("ARXRF is not one of the linear families").  Now the code tracks the door, computes the ramp
per time scale and walks every tree from its root over flat arrays (feature, threshold, left,
right, value) in a loop of fixed length, comparing the feature cast to float32 as scikit-learn's
trees do.  The compiled C, the Structured Text and the numpy reading equal ``replay`` to 1e-9 µm,
plain and as a blend member of ``model=auto``, the door missing on some rows (held, as the
stream holds it), a threshold set between a feature's float64 value and its float32 rounding
(the cast decides the branch), and ``thermocomp export``'s check pack passes, the forest's size
said.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from cbuild import LEVEL
from test_export import (
    StructuredText,
    _compiled,
    _exported_code,
    _make_dataset,
    _stdin,
    _streamed,
    checked_pack,
    needs_cc,
    parses_as_the_parsed_block,
)
from test_export_auto57 import TOLERANCE_UM, _proved, deployed
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.deploy.streaming import replay
from thermocomp.core.models.arx_rf import ARXRF
from thermocomp.shell.stages.export import PLC_LIMIT_BYTES, _forest_said

SMALL = ("model.estimator.forest.n_estimators=4",)


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return _make_dataset(tmp_path_factory.mktemp("forest62") / "data")


def _forests(stream) -> list:
    return [e for _, e, _ in stream._plan if isinstance(e, ARXRF)]


@needs_cc
@pytest.mark.parametrize("taus", ["60.0", "[60.0,600.0]"], ids=["one-tau", "two-taus"])
def test_an_arx_rf_model_streams_as_replay_in_c_st_and_the_arrays(data, tmp_path, taus):
    stream, tests, _ = deployed(data, "model=arx_rf", *SMALL, f"model.estimator.tau_s={taus}")
    assert len(_forests(stream)) == 2
    ss = state_space(stream)                                  # refused before
    door = ss.inputs.index("S_door")
    assert ss.switch_input == [door] and ss.held[door] == 1 and ss.clamp_outright == [1, 1]
    assert len(ss.switch_feature) == len(json.loads(taus) if "[" in taus else [taus])
    assert len(ss.tree_root) == 8 and ss.forest_trees == [0, 4, 8]
    tests[1].loc[5:8, "S_door"] = np.nan        # a missing door: held, as the stream holds it
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM


@needs_cc
def test_a_blend_member_arx_rf_exports_its_forest_times_its_weight(data, tmp_path):
    stream, tests, _ = deployed(data, "model=auto", "model.candidates=[mlr,arx_rf]",
                                "model.candidate_params={arx_rf:{forest:{n_estimators:3}}}",
                                "+model.estimator.chosen={E_X:mlr,E_Z:{mlr:0.7,arx_rf:0.3}}")
    ss = state_space(stream)                                  # refused before
    assert ss.forest_target == [1] and ss.forest_weight == [0.3]
    assert ss.provenance["laws"]["E_Z"] == "blend mlr 0.7 + arx_rf 0.3"
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM


def _on_a_float32_tie(stream, tests) -> int:
    """Sets the root threshold of E_X's first tree between a feature's float64 value at a test
    sample and its float32 rounding, so that the two sides of the comparison take different
    branches there; returns how many test samples fall between them."""
    est = _forests(stream)[0]
    sim = Simulator(state_space(stream))
    seen = []
    for df in tests:
        sim.reset()
        for u, t in zip(df[stream.columns_].to_numpy(float), df["time"]):
            sim.step(u, t)
            seen.append(float(sim.switches.features[0]))
    value = next(v for v in seen if float(np.float32(v)) != v)
    rounded = float(np.float32(value))
    tree = est.forest_.estimators_[0].tree_
    tree.feature[0] = 0
    tree.threshold[0] = (value + rounded) / 2 if rounded < value else value
    est.forest_.__dict__.pop("_thermocomp_flat", None)      # the stream's cached node table
    return sum(min(value, rounded) <= v <= max(value, rounded) for v in seen)


@needs_cc
def test_the_code_compares_the_feature_cast_to_float32_as_the_trees_do(data, tmp_path):
    stream, tests, _ = deployed(data, "model=arx_rf", *SMALL, "monitor.adaptive=false",
                                "model.estimator.tau_s=1000.0")
    assert _on_a_float32_tie(stream, tests) >= 1
    expected = np.vstack([-replay(stream, df)[stream.targets_].to_numpy(float) for df in tests])
    got = _streamed(_compiled(stream, tmp_path, LEVEL), _stdin(stream, tests)).to_numpy(float)
    assert np.max(np.abs(got - expected)) <= TOLERANCE_UM
    fb = StructuredText(exported_files(stream, "st")["compensator.st"])
    rows = [fb(r, t, k == 0) for df in tests
            for k, (r, t) in enumerate(zip(df[stream.columns_].to_numpy(float), df["time"]))]
    assert np.max(np.abs(np.array(rows) - expected)) <= TOLERANCE_UM


def _exported(data, tmp_path, fmt: str, *model: str):
    return _exported_code(data, tmp_path, fmt, "arx_rf", *model)


@needs_cc
def test_the_export_commands_check_pack_passes_and_the_forests_size_is_said(data, tmp_path,
                                                                           capsys):
    out = _exported(data, tmp_path, "c", *SMALL)
    said = capsys.readouterr().err
    exported = json.loads((out / "compensator.json").read_text())
    size = (out / "compensator.c").stat().st_size / 1024
    assert (f"forest: 2 forest(s) of 8 trees, {len(exported['node_left']):,} nodes (depth <= "
            f"{exported['tree_depth']}) walked as arrays: compensator.c {size:,.0f} KB") in said
    assert "beyond 1 MB" not in said
    # (the test campaigns, and the jump and the freeze the pack plants: cmon76; a dropout: cdrop77;
    # a reading beyond its range and a common step: cmon80)
    assert checked_pack(out).count("stream: check passed: 40 rows") == 7


def test_the_structured_text_of_a_forest_parses_as_iec_61131_3(data, tmp_path, parsed_block):
    """A tiny forest (two trees of depth 2), held to the block blark parses."""
    out = _exported(data, tmp_path, "st", "model.estimator.forest.n_estimators=2",
                    "+model.estimator.forest.max_depth=2")
    text = (out / "compensator.st").read_text()
    assert "LREAL_TO_REAL" in text and "NODE_THRESHOLD : ARRAY" in text
    parses_as_the_parsed_block(text, parsed_block)


# (an arx_rf within an ATI model, refused here before, exports since exportati63:
# test_export_ati63.py)


def test_a_forest_whose_code_exceeds_a_megabyte_is_said_to_be_too_large_for_many_plcs():
    exported = {"forest_target": [0], "node_left": [-1] * 3, "tree_root": [0], "tree_depth": 1}
    small = {"compensator.st": "x" * PLC_LIMIT_BYTES, "compensator.json": "y" * (2 * PLC_LIMIT_BYTES)}
    said = _forest_said(exported, small)
    assert said.endswith("compensator.st 1,024 KB") and "beyond" not in said
    said = _forest_said(exported, {**small, "compensator.st": "x" * (PLC_LIMIT_BYTES + 1)})
    assert "compensator.st beyond 1 MB: more than many PLCs take" in said
    assert "model.estimator.forest.n_estimators" in said
