"""The guard's held-step gain from each campaign's last stream state (guard111c).

``held_gains.stepped_gain`` re-predicted every campaign's whole prefix with each of its p + 1
held steps (lathe-sized set: per-interval lstm 3.2 -> 15.4 s CPU at deploy).  A model whose own
``stream_steps`` starts a block from a state now streams the prefix once and holds the steps from
copies of the state; the gains are the batch ``predict``'s, without calling it.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from thermocomp.apps.deploy.held_gains import _by_predict, stepped_gain
from thermocomp.core.models.arx_rf import ARXRF
from thermocomp.core.models.ati import ATIRegressor
from thermocomp.core.models.lstm import LSTM

ROWS, PERIOD_S, HORIZON_S = 40, 60.0, 600.0


def _training(rng) -> tuple[np.ndarray, np.ndarray, pd.DataFrame]:
    """Four campaigns of three heating inputs, an error with a lag, a door and an ambient each."""
    X, y, ctx = [], [], []
    for k in range(4):
        t = np.arange(ROWS) * PERIOD_S
        lags = np.array([600.0, 1200.0, 2400.0])
        x = (1 + k) * (1 - np.exp(-t[:, None] / lags)) + rng.normal(0, .05, (ROWS, 3))
        X.append(x)
        y.append(2.0 * x[:, 0] - x[:, 1] + 0.5 * np.r_[0, x[:-1, 2]] + rng.normal(0, .05, ROWS))
        ctx.append(pd.DataFrame({"campaign": f"K{k}", "time": t, "ambient_c0": 16.0 + 3 * k,
                                 "S_door": (np.arange(ROWS) // 7 + k) % 2 * 1.0}))
    return np.vstack(X), np.concatenate(y), pd.concat(ctx, ignore_index=True)


MODELS = {"lstm": lambda: LSTM(hidden_size=2, max_epochs=2),
          "ati_lstm": lambda: ATIRegressor(LSTM(hidden_size=2, max_epochs=1), n_intervals=2,
                                           ambient_interaction=True, min_campaigns=1),
          "arx_rf": lambda: ARXRF(forest=None)}


@pytest.mark.parametrize("name", MODELS)
def test_the_held_gain_from_states_is_the_batch_predicts_without_calling_it(name, monkeypatch):
    X, y, ctx = _training(np.random.default_rng(111))
    est = MODELS[name]().fit(X, y, context=ctx)
    ends = [ROWS * (k + 1) - 1 for k in range(4)]
    held, steps = int(HORIZON_S / PERIOD_S), np.vstack([np.zeros(3), np.eye(3)])
    batch = _by_predict(est, X, ctx, zip([e - ROWS + 1 for e in ends], ends), held, PERIOD_S, steps)
    want = np.max(np.abs(batch[:, 1:] - batch[:, :1]), axis=0)
    assert (want > 1e-3).all()
    calls = []
    monkeypatch.setattr(type(est), "predict", lambda self, *a, **k: calls.append(1))
    got = stepped_gain(est, X, ctx, HORIZON_S, PERIOD_S)
    assert not calls                                  # the prefix streamed once, no batch predict
    np.testing.assert_allclose(got, want, rtol=1e-9, atol=0)
