"""The correction guard's bound follows a real excursion on the training pattern (stop 56).

A machine whose sensors share one heat source runs hotter in test than in training (the source
at 1.8 x its largest training power): every sensor beyond its training range, together as in
training.  The model's correction then leaves the training error range widened by the guard's
margin; the fixed bound clipped it (``long_record`` overspeeds: 1.2-6.8 x the plain stream's
Σ² vs truth, benchmarks/bench_guard56.py).  The bound now widens by the model's response to the
inputs' excess over their training range, on the pattern only: a sample where one sensor does
not follow the others (a fault) keeps the bound as trained.  The exported code does the same.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from conftest import deployed_as_replay
from test_export import TOLERANCE_UM, StructuredText, _compiled, _compose, _streamed, needs_cc
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.deploy.streaming import replay

ROWS, STEP_S = 60, 120.0
SPLITS = ["train"] * 5 + ["test"]


def _campaign(power: float, amb: float, rng) -> pd.DataFrame:
    """Four sensors heated by one source of ``power`` (each with its own share and lag), the
    air, and the error they explain."""
    t = np.arange(ROWS) * STEP_S
    rise = power * (1 - np.exp(-t / 2400))
    late = power * (1 - np.exp(-t / 4800))
    noise = lambda: rng.normal(0, 0.03, ROWS)          # noqa: E731
    frame = pd.DataFrame({"time": t, "T_amb": amb + 0.2 * np.sin(t / 3000) + noise(),
                          "T_a": amb + rise + noise(), "T_b": amb + 0.6 * rise + noise(),
                          "T_c": amb + 0.8 * late + noise(), "T_d": amb + 0.4 * late + noise()})
    d = frame - frame.iloc[0]
    frame["E_X"] = 3.0 * d["T_a"] - 1.0 * d["T_b"] + 2.0 * d["T_c"] + rng.normal(0, 0.1, ROWS)
    return frame


@pytest.fixture(scope="module")
def hotter_data(tmp_path_factory):
    """The folder of the five training campaigns and the hotter test campaign."""
    root = tmp_path_factory.mktemp("guard56") / "data"
    root.mkdir()
    rng = np.random.default_rng(56)
    for i, split in enumerate(SPLITS):
        power = 9.0 if split == "test" else 3.0 + 0.5 * i      # training at most 5.0
        _campaign(power, 18.0 + 0.5 * i, rng).to_csv(root / f"K{i}.csv", index=False)
    pd.DataFrame({"campaign": [f"K{i}" for i in range(len(SPLITS))],
                  "file": [f"K{i}.csv" for i in range(len(SPLITS))], "split": SPLITS,
                  "notes": ""}).to_csv(root / "campaigns.csv", index=False)
    return root


def _deployed(root, *model) -> tuple:
    cfg = _compose(f"data.path={root}", "track=false", "monitor.adaptive=true", *model)
    deployed, ds, test_ids = deployed_as_replay(cfg)
    return deployed, ds.campaigns[test_ids[0]].reset_index(drop=True)


@pytest.fixture(scope="module")
def hotter(hotter_data):
    """``(adaptive compensator as replay deploys it (MLR), the hotter test campaign)``."""
    return _deployed(hotter_data, "model=mlr")


def test_the_bound_follows_a_hotter_machine_and_not_one_sensor(hotter):
    deployed, df = hotter
    assert deployed.streaming.envelope.basis is not None        # the sensors moved together
    free = replay(deployed.streaming, df)[deployed.targets_].to_numpy(float)
    got = replay(deployed, df)
    assert (got["excluded_inputs"] == "").all()                 # nothing read as a fault
    y = got[deployed.targets_].to_numpy(float)
    hi = deployed.guard.hi
    # the model's correction goes beyond the trained bound, and reaches the CNC as it is
    assert free.max() > hi.max() + 5.0
    np.testing.assert_allclose(y, free, rtol=0, atol=1e-9)
    # the bound widened by the response to the excess over the training range; a sample off
    # the pattern (one sensor not following the others, as a fault) keeps the trained bound
    env, guard, cols = deployed.streaming.envelope, deployed.guard, deployed.columns_
    x = (df[cols] - df[cols].iloc[0]).to_numpy(float)[-1]
    excess = np.maximum(x - guard.in_hi, guard.in_lo - x).clip(0)
    np.testing.assert_allclose(guard.allowance(x, env), np.abs(guard.in_gain) @ excess)
    assert free[-1] > hi.max() and not env.leaves_pattern(x)
    lone = x.copy()
    lone[cols.index("T_b")] *= 0.5
    assert env.leaves_pattern(lone) and guard.allowance(lone, env) is None
    assert guard.allowance(np.clip(x, guard.in_lo, guard.in_hi), env) is None    # in range


@needs_cc
def test_the_code_follows_the_hotter_machine_as_replay_does(hotter, tmp_path):
    deployed, df = hotter
    expected = -replay(deployed, df)[deployed.targets_].to_numpy(float)
    assert -expected.min() > deployed.guard.hi.max() + 5.0
    ss, cols = state_space(deployed), deployed.columns_
    assert ss.guard_inputs
    sim = Simulator(ss)
    got = np.array([sim.step(u, t) for u, t in zip(df[cols].to_numpy(float), df["time"])])
    assert np.max(np.abs(got - expected)) <= TOLERANCE_UM
    rows = df[["time", *cols]].to_csv(index=False, float_format="%.17g")
    assert np.max(np.abs(_streamed(_compiled(deployed, tmp_path), rows).to_numpy(float)
                         - expected)) <= TOLERANCE_UM
    fb = StructuredText(exported_files(deployed, "st")["compensator.st"])
    st = np.array([fb(u, t, k == 0) for k, (u, t) in enumerate(zip(df[cols].to_numpy(float),
                                                                    df["time"]))])
    assert np.max(np.abs(st - expected)) <= TOLERANCE_UM


def test_the_machine_gets_the_correction_the_compensator_computed(hotter):
    """``connect`` writes through an offset limiter bounded as the guard: it widens with it (it
    kept the trained bound and cut the hotter machine's correction there), and a stale offset
    decays from what was written, not cut to the trained bound first."""
    from thermocomp.shell.stages.connect import offset_limiter

    deployed, df = hotter
    limiter = offset_limiter(deployed, deployed.guard, hold_s=60.0, decay_s=600.0)
    deployed.reset()
    computed, written = [], []
    for u, t in zip(df[deployed.columns_].to_numpy(float), df["time"]):
        computed.append(np.asarray(deployed.step(u, t), float))     # as connect's client steps it
        written.append(limiter.fresh(computed[-1], now=t).copy())
    computed, written = np.array(computed), np.array(written)
    assert computed.max() > deployed.guard.hi.max() + 5.0
    np.testing.assert_allclose(written, computed, rtol=0, atol=1e-9)
    late = df["time"].iloc[-1] + 60.0 + 600.0        # held 60 s, then one time constant
    np.testing.assert_allclose(limiter.stale(now=late), written[-1] * np.exp(-1.0), rtol=1e-12)


def test_the_bound_follows_a_model_whose_gain_needs_the_ambient(hotter_data):
    """An ATI model (one interval, its ambient interaction: the gain is the base's plus the
    interaction's times ``A0 - 20``) has no step gain before a campaign's ``A0`` is known; the
    guard takes its largest |gain| over the training campaigns' ``A0`` (dep108c: a row of 0 kept
    the bound as trained and cut a diagnosed climate room's right correction on every test row).
    The exported code reads the same gain."""
    deployed, df = _deployed(hotter_data, "model=mlr", "ati=cmeans", "ati.estimator.n_intervals=1")
    est = deployed.streaming._plan[0][1]
    assert type(est).__name__ == "ATIRegressor" and est.step_gain(None) is None
    guard, env = deployed.guard, deployed.streaming.envelope
    a0s = [pd.read_csv(hotter_data / f"K{i}.csv")["T_amb"].iloc[0] for i in range(5)]   # training's
    at = [np.abs(est.step_gain(est.stream_init({"ambient_c0": a0}), env.horizon_s)) for a0 in a0s]
    np.testing.assert_allclose(guard.in_gain[0], np.max(at, axis=0), rtol=1e-12)
    assert guard.in_gain[0].max() > 1.0
    free = replay(deployed.streaming, df)[deployed.targets_].to_numpy(float)
    y = replay(deployed, df)[deployed.targets_].to_numpy(float)
    assert free.max() > guard.hi.max() + 5.0
    np.testing.assert_allclose(y, free, rtol=0, atol=1e-9)      # not cut to the trained bound
    ss, cols = state_space(deployed), deployed.columns_
    sim = Simulator(ss)
    got = np.array([sim.step(u, t) for u, t in zip(df[cols].to_numpy(float), df["time"])])
    assert np.max(np.abs(-got - y)) <= TOLERANCE_UM


def _follows_past_training(deployed, df):
    """The held-step gain sees T_a and T_c (3 and 2 µm/K of E_X in truth); the hotter machine's
    correction is not cut to the trained bound; the code reads the same."""
    cols, guard = deployed.columns_, deployed.guard
    assert guard.in_gain[0, cols.index("T_a")] > 1.0 and guard.in_gain[0, cols.index("T_c")] > 0.5
    free = replay(deployed.streaming, df)[deployed.targets_].to_numpy(float)
    y = replay(deployed, df)[deployed.targets_].to_numpy(float)
    assert free.max() > guard.hi.max() + 5.0
    np.testing.assert_allclose(y, free, rtol=0, atol=1e-9)      # not cut to the trained bound
    sim = Simulator(state_space(deployed))
    got = np.array([sim.step(u, t) for u, t in zip(df[cols].to_numpy(float), df["time"])])
    assert np.max(np.abs(-got - y)) <= TOLERANCE_UM


def test_the_bound_follows_an_lstm_by_its_held_steps(hotter_data):
    """An lstm has no analytic step gain: its row was 0 and the bound stayed as trained (guard111:
    climate room 10158's E_X cut on 230 test rows, 3.65 µm deployed against 3.26 unguarded).  The
    guard reads a gain off the model: each input held one unit higher for the envelope's horizon
    from each training campaign's last state, the largest |change|.  The code reads the same."""
    deployed, df = _deployed(hotter_data, "model=lstm", "model.estimator.hidden_size=2",
                             "model.estimator.max_epochs=1")
    assert not hasattr(deployed.streaming._plan[0][1], "step_gain")
    assert deployed.streaming.envelope.basis is not None
    _follows_past_training(deployed, df)


def test_the_bound_follows_an_ati_lstm_by_its_held_steps(hotter_data):
    """Held steps are the one fallback of any model without an analytic gain, not lstm's alone
    (guard111b): an ATI lstm (one interval, its ambient interaction) has no gain, with or without
    a campaign's ``A0``; its row was 0 and the hotter machine's correction was cut to the trained
    bound.  The code reads the same gain."""
    deployed, df = _deployed(hotter_data, "model=lstm", "model.estimator.hidden_size=2",
                             "model.estimator.max_epochs=1", "ati=cmeans", "ati.estimator.n_intervals=1")
    est = deployed.streaming._plan[0][1]
    assert type(est).__name__ == "ATIRegressor"
    assert est.step_gain(est.stream_init({"ambient_c0": 20.0}), np.inf) is None
    _follows_past_training(deployed, df)
