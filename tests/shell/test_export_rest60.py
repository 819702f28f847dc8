"""A diagnosed lag's initial-state transient, an ambient step, a lag bank's lag of a diagnosed lag
and effects around an ATI model export exactly (exportrest60).

``thermocomp diagnose`` tries every lag also "from the initial thermal state": extra regressors
``w_k . (c(0) - A0) (1 - exp(-(t - t0)/tau))`` (the sensors' first values less the campaign's
initial ambient, on the directions learned over the training campaigns), and the inputs times a
step of the initial ambient ``x [A0 > A_thr]``; ``export`` refused both by name, a lag-bank
base's lag of a diagnosed lag (a second-order lag), and any effect around an ATI model
(``diagnose ati=cmeans``).  Each is now what the code computes as the served model's
``stream_step`` does: the transient from the first sample of the campaign that has one of the
sensors (one missing there: offset 0), ``A0`` the campaign's initial ambient as an ATI law reads
it, ``t - t0`` on the stream's clock, restarted at each campaign only (not at a gap); the step a
law on ``x`` that counts where ``A0 > A_thr``; the lag of a lag a lag channel on the first lag's
channel (a cascade); around an ATI model, per interval (with its interaction, times ``A0 -
20``).  The C (compiled), the Structured Text, the numpy reference and the JSON read back equal
``replay`` to 1e-9 µm, the clamp acting, a sensor of the transient missing at a campaign's first
rows, a missing time and a gap."""

from __future__ import annotations

import numpy as np
import pytest
from sklearn.base import clone

from covering import covering
from test_export import _compose, needs_cc
from test_export_auto57 import TOLERANCE_UM, _proved, deployed
from test_export_effects59 import LAG, LOWPASS, PRODUCT, _diagnosed, _door, _json_proved
from thermocomp.apps.deploy.export import exported_files, state_space
from thermocomp.apps.diagnose import AugmentedRegressor
from thermocomp.apps.diagnose.features import as_effect
from thermocomp.core.models import MLR, LagBank
from thermocomp.core.models.ati import ATIRegressor
from thermocomp.shell.builders import deploy_stream
from thermocomp.shell.source import read_streamed

# the door's lag from the initial distances of T_a and the door (missing at tests[0]'s first
# two rows: T_a's offset alone there), on one learned direction or one each
INITIAL = {**LAG, "initial_state": ["T_a", "S_door"], "initial_directions": 1}
PER_SENSOR = {**LAG, "initial_state": ["T_a", "T_b"]}
DOOR_ONLY = {**LAG, "initial_state": ["S_door"]}      # no sensor at tests[0]'s first rows
INPUT_INITIAL = {"kind": "dynamics", "transform": "first_order_lag", "column": "T_a",
                 "tau_s": 3600.0, "initial_state": ["T_a", "T_b"], "initial_directions": 2}
LOWPASS_INITIAL = {**LOWPASS, "initial_state": ["T_a", "T_b"], "initial_directions": 1}
STEP = {"kind": "ambient_interval", "transform": "ambient_step", "threshold_c": 23.0}
AMBIENT_LAW = {"kind": "ambient_interval", "transform": "ambient_linear"}


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return _door(tmp_path_factory.mktemp("initial") / "data")


def _exported(data, tmp_path, effects, base=None) -> object:
    stream, tests = _diagnosed(data, effects, base=base)
    # a missing time (one period after the previous sample) and a gap of 3 h (the served model
    # restarts nothing at a gap: the transient runs on; only a campaign's start restarts it)
    tests[0].loc[5, "time"] = float("nan")
    tests[1].loc[30:, "time"] += 3 * 3600.0
    ss = state_space(stream)                                  # refused before
    laws = ss.provenance["laws"]["E_X"]
    banner = exported_files(stream, "c")["compensator.c"].split("*/")[0]
    for e in effects:
        title = as_effect(e).title
        assert title in laws                                      # the effect named
        assert title.replace("°C", " degC") in banner             # (the banner's units)
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM
    assert _json_proved(stream, tests) <= TOLERANCE_UM
    return ss


@needs_cc
@pytest.mark.parametrize("effect, directions", [(INITIAL, 1), (PER_SENSOR, 2), (DOOR_ONLY, 1),
                                                (INPUT_INITIAL, 2), (LOWPASS_INITIAL, 1)],
                         ids=["signal-direction", "signal-per-sensor", "door-only", "input",
                              "lowpass"])
def test_a_lags_initial_state_transient_exports_and_equals_replay(data, tmp_path, effect,
                                                                  directions):
    ss = _exported(data, tmp_path, [effect])
    assert len(ss.initial) == directions
    sensors = [ss.inputs.index(c) for c in effect["initial_state"]]
    assert all(f[0] == effect["tau_s"] and f[1] == sensors for f in ss.initial)
    assert ss.ambient_inputs == [ss.inputs.index("T_amb")]      # A0, as an ATI law reads it


@needs_cc
def test_transients_and_a_step_among_other_effects_equal_replay(data, tmp_path):
    """Each effect's columns in the model's order (a step first, a low-pass's transient after
    its block, the ambient law between, a product after a transient)."""
    ss = _exported(data, tmp_path, [STEP, LOWPASS_INITIAL, AMBIENT_LAW, INITIAL, PRODUCT])
    assert len(ss.initial) == 2 and len(ss.derived) == 2 and sorted(ss.law_ambient) == [0, 0, 1]


@needs_cc
@pytest.mark.parametrize("effects", [[STEP], [STEP, {**STEP, "threshold_c": 21.0}, AMBIENT_LAW]],
                         ids=["one", "two-and-the-ambient-law"])
def test_an_ambient_step_exports_as_a_law_counting_above_its_threshold(data, tmp_path, effects):
    ss = _exported(data, tmp_path, effects)
    steps = sorted(e["threshold_c"] for e in effects if e["transform"] == "ambient_step")
    assert sorted(lo for lo in ss.law_lo if lo > -1e300) == steps


@needs_cc
@pytest.mark.parametrize("effects", [[LAG], [INITIAL, PRODUCT], [LOWPASS, LAG]],
                         ids=["lag", "transient-and-product", "lowpass"])
def test_a_lag_banks_lag_of_a_diagnosed_lag_exports_as_a_cascade(data, tmp_path, effects):
    """The base lag bank lags every feature, the effect's lag too: a lag of that lag's channel
    (``lag_of``, after it: the second-order lag the stream runs), refused before."""
    ss = _exported(data, tmp_path, effects, base=LagBank(n_taus=2))
    cascades = [k for k, src in enumerate(ss.lag_of) if src >= 0]
    assert cascades and all(ss.lag_of[k] < k and ss.lag_of[ss.lag_of[k]] < 0 for k in cascades)


@needs_cc
@pytest.mark.parametrize("effects, interaction", covering(
    "each interval's laws count the effects' columns alike, with or without the interaction",
    effects={"transient-and-step": [INITIAL, STEP],
             "product-lowpass-door": [PRODUCT, LOWPASS_INITIAL, DOOR_ONLY]},
    interaction={"intervals": False, "with-interaction": True}))
def test_effects_around_an_ati_model_export_per_interval(data, tmp_path, effects, interaction):
    """``diagnose ati=cmeans`` puts the effects around the ATI model: each interval's model is
    fitted on the features (with the interaction, on the features times ``A0 - 20`` too), so
    its laws on them count in its interval (the interaction's times ``A0 - 20``)."""
    ati = ATIRegressor(MLR(), n_intervals=2, ambient_interaction=interaction)
    ss = _exported(data, tmp_path, effects, base=ati)
    assert len({(lo, hi) for lo, hi in zip(ss.law_lo, ss.law_hi)}) >= 2 + (STEP in effects)
    assert any(ss.law_ambient) == interaction
    assert ss.provenance["laws"]["E_X"].startswith("ati (A0 <= ")


@needs_cc
@pytest.mark.parametrize("base", [None, ATIRegressor(MLR(), n_intervals=1, ambient_interaction=True)],
                         ids=["mlr", "ati-interaction"])
def test_two_effects_on_one_signal_add_up_in_the_code(data, tmp_path, base):
    """The door's lag and the door as read are one derived input (its change), each effect's
    coefficient on it: both count (``diagnose ati=cmeans`` accepted that pair on a door record,
    seed 6002, and the code kept one of them: 61.8 µm off the served corrections)."""
    raw = {"kind": "signal", "transform": "raw", "column": "S_door"}
    ss = _exported(data, tmp_path, [LAG, raw], base=base)
    assert len(ss.derived) == 1


@needs_cc
def test_a_transient_of_denoised_sensors_and_a_step_equal_replay(data, tmp_path):
    """With the causal FIR denoiser a declared sensor's ``c(0)`` is its filtered first value,
    as the stream's model reads its context (the door, no declared input, as read)."""
    _, tests, comp = deployed(data, "model=mlr", "denoise=emd", pushed="T_a")
    cfg = _compose(f"data.path={data}", "denoise=emd", "track=false", "monitor.adaptive=false",
                   "promote.envelope.pattern=false")
    ds, train_ids, _, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    comp = clone(comp).set_params(estimator=AugmentedRegressor(
        MLR(), effects={"E_X": [PER_SENSOR, INITIAL, STEP]})).fit(train)
    stream = deploy_stream(cfg, comp, train)
    tests[0].loc[[0, 1], "S_door"] = np.nan
    ss = state_space(stream)
    assert len(ss.fir) > 1 and len(ss.initial) == 3
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM

