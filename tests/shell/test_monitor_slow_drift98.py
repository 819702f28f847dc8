"""A slow drift named, served and in the exported code alike (mon98, issue 34; benchmarks/
bench_mon98.py).

cr9763 (audit95's climate room, mlr): ``T_amb`` drifts +1 K/h from a quarter into test campaign
C07.  At row 18 of the drift its error passes its band; it is the likelier single fault and with
it out every other judged sensor is within band, but its exclusion leaves its coupled partner
``T_nc_cabinet`` (within its band) unjudged, which mon84b's clause refused: a new thermal state
that named no sensor, nothing out (before mon98).  Its error departed slowly (the field's memory
held 0.34 of it, ``SLOW_SHARE`` 0.25), so it is taken now, its blind partner with it, served, in
the export's mirror and in the compiled C alike; an export or a monitor from before the rule
judges as before."""

from __future__ import annotations

import copy
import pickle

import numpy as np
import pytest

from test_export import needs_cc
from test_export_cmon80 import streamed_as_served
from test_monitor_readmit88 import deployed_record
from thermocomp.apps.deploy.export import state_space
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.export.watch import EXCLUDED, NOT_IN_CODE, CodeMonitor, monitor_fields
from thermocomp.apps.deploy.report import stream_rows
from thermocomp.apps.deploy.surveillance import SensorMonitor

ROOM = ("sim=climate_room", "seed=9763", "sim.generator.n_runs=8",
        "sim.generator.duration_h=[3.0,4.0]", "sim.generator.test_fraction=0.25")
K_PER_H = 1.0


@pytest.fixture(scope="module")
def drifted(tmp_path_factory):
    """``(deployed, C07 with T_amb drifting from a quarter in, the drift's first row)``."""
    deployed, ds, _ = deployed_record(tmp_path_factory.mktemp("cr9763") / "data", ROOM)
    frame = ds.campaigns["C07"].reset_index(drop=True).copy()
    start = len(frame) // 4
    period = float(np.median(np.diff(frame["time"])))
    frame.loc[start:, "T_amb"] += K_PER_H * period / 3600 * np.arange(1, len(frame) - start + 1)
    return deployed, frame, start


def _moves(events: list) -> list[tuple[float, str | None, str]]:
    return [(e["time"], e.get("sensor"), e["to"]) for e in events
            if e["to"] in ("excluded", "new thermal state")]


def test_the_drifting_ambient_goes_out_with_its_blind_partner_no_new_state(drifted):
    deployed, frame, start = drifted
    moves = _moves(stream_rows(deployed, frame, "C07").events)
    at = float(frame["time"].iloc[start + 18])
    # the drifting T_amb first, for drift, at row 18; its partner, unjudged without it, with it
    assert moves[:2] == [(at, "T_amb", "excluded"), (at, "T_nc_cabinet", "excluded")], moves
    assert not [m for m in moves if m[2] == "new thermal state"]


def test_a_monitor_pickled_before_the_rule_declares_a_new_state_as_before(drifted):
    deployed, frame, start = drifted
    old = copy.deepcopy(deployed)
    state = {k: v for k, v in old.monitor.__dict__.items() if k != "slow_share"}
    old.monitor = SensorMonitor.__new__(SensorMonitor)
    old.monitor.__setstate__(pickle.loads(pickle.dumps(state)))
    moves = _moves(stream_rows(old, frame, "C07").events)
    assert moves[0] == (float(frame["time"].iloc[start + 18]), None, "new thermal state"), moves
    assert not [m for m in moves if m[2] == "excluded"]


def _mirror_outs(deployed, frame, drop: tuple = ()) -> tuple[list[tuple[int, str]], int | None]:
    """The export's numpy mirror of ``deployed``'s monitor on ``frame`` (its arrays less the keys
    ``drop``): its exclusions ``(row, sensor)`` and the row it first holds a new thermal state; it
    must flag nothing it does not hold."""
    names = deployed.monitor.names
    arrays = monitor_fields(deployed, names)["monitor"]
    code, outs, novel = CodeMonitor({k: v for k, v in arrays.items() if k not in drop}), [], None
    t = frame["time"].to_numpy(float)
    for i, row in enumerate(frame[names].to_numpy(float)):
        code.step(row, i == 0, t[i] - t[i - 1] if i else deployed.period_s)
        assert not code.flags & NOT_IN_CODE, (i, code.missed)
        if code.flags & EXCLUDED:
            outs.append((i, names[code.sensor]))
        if code.novel and novel is None:
            novel = i
    return outs, novel


def test_the_exported_mirror_takes_it_out_as_served_and_an_older_export_does_not(drifted):
    deployed, frame, start = drifted
    outs, novel = _mirror_outs(deployed, frame)
    assert outs[0] == (start + 18, "T_amb") and novel is None, outs
    outs, novel = _mirror_outs(deployed, frame, drop=("slow_share",))   # an export before it
    assert not outs and novel == start + 18


@needs_cc
def test_the_compiled_c_streams_it_as_served(drifted, tmp_path):
    deployed, frame, _ = drifted
    ss = state_space(deployed, monitor=True)
    assert ss.monitor["slow_share"] == pytest.approx(0.25)
    want = corrections(ss, stream_rows(deployed, frame, "C07").y)
    streamed_as_served(tmp_path, deployed, ss, "C07", frame, want)
