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

import subprocess

import numpy as np
import pytest

from test_export import _compose, built_stream, needs_cc
from test_export_cmon80 import _streamed
from test_export_cmon85 import SEED, _mirror, without
from thermocomp.apps.deploy.export import exported_files, state_space
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
from thermocomp.apps.deploy.export.watch import BLIND, OFF_RANGE
from thermocomp.apps.deploy.report import stream_rows

SENSOR = "T_front3"


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """``(deployed, its system with the monitor, the faulted test campaign, the fault's row
    (1-based), the test campaigns by id)``."""
    from thermocomp.shell.builders import build_compensator, deploy_stream, deployable
    from thermocomp.shell.cli import main
    from thermocomp.shell.source import read_streamed

    data = tmp_path_factory.mktemp(f"column{SEED}") / "data"
    assert main(["-q", "simulate", f"seed={SEED}", f"data.path={data}", "track=false",
                 "sim=column_moving_source"]) == 0
    cfg = _compose(f"data.path={data}", "track=false", "model=mlr")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {k: ds.campaigns[k] for k in train_ids}
    deployed = deployable(cfg, deploy_stream(cfg, build_compensator(cfg, ds=ds).fit(train), train),
                          train, ds)
    ss = state_space(deployed, monitor=True)
    frame = ds.campaigns[test_ids[0]].reset_index(drop=True)
    x = frame[SENSOR].to_numpy(float).copy()
    mid = len(x) // 2
    x[mid:mid + max(10, len(x) // 10)] = np.nanmax(x) + 25.0     # bench_audit89's range fault
    frame[SENSOR] = x
    return deployed, ss, frame, mid + 1, {test_ids[0]: frame}


def _served(deployed, frame) -> tuple[np.ndarray, list[dict]]:
    rows = stream_rows(deployed, frame, "test")
    return rows.y, [e for e in rows.events if e.get("sensor") == SENSOR]


def test_the_fault_is_of_a_sensor_no_other_predicts_served_out_and_back_by_its_leak(record):
    deployed, ss, frame, row, _ = record
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    assert not ss.monitor["predictable"][names.index(SENSOR)]
    _, events = _served(deployed, frame)
    assert [e["to"] for e in events[:2]] == ["excluded", "ok"]
    assert "leak" in events[1]["reason"]


@needs_cc
def test_the_code_holds_the_range_reading_and_its_return_as_served(record, tmp_path):
    deployed, ss, frame, row, tests = record
    want = corrections(ss, _served(deployed, frame)[0])
    got, out, missed = _mirror(ss, frame)
    assert not missed and (row, SENSOR, OFF_RANGE) in out
    assert np.max(np.abs(got - want)) < 1e-9
    files, summary = conformance_pack(deployed, ss, tests, {})
    entry = summary["campaigns"][0]
    assert (entry["rows"], entry["cut"]) == (len(frame), None)
    stream = built_stream(tmp_path, {**exported_files(deployed, "c"), **files})
    c, said = _streamed(stream, frame, ss.inputs)
    assert c.shape == want.shape and np.max(np.abs(c - want)) < 1e-9        # every row
    assert "not in the code" not in said
    script = subprocess.run(["sh", "check/check.sh"], cwd=tmp_path, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr


def test_an_export_before_cmon89b_flags_the_range_reading(record):
    """Arrays without ``blind_range``: flagged ``BLIND`` at the fault's row, the correction parting
    from the served one there, the pack cut at it."""
    deployed, ss, frame, row, tests = record
    old = without(ss, "blind_range")
    got, _, missed = _mirror(old, frame)
    assert missed and missed[0] == (row, BLIND)
    want = corrections(ss, _served(deployed, frame)[0])
    assert (np.flatnonzero(np.abs(got - want).max(axis=1) > 1e-9) + 1).min() == row
    _, summary = conformance_pack(deployed, old, tests, {})
    assert summary["campaigns"][0]["rows"] == row - 1
