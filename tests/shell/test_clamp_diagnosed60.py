"""A diagnosed model is clamped by its step gain as a plain one is (clampdiag60).

The training-envelope clamp takes out of a prediction the model's response to an input's excess,
but never more than ``|gain @ e|`` (the excess held for the longest training campaign).  A model
``diagnose`` writes had no step gain and was clamped outright: its lag bank streamed on the
flattened input alone, whose opposed lag weights do not cancel there (a 0.15 K excess on one row
moved a lag-bank base's correction 2.61 µm, bench record ``ambientlaw6003``).  Its features are
linear in the inputs' excess (the ambient law scales ``x`` by the campaign's fixed ``A0``; a
signal's lag, a product, a square read the context, which the clamp does not touch), so its gain
is the base's through them: the deployed correction stays within the plain rule's bound, and the
exported code (C, ST, numpy, JSON) clamps by that gain as replay does."""

from __future__ import annotations

import copy
from dataclasses import replace

import numpy as np
import pytest

from test_export import needs_cc
from test_export_auto57 import PUSH_C, TOLERANCE_UM, _proved
from test_export_diagnosed59 import _diagnosed
from test_export_effects59 import LAG, LOWPASS, PRODUCT, SQUARE, _door, _json_proved
from thermocomp.apps.deploy.export import Simulator, state_space
from thermocomp.apps.deploy.streaming import replay
from thermocomp.core.context import step_gain
from thermocomp.core.frame import ambient_c0
from thermocomp.core.models import ARX, MLR, LagBank
from thermocomp.core.models.ati import ATIRegressor

AMBIENT_LAW = {"kind": "ambient_interval", "transform": "ambient_linear"}
EXCESS_K = 0.15


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return _door(tmp_path_factory.mktemp("clampdiag") / "data")


def _one_row_over(stream, df):
    """``df`` (its push undone) with T_a over its envelope bound by EXCESS_K on one row (the row)."""
    df = df.copy()
    df.loc[len(df) // 2:, "T_a"] -= PUSH_C
    j = stream.columns_.index("T_a")
    row = len(df) // 3
    df.loc[row, "T_a"] = df.loc[0, "T_a"] + stream.envelope.hi[j] + EXCESS_K
    return df, row


@pytest.mark.parametrize("effects", [[AMBIENT_LAW], [AMBIENT_LAW, LAG, PRODUCT, SQUARE]],
                         ids=["ambient-law", "with-context-features"])
def test_a_diagnosed_lag_banks_small_excess_moves_it_within_the_plain_bound(data, effects):
    stream, tests, _ = _diagnosed(data, effects, base=LagBank(n_taus=2))
    df, row = _one_row_over(stream, tests[1])
    off = copy.deepcopy(stream)
    off.policy = "off"
    deployed = replay(stream, df)
    batch = replay(off, df)
    assert deployed["n_clamped"].iloc[row] == 1 and deployed["n_clamped"].sum() == 1
    # the plain rule's bound |gain @ e|, written out: the base lag bank's gain on T_a and, times
    # A0 - 20 (the campaign's initial ambient, as the stream reads it), on its ambient law's T_a
    model = stream._plan[0][1]
    k, j = int(model.n_features_in_), stream.columns_.index("T_a")
    base = model.estimator_.step_gain(None, stream.envelope.horizon_s)
    a0 = ambient_c0(df[[stream.columns_[i] for i in stream._amb_idx]].to_numpy(float)[0])
    bound = abs(base[j] + (a0 - 20.0) * base[k + j]) * EXCESS_K
    moved = np.abs(deployed["E_X"].to_numpy() - batch["E_X"].to_numpy())
    assert moved[row] > 0.0
    assert moved.max() <= bound + 1e-9


@needs_cc
def test_a_lowpass_copy_over_an_arx_base_exports_clamped_by_its_gain(data, tmp_path):
    """gain61: the low-pass copy's lag through an ARX model's delays and feedback had no gain
    (clamped outright: the clamped stream's value whatever the excess); its gain is now the
    difference equation's response to the lag at the horizon, the code's the model's own, and
    the code = replay where the bound takes out less than the outright clamp did."""
    stream, tests, _ = _diagnosed(data, [LOWPASS], base=ARX(ar=True))
    model = stream._plan[0][1]
    k = int(model.n_features_in_)
    # the ARX model reads the copy (a column after the inputs), through its feedback
    assert model.estimator_.ar_coef_ != 0.0 and any(j >= k for j, _ in model.estimator_.terms_)
    ss = state_space(stream)
    gain = step_gain(model, None, stream.envelope.horizon_s)
    assert not ss.clamp_outright
    np.testing.assert_array_equal(np.sum(ss.clamp_gain, axis=0)[:k], gain)
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM
    assert _json_proved(stream, tests) <= TOLERANCE_UM
    outright = _simulated(replace(ss, clamp_outright=[1]), stream, tests)
    assert np.abs(_simulated(ss, stream, tests) - outright).max() > 1.0     # µm: the bound acts


def _simulated(ss, stream, tests) -> np.ndarray:
    """The numpy reference's corrections of ``ss`` over the test campaigns."""
    sim, rows = Simulator(ss), []
    for df in tests:
        sim.reset()
        rows += [sim.step(u, t) for u, t in zip(df[stream.columns_].to_numpy(float), df["time"])]
    return np.array(rows)


@needs_cc
@pytest.mark.parametrize("effects, base", [([AMBIENT_LAW], LagBank(n_taus=2)),
                                           ([AMBIENT_LAW, LOWPASS, LAG, PRODUCT], MLR()),
                                           ([LOWPASS], LagBank(n_taus=2)),
                                           ([AMBIENT_LAW, LOWPASS, LAG], LagBank(n_taus=2))],
                         ids=["lagbank-ambient-law", "mlr-lowpass-and-signals",
                              "lagbank-lowpass", "lagbank-lowpass-and-signals"])
def test_the_export_clamps_a_diagnosed_model_by_its_gain_as_replay(data, tmp_path, effects, base):
    stream, tests = _diagnosed(data, effects, base=base)[:2]
    ss = state_space(stream)
    assert not ss.clamp_outright and np.abs(ss.clamp_gain).max() > 0.0
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM
    assert _json_proved(stream, tests) <= TOLERANCE_UM


@needs_cc
@pytest.mark.parametrize("base", [LagBank(n_taus=2), ARX(ar=True)], ids=["lagbank", "arx"])
def test_a_lowpass_copy_over_an_ati_model_exports_clamped_by_its_gain(data, tmp_path, base):
    """gain61: over an ATI model (its ambient interaction on the copy too) the clamp took the
    clamped stream outright; the gain is its intervals' (the lag passed to each), each interval's
    laws carry theirs, and the code = replay."""
    ati = ATIRegressor(base, n_intervals=2, ambient_interaction=True)
    stream, tests = _diagnosed(data, [LOWPASS, AMBIENT_LAW], base=ati)[:2]
    model = stream._plan[0][1]
    assert model.estimator_.n_intervals_ == 2
    ss = state_space(stream)
    assert not ss.clamp_outright and set(ss.law_ambient) == {0, 1, 2}
    # per campaign, the code's bound is the stream's: the laws' gains at its A0
    for a0 in {float(a) for a in ss.law_hi if abs(a) < 1e300} | {40.0}:
        state = {"ambient_c0": a0, "base": None}
        np.testing.assert_allclose(ss.factors(a0) @ np.array(ss.clamp_gain),
                                   step_gain(model, state, stream.envelope.horizon_s),
                                   rtol=1e-12, atol=1e-12)
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM
    assert _json_proved(stream, tests) <= TOLERANCE_UM
