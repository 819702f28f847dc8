"""The Structured Text block judges a frozen sensor as the C does (st98, issue 34): ``FREEZE`` on
the C's row and sensor -- a dithered reading constant past ``dither_run`` (mon97), one no other
predicts past ``blind_run`` -- and its judgement ends there.  Before st98 the block judged no
freeze: silent where the C took the sensor out, then the reading's return a ``JUMP``.

lr9132 (``thermocomp simulate sim=long_record``, seed 9132, 3 days), MLR deployed adaptive with
``data.reference=none``, its first rows (tests/shell/test_export_st94.py's fixture;
benchmarks/bench_st98.py measures the rule on seen and fresh records)."""

from __future__ import annotations

import numpy as np

from test_export import TOLERANCE_UM
from test_export_st94 import record  # noqa: F401 (the module's fixture)
from test_export_st96 import START, _stepped
from thermocomp.apps.deploy.export.watch import EXCLUDED, FREEZE

HELD = 60      # rows a reading is held (bench_cmon92's freeze)


def _lost(v) -> bool:
    return bool(v["mon_lost"])


def test_the_block_names_a_frozen_sensor_at_the_cs_row_and_stops_judging(record):  # noqa: F811
    _, ss, frame, block = record
    m = ss.monitor
    names = [ss.inputs[i] for i in m["inputs"]]
    dithered = next(k for k, r in enumerate(m["dither_run"]) if np.isfinite(r) and m["predictable"][k])
    blind = next(k for k, p in enumerate(m["predictable"]) if not p)
    part = frame.iloc[:START + HELD].copy()
    assert set(_stepped(ss, block, part, _lost)[2]) == {False}      # healthy: judging throughout
    for k in (dithered, blind):
        df = part.copy()
        df.loc[START:, names[k]] = df.loc[START, names[k]]
        st, st_said, lost, c, c_said = _stepped(ss, block, df, _lost)
        out = next(i for i, s in enumerate(c_said) if s[1])
        # the C's first event: the freeze, past the sensor's run (its noise spans its resolution)
        assert c_said[out][0] & EXCLUDED and c_said[out][1:] == (FREEZE, k)
        run = m["dither_run"][k] if k == dithered else m["blind_run"][k]
        assert START < out <= START + int(np.floor(run)) + 1     # (its run may begin before START)
        assert np.max(np.abs(st[:out] - c[:out])) <= TOLERANCE_UM
        # the block names it there, alike, and nothing before; its judgement ends on that row
        assert st_said[out] == (True, FREEZE, k)
        assert not any(s[0] for s in st_said[:out])
        assert lost[:out] == [False] * out and all(lost[out:])
