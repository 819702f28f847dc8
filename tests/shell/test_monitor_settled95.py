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


def test_the_per_sample_test_is_the_whole_tests_last_row():
    """``level_shift(last=True)``, the served sample's and the mirror's test of their ring's last
    ``2 w`` readings, computes the two windows it reads alone (ci97: 98 -> 55 us a call): the
    whole test's last row, bit for bit, missing readings, ties and steady 0 too."""
    from thermocomp.apps.deploy.surveillance.settled import level_shift
    rng = np.random.default_rng(97)
    for _ in range(400):
        w, cols = int(rng.integers(1, 13)), int(rng.integers(1, 6))
        a = rng.normal(0.0, 1.0, (2 * w + int(rng.integers(0, 3)), cols)) * rng.choice([1e-3, 1, 50])
        a[rng.random(a.shape) < rng.choice([0.0, 0.1])] = np.nan
        a = np.round(a, 1) if rng.random() < 0.3 else a
        lim, steady = rng.normal(0.0, 1.0, cols), rng.choice([0.0, 2.5, 6.0])
        (parted, shift), (one, one_shift) = (level_shift(a, w, lim, steady, last=last)
                                             for last in (False, True))
        assert one.shape == one_shift.shape == (1, cols)
        assert np.array_equal(one[0], parted[-1]) and np.array_equal(one_shift[0], shift[-1],
                                                                     equal_nan=True)


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
