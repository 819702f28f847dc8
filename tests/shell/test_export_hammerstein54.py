"""The exported Hammerstein model when the envelope clamp acts.

The code runs one system on two channels: the inputs as measured, with the static powers of the
machine states (``S_*``), and their excess over the envelope, whose power columns are 0: the
stream's clamped copy of the model reads the states as measured (a power is never clamped, and
the bound ``|gain . ex|`` holds no power term).  Healthy records leave the excess channel at 0
and its bound at 0, so they cannot tell a broken padding (the powers in the excess channel) from
the right one.  Here a spindle record leaves the envelope four ways (a temperature pushed out
for a stretch then back, all three pushed out together, the spindle speed at twice its training
maximum for a stretch, a one-row spike), the speed read by the powers alone or declared an input
too (then clamped itself, its powers not), or with the pattern gate on (the temperatures moving
together in training: the state padded out of the pattern, scale UNBOUNDED; the temperatures out
together stay on it, passed); the compiled C, the Structured Text and the numpy reference follow
the stream the code is (plain; guarded: the adaptive compensator without its sensor monitor,
which the code does not carry) to 1e-9 µm.
"""

from __future__ import annotations

import shutil
from functools import lru_cache

import numpy as np
import pandas as pd
import pytest

from conftest import deployed_as_replay
from covering import covering
from test_export import EVERY_EXCURSION, _compose, needs_cc
from test_export_cadence72 import FASTER, _faster
from test_export_dropout53 import _c, _st
from test_export_guard import _simulated, _spindle_dataset
from thermocomp.apps.deploy.adaptive import AdaptiveCompensator
from thermocomp.apps.deploy.export import state_space
from thermocomp.apps.deploy.streaming import batch_prediction, replay

TOLERANCE_UM = 1e-9
# variant: (data set, overrides); every excursion clamped but on the pattern (test_export.EVERY_EXCURSION)
VARIANTS = {"powers_only": ("independent", EVERY_EXCURSION, "data.inputs=[T_*]"),
            "declared_too": ("independent", EVERY_EXCURSION, "data.inputs=[T_*,S_*]"),
            "on_pattern": ("one_pattern", "data.inputs=[T_*]")}
STATE, SENSOR = "S_spindle_rpm", "T_hall"
ALONG = {"T_hall": 1.0, "T_far": 1.5, "T_amb": 0.5}     # the pattern of the one_pattern data set


@pytest.fixture(scope="module")
def datasets(tmp_path_factory) -> dict:
    """The spindle record as made (sensors moving independently: no pattern to gate on), and with
    ``T_far`` and ``T_amb`` following ``T_hall`` (one pattern: ``T_hall`` out alone leaves it)."""
    root = tmp_path_factory.mktemp("hammerstein")
    independent = _spindle_dataset(root / "independent")
    one_pattern = root / "one_pattern"
    shutil.copytree(independent, one_pattern)
    rng = np.random.default_rng(7)
    for csv in one_pattern.glob("K*.csv"):
        df = pd.read_csv(csv)
        for col in ("T_far", "T_amb"):
            df[col] = ALONG[col] * df["T_hall"] + 10.0 + rng.normal(0, 0.002, len(df))
        df.to_csv(csv, index=False)
    return {"independent": independent, "one_pattern": one_pattern}


@lru_cache(maxsize=None)        # one fit per variant for the module (replay resets the stream)
def _fitted(dataset, variant):
    """``(adaptive compensator as replay deploys it, a healthy test campaign)``."""
    cfg = _compose(f"data.path={dataset}", "track=false", "monitor.adaptive=true", "model=hammerstein",
                   "model.estimator.lagbank.n_taus=3", *VARIANTS[variant][1:])
    deployed, ds, test_ids = deployed_as_replay(cfg)
    return deployed, ds.campaigns[test_ids[0]].reset_index(drop=True).copy()


def _excursions(healthy, state_max) -> dict:
    """The record leaving the envelope four ways, then the record itself (the bound starts at 0
    again with the next campaign)."""
    n = len(healthy)
    stretch = slice(n // 3, n // 2)
    names = ("out_and_back", "hotter", "state_beyond", "spike", "healthy")
    out = {name: healthy.copy() for name in names}
    out["out_and_back"].loc[stretch, SENSOR] += 30.0
    for col, k in ALONG.items():            # the temperatures out together, as on the pattern
        out["hotter"].loc[stretch, col] += 0.8 * k      # T_hall beyond its bound (+0.45)
    out["state_beyond"].loc[stretch, STATE] = 2.0 * state_max
    out["spike"].loc[n // 2, SENSOR] += 50.0
    return out


@needs_cc
@pytest.mark.parametrize("variant, follows", covering(
    "the guard wraps the same excess channel and powers, whichever variant fed them",
    variant=list(VARIANTS), follows=["plain", "guarded"]))
def test_every_form_of_a_hammerstein_code_follows_its_stream_out_of_the_envelope(datasets, tmp_path,
                                                                               variant, follows):
    adaptive, healthy = _fitted(datasets[VARIANTS[variant][0]], variant)
    stream = adaptive.streaming
    deployed = stream if follows == "plain" else AdaptiveCompensator(
        stream, None, adaptive.guard, adaptive.period_s)
    ss, cols = state_space(deployed), deployed.columns_
    assert ss.clamp and ss.powers and ss.inputs.index(STATE) in [q[0] for q in ss.powers]
    assert ss.pattern == (variant == "on_pattern")
    records = _excursions(healthy, ss.powers[0][1])          # the power's scale: |S| max on train
    clamped = {k: replay(stream, df)["n_clamped"].to_numpy() for k, df in records.items()}
    n = len(healthy)
    assert clamped["out_and_back"][n // 3:n // 2 + 1].all() and not clamped["out_and_back"][n // 2 + 1:].any()
    assert np.flatnonzero(clamped["spike"]).tolist() == [n // 2]
    hotter = records["hotter"][SENSOR] - healthy[SENSOR].iloc[0]       # referenced, no denoiser
    assert (hotter > ss.hi[ss.inputs.index(SENSOR)]).any()               # out of the envelope, yet
    assert clamped["hotter"].any() == (variant != "on_pattern")       # on the pattern: passed
    assert clamped["state_beyond"].any() == (variant == "declared_too")   # a power is never clamped
    assert not clamped["healthy"].any()
    expected = np.vstack([-replay(deployed, df)[deployed.targets_].to_numpy(float)
                          for df in records.values()])
    split = np.cumsum([len(df) for df in records.values()])[:-1]
    baseline = np.split(expected, split)[-1]
    for name, moved in zip(records, np.split(expected, split)):      # each excursion reaches the code
        assert name == "healthy" or np.max(np.abs(moved - baseline)) > 0.05, name
    returned, c_out = _c(deployed, tmp_path, list(records.values()), cols)
    refused, st_out = _st(deployed, list(records.values()), cols)
    assert (returned >= 0).all() and not refused.any()
    for form in (c_out, st_out, _simulated(ss, list(records.values()), cols)):
        np.testing.assert_allclose(form, expected, rtol=0, atol=TOLERANCE_UM)


@needs_cc
def test_a_missing_machine_state_is_held_in_the_code_as_the_stream_holds_it(datasets, tmp_path):
    """The speed read by the powers alone, missing at the campaign's first rows (0 before any)
    and for a stretch mid-run (its last value): the code held it as the served Hammerstein model
    does; it refused those samples and repeated its last correction (lead59)."""
    adaptive, healthy = _fitted(datasets["independent"], "powers_only")
    stream, cols = adaptive.streaming, adaptive.streaming.columns_
    ss = state_space(stream)
    assert ss.held[ss.inputs.index(STATE)] == 1 and sum(ss.held) == 1
    gappy = healthy.copy()
    turning = np.flatnonzero(healthy[STATE].to_numpy() > 0)
    assert turning.size > 20                       # a stretch where holding its value matters
    gappy.loc[:2, STATE] = np.nan
    gappy.loc[turning[10]:turning[10] + 5, STATE] = np.nan
    expected = -replay(stream, gappy)[stream.targets_].to_numpy(float)
    filled = -replay(stream, gappy.fillna({STATE: 0.0}))[stream.targets_].to_numpy(float)
    assert np.max(np.abs(expected - filled)) > 0.05       # the holding shows in the correction
    returned, c_out = _c(stream, tmp_path, [gappy], cols)
    refused, st_out = _st(stream, [gappy], cols)
    assert (returned >= 0).all() and not refused.any()
    for form in (c_out, st_out, _simulated(ss, [gappy], cols)):
        np.testing.assert_allclose(form, expected, rtol=0, atol=TOLERANCE_UM)


@needs_cc
def test_a_faster_stream_between_grid_rows_in_every_form_out_of_the_envelope(datasets, tmp_path):
    """Streamed FASTER times as often as trained, a row between two of the training grid is the
    model's step from the state the last grid row committed, not kept (between73): its answer
    moves between them (it held the grid row's), the batch ``run`` predicts is the stream's (a
    campaign's first row stepped alone: the lags of the states' powers start at rest), and the
    code follows the stream while the clamp forks, bounds and returns on rows between."""
    adaptive, healthy = _fitted(datasets["independent"], "declared_too")
    stream, cols = adaptive.streaming, adaptive.streaming.columns_
    assert stream.compensator.grid_period_s_ > 0
    ss = state_space(stream)
    records = [_faster(df) for name, df in _excursions(healthy, ss.powers[0][1]).items()
               if name in ("out_and_back", "state_beyond", "healthy")]
    expected = [-replay(stream, df)[stream.targets_].to_numpy(float) for df in records]
    fast = expected[-1]
    at_training = -replay(stream, healthy)[stream.targets_].to_numpy(float)
    np.testing.assert_allclose(fast[::FASTER], at_training, rtol=0, atol=TOLERANCE_UM)
    between = np.flatnonzero(np.arange(len(fast)) % FASTER)
    assert np.min(np.abs(fast[between] - at_training[between // FASTER])) > 0
    batch = -batch_prediction(stream.compensator, records[-1])[stream.targets_].to_numpy(float)
    np.testing.assert_allclose(batch, fast, rtol=0, atol=TOLERANCE_UM)
    expected = np.vstack(expected)
    returned, c_out = _c(stream, tmp_path, records, cols)
    refused, st_out = _st(stream, records, cols)
    assert (returned >= 0).all() and not refused.any()
    for form in (c_out, st_out, _simulated(ss, records, cols)):
        np.testing.assert_allclose(form, expected, rtol=0, atol=TOLERANCE_UM)
