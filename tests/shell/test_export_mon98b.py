"""A reading beyond its range of a sensor no other predicts while another sensor is out, in the
exported C (mon98b, issue 34): the code's monitor holds it out as the second, as the served
monitor does (read as missing, held at its last reading), where before it flagged ``RANGE`` and
the pack was cut at the fault's row (benchmarks/bench_mon98b.py: fresh dl9845's drifting
``T_amb`` left its range while the blind ``T_table`` was out as explaining; served took ``T_amb``
out and ``T_table`` back in one sample, the code kept ``T_table`` out: 10.6 µm apart).

The column machine (cmon85's record, seed 8841), MLR deployed adaptive as by default, its test
campaign with a dropout of a sensor the others predict and, inside it, cmon89b's range fault on
``T_front3``, which no other sensor predicts."""

from __future__ import annotations

import numpy as np
import pytest

from test_export import needs_cc
from test_export_cmon85 import _mirror, column_system, without
from test_export_cmon87 import held_as_served
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.export.served import ServedStreams
from thermocomp.apps.deploy.export.watch import OFF_RANGE, RANGE

SENSOR = "T_front3"


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """``(deployed, its system, the faulted test campaign, 0 lead-in rows, the test campaigns by
    id, no lead-ins)``, the sensor dropped out and the range fault's row (1-based)."""
    deployed, ss, frame = column_system(tmp_path_factory)
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    dropped = next(n for n, p in zip(names, ss.monitor["predictable"]) if p and n != SENSOR)
    mid, rows = len(frame) // 2, max(10, len(frame) // 10)
    frame.loc[mid - 5:mid + rows + 5, dropped] = np.nan            # out first, back after
    x = frame[SENSOR].to_numpy(float).copy()
    x[mid:mid + rows] = np.nanmax(x) + 25.0                        # bench_audit89's range fault
    frame[SENSOR] = x
    return (deployed, ss, frame, 0, {"test": frame}, {}), dropped, mid + 1


@pytest.fixture(scope="module")
def streams(record):
    """The served streams of ``record``'s model, made once for the module's tests and packs."""
    return ServedStreams(record[0][0])


def test_served_takes_the_range_reading_out_as_the_second(record, streams):
    (deployed, ss, frame, *_), dropped, row = record
    rows = streams.rows(frame, "test")
    out = [e["sensor"] for e in rows.events if e.get("to") == "excluded"]
    assert out[:2] == [dropped, SENSOR]


@needs_cc
def test_the_code_holds_it_as_the_second_as_served(record, streams, tmp_path):
    """The mirror and the compiled C equal to the served corrections on every row, nothing
    flagged, the pack whole and its check passing (fails on da1272c3: ``RANGE`` flagged)."""
    system, _, row = record
    out, _, _ = held_as_served(system, tmp_path, streams)
    assert (row, SENSOR, OFF_RANGE) in out


def test_an_export_before_mon98b_flags_the_range_reading(record, streams):
    """Arrays without ``second_range``: flagged ``RANGE`` at the fault's row, parting there."""
    (deployed, ss, frame, *_), _, row = record
    got, _, missed = _mirror(without(ss, "second_range"), frame, rows=row)    # (to the fault)
    assert missed and missed[0] == (row, RANGE)
    want = corrections(ss, streams.rows(frame, "test").y)[:row]      # (the rows stepped)
    assert (np.flatnonzero(np.abs(got - want).max(axis=1) > 1e-9) + 1).min() == row
