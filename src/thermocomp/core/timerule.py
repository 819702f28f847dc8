"""The rule for a sample's time, one definition for every streamed form: an estimator's own
``stream_step`` (:func:`step_time`, e.g. the lag bank's), the plain and the adaptive
compensator (:class:`SampleClock`), the exported Simulator (same class), and the C and
Structured Text code (:data:`C_TIME_RULE`, :data:`ST_TIME_RULE`, the same steps in those
languages, rendered into ``compensator.c`` and ``compensator.st``; the export tests run every
form against the others).

* A sample with no time (``judge``: or one not after the last time read) is one ``period``
  (the training sample period, saved with the model) after the previous sample.
* A campaign's first sample with no time is at 0 of the stream's clock, and the steps count
  from it: the first time read after it lies one period per sample after it, and every later
  time keeps that offset.  On a logger's clock (150030 s, ...) the stream then steps as the
  complete record does (its first time 150000 s); taking the first time as 0.0 had put
  150030 s between the first two samples and thrown every lag state a day ahead.

* (restart66) A time not after the last one read, then a time after it that is still not after
  the last one read, is a clock that restarted (the next file of a record whose time starts
  again at 0, each file's logger run from 0; a clock set back for good): the first of them
  stays one ``period`` after the previous sample, and the stream counts on from it by the new
  clock's steps.  That is what ``run``, ``replay`` and the check pack do where a file that
  continues another (the manifest's ``continues``) starts its time again: the two joined one
  period apart, the file's own steps after.  Judged against the last time read only, the
  restarted clock's times were taken as one period each until they passed it, then read as
  they were: a step back by all of them (dt < 0, the lag bank's ``exp(-dt/tau)`` growing).  A
  lone time set back (the next time after the last read again) stays a missing one.

A reader that has the whole record takes such a first time as the next time read less one
period per sample: the same steps (:func:`stream_start` says where the stream's clock starts).

* (dup99) A row written again -- its time not after the last one read and every input equal to
  those of the last sample stepped on in the campaign (a logger re-sending its last sample) -- is
  no new sample (:func:`repeats`, :data:`C_REPEAT_RULE`, :data:`ST_REPEAT_RULE`): the stream
  that skips repeats (the adaptive compensator's; ``skip_repeats`` in the code) takes it before
  this rule, nothing remembered changes and the last corrections are given again.  The record
  scored has no such row (the contract refuses a time that repeats: the row written twice is to
  be deleted), so skipping it is what ``run`` scored.  A repeated time with other values stays a
  sample, one period on; a stream without a time cannot tell a re-sent row from a machine
  standing still (``run`` scores every row of such a file), and steps it.

The period is the training's sample period, :func:`median_step` of its times: the one
definition every reader, model and report of a time column's period uses.
"""

from __future__ import annotations

import math

import numpy as np

# a campaign's start, as SampleClock.snapshot: (first, t, t_read, shift, back)
CLOCK_START = (True, math.nan, math.nan, math.nan, math.nan)


def step_time(clock: tuple, time: float, period_s: float, judge: bool = False
              ) -> tuple[tuple, float, float, str | None]:
    """One sample of the rule on a clock's state ``(first, t, t_read, shift, back)``
    (:data:`CLOCK_START` at a campaign's start; ``back``: the previous row's time where it was not
    after the last one read, else NaN; a state of four, saved before restart66, has none):
    ``(new clock, t, dt, why)`` as :meth:`SampleClock.step` returns them."""
    first, t_prev, t_read, shift = clock[:4]
    back = clock[4] if len(clock) > 4 else math.nan
    why, restarted = None, False
    if not math.isfinite(time):
        why = "time has no finite value"
    elif judge and math.isfinite(t_read) and time <= t_read:
        # after a time not after the last read, a time after that one: a clock that restarted
        restarted = math.isfinite(back) and time > back
        if not restarted:
            why = f"time {time:.6g} s does not increase (previous {t_read:.6g} s)"
    if why is None:
        t_read = time
        if restarted:                     # counted on from the previous row (one period in)
            shift = back - t_prev
        elif not math.isfinite(shift):    # the first time read sets the clock
            shift = 0.0 if first else time - (t_prev + period_s)
        now = time - shift
        back = math.nan
    else:
        now = 0.0 if first else t_prev + period_s
        back = time if math.isfinite(time) and not first else math.nan
    dt = math.nan if first else now - t_prev
    return (False, now, t_read, shift, back), now, dt, why


def repeats(clock: tuple, time: float, x: np.ndarray, last: np.ndarray | None) -> bool:
    """(dup99) Whether a sample is a row written again (module doc): on a clock's state ``clock``
    (:meth:`SampleClock.snapshot`) its ``time`` finite and not after the last time read, and
    its inputs ``x`` every one equal to ``last``, those of the last sample stepped on in the
    campaign (None: none yet; a missing value, NaN, equals nothing)."""
    first, _, t_read = clock[:3]
    return (not first and last is not None and math.isfinite(time) and math.isfinite(t_read)
            and time <= t_read and bool(np.all(np.asarray(x) == last)))


class SampleClock:
    """The stream's clock: ``step(time)`` -> ``(t, dt, why)``, ``t`` the sample's time on the
    stream's clock, ``dt`` the step from the previous sample (NaN at a campaign's first), ``why``
    the reason the time read was not used (None when it was)."""

    def __init__(self, period_s: float, judge: bool = True):
        self.period_s, self.judge = float(period_s), bool(judge)
        self.reset()

    def reset(self) -> None:
        """A new campaign: the next sample is its first."""
        self.restore(CLOCK_START)

    def snapshot(self) -> tuple:
        return self.first, self.t, self.t_read, self.shift, self.back

    def restore(self, snap: tuple) -> None:
        """``snap``: a :meth:`snapshot` (of four, saved before restart66: no time set back)."""
        self.first, self.t, self.t_read, self.shift = snap[:4]
        self.back = snap[4] if len(snap) > 4 else math.nan

    def step(self, time: float) -> tuple[float, float, str | None]:
        clock, now, dt, why = step_time(self.snapshot(), time, self.period_s, self.judge)
        self.restore(clock)
        return now, dt, why


def stream_start(time, period_s: float) -> float:
    """Where the stream's clock puts a campaign's first sample, on the clock of its ``time``
    column (NaN where missing): its own time, else the first time read less one period per
    sample before it (0 without any time)."""
    for i, t in enumerate(time):
        if math.isfinite(t):
            return float(t) - i * period_s
    return 0.0


# steps within this share of the median are one period written with a clock's resolution
NEAR_MEDIAN = 0.05
# a spread of the steps near the median below this share of it (of 1 s for a shorter one) is
# a float grid's rounding: epoch seconds (1.7e9 s) hold steps to ~2.4e-7 s
GRID_ROUNDING = 1e-6


def median_step(time, groups=None) -> float | None:
    """The sample period of a time column: the median of its positive steps.

    Parameters
    ----------
    time : array-like of float, or a list of them
        Times (s); a list holds one column per campaign.
    groups : array-like, optional
        The campaign of each row of ``time`` (one column): no step joins two segments (runs
        of consecutive rows with the same label), as none joins two columns of a list.

    Returns
    -------
    float or None
        The median of the finite positive steps within the campaigns (where the steps within
        5 % of it differ by more than rounding, a clock's resolution, their mean): a time that goes back
        (a new run), repeats, or is missing (NaN) makes no step.  None without one such step
        (one row, a time never increasing): the caller says its fallback (``or 1.0``).
    """
    if isinstance(time, (list, tuple)) and time and np.ndim(time[0]):
        steps = np.concatenate([np.diff(np.asarray(t, dtype=float)) for t in time])
    else:
        time = np.asarray(time, dtype=float)
        steps = np.diff(time)
        if groups is not None:
            g = np.asarray(groups)
            if len(g) != len(time):
                raise ValueError(f"groups has {len(g)} rows, time {len(time)}")
            steps = steps[g[1:] == g[:-1]]
    steps = steps[np.isfinite(steps) & (steps > 0)]
    if not steps.size:
        return None
    middle = float(np.median(steps))
    # A clock written with few decimals jitters around its period by its resolution (elapsed
    # hours to 4 places: steps of 59.76 and 60.12 s for a 60 s logger, the median 60.12; a
    # stranger64 finding): the mean of the steps near the median is the period. On a grid the
    # steps near it are equal to rounding and the median stays, bit for bit.
    near = steps[np.abs(steps - middle) <= NEAR_MEDIAN * middle]
    if near.size and np.ptp(near) > GRID_ROUNDING * max(middle, 1.0):
        return float(near.mean())
    return middle


# The same steps in C (tc_step: ``time`` NAN when missing; state s->t, s->t_read, s->shift).
C_TIME_RULE = """\
    /* the time rule (timerule.py): a missing time (TC_SUBSTITUTE_TIME: or one not after the
       last one read) is one TIME_PERIOD after the previous sample; a first one, 0, and the
       first time read then counts from it */
    if (s->first) { s->t_read = NAN; s->shift = NAN; s->t_back = NAN; }
    if (isfinite(time) && TC_SUBSTITUTE_TIME && isfinite(s->t_read) && time <= s->t_read
        && isfinite(s->t_back) && time > s->t_back) {
        /* (restart66) after a time not after the last read, one after that: a clock restarted
           (the next file's time from 0), counted on from the previous row */
        s->t_read = time;
        s->shift = s->t_back - s->t;
        now = time - s->shift;
        s->t_back = NAN;
    } else if (isfinite(time) && !(TC_SUBSTITUTE_TIME && isfinite(s->t_read)
                                   && time <= s->t_read)) {
        s->t_read = time;
        if (!isfinite(s->shift)) s->shift = s->first ? 0.0 : time - (s->t + TIME_PERIOD);
        now = time - s->shift;
        s->t_back = NAN;
    } else {
        now = s->first ? 0.0 : s->t + TIME_PERIOD;
        s->t_back = (isfinite(time) && !s->first) ? time : NAN;
    }
    dt = s->first ? NAN : now - s->t;
"""

# (dup99) :func:`repeats` in C, before anything of tc_step (TC_SKIP_REPEATS; state s->u_last,
# the inputs of the last sample stepped on, s->repeated, s->n_repeated).
C_REPEAT_RULE = """\
    /* (dup99) a row written again (timerule.repeats): its time not after the last one read and
       every input equal to the last sample's stepped on (a NAN equals nothing) is no new sample:
       skipped, nothing remembered changes, c the last corrections given */
    s->repeated = TC_SKIP_REPEATS && !s->first && isfinite(time) && isfinite(s->t_read)
                  && time <= s->t_read;
    for (j = 0; j < TC_N_INPUTS && s->repeated; j++)
        if (!(u[j] == s->u_last[j])) s->repeated = 0;
    if (s->repeated) {
        s->n_repeated++;
        s->refused = 0;
        for (i = 0; i < TC_N_OUTPUTS; i++) c[i] = s->c[i];
        return 0;
    }
"""

# ... in Structured Text, around the whole scan (``IF NOT repeated THEN`` ... ``END_IF;``).
ST_REPEAT_RULE = """\
(* (dup99) a row written again (timerule.repeats): its time not after the last one read and every *)
(* input equal to the last sample's stepped on is no new sample: skipped, nothing remembered *)
(* changes, c keeps the last corrections *)
repeated := SKIP_REPEATS AND NOT first AND has_time AND read_valid;
IF repeated THEN
    repeated := time_s <= t_read;
END_IF;
FOR j := 0 TO N_INPUTS - 1 DO
    IF repeated AND NOT (u[j] = u_last[j]) THEN
        repeated := FALSE;
    END_IF;
END_FOR;
IF repeated THEN
    n_repeated := n_repeated + 1;
    n_clamped := 0;
    refused := FALSE;
END_IF;
"""

# The same steps in Structured Text (no NaN: ``has_time``, ``read_valid``, ``shift_valid``).
ST_TIME_RULE = """\
(* the time rule (timerule.py): a missing time (SUBSTITUTE_TIME: or one not after the last read) *)
(* is one TIME_PERIOD after the previous sample; a first one, 0: the first time read counts from it *)
IF first THEN
    read_valid := FALSE;
    shift_valid := FALSE;
    back_valid := FALSE;
END_IF;
(* after a time not after the last read, one after that: a clock restarted, counted on *)
IF has_time AND SUBSTITUTE_TIME AND read_valid AND time_s <= t_read AND back_valid AND time_s > t_back THEN
    t_read := time_s;
    shift := t_back - t_prev;
    shift_valid := TRUE;
    now := time_s - shift;
    back_valid := FALSE;
ELSIF has_time AND NOT (SUBSTITUTE_TIME AND read_valid AND time_s <= t_read) THEN
    t_read := time_s;
    read_valid := TRUE;
    IF NOT shift_valid THEN
        IF first THEN
            shift := 0.0;
        ELSE
            shift := time_s - (t_prev + TIME_PERIOD);
        END_IF;
        shift_valid := TRUE;
    END_IF;
    now := time_s - shift;
    back_valid := FALSE;
ELSE
    IF first THEN
        now := 0.0;
    ELSE
        now := t_prev + TIME_PERIOD;
    END_IF;
    t_back := time_s;
    back_valid := has_time AND NOT first;
END_IF;
IF first THEN
    dt := 0.0;
ELSE
    dt := now - t_prev;
END_IF;
"""


# -- the training grid (cadence72) ---------------------------------------------------------------

def on_grid(elapsed, step, period_s: float):
    """Whether the models step on a sample ``elapsed`` seconds after the last one they stepped
    on and ``step`` after the previous sample (arrays element-wise).  A model with a memory
    (ARX's history, a lag bank's feedback and its lags' hold of each input over the step before
    it) answers for the period it was fitted at: a lag bank fitted on 300 s rows and fed 60 s
    ones was 10.2 µm off its own 300 s answer (rate71).  A sample of a FASTER stream, a step
    of at most half a training ``period_s``, is held unless it is the one nearest a period on
    (the first at least ``period_s - step / 2`` after the last stepped); every other sample is
    stepped as it comes: the training period, a slower stream, a clock's jitter, a gap, a
    repeated or substituted time (a step of 0), a missing one (NaN)."""
    elapsed, step = np.asarray(elapsed), np.asarray(step)
    with np.errstate(invalid="ignore"):
        return np.logical_not((step > 0) & (step <= period_s / 2) & (elapsed + step / 2 < period_s))


def grid_rows(time, groups, period_s: float) -> np.ndarray:
    """Per row, whether the model steps on it (:func:`on_grid`), each segment of ``groups`` a
    stream from its first row, the times on the stream's clock (:func:`step_time`: a missing
    or repeated time one period on).  All True where every step is over half a period."""
    time = np.asarray(time, dtype=float)
    n = len(time)
    steps = np.diff(time)
    with np.errstate(invalid="ignore"):       # after a stepped row each step is its elapsed
        each = on_grid(steps, steps, period_s) & (steps > 0)
    quick = bool(each.all())
    if groups is not None and not quick:
        g = np.asarray(groups)
        quick = bool(np.all(each | (g[1:] != g[:-1])))
    stepped = np.ones(n, dtype=bool)
    if quick or n < 2:
        return stepped
    starts = np.r_[True, np.asarray(groups)[1:] != np.asarray(groups)[:-1]] if groups is not None \
        else np.r_[True, np.zeros(n - 1, bool)]
    clock, grid = CLOCK_START, math.nan
    for i in range(n):
        if starts[i]:
            clock = CLOCK_START
        clock, now, dt, _ = step_time(clock, float(time[i]), period_s, judge=True)
        if starts[i] or bool(on_grid(now - grid, dt, period_s)):
            grid = now
        else:
            stepped[i] = False
    return stepped
