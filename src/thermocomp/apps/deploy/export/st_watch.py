"""(st93) The sensor monitor's detection in Structured Text: the rules the C's monitor
(:mod:`.watch`) checks on each monitored reading without the POD, as outputs of ``FB_ThermoComp``.

Per sample, of each monitored sensor ``k`` (the input ``MON_INPUT[k]``, the C's ``TC_MONITORED``):

* a reading not measured (NaN, an infinity, beyond its ``U_LIMIT``): ``DROPOUT`` (``MISSING_FIRST``
  at a campaign's first sample);
* a reading beyond the monitor's range (``MON_LO_LIM`` / ``MON_HI_LIM``): ``OFF_RANGE`` (``RANGE``
  at a campaign's first sample);
* a one-sample step from its last reading beyond its jump limit times the samples it spans (a
  gap in time: its periods, past ``MON_GAP_PERIODS``): ``JUMP`` (``GLITCH`` at the sample after
  the reference; several sensors at once ``COMMON``, at least ``MON_COMMON_MIN`` a common step,
  ``COMMON_STEP``, not flagged); one that brings a re-referenced sensor back within its jump
  limit of its reference before its jumps ends the fault (a spike's return, the jump undone:
  ``SPIKE``, not flagged, as the C re-admits a spike);
* (st94) a step of a sensor no other predicts off its own last step by more than
  ``MON_BEND_LIM`` (the C's ``bend_lim``; the largest LREAL for one the others predict), under
  its jump limit, no gap: re-referenced by the departure and kept in, the C's arithmetic
  (``BENT``, named but not flagged: the C's ``REREFERENCED``, as a common step); a second one
  since it was re-referenced a jump (the C's ``mon_jumps``), none judged of a sensor re-referenced
  by a jump (the C holds it out) nor over a gap (the C's last step);
* (st94) two sensors jumping in one sample, every reading there and in range, not at the sample
  after the reference, each one in taken out by the C (:func:`pair_places`): ``JUMP`` on the
  first in (the C's exclusion, where before ``COMMON``); where both were re-referenced by jumps,
  each first tried as a spike's return, one not back re-referenced again with no new fault;
* (stwires100) two wires exchanged, the C's ``mon_exchange``: where the export has ``exchange``
  and the block knows the C has none out (``NOT mon_lost``, none held), every input measured,
  exactly two sensors flagged (a step past the jump limit, a reading beyond range), each reading
  within the other's jump limit of the other's last reading plus the change the rest predict
  for it (:func:`exchange_constants`): read exchanged from there (``mon_perm``, ``u`` reordered
  before every check and the model; st.py's ``u_read`` keeps them as read for the repeat rule),
  ``WIRES_EXCHANGED`` named on the first, not flagged (the C's ``REREFERENCED``); after the
  block's first exclusion it cannot tell the C's outs, and reads them as jumps, as before;
* (st94b) while the field is whole -- no reading missing, beyond its range or jumping since the
  campaign's first sample, nor a stepped error flagged (a BENT re-reference keeps it whole) -- a
  judged sensor's self-prediction error ``e = (d - M d) / (1 - h)`` stepping past its alarm
  band (``|e|`` and its one-sample change at least ``MON_ALARM``): the C's ``STEP_OUT`` on the
  culprit (the largest change times ``sqrt(1 - h)``; ``BLIND`` where the C does not hold it out),
  flagged.  ``d`` the readings on their references (the first sample's, moved by the block's
  re-references), ``M`` / ``h`` the POD's operator and leverages with every sensor in: the one
  fixed operator the C holds first (``MON_SELF``, ``MON_SCALE``), no Cholesky in the block;
* (st95b) a sensor out alone by that ``STEP_OUT`` (one the C holds out, nothing else named in its
  row) followed to the C's ``BACK`` (:func:`back_constants`): not judged while it is out, back
  after the C's wait where its error with every sensor in is within ``MON_BACK_BAND`` over the
  ring of the last ``MON_WINDOW`` readings (the C's ``_pass_once_back`` with all in), the block
  judging on from there;
* (st96) the C's drift judgement with every sensor in, none out (:func:`blind_constants`): a
  sensor no other predicts that explains the judged sensors beyond the band (the C's
  ``_explaining``) flagged ``BLIND_OUT`` and held out alone by the same hold, back where every
  judged sensor's error with every sensor in is within its warning band over the ring, (st106b)
  its reading standing still not ending this hold (the C names nothing for it, serving its
  fallback set on, and lets it back once the reading moves); while it is out the set without it
  judged, the block's judgement ending where the C could act on it.  A drift judgement it cannot
  follow ends the ``BLIND_OUT`` judgement to the campaign's end;
  (st100) but one with ``MON_FOLLOW_OTHERS`` + 1 judged sensors at their warning band
  (``mon_field_warned``), where whatever its culprit the C vetoes or declares a new thermal
  state and takes nothing out, pauses it (``mon_pause``) to a calm window: ``MON_WINDOW`` rows in
  a row with none at its warning band (``mon_quiet``, the C's ``calm_field``); in the pause such
  a reach pauses on, any other reach or a sensor out ends it;
* (st101) the block's own JUMP of one sensor the C holds out alone for a jump (``MON_JUMP_HELD``,
  cmon87: one no other predicts), its field whole before it, held (``mon_jheld``): the field
  computed on through the hold and not judged, to the C's ``BACK`` (``mon_jcalm`` rows since its
  last jump at least the C's wait, a full window counted, its reading moving), the C's ``_undone``
  there, the block judging on from the next row; anything else named or flagged in the hold (but
  BENT) ends it as before; (st105) held too where its ``BLIND_OUT`` judgement is paused or stopped
  (a pause stops there, as at any sensor out: st100);
* (st102) a lone jump of the sensor the block holds out by its ``BLIND_OUT``, one the C holds out
  for a jump (``MON_JUMP_HELD``): the C's silent re-reference of a sensor out (``mon_hjump``), not
  flagged, no spike's return read, re-referenced by its whole step and counted (``mon_jn``), its
  calm from it; at the hold's ``BACK`` the C's ``_undone``, st101's (``mon_jk``);
* (st107) the block's own JUMP of another sensor while it holds a ``BLIND_OUT`` (not jumped in its
  hold), one the C takes out beside it as its second (``MON_OUT_JUMP_HELD``, cmon88's second
  jump), held as st101's beside it: both out, nothing judged, the second's own later jumps the
  C's silent re-references (``mon_jbeside``); the ``BLIND_OUT``'s ``BACK`` judged in the set
  without the second (``MON_OUT_SET``'s row of the ``MON_OUT_*`` constants, one added per sensor
  held for a jump that is no candidate) unless that one is due back on the same row, the
  second's ``BACK`` st101's; the model reads both at their last readings in (``mon_hlast``,
  ``mon_jlast``), the C's served set (st.py);
* (st96b) the C's level shift of a sensor no other predicts (``SETTLED``), told by the C's test
  over ``2 MON_WINDOW`` readings (``mon_settle_ring``, ``settled.level_shift``) on the C's
  conditions (its reference unmoved for ``2 MON_WINDOW - 1`` samples, no gap, the reading before
  the sample's BENT): named, not flagged (a re-reference, as BENT), and re-referenced as the C
  does (``mon_shift``, the window ``mon_ring``; the band test reads a row from before it on its
  reference, as the C's stored errors), the block judging on;
* (st98) the C's freeze, judged while the field is whole and none is held out
  (:func:`freeze_constants`): a sensor whose reading, in range, has equalled its last one
  (``mon_frun``, the C's run) past ``MON_DITHER_RUN`` (mon97: a reading that dithers), past
  ``MON_BLIND_RUN`` (one no other predicts), or for ``MON_SEEN_RUN`` samples while the others'
  prediction of it with every sensor in moved by its warning band since the run began
  (``mon_fpred``, the C's ``run_pred``): ``FREEZE`` (``BLIND`` where the C does not hold it out),
  flagged, the block's judgement ending there (the C rebuilds it or holds it);
* (st98b) after the block's own earlier flag (``mon_lost``), the C's two run rules alone, written
  once for both paths (``mon_fpast``: the run past ``MON_DITHER_RUN``, or ``MON_BLIND_RUN`` of
  one no other predicts; ``mon_fnew``: its first sample past them): ``FREEZE`` (``BLIND``) there,
  once a run, where no rule named the sample, of a sensor the block does not hold re-referenced
  out (``mon_out``).  Not the field's rule: it needs the set the C judges;
* (st99) while the block holds a ``BLIND_OUT`` (the C's set without it, ``mon_fset``), st98's
  freeze judged in that set (its prediction ``MON_OUT_SELF`` / ``MON_OUT_SCALE``, its warning band
  ``MON_OUT_WARN``, "no other predicts" read there too): the C's second out, ``FREEZE`` where it
  holds it (``MON_OUT_FREEZE_HELD``: the set of the two had, fixed per pair), else ``SECOND``;
  and the hold judged on past one sensor at its warning band, to where the C could act (one at
  its alarm band, ``MON_FOLLOW_OTHERS`` at their warning band, a stepped error); (st107c) the
  warning-band count only within ``MON_WINDOW`` rows of its exclusion (``mon_hsince``, the C's
  ``since``: its ``_follow_field`` lets a drift exclusion back for the field only there, and with
  the field's level at the alarm band while one is out by the field, nothing else acts on it), past
  them the hold kept as the C keeps it.  A freeze named
  by the field's rule is named once a run (``mon_fpast`` kept to the run's end).

``mon_flag`` says the sample's fault, ``mon_rule`` its rule (the C's ``mon_rule`` codes, named
by ``TC_MONITOR_REASONS``) and ``mon_sensor`` its monitored sensor ``k`` (-1: none): the first,
in that order, as the C's ``tc_state`` names the sample's first event.  (st97d) ``mon_stop`` is
TRUE on the one sample where the ``BLIND_OUT`` judgement ends for the campaign (the C's lone fault,
veto or new thermal state, which the block does not follow), ``mon_stop_row`` that sample's
number in the campaign (1 the first; 0 while it judges): said once, no fault flagged with it, so
that the block's silence from there is not read as "healthy".  (st108b) ``mon_unsure`` is TRUE on
the rows where the block's number may differ from the C's because the C may hold out and rebuild a
sensor the block reads: a ``STEP_OUT`` it holds, and, from its stop or a flag that ends its
judgement (``mon_lost``), each row it flags or where a judged sensor's error with every sensor in
is at its warning band, and ``2 MON_WINDOW`` rows after (the C's first wait); it only says so.
(st109) A reading beyond its range at a campaign's first sample, one alone of a sensor the
others predict (:func:`late_constants`), is read as the C reads it (dep108 / dep108f): the
stand-in ``MON_FIRST_C`` plus the others' prediction (``mon_late``, ``mon_lpred``: not refused),
referenced late at its return and read so to the C's ``BACK``; anything else gone or named
meanwhile sets ``mon_rfirst`` (st108d: ``mon_unsure`` to the campaign's end).  (st109b) So does a
reading beyond its range after the first sample (``mon_rlater``; but the followed one's): the C
may read it on as a machine hotter than training and re-reference it at its return.
(st111b) After ``mon_lost`` the errors with every sensor in are computed on for that test (the C
judges on), and a later jump of a sensor the others predict sets ``mon_rjump`` (``mon_unsure`` to
the campaign's end: the C re-references it by its step less the others' change).
(st111c) So does a level shift after ``mon_lost`` of one no other predicts (``mon_rsettle``: its
windows parted past ``MON_SETTLE_LIM`` on the block's readings, the C's ``SETTLED`` test without its
steadiness test): the C re-references it, by an amount the block cannot tell.
(st112) Not the return of a sensor whose lone jump, the set whole before it, ended the judgement
within a window, nothing else since, where the C's spike test passes (:func:`spike_constants`:
its prediction by the others within ``MON_READMIT`` of its warning band): the C puts its reference
back as the block does and its set is whole again.  (st112c) Nor, from that return, st108b's
wait: nothing at the band since the jump nor on the return row, the hold followed (st112b), the
C's window recomputed with every sensor in is the block's ``mon_e``: only a new band row restarts it.
The counters that grow with the campaign
(``mon_count``, ``mon_stop_row``, ``mon_calm``, ``mon_run``, ``mon_quiet``, ``mon_jcalm``, ``mon_lcalm``,
``mon_hsince``, ``mon_sj_age``) are DINT: an INT wraps after 32767 samples (9 h at 1 s), and a wrapped
count stops the judgement (``mon_count + 1 >= MON_CONFIRM``).

What the block does then, without the POD that rebuilds a sensor in the C: a reading not
measured or beyond the range refuses the sample (``refused``: ``c`` holds the last correction,
nothing remembered changes, as for any input not measured), the correction of a sensor the
block cannot read being the last one read with it; a jump is re-referenced by its whole step
(``mon_shift``), the C's path for a sensor no other predicts (cmon87), so that the model reads
the sensor continuous with its last reading and a spike's return undoes it; a pair's jumpers too
(the C re-references them by their step less the change the others predict, and rebuilds them:
the block parts from the C after the pair's sample, as after any jump the C excludes).  The block
keeps no count of the sensors the C holds out (it cannot tell the C's re-admission): a pair is
judged as the C judges it with none out but the jumpers.  The freeze with a
sensor out (but a ``BLIND_OUT`` the block holds: st99), the drift, the re-admission and the
rest judge a sensor by the others' prediction of it over a set the block does not know (the
POD): not in the ST, they stay with the served model (``provenance.not_in_code``); (st103b) but
while the block holds a sensor out by its ``BLIND_OUT`` the model reads it at its last reading in
and the outputs sum its fallback model's laws, as the C's (st.py ``serving``).  (st94b)
The stepped self-prediction error is judged while the field is whole only: from the first
exclusion the block flags (a jump, a dropout, a reading beyond range, a stepped error not
followed to its ``BACK``; st101: a jump it holds to the C's ``BACK`` neither) to the campaign's
end the C judges it with a sensor out (or re-admitted by a band the block does not hold), and the
block does not; that flag marks the row its judgement ends (st95b: or, while one is out, a rule
named or its reading standing still).
"""

from __future__ import annotations

import sys

import numpy as np

from .watch import (
    BENT,
    BLIND,
    BLIND_OUT,
    COMMON,
    COMMON_STEP,
    DROPOUT,
    FREEZE,
    GLITCH,
    JUMP,
    MISSING_FIRST,
    OFF_RANGE,
    RANGE,
    SECOND,
    SETTLED,
    SPIKE,
    STEP_OUT,
    WIRES_EXCHANGED,
)


def pair_places(watch: dict) -> tuple[np.ndarray, np.ndarray]:
    """(st94) Which monitored sensors the C takes out for a jump of two in one sample (cmon93,
    :meth:`.watch.CodeMonitor._pair_held`): ``(first, second)``, as the first out (the others
    predict it, or cmon87 one no other predicts held at its last reading) and as the second
    (cmon88: one the others predict; cmon89: one no other predicts where the field is rebuilt
    without both), the set of the two solved (``solve``).  All False for an export before
    ``pair_jump``: the pair flagged ``COMMON`` as before."""
    n = len(watch.get("inputs", []))
    if not watch.get("pair_jump") or not n:
        return np.zeros(n, bool), np.zeros(n, bool)
    ported = np.asarray(watch["ported_out"], bool)
    spikes = jump_held(watch)
    second = bool(watch.get("second_jump")) and bool(watch.get("solve")) and "basis" in watch
    instant = bool(watch.get("second_instant")) & spikes & (n - 2 >= watch["min_active"])
    return ported | spikes, second & (ported | instant)


def jump_held(watch: dict) -> np.ndarray:
    """(cmon87) The sensors no other predicts that the C holds out alone for a jump, back at its
    ``BACK`` with the jump undone (``blind_jump``, with ``blind_drop``: held at the last reading,
    every other in); all False for an export before it (the C flags the jump ``BLIND``)."""
    n = len(watch.get("inputs", []))
    blind = ~np.asarray(watch.get("predictable", [True] * n), bool)
    held = bool(watch.get("blind_drop")) and bool(watch.get("blind_jump"))
    return blind & held & (n - 1 >= watch.get("min_active", n))


def self_prediction(watch: dict) -> tuple:
    """(st94b) The C's self-prediction error with every monitored sensor in, as fixed arrays:
    ``(M, scale, root, judged, alarm, on)``, ``e = (d - M d) * scale`` (``scale`` ``1 / (1 - h)``
    of a judged sensor, 0 of another), ``root`` ``sqrt(|1 - h|)`` (the culprit's weight), the
    sensors judged (``h`` below the POD's leverage limit), their alarm bands (the whole set's),
    and whether the block judges it (an export with ``stepped``: all zero, off, before)."""
    n = len(watch.get("inputs", []))
    if not (n and watch.get("stepped") and watch.get("M")):
        return np.zeros((n, n)), np.zeros(n), np.zeros(n), np.zeros(n, bool), np.zeros(n), False
    M, lev = np.asarray(watch["M"][0], float), np.asarray(watch["lev"][0], float)
    judged = lev < float(watch["max_leverage"])
    # (the C's scale, the mirror's ``_set``: 1 / (1 - h), floored as there)
    scale = np.where(judged, 1.0 / np.maximum(1.0 - lev, 1e-12), 0.0)
    return M, scale, np.sqrt(np.abs(1.0 - lev)), judged, np.asarray(watch["alarm"], float), True


def back_constants(watch: dict, n: int, stepped: bool, constant) -> list[str]:
    """(st95b) What the block needs to follow the C's re-admission by ``BACK`` of one sensor out
    alone by its own ``STEP_OUT``: the window ``w`` (its ring's rows, the C's count before any
    return), the largest doubling of the wait (``max_backoff``) and each sensor's re-admission
    band with every sensor in (``READMIT`` times the whole set's warning band)."""
    band = float(watch.get("readmit", 0.5)) * np.asarray(watch.get("warning", [0.0] * n), float)
    # the shorter of its freeze runs (one the others see, one they do not: the C's frozen)
    runs = np.minimum(np.asarray(watch.get("seen_run", [1] * n), int),
                      np.asarray(watch.get("blind_run", [0] * n), int) + 1)
    return [f"    MON_FOLLOW_BACK : BOOL := {'TRUE' if stepped and n else 'FALSE'};",
            f"    MON_WINDOW : INT := {max(int(watch.get('window', 1)), 1)};",
            f"    MON_MAX_BACKOFF : INT := {int(watch.get('max_backoff', 10))};",
            constant("MON_BACK_BAND", band.tolist(), (n,)),
            constant("MON_FREEZE_RUN", runs.tolist(), (n,), "INT"),
            constant("MON_JUMP_HELD", jump_held(watch).astype(int).tolist(), (n,), "INT")]


def freeze_constants(watch: dict, n: int, constant) -> list[str]:
    """(st98) What the block needs to judge a freeze as the C does with every sensor in (the
    mirror's ``frozen``): each sensor's runs as whole samples -- ``seen_run`` (one the others
    predict, while their prediction of it moved by its warning band: a run at least it), and
    ``blind_run`` (one they do not) and ``dither_run`` (mon97: one whose reading dithers; none
    elsewhere, an export before it) that a run must pass -- and whether the C holds it out for
    it (``MON_FREEZE_HELD``: the others predict it, or cmon84 one no other predicts held at its
    last reading; else the C flags it ``BLIND``).  No run bound: DINT's top, never reached."""
    top = 2**31 - 1
    blind = ~np.asarray(watch.get("predictable", [True] * n), bool)
    drops = blind & bool(watch.get("blind_drop")) & (n - 1 >= watch.get("min_active", n))
    held = np.asarray(watch.get("ported_out", [0] * n), bool) | drops

    def runs(key: str, whole) -> list[int]:
        values = np.asarray(watch.get(key, [np.inf] * n), float)
        return [int(whole(v)) if np.isfinite(v) and v < top else top for v in values]

    return [constant("MON_SEEN_RUN", runs("seen_run", np.ceil), (n,), "DINT"),
            constant("MON_BLIND_RUN", runs("blind_run", np.floor), (n,), "DINT"),
            constant("MON_DITHER_RUN", runs("dither_run", np.floor), (n,), "DINT"),
            constant("MON_FREEZE_HELD", held.astype(int).tolist(), (n,), "INT")]


def exchange_constants(watch: dict, n: int, constant) -> list[str]:
    """(stwires100) What the block needs to read two exchanged wires as the C (``mon_exchange``,
    the mirror's ``CodeMonitor._exchanged``): ``MON_XCH_CHANGE[i, k, m]``, the weight of sensor
    ``m``'s one-sample change in the change the set without ``i`` and ``k`` predicts for ``i``
    (row ``i`` of its operator on the others; 0 where ``i``'s leverage without ``k`` is at the
    limit: the C reads its last reading), and ``MON_XCH_SOLVED[i, k]``, whether the C has the
    operators (``_change_seen``: None, the C's ``NOT_IN_CODE``).  Off (``MON_EXCHANGE``) for an
    export before wires100."""
    from .watch import CodeMonitor

    on = bool(n and watch.get("exchange"))
    change, solved = np.zeros((n, n, n)), np.zeros((n, n), int)
    mon = CodeMonitor(watch) if on else None
    for i, k in ((i, k) for i in range(n) for k in range(n) if on and i != k):
        pair = np.isin(np.arange(n), (i, k))
        op, own = mon._operator(pair), mon._operator(np.arange(n) == k)
        if op is None or own is None or mon._operator(np.arange(n) == i) is None:
            continue
        solved[i, k] = 1
        if own[1][i] < mon.max_lev:
            change[i, k] = np.where(pair, 0.0, op[0][i])
    return [f"    MON_EXCHANGE : BOOL := {'TRUE' if on else 'FALSE'};",
            constant("MON_XCH_CHANGE", change.tolist(), (n, n, n)),
            constant("MON_XCH_SOLVED", solved.tolist(), (n, n), "INT")]


def blind_constants(watch: dict, n: int, stepped: bool, literal, constant) -> list[str]:
    """(st96) What the block needs to take out, as the C's drift judgement does with every sensor
    in, a sensor no other predicts that explains the others' errors (``BLIND_OUT``, the C's
    ``_explaining``), and to hold it out alone to the C's ``BACK``: the band the last ``confirm``
    errors must all reach (``exclude_level``'s: ``MON_FIELD_BAND``), the whole set's warning band,
    the sensors whose error is evidence (not ``warn_only``), each residual's divisor
    ``sqrt(1 - h)``, and per such sensor (``MON_BLIND``) the operator, scale, evidence and bands
    of the set without it (:class:`.watch.CodeMonitor`'s ``_operator`` / ``_bands``)."""
    from .watch import CodeMonitor

    judge = bool(n and stepped and watch.get("blind_out") and watch.get("drift"))
    mon = CodeMonitor(watch) if judge else None
    lev = np.asarray(watch["lev"][0], float) if judge else np.zeros(n)
    judged = lev < float(watch.get("max_leverage", 1.0))
    warned = np.asarray(watch.get("warn_only", [0] * n), bool)
    evidence = judged & ~warned
    # (the C's candidates: in, no other predicts it, its error evidence, enough left without it)
    blinds = [u for u in range(n) if judge and not judged[u] and not warned[u]
              and n - 1 >= watch["min_active"]]
    # (st107) and, past them, each other sensor the C holds out for a jump: their sets' rows
    # (MON_OUT_SET), read by a BLIND_OUT's BACK test while that one is held beside it
    sets = blinds + [u for u in range(n) if judge and mon.spikes[u] and u not in blinds]
    rows = max(len(sets), 1)
    self_m, scale, judging, warn, alarm, second, jumps = (np.zeros((rows, n, n)),
                                                          *(np.zeros((rows, n)) for _ in range(6)))
    for b, u in enumerate(sets):
        out = np.arange(n) == u
        M, lu = mon._operator(out)
        self_m[b] = M
        scale[b] = np.where(~out & (lu < mon.max_lev), 1.0 / np.maximum(1.0 - lu, 1e-12), 0.0)
        judging[b] = (scale[b] > 0) & ~mon.warn_only
        warn[b], alarm[b] = mon._bands(~out)
        # (st99) a freeze with it out: the second out where the C holds it (one the others
        # predict; freezeu100: or one no other predicts, as its dropout, where the field is
        # rebuilt without the two: _second_kind; the set of the two had: cmon85's _second_held,
        # static per pair), else SECOND
        kind = mon.ported | (mon.instant & mon.drops & (n - 2 >= watch["min_active"]))
        second[b] = [k != u and kind[k] and mon.solve and FREEZE in mon.seconds
                     and mon._operator(out | (np.arange(n) == k)) is not None for k in range(n)]
        # (st107) a jump with it out: the second out the block holds too where the C holds it at
        # its last reading (cmon88's second jump of one no other predicts, _second_kind /
        # _second_held: the set of the two solved, static per pair), one with its own set here
        # (its BACK test's operator) and enough left in to serve a fallback set (the C's serving)
        jumps[b] = [k != u and u in blinds and mon.spikes[k] and not mon.ported[k] and mon.instant
                    and mon.solve and JUMP in mon.seconds and n - 2 >= watch["min_active"]
                    and mon._operator(out | (np.arange(n) == k)) is not None for k in range(n)]
    field = (watch.get("warning") if int(watch.get("exclude_level", 2)) == 1 else watch.get("alarm"))
    nb, ns = len(blinds), len(sets)
    w = max(int(watch.get("window", 1)), 1)
    # (jump94b) the sensors whose level shift the C re-references (SETTLED)
    settle = np.asarray(watch.get("settle_lim", [np.inf] * n), float)
    settles = bool(watch.get("settled")) & np.isfinite(settle)
    judge = judge and n > watch["min_active"] and nb > 0     # (the C's: more in than min_active)
    return [f"    MON_BLIND_JUDGE : BOOL := {'TRUE' if judge else 'FALSE'};",
            f"    MON_CONFIRM : INT := {max(int(watch.get('confirm', 1)), 1)};",
            f"    MON_BLINDS : INT := {nb};",
            constant("MON_BLIND", blinds, (nb,), "INT"),
            constant("MON_FIELD_BAND", list(field or [0.0] * n), (n,)),
            constant("MON_WARN", list(watch.get("warning", [0.0] * n)), (n,)),
            constant("MON_JUDGING", evidence.astype(int).tolist(), (n,), "INT"),
            constant("MON_SETTLES", settles.astype(int).tolist(), (n,), "INT"),
            constant("MON_SETTLE_LIM", np.where(settles, settle, 0.0).tolist(), (n,)),
            f"    MON_SETTLE_STEADY : LREAL := {literal(watch.get('settle_steady', 0.0))};",
            f"    MON_MID_LO : INT := {(w - 1) // 2};",
            f"    MON_MID_HI : INT := {w // 2};",
            constant("MON_Z_ROOT", np.sqrt(np.maximum(1.0 - lev, 1e-12)).tolist(), (n,)),
            constant("MON_OUT_SELF", self_m.tolist(), (ns, n, n)),
            constant("MON_OUT_SCALE", scale.tolist(), (ns, n)),
            constant("MON_OUT_JUDGING", judging.astype(int).tolist(), (ns, n), "INT"),
            constant("MON_OUT_WARN", warn.tolist(), (ns, n)),
            constant("MON_OUT_ALARM", alarm.tolist(), (ns, n)),
            constant("MON_OUT_FREEZE_HELD", second.astype(int).tolist(), (ns, n), "INT"),
            constant("MON_OUT_JUMP_HELD", jumps.astype(int).tolist(), (ns, n), "INT"),
            constant("MON_OUT_SET", [sets.index(k) if k in sets else -1 for k in range(n)], (n,), "INT"),
            f"    MON_FOLLOW_OTHERS : INT := {int(watch.get('new_state_others', 2))};"]


def late_constants(watch: dict, n: int, stepped: bool, constant) -> list[str]:
    """(st109) What the block needs to start a sensor beyond its range at a campaign's first sample
    as the C does (dep108 / dep108f, :meth:`.watch.CodeMonitor.step`'s ``late``): its stand-in
    ``MON_FIRST_C`` (the training's first reading), the row of the set-without-it operator that
    rebuilds it from the others (``MON_LATE_FIELD[k, m]``, 0 at ``m = k``) and whether the block
    follows it (``MON_LATE_OK``: ``late`` exported, the others predict it, it has no fallback model,
    enough are left without it, and, for the C's ``BACK`` test with every sensor in, ``stepped``
    and it judged there)."""
    from .watch import CodeMonitor

    field, ok = np.zeros((n, n)), np.zeros(n, int)
    late = bool(n and watch.get("late") and stepped)
    mon = CodeMonitor(watch) if late else None
    judged = np.asarray(watch["lev"][0], float) < float(watch["max_leverage"]) if late else ok
    for k in (k for k in range(n) if late and n - 1 >= watch["min_active"]):
        op = mon._operator(np.arange(n) == k)
        if op is None or not (mon.predictable[k] and judged[k]) or watch.get("fallback", [0] * n)[k]:
            continue
        ok[k], field[k] = 1, np.where(np.arange(n) == k, 0.0, op[0][k])
    return [constant("MON_FIRST_C", list(watch.get("first_c", [0.0] * n)), (n,)),
            constant("MON_LATE_FIELD", field.tolist(), (n, n)),
            constant("MON_LATE_OK", ok.tolist(), (n,), "INT")]


def spike_constants(watch: dict, n: int, stepped: bool, literal, constant) -> list[str]:
    """(st112) What the block needs to tell, after its own ``mon_lost``, that the C took a lone
    jump's return as a spike (:meth:`.watch.CodeMonitor._spike_back` with every other sensor in):
    per sensor the others predict (``MON_SPIKE_OK``: the C's spike rule on, judged with every sensor
    in, enough left without it) the row of the set-without-it operator that predicts it
    (``MON_SPIKE_FIELD``) and the C's re-admission factor (``MON_READMIT``, times ``MON_WARN``)."""
    from .watch import CodeMonitor

    field, ok = np.zeros((n, n)), np.zeros(n, int)
    on = bool(n and stepped and watch.get("spike") and n - 1 >= watch["min_active"])
    mon = CodeMonitor(watch) if on else None
    for k in (k for k in range(n) if on and mon.predictable[k] and mon.lev[0][k] < mon.max_lev):
        op = mon._operator(np.arange(n) == k)
        if op is not None:
            ok[k], field[k] = 1, op[0][k]
    return [constant("MON_SPIKE_OK", ok.tolist(), (n,), "INT"),
            constant("MON_SPIKE_FIELD", field.tolist(), (n, n)),
            f"    MON_READMIT : LREAL := {literal(float(watch.get('readmit', 0.0)))};"]


def constants(watch: dict, literal, constant) -> list[str]:
    """The monitor's constants (``watch``: :func:`.watch.monitor_fields`'s ``monitor``, empty:
    none, ``MON_N`` 0) in the block's ``VAR CONSTANT``."""
    n = len(watch.get("inputs", []))
    rules = (("JUMP", JUMP), ("GLITCH", GLITCH), ("COMMON", COMMON), ("COMMON_STEP", COMMON_STEP),
             ("DROPOUT", DROPOUT), ("MISSING_FIRST", MISSING_FIRST), ("OFF_RANGE", OFF_RANGE),
             ("RANGE", RANGE), ("SPIKE", SPIKE), ("BENT", BENT),
             ("STEP_OUT", STEP_OUT), ("BLIND", BLIND), ("BLIND_OUT", BLIND_OUT),
             ("SETTLED", SETTLED), ("FREEZE", FREEZE), ("SECOND", SECOND),
             ("WIRES_EXCHANGED", WIRES_EXCHANGED))
    # (st94) no bound where the export has none (before step93, a sensor the others predict):
    # the largest LREAL, as ST has no infinity
    bends = np.asarray(watch.get("bend_lim", []) if watch.get("bent") else [np.inf] * n, float)
    first, second = pair_places(watch)
    self_m, scale, root, judged, alarm, stepped = self_prediction(watch)
    return [f"    MON_N : INT := {n};",
            constant("MON_INPUT", watch.get("inputs", []), (n,), "INT"),
            *(constant(f"MON_{name}", watch.get(key, []), (n,))
              for name, key in (("JUMP_LIM", "jump_lim"), ("LO_LIM", "lo_lim"), ("HI_LIM", "hi_lim"))),
            constant("MON_BEND_LIM", np.minimum(bends, sys.float_info.max).tolist(), (n,)),
            f"    MON_PAIR_JUMP : BOOL := {'TRUE' if first.any() else 'FALSE'};",
            constant("MON_PAIR_FIRST", first.astype(int).tolist(), (n,), "INT"),
            constant("MON_PAIR_SECOND", second.astype(int).tolist(), (n,), "INT"),
            f"    MON_STEP_JUDGE : BOOL := {'TRUE' if stepped else 'FALSE'};",
            constant("MON_SELF", self_m.tolist(), (n, n)),
            *(constant(name, values.tolist(), (n,)) for name, values in
              (("MON_SCALE", scale), ("MON_ROOT", root), ("MON_ALARM", alarm))),
            constant("MON_JUDGED", judged.astype(int).tolist(), (n,), "INT"),
            constant("MON_STEP_HELD", [int(p) for p in watch.get("ported_out", [])], (n,), "INT"),
            *back_constants(watch, alarm.size, stepped, constant),
            *blind_constants(watch, alarm.size, stepped, literal, constant),
            *freeze_constants(watch, alarm.size, constant),
            *exchange_constants(watch, alarm.size, constant),
            *late_constants(watch, alarm.size, stepped, constant),
            *spike_constants(watch, alarm.size, stepped, literal, constant),
            f"    MON_PERIOD : LREAL := {literal(watch.get('period', 1.0))};",
            f"    MON_GAP_PERIODS : LREAL := {literal(watch.get('gap_periods', 1.5))};",
            f"    MON_COMMON_MIN : INT := {int(watch.get('common_min', 3))};",
            *(f"    RULE_{name} : INT := {code};" for name, code in rules)]


OUTPUTS = """    mon_flag : BOOL;
    mon_rule : INT;
    mon_sensor : INT;
    mon_stop : BOOL;
    mon_stop_row : DINT;
    mon_unsure : BOOL;
"""

VARS = """    mon_last : ARRAY[{nm}] OF LREAL;
    mon_gap : ARRAY[{nm}] OF LREAL;
    mon_step : ARRAY[{nm}] OF LREAL;
    mon_big : ARRAY[{nm}] OF BOOL;
    mon_last_step : ARRAY[{nm}] OF LREAL;
    mon_has_step : ARRAY[{nm}] OF BOOL;
    mon_out : ARRAY[{nm}] OF BOOL;
    mon_rerefd : ARRAY[{nm}] OF BOOL;
    mon_spike : ARRAY[{nm}] OF BOOL;
    mon_shift : ARRAY[{n}] OF LREAL;
    mon_base : ARRAY[{nm}] OF LREAL;
    mon_d : ARRAY[{nm}] OF LREAL;
    mon_e : ARRAY[{nm}] OF LREAL;
    mon_prev_e : ARRAY[{nm}] OF LREAL;
    mon_lost : BOOL;
    mon_e_known : BOOL;
    mon_best : LREAL;
    mon_culprit : INT;
    mj : INT;
    mon_t_prev : LREAL;
    mon_t_known : BOOL;
    mon_count : DINT;
    mon_span : LREAL;
    mon_lim : LREAL;
    mon_x : LREAL;
    mon_jumps : INT;
    mon_gone : BOOL;
    mon_back : BOOL;
    mon_off : LREAL;
    mon_pair : BOOL;
    mon_place : INT;
    mon_outs : INT;
    mk : INT;
    mon_ring : ARRAY[{ring}] OF LREAL;
    mon_pos : INT;
    mon_held : INT;
    mon_was : INT;
    mon_calm : DINT;
    mon_hsince : DINT;
    mon_run : DINT;
    mon_run_was : DINT;
    mon_dwell : INT;
    mon_field_outs : ARRAY[{nm}] OF INT;
    mr : INT;
    mon_held_set : INT;
    mon_take : INT;
    mon_take_set : INT;
    mon_judge : BOOL;
    mon_blind_lost : BOOL;
    mon_reach : BOOL;
    mon_go : BOOL;
    mon_ok : BOOL;
    mon_ev : BOOL;
    mon_zbest : LREAL;
    mon_set : INT;
    mb : INT;
    mi : INT;
    mon_min : ARRAY[{nm}] OF LREAL;
    mon_r : ARRAY[{nm}] OF LREAL;
    mon_z : ARRAY[{nm}] OF LREAL;
    mon_over : ARRAY[{nm}] OF BOOL;
    mon_eu : ARRAY[{nm}] OF LREAL;
    mon_prev_eu : ARRAY[{nm}] OF LREAL;
    mon_settle_ring : ARRAY[{settle}] OF LREAL;
    mon_spos : INT;
    mon_sort : ARRAY[{w}] OF LREAL;
    mon_wlo : ARRAY[0..1] OF LREAL;
    mon_whi : ARRAY[0..1] OF LREAL;
    mon_med : ARRAY[0..1] OF LREAL;
    mon_mad : ARRAY[0..1] OF LREAL;
    mw : INT;
    mq : INT;
    ma : INT;
    mon_bent : ARRAY[{nm}] OF LREAL;
    mon_sage : ARRAY[{nm}] OF INT;
    mon_since : ARRAY[{nm}] OF INT;
    mon_sback : ARRAY[{nm}] OF LREAL;
    mon_undo : LREAL;
    mon_frun : ARRAY[{nm}] OF DINT;
    mon_fpred : ARRAY[{nm}] OF LREAL;
    mon_fpast : ARRAY[{nm}] OF BOOL;
    mon_fnew : ARRAY[{nm}] OF BOOL;
    mon_froze : INT;
    mon_still : BOOL;
    mon_fset : INT;
    mon_warned : INT;
    mon_field_warned : INT;
    mon_pause : BOOL;
    mon_quiet : DINT;
    mon_jheld : INT;
    mon_jcalm : DINT;
    mon_jn : INT;
    mon_jdwell : INT;
    mon_jshift0 : LREAL;
    mon_jlast : LREAL;
    mon_hlast : LREAL;    (* (st107) the BLIND_OUT held's last reading in (mon_jlast: the jumped one's) *)
    mon_jset : INT;    (* (st107) the jumped one's set (MON_OUT_SET's) where held beside a BLIND_OUT *)
    mon_bset : INT;
    mon_jbeside : BOOL;
    mon_hjump : BOOL;
    mon_jk : INT;
    mon_perm : ARRAY[{nm}] OF INT;
    mon_xr : ARRAY[{nm}] OF LREAL;
    mon_xlim : ARRAY[{nm}] OF LREAL;
    mon_xn : INT;
    mon_xi : INT;
    mon_xk : INT;
    mon_xsi : LREAL;
    mon_xsk : LREAL;
    mon_usince : DINT;
    mon_rfirst : BOOL;
    mon_rlater : BOOL;    (* (st109b) a reading beyond its range after the first sample *)
    mon_other : ARRAY[{nm}] OF LREAL;
    mon_other_known : BOOL;    (* (st111) mon_other is the C's last one: its set whole on that row *)
    mon_whole : BOOL;    (* (st111) the C's set whole before this row, as far as the block knows *)
    mon_junsure : BOOL;    (* (st111) a lone jump re-referenced otherwise than the C *)
    mon_rjump : BOOL;    (* (st111b) a jump of one the others predict after mon_lost *)
    mon_rsettle : BOOL;    (* (st111c) the C's level shift possible after mon_lost *)
    mon_sj : INT;    (* (st112) the one whose lone jump ended the judgement, its return awaited *)
    mon_sj_age : DINT;    (* (st112) rows since that jump *)
    mon_rb : INT := -1;    (* (st112b) the one the C holds out and rebuilds this row; -1: none *)
    mon_rbx : LREAL;    (* (st112b) its rebuild: the others' prediction of it, its set without it *)
    mon_rbheld : BOOL;    (* (st112b) the C holds mon_sj out, its BACK not come *)
    mon_rbok : DINT;    (* (st112b) rows in a row since its jump its error within its back band *)
    mon_rbdwell : DINT;    (* (st112b) the C's wait for it *)
    mon_rbu : LREAL;    (* (st112b) its reading on the row before *)
    mon_rbk : INT;    (* (st112b) the one held *)
    mon_rbrun : INT;    (* (st112b) rows its reading stood still *)
    mon_rbunsure : BOOL;    (* (st112b) the C's hold of it lost track of: unsure to the end *)
    (* (st111c) each sensor's shift at the row before *)
    mon_rshift : ARRAY[{nm}] OF LREAL;
    mon_efresh : BOOL;    (* (st111b) mon_e computed by the judgement this row *)
    mon_late : INT;    (* (st109) the sensor beyond its range since the first sample, followed *)
    mon_lback : BOOL;
    mon_lcalm : DINT;
    mon_lpred : LREAL;
    mon_lgone : INT;
    mon_lpos : INT;
    mon_lring : ARRAY[{ring}] OF LREAL;
"""

# before the refusal: the sample's monitored readings judged (the block's first == a campaign's)
# the C's level-shift test's first half (settled.level_shift): how far the settle ring's two
# windows of sensor mk part (mon_x), one text where the block judges and where it only flags
# after its own mon_lost (st111c)
_WINDOWS_PARTED = """            FOR mw := 0 TO 1 DO
                FOR mi := 0 TO MON_WINDOW - 1 DO
                    mr := mon_spos - mi - mw * MON_WINDOW;
                    IF mr < 0 THEN
                        mr := mr + 2 * MON_WINDOW;
                    END_IF;
                    mon_x := mon_settle_ring[mr, mk];
                    IF mi = 0 OR mon_x < mon_wlo[mw] THEN
                        mon_wlo[mw] := mon_x;
                    END_IF;
                    IF mi = 0 OR mon_x > mon_whi[mw] THEN
                        mon_whi[mw] := mon_x;
                    END_IF;
                END_FOR;
            END_FOR;
            mon_x := mon_wlo[0] - mon_whi[1];
            IF mon_wlo[1] - mon_whi[0] > mon_x THEN
                mon_x := mon_wlo[1] - mon_whi[0];
            END_IF;
"""

BLOCK = """(* (st93) the sensor monitor's detection (the C's rules without the POD): a reading not *)
(* measured, beyond the monitor's range, or a step from its last reading past its jump limit *)
mon_flag := FALSE;
mon_rule := 0;
mon_sensor := -1;
mon_stop := FALSE;
mon_gone := FALSE;
mon_jk := -1;
IF first THEN
    mon_count := 0;
    mon_stop_row := 0;
    mon_usince := 2147483646;
    mon_t_known := FALSE;
    FOR j := 0 TO N_INPUTS - 1 DO
        mon_shift[j] := 0.0;
    END_FOR;
    FOR mk := 0 TO MON_N - 1 DO
        mon_out[mk] := FALSE;
        mon_rerefd[mk] := FALSE;
        mon_base[mk] := u[MON_INPUT[mk]];    (* (st94b) the C's reference *)
        mon_field_outs[mk] := 0;
        mon_sage[mk] := 0;    (* (st96b) the C's reference age and its last SETTLED *)
        mon_since[mk] := MON_WINDOW;
        mon_sback[mk] := 0.0;
    END_FOR;
    mon_lost := FALSE;
    mon_blind_lost := FALSE;
    mon_pause := FALSE;
    mon_quiet := 0;
    mon_e_known := FALSE;
    mon_pos := 0;
    mon_spos := 0;
    mon_held := -1;
    mon_held_set := -1;
    mon_jheld := -1;
    mon_jset := -1;
    mon_other_known := FALSE;
END_IF;
IF reset THEN    (* (st111) to the campaign's end, not first's (held through refused rows) *)
    mon_junsure := FALSE;
    mon_sj := -1;
END_IF;
(* (st99) the set the C judges a freeze by: every sensor in (-1), or without the BLIND_OUT *)
(* the block holds (its set, MON_OUT_SELF's): the C's second out *)
mon_fset := -1;
IF mon_held >= 0 AND NOT mon_lost THEN
    mon_fset := mon_held_set;
END_IF;
(* a gap in time: each step judged as that many one-sample steps, as the C *)
mon_span := 1.0;
IF has_time AND mon_t_known AND NOT first THEN
    IF time_s - mon_t_prev > MON_GAP_PERIODS * MON_PERIOD THEN
        mon_span := (time_s - mon_t_prev) / MON_PERIOD;
    END_IF;
END_IF;
(* (stwires100) two wires exchanged, as the C's mon_exchange: the monitored readings read in *)
(* mon_perm's order (u rewritten: every check and the model read them so); where the block *)
(* knows the C has none out (its field whole, none held), every input measured, exactly two *)
(* flagged (a step past the jump limit, a reading beyond range), each reading within the *)
(* OTHER's jump limit of the other's last reading plus the change the rest predict for it: *)
(* read exchanged from here, named WIRES_EXCHANGED (not flagged: the C's REREFERENCED) *)
IF first THEN
    FOR mk := 0 TO MON_N - 1 DO
        mon_perm[mk] := mk;
    END_FOR;
ELSE
    mon_xn := 0;
    FOR j := 0 TO N_INPUTS - 1 DO
        IF HELD[j] = 0 AND NOT (u[j] >= -U_LIMIT[j] AND u[j] <= U_LIMIT[j]) THEN
            mon_xn := MON_N + 1;    (* refused or missing: the C reads no pair *)
        END_IF;
    END_FOR;
    FOR mk := 0 TO MON_N - 1 DO
        mon_xr[mk] := u[MON_INPUT[mon_perm[mk]]];
    END_FOR;
    mon_xi := -1;
    mon_xk := -1;
    IF MON_EXCHANGE AND NOT mon_lost AND mon_held < 0 AND mon_count > 0 THEN
        FOR mk := 0 TO MON_N - 1 DO
            mon_xlim[mk] := MON_JUMP_LIM[mk] * mon_gap[mk];
            IF mon_span > mon_gap[mk] THEN
                mon_xlim[mk] := MON_JUMP_LIM[mk] * mon_span;
            END_IF;
            mon_x := mon_xr[mk] - mon_last[mk];
            mon_ev := mon_xr[mk] < MON_LO_LIM[mk] OR mon_xr[mk] > MON_HI_LIM[mk];
            IF mon_ev OR mon_x > mon_xlim[mk] OR mon_x < -mon_xlim[mk] THEN
                IF mon_xi < 0 THEN
                    mon_xi := mk;
                ELSE
                    mon_xk := mk;
                END_IF;
                mon_xn := mon_xn + 1;
            END_IF;
        END_FOR;
    END_IF;
    IF mon_xn = 2 THEN
        IF MON_XCH_SOLVED[mon_xi, mon_xk] = 0 THEN
            mon_flag := TRUE;    (* a set the C cannot solve: its NOT_IN_CODE, read as before *)
            mon_sensor := mon_xi;
            mon_rule := RULE_WIRES_EXCHANGED;
        ELSE
            (* each one's last reading plus the change the others predict (MON_XCH_CHANGE) *)
            mon_xsi := mon_last[mon_xi];
            mon_xsk := mon_last[mon_xk];
            FOR mk := 0 TO MON_N - 1 DO
                mon_x := mon_xr[mk] - mon_last[mk];
                mon_xsi := mon_xsi + MON_XCH_CHANGE[mon_xi, mon_xk, mk] * mon_x;
                mon_xsk := mon_xsk + MON_XCH_CHANGE[mon_xk, mon_xi, mk] * mon_x;
            END_FOR;
            mon_xsi := mon_xr[mon_xk] - mon_xsi;
            mon_xsk := mon_xr[mon_xi] - mon_xsk;
            mon_ev := mon_xsi < mon_xlim[mon_xi] AND mon_xsi > -mon_xlim[mon_xi];
            IF mon_ev AND mon_xsk < mon_xlim[mon_xk] AND mon_xsk > -mon_xlim[mon_xk] THEN
                mk := mon_perm[mon_xi];
                mon_perm[mon_xi] := mon_perm[mon_xk];
                mon_perm[mon_xk] := mk;
                mon_x := mon_xr[mon_xi];
                mon_xr[mon_xi] := mon_xr[mon_xk];
                mon_xr[mon_xk] := mon_x;
                mon_sensor := mon_xi;
                mon_rule := RULE_WIRES_EXCHANGED;
            END_IF;
        END_IF;
    END_IF;
    FOR mk := 0 TO MON_N - 1 DO
        u[MON_INPUT[mk]] := mon_xr[mk];
    END_FOR;
END_IF;
mon_jumps := 0;
FOR mk := 0 TO MON_N - 1 DO
    j := MON_INPUT[mk];
    mon_x := u[j];
    mon_big[mk] := FALSE;
    mon_bent[mk] := 0.0;
    (* (st98) its readings standing still, in range: the C's run (its reading its last one) *)
    mon_still := mon_x >= MON_LO_LIM[mk] AND mon_x <= MON_HI_LIM[mk] AND mon_x = mon_last[mk];
    IF first OR NOT mon_still THEN
        mon_frun[mk] := 0;
    ELSIF mon_frun[mk] < 2147483646 THEN
        mon_frun[mk] := mon_frun[mk] + 1;
    END_IF;
    (* its run past the C's run rules (MON_DITHER_RUN: a reading that dithers; MON_BLIND_RUN: *)
    (* one no other predicts), whatever the block's field; (st98b) mon_fnew: its first sample *)
    (* (st99: "no other predicts" in the set in force, mon_fset) *)
    mon_still := MON_JUDGED[mk] = 1;
    IF mon_fset >= 0 THEN
        mon_still := MON_OUT_SCALE[mon_fset, mk] > 0.0;
    END_IF;
    mon_ev := mon_frun[mk] > MON_DITHER_RUN[mk];
    mon_ev := mon_ev OR (NOT mon_still AND mon_frun[mk] > MON_BLIND_RUN[mk]);
    mon_fnew[mk] := mon_ev AND NOT mon_fpast[mk];
    mon_fpast[mk] := mon_ev OR (mon_fpast[mk] AND mon_frun[mk] > 0);    (* (st99) or named *)
    IF NOT (mon_x >= -U_LIMIT[j] AND mon_x <= U_LIMIT[j]) THEN
        IF mon_rule = 0 THEN
            mon_sensor := mk;
            mon_rule := RULE_DROPOUT;
            IF first THEN
                mon_rule := RULE_MISSING_FIRST;
            END_IF;
        END_IF;
        mon_gone := TRUE;
    ELSIF mon_x < MON_LO_LIM[mk] OR mon_x > MON_HI_LIM[mk] THEN
        mon_gone := TRUE;
    ELSIF NOT first AND (mk <> mon_late OR mon_lback) THEN    (* (st109) a late one's return: no step *)
        mon_lim := MON_JUMP_LIM[mk] * mon_gap[mk];
        IF mon_span > mon_gap[mk] THEN
            mon_lim := MON_JUMP_LIM[mk] * mon_span;
        END_IF;
        mon_step[mk] := mon_x - mon_last[mk];
        IF mon_step[mk] > mon_lim OR mon_step[mk] < -mon_lim THEN
            mon_big[mk] := TRUE;
        ELSIF mon_has_step[mk] AND mon_gap[mk] = 1.0 AND mon_span = 1.0 THEN
            (* (st94) a step of a sensor no other predicts off its own last one (the C's BENT) *)
            mon_off := mon_step[mk] - mon_last_step[mk];
            IF mon_off > MON_BEND_LIM[mk] OR mon_off < -MON_BEND_LIM[mk] THEN
                IF mon_rerefd[mk] THEN
                    mon_big[mk] := TRUE;    (* a second since it was in: a jump, as the C *)
                ELSE
                    (* re-referenced by the departure and kept in, its step its last one *)
                    mon_shift[j] := mon_shift[j] + mon_off;
                    mon_bent[mk] := mon_off;
                    mon_step[mk] := mon_step[mk] - mon_off;
                    mon_rerefd[mk] := TRUE;
                    IF mon_rule <> RULE_BENT AND mon_rule <> RULE_WIRES_EXCHANGED THEN
                        (* the C judges it before a dropout, after the exchange *)
                        mon_sensor := mk;
                        mon_rule := RULE_BENT;
                    END_IF;
                END_IF;
            END_IF;
        END_IF;
        IF mon_big[mk] THEN
            mon_jumps := mon_jumps + 1;
        END_IF;
    END_IF;
END_FOR;
(* then a reading beyond the range (read as missing, as the C), then the jumps *)
FOR mk := 0 TO MON_N - 1 DO
    j := MON_INPUT[mk];
    mon_x := u[j];
    IF mon_rule = 0 AND mon_x >= -U_LIMIT[j] AND mon_x <= U_LIMIT[j] THEN
        IF mon_x < MON_LO_LIM[mk] OR mon_x > MON_HI_LIM[mk] THEN
            mon_sensor := mk;
            mon_rule := RULE_OFF_RANGE;
            IF first THEN
                mon_rule := RULE_RANGE;
            END_IF;
        END_IF;
    END_IF;
END_FOR;
(* (st94) two sensors jumping in one sample, every reading there and in range, not at the *)
(* sample after the reference: held where the C takes each jumper in out (the first, the *)
(* second: MON_PAIR_FIRST / MON_PAIR_SECOND), each out tried first as a spike's return *)
mon_pair := FALSE;
mon_outs := 0;
IF MON_PAIR_JUMP AND mon_jumps = 2 AND NOT mon_gone AND mon_count <> 1 THEN
    mon_pair := TRUE;
    FOR mk := 0 TO MON_N - 1 DO
        IF mon_big[mk] AND mon_out[mk] THEN
            mon_outs := mon_outs + 1;
        END_IF;
    END_FOR;
    mon_place := mon_outs;
    FOR mk := 0 TO MON_N - 1 DO
        IF mon_big[mk] AND NOT mon_out[mk] THEN
            IF mon_place = 0 THEN
                mon_pair := mon_pair AND MON_PAIR_FIRST[mk] = 1;
            ELSE
                mon_pair := mon_pair AND mon_place = 1 AND MON_PAIR_SECOND[mk] = 1;
            END_IF;
            mon_place := mon_place + 1;
        END_IF;
    END_FOR;
END_IF;
(* (st102) a lone jump of the sensor the block holds out by its BLIND_OUT, one the C holds out *)
(* for a jump (MON_JUMP_HELD): the C's silent re-reference of one out (its whole step, no *)
(* spike's return of one no other predicts), no fault; the hold and the judgement go on *)
(* (st107) with a second held beside it (mon_jset): that one's lone jump alone is silent *)
(* (mon_jbeside), the C's re-reference of one out, counted in its hold below *)
mon_hjump := mon_held >= 0 AND mon_held_set >= 0 AND NOT mon_lost AND mon_jumps = 1;
mon_jbeside := FALSE;
IF mon_hjump AND mon_jset >= 0 AND mon_jheld >= 0 THEN
    mon_jbeside := mon_big[mon_jheld] AND NOT mon_gone AND mon_rule = 0;
    mon_hjump := FALSE;
ELSIF mon_hjump THEN
    mon_hjump := MON_JUMP_HELD[mon_held] = 1 AND mon_big[mon_held] AND NOT mon_gone AND mon_rule = 0;
END_IF;
(* (st111) the C's set whole before this row as far as the block knows: nothing flagged, held *)
(* or followed late, no reading beyond its range, the others' last prediction known *)
mon_whole := MON_STEP_JUDGE AND mon_other_known AND NOT mon_lost AND mon_held < 0 AND mon_jheld < 0;
mon_whole := mon_whole AND mon_late < 0 AND NOT mon_rfirst AND NOT mon_rlater AND mon_count <> 1;
mon_whole := mon_whole AND NOT mon_gone AND (mon_rule = 0 OR mon_rule = RULE_BENT);
(* the spikes' returns first (named first, as the C re-admits them before it excludes) *)
FOR mk := 0 TO MON_N - 1 DO
    j := MON_INPUT[mk];
    mon_spike[mk] := FALSE;
    mon_back := FALSE;
    IF mon_big[mk] AND mon_out[mk] AND NOT mon_hjump AND NOT mon_jbeside THEN
        mon_back := mon_jumps = 1 OR (mon_pair AND mon_outs = 2);
    END_IF;
    IF mon_back THEN
        (* back within its jump limit of its reference before the jump: a spike's end, *)
        (* the jump undone (the C's SPIKE: the fault is over, not a new one) *)
        mon_x := mon_shift[j] + mon_step[mk];
        mon_back := mon_x <= MON_JUMP_LIM[mk] AND mon_x >= -MON_JUMP_LIM[mk];
    END_IF;
    IF mon_back THEN
        mon_spike[mk] := TRUE;
        mon_shift[j] := 0.0;
        mon_out[mk] := FALSE;
        mon_rerefd[mk] := FALSE;
        IF mon_rule = 0 THEN
            mon_sensor := mk;
            mon_rule := RULE_SPIKE;
        END_IF;
    END_IF;
END_FOR;
FOR mk := 0 TO MON_N - 1 DO
    j := MON_INPUT[mk];
    IF mon_big[mk] AND NOT mon_spike[mk] THEN
        (* re-referenced by its whole step: the model reads it on from its last reading *)
        IF mon_hjump AND mon_jn = 0 THEN
            mon_jshift0 := mon_shift[j];    (* (st102) the C's ref0: before its first jump *)
        END_IF;
        mon_off := mon_step[mk];
        IF mon_jumps = 1 AND NOT mon_hjump AND NOT mon_jbeside AND MON_JUDGED[mk] = 1 THEN
            (* (st111) a lone jump of one the others predict: the C re-references one it holds *)
            (* out (MON_STEP_HELD) by its step less the change they predict for it since the *)
            (* last row (d - e does not read its own d), and none other; where the block cannot *)
            (* tell that change, or the C does not re-reference, mon_unsure to the campaign's end *)
            IF mon_whole AND MON_STEP_HELD[mk] = 1 THEN
                mon_x := 0.0;
                FOR mj := 0 TO MON_N - 1 DO
                    mi := MON_INPUT[mj];
                    mon_x := mon_x + MON_SELF[mk, mj] * (u[mi] - mon_base[mj] - mon_shift[mi]);
                END_FOR;
                mon_lim := u[j] - mon_base[mk] - mon_shift[j];
                mon_off := mon_step[mk] - (mon_lim - (mon_lim - mon_x) * MON_SCALE[mk] - mon_other[mk]);
            ELSE
                mon_junsure := TRUE;
            END_IF;
        END_IF;
        mon_shift[j] := mon_shift[j] + mon_off;
        mon_back := mon_pair AND mon_out[mk];  (* a pair's out already: no new fault, as the C *)
        mon_back := mon_back OR mon_hjump OR mon_jbeside;    (* (st102) the held one's: the C's, silent *)
        mon_out[mk] := TRUE;
        mon_rerefd[mk] := TRUE;
        IF NOT mon_back AND mon_jumps < MON_COMMON_MIN THEN
            mon_flag := TRUE;
        END_IF;
        IF mon_rule = 0 AND NOT mon_back THEN
            mon_sensor := mk;
            IF mon_pair THEN
                mon_rule := RULE_JUMP;
            ELSIF mon_jumps >= MON_COMMON_MIN THEN
                mon_rule := RULE_COMMON_STEP;
            ELSIF mon_jumps > 1 THEN
                mon_rule := RULE_COMMON;
            ELSIF mon_count = 1 THEN
                mon_rule := RULE_GLITCH;
            ELSE
                mon_rule := RULE_JUMP;
            END_IF;
        END_IF;
    END_IF;
END_FOR;
(* a fault: a reading not read, or a jump not a common step nor a spike's return (BENT, *)
(* re-referenced and kept in, is named by mon_rule and not flagged, as a common step) *)
mon_flag := mon_flag OR mon_gone;
(* (st94b) the self-prediction error stepped past the alarm band (the C's STEP_OUT), judged *)
(* while the field is whole: any exclusion since the campaign's first sample ends it, but *)
(* (st95b) one sensor out alone by the block's own STEP_OUT, followed to the C's BACK *)
(* (st101) the block's own JUMP of one sensor no other predicts, its field whole before it *)
(* (none held): out in the C as here (MON_JUMP_HELD), the field computed on through the hold *)
(* and not judged (mon_jheld), to the C's BACK below; (st105) its BLIND_OUT judgement paused *)
(* or stopped too (the C holds it alone where it took none out): a pause stops at the hold *)
(* (st107) or beside the BLIND_OUT the block holds (not jumped while held, none else held), *)
(* one the C holds out with it as its second (MON_OUT_JUMP_HELD): both held, neither judged, *)
(* each to its own BACK as the C's *)
IF MON_STEP_JUDGE AND NOT mon_lost AND mon_rule = RULE_JUMP AND mon_jumps = 1 AND NOT mon_gone THEN
    mon_go := MON_JUMP_HELD[mon_sensor] = 1 AND mon_held < 0;
    IF mon_held >= 0 AND mon_held_set >= 0 AND mon_jheld < 0 AND mon_jn = 0 THEN
        mon_jbeside := MON_OUT_JUMP_HELD[mon_held_set, mon_sensor] = 1;
        mon_go := mon_jbeside;
    END_IF;
    IF mon_go THEN
        mon_jset := -1;
        IF mon_jbeside THEN
            mon_jset := MON_OUT_SET[mon_sensor];
        END_IF;
        mon_jheld := mon_sensor;
        mon_jn := 0;
        mon_jshift0 := mon_shift[MON_INPUT[mon_sensor]] - mon_step[mon_sensor];
        mon_jlast := mon_last[mon_sensor] - mon_base[mon_sensor] - mon_jshift0;
        mon_jdwell := MON_WINDOW;    (* the C's wait: the window, doubled per drift exclusion *)
        FOR mr := 2 TO mon_field_outs[mon_sensor] DO
            IF mr <= MON_MAX_BACKOFF + 1 THEN
                mon_jdwell := mon_jdwell * 2;
            END_IF;
        END_FOR;
    END_IF;
END_IF;
IF mon_hjump THEN
    mon_jn := mon_jn + 1;    (* (st102) its jumps in the hold, undone at its BACK as the C's *)
    mon_sage[mon_held] := 0;    (* its reference moved: the C's age 1 on this row *)
ELSIF (mon_gone OR mon_jumps > 0) AND NOT mon_jbeside THEN
    (* (st111b) a jump after the block's own mon_lost (its value from the row before) of one *)
    (* the others predict: the C re-references it by its step less the others' change, which *)
    (* the block cannot compute here, the block by its whole step: apart to the campaign's end *)
    (* (st112) but not the return of one whose lone jump, the set whole before it, ended the *)
    (* judgement within a window, nothing else since, where the C's spike test (its prediction *)
    (* by the others, every other in, within MON_READMIT of its band) passes: the C's reference *)
    (* put back as the block's (0), the set whole again *)
    FOR mk := 0 TO MON_N - 1 DO
        mon_go := mon_sj = mk AND mon_spike[mk] AND mon_jumps = 1 AND NOT mon_gone AND mon_late < 0;
        mon_go := mon_go AND mon_rule = RULE_SPIKE AND mon_sensor = mk AND mon_sj_age < MON_WINDOW;
        IF mon_go THEN
            mon_x := 0.0;
            FOR mj := 0 TO MON_N - 1 DO
                mi := MON_INPUT[mj];
                mon_x := mon_x + MON_SPIKE_FIELD[mk, mj] * (u[mi] - mon_base[mj] - mon_rshift[mj]);
            END_FOR;
            mon_x := u[MON_INPUT[mk]] - mon_base[mk] - mon_x;
            IF mon_x < 0.0 THEN
                mon_x := -mon_x;
            END_IF;
            mon_go := mon_x < MON_READMIT * MON_WARN[mk] * 0.999999;    (* a margin: never on a tie *)
        END_IF;
        IF mon_lost AND mon_big[mk] AND MON_JUMP_HELD[mk] = 0 AND NOT mon_go THEN
            mon_rjump := TRUE;
        END_IF;
    END_FOR;
    mon_sj := -1;
    IF NOT mon_lost AND mon_whole AND mon_jumps = 1 AND mon_rule = RULE_JUMP AND NOT mon_junsure THEN
        (* this jump ends the judgement: the C holds it out, re-referenced as here (st111) *)
        mk := mon_sensor;
        IF MON_SPIKE_OK[mk] = 1 AND MON_STEP_HELD[mk] = 1 AND mon_rshift[mk] = 0.0 THEN
            mon_sj := mk;
            mon_sj_age := 0;
        END_IF;
    END_IF;
    mon_lost := TRUE;
END_IF;
mon_was := mon_held;
mon_run := 0;
IF mon_held >= 0 THEN
    (* its readings standing still: the C's run (no return while it runs), a freeze past the *)
    (* shorter of its freeze runs not followed *)
    IF u[MON_INPUT[mon_held]] = mon_last[mon_held] THEN
        mon_run := mon_run_was + 1;
    END_IF;
    mon_run_was := mon_run;
    (* anything else while it is out the block does not follow (a rule named) ends its *)
    (* judgement, as before st95b; (st106b) not a run of one out by BLIND_OUT: the C keeps *)
    (* it out, its fallback set served, and lets it back only once its reading moves *)
    IF (mon_rule <> 0 AND NOT mon_jbeside) OR (mon_run >= MON_FREEZE_RUN[mon_held] AND mon_held_set < 0) THEN
        mon_lost := TRUE;
    END_IF;
    IF mon_lost THEN
        mon_held := -1;
    END_IF;
END_IF;
IF MON_STEP_JUDGE AND mon_lost AND mon_rule = 0 THEN
    (* (st98b) after the block's own earlier flag: the run rules alone (the field's rule needs *)
    (* the set the C judges, not the block's), named once a run, the first sensor past them *)
    (* that the block does not hold re-referenced out *)
    FOR mk := 0 TO MON_N - 1 DO
        IF mon_fnew[mk] AND NOT mon_out[mk] AND mon_rule = 0 THEN
            mon_flag := TRUE;
            mon_sensor := mk;
            mon_rule := RULE_BLIND;
            IF MON_FREEZE_HELD[mk] = 1 THEN
                mon_rule := RULE_FREEZE;
            END_IF;
        END_IF;
    END_FOR;
END_IF;
(* (st101) the jumped sensor held: its own jump or return starts the C's calm again; anything *)
(* else named or flagged is not followed (lost as before) *)
IF mon_jheld >= 0 THEN
    IF mon_big[mon_jheld] AND mon_jumps = 1 AND NOT mon_gone THEN
        mon_jcalm := 0;
        mon_jn := mon_jn + 1;
        mon_sage[mon_jheld] := 0;    (* its reference moved: the C's age 1 on this row *)
    ELSIF mon_flag OR (mon_rule <> 0 AND mon_rule <> RULE_BENT) THEN
        mon_jheld := -1;
    ELSIF mon_jcalm < 2147483646 THEN
        mon_jcalm := mon_jcalm + 1;
    END_IF;
END_IF;
mon_efresh := FALSE;
IF MON_STEP_JUDGE AND (NOT mon_lost OR mon_jheld >= 0) THEN
    mon_efresh := TRUE;
    FOR mk := 0 TO MON_N - 1 DO
        j := MON_INPUT[mk];
        mon_d[mk] := u[j] - mon_base[mk] - mon_shift[j];
        (* (st96b) the C tests its level shift before the sample's BENT: on the reading *)
        (* before it *)
        mon_settle_ring[mon_spos, mk] := mon_d[mk] + mon_bent[mk];
        IF mon_since[mk] < MON_WINDOW THEN
            mon_since[mk] := mon_since[mk] + 1;
        END_IF;
        mon_go := mon_span = 1.0 AND mon_gap[mk] = 1.0;    (* no gap *)
        mon_go := mon_go AND mk <> mon_jheld;    (* (st101) out for its jump: not in the C *)
        mon_go := mon_go AND (mk <> mon_held OR mon_jn = 0 OR mon_jset >= 0);    (* (st102) nor jumped out *)
        IF MON_SETTLES[mk] = 1 AND mon_sage[mk] >= 2 * MON_WINDOW - 1 AND mon_go THEN
            (* (st96) the C's level shift (SETTLED): the window ending here parted from the *)
            (* one before by MON_SETTLE_LIM and moved past MON_SETTLE_STEADY x their spread *)
            (* (settled.level_shift), on one reference for 2 w - 1 samples, no gap *)
<<WINDOWS_PARTED>>
            IF mon_x > MON_SETTLE_LIM[mk] THEN
                (* each window's median, then its readings' median deviation from it *)
                FOR mw := 0 TO 1 DO
                    FOR mq := 0 TO 1 DO
                        FOR mi := 0 TO MON_WINDOW - 1 DO
                            mr := mon_spos - mi - mw * MON_WINDOW;
                            IF mr < 0 THEN
                                mr := mr + 2 * MON_WINDOW;
                            END_IF;
                            mon_sort[mi] := mon_settle_ring[mr, mk];
                            IF mq = 1 THEN
                                mon_sort[mi] := mon_sort[mi] - mon_med[mw];
                                IF mon_sort[mi] < 0.0 THEN
                                    mon_sort[mi] := -mon_sort[mi];
                                END_IF;
                            END_IF;
                        END_FOR;
                        FOR ma := 1 TO MON_WINDOW - 1 DO
                            FOR mi := 0 TO MON_WINDOW - 1 - ma DO
                                IF mon_sort[mi] > mon_sort[mi + 1] THEN
                                    mon_x := mon_sort[mi];
                                    mon_sort[mi] := mon_sort[mi + 1];
                                    mon_sort[mi + 1] := mon_x;
                                END_IF;
                            END_FOR;
                        END_FOR;
                        mon_x := (mon_sort[MON_MID_LO] + mon_sort[MON_MID_HI]) / 2.0;
                        IF mq = 0 THEN
                            mon_med[mw] := mon_x;
                        ELSE
                            mon_mad[mw] := mon_x;
                        END_IF;
                    END_FOR;
                END_FOR;
                mon_x := mon_med[0] - mon_med[1];
                IF mon_x < 0.0 THEN
                    mon_x := -mon_x;
                END_IF;
                mon_lim := mon_mad[0];
                IF mon_mad[1] > mon_lim THEN
                    mon_lim := mon_mad[1];
                END_IF;
                IF mon_x > MON_SETTLE_STEADY * mon_lim THEN
                    (* (st96b) re-referenced by the windows' median difference, kept in, as *)
                    (* the C: its window of readings shifted (the C's hist), its errors *)
                    (* stored before it not (mon_sback, mon_since: its err rows) *)
                    mon_off := mon_med[0] - mon_med[1];
                    mon_shift[j] := mon_shift[j] + mon_off;
                    mon_d[mk] := mon_d[mk] - mon_off;
                    FOR mr := 0 TO MON_WINDOW - 1 DO
                        mon_ring[mr, mk] := mon_ring[mr, mk] - mon_off;
                    END_FOR;
                    FOR mi := 1 TO MON_WINDOW - 1 DO    (* and the ring's last w - 1 rows *)
                        mr := mon_spos - mi;
                        IF mr < 0 THEN
                            mr := mr + 2 * MON_WINDOW;
                        END_IF;
                        mon_settle_ring[mr, mk] := mon_settle_ring[mr, mk] - mon_off;
                    END_FOR;
                    mon_sback[mk] := mon_off;
                    mon_since[mk] := 1;
                    IF mon_rule = 0 OR mon_rule = RULE_BENT THEN    (* the C's first event *)
                        mon_sensor := mk;
                        mon_rule := RULE_SETTLED;
                    END_IF;
                END_IF;
            END_IF;
        END_IF;
        (* the ring's row as the C keeps it (after its BENT and SETTLED), the reference's age *)
        (* (1 where its BENT moved it: the C's SETTLED moves it before the age is taken) *)
        mon_settle_ring[mon_spos, mk] := mon_d[mk];
        IF mon_bent[mk] <> 0.0 THEN
            mon_sage[mk] := 1;
        ELSIF mon_sage[mk] < 2 * MON_WINDOW THEN
            mon_sage[mk] := mon_sage[mk] + 1;
        END_IF;
        mon_ring[mon_pos, mk] := mon_d[mk];    (* (st95b) the C's window of readings *)
    END_FOR;
    mon_pos := mon_pos + 1;
    IF mon_pos >= MON_WINDOW THEN
        mon_pos := 0;
    END_IF;
    mon_spos := mon_spos + 1;
    IF mon_spos >= 2 * MON_WINDOW THEN
        mon_spos := 0;
    END_IF;
    mon_best := -1.0;
    mon_culprit := -1;
    FOR mk := 0 TO MON_N - 1 DO
        mon_x := 0.0;
        FOR mj := 0 TO MON_N - 1 DO
            mon_x := mon_x + MON_SELF[mk, mj] * mon_d[mj];
        END_FOR;
        mon_e[mk] := (mon_d[mk] - mon_x) * MON_SCALE[mk];
        IF mon_e_known AND MON_JUDGED[mk] = 1 AND mon_held < 0 AND mon_jheld < 0 THEN
            mon_off := mon_e[mk] - mon_prev_e[mk];
            IF mon_off < 0.0 THEN
                mon_off := -mon_off;
            END_IF;
            IF mon_off >= MON_ALARM[mk] AND (mon_e[mk] >= MON_ALARM[mk] OR mon_e[mk] <= -MON_ALARM[mk]) THEN
                (* the culprit: the largest change times sqrt(1 - h), the first of equals *)
                IF mon_off * MON_ROOT[mk] > mon_best THEN
                    mon_best := mon_off * MON_ROOT[mk];
                    mon_culprit := mk;
                END_IF;
            END_IF;
        END_IF;
        (* (st95b) its error with every sensor in, also while one is out: the C's last errors *)
        (* once it is back *)
        mon_prev_e[mk] := mon_e[mk];
        mon_other[mk] := mon_d[mk] - mon_e[mk];    (* (st111) the C's prev_other, its set whole *)
    END_FOR;
    mon_e_known := TRUE;
    (* (st98) the C's freeze with every sensor in, none held out: a reading standing still past *)
    (* its run (MON_BLIND_RUN of one no other predicts, MON_DITHER_RUN of one whose reading *)
    (* dithers), or, of one the others predict, MON_SEEN_RUN samples while their prediction *)
    (* of it moved by its warning band since the run began; the first frozen named; (st99) *)
    (* also of one in while a BLIND_OUT is held, by the set without it (mon_fset) *)
    mon_froze := -1;
    FOR mk := 0 TO MON_N - 1 DO
        mon_x := mon_d[mk] - mon_e[mk];    (* the others' prediction of it (MON_JUDGED) *)
        mon_ev := MON_JUDGED[mk] = 1;
        mon_lim := MON_WARN[mk];
        IF mon_fset >= 0 THEN
            mon_x := 0.0;
            FOR mj := 0 TO MON_N - 1 DO
                mon_x := mon_x + MON_OUT_SELF[mon_fset, mk, mj] * mon_d[mj];
            END_FOR;
            mon_x := mon_d[mk] - (mon_d[mk] - mon_x) * MON_OUT_SCALE[mon_fset, mk];
            mon_ev := MON_OUT_SCALE[mon_fset, mk] > 0.0;
            mon_lim := MON_OUT_WARN[mon_fset, mk];
        END_IF;
        IF mon_frun[mk] = 1 THEN
            mon_fpred[mk] := mon_x;
        END_IF;
        mon_go := mon_froze < 0 AND mon_jheld < 0;    (* (st101) none judged while one is held *)
        IF mon_frun[mk] > 0 AND (mon_was < 0 OR mon_fset >= 0) AND mk <> mon_was AND mon_go THEN
            mon_off := mon_x - mon_fpred[mk];
            IF mon_off < 0.0 THEN
                mon_off := -mon_off;
            END_IF;
            mon_ev := mon_ev AND mon_off >= mon_lim;
            mon_ev := mon_fpast[mk] OR (mon_ev AND mon_frun[mk] >= MON_SEEN_RUN[mk]);
            IF mon_ev THEN
                mon_froze := mk;
                mon_fpast[mk] := TRUE;    (* (st99) named once a run: not by its run again *)
            END_IF;
        END_IF;
    END_FOR;
    IF mon_froze >= 0 THEN
        (* the C names its freeze before a stepped error: the frozen one is the culprit, out *)
        (* in the C (rebuilt, or held at its last reading, the frozen one), not followed *)
        mon_culprit := mon_froze;
    END_IF;
    mon_take := -1;
    mon_take_set := -1;
    IF mon_culprit >= 0 THEN
        (* out in the C (rebuilt by the POD, or flagged where it does not hold it out) *)
        mon_flag := TRUE;
        mon_lost := TRUE;
        IF mon_rule = 0 THEN
            mon_sensor := mon_culprit;
            mon_rule := RULE_BLIND;
            IF mon_froze >= 0 AND mon_fset >= 0 THEN
                (* (st99) the second out beside the BLIND_OUT held: held where the C has the *)
                (* set of the two (MON_OUT_FREEZE_HELD), else the C's SECOND *)
                mon_rule := RULE_SECOND;
                IF MON_OUT_FREEZE_HELD[mon_fset, mon_culprit] = 1 THEN
                    mon_rule := RULE_FREEZE;
                END_IF;
            ELSIF mon_froze >= 0 AND MON_FREEZE_HELD[mon_culprit] = 1 THEN
                mon_rule := RULE_FREEZE;
            ELSIF mon_froze < 0 AND MON_STEP_HELD[mon_culprit] = 1 THEN
                mon_rule := RULE_STEP_OUT;
                IF MON_FOLLOW_BACK THEN
                    mon_lost := FALSE;    (* (st95b) out alone, followed to its BACK *)
                    mon_take := mon_culprit;
                END_IF;
            END_IF;
        END_IF;
    END_IF;
    (* (st96) the C's drift judgement with every sensor in, where its last MON_CONFIRM errors *)
    (* reach the band (MON_FIELD_BAND): a sensor no other predicts that explains them out *)
    (* (BLIND_OUT); a judgement the block cannot follow ends this one (not the stepped one) *)
    mon_judge := MON_BLIND_JUDGE AND NOT mon_blind_lost AND mon_was < 0 AND mon_culprit < 0;
    mon_judge := mon_judge AND mon_jheld < 0;
    mon_judge := mon_judge AND mon_count + 1 >= MON_CONFIRM;
    mon_reach := FALSE;
    mon_field_warned := 0;
    mon_zbest := -1.0;
    FOR mb := -1 TO MON_BLINDS DO
        (* -1: every sensor in; 0 .. MON_BLINDS - 1: each candidate out; MON_BLINDS: the one out *)
        mon_set := mb;
        mon_go := mon_judge;
        IF mb = MON_BLINDS THEN
            IF mon_reach AND mon_take_set < 0 AND mon_field_warned > MON_FOLLOW_OTHERS THEN
                (* (st100) new_state_others + 1 at their warning band: whatever its culprit, *)
                (* the C's _others vetoes it or it declares a new thermal state; nothing out, *)
                (* no DRIFT_OUT: paused to a calm window (the C's end of a new state) *)
                mon_pause := TRUE;
            ELSIF (mon_reach AND mon_take_set < 0) OR (mon_pause AND (mon_reach OR NOT mon_judge)) THEN
                (* the C's lone fault, veto or new state: not here; (st100) in the pause any *)
                (* other reach (the C, not in a new state, may take one out) or a sensor out *)
                mon_blind_lost := TRUE;
                mon_pause := FALSE;
                (* (st97d) said, once, with its row: the block silent from here is not "healthy" *)
                mon_stop := TRUE;
                mon_stop_row := mon_count + 1;
            ELSIF mon_take_set >= 0 THEN
                mon_flag := TRUE;
                mon_lost := mon_rule <> 0;
                IF mon_rule = 0 THEN
                    mon_sensor := MON_BLIND[mon_take_set];
                    mon_rule := RULE_BLIND_OUT;
                    mon_take := mon_sensor;
                END_IF;
            END_IF;
            IF mon_pause THEN
                (* (st100) calm: no judged sensor at its warning band (the C's _follow_field: *)
                (* every sensor in, mon_min over MON_CONFIRM rows), MON_WINDOW rows in a row *)
                mon_quiet := mon_quiet + 1;
                IF mon_field_warned > 0 THEN
                    mon_quiet := 0;
                END_IF;
                IF mon_quiet >= MON_WINDOW THEN
                    mon_pause := FALSE;    (* the C judges from the next row: so the block *)
                    mon_quiet := 0;
                END_IF;
            END_IF;
            IF mon_take >= 0 AND NOT mon_lost THEN
                (* (st95b) out alone, as a drift exclusion is: its wait the window doubled at *)
                (* each exclusion of it by judgement (at most MON_MAX_BACKOFF times) *)
                mon_held := mon_take;
                mon_held_set := mon_take_set;
                mon_jn := 0;    (* (st102) its jumps while held, and its last reading in (the C's last) *)
                mon_jlast := mon_last[mon_take] - mon_base[mon_take] - mon_shift[MON_INPUT[mon_take]];
                mon_hlast := mon_jlast;
                mon_calm := 0;
                mon_hsince := mon_count;    (* (st107c) the C's since: its exclusion's row *)
                mon_run_was := 0;
                mon_dwell := MON_WINDOW;
                FOR mr := 1 TO mon_field_outs[mon_take] DO
                    IF mr <= MON_MAX_BACKOFF THEN
                        mon_dwell := mon_dwell * 2;
                    END_IF;
                END_FOR;
                mon_field_outs[mon_take] := mon_field_outs[mon_take] + 1;
            END_IF;
            mon_set := mon_held_set;
            (* (st107) not with a second held: the C judges the set without both *)
            mon_go := mon_held >= 0 AND mon_held_set >= 0 AND NOT mon_lost AND mon_jheld < 0;
        ELSIF mb >= 0 THEN
            mon_go := mon_go AND mon_reach AND mon_z[MON_BLIND[mb]] > mon_zbest;
        END_IF;
        IF mon_go THEN
            (* each evidence sensor's smallest |error| in the set over the last MON_CONFIRM *)
            (* rows, and each residual's sum (the C's err window under the set's operator) *)
            FOR mk := 0 TO MON_N - 1 DO
                mon_min[mk] := -1.0;
                mon_r[mk] := 0.0;
            END_FOR;
            FOR mi := 1 TO MON_CONFIRM DO
                mr := mon_pos - mi;
                IF mr < 0 THEN
                    mr := mr + MON_WINDOW;
                END_IF;
                FOR mk := 0 TO MON_N - 1 DO
                    mon_x := 0.0;
                    mon_undo := 0.0;
                    FOR mj := 0 TO MON_N - 1 DO
                        mon_off := mon_ring[mr, mj];
                        IF mi > mon_since[mj] THEN
                            mon_off := mon_off + mon_sback[mj];    (* as read, before SETTLED *)
                        END_IF;
                        IF mon_set < 0 THEN
                            mon_x := mon_x + MON_SELF[mk, mj] * mon_ring[mr, mj];
                            mon_undo := mon_undo + MON_SELF[mk, mj] * mon_off;
                        ELSE
                            mon_x := mon_x + MON_OUT_SELF[mon_set, mk, mj] * mon_ring[mr, mj];
                            mon_undo := mon_undo + MON_OUT_SELF[mon_set, mk, mj] * mon_off;
                        END_IF;
                    END_FOR;
                    mon_x := mon_ring[mr, mk] - mon_x;
                    mon_r[mk] := mon_r[mk] + mon_x;
                    IF mb < 0 OR mb = MON_BLINDS THEN
                        (* (st96b) the C's stored errors (its _judge), not its window: a row *)
                        (* from before a SETTLED on the reference it was read on *)
                        mon_x := mon_ring[mr, mk] - mon_undo;
                        IF mi > mon_since[mk] THEN
                            mon_x := mon_x + mon_sback[mk];
                        END_IF;
                    END_IF;
                    IF mon_set < 0 THEN
                        mon_off := mon_x * MON_SCALE[mk];
                        mon_ev := MON_JUDGING[mk] = 1;
                    ELSE
                        mon_off := mon_x * MON_OUT_SCALE[mon_set, mk];
                        mon_ev := MON_OUT_JUDGING[mon_set, mk] = 1;
                        IF mi = 1 THEN
                            mon_eu[mk] := mon_off;
                        END_IF;
                    END_IF;
                    IF mon_off < 0.0 THEN
                        mon_off := -mon_off;
                    END_IF;
                    IF mon_ev AND (mon_min[mk] < 0.0 OR mon_off < mon_min[mk]) THEN
                        mon_min[mk] := mon_off;
                    END_IF;
                END_FOR;
            END_FOR;
            mon_ok := TRUE;
            mon_warned := 0;
            FOR mk := 0 TO MON_N - 1 DO
                IF mb < 0 THEN
                    (* the C's _judge (the band its last errors all reach), _explaining's z; *)
                    (* (st100) and the judged at their warning band, every sensor in *)
                    IF MON_JUDGING[mk] = 1 AND mon_min[mk] >= MON_WARN[mk] THEN
                        mon_field_warned := mon_field_warned + 1;
                    END_IF;
                    mon_over[mk] := MON_JUDGING[mk] = 1 AND mon_min[mk] >= MON_FIELD_BAND[mk];
                    IF mon_over[mk] THEN
                        mon_reach := TRUE;
                    END_IF;
                    mon_x := mon_r[mk] / MON_CONFIRM;
                    IF mon_x < 0.0 THEN
                        mon_x := -mon_x;
                    END_IF;
                    mon_z[mk] := mon_x / MON_Z_ROOT[mk];
                    IF MON_JUDGING[mk] = 1 AND mon_z[mk] > mon_zbest THEN
                        mon_zbest := mon_z[mk];
                    END_IF;
                ELSIF mb < MON_BLINDS THEN
                    (* _explaining: with it out each sensor beyond the band still judged, and *)
                    (* every judged one within the band on a row at least *)
                    IF mon_over[mk] AND MON_OUT_JUDGING[mb, mk] = 0 THEN
                        mon_ok := FALSE;
                    END_IF;
                    IF MON_OUT_JUDGING[mb, mk] = 1 AND mon_min[mk] >= MON_FIELD_BAND[mk] THEN
                        mon_ok := FALSE;
                    END_IF;
                ELSE
                    (* one held out by its BLIND_OUT: where the C, judging the set without it, *)
                    (* may take a second out or let it back another way (a stepped error, *)
                    (* _stepped; (st99) a sensor at its alarm band, _drift's with one out by *)
                    (* the field; MON_FOLLOW_OTHERS at their warning band, _follow_field), no more *)
                    (* (st107c) the C's _follow_field lets it back for the field only within *)
                    (* MON_WINDOW rows of its exclusion (its since); later it keeps it out *)
                    IF MON_OUT_JUDGING[mon_set, mk] = 1 AND mon_min[mk] >= MON_OUT_WARN[mon_set, mk] THEN
                        mon_warned := mon_warned + 1;
                        IF mon_min[mk] >= MON_OUT_ALARM[mon_set, mk] THEN
                            mon_ok := FALSE;
                        END_IF;
                        IF mon_warned >= MON_FOLLOW_OTHERS AND mon_count - mon_hsince <= MON_WINDOW THEN
                            mon_ok := FALSE;
                        END_IF;
                    END_IF;
                    mon_x := mon_eu[mk] - mon_prev_eu[mk];
                    IF mon_x < 0.0 THEN
                        mon_x := -mon_x;
                    END_IF;
                    mon_off := mon_eu[mk];
                    IF mon_off < 0.0 THEN
                        mon_off := -mon_off;
                    END_IF;
                    IF mon_was >= 0 AND MON_OUT_SCALE[mon_set, mk] > 0.0 THEN
                        IF mon_x >= MON_OUT_ALARM[mon_set, mk] AND mon_off >= MON_OUT_ALARM[mon_set, mk] THEN
                            mon_ok := FALSE;
                        END_IF;
                    END_IF;
                    mon_prev_eu[mk] := mon_eu[mk];
                END_IF;
            END_FOR;
            IF mb >= 0 AND mb < MON_BLINDS AND mon_ok THEN
                mon_zbest := mon_z[MON_BLIND[mb]];
                mon_take_set := mb;
            ELSIF mb = MON_BLINDS AND NOT mon_ok THEN
                mon_lost := TRUE;
                mon_held := -1;
            END_IF;
        END_IF;
    END_FOR;
    IF mon_was >= 0 AND mon_held >= 0 AND NOT mon_lost THEN
        (* (st95b) the C's BACK of the one out: calm for its wait, a full window counted, and *)
        (* on every row of the window, with every sensor in, its error within MON_BACK_BAND *)
        (* (st96: one out by BLIND_OUT, every judged sensor's within its warning band) *)
        mon_calm := mon_calm + 1;
        IF mon_big[mon_was] THEN
            mon_calm := 0;    (* (st102) its silent jump: the C's calm from it *)
        END_IF;
        IF mon_calm >= mon_dwell AND mon_count + 1 >= MON_WINDOW AND mon_run = 0 THEN
            mon_ok := TRUE;
            (* (st107) a second held beside it and not due back on this row: the C's set *)
            (* without that one (its operator, its warning band), as its _pass_once_back *)
            mon_bset := -1;
            IF mon_jset >= 0 AND mon_jheld >= 0 THEN
                mon_bset := mon_jset;
                IF mon_jcalm >= mon_jdwell AND u[MON_INPUT[mon_jheld]] <> mon_last[mon_jheld] THEN
                    mon_bset := -1;    (* both due: judged together, every sensor in *)
                END_IF;
            END_IF;
            FOR mr := 0 TO MON_WINDOW - 1 DO
                FOR mk := 0 TO MON_N - 1 DO
                    mon_ev := mk = mon_was;
                    mon_lim := MON_BACK_BAND[mk];
                    IF mon_held_set >= 0 THEN
                        mon_ev := MON_SCALE[mk] > 0.0;
                        mon_lim := MON_WARN[mk];
                    END_IF;
                    IF mon_bset >= 0 THEN
                        mon_ev := MON_OUT_SCALE[mon_bset, mk] > 0.0;
                        mon_lim := MON_OUT_WARN[mon_bset, mk];
                    END_IF;
                    IF mon_ev THEN
                        mon_x := 0.0;
                        FOR mj := 0 TO MON_N - 1 DO
                            IF mon_bset >= 0 THEN
                                mon_x := mon_x + MON_OUT_SELF[mon_bset, mk, mj] * mon_ring[mr, mj];
                            ELSE
                                mon_x := mon_x + MON_SELF[mk, mj] * mon_ring[mr, mj];
                            END_IF;
                        END_FOR;
                        mon_off := (mon_ring[mr, mk] - mon_x) * MON_SCALE[mk];
                        IF mon_bset >= 0 THEN
                            mon_off := (mon_ring[mr, mk] - mon_x) * MON_OUT_SCALE[mon_bset, mk];
                        END_IF;
                        IF mon_off < 0.0 THEN
                            mon_off := -mon_off;
                        END_IF;
                        IF mon_off >= mon_lim THEN
                            mon_ok := FALSE;
                        END_IF;
                    END_IF;
                END_FOR;
            END_FOR;
            IF mon_ok THEN
                mon_held := -1;
                mon_lost := mon_jheld >= 0;    (* (st107) the second held alone: st101's hold *)
                IF mon_jn > 0 AND mon_jset < 0 THEN
                    mon_jk := mon_was;    (* (st102) jumped while held: the C's _undone below *)
                END_IF;
            END_IF;
        END_IF;
    END_IF;
END_IF;
(* (st101) the C's BACK of the jumped sensor: calm for its wait, a full window counted, its *)
(* reading moving (one no other predicts passes); the block judging on from the next row *)
IF mon_jheld >= 0 AND mon_jcalm >= mon_jdwell AND mon_count + 1 >= MON_WINDOW THEN
    IF u[MON_INPUT[mon_jheld]] <> mon_last[mon_jheld] THEN
        mon_jk := mon_jheld;
        mon_lost := FALSE;
        mon_jheld := -1;
    END_IF;
END_IF;
(* the C's _undone at that BACK, or (st102) at the BACK of a BLIND_OUT that jumped while held: *)
(* its jumps undone where it jumped more than once, or where its reading on the reference *)
(* before them is nearer its last one in *)
IF mon_jk >= 0 THEN
    mk := mon_jk;
    j := MON_INPUT[mk];
    mon_off := mon_shift[j] - mon_jshift0;
    mon_x := mon_d[mk] + mon_off - mon_jlast;
    mon_lim := mon_d[mk] - mon_jlast;
    IF mon_jn > 1 OR (mon_off <> 0.0 AND mon_x * mon_x < mon_lim * mon_lim) THEN
        mon_sage[mk] := 1;    (* the C's reference moved back on this row *)
        mon_shift[j] := mon_jshift0;
        mon_d[mk] := mon_d[mk] + mon_off;
        FOR mr := 0 TO MON_WINDOW - 1 DO
            mon_ring[mr, mk] := mon_ring[mr, mk] + mon_off;
        END_FOR;
        FOR mr := 0 TO 2 * MON_WINDOW - 1 DO
            mon_settle_ring[mr, mk] := mon_settle_ring[mr, mk] + mon_off;
        END_FOR;
        mon_out[mk] := FALSE;    (* its re-reference gone; else kept: a return is a spike's *)
        mon_rerefd[mk] := FALSE;
        FOR mi := 0 TO MON_N - 1 DO    (* the errors the next row steps from, as the C's *)
            mon_x := 0.0;
            FOR mj := 0 TO MON_N - 1 DO
                mon_x := mon_x + MON_SELF[mi, mj] * mon_d[mj];
            END_FOR;
            mon_prev_e[mi] := (mon_d[mi] - mon_x) * MON_SCALE[mi];
        END_FOR;
    END_IF;
END_IF;
(* (st107) the second one back (or lost): the held BLIND_OUT's own jump count and last reading *)
IF mon_jset >= 0 AND mon_jheld < 0 THEN
    mon_jset := -1;
    mon_jn := 0;
    mon_jlast := mon_hlast;
END_IF;
(* a return is stepped from the last reading, over the samples it spans *)
FOR mk := 0 TO MON_N - 1 DO
    j := MON_INPUT[mk];
    mon_x := u[j];
    mon_back := mon_x >= -U_LIMIT[j] AND mon_x <= U_LIMIT[j];
    (* (st94) its own step, the next one's to bend from: none over a gap, of a jump, of a *)
    (* sensor out, or a campaign's first sample (the C's last step) *)
    mon_has_step[mk] := NOT first AND mon_back AND mon_gap[mk] = 1.0 AND mon_span = 1.0;
    mon_has_step[mk] := mon_has_step[mk] AND NOT mon_big[mk] AND NOT mon_out[mk];
    (* (st95b) none of one out by a STEP_OUT, nor at its return (the C's last step) *)
    mon_has_step[mk] := mon_has_step[mk] AND mk <> mon_was AND mk <> mon_held;
    mon_has_step[mk] := mon_has_step[mk] AND mk <> mon_late;    (* (st109) out in the C, or back now *)
    mon_last_step[mk] := mon_step[mk];
    IF first OR (mon_back AND mon_x >= MON_LO_LIM[mk] AND mon_x <= MON_HI_LIM[mk]) THEN
        mon_last[mk] := mon_x;
        mon_gap[mk] := 1.0;
    ELSE
        mon_has_step[mk] := FALSE;
        IF mon_span > mon_gap[mk] THEN
            mon_gap[mk] := mon_span;
        END_IF;
        mon_gap[mk] := mon_gap[mk] + 1.0;
    END_IF;
END_FOR;
(* (st109) a reading beyond its range at the first sample, as the C (dep108, dep108f): one *)
(* alone of a sensor the others predict (MON_LATE_OK), read MON_FIRST_C + the others' *)
(* prediction of it (mon_lpred) while beyond, referenced late at its return (its d the *)
(* prediction), read so to the C's BACK; anything else gone or named meanwhile: not followed, *)
(* mon_rfirst (mon_unsure to the campaign's end, as st108d; so a first sample not taken) *)
IF reset THEN    (* not first: that holds through the refused rows to the first taken one *)
    mon_rfirst := FALSE;
END_IF;
IF first THEN
    mon_late := -1;
    mon_lgone := 0;
    FOR mk := 0 TO MON_N - 1 DO
        j := MON_INPUT[mk];
        IF NOT (u[j] >= -U_LIMIT[j] AND u[j] <= U_LIMIT[j]) THEN
            mon_lgone := mon_lgone + 2;
        ELSIF u[j] < MON_LO_LIM[mk] OR u[j] > MON_HI_LIM[mk] THEN
            mon_lgone := mon_lgone + 1;
            mon_late := mk;
        END_IF;
    END_FOR;
    IF mon_late >= 0 THEN
        IF mon_lgone > 1 OR MON_LATE_OK[mon_late] = 0 THEN
            mon_rfirst := TRUE;
            mon_late := -1;
        ELSE
            mon_base[mon_late] := MON_FIRST_C[mon_late];    (* the C's base: the stand-in *)
            mon_lback := FALSE;
        END_IF;
    END_IF;
ELSIF mon_late >= 0 THEN
    mon_ok := mon_jumps = 0 AND (mon_rule = 0 OR (mon_rule = RULE_OFF_RANGE AND mon_sensor = mon_late));
    FOR mk := 0 TO MON_N - 1 DO
        j := MON_INPUT[mk];
        mon_ev := NOT (u[j] >= -U_LIMIT[j] AND u[j] <= U_LIMIT[j]) OR mon_fnew[mk];
        IF mk <> mon_late OR mon_lback THEN
            mon_ev := mon_ev OR u[j] < MON_LO_LIM[mk] OR u[j] > MON_HI_LIM[mk];
        END_IF;
        IF mon_ev THEN
            mon_ok := FALSE;
        END_IF;
    END_FOR;
    IF NOT mon_ok THEN
        mon_rfirst := TRUE;
        mon_late := -1;
    END_IF;
END_IF;
(* (st109b) a reading beyond its range after the first sample (but the followed one's): the C *)
(* may read it on (a machine hotter than training, cmon80) and re-reference it at its return *)
(* (a jump), which the block does not follow: mon_rlater (mon_unsure to the campaign's end) *)
IF reset THEN
    mon_rlater := FALSE;
    mon_rjump := FALSE;
    mon_rbunsure := FALSE;
    mon_rbheld := FALSE;
    mon_rsettle := FALSE;
END_IF;
IF NOT first THEN
    FOR mk := 0 TO MON_N - 1 DO
        j := MON_INPUT[mk];
        mon_ev := u[j] >= -U_LIMIT[j] AND u[j] <= U_LIMIT[j] AND (mk <> mon_late OR mon_lback);
        IF mon_ev AND (u[j] < MON_LO_LIM[mk] OR u[j] > MON_HI_LIM[mk]) THEN
            mon_rlater := TRUE;
        END_IF;
    END_FOR;
END_IF;
IF mon_late >= 0 THEN
    mon_lpred := 0.0;
    FOR mk := 0 TO MON_N - 1 DO
        j := MON_INPUT[mk];
        IF mk <> mon_late THEN
            mon_lpred := mon_lpred + MON_LATE_FIELD[mon_late, mk] * (u[j] - mon_base[mk] - mon_shift[j]);
        END_IF;
    END_FOR;
    j := MON_INPUT[mon_late];
    IF NOT first AND NOT mon_lback AND u[j] >= MON_LO_LIM[mon_late] AND u[j] <= MON_HI_LIM[mon_late] THEN
        mon_lback := TRUE;    (* its return: referenced late, its d the prediction *)
        mon_lcalm := 0;
        mon_lpos := 0;
        mon_shift[j] := u[j] - mon_base[mon_late] - mon_lpred;
    ELSIF mon_lback AND mon_lcalm < 2147483646 THEN
        mon_lcalm := mon_lcalm + 1;
    END_IF;
END_IF;
IF mon_late >= 0 AND mon_lback THEN
    FOR mk := 0 TO MON_N - 1 DO    (* the C's window of readings since the return *)
        j := MON_INPUT[mk];
        mon_lring[mon_lpos, mk] := u[j] - mon_base[mk] - mon_shift[j];
    END_FOR;
    mon_lpos := mon_lpos + 1;
    IF mon_lpos >= MON_WINDOW THEN
        mon_lpos := 0;
    END_IF;
    (* the C's BACK: a window on, its reading moving, its error with every sensor in within *)
    (* its band on every row of the window *)
    IF mon_lcalm >= MON_WINDOW AND mon_frun[mon_late] = 0 AND mon_count + 1 >= MON_WINDOW THEN
        mon_ok := TRUE;
        FOR mr := 0 TO MON_WINDOW - 1 DO
            mon_x := mon_lring[mr, mon_late];
            FOR mj := 0 TO MON_N - 1 DO
                mon_x := mon_x - MON_SELF[mon_late, mj] * mon_lring[mr, mj];
            END_FOR;
            mon_x := mon_x * MON_SCALE[mon_late];
            IF NOT (mon_x < MON_BACK_BAND[mon_late] AND mon_x > -MON_BACK_BAND[mon_late]) THEN
                mon_ok := FALSE;
            END_IF;
        END_FOR;
        IF mon_ok THEN
            mon_late := -1;    (* back: read as measured on its late reference *)
        END_IF;
    END_IF;
END_IF;
(* (st111) mon_other is the C's last prediction where its set was whole through the row *)
mon_other_known := MON_STEP_JUDGE AND NOT mon_lost AND mon_held < 0 AND mon_jheld < 0 AND mon_late < 0;
(* (st108b) where the block no longer judges (its stop, or a flag that ends its judgement) *)
(* the C may take out a sensor the block reads (DRIFT_OUT, its partner, BLIND_OUT, STEP_OUT, *)
(* a jump's) and rebuild it: mon_unsure where the block flags or a judged sensor's error with *)
(* every sensor in reaches its warning band, and the C's first wait after (2 MON_WINDOW) *)
(* (st111b) after mon_lost the block judges nothing but the C judges on: the errors with every *)
(* sensor in still computed for the test below (a reading not measured or beyond its range at *)
(* its last value), else the C's later exclusions (DRIFT_OUT, STEP_OUT, ...) would go unflagged *)
IF MON_STEP_JUDGE AND mon_lost AND NOT mon_efresh THEN
    FOR mk := 0 TO MON_N - 1 DO
        j := MON_INPUT[mk];
        IF u[j] >= MON_LO_LIM[mk] AND u[j] <= MON_HI_LIM[mk] THEN
            mon_d[mk] := u[j] - mon_base[mk] - mon_shift[j];
        END_IF;
    END_FOR;
    FOR mk := 0 TO MON_N - 1 DO
        mon_x := 0.0;
        FOR mj := 0 TO MON_N - 1 DO
            mon_x := mon_x + MON_SELF[mk, mj] * mon_d[mj];
        END_FOR;
        mon_e[mk] := (mon_d[mk] - mon_x) * MON_SCALE[mk];
    END_FOR;
END_IF;
(* (st111c) and so does its level shift (SETTLED) of one no other predicts (a step under its *)
(* jump and bend limits): the C re-references it there, the block cannot tell by how much from *)
(* its own readings (the C's reference may differ): where its two windows part past *)
(* MON_SETTLE_LIM on one reference (the C's test without its steadiness test, so never on *)
(* fewer rows), mon_rsettle (mon_unsure to the campaign's end) *)
IF MON_STEP_JUDGE AND mon_lost AND NOT mon_efresh THEN
    FOR mk := 0 TO MON_N - 1 DO
        IF mon_shift[MON_INPUT[mk]] <> mon_rshift[mk] THEN
            mon_sage[mk] := 0;    (* re-referenced on this row: the C's age 1 *)
        END_IF;
        mon_settle_ring[mon_spos, mk] := mon_d[mk];
        mon_go := MON_SETTLES[mk] = 1 AND mon_sage[mk] >= 2 * MON_WINDOW - 1;
        IF mon_go AND mon_span = 1.0 AND mon_gap[mk] = 1.0 THEN
<<WINDOWS_PARTED>>
            IF mon_x > MON_SETTLE_LIM[mk] THEN
                mon_rsettle := TRUE;
            END_IF;
        END_IF;
        IF mon_sage[mk] < 2 * MON_WINDOW THEN
            mon_sage[mk] := mon_sage[mk] + 1;
        END_IF;
    END_FOR;
    mon_spos := mon_spos + 1;
    IF mon_spos >= 2 * MON_WINDOW THEN
        mon_spos := 0;
    END_IF;
END_IF;
IF MON_STEP_JUDGE THEN
    FOR mk := 0 TO MON_N - 1 DO
        mon_rshift[mk] := mon_shift[MON_INPUT[mk]];
    END_FOR;
END_IF;
mon_unsure := FALSE;
mon_rb := -1;
IF mon_stop_row > 0 OR mon_lost THEN
    IF mon_flag THEN
        mon_usince := 0;
    END_IF;
    FOR mk := 0 TO MON_N - 1 DO
        mon_x := mon_e[mk];
        IF mon_x < 0.0 THEN
            mon_x := -mon_x;
        END_IF;
        IF MON_JUDGED[mk] = 1 AND mon_x >= MON_WARN[mk] THEN
            mon_usince := 0;
        END_IF;
    END_FOR;
    (* (st112) anything after the jump but its return: the C's set not known at the return *)
    (* (st112b) where the C may hold it out still (no spike's return it takes), its set and *)
    (* hold no longer known: unsure to the campaign's end *)
    IF mon_sj >= 0 AND mon_sj_age > 0 AND (mon_flag OR mon_rule <> 0 OR mon_usince = 0) THEN
        mon_sj := -1;
    END_IF;
    IF mon_rbheld AND mon_sj <> mon_rbk THEN
        IF NOT (mon_rule = RULE_SPIKE AND mon_sensor = mon_rbk AND NOT mon_rjump) THEN
            mon_rbunsure := TRUE;
        ELSIF mon_usince > 0 AND mon_stop_row = 0 THEN
            (* (st112c) the spike's return the C takes, nothing at the band since its jump nor *)
            (* on this row: the C's set whole again, its window's errors the block's with every *)
            (* sensor in (recomputed at the re-admission), the hold followed: the wait ends *)
            mon_usince := 2 * MON_WINDOW + 1;
        END_IF;
        mon_rbheld := FALSE;
    END_IF;
    (* (st112b) the C holds that one out from its jump's row to its BACK: calm (rows since the *)
    (* jump) for its wait, a full window counted, its reading moving, and its error with every *)
    (* sensor in within MON_BACK_BAND on each row of the window (the C's _pass_once_back); *)
    (* a near tie, or its reading standing still to its freeze run, not followed: unsure *)
    IF mon_sj >= 0 AND mon_sj_age = 0 THEN
        mon_rbheld := TRUE;
        mon_rbk := mon_sj;
        mon_rbok := 0;
        mon_rbrun := 0;
        mon_rbdwell := MON_WINDOW;    (* doubled per drift exclusion, as st101's *)
        FOR mr := 2 TO mon_field_outs[mon_sj] DO
            IF mr <= MON_MAX_BACKOFF + 1 THEN
                mon_rbdwell := mon_rbdwell * 2;
            END_IF;
        END_FOR;
    ELSIF mon_sj >= 0 AND mon_rbheld THEN
        mk := mon_sj;
        mon_x := mon_e[mk];
        IF mon_x < 0.0 THEN
            mon_x := -mon_x;
        END_IF;
        IF mon_x < MON_BACK_BAND[mk] * 0.999999 THEN
            mon_rbok := mon_rbok + 1;
        ELSE
            mon_rbok := 0;
        END_IF;
        IF u[MON_INPUT[mk]] = mon_rbu THEN
            mon_rbrun := mon_rbrun + 1;    (* (the C's run: no BACK on this row) *)
        ELSE
            mon_rbrun := 0;
        END_IF;
        mon_go := mon_x >= MON_BACK_BAND[mk] * 0.999999 AND mon_x <= MON_BACK_BAND[mk] * 1.000001;
        IF (mon_rbrun > 0 AND mon_rbrun >= MON_FREEZE_RUN[mk]) OR mon_go THEN
            mon_rbunsure := TRUE;
            mon_rbheld := FALSE;
        ELSIF mon_sj_age >= mon_rbdwell AND mon_count + 1 >= MON_WINDOW AND mon_rbok >= MON_WINDOW THEN
            mon_rbheld := mon_rbrun > 0;    (* its BACK where its reading moved: measured from here *)
        END_IF;
    END_IF;
    IF mon_sj >= 0 THEN
        mon_rbu := u[MON_INPUT[mon_sj]];
    END_IF;
    IF mon_sj >= 0 AND mon_sj_age < 2147483646 THEN
        mon_sj_age := mon_sj_age + 1;
    END_IF;
    (* (st112b) held: the C feeds the model its rebuild from the others (the set without it, *)
    (* the C's order), as here *)
    IF mon_rbheld AND NOT mon_rjump AND NOT mon_rsettle THEN
        mon_rb := mon_rbk;
        mon_rbx := 0.0;
        FOR mj := 0 TO MON_N - 1 DO
            mi := MON_INPUT[mj];
            mon_rbx := mon_rbx + MON_SPIKE_FIELD[mon_rb, mj] * (u[mi] - mon_base[mj] - mon_shift[mi]);
        END_FOR;
    END_IF;
    mon_unsure := mon_usince <= 2 * MON_WINDOW AND mon_rb < 0;
    IF mon_usince < 2147483646 THEN
        mon_usince := mon_usince + 1;
    END_IF;
END_IF;
IF mon_held >= 0 AND mon_held_set < 0 AND NOT mon_lost THEN
    mon_unsure := TRUE;    (* a STEP_OUT it holds: the C rebuilds the sensor, the block reads it *)
END_IF;
IF mon_rfirst THEN
    mon_unsure := TRUE;    (* (st108d) the C's start from a reading out of range not followed (st109) *)
END_IF;
IF mon_rlater THEN
    mon_unsure := TRUE;    (* (st109b) the C may read a reading beyond its range on *)
END_IF;
IF mon_junsure THEN
    mon_unsure := TRUE;    (* (st111) a lone jump re-referenced otherwise than the C *)
END_IF;
IF mon_rjump THEN
    mon_unsure := TRUE;    (* (st111b) a jump after mon_lost, re-referenced not as the C *)
END_IF;
IF mon_rsettle THEN
    mon_unsure := TRUE;    (* (st111c) a level shift after mon_lost the C may re-reference *)
END_IF;
IF mon_rbunsure THEN
    mon_unsure := TRUE;    (* (st112b) the C's hold after a lone jump not followed *)
END_IF;
(* a campaign's sample count, held at DINT's top: never wraps back through 1 *)
IF mon_count < 2147483646 THEN
    mon_count := mon_count + 1;
END_IF;
IF has_time THEN
    mon_t_prev := time_s;
    mon_t_known := TRUE;
END_IF;
""".replace("<<WINDOWS_PARTED>>\n", _WINDOWS_PARTED)


def declarations(n_inputs: int, watch: dict, dims) -> str:
    """The block's monitor memory (``VAR``), sized by its inputs and monitored sensors."""
    n = len(watch.get("inputs", []))
    w = max(int(watch.get("window", 1)), 1)
    return VARS.format(nm=dims(n), n=dims(n_inputs), ring=dims(w, n), settle=dims(2 * w, n), w=dims(w))
