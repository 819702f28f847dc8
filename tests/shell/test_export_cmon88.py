"""A second sensor out for a jump in the exported C (cmon88, issue 34): with one sensor out
already, a jump of a sensor the others predict is re-referenced and taken out as the second, as
the served monitor does, where before the code flagged ``SECOND``, kept the sensor in as read and
parted from the served corrections once the served monitor took it back (benchmarks/
bench_cmon88.py).

lr9126 as drawn (``thermocomp simulate sim=long_record``, seed 9126, 3 days, R1b the last fifth
continuing R1a), MLR deployed adaptive with ``data.reference=none``, R1b streamed after R1a's last
864 rows (:data:`LEAD_ROWS`, ci102a; R1a whole before): the simulator's own outliers put a stepped
self-prediction error (``T_zdrive`` out) three rows before a -2.31 degC one-sample jump of
``T_bed_left``, taken out at R1b's row 820 and back at 821, as after R1a whole."""

from __future__ import annotations

import numpy as np
import pytest

from test_export import needs_cc
from test_export_cmon85 import _mirror, without
from test_export_cmon87 import LEAD_ROWS, held_as_served, long_record
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
from thermocomp.apps.deploy.export.served import ServedStreams
from thermocomp.apps.deploy.export.watch import JUMP, SECOND

SEED = 9126


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    return long_record(tmp_path_factory, SEED, LEAD_ROWS)


@pytest.fixture(scope="module")
def streams(record):
    """The served streams of ``record``'s model, made once for the module's tests and packs."""
    return ServedStreams(record[0])


def _served_second(streams, frame) -> tuple[int, int, str]:
    """The served exclusion of a sensor for a jump while another is out: ``(row, its return's
    row, sensor)``, 1-based in the fed ``frame``."""
    times = frame["time"].to_numpy(float) - frame["time"].iloc[0]
    moves = [(int(np.searchsorted(times, e["time"])) + 1, e["sensor"], e["to"], e["reason"])
             for e in streams.rows(frame, "R1b").events if e.get("sensor")]
    out, seconds = set(), []
    for i, (row, sensor, to, why) in enumerate(moves):
        if to == "excluded" and out and why.startswith("jump") and "stepped" not in why:
            back = next(r for r, s, t, _ in moves[i + 1:] if s == sensor and t == "ok")
            seconds.append((row, back, sensor))
        if to == "excluded":
            out.add(sensor)
        elif to == "ok":
            out.discard(sensor)
    (second,) = seconds
    return second


@needs_cc
def test_a_second_sensor_out_for_a_jump_is_what_the_code_does_as_served(record, streams,
                                                                         tmp_path):
    deployed, _, frame, lead, _, _ = record
    row, back, sensor = _served_second(streams, frame)
    assert lead < row < back
    out, said, _ = held_as_served(record, tmp_path, streams)     # every row, nothing flagged, pack whole
    assert (row, sensor, JUMP) in out
    assert f"line {row + 1}: monitor: {sensor}: jump: re-referenced and excluded" in said


def test_an_export_before_cmon88_flags_the_second_jump(record, streams):
    """Arrays without ``second_jump``: the jump flagged (``SECOND``) at the served exclusion's
    row, the sensor kept in as read, the correction parting from the served one from its served
    return, and the pack cut there."""
    deployed, ss, frame, lead, tests, leads = record
    row, back, _ = _served_second(streams, frame)
    old = without(ss, "second_jump")
    got, _, missed = _mirror(old, frame, rows=back)        # (to the parting its assertions read)
    assert missed and missed[0] == (row, SECOND)
    want = corrections(ss, streams.rows(frame, "R1b").y)[:back]      # (the rows stepped)
    parted = np.flatnonzero(np.abs(got - want).max(axis=1) > 1e-9) + 1
    assert parted.min() == back
    _, summary = conformance_pack(deployed, old, tests, leads, served=streams)
    assert summary["campaigns"][0]["rows"] == back - 1
