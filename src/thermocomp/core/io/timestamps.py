"""How a ``time`` column of text is read: ISO 8601, a lab's day-first ``28.11.2026 13:05:00``
(dots: the European order, never month first; Excel's two-digit year ``28.11.26 13:05`` too),
the strptime format ``data.time`` names, or a logger's elapsed time ``25:30:00`` (``h:mm:ss``,
hours past 24: :func:`elapsed_seconds`).
A date with slashes (``03/11/2026``) is day-first in Europe and month-first in the US: never
guessed, refused naming ``data.time``; where a field is past 12 (``15/06/2026``) the order is no
guess, and the date is read so (:func:`slashed_format`); so is a Keysight DAQ's ``Time``,
``MM/DD/YYYY HH:MM:SS:mmm``, its milliseconds after a colon (keysight70)."""

from __future__ import annotations

import re
from datetime import datetime, timedelta, timezone
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.compute as pc

from ...base.errors import position
from ...base.log import logger
from ..timerule import median_step
from .contract import TIME, ContractError
from .dayfirst import ORDER
from .units import UNITS

# a first cell that is a date and a time of day (the time column when no header says so)
_STAMP = re.compile(r"\s*\d{1,4}[-./]\d{1,2}[-./]\d{2,4}[T ]\d\d?:\d\d")
_DAY_FIRST = re.compile(r"\s*\d{1,2}\.\d{1,2}\.(?P<y>\d{4}|\d\d)[ T]\d{1,2}:\d\d"
                        r"(?P<s>:\d\d([.,:]\d+)?)?\s*")
_SLASHED = re.compile(r"\s*\d{1,2}/\d{1,2}/\d{2,4}\b")
_SLASHED_STAMP = re.compile(r"\s*(?P<a>\d{1,2})/(?P<b>\d{1,2})/(?P<y>\d{4}|\d\d)(?P<sep>[ T])"
                            r"\d{1,2}:\d\d(?P<s>:\d\d([.,:]\d+)?)?\s*")
_KEYSIGHT_MS = re.compile(r"\d:\d\d:\d\d:\d{3}\s*$")     # HH:MM:SS:mmm, a Keysight DAQ's Time
DATE = re.compile(r"\s*(\d{1,2}\.\d{1,2}\.(\d{4}|\d\d)|\d{4}-\d\d-\d\d|\d{1,2}/\d{1,2}/\d{2,4})\s*")
TIME_OF_DAY = re.compile(r"\s*\d{1,2}:\d\d(:\d\d([.,:]\d+)?)?\s*")
_ZONE_OFFSET = re.compile(r"\d:\d\d(?::\d\d(?:[.,]\d+)?)?\s*(?:Z|[+-]\d\d(?::?\d\d)?)$")
COMMA_FRACTION = r"(\d:\d\d:\d\d),(\d)"     # a second's fraction after a comma
FRACTION = r"\d:\d\d:\d\d[.,:](?P<f>\d{1,9})"   # a second's fraction (Keysight's after a colon)
EXAMPLE = "'%d/%m/%Y %H:%M:%S'"
CLOCK = " time of day"       # the column joined to the date (data.roles.time: [date, time]); no
# contract name has a space
ELAPSED = "elapsed"          # data.time: h:mm:ss since the start, the hours past 24
# (data91) data.time: a time of day without its date, seconds since midnight (or h:mm:ss), read
# by the time of day's rule whatever its header or its steps say (:func:`seconds_of_day`)
OF_DAY_KIND = "of_day"
_ELAPSED = re.compile(r"\s*(?P<h>\d+):(?P<m>[0-5]\d):(?P<s>[0-5]\d(?:[.,]\d+)?)\s*")
# a time column's header that says it holds an elapsed time (the word, or a unit after it)
ELAPSED_HEADERS = frozenset({"elapsed", "elapsed time", "elapsed_time", "duration", "dauer",
                             "laufzeit", "verstrichene zeit"})
# (data92b) a time column's header that names the time of day, its h:mm:ss read by data.time=of_day
# (:func:`names_time_of_day`): the time-of-day column of the date + time pairs loggers write in
# their language, `Datum;Uhrzeit`, `Date;Heure`, `Fecha;Hora`, `Data;Ora`, `日付;時刻`, and the
# English words.  Not 'time' nor 'Zeit' (an elapsed h:mm:ss as often), nor a bare 'clock' (a
# CPU's 'Clock [MHz]' reads as a time header then)
CLOCK_HEADERS = frozenset({"uhrzeit", "tageszeit", "time of day", "time_of_day", "timeofday",
                           "clock time", "heure", "hora", "ora", "時刻", "时刻"})


def looks_like_timestamp(text) -> bool:
    """A date followed by a time of day, in any of the orders :func:`time_kind` knows of."""
    return bool(_STAMP.match(str(text or "")))


def written_seconds(cell) -> float:
    """(con109) A time cell as it is written, in s: a number as it is, an ``h:mm:ss`` its seconds
    on the clock (no day added past midnight); NaN for anything else (a date and time)."""
    try:
        return float(cell)
    except (TypeError, ValueError):
        hms = _ELAPSED.fullmatch(str(cell))
    if hms is None:
        return float("nan")
    return int(hms["h"]) * 3600.0 + int(hms["m"]) * 60.0 + float(hms["s"].replace(",", "."))


def maybe_elapsed(value: str, kind: str) -> bool:
    """The time column's first cell may start an elapsed time (``h:mm:ss``): ``data.time``
    ``elapsed``, or ``auto``, the whole column telling it from a time of day
    (:func:`elapsed_seconds`); (data91) or ``of_day``'s ``h:mm:ss``, read there as a time of
    day."""
    return kind == ELAPSED or kind in ("auto", OF_DAY_KIND) and bool(_ELAPSED.fullmatch(value))


def elapsed_seconds(text, kind: str, path: Path, header: str | None = None,
                    stream: bool = False, unwrap: bool = True, carried: list | None = None):
    """A time column of text (``h:mm:ss``, a fraction of a second after ``.`` or ``,``) as a
    duration (ns: the report says ``elapsed``), read so where it cannot be a time of day:
    ``data.time=elapsed``, a header saying so (:data:`ELAPSED_HEADERS`: ``Dauer``, ``elapsed
    time``), or an hour past 23 in the column.  Else refused as a time of day
    (:func:`time_kind`) naming ``data.time`` (a ``stream``'s: what its time must be), unless it
    passes midnight (:func:`past_midnight`: a file's and, data89, a stream's rows alike;
    ``unwrap=False``, a served model's block read alone, never); a cell that is no ``h:mm:ss``
    is refused with its row.  (data89b) A file's pauses are said here, once each, as what
    reads each run as a campaign (:func:`_said_pauses`): ``data.runs_at_pauses`` cannot split a
    time written as text, and the record's own pause warning leaves such a time to this one.
    (data91) ``carried``: a served session's time of day, continued (:func:`continued`), its
    block read as the rows of a file go on, not alone."""
    parts = pc.extract_regex(text, f"^{_ELAPSED.pattern}$")
    hours = pc.cast(pc.struct_field(parts, "h"), pa.float64())
    seconds = pc.cast(pc.replace_substring(pc.struct_field(parts, "s"), ",", "."), pa.float64())
    minutes = pc.cast(pc.struct_field(parts, "m"), pa.float64())
    total = pc.add(pc.add(pc.multiply(hours, 3600.0), pc.multiply(minutes, 60.0)), seconds)
    if kind == "auto" and names_time_of_day(header):
        kind = OF_DAY_KIND     # (data92b) its header says so, as the key does
    said = kind == ELAPSED or (header is not None and _bare(header) in ELAPSED_HEADERS
                               and kind != OF_DAY_KIND)
    past_a_day = (pc.max(hours).as_py() or 0) >= 24       # (an elapsed time's hours only)
    if kind == OF_DAY_KIND and past_a_day:
        row = int(np.argmax(hours.to_numpy(zero_copy_only=False) >= 24))
        raise ContractError(f"value {text[row].as_py()!r} is no time of day (data.time="
                            f"{OF_DAY_KIND}): an elapsed time? data.time={ELAPSED}", file=path,
                            column=TIME, row=row + 1)
    if carried is not None and not said and not past_a_day:
        # (data91) a served session's time of day: what it read before tells the days
        total = continued(total, carried, path)
    elif kind == OF_DAY_KIND:       # (data91) said a time of day: one that never wraps is one
        unwrapped = past_midnight(total, path, header) if unwrap else None
        total = total if unwrapped is None else unwrapped
    elif not said and not past_a_day:
        total = past_midnight(total, path, header) if unwrap else None
        if total is None:       # a time of day that never wraps: no date, nothing to unwrap
            first = text.filter(text.is_valid())
            time_kind(first[0].as_py().strip() if len(first) else "", "auto", False, path, header,
                      stream)
    elif not stream:       # (data89b) a stream's rows come a block at a time: no pause to tell
        values = total.to_numpy(zero_copy_only=False).astype(float)
        valid = np.flatnonzero(~np.isnan(values))
        _said_pauses(values[valid], valid, Path(path).name, repr(header) if header else TIME,
                     clock=False)
    bad = pc.and_(text.is_valid(), parts.is_null()).to_numpy(zero_copy_only=False)
    if bad.any():
        row = int(np.argmax(bad))
        raise ContractError(f"value {text[row].as_py()!r} is not an elapsed time h:mm:ss (hours "
                            "may pass 24)", file=path, column=TIME, row=row + 1)
    return pc.cast(pc.round(pc.multiply(total, 1e9)), pa.int64()).cast(pa.duration("ns"))


DAY_S = 86400.0


def past_midnight(seconds: pa.Array, path: Path, header: str | None = None,
                  pauses_said: bool = True) -> pa.Array | None:
    """(extension, data88b) A time of day without its date (``seconds`` since midnight, null
    where a cell is missing or no ``h:mm:ss``) as a continuing time: a day added at each step
    back of more than half a day between consecutive valid rows (the clock passing midnight,
    ``23:55:00`` then ``00:00:00``); None where no step goes back so.  The rows' own times
    are kept, so a sample a logger skipped stays skipped (timing the rows by their period
    closed the gap); any other step back stays, for the reader to refuse ("time decreases").
    Each step is read as the shorter way round the clock: one of half a day or more forward
    reads as well as a step back past midnight and is refused (file, column, row); a pause of
    a day or more between two rows cannot be told from the clock alone: (data89) a pause, a
    step of :data:`PAUSE_PERIODS` sample periods or more, is warned of with its row, as well
    a day (or more) longer, naming the date column that tells; not where ``pauses_said`` is False
    (lead90: the pauses ``data.runs_at_pauses`` splits the record at, each run a campaign)."""
    values = seconds.to_numpy(zero_copy_only=False).astype(float)
    valid = np.flatnonzero(~np.isnan(values))
    steps = np.diff(values[valid])
    wraps = steps < -DAY_S / 2
    if not wraps.any():
        return None
    if (far := np.flatnonzero(steps >= DAY_S / 2)).size:
        k = valid[far[0] + 1]
        raise ContractError(f"a time of day without its date that passes midnight steps "
                            f"{steps[far[0]] / 3600:.3g} h forward here: as well "
                            f"{(DAY_S - steps[far[0]]) / 3600:.3g} h back (no date to tell): "
                            "give the date column with it, data.roles.time=[<date column>, "
                            f"{repr(header) if header else '<this column>'}]",
                            file=path, column=TIME, row=int(k) + 1)
    days = np.zeros(len(values))
    days[valid[1:]] = np.cumsum(wraps) * DAY_S
    name = Path(path).name        # (a stream's: <stdin>)
    column = repr(header) if header else TIME
    logger.info(f"{name}: {column} is a time of day that passes midnight {int(wraps.sum())} "
                "time(s) (no date): read as a continuing time, a day added at each")
    if pauses_said:
        _said_pauses(values[valid] + days[valid], valid, name, column)
    return pa.array(values + days, from_pandas=True)


def continued(seconds: pa.Array, carried: list, path: Path) -> pa.Array:
    """(data91) A served block's time of day without its date (``seconds`` since midnight) as
    its session's continuing time: the block read after the last time of day the session read,
    by the file's rule (:func:`past_midnight`: a day added at each step back by more than half a
    day, a step of half a day or more forward refused), so a stream of blocks passing midnight
    reads as the rows of one file do (it was refused, each block read alone).  ``carried``: the
    session's ``[last time of day read (s; NaN: none yet), days added (s)]``, updated in place
    (the caller keeps it only where the block is taken).  A block whose time never passes
    midnight is read as it is, hours past 24 being the elapsed time's (:func:`elapsed_seconds`)."""
    last, added = carried
    raw = seconds.to_numpy(zero_copy_only=False).astype(float)
    joined = pa.array(np.concatenate([[last], raw]), from_pandas=True)
    unwrapped = past_midnight(joined, path, pauses_said=False)
    values = (joined if unwrapped is None else unwrapped).to_numpy(zero_copy_only=False)[1:] + added
    valid = np.flatnonzero(~np.isnan(raw))
    if valid.size:
        if not np.isnan(last):
            _said_session_pause(np.concatenate([[last + added], values]), valid)
        carried[:] = [raw[valid[-1]], values[valid[-1]] - raw[valid[-1]]]
    return pa.array(values, from_pandas=True)


def _said_session_pause(seconds: np.ndarray, valid: np.ndarray) -> None:
    """(data92) Warn of a pause in a served session's time of day (``seconds``: the last time
    it read, then the block's continuing times; ``valid``: the block's rows with a time), by the
    file's rule (:func:`pauses`): read as the clock says, but it reads as well a day or more
    longer (the machine stopped overnight between two blocks), which no time of day tells, as
    a file's dateless clock is warned of (:func:`_said_pauses`).  (data93) Rows missing too
    (:func:`row_gaps`, fewer than :data:`PAUSE_PERIODS`: a block resuming 30 min on may
    as well resume a day and 30 min on); a day lost at a step of one period shows nowhere."""
    timed = np.concatenate([[0], valid + 1])
    found = np.union1d(pauses(seconds[timed]), row_gaps(seconds[timed]))
    if not found.size:
        return
    k = int(found[0])
    step = seconds[timed[k + 1]] - seconds[timed[k]]
    where = "since the session's last block" if k == 0 else "within the block"
    logger.warning(f"served session, data row {int(valid[k]) + 1} of the block: the time of day "
                   f"pauses {step / 3600:.3g} h {where}: read so, but as well {step / 3600 + 24:.3g} "
                   "h or more, a day lost (no date to tell): send the time with its date (a "
                   "timestamp) where a day may pass between blocks, or reset=true to start a new "
                   "campaign")


PAUSE_PERIODS = 100   # a record silent this many sample periods: runs joined in one file?
GAP_PERIODS = 1.5     # a step this many sample periods or more: rows not logged
OF_DAY = "seconds of day"   # (data89b) the report's time of seconds since midnight, unwrapped
# (data89b) a numeric time column's header that says it holds seconds since midnight
OF_DAY_HEADERS = frozenset({"seconds of day", "second of day", "seconds of the day", "sec of day",
                            "secs of day", "seconds since midnight", "daysec", "day seconds",
                            "tagessekunden", "sekunden seit mitternacht", "sekunde des tages"})


def pauses(seconds: np.ndarray) -> np.ndarray:
    """The steps of ``seconds`` (a record's time, s, increasing) longer than
    :data:`PAUSE_PERIODS` of its median period: where one file's runs, appended, join (index
    ``i``: between rows ``i`` and ``i + 1``).  The one rule of the pause warning, of
    ``data.runs_at_pauses`` and of ``init`` proposing it."""
    period = median_step(seconds)
    if not period or len(seconds) < 3:
        return np.array([], int)
    return np.flatnonzero(np.diff(seconds) > PAUSE_PERIODS * period)


def row_gaps(seconds: np.ndarray) -> np.ndarray:
    """The steps of ``seconds`` (a time, s, increasing) of :data:`GAP_PERIODS` sample periods or
    more, up to :data:`PAUSE_PERIODS` (a pause, said on its own), but for an hour and a period
    (daylight saving time, said on its own): rows not logged (index ``i``: between rows ``i``
    and ``i + 1``)."""
    period = median_step(seconds)
    if period is None or period <= 0:
        return np.array([], int)
    steps = np.diff(seconds)
    return np.flatnonzero((steps >= GAP_PERIODS * period) & (steps <= PAUSE_PERIODS * period)
                          & ~skips_an_hour(steps, period))


def seconds_of_day(seconds: np.ndarray, path: Path, header: str | None = None,
                   pauses_said: bool = True, kind: str = "auto",
                   unit: str | None = None) -> np.ndarray | None:
    """(extension, data89b) A numeric time column of seconds since midnight, a logger's
    ``Seconds of day`` (77400 ... 86100, then 0, 300 ...), as a continuing time by the time of
    day's rule (:func:`past_midnight`: a day added at each step back by more than half a day):
    where all its values are within a day, [0, 86400) s, and its header says so
    (:data:`OF_DAY_HEADERS`) or its values do (:func:`over_midnight`); None otherwise (a step
    back is the reader's to refuse, "time decreases"), as where it never passes midnight;
    ``pauses_said``: its pauses warned of (:func:`past_midnight`).
    (data91) ``kind``, ``data.time``: ``of_day`` says it whatever the header (``t``, ``time``)
    and the steps (a logger paused over midnight: its step over it longer than any other): the
    values read so, those that never pass midnight as they are; a value outside a day refused
    with its row; (data94) ``unit``: the unit the column was written in (``data.units``' or its
    header's, :func:`.roles.time_unit`), the refused value named in it, as the lab wrote it
    (``25.25 h``, not the 90900 s it was converted to)."""
    finite = seconds[np.isfinite(seconds)]
    said = kind == OF_DAY_KIND
    if said and finite.size and (finite.min() < 0 or finite.max() >= DAY_S):
        row = int(np.argmax((seconds < 0) | (seconds >= DAY_S)))
        raise ContractError(no_time_of_day(seconds[row], unit, header), file=path,
                            column=TIME, row=row + 1)
    if not finite.size or finite.min() < 0 or finite.max() >= DAY_S:
        return None
    said = said or names_seconds_of_day(header)
    if not (said or over_midnight(finite)):
        return None
    unwrapped = past_midnight(pa.array(seconds, from_pandas=True), path, header,
                              pauses_said)
    if unwrapped is None:      # (data91: said by data.time, a record within one day is one)
        return seconds if kind == OF_DAY_KIND else None
    return unwrapped.to_numpy(zero_copy_only=False)


# (data94) the word a unit of time says a time of day in, its refusal naming the value in it
_OF_DAY_WORDS = {1.0: "second", 60.0: "minute", 3600.0: "hour"}


def no_time_of_day(seconds: float, unit: str | None, header: str | None) -> str:
    """What a refusal of ``seconds`` (read under ``data.time=of_day``) says, the value named as
    the lab wrote it, in ``unit`` (the column's, ``data.units``' or its header's: ``25.25 h``,
    not the 90900 s it was converted to; seconds where None or no time's unit), 12
    significant digits (the conversion's last bit is no digit the lab wrote)."""
    scale = UNITS["time"].get((unit or "s").lower().replace(" ", ""), (1.0, 0.0))[0]
    if scale == 1.0:
        return (f"value {seconds:g} s is no second of a day, [0, 86400) (data.time={OF_DAY_KIND}: "
                "seconds since midnight)")
    word = _OF_DAY_WORDS.get(scale, "time")
    return (f"value {seconds / scale:.12g} {unit} is no {word} of a day, [0, "
            f"{DAY_S / scale:.12g}) {unit} (data.time={OF_DAY_KIND}, data.units="
            f"{{{header!r}: {unit}}}: the time since midnight in {unit}; read as {seconds:g} s)")


def names_seconds_of_day(header: str | None) -> bool:
    """The header says seconds since midnight (:data:`OF_DAY_HEADERS`, its unit aside)."""
    return header is not None and _bare(header) in OF_DAY_HEADERS


def names_time_of_day(header: str | None) -> bool:
    """(data92b) The header names the time of day (:data:`CLOCK_HEADERS`, its unit aside): its
    ``h:mm:ss`` is read as ``data.time=of_day`` says, without a date column beside it."""
    return header is not None and _bare(header) in CLOCK_HEADERS


def names_day_seconds(headers: list) -> bool:
    """The lab's time headers say plain seconds of the day (one does, or a lone time of day: data92b)."""
    return any(names_seconds_of_day(str(h)) for h in headers) or (
        len(headers) == 1 and names_time_of_day(str(headers[0])))


HOURS_OF_DAY = 24.0


def hours_of_day(values: np.ndarray, header: str | None, unit: str | None) -> bool:
    """(extension, data93) A numeric time column under a time-of-day header
    (:func:`names_time_of_day`, ``Hora``), no unit in the header nor in ``data.units``
    (``unit``), whose values are mostly within a day's hours (their median below 24): a lab's
    decimal hours, ``21.5``, ``21.58`` ...  Read as seconds since midnight the record would lie
    within 24 s of midnight, no thermal test; the median, not every value, so that a cell
    past 24 is refused at its row once the unit is set (:func:`seconds_of_day`), not read as
    seconds with the rest."""
    finite = values[np.isfinite(values)]
    return (unit is None and names_time_of_day(header) and finite.size > 0
            and float(np.median(finite)) < HOURS_OF_DAY)


def day_fraction_too(values: np.ndarray) -> bool:
    """(data93) Decimal hours that may as well be a fraction of a day, as Excel stores a time
    (21:30 is 0.896): every value within [0, 1], a record within the hour after midnight read
    as hours, or a whole day read as a day's fraction; no step tells them apart."""
    finite = values[np.isfinite(values)]
    return bool(finite.size and finite.min() >= 0 and finite.max() <= 1)


def refuse_hours(values: np.ndarray, path: Path, header: str) -> None:
    """(data93) Refuse a time column :func:`hours_of_day` says holds hours, read without its
    unit (as seconds: a sample period of 0.083 s for a lab's every 5 min, refused at midnight),
    naming the keys that read it (``init`` writes them where no fraction of a day is as
    likely, :func:`day_fraction_too`)."""
    row = int(np.argmax(np.isfinite(values)))
    either = (f"; or a fraction of a day, as Excel stores a time (21:30 is 0.896): "
              f"data.units={{{header!r}: d}}" if day_fraction_too(values) else "")
    raise ContractError(f"value {values[row]:g} under a time-of-day header, no unit: read as "
                        "seconds since midnight the record would lie within 24 s of midnight; "
                        f"decimal hours (21.5 is 21:30)? data.units={{{header!r}: h}} data.time="
                        f"{OF_DAY_KIND}{either}", file=path, column=TIME, row=row + 1)


def over_midnight(seconds: np.ndarray) -> bool:
    """``seconds`` (within a day) step back by more than half a day, and each such step, a day
    added, is no longer than a step the clock takes elsewhere: a clock of the day's seconds
    passing midnight.  An elapsed time started again after half a day (a logger restarted:
    57000 s, then 0; as well 29400 s forward) is no such step, and stays refused (a header
    saying seconds of the day reads it, a pause at midnight warned of)."""
    steps = np.diff(seconds)
    back, forward = steps < -DAY_S / 2, steps > 0
    return bool(back.any() and forward.any()
                and np.all(steps[back] + DAY_S <= steps[forward].max()))


def _said_pauses(seconds: np.ndarray, rows: np.ndarray, name: str, column: str,
                 clock: bool = True) -> None:
    """(data89) Warn of the pauses of a dateless clock's continuing time (``seconds`` of the
    data rows ``rows``): a stretch of more than :data:`PAUSE_PERIODS` sample periods without
    rows (:func:`pauses`, the reader's one rule) is read as the clock says, but reads as well
    a whole day or more longer (the logger stopped overnight, or over a weekend): the date
    column tells, the clock cannot.
    (data89b) ``clock=False``: an elapsed ``h:mm:ss``, whose pause says runs joined in one
    file, what reads each as a campaign named (not ``data.runs_at_pauses``, which cannot
    split a time written as text)."""
    found = pauses(seconds)
    if not found.size:
        return
    steps, period = np.diff(seconds), median_step(seconds)
    k = int(found[0])
    if not clock:
        logger.warning(f"{name}, column {column}, {position(int(rows[k + 1]) + 1)}: the elapsed "
                       f"time pauses {steps[k] / 3600:.3g} h ({steps[k] / period:.0f} sample "
                       f"periods of {period:g} s{f'; {found.size} such pauses' if found.size > 1 else ''}"
                       "): runs joined in one file? One file per run in a folder, or a column "
                       "numbering the runs (data.roles.campaign=<header>), reads each as a "
                       "campaign (data.runs_at_pauses cannot split a time written as h:mm:ss)")
        return
    logger.warning(f"{name}, column {column}, {position(int(rows[k + 1]) + 1)}: the time of day "
                   f"pauses {steps[k] / 3600:.3g} h ({steps[k] / period:.0f} sample periods of "
                   f"{period:g} s{f'; {found.size} such pauses' if found.size > 1 else ''}): "
                   f"read so, but as well {steps[k] / 3600 + 24:.3g} h or more, a day lost "
                   "(no date to tell): give the date column with it, data.roles.time=[<date "
                   f"column>, {column}], or cut the record at the pause")


def _bare(header: str) -> str:
    """A header without a bracketed unit, lower case (``Dauer [h:mm:ss]``: ``dauer``)."""
    return re.sub(r"\s*[\[(].*$", "", header).strip().lower()


def is_format(kind: str) -> bool:
    """``data.time`` is a strptime format (not ``auto``, ``seconds``, ``iso8601``)."""
    return "%" in kind


STREAMED = ("a stream's time is one column, seconds or a timestamp with its date (or, data89, a "
            "time of day that passes midnight, read as a file's: not in a served model's block, "
            "read alone, where a day passing between two blocks cannot be told; data91: a "
            "session's blocks are read on from the last time it read), or two joined "
            "as a file's are, data.roles.time=[<date column>, <time column>]")


def time_kind(value: str, kind: str, number: bool, path: Path, header: str | None = None,
              stream: bool = False, dayfirst: bool | None = None) -> str:
    """``'seconds'``, ``'iso8601'`` or a strptime format for a time column whose first cell is
    ``value`` (``number``: it reads as one), ``kind`` being ``data.time``.  A date alone or a
    time of day alone (``header``: its column's) is refused naming ``data.roles.time`` (a
    ``stream``'s: what its time must be): the one repeats every sample of a day, the other
    wraps past midnight.  ``dayfirst`` (``data.dayfirst``): the order of a date with slashes no
    row decided."""
    if kind != "auto":
        return kind
    if keyed := keyed_format(value, dayfirst):
        return keyed
    if number:
        return compact_format(value) or "seconds"
    name = repr(header) if header else "<this column>"
    if TIME_OF_DAY.fullmatch(value):
        # (data88) "or set data.sample_period_s" alone was refused again by this very message:
        # the column is still read as the time; left out, the rows are timed by the period
        way = STREAMED if stream else (f"name the date column with it, data.roles.time=[<date "
                                       f"column>, {name}], or leave it out and time the rows by "
                                       f"their period, data.roles.ignore=[{name}] "
                                       "data.sample_period_s=<s>")
        raise ContractError(f"value {value!r} is a time of day without its date (it would go back "
                            f"at midnight): {way}; or, the time elapsed since the start (h:mm:ss), "
                            f"data.time={ELAPSED} (and data.roles.time={name} if it is not the time "
                            f"column); or the time of day as the time, data.time={OF_DAY_KIND}"
                            # (data92) the key alone read no time column: this refusal again
                            f" (and data.roles.time={name} if it is not the time column)",
                            file=path, column=TIME, row=1)
    if DATE.fullmatch(value):
        way = STREAMED if stream else (f"name the time-of-day column with it, data.roles.time="
                                       f"[{name}, <time column>], or leave it out and time the "
                                       f"rows by their period, data.roles.ignore=[{name}] "
                                       "data.sample_period_s=<s>")
        raise ContractError(f"value {value!r} is a date without a time of day: {way}", file=path,
                            column=TIME, row=1)
    told = dated_format(value)
    if told:
        return told
    if _SLASHED.match(value):
        raise ContractError(f"value {value!r} is a date with slashes, day or month first? set "
                            f"data.time to its format, e.g. data.time={EXAMPLE} (or "
                            "'%m/%d/%Y %H:%M:%S'), or data.dayfirst=true|false", file=path,
                            column=TIME, row=1)
    return "iso8601"


# a date and time written as digits alone, ``yyyymmddHHMM[SS]``: the AmeriFlux / FLUXNET
# ``TIMESTAMP_START`` a Campbell Scientific logger's flux table writes (``202503272330``)
_COMPACT = re.compile(r"\s*(?:19|20|21)\d{10}(?:\d\d)?\s*")


def compact_format(value: str) -> str | None:
    """The strptime format of a time written as 12 or 14 digits that are a date and a time of
    day (``202503272330``: ``%Y%m%d%H%M``), None otherwise.  No elapsed time in seconds has such
    a value (2e11 s are 6,000 years), nor milliseconds since 1970 (13 digits)."""
    if not _COMPACT.fullmatch(value):
        return None
    form = "%Y%m%d%H%M%S" if len(value.strip()) == 14 else "%Y%m%d%H%M"
    try:
        datetime.strptime(value.strip(), form)
    except ValueError:
        return None
    return form


def dated_format(value: str) -> str | None:
    """The strptime format of a date and time of day that is no ISO 8601 but says its order:
    day first with dots (``07.05.2027 12:00:00``, as German software writes it) or with slashes
    where a field past 12 tells (:func:`slashed_format`); None otherwise."""
    day_first = _DAY_FIRST.fullmatch(value)
    if day_first:
        year = "%Y" if len(day_first["y"]) == 4 else "%y"     # %y: 69-99 the 1900s, as C's
        return f"%d.%m.{year} %H:%M" + (":%S" if day_first["s"] else "")
    return slashed_format(value)


def slashed_format(value: str, keysight: bool = True, order: str | None = None) -> str | None:
    """The strptime format of a date with slashes and a time of day whose order the date itself
    says: a first field past 12 is the day (``15/06/2026 06:00:00``: ``%d/%m/%Y %H:%M:%S``), a
    second past 12 the day after the month (``06/15/2026``), and, where neither is and
    ``keysight``, the milliseconds after a colon of a Keysight DAQ's ``Time``
    (``03/01/2027 06:00:00:011``, as BenchLink Data Logger and the DAQ970A write it: month
    first); None for ``03/11/2026`` (either order) and for anything else.  ``order``
    (``'%d/%m/'`` or ``'%m/%d/'``, a record's, code71): ``value``'s format in that order."""
    match = _SLASHED_STAMP.fullmatch(value)
    if match is None:
        return None
    first, second = int(match["a"]), int(match["b"])
    if order is not None:
        date = order
    elif first > 12 >= second:
        date = ORDER[True]
    elif second > 12 >= first or keysight and first <= 12 and keysight_stamp(value):
        date = ORDER[False]
    else:
        return None
    year = "%Y" if len(match["y"]) == 4 else "%y"
    return f"{date}{year}{match['sep']}%H:%M" + (":%S" if match["s"] else "")


def keysight_stamp(value: str) -> bool:
    """``value`` is a Keysight DAQ's ``Time``, its milliseconds after a colon
    (``03/01/2027 06:00:00:011``): month first."""
    return bool(_SLASHED_STAMP.fullmatch(value) and _KEYSIGHT_MS.search(value))


def is_slashed_stamp(value: str) -> bool:
    """``value`` is a date with slashes and a time of day (``01/07/2026 13:22:42``)."""
    return bool(_SLASHED_STAMP.fullmatch(value))


def keyed_format(value: str, dayfirst: bool | None) -> str | None:
    """The format of ``value``, a date with slashes and a time of day, in ``data.dayfirst``'s
    order (dates84); None where the key is unset or ``value`` is no such date."""
    if dayfirst is None or not is_slashed_stamp(value):
        return None
    return slashed_format(value, order=ORDER[bool(dayfirst)])


def time_type(kind: str, value: str) -> pa.DataType:
    """The Arrow type a time column of ``kind`` is read as (``value``: its first cell)."""
    if kind in ("seconds", ELAPSED, OF_DAY_KIND):
        return pa.float64()
    zoned = "%z" in kind if is_format(kind) else bool(_ZONE_OFFSET.search(value))
    return pa.timestamp("ns", tz="UTC" if zoned else None)


def _strptime(values, kind: str):
    """``values`` read with the strptime format ``kind``, a second's fraction after the
    seconds (``29.03.2026 00:59:59,500``; ``,%f`` or ``.%f`` in ``kind`` says it, or nothing)
    added to them: Arrow's strptime reads none."""
    fraction = pc.struct_field(pc.extract_regex(values, FRACTION), "f")
    whole = pc.replace_substring_regex(values, r"(\d:\d\d:\d\d)[.,:]\d{1,9}", r"\1")
    form = _whole_seconds(kind)
    stamps = pc.strptime(whole, format=form, unit="ns", error_is_null=False)
    day = first_impossible_day(whole, stamps, form)
    if day is not None:
        raise pa.ArrowInvalid(f"no such day: {day!r}")
    ns = pc.fill_null(pc.cast(pc.utf8_rpad(fraction, 9, "0"), pa.int64()), 0)
    return pc.add(stamps, pc.cast(ns, pa.duration("ns")))


def _whole_seconds(kind: str) -> str:
    """The strptime format ``kind`` without its second's fraction (``%f``), which Arrow's
    strptime does not read: :func:`_strptime` adds the fraction itself."""
    return re.sub(r"[.,:]%f", "", kind)


def no_such_day(value: str, form: str) -> bool:
    """``value`` names a day its month has not (``31.02.2027 04:19:00``) in the strptime
    format ``form``: Python's strptime refuses it so, as the exported C does."""
    try:
        datetime.strptime(value.strip(), form)
    except ValueError as exc:
        return "out of range" in str(exc)
    return False


def first_impossible_day(text, stamps, form: str) -> str | None:
    """The first cell of ``text`` that :func:`no_such_day` refuses, None where none does.
    (audit97) Arrow's strptime reads day 29-31 of a shorter month as the next month's first
    days (``31.02.2027`` as 2027-03-03), so a mistyped date was read as another and refused as
    "time decreases ... sort them".  Only a cell read as day 1-3 whose stamp, written back in
    ``form``, is not the cell may be one: a file's rows are not looked at one by one."""
    seconds = pc.cast(stamps, pa.timestamp("s", stamps.type.tz), safe=False)
    try:
        back = pc.strftime(seconds, format=form)
    except (pa.ArrowInvalid, pa.ArrowNotImplementedError):
        back = None
    near = pc.less_equal(pc.day(stamps), 3)
    if back is not None:
        near = pc.and_(near, pc.not_equal(back, text))
    for value in pc.filter(text, pc.fill_null(near, False)).to_pylist():
        if no_such_day(value, form):
            return value
    return None


def unread_fraction(value: str, kind: str) -> bool:
    """A timestamp whose second's fraction Arrow's CSV reader does not read: after a comma in
    ISO 8601 (``kind``), as it allows and a European logger writes (``13:05:00,500``), or in a
    strptime format (``29.03.2026 00:59:59,500``)."""
    return (kind == "iso8601" and re.search(COMMA_FRACTION, value) is not None
            or is_format(kind) and re.search(FRACTION, value) is not None)


def parsed(values, target: pa.DataType, kind: str):
    """``values`` (text) as ``target``; raises ``pa.ArrowInvalid`` on a cell that is not.
    Spaces around a cell are no part of it (``T_a; time``: numbers are read so too)."""
    values = pc.utf8_trim_whitespace(values)
    if is_format(kind) and pa.types.is_timestamp(target):
        stamps = _strptime(values, kind)
        return stamps if target.tz is None else pc.cast(stamps, target)
    if kind == "iso8601":    # ISO 8601's decimal comma, a European logger's 13:05:00,500
        values = pc.replace_substring_regex(values, COMMA_FRACTION, r"\1.\2")
    return pc.cast(values, target)


def described(target: pa.DataType, kind: str, value=None) -> str:
    """What a cell of a time column (``value``, where given) should have been."""
    if is_format(kind):
        if value is not None and no_such_day(str(value), _whole_seconds(kind)):
            return f"a day of the calendar (its month has fewer days; data.time's format {kind!r})"
        return f"a time in data.time's format {kind!r}"
    zone = "with" if target.tz else "without"
    return (f"an ISO 8601 timestamp {zone} zone offset (like the first row; another format: "
            f"set data.time to it, e.g. data.time={EXAMPLE})")


def said_if_not_seconds(time: np.ndarray, file: Path, header: str, own: bool = False) -> None:
    """Say (not refuse: no rule on the values alone tells a slow logger's seconds from ms) a
    time column without a unit that reads like milliseconds: steps of whole thousands (1000,
    60000), or, in a lab's ``own`` export (headers read by ``data.roles``: a contract file's
    ``time`` is seconds by the contract, the simulator's every 100 s), whole numbers 100 or
    more apart (a median step) that are no whole number of minutes (500, 2500, 998-1003: a
    logger's seconds come every 1, 10, 60, 300 s ...).  A volumetric cycle of 1200 s or a
    logger every 120 s is no such step; a lab's every 100 s or 500 s in seconds is said and
    quietened with ``data.units={time: s}``.  Also said: Excel's serial day numbers (a date
    shown as a number, :func:`excel_days`), ``data.units={time: d}``."""
    period = median_step(time)
    if period is None or not np.all(np.isfinite(time)):
        return
    steps = np.diff(time)
    thousands = period >= 1000 and np.all(steps % 1000 == 0)
    odd = own and period >= 100 and period % 60 != 0 and np.all(time == np.round(time))
    if thousands or odd:
        why = "in whole thousands" if thousands else "whole numbers, no whole minutes"
        logger.warning(f"{file}, column {header!r}: samples {period:g} s apart, {why}: "
                       f"milliseconds? say so with data.units={{{header!r}: ms}} (or a unit in "
                       f"the header, 'time [ms]'; seconds: data.units={{{header!r}: s}})")
    elif excel_days(time[0], period):
        logger.warning(f"{file}, column {header!r}: from {time[0]:g}, samples {period:g} s = "
                       f"{period * 86400:.4g} s / 86400 apart: Excel's serial days (a date shown "
                       f"as a number)? say so with data.units={{{header!r}: d}}, or save the "
                       "column formatted as a date")


EXCEL_DAYS = (20000.0, 80000.0)   # Excel's serial day numbers 1954 .. 2119


def excel_days(first: float, period: float) -> bool:
    """A time from an Excel serial day number, sampled at whole seconds: not a second apart as
    seconds, whole seconds as days (a 1440 Hz record starting 46000 s in is no thermal test)."""
    seconds = period * 86400
    return (EXCEL_DAYS[0] <= first <= EXCEL_DAYS[1] and 0 < period < 1 and seconds >= 0.5
            and abs(seconds - round(seconds)) <= 0.01 * seconds)


HOUR_S = 3600.0


def on_local_clock(ns: np.ndarray, zone: str, file, column: str = TIME) -> np.ndarray:
    """Timestamps without an offset (``ns``, int64) written on ``zone``'s local clock, as UTC
    (int64 ns): the hour repeated when daylight saving time ends told apart by the order of the
    rows, the hour skipped when it begins not counted (``data.timezone``).  A time the clock
    never showed, or a repeated hour whose rows do not run through it in order, is refused
    with its row."""
    index = pd.DatetimeIndex(ns.astype("datetime64[ns]"))
    try:
        return index.tz_localize(zone, ambiguous="infer", nonexistent="raise").as_unit("ns").asi8
    except ValueError:
        pass
    skipped = index.tz_localize(zone, ambiguous=np.ones(len(index), bool), nonexistent="NaT")
    unsure = index.tz_localize(zone, ambiguous="NaT", nonexistent="shift_forward")
    row = int(np.argmax(pd.isna(skipped) | pd.isna(unsure)))
    what = (f"never shown by data.timezone={zone}'s clock (the hour skipped when daylight saving "
            "time begins): another zone?" if pd.isna(skipped[row]) else
            f"in the hour data.timezone={zone}'s clock repeats when daylight saving time ends, "
            "and the rows do not run through it in order to tell which")
    raise ContractError(f"time {index[row]} is {what}", file=file, column=column, row=row + 1)


def clock_set_back(before: float, after: float, period: float | None = None,
                   origin: str | None = None) -> str:
    """What to say of a local clock going back by an hour less a sample period (daylight saving
    time ends: 02:59 is followed by 02:00), within a period either way (``period`` None: by up to
    an hour); a clock resynchronised by minutes is no daylight saving time.  ``origin`` (the
    first timestamp, ``before`` / ``after`` seconds since it): the zones whose clocks went back
    then named (lab77)."""
    back = before - after
    near = (abs(back + period - HOUR_S) <= period if period and period < HOUR_S
            else 0 < back <= HOUR_S)
    if not near:
        return ""
    return ": the clock set back by an hour" + dst_said(origin, before, after, "ending")


def dst_said(origin: str | None, before: float, after: float, change: str,
             served: bool = False) -> str:
    """``, daylight saving time ending? set data.timezone ...``: the zone to set, named where
    ``origin`` + ``before`` / ``after`` (local times) are a daylight saving change of some
    zone's clock (``change``: ``'ending'``, the clock back; ``'beginning'``, forward).
    ``served``: a block of the served model, which reads no ``data.timezone`` (tidy77: the
    reader's 'set data.timezone' could not be done there): the time to send with its offset."""
    zones = dst_zones(origin, before, after) if origin is not None else []
    if served:
        return _served_said(origin, after, change, zones)
    if not zones and origin is not None:
        return (f", at no zone's daylight saving time {change} (a clock set by hand or by a time "
                "server? data.timezone does not read it)")
    if not zones:
        return (f", daylight saving time {change}? set data.timezone to the zone it was written "
                "in (e.g. data.timezone=Europe/Berlin)")
    at = (pd.Timestamp(origin) + pd.Timedelta(seconds=float(after))).strftime("%Y-%m-%d")
    pick = next((z for z in _USUAL if z in zones), zones[0])
    return (f", daylight saving time {change} on {at} in {len(zones)} zone"
            f"{'s' * (len(zones) > 1)} ({_named(pick, zones)}): set data.timezone to the one it "
            f"was written in (e.g. data.timezone={pick})")


def _served_said(origin: str | None, after: float, change: str, zones: list[str]) -> str:
    """:func:`dst_said`'s words for the served model: no zone it could be told (its data config
    is not read per block), so the way out is the client's: the time in UTC or with its offset
    (that of the zone named first, after the change, as the example)."""
    from zoneinfo import ZoneInfo

    fix = ("a served model reads no data.timezone: send the time with its UTC offset or in UTC "
           "(Z)")
    if not zones:
        return (f", at no zone's daylight saving time {change} (a clock set by hand or by a time "
                f"server?); {fix}")
    pick = next((z for z in _USUAL if z in zones), zones[0])
    wall = pd.Timestamp(origin).tz_localize(None).to_pydatetime() + timedelta(seconds=float(after))
    shown = wall.replace(tzinfo=ZoneInfo(pick), fold=1).isoformat(timespec="seconds")
    return (f", daylight saving time {change} on {wall:%Y-%m-%d} in {len(zones)} zone"
            f"{'s' * (len(zones) > 1)} ({_named(pick, zones)}); {fix} (e.g. {shown}, {pick}'s "
            "clock after the change)")


def _named(pick: str, zones: list[str]) -> str:
    """``pick`` and up to three more of ``zones``, its region's first (Europe/Paris, not
    Africa/Ceuta)."""
    region = pick.split("/")[0]
    others = sorted((z for z in zones if z != pick), key=lambda z: (z.split("/")[0] != region, z))
    return ", ".join([pick, *others[:3]]) + (", ..." if len(others) > 3 else "")


# (the zone named first where several change their clocks alike: those of the labs met so far)
_USUAL = ("Europe/Berlin", "Europe/London", "Europe/Helsinki", "America/New_York",
          "America/Chicago", "America/Denver", "America/Los_Angeles", "Australia/Sydney")


def dst_zones(origin: str, before: float, after: float) -> list[str]:
    """The zones (IANA, sorted) whose local clock shows ``origin`` + ``before`` s and then, an
    hour later or earlier on the wall, ``origin`` + ``after`` s across a daylight saving change:
    their UTC offset one hour larger before the step back (one hour smaller before a step
    forward), the step within an hour of the change's instant.  Empty where none (a clock set by
    hand, a logger paused)."""
    import zoneinfo

    first = pd.Timestamp(origin).tz_localize(None).to_pydatetime()
    wall_before = first + timedelta(seconds=float(before))
    wall_after = first + timedelta(seconds=float(after))
    forward = after > before
    found = []
    for name in sorted(zoneinfo.available_timezones()):
        if name.startswith(("Etc/", "SystemV/")) or "/" not in name:
            continue
        zone = zoneinfo.ZoneInfo(name)
        # before the step: the earlier reading of a repeated hour (fold 0); after: the later
        was = wall_before.replace(tzinfo=zone, fold=0)
        now = wall_after.replace(tzinfo=zone, fold=1)
        shift = (was.utcoffset() - now.utcoffset()).total_seconds()
        if shift != (-HOUR_S if forward else HOUR_S) or not (_shown_by(was) and _shown_by(now)):
            continue
        # the two readings within a period or so of each other in UTC: the change between them
        gap = (now.astimezone(timezone.utc) - was.astimezone(timezone.utc)).total_seconds()
        if 0 < gap <= HOUR_S:
            found.append(name)
    return found


def _shown_by(wall: datetime) -> bool:
    """The zone's clock shows ``wall`` (not in the hour it skips)."""
    back = wall.astimezone(timezone.utc).astimezone(wall.tzinfo)
    return back.replace(tzinfo=None, fold=0) == wall.replace(tzinfo=None, fold=0)


def skips_an_hour(steps: np.ndarray, period: float) -> np.ndarray:
    """Per step of a clock sampled every ``period`` s: one hour and a period forward (within half
    a period), what daylight saving time's beginning makes of one sample period."""
    return np.abs(steps - HOUR_S - period) <= period / 2


def said_if_clock_skips(seconds: np.ndarray, file, header: str = TIME, at=position,
                        origin: str | None = None) -> None:
    """Say (not refuse: a logger may pause an hour) timestamps without an offset that jump one
    hour plus a sample period forward once: daylight saving time beginning, read as an hour
    without samples unless ``data.timezone`` says the zone (``at``: names a data row;
    ``origin``: the first timestamp, the zones whose clocks went forward then named)."""
    period = median_step(seconds)
    if period is None or period >= HOUR_S:
        return
    jumps = np.flatnonzero(skips_an_hour(np.diff(seconds), period))
    if jumps.size:
        k = int(jumps[0])
        logger.warning(f"{file}, column {header!r}, {at(k + 2)}: the clock jumps an hour forward, "
                       "read as an hour without samples"
                       + dst_said(origin, seconds[k], seconds[k + 1], "beginning"))
