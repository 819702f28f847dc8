"""The Structured Text block takes out, as the C's drift judgement does, a sensor no other
predicts that explains the others' errors (``BLIND_OUT``), holds it out alone to the C's ``BACK``
and judges on (st96, issue 34): before st96 the block did not see the C's exclusion and judged
the field as whole while the C held the sensor out.  (st103b) While it holds the sensor out the
block serves the C's fallback law set on the sensor's last reading in, as the C (bench_st103b.py).

lr9132 (``thermocomp simulate sim=long_record``, seed 9132, 3 days), MLR deployed adaptive with
``data.reference=none``, its first 1100 fed rows, as tests/shell/test_export_st95b.py
(benchmarks/bench_st96.py scores the rule on fresh records)."""

from __future__ import annotations

import numpy as np

from test_export import TOLERANCE_UM
from test_export_st94 import FAULT, record, resumed  # noqa: F401 (the module's fixture)
from thermocomp.apps.deploy.export.watch import BAND, BLIND_OUT, EXCLUDED, READMITTED, RULES, STEP_OUT

BLIND = "T_spindle_rear"     # one no other predicts (lr9132)
START, RISE, HOLD, RISE_C = 600, 20, 30, 6.0    # a smooth bump of it, +6 °C for 30 rows
PULSE = FAULT - 60           # then st95b's one-row step (2.9 x its largest training step)


def _held(v) -> int:
    """The sensor the block holds out (``mon_held``, -1 none; -2 ``mon_lost``: its judgement ended)."""
    return -2 if v["mon_lost"] else int(v["mon_held"])


def bumped(frame, sensor: str, start: int = START, size: float = RISE_C):
    """``frame`` with ``sensor`` bumped smoothly from ``start``: up ``size`` (°C) over ``RISE``
    rows, held ``HOLD`` rows, down again; and the bump's last row (benchmarks/bench_st99b.py
    plants it in fresh records)."""
    df = frame.copy()
    rise = size * (1 - np.cos(np.pi * np.arange(RISE) / RISE)) / 2
    bump = np.concatenate([rise, np.full(HOLD, size), rise[::-1]])
    df.loc[start:start + len(bump) - 1, sensor] += bump
    return df, start + len(bump) - 1


def _stepped(ss, block, frame, kept=_held):
    """Per row: the block's corrections, ``(mon_flag, mon_rule, mon_sensor)`` and what ``kept``
    reads of its memory (default :func:`_held`); the C mirror's corrections and ``(flags, rule,
    sensor)``."""
    def read(fb, sim, u, t, i):
        st = fb(u, t, i == 0)
        v = fb.vars
        said = (bool(v["mon_flag"]), int(v["mon_rule"]), int(v["mon_sensor"]))
        held = kept(v)
        c = sim.step(u, t)
        return st, said, held, c, (int(sim.watch.flags) & ~BAND, int(sim.watch.rule), int(sim.watch.sensor))
    st, st_said, held, c, c_said = zip(*resumed(ss, block, frame, read, kept))   # (shared rows once)
    return np.array(st), list(st_said), list(held), np.array(c), list(c_said)


def test_the_block_takes_out_a_blind_sensor_as_the_c_and_follows_its_back(record):  # noqa: F811
    deployed, ss, frame, block = record
    k = [ss.inputs[i] for i in ss.monitor["inputs"]].index(BLIND)
    df, end = bumped(frame, BLIND)
    df.loc[PULSE:PULSE, BLIND] += 2.9 * float(deployed.monitor.max_step_c[k])
    st, st_said, held, c, c_said = _stepped(ss, block, df.iloc[:FAULT])
    # the C's first event: BLIND_OUT of the bumped sensor (it explains the others' errors)
    out = next(i for i, s in enumerate(c_said) if s[1])
    assert START < out <= end and c_said[out][0] & EXCLUDED
    assert c_said[out][1:] == (BLIND_OUT, k)
    assert np.max(np.abs(st[:out] - c[:out])) <= TOLERANCE_UM
    # the block names it at its row (before st96: nothing) and holds it out
    assert st_said[out] == (True, BLIND_OUT, k)
    # the C's BACK of it after its wait, no other C event between
    back = next(i for i in range(out + 1, PULSE) if c_said[i][1])
    assert back > out + ss.monitor["window"]
    assert c_said[back][0] & READMITTED and (RULES[c_said[back][1]], c_said[back][2]) == ("BACK", k)
    # the block held it out up to that row and lets it back there, judging on
    assert held[out:back] == [k] * (back - out) and held[back] == -1
    # (st103b) while it holds it out, the block = the C: the sensor read at its last reading in,
    # the correction its fallback model's (before st103b: the model's laws on the live reading)
    assert ss.monitor["fallback_set"][k] > 0
    assert np.max(np.abs(st[out:back] - c[out:back])) <= TOLERANCE_UM
    # back in, the block = the C again (the C served its fallback while it was out)
    assert np.max(np.abs(st[back:PULSE] - c[back:PULSE])) <= TOLERANCE_UM
    # the pulse: the C's STEP_OUT, named alike by the block; no other block flag
    assert c_said[PULSE][1] == STEP_OUT and st_said[PULSE] == (True, STEP_OUT, c_said[PULSE][2])
    assert [i for i, s in enumerate(st_said[:PULSE + 1]) if s[0]] == [out, PULSE]
    assert [i for i, s in enumerate(c_said[:PULSE]) if s[1]] == [out, back]
