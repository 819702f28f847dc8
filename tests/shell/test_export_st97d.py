"""The Structured Text block says, once and with its row, where its ``BLIND_OUT`` judgement ends
for the campaign (st97d, issue 34): ``mon_stop`` TRUE on that sample, ``mon_stop_row`` its number
from there on (0 while it judges).  Before st97d the judgement ended without a word
(``mon_blind_lost``, internal) and the block, silent from there, read as "all healthy" where the
C went on naming faults.

lr9132 (``thermocomp simulate sim=long_record``, seed 9132, 3 days), MLR deployed adaptive with
``data.reference=none``, its first 670 fed rows (tests/shell/test_export_st94.py's fixture;
benchmarks/bench_st97d.py measures the rule on the seen records).

(st105b) The C's lone fault the block can tell -- the culprit at its warning band and past the
field's band by more than its rounding, the rest within band with it out -- is followed: named
``DRIFT_OUT`` on the C's row and held to the C's ``BACK``, the block judging on, so that the C's
next ``BLIND_OUT`` is named on its row and served as the C's (benchmarks/bench_st105b.py).  The
stop is said where it cannot tell (a culprit within its rounding of the band: the C's memory)."""

from __future__ import annotations

import numpy as np

from test_export import TOLERANCE_UM
from test_export_st94 import record  # noqa: F401 (the module's fixture)
from test_export_st96 import START, _stepped, bumped
from thermocomp.apps.deploy.export.watch import BLIND_OUT, DRIFT_OUT, EXCLUDED, OUT

DRIFTED = "T_head_right"     # one the others predict (lr9132): its drift is the C's lone fault,
SMALL_C = 3.0                # at +3 °C within its rounding of the band (st105b: not told)
FOLLOWED = "T_head_left"     # (st105b) at +3 °C past the band by more than its rounding: told
BLIND, LATER = "T_zdrive", 700       # then a blind sensor's bump from row 700: the C's BLIND_OUT


def _stop(v) -> tuple:
    """``(mon_stop, mon_stop_row, mon_blind_lost)``."""
    return bool(v["mon_stop"]), int(v["mon_stop_row"]), bool(v["mon_blind_lost"])


def test_the_block_says_once_with_its_row_where_its_blind_out_judgement_ends(record):  # noqa: F811
    _, ss, frame, block = record
    k = [ss.inputs[i] for i in ss.monitor["inputs"]].index(DRIFTED)
    # a drift of a sensor the others predict: the C takes it out (its lone fault), which the
    # block does not follow: its BLIND_OUT judgement ends on that row, and it says so there
    df, end = bumped(frame, DRIFTED, size=SMALL_C)
    # healthy: the judgement never ends, nothing said
    assert set(_stepped(ss, block, frame.iloc[:end + 1], _stop)[2]) == {(False, 0, False)}
    st, st_said, stop, c, c_said = _stepped(ss, block, df.iloc[:end + 1], _stop)
    out = next(i for i, s in enumerate(c_said) if s[1])
    assert START < out <= end and c_said[out] == (EXCLUDED | OUT, DRIFT_OUT, k)
    assert np.max(np.abs(st[:out] - c[:out])) <= TOLERANCE_UM
    assert stop[:out] == [(False, 0, False)] * out
    assert stop[out] == (True, out + 1, True)             # the row, 1-based, as the campaign's
    assert stop[out + 1:] == [(False, out + 1, True)] * (len(stop) - out - 1)    # once
    # the status is all it says there: no fault flagged on that row (the C's is not the block's)
    assert st_said[out] == (False, 0, -1)


def _held(v) -> tuple:
    """``(mon_stop_row, mon_held)``."""
    return int(v["mon_stop_row"]), int(v["mon_held"])


def test_the_block_follows_the_lone_fault_it_can_tell_and_names_the_next_blind_out(record):  # noqa: F811
    _, ss, frame, block = record
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    k, b = names.index(FOLLOWED), names.index(BLIND)
    df, _ = bumped(frame, FOLLOWED, size=SMALL_C)
    df, end = bumped(df, BLIND, start=LATER)
    st, st_said, held, c, c_said = _stepped(ss, block, df.iloc[:end + 1], _held)
    said = [(i, s[1], s[2]) for i, s in enumerate(c_said) if s[1] in (DRIFT_OUT, BLIND_OUT)]
    out, blind = said[0][0], said[1][0]
    back = next(i for i in range(out + 1, len(c_said)) if c_said[i][1] and c_said[i][2] == k)
    assert START < out < back < LATER < blind <= end and said == [(out, DRIFT_OUT, k), (blind, BLIND_OUT, b)]
    # the C's lone fault named on its row (4b70457f: the judgement ended there, nothing named)
    assert st_said[out] == (True, DRIFT_OUT, k) and st_said[blind] == (True, BLIND_OUT, b)
    assert [s for i, s in enumerate(st_said) if s[0] and i not in (out, blind)] == []
    # held to the C's BACK, the judgement never ended; then the BLIND_OUT held to the end
    assert held[out:back] == [(0, k)] * (back - out) and held[back:blind] == [(0, -1)] * (blind - back)
    assert held[blind:] == [(0, b)] * (len(held) - blind)
    # from the BACK on (the BLIND_OUT's hold too: its fallback set on the held reading) the C's c
    assert np.max(np.abs(st[:out] - c[:out])) <= TOLERANCE_UM
    assert np.max(np.abs(st[back:] - c[back:])) <= 1e-12
