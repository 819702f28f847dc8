"""The Structured Text block names a freeze after its own earlier flag (st98b, issue 34): a
spike of one sensor flagged first (``JUMP``, the block's judgement ended: ``mon_lost``), then a
sensor no other predicts frozen -- the block names the C's ``FREEZE`` at the C's row and sensor,
once, past its run (``blind_run``).
Before st98b it stayed silent there (its judgement had ended at the spike).

lr9132, tests/shell/test_export_st94.py's fixture (as test_export_st98.py); benchmarks/
bench_st98b.py measures the rule on seen and fresh records."""

from __future__ import annotations

from test_export_st94 import record  # noqa: F401 (the module's fixture)
from test_export_st96 import START, _stepped
from test_export_st98 import HELD, _lost
from thermocomp.apps.deploy.export.watch import EXCLUDED, FREEZE, JUMP

LEAD, SPIKE_C, SPIKE_ROWS = 20, 5.0, 10     # bench_st98b's case (bench_cmon92's spike)


def test_the_block_names_a_freeze_after_its_own_earlier_flag(record):  # noqa: F811
    _, ss, frame, block = record
    m = ss.monitor
    names = [ss.inputs[i] for i in m["inputs"]]
    k = next(k for k, p in enumerate(m["predictable"]) if not p)
    spiked = next(a for a, p in enumerate(m["predictable"]) if p and a != k)
    df = frame.iloc[:START + HELD].copy()
    df.loc[START - LEAD:START - LEAD + SPIKE_ROWS - 1, names[spiked]] += SPIKE_C
    df.loc[START:, names[k]] = df.loc[START, names[k]]
    st, st_said, lost, c, c_said = _stepped(ss, block, df, _lost)
    # the block's own earlier flag: the spike's JUMP, its judgement ended from there
    assert st_said[START - LEAD] == (True, JUMP, spiked) and all(lost[START - LEAD:])
    # the C's FREEZE of the frozen sensor, held out
    out = next(i for i in range(START, len(c_said)) if c_said[i][1] == FREEZE)
    assert c_said[out][0] & EXCLUDED and c_said[out][2] == k
    # the block names it there, alike, once; no other freeze named
    assert st_said[out] == (True, FREEZE, k)
    assert [i for i, s in enumerate(st_said) if s[1] == FREEZE] == [out]
