"""Time in seconds and the checks of every value: strictly increasing time, finite values,
temperatures in °C, and the missing samples (repaired or kept, see :mod:`thermocomp.core.io.read`)."""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.compute as pc

from ...base.errors import listed
from ...base.log import logger
from ..timerule import median_step
from .clocksets import undone
from .contract import TIME, ContractError, role
from .lines import Lines, at
from .marks import ABSOLUTE_ZERO_C
from .options import ReadOptions
from .rates import period_groups, said_if_rate_changes, said_if_rows_missing
from .roles import time_unit
from .sparse import intermittent, probe_cycle
from .tables import PIPED_HINT, _chunks, _values, all_empty
from .timestamps import (
    DAY_S,
    ELAPSED,
    OF_DAY,
    OF_DAY_KIND,
    clock_set_back,
    hours_of_day,
    names_time_of_day,
    on_local_clock,
    refuse_hours,
    said_if_clock_skips,
    seconds_of_day,
)

MAX_ABS_T_C = 1e4  # refused whatever data.kelvin_threshold_c says
FAULTY_SHARE = 0.1  # at most this share of a streamed T_ column above the kelvin threshold: faults


def reading_limit(column: str) -> float:
    """The largest |value| a sensor of ``column`` reads: a temperature's :data:`MAX_ABS_T_C`
    (beyond it a logger's overload or open-circuit mark, a Keysight DAQ's +9.9E+37), inf for any
    other column.  What the streams refuse and the exported code takes as a missing value."""
    return MAX_ABS_T_C if str(column).startswith("T_") else float("inf")


# ---------------------------------------------------------------------------
# Time


def _set_time_seconds(columns: dict, rows: int, path: Path, opts: ReadOptions,
                      lines: Lines | None = None, header: str | None = None) -> dict:
    """Replace (or add) ``time`` by float seconds; describe its source (``lines``: where a
    row stands in the file, for a warning; ``header``: the time column's in the file, which
    may say it holds seconds of the day, :func:`.timestamps.seconds_of_day`)."""
    if TIME not in columns:
        columns[TIME] = pa.array(np.arange(rows) * opts.sample_period_s)
        return {"time": "sample_period_s"}
    column = columns[TIME]
    try:
        if column.null_count:
            row = int(np.argmax(column.is_null().to_numpy(zero_copy_only=False))) + 1
            raise ContractError("missing time value", file=path, column=TIME, row=row)
        seconds, info = _seconds(column, path, opts.timezone, header, opts.time,
                                 time_unit(header, opts))
        seconds, origin, found = undone(seconds, info.get("time_origin"), opts.clock_sets, path)
        if found:       # (the sets found, by index: the record's report names those not found)
            info.update(time_origin=origin, clock_sets_undone=len(found), clock_sets_found=found)
        # timestamps on a local clock without an offset, and no data.timezone to read it
        local = (pa.types.is_timestamp(column.type) and column.type.tz is None
                 and opts.timezone is None)
        _check_increasing(seconds, path, local, info.get("time_origin"), opts.max_duration_days,
                          lines.time_cell if lines is not None else _zoned_cell(column))
        if local:
            said_if_clock_skips(seconds, path, at=at(lines), origin=info.get("time_origin"))
        if opts.resample_s is None:        # (on one grid, as the warning says to put it)
            if not said_if_rate_changes(seconds, path, at=at(lines)):   # (its slower steps)
                said_if_rows_missing(seconds, path, at=at(lines),
                                     dateless=is_time_of_day(info, header, opts.time))
    except ContractError as exc:
        if opts.missing != "keep":
            raise
        raise ContractError(f"{exc.reason} ({PIPED_HINT})",
                            file=exc.file, column=exc.column, row=exc.row, line=exc.line) from None
    _check_duration(seconds, path, opts.max_duration_days)
    columns[TIME] = pa.array(seconds)
    return info


def _zoned_cell(column: pa.ChunkedArray) -> Callable[[int], str] | None:
    """(audit106) A data row's time as a table with no text (Parquet) holds it: a timestamp on its
    zone's clock, ``+02:00`` after the change to summer time, not the first row's ``+01:00``, which
    that clock never showed; None where the column is no timestamp with a zone."""
    kind = column.type
    if not (pa.types.is_timestamp(kind) and kind.tz):
        return None
    ns = pc.cast(pc.cast(column, pa.timestamp("ns", kind.tz)), pa.int64()).to_numpy()
    return lambda row: pd.Timestamp(int(ns[row - 1]), tz="UTC").tz_convert(kind.tz).isoformat()


def is_time_of_day(info: dict, header: str | None, written: str) -> bool:
    """(data93) The time was read as a time of day without its date (``info``: the reader's
    report of it): ``data.time=of_day`` (``written``), seconds of the day, or an ``h:mm:ss``
    under a time-of-day header (:func:`.timestamps.names_time_of_day`), read as a duration."""
    return (written == OF_DAY_KIND or info.get("time") == OF_DAY
            or written != ELAPSED and info.get("time") == ELAPSED and names_time_of_day(header))


def _seconds(column: pa.ChunkedArray, path: Path, zone: str | None = None,
             header: str | None = None, written: str = "auto",
             unit: str | None = None) -> tuple[np.ndarray, dict]:
    kind = column.type
    if pa.types.is_timestamp(kind):
        ns = pc.cast(pc.cast(column, pa.timestamp("ns", kind.tz)), pa.int64()).to_numpy()
        if kind.tz is None and zone is not None:      # a local clock: data.timezone
            ns = on_local_clock(ns, zone, path)
            origin = pd.Timestamp(ns[0], tz="UTC").tz_convert(zone).isoformat()
        else:
            origin = pd.Timestamp(ns[0], tz=kind.tz).isoformat()
        return (ns - ns[0]) / 1e9, {"time": "iso8601", "time_origin": origin}
    if pa.types.is_duration(kind):     # an elapsed time (h:mm:ss, a Parquet timedelta)
        ns = pc.cast(pc.cast(column, pa.duration("ns")), pa.int64()).to_numpy()
        return ns / 1e9, {"time": "elapsed"}
    seconds = pc.cast(column, pa.float64()).to_numpy()
    if written in ("auto", OF_DAY_KIND) and hours_of_day(seconds, header, unit):
        refuse_hours(seconds, path, header)      # (data93) a lab's decimal hours, no unit
    if (of_day := seconds_of_day(seconds, path, header, kind=written, unit=unit)) is not None:
        return of_day, {"time": OF_DAY}
    return seconds, {"time": "seconds"}


def _check_increasing(seconds: np.ndarray, path: Path, local: bool = False,
                      origin: str | None = None, max_days: float | None = None,
                      written: Callable[[int], str | None] | None = None) -> None:
    """Refuse a time that does not increase, saying the fix (``local``: timestamps on a local
    clock without an offset, where an hour set back is daylight saving time ending, said so;
    ``origin``: the first timestamp, so that a time is named as written, not as seconds;
    ``max_days``: a longer campaign, sorted, is no run but a clock reset; ``written``: a data
    row's time cell as the file writes it, :meth:`.lines.Lines.time_cell`)."""
    def shown(row: int) -> str:
        return _as_written(seconds[row - 1], origin, written and written(row))

    finite = np.isfinite(seconds)
    if not finite.all():
        row = int(np.argmin(finite)) + 1
        raise ContractError(f"time {seconds[row - 1]} is not finite", file=path, column=TIME,
                            row=row)
    steps = np.diff(seconds)
    if (steps > 0).all():
        return
    i = int(np.argmax(steps <= 0))
    before, after = seconds[i], seconds[i + 1]
    if after == before:
        what = (f"duplicate time {shown(i + 2)} (same as row {i + 1}): two samples at "
                "one time; delete the row written twice, or give it its own time")
    else:
        dst = clock_set_back(before, after, median_step(seconds), origin) if local else ""
        # rows a lab exported or pasted out of order: sorting them gives one time per sample
        unsorted = "" if dst or np.unique(seconds).size < seconds.size else (
            _clock_reset(seconds, after - before, max_days)
            or ": the rows are not in time order; sort them by their time")
        # a logger's clock that starts again (restarted, or runs joined): its times repeat
        again = "" if dst or unsorted or after > seconds[0] else (
            ": the time starts again (the logger restarted, or runs joined in one file?): one "
            "file per run in a folder reads each as a campaign")
        what = (f"time decreases from {shown(i + 1)} (row {i + 1}) to "
                f"{shown(i + 2)}{dst}{unsorted}{again}{_of_day_said(seconds, origin, i)}")
    raise ContractError(what, file=path, column=TIME, row=i + 2)


def _of_day_said(seconds: np.ndarray, origin: str | None, i: int) -> str:
    """(data89b) What to say of seconds within a day going back by more than half a day after
    row ``i + 1`` that are not read as seconds of the day (:func:`.timestamps.seconds_of_day`:
    the step over midnight longer than any other of the record's)."""
    if origin is not None or seconds.min() < 0 or seconds.max() >= DAY_S or \
            seconds[i] - seconds[i + 1] <= DAY_S / 2:
        return ""
    pause = (seconds[i + 1] + DAY_S - seconds[i]) / 3600
    # (data91) the key that says it (was: only a header naming it, the file edited by hand)
    return (f"; or seconds of the day past midnight after {pause:.3g} h without rows? say so, "
            f"data.time={OF_DAY_KIND} (a header saying so, 'Seconds of day', reads them so too)")


def _clock_reset(seconds: np.ndarray, back: float, max_days: float | None) -> str:
    """What to say of unique times that sorting would not make a run of (``back``: the first
    step back, s): the stretches after and before it interleave (a clock set back into the
    run's own span), or sorted they would span more than ``max_days`` (a logger's clock reset
    to its default date, 01.01.2000); '' where sorting mends them (exports pasted out of order)."""
    order = np.argsort(seconds, kind="stable")
    stretches = 1 + int(np.count_nonzero(np.diff(seconds) < 0))
    # a clock set back into the run's own span puts its samples between the earlier ones:
    # sorted, some are closer than the logger's period; a row merely written out of place
    # (a sample a gateway sent late) sorts into the run's regular steps
    steps = np.diff(seconds[order])
    interleaved = (1 + int(np.count_nonzero(np.diff(order) != 1)) > stretches
                   and steps.min() < 0.75 * np.median(steps))
    too_long = max_days is not None and np.ptp(seconds) > max_days * 86400
    if not (interleaved or too_long):
        return ""
    said = ("mix its stretches before and after this row" if interleaved else
            f"make a campaign of {np.ptp(seconds) / 86400:.4g} days")
    return (f" ({_span(-back)} back): the logger's clock set back (reset, or set to another "
            f"date?); sorting the rows would {said}: cut the file at this row into two runs "
            "(a file each), or correct the times from this row on")


def _span(seconds: float) -> str:
    """A duration in the unit that reads it: ``90 s``, ``12 min``, ``5.5 h``, ``23.1 years``."""
    for unit, size in (("years", 365.25 * 86400), ("days", 86400), ("h", 3600), ("min", 60)):
        if seconds >= 2 * size:
            return f"{seconds / size:.3g} {unit}"
    return f"{seconds:g} s"


def _shown(seconds: float, origin: str | None) -> str:
    """A time as the file gives it: a timestamp (``origin`` + ``seconds``), else seconds."""
    if origin is None:
        return f"{seconds:g} s"
    return (pd.Timestamp(origin) + pd.Timedelta(seconds=float(seconds))).isoformat()


# a timestamp cell in ISO 8601's order, with its offset or without
_ISO_CELL = re.compile(r"\d{4}-\d\d-\d\d[T ]\d\d:\d\d(:\d\d([.,]\d+)?)?\s*(Z|[+-]\d\d(:?\d\d)?)?")


def _as_written(seconds: float, origin: str | None, cell: str | None) -> str:
    """:func:`_shown`, said as the file's ``cell`` writes it where the cell is that instant:
    timestamps whose offsets change (daylight saving time, ``+01:00`` then ``+02:00``) are held
    in UTC, and ``08:29:00+00:00`` is no time the lab's file holds (audit96); UTC beside it."""
    shown = _shown(seconds, origin)
    if origin is None or not cell or not _ISO_CELL.fullmatch(cell):
        return shown       # (a date with dots stays ISO 8601 as read: one order, messy58)
    try:
        stamp = pd.Timestamp(cell)
        same = stamp == pd.Timestamp(shown)
    except (ValueError, TypeError):     # another layout (a date with dots), or no zone to compare
        return shown
    if not same:
        return shown
    if stamp.tzinfo is None or not stamp.utcoffset():
        return cell
    return f"{cell} = {stamp.tz_convert('UTC'):%Y-%m-%d %H:%M:%S} UTC"


def _check_duration(seconds: np.ndarray, path: Path, max_days: float | None) -> None:
    days = (seconds[-1] - seconds[0]) / 86400
    if max_days is None or days <= max_days:
        return
    limit = f"more than data.max_duration_days={max_days:g}"
    steps = np.diff(seconds)
    i = int(np.argmax(steps))
    if steps[i] > 0.5 * (seconds[-1] - seconds[0]):   # one jump, not a unit: name its row
        row = 1 if i == 0 else i + 2      # a first time far before the rest is the odd one
        raise ContractError(f"time jumps by {steps[i] / 86400:.4g} days from row {i + 1} to "
                            f"row {i + 2}: the campaign would last {days:.4g} days, {limit}",
                            file=path, column=TIME, row=row)
    epoch = (f" (from {seconds[0]:.4g}: milliseconds since 1970, as a gateway stamps a message)"
             if EPOCH_MS[0] <= seconds[0] <= EPOCH_MS[1] else "")
    raise ContractError(f"the campaign lasts {days:.4g} days, {limit}: is time in ms{epoch}? it "
                        "must be in seconds: say so with data.units={<its header>: ms}",
                        file=path, column=TIME, row=len(seconds))


EPOCH_MS = (9.46e11, 4.1e12)      # milliseconds since 1970: 2000 .. 2099


def _check_periods(periods: dict, files: Mapping, root: Path, ratio: float | None) -> None:
    """Refuse a campaign whose median sample period is ``ratio`` times (or 1/``ratio``) the
    median of the others': its time column is in another unit (ms, minutes) than theirs."""
    periods = {c: p for c, p in periods.items() if p}
    if len(periods) < 2:
        return
    off, minutes = {}, False
    for cid, p in periods.items():
        r = p / np.median([q for c, q in periods.items() if c != cid])
        if ratio is not None and (r >= ratio or r <= 1 / ratio):
            off[cid] = r
        elif any(abs(np.log(r) - k * np.log(60)) < 0.05 for k in (-1, 1)):
            # 60x apart may be two logging rates (1 s and 1 min): said, not refused
            logger.warning(f"{root / files[cid]}: median sample period {p:g} s is {r:.3g}x the "
                           "other campaigns': if its time is in minutes (or theirs), convert it "
                           "to seconds")
            minutes = True
    if not off:
        if not minutes:     # one word per cause: a time in minutes is said above
            _said_if_periods_differ(periods, root)
        return
    cid = max(off, key=off.get)  # two campaigns disagree: ms (a time 1000x too large) is likelier
    r = off[cid]
    unit = ("ms" if r < 3e4 else "µs") if r > 1 else ("minutes" if r > 1 / 600 else "hours")
    raise ContractError(f"median sample period {periods[cid]:g} s is {r:.3g}x the other "
                        f"campaigns' ({periods[cid] / r:g} s): is its time in {unit}? it must be "
                        f"in seconds (data.max_period_ratio={ratio:g})",
                        file=root / files[cid], column=TIME)


def _said_if_periods_differ(periods: dict, root: Path) -> None:
    """Say campaigns logged at sample periods :data:`RATE_CHANGE` times apart or more (a lab's
    runs at 10 s and at 60 s): each weighs by its rows in a fit and in the scores, and a model
    whose lags count samples reads a sample as another span in each (said before only 60x
    apart, as minutes for seconds); ``data.resample_s`` puts them on one grid."""
    groups = period_groups(periods)
    if not groups:
        return
    lo, hi = min(periods.values()), max(periods.values())
    said = "; ".join(f"{p:g} s: {len(ids)} ({listed(ids, 3)})" for p, ids in groups.items())
    logger.warning(f"{root}: its campaigns are logged at different sample periods ({said}): each "
                   f"weighs by its rows in the fit and in the scores (a {lo:g} s run {hi / lo:.3g} "
                   f"times a {hi:g} s run as long), and a model whose lags count samples (arx, "
                   f"lstm) reads a sample as another span in each; data.resample_s={hi:g} puts "
                   "them on one grid")


def _error_ranges(table: pa.Table, roles: tuple = ("E",)) -> dict:
    """``{E_ column: (peak-to-peak, constant)}`` of one campaign (finite values only; the
    columns of ``roles``)."""
    names = [name for name in table.column_names if role(name) in roles]
    if not names:
        return {}
    # every column at once (a volumetric campaign's 1430 one by one: 30 ms)
    values = np.column_stack([_values(table.column(name)) for name in names])
    finite = np.isfinite(values)
    count = finite.sum(axis=0)
    highest = np.where(finite, values, -np.inf).max(axis=0, initial=-np.inf)
    lowest = np.where(finite, values, np.inf).min(axis=0, initial=np.inf)
    return {name: (float(hi - lo), bool(n >= 3 and hi == lo))
            for name, n, hi, lo in zip(names, count, highest, lowest) if n}


SCALE_FACTOR = 300.0   # a campaign's error range this far off the others' median: another unit?


def _warn_error_ranges(ranges: dict, files: Mapping, root: Path) -> None:
    """Say what no unit check can refuse but a measurement hardly shows: an ``E_`` (or ``T_``)
    column constant over a whole campaign (a dead channel: not measured is an empty cell), and one
    whose range is :data:`SCALE_FACTOR` times off the other campaigns' median (mm or nm for
    µm).  Said on stderr, not refused: an idle campaign may drift little."""
    columns = {c for r in ranges.values() for c in r}
    for col in sorted(columns):
        spans = {cid: r[col][0] for cid, r in ranges.items() if col in r and r[col][0] > 0}
        for cid, r in ranges.items():
            if col not in r:
                continue
            span, constant = r[col]
            if constant:
                logger.warning(f"{root / files[cid]}, column '{col}': constant over the whole "
                               "campaign (a dead channel?); leave the cells empty where it was not "
                               "measured" + ("" if role(col) == "E" else ", or leave the column "
                                             "out (data.roles.ignore, data.inputs)"))
            elif len(spans) >= 3 and role(col) == "E":
                typical = float(np.median([v for c, v in spans.items() if c != cid]))
                if span * SCALE_FACTOR < typical or span > SCALE_FACTOR * typical:
                    logger.warning(f"{root / files[cid]}, column '{col}': range {span:.3g} against "
                                   f"{typical:.3g} in the other campaigns (median): is it in "
                                   "another unit? E_ columns are in µm (µm/m angular)")


# ---------------------------------------------------------------------------
# Values and missing samples


def _refuse_empty(columns: dict, path: Path) -> None:
    """Refuse the columns whose every cell is empty, all of them in one message (a logger's
    unused channels: one refusal per channel, a run of the command each, before)."""
    empty = [name for name, column in columns.items() if name != TIME and all_empty(column)]
    if not empty:
        return
    others = f", nor {'has' if len(empty) == 2 else 'have'} {listed(map(repr, empty[1:]))}" \
        if len(empty) > 1 else ""
    raise ContractError(f"column has no valid value (every cell is empty){others}: not measured? "
                        f"leave {'it' if len(empty) == 1 else 'them'} out (data.roles.ignore)",
                        file=path, column=empty[0])


def _check_values(values: np.ndarray, name: str, path: Path, opts: ReadOptions) -> np.ndarray:
    """Refuse impossible values; return the positions of missing ones (a column without any
    value was refused before, with the others: :func:`_refuse_empty`)."""
    finite = np.isfinite(values)
    missing = np.empty(0, dtype=np.intp)
    if not finite.all():
        missing = np.flatnonzero(~finite)
        infinite = missing[np.isinf(values[missing])]
        if infinite.size:
            row = int(infinite[0]) + 1
            raise ContractError(f"infinite value {values[row - 1]}", file=path, column=name,
                                row=row)
    limit, unit, what = {"E": (opts.max_abs_error, "µm", "error"),
                         "S": (opts.max_abs_state, "", "state")}.get(role(name), (None,) * 3)
    if limit is not None:
        with np.errstate(invalid="ignore"):
            beyond = np.abs(values) > limit
        if beyond.any():
            row = int(np.argmax(beyond)) + 1
            raise ContractError(f"value {values[row - 1]:g}{' ' + unit if unit else ''} is beyond "
                                f"data.max_abs_{what}={limit:g}: not a plausible {what} value "
                                "(check the unit)", file=path, column=name, row=row)
    if role(name) == "T":
        _check_celsius(values, name, path, opts.kelvin_threshold_c, complete=not missing.size,
                       streamed=opts.missing == "keep")
    return missing


def _check_celsius(values: np.ndarray, name: str, path: Path, threshold: float,
                   complete: bool, streamed: bool = False) -> None:
    """Refuse kelvin (a column above ``threshold``) and values no sensor reads.  A streamed
    campaign (``missing="keep"``) keeps a few readings (at most :data:`FAULTY_SHARE`) above
    ``threshold``: a failing sensor (an open circuit reads 850 °C) that the compensator's
    range check is there to catch, as on the machine."""
    lowest, highest = ((values.min(), values.max()) if complete
                       else (np.nanmin(values), np.nanmax(values)))
    if highest > min(threshold, MAX_ABS_T_C):
        median = float(np.nanmedian(values))
        share = float(np.mean(values[np.isfinite(values)] > threshold))
        if streamed and share <= FAULTY_SHARE and highest <= MAX_ABS_T_C:
            pass
        else:
            row = int(np.argmax(values > min(threshold, MAX_ABS_T_C))) + 1
            # kelvin only where the values in °C would pass: a spindle speed (3000, a column
            # 'S' read as a temperature by default) is no temperature in any unit, nor is one
            # whose readings are not nearly all in kelvin's range (a hob's 0 / 400 / 1000 rpm,
            # median 400, was told to be kelvin: 0 K)
            finite = values[np.isfinite(values)]
            as_kelvin = (finite > threshold) & (finite <= threshold - ABSOLUTE_ZERO_C)
            readings = finite[np.abs(finite) <= MAX_ABS_T_C]
            if highest > MAX_ABS_T_C and readings.size and np.median(readings) <= threshold:
                # (faults71) a logger's mark among temperatures: it was told to be another
                # quantity where it filled half the column, or a fault replay streams (it refuses)
                row = int(np.argmax(values > MAX_ABS_T_C)) + 1
                raise ContractError(
                    f"{values[row - 1]:g} °C is beyond {MAX_ABS_T_C:g} °C, which no sensor reads "
                    "(the column's other readings are temperatures): the logger's mark for an "
                    "overload or an open circuit (a Keysight DAQ writes +9.90000000E+37)? list "
                    "it as the file writes it in data.missing_values: a value not measured",
                    file=path, column=name, row=row)
            after = values[row - 1:][np.isfinite(values[row - 1:])]
            kelvin_after = (row > 1 and not (np.nan_to_num(values[:row - 1]) > threshold).any()
                            and np.mean((after > threshold) & (after <= threshold - ABSOLUTE_ZERO_C))
                            >= 1 - FAULTY_SHARE)
            why = ("the rows from here on read as kelvin of the °C before: the unit changes "
                   "inside the file, convert it"    # (data87: was "another quantity? ...")
                   if kelvin_after else
                   "temperatures look like kelvin, convert to °C, or say so: "
                   "data.units={<its header>: K}"
                   if threshold < median <= threshold - ABSOLUTE_ZERO_C
                   and as_kelvin.mean() >= 1 - FAULTY_SHARE else
                   f"no temperature, in °C or kelvin (the column's median is {median:.4g}): "
                   "another quantity? give its column a role, data.roles.state=[<header>] or "
                   "data.roles.ignore=[<header>]" if median > threshold else
                   f"a faulty reading (the column's median is {median:.4g} °C): a campaign "
                   "fitted on must be clean; replay and monitor stream a test campaign with it")
            raise ContractError(f"{values[row - 1]:g} °C is above data.kelvin_threshold_c="
                                f"{threshold:g}: {why}", file=path, column=name, row=row)
    if lowest < ABSOLUTE_ZERO_C:
        row = int(np.argmax(values < ABSOLUTE_ZERO_C)) + 1
        # (lab74) a logger's mark for a value not measured, as AmeriFlux's -9999: said so
        hint = (f": the logger's mark for a value not measured? data.missing_values="
                f"[{values[row - 1]:g}] reads it as missing" if values[row - 1] <= -999 else "")
        raise ContractError(f"{values[row - 1]:g} °C is below absolute zero{hint}",
                            file=path, column=name, row=row)


def _repair_missing(columns: dict, rows: int, path: Path, opts: ReadOptions) -> dict:
    """Validate every data column; trim incomplete edge rows, interpolate gaps.

    Returns ``{"repairs": {column: n}, "trimmed": {"start": n, "end": n}}``; with
    ``missing="keep_errors"`` the ``E_`` columns' missing values are left as they are (a
    volumetric dataset's distance not measured in a cycle) and counted under ``missing``.
    """
    # a distance column empty over a whole campaign is a pose not measured in it: refused as a
    # logger's unused channel, its fix (data.roles.ignore) then failed as a declared pose
    # without columns, so a campaign could not lack a pose the others have
    keep_errors = opts.missing == "keep_errors"
    _refuse_empty({n: c for n, c in columns.items() if not (keep_errors and role(n) == "E")}, path)
    gaps = {}  # column -> sorted positions of its missing values
    kept, sparse = {}, {}
    for name in columns:
        if name != TIME:
            missing = _check_values(_values(columns[name]), name, path, opts)
            if missing.size and opts.missing == "keep_errors" and role(name) == "E":
                kept[name] = missing
            elif missing.size and probe_cycle(name, missing, rows, opts.sparse_targets):
                sparse[name] = missing      # measured now and then: kept, never interpolated
            elif missing.size:
                gaps[name] = missing
    # a sparse target's empty rows before its first measurement (and after its last) are no
    # incomplete edge: kept, the stream warms on their temperatures (the rule: .sparse)
    edges = gaps
    if not edges:
        return {"repairs": {}, "trimmed": {"start": 0, "end": 0}, **_kept(kept, 0, rows, opts),
                **_sparse(sparse, 0, rows)}
    start, stop = _complete_span(rows, edges, path, opts.max_edge_samples)
    for name in columns:
        columns[name] = columns[name].slice(start, stop - start)
    time = _values(columns[TIME])
    repairs = {}
    for name, positions in gaps.items():
        inside = positions[(positions >= start) & (positions < stop)] - start
        if inside.size:
            try:
                _check_gap_lengths(inside, name, start, path, opts.max_gap_samples)
            except ContractError as exc:
                if role(name) != "E":
                    raise
                # an error column: a gap, or a measurement not taken on every row
                raise ContractError(f"{exc.reason} (an error measured only now and then: "
                                    "data.sparse_targets=true leaves its empty cells empty, "
                                    "never interpolated, the models fit on the measured rows)",
                                    file=exc.file, column=exc.column, row=exc.row) from None
            columns[name] = _patched(columns[name], inside, _gap_values(columns[name], time, inside))
            repairs[name] = int(inside.size)
    return {"repairs": repairs, "trimmed": {"start": start, "end": rows - stop},
            **_kept(kept, start, stop, opts), **_sparse(sparse, start, stop)}


def _sparse(sparse: dict, start: int, stop: int) -> dict:
    """``{"sparse_targets": {column: {"measured": rows, "every": rows}}}`` of the ``E_``
    columns read as measured now and then, within the rows kept; {} where there is none."""
    out = {}
    for name, positions in sparse.items():
        inside = positions[(positions >= start) & (positions < stop)] - start
        entry = intermittent(inside, stop - start, "true")
        if entry is not None:
            out[name] = entry
    return {"sparse_targets": out} if out else {}


def _kept(kept: dict, start: int, stop: int, opts: ReadOptions) -> dict:
    """``{"missing": {column: n}}`` of the cells left missing within the rows kept (only with
    ``missing="keep_errors"``)."""
    if opts.missing != "keep_errors":
        return {}
    counts = {name: int(np.sum((p >= start) & (p < stop))) for name, p in kept.items()}
    return {"missing": {name: n for name, n in counts.items() if n}}


def _keep_missing(columns: dict, rows: int, path: Path, opts: ReadOptions) -> dict:
    """Validate every data column and leave its missing values as they are (``missing="keep"``).

    Returns ``{"repairs": {}, "trimmed": {"start": 0, "end": 0}, "missing": {column: n}}``.
    """
    _refuse_empty(columns, path)
    kept = {}
    for name in columns:
        if name != TIME:
            count = _check_values(_values(columns[name]), name, path, opts).size
            if count:
                kept[name] = int(count)
    return {"repairs": {}, "trimmed": {"start": 0, "end": 0}, "missing": kept}


def _complete_span(rows: int, gaps: dict, path: Path, max_edge: int) -> tuple[int, int]:
    """First and past-last row where every column is valid, within the trim limit."""
    incomplete = np.zeros(rows, dtype=bool)
    for positions in gaps.values():
        incomplete[positions] = True
    if incomplete.all():
        raise ContractError("no row has every sensor valid", file=path, column=next(iter(gaps)))
    start, stop = int(np.argmin(incomplete)), rows - int(np.argmin(incomplete[::-1]))
    if start > max_edge:
        name, first = _run_through(gaps, start - 1)
        raise ContractError(f"{start} incomplete rows at the campaign start (first complete row "
                            f"{start + 1}); data.max_edge_samples={max_edge} allows trimming "
                            f"{max_edge}, values are never back-filled",
                            file=path, column=name, row=first + 1)
    if rows - stop > max_edge:
        name, first = _run_through(gaps, stop)
        raise ContractError(f"{rows - stop} incomplete rows at the campaign end (last complete "
                            f"row {stop}); data.max_edge_samples={max_edge} allows trimming "
                            f"{max_edge}, values are never forward-filled",
                            file=path, column=name, row=first + 1)
    return start, stop


def _run_through(gaps: dict, position: int) -> tuple[str, int]:
    """First column missing at ``position``, and where its run of missing values starts."""
    for name, positions in gaps.items():
        starts, lengths = _runs(positions)
        k = int(np.searchsorted(starts, position, side="right")) - 1
        if k >= 0 and position < starts[k] + lengths[k]:
            return name, int(starts[k])
    raise AssertionError(f"no column is missing at {position}")


def _check_gap_lengths(positions: np.ndarray, name: str, offset: int, path: Path,
                       max_gap: int) -> None:
    starts, lengths = _runs(positions)
    too_long = np.flatnonzero(lengths > max_gap)
    if too_long.size:
        row = offset + int(starts[too_long[0]]) + 1
        length = int(lengths[too_long[0]])
        where = f"row {row}" if length == 1 else f"rows {row}-{row + length - 1}"
        longest = int(lengths.max())     # (said: the refusals came one gap at a time)
        most = (f"; its longest gap is {longest} values, data.max_gap_samples={longest} "
                "interpolates every one of this column" if longest > length else "")
        raise ContractError(f"gap of {length} missing value{'s' * (length > 1)} ({where}) is "
                            f"longer than data.max_gap_samples={max_gap}{most}",
                            file=path, column=name, row=row)


def _runs(positions: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Start and length of every run of consecutive integers in sorted ``positions``."""
    breaks = np.flatnonzero(np.diff(positions) != 1) + 1
    first = np.concatenate(([0], breaks))
    last = np.concatenate((breaks - 1, [len(positions) - 1]))
    return positions[first], positions[last] - positions[first] + 1


def _gap_values(column, time: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """Values at ``positions`` on the line between each gap's two valid neighbours."""
    starts, lengths = _runs(positions)
    run = np.repeat(np.arange(len(starts)), lengths)
    before, after = (starts - 1)[run], (starts + lengths)[run]
    v0 = pc.take(column, pa.array(before)).to_numpy()
    v1 = pc.take(column, pa.array(after)).to_numpy()
    weight = (time[positions] - time[before]) / (time[after] - time[before])
    return v0 + weight * (v1 - v0)


def _patched(column, positions: np.ndarray, values: np.ndarray) -> pa.ChunkedArray:
    """``column`` with ``values`` written at the sorted ``positions``."""
    chunks, offset = [], 0
    for chunk in _chunks(column):
        lo, hi = np.searchsorted(positions, [offset, offset + len(chunk)])
        if lo < hi:
            mask = np.zeros(len(chunk), dtype=bool)
            mask[positions[lo:hi] - offset] = True
            # Built by Arrow, so it reuses the pool memory of the chunks it replaces.
            chunk = pc.replace_with_mask(chunk, pa.array(mask), pa.array(values[lo:hi]))
        chunks.append(chunk)
        offset += len(chunk)
    return pa.chunked_array(chunks, type=pa.float64())


