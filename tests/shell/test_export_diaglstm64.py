"""A diagnosed lstm exports with any effect set a diagnosed MLR exports with (exportlstm64).

``diagnose`` around an ``lstm`` base fits its network on ``[x, features]``; ``export`` took such a
model only when its one effect was the ambient law (diaglstm63: the network reading ``[x, x (A0
- 20)]``) and refused any other effect by name ("a diagnosed model on lstm with ...").  The
features are those the code computes for a diagnosed linear base anyway (derived inputs, their
lags, low-pass copies, initial-state transients, the laws' factors of ``A0``), so the network's
first layer now reads them from there: per column of the model a source in the code's ``[x,
lags]`` (``lstm_in``) and the law whose factor multiplies it (``lstm_in_law``).  On
test_export_effects59's door record (T_a pushed out half-way: the clamp acting, as the stream
runs the model on the clamped inputs; the door missing at a start and mid-run) the compiled C,
the Structured Text and the numpy reading equal ``replay`` for each effect set, around an ATI
model's interaction too, and ``thermocomp export``'s check pack passes.
"""

from __future__ import annotations

import numpy as np
import pytest
from sklearn.base import clone

from test_export import _compose, checked_pack, needs_cc, parses_as_the_parsed_block
from test_export_ati63 import ATI, NET, _levels_with_a_door
from test_export_auto57 import TOLERANCE_UM, _proved, deployed
from test_export_effects59 import (
    AMBIENT_LAW,
    INPUT_LAG,
    LAG,
    LOWPASS,
    PRODUCT,
    SQUARE,
    _diagnosed,
    _door,
    _json_proved,
)
from test_export_rest60 import INITIAL, LOWPASS_INITIAL, STEP
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.diagnose import AugmentedRegressor
from thermocomp.core.models.lstm import LSTM
from thermocomp.shell.builders import deploy_stream
from thermocomp.shell.cli import main
from thermocomp.shell.model_store import save_model
from thermocomp.shell.source import read_streamed

RAW = {"kind": "signal", "transform": "raw", "column": "S_door"}
STATE_TIMES_RISES = {"kind": "interaction", "transform": "inputs_product", "column": "S_door"}
# each effect a diagnosed MLR exports with, around the lstm (diaglstm63 refused all but the first)
EFFECT_SETS = {
    "ambient-law": [AMBIENT_LAW],
    "law-and-lag": [AMBIENT_LAW, LAG],
    "square": [SQUARE],
    "step": [STEP],
    "law-twice": [AMBIENT_LAW, AMBIENT_LAW],
    "input-lag": [INPUT_LAG],
    "lag-product-square-raw": [LAG, PRODUCT, SQUARE, RAW],
    "low-pass-law-step": [LOWPASS, AMBIENT_LAW, STEP],
    "initial-state": [INITIAL, LOWPASS_INITIAL],
    "state-times-rises": [STATE_TIMES_RISES, LAG],
}


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    """test_export_effects59's door record."""
    return _door(tmp_path_factory.mktemp("diaglstm64") / "data")


def _net() -> LSTM:
    """test_export_lstm62's tiny network, kept whatever its held-out score."""
    return LSTM(max_epochs=2, hidden_size=4, chunk=16, validation_fraction=0.0)


def _reads_its_features(ss, est) -> None:
    """One network over the model's columns, each a feature of the code: the inputs first (x,
    factor 1), a lag's column a lag of the code, an ambient law's block times ``A0 - 20``."""
    n_x = len(ss.inputs) + len(ss.powers) + len(ss.derived) + len(ss.initial)
    [sources], [laws] = ss.lstm_in, ss.lstm_in_law
    k = int(est.n_features_in_)
    assert len(sources) == len(est.estimator_.x_mean_) == len(ss.lstm_x_mean[0])
    assert all(0 <= s < n_x + len(ss.taus) for s in sources)
    assert ss.law_ambient[laws[0]] == 0 and laws[:k] == [ss.lstm_law[0]] * k
    transforms = [e.transform for e in est.effects_]
    lagged = sum(1 for s in sources if s >= n_x)    # a lag's or a low-pass copy's column
    assert lagged == sum(t == "first_order_lag" for t in transforms) + k * transforms.count(
        "lowpass_inputs")
    powers = [ss.law_ambient[r] for r in laws]
    assert powers.count(1) == k * transforms.count("ambient_linear")
    assert ss.clamp_outright == [1]          # no step gain: clamped outright, as streamed


@needs_cc
@pytest.mark.parametrize("effects", EFFECT_SETS.values(), ids=EFFECT_SETS.keys())
def test_a_diagnosed_lstm_with_any_effect_set_streams_as_replay(data, tmp_path, effects):
    stream, tests = _diagnosed(data, effects, base=_net())
    [(_, est, _)] = stream._plan
    assert isinstance(est, AugmentedRegressor) and type(est.estimator_) is LSTM
    ss = state_space(stream)                                  # refused before (but the first)
    _reads_its_features(ss, est)
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM
    assert _json_proved(stream, tests) <= TOLERANCE_UM


def test_the_network_counts_in_what_the_code_gives(data):
    """The proof above is no proof of a network that adds nothing: its residual moves the
    corrections by far more than the tolerance, and a feature read from another source (the
    lag's column from the signal it lags) moves them too."""
    stream, tests = _diagnosed(data, [LAG, PRODUCT], base=_net())
    ss = state_space(stream)

    def corrections(ss) -> np.ndarray:
        sim, rows = Simulator(ss), []
        for df in tests:
            sim.reset()
            rows += [sim.step(u, t) for u, t in zip(df[stream.columns_].to_numpy(float), df["time"])]
        return np.array(rows)

    own = corrections(ss)
    silent = state_space(stream)
    silent.lstm_weight = [0.0]
    assert np.max(np.abs(own - corrections(silent))) > 1e3 * TOLERANCE_UM
    n_x = len(ss.inputs) + len(ss.powers) + len(ss.derived) + len(ss.initial)
    lag = next(j for j, s in enumerate(ss.lstm_in[0]) if s >= n_x)
    moved = state_space(stream)
    moved.lstm_in[0][lag] = ss.lag_input[ss.lstm_in[0][lag] - n_x]    # its lag's input instead
    assert np.max(np.abs(own - corrections(moved))) > 1e3 * TOLERANCE_UM


@pytest.fixture(scope="module")
def levels(tmp_path_factory):
    """test_export_ati63's record, with its plain ATI lstm's pushed test campaigns and
    compensator (``deployed`` once: both effect sets clone it, the tests get copies)."""
    data = _levels_with_a_door(tmp_path_factory.mktemp("diaglstm64_ati") / "data")
    _, tests, ati = deployed(data, "model=lstm", *NET, *ATI, pushed="T_a")
    return data, tests, ati


def _ati_diagnosed(levels, effects):
    """``diagnose ati=cmeans`` around lstm: each interval's network on ``[Z, Z (A0 - 20)]``
    (with the interaction), ``Z`` the inputs and the effects' features."""
    data, tests, ati = levels
    tests = [df.copy() for df in tests]
    cfg = _compose(f"data.path={data}", "track=false", "monitor.adaptive=false",
                   "promote.envelope.pattern=false")
    ds, train_ids, _, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    comp = clone(ati).set_params(estimator=AugmentedRegressor(ati.estimator,
                                                              effects={"E_X": effects}))
    return deploy_stream(cfg, comp.fit(train), train), tests


@needs_cc
@pytest.mark.parametrize("effects", [[AMBIENT_LAW], [LAG, AMBIENT_LAW, STEP]],
                         ids=["ambient-law", "lag-law-step"])
def test_effects_around_an_ati_lstms_interaction_stream_as_replay(levels, tmp_path, effects):
    """The ambient law's block times the interaction is ``x (A0 - 20)^2``, the laws' own factor."""
    stream, tests = _ati_diagnosed(levels, effects)
    est = stream._plan[0][1]
    assert all(est.estimator_.interactions_)
    ss = state_space(stream)                                  # refused before
    assert len(ss.lstm_target) == est.estimator_.n_intervals_
    powers = {ss.law_ambient[r] for laws in ss.lstm_in_law for r in laws}
    assert powers == {0, 1, 2}
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM


@needs_cc
def test_the_export_commands_check_pack_passes(data, tmp_path):
    """``thermocomp export`` of the saved model (a lag, a product, a low-pass copy and the
    ambient law): its pack, run on the compiled ``stream``, passes."""
    _, _, comp = _diagnosed(data, [LAG, PRODUCT, LOWPASS, AMBIENT_LAW], base=_net(),
                            with_model=True)
    pkl = save_model(comp, tmp_path / "model.pkl")
    out = tmp_path / "code"
    assert main(["export", f"data.path={data}", f"export.model={pkl}", "export.format=c",
                 f"out={out}", "track=false"]) == 0               # refused before
    assert "stream: check passed" in checked_pack(out)


def test_its_structured_text_parses_as_iec_61131_3(data, parsed_block):
    stream, _ = _diagnosed(data, [LAG, AMBIENT_LAW], base=_net())
    text = exported_files(stream, "st")["compensator.st"]         # refused before
    assert "LSTM_IN : ARRAY" in text and "LSTM_LAG_FROM" in text
    parses_as_the_parsed_block(text, parsed_block)
