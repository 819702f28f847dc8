"""The Structured Text block re-references a lone jump of a sensor the others predict as the C does
(st111, issue 34 "deployed as scored"): the C re-references it by its step less the change the
others predict for it since the last row (watch_c.py ``other - mon_prev_other``, every sensor in),
and reads it so from its ``BACK``; before st111 the block took the whole step, off the C from there
to the campaign's end with nothing flagged.

lr9132's first rows and fixture as tests/shell/test_export_st94.py (its healthy pass resumed);
benchmarks/bench_st111.py scores the seen and fresh cases."""

from __future__ import annotations

import numpy as np

from test_export import TOLERANCE_UM
from test_export_st94 import AT, HEAD, _both, record, resumed  # noqa: F401 (the module's fixture)
from thermocomp.apps.deploy.export.watch import BAND, EXCLUDED, JUMP, READMITTED


def test_a_lone_jump_of_a_sensor_the_others_predict_is_re_referenced_as_the_c_does(record):  # noqa: F811
    _, ss, frame, block = record
    m = ss.monitor
    names = [ss.inputs[i] for i in m["inputs"]]
    k = [k for k, p in enumerate(m["ported_out"]) if p][0]      # one the others predict, held out
    df = frame.iloc[:HEAD].copy()
    df.loc[AT:, names[k]] -= 2.0 * m["jump_lim"][k]     # twice its jump limit, to the end
    st, st_said, shifts, c, c_said = _both(ss, block, df)
    # the C excludes it at the jump and lets it back later, on its new reference
    assert c_said[AT][1:] == (JUMP, k) and c_said[AT][0] & EXCLUDED
    back = [i for i in range(AT + 1, HEAD) if c_said[i][0] & READMITTED and c_said[i][2] == k]
    assert back, "the C did not let it back within the rows fed"
    # the block flags the jump, re-referenced there only, by less than its whole step (the
    # others' change); from the C's BACK on it is the C (before st111: off to the end)
    assert st_said[AT] == (True, JUMP, k)
    assert np.max(np.abs(st[back[0]:] - c[back[0]:])) <= TOLERANCE_UM
    moved = np.flatnonzero(np.any(np.diff(shifts, axis=0) != 0.0, axis=1)) + 1
    assert moved.tolist() == [AT]
    assert shifts[AT, k] != -2.0 * m["jump_lim"][k]


def test_the_cs_hold_after_a_lone_jump_is_rebuilt_in_the_block_not_flagged(record):  # noqa: F811
    """(st112b) From the jump to its BACK the C holds the sensor out and feeds the model its rebuild
    from the others (the set without it): the block computes the same there, unflagged, and tells
    the C's BACK (its calm, its error over the window within its band): the C from there (before
    st112b: every hold row read as measured, off the C, flagged)."""
    _, ss, frame, block = record
    m = ss.monitor
    idx, names = m["inputs"], [ss.inputs[i] for i in m["inputs"]]
    k = [k for k, p in enumerate(m["ported_out"]) if p][0]
    df = frame.iloc[:HEAD].copy()
    df.loc[AT:, names[k]] += 3.0 * m["jump_lim"][k]     # not the case above: its own rows stepped
    unsure = {}

    def read(fb, sim, u, t, i):     # _both's row, so its healthy pass is resumed; mon_unsure kept
        st, v = fb(u, t, i == 0), fb.vars
        unsure[i] = bool(v["mon_unsure"])
        said = (bool(v["mon_flag"]), int(v["mon_rule"]), int(v["mon_sensor"]))
        c = sim.step(u, t)
        return (st, said, np.array(v["mon_shift"], float)[idx], c,
                (int(sim.watch.flags) & ~BAND, int(sim.watch.rule), int(sim.watch.sensor)))
    st, _, _, c, c_said = zip(*resumed(ss, block, df, read, "_both"))
    gap = np.max(np.abs(np.array(st) - np.array(c)), axis=1)
    back = [i for i in range(AT + 1, HEAD) if c_said[i][0] & READMITTED and c_said[i][2] == k][0]
    assert c_said[AT][1:] == (JUMP, k) and back - AT >= m["window"]
    assert np.max(gap[AT:]) <= TOLERANCE_UM
    assert not any(unsure[i] for i in range(AT, back))
