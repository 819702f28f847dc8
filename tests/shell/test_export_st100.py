"""The Structured Text block pauses where the C vetoes a drift or declares a new thermal state, to
a calm window, and judges ``BLIND_OUT`` on (st100, issue 34): before st100 a drift judgement with
every sensor in that reached the band, no sensor no other predicts explaining it, ended the
block's ``BLIND_OUT`` judgement for the campaign (``mon_stop``), though with ``new_state_others``
+ 1 judged sensors at their warning band the C takes nothing out there and judges on.

lr9132 (``thermocomp simulate sim=long_record``, seed 9132, 3 days), MLR deployed adaptive with
``data.reference=none``, its first 1100 fed rows (tests/shell/test_export_st94.py's fixture): three
sensors the others predict bumped -2 °C from row 300 (test_export_st96's bump), where the C
declares a new thermal state, then test_export_st96's bump of a sensor no other predicts from row
600, the C's ``BLIND_OUT`` (benchmarks/bench_st100.py measures the rule on seen and fresh records).

(st101) The block's own ``JUMP`` of a sensor no other predicts ended its judgement of the field
for the campaign (``mon_lost``), while the C holds the sensor out to its ``BACK`` and judges on:
the same record, a spike of the sensor the C holds out for a jump 150 rows before the bump
(benchmarks/bench_st101.py); (st103c) while it holds it, the block serves the C's fallback law set
on its last reading in, as the C (benchmarks/bench_st103c.py).

(st102) A jump of the sensor the block holds out by its ``BLIND_OUT`` was flagged ``JUMP`` and
ended the block's judgement, where the C re-references it silently and names its ``BACK`` with the
jumps undone: the bump, and a spike of the bumped sensor while it is out (benchmarks/bench_st102.py).

(st105) The block's own JUMP while its ``BLIND_OUT`` judgement is paused (or stopped) was not held
(lost), while the C holds the sensor out alone to its ``BACK``: st101's spike inside the C's new
state (benchmarks/bench_st105.py).

(st107c) Two judged sensors at their warning band in the set without the ``BLIND_OUT`` ended the
block's hold (the one-out stop, ``MON_FOLLOW_OTHERS``) where the C, past a window of the exclusion,
keeps the sensor out and names nothing (its ``_follow_field`` lets it back only within one):
benchmarks/bench_st107c.py."""

from __future__ import annotations

import numpy as np

from test_export import TOLERANCE_UM
from test_export_st94 import record  # noqa: F401 (the module's fixture)
from test_export_st96 import BLIND, START, _stepped, bumped
from thermocomp.apps.deploy.export.watch import BACK, BLIND_OUT, EXCLUDED, JUMP, NOVEL, OUT

FIELD, AT, SIZE = ("T_head_left", "T_col_front_top", "T_bed_right"), 300, -2.0
JUMPED, JUMP_AT, JUMP_LIMITS = "T_amb", START - 150, 3.0    # (st101) its spike: 2 rows, 3 jump limits
HELD_AT, HELD_LIMITS = START + 30, -1.2    # (st102) the bumped one's spike while out (up: beyond range)
PAUSED_AT = AT + 18    # (st105) st101's spike 10 rows into the C's new state (from AT + 8)
STILL_AT, STILL = START + 40, 12    # (st106b) the bumped one's reading standing still while out
FOLLOW_AT, FOLLOW_C = START + 36, -0.6    # (st107c) two of FIELD bumped while it is out


def _judging(v) -> tuple:
    """``(mon_stop, mon_blind_lost, mon_pause, mon_jheld)`` (an export before st100: no pause;
    before st101: no hold, -1)."""
    return (bool(v["mon_stop"]), bool(v["mon_blind_lost"]), bool(v.get("mon_pause", False)),
            int(v.get("mon_jheld", -1)))


def test_the_block_pauses_at_the_cs_new_state_and_names_a_blind_out_after_it(record):  # noqa: F811
    _, ss, frame, block = record
    k = [ss.inputs[i] for i in ss.monitor["inputs"]].index(BLIND)
    df = frame
    for sensor in FIELD:
        df, _ = bumped(df, sensor, AT, SIZE)
    df, end = bumped(df, BLIND)
    st, st_said, judging, c, c_said = _stepped(ss, block, df.iloc[:end + 1], _judging)
    # the C: a new thermal state from the field's bump (nothing out), ended by a calm window,
    # then its BLIND_OUT of the bumped sensor no other predicts
    novel = [i for i, s in enumerate(c_said) if s[0] & NOVEL]
    assert novel and AT < novel[0] and novel == list(range(novel[0], novel[-1] + 1)) and novel[-1] < START
    assert not any(s[0] & EXCLUDED for s in c_said[:START])
    out = next(i for i, s in enumerate(c_said) if s[1] == BLIND_OUT)
    assert START < out <= end and c_said[out] == (EXCLUDED | OUT, BLIND_OUT, k)
    assert np.max(np.abs(st[:out] - c[:out])) <= TOLERANCE_UM
    # the block names it on the C's row (before st100: its judgement had ended at the new state)
    assert st_said[out] == (True, BLIND_OUT, k)
    assert [i for i, s in enumerate(st_said[:out + 1]) if s[0]] == [out]
    # never stopped: paused from the C's new state to its end (the calm window), judging on
    assert {(s, lost) for s, lost, _, _ in judging} == {(False, False)}
    paused = [i for i, (_, _, p, _) in enumerate(judging) if p]
    assert paused == list(range(novel[0], novel[-1] + 1))


def test_the_block_holds_its_own_jump_in_the_pause_to_the_cs_back(record):  # noqa: F811
    """(st105) The same, and st101's spike of the sensor the C holds out for a jump inside the C's
    new state: before st105 the block held no jump while paused (or stopped), flagged it and lost
    its field, while the C holds it out alone to its BACK, serving its fallback set."""
    _, ss, frame, block = record
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    j = names.index(JUMPED)
    df = frame
    for sensor in FIELD:
        df, _ = bumped(df, sensor, AT, SIZE)
    df, end = bumped(df, BLIND)
    df.loc[PAUSED_AT:PAUSED_AT + 1, JUMPED] += JUMP_LIMITS * float(ss.monitor["jump_lim"][j])
    st, st_said, judging, c, c_said = _stepped(ss, block, df.iloc[:end + 1], _judging)
    # the C: the jump in its new state, the sensor out alone to its BACK after its wait
    assert c_said[PAUSED_AT][0] & NOVEL and c_said[PAUSED_AT][1:] == (JUMP, j)
    back = next(i for i in range(PAUSED_AT + 1, len(c_said)) if c_said[i][1])
    assert c_said[back][1:] == (BACK, j) and back >= PAUSED_AT + ss.monitor["window"]
    after = next(i for i in range(back + 1, len(c_said)) if c_said[i][1])
    # the block paused there, names the JUMP, holds it to the C's BACK (its pause stopped: a
    # sensor out in a pause, st100), and = the C from the jump to the C's next event
    assert judging[PAUSED_AT - 1][2] and st_said[PAUSED_AT] == (True, JUMP, j)
    assert [i for i, x in enumerate(judging) if x[3] >= 0] == list(range(PAUSED_AT, back))
    assert judging[PAUSED_AT][:3] == (True, True, False)
    assert ss.monitor["fallback_set"][j] > 0
    assert np.max(np.abs(st[PAUSED_AT:after] - c[PAUSED_AT:after])) <= TOLERANCE_UM


def _jumped(v) -> tuple:
    """``(mon_lost, mon_jheld)`` (an export before st101: no hold, -1)."""
    return bool(v["mon_lost"]), int(v.get("mon_jheld", -1))


def test_the_block_holds_its_own_jump_to_the_cs_back_and_names_a_blind_out_after_it(record):  # noqa: F811
    _, ss, frame, block = record
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    k, j = names.index(BLIND), names.index(JUMPED)    # (one the C holds out for a jump)
    df = frame.copy()
    df.loc[JUMP_AT:JUMP_AT + 1, names[j]] += JUMP_LIMITS * float(ss.monitor["jump_lim"][j])
    df, end = bumped(df, BLIND)
    st, st_said, judging, c, c_said = _stepped(ss, block, df.iloc[:end + 1], _jumped)
    # the C: the sensor out for its jump, back after its wait, then its BLIND_OUT of the bump
    assert c_said[JUMP_AT][1:] == (JUMP, j)
    back = next(i for i in range(JUMP_AT + 1, START) if c_said[i][1])
    assert c_said[back][1:] == (BACK, j) and back >= JUMP_AT + ss.monitor["window"]
    out = next(i for i in range(back + 1, len(c_said)) if c_said[i][1])
    assert START < out <= end and c_said[out][1:] == (BLIND_OUT, k)
    # the block names it on the C's row (before st101: its judgement ended at its own JUMP)
    assert st_said[out] == (True, BLIND_OUT, k)
    assert [i for i, s in enumerate(st_said[:out + 1]) if s[0]] == [JUMP_AT, out]
    # held from its JUMP to the C's BACK (the field computed, not judged), then the C's again
    assert [i for i, (_, held) in enumerate(judging) if held >= 0] == list(range(JUMP_AT, back))
    assert judging[back] == (False, -1)
    # (st103c) while it holds it, the block = the C: the sensor read at its last reading in, the
    # correction its fallback model's (before st103c: the model's laws on the live reading)
    assert ss.monitor["fallback_set"][j] > 0
    assert np.max(np.abs(st[JUMP_AT:back] - c[JUMP_AT:back])) <= TOLERANCE_UM
    assert np.max(np.abs(st[back:out] - c[back:out])) <= TOLERANCE_UM


def _held(v) -> tuple:
    """``(mon_lost, mon_held)``."""
    return bool(v["mon_lost"]), int(v["mon_held"])


def test_the_block_follows_the_cs_silent_re_reference_of_the_blind_out_it_holds(record):  # noqa: F811
    _, ss, frame, block = record
    k = [ss.inputs[i] for i in ss.monitor["inputs"]].index(BLIND)
    df, end = bumped(frame, BLIND)
    df.loc[HELD_AT:HELD_AT + 1, BLIND] += HELD_LIMITS * float(ss.monitor["jump_lim"][k])
    st, st_said, held, c, c_said = _stepped(ss, block, df.iloc[:end + 40], _held)
    # the C: its BLIND_OUT, then the held sensor's spike re-referenced twice, silently (cmon87),
    # and its BACK after its wait from the second, its jumps undone there
    out = next(i for i, s in enumerate(c_said) if s[1])
    assert c_said[out][1:] == (BLIND_OUT, k) and START < out < HELD_AT
    back = next(i for i in range(out + 1, len(c_said)) if c_said[i][1])
    assert c_said[back][1:] == (BACK, k) and back >= HELD_AT + 2 + ss.monitor["window"]
    # the block: the same BLIND_OUT, nothing flagged at the jumps (before st102: JUMP at the
    # first, its judgement ended there), held to the C's BACK, the C's corrections after it
    assert [i for i, s in enumerate(st_said) if s[0]] == [out]
    assert st_said[HELD_AT] == st_said[HELD_AT + 2] == (False, 0, -1)
    assert held[out:back] == [(False, k)] * (back - out) and held[back] == (False, -1)
    assert np.max(np.abs(st[back:] - c[back:])) <= TOLERANCE_UM


def test_the_block_holds_a_blind_out_whose_reading_stands_still(record):  # noqa: F811
    """(st106b) The bumped sensor's reading standing still while the C holds it out by its
    ``BLIND_OUT``: past st95b's ``MON_FREEZE_RUN`` the block ended the hold (``mon_lost``) and
    served the model's set on the live reading, while the C names nothing there, keeps it out with
    its fallback set served and lets it back only after its reading moves again."""
    _, ss, frame, block = record
    k = [ss.inputs[i] for i in ss.monitor["inputs"]].index(BLIND)
    df, end = bumped(frame, BLIND)
    df.loc[STILL_AT:STILL_AT + STILL - 1, BLIND] = df.loc[STILL_AT - 1, BLIND]
    st, st_said, held, c, c_said = _stepped(ss, block, df.iloc[:end + 40], _held)
    # the C: its BLIND_OUT before the run, nothing named in it, its BACK after it
    out = next(i for i, s in enumerate(c_said) if s[1])
    assert c_said[out][1:] == (BLIND_OUT, k) and START < out < STILL_AT
    back = next(i for i in range(out + 1, len(c_said)) if c_said[i][1])
    assert c_said[back][1:] == (BACK, k) and back > STILL_AT + STILL
    # the block: held from the C's BLIND_OUT to its BACK through the run (before st106b: lost at
    # the run's MON_FREEZE_RUN-th row, then flagged FREEZE past MON_BLIND_RUN, st98b, where
    # the C names nothing), = the C all along, its fallback set served
    assert [i for i, s in enumerate(st_said) if s[0]] == [out]
    assert held[out:back] == [(False, k)] * (back - out) and held[back] == (False, -1)
    assert ss.monitor["fallback_set"][k] > 0
    assert np.max(np.abs(st - c)) <= TOLERANCE_UM



def _both(v) -> tuple:
    """``(mon_lost, mon_held, mon_jheld)`` (an export before st101: no jump held, -1)."""
    return bool(v["mon_lost"]), int(v["mon_held"]), int(v.get("mon_jheld", -1))


def test_the_block_holds_a_second_jump_beside_its_blind_out_to_each_back(record):  # noqa: F811
    """(st107) st101's spike of the sensor the C holds out for a jump, while the block holds the
    bumped one by its ``BLIND_OUT``: the C takes it out as its second (cmon88), holds both, serves
    the first one's fallback set in the monitor's order and lets each back at its own ``BACK`` (the
    bumped one's judged in the set without the other); before st107 the block flagged the jump,
    ended its hold and its judgement (``mon_lost``) and read both live on the model's laws."""
    _, ss, frame, block = record
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    k, j = names.index(BLIND), names.index(JUMPED)
    df, end = bumped(frame, BLIND)
    df.loc[HELD_AT:HELD_AT + 1, JUMPED] += JUMP_LIMITS * float(ss.monitor["jump_lim"][j])
    st, st_said, held, c, c_said = _stepped(ss, block, df.iloc[:end + 40], _both)
    # the C: its BLIND_OUT, the jump out beside it (its return re-referenced silently), the
    # jumped one back first, the bumped one later (with the other out it did not pass)
    events = [(i, s[1:]) for i, s in enumerate(c_said) if s[1]]
    out, (jback, _), (kback, _) = events[0][0], events[2], events[3]
    assert events[0][1] == (BLIND_OUT, k) and START < out < HELD_AT
    assert events[1:4] == [(HELD_AT, (JUMP, j)), (jback, (BACK, j)), (kback, (BACK, k))]
    assert HELD_AT + 2 + ss.monitor["window"] <= jback < kback
    # the block: the two flags, nothing else; both held, each to the C's BACK of it, = the C
    assert [i for i, s in enumerate(st_said) if s[0]] == [out, HELD_AT]
    assert st_said[HELD_AT] == (True, JUMP, j)
    assert [i for i, x in enumerate(held) if x[1] == k] == list(range(out, kback))
    assert [i for i, x in enumerate(held) if x[2] == j] == list(range(HELD_AT, jback))
    assert not any(x[0] for x in held)
    assert ss.monitor["fallback_set"][j] > 0 and ss.monitor["fallback_set"][k] > 0
    assert np.max(np.abs(st - c)) <= TOLERANCE_UM


def _warned(v) -> tuple:
    """``(mon_lost, mon_held, mon_warned)``: the judged sensors at their warning band in the set
    without the one held, on the row's last judgement."""
    return bool(v["mon_lost"]), int(v["mon_held"]), int(v["mon_warned"])


def test_the_block_holds_its_blind_out_past_a_window_as_the_c_with_the_field_at_its_band(record):  # noqa: F811
    """(st107c) Two sensors the others predict bumped (FOLLOW_C °C, test_export_st96's bump) while
    the C holds the bumped one out by its ``BLIND_OUT``, more than a window after it: two judged
    sensors at their warning band in the set without it, where the C (its ``_follow_field`` past
    the window) keeps it out and names nothing to its ``BACK``; before st107c the block ended the
    hold there (``mon_lost``) and read it live on the model's laws, 0.39 um off the C."""
    _, ss, frame, block = record
    k = [ss.inputs[i] for i in ss.monitor["inputs"]].index(BLIND)
    df, end = bumped(frame, BLIND)
    for sensor in FIELD[:2]:
        df, _ = bumped(df, sensor, FOLLOW_AT, FOLLOW_C)
    st, st_said, held, c, c_said = _stepped(ss, block, df.iloc[:end + 60], _warned)
    # the C: its BLIND_OUT, then nothing but its BACK, after the two bumps' rise
    events = [(i, s[1:]) for i, s in enumerate(c_said) if s[1]]
    out, back = events[0][0], events[1][0]
    assert events == [(out, (BLIND_OUT, k)), (back, (BACK, k))]
    assert START < out < FOLLOW_AT - ss.monitor["window"] and back > FOLLOW_AT + 20
    # the block: MON_FOLLOW_OTHERS (2) judged at their band while it holds, past the window
    warned = [i for i in range(out, back) if held[i][2] >= 2]
    assert warned and warned[0] > out + ss.monitor["window"]
    # held from the C's BLIND_OUT to its BACK (before st107c: lost at the first of them), = the C
    assert [i for i, s in enumerate(st_said) if s[0]] == [out]
    assert held[out:back] == [(False, k, x[2]) for x in held[out:back]] and held[back][1] == -1
    assert np.max(np.abs(st - c)) <= TOLERANCE_UM
