"""One impossible sample must not stay in the deployed compensator's memory.

A +50 °C spike on one row of one sensor leaves the envelope; the clamp takes the model's
response to the excess out within ``|gain . ex|``, the response to it held for the longest
training campaign.  With the bound of each sample, 0 once the spike is over, what the spike left
in the lags and the AR feedback passed on to the campaign's end (``yearround_spindle``, a lag
bank: 261 µm on the next row in the plain stream, 9 at the end; the exported code, within its
guard, 34 at most and 9 at the end).  Back in range the bound of the excess's last sample holds: the
spike's memory is taken out as it decays, and every later correction is the one of the same
record read at the envelope's edge on that row (what the clamp gives for it), in the plain
stream, the numpy reference, the compiled C and the Structured Text.  A lasting step of the
ambient reading (the column alone: the code cannot tell the air from the sensor) is followed in
every form, never refused.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pandas as pd
import pytest

from conftest import deployed_as_replay
from test_export import EVERY_EXCURSION, _compose, _make_dataset, needs_cc
from test_export_dropout53 import _c, _st
from test_export_guard import _simulated
from thermocomp.apps.deploy.export import state_space
from thermocomp.apps.deploy.streaming import replay, streaming_deviation

FAMILIES = {"arx": ["model=arx", "model.estimator.ar=true", "model.estimator.delays=[2]"],
            "lagbank": ["model=lagbank"]}
SPIKE_C, SENSOR = 50.0, "T_a"
TOLERANCE_UM = 1e-9


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return _make_dataset(tmp_path_factory.mktemp("spike") / "data")


@lru_cache(maxsize=None)        # one fit per family for the module (replay resets the stream)
def _deployed(dataset, family):
    """``(adaptive compensator as replay deploys it, a healthy test campaign)``; every excursion
    clamped (the sensors here move independently: test_export.EVERY_EXCURSION)."""
    cfg = _compose(f"data.path={dataset}", "track=false", "monitor.adaptive=true",
                   EVERY_EXCURSION, *FAMILIES[family])
    deployed, ds, test_ids = deployed_as_replay(cfg)
    return deployed, ds.campaigns[test_ids[0]].reset_index(drop=True).copy()


def _spiked(deployed, healthy) -> tuple[pd.DataFrame, pd.DataFrame, int]:
    """``(the record with one row spiked, the same row read at the envelope's edge, that row)``."""
    ss, row = state_space(deployed), len(healthy) // 2
    j = deployed.columns_.index(SENSOR)
    spiked, edge = healthy.copy(), healthy.copy()
    spiked.loc[row, SENSOR] += SPIKE_C
    edge.loc[row, SENSOR] = healthy[SENSOR].iloc[0] + ss.hi[j]     # referenced, no denoiser
    assert ss.referenced[j] and len(ss.fir) == 1 and ss.clamp
    return spiked, edge, row


@needs_cc
@pytest.mark.parametrize("family", FAMILIES)
def test_a_one_row_spike_leaves_no_memory_in_any_form_of_the_code(dataset, tmp_path, family):
    deployed, healthy = _deployed(dataset, family)
    cols, ss = deployed.columns_, state_space(deployed)
    spiked, edge, row = _spiked(deployed, healthy)
    # the code's arithmetic without its sensor monitor (cmon76), as the ST's: to the monitor the
    # record read at the envelope's edge is a jump of T_a, which it takes out for a window
    returned, c_spiked = _c(deployed, tmp_path, [spiked], cols, monitor=False)
    assert returned[row] > 0 and (returned[row + 1:] == 0).all()     # clamped on that row only
    _, c_edge = _c(deployed, tmp_path, [edge], cols, monitor=False)
    _, c_healthy = _c(deployed, tmp_path, [healthy], cols, monitor=False)
    # with it, the spike passes the monitor by (out of range: not in the code) and every later
    # correction is the plain code's
    _, c_watched = _c(deployed, tmp_path, [spiked], cols)
    np.testing.assert_allclose(c_watched, c_spiked, rtol=0, atol=TOLERANCE_UM)
    after = slice(row + 1, None)
    assert np.max(np.abs(c_spiked - c_healthy)[after]) > 0.05         # the spike did reach the model
    np.testing.assert_allclose(c_spiked[after], c_edge[after], rtol=0, atol=TOLERANCE_UM)
    # the ST without its monitor's detection (st93), as the C above: its arithmetic, compared
    refused, st_spiked = _st(deployed, [spiked], cols, monitor=False)
    sim_spiked = _simulated(ss, [spiked], cols)
    assert not refused.any()
    for other in (st_spiked, sim_spiked):
        np.testing.assert_allclose(other, c_spiked, rtol=0, atol=TOLERANCE_UM)


@pytest.mark.parametrize("family", FAMILIES)
def test_a_one_row_spike_leaves_no_memory_in_the_plain_stream(dataset, family):
    deployed, healthy = _deployed(dataset, family)
    stream, targets = deployed.streaming, deployed.targets_
    spiked, edge, row = _spiked(deployed, healthy)
    y_spiked = replay(stream, spiked)[targets].to_numpy()
    y_edge = replay(stream, edge)[targets].to_numpy()
    np.testing.assert_allclose(y_spiked[row + 1:], y_edge[row + 1:], rtol=0, atol=TOLERANCE_UM)
    # the healthy record never leaves the envelope: the stream is the scored model's
    assert not replay(stream, healthy)["n_clamped"].any()
    assert streaming_deviation(stream, healthy) <= TOLERANCE_UM


@needs_cc
def test_a_lasting_step_of_the_ambient_reading_is_followed_not_refused(dataset, tmp_path):
    """+5 K on the T_amb reading from mid-campaign on (beyond the monitor's jump limit and the envelope):
    no form refuses a sample, and the correction moves with it as the plain stream's does."""
    deployed, healthy = _deployed(dataset, "lagbank")
    cols, ss = deployed.columns_, state_space(deployed)
    warmer = healthy.copy()
    warmer.loc[len(healthy) // 2:, "T_amb"] += 5.0
    # (the C without its sensor monitor, as the ST: the monitor takes the step for a jump of
    # T_amb, which the others predict here, and re-references it: tests/shell/test_export_monitor76)
    returned, c_warmer = _c(deployed, tmp_path, [warmer], cols, monitor=False)
    _, c_healthy = _c(deployed, tmp_path, [healthy], cols, monitor=False)
    refused, st_warmer = _st(deployed, [warmer], cols, monitor=False)
    assert (returned >= 0).all() and not refused.any()
    np.testing.assert_allclose(st_warmer, c_warmer, rtol=0, atol=TOLERANCE_UM)
    moved = np.abs(c_warmer - c_healthy)[-1]
    plain = replay(deployed.streaming, warmer)[deployed.targets_].to_numpy()
    plain_moved = np.abs(plain - replay(deployed.streaming, healthy)[deployed.targets_].to_numpy())[-1]
    assert moved.max() > 0.05 and plain_moved.max() > 0.05
    assert 5.0 > deployed.monitor._jump_lim[deployed.monitor.names.index("T_amb")]
    assert 5.0 > ss.hi[cols.index("T_amb")]
