"""A stepped error's culprit out in the exported C (cmon86, issue 34): the code's monitor excludes
the culprit of a self-prediction error stepped past the alarm band (the served
``_check_stepped``), a second sensor beside one out, where before it flagged ``STEPPED`` and the
pack was cut there (benchmarks/bench_cmon86.py).

The column machine (``thermocomp simulate sim=column_moving_source``, seed 8841, bench_cmon85's),
MLR deployed adaptive as by default, its test campaign with bench_cmon82's sensor drifting from
the middle (bench_cmon84's drift): it goes out for its range, and with it out another sensor's
error steps past its alarm band."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from test_export import needs_cc
from test_export_cmon80 import assert_packed_as_served
from test_export_cmon85 import _mirror, _served_out, column_record, without
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
from thermocomp.apps.deploy.export.served import ServedStreams
from thermocomp.apps.deploy.export.watch import STEPPED

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))

SEED = 8841


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """``(deployed, its system with the monitor, the test campaign with the drift)``."""
    return column_record(tmp_path_factory, "drift")


@pytest.fixture(scope="module")
def streams(record):
    """The served streams of ``record``'s model, made once for the module's tests and packs."""
    return ServedStreams(record[0])


def _outs(ss) -> tuple[list[tuple[int, str, bool]], object]:
    """Each sensor the numpy mirror puts out: ``(row, sensor, by its error)`` (two in a row
    too: the sample's first event alone names its rule), filled by the second item, the
    ``each`` of :func:`_mirror`'s pass (ci104b: read from that pass, not a second one)."""
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    out, seen = [], set()

    def each(i, sim):
        nonlocal seen
        w = sim.watch
        now = {k for k in (w.out, w.out2) if k >= 0}
        out.extend((i + 1, names[k], bool(w.by_field[k])) for k in sorted(now - seen))
        seen = now
    return out, each


def _stepped_row(served) -> tuple[int, str]:
    """The served stepped exclusion's ``(row, sensor)``: in the sample of another sensor's
    exclusion (a second out)."""
    row, sensor = next((r, s) for r, s, why in served if why == "jump" and (r, s) != served[0][:2])
    assert any(r == row and s != sensor for r, s, _ in served), served
    return row, sensor


@needs_cc
def test_a_stepped_culprit_is_followed_by_the_code_as_served(record, streams, tmp_path):
    deployed, ss, frame = record
    served = _served_out(streams, frame)
    row, sensor = _stepped_row(served)
    want = corrections(ss, streams.rows(frame, "test").y)
    out, each = _outs(ss)
    got, _, missed = _mirror(ss, frame, each=each)
    assert not missed and np.max(np.abs(got - want)) < 1e-9
    assert sorted((r, s) for r, s, _ in out) == sorted((r, s) for r, s, _ in served)
    # the culprit out by its error (its wait doubled), beside the one out for its range
    assert sorted((s, by) for r, s, by in out if r == row) == sorted(
        [(s, s == sensor) for r, s, _ in served if r == row])
    assert_packed_as_served(tmp_path, deployed, ss, "test", frame, want, streams)


def test_an_export_before_cmon86_flags_the_stepped_error(record, streams):
    """Arrays without ``stepped``: the stepped error flagged (``STEPPED``) at the served
    exclusion's row, and the pack cut there."""
    deployed, ss, frame = record
    row, _ = _stepped_row(_served_out(streams, frame))
    _, _, missed = _mirror(without(ss, "stepped"), frame, rows=row)     # (its first flag)
    assert missed and missed[0] == (row, STEPPED)
    _, summary = conformance_pack(deployed, without(ss, "stepped"), {"test": frame},
                                  served=streams)
    assert summary["campaigns"][0]["rows"] < row
