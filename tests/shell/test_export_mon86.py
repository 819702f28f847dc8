"""The bands of the set a sensor is judged in, in the exported code too (mon86, issue 34): the
numpy mirror scales them from the exported floor, training moment and whole-set moment as the
served monitor does (the C's ``mon_bands`` the same arithmetic: bench_mon86's ``ccode``).

test_export_mon85b's deployed fl_thermal (adaptive MLR); its test campaign as measured with
``T_t12`` frozen from row ``ONSET`` (out for the freeze: the rest judged without it)."""

from __future__ import annotations

import copy

import numpy as np

import test_export
from conftest import FL_THERMAL_MLR
from test_export import needs_cc
from test_export_cmon80 import streamed_as_served
from test_export_mon85b import ONSET, served  # noqa: F401  (the module's fixture)
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.export.served import ServedStreams
from thermocomp.apps.deploy.export.watch import CodeMonitor
from thermocomp.shell.source import read_streamed


def _frozen():
    """The test campaign as measured, ``T_t12`` held at its reading of row ``ONSET`` from there."""
    ds, _, test_ids, _ = read_streamed(test_export._compose(*FL_THERMAL_MLR))
    frame = ds.campaigns[test_ids[-1]].reset_index(drop=True)
    frame.loc[ONSET:, "T_t12"] = frame["T_t12"].iloc[ONSET]
    return frame


def test_the_mirror_scales_each_band_to_its_set_as_served(served):  # noqa: F811
    deployed, ss, _ = served
    mon, n = deployed.monitor, len(deployed.monitor.names)
    assert {"floor", "moment", "q_full"} <= set(ss.monitor)
    code = CodeMonitor(ss.monitor)
    wider = 0
    for j in range(n):
        subset = np.arange(n) != j
        (w, a), (cw, ca) = mon._bands_of(subset), code._bands(subset)
        np.testing.assert_allclose(cw, w, rtol=1e-9, atol=0)
        np.testing.assert_allclose(ca, a, rtol=1e-9, atol=0)
        wider += int((w > mon.warning_c).any())
    assert wider                        # some set of this model judges a sensor more loosely
    every = code._bands(np.ones(n, bool))
    assert (every[0] == mon.warning_c).all() and (every[1] == mon.alarm_c).all()


def test_an_export_before_the_rule_judges_every_set_by_the_whole_sets_bands(served):  # noqa: F811
    _, ss, _ = served
    old = CodeMonitor({k: v for k, v in ss.monitor.items() if k not in ("floor", "moment", "q_full")})
    n = len(ss.monitor["inputs"])
    w, a = old._bands(np.arange(n) != 0)
    assert (w == np.asarray(ss.monitor["warning"])).all() and (a == np.asarray(ss.monitor["alarm"])).all()


@needs_cc
def test_a_frozen_sensor_out_the_rest_judged_in_its_set_served_mirror_and_c(served, tmp_path):  # noqa: F811
    """``T_t12`` frozen from row ``ONSET``: out for the freeze (no guess), the others judged
    without it against that set's bands (wider than the whole set's for some), in the C too: it
    reads what served reads on every row and flags no rule it lacks.  (No sensor leaves its band
    on this record either way: the bands change no decision here; bench_mon86's trace is where
    they do, a record no deployed model streams.)"""
    deployed, ss, _ = served
    frame = _frozen()
    mon = copy.deepcopy(deployed.monitor)
    mon.reset()
    wider = 0
    for i, row in enumerate(frame[mon.names].to_numpy(float)):
        mon.update(row, float(frame["time"].iloc[i]))
        wider += int((mon._warn > mon.warning_c).any())
    assert mon.excluded == ["T_t12"] and wider          # the set's bands judged the rest
    streams = ServedStreams(deployed)         # (the pack's stream of the frame: this one)
    want = corrections(ss, streams.rows(frame, "K06").y)
    streamed_as_served(tmp_path, deployed, ss, "K06", frame, want, streams)
