"""Two sensors jumping in one sample in the exported C (cmon93, issue 34): the code's monitor
re-references both by their step less their change as the sensors that did not jump predict it
and takes both out, then reads their return as a spike's, as the served monitor does, where
before it flagged ``COMMON`` ("several sensors jumping in one sample") and parted from the served
corrections (benchmarks/bench_cmon92.py: 2382 of the 2402 fresh spiked cases that part;
benchmarks/bench_cmon93.py).

bench_audit86b's lr9032 (``thermocomp simulate sim=long_record``, seed 9032, 3 days, R1b the last
fifth continuing R1a), MLR deployed adaptive with ``data.reference=none``; ``T_head_left`` and
``T_head_right`` (the others predict both) read 5 degC high together for 10 samples from R1b's
row a quarter in (bench_cmon92's spike); R1b streamed after R1a's last 864 rows (:data:`LEAD_ROWS`,
ci102a; R1a whole before: the same rows held, the module's tests pass on both)."""

from __future__ import annotations

import numpy as np
import pytest

from test_export import built_stream, needs_cc
from test_export_cmon80 import _streamed
from test_export_cmon85 import _mirror, without
from test_export_cmon87 import LEAD_ROWS, held_as_served, long_record
from thermocomp.apps.deploy.export import exported_files
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections, fed
from thermocomp.apps.deploy.export.served import ServedStreams
from thermocomp.apps.deploy.export.watch import COMMON, JUMP, SPIKE

SEED = 9032
PAIR = ("T_head_left", "T_head_right")
SPIKE_C, SPIKE_ROWS = 5.0, 10


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """``long_record``'s tuple with R1b spiked on :data:`PAIR`, and the fault's row (1-based in
    the fed frame)."""
    deployed, ss, _, lead, tests, leads = long_record(tmp_path_factory, SEED, LEAD_ROWS)
    (test, campaign), = tests.items()
    campaign = campaign.copy()
    start = len(campaign) // 4
    for sensor in PAIR:
        campaign.loc[campaign.index[start:start + SPIKE_ROWS], sensor] += SPIKE_C
    frame = fed(campaign, leads.get(test))
    return (deployed, ss, frame, lead, {test: campaign}, leads), lead + start + 1


@pytest.fixture(scope="module")
def streams(record):
    """The served streams of ``record``'s model, made once for the module's tests and packs."""
    return ServedStreams(record[0][0])


@needs_cc
def test_two_sensors_jumping_in_one_sample_are_held_as_served(record, streams, tmp_path):
    (deployed, ss, frame, *_), row = record
    # every row through the compiled C = served, nothing flagged, the pack whole and passing
    back, each = _readmitted()
    out, said, _ = held_as_served(record[0], tmp_path, streams, each)
    assert (row, PAIR[0], JUMP) in out
    assert f"line {row + 1}: monitor: {PAIR[0]}: jump: re-referenced and excluded" in said
    # their return SPIKE_ROWS later read as a spike's (the jump undone), as served
    assert (row + SPIKE_ROWS, SPIKE) in [(r, rule) for r, _, rule in back]


def _readmitted() -> tuple[list[tuple[int, int, int]], object]:
    """The mirror's re-admissions ``(row, sensor, rule)``, 1-based, filled by the second item,
    the ``each`` of ``held_as_served``'s mirror pass (ci104b: read from it, not a second pass)."""
    from thermocomp.apps.deploy.export.watch import READMITTED

    back = []

    def each(i, sim):
        if sim.watch.flags & READMITTED:
            back.append((i + 1, sim.watch.sensor, sim.watch.rule))
    return back, each


def test_an_export_before_cmon93_flags_the_pair(record, streams):
    """Arrays without ``pair_jump``: ``COMMON`` flagged at the fault's row, the corrections
    parting from the served ones there, and the pack cut there."""
    (deployed, ss, frame, _, tests, leads), row = record
    old = without(ss, "pair_jump")
    got, _, missed = _mirror(old, frame)
    assert missed and missed[0] == (row, COMMON)
    want = corrections(ss, streams.rows(frame, "R1b").y)
    parted = np.flatnonzero(np.abs(got - want).max(axis=1) > 1e-9) + 1
    assert parted.min() >= row and np.abs(got - want).max() > 1e-3
    _, summary = conformance_pack(deployed, old, tests, leads, served=streams)
    assert summary["campaigns"][0]["rows"] == parted.min() - 1


# (dep105c) steps for good in one sample, past each sensor's jump limit (pt10044's W3 first row:
# a restart read as one record); T_table no other predicts, and with the four before it out too
# few are left to rebuild the field (``min_active`` 10 of 14)
STEPS = {"T_head_left": -1.8, "T_head_right": -2.5, "T_col_front_low": -1.5, "T_col_back": -1.0,
         "T_table": -2.2}


@needs_cc
def test_five_sensors_stepping_in_one_sample_are_held_as_served(record, streams, tmp_path):
    """dep105c: the five re-referenced and out together (the last where the field is not
    rebuilt: held at its last reading, as served), C = mirror = served on every row; on 6c013931
    ``COMMON`` flagged at their row (not in the code) and read unreferenced for good."""
    (deployed, ss, frame, *_), row = record
    frame = frame.copy()
    at = row + 300       # (1-based; after the spike's return)
    for sensor, step in STEPS.items():
        frame.loc[frame.index[at - 1:], sensor] += step
    want = corrections(ss, streams.rows(frame, "R1b").y)
    got, out, missed = _mirror(ss, frame)
    assert not missed and np.abs(got - want).max() < 1e-9 and (at, "T_head_left", JUMP) in out
    # (no pack: the mirror's and the stream's rows are the pack's check; ~3 s CPU saved)
    c, said = _streamed(built_stream(tmp_path, exported_files(deployed, "c")), frame, ss.inputs)
    assert c.shape == want.shape and np.abs(c - want).max() < 1e-9
    assert f"line {at + 1}: monitor: T_head_left: jump: re-referenced and excluded" in said
    assert "not in the code" not in said
