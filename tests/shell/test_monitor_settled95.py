"""A fast ramp of a sensor no other predicts is not a settled step, served, numpy mirror and
compiled C (settle95; benchmarks/bench_settle95.py).

test_export_cmon82c's machine and ramp: ``T_u`` (no other sensor predicts it) ramps down 0.8 °C
a row for 20 rows and back as fast.  Its successive windows part by the ramp's rise over a
sample, past the settled limit, so jump94b's rule re-referenced it by -9.77 °C (row 63) and
+8.81 °C (row 80) and left it that far off its truth.  Each window of a ramp spreads about as
much as the ramp moves their medians (median difference over the larger median absolute
deviation 3.4-4.2 here): the rule now asks that ratio past ``STEADY`` (6), so the ramp is not
re-referenced, while fl_thermal's planted step (test_monitor_settled94b) still is."""

from __future__ import annotations

import dataclasses

import numpy as np

from test_export import needs_cc
from test_export_cmon80 import streamed_as_served
from test_export_cmon82c import _deployed, _machine
from test_monitor_settled94b import _mirror
from thermocomp.apps.deploy.export import state_space
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.report import stream_rows


def test_a_straight_ramp_spreads_its_windows_as_much_as_it_parts_them():
    from thermocomp.apps.deploy.surveillance.settled import STEADY, steadiness  # (settle95)
    w = 10
    ramp = -0.8 * np.arange(2 * w, dtype=float)[:, None]
    step = np.r_[np.zeros(w), np.ones(w)][:, None] + 0.01 * np.sin(np.arange(2 * w))[:, None]
    (r_shift, r_spread), (s_shift, s_spread) = steadiness(ramp, w), steadiness(step, w)
    assert np.isclose(r_shift[0, 0], -8.0) and np.isclose(r_spread[0, 0], 2.0)    # ratio 4
    assert abs(r_shift[0, 0]) < STEADY * r_spread[0, 0]
    assert abs(s_shift[0, 0]) > STEADY * s_spread[0, 0] and np.isclose(s_shift[0, 0], 1.0, atol=0.02)


@needs_cc
def test_a_blind_sensors_fast_ramp_is_not_re_referenced_served_mirror_and_code(tmp_path):
    deployed, frame = _deployed(_machine(tmp_path / "data"), "none")
    run = stream_rows(deployed, frame, "K06")
    said = [(e["to"], e["reason"][:30]) for e in run.events if e.get("sensor") == "T_u"]
    # main: re-referenced -9.77 °C at row 63 and +8.81 °C at row 80
    assert not [s for s in said if s[0] == "re-referenced"], said
    assert [to for to, _ in said] == ["excluded", "ok"], said     # out on its leak, back
    mon = deployed.monitor
    assert np.isfinite(mon._settle_lim[mon.names.index("T_u")])   # judged by the rule
    ss = state_space(deployed, monitor=True)
    want = corrections(ss, run.y)
    got, rows = _mirror(ss, frame)
    assert rows == [] and np.max(np.abs(got - want)) < 1e-9
    _, stderr = streamed_as_served(tmp_path, deployed, ss, "K06", frame, want)
    assert "settled off its own" not in stderr
    # an export before settle95 (no ``settle_steady``): the mirror settles the ramp as before
    old = dataclasses.replace(ss, monitor={k: v for k, v in ss.monitor.items()
                                           if k != "settle_steady"})
    assert len(_mirror(old, frame)[1]) == 2
