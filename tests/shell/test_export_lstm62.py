"""An ``lstm`` model exports: its skip path a law, its network stepped over arrays (lstmexport62).

``lstm`` streams as a linear skip path plus an LSTM's read-out, the cell run in float64 from
``(h, c) = 0`` at a campaign's first sample, and ``thermocomp export`` refused it ("LSTM is not one
of the linear families"), so ``model=auto``'s blend on fl_thermal, which holds one, could not reach
a machine.  Now the skip path is a law of the code and the cell is stepped per sample over the
network's arrays (gates i, f, g, o as torch orders them, the input standardisation, the
read-out, the output scale), on the clamped inputs as the stream runs a model without a step
gain, times its blend weight.  The compiled C, the Structured Text and the numpy reading equal
``replay`` to 1e-9 µm (one test sensor pushed out of the envelope: the clamp acts), plain (one
or two layers) and as a blend member, ``thermocomp export``'s check pack passes and the
network's size is said (within an ATI model: test_export_ati63.py).
"""

from __future__ import annotations

import json

import pytest

from test_export import (
    _exported_code,
    _make_dataset,
    checked_pack,
    needs_cc,
    parses_as_the_parsed_block,
)
from test_export_auto57 import TOLERANCE_UM, _proved, deployed
from thermocomp.apps.deploy.export import state_space
from thermocomp.core.models.lstm import LSTM

# a tiny network (test_export_auto57's): two epochs of four hidden units, kept whatever its
# held-out score (validation_fraction 0: early stopping would keep the bare skip law here, the
# read-out 0, and the cell's arrays would go untested)
TINY = ("model.estimator.max_epochs=2", "model.estimator.hidden_size=4", "model.estimator.chunk=16",
        "model.estimator.validation_fraction=0.0")


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return _make_dataset(tmp_path_factory.mktemp("lstm62") / "data")


@needs_cc
@pytest.mark.parametrize("layers", [1, 2])
def test_an_lstm_model_streams_as_replay_in_c_st_and_the_arrays(data, tmp_path, layers):
    stream, tests, _ = deployed(data, "model=lstm", *TINY, f"model.estimator.num_layers={layers}")
    nets = [e for _, e, _ in stream._plan if isinstance(e, LSTM)]
    assert len(nets) == 2 and all(e.net_.head.weight.abs().min() > 0 for e in nets)   # a network
    ss = state_space(stream)                                  # refused before
    assert ss.lstm_target == [0, 1] and ss.lstm_weight == [1.0, 1.0]
    assert (ss.lstm_hidden, ss.lstm_layers) == (4, layers) and ss.clamp_outright == [1, 1]
    assert len(ss.lstm_w_ih[0]) == layers and len(ss.lstm_w_ih[0][0]) == 16    # 4 gates x 4
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM


@needs_cc
def test_a_blend_member_lstm_exports_its_network_times_its_weight(data, tmp_path):
    stream, tests, _ = deployed(data, "model=auto", "model.candidates=[mlr,lstm]",
                                "model.candidate_params={lstm:{max_epochs:2,hidden_size:4,chunk:16,"
                                "validation_fraction:0.0}}",
                                "+model.estimator.chosen={E_X:mlr,E_Z:{mlr:0.7,lstm:0.3}}")
    ss = state_space(stream)                                  # refused before
    assert ss.lstm_target == [1] and ss.lstm_weight == [0.3] and any(ss.lstm_head[0])
    assert ss.provenance["laws"]["E_Z"] == "blend mlr 0.7 + lstm 0.3"
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM


def _exported(data, tmp_path, fmt: str, *model: str):
    return _exported_code(data, tmp_path, fmt, "lstm", *TINY, *model)


@needs_cc
def test_the_export_commands_check_pack_passes_and_the_networks_size_is_said(data, tmp_path,
                                                                           capsys):
    out = _exported(data, tmp_path, "c")
    said = capsys.readouterr().err
    size = (out / "compensator.c").stat().st_size / 1024
    # per net: W_ih 16 x 4 inputs, W_hh 16 x 4, two biases of 16, the read-out 4 and its bias
    assert (f"lstm: 2 network(s) of 1 layer(s), hidden size 4, {2 * (64 + 64 + 32 + 5)} weights "
            f"stepped per sample (double): compensator.c {size:,.0f} KB") in said
    assert "beyond 1 MB" not in said
    exported = json.loads((out / "compensator.json").read_text())
    assert exported["lstm_width"] == 4 and len(exported["lstm_head"][0]) == 4
    # (the test campaigns, and the jump and the freeze the pack plants: cmon76; a dropout: cdrop77;
    # a reading beyond its range and a common step: cmon80)
    assert checked_pack(out).count("stream: check passed: 40 rows") == 7


def test_the_structured_text_of_an_lstm_parses_as_iec_61131_3(data, tmp_path, parsed_block):
    out = _exported(data, tmp_path, "st", "model.estimator.hidden_size=2")
    text = (out / "compensator.st").read_text()
    assert "LSTM_W_IH : ARRAY" in text and "EXP(2.0 * la)" in text
    parses_as_the_parsed_block(text, parsed_block)


# (an lstm within an ATI model, refused here before, exports since exportati63:
# test_export_ati63.py)


def declares_each_once(text: str) -> None:
    """The Structured Text ``text`` declares each variable of its function block once (a PLC's
    compiler refuses a name declared twice)."""
    import re

    head = text.split("VAR CONSTANT", 1)[0]
    names = re.findall(r"^\s+(\w+) : ", head, flags=re.M)
    assert names and len(names) == len(set(names)), sorted(n for n in names if names.count(n) > 1)


def test_the_structured_text_declares_each_variable_once(data):
    """A PLC's compiler refuses a name declared twice (exportrest62 declared ``tr`` LREAL for the
    reference update and DINT for the forests' tree loop; blark and the tests' reader took it)."""
    from thermocomp.apps.deploy.export import exported_files

    stream, _, _ = deployed(data, "model=mlr")
    declares_each_once(exported_files(stream, "st")["compensator.st"])


def test_a_network_whose_code_exceeds_a_megabyte_is_said_to_be_too_large_for_many_plcs():
    from thermocomp.shell.stages.export import PLC_LIMIT_BYTES, _lstm_said

    net = {"lstm_target": [0], "lstm_layers": 1, "lstm_hidden": 1, "lstm_w_ih": [[[1.0], [2.0]]],
           "lstm_w_hh": [[[3.0]]], "lstm_b_ih": [[[0.0]]], "lstm_b_hh": [[[0.0]]],
           "lstm_head": [[1.0]], "lstm_head_bias": [0.5]}
    small = {"compensator.st": "x" * PLC_LIMIT_BYTES, "compensator.json": "y" * (2 * PLC_LIMIT_BYTES)}
    said = _lstm_said(net, small)
    assert said == ("lstm: 1 network(s) of 1 layer(s), hidden size 1, 7 weights stepped per "
                    "sample (double): compensator.st 1,024 KB")
    said = _lstm_said(net, {**small, "compensator.st": "x" * (PLC_LIMIT_BYTES + 1)})
    assert "compensator.st beyond 1 MB: more than many PLCs take" in said
    assert "model.estimator.hidden_size" in said
