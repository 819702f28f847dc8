"""A reading beyond its range of a sensor no other predicts in the exported C (cmon89b, issue 34):
the code's monitor holds it out as the served monitor does (read as missing, held at its last
reading) and re-admits it by the served test, its leak onto the others with it and without it
within ``readmit`` of their warning bands over the window (``Readmission._leak_passes``), where
before it flagged ``BLIND`` and the pack was cut at the fault's row (benchmarks/bench_cmon89b.py).

The column machine (``thermocomp simulate sim=column_moving_source``, seed 8841: cmon85's record),
MLR deployed adaptive as by default, its test campaign with bench_audit89's range fault (the
campaign's maximum + 25 degC for a tenth of the rows from the middle) on ``T_front3``, which no
other sensor predicts."""

from __future__ import annotations

import numpy as np
import pytest

from test_export import needs_cc
from test_export_cmon85 import _mirror, column_system, without
from test_export_cmon87 import held_as_served
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
from thermocomp.apps.deploy.export.served import ServedStreams
from thermocomp.apps.deploy.export.watch import BLIND, OFF_RANGE

SENSOR = "T_front3"


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """``(deployed, its system with the monitor, the faulted test campaign, 0 lead-in rows, the
    test campaigns by id, no lead-ins)`` (test_export_cmon87's record's shape) and the fault's
    row (1-based)."""
    deployed, ss, frame = column_system(tmp_path_factory)
    x = frame[SENSOR].to_numpy(float).copy()
    mid = len(x) // 2
    x[mid:mid + max(10, len(x) // 10)] = np.nanmax(x) + 25.0     # bench_audit89's range fault
    frame[SENSOR] = x
    return (deployed, ss, frame, 0, {"test": frame}, {}), mid + 1


@pytest.fixture(scope="module")
def streams(record):
    """The served streams of ``record``'s model, made once for the module's tests and packs."""
    return ServedStreams(record[0][0])


def _served(streams, frame) -> tuple[np.ndarray, list[dict]]:
    rows = streams.rows(frame, "test")
    return rows.y, [e for e in rows.events if e.get("sensor") == SENSOR]


def test_the_fault_is_of_a_sensor_no_other_predicts_served_out_and_back_by_its_leak(record,
                                                                                     streams):
    (deployed, ss, frame, *_), row = record
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    assert not ss.monitor["predictable"][names.index(SENSOR)]
    _, events = _served(streams, frame)
    assert [e["to"] for e in events[:2]] == ["excluded", "ok"]
    assert "leak" in events[1]["reason"]


@needs_cc
def test_the_code_holds_the_range_reading_and_its_return_as_served(record, streams, tmp_path):
    """The mirror and the compiled C equal to the served corrections on every row, nothing
    flagged, the pack whole and its check passing (test_export_cmon87's ``held_as_served``)."""
    system, row = record
    out, _, _ = held_as_served(system, tmp_path, streams)
    assert (row, SENSOR, OFF_RANGE) in out


def test_an_export_before_cmon89b_flags_the_range_reading(record, streams):
    """Arrays without ``blind_range``: flagged ``BLIND`` at the fault's row, the correction parting
    from the served one there, the pack cut at it."""
    (deployed, ss, frame, _, tests, _), row = record
    old = without(ss, "blind_range")
    got, _, missed = _mirror(old, frame, rows=row)         # (to the fault its assertions read)
    assert missed and missed[0] == (row, BLIND)
    want = corrections(ss, _served(streams, frame)[0])[:row]      # (the rows stepped)
    assert (np.flatnonzero(np.abs(got - want).max(axis=1) > 1e-9) + 1).min() == row
    _, summary = conformance_pack(deployed, old, tests, {}, served=streams)
    assert summary["campaigns"][0]["rows"] == row - 1
