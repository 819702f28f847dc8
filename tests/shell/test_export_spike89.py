"""The exported C follows mon89's spike as served (benchmarks/bench_mon89.py ``pack``): a sensor
out for a jump whose next jump brings it back to the field on its reference before the first is
in again at once, its reference put back (``spike``).  The record is
tests/shell/test_monitor_spike89.py's lr9211 (MLR), R1b fed after its lead-in R1a."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from test_export import built_stream, needs_cc
from test_export_cmon80 import _streamed
from test_monitor_readmit88 import deployed_record
from test_monitor_spike89 import LONG
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections, fed
from thermocomp.apps.deploy.report import plain, stream_rows
from thermocomp.core.continuation import lead_ins


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """``(deployed, ss, {R1b: frame}, {R1b: lead-in})`` of lr9211."""
    deployed, ds, test_ids = deployed_record(tmp_path_factory.mktemp("lr9211") / "data", LONG,
                                             ("data.reference=none",))
    (test,) = test_ids
    return (deployed, state_space(deployed, monitor=True),
            {test: ds.campaigns[test].reset_index(drop=True)},
            lead_ins(plain(deployed).compensator, ds, test_ids))


def _mirror_out_rows(ss, frame, lead: int) -> list[int]:
    """The rows (0-based, of the campaign after its ``lead`` rows of lead-in) after which the
    numpy mirror holds a sensor out."""
    sim = Simulator(ss)
    sim.reset()
    rows = []
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
        sim.step(u, t)
        if sim.watch.out >= 0 and i >= lead:
            rows.append(i - lead)
    return rows


@needs_cc
def test_the_code_reads_the_spike_as_served(record, tmp_path):
    deployed, ss, tests, leads = record
    (cid, campaign), = tests.items()
    frame = fed(campaign, leads.get(cid))
    want = corrections(ss, stream_rows(deployed, frame, cid).y)
    assert len(_mirror_out_rows(ss, frame, len(frame) - len(campaign))) == 1   # the spike's alone
    files, summary = conformance_pack(deployed, ss, tests, leads)
    entry = next(e for e in summary["campaigns"] if e["campaign"] == cid)
    assert entry["cut"] is None and entry["rows"] == len(frame)
    stream = built_stream(tmp_path, {**exported_files(deployed, "c"), **files})
    c, said = _streamed(stream, frame, ss.inputs)
    assert c.shape == want.shape and np.max(np.abs(c - want)) < 1e-9        # every row
    assert "not in the code" not in said


def test_an_export_before_mon89_re_references_the_return_as_before(record):
    """Arrays without ``spike``: the mirror as before (out until its calm window has passed)."""
    deployed, ss, tests, leads = record
    old = dataclasses.replace(ss, monitor={k: v for k, v in ss.monitor.items() if k != "spike"})
    (cid, campaign), = tests.items()
    frame = fed(campaign, leads.get(cid))
    out = _mirror_out_rows(old, frame, len(frame) - len(campaign))
    assert len(out) > deployed.monitor.window
