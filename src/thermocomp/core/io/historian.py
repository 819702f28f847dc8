"""A process historian's LONG export (extension): one row per tag sample, ``Timestamp;TagName;
Value;Quality`` (OSIsoft PI, Wonderware, an OPC UA historian, a SCADA trend), read as the wide
record the rest of the reader takes.

Each tag is logged on change (report by exception: its own irregular stamps), so its value
between two of its samples is the first one's: every tag is put onto one grid, ``t0, t0 + p,
...`` with ``p = data.resample_s`` (no default: a missing period is an error naming the key and
the tags' median intervals, never a guess), by SAMPLE AND HOLD (``pandas.merge_asof``,
backward): a grid point takes the tag's last sample at or before it.  ``t0`` is the first time
every tag has a sample (a tag's samples before it but its last, held there, are said
and not read); the grid ends at the record's
last stamp.  A sample whose quality is not Good (``Bad``, ``Uncertain``, an OPC quality byte
below 192) is missing from its stamp to the tag's next sample: the grid's empty cells are then
repaired or refused as a wide file's are (``data.max_gap_samples``: interpolated over at most
that many grid points, else refused naming the tag and the sample that began the gap).

The grid is written to a temporary Parquet file (the time as ISO 8601 text, or seconds, one
column per tag under its name) that the reader reads, as a workbook's sheet is (:mod:`.workbook`):
roles by pattern over the TAG names, units, every check apply unchanged, and a message about
that file names the long file, the tag and the long file's row instead.  Which files are long is
:mod:`.historian_layout`'s.  Refused (exit 2, file,
column, row): a tag with two samples at one stamp holding other values, a value cell of text
where the quality says Good (unless ``data.missing_values`` lists it), a quality no rule reads.
The time column is read as a wide file's is (:func:`.tables.time_of_text`: ISO 8601, day-first,
slashed dates, ``data.time``, ``h:mm:ss`` past 24 h, numbers in the unit ``data.units`` gives:
epoch ms, Excel's serial days), a time it does not read refused with its message.
"""

from __future__ import annotations

import csv
import re
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.compute as pc

from ...base.errors import listed
from ...base.log import logger
from . import marks
from .cells import Runs, run_starts
from .contract import ContractError
from .converted import named_as
from .encoding import UTF8
from .historian_layout import Layout, quality_of
from .influx import influx_samples
from .roles import time_unit
from .separators import reads_as_number
from .tables import time_of_text
from .timestamps import DATE, TIME_OF_DAY, on_local_clock, said_if_not_seconds
from .units import UNITS

PERIOD_KEY = "data.resample_s"
_GRID_ROW = re.compile(r"\b(rows? \d+(?:-\d+)?)")
SILENCE_PERIODS = 100     # a stretch without any tag's sample this many grid periods long: said


@dataclass(frozen=True)
class Wide:
    """A long file held onto its grid: the ``frame`` (time column first, one per tag), the
    ``period`` (s), the long file's data ``rows`` each grid cell's value came from (-1: none),
    the ``layout`` read, the tags' median ``intervals`` (s)."""

    frame: pd.DataFrame
    period: float
    rows: pd.DataFrame
    layout: Layout
    intervals: dict


def read_long(path: Path, opts, layout: Layout) -> Wide:
    """The long file held onto the grid of ``data.resample_s`` (see the module)."""
    samples, intervals, origin, zone = tag_samples(path, opts, layout)
    names = layout.header
    if opts.resample_s is None:
        raise ContractError(
            f"a historian's long file (one row per tag sample: {names[layout.tag]!r} names the "
            f"tag): its tags are held onto a grid whose period {PERIOD_KEY} gives, and it is not "
            f"given; the tags' median intervals: {_intervals(intervals)} (`thermocomp init` "
            "proposes the fastest error tag's)", file=path)
    frame, rows = _held(samples, float(opts.resample_s), path, origin)
    frame.insert(0, names[layout.time], _stamps(frame.index.to_numpy(), origin, zone))
    return Wide(frame.reset_index(drop=True), float(opts.resample_s), rows, layout, intervals)


def tag_samples(path: Path, opts, layout: Layout) -> tuple[pd.DataFrame, dict, object, object]:
    """The long file's samples (``time`` s since its first stamp, ``tag``, ``value``: NaN where
    not Good, ``row``), sorted by tag and time, one per tag and stamp; each tag's median
    interval (s); the first stamp (None: the time is seconds) and its zone."""
    if layout.influx:                         # InfluxDB's tables: indexed by their lines
        raw = influx_samples(path, opts.encoding)
    else:
        raw = pd.read_csv(path, sep=layout.delimiter, skiprows=layout.skip, header=0, dtype=str,
                          keep_default_na=False, skip_blank_lines=False, encoding=opts.encoding,
                          usecols=[i for i in (layout.time, layout.tag, layout.value,
                                               layout.quality) if i is not None],
                          quoting=csv.QUOTE_MINIMAL)
        raw.columns = [layout.header[i] for i in sorted(
            i for i in (layout.time, layout.tag, layout.value, layout.quality) if i is not None)]
    raw = raw.apply(lambda s: s.str.strip())
    raw = raw[(raw != "").any(axis=1)]        # blank lines: left out
    row = raw.index.to_numpy() + 1            # the data row (1-based; InfluxDB's: the line)
    names = layout.header
    tag = raw[names[layout.tag]]
    if (tag == "").any():
        at = int(np.argmax((tag == "").to_numpy()))
        raise ContractError("a sample without its tag", file=path, column=names[layout.tag],
                            **_at(layout, int(row[at])))
    good = _good(raw, names, layout, row, path)
    value = _values(raw[names[layout.value]], good, tag, opts, layout, row, path)
    seconds, origin, zone = _times(raw[names[layout.time]], tag, opts, layout, row, path)
    samples = pd.DataFrame({"time": seconds, "tag": tag.to_numpy(), "value": value,
                            "row": row}).sort_values(["tag", "time", "row"], kind="stable")
    samples = _without_repeats(samples, path, names[layout.value], origin, layout)
    intervals = {t: float(np.median(np.diff(g["time"].to_numpy()))) if len(g) > 1 else np.nan
                 for t, g in samples.groupby("tag", sort=False)}
    return samples, intervals, origin, zone


def proposed_period(intervals: dict, tags) -> tuple[float, str]:
    """The grid period ``init`` proposes, and the tag it is taken from: the shortest median
    interval of ``tags`` (the error tags, a tie the first's; none: every tag), to two digits (a
    collector's latency and a deadband's skipped scans put it at 10.01 s for a 10 s scan).  On
    the error's own rate each of its samples lands on a grid row of its own: a shorter period
    only repeats held values (more rows, a lag in samples spanning less time), a longer one
    drops error samples."""
    # (in the order of ``tags``: a tie goes to the first named)
    timed = {t: intervals[t] for t in tags if t in intervals and np.isfinite(intervals[t])
             and intervals[t] > 0}
    timed = timed or {t: v for t, v in intervals.items() if np.isfinite(v) and v > 0}
    if not timed:
        raise ContractError("no tag has two samples: no period to hold the tags onto")
    tag = min(timed, key=timed.get)
    return float(f"{timed[tag]:.2g}"), tag


PERIOD_COMMENT = ("# the grid a historian's tags are held onto (sample and hold): the median "
                  "interval of the\n# fastest error tag, proposed by `thermocomp init`; a "
                  "shorter one repeats held values,\n# a longer one drops error samples")


def intervals_said(intervals: dict) -> str:
    """``tag 10 s, ...``: each tag's median interval, the fastest first."""
    return _intervals(intervals)


def _intervals(intervals: dict, most: int = 12) -> str:
    order = sorted(intervals, key=lambda t: (np.nan_to_num(intervals[t], nan=np.inf), t))
    return listed([f"{t} {intervals[t]:.4g} s" if np.isfinite(intervals[t]) else f"{t} (one sample)"
                   for t in order], most=most)


def _good(raw, names, layout, row, path) -> np.ndarray:
    if layout.quality is None:
        return np.ones(len(raw), bool)
    column = raw[names[layout.quality]]
    read = {q: quality_of(q) if q else True for q in column.unique()}
    unknown = [q for q, v in read.items() if v is None]
    if unknown:
        at = int(np.argmax(column.isin(unknown).to_numpy()))
        raise ContractError(f"quality {column.iloc[at]!r} is read by no rule (Good, Bad, "
                            "Uncertain and their OPC UA names, or an OPC quality byte: 192 Good, "
                            "64 Uncertain, 0 Bad): correct the file, or leave the column out "
                            "(every sample then Good)", file=path, column=names[layout.quality],
                            **_at(layout, int(row[at])))
    return column.map(read).to_numpy(bool)


def _values(column: pd.Series, good: np.ndarray, tag: pd.Series, opts, layout, row, path
            ) -> np.ndarray:
    text = column.str.replace("\u2212", "-", regex=False)
    if opts.thousands:
        text = text.str.replace(opts.thousands, "", regex=False)
    if layout.decimal != ".":
        text = text.str.replace(layout.decimal, ".", regex=False)
    value = pd.to_numeric(text, errors="coerce").to_numpy(float)
    numbered = marks.hits(value, opts.missing_values)        # -9999 however written (lab74)
    marked = (column.isin(marks.texts(opts.missing_values)).to_numpy() | (column == "").to_numpy()
              | numbered)
    bad = np.isnan(value) & ~marked & good & ~column.str.lower().isin(["nan"]).to_numpy()
    if bad.any():
        at = int(np.argmax(bad))
        raise ContractError(
            f"value {column.iloc[at]!r} of tag {tag.iloc[at]!r} is not a number, and its quality "
            "says Good: a historian's state text (a digital state, 'I/O Timeout')? list it in "
            f"data.missing_values (['{column.iloc[at]}'])", file=path,
            column=layout.header[layout.value], **_at(layout, int(row[at])))
    return np.where(good & ~numbered, value, np.nan)


def _times(column: pd.Series, tag: pd.Series, opts, layout: Layout, row, path
           ) -> tuple[np.ndarray, object, object]:
    """Seconds (float, since the first stamp), the first stamp (a Timestamp; None: the file's
    time is a number or an elapsed time) and its zone (stamps without an offset with
    ``data.timezone``: UTC), read as a wide file's time column is (:func:`.tables.time_of_text`:
    every form, ``data.time`` and the refusals the same; a number in the unit ``data.units``
    or the header gives, Excel's serial days with ``d``)."""
    header = column.name
    if (column == "").any():
        raise ContractError("missing time value", file=path, column=header,
                            **_at(layout, int(row[int(np.argmax((column == "").to_numpy()))])))
    text = column
    # a number read as the wide reader's CSV reader reads one (data.decimal its point)
    if reads_as_number(column.iloc[0], layout.decimal, opts.thousands):
        text = text.str.replace("\u2212", "-", regex=False)
        text = text.str.replace(opts.thousands, "", regex=False) if opts.thousands else text
        text = text.str.replace(layout.decimal, ".", regex=False)
    wide = replace(opts, decimal=".", thousands=None)
    try:
        read = time_of_text(pa.chunked_array([pa.array(text.to_numpy(str), pa.string())]), path,
                            wide, header)
    except ContractError as exc:     # its row among the column's cells: the long file's row
        at = None if exc.row is None else int(row[exc.row - 1])
        cell = str(column.iloc[exc.row - 1]) if exc.row is not None else ""
        if TIME_OF_DAY.fullmatch(cell) or DATE.fullmatch(cell):
            # the wide reader's way (a second column joined to it, data.sample_period_s) is no
            # way here: every sample needs its own time
            what = "a time of day without its date" if TIME_OF_DAY.fullmatch(cell) else \
                "a date without a time of day"
            raise ContractError(
                f"value {cell!r} is {what}: a historian's long file needs each sample's date and "
                f"time in its time column (export the timestamps whole); or, the time elapsed "
                f"since the start (h:mm:ss), data.time=elapsed", file=path, column=header,
                **_at(layout, at)) from None
        raise ContractError(exc.reason, file=path, column=header, **_at(layout, at)) from None
    if pa.types.is_duration(read.type):           # an elapsed time, h:mm:ss
        seconds = pc.cast(read, pa.int64()).to_numpy() / 1e9
        return seconds - seconds.min(), None, None
    if not pa.types.is_timestamp(read.type):      # a number: its unit's seconds
        number = pc.cast(read, pa.float64()).to_numpy()
        scale = _time_scale(header, opts, path)
        if time_unit(header, opts) is None:      # (milliseconds? Excel's days? said)
            said_if_not_seconds(np.unique(number), path, header)
        seconds = (number - number.min()) * scale
        # a unit's seconds to the microsecond: 46000.5 serial days hold no finer, and a sample
        # 1e-7 s past a grid point would miss it (the grid starts at a sample's own time)
        return (seconds if scale == 1.0 else np.round(seconds, 6)), None, None
    # (by position: the rows' labels skip blank lines, a Series given would be aligned by label)
    stamps = pd.Series(read.to_pandas().array, index=column.index)
    if opts.timezone and stamps.dt.tz is None:
        stamps = _on_clock(stamps, tag, opts.timezone, row, path, header, layout)
    zone = getattr(stamps.dt, "tz", None)
    origin = stamps.min()
    return (stamps - origin).dt.total_seconds().to_numpy(float), origin, zone


def _at(layout: Layout, row: int | None) -> dict:
    """Where a message points: a long file's data row, or InfluxDB's line (its tables' rows
    between annotations and blank lines: the line is what an editor shows)."""
    return {"line": row} if layout.influx else {"row": row}


def _word(layout: Layout) -> str:
    return "line" if layout.influx else "data row"


def _time_scale(header: str, opts, path) -> float:
    """The seconds one unit of the time column is (``data.units={<its header>: ms}``: 0.001)."""
    unit = time_unit(header, opts)
    if unit is None:
        return 1.0
    scale = UNITS["time"].get(unit.lower().replace(" ", ""))
    if scale is None:
        raise ContractError(f"{header!r}: unit {unit!r} is not a time's (s, ms, min, h, d)",
                            file=path, column=header)
    return scale[0]


def _on_clock(stamps: pd.Series, tag: pd.Series, zone: str, row, path, header, layout
              ) -> pd.Series:
    """Stamps without an offset on ``zone``'s local clock, as UTC, as a wide file's are
    (:func:`.timestamps.on_local_clock`), each tag's in its file order: a tag logs through the
    hour the clock repeats in order, while the tags' rows interleave (a sort by stamp would
    mix the two passes)."""
    ns = stamps.to_numpy("datetime64[ns]").astype("int64")
    out = np.empty_like(ns)
    for positions in pd.Series(tag.to_numpy()).groupby(tag.to_numpy()).indices.values():
        try:
            out[positions] = on_local_clock(ns[positions], zone, path, header)
        except ContractError as exc:     # its row among the tag's samples: the file's row
            raise ContractError(exc.reason, file=path, column=header,
                                **_at(layout, int(row[positions[exc.row - 1]]))) from None
    return pd.Series(pd.to_datetime(out, utc=True), index=stamps.index)


def _without_repeats(samples: pd.DataFrame, path, value_header: str, origin, layout
                     ) -> pd.DataFrame:
    """One sample per tag and stamp: a repeat of the same value dropped, another value refused."""
    twice = samples.duplicated(["tag", "time"], keep=False)
    if not twice.any():
        return samples
    groups = samples[twice].groupby(["tag", "time"], sort=False)["value"]
    differ = groups.transform(lambda v: v.nunique(dropna=False) > 1)
    if differ.any():
        clash = samples[twice][differ.to_numpy()]
        first, second = clash.iloc[0], clash.iloc[1]
        raise ContractError(
            f"tag {first['tag']!r} has two samples at {_said(first['time'], origin)} with other "
            f"values ({float(first['value']):g} in {_word(layout)} {int(first['row'])}, "
            f"{float(second['value']):g} in "
            "this one): which one the tag held is not known; delete one", file=path,
            column=value_header, **_at(layout, int(second["row"])))
    return samples.drop_duplicates(["tag", "time"], keep="first")


def _held(samples: pd.DataFrame, period: float, path, origin) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Every tag on the grid by sample and hold; the long rows each cell's value came from."""
    firsts = samples.groupby("tag", sort=False)["time"].min()
    start, end = float(firsts.max()), float(samples["time"].max())
    # each tag's last sample at or before the start is held there: only its earlier ones are
    # not read (loggers started a few ms apart lose none: it was said for every file, labfiles62)
    early = samples[samples["time"] <= start]
    unread = int((early["time"] < early["tag"].map(early.groupby("tag")["time"].max())).sum())
    if unread:
        logger.warning("%s: the grid (data.resample_s=%g) starts where every tag has a sample, "
                       "%.4g s after the first stamp (tag %r logs first at %s): %d sample(s) "
                       "before it are not read", path, period, start - samples["time"].min(),
                       firsts.idxmax(), _said(start, origin), unread)
    count = int(np.floor((end - start) / period + 1e-9)) + 1
    grid = _not_silent(start + period * np.arange(count), np.sort(samples["time"].to_numpy()),
                       period, path, origin)
    count = len(grid)
    tags = list(dict.fromkeys(samples.sort_values("row")["tag"]))
    left = pd.DataFrame({"time": np.repeat(grid, len(tags)), "tag": np.tile(tags, count)})
    held = pd.merge_asof(left, samples.sort_values("time", kind="stable"), on="time", by="tag",
                         direction="backward", allow_exact_matches=True)
    value = held.pivot(index="time", columns="tag", values="value")[tags]
    rows = held.pivot(index="time", columns="tag", values="row")[tags].fillna(-1).astype(int)
    value.columns.name = rows.columns.name = None
    return value, rows.reset_index(drop=True)


def _not_silent(grid: np.ndarray, stamps: np.ndarray, period: float, path, origin
                ) -> np.ndarray:
    """The grid without its points inside a silence, a stretch where no tag logged for over
    :data:`SILENCE_PERIODS` periods (a collector or a machine off: nothing is held over it, the
    record has no rows there, as a logger's pause), said."""
    steps = np.diff(stamps)
    long = np.flatnonzero(steps > SILENCE_PERIODS * period)
    if not long.size:
        return grid
    inside = np.zeros(len(grid), bool)
    for k in long:
        inside |= (grid > stamps[k]) & (grid < stamps[k + 1])
    k = long[np.argmax(steps[long])]
    logger.warning("%s: %d stretch(es) where no tag logged for over %d grid periods (data."
                   "resample_s=%g), the longest %.4g min from %s: left out, no tag held over them "
                   "(%d grid rows)", path, long.size, SILENCE_PERIODS, period, steps[k] / 60,
                   _said(stamps[k], origin), int(inside.sum()))
    return grid[~inside]


def _said(seconds: float, origin) -> str:
    if origin is None:
        return f"{seconds:g} s"
    return (origin + pd.Timedelta(seconds=round(seconds, 3))).isoformat(timespec="milliseconds")


def _stamps(seconds: np.ndarray, origin, zone) -> list:
    """The grid's times as the wide file writes them: ISO 8601 (``Z`` for UTC), or seconds."""
    if origin is None:
        return [repr(float(s)) for s in seconds]
    stamps = origin + pd.to_timedelta(np.round(seconds * 1e6).astype("int64"), unit="us")
    if zone is not None:
        stamps = stamps.tz_convert("UTC").tz_localize(None)
    fraction = (stamps.microsecond != 0).any()
    text = stamps.strftime("%Y-%m-%dT%H:%M:%S.%f" if fraction else "%Y-%m-%dT%H:%M:%S")
    return [t + "Z" for t in text] if zone is not None else list(text)


# --- the file the reader reads ----------------------------------------------------------------

_CACHE: dict = {}


def held_wide(path: Path, opts, layout: Layout) -> Wide:
    """:func:`read_long`, kept for the file as it is and the options that read it (each look
    at the file, init's and the read's, converts it once)."""
    stat = path.stat()
    key = (str(path), stat.st_mtime_ns, stat.st_size, opts.encoding, opts.time, opts.thousands,
           tuple(map(str, opts.missing_values)), opts.resample_s, opts.timezone,
           tuple(sorted(opts.units.items())), layout)
    if key not in _CACHE:
        _CACHE.clear()                        # (one record at a time: its memory only)
        _CACHE[key] = read_long(path, opts, layout)
    return _CACHE[key]


def grid_runs(path: Path, opts, layout: Layout) -> list:
    """Each tag's runs of missing grid rows (after a sample not Good or without a value, to
    the tag's next one) in the grid the read holds it onto, counted as the read counts them: a
    tag's run is its own, a 10 s probe's six Bad samples six rows, never a 300 s tag's 30 each
    (lab83); each run said with the long file's row that began it."""
    wide = held_wide(path, opts, layout)
    runs = []
    for tag in wide.rows.columns:
        missing = wide.frame[tag].isna().to_numpy()
        if not missing.any():
            continue
        gap, edge, starts = run_starts(missing)
        said = {k: (f"from {_word(layout)} {wide.rows[tag].iloc[i]} of {path.name}"
                    if wide.rows[tag].iloc[i] > 0 else f"from {path.name}'s start")
                for k, i in starts.items()}
        runs.append(Runs(str(tag), gap, edge, np.flatnonzero(missing), len(missing),
                          said.get("gap", ""), said.get("edge", "")))
    return runs


def wide_options(opts, layout: Layout):
    """The read options of the wide (Parquet) file a long one is written to: its time is
    seconds or ISO 8601 text (the long file's unit and format read already)."""
    time = opts.time if opts.time in ("auto", "seconds") else "auto"
    header = layout.header[layout.time]
    # (its unit, data.units' or the header's, read into the grid's seconds already)
    units = opts.units if time_unit(header, opts) is None else {**opts.units, header: "s"}
    # (the grid is the resampling: read as it is, a silence left without rows)
    return replace(opts, delimiter=",", decimal=".", thousands=None, encoding=UTF8,
                   time=time, missing_values=[], resample_s=None, units=units)


@contextmanager
def long_as_wide(path: Path, opts, layout: Layout, rows: int | None = None) -> Iterator[Path]:
    """The long file ``path`` as a temporary wide Parquet file (its first ``rows`` only, where
    given), removed after; a :class:`ContractError` or a warning about it names ``path``, the
    tag and the long file's row the grid cell's value came from."""
    wide = held_wide(path, opts, layout)
    with tempfile.TemporaryDirectory(prefix="thermocomp-long-") as tmp:
        # Parquet, not CSV: every digit kept without a text round trip (a CSV file of the
        # lathe's 181,440 x 21 grid cost 4 s to write and 5 s to read again)
        out = Path(tmp) / f"{path.stem}.parquet"
        frame = wide.frame if rows is None else wide.frame.head(rows)
        frame.to_parquet(out, index=False)
        with named_as(out, str(path), lambda exc: _located(exc, out, path, wide)):
            yield out


def _located(exc: ContractError, temp: Path, path: Path, wide: Wide) -> ContractError:
    """A message about the grid's file as about the long file: the grid row's time, and the
    long row the tag's cell came from (the sample that began a gap)."""
    if exc.file is None or Path(exc.file) != temp:
        return exc
    reason = exc.reason.replace(str(temp), str(path))
    tag = exc.column if exc.column in wide.rows.columns else next(   # (its contract name)
        (t for t in wide.rows.columns if repr(t) in reason), None)
    if exc.row is None or tag is None:
        return ContractError(reason, file=path, column=exc.column)
    reason = _GRID_ROW.sub(r"grid \1", reason)
    grid = min(max(exc.row - 1, 0), len(wide.frame) - 1)
    time = wide.frame.iloc[grid, 0]
    source = int(wide.rows[tag].iloc[grid])
    said = (f" (the grid row at {time}, data.resample_s={wide.period:g}"
            + (f"; the tag's sample there is {_word(wide.layout)} {source} of the long file)"
               if source > 0
               else "; the tag has no sample before it)"))
    return ContractError(reason + said, file=path, column=tag,
                         **_at(wide.layout, source if source > 0 else None))
