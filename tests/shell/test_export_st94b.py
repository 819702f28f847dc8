"""The Structured Text block judges a sensor's self-prediction error while the field is whole
(st94b, issue 34): a sensor the others predict stepping under its jump limit but past its alarm
band in one sample is the C's ``STEP_OUT`` (its error stepped past the band, excluded); the block
flags it at its row with the C's culprit and rule, where before st94b it said nothing.

lr9132 (``thermocomp simulate sim=long_record``, seed 9132, 3 days), MLR deployed adaptive with
``data.reference=none``, its first 1100 fed rows, as tests/shell/test_export_st94.py
(benchmarks/bench_st94b.py scores the rule on fresh records)."""

from __future__ import annotations

import numpy as np

from test_export import TOLERANCE_UM
from test_export_st94 import FAULT, _both, record  # noqa: F401 (the module's fixture)
from thermocomp.apps.deploy.export.watch import EXCLUDED, STEP_OUT

BLIND = "T_spindle_rear"     # one no other predicts (lr9132)


def test_a_stepped_self_prediction_error_is_flagged_as_the_c_excludes_it(record):  # noqa: F811
    deployed, ss, frame, block = record
    m = ss.monitor
    names = [ss.inputs[i] for i in m["inputs"]]
    # a sensor no other predicts stepped under its jump limit from FAULT on (bench_st94's planted
    # step, 2.9 x its largest training step; its jump limit 3 x): the others' errors step with it
    # (its column of the POD's operator), one the others predict past its alarm band: the C's culprit
    k = names.index(BLIND)
    df = frame.copy()
    df.loc[FAULT:, BLIND] += 2.9 * float(deployed.monitor.max_step_c[k])
    st, st_said, _, c, c_said = _both(ss, block, df)
    assert c_said[FAULT][1] == STEP_OUT
    # the C silent before, the block = the C there and silent too
    assert all(s == (0, 0, -1) for s in c_said[:FAULT])
    assert np.max(np.abs(st[:FAULT] - c[:FAULT])) <= TOLERANCE_UM
    assert all(s == (False, 0, -1) for s in st_said[:FAULT])
    # the C excludes the culprit; the block flags the same sensor with the same rule at that row
    assert c_said[FAULT][0] & EXCLUDED
    assert st_said[FAULT] == (True, STEP_OUT, c_said[FAULT][2])
    # and judges no more (the C rebuilds the sensor from the others, the block cannot)
    assert [i for i, s in enumerate(st_said) if s[0]] == [FAULT]
