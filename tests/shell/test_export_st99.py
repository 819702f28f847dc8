"""The Structured Text block names a freeze while it holds a ``BLIND_OUT`` out, as the C does
(st99, issue 34): a sensor no other predicts bumped (the C's and the block's ``BLIND_OUT``, held
out), then, while it is out, another sensor frozen -- the C takes one the others predict out as
the second (``FREEZE``), and (freezeu100) one no other predicts too, as its dropout, where the
field is rebuilt without the two (before it the C flagged ``SECOND`` while served took it out) --
and the block names it alike at that row, once, its judgement ending there.  Before st99 the
block judged no freeze while one was held, and ended its judgement, silent, at the first sensor
at its warning band of the set without the held one.

lr9132, tests/shell/test_export_st94.py's fixture (as test_export_st96.py / test_export_st98.py);
benchmarks/bench_st99.py measures the rule on seen and fresh records."""

from __future__ import annotations

from test_export_st94 import record  # noqa: F401 (the module's fixture)
from test_export_st96 import BLIND, _stepped, bumped
from thermocomp.apps.deploy.export.watch import BLIND_OUT, EXCLUDED, FREEZE

HELD = 60      # rows a reading is held (bench_cmon92's freeze)
# one the others predict (the C's second out beside BLIND, the set of the two solved) and one no
# other predicts (frozen past its run: out as its dropout, freezeu100)
HELD_SECOND, NOT_HELD = "T_head_left", "T_amb"


def test_the_block_names_a_freeze_while_it_holds_a_blind_out(record):  # noqa: F811
    _, ss, frame, block = record
    m = ss.monitor
    names = [ss.inputs[i] for i in m["inputs"]]
    k = names.index(BLIND)
    df, end = bumped(frame, BLIND)
    c_said = _stepped(ss, block, df.iloc[:end])[4]
    out = next(i for i, s in enumerate(c_said) if s[1])
    for f, rule, bit in ((names.index(HELD_SECOND), FREEZE, EXCLUDED),
                         (names.index(NOT_HELD), FREEZE, EXCLUDED)):
        dff = df.iloc[:out + 1 + HELD].copy()
        dff.loc[out + 1:, names[f]] = dff.loc[out + 1, names[f]]
        _, st_said, held, _, c_said = _stepped(ss, block, dff)
        # the C's BLIND_OUT of the bumped one, named alike; then its first event: the freeze
        assert c_said[out][1:] == (BLIND_OUT, k) and st_said[out] == (True, BLIND_OUT, k)
        second = next(i for i in range(out + 1, len(c_said)) if c_said[i][1])
        assert c_said[second][0] & bit and c_said[second][1:] == (rule, f)
        # the block held the bumped one out up to there, judging, and names the freeze alike
        assert held[out:second] == [k] * (second - out) and held[second] == -2
        assert st_said[second] == (True, rule, f)
        assert [i for i, s in enumerate(st_said) if s[0]] == [out, second]
