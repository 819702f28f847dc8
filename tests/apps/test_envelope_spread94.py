"""The per-target clamp (``promote.envelope.per_target``) priced against a sensor fault (env94):
a white target streams unclamped only at a sample whose excess over the envelope at least two
inputs share (a heat source warms the sensors around it together); one sensor out alone (a drift,
a jump: a fault the adaptive monitor does not take out) is clamped as every target is, in the
stream and in the exported code.  Measured: benchmarks/bench_env94.py.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from thermocomp.apps.deploy import replay
from thermocomp.apps.deploy.export import Simulator, state_space
from thermocomp.apps.sim.column import ColumnMovingSource
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR
from thermocomp.shell.builders import deploy_stream
from thermocomp.shell.config import overrides

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "shell"))
from test_export import needs_cc  # noqa: E402
from test_export_dropout53 import _c, _st  # noqa: E402

PER_TARGET = "promote.envelope.per_target=true"
SENSOR = "T_left3"       # E_X's left face; the never-trained source Q3 heats the right one


@pytest.fixture(scope="module")
def column():
    """A small column record (24 h train, 24 h test with Q3 from 12 h to 18 h), MLR on it, and the
    test campaign with one sensor two training widths off from 3 h to 7 h, before Q3: alone."""
    ds, _ = ColumnMovingSource(train_hours=24.0, test_hours=24.0, sample_period_s=200.0, seed=9301).generate()
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    test = ds.campaigns[ds.ids("test")[0]]
    comp = Compensator(MLR()).fit(train)
    env = _deployed(comp, train).envelope
    j = list(env.columns).index(SENSOR)
    faulty = test.copy()
    faulty.loc[faulty.index[54:126], SENSOR] += 2.0 * (env.hi[j] - env.lo[j]) / (1 + 2 * env.margin)
    return comp, train, test, faulty


def _deployed(comp, train, *keys):
    """The stream the deploying stages build (replay, promote, export) under ``keys``."""
    return deploy_stream(overrides.compose(["data.path=/x", *keys], "replay"), comp, train)


def _three(comp, train, campaign):
    """The campaign replayed per target, with one clamp for every target, and unclamped."""
    return (replay(_deployed(comp, train, PER_TARGET), campaign), replay(_deployed(comp, train), campaign),
            replay(_deployed(comp, train, "promote.envelope.policy=off"), campaign))


def test_a_sensor_off_alone_clamps_the_white_target_again(column):
    comp, train, _, faulty = column
    per_target, shared, off = _three(comp, train, faulty)
    alone = np.arange(54, 126)
    assert (per_target["n_clamped"].to_numpy()[alone] == 1).all()      # that sensor alone is out
    assert np.abs(off["E_X"] - shared["E_X"]).to_numpy()[alone].min() > 1.0
    # main left E_X unclamped there: the fault carried into the correction, as ``off``
    np.testing.assert_allclose(per_target["E_X"].to_numpy()[alone], shared["E_X"].to_numpy()[alone],
                               atol=1e-9)
    measured = comp.measured({"t": faulty})["t"]["E_X"].to_numpy()[alone]
    rms = {k: np.sqrt(np.mean((measured - s["E_X"].to_numpy()[alone]) ** 2)) for k, s in
           (("per_target", per_target), ("off", off))}
    assert rms["per_target"] < rms["off"] / 2


@pytest.mark.parametrize("record", ["healthy", "faulty"])
def test_the_white_target_is_unclamped_where_two_inputs_or_more_are_out(column, record):
    comp, train, test, faulty = column
    per_target, shared, off = _three(comp, train, test if record == "healthy" else faulty)
    spread = per_target["n_clamped"].to_numpy() >= 2
    assert spread.sum() > 10 and (per_target["n_clamped"].to_numpy() == 1).any()
    # unclamped, its stream is off's (the clamp never changes its states); else the shared clamp's
    np.testing.assert_allclose(per_target["E_X"], np.where(spread, off["E_X"], shared["E_X"]), atol=1e-9)
    np.testing.assert_allclose(per_target["E_Y"], shared["E_Y"], atol=1e-9)


@needs_cc
def test_the_exported_code_clamps_the_lone_sensor_as_the_stream_does(column, tmp_path):
    comp, train, test, faulty = column
    stream = _deployed(comp, train, PER_TARGET)
    cols, served = stream.columns_, replay(stream, faulty)[stream.targets_].to_numpy()
    sim = Simulator(state_space(stream))
    numpy_ref = np.array([-sim.step(u, t) for u, t in zip(faulty[cols].to_numpy(float), faulty["time"])])
    _, c_out = _c(stream, tmp_path, [faulty], cols, monitor=False)
    _, st_out = _st(stream, [faulty], cols, monitor=False)
    for code in (numpy_ref, -c_out, -st_out):
        np.testing.assert_allclose(code, served, atol=1e-8)
    # and the code's E_X on the lone sensor's rows is the shared clamp's (main's code: off's)
    k, alone = stream.targets_.index("E_X"), np.arange(54, 126)
    shared = replay(_deployed(comp, train), faulty)["E_X"].to_numpy()
    np.testing.assert_allclose(-c_out[alone, k], shared[alone], atol=1e-8)
