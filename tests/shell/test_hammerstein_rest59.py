"""A machine state's lags started at rest (``Hammerstein(state_start='rest')``): a run logged
from a soaked machine whose spindle already turns at its first sample (bench_auto_hmc59)."""

from __future__ import annotations

import numpy as np
import pandas as pd
from sklearn.metrics import mean_squared_error

from conftest import stream_context
from thermocomp.core.models import Hammerstein, LagBank
from thermocomp.core.models._dynamics import first_order_lags

PERIOD_S = 60.0
TAU_S = 3 * 3600.0      # the structure's lag: longer than a block, about a run


def _soaked(u: np.ndarray, a: float) -> np.ndarray:
    """A first-order lag of ``u`` from 0 (the machine soaked: no heat before the record)."""
    z, out = 0.0, np.empty_like(u)
    for k, v in enumerate(u):
        z = z if k == 0 else a * z + (1 - a) * v
        out[k] = z
    return out


def _runs(seed: int, n_campaigns: int = 10, n: int = 360):
    """Runs of a soaked machine, each starting at a random speed (0 included); the error is
    the lagged friction heat, the sensors see the hall only; a pallet number (1 / 2) too."""
    rng = np.random.default_rng(seed)
    a = np.exp(-PERIOD_S / TAU_S)
    X, y, frames = [], [], []
    for c in range(n_campaigns):
        rpm = np.repeat(rng.choice([0.0, 4000.0, 8000.0], size=n // 40 + 1), 40)[:n]
        heat = _soaked((rpm / 8000.0) ** 2, a)
        hall = np.cumsum(rng.normal(0, 0.01, n))
        X.append(np.column_stack([hall, hall + rng.normal(0, 0.05, n)]))
        y.append(5.0 * heat + hall + rng.normal(0, 0.05, n))
        frames.append(pd.DataFrame({"campaign": f"C{c}", "time": np.arange(n) * PERIOD_S,
                                    "S_spindle_rpm": rpm, "S_pallet": 1 + np.arange(n) // 90 % 2}))
    return np.vstack(X), np.concatenate(y), pd.concat(frames, ignore_index=True)


def _held_out(state_start: str, seed: int = 0):
    X, y, ctx = _runs(seed)
    train = ctx["campaign"].isin([f"C{i}" for i in range(7)]).to_numpy()
    ham = Hammerstein(lagbank=LagBank(n_taus=4), state_start=state_start)
    ham.fit(X[train], y[train], context=ctx[train].reset_index(drop=True))
    test = ctx[~train].reset_index(drop=True)
    pred = ham.predict(X[~train], context=test)
    return ham, float(np.sqrt(mean_squared_error(y[~train], pred))), X[~train], test, pred


def test_lags_of_a_rest_column_start_at_zero_the_others_at_their_first_value():
    time = np.arange(5) * 60.0
    u = np.column_stack([np.full(5, 2.0), np.full(5, 3.0)])
    for t in (time, time * np.array([1, 1, 1.5, 1, 1])):       # uniform and irregular sampling
        z = first_order_lags(u, t, None, [600.0], rest=np.array([True, False]))
        a = np.exp(-np.diff(t) / 600.0)
        expected = np.r_[0.0, 2.0 * (1 - np.cumprod(a))]
        np.testing.assert_allclose(z[:, 0], expected, rtol=1e-12)
        np.testing.assert_allclose(z[:, 1], 3.0)              # steady start, as before


def test_a_run_started_at_speed_is_predicted_from_rest_not_as_a_constant_offset():
    """The steady start holds each run's first speed in its long lags all run (an offset that
    depends on how the run began); from rest the held-out error is the noise's order."""
    ham, rest, *_ = _held_out("rest")
    _, steady, *_ = _held_out("steady")
    assert ham.rest_states_ == ["S_spindle_rpm"]        # the pallet (1 / 2) has no rest at 0
    assert rest < 0.5 * steady, (rest, steady)


def test_it_streams_as_it_predicts_from_rest():
    ham, _, X, test, batch = _held_out("rest")
    assert test.groupby("campaign")["S_spindle_rpm"].first().gt(0).any()
    np.testing.assert_allclose(stream_context(ham, X, test), batch, rtol=0, atol=1e-9)


def test_a_power_at_rest_in_one_model_and_steady_in_another_exports_as_two():
    # audit106: ATI's one model per interval (cr10066's hammerstein-interval): an interval whose
    # spindle stood still starts its speed's power at rest, one where it always turned steady;
    # the C and ST export refused both, "one exported power has one start"
    from thermocomp.apps.deploy.export.laws import Powers, _powered

    X, y, ctx = _runs(0, n_campaigns=4)
    turning = ctx.assign(S_spindle_rpm=ctx["S_spindle_rpm"].replace(0.0, 2000.0))
    fitted = [Hammerstein(lagbank=LagBank(n_taus=2), state_start="rest", choose_exponents=False)
              .fit(X, y, context=c) for c in (ctx, turning)]
    at_rest, steady = fitted
    assert at_rest.rest_states_ == ["S_spindle_rpm"] and steady.rest_states_ == []
    assert list(at_rest.state_scale_) == list(steady.state_scale_)     # the same power, but its start
    powers = Powers()
    inputs = list(at_rest.state_columns_)
    (_, rest_feats), (_, steady_feats) = (_powered(h, inputs, powers) for h in fitted)
    speed = inputs.index("S_spindle_rpm")
    starts = {k[3] if len(k) > 3 else "first" for k in powers if k[0] == speed}
    assert starts == {"first", "steady"}                     # two features of the speed's power
    assert set(rest_feats) & powers.rest and not set(steady_feats) & powers.rest
    assert not powers.rest & powers.steady
