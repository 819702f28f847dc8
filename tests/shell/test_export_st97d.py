"""The Structured Text block says, once and with its row, where its ``BLIND_OUT`` judgement ends
for the campaign (st97d, issue 34): ``mon_stop`` TRUE on that sample, ``mon_stop_row`` its number
from there on (0 while it judges).  Before st97d the judgement ended without a word
(``mon_blind_lost``, internal) and the block, silent from there, read as "all healthy" where the
C went on naming faults.

lr9132 (``thermocomp simulate sim=long_record``, seed 9132, 3 days), MLR deployed adaptive with
``data.reference=none``, its first 670 fed rows (tests/shell/test_export_st94.py's fixture;
benchmarks/bench_st97d.py measures the rule on the seen records)."""

from __future__ import annotations

import numpy as np

from test_export import TOLERANCE_UM
from test_export_st94 import record  # noqa: F401 (the module's fixture)
from test_export_st96 import START, _stepped, bumped
from thermocomp.apps.deploy.export.watch import DRIFT_OUT, EXCLUDED, OUT, SETTLED, SPIKE

DRIFTED = "T_head_left"      # one the others predict (lr9132): its drift is the C's lone fault
LOST_AT = 670                # (st111b) a dropout there: the block's own mon_lost
SETTLING = "T_spindle_rear"  # (st111c) one no other predicts whose level shift the C re-references


def _stop(v) -> tuple:
    """``(mon_stop, mon_stop_row, mon_blind_lost, mon_unsure)`` (before st108b: no mon_unsure)."""
    return (bool(v["mon_stop"]), int(v["mon_stop_row"]), bool(v["mon_blind_lost"]),
            bool(v.get("mon_unsure", False)))


def test_the_block_says_once_with_its_row_where_its_blind_out_judgement_ends(record):  # noqa: F811
    _, ss, frame, block = record
    k = [ss.inputs[i] for i in ss.monitor["inputs"]].index(DRIFTED)
    # a drift of a sensor the others predict: the C takes it out (its lone fault), which the
    # block does not follow: its BLIND_OUT judgement ends on that row, and it says so there
    df, end = bumped(frame, DRIFTED)
    # healthy: the judgement never ends, nothing said
    assert set(_stepped(ss, block, frame.iloc[:end + 1], _stop)[2]) == {(False, 0, False, False)}
    st, st_said, stop, c, c_said = _stepped(ss, block, df.iloc[:end + 1], _stop)
    stop = [s[:3] for s in stop]
    out = next(i for i, s in enumerate(c_said) if s[1])
    assert START < out <= end and c_said[out] == (EXCLUDED | OUT, DRIFT_OUT, k)
    assert np.max(np.abs(st[:out] - c[:out])) <= TOLERANCE_UM
    assert stop[:out] == [(False, 0, False)] * out
    assert stop[out] == (True, out + 1, True)             # the row, 1-based, as the campaign's
    assert stop[out + 1:] == [(False, out + 1, True)] * (len(stop) - out - 1)    # once
    # the status is all it says there: no fault flagged on that row (the C's is not the block's)
    assert st_said[out] == (False, 0, -1)


def test_the_block_flags_every_row_after_its_stop_where_the_c_rebuilds_what_it_reads(record):  # noqa: F811
    """(st108b) From its stop the C holds the drifted sensor out and rebuilds it from the others,
    where the block reads it as measured: ``mon_unsure`` on every row where the block differs from
    the C (before st108b none was flagged), none before the stop (the same pass as above)."""
    _, ss, frame, block = record
    df, end = bumped(frame, DRIFTED)
    st, st_said, stop, c, _ = _stepped(ss, block, df.iloc[:end + 1], _stop)
    at = next(i for i, s in enumerate(stop) if s[0])
    off = np.max(np.abs(st - c), axis=1) > TOLERANCE_UM
    assert off[at:].sum() >= 10 and not off[:at].any()
    flagged = np.array([said[0] or s[3] for said, s in zip(st_said, stop)])
    assert flagged[off].all()
    assert not any(s[3] for s in stop[:at])


def test_the_block_flags_every_row_where_the_c_parts_from_it_after_its_own_lost_judgement(record):  # noqa: F811
    """(st111b) After the block's own ``mon_lost`` (here a dropout) it judges no sensor, while the
    C goes on: a later jump of a sensor the others predict is excluded and rebuilt by the C, then
    re-referenced by its step less the others' change, where the block re-references it by its
    whole step.  Every row where the block differs from the C is flagged (before st111b the rows
    past the jump's ``2 MON_WINDOW`` were not)."""
    deployed, ss, frame, block = record
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    dropped = next(c for c in names if c not in ("T_amb", DRIFTED))
    k = names.index(DRIFTED)
    df = frame.copy()
    df.loc[LOST_AT:LOST_AT + 1, dropped] = np.nan
    df.loc[LOST_AT + 20:, DRIFTED] += 3.0 * float(deployed.monitor.max_step_c[k])
    st, st_said, stop, c, _ = _stepped(ss, block, df.iloc[:LOST_AT + 120], _stop)
    off = np.max(np.abs(st - c), axis=1) > TOLERANCE_UM
    flagged = np.array([said[0] or s[3] for said, s in zip(st_said, stop)])
    assert off[LOST_AT + 20:].sum() >= 50
    assert flagged[off].all()


def test_the_block_flags_the_cs_level_shift_after_its_own_lost_judgement(record):  # noqa: F811
    """(st111c) After the block's own ``mon_lost`` (a dropout) a lasting step of a sensor no other
    predicts, under its jump and bend limits: the C re-references it by its ``SETTLED`` test a few
    rows later, where the block stopped that test at ``mon_lost`` and reads the step on.  Every row
    where the block differs from the C is flagged (before st111c, from the C's SETTLED on, none)."""
    deployed, ss, frame, block = record
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    dropped = next(c for c in names if c not in ("T_amb", DRIFTED, SETTLING))
    k = names.index(SETTLING)
    df = frame.copy()
    df.loc[LOST_AT:LOST_AT + 1, dropped] = np.nan
    df.loc[LOST_AT + 20:, SETTLING] += float(deployed.monitor.max_step_c[k])
    st, st_said, stop, c, c_said = _stepped(ss, block, df.iloc[:LOST_AT + 120], _stop)
    settled = next(i for i in range(LOST_AT + 20, len(c_said)) if c_said[i][1] == SETTLED)
    assert c_said[settled][2] == k and settled <= LOST_AT + 20 + ss.monitor["window"]
    off = np.max(np.abs(st - c), axis=1) > TOLERANCE_UM
    flagged = np.array([said[0] or s[3] for said, s in zip(st_said, stop)])
    assert off[settled:].all()    # the C's reference moved: off to the end
    assert flagged[off].all()


def _spiked(deployed, ss, block, frame, off: float):
    """(st112) ``DRIFTED`` up 6 of its largest steps for 3 rows from LOST_AT (the block's own lone
    jump, its ``mon_lost``), back ``off`` K off its readings: per row off the C, flagged,
    ``mon_unsure``; the C's SPIKE row (None: not taken)."""
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    df = frame.copy()
    df.loc[LOST_AT:LOST_AT + 2, DRIFTED] += 6.0 * float(deployed.monitor.max_step_c[names.index(DRIFTED)])
    df.loc[LOST_AT + 3:, DRIFTED] += off
    st, st_said, stop, c, c_said = _stepped(ss, block, df.iloc[:LOST_AT + 80], _stop)
    off_c = np.max(np.abs(st - c), axis=1) > TOLERANCE_UM
    unsure = np.array([s[3] for s in stop])
    flagged = np.array([said[0] for said in st_said]) | unsure
    spike = next((i for i in range(LOST_AT, len(c_said)) if c_said[i][1] == SPIKE), None)
    return off_c, flagged, unsure, spike


def test_the_block_clears_its_flag_after_a_spike_the_c_takes_back(record):  # noqa: F811
    """(st112) A lone jump of one the others predict ends the block's judgement; 3 rows later it
    jumps back.  Where the C takes that as a spike (back within its re-admission band of the
    others' prediction) its reference is put back as the block's: the block equals the C from
    there (before st112: ``mon_rjump``, to the campaign's end); (st112b) on the jump's row and the
    2 held, the C's rebuild, computed: not unsure; (st112c) nor after the return (st108b's wait).  Back
    0.3 K off (past that band, under the jump limit) the C re-references it and holds
    it out, the block reads it as back: every row off the C stays flagged."""
    deployed, ss, frame, block = record
    off_c, flagged, unsure, spike = _spiked(deployed, ss, block, frame, 0.0)
    assert spike == LOST_AT + 3 and not off_c[LOST_AT:].any() and flagged[off_c].all()
    assert not unsure[LOST_AT:].any()    # (st112c) nor after the return: the C's set whole, known
    off_c, flagged, unsure, spike = _spiked(deployed, ss, block, frame, 0.3)
    assert spike is None and off_c[LOST_AT + 3:].all() and flagged[off_c].all()
