"""A diagnosed state times the inputs' rises around an ATI model exports (exportprod65).

``inputs_product`` (diagpos61: a state ``c`` times the rise ``x_i - x_i(0)`` of every model
input) exported around a plain base since export62, and was refused by name around an ATI model
(``diagnose ati=cmeans``): "its clamp's gain: a state's value times an ATI interval's: not held".
It is held the way the plain one is: the stream's gain is the ATI model's gain terms (per
interval of the campaign's initial ambient ``A0``, the interaction's times ``A0 - 20``), and the
part the state's held value multiplies (``held_gain_terms``) is a set of such terms too, each
put on the law of its interval and power (``gain_by`` -> ``clamp_state_gain``), as the laws'
own gains are; the derived inputs are each interval's laws' columns as any diagnosed feature's.
No second emitter: the C, the ST and the numpy reference are export62's and exportati63's.

On test_export_inputs_product62's gantry (a saddle's position the lever of a rail's rise), a
rail sensor pushed 30 K out half-way (the clamp acting, its bound grown by the position held
before the first excess) and each test campaign's temperatures shifted so that its initial
ambient lies outside the train campaigns' (the first interval's laws and the interaction's
``A0 - 20`` extrapolated), the compiled C, the Structured Text and the numpy reading equal
``replay`` for every family that exports within an ATI model, with and without the interaction;
the adaptive code (``adapt.method=bias``) learns from reference measurements as the served model.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from sklearn.ensemble import RandomForestRegressor

from cbuild import LEVEL
from conftest import copied_once
from covering import covering
from test_export import (
    StructuredText,
    _compiled,
    _streamed,
    checked_pack,
    needs_cc,
    parses_as_the_parsed_block,
)
from test_export_ati57 import CAMPAIGNS
from test_export_auto57 import _proved
from test_export_effects59 import AMBIENT_LAW, _json_proved
from test_export_guard import EVERY, OFFSET_UM, _rows, _served, _simulated, _st
from test_export_inputs_product62 import PRODUCT, _diagnosed, _gantry
from test_export_lstm62 import declares_each_once
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.deploy.streaming import replay
from thermocomp.core.models import ARX, ARXRF, MLR, PCR, Hammerstein, LagBank
from thermocomp.core.models.ati import ATIRegressor
from thermocomp.core.models.lstm import LSTM
from thermocomp.shell.cli import main
from thermocomp.shell.model_store import save_model

# float64 in another order than replay's: 5.7e-13 µm the largest measured (corrections of
# hundreds of µm); the other export tests' 1e-9 would hide a term of a few 1e-10
TOLERANCE_UM = 1e-11
FAMILIES = {
    "mlr": MLR,
    "pcr": PCR,
    "arx": lambda: ARX(ar=True),
    "lagbank": lambda: LagBank(n_taus=2),
    # the position's power entering whatever its CV (it chose none on this record: a lag bank)
    "hammerstein": lambda: Hammerstein(lagbank=LagBank(n_taus=2), exponents=(1.0,),
                                       choose_exponents=False),
    "arx_rf": lambda: ARXRF(state_column="S_y_pos", forest=RandomForestRegressor(
        n_estimators=4, min_samples_leaf=5, random_state=0)),
    # test_export_lstm62's tiny network, kept whatever its held-out score
    "lstm": lambda: LSTM(max_epochs=2, hidden_size=4, chunk=16, validation_fraction=0.0),
}
SHIFT_C = 8.0       # beyond the train campaigns' ambients, below the coldest and above the warmest


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return _gantry(tmp_path_factory.mktemp("atiprod65") / "data")


@copied_once
def _around_ati(data, family: str, interaction: bool, *overrides, effects=(PRODUCT,),
                pushed_from="half", adaptive: bool = False):
    """``(stream, test campaigns, compensator)``: the diagnosed model ``diagnose ati=cmeans``
    builds (the effects around an ATI model of two intervals of ``family``), T_a pushed out
    half-way, each test campaign's temperatures shifted out of the train campaigns' ambients.
    A deep copy, made once per arguments (three tests read the lag bank's with the interaction)."""
    ati = ATIRegressor(FAMILIES[family](), n_intervals=2, ambient_interaction=interaction)
    stream, tests, comp = _diagnosed(data, list(effects), ati, *overrides, pushed_from=pushed_from,
                                     adaptive=adaptive)
    trained = [a0 for _, split, a0 in CAMPAIGNS if split == "train"]
    for df in tests:
        cold = df["T_amb"].iloc[0] < np.mean(trained)
        for c in ("T_a", "T_b", "T_amb"):
            df[c] += -SHIFT_C if cold else SHIFT_C
        assert not min(trained) <= df["T_amb"].iloc[0] <= max(trained)
    return stream, tests, comp


def _corrections(ss, stream, tests) -> np.ndarray:
    sim, rows = Simulator(ss), []
    for df in tests:
        sim.reset()
        rows += [sim.step(u, t) for u, t in zip(df[stream.columns_].to_numpy(float), df["time"])]
    return np.array(rows)


@needs_cc
@pytest.mark.parametrize("family, interaction", covering(
    "the state's gain is put on each interval's laws (and each power of A0 - 20) alike, whatever "
    "family fitted them", family=list(FAMILIES),
    interaction={"intervals": False, "interaction": True}))
def test_a_state_times_the_rises_around_an_ati_model_streams_as_replay(data, tmp_path, family,
                                                                      interaction):
    stream, tests, comp = _around_ati(data, family, interaction)
    [(_, est, _)] = stream._plan
    assert all(type(e) is type(FAMILIES[family]()) for e in est.estimator_.estimators_)
    assert est.estimator_.n_intervals_ == 2 and all(est.estimator_.interactions_) == interaction
    ss = state_space(stream)                                   # refused before
    state, k = ss.inputs.index("S_y_pos"), len(stream.compensator.inputs_)
    assert ss.derived == [[state, j, 0, 1] for j in range(k)] and ss.derived_clamped == [1] * k
    assert "interaction:S_y_pos product(model inputs' rises)" in ss.provenance["laws"]["E_X"]
    assert [ss.inputs[j] for j in ss.ambient_inputs] == ["T_amb"]
    assert bool(ss.powers) == (family == "hammerstein")       # the position's, beside
    if family in ("arx_rf", "lstm"):          # no step gain: clamped outright, as streamed
        assert ss.clamp_outright == [1]
    else:
        # the state's gain per interval (and per power of A0 - 20): on a law of each
        assert ss.clamp_states == [[state, 0]] and not ss.clamp_outright
        gained = {(ss.law_lo[r], ss.law_ambient[r]) for r, g in enumerate(ss.clamp_state_gain)
                  if np.abs(g).max() > 0.0}
        assert len({lo for lo, _ in gained}) == 2
        assert {p for _, p in gained} == ({0, 1} if interaction else {0})
        # and it moves the corrections: without it the bound is the state-0 gain's
        still = state_space(stream)
        still.clamp_state_gain = np.zeros_like(ss.clamp_state_gain).tolist()
        expected = np.vstack([-replay(stream, df)[stream.targets_].to_numpy(float) for df in tests])
        assert np.max(np.abs(_corrections(still, stream, tests) - expected)) > 1e3 * TOLERANCE_UM
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM    # C, ST, numpy: as replay
    assert _json_proved(stream, tests) <= TOLERANCE_UM


@needs_cc
@pytest.mark.parametrize("family", ["mlr", "lagbank"])
def test_with_the_ambient_law_under_the_interaction_too(data, tmp_path, family):
    """The ambient law's block under the interaction counts ``(A0 - 20)^2`` (exportati60)."""
    stream, tests, _ = _around_ati(data, family, True, effects=(PRODUCT, AMBIENT_LAW))
    ss = state_space(stream)                                   # refused before
    assert set(ss.law_ambient) == {0, 1, 2} and ss.clamp_states
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM


@needs_cc
def test_a_campaign_out_at_its_first_sample_is_clamped_outright_as_the_stream_does(data, tmp_path):
    """Inputs in the absolute frame, T_a out from the first sample: no state value held yet, the
    target clamped outright for that campaign (the other out half-way: the held value's gain)."""
    stream, tests, _ = _around_ati(data, "lagbank", True, "data.reference=none", pushed_from=0)
    assert state_space(stream).clamp_state_first == [1]
    tests[0]["T_a"] += np.linspace(0.0, 30.0, len(tests[0]))
    tests[1].loc[:len(tests[1]) // 2 - 1, "T_a"] -= 30.0
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM
    assert _json_proved(stream, tests) <= TOLERANCE_UM


@needs_cc
def test_the_adaptive_code_learns_a_bias_around_it_as_the_served_model(data, tmp_path):
    """Healthy test campaigns (shifted out of the trained ambients), every EVERY-th row a
    reference measurement of a machine whose error moved by OFFSET_UM: the C, the ST and the
    numpy reference learn the bias as the served model does."""
    deployed_, tests, _ = _around_ati(data, "lagbank", True, "adapt.method=bias", adaptive=True,
                                      pushed_from=None)
    targets, cols = deployed_.targets_, deployed_.columns_
    references = []
    for df in tests:
        e = df[targets].to_numpy(float) + OFFSET_UM
        e[np.arange(len(df)) % EVERY != EVERY - 1] = np.nan
        references.append(e)
    expected = _served(deployed_, tests, references)
    assert np.max(np.abs(expected - _served(deployed_, tests, [np.full_like(e, np.nan)
                                                                for e in references]))) > OFFSET_UM / 2
    ss = state_space(deployed_)                                # refused before
    assert ss.adapt == "bias" and ss.clamp_states and set(ss.law_ambient) == {0, 1}
    text = _rows([df.assign(**{t: e[:, i] for i, t in enumerate(targets)})
                  for df, e in zip(tests, references)], [*cols, *targets])
    got = _streamed(_compiled(deployed_, tmp_path, LEVEL), text)
    assert np.max(np.abs(got.to_numpy(float) - expected)) <= TOLERANCE_UM
    assert np.max(np.abs(_simulated(ss, tests, cols, references) - expected)) <= TOLERANCE_UM
    fb = StructuredText(exported_files(deployed_, "st")["compensator.st"])
    assert np.max(np.abs(_st(fb, tests, cols, references) - expected)) <= TOLERANCE_UM


def test_its_structured_text_declares_each_variable_once_and_parses(data, parsed_block):
    stream, _, _ = _around_ati(data, "lagbank", True)
    text = exported_files(stream, "st")["compensator.st"]      # refused before
    assert "STATE_GAIN" in text and "DERIVED_CLAMPED" in text
    declares_each_once(text)
    parses_as_the_parsed_block(text, parsed_block)


@needs_cc
def test_the_export_command_writes_it_and_its_check_pack_passes(data, tmp_path):
    """``thermocomp export`` of the model.pkl, the default deployment (adaptive): exit 2 naming
    the effect before; now the C compiles with warnings as errors and the pack passes."""
    _, _, comp = _around_ati(data, "lagbank", True)
    out = tmp_path / "code"
    assert main(["export", f"data.path={data}", f"export.model={save_model(comp, tmp_path / 'm.pkl')}",
                 "export.format=c", f"out={out}", "track=false"]) == 0
    banner = (out / "compensator.c").read_text().split("*/")[0]
    assert "interaction:S_y_pos product(model inputs' rises) (absolute)" in banner
    # (the test campaigns, and the jump and the freeze the pack plants: cmon76; a dropout: cdrop77;
    # a reading beyond its range and a common step: cmon80)
    assert checked_pack(out).count("stream: check passed: 50 rows") == 7


@needs_cc
def test_with_the_ambient_given_at_a_campaigns_start_its_check_pack_passes(tmp_path):
    """No ambient sensor: the ATI model's ``A0`` is each campaign's manifest ``ambient_c``
    (exportrest62's ``ambient_given``), the pack carrying it per campaign."""
    root = _gantry(tmp_path / "data")
    for f in root.glob("K*.csv"):
        pd.read_csv(f).drop(columns=["T_amb"]).to_csv(f, index=False)
    stream, _, comp = _diagnosed(root, [PRODUCT], ATIRegressor(LagBank(n_taus=2), n_intervals=2,
                                                               ambient_interaction=True))
    ss = state_space(stream)                                   # refused before
    assert ss.ambient_given and not ss.ambient_inputs and ss.clamp_states
    out = tmp_path / "code"
    assert main(["export", f"data.path={root}", f"export.model={save_model(comp, tmp_path / 'm.pkl')}",
                 "export.format=c", f"out={out}", "track=false"]) == 0
    assert checked_pack(out).count("stream: check passed: 50 rows") == 2
