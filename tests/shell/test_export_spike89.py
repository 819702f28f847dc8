"""The exported C follows mon89's spike as served (benchmarks/bench_mon89.py ``pack``): a sensor
out for a jump whose next jump brings it back to the field on its reference before the first is
in again at once, its reference put back (``spike``).  The record is
tests/shell/test_monitor_spike89.py's lr9211 (MLR), R1b fed after its lead-in R1a's last 864 rows
(test_export_cmon87's ``LEAD_ROWS``, ci102h; R1a's 3457 before): the spike the same, ``T_head_left``
out at R1b's row 581 and back a sample later, served and in the mirror, as after R1a whole (the
export before mon89 holds it out 11 rows, 17 after R1a whole: both past the calm window of 10)."""

from __future__ import annotations

import dataclasses

import pytest

from test_export import needs_cc
from test_export_cmon87 import last_rows
from test_export_mon88 import assert_code_as_served
from test_monitor_readmit88 import deployed_record
from test_monitor_spike89 import LONG
from thermocomp.apps.deploy.export import Simulator, state_space
from thermocomp.apps.deploy.export.pack import fed
from thermocomp.apps.deploy.report import plain
from thermocomp.core.continuation import lead_ins


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """``(deployed, ss, {R1b: frame}, {R1b: its lead-in's last LEAD_ROWS})`` of lr9211."""
    deployed, ds, test_ids = deployed_record(tmp_path_factory.mktemp("lr9211") / "data", LONG,
                                             ("data.reference=none",))
    (test,) = test_ids
    return (deployed, state_space(deployed, monitor=True),
            {test: ds.campaigns[test].reset_index(drop=True)},
            last_rows(lead_ins(plain(deployed).compensator, ds, test_ids)))


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
    assert len(_mirror_out_rows(ss, frame, len(frame) - len(campaign))) == 1   # the spike's alone
    assert_code_as_served(deployed, ss, tests, leads, tmp_path)


def test_an_export_before_mon89_re_references_the_return_as_before(record):
    """Arrays without ``spike``: the mirror as before (out until its calm window has passed)."""
    deployed, ss, tests, leads = record
    old = dataclasses.replace(ss, monitor={k: v for k, v in ss.monitor.items() if k != "spike"})
    (cid, campaign), = tests.items()
    frame = fed(campaign, leads.get(cid))
    out = _mirror_out_rows(old, frame, len(frame) - len(campaign))
    assert len(out) > deployed.monitor.window
