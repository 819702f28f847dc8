"""The Structured Text block holds a lone jumper no other predicts at its last reading, as the C
does, and follows its ``BACK`` (st97b, issue 34): before st97b the block's judgement ended at the
C's JUMP, its model read the jumper on from the jump and it took the jump's return as a ``SPIKE``
where the C holds the sensor out, re-references the return and lets it back a window later.

lr9132 (``thermocomp simulate sim=long_record``, seed 9132, 3 days), MLR deployed adaptive with
``data.reference=none``, its first 1000 fed rows, as tests/shell/test_export_st96.py
(benchmarks/bench_st97b.py scores the rule on fresh records)."""

from __future__ import annotations

import numpy as np

from test_export import TOLERANCE_UM
from test_export_st94 import FAULT, record  # noqa: F401 (the module's fixture)
from test_export_st96 import _stepped
from thermocomp.apps.deploy.export.watch import EXCLUDED, JUMP, READMITTED, RULES, STEP_OUT

BLIND = "T_spindle_rear"     # one no other predicts that the C holds out for a jump (lr9132)
START, LASTS = 600, 3        # a spike down of 1.1 x its jump limit, 3 rows
PULSE = FAULT - 60           # then st95b's one-row step (2.9 x its largest training step)


def test_the_block_holds_a_blind_jumper_as_the_c_and_follows_its_back(record):  # noqa: F811
    deployed, ss, frame, block = record
    k = [ss.inputs[i] for i in ss.monitor["inputs"]].index(BLIND)
    df = frame.copy()
    df.loc[START:START + LASTS - 1, BLIND] -= 1.1 * float(ss.monitor["jump_lim"][k])
    df.loc[PULSE:PULSE, BLIND] += 2.9 * float(deployed.monitor.max_step_c[k])
    st, st_said, held, c, c_said = _stepped(ss, block, df.iloc[:FAULT])
    # the C: JUMP of the sensor at START, held out (its return re-referenced, no event) to BACK
    assert c_said[START][0] & EXCLUDED and c_said[START][1:] == (JUMP, k)
    back = next(i for i in range(START + 1, PULSE) if c_said[i][1])
    assert back > START + LASTS + ss.monitor["window"] - 1
    assert c_said[back][0] & READMITTED and (RULES[c_said[back][1]], c_said[back][2]) == ("BACK", k)
    assert np.max(np.abs(st[:START] - c[:START])) <= TOLERANCE_UM
    # the block: JUMP at its row, holds it out to that row (before st97b: its judgement ended
    # there, -2, and it named the return START + LASTS a SPIKE), lets it back there, judging on
    assert st_said[START] == (True, JUMP, k)
    assert held[START:back] == [k] * (back - START) and held[back] == -1
    assert [i for i, s in enumerate(st_said[START + 1:back + 1]) if s[1]] == []
    # back in (its jumps undone as the C's), the block = the C again
    assert np.max(np.abs(st[back:PULSE] - c[back:PULSE])) <= TOLERANCE_UM
    # the pulse: the C's STEP_OUT, named alike by the block
    assert c_said[PULSE][1] == STEP_OUT and st_said[PULSE] == (True, STEP_OUT, c_said[PULSE][2])
    assert [i for i, s in enumerate(c_said[:PULSE + 1]) if s[1]] == [START, back, PULSE]
