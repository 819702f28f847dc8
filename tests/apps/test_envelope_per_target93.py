"""The envelope's clamp per target (env93, ``promote.envelope.per_target=true``, opt-in): a target
whose training residual is white streams unclamped, the others keep the training-pattern gate.

A column with a heat source the training never saw (``column_moving_source``'s Q3, on the right
face): E_X (left face against right, both measured) is fitted to its noise and its model carries
the new source on as the physics does; E_Y (front against the unmeasured back) keeps structure in
its residual and its model's response to Q3 is wrong.  Measured on 19 + 10 seeds:
benchmarks/bench_env93.py.
"""

from __future__ import annotations

import numpy as np
import pytest

from thermocomp.apps.deploy import replay
from thermocomp.apps.deploy.export import Simulator, state_space
from thermocomp.apps.sim.column import ColumnMovingSource
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR
from thermocomp.shell.builders import deploy_stream
from thermocomp.shell.config import overrides


@pytest.fixture(scope="module")
def column():
    """A small column record (24 h train, 24 h test with Q3 from 12 h to 18 h) and MLR on it."""
    ds, _ = ColumnMovingSource(train_hours=24.0, test_hours=24.0, sample_period_s=200.0, seed=9301).generate()
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    test = ds.campaigns[ds.ids("test")[0]]
    return Compensator(MLR()).fit(train), train, test


PER_TARGET = "promote.envelope.per_target=true"


def _deployed(comp, train, *keys):
    """The stream the deploying stages build (replay, promote, export) under ``keys``."""
    return deploy_stream(overrides.compose(["data.path=/x", *keys], "replay"), comp, train)


def test_the_target_left_unclamped_is_the_one_whose_physics_is_measured(column):
    comp, train, _ = column
    free = _deployed(comp, train, PER_TARGET).unclamped_
    assert "E_X" in free
    assert "E_Y" not in free and "E_Z" not in free
    assert _deployed(comp, train).unclamped_ == ()               # the default: one clamp for all


def test_a_white_target_streams_unclamped_the_others_stay_clamped(column):
    comp, train, test = column
    per_target = replay(_deployed(comp, train, PER_TARGET), test)
    shared = replay(_deployed(comp, train), test)             # one envelope for every target
    off = replay(_deployed(comp, train, "promote.envelope.policy=off"), test)
    assert (per_target["n_clamped"] > 0).sum() > 10            # Q3 takes the inputs off the pattern
    acted = shared["n_clamped"].to_numpy() > 0
    assert np.abs(shared["E_X"] - off["E_X"]).to_numpy()[acted].max() > 1.0   # main froze E_X
    # unclamped where the excess is a source's, two inputs or more out (env94: one alone, clamped)
    spread = per_target["n_clamped"].to_numpy() >= 2
    np.testing.assert_allclose(per_target["E_X"].to_numpy()[spread], off["E_X"].to_numpy()[spread],
                               atol=1e-9)
    np.testing.assert_allclose(per_target["E_Y"], shared["E_Y"], atol=1e-9)
    assert np.abs(per_target["E_Y"] - off["E_Y"]).max() > 1.0
    # the new source's E_X carried on: closer to the measured error than the clamped stream
    measured = comp.measured({"t": test})["t"]["E_X"].to_numpy()
    rms = {k: np.sqrt(np.mean((measured - s["E_X"].to_numpy())[acted] ** 2)) for k, s in
           (("per_target", per_target), ("shared", shared))}
    assert rms["per_target"] < rms["shared"]


def test_the_exported_code_leaves_the_same_target_unclamped(column):
    comp, train, test = column
    stream = _deployed(comp, train, PER_TARGET)
    assert stream.unclamped_
    out = replay(stream, test)
    sim = Simulator(state_space(stream))
    rows = zip(test[stream.columns_].to_numpy(float), test["time"])
    exported = np.array([-sim.step(u, t) for u, t in rows])
    np.testing.assert_allclose(exported, out[stream.targets_].to_numpy(), atol=1e-8)
