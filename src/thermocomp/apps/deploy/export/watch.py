"""The sensor monitor in the code (cmon76): the part of the served
:class:`~..surveillance.SensorMonitor` the C holds, as arrays and in numpy (pure core).

The served adaptive compensator judges every ``T_`` input before the model reads it
(docs/monitoring.md).  The code holds this slice of it, the same arithmetic:

* each sensor predicted from the other active ones by the POD (``M`` per active set: every
  sensor in, or one sensor ``j`` out, column ``j`` zero; ``lev`` its leverages), the error
  ``(d - M d) / (1 - h)`` of the referenced readings ``d`` kept over ``window`` samples, a band
  left when the last ``confirm`` are beyond it;
* a **jump** of one sensor (a one-sample step beyond ``jump_lim``, times the periods a gap in
  time spans): re-referenced by its step less its change as the others predict it, excluded;
* a **freeze** (its reading constant for ``seen_run`` samples while the others' prediction of
  it moved by its warning band; one no other predicts, or whose reading dithers over its
  resolution (mon97, ``dither_run``): longer than ``blind_run``): excluded;
* a **dropout** (cdrop77: a missing reading, NaN, an infinity or a value beyond its input's
  limit, after a campaign's first sample): excluded at that sample, its last reading kept as the
  one its return is stepped from (a jump limit times the samples it spans);
* (cmon80) a reading **beyond its range** (``lo_lim`` / ``hi_lim``) after a campaign's first
  sample, of one sensor while no other is out (or of the sensor out): read as missing, the
  sensor excluded as for a dropout (its re-admission band half its warning band, as served),
  its return stepped from its last reading; unless the others predict it beyond the same
  training edge (``lo_c`` / ``hi_c``) by more than its warning band and it reads nearer that
  prediction than half its distance from the edge (a machine hotter than training: read);
* (cmon80) a **common step**: at least ``common_min`` active sensors jumping in one sample
  (the median of their steps the common one), every active sensor whose step is within a
  factor ``common_spread`` of it re-referenced by its own step and kept in, where they are
  more than half the active ones read; a jump off it judged as before;
* (cmon82) a **drift**: every sensor in, a judged one beyond its band over the last
  ``confirm`` samples (no sensor no other predicts explaining them, the served
  ``_explaining``): the culprit (the largest ``|E|(1 - h)``, or the lone fault that explains the
  bands, the served ``_lone_fault``, mon84 only the likelier single fault: the largest
  ``|E| sqrt(1 - h)``, mon84b leaving every judged sensor judged; a culprit within its band,
  mon85, not by leaving the likelier single fault out of band in and unjudged) excluded where
  with it out every other judged sensor is within its warning band, fewer than
  ``new_state_others`` others are out of it, and (a culprit within its own band, or mon83
  beyond it by less than its readings' rounding moves its error, ``rounding``, the memory's
  error within that of the band) the excursion does not hover against the field's memory
  (``tau``, ``growth``: the served ``_excursion_hovers``); else nothing, as served (a veto).
  Its blind partner (``pairs``: the one judged sensor no other predicts once it is out, an
  operator per pair) goes out with it under the same veto.  Each waits ``window`` times 2 to
  the drift exclusions it had (``max_backoff`` at most) to return;
* while a sensor is out the model reads its POD reconstruction from the others, and it is
  re-admitted after a calm wait (a window; doubled per drift exclusion) whose leave-one-out
  errors stay within half its warning band (``READMIT``; one out for a dropout alone, or as a
  culprit within its band (mon85b), within its whole band, as served), the sensors due back
  judged together as served;
* (cmon82b) a **new thermal state** (``novel``), the served ``_declare``: where with the culprit
  (or its blind partner) out the others stay out of their warning band, or where within a
  window of a drift exclusion ``new_state_others`` other judged sensors leave it (the field
  followed: the sensor re-admitted at once, ``FOLLOWED``, its wait back to a window).  While it
  lasts no drift exclusion (the fault signatures still exclude), ``NOVEL`` in the flags and the
  guard's bound ``guard_lo_new`` / ``guard_hi_new`` (:mod:`.output`); it ends after a window of
  samples with every judged sensor within its band.  An export before it (no ``novel``) flags it.
* (cmon82c) a sensor no other predicts, every sensor in, **excluded as explaining** the judged
  sensors beyond the band (the served ``_explaining``): a drift exclusion (its wait doubled) that
  the model reads held at its last reading while in (``last``), re-admitted where every judged
  sensor of the set with it in is within its warning band over the window (``explains``), or at
  once where the field follows it; judged again after it, one beyond the alarm band flagged.  A
  jump of it or a reading beyond its range while it is out flagged ``BLIND``.  An export before
  it (no ``blind_out``) flags it.
* (cmon83) the **fallback model** (``fallback``: the served correction while such a sensor is
  out is the model fitted without it): its laws step beside the model's (:mod:`.fallbacks`,
  ``law_set``) and the code serves them while the sensor is out and enough are in to rebuild the
  field (:meth:`CodeMonitor.serving`, the served ``_fallen_back``; ``fallback_set``), the model's
  again once it is back; (cmon91) an arx_rf fallback's forest too, walked while its set is served.
  One the code cannot hold (a forest ramping on another clock, an lstm network of another shape,
  other inputs or derived inputs, a cascade of lags, a state times the inputs' rises), or an
  export before it (no ``fallback_set``), flags the campaign ``FALLBACK`` from the exclusion on.
* (mon88) a sensor out by the field's judgement whose return no sensor in trial predicts passes
  where a partner out, frozen by the rule for one no other predicts (constant longer than
  ``blind_run``), would predict it (``cleared``), as served (``Readmission._blind_for_frozen``).
  An export before it (no ``cleared``) keeps it out, as before.
* (mon105d) a sensor out for a freeze by its run alone (not where the field moved past its band
  while it held) is read at its held value instead of its stand-in while the rate fitted to its
  readings within ``tau`` before its run projects a drift, over at least the span fitted, within
  ``spread`` (the served ``_hold_until`` / ``_read_held``; the time the time rule's ``now``).  An
  export before it (no ``spread``) reads the stand-in, as before.  (dep106) Its ring of
  ``TREND_ROWS`` keeps one row per ``tau / (TREND_ROWS // 2)`` s (``frozen_hold.keeps``), each
  with its sample's number, so half of it spans ``tau`` at any logger (every row at 28.1 s or
  slower, as before).
* (freeze84) a sensor out for a **freeze alone** (no other detector fired on it since) is
  re-admitted once ``THAW`` readings in a row are off the value it held (``THAWED``), judged from
  there as an active one, as served (``Readmission._thawed``).  An export before it (no
  ``thawed``) flags it ``NO_THAW``.
* (cmon84) a sensor no other predicts, every other in, **out for a dropout or a freeze** (its
  missing reading after a campaign's first sample; its reading constant longer than
  ``blind_run``), as served: held at its last reading while in, its fallback model served while
  it is out, but, after a dropout, not once it reads again (the served ``_fallen_back``: its
  held reading the model's while it waits out its window), re-admitted after a calm window
  (no band judges it).  Not where too few would be left in to rebuild the field.  A jump of it
  while it is out is flagged ``BLIND`` as before (the served return may undo it).  An export
  before it (no ``blind_drop``) refuses the missing reading (``MISSING_BLIND``) and flags the
  freeze (``BLIND``).
* (cmon85) the operator of a set the code does not hold, **solved** (``solve``, ``basis``: the
  POD basis's ``modes`` columns; :meth:`CodeMonitor._solved`, the C's ``mon_operator``): a
  QR of ``Phi_a`` (qr103; a Cholesky of ``Phi_a^T Phi_a`` before), as the served
  ``pod.operator``.  With it the drift judgement goes on with a sensor out (its explaining,
  lone fault and veto sets solved), a second culprit (or a second sensor's freeze) out beside
  the first, as served; at most two out by these rules (a third flagged).  An export before it
  (no ``solve``) flags a drift with a sensor out (``DRIFT``) and a second sensor out
  (``SECOND``).
* (cmon86) a **stepped error** (``stepped``): a judged sensor's error stepping past its alarm band
  in one sample (the served ``_check_stepped``), each such sensor fired on; the culprit (the
  largest step times ``sqrt(1 - h)``) out as a drift exclusion is (its wait doubled, no field to
  follow it), the second beside one out where the set is solved.  An export before it (no
  ``stepped``) flags it (``STEPPED``).
* (cmon88) a **jump with one sensor out** (``second_jump``): a sensor the others predict,
  re-referenced by its step less its change as the others see it and out as the second where the
  set is solved, as served (``_instant``; its change judged by the set in before the sample's
  dropout or range exclusion: the served monitor reads a sample's instant faults together, then
  excludes).  An export before it (no ``second_jump``) flags it (``SECOND``).
* (cmon87) a sensor no other predicts, every other in, **out for a jump** (``blind_jump``, as
  cmon84's dropout: ``spikes``): re-referenced by its whole step (no prediction of its change),
  held at its last reading, its fallback's law set served while it is out, back after a calm
  window; a jump while it is out re-referenced too; on its return its jumps are undone as served
  (``Readmission._readmit``: several are noise or a spike, of one the reading nearer its held
  value is taken): the reference before its first jump (``ref0``) restored, its window shifted
  back.  An export before it (no ``blind_jump``) flags the jump (``BLIND``).
* (cmon89) an **instant fault as the second out** (``second_instant``): with one sensor out, the
  set of the two out solved and the field rebuilt without both (``min_active`` left in), a
  missing reading or a reading beyond its range of a sensor the others predict is excluded as
  the second (a dropout; a machine hotter than training judged by the others in), and the jump of
  a sensor no other predicts re-referenced by its whole step and out as the second, held at its
  last reading (cmon87's path), as served; the second out missing (or beyond its range) again is
  read as missing, as the first is.  An export before it (no ``second_instant``) refuses the
  missing reading (``MISSING_SECOND``) and flags the range (``RANGE``) and the jump (``SECOND``).
* (dep101) **several readings missing in one sample** (a pair's both, the drop): each out in
  the monitor's order where the code holds it in turn (:meth:`CodeMonitor._pair_held`, cmon93's
  trial of the out set, for a dropout): the first as a lone dropout, each after it by cmon89's
  path beside those out, the set's operator held (``pairs``) or solved; a dropout beside those
  out wherever it is (the field rebuilt or not: served's ``_instant`` takes every missing reading
  out, a returned one read where too few are in, dep99) and of one no other predicts too (held
  at its last reading).  (dep105) A dropout beside two or more out too, each in turn, and a
  pair's readings back read where too few are in (dep99), as served, where a sensor is left in;
  a set not solved: refused.  (dep105b) One that leaves none in too: served, no operator
  left, holds its last field (``_clean``), and so does the code (``clean``, the C's
  ``mon_clean``: the field the model read at the last sample, where nothing rebuilds a sensor),
  the readings back read and every sensor re-admitted together a window on, as served.
* (cmon89b) a sensor no other predicts, every other in, **out for a reading beyond its range**
  (``blind_range``: ``ranges``): read as missing, held at its last reading, back after a calm
  window only where its leak onto the others passes (:meth:`CodeMonitor._leak_passes`, the
  served ``Readmission._leak_passes``).  An export before it flags the reading (``BLIND``).
* (mon98b) ... **and as the second out** (``second_range``: with one sensor out, cmon89's path,
  the field rebuilt without both), as served: its return judged by its leak, the first's by its
  own rule in the same sample (a drifting ``T_amb`` out of range took the blind ``T_table``, out
  as explaining, back in served).  An export before it flags the reading (``RANGE``).
* (dep99) an **out set of any size** (``gone``, the C's ``mon_out_set`` / ``mon_nout``: the
  sensors out in the order they went, fixed arrays bounded by the sensor count; ``out`` /
  ``out2`` its first two places): several readings beyond range in one sample (a logger card in
  kelvin) each read as missing and out in the monitor's order, and one beside any number out,
  wherever the set's operator is had (solved), as served (``_instant``: no cap, no fallback below
  ``min_active``: :meth:`CodeMonitor.serving`); the model reads each by :meth:`CodeMonitor._rebuilt`'s
  rule (held at its last reading in, or rebuilt by the set's operator; where too few are in to
  rebuild the field, one out for a dropout alone whose reading is back and moved read, as served
  ``_rebuilds``), the set re-admitted together (:meth:`CodeMonitor._returning`).  The one- and
  two-out paths are its first places; the other rules still take at most two.
* (mon89; kept by bar91b) a sensor the others predict, out for jumps alone, whose next jump
  within a window brings its reading, on its reference before the first (``ref0``), within
  its re-admission band of the field: a **spike** (``spike``), in again at once with that
  reference put back (``SPIKE``), as served (``InstantFaults._spike_back``).  An export
  before it (no ``spike``) re-references the return as before.
* (cmon93) **two sensors jumping in one sample** (``pair_jump``), no common step, every reading
  there and in range, as served (``_spike_back``, ``_instant``): where both are out, each tried
  as a spike's return first; every jumper left re-referenced by its step less its change as the
  active sensors that did not jump predict it (one operator on that set, its whole step where
  its leverage with it reaches the limit), those in out in the monitor's order (the second by
  cmon88's rule).  A third out or a set the code cannot solve, or an export before it (no
  ``pair_jump``), flags ``COMMON`` as before.
* (quiet94c) the **warned air of a one-campaign training** (``warn_only``: the served
  ``drift_warn_only``): such a sensor's error is no evidence for the drift judgement (its
  trigger, culprit, lone fault, explaining sensor, veto and resolve sets, blind partner, hover,
  followed field, a new state's end: :meth:`CodeMonitor._judging`, as the served ``_judging``),
  its band still flagged and its fault signatures still excluding it.  An export before it (no
  ``warn_only``) judges it as any other sensor.

What else the served monitor does it flags, ``NOT_IN_CODE`` with the rule (:data:`REASONS`), and
goes on by its own rules: a reading beyond its range at a campaign's first sample (dep108: read as
served, the training's first reading ``first_c`` plus the rebuild, the campaign's A0 too, flagged
only where it reads within range again, the served late reference), of every sensor at once
(kelvin97: nothing to rebuild from, the model reads the last field) or beside those out
where the code does not hold it (its sample passes the monitor by, the state as it was, so that the
reading's return is no jump), several sensors jumping at once that are no common step (cmon93;
dep105c: two or more it cannot hold, a set not solved), a jump at the reference's next sample, a
stepped self-prediction error whose culprit would be a third out (or one it does not hold out), a
drift beyond the band that takes a third sensor out (cmon85: with one out, as served), of more than
one blind partner, a second culprit beyond the alarm band, a third for a jump, and a sensor no
other predicts out for any other rule (its range; cmon84: too few left to rebuild the field without
it), or with a fallback model the code does not hold.  A missing reading the code cannot rebuild
(at a campaign's first sample, beside those out where it cannot solve the set, of a sensor
it does not hold out; dep105b: no longer where it would leave no sensor in) is refused as
before (:meth:`CodeMonitor.refuses`: the sample is not read).  From such a row on the code may
part from the served model; the conformance pack cuts there (:func:`~.pack.conformance_pack`).
"""

from __future__ import annotations

import contextlib
import functools
import math
from dataclasses import dataclass, field

import numpy as np

from ..adaptive import GAP_PERIODS, AdaptiveCompensator
from ..surveillance.frozen_hold import held_until, push_row
from ..surveillance.settled import STEADY, advanced, level_shift_now
from ..surveillance.states import (
    ALARM,
    COMMON_MIN,
    COMMON_SPREAD,
    EXCURSION_GROWTH,
    EXCURSION_TAU_S,
    MAX_BACKOFF,
    READMIT,
    SPREAD_FACTOR,
    THAW,
    TREND_ROWS,
    WARNING,
)

# what the code's monitor reports per sample (bits of tc_state.mon_flags; REREFERENCED: a common
# step, cmon80; NOVEL: a new thermal state declared, cmon82b)
EXCLUDED, READMITTED, OUT, BAND, NOT_IN_CODE, REREFERENCED, NOVEL = 1, 2, 4, 8, 16, 32, 64
# (cflags100) the flag kinds as ``stream --flags`` prints them, one 0/1 column each (``mon_<kind>``)
FLAG_KINDS = (("excluded", EXCLUDED), ("readmitted", READMITTED), ("out", OUT), ("band", BAND),
              ("not_in_code", NOT_IN_CODE), ("rereferenced", REREFERENCED), ("new_state", NOVEL))
# the reason of a flagged event (tc_state.mon_rule): what the code did, then what it does not do
REASONS = ("", "jump: re-referenced and excluded", "freeze: excluded",
           "re-admitted: within half its warning band for a window (its whole band after a "
           "dropout, or out as a culprit within it)",
           "not in the code: a reading beyond its training range at a campaign's first sample, "
           "of every sensor at once, or beside those out where the code does not hold it",
           "not in the code: several sensors jumping in one sample (no common step)",
           "not in the code: a jump at the sample after the reference",
           "not in the code: a self-prediction error stepped past the alarm band",
           "not in the code: a drift beyond the band (with a sensor out, of one no other "
           "predicts, a new thermal state, a second culprit)",
           "not in the code: a second sensor out",
           "not in the code: a sensor no other predicts out (or too few left to rebuild it)",
           "dropout: no finite value, excluded",
           "not in the code: a missing reading at a campaign's first sample",
           "not in the code: a missing reading with another sensor out or missing",
           "not in the code: a missing reading of a sensor the code does not hold out",
           "not in the code: a missing reading of a sensor out for a freeze (its re-admission band)",
           "out of range: read as missing, excluded",
           "common step: re-referenced, kept in",
           "drift: its self-prediction error explains the others' bands, excluded",
           "re-admitted: the field followed its exclusion (a new thermal state)",
           "drift: no other sensor predicts it and its reading explains the others' bands, "
           "excluded, held at its last reading",
           "not in the code: the correction of the model fitted without a sensor no other "
           "predicts (of a kind the code does not hold), from its exclusion on (monitor.fallbacks)",
           "re-admitted: readings in a row off the value it held when frozen (out for it alone)",
           "not in the code: the return of a sensor out for a freeze on readings off the value it "
           "held (an export before freeze84)",
           "jump: its self-prediction error stepped past the alarm band, excluded",
           "re-admitted: a spike, its reading back with the field on its reference before the "
           "jump (the jump undone)",
           "step off its own: a sensor no other predicts re-referenced by its step less its last, "
           "kept in",
           "settled off its own: a sensor no other predicts whose last window lies wholly off the "
           "window before, re-referenced by their medians' difference, kept in",
           "wires exchanged: two sensors flagged in one sample, each reading where the others "
           "predict the other, read exchanged from here")
RULES = ("", "JUMP", "FREEZE", "BACK", "RANGE", "COMMON", "GLITCH", "STEPPED", "DRIFT", "SECOND",
         "BLIND", "DROPOUT", "MISSING_FIRST", "MISSING_SECOND", "MISSING_BLIND",
         "MISSING_FROZEN", "OFF_RANGE", "COMMON_STEP", "DRIFT_OUT",
         "FOLLOWED", "BLIND_OUT", "FALLBACK",
         "THAWED", "NO_THAW", "STEP_OUT", "SPIKE", "BENT",
         "SETTLED", "WIRES_EXCHANGED")   # their names in the C (TC_MON_JUMP ...)
(JUMP, FREEZE, BACK, RANGE, COMMON, GLITCH, STEPPED, DRIFT, SECOND, BLIND, DROPOUT, MISSING_FIRST,
 MISSING_SECOND, MISSING_BLIND, MISSING_FROZEN, OFF_RANGE, COMMON_STEP, DRIFT_OUT, FOLLOWED,
 BLIND_OUT, FALLBACK, THAWED, NO_THAW, STEP_OUT, SPIKE, BENT, SETTLED,
 WIRES_EXCHANGED) = range(1, len(RULES))


def flag_row(watch, names: list[str]) -> tuple:
    """What ``stream --flags`` prints after a sample's corrections, as the mirror ``watch`` (a
    :class:`CodeMonitor`) has it: one 0/1 per :data:`FLAG_KINDS`, then the names of the sensors
    out (``names``: the monitored ones) in the order they went out, joined by ``;``."""
    return (*(int(bool(watch.flags & bit)) for _, bit in FLAG_KINDS),
            ";".join(names[k] for k in watch.gone))


@dataclass
class MonitorArrays:
    """:class:`~.statespace.StateSpace`'s monitor (:func:`monitor_fields`; empty: none in the
    code, the C's only: the ST does not hold it)."""

    monitor: dict = field(default_factory=dict)


def monitor_fields(deployed, inputs: list) -> dict:
    """``{"monitor": arrays}`` of an adaptive compensator's sensor monitor (:data:`REASONS`'s
    slice; none where it has no adaptive monitor, or a monitored sensor is no input)."""
    mon = getattr(deployed, "monitor", None)
    if not isinstance(deployed, AdaptiveCompensator) or mon is None or not mon.adaptive:
        return {}
    if any(c not in inputs for c in mon.names):
        return {}
    n = len(mon.names)
    pairs = _pairs(mon)
    sets = [np.ones(n, bool)] + [np.arange(n) != j for j in range(n)]
    sets += [~np.isin(np.arange(n), pair) for pair in pairs]
    M, lev = [], []
    for active in sets:
        m, h = mon._operator(active)
        full = np.zeros((n, n))
        full[:, active] = m
        M.append(full.tolist())
        lev.append(h.tolist())
    falls = set(getattr(deployed, "fallbacks_", {}) or {})
    ported = [int(bool(mon._predictable[j]) and mon.names[j] not in falls
                  and n - 1 >= mon.min_active_) for j in range(n)]
    return {"monitor": {
        "inputs": [inputs.index(c) for c in mon.names], "M": M, "lev": lev,
        "max_leverage": float(mon.pod.max_leverage), "min_active": int(mon.min_active_),
        "warning": mon.warning_c.tolist(), "alarm": mon.alarm_c.tolist(),
        "window": mon.window, "confirm": mon.confirm,
        "exclude_level": int(mon.exclude_level), "jump_lim": mon._jump_lim.tolist(),
        "lo_lim": mon._lo_lim.tolist(), "hi_lim": mon._hi_lim.tolist(),
        # (dep108) the served stand-in of a reading beyond its range at a campaign's first sample
        "first_c": mon.first_c.tolist(), "late": 1,
        "lo_c": mon.lo_c.tolist(), "hi_c": mon.hi_c.tolist(),
        "common_min": COMMON_MIN, "common_spread": COMMON_SPREAD,
        "seen_run": mon._seen_run.tolist(), "blind_run": mon._blind_run.tolist(),
        # (mon97) a dithered reading frozen by its run alone (inf: by the field, as before)
        "dither_run": getattr(mon, "_dither_run", np.full(n, np.inf)).tolist(),
        "predictable": [int(p) for p in mon._predictable], "ported_out": ported,
        "period": float(deployed.period_s), "gap_periods": GAP_PERIODS, "readmit": READMIT,
        "drift": 1, "pairs": [list(p) for p in pairs], "new_state": int(mon.new_state),
        "new_state_others": int(mon.new_state_others), "max_backoff": MAX_BACKOFF,
        "tau": EXCURSION_TAU_S, "growth": EXCURSION_GROWTH, "novel": 1, "blind_out": 1, "thawed": 1,
        "blind_drop": 1, "solve": 1, "stepped": 1, "cleared": 1, "blind_jump": 1, "second_jump": 1,
        "second_instant": 1,
        "blind_range": 1,
        "second_range": 1,
        "spike": 1,
        "bent": 1, "bend_lim": mon._bend_lim.tolist(),
        "settled": int(getattr(mon, "_settles", False)),
        "settle_lim": getattr(mon, "_settle_lim", np.full(n, np.inf)).tolist(),
        "settle_steady": STEADY,
        "pair_jump": 1,
        "exchange": 1,
        # (quiet94c) the ambient of a one-campaign training: its drift warned, not acted on
        "warn_only": [int(w) for w in getattr(mon, "drift_warn_only", np.zeros(n, bool))],
        "modes": int(mon.pod.n_modes_),
        "basis": mon.pod.basis_[:, :int(mon.pod.n_modes_)].tolist(),
        "fallback": [int(c in falls) for c in mon.names],
        "rounding": np.broadcast_to(getattr(mon, "rounding_c", 0.0), (n,)).tolist(),
        # (mon105d) the stand-in's training spread: a frozen sensor's held value read within it
        "spread": (np.broadcast_to(mon.floor_c, (n,)) / SPREAD_FACTOR).tolist(),
        **_set_bands(mon)}}


def _set_bands(mon) -> dict:
    """(mon86) What scales a sensor's bands to the set it is judged in (the served
    ``_bands_of``): its floor, the training moment of the windowed snapshots and its windowed
    error's moment with every sensor in (0 where none: never scaled)."""
    if getattr(mon, "moment", None) is None:
        return {}
    return {"floor": mon.floor_c.tolist(), "moment": mon.moment.tolist(),
            "q_full": np.nan_to_num(mon._q_full, nan=0.0).tolist()}


def _pairs(mon) -> list[tuple[int, int]]:
    """(cmon82) The sets of two the code holds out: a sensor and the one judged sensor that no
    other predicts once it is out (its blind partner, a drift exclusion takes it out too)."""
    n = len(mon.names)
    every = mon._operator(np.ones(n, bool))[1] < mon.pod.max_leverage
    out = []
    for j in range(n):
        blind = every & (mon._operator(np.arange(n) != j)[1] >= mon.pod.max_leverage)
        blind[j] = False
        if blind.sum() == 1 and tuple(sorted((j, int(np.argmax(blind))))) not in out:
            out.append(tuple(sorted((j, int(np.argmax(blind))))))
    return out


def planted(ss, campaigns) -> dict[str, tuple]:
    """``{id: (campaign, what, the campaign it copies)}``: the first campaign of 8 rows or more
    with a fault planted on the first monitored sensor whose exclusion the code holds, from its
    middle row on: a jump of twice its step limit (where the reading stays within its range),
    a freeze (its reading held), a dropout (no reading for a quarter of the rows after the
    middle, then read again: cdrop77), a reading beyond its range for as many rows and a common
    step of every monitored sensor (twice the largest step limit, where the readings within
    their range stay so: cmon80), so that the conformance pack checks the code's monitor on
    every record (its expected corrections the served model's, its monitor acting; cut where it
    does what the code's does not).  None without a monitor in the code."""
    m = ss.monitor
    ported = [k for k, p in enumerate(m.get("ported_out", [])) if p]
    first = next((c for c, df in campaigns.items() if len(df) >= 8), None)
    if not ported or first is None:
        return {}
    k = ported[0]
    sensor, frame = ss.inputs[m["inputs"][k]], campaigns[first]
    half = len(frame) // 2
    out = {}
    jump = 2.0 * float(m["jump_lim"][k])
    if np.isfinite(jump) and (frame[sensor].iloc[half:] + jump <= m["hi_lim"][k]).all():
        df = frame.copy()
        df.loc[df.index[half:], sensor] += jump
        out[f"{first}.jump.{sensor}"] = (df, f"{sensor} {jump:+.4g} degC from row {half + 1} "
                                             "(a jump: twice its step limit)", first)
    df = frame.copy()
    df.loc[df.index[half:], sensor] = frame[sensor].iloc[half]
    out[f"{first}.freeze.{sensor}"] = (df, f"{sensor} held at its reading of row {half + 1} "
                                           "from there (a freeze)", first)
    # (cdrop77) a broken wire: no reading for a quarter of the rows after the middle, then back
    lost = max(1, (len(frame) - half) // 4)
    df = frame.copy()
    df.loc[df.index[half:half + lost], sensor] = np.nan
    out[f"{first}.dropout.{sensor}"] = (df, f"{sensor} missing (an empty cell) in rows {half + 1}-"
                                            f"{half + lost} (a dropout), read again after", first)
    # (cmon80) a reading beyond its range (its limit's margin again beyond it) for as many rows,
    # then back; and a common step of every monitored sensor (twice the largest step limit)
    far = float(m["hi_lim"][k]) + (float(m["hi_lim"][k]) - float(m.get("hi_c", m["hi_lim"])[k]) or 10.0)
    if np.isfinite(far) and abs(far) <= ss.limits[m["inputs"][k]]:
        df = frame.copy()
        df.loc[df.index[half:half + lost], sensor] = far
        out[f"{first}.range.{sensor}"] = (df, f"{sensor} reads {far:.4g} degC (beyond its range) in "
                                              f"rows {half + 1}-{half + lost}, read again after",
                                          first)
    names = [ss.inputs[i] for i in m["inputs"]]
    lims = np.asarray(m["jump_lim"], float)
    step = 2.0 * float(lims.max()) if len(names) >= m.get("common_min", np.inf) else np.nan
    after = frame[names].iloc[half:].to_numpy(float)
    lo, hi = np.asarray(m["lo_lim"], float), np.asarray(m["hi_lim"], float)
    inside = (after >= lo) & (after <= hi)       # (a reading beyond already, or none: as it is)
    for by in (step, -step):
        if np.isfinite(by) and (((after + by >= lo) & (after + by <= hi)) | ~inside).all():
            df = frame.copy()
            df.loc[df.index[half:], names] += by
            out[f"{first}.common.step"] = (df, f"every monitored sensor {by:+.4g} degC from row "
                                               f"{half + 1} (a common step: a logger's reference)",
                                           first)
            break
    return out


class CodeMonitor:
    """The code's monitor in numpy (module doc): :meth:`step` gives the inputs the model reads."""

    def __init__(self, arrays: dict):
        a = {k: np.asarray(v, float) for k, v in arrays.items()}
        n = len(arrays["inputs"])
        for k in ("lo_c", "hi_c"):        # (an export before cmon80: never a hotter machine)
            a.setdefault(k, np.full(n, np.nan))
        a.setdefault("common_min", np.float64(np.inf))     # (nor a common step)
        a.setdefault("common_spread", np.float64(COMMON_SPREAD))
        for k, v in (("drift", 0), ("new_state", 1), ("new_state_others", 2),
                     ("max_backoff", MAX_BACKOFF), ("tau", EXCURSION_TAU_S),
                     ("growth", EXCURSION_GROWTH),        # (an export before cmon82: flagged)
                     ("novel", 0),        # (before cmon82b: a new thermal state flagged)
                     ("blind_out", 0),    # (before cmon82c: a sensor no other predicts, flagged)
                     ("thawed", 0),       # (before freeze84: a freeze's return flagged)
                     ("blind_drop", 0),   # (before cmon84: its missing reading refused)
                     ("solve", 0),        # (before cmon85: only the operators it holds)
                     ("stepped", 0),      # (before cmon86: a stepped error flagged)
                     ("cleared", 0),      # (before mon88: no partner's freeze clears one)
                     ("blind_jump", 0),   # (before cmon87: a blind sensor's jump flagged)
                     ("second_jump", 0),   # (before cmon88: a jump with one out flagged)
                     ("second_instant", 0),   # (before cmon89: a dropout, ... flagged)
                     ("blind_range", 0),   # (before cmon89b: a blind sensor's range flagged)
                     ("second_range", 0),  # (before mon98b: ... with one out, flagged RANGE)
                     ("spike", 0),         # (before bar91b: a spike's return re-referenced)
                     ("bent", 0),          # (before step93: a step off its own read as heat)
                     ("settled", 0),       # (before jump94b: a blind level shift read as heat)
                     ("pair_jump", 0),     # (before cmon93: two jumping in one sample flagged)
                     ("exchange", 0)):     # (before wires100: two wires exchanged read as jumps)
            a.setdefault(k, np.float64(v))
        a.setdefault("bend_lim", np.full(n, np.inf))
        a.setdefault("late", np.float64(0))      # (before dep108: beyond range at the first, flagged)
        a.setdefault("first_c", np.zeros(n))
        a.setdefault("settle_lim", np.full(n, np.inf))
        a.setdefault("dither_run", np.full(n, np.inf))   # (before mon97: frozen by the field)
        a.setdefault("settle_steady", np.float64(0))   # (before settle95: a fast ramp settled)
        # (jump94b) the sensors no other predicts whose level shift two windows tell
        self.settles = np.flatnonzero(bool(a["settled"]) & np.isfinite(a["settle_lim"]))
        a.setdefault("rounding", np.zeros(n))    # (before mon83: no culprit held for rounding)
        a.setdefault("spread", np.zeros(n))      # (before mon105d: a frozen sensor's stand-in)
        # (before mon86: every set judged by the whole set's bands)
        a.setdefault("floor", np.zeros(n))
        a.setdefault("q_full", np.zeros(n))
        a["moment"] = np.asarray(arrays.get("moment", np.zeros((n, n))), float).reshape(n, n)
        self.pairs = [tuple(int(i) for i in p) for p in arrays.get("pairs", [])]
        self.idx = np.asarray(arrays["inputs"], int)
        self.M, self.lev = a["M"], a["lev"]
        self.n, self.window, self.confirm = len(self.idx), int(arrays["window"]), int(arrays["confirm"])
        self.a = a
        self.max_lev = float(arrays["max_leverage"])
        self.ported = np.asarray(arrays["ported_out"], bool)
        self.predictable = np.asarray(arrays["predictable"], bool)
        # (quiet94c) sensors whose drift is warned only (an export before it: none)
        self.warn_only = np.asarray(arrays.get("warn_only", [0] * n), bool)
        self.fallback = np.asarray(arrays.get("fallback", [0] * n), bool)
        # (cmon83) the law set of its fallback model in the code (0: none, an export before it)
        self.fallset = np.asarray(arrays.get("fallback_set", [0] * n), int)
        # (cmon84) one no other predicts that the code holds out for a dropout or a freeze (held
        # at its last reading), as served: enough left in to rebuild the field without it
        self.drops = bool(a["blind_drop"]) & ~self.predictable & (n - 1 >= a["min_active"])
        # (cmon87) ... and for a jump, its jumps undone on its return where the reading returned
        self.spikes = self.drops & bool(a["blind_jump"])
        # (cmon89b) ... and for a reading beyond its range, back only where its leak onto the
        # others passes (:meth:`_leak_passes`), as served
        self.ranges = self.drops & bool(a["blind_range"])
        # (mon98b) ... and as the second out where the first is out for explaining the others'
        # errors: served takes it out and the first back in one sample (dl9845's drifting T_amb)
        self.second_range = self.ranges & bool(a["second_range"])
        # (cmon85, cmon86) the rules that take a second sensor out beside one; (cmon88) a jump too
        self.seconds = (DRIFT_OUT, FREEZE, STEP_OUT) + ((JUMP,) if a["second_jump"] else ())
        # (cmon89) a dropout or a reading beyond its range as the second out, and the jump of
        # one no other predicts (held at its last reading)
        self.instant = bool(a["second_instant"])
        if self.instant:
            self.seconds += (DROPOUT, OFF_RANGE)
        # (cmon85) the POD basis (n x modes): any other set's operator solved at run time
        self.solve = bool(a["solve"]) and "basis" in arrays
        self.phi = np.asarray(arrays.get("basis", np.zeros((n, 0))), float).reshape(n, -1)
        # (ci98) the active masks by the sensors out, the active set's and the judgement's arrays
        # as last made (:meth:`_set`, :meth:`_judge`)
        self._actives, self._set_memo, self._judge_memo = {}, None, None
        self._errors_memo = None
        self.reset()

    def reset(self) -> None:
        n, w = self.n, self.window
        self.ref = self.base = self.ref0 = None    # (ref0: the reference before a first jump)
        # (dep99) the sensors out, in the order they went out (any number: a logger card beyond
        # range takes several at once, as served; cmon82: the second its blind partner, cmon85 or
        # a second out by drift); Mc / levc the active set's operator and leverages
        self.gone: list[int] = []
        self.late = np.zeros(n, bool)     # (dep108) beyond its range since the first sample
        self.Mc, self.levc = self.M[0], self.lev[0]
        # (mon86) the bands the active set is judged against
        self.warn, self.alarm = self.a["warning"], self.a["alarm"]
        self.hist, self.err = np.full((w, n), np.nan), np.full((w, n), np.nan)
        self.pos = self.count = 0
        self.prev, self.prev_e, self.prev_other = (np.full(n, np.nan) for _ in range(3))
        self.last_step = np.full(n, np.nan)      # (step93) each sensor's last one-sample change
        # (jump94b) its last 2 w - 1 readings on its current reference (oldest first), and the
        # samples since that reference moved
        self.settle, self.settle_age = np.full((2 * w - 1, n), np.nan), np.zeros(n, int)
        self.run, self.calm = np.zeros(n, int), np.zeros(n, int)
        self.run_pred = np.full(n, np.nan)
        # samples the next step spans (1 + its missing ones since its last reading, or a gap in
        # time), jumps re-referenced since it was last in, out for a dropout (cdrop77)
        self.gap, self.jumps = np.ones(n), np.zeros(n, int)
        self.dropped = np.zeros(n, bool)
        self.ranged = np.zeros(n, bool)     # (cmon89b) out for a reading beyond its range
        # (freeze84) out for a freeze alone, the reading it held, its readings in a row off it
        self.froze, self.held, self.off = np.zeros(n, bool), np.zeros(n), np.zeros(n, int)
        # (cmon82) out by a drift exclusion, its exclusions so, the calm samples it needs to
        # return (doubled at each), the sample count at its exclusion (-1: none)
        self.by_field, self.outs = np.zeros(n, bool), np.zeros(n, int)
        self.dwell, self.since = np.full(n, w), np.full(n, -1)
        # the field's memory of the served monitor's excursion rule (mon73): its age unknown
        # before a campaign's second sample
        self.slow, self.slow_known = np.zeros(n), False
        # (cmon82b) a new thermal state declared, the samples since a judged sensor was last out
        # of its warning band (the state ends after a window of them)
        self.novel, self.calm_field = False, 0
        # (cmon82c) out for explaining the others' errors (no other predicts it), and each
        # sensor's last reading while it was in (what the model reads of one no other predicts)
        self.explains, self.last = np.zeros(n, bool), np.zeros(n)
        # (dep105b) the field the model read at the last sample (referenced; 0 before the first,
        # as served's ``_clean``): what it reads where nothing is left to rebuild a sensor from
        self.clean = np.zeros(n)
        # (mon85b) out as a culprit within its own warning band: its whole band to return
        self.hid = np.zeros(n, bool)
        self.fell = False      # one whose fallback model the code lacks went out: flagged to the end
        self.read = np.ones(n, bool)     # (cmon84) the sample's monitored readings there
        self.perm = np.arange(n)         # (wires100) the monitored readings' order as read
        # (mon105d) the last TREND_ROWS referenced rows and their times (a ring), the sample's
        # time (the time rule's) and, per sensor out for a freeze, until when its held value is
        # read instead of its stand-in (the served _hold_until)
        self.past, self.past_t = np.full((TREND_ROWS, n), np.nan), np.full(TREND_ROWS, np.nan)
        self.past_pos, self.now = 0, np.nan
        # (dep106) the ring keeps a row a step of time (frozen_hold.keeps), each with its number
        self.past_n, self.rows = np.full(TREND_ROWS, np.nan), 0
        self.hold_to = np.full(n, -np.inf)
        self._clear()

    # the active set's operator, leverages, which sensors are judged and the errors' scale
    def _op_of(self, out: np.ndarray) -> int | None:
        """The index of the operator with the sensors ``out`` out (None: not in the code)."""
        k = tuple(int(i) for i in np.flatnonzero(out))
        if len(k) < 2:
            return k[0] + 1 if k else 0
        return self.n + 1 + self.pairs.index(k) if k in self.pairs else None

    def _operator(self, out: np.ndarray):
        """``(M, lev)`` of the set with the sensors ``out`` out: the one the code holds, else
        (cmon85) solved (:meth:`_solved`); None: neither."""
        s = self._op_of(out)
        if s is not None:
            return self.M[s], self.lev[s]
        return self._solved(~np.asarray(out, bool)) if self.solve else None

    def _solved(self, active: np.ndarray):
        """:func:`_solved_operator` of this basis and ``active`` (its arrays read-only)."""
        return _solved_operator(self.phi.tobytes(), self.phi.shape,
                                np.asarray(active, bool).tobytes())

    @property
    def out(self) -> int:
        """The first sensor out (-1: none): the out set's first place."""
        return self.gone[0] if self.gone else -1

    @property
    def out2(self) -> int:
        """The second sensor out (-1: fewer than two out): the out set's second place."""
        return self.gone[1] if len(self.gone) > 1 else -1

    def _active(self) -> np.ndarray:
        """The sensors in (a copy: callers mark a trial set in it)."""
        return self._in().copy()

    def _in(self) -> np.ndarray:
        """The sensors in, read only (ci101b: the step's own reads, no copy made)."""
        return self._active_of(tuple(sorted(self.gone)))

    def _active_of(self, gone: tuple) -> np.ndarray:
        """The sensors in with the sensors ``gone`` out, made once per set and read only (ci98:
        the mirror asks for it some twenty times a sample)."""
        got = self._actives.get(gone)
        if got is None:
            got = np.ones(self.n, bool)
            got[list(gone)] = False
            got.flags.writeable = False
            self._actives[gone] = got
        return got

    def _set(self):
        """``(M, active, observable, judged, scale)`` of the active set, read only: made again
        only where the sensors out or the operator changed (ci98: the same arrays, asked for
        seven times a sample)."""
        key, memo = tuple(sorted(self.gone)), self._set_memo
        if memo is not None and memo[0] == key and memo[1] is self.Mc and memo[2] is self.levc:
            return memo[3]
        lev = self.levc
        active = self._active_of(key)
        observable = lev < self.max_lev
        judged = active & observable
        scale = np.where(judged, 1.0 / np.maximum(1 - lev, 1e-12), 1.0)
        scale[active & ~observable] = np.nan
        for made in (observable, judged, scale):
            made.flags.writeable = False
        self._set_memo = (key, self.Mc, self.levc, (self.Mc, active, observable, judged, scale))
        return self._set_memo[3]

    def _judging(self) -> np.ndarray:
        """(quiet94c) The judged sensors whose error is the drift rule's evidence, as served
        (``SensorMonitor._judging``): a ``warn_only`` one's is warned (its band), not acted on."""
        return self._set()[3] & ~self.warn_only

    def _referenced_late(self, x, d, pred, e, back, pos):
        """(dep108f) The served late reference of the sensors ``back`` in range (beyond it since
        the first sample): each agrees with the field where the others predict it, else goes on
        from the value the model was given; ``d`` and the window's row ``pos`` changed in place."""
        e = e.copy()
        for j in np.flatnonzero(back):
            by_field = bool(self.predictable[j] and np.isfinite(pred[j]))
            d[j] = self.hist[pos, j] = pred[j] if by_field else self.clean[j]
            self.ref[j] = x[j] - d[j]
            e[j] = 0.0 if by_field else np.nan
        self.late &= ~back
        return self._errors(d)[0], e

    def _errors(self, d):
        """``(pred, error)`` of the sample ``d`` under the active set, read only (ci101b: kept
        for the last ``d`` and set; a sample asks again with neither changed)."""
        made, key, memo = self._set(), d.tobytes(), self._errors_memo
        if memo is not None and memo[0] is made and memo[1] == key:
            return memo[2]
        M, _, _, _, scale = made
        pred = M @ np.where(np.isfinite(d), d, 0.0)      # (a missing reading is out: column 0)
        e = (d - pred) * scale
        pred.flags.writeable = e.flags.writeable = False
        self._errors_memo = (made, key, (pred, e))
        return pred, e

    def _others_seen(self, d) -> np.ndarray:
        """Each judged sensor's reading as the other active ones predict it (NaN: not judged)."""
        _, e = self._errors(d)
        return np.where(self._set()[3], d - e, np.nan)

    def _recompute(self) -> None:
        """The window's errors under the new operator (an exclusion, a re-admission)."""
        self.Mc, self.levc = self._operator(~self._active())
        if not self._in().any():     # (dep105b) no operator, as served's (``M`` None): every
            # prediction and error NaN, where the solve of the empty set would read 0
            self.Mc = np.full((self.n, self.n), np.nan)
        M, _, _, _, scale = self._set()
        H = np.where(np.isfinite(self.hist), self.hist, 0.0)
        self.err = (self.hist - H @ M.T) * scale
        self._set_bands()

    def _set_bands(self) -> None:
        """(mon86) The active set's bands, a culprit out within its band counted in (served)."""
        # (dep105b) none in: the whole set's, as served (whatever culprit is counted in)
        self.warn, self.alarm = (self._bands(self._active() | self.hid) if self._in().any()
                                 else (self.a["warning"], self.a["alarm"]))

    def _bands(self, ins: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(mon86) ``(warning, alarm)`` of the set ``ins``, the served ``_bands_of``: each floor
        times ``sqrt(a' C a / q_full)`` (at least 1), ``a`` its row of ``(I - M) / (1 - h)``, never
        below the whole set's bands; those where the set's operator is not had."""
        a = self.a
        if ins.all() or not a["floor"].any() or (op := self._operator(~ins)) is None:
            return a["warning"], a["alarm"]
        M, lev = op
        g = np.ones(self.n)
        for k in np.flatnonzero(ins & (lev < self.max_lev)):
            row = np.where(ins, -M[k], 0.0)
            row[k] += 1.0
            row /= 1.0 - lev[k]
            q = float(row @ a["moment"] @ row)
            if a["q_full"][k] > 0 and q > a["q_full"][k]:
                g[k] = math.sqrt(q / a["q_full"][k])
        return (np.maximum(a["warning"], a["floor"] * g),
                np.maximum(a["alarm"], 2 * a["floor"] * g))

    def _level(self) -> np.ndarray:
        return self._judge()[0]

    def _rows(self) -> np.ndarray:
        """The window's rows of the last ``confirm`` samples, the last first."""
        return (self.pos - 1 - np.arange(min(self.count, self.confirm))) % self.window

    def _judge(self) -> tuple[np.ndarray, np.ndarray]:
        """``(level, error)``: the band the last ``confirm`` errors all exceed, their mean (read
        only; ci98: made again only where the window, its errors or the bands changed, the
        window's row written in place clearing it)."""
        memo = self._judge_memo
        if (memo is not None and memo[0] == (self.pos, self.count) and memo[1] is self.err
                and memo[2] is self.warn and memo[3] is self.alarm):
            return memo[4]
        rows = self._rows()
        last = self.err[rows]
        err = last.sum(axis=0) / max(len(rows), 1)
        if len(rows) < self.confirm:
            level = np.zeros(self.n, int)
        else:
            a = np.abs(last).min(axis=0)
            with np.errstate(invalid="ignore"):
                level = (a >= self.warn).astype(int) + (a >= self.alarm)
        level.flags.writeable = err.flags.writeable = False
        self._judge_memo = ((self.pos, self.count), self.err, self.warn, self.alarm, (level, err))
        return level, err

    def _clear(self) -> None:
        """The sample's flags, its first event and its first rule not in the code cleared (the
        C's ``mon_clear``): by :meth:`refuses` and :meth:`step`, whichever reads it first."""
        self.flags, self.sensor, self.rule, self.missed = 0, -1, 0, 0

    def _flag(self, bit: int, sensor: int, rule: int) -> None:
        self.flags |= bit
        if not self.rule:            # the sample's first event names its sensor and rule
            self.sensor, self.rule = sensor, rule
        if bit == NOT_IN_CODE and not self.missed:     # (and its first rule not in the code)
            self.missed = rule

    def _exclude(self, j: int, rule: int) -> bool:
        """``j`` out where the code holds it (one sensor out, others predict it, or cmon84 a
        dropout or a freeze of one no other predicts; cmon85 a second, for a drift, a freeze,
        cmon86 a stepped error or cmon88 a jump); else flagged."""
        held = self.ported[j] or (rule in (DROPOUT, FREEZE) and self.drops[j]) or (
            rule == JUMP and self.spikes[j]) or (rule == OFF_RANGE and self.ranges[j])
        second = self.out >= 0 and not self._second_taken(j, rule)
        if second or not held:
            self._flag(NOT_IN_CODE, j, SECOND if second else BLIND)
            return False
        self._put_out(j)
        self._recompute()
        self._flag(EXCLUDED, j, rule)
        self.fell = self.fell or bool(self.fallback[j] and not self.fallset[j])
        return True

    def _second_taken(self, j: int, rule: int) -> bool:
        """``j`` taken out for ``rule`` beside those out, as served: the rule takes a second, the
        others predict ``j`` (or cmon89's kinds) and the set is held or solved (the C's
        ``mon_second_taken``; cmon88: a jump, re-referenced and out as the second)."""
        return rule in self.seconds and self._second_kind(j, rule) and self._second_held(j)

    def _second_kind(self, j: int, rule: int) -> bool:
        """Whether the code takes ``j`` out beside those out for ``rule``: one the others
        predict; (cmon89) for a dropout or a jump of one no other predicts (held at its last
        reading, as served) only where the field is rebuilt without them (served feeds a dropped
        sensor's returned reading where it is not); (dep99) for a range reading wherever it is
        (read as missing while beyond, never fed back: the stand-ins served makes); (freezeu100)
        for a freeze of one no other predicts as for its dropout (served's freeze check has no
        cap and holds it at its last reading, the one it held at); (dep101) for a dropout wherever
        it is, of one no other predicts too (served's ``_instant`` takes every missing reading
        out, rebuilt by the set's operator or held at its last reading; a returned one read where
        too few are in: :meth:`_rebuilt`, dep99)."""
        blind = self.instant and not self.ported[j] and bool(
            self.spikes[j] if rule == JUMP else self.drops[j] if rule in (FREEZE, DROPOUT)
            else rule == OFF_RANGE and self.second_range[j])
        if rule not in (DROPOUT, OFF_RANGE) and not blind:
            return bool(self.ported[j])
        # (dep105c) a jump wherever the field is: served holds a jumper at its last reading and
        # serves no fallback while too few are in (the rebuild is a dropout's: its reading fed)
        rebuilds = rule in (OFF_RANGE, DROPOUT, JUMP) or self._active().sum() - 1 >= self.a["min_active"]
        return bool(rebuilds and (self.ported[j] or blind))

    def _outs(self) -> list[int]:
        """The sensors out whose missing reading (or range) is read as such: the first; (cmon89)
        every one out."""
        return list(self.gone if self.instant else self.gone[:1])

    def _second_held(self, j: int) -> bool:
        """(cmon85) ``j`` out (a drift exclusion, a freeze) beside those out: a place free (the
        second; dep99: any, for a reading beyond range, as served; dep99b: and for a jump, which
        served re-references and takes out whatever the set; step99: and for a stepped error,
        served's stepped check having no cap either; dep100: and for a drift exclusion, its
        blind-out too, and a freeze, served's judgement and freeze check having none; dep105:
        and for a dropout beside two or more out where a sensor is left in, served's ``_instant``
        having none) and the set's operator solved; (dep105b) a dropout that leaves none in
        too: served, no operator left, holds its last field (``_clean``), as the code now does
        (:meth:`_recompute`, :meth:`_rebuilt`; before, refused: ``MISSING_SECOND``): whatever the
        rule now, so the rule is no argument."""
        out = ~self._active() | (np.arange(self.n) == j)
        return self.solve and self._operator(out) is not None

    def _put_out(self, j: int) -> None:
        """``j`` in the out set (its last place), its calm count and its within-band mark
        (mon85b) cleared: the served ``_exclude``'s, whatever took it out."""
        if j not in self.gone:
            self.gone.append(j)
        self.calm[j], self.hid[j] = 0, False

    def refuses(self, u: np.ndarray, first: bool) -> int:
        """The rule by which the code refuses the sample ``u`` (inputs in the code's order, a
        missing reading NaN) for a monitored reading it cannot rebuild (0: it takes the sample):
        at a campaign's first sample, with another sensor out or missing (or out of range), of a
        sensor it does not hold out.  The reason is flagged; nothing else changes."""
        self._clear()
        x = np.asarray(u, float)[self.idx if first else self.idx[self.perm]]
        missing = ~np.isfinite(x)
        if not missing.any():
            return 0
        new = missing.copy()
        if not first:
            new[self._outs()] = False        # the sensor out, missing again: rebuilt as it was
        j = int(np.argmax(new if new.any() else missing))
        with np.errstate(invalid="ignore"):
            rng = (x < self.a["lo_lim"]) | (x > self.a["hi_lim"])
        if first:
            rule = MISSING_FIRST
        elif new.any() and (rng.any() or (new.sum() > 1 or self.out >= 0)
                            and not self._pair_held(new, DROPOUT)):
            rule = MISSING_SECOND       # (dep101: several new ones, each out in turn, taken)
        elif new.any() and not (self.ported[j] or self.drops[j]):
            rule = MISSING_BLIND
        else:
            return 0
        self._flag(NOT_IN_CODE, j, rule)
        return rule

    def step(self, u: np.ndarray, first: bool, dt: float, now: float = np.nan) -> np.ndarray:
        """The inputs ``u`` (order of the code's; a missing monitored reading NaN, one that
        :meth:`refuses` takes) with the monitored ones as the model reads them; ``now`` the
        sample's time (the time rule's; NaN: unknown, a frozen sensor's stand-in)."""
        if first:
            self.reset()
        self.now = float(now)
        out = self._sample(u, first, dt)
        self.past_pos, self.rows = push_row(     # (mon105d) the row kept, as the served update keeps it
            self.past, self.past_t, self.past_n, self.past_pos, self.rows,
            self.hist[(self.pos - 1) % self.window], self.now, self.a["tau"])
        return out

    def _hold_until(self, j: int) -> float:
        """(mon105d) Until when sensor ``j``, just out for a freeze by its run alone, is read at
        its held value (the served ``_hold_until``, the same arithmetic): its rate fitted to its
        readings over the ``tau`` before its run began; -inf: never (its stand-in)."""
        return held_until(self.past_t, self.past[:, j], self.past_n, self.past_pos,
                          self.rows - int(self.run[j]), self.a["tau"], self.a["spread"][j])

    def _sample(self, u: np.ndarray, first: bool, dt: float) -> np.ndarray:
        self._clear()
        u = np.asarray(u, float)
        with np.errstate(invalid="ignore"):
            if not first:
                u = self._exchanged(u, dt)
            if not len(self.settles):
                return self._step(u, first, dt, self.a)
            x = u[self.idx]
            if not first:
                self._settled(x, dt)
            ref, count = (None, -1) if first else (self.ref.copy(), self.count)
            out = self._step(u, first, dt, self.a)
            # the row: NaN beyond range; (dep98) of a sample that passed the monitor by too (its
            # window untouched), as served: the window's last row again read a unit's return
            # (K -> °C after 30 samples) as a settled step of 3.15 °C, kept for good
            row = self.hist[(self.pos - 1) % self.window] if self.count != count else np.where(
                (x < self.a["lo_lim"]) | (x > self.a["hi_lim"]), np.nan, x - self.ref)
            self.settle, self.settle_age = advanced(self.settle, self.settle_age, self.ref, ref, row)
            return out

    def _settled(self, x, dt) -> None:
        """(jump94b) Before the sample: a sensor no other predicts, in or out for another rule
        than a jump, whose window ending at ``x`` lies wholly off the one before by more than
        ``settle_lim`` and (settle95) whose windows' median difference passes ``settle_steady`` x
        their larger median absolute deviation (not a ramp), on one reference for 2 w - 1
        samples (``served Settled._settled``):
        re-referenced by the two windows' median difference, kept in (``SETTLED``)."""
        w, a, cols = self.window, self.a, self.settles
        gap = np.maximum(self.gap, max(1.0, dt / a["period"])) if (
            dt > a["gap_periods"] * a["period"]) else self.gap
        parted, shift = level_shift_now(self.settle[:, cols], x[cols] - self.ref[cols], w,
                                        a["settle_lim"][cols], a["settle_steady"])
        if not parted.any():       # nearly every sample: none fires (as served)
            return
        active = self._active()[cols]
        fire = ((active | (self.jumps[cols] == 0)) & parted
                & (gap[cols] == 1) & (self.settle_age[cols] >= 2 * w - 1))
        for k in np.flatnonzero(fire):
            j = int(cols[k])
            off = float(shift[k])
            self.ref[j] += off
            self.prev[j] -= off
            self.hist[:, j] -= off
            if active[k]:
                self.last[j] -= off
            self.settle[w:, j] -= off
            self._flag(REREFERENCED, j, SETTLED)

    def _step(self, u, first, dt, a):
        x = u[self.idx]
        missing = ~np.isfinite(x)
        self.read = ~missing
        rng = (x < a["lo_lim"]) | (x > a["hi_lim"])
        if first:
            # (dep108) beyond its range: the model reads the served stand-in (its training's
            # first reading, the campaign's A0 too) rebuilt from the others while it stays beyond
            self.late = rng & bool(a["late"])
            if (rng & ~self.late).any():   # not in the code: the served monitor references it late
                self._flag(NOT_IN_CODE, int(np.argmax(rng)), RANGE)
            self.ref, self.base, self.ref0 = x.copy(), np.where(self.late, a["first_c"], x), x.copy()
        # (dep108f) in range again: no reference yet (served: NaN), read as no finite value until
        # referenced late (below)
        back = self.late & ~missing & ~rng if not first and self.late.any() else None
        back = back if back is not None and back.any() else None
        d = x - self.ref
        if back is not None:
            d[back] = np.nan
        # a gap in time: each step judged as that many one-sample steps, and a sensor's own
        # missing samples since its last reading too (the served monitor's gap per sensor)
        gap = np.maximum(self.gap, max(1.0, dt / a["period"])) if (
            not first and dt > a["gap_periods"] * a["period"]) else self.gap
        if rng.any() and not first:
            every, far = bool(rng.all()), rng | missing
            rng = self._beyond(x, d, rng)
            if rng is None:  # not in the code: the sample passes the monitor by, its state as it
                # was (so that the return is no jump); (kelvin97) every reading beyond its range:
                # nothing to rebuild from, the model reads the last field, as served (``_clean``);
                # (dep98) but each step spans it, as served: a reading beyond range one sample
                # more of its gap, one in range its last (the return after 20 samples in kelvin
                # was read as one sample's common step, the sensors re-referenced for good)
                self.prev = np.where(far, self.prev, d)
                self.gap = np.where(far, gap + 1, 1.0)
                return self._rebuilt(u, self.last if every else x - self.ref)
        gone = missing | rng        # read as missing (cmon80: beyond its range too)
        pos = self.pos
        self.hist[pos] = d
        self.pos, self.count = (pos + 1) % self.window, self.count + 1
        step = d - self.prev
        big = (np.abs(step) > a["jump_lim"] * gap) & ~rng
        same = step == 0
        jumped = -1
        instant = missing | rng if back is None else missing | rng | back   # (served: a dropout's)
        if big.sum() >= a["common_min"]:
            big = self._common_step(d, step, big, pos)
        was_in = self._in()
        if a["bent"]:
            big = self._bent(d, step, big, gone, gap, pos)
        # a lone jump's change as the others see it, judged by the set in before this sample's
        # dropout or range exclusion, as served (its instant faults read first, then excluded)
        n_big = int(big.sum())      # (big as judged from here; ci101b: counted once)
        other = self._others_seen(d) if n_big == 1 else None
        if missing.any():   # (refuses() let one through: a new one, or the sensor out again)
            new = missing.copy()
            new[self._outs()] = False
            if new.any():   # (dep101) each new one out in the monitor's order, as served
                for j in np.flatnonzero(new):
                    self._exclude(int(j), DROPOUT)
            elif not self.dropped[j := int(np.argmax(missing))] and not self.jumps[j]:
                # out for a freeze: the served monitor marks it dropped or not by the path it
                # takes (its band on re-admission), which the code does not follow
                self._flag(NOT_IN_CODE, j, MISSING_FROZEN)
        for j in [int(k) for k in np.flatnonzero(rng) if k not in self._outs()]:
            self._exclude(j, OFF_RANGE)   # (cmon80: read as missing, as a dropout; dep99: each)
        if n_big >= 2 and a["pair_jump"] and not gone.any() and self.count != 2 and (
                (held := self._pair_jump(x, d, step, big)) is not None):
            instant |= held
            self.hist[pos] = d
        elif n_big > 1:
            self._flag(NOT_IN_CODE, int(np.argmax(big)), COMMON)
        elif big.any() and self.count == 2:
            self._flag(NOT_IN_CODE, int(np.argmax(big)), GLITCH)
        elif big.any():
            j = int(np.argmax(big))
            active = self._active()
            if (not active[j] and a["spike"] and not gone.any() and back is None
                    and self._spike_back(j, x, d)):
                self._readmit(j, SPIKE)
            elif active[j] and not (self._second_taken(j, JUMP) if self.out >= 0
                                  else self.ported[j] or self.spikes[j]):
                self._exclude(j, JUMP)       # flagged: not in the code; the sensor stays as read
            else:
                if not active[j] and not self.predictable[j] and not a["blind_jump"]:
                    # (cmon82c) the served return may undo it (readmission.py): not in the code
                    self._flag(NOT_IN_CODE, j, BLIND)
                if not self.jumps[j]:
                    self.ref0[j] = self.ref[j]
                expected = other[j] - self.prev_other[j]
                offset = step[j] - (expected if np.isfinite(expected) else 0.0)
                self.ref[j] += offset
                d[j] -= offset
                jumped = j
                self.jumps[j] += 1
                if active[j]:
                    self._exclude(j, JUMP)
            self.hist[pos] = d
        if rng.any():       # read as missing from here (neither a step's last reading nor in the
            d[rng] = np.nan     # window that decides re-admission), as served
            self.hist[pos] = d
        self.run = np.where(same, self.run + 1, 0)
        self.calm += 1
        if jumped >= 0:
            instant[jumped] = True
        self.calm[instant] = 0
        pred, e = self._errors(d)
        if back is not None:
            pred, e = self._referenced_late(x, d, pred, e, back, pos)
        self.err[pos] = e
        self._judge_memo = None          # (the window's errors changed in place)
        self.froze[instant] = False      # another detector fired on it: out for that now
        self.off = np.where(self.froze & np.isfinite(d) & (d != self.held), self.off + 1, 0)
        # freeze: constant while the field (its prediction from the others) moves
        _, active, observable, judged, _ = self._set()
        other = d - np.where(np.isfinite(e), e, d - pred)
        start = same & (self.run == 1)
        self.run_pred[start] = other[start]
        moved = np.abs(other - self.run_pred)
        frozen = same & ((observable & (moved >= self.warn) & (self.run >= a["seen_run"]))
                         | (~observable & (self.run > a["blind_run"])) | (self.run > a["dither_run"]))
        for j in np.flatnonzero(frozen & ~instant):
            instant[j] = True
            if active[j] and self._exclude(int(j), FREEZE):
                self.froze[j], self.held[j], self.off[j] = True, d[j], 0
                # (mon105d) its held value read while its own past says it stood still; never
                # where the field moved past its band while it held
                by_field = observable[j] and moved[j] >= self.warn[j]
                self.hold_to[j] = -np.inf if by_field else self._hold_until(int(j))
        self._stepped(e, instant)
        level = self._level()
        if level[judged].any():
            self.flags |= BAND
        self._judgement()
        for j in [k for k in self.gone if self.count >= self.window]:
            self._thaw(j, gone, instant)
        due = ~self._in() & ~gone & (self.run == 0) & ~instant & (self.calm >= self.dwell)
        if due.any() and self.count >= self.window:
            for j in np.flatnonzero(self._returning(due)):
                if a["blind_jump"]:
                    self._undone(int(j), d)
                self.jumps[j], self.froze[j] = 0, False
                self._readmit(int(j), BACK)
        pred, e = self._errors(d)
        _, active, _, judged, _ = self._set()
        self.prev_other = np.where(judged, d - e, np.nan)
        # (step93) none over a gap, of a jump, of a sensor out or back (a return's undo)
        self.last_step = np.where(~gone & (gap == 1) & ~big & was_in & active, d - self.prev, np.nan)
        self.prev = np.where(gone, self.prev, d)     # a return is stepped from the last reading
        self.gap = np.where(gone, gap + 1, 1.0)
        self.prev_e = e
        self.dropped[instant] = missing[instant]       # (the last detector to fire on it)
        self.ranged[instant] = rng[instant]
        self.last = np.where(active & np.isfinite(d), d, self.last)
        self._fold(self.hist[pos], first, dt)
        return self._rebuilt(u, d, pred)

    def _pair_jump(self, x, d, step, big) -> np.ndarray | None:
        """(cmon93) Two sensors jumping in one sample (``big``), no common step, every reading
        there and in range, as the served monitor reads a sample's instant faults together
        (``_spike_back``, ``_instant``): where both are out, each tried as a spike's return first
        (mon89, in the monitor's order, the field's prediction redone after a return; dep109: none
        on a sample with a value not finite, a late reference's, as served); every
        jumper left re-referenced by its step less its change as the active sensors that did
        not jump predict it (:meth:`_unjumped_change`; alone, its whole step), those in excluded
        in the monitor's order.  The jumpers re-referenced (they fired), or None where the code
        does not hold it (a third out, a set it cannot solve, one it does not hold out):
        nothing changed, flagged by the caller as before (``d`` changed in place)."""
        left = big.copy()
        if self.a["spike"] and not (big & self._active()).any() and np.isfinite(d).all():
            for j in np.flatnonzero(big):
                if self._spike_back(int(j), x, d):
                    self._readmit(int(j), SPIKE)
                    left[j] = False
        expected = self._unjumped_change(d, left) if left.sum() >= 2 else np.full(self.n, np.nan)
        if expected is None or not self._pair_held(left & self._active()):
            return None
        for j in np.flatnonzero(left):
            if not self._active()[j] and not self.predictable[j] and not self.a["blind_jump"]:
                self._flag(NOT_IN_CODE, int(j), BLIND)   # (cmon82c: the served return may undo it)
            if not self.jumps[j]:
                self.ref0[j] = self.ref[j]
            offset = step[j] - (expected[j] if np.isfinite(expected[j]) else 0.0)
            self.ref[j] += offset
            d[j] -= offset
            self.jumps[j] += 1
        for j in np.flatnonzero(left & self._active()):
            self._exclude(int(j), JUMP)
        return left

    def _unjumped_change(self, d, big) -> np.ndarray | None:
        """(cmon93) The change since the last sample of each ``big`` sensor as the active ones
        that did not jump predict it (one operator on that set, the served
        ``_unjumped_change``); NaN where they cannot (fewer than ``min_active`` of them, or its
        leverage with them at the limit); None where the code has no operator of a set."""
        base = self._active() & ~big & np.isfinite(self.prev)
        if base.sum() < self.a["min_active"]:
            return np.full(self.n, np.nan)
        return self._change_seen(d, base, big)

    def _change_seen(self, d, base, which) -> np.ndarray | None:
        """The change since the last sample of each ``which`` sensor as the sensors ``base``
        predict it (one operator on that set), NaN where they cannot (its leverage with them at
        the limit); None where the code has no operator of a set: the jump's expected change
        (:meth:`_unjumped_change`) and (wires100) the exchanged wires' prediction alike, as
        served (``InstantFaults._change_seen``)."""
        expected = np.full(self.n, np.nan)
        if (op := self._operator(~base)) is None:
            return None
        change = np.where(base, d - self.prev, 0.0)
        for j in np.flatnonzero(which):
            if (own := self._operator(~base & (np.arange(self.n) != j))) is None:
                return None
            if own[1][j] < self.max_lev:
                expected[j] = op[0][j] @ change
        return expected

    def _exchanged(self, u, dt):
        """(wires100) ``u`` with the monitored readings as read from two wires exchanged, as
        served (``InstantFaults._exchanged``): every sensor in and read, exactly two flagged at
        one sample (a step past the jump limit times the samples it spans, or a reading beyond
        range), each reading within the OTHER's jump limit of the reading the sensors without
        both predict for the other (its last reading where no other predicts it): read exchanged
        from that sample on (``perm``), flagged ``REREFERENCED`` / ``WIRES_EXCHANGED`` on the
        first of the two (``perm`` names the other).  A set the code cannot solve: flagged
        ``NOT_IN_CODE``, read as before."""
        a = self.a
        x = u[self.idx[self.perm]]
        if self.gone or not self.count or not a["exchange"]:
            return self._permuted(u)
        gap = np.maximum(self.gap, max(1.0, dt / a["period"])) if (
            dt > a["gap_periods"] * a["period"]) else self.gap
        d = x - self.ref
        lim = a["jump_lim"] * gap
        flagged = (np.abs(d - self.prev) > lim) | (x < a["lo_lim"]) | (x > a["hi_lim"])
        if flagged.sum() != 2 or not np.isfinite(d - self.prev).all():
            return self._permuted(u)
        i, k = np.flatnonzero(flagged)
        change = self._change_seen(d, ~flagged, flagged)
        if change is None:
            self._flag(NOT_IN_CODE, int(i), WIRES_EXCHANGED)
            return self._permuted(u)
        seen = self.ref + self.prev + np.nan_to_num(change)
        if abs(x[k] - seen[i]) < lim[i] and abs(x[i] - seen[k]) < lim[k]:
            self.perm = self.perm.copy()
            self.perm[[i, k]] = self.perm[[k, i]]
            self._flag(REREFERENCED, int(i), WIRES_EXCHANGED)
        return self._permuted(u)

    def _permuted(self, u):
        """``u`` with the monitored readings in the order ``perm`` reads them (wires100)."""
        if (self.perm == np.arange(self.n)).all():
            return u
        u = u.copy()
        u[self.idx] = u[self.idx[self.perm]]
        return u

    def _pair_held(self, ins: np.ndarray, rule: int = JUMP) -> bool:
        """(cmon93) Whether the code takes every sensor of ``ins`` out for ``rule`` (a jump;
        dep101: a dropout, several readings missing in one sample), in the monitor's order, as
        the first out (one it holds out: the others predict it, or cmon84 / cmon87 one no other
        predicts) or beside those out (cmon88 / cmon89's second, the set solved)."""
        blind = self.spikes if rule == JUMP else self.drops
        with self._trial():
            for j in np.flatnonzero(ins):
                if not (self._second_taken(int(j), rule) if self.out >= 0
                        else self.ported[j] or blind[j]):
                    return False
                self.gone.append(int(j))
            return True

    @contextlib.contextmanager
    def _trial(self):
        """The out set grown for a trial (each sensor judged beside those taken before it, in
        the monitor's order: cmon93's pair, dep99's readings beyond range), as it was after."""
        saved = list(self.gone)
        try:
            yield
        finally:
            self.gone = saved

    def _spike_back(self, j: int, x, d) -> bool:
        """(mon89) ``j``, out for jumps alone and the others predicting it, jumping back within a
        window of its last jump to within its re-admission band of the field the active sensors
        predict, on its reference before the first jump: a spike, its reference put back and
        ``d`` with it, as served (``InstantFaults._spike_back``)."""
        _, active, _, _, _ = self._set()
        if (not self.predictable[j] or not self.jumps[j] or self.by_field[j] or self.froze[j]
                or self.dropped[j] or not self.calm[j] < self.window
                or active.sum() < self.a["min_active"] or not np.isfinite(d[active]).all()):
            return False
        trial = active.copy()
        trial[j] = True
        if (op := self._operator(~trial)) is None or not op[1][j] < self.max_lev:
            return False
        pred, _ = self._errors(d)
        back = x[j] - self.ref0[j]
        if not abs(back - pred[j]) < self.a["readmit"] * self._bands(trial | self.hid)[0][j]:
            return False
        self.ref[j], d[j], self.jumps[j] = self.ref0[j], back, 0
        return True

    def _undone(self, j: int, d) -> None:
        """(cmon87) ``j``, no other predicts it, back: its jumps undone as served (``_readmit``:
        several are noise or a spike; of one, the reading nearer its held value taken), its
        reference restored and ``d`` and its window shifted back."""
        shift = self.ref[j] - self.ref0[j]
        if self.predictable[j] or not self.jumps[j] or (
                self.jumps[j] == 1 and not abs(d[j] + shift - self.last[j]) < abs(d[j] - self.last[j])):
            return
        self.ref[j] = self.ref0[j]
        d[j] += shift
        self.hist[:, j] += shift

    def _stepped(self, e, instant) -> None:
        """A self-prediction error stepped past the alarm band in one sample (the served
        ``_check_stepped``): each such sensor fired on (``instant``); (cmon86) the culprit, the
        largest step times ``sqrt(1 - h)``, out as a drift exclusion is (its wait doubled, no
        field to follow), a second beside one out where the set is solved.  An export before
        it (no ``stepped``) flags it."""
        _, active, _, judged, _ = self._set()
        de = e - self.prev_e
        stepped = judged & (np.abs(e) >= self.alarm) & (np.abs(de) >= self.alarm)   # (mon86: the set's)
        if not stepped.any():
            return
        if not self.a["stepped"]:
            self._flag(NOT_IN_CODE, int(np.argmax(stepped)), STEPPED)
            return
        instant |= stepped
        j = int(np.argmax(np.where(stepped, np.abs(de) * np.sqrt(np.abs(1 - self.levc)), -1.0)))
        if self._exclude(j, STEP_OUT):
            self._by_drift(j, follows=False)

    def _thaw(self, j, gone, instant) -> None:
        """(freeze84) ``j``, out for a freeze alone, ``THAW`` readings in a row off the value it
        held: back at once (cmon85: either of the two out)."""
        if not self.froze[j] or gone[j] or instant[j] or self.off[j] < THAW:
            return
        if not self.a["thawed"]:
            self._flag(NOT_IN_CODE, j, NO_THAW)
            return
        self.froze[j] = False
        self._readmit(j, THAWED)

    def _beyond(self, x, d, rng):
        """(cmon80) The readings beyond their range that are read as missing (``rng`` less a
        machine hotter than training, as the served monitor's ``_hotter``), or None where the
        code does not hold them (flagged): every reading beyond (kelvin97: nothing to rebuild
        from), one of a sensor it does not hold out, or beside those out where the set's
        operator is not had.  (dep99) Several at once are each out, in the monitor's order, the
        set of any size, as served (``_instant``: a logger card of three in kelvin)."""
        a = self.a
        if rng.all():
            self._flag(NOT_IN_CODE, int(np.argmax(rng)), RANGE)
            return None
        # predicted from the others in and within range (cmon89: one out already, set solved)
        inside = self._active() & ~rng & np.isfinite(d)
        op = self._operator(~inside) if inside.sum() >= a["min_active"] else None
        rng = rng.copy()
        # the set grown in the monitor's order, as the caller takes them out
        with self._trial():
            for j in map(int, np.flatnonzero(rng)):
                outs = self._outs()
                if self.gone and j not in outs and not self._second_taken(j, OFF_RANGE):
                    self._flag(NOT_IN_CODE, j, RANGE)
                    return None
                if j in outs:            # out already: read as missing (served: its leak
                    if not (self.predictable[j] or self.ranges[j] and (   # judges its return)
                            j == self.out or self.second_range[j])):
                        self._flag(NOT_IN_CODE, j, BLIND)
                        return None
                    continue
                if op is not None:
                    p = (x - d)[j] + op[0][j] @ np.where(inside, d, 0.0)
                    up = x[j] > a["hi_c"][j]
                    edge = a["hi_c"][j] if up else a["lo_c"][j]
                    beyond = (p - edge if up else edge - p) > a["warning"][j]
                    if beyond and abs(x[j] - p) < 0.5 * abs(x[j] - edge):
                        rng[j] = False       # a machine hotter than training: read
                        continue
                if not (self.ported[j] or self.ranges[j]):
                    self._flag(NOT_IN_CODE, j, BLIND)
                    return None
                self.gone.append(j)
        return rng

    def _common_step(self, d, step, big, pos):
        """(cmon80) A common step (module doc): each active sensor that took it re-referenced
        by its own step (``d``, ``step``, the window's row ``pos`` changed in place); the jumps
        left after it; called with at least ``common_min`` of them."""
        a = self.a
        active = self._active()
        common = float(np.median(step[big]))
        ratio = step / common if common else np.zeros_like(step)
        took = active & (ratio >= 1 / a["common_spread"]) & (ratio <= a["common_spread"])
        if (took & big).sum() < a["common_min"] or 2 * took.sum() <= (active & np.isfinite(d)).sum():
            return big
        for j in np.flatnonzero(took):
            self.ref[j] += step[j]
            d[j] -= step[j]
            self.hist[pos, j] = d[j]
        self._flag(REREFERENCED, int(np.argmax(took)), COMMON_STEP)
        step[took] = 0.0
        return big & ~took

    def _bent(self, d, step, big, gone, gap, pos):
        """(step93) A step of a sensor no other predicts off its own last one beyond ``bend_lim``
        (``InstantFaults._bent``): re-referenced by the departure and kept in, counted a jump
        (``ref0``); a second since it was in is a jump (step93b).  ``d``, ``step``, the window's
        row ``pos`` changed in place.  The jumps after it."""
        off = step - self.last_step       # NaN for a sensor out or back (no last step)
        bent = ~big & ~gone & (gap == 1) & (np.abs(off) > self.a["bend_lim"])
        again = bent & (self.jumps > 0)
        for j in np.flatnonzero(bent & ~again):
            self.ref0[j], self.jumps[j] = self.ref[j], 1
            self.ref[j] += off[j]
            d[j] -= off[j]
            step[j] -= off[j]
            self.hist[pos, j] = d[j]
            self._flag(REREFERENCED, int(j), BENT)
        return big | again

    def _rebuilt(self, u, d, pred=None):
        """``u`` with the monitored inputs as the model reads them: the reading, a sensor out
        rebuilt from the others (``pred``: their predictions), one no other predicts held at its
        last reading in (cmon82c); (dep99) where too few are in to rebuild the field (a set
        out), one out for a dropout alone whose reading is back and moved, as served (its
        ``_rebuilds``: nearer the truth than a held value)."""
        if pred is None:
            pred = self._errors(d)[0]
        v = u.copy()
        read = self._active()
        if read.sum() < self.a["min_active"]:
            read |= self.dropped & np.isfinite(d) & (self.run == 0)
        # (mon105d) one out for a freeze alone read at its held value while its past allows
        held = self.froze & ~self._active() & (self.off == 0) & (self.now <= self.hold_to)
        field = np.where(read, d, np.where(self.predictable & ~held, pred, self.last))
        # (dep105b) nothing to rebuild from (none in: no operator): the last field, as served
        self.clean = field = np.where(np.isfinite(field), field, self.clean)
        v[self.idx] = self.base + field
        if self.out >= 0:
            self.flags |= OUT
        if self.novel:
            self.flags |= NOVEL
        if self.fell:       # the served correction is the fallback's (and its switch back)
            self._flag(NOT_IN_CODE, int(np.argmax(self.fallback)), FALLBACK)
        return v

    def _returning(self, due: np.ndarray) -> np.ndarray:
        """Which of the ``due`` sensors come back, judged together as served: those that pass in
        the set of the active ones and every due one, the worst failing one left out until the
        rest pass."""
        trial = self._active() | due
        while True:
            ok, worst = self._pass_once_back(trial)
            failing = due & trial & ~ok
            if not failing.any():
                return due & trial
            trial[int(np.argmax(np.where(failing, worst, -1.0)))] = False

    def _pass_once_back(self, trial: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(passes, worst error)`` of the sensors of ``trial``: their leave-one-out error in it
        over the whole window within ``READMIT`` of the warning band (its whole band for one out
        for a dropout alone: it had passed its judgement until its reading went missing); one
        the others in ``trial`` cannot predict passes where no other predicts it at all."""
        n = self.n
        if trial.sum() < self.a["min_active"] or (op := self._operator(~trial)) is None:
            return np.zeros(n, bool), np.full(n, np.inf)
        M, lev = op
        blind = lev >= self.max_lev
        H = np.where(np.isfinite(self.hist), self.hist, 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            worst = np.abs((H - H @ M.T) / (1 - lev)).max(axis=0)
        worst[blind] = np.inf
        lost = self.dropped & ~self.by_field & (self.jumps == 0)
        warn = self._bands(trial | self.hid)[0]      # (mon86) the trial set's
        band = np.where(lost | self.hid, 1.0, self.a["readmit"]) * warn
        ok = np.where(blind, ~self.predictable, worst < band) & trial
        # (cmon82c) one out for explaining the others' errors: back where they all pass their
        # warning band with it in, as served
        explains = trial & blind & self.explains
        if explains.any():
            judged = trial & ~blind
            ok[explains] = bool((worst[judged] < warn[judged]).all())
        # (mon88) one out by the field's judgement, blind only for want of a partner out frozen
        if self.a["cleared"]:
            for j in np.flatnonzero(trial & blind & self.by_field & ~self.explains & ~self._active()):
                ok[j] = self._blind_for_frozen(j, trial)
        # (cmon89b) one no other predicts, out of range: back where its leak passes, as served
        for j in np.flatnonzero(ok & ~self._active() & self.ranges & self.ranged):
            ok[j] = self._leak_passes(j, trial, H, M, lev)
        return ok, worst

    def _leak_passes(self, u: int, trial: np.ndarray, H, M, lev) -> bool:
        """(cmon89b) Whether the leak of ``u`` onto the sensors judged in ``trial`` with it and
        without it is within ``readmit`` of their warning bands on every sample of the window
        ``H``, as served (``Readmission._leak_passes``): True where too few are left without it
        to judge; False where the set without it has no operator in the code."""
        rest = trial & (np.arange(self.n) != u)
        if rest.sum() < self.a["min_active"]:
            return True
        if (op := self._operator(~rest)) is None:
            return False
        M2, lev2 = op
        both = rest & (lev < self.max_lev) & (lev2 < self.max_lev)
        if not both.any():
            return True
        with np.errstate(divide="ignore", invalid="ignore"):
            e_in = (H[:, both] - H @ M[both].T) / (1 - lev[both])
            e_out = (H[:, both] - H @ M2[both].T) / (1 - lev2[both])
        return bool((np.abs(e_in - e_out) / self.a["warning"][both]).max() < self.a["readmit"])

    def _blind_for_frozen(self, j: int, trial: np.ndarray) -> bool:
        """(mon88) Whether a sensor out of ``trial``, frozen by the rule for one no other
        predicts (constant longer than ``blind_run``), would predict ``j``: as served
        (``Readmission._blind_for_frozen``)."""
        frozen = ~trial & ~self._active() & (self.run > self.a["blind_run"])
        for k in np.flatnonzero(frozen):
            with_k = trial.copy()
            with_k[k] = True
            op = self._operator(~with_k)
            if op is not None and op[1][j] < self.max_lev:
                return True
        return False

    # -- (cmon82) the exclusion by judgement (module doc) --------------------------------------
    def _judgement(self) -> None:
        """The served monitor's drift exclusion where the code holds it, else flagged."""
        a = self.a
        level, err = self._judge()
        active, judged = self._in(), self._judging()
        field = ALARM if (self.by_field & ~active).any() else a["exclude_level"]
        # (cmon82b) in a new thermal state no drift exclusion at all (served: every one vetoed)
        if (judged & (level >= field)).any() and active.sum() > a["min_active"] and not (
                a["new_state"] and self.novel):
            if not a["drift"] or (self.out >= 0 and not self.solve):
                self._flag(NOT_IN_CODE, int(np.argmax(judged & (level >= field))), DRIFT)
            else:
                self._drift(level, err, field)
        if not a["new_state"]:
            return
        self._follow_field()

    def _follow_field(self) -> None:
        """(cmon82b) The served ``_follow_field``: a drift-excluded sensor whose exclusion the
        field followed (``new_state_others`` other judged sensors out of band within a window
        of it) comes back at once, a new thermal state declared; the state ends after a window
        with every judged sensor within band (flagged by an export before cmon82b)."""
        a = self.a
        level, _ = self._judge()
        active, judged = self._in(), self._judging()
        self.since[active | (self.count - self.since > self.window)] = -1
        out = int((judged & (level >= WARNING)).sum())
        for j in np.flatnonzero(self.since >= 0):
            if out < a["new_state_others"]:
                continue
            if not a["novel"]:
                self._flag(NOT_IN_CODE, int(j), DRIFT)
                return
            self.since[j], self.dwell[j] = -1, self.window
            self._readmit(int(j), FOLLOWED)
            self._declare()
            level, _ = self._judge()
            judged = self._judging()
            out = int((judged & (level >= WARNING)).sum())
        self.calm_field = 0 if out else self.calm_field + 1
        if self.novel and self.calm_field >= self.window:
            self.novel = False

    def _readmit(self, j: int, rule: int) -> None:
        """``j`` back in (``rule``: why), its partner's place kept, the window re-judged."""
        self.by_field[j], self.explains[j], self.ranged[j] = False, False, False
        self.gone.remove(j)
        self._recompute()
        self._flag(READMITTED, j, rule)

    def _declare(self) -> None:
        """A new thermal state (the served ``_declare``): no drift exclusion until it ends."""
        self.novel, self.calm_field = True, 0

    def _drift(self, level, err, field) -> None:
        """A judged sensor beyond the band (every sensor in, or cmon85 one out already): the
        culprit (the largest ``|E|(1 - h)``) out
        where with it out the others are within their warning bands and fewer than
        ``new_state_others`` others are out of it (else nothing: the served monitor's veto), its
        blind partner with it; flagged where the served monitor does what the code does not."""
        a = self.a
        judged = self._judging()
        if (u := self._explaining(level, field)) is not None:
            if a["blind_out"] and (self.out < 0 or self._second_held(u)):
                self._blind_out(u)
            else:
                self._flag(NOT_IN_CODE, u, DRIFT)
            return
        z = np.where(judged, np.abs(np.nan_to_num(err)) * np.sqrt(np.abs(1 - self.levc)) ** 2,
                     -1.0)
        j = int(np.argmax(z))
        if a["new_state"]:
            j, resolves = self._lone_fault(j, z, level, err, judged)
            if j < 0:
                return
            if not resolves:              # a new thermal state (served: declared)
                if not a["novel"]:
                    self._flag(NOT_IN_CODE, j, DRIFT)
                else:
                    self._declare()
                return
            if self._others(j, level, judged) >= a["new_state_others"]:
                return
            if (level[j] < WARNING or self._within_rounding(j, field)) and self._hovers(level, err):
                return          # a regime, not a fault (served: nothing excluded)
        if not self._exclude(j, DRIFT_OUT):
            return
        self._by_drift(j)
        self.hid[j] = bool(level[j] < WARNING)     # (mon85b) it passed its own band
        self._set_bands()
        _, active, observable, _, _ = self._set()
        blind = np.flatnonzero(active & ~observable & ~self.warn_only & (z >= 0.7 * z[j]))
        for i in blind:
            if active.sum() <= a["min_active"]:
                continue
            # (dep100) the partner out beside any number out, as served: no cap, the set solved
            if len(blind) > 1 or not self.ported[i] \
                    or self._operator(~active | (np.arange(self.n) == i)) is None:
                self._flag(NOT_IN_CODE, int(i), DRIFT)
                return
            if a["new_state"]:
                lv, _ = self._judge()
                jd = self._judging()
                if not self._resolves(int(i)):    # a new thermal state (served: declared)
                    if not a["novel"]:
                        self._flag(NOT_IN_CODE, int(i), DRIFT)
                    else:
                        self._declare()
                    return
                if self._others(int(i), lv, jd) >= a["new_state_others"]:
                    return
            self._put_out(int(i))
            self._recompute()
            self._by_drift(int(i))
            self._flag(EXCLUDED, int(i), DRIFT_OUT)
        self._second_culprit()

    def _blind_out(self, u: int) -> None:
        """(cmon82c) ``u`` (no other predicts it) out for explaining the others' errors, as
        served: a drift exclusion held at its last reading; judged again, a sensor still beyond
        the alarm band is flagged (the served monitor goes on with one out)."""
        self._put_out(u)
        self._recompute()
        self._by_drift(u)
        self.explains[u] = True
        self._flag(EXCLUDED, u, BLIND_OUT)
        self.fell = self.fell or bool(self.fallback[u] and not self.fallset[u])
        self._second_culprit()

    def serving(self) -> int:
        """(cmon83) The law set the correction sums (:mod:`.fallbacks`): the fallback model's of
        the first sensor out (the monitor's order) that has one, as served (``_fallen_back``: not
        while too few are in to rebuild the field, nor of one out for a dropout that reads again:
        cmon84, its held reading the model's while it waits out its window; one that has none in
        the code: 0, flagged ``FALLBACK``); 0: the model's."""
        active = self._in()
        if active.sum() < self.a["min_active"]:
            return 0
        back = self.dropped & self.read
        k = next((k for k in range(self.n) if not active[k] and not back[k] and self.fallback[k]),
                 None)
        return 0 if k is None else int(self.fallset[k])

    def _second_culprit(self) -> None:
        """After an exclusion the served monitor judges again and goes on with one out: a sensor
        still beyond the alarm band is flagged (a second culprit, not in the code)."""
        level, _ = self._judge()
        active, judged = self._active(), self._judging()
        if (judged & (level >= ALARM)).any() and active.sum() > self.a["min_active"]:
            self._flag(NOT_IN_CODE, int(np.argmax(judged & (level >= ALARM))), DRIFT)

    def _lone_fault(self, j, z, level, err, judged) -> tuple[int, bool]:
        """The served monitor's ``_lone_fault``: ``(sensor, whether with it out the others are
        within band)``, every sensor in."""
        out = judged & (level >= WARNING)
        size = np.abs(np.where(judged, np.nan_to_num(err), 0.0))
        std = np.sqrt(np.abs(1 - self.levc))
        likelier = np.argmax(size * std)     # (mon84: asked of every lone fault)
        # (mon86b: j within band, the likelier fault out of band: that one or none yet, -1;
        # mon87: not where the excursion hovers, j then, held as a regime)
        doubted = self._resolves(j, out if level[j] < WARNING else None)
        if doubted and not (level[j] < WARNING and out[likelier] and not self._hovers(level, err)):
            return j, True
        # (mon85: j within band hiding the likelier single fault, not its blind partner: no)
        hidden = out & (z < 0.7 * z[j]) & (np.arange(len(z)) == likelier)
        hides = bool(level[j] < WARNING) and self._resolves(j, hidden)
        for k in np.argsort(-z):
            if (k != j and z[k] >= 0 and level[k] >= WARNING and likelier == k
                    and self._resolves(int(k), judged,   # (mon84b: every judged sensor)
                                       float(np.max(np.delete(size, k), initial=0.0)))):
                return int(k), True
        return (-1, True) if doubted else (j, hides)

    def _fold(self, d, first, dt) -> None:
        """The served monitor's memory of the field (``EXCURSION_TAU_S``), the sample ``d``."""
        if first or not np.isfinite(dt):
            self.slow_known = bool(first)
            return
        keep = np.exp(-max(dt, 0.0) / self.a["tau"])
        self.slow = np.where(np.isfinite(d), keep * self.slow + (1 - keep) * d, self.slow)

    def _within_rounding(self, j: int, field) -> bool:
        """(mon83) The served ``_within_rounding``: ``j``'s smallest error over the last
        ``confirm`` samples beyond the band that excludes by less than its rounding bound, the
        memory's error within that of the band already, on the same side."""
        band = (self.warn if field == WARNING else self.alarm)[j]
        last, bound = self.err[self._rows(), j], self.a["rounding"][j]
        if not self.slow_known or not np.abs(last).min() < band + bound:
            return False
        M, _, _, _, scale = self._set()
        past = (self.slow[j] - M[j] @ self.slow) * scale[j]
        return bool(past * np.sign(last.sum()) >= band - bound)

    def _hovers(self, level, err) -> bool:
        """The served monitor's ``_excursion_hovers``: every judged sensor out of band has an
        error no larger a share of its rise than the memory's (a regime, not a fault)."""
        M, _, _, _, scale = self._set()
        out = np.flatnonzero(self._judging() & (level >= WARNING))
        if not self.slow_known or self.count < 2 or not len(out):
            return False
        past = (self.slow - M @ self.slow) * scale
        rise = np.abs(self.hist[self._rows()].mean(axis=0))
        now = np.abs(err[out]) * np.abs(self.slow[out])
        then = np.maximum(past[out] * np.sign(err[out]), 0.0) * rise[out]
        return bool(np.all(now <= self.a["growth"] * then))

    @staticmethod
    def _others(j, level, judged) -> int:
        others = judged & (level >= WARNING)
        others[j] = False
        return int(others.sum())

    def _by_drift(self, j: int, follows: bool = True) -> None:
        """``j`` out by a drift exclusion: its return waits longer each time (served); the field
        may follow it (``follows``: not a stepped error's culprit, cmon86)."""
        self.by_field[j] = True
        self.dwell[j] = self.window * 2 ** min(self.outs[j], int(self.a["max_backoff"]))
        self.outs[j] += 1
        if follows:
            self.since[j] = self.count

    def _X(self) -> np.ndarray:
        rows = self.hist[self._rows()]
        return np.where(np.isfinite(rows), rows, 0.0)

    def _resolves(self, j: int, seen=None, alone=None) -> bool:
        """With ``j`` out too, every other judged sensor's leave-one-out error over the last
        ``confirm`` samples (their mean) within its warning band (True: too few left to judge;
        ``seen``: and each of them still judged; ``alone``: and ``j`` off the others' field by
        that much at least), as served."""
        trial = self._active()
        trial[j] = False
        if trial.sum() < self.a["min_active"]:
            return True
        if (op := self._operator(~trial)) is None:
            return False
        M, lev = op
        jd = trial & (lev < self.max_lev) & ~self.warn_only
        if seen is not None and (seen & trial & ~jd).any():
            return False
        X = self._X()
        E = ((X[:, jd] - X @ M[jd].T) / (1 - lev[jd])).mean(axis=0)
        if not (np.abs(E) < self.warn[jd]).all():
            return False
        return alone is None or bool(abs((X[:, j] - X @ M[j]).mean()) >= alone)

    def _explaining(self, level, field) -> int | None:
        """The served monitor's ``_explaining`` (every sensor in): a sensor no other predicts
        whose reading explains the judged sensors beyond the band (None: none does)."""
        _, active, observable, _, _ = self._set()
        judged = self._judging()
        M, lev = self.Mc, self.levc
        out = judged & (level >= field)
        band = self.warn if field == WARNING else self.alarm
        X = self._X()
        r = (X - X @ M.T).mean(axis=0)
        z = np.where(active, np.abs(r) / np.sqrt(np.maximum(1 - lev, 1e-12)), -1.0)
        best, best_z = None, float(np.max(np.where(judged, z, -1.0)))
        for u in np.flatnonzero(active & ~observable & ~self.warn_only & (z > best_z)):
            trial = active.copy()
            trial[u] = False
            if trial.sum() < self.a["min_active"]:
                continue
            if (op := self._operator(~trial)) is None:
                continue
            Mu, lu = op
            jd = trial & (lu < self.max_lev) & ~self.warn_only
            if (out & ~jd).any():
                continue
            E = (X[:, jd] - X @ Mu[jd].T) / (1 - lu[jd])
            if (np.abs(E).min(axis=0) >= band[jd]).any():
                continue
            if z[u] > best_z:
                best, best_z = int(u), float(z[u])
        return best


@functools.lru_cache(maxsize=1024)
def _solved_operator(basis: bytes, shape: tuple, active_mask: bytes):
    """(cmon85) The served ``pod.operator`` of the set ``active_mask`` (bool bytes) of the basis
    ``basis`` (``shape``: sensors x modes), as the C solves it: ``r = min(modes, s)`` modes, (qr103)
    ``Q R`` of ``Phi_a`` (``s x r``) by Gram-Schmidt twice (``R^T R = G = Phi_a^T Phi_a``, G never
    formed: its condition is not squared), ``w_k`` Q's row for ``k`` in, ``R^-T phi_k`` for ``k``
    out, ``M[k, m] = w_k . w_m`` for ``m`` in, the leverage ``w_k . w_k`` (1 out); None where
    ``Phi_a`` is rank-deficient (``R[p, p]^2`` within 1e-12 of column ``p``'s squared norm
    ``G[p, p]``: the Cholesky pivot test it replaced)."""
    # memoized by the basis's and the set's bytes: the mirror asks for the same few sets on many
    # rows (a sensor out for a stretch), and these loops are the C's order, slow in Python (ci101)
    active = np.frombuffer(active_mask, bool)
    n, ins = shape[0], np.flatnonzero(active)
    r = min(shape[1], len(ins))
    phi = np.frombuffer(basis).reshape(shape).tolist()   # (python floats: the C's order)
    W = [[0.0] * r for _ in range(n)]
    g = [0.0] * r
    for i in ins:
        for p in range(r):
            W[i][p] = phi[i][p]
            g[p] += W[i][p] * W[i][p]
    R = [[0.0] * r for _ in range(r)]
    for q in range(r):
        for _ in range(2):          # twice: Q's columns orthonormal to rounding (once: eps cond)
            for p in range(q):
                v = 0.0
                for i in ins:
                    v += W[i][p] * W[i][q]
                R[p][q] += v
                for i in ins:
                    W[i][q] -= v * W[i][p]
        v = 0.0
        for i in ins:
            v += W[i][q] * W[i][q]
        if not v > 1e-12 * max(g[q], 1e-300):
            return None
        R[q][q] = math.sqrt(v)
        for i in ins:
            W[i][q] /= R[q][q]
    for k in np.flatnonzero(~active):   # the rows in keep Q's: R^-T phi_k would undo it
        for p in range(r):
            v = phi[k][p]
            for c in range(p):
                v -= R[c][p] * W[k][c]
            W[k][p] = v / R[p][p]
    M, lev = np.zeros((n, n)), np.ones(n)
    for k in range(n):
        for m in ins:
            v = 0.0
            for p in range(r):
                v += W[k][p] * W[m][p]
            M[k, m] = v
        if active[k]:
            lev[k] = M[k, k]
    M.flags.writeable = lev.flags.writeable = False     # shared by every caller of the memo
    return M, lev
