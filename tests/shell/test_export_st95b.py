"""The Structured Text block follows the C's re-admission by ``BACK`` of one sensor out alone by
its own ``STEP_OUT`` and judges on (st95b, issue 34): where before st95b the block judged no more
after its first ``STEP_OUT``, it now holds the culprit out for the C's wait, re-admits it where
its error with every sensor in is within ``READMIT`` of its warning band over the window, and
names the C's next ``STEP_OUT`` at its row.

lr9132 (``thermocomp simulate sim=long_record``, seed 9132, 3 days), MLR deployed adaptive with
``data.reference=none``, its first 1100 fed rows, as tests/shell/test_export_st94b.py
(benchmarks/bench_st95b.py scores the rule on fresh records)."""

from __future__ import annotations

import numpy as np

from test_export import TOLERANCE_UM
from test_export_st94 import FAULT, _both, record  # noqa: F401 (the module's fixture)
from thermocomp.apps.deploy.export.watch import READMITTED, RULES, STEP_OUT

BLIND = "T_spindle_rear"     # one no other predicts (lr9132)
PULSE = FAULT - 60           # a one-row step 60 rows before the lasting one


def test_the_block_follows_the_c_back_and_names_its_next_stepped_error(record):  # noqa: F811
    deployed, ss, frame, block = record
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    k = names.index(BLIND)
    # bench_st94's planted step (2.9 x its largest training step, under its jump limit) for one
    # row, then from FAULT on: the others' errors step with it, one past its alarm band each time
    df = frame.copy()
    size = 2.9 * float(deployed.monitor.max_step_c[k])
    df.loc[PULSE:PULSE, BLIND] += size
    df.loc[FAULT:, BLIND] += size
    st, st_said, _, c, c_said = _both(ss, block, df)
    # the C silent before the pulse, the block = the C there
    assert all(s == (0, 0, -1) for s in c_said[:PULSE])
    assert np.max(np.abs(st[:PULSE] - c[:PULSE])) <= TOLERANCE_UM
    # the pulse: the C's STEP_OUT, named alike by the block (as st94b)
    assert c_said[PULSE][1] == STEP_OUT
    culprit = c_said[PULSE][2]
    assert st_said[PULSE] == (True, STEP_OUT, culprit)
    # the C's BACK of it after its wait (a window), no other C event up to FAULT
    back = [i for i in range(PULSE + 1, FAULT) if c_said[i][1]]
    assert len(back) == 1 and back[0] > PULSE + ss.monitor["window"]
    bits, rule, sensor = c_said[back[0]]
    assert bits & READMITTED and (RULES[rule], sensor) == ("BACK", culprit)
    # the lasting step: the C's STEP_OUT again, and the block names it at its row (before st95b
    # the block judged no more after the pulse and said nothing here)
    assert c_said[FAULT][1] == STEP_OUT
    assert st_said[FAULT] == (True, STEP_OUT, c_said[FAULT][2])
    # and no block flag between (no false one while the sensor was out, nor after its return)
    assert [i for i, s in enumerate(st_said[:FAULT + 1]) if s[0]] == [PULSE, FAULT]
