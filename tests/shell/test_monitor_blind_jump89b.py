"""A blind sensor's own one-sample jump behind a frozen-out partner (mon89b, issue 34;
benchmarks/bench_mon89b.py).

bench_mon88's fresh cr9201 (a climate room, MLR), test campaign C12 as that bench planted it:
``T_amb`` frozen from a third of the campaign (out for its freeze), then ``T_nc_cabinet`` -3.31 °C
on one sample two thirds in.  With ``T_amb`` out no sensor predicts ``T_nc_cabinet``; out for its
jump, it was blind at every re-admission check and stayed out to the campaign's end (served,
mirror and C alike).  Now, out for its own jumps alone and blind only for want of a partner out
frozen, it passes after its calm window as one no other predicts does, its two jumps undone
(``Readmission._jumped_alone``; the export key ``jump_cleared``)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from test_export import needs_cc
from test_export_mon88 import _mirror_out, assert_code_as_served
from test_monitor_readmit88 import deployed_record, frozen_amb
from thermocomp.apps.deploy.export import state_space
from thermocomp.apps.deploy.report import stream_rows
from thermocomp.apps.deploy.surveillance.monitor import SensorMonitor

ROOM = ("sim=climate_room", "seed=9201", "sim.generator.n_runs=12",
        "sim.generator.duration_h=[3.0,4.0]", "sim.generator.test_fraction=0.25")
SPIKE_C = -3.31      # bench_mon88's planted spike on C12 (one sample, two thirds in)


@pytest.fixture(scope="module")
def room(tmp_path_factory):
    """``(deployed, ss, C12 as drawn, C12 with T_amb frozen and the spike, spike row)``."""
    deployed, ds, _ = deployed_record(tmp_path_factory.mktemp("cr9201") / "data", ROOM)
    drawn = ds.campaigns["C12"].reset_index(drop=True)
    frame = frozen_amb(drawn)
    row = 2 * len(frame) // 3
    frame.loc[row, "T_nc_cabinet"] += SPIKE_C
    return deployed, state_space(deployed, monitor=True), drawn, frame, row


def _moves(events: list, sensor: str) -> list[tuple[str, float]]:
    return [(e["to"], e["time"]) for e in events if e.get("sensor") == sensor]


def test_the_spiked_sensor_comes_back_after_its_calm_window(room):
    deployed, _, _, frame, row = room
    mon = deployed.monitor
    period = float(np.median(np.diff(frame["time"])))
    events = stream_rows(deployed, frame, "C12").events
    cabinet, amb = _moves(events, "T_nc_cabinet"), _moves(events, "T_amb")
    assert [to for to, _ in amb] == ["excluded"]                   # frozen: out to the end
    assert cabinet[0] == ("excluded", frame["time"][row])           # out for its jump ...
    assert len(cabinet) == 2 and cabinet[1][0] == "ok", cabinet      # ... and back (main: never)
    # within its calm window and confirm of the spike's end (one sample)
    assert cabinet[1][1] - frame["time"][row] <= (1 + mon.window + mon.confirm) * period


def test_its_jumps_are_undone_at_its_return(room, monkeypatch):
    """The return puts back the reference it had before the spike: the spike's two whole-step
    re-references leave nothing in it (they were the field's one-sample change and noise)."""
    deployed, _, _, frame, row = room
    k = deployed.monitor.names.index("T_nc_cabinet")
    refs, update = [], SensorMonitor.update

    def kept(self, *args, **kwargs):     # each sample's reference of the spiked sensor
        out = update(self, *args, **kwargs)
        refs.append(np.nan if self._ref is None else float(self._ref[k]))
        return out

    monkeypatch.setattr(SensorMonitor, "update", kept)
    stream_rows(deployed, frame, "C12")
    refs = np.asarray(refs[-len(frame):])
    assert abs(refs[row] - refs[row - 1]) > 1.0            # re-referenced at the spike
    assert refs[-1] == pytest.approx(refs[row - 1], abs=1e-12)   # main: +0.05 °C kept


def test_one_no_other_predicts_comes_back_on_calm_as_before(room):
    """The control (passes on main; the rule's first draft, which cleared it only behind a
    frozen partner that would predict it, kept it out to the end: fresh cr9360): a one-sample
    jump of ``T_nc_tool_motor``, predicted by no sensor, behind the frozen ``T_amb``."""
    deployed, _, drawn, _, row = room
    frame = frozen_amb(drawn)
    frame.loc[row, "T_nc_tool_motor"] += 2.48
    moves = _moves(stream_rows(deployed, frame, "C12").events, "T_nc_tool_motor")
    assert [to for to, _ in moves] == ["excluded", "ok"], moves


def test_the_campaign_as_drawn_stays_quiet(room):
    """The control: C12 as drawn, nothing excluded (on main too)."""
    deployed, _, drawn, _, _ = room
    assert not [e for e in stream_rows(deployed, drawn, "C12").events if e.get("sensor")]


@needs_cc
def test_the_code_brings_it_back_as_served(room, tmp_path):
    deployed, ss, _, frame, _ = room
    assert_code_as_served(deployed, ss, {"C12": frame}, {}, tmp_path, ["T_amb"])


def test_an_export_before_mon89b_keeps_it_out_as_before(room):
    """Arrays without ``jump_cleared``: the mirror as before (the spiked sensor kept out)."""
    _, ss, _, frame, _ = room
    old = dataclasses.replace(ss, monitor={k: v for k, v in ss.monitor.items()
                                           if k != "jump_cleared"})
    assert sorted(_mirror_out(old, frame)) == ["T_amb", "T_nc_cabinet"]
