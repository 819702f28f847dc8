"""The exported C follows mon88's re-admission as served (benchmarks/bench_mon88.py ``pack``): a
sensor out by the field's judgement, blind only for want of a partner out frozen, comes back
(``cleared``).  The record is tests/shell/test_monitor_readmit88.py's cr9031 (MLR) with
``T_amb`` frozen from a third of C11, on the monitor as before mon97 (``undithered``: its
premise, the cabinet taken for the frozen ambient); and, as the room is since mon97, the C taking
the frozen ambient out for its freeze as served."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from test_export import built_stream, needs_cc
from test_export_cmon80 import _streamed
from test_monitor_readmit88 import ROOM, deployed_record, frozen_amb, undithered
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections, fed
from thermocomp.apps.deploy.export.served import ServedStreams
from thermocomp.apps.deploy.report import stream_rows


@pytest.fixture(scope="module")
def drawn(tmp_path_factory):
    """``(deployed, {C11: frame with T_amb frozen}, {})`` of cr9031."""
    deployed, ds, _ = deployed_record(tmp_path_factory.mktemp("cr9031") / "data", ROOM)
    return deployed, {"C11": frozen_amb(ds.campaigns["C11"].reset_index(drop=True))}, {}


@pytest.fixture(scope="module")
def room(drawn):
    """``(deployed, ss, tests, leads)``, the monitor as before mon97 (``undithered``)."""
    deployed, tests, leads = drawn
    deployed = undithered(deployed)
    return deployed, state_space(deployed, monitor=True), tests, leads


def _mirror_out(ss, frame) -> list[str]:
    """The sensors the numpy mirror holds out after ``frame``'s last row."""
    sim = Simulator(ss)
    sim.reset()
    for u, t in zip(frame[ss.inputs].to_numpy(float), frame["time"]):
        sim.step(u, t)
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    return [names[k] for k in (sim.watch.out, sim.watch.out2) if k >= 0]


def assert_code_as_served(deployed, ss, tests: dict, leads: dict, folder,
                          served: ServedStreams | None = None) -> None:
    """The compiled C of ``deployed`` (built in ``folder``) streams the one test campaign of
    ``tests`` after its lead-in as served, every row, nothing flagged "not in the code".
    ``served``: the served streams of ``deployed`` made so far (else new ones)."""
    (cid, campaign), = tests.items()
    frame = fed(campaign, leads.get(cid))
    served = ServedStreams(deployed) if served is None else served
    want = corrections(ss, served.rows(frame, cid).y)
    files, summary = conformance_pack(deployed, ss, tests, leads, served=served)
    entry = next(e for e in summary["campaigns"] if e["campaign"] == cid)
    assert entry["cut"] is None and entry["rows"] == len(frame)
    stream = built_stream(folder, {**exported_files(deployed, "c"), **files})
    c, said = _streamed(stream, frame, ss.inputs)
    assert c.shape == want.shape and np.max(np.abs(c - want)) < 1e-9        # every row
    assert "not in the code" not in said


@needs_cc
def test_the_code_brings_the_healthy_sensor_back_as_served(room, tmp_path):
    deployed, ss, tests, leads = room
    (cid, campaign), = tests.items()
    assert _mirror_out(ss, fed(campaign, leads.get(cid))) == ["T_amb"]
    assert_code_as_served(deployed, ss, tests, leads, tmp_path)


def test_an_export_before_mon88_keeps_it_out_as_before(room):
    """Arrays without ``cleared``: the mirror as before (the healthy sensor kept out)."""
    deployed, ss, tests, leads = room
    old = dataclasses.replace(ss, monitor={k: v for k, v in ss.monitor.items() if k != "cleared"})
    (cid, campaign), = tests.items()
    assert sorted(_mirror_out(old, fed(campaign, leads.get(cid)))) == ["T_amb", "T_nc_cabinet"]


@needs_cc
def test_the_code_takes_the_frozen_ambient_out_for_its_freeze_as_served(drawn, tmp_path):
    """(mon97) The room as it is: ``T_amb`` out for its freeze (its readings dither), the cabinet
    never, the C as served on every row (before mon97: the cabinet out with it, then back)."""
    deployed, tests, leads = drawn
    ss = state_space(deployed, monitor=True)
    (cid, campaign), = tests.items()
    frame = fed(campaign, leads.get(cid))
    out = [e for e in stream_rows(deployed, frame, cid).events
           if e.get("sensor") and e["to"] == "excluded"]
    assert [e["sensor"] for e in out] == ["T_amb"] and out[0]["reason"].startswith("freeze:"), out
    assert _mirror_out(ss, frame) == ["T_amb"]
    assert_code_as_served(deployed, ss, tests, leads, tmp_path)
