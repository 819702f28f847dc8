"""The guard's rate limit judges the model's own step, not the envelope clamp's (guard96).

On a climate room ramped past training (audit95's cr9762) every rate-limited row was one where
the envelope clamp switched on or off, its pattern gate on its threshold: a step of the
deployment's own, reported as a fault 2-9 times a cell on a healthy record.  The output is still
paced; an event says the model moved too fast (bench_guard96.py).
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd

from test_deploy import _library
from thermocomp.apps.deploy import AdaptiveCompensator, StreamingCompensator
from thermocomp.apps.deploy.guard import CorrectionGuard
from thermocomp.apps.deploy.streaming import replay


def _campaign(seed: int, hours: float = 5.0) -> pd.DataFrame:
    """A spindle heating up, read every 300 s with 0.005 K of noise: the spindle and column
    sensors move together (the envelope's training pattern); E_X follows the spindle."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, hours * 3600 + 150, 300.0)
    heat = 6.0 * (1 - np.exp(-t / 4000))
    true = np.column_stack([20 + heat, 20 + 0.4 * heat, 20 + 0.2 * np.sin(t / 5000)])
    read = true + rng.normal(0, 0.005, true.shape)
    return pd.DataFrame({"time": t, "T_spindle": read[:, 0], "T_column": read[:, 1],
                         "T_amb": read[:, 2], "E_X": 4.0 * heat + rng.normal(0, 0.1, len(t))})


def _guard() -> CorrectionGuard:
    guard = CorrectionGuard(["E_X"], [-100.0], [100.0], [0.01], 300.0)   # 3 µm a period
    guard.step(np.array([0.0]), np.nan, 0.0, take=np.array([0.0]))
    return guard


def test_a_step_the_clamp_made_is_paced_without_an_event():
    guard = _guard()
    # the model's own correction stays at 0.5; the clamp stops taking 9.5 out of it
    out, events = guard.step(np.array([10.0]), 300.0, 300.0, take=np.array([-9.5]))
    assert out[0] == 3.0 and events == []       # 55f940b8: rate_limited (no take: TypeError)
    out, events = guard.step(np.array([10.0]), 300.0, 600.0, take=np.array([-9.5]))
    assert out[0] == 6.0 and events == []
    assert guard.changed_.tolist() == [2]       # the rows whose correction it changed


def test_the_models_own_jump_is_still_a_rate_limited_event():
    guard = _guard()
    out, events = guard.step(np.array([10.0]), 300.0, 300.0, take=np.array([0.0]))
    assert out[0] == 3.0 and [e["to"] for e in events] == ["rate_limited"]
    # a jump while the clamp also switches: the model's part alone is beyond the limit
    guard = _guard()
    out, events = guard.step(np.array([10.0]), 300.0, 300.0, take=np.array([-4.0]))
    assert out[0] == 3.0 and [e["to"] for e in events] == ["rate_limited"]
    # no take given (a guard stepped by hand, older callers): judged on the output, as before
    guard = CorrectionGuard(["E_X"], [-100.0], [100.0], [0.01], 300.0)
    guard.step(np.array([0.0]), np.nan, 0.0)
    assert [e["to"] for e in guard.step(np.array([10.0]), 300.0, 300.0)[1]] == ["rate_limited"]


def _gate_edge(env, s: float, j_s: int, j_c: int) -> float:
    """The column reading at which the sample (spindle ``s``, column c, ambient 0; model frame)
    leaves the envelope's training pattern, by bisection between on it and off it."""
    x = np.zeros(len(env.columns))
    lo, hi = 0.4 * s, -3.0 * s                  # on the pattern (column follows), far off it
    x[j_s] = s
    for _ in range(60):
        x[j_c] = (lo + hi) / 2
        lo, hi = (lo, x[j_c]) if env.leaves_pattern(x) else (x[j_c], hi)
    return (lo + hi) / 2


def test_a_healthy_stream_whose_clamp_chatters_reports_no_guard_event():
    train = {f"K{i}": _campaign(i) for i in range(4)}
    stream = StreamingCompensator.from_training(_library("mlr").fit(train), train)
    # a bound wide enough for the hotter state (margin 1.0): the rate limit alone is judged here
    guard = AdaptiveCompensator.from_training(stream, train, guard={"margin": 1.0}).guard
    deployed = AdaptiveCompensator(stream, None, guard, guard.period_s)     # no sensor monitor
    env = stream.envelope
    j_s, j_c = env.columns.index("T_spindle"), env.columns.index("T_column")
    s = env.hi[j_s] + 2.0                       # the spindle 2 K beyond its training range
    edge = _gate_edge(env, s, j_s, j_c)
    # a slow heating along the training pattern (no clamp), then the column rides the gate's
    # threshold (±0.02 K) while the spindle holds: the clamp switches every row
    ramp, n = np.linspace(0.0, s, 60), 40
    spindle = np.r_[ramp, np.full(n, s)]
    column = np.r_[0.4 * ramp, np.where(np.arange(n) % 2 == 0, edge + 0.02, edge - 0.02)]
    test = pd.DataFrame({"time": 300.0 * np.arange(len(spindle)), "T_spindle": 20.0 + spindle,
                         "T_column": 20.0 + column, "T_amb": 20.0, "E_X": 0.0})
    got = replay(deployed, test)
    clamped = got["n_clamped"].to_numpy() > 0
    assert not clamped[:60].any() and clamped[60:].sum() == n // 2      # every other row
    plain = replay(stream, test)["E_X"].to_numpy()
    assert np.abs(np.diff(plain)).max() > guard.max_rate_per_s[0] * guard.period_s
    guarded = [e for row in got["events"] for e in json.loads(row) if e.get("target")]
    assert guarded == []              # 55f940b8: rate_limited / free pairs on the healthy stream
    # the correction sent is still paced: no step beyond the limit
    y = got["E_X"].to_numpy()
    assert np.abs(np.diff(y)).max() <= guard.max_rate_per_s[0] * guard.period_s + 1e-9
