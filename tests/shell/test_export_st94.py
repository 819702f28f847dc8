"""The Structured Text block holds the C's BENT and its pair jump (st94, issue 34): a sensor no other
predicts stepping off its own last step under its jump limit is re-referenced by the departure
and kept in, as the C re-references it (``mon_rule`` BENT, the block = the C after it); two
sensors jumping in one sample are flagged ``JUMP`` on the first, as the C excludes them, where
before st94 the block read the first as heat and flagged the second ``COMMON``.

lr9132 (``thermocomp simulate sim=long_record``, seed 9132, 3 days), MLR deployed adaptive with
``data.reference=none``, its first 1100 fed rows, as tests/shell/test_export_st93.py
(benchmarks/bench_st94.py scores both rules on fresh records); the fixture and FAULT are
st94b-st100's too.  This module's own two tests read the first 300 of them with the faults
planted at row 201 (:data:`HEAD`, :data:`AT`; ci102h: 1100 and 1001 before): the C's BENT and
its two jumps at the fault's row, nothing before it, as then."""

from __future__ import annotations

import copy

import numpy as np
import pytest

from test_export import TOLERANCE_UM, StructuredText
from test_export_cmon87 import long_record
from thermocomp.apps.deploy.export import Simulator, exported_files
from thermocomp.apps.deploy.export.watch import BAND, BENT, EXCLUDED, JUMP, REREFERENCED, SPIKE

SEED = 9132
ROWS, FAULT, LOST = 1100, 1000, 5       # rows fed, the fault's first (0-based), rows a spike lasts
HEAD, AT = 300, 200     # this module's tests: the rows they feed, their fault's first (ci102h)


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """``(deployed, ss, the fed rows, the ST block)``: one tuple for the st modules of a worker,
    which read it only (each plants its faults in a copy of the rows), so that :func:`resumed`
    takes up another module's pass over the same healthy rows (scopec: its passes are keyed on
    the system itself; each module stepped the rows before its faults again)."""
    if not _RECORD:
        deployed, ss, frame, *_ = long_record(tmp_path_factory, SEED)
        block = exported_files(deployed, "st")["compensator.st"]
        _RECORD.append((deployed, ss, frame.iloc[:ROWS].reset_index(drop=True), block))
    return _RECORD[0]


_RECORD: list = []      # [record's tuple], once made


EVERY = 50          # rows between the states :func:`resumed` keeps of a pass
_PASSES: list = []  # (ss, block, key, the pass's inputs and times, rows read, {row: (block, mirror)})


def resumed(ss, block, frame, read, key) -> list:
    """``read(fb, sim, u, t, i)`` of each row of ``frame`` stepped through the ST block ``fb`` and
    the C mirror ``sim`` of ``ss``; a pass of the same ``(ss, block, key)`` over the same first
    rows resumed from its states after them (kept every :data:`EVERY` rows, deep copies), not
    stepped again (ci104b: a module's cases share the healthy rows before their faults; a row's
    step reads no later row, so the rows read are those of a whole pass)."""
    U, T = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
    times = list(frame["time"])     # (Python floats, as a Series' own iteration gives them)
    start, state = 0, None
    for ss0, block0, key0, (U0, T0), read0, marks in _PASSES:
        if ss0 is not ss or block0 != block or key0 != key:
            continue
        n = min(len(U), len(U0))
        same = np.all((U[:n] == U0[:n]) | (np.isnan(U[:n]) & np.isnan(U0[:n])), axis=1) & (
            (T[:n] == T0[:n]) | (np.isnan(T[:n]) & np.isnan(T0[:n])))
        shared = int(np.argmin(same)) if not same.all() else n
        best = max((r for r in marks if r <= shared), default=0)
        if best > start:
            start, state = best, (*marks[best], read0[:best])
    if state is None:
        fb, sim, rows = StructuredText(block), Simulator(ss), []
        sim.reset()
    else:
        fb, sim, rows = (*copy.deepcopy(state[:2]), list(state[2]))
    marks = {}
    for i in range(start, len(U)):
        if i and i % EVERY == 0:
            marks[i] = copy.deepcopy((fb, sim))
        rows.append(read(fb, sim, U[i], times[i], i))
    _PASSES.append((ss, block, key, (U, T), rows, marks))
    return rows


def _both(ss, block, frame):
    """Per row: the block's corrections and ``(mon_flag, mon_rule, mon_sensor)``, its mon_shift of
    the monitored inputs; the C mirror's corrections and ``(flags, rule, sensor)``."""
    idx = ss.monitor["inputs"]

    def read(fb, sim, u, t, i):
        st = fb(u, t, i == 0)
        v = fb.vars
        said = (bool(v["mon_flag"]), int(v["mon_rule"]), int(v["mon_sensor"]))
        shift = np.array(v["mon_shift"], float)[idx]
        c = sim.step(u, t)
        return st, said, shift, c, (int(sim.watch.flags) & ~BAND, int(sim.watch.rule), int(sim.watch.sensor))
    st, st_said, shifts, c, c_said = zip(*resumed(ss, block, frame, read, "_both"))
    return np.array(st), list(st_said), np.array(shifts), np.array(c), list(c_said)


def test_a_blind_sensors_step_off_its_own_is_re_referenced_as_the_c_does(record):
    deployed, ss, frame, block = record
    frame = frame.iloc[:HEAD]
    m, mon = ss.monitor, deployed.monitor
    names = [ss.inputs[i] for i in m["inputs"]]
    # the sensors no other predicts, each stepped twice its largest training step from AT on
    # (bench_step93's 2x: under the jump limit of 3x), the first the C re-references as BENT
    for k in [k for k, p in enumerate(m["predictable"]) if not p]:
        df = frame.copy()
        df.loc[AT:, names[k]] += 2.0 * float(mon.max_step_c[k])
        st, st_said, shifts, c, c_said = _both(ss, block, df)
        if c_said[AT] == (REREFERENCED, BENT, k):
            break
    else:
        pytest.fail("no blind sensor's step re-referenced by the C")
    # the C nothing else on these rows: the block = the C on every row, the step's included
    assert all(s == (0, 0, -1) for i, s in enumerate(c_said) if i != AT)
    assert np.max(np.abs(st - c)) <= TOLERANCE_UM
    # named at its row (kept in: no fault flagged), re-referenced there and only there
    assert st_said[AT] == (False, BENT, k)
    assert [i for i, s in enumerate(st_said) if s != (False, 0, -1)] == [AT]
    moved = np.flatnonzero(np.any(np.diff(shifts, axis=0) != 0.0, axis=1)) + 1
    assert moved.tolist() == [AT]


def test_two_sensors_jumping_in_one_sample_are_flagged_as_the_c_excludes_them(record):
    _, ss, frame, block = record
    frame = frame.iloc[:HEAD]
    m = ss.monitor
    names = [ss.inputs[i] for i in m["inputs"]]
    a, b = [k for k, p in enumerate(m["ported_out"]) if p][:2]     # two the others predict
    df = frame.copy()
    for k in (a, b):             # twice its jump limit for LOST rows, then back
        df.loc[AT:AT + LOST - 1, names[k]] += 2.0 * m["jump_lim"][k]
    st, st_said, shifts, c, c_said = _both(ss, block, df)
    # the C excludes both, the first named; nothing before, the block = the C there
    assert c_said[AT][1:] == (JUMP, a) and c_said[AT][0] & EXCLUDED
    assert all(s == (0, 0, -1) for s in c_said[:AT])
    assert np.max(np.abs(st[:AT] - c[:AT])) <= TOLERANCE_UM
    # the block: a jump of the first (not COMMON), both re-referenced; their return the spikes'
    # end (not flagged), the jumps undone
    assert st_said[AT] == (True, JUMP, a)
    assert set(np.flatnonzero(shifts[AT] != shifts[AT - 1])) == {a, b}
    back = AT + LOST
    assert st_said[back] == (False, SPIKE, a)
    assert [i for i, s in enumerate(st_said) if s[0]] == [AT]
    assert np.all(shifts[back:, [a, b]] == 0.0)
