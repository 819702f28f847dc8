"""A one-sample spike is no jump (mon89, issue 34; benchmarks/bench_mon89.py).

lr9211 (deploy88's long record, R1b continuing R1a): the generator's -3.85 °C one-sample spike on
``T_head_left``, which the others predict.  The served monitor read it as a jump (excluded,
re-referenced), and its return as a second jump re-referenced by the whole step while it was out:
the pair's noise (+0.123 °C) stayed in its reference for the record's last 4.7 h and it waited
out 16 samples, so the deployed stream left the scored one from the spike to the end (lagbank
0.856 -> 0.991 µm).  Now a return that brings the reading back to the field on its reference
before the jump (within its re-admission band) is a spike's end: the reference put back and the
sensor in again at once (``InstantFaults._spike_back``); only the spike's sample reads the field."""

from __future__ import annotations

import numpy as np
import pytest

from test_monitor_readmit88 import _moves, deployed_record
from thermocomp.apps.deploy.report import plain, stream_rows
from thermocomp.core.continuation import lead_ins

LONG = ("sim=long_record", "seed=9211", "sim.generator.duration_days=3.0",
        "sim.generator.test_fraction=0.2")


@pytest.fixture(scope="module")
def long_record(tmp_path_factory):
    """``(deployed MLR, R1b, its lead-in)`` of lr9211."""
    deployed, ds, test_ids = deployed_record(tmp_path_factory.mktemp("lr9211") / "data", LONG,
                                             ("data.reference=none",))
    (test,) = test_ids
    return (deployed, ds.campaigns[test].reset_index(drop=True),
            lead_ins(plain(deployed).compensator, ds, test_ids)[test])


@pytest.fixture(scope="module")
def spiked(long_record):
    """The deployed stream of R1b as recorded (the spike in it), run once: two tests read it."""
    deployed, frame, lead = long_record
    return stream_rows(deployed, frame, "R1b", lead_in=lead)


def test_the_spiked_sensor_is_back_at_the_spikes_end(long_record, spiked):
    _, frame, _ = long_record
    period = float(np.median(np.diff(frame["time"])))
    moves = _moves(spiked.events, "T_head_left")
    assert [to for to, _ in moves] == ["excluded", "ok"], moves
    assert moves[1][1] - moves[0][1] == period            # the next sample, not a window later


def test_deployed_reads_as_scored_but_for_the_spike(long_record, spiked):
    """MLR has no memory: the deployed stream equals the plain one (no monitor, as ``run``
    scores) on every row but the spike's, where the model reads the field's prediction."""
    deployed, frame, lead = long_record
    got = spiked.y
    want = stream_rows(plain(deployed), frame, "R1b", lead_in=lead).y
    parted = np.flatnonzero(np.abs(got - want).max(axis=1) > 1e-9)
    spike = int(np.argmax(np.abs(np.diff(frame["T_head_left"].to_numpy(float))))) + 1
    assert parted.tolist() == [spike], parted


def test_a_step_that_stays_is_still_a_jump(long_record):
    """The control (as on main): the spike's step kept to the end (a sensor's offset) is
    re-referenced and waits out its calm window, never taken back on the reference before it."""
    deployed, frame, lead = long_record
    series = frame["T_head_left"].to_numpy(float)
    row = int(np.argmax(np.abs(np.diff(series)))) + 1    # the spike's row
    stepped = frame.copy()
    stepped.loc[row + 1:, "T_head_left"] += series[row] - series[row - 1]
    mon = deployed.monitor
    period = float(np.median(np.diff(frame["time"])))
    events = stream_rows(deployed, stepped, "R1b", lead_in=lead).events     # streamed once
    moves = _moves(events, "T_head_left")
    assert moves[0][0] == "excluded"
    back = [t for to, t in moves if to == "ok"]
    assert back and back[0] - moves[0][1] >= mon.window * period, moves
    assert all("spike" not in e["reason"] for e in events if e.get("sensor"))
