"""The Structured Text block names the C's level shift of a sensor no other predicts
(``SETTLED``) at its row, re-references the sensor as the C does and judges on (st96b, issue 34):
before st96b the block told the shift by the C's test only to stop its drift judgement, named
nothing and read the shifted sensor off the C's reference.

lr9132 (``thermocomp simulate sim=long_record``, seed 9132, 3 days), MLR deployed adaptive with
``data.reference=none``, its first 1000 fed rows, as tests/shell/test_export_st96.py
(benchmarks/bench_st96b.py scores the rule on fresh records)."""

from __future__ import annotations

import numpy as np

from test_export import TOLERANCE_UM
from test_export_st94 import FAULT, record  # noqa: F401 (the module's fixture)
from test_export_st96 import _stepped
from thermocomp.apps.deploy.export.watch import REREFERENCED, SETTLED, STEP_OUT

BLIND = "T_spindle_rear"     # one no other predicts whose level shift the C re-references (lr9132)
START = 600                  # a lasting step of its largest training step from here on
PULSE = FAULT - 60           # then st95b's one-row step (2.9 x its largest training step), down


def test_the_block_names_the_cs_settled_re_references_as_the_c_and_judges_on(record):  # noqa: F811
    deployed, ss, frame, block = record
    k = [ss.inputs[i] for i in ss.monitor["inputs"]].index(BLIND)
    largest = float(deployed.monitor.max_step_c[k])
    df = frame.copy()
    df.loc[START:, BLIND] += largest      # under its bend limit: read as heat until it settles
    df.loc[PULSE:PULSE, BLIND] -= 2.9 * largest    # (down: up, past its range)
    st, st_said, held, c, c_said = _stepped(ss, block, df.iloc[:FAULT])
    # the C's first event: SETTLED of the stepped sensor, a window after the step
    settled = next(i for i, s in enumerate(c_said) if s[1])
    assert START < settled <= START + ss.monitor["window"]
    assert c_said[settled] == (REREFERENCED, SETTLED, k)
    # the block names it at its row (before st96b: nothing), not a fault, and judges on
    assert st_said[settled] == (False, SETTLED, k) and held[settled] == -1
    # re-referenced as the C: the model reads the sensor alike after it (before: off by the step)
    assert np.max(np.abs(st[:PULSE] - c[:PULSE])) <= TOLERANCE_UM
    # the pulse: the C's STEP_OUT, named alike by the block; no other event either side
    assert c_said[PULSE][1] == STEP_OUT and st_said[PULSE] == (True, STEP_OUT, c_said[PULSE][2])
    assert [i for i, s in enumerate(st_said[:PULSE + 1]) if s[1]] == [settled, PULSE]
    assert [i for i, s in enumerate(c_said[:PULSE + 1]) if s[1]] == [settled, PULSE]
