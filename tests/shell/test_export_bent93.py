"""The exported C reads a step of a sensor no other predicts off its own last step as served
(step93; benchmarks/bench_step93.py): re-referenced by the departure, kept in.  The record is
bench_audit89's swiss9317 (``sim=swiss_lathe_door``, MLR), its spindle motor stepped by twice its
largest training step (under its jump limit) from the test campaign's middle row on."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from test_export import needs_cc
from test_export_mon88 import assert_code_as_served
from test_monitor_readmit88 import deployed_record
from thermocomp.apps.deploy.export import Simulator, state_space
from thermocomp.apps.deploy.export.pack import fed
from thermocomp.apps.deploy.export.served import ServedStreams
from thermocomp.apps.deploy.export.watch import BENT, REREFERENCED
from thermocomp.apps.deploy.report import plain
from thermocomp.core.continuation import lead_ins

MOTOR = "T_nc_spindle_motor"


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """``(deployed, ss, {test: stepped frame}, leads, the step's row)`` of swiss9317."""
    deployed, ds, test_ids = deployed_record(tmp_path_factory.mktemp("swiss9317") / "data",
                                             ("seed=9317", "sim=swiss_lathe_door"))
    (test,) = test_ids
    frame = ds.campaigns[test].reset_index(drop=True)
    row = len(frame) // 2
    j = deployed.monitor.names.index(MOTOR)
    frame.loc[row:, MOTOR] += 2.0 * deployed.monitor.max_step_c[j]
    return (deployed, state_space(deployed, monitor=True), {test: frame},
            lead_ins(plain(deployed).compensator, ds, test_ids), row)


@pytest.fixture(scope="module")
def streams(record):
    """The served streams of ``record``'s model, made once for the module's tests and packs."""
    return ServedStreams(record[0])


def _mirror_bent_rows(ss, frame, lead: int) -> list[int]:
    """The rows (0-based, of the campaign after ``lead`` rows of lead-in) where the numpy mirror
    re-references a sensor for a step off its own."""
    sim = Simulator(ss)
    sim.reset()
    rows = []
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
        sim.step(u, t)
        if sim.watch.flags & REREFERENCED and sim.watch.rule == BENT and i >= lead:
            rows.append(i - lead)
    return rows


def test_served_re_references_the_step_and_keeps_the_motor_in(record, streams):
    deployed, _, tests, leads, row = record
    (cid, frame), = tests.items()
    got = streams.rows(fed(frame, leads.get(cid)), cid)
    said = [(e["sensor"], e["to"]) for e in got.events if e.get("sensor")]
    assert said == [(MOTOR, "re-referenced")], said          # before: nothing (read as heat)


@needs_cc
def test_the_code_reads_the_step_as_served(record, streams, tmp_path):
    deployed, ss, tests, leads, row = record
    (cid, campaign), = tests.items()
    frame = fed(campaign, leads.get(cid))
    assert _mirror_bent_rows(ss, frame, len(frame) - len(campaign)) == [row]
    assert_code_as_served(deployed, ss, tests, leads, tmp_path, streams)


def test_an_export_before_step93_reads_the_step_as_heat(record):
    """Arrays without ``bent``: the mirror as before (no re-reference)."""
    _, ss, tests, leads, _ = record
    old = dataclasses.replace(ss, monitor={k: v for k, v in ss.monitor.items() if k != "bent"})
    (cid, campaign), = tests.items()
    frame = fed(campaign, leads.get(cid))
    assert _mirror_bent_rows(old, frame, len(frame) - len(campaign)) == []
    assert np.isfinite(ss.monitor["bend_lim"]).sum() == 2     # the two motors no other predicts
