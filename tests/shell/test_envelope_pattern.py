"""The training envelope clamps an excursion only where it leaves the training *pattern*
(``promote.envelope.pattern``, default true): in the stream, the Simulator, the compiled C and
the Structured Text alike.

A linear machine whose three sensors follow one heat source and the ambient (a pattern of
rank 2 in four inputs): run uniformly hotter, its inputs leave the envelope along the pattern
and are streamed as ``run`` scores them; one sensor pushed far out leaves the pattern and is
clamped.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest

from test_export import StructuredText, _compiled, _compose, _stdin, _streamed, needs_cc
from thermocomp.apps.deploy import StreamingCompensator, replay
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR
from thermocomp.shell.builders import deploy_stream

ROWS, DT_S = 120, 60.0


def _machine(seed: int, heat: float) -> pd.DataFrame:
    """Sensors 20 + ambient swing + (5, 3, 1) × the source's rise (``heat`` K at full power),
    the error a linear law of them (µm)."""
    rng = np.random.default_rng(seed)
    t = np.arange(ROWS) * DT_S
    rise = heat * (1 - np.exp(-t / 1800.0))
    amb = 20 + 0.8 * np.sin(2 * np.pi * t / 5400.0 + seed)
    noise = 0.01 * rng.standard_normal((4, ROWS))
    frame = {"time": t, "T_1": amb + 5 * rise + noise[0], "T_2": amb + 3 * rise + noise[1],
             "T_3": amb + rise + noise[2], "T_amb": amb + noise[3]}
    frame["E_X"] = 4 * (frame["T_1"] - frame["T_1"][0]) - 2 * (frame["T_2"] - frame["T_2"][0])
    return pd.DataFrame(frame)


@pytest.fixture(scope="module")
def fitted():
    train = {f"K{k}": _machine(k, 1.0 + 0.2 * k) for k in range(4)}
    comp = Compensator(MLR()).fit(train)
    return comp, train


def _forms(stream, df) -> dict:
    """The corrections (µm, = -predicted error) of the Simulator and the Structured Text."""
    u, t = df[stream.columns_].to_numpy(float), df["time"].to_numpy(float)
    ss = state_space(stream)
    sim = Simulator(ss)
    fb = StructuredText(exported_files(stream, "st")["compensator.st"])
    return {"simulator": np.array([sim.step(r, s)[0] for r, s in zip(u, t)]),
            "st": np.array([fb(r, s, k == 0)[0] for k, (r, s) in enumerate(zip(u, t))])}


def _batch(comp, df) -> np.ndarray:
    return comp.predict({"c": df})["c"]["E_X"].to_numpy()


def test_a_uniformly_hotter_machine_streams_as_scored_in_every_form(fitted):
    comp, train = fitted
    stream = StreamingCompensator.from_training(comp, train)
    hot = _machine(9, 2.5)                          # the hottest training campaign: 1.6 K
    m = comp.stacked({"c": hot}, targets=[]).X.to_numpy()
    assert stream.envelope.outside(m).any(axis=1).sum() > ROWS // 3   # beyond the envelope
    out = replay(stream, hot)
    assert out["n_clamped"].eq(0).all()
    batch = _batch(comp, hot)
    np.testing.assert_allclose(out["E_X"], batch, atol=1e-9)          # deployed = run
    for form, c in _forms(stream, hot).items():
        np.testing.assert_allclose(-c, batch, atol=1e-9, err_msg=form)
    # with the pattern off (promote.envelope.pattern=false): every excursion clamped, as before
    every = StreamingCompensator.from_training(comp, train, pattern=False)
    clamped = replay(every, hot)
    assert clamped["n_clamped"].gt(0).sum() > ROWS // 3
    assert np.abs(clamped["E_X"] - batch).max() > 1.0
    np.testing.assert_allclose(-_forms(every, hot)["simulator"], clamped["E_X"], atol=1e-9)


def _clipped(stream, df) -> pd.DataFrame:
    env, out = stream.envelope, df.copy()
    for j, c in enumerate(env.columns):
        first = df[c].iloc[0]
        out[c] = first + np.clip(df[c] - first, env.lo[j], env.hi[j])
    return out


def _one_sensor_out(stream) -> pd.DataFrame:
    far = _machine(7, 1.2)
    far.loc[ROWS // 2:, "T_1"] += 30.0
    return far


def test_one_sensor_far_out_is_still_clamped_in_every_form(fitted):
    comp, train = fitted
    stream = StreamingCompensator.from_training(comp, train)
    far = _one_sensor_out(stream)
    out = replay(stream, far)
    assert out["n_clamped"].iloc[ROWS // 2:].gt(0).all()
    clamped = _batch(comp, _clipped(stream, far))
    assert np.abs(_batch(comp, far) - clamped).max() > 10.0              # the clamp matters
    np.testing.assert_allclose(out["E_X"], clamped, atol=1e-9)
    for form, c in _forms(stream, far).items():
        np.testing.assert_allclose(-c, out["E_X"], atol=1e-9, err_msg=form)


@needs_cc
def test_the_compiled_c_gates_as_the_stream(fitted, tmp_path):
    comp, train = fitted
    stream = StreamingCompensator.from_training(comp, train)
    cases = [_machine(9, 2.5), _one_sensor_out(stream)]
    expected = np.concatenate([replay(stream, df)["E_X"].to_numpy() for df in cases])
    got = _streamed(_compiled(stream, tmp_path), _stdin(stream, cases))
    np.testing.assert_allclose(-got["C_X"].to_numpy(float), expected, atol=1e-9)
    assert np.abs(expected[:ROWS] - _batch(comp, cases[0])).max() < 1e-9   # the hot one passed


def test_the_pattern_is_a_promote_key_and_old_envelopes_clamp_every_excursion(fitted):
    comp, train = fitted
    stream = deploy_stream(_compose("track=false"), comp, train)
    assert stream.envelope.basis.shape == (4, 2)          # ambient and source: rank 2 of 4
    off = deploy_stream(_compose("track=false", "promote.envelope.pattern=false"), comp, train)
    assert off.envelope.basis is None
    assert not state_space(off).pattern and state_space(stream).pattern
    old = dataclasses.replace(stream.envelope, mean=None, scale=None, basis=None)   # a pickle
    assert old.leaves_pattern(np.zeros(4))


def test_inputs_trained_independently_have_no_gate_and_every_excursion_is_clamped():
    """Two inputs that training moved independently span every direction: no sample could
    leave the pattern, so a gate would pass a sensor 30 K out; there every excursion is clamped,
    as with the pattern off, in the stream and the export."""
    rng = np.random.default_rng(3)
    train = {f"K{k}": pd.DataFrame({"time": np.arange(ROWS) * DT_S,
                                    "T_1": 20 + rng.uniform(0, 2, ROWS),
                                    "T_2": 20 + rng.uniform(0, 2, ROWS)}) for k in range(2)}
    for df in train.values():
        df["E_X"] = 3 * (df["T_1"] - df["T_1"][0]) - df["T_2"] + df["T_2"][0]
    comp = Compensator(MLR()).fit(train)
    stream = StreamingCompensator.from_training(comp, train)
    assert stream.envelope.basis is None
    far = train["K0"].copy()
    far.loc[ROWS // 2:, "T_1"] += 30.0
    out = replay(stream, far)
    assert out["n_clamped"].iloc[ROWS // 2:].gt(0).all()
    every = replay(StreamingCompensator.from_training(comp, train, pattern=False), far)
    np.testing.assert_allclose(out["E_X"], every["E_X"], atol=1e-12)
    assert np.abs(out["E_X"] - _batch(comp, far)).max() > 10.0
    assert state_space(stream).clamp and not state_space(stream).pattern
