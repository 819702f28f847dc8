"""The training envelope of a deployed model with memory (``promote.envelope.policy=clamp``).

The clamp takes the model's response to an input's excess over its bound out of the
prediction, never more than the response to that excess held for the longest training
campaign (:mod:`thermocomp.apps.deploy.streaming`): a lag model's dynamics are not distorted
by an input a little out of range, and an input far out is still clamped.

These machines read one or two inputs that training moved independently: their training
pattern spans every input and the default gate (``promote.envelope.pattern``) would pass every
excursion, so the clamp's arithmetic is checked with ``pattern=False`` (every excursion
clamped); the gate itself: tests/shell/test_envelope_pattern.py.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from test_deploy import ARStub
from test_protocol import _door_problem
from thermocomp.apps.deploy import StreamingCompensator, replay
from thermocomp.apps.deploy.export import Simulator, state_space
from thermocomp.apps.diagnose import AugmentedRegressor
from thermocomp.core.compensator import Compensator
from thermocomp.core.context import step_gain
from thermocomp.core.models import ARX, LSTM, MLR, Hammerstein, LagBank
from thermocomp.core.models.ati import ATIRegressor
from thermocomp.core.models.blend import Blend

DT_S = 60.0
ROWS = 480


def _lag(x: np.ndarray, tau_s: float) -> np.ndarray:
    out, z, a = np.empty_like(x), x[0], np.exp(-DT_S / tau_s)
    for i, v in enumerate(x):
        z = a * z + (1 - a) * v
        out[i] = z
    return out


def _band_pass(seed: int, amplitude: float) -> pd.DataFrame:
    """The ambient swings (2 h period); the structure answers its changes only while they
    last (a band-pass response, nothing at steady state)."""
    rng = np.random.default_rng(seed)
    t = np.arange(ROWS) * DT_S
    amb = 20 + amplitude * np.sin(2 * np.pi * t / 7200.0) + 0.01 * rng.standard_normal(ROWS)
    e = 6.0 * (_lag(amb, 600.0) - _lag(amb, 3000.0)) + 0.02 * rng.standard_normal(ROWS)
    return pd.DataFrame({"time": t, "T_amb": amb, "E_X": e})


def _heated(seed: int) -> pd.DataFrame:
    """A sensor heated by steps of power, a swinging ambient; the error follows the sensor."""
    rng = np.random.default_rng(seed)
    t = np.arange(ROWS) * DT_S
    power = np.repeat(rng.uniform(0.3, 1.0, ROWS // 120 + 1), 120)[:ROWS]
    t1 = 20 + 6 * _lag(power, 2400.0)
    amb = 20 + np.sin(2 * np.pi * t / 14400.0 + seed)
    e = 4.0 * _lag(t1 - t1[0], 1800.0) + 0.02 * rng.standard_normal(ROWS)
    return pd.DataFrame({"time": t, "T_1": t1, "T_amb": amb, "E_X": e})


def _rmse(r) -> float:
    return float(np.sqrt(np.mean(np.square(r))))


def _clipped(stream: StreamingCompensator, df: pd.DataFrame) -> pd.DataFrame:
    """``df`` with every input clamped to the envelope (in the first-sample frame)."""
    env, out = stream.envelope, df.copy()
    for j, c in enumerate(env.columns):
        first = df[c].iloc[0] if stream._is_ref[j] else 0.0
        out[c] = first + np.clip(df[c] - first, env.lo[j], env.hi[j])
    return out


def _held(stream: StreamingCompensator, comp: Compensator, df: pd.DataFrame) -> np.ndarray:
    """Per row, how far the clamp may take the prediction from the model's own: the response to
    the row's excess held for the horizon, back in range the last out-of-range row's."""
    m = comp.stacked({"c": df}, targets=[]).X.to_numpy()
    excess = m - np.clip(m, stream.envelope.lo, stream.envelope.hi)
    held = np.abs(excess @ step_gain(comp.estimators_["E_X"], None, stream.envelope.horizon_s))
    return pd.Series(np.where(excess.any(axis=1), held, np.nan)).ffill().fillna(0.0).to_numpy()


def test_a_lag_bank_a_little_out_of_range_streams_as_scored():
    """The ambient swings 1.5 times as far as in training: the lag bank's opposed weights on
    several time constants stay in balance (clamping the signal broke it: 0.45 µm against
    0.07 scored)."""
    train = {f"K{k}": _band_pass(k, 1.0) for k in range(3)}
    comp = Compensator(LagBank(n_taus=6)).fit(train)
    stream = StreamingCompensator.from_training(comp, train, pattern=False)
    test = _band_pass(9, 1.5)
    out = replay(stream, test)
    assert (out["n_clamped"] > 0).sum() > 100                 # the envelope acts
    batch = comp.predict({"c": test})["c"]["E_X"].to_numpy()
    measured = comp.measured({"c": test})["c"]["E_X"].to_numpy()
    assert _rmse(measured - out["E_X"]) < 1.2 * _rmse(measured - batch)
    # never further from the model's own prediction than the excess held for the horizon is worth
    assert stream.envelope.horizon_s == pytest.approx((ROWS - 1) * DT_S)
    assert (np.abs(out["E_X"].to_numpy() - batch) <= _held(stream, comp, test) + 1e-9).all()
    clamped = comp.predict({"c": _clipped(stream, test)})["c"]["E_X"].to_numpy()
    assert np.abs(out["E_X"].to_numpy() - clamped).max() > 0.1     # the limit is what acts
    sim = Simulator(state_space(stream))                            # and the exported code does it
    exported = [-sim.step(u, t)[0] for u, t in zip(test[stream.columns_].to_numpy(float), test["time"])]
    np.testing.assert_allclose(exported, out["E_X"], atol=1e-9)


def test_an_input_far_out_is_still_clamped():
    """A sensor 40 K beyond anything in training: the correction is the one on the clamped
    inputs, not the model's extrapolation (taking the held response out at once, without the
    clamped stream, reversed it by 145 µm after the step)."""
    train = {f"K{k}": _heated(k) for k in range(4)}
    comp = Compensator(LagBank(n_taus=6)).fit(train)
    stream = StreamingCompensator.from_training(comp, train, pattern=False)
    hot = _heated(9)
    hot.loc[ROWS // 2:, "T_1"] += 40.0
    deployed = replay(stream, hot)["E_X"].to_numpy()
    unclamped = comp.predict({"c": hot})["c"]["E_X"].to_numpy()
    clamped = comp.predict({"c": _clipped(stream, hot)})["c"]["E_X"].to_numpy()
    far = np.abs(unclamped - clamped).max()
    assert far > 100.0
    assert np.abs(deployed - clamped).max() < 0.05 * far


@pytest.mark.parametrize("model", [MLR(), ARX(ar=True, delays=(0, 2)), LagBank(n_taus=4, ar=True),
                                   ARStub()], ids=["mlr", "arx-ar", "lagbank-ar", "no-step-gain"])
def test_every_family_streams_out_of_range(model):
    """A static model, or one without a step gain, is streamed on the clamped inputs; every
    other stays within its held response of its own prediction (back in range: the excess's at
    its last sample, so that the memory of an excess that ends at once is taken out as it decays)."""
    train = {f"K{k}": _heated(k) for k in range(4)}
    comp = Compensator(model).fit(train)
    stream = StreamingCompensator.from_training(comp, train, pattern=False)
    hot = _heated(9)
    hot.loc[200:300, "T_1"] += 8.0
    out = replay(stream, hot)
    deployed = out["E_X"].to_numpy()
    clamped = comp.predict({"c": _clipped(stream, hot)})["c"]["E_X"].to_numpy()
    batch = comp.predict({"c": hot})["c"]["E_X"].to_numpy()
    gain = step_gain(comp.estimators_["E_X"], None, stream.envelope.horizon_s)
    assert (out["n_clamped"] > 0).any()
    if gain is None or isinstance(model, MLR):
        np.testing.assert_allclose(deployed, clamped, atol=1e-9)
        return
    assert (np.abs(deployed - batch) <= _held(stream, comp, hot) + 1e-9).all()
    rows = np.arange(len(hot))
    np.testing.assert_allclose(deployed[rows < 200], batch[rows < 200], atol=1e-9)   # as scored
    # the 8 K end at once (a sensor's offset gone): what they left in the lags and the AR feedback
    # is taken out as it decays, the correction the clamped inputs' (with the sample's bound, 0 in
    # range, it had been the model's own: 29.9 µm off the healthy stream after the return, now 19.0)
    np.testing.assert_allclose(deployed[rows > 300], clamped[rows > 300], atol=1e-9)


def _step_response(est, j: int, n: int, rows: int, ambient_c0: float = 20.0) -> float:
    """Change of ``est``'s streamed prediction after ``rows`` samples (60 s apart) of a unit
    step of input ``j`` (of ``n``) begun one sample after the stream's start."""
    def run(step: float) -> float:
        state, y = None, 0.0
        for k in range(rows + 1):
            row = {"campaign": "S", "time": k * 60.0, "ambient_c0": ambient_c0, "S_door": 0.0}
            x = np.zeros(n)
            x[j] = step if k > 0 else 0.0
            state = est.stream_init(row) if state is None else state
            y, state = est.stream_step(x, state, row)
        return y
    return run(1.0) - run(0.0)


STEP_GAINS = {
    "MLR": MLR, "ARX ar": lambda: ARX(ar=True, delays=(0, 2)), "LagBank": lambda: LagBank(n_taus=3),
    "Hammerstein": lambda: Hammerstein(lagbank=LagBank(n_taus=3), states=["S_door"]),
    "ATI(ARX ar)": lambda: ATIRegressor(ARX(ar=True), n_intervals=3),
    "Blend(MLR, LagBank)": lambda: Blend({"mlr": MLR(), "lagbank": LagBank(n_taus=3)},
                                         {"mlr": 0.3, "lagbank": 0.7}),
    "LSTM": lambda: LSTM(hidden_size=4, max_epochs=2),
}


@pytest.mark.parametrize("name", sorted(STEP_GAINS))
def test_the_step_gain_is_the_held_step_response(name):
    """What the clamp takes out is what the model streams: a unit step held for the horizon
    changes the prediction by the step gain, through every wrapper (none for a model that is
    not linear in its inputs)."""
    X, y, context = _door_problem(seed=1)
    est = STEP_GAINS[name]().fit(X, y, context=context)
    rows = 600
    state = est.stream_init({"campaign": "S", "time": 0.0, "ambient_c0": 20.0, "S_door": 0.0})
    gain = step_gain(est, state, rows * 60.0)
    if name == "LSTM":
        assert gain is None
        return
    held = [_step_response(est, j, X.shape[1], rows) for j in range(X.shape[1])]
    np.testing.assert_allclose(gain, held, rtol=1e-6, atol=1e-9)


# clampdiag60: a diagnosed model's gain through its features (the base's on x, on its ambient
# law's and step's blocks times the campaign's factor, on a low-pass copy over a static base)
DOOR_LAG = {"kind": "signal", "transform": "first_order_lag", "column": "S_door", "tau_s": 600.0}
DIAGNOSED_GAINS = {
    "lagbank ambient law": (lambda: LagBank(n_taus=3),
                            [{"kind": "ambient_interval", "transform": "ambient_linear"}]),
    "lagbank ambient step": (lambda: LagBank(n_taus=3),
                             [{"kind": "ambient_interval", "transform": "ambient_step",
                               "threshold_c": 18.0}]),
    "lagbank door lag, square": (lambda: LagBank(n_taus=3),
                                 [DOOR_LAG, {"kind": "nonlinear", "transform": "square",
                                             "column": "S_door"}]),
    "mlr low-pass, ambient law": (MLR, [{"kind": "dynamics", "transform": "lowpass_inputs",
                                         "tau_s": 5400.0},
                                        {"kind": "ambient_interval", "transform": "ambient_linear"}]),
    # exportati60: a low-pass copy over a lag bank, its lags of it cascades (one tau the bank's
    # own in the second: the equal-tau form), and over a Hammerstein model
    "lagbank low-pass, ambient law": (lambda: LagBank(n_taus=3),
                                      [{"kind": "dynamics", "transform": "lowpass_inputs",
                                        "tau_s": 5400.0},
                                       {"kind": "ambient_interval", "transform": "ambient_linear"}]),
    "lagbank low-pass at its own taus": (lambda: LagBank(n_taus=2, tau_min_s=600.0, tau_max_s=3600.0),
                                         [{"kind": "dynamics", "transform": "lowpass_inputs",
                                           "tau_s": 3600.0}, DOOR_LAG]),
    "hammerstein low-pass": (lambda: Hammerstein(lagbank=LagBank(n_taus=2), states=["S_door"]),
                             [{"kind": "dynamics", "transform": "lowpass_inputs", "tau_s": 1800.0}]),
}


@pytest.mark.parametrize("name", sorted(DIAGNOSED_GAINS))
def test_a_diagnosed_models_step_gain_is_its_held_step_response(name):
    """The diagnosed model's gain (None before: clamped outright) is its streamed response to a
    unit step held for the horizon, in a campaign whose initial ambient (24 °C) switches its
    ambient law and step on."""
    X, y, context = _door_problem(seed=1)
    base, effects = DIAGNOSED_GAINS[name]
    est = AugmentedRegressor(base(), effects=effects).fit(X, y, context=context)
    rows, a0 = 600, 24.0
    state = est.stream_init({"campaign": "S", "time": 0.0, "ambient_c0": a0, "S_door": 0.0})
    gain = step_gain(est, state, rows * 60.0)
    held = [_step_response(est, j, X.shape[1], rows, a0) for j in range(X.shape[1])]
    np.testing.assert_allclose(gain, held, rtol=1e-6, atol=1e-9)
