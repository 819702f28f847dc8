"""One run logged by two loggers read as one campaign (extension, twolog70): the temperature
file and the error file (:mod:`.loggers` pairs them) each read and checked as a campaign file is
(its own separators, time, units, gaps and repairs, a message naming its own file and row),
then joined by time.

The rows are the ERROR logger's samples: the error is what is scored, so each scored row is an
error as measured, never one interpolated between two probe readings (nor repeated: held errors
would weigh a slow probe's reading once per temperature sample).  Every column of the
temperature file is held, its last sample at or before the error's time, what a control has
then, and the row's time is that sample's, the clock a control's models step on (rate83:
temperatures were interpolated between the samples around the error, reading the next one up to
a period ahead, at the error's time: the scored rows were no stream's; fed the samples, the
deployed stream commits its dynamic models' steps once a training period, cadence72, on the
samples the rows are).  An error logger faster than the temperatures (two errors on one sample)
keeps the errors' times.  The times are put on one clock: timestamps on both sides as instants,
the error logger's moved back by ``data.join.offset_s`` (how far its clock runs ahead); seconds
from each logger's start on both sides are taken as started together (said).  Error rows outside
the temperature logger's span (one logger started late or stopped early), or inside a
temperature step longer than ``data.join.tolerance_s`` (default 3 times the temperature logger's
median step: a pause of the DAQ), are cut, said once per run.  Refused (exit 2), naming the
files: times that do not overlap (fewer than 2 rows in common), timestamps on one side and
seconds on the other, a column name in both files.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pyarrow as pa

from ...base.log import logger
from ..timerule import median_step
from .contract import TIME, ContractError
from .options import ReadOptions

TOLERANCE_STEPS = 3.0     # data.join.tolerance_s's default, in temperature logger periods


def joined(temps: pa.Table, temp_report: dict, errors: pa.Table, error_report: dict,
           files: tuple, opts: ReadOptions) -> tuple[dict, dict]:
    """The columns (``time`` in seconds from the first joined row) and report of the run whose
    temperature file (``files[0]``) read as ``temps`` and error file as ``errors``."""
    temp_file, error_file = files
    clash = sorted((set(temps.column_names) & set(errors.column_names)) - {TIME})
    if clash:
        raise ContractError(f"column in both files of one run ({temp_file.name} and "
                            f"{error_file.name}): which logger's to read is not known; leave one "
                            "out (data.roles.ignore)", file=error_file, column=clash[0])
    t_temp = temps.column(TIME).to_numpy()
    t_error = errors.column(TIME).to_numpy() + _shift(temp_report, error_report, files) \
        - opts.join_offset_s
    period = median_step(t_temp)
    tolerance = opts.join_tolerance_s or TOLERANCE_STEPS * period
    keep, cut = _covered(t_temp, t_error, tolerance)
    if keep.sum() < 2:
        raise ContractError(
            f"its times ({_span(t_temp, temp_report)}) and {error_file.name}'s "
            f"({_span(t_error, temp_report)} on this file's clock, data.join.offset_s="
            f"{opts.join_offset_s:g}) have {int(keep.sum())} error sample(s) in common: the two "
            "loggers' files of one run must overlap in time (check both clocks' dates and "
            "data.join.offset_s)", file=temp_file)
    if any(cut.values()):
        logger.warning("%s: error samples cut where %s has no temperatures around them: %s (%s)",
                       error_file.name, temp_file.name, _said(cut, tolerance),
                       "data.join.tolerance_s" if cut["gaps"] else "the run's rows start and "
                       "end where both loggers logged")
    after = np.searchsorted(t_temp, t_error[keep], side="right") - 1   # never a later sample
    # a row's time is its sample's, the instant of what a control holds at the error's (its
    # dynamic models stepped on the samples' clock); an error logger faster: the errors' own
    grid = t_temp[after] if np.unique(after).size == after.size else t_error[keep]
    columns = {TIME: pa.array(grid - grid[0])}
    for name in temps.column_names[1:]:
        columns[name] = pa.array(temps.column(name).to_numpy(zero_copy_only=False)[after])
    for name in errors.column_names[1:]:
        columns[name] = pa.array(errors.column(name).to_numpy(zero_copy_only=False)[keep])
    return columns, _report(temp_report, error_report, grid, files, opts, cut, period)


def _shift(temp_report: dict, error_report: dict, files: tuple) -> float:
    """Seconds from the temperature logger's first sample to the error logger's (0 where
    neither file has timestamps: both taken as started together, said)."""
    origins = [r.get("time_origin") for r in (temp_report, error_report)]
    if origins == [None, None]:
        logger.warning("%s and %s: times from each logger's start, no timestamps: taken as "
                       "started together (data.join.offset_s: how far the error logger's "
                       "clock runs ahead)", files[0].name, files[1].name)
        return 0.0
    if None in origins:
        stamped = files[1 - origins.index(None)]
        raise ContractError(f"of one run's two files only {stamped.name} has timestamps: the "
                            "other's seconds from its start cannot be put on its clock; give "
                            "both files timestamps", file=files[0])
    try:
        return (pd.Timestamp(origins[1]) - pd.Timestamp(origins[0])).total_seconds()
    except TypeError:          # one with an offset, one without
        raise ContractError(f"{files[1].name}'s timestamps carry a UTC offset and "
                            f"{files[0].name}'s not (or the other way round): set "
                            "data.timezone (the zone of the ones without)", file=files[0]) from None


def _covered(t_temp: np.ndarray, t_error: np.ndarray, tolerance: float
             ) -> tuple[np.ndarray, dict]:
    """The error samples with temperature samples around them at most ``tolerance`` apart,
    and the cut ones counted: before the first temperature, after the last, in a longer step."""
    before, after = t_error < t_temp[0], t_error > t_temp[-1]
    inside = ~(before | after)
    right = np.clip(np.searchsorted(t_temp, t_error, side="left"), 1, len(t_temp) - 1)
    exact = t_temp[right] == t_error
    wide = inside & ~exact & (t_temp[right] - t_temp[right - 1] > tolerance)
    wide &= t_error != t_temp[0]
    return inside & ~wide, {"before": int(before.sum()), "after": int(after.sum()),
                            "gaps": int(wide.sum())}


def _said(cut: dict, tolerance: float) -> str:
    parts = []
    if cut["before"]:
        parts.append(f"{cut['before']} before its first sample (its logger started later)")
    if cut["after"]:
        parts.append(f"{cut['after']} after its last (it stopped earlier)")
    if cut["gaps"]:
        parts.append(f"{cut['gaps']} inside its steps longer than {tolerance:g} s")
    return ", ".join(parts)


def _span(seconds: np.ndarray, temp_report: dict) -> str:
    origin = temp_report.get("time_origin")
    if origin is None:
        return f"{seconds[0]:g} .. {seconds[-1]:g} s"
    first, last = (pd.Timestamp(origin) + pd.Timedelta(seconds=float(s))
                   for s in (seconds[0], seconds[-1]))
    return f"{first.isoformat()} .. {last.isoformat()}"


def _report(temp_report: dict, error_report: dict, grid: np.ndarray, files: tuple,
            opts: ReadOptions, cut: dict, period: float) -> dict:
    """The run's read report: the error file's (its rows are the run's), each mapping of both
    files' (renames, repairs, conversions) merged, the pair said."""
    report = {**temp_report, **error_report}
    for key, value in temp_report.items():
        if isinstance(value, dict) and isinstance(error_report.get(key), dict):
            report[key] = {**value, **error_report[key]}
    report["rows"] = len(grid)
    if temp_report.get("time_origin") is not None:
        start = pd.Timestamp(temp_report["time_origin"]) + pd.Timedelta(seconds=float(grid[0]))
        report["time_origin"] = start.isoformat()
    converted = {*temp_report.get("converted", []), *error_report.get("converted", [])}
    if converted:
        report["converted"] = sorted(converted)
    report["paired"] = {"temperatures": files[0].name, "errors": files[1].name,
                        "periods_s": [period, median_step(grid)],
                        "offset_s": opts.join_offset_s, "cut": cut}
    return report
