"""A culprit taken out within its own band comes back within its whole band in the exported code
too (mon85b, issue 34): served, numpy mirror and compiled C on a deployed model whose record
takes that branch (bench_mon85b's own case, the monitor warmed on the train part, is no
deployed model: neither the mirror's ``hid`` nor the C's ``mon_hid`` was reached there).

fl_thermal (the measured spindle, ``data=fl_thermal``) deployed as replay does (adaptive MLR),
its test campaign with ``T_t1`` drifting 2.7 K/h and ``T_t7`` 1 K/h from row ``ONSET`` for ``RISE``
rows, then back as fast (a transient that ends): the healthy ``T_t2`` (``T_t1``'s neighbour) goes
out as the culprit while still within its own warning band, itself the likelier single fault
(measured: row 284, -0.38 °C for a 0.40 band, standardised 0.291 against the drifting ``T_t1``'s
0.289), and the served monitor re-admits it within that whole band as the transient ebbs (row
326; half of it, before mon85b: row 349).  The campaign as measured: nothing out.  The record
before (mon85b's, ``T_t12`` 1 K/h and ``T_t14`` 2.7 K/h kept on) took the healthy ``T_t15`` out
within its band for the drifting ``T_t14``, the likelier fault and out of its band; under mon87's
rule (benchmarks/bench_mon87.py) ``T_t14`` goes out instead and that record no longer reaches
this branch.  One drift alone did not serve (mon85b's search, each sensor at 0.5-6.7 K/h): the
code holds one sensor out at a time, and there the culprit came back only as the drifting sensor
went out (``T_t1`` at 4 K/h: ``T_t2`` out at row 269, back at 973 as ``T_t1`` goes out), which the
code flags as not in it (a drift judged with a sensor out, row 294) before that return."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import copied_once, fl_thermal_served
from test_export import needs_cc
from test_export_cmon80 import streamed_as_served
from thermocomp.apps.deploy.export import Simulator
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.export.served import ServedStreams
from thermocomp.apps.deploy.export.watch import EXCLUDED, NOT_IN_CODE, READMITTED

# °C a 15 s row from row ONSET for RISE rows, then back as fast: T_t1 2.7 K/h, T_t7 1 K/h
ONSET, RISE, DRIFTS, CULPRIT = 240, 60, {"T_t1": 40 / 3600, "T_t7": 15 / 3600}, "T_t2"


@pytest.fixture(scope="module")
def served():
    """``(deployed, its system with the monitor, the test campaign with the transient)``: fitted
    once for a worker's tests, each module given a deep copy (scopec: test_export_mon86 takes this
    fixture, and fitted the same model again)."""
    deployed, ss, frame = _fl_thermal_copy()
    rows = np.arange(len(frame) - ONSET)
    for name, rate in DRIFTS.items():
        frame.loc[ONSET:, name] += np.clip(RISE - np.abs(rows - RISE), 0, None) * rate
    return deployed, ss, frame


_fl_thermal_copy = copied_once(fl_thermal_served)


def _mirror(ss, frame, hid: bool = True, rows: int | None = None):
    """The numpy mirror's corrections and its ``(row, flag)`` moves of ``CULPRIT`` (1-based;
    excluded, re-admitted), each with whether it was out as a culprit within its band there,
    and the rows it flags a rule not in the code (with that rule);
    ``hid=False``: that mark wiped every row (the code before mon85b); ``rows``: the first rows
    only (ci104b: a row's step reads no later row)."""
    sim = Simulator(ss)
    sim.reset()
    k = [ss.inputs[i] for i in ss.monitor["inputs"]].index(CULPRIT)
    got, moves = [], []
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float)[:rows], frame["time"].iloc[:rows])):
        if not hid:
            sim.watch.hid[:] = False
        was = bool(sim.watch.hid[k])
        got.append(sim.step(u, t))
        w = sim.watch
        if w.flags & NOT_IN_CODE:
            moves.append((i + 1, "not in the code", w.missed))
        if w.sensor == k and w.flags & EXCLUDED:
            moves.append((i + 1, "excluded", bool(w.hid[k])))
        if w.sensor == k and w.flags & READMITTED:
            moves.append((i + 1, "ok", was))
    return np.array(got), moves


@needs_cc
def test_a_culprit_out_within_its_band_is_back_within_it_served_mirror_and_c(served, tmp_path):
    deployed, ss, frame = served
    streams = ServedStreams(deployed)         # (the pack's stream of the frame: this one)
    run = streams.rows(frame, "K06")
    times = frame["time"].to_numpy(float) - frame["time"].iloc[0]
    moves = [(int(np.searchsorted(times, e["time"])) + 1, e["to"]) for e in run.events
             if e.get("sensor") == CULPRIT and "excluded" in (e["from"], e["to"])]
    assert [to for _, to in moves][:2] == ["excluded", "ok"], moves
    assert moves[0][0] > ONSET
    got, code = _mirror(ss, frame)
    # the mirror moves on the served rows, marked within its band when out, and the first return
    # is by the whole band: without the mark it is not back there
    assert [(r, to) for r, to, _ in code] == moves
    assert code[0][2] and code[1][2]
    _, before = _mirror(ss, frame, hid=False, rows=moves[1][0])      # (to the rows it reads)
    assert before[0] == code[0], before
    assert not any(to == "ok" and r <= moves[1][0] for r, to, _ in before), before
    want = corrections(ss, run.y)
    assert np.max(np.abs(got - want)) < 1e-9
    _, said = streamed_as_served(tmp_path, deployed, ss, "K06", frame, want, streams)
    # the code's own word on the served rows (its line = the row + the header's)
    assert [int(m.split(":")[1].split()[-1]) - 1 for m in said.splitlines()
            if f"{CULPRIT}: re-admitted" in m][:1] == [moves[1][0]]
    assert "or out as a culprit within it" in said
