"""The Structured Text block says, once and with its row, where its ``BLIND_OUT`` judgement ends
for the campaign (st97d, issue 34): ``mon_stop`` TRUE on that sample, ``mon_stop_row`` its number
from there on (0 while it judges).  Before st97d the judgement ended without a word
(``mon_blind_lost``, internal) and the block, silent from there, read as "all healthy" where the
C went on naming faults.

lr9132 (``thermocomp simulate sim=long_record``, seed 9132, 3 days), MLR deployed adaptive with
``data.reference=none``, its first 670 fed rows (tests/shell/test_export_st94.py's fixture;
benchmarks/bench_st97d.py measures the rule on the seen records)."""

from __future__ import annotations

import numpy as np

from test_export import TOLERANCE_UM, StructuredText
from test_export_st94 import record  # noqa: F401 (the module's fixture)
from thermocomp.apps.deploy.export import Simulator
from thermocomp.apps.deploy.export.watch import BAND, DRIFT_OUT, EXCLUDED, OUT

DRIFTED = "T_head_left"      # one the others predict (lr9132): its drift is the C's lone fault
START, RISE, HOLD, RISE_C = 600, 20, 30, 6.0    # a smooth bump of it, +6 °C for 30 rows


def _said(ss, block, frame):
    """Per row: the block's corrections, ``(mon_flag, mon_rule, mon_sensor)`` and ``(mon_stop,
    mon_stop_row, mon_blind_lost)``; the C mirror's corrections and ``(flags, rule, sensor)``."""
    fb, sim = StructuredText(block), Simulator(ss)
    sim.reset()
    st, st_said, stop, c, c_said = [], [], [], [], []
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
        st.append(fb(u, t, i == 0))
        v = fb.vars
        st_said.append((bool(v["mon_flag"]), int(v["mon_rule"]), int(v["mon_sensor"])))
        stop.append((bool(v["mon_stop"]), int(v["mon_stop_row"]), bool(v["mon_blind_lost"])))
        c.append(sim.step(u, t))
        c_said.append((int(sim.watch.flags) & ~BAND, int(sim.watch.rule), int(sim.watch.sensor)))
    return np.array(st), st_said, stop, np.array(c), c_said


def test_the_block_says_once_with_its_row_where_its_blind_out_judgement_ends(record):  # noqa: F811
    _, ss, frame, block = record
    k = [ss.inputs[i] for i in ss.monitor["inputs"]].index(DRIFTED)
    # healthy: the judgement never ends, nothing said
    _, _, stop, _, _ = _said(ss, block, frame.iloc[:START + 2 * RISE + HOLD])
    assert set(stop) == {(False, 0, False)}
    # a drift of a sensor the others predict: the C takes it out (its lone fault), which the
    # block does not follow: its BLIND_OUT judgement ends on that row, and it says so there
    df = frame.copy()
    rise = RISE_C * (1 - np.cos(np.pi * np.arange(RISE) / RISE)) / 2
    df.loc[START:START + 2 * RISE + HOLD - 1, DRIFTED] += np.concatenate(
        [rise, np.full(HOLD, RISE_C), rise[::-1]])
    st, st_said, stop, c, c_said = _said(ss, block, df.iloc[:START + 2 * RISE + HOLD])
    out = next(i for i, s in enumerate(c_said) if s[1])
    assert START < out < START + RISE and c_said[out] == (EXCLUDED | OUT, DRIFT_OUT, k)
    assert np.max(np.abs(st[:out] - c[:out])) <= TOLERANCE_UM
    assert stop[:out] == [(False, 0, False)] * out
    assert stop[out] == (True, out + 1, True)             # the row, 1-based, as the campaign's
    assert stop[out + 1:] == [(False, out + 1, True)] * (len(stop) - out - 1)    # once
    # the status is all it says there: no fault flagged on that row (the C's is not the block's)
    assert st_said[out] == (False, 0, -1)
