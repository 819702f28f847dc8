"""The correction guard's rate limit on a stream faster than the training rows (rate71).

The rate is learnt from rows one training period apart; a correction's sample-to-sample jitter
(sensor noise through the model's gains) does not shrink with the step, so a healthy stream at
a fifth of the period was rate-limited (bench_rate71: a lag bank trained on 300 s rows, fed the
60 s DAQ file, 88 events).  The limit spans a step or one training period, the longer.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd

from test_deploy import _library
from thermocomp.apps.deploy import AdaptiveCompensator, StreamingCompensator
from thermocomp.apps.deploy.guard import CorrectionGuard
from thermocomp.apps.deploy.streaming import replay


def _campaign(seed: int, dt: float, hours: float = 5.0) -> pd.DataFrame:
    """A spindle heating up, three sensors read with 0.05 K of noise every ``dt`` s; E_X follows
    the spindle sensor's true temperature."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, hours * 3600 + dt / 2, dt)
    heat = 6.0 * (1 - np.exp(-t / 4000))
    true = np.column_stack([20 + heat, 20 + 0.4 * heat, 20 + 0.2 * np.sin(t / 5000)])
    read = true + rng.normal(0, 0.05, true.shape)
    return pd.DataFrame({"time": t, "T_spindle": read[:, 0], "T_column": read[:, 1],
                         "T_amb": read[:, 2], "E_X": 4.0 * heat + rng.normal(0, 0.1, len(t))})


def test_a_healthy_stream_at_a_fifth_of_the_training_period_is_not_rate_limited():
    train = {f"K{i}": _campaign(i, 300.0) for i in range(4)}
    stream = StreamingCompensator.from_training(_library("mlr").fit(train), train)
    adaptive = AdaptiveCompensator.from_training(stream, train)
    assert adaptive.guard.period_s == 300.0
    test = _campaign(9, 60.0, hours=10.0)
    got = replay(adaptive, test)
    guarded = [e for row in got["events"] for e in json.loads(row) if e.get("target")]
    assert guarded == []          # the code before: rate-limited twice (4 events)
    np.testing.assert_allclose(got["E_X"], replay(stream, test)["E_X"], atol=1e-9)
    # the sample-to-sample jitter is what a per-step limit would have cut: above rate x 60 s
    assert np.abs(np.diff(got["E_X"])).max() > adaptive.guard.max_rate_per_s[0] * 60.0


def test_a_jump_within_a_short_step_is_still_limited_to_one_training_period():
    guard = CorrectionGuard(["E_X"], [-100.0], [100.0], [0.01], 300.0)
    guard.step(np.array([0.0]), np.nan, 0.0)
    out, events = guard.step(np.array([10.0]), 60.0, 60.0)
    assert out[0] == 3.0 and events[0]["to"] == "rate_limited"       # 0.01 µm/s x 300 s
    out, _ = guard.step(np.array([30.0]), 900.0, 960.0)              # a longer step: its own
    assert out[0] == 12.0
    # the fast path of a block takes the same span
    guard.reset()
    guard.step(np.array([0.0]), np.nan, 0.0)
    passed = guard.step_block(np.array([[2.9], [5.8], [9.0]]), np.array([60.0, 60.0, 60.0]),
                              np.zeros(3, bool))
    assert passed == 2
