"""A logger set to another sample rate inside one file (1 min, then 10 s from some row on), or
writing no row for a while (a gateway's outage): said, not refused (the contract's time need not
be uniform), naming the row where the rate changes or the rows stop.

A model whose lags and autoregressive term count samples (``arx``, ``lstm``) reads a sample as
one span of time on one side of that row and another span on the other, with nothing to say so.
``data.resample_s`` puts the record on one grid."""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np

from ...base.errors import position
from ...base.log import logger
from ..timerule import median_step
from .contract import TIME

# (data93) the rows-missing rule lives beside the pause rule, which a served session reads too;
# its periods re-exported here, where the machine client reads them
from .timestamps import GAP_PERIODS as GAP_PERIODS
from .timestamps import PAUSE_PERIODS as PAUSE_PERIODS
from .timestamps import row_gaps

RATE_CHANGE = 2.0    # the median steps before and after the change this far apart
SETTLED = 10         # steps at least on each side of a change
LEARNING_GAP = 2.0   # (con111) a stretch while the period is learned: this many times the other steps
SAID_AT_MOST = 5     # (dep107c) a stream's warnings of one kind per campaign (a jittery clock's gaps)
FOUND = {"period": "period changed", "gap": "rows missing"}    # a finding's event (``to``)


def period_groups(periods: Mapping[str, float]) -> dict[float, list[str]]:
    """``{period (3 digits): its campaigns}``, shortest first, of campaigns logged at sample
    periods (s, positive) :data:`RATE_CHANGE` times apart or more (a lab's runs at 10 s and at
    60 s); ``{}`` where they are not."""
    if not periods or max(periods.values()) / min(periods.values()) < RATE_CHANGE:
        return {}
    groups: dict[float, list[str]] = {}
    for cid, p in periods.items():
        groups.setdefault(float(f"{p:.3g}"), []).append(cid)
    return dict(sorted(groups.items()))


def said_if_rate_changes(seconds: np.ndarray, file, at: Callable[[int], str] = position) -> bool:
    """Say where the sample period of ``seconds`` (a campaign's time, s, increasing) changes
    once, the median steps before and after at least :data:`RATE_CHANGE` times apart (``at``:
    names a data row); whether it was said."""
    steps = np.diff(seconds)
    k = _change(steps)
    if k is None:
        return False
    before, after = float(np.median(steps[:k])), float(np.median(steps[k:]))
    if min(before, after) <= 0 or max(before, after) / min(before, after) < RATE_CHANGE:
        return False
    logger.warning(f"{file}, column {TIME!r}, {at(k + 2)}: the sample period changes from "
                   f"{before:g} s to {after:g} s here (the logger set to another rate?): a model "
                   "whose lags count samples (arx, lstm) reads a sample as "
                   f"{before:g} s before it and {after:g} s after; data.resample_s="
                   f"{max(before, after):g} puts the record on one grid")
    return True


def _change(steps: np.ndarray) -> int | None:
    """The step where the log of the steps shifts most (the largest two-sample statistic of
    their means: one pass of cumulative sums, a year at 1 s as fast as a day), at least
    :data:`SETTLED` steps from either end; None for a shorter record."""
    n = steps.size
    if n < 2 * SETTLED or not (steps > 0).all():
        return None
    logs = np.log(steps)
    k = np.arange(SETTLED, n - SETTLED + 1)
    head = np.cumsum(logs)[k - 1]
    shift = head / k - (logs.sum() - head) / (n - k)
    return int(k[np.argmax(np.abs(shift) * np.sqrt(k * (n - k)))])


# (data93) what a gap in a time of day without its date reads as as well: the clock cannot tell
# a day lost with the rows, nor, at a step of one period, a day lost between two rows at all
DAY_HIDDEN = ("; a time of day without its date: as well a day longer ({hours:.3g} h or more, "
              "the logger stopped overnight), no date to tell: give the date column with it")


def said_if_rows_missing(seconds: np.ndarray, file, at: Callable[[int], str] = position,
                         dateless: bool = False) -> None:
    """Say the stretches of ``seconds`` (a campaign's time, s, increasing) without rows
    (:func:`row_gaps`: a gateway's outage, a lost buffer; newmachine59's EDM lost 7 and 25 min of
    rows and nothing said so).  A model whose lags count samples reads each as one period.
    (data93) ``dateless``: a time of day without its date (``data.time=of_day``, a clock header),
    whose gap reads as well a day longer (:data:`DAY_HIDDEN`): said so."""
    gaps = row_gaps(seconds)
    if not gaps.size:
        return
    period, steps = median_step(seconds), np.diff(seconds)
    k = int(gaps[np.argmax(steps[gaps])])
    sizes = ", ".join(f"{steps[g] / period:.3g}" for g in gaps[:5]) + (", ..." if gaps.size > 5 else "")
    day = DAY_HIDDEN.format(hours=steps[k] / 3600 + 24) if dateless else ""
    logger.warning(f"{file}, column {TIME!r}: {gaps.size} stretch(es) without rows (steps of "
                   f"{sizes} sample periods of {period:g} s; the longest {steps[k] / 60:.3g} min, "
                   f"before {at(k + 2)}): a logger's outage? The lag bank and Hammerstein read "
                   "the time; a model whose lags count samples (arx, lstm) reads each as one "
                   f"period; data.resample_s={period:g} fills them by linear interpolation{day}")


class StepWatch:
    """(dep107c) The two rules above read one row at a time, as a stream must (the served model;
    ``stream.c`` holds the same rule, its ``watch_``): the file reader's words of a whole record
    came from neither.  A campaign's period is the median of its first :data:`SETTLED` steps;
    then the period changes where most of the last :data:`SETTLED` steps lie :data:`RATE_CHANGE`
    times from it on one side (named at the first of them, the new period their median, held
    from there); rows are missing where one step lies :data:`GAP_PERIODS` to :data:`PAUSE_PERIODS`
    periods long (not an hour and a period: daylight saving time) and the next is shorter than
    :data:`GAP_PERIODS` again (a run of long steps is a new rate, not a gap).  It says; it
    changes no correction.  (dep108e) ``hour_steps=False``: a clock without daylight saving time
    (an OPC UA server's, UTC): a step of an hour and a period is rows missing too.  (con111) While
    it learns the period, a step :data:`LEARNING_GAP` times the others read is a stretch: one in
    the first :data:`SETTLED` steps (but the first) is said as the file reader says it."""

    def __init__(self, hour_steps: bool = True) -> None:
        self.last, self.period = float("nan"), float("nan")
        self.hour_steps = hour_steps
        self.steps: list[tuple[int, float]] = []      # (row, step): the first, then the last ones
        self.gap: tuple[int, float] | None = None     # a long step waiting for the next
        self.said: dict[str, int] = {}                # (the caller's count of what it said)

    def read(self, time: float, row: int) -> list[tuple[str, int, float, float]]:
        """What row ``row`` at ``time`` (s) shows: ``("period", row, before, after)`` (s) and
        ``("gap", row, step, period)`` (s; ``row`` the first after the stretch)."""
        if not np.isfinite(time) or (np.isfinite(self.last) and time <= self.last):
            return []        # (a time missing or not after the last: the time rule's to say)
        step, self.last = time - self.last, time
        if not np.isfinite(step):
            return []
        self.steps.append((row, step))
        if not np.isfinite(self.period):
            return self._learning(row, step)
        period, found = self.period, []
        if self.gap is not None and step < GAP_PERIODS * period:
            found.append(("gap", *self.gap, period))
        self.gap = (row, step) if self.is_long(step, period) else None
        self.steps = self.steps[-SETTLED:]
        for changed in ([rs for rs in self.steps if rs[1] >= RATE_CHANGE * period],
                        [rs for rs in self.steps if rs[1] <= period / RATE_CHANGE]):
            if len(changed) > SETTLED // 2:
                self.period = float(np.median([s for _, s in changed]))
                found.append(("period", changed[0][0], period, self.period))
                self.steps, self.gap = [], None
                break
        return found

    def _learning(self, row: int, step: float) -> list[tuple[str, int, float, float]]:
        """(con111) A step read before the campaign's period is learned.  The step before it (but
        the campaign's first) is a stretch without rows where it is :data:`LEARNING_GAP` times the
        longest of the others read (the file reader's median is not known yet: a few steps of a
        jittery clock lie 1.5 times apart; a run of long steps is a new period), said as the file
        reader names it, its periods those of the others' median.  The period learned at
        :data:`SETTLED` steps, the last of them long waiting for the next as after.  Before,
        nothing was said here, while ``connect``'s ``clock_gap`` and the file reader said it."""
        found = []
        if len(self.steps) >= 3:
            (at, long), others = self.steps[-2], [s for _, s in self.steps[:-2]] + [step]
            period = float(np.median(others))
            if long >= LEARNING_GAP * max(others) and self.is_long(long, period):
                found.append(("gap", at, long, period))
        if len(self.steps) == SETTLED:
            self.period, self.steps = float(np.median([s for _, s in self.steps])), []
            self.gap = (row, step) if self.is_long(step, self.period) else None
        return found

    def is_long(self, step: float, period: float) -> bool:
        """Whether ``step`` (s) is a stretch without rows at ``period``: not a pause, nor (where
        the clock keeps daylight saving time) an hour and a period."""
        dst = self.hour_steps and abs(step - 3600.0 - period) <= period / 2
        return bool(GAP_PERIODS * period <= step <= PAUSE_PERIODS * period) and not dst


def found_words(kind: str, was: float, now: float) -> str:
    """(dep108b) What a stream says of a :meth:`StepWatch.read` finding (its ``kind``, then its
    last two figures, s): the served model's and ``connect``'s words, one text."""
    if kind == "period":
        return (f"the sample period changes from {was:g} s to {now:g} s here (the logger set to "
                "another rate?): a model whose lags count samples (arx, lstm) reads a sample as "
                f"{was:g} s before it and {now:g} s after")
    return (f"{was / now:.3g} sample periods of {now:g} s without rows before this one (a "
            "logger's outage?): a model whose lags count samples (arx, lstm) reads them as "
            "one period")
