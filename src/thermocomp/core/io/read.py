"""Read, validate and ingest datasets in the contract of ``DATA_FORMAT.md``.

A dataset folder holds a manifest ``campaigns.csv`` and one ``.csv`` or
``.parquet`` file per campaign (or ``data.path`` is one such file, a record cut by
:mod:`.record`).  Every campaign goes through the same steps,
column by column on an Arrow table so that memory stays bounded by about one
copy of the campaign:

1. load (``pyarrow.csv.read_csv`` with every data column typed ``float64``, or
   ``pyarrow.parquet.read_table``; separator and decimal mark detected by :mod:`.sniff`) and
   rename columns through ``data.columns`` and ``data.roles`` (:mod:`.roles`, units converted);
2. check names: only ``time``, ``T_*``, ``E_*``, ``S_*``; at least one ``E_``;
3. build ``time`` in seconds (float seconds as given, ISO 8601 timestamps as
   seconds since the first sample, or ``row * sample_period_s``) and require
   it strictly increasing;
4. check values (finite, not all missing, temperatures in °C, no unit changing part
   way through a file) and deal with missing values (see below);
5. optionally resample onto a uniform grid; order the columns ``time``, then
   ``T_``, ``E_``, ``S_`` in file order.

Missing values
--------------
Missing values are empty cells (and the usual null spellings ``NA``, ``NaN``,
``null``, ...).  A repaired campaign never contains NaN: downstream code can
rely on complete rows.  Nothing is invented without a config key saying so:

* *interior gaps* (a run of missing values between two valid samples of a
  column, including an isolated missing ``E_`` value) of at most
  ``max_gap_samples`` samples are linearly interpolated in time and counted
  per column in the report; a longer gap is a :class:`ContractError` naming
  the column and the gap's first row.  With the default ``0`` every gap is
  refused.
* *edges*: rows at the start or the end of a campaign where some column is
  missing are never filled, because the contract references ``T_`` and ``E_``
  to the first valid sample and a back-filled value would fake that reference.
  Up to ``max_edge_samples`` such rows (default ``0``) are dropped at each end
  (counted in the report under ``trimmed``); more is a :class:`ContractError`.
  An ``E_`` column measured now and then (``data.sparse_targets``) has no edge:
  the rows before its first measurement and after its last are read, batch and
  stream alike (:mod:`.sparse`: a stream warms on their temperatures).

``ReadOptions.missing="keep"`` (not a data config key: the ``monitor`` stage
passes it through ``read_dataset(..., missing="keep")`` to stream a campaign
as the machine saw it) skips both repairs: missing values stay NaN, no row is
trimmed, no gap is refused, and the report counts the cells kept per column
(``missing``).  Everything else is still refused, including a column with no
valid value and a missing ``time``.  ``missing="keep_errors"`` (a volumetric
dataset: an empty ``E_`` cell is a distance not measured in that cycle) keeps
the ``E_`` columns' missing values and counts them so, and repairs or refuses
the other columns' as above.

Row numbers in error messages are 1-based data rows of the source file,
header excluded; a CSV file's message names the row's line in the file too (:mod:`.lines`).
"""

from __future__ import annotations

import contextlib
import functools
import json
import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa

from ...base.files import atomic_dir, folder_digest, write_json
from ...base.log import logger
from ..timerule import median_step
from .bits import decoded
from .clocksets import unfound
from .contract import (
    AMBIENT_C,
    MANIFEST,
    TIME,
    ContractError,
    Dataset,
    ambient_source,
    is_ambient,
    role,
)
from .dayfirst import WAY
from .derived import sparse_derived, with_derived, without_derived
from .instants import START, start_instants, start_stamp
from .joined import joined
from .lines import Lines
from .loggers import (
    ERROR_FILE,
    NO_ERROR,
    errors_elsewhere,
    named_error_file,
    paired_id,
    partner,
    unrecorded,
)
from .manifest import (
    apply_split_overrides,
    campaign_files,
    read_manifest,
    said_subfolders,
    subfolder_runs,
)
from .options import ROLE_ORDER, RUN_ROLE, ReadOptions
from .own_headers import with_own_header
from .plain import as_read, is_lab_file, lab_dayfirst
from .record import check_record_file, cut, hold_out, record_id, shares
from .roles import RUN, split_unit, time_unit
from .runs import (
    looks_like_run_counter,
    pause_blocks,
    run_blocks,
    run_ends,
    run_hint,
    run_values,
)
from .sheetruns import several_runs, sheet_parts
from .slashed import record_order, rows_tell
from .slashed_rows import read_in
from .sparse import measured_on, on_grid, said, sparse_totals
from .starts import campaign_starts, commented_start
from .steps import check_unit_steps
from .tables import NoRows, _load_csv, _load_parquet, _ordered, _values, parquet
from .timestamps import CLOCK, OF_DAY, seconds_of_day
from .values import (
    _check_periods,
    _error_ranges,
    _keep_missing,
    _repair_missing,
    _set_time_seconds,
    _warn_error_ranges,
)

INGEST_REPORT = "ingest_report.json"
MIN_ROWS = 2  # the first sample is the reference: one more is needed to have anything to score
MAX_GRID_ROWS = 5_000_000
_READ_ATTEMPTS = 5
DEAD_ROLES = ("E", "T")   # columns said when constant over a whole campaign (a dead channel)


# ---------------------------------------------------------------------------
# Resampling and assembly


def _check_length(rows: int, path: Path, what: str) -> None:
    if rows < MIN_ROWS:
        raise ContractError(f"the campaign has {rows} {what}sample(s): at least {MIN_ROWS} are "
                            "needed (the first is the reference, the others are scored)",
                            file=path)


def _check_fahrenheit(columns: dict, path: Path, threshold: float | None, start: int) -> None:
    """A lab's coldest sensor sits near ambient at a campaign's first sample: if even the
    coldest ``T_`` is above ``threshold`` (°C) there, the file is in °F."""
    first = {n: c[0].as_py() for n, c in columns.items() if role(n) == "T"}
    first = {n: v for n, v in first.items() if v is not None and not math.isnan(v)}  # kept missing
    if threshold is None or not first:
        return
    name = min(first, key=first.get)
    if first[name] > threshold:
        raise ContractError(f"the coldest temperature at the first sample is {first[name]:g} °C, "
                            f"above data.fahrenheit_threshold_c={threshold:g}: temperatures look "
                            "like °F, convert to °C", file=path, column=name, row=start + 1)


def _resample(columns: dict, step: float, path: Path, max_factor: float,
              sparse=()) -> None:
    """Linear interpolation of every column onto ``t0, t0 + step, ...``; a column of ``sparse``
    (a target measured now and then) is not interpolated: each measurement is put on the grid
    point nearest its time, the others left empty (:func:`.sparse.on_grid`)."""
    time = _values(columns[TIME])
    count = (time[-1] - time[0]) / step + 1
    if not count <= min(max_factor * len(time), MAX_GRID_ROWS):  # before allocating it
        raise ContractError(f"data.resample_s={step:g} would make {count:.4g} rows from "
                            f"the file's {len(time)} (at most data.max_resample_factor={max_factor:g} "
                            f"times the file's rows and {MAX_GRID_ROWS:.0e})", file=path)
    count = int(math.floor((time[-1] - time[0]) / step + 1e-9)) + 1
    grid = time[0] + step * np.arange(count)
    for name in columns:
        if name in sparse:
            columns[name] = pa.array(on_grid(grid, time, _values(columns[name])))
        elif name != TIME:
            columns[name] = pa.array(np.interp(grid, time, _values(columns[name])))
    columns[TIME] = pa.array(grid)


def read_campaign(path: str | Path, cfg: Mapping | ReadOptions | None = None,
                  one_run: bool = False, errors: Path | None = None) -> tuple[pa.Table, dict]:
    """Read and validate one campaign file into an Arrow table.

    Parameters
    ----------
    path : str or Path
        A ``.csv`` or ``.parquet`` campaign file, or an Excel workbook (``.xlsx``, ``.xlsm``):
        its sheet ``data.sheet`` (the first) read as its CSV export (:mod:`.workbook`).
    cfg : mapping or ReadOptions, optional
        The ``data`` config (see :func:`read_dataset`).
    one_run : bool
        ``path`` is a folder's campaign file: a TDMS or MATLAB file of several runs is refused.
    errors : Path, optional
        The file of the run's errors, its other logger's, as a manifest's ``error_file`` names
        it (:func:`.loggers.named_error_file`); without it, a file without an error column is
        joined with the one its name pairs it with (:func:`.loggers.partner`).

    Returns
    -------
    table : pyarrow.Table
        ``time`` (float seconds), then ``T_``, ``E_``, ``S_`` columns, all
        float64, no missing value (``missing="keep"``: missing values stay,
        as nulls; a resampled grid point next to one is missing too).
    report : dict
        ``rows``, ``source_rows``, ``time`` (``'seconds'``, ``'iso8601'``, ``'elapsed'``
        or ``'sample_period_s'``; ``time_origin`` for timestamps), ``repairs``
        ({column: interpolated samples}), ``trimmed`` ({"start", "end"} rows),
        ``resampled_s`` when resampled and, with ``missing="keep"``,
        ``missing`` ({column: missing cells kept}).

    Raises
    ------
    ContractError
        If the file breaks the contract; see :func:`read_dataset`.
    """
    opts = cfg if isinstance(cfg, ReadOptions) else ReadOptions.from_cfg(cfg)
    return _derived(*_campaign(Path(path), opts, one_run, errors), opts, Path(path))


def _derived(table: pa.Table, report: dict, opts: ReadOptions, path: Path
             ) -> tuple[pa.Table, dict]:
    """A campaign's ``table`` with ``data.derive``'s columns and its ``report`` with those of
    them measured now and then (:func:`.derived.sparse_derived`)."""
    table = with_derived(table, opts.derive, path)
    sparse = sparse_derived(table, opts.derive, report.get("sparse_targets", {}), path)
    if sparse:
        report = {**report, "sparse_targets": {**report.get("sparse_targets", {}), **sparse}}
    return table, report


def _campaign(path: Path, opts: ReadOptions, one_run: bool, errors: Path | None
              ) -> tuple[pa.Table, dict]:
    """:func:`read_campaign` but ``data.derive``'s columns."""
    if not path.is_file():
        raise ContractError("campaign file not found", file=path)
    if path.stat().st_size == 0:
        raise ContractError("empty file", file=path)
    if errors is not None:           # (a manifest's error_file: the pair named, not found)
        return _read_pair(path, errors, opts)
    try:
        with as_read(path, opts, one_run=one_run) as (source, source_opts):   # a workbook: as CSV
            return _read_file(source, source_opts)
    except ContractError as exc:     # a folder's file of temperatures: its run's other logger's?
        errors = (partner(path, opts, campaign_files(path.parent))
                  if one_run and exc.reason.startswith(NO_ERROR) else None)
        if errors is None:
            raise
    return _read_pair(path, errors, opts)


def _read_pair(path: Path, errors: Path, opts: ReadOptions) -> tuple[pa.Table, dict]:
    """The run whose temperatures ``path`` holds and errors the file ``errors`` (two loggers),
    each file read as a campaign file is, joined on the errors' times (:mod:`.joined`)."""
    halves = [_read_half(f, opts) for f in (path, errors)]
    columns, report = joined(*halves[0], *halves[1], (path, errors), opts)
    if opts.resample_s is not None:
        _resample(columns, opts.resample_s, errors, opts.max_resample_factor,
                  report.get("sparse_targets", {}))
        report["resampled_s"] = opts.resample_s
        _check_length(len(columns[TIME]), errors, f"(after data.resample_s={opts.resample_s:g}) ")
    table = pa.table({name: columns.pop(name) for name in _ordered(list(columns))})
    return table, {**report, "rows": table.num_rows}


def _read_half(path: Path, opts: ReadOptions) -> tuple[pa.Table, dict]:
    """One logger's file of a run of two, read and checked as a campaign file (no error column
    needed, not resampled: the join makes the run's rows)."""
    opts = replace(opts, half=True, resample_s=None)
    with as_read(path, opts, one_run=True) as (source, source_opts):
        columns, renamed, rescaled, lines = _loaded(source, source_opts)
        return _assembled(columns, renamed, rescaled, source, source_opts, lines)


def _read_file(path: Path, opts: ReadOptions) -> tuple[pa.Table, dict]:
    """:func:`read_campaign` of a CSV or Parquet file."""
    columns, renamed, rescaled, lines = _loaded(path, opts)
    if RUN in columns:       # (a folder's file, a train file repaired: no long file to split)
        raise ContractError(f"data.roles.{RUN_ROLE} splits the one file data.path names into "
                            "its runs; a folder's files are a campaign each", file=path)
    return _assembled(columns, renamed, rescaled, path, opts, lines)


def _loaded(path: Path, opts: ReadOptions) -> tuple:
    """A CSV or Parquet file's columns (contract names), renames, conversions and lines."""
    load = _load_parquet if path.suffix.lower() == ".parquet" else _load_csv
    return load(path, opts)


def _assembled(columns: dict, renamed: dict, rescaled: dict, path: Path, opts: ReadOptions,
               lines: Lines | None, first_row: int = 0) -> tuple[pa.Table, dict]:
    """A campaign's loaded columns checked (:func:`_checked`) as a table, with its report;
    ``first_row``: the data rows above it in ``path`` (one run of a long file), for messages."""
    if lines is not None:
        lines = replace(lines, shift=first_row)
    # the time of day joined to its date: no column of its own, its header kept apart (export
    # refuses a pair stream.c does not join, a model from the registry too: lab_names)
    clock = [raw for raw, name in renamed.items() if name == CLOCK]
    renamed = {raw: name for raw, name in renamed.items() if name != CLOCK}
    try:
        if opts.bits:                   # (before the checks: a word's gap is its bits')
            renamed = dict(renamed)
            decoded(columns, renamed, opts.bits, path)
        report = _checked(columns, path, opts, lines,
                          next((raw for raw, name in renamed.items() if name == TIME), None))
    except ContractError as exc:        # a CSV file's row: its line too
        exc = with_own_header(exc, renamed)
        if lines is not None:
            raise lines.located(exc) from None
        raise (exc if exc.row is None else ContractError(
            exc.reason, file=exc.file, column=exc.column, row=exc.row + first_row,
            line=exc.line, sheet=exc.sheet)) from None
    table = pa.table({name: columns.pop(name) for name in _ordered(list(columns))})
    if renamed:          # the file's own names (data.columns, data.roles): raw -> contract
        report["columns"] = renamed
    if clock:
        report["time_of_day"] = clock[0]
    if rescaled:         # read in another unit (mm, K, ...): the lab's name carries other values
        report["converted"] = sorted(rescaled)
        report["scales"] = rescaled       # {contract: [scale, offset]}, as applied
    return table, {"rows": table.num_rows, **report}


def _checked(columns: dict, path: Path, opts: ReadOptions, lines: Lines | None,
             time_header: str | None = None) -> dict:
    """A campaign's columns made the contract's (time in seconds, values checked, missing
    ones repaired or kept, resampled), in place; its report (``time_header``: the time
    column's header in the file, which may say it holds seconds of the day)."""
    rows = len(next(iter(columns.values())))
    if rows == 0:
        raise ContractError("file has no data rows", file=path)
    missing = _keep_missing if opts.missing == "keep" else _repair_missing
    report = {"source_rows": rows, **_set_time_seconds(columns, rows, path, opts, lines, time_header),
              **missing(columns, rows, path, opts)}
    _check_length(len(columns[TIME]), path, "complete " if opts.missing != "keep" else "")
    _check_fahrenheit(columns, path, opts.fahrenheit_threshold_c, report["trimmed"]["start"])
    check_unit_steps(columns, path, opts.max_step_ratio, report["trimmed"]["start"], lines)
    if opts.resample_s is not None:
        sparse = report.get("sparse_targets", {})
        _resample(columns, opts.resample_s, path, opts.max_resample_factor, sparse)
        report["resampled_s"] = opts.resample_s
        if sparse:      # counted again on the grid
            report["sparse_targets"] = {n: measured_on(_values(columns[n])) for n in sparse}
        _check_length(len(columns[TIME]), path, f"(after data.resample_s={opts.resample_s:g}) ")
    return report


def check_kept_values(columns: dict, path, opts: ReadOptions) -> None:
    """Refuse the values of a streamed campaign's ``columns`` (``T_``, ``E_``, ``S_``; missing
    ones kept) that :func:`_checked` refuses in a file read so: impossible values, kelvin, °F at
    the first sample, a unit changed inside it (a stream on stdin, data87)."""
    if not columns:
        return
    _keep_missing(columns, len(next(iter(columns.values()))), path, replace(opts, missing="keep"))
    _check_fahrenheit(columns, path, opts.fahrenheit_threshold_c, 0)
    check_unit_steps(columns, path, opts.max_step_ratio, 0)


def repaired_part(frame: pd.DataFrame, path: Path, cfg: Mapping | None, first_row: int) -> pa.Table:
    """A part of one record read as kept (``missing="keep"``), repaired as a batch repairs a
    campaign (gaps, edges, kelvin refused); ``first_row``: its first row in the record ``path``
    (0-based), so that an error names the record's row."""
    opts = replace(ReadOptions.from_cfg(cfg), missing="repair")
    columns = {c: pa.chunked_array([pa.array(frame[c].to_numpy(float))])
               for c in without_derived(frame.columns, opts.derive)}   # (derived after)
    try:
        _repair_missing(columns, len(frame), path, opts)
    except ContractError as exc:
        raise ContractError(exc.reason, file=exc.file, column=exc.column,
                            row=None if exc.row is None else exc.row + first_row) from None
    return with_derived(pa.table(columns), opts.derive, path)


def _iter_campaigns(root: Path, manifest: pd.DataFrame, opts: ReadOptions
                    ) -> Iterator[tuple[str, pa.Table, dict]]:
    """Every campaign, read and validated; once all are read, their sample periods are
    compared (a campaign timed in another unit is refused)."""
    periods, ranges = {}, {}
    for cid, row in manifest.iterrows():
        try:
            table, report = read_campaign(root / row["file"], opts, one_run=True,
                                          errors=named_error_file(root, manifest, cid))
        except ContractError as exc:     # (a file of two loggers' pair: said so)
            raise errors_elsewhere(exc, root, manifest, cid, opts) from None
        periods[cid] = median_step(table.column(TIME).to_numpy())
        ranges[cid] = _error_ranges(table, DEAD_ROLES)
        yield cid, table, {"file": row["file"], "split": row["split"], **report}
        del table  # before reading the next campaign
    _check_periods(periods, manifest["file"], root, opts.max_period_ratio)
    _warn_error_ranges(ranges, manifest["file"], root)


def _dataset_report(name: str, entries: dict, columns: dict, opts: ReadOptions) -> dict:
    def totals(key: str) -> dict[str, int]:
        out: dict[str, int] = {}
        for entry in entries.values():
            for column, count in entry.get(key, {}).items():
                out[column] = out.get(column, 0) + count
        return out

    report = {"dataset": name, "rows": sum(e["rows"] for e in entries.values()),
              "campaigns": entries, "repairs": totals("repairs"),
              "columns": {r: list(columns.get(r, {})) for r in ROLE_ORDER},
              **_renamed(entries),
              # (data89b) under the data config's keys, as ingested_with.settings names them
              "settings": {k: [list(v) for v in value] if k == "clock_sets" else value
                           for k, value in opts.data_keys().items()}}
    if opts.missing != "repair":
        report["missing"] = totals("missing")
    sparse = sparse_totals(entries)
    if sparse:          # a target measured now and then: rows measured, per campaign too
        report["sparse_targets"] = sparse
    if opts.clock_sets:
        _said_clock_sets(report, entries, opts)
    return report


def _said_clock_sets(report: dict, entries: dict, opts: ReadOptions) -> None:
    """How many of ``data.clock_sets``' sets were found in the record's timestamps (a set
    found in several files once: a file rotated after it); a warning naming those that were not
    (lead73: it said nothing, a set unfound left as a pause)."""
    found = {k for e in entries.values() for k in e.pop("clock_sets_found", ())}
    report["clock_sets_undone"] = len(found)
    if len(found) < len(opts.clock_sets):
        logger.warning(f"data.clock_sets: {len(found)} of the {len(opts.clock_sets)} clock set(s) "
                       "found in the record's timestamps (a row at or after the set's at_utc, the "
                       "row before it at or before its from_utc); not found: "
                       f"{unfound(opts.clock_sets, found)}: left as the log has them (a log of "
                       "another machine, clock or time zone, or of other days?)")


def lab_units(entries: dict) -> dict[str, list]:
    """``{the lab's header: [contract name, scale, offset]}`` of every column a campaign read in
    another unit (``value * scale + offset`` in the contract's); a header converted two ways
    (a letter unit read apart by its first value) holds ``None`` for the scale."""
    out: dict[str, list] = {}
    for entry in entries.values():
        scales = entry.get("scales", {})
        named = {**{c: c for c in scales}, **{c: r for r, c in entry.get("columns", {}).items()}}
        for contract, (scale, offset) in scales.items():
            raw = named[contract]
            if raw in out and out[raw][1:] != [scale, offset]:
                out[raw] = [contract, None, None]
            else:
                out.setdefault(raw, [contract, scale, offset])
    return out


def _renamed(entries: dict) -> dict:
    """``{"column_map": {raw: contract}}`` over every campaign whose headers were renamed (what
    :func:`.roles.contract_columns` gives; a deployed model reads the lab's names through it)."""
    out: dict[str, str] = {}
    for entry in entries.values():
        out.update(entry.get("columns", {}))
    return {"column_map": out} if out else {}


def _collect_roles(columns: dict, names: list[str]) -> None:
    for name in names:
        if name != TIME:
            columns.setdefault(role(name), {}).setdefault(name, None)


def _to_frame(table: pa.Table) -> pd.DataFrame:
    return table.to_pandas(split_blocks=True)


# ---------------------------------------------------------------------------
# Public entry points


def read_dataset(path: str | Path, cfg: Mapping | None = None, *, missing: str = "repair",
                 campaigns: Sequence[str] | None = None, needs_errors: bool = True
                 ) -> tuple[Dataset, dict]:
    """Read, validate and repair a dataset folder.

    Parameters
    ----------
    path : str or Path
        Dataset folder with ``campaigns.csv`` and the campaign files, or one ``.csv`` /
        ``.parquet`` file: one record (:mod:`.record`).
    cfg : mapping, optional
        The ``data`` config group (dict or ``DictConfig``); every key is
        optional:

        columns : mapping
            Raw column name -> contract name, applied to every campaign file
            before validation (e.g. ``{"delta L": "E_L", "Zeit": "time"}``).
        roles : mapping
            ``error``/``state``/``ambient``/``ignore`` header patterns and ``time``
            (:mod:`.roles`); ``columns`` wins.
        test_fraction, val_fraction, split_order
            A chronological test (val) part of one record, or the last campaigns of a folder
            without that split (:mod:`.record`).
        sample_period_s : float
            Files without a ``time`` column get ``time = row * sample_period_s``.
            A file with a ``time`` column keeps its own.
        time : {'auto', 'seconds', 'iso8601', 'elapsed'} or a strptime format
            How to read ``time``; ``'auto'`` decides from the first row (an ``h:mm:ss``
            one, from the column: :func:`.timestamps.elapsed_seconds`).
            Seconds are kept as given; timestamps become seconds since the
            file's first sample (rows with zone offsets are compared as
            instants, naive ones as written).
        split_overrides : mapping
            Campaign id -> split, replacing the manifest's.
        max_gap_samples : int, default 0
            Longest interior run of missing values that is interpolated.
        max_edge_samples : int, default 0
            Most incomplete rows that are dropped at each end of a campaign.
        resample_s : float
            If set, every campaign is linearly interpolated onto a uniform
            grid with this step, starting at its first sample.
        kelvin_threshold_c : float, default 200
            A ``T_`` value above it is taken for kelvin and refused.
        max_step_ratio : float or None, default 5
            A unit change inside a file (a ``T_`` or ``E_`` step this many
            times the column's typical step that a unit conversion explains
            and that persists) is refused; see :mod:`thermocomp.core.io.steps`.
        delimiter, decimal : str, default 'auto'
            CSV field separator and decimal mark of the campaign files; ``'auto'``:
            detected from each file's first lines (:mod:`.sniff`).
        thousands : str or None, default None
            CSV thousands separator (``','`` reads ``6,000``).
    missing : {'repair', 'keep', 'keep_errors'}, default 'repair'
        Not a config key: ``'keep'`` leaves missing values NaN (no trim, no
        interpolation, no gap refused) and counts them in the report's
        ``missing``, for a stage that must see the data as it was recorded;
        ``'keep_errors'`` does so for the ``E_`` columns only (a volumetric
        dataset's distances not measured) and repairs the others.
    needs_errors : bool, default True
        Not a config key: False reads a file without an ``E_`` column too (``thermocomp rows``
        of the inputs a control is fed: a run's DAQ file whose errors another logger holds).

    Returns
    -------
    dataset : Dataset
        Manifest indexed by campaign id; one float64 frame per campaign with
        ``time`` (s), then ``T_``, ``E_``, ``S_`` columns in file order, and
        no missing value (unless ``missing='keep'``).
    report : dict
        ``{"dataset": name, "rows": total, "campaigns": {id: {"file", "split",
        "rows", "source_rows", "time", "repairs": {column: n}, "trimmed":
        {"start", "end"}, ...}}, "repairs": {column: total}, "columns": {"T":
        [...], "E": [...], "S": [...]}, "settings": {...}}``.  ``repairs``
        lists only columns with at least one interpolated sample; with
        ``missing='keep'`` the campaigns and the report also have ``missing``
        ({column: missing cells}, columns with at least one).

    Raises
    ------
    ContractError
        On input that breaks the contract, with a one-line message naming the
        file, the column and the 1-based data row where they apply: missing
        manifest or campaign file, invalid manifest, empty file, unknown
        column prefix, no ``E_`` column, no time, unreadable time, duplicate
        or decreasing times, non-numeric cells (or non-numeric Parquet
        dtypes), infinite values, temperatures that look like kelvin, a
        unit that changes inside a file, an
        all-missing column, gaps or incomplete edges beyond the configured
        limits, and invalid config values.

    Notes
    -----
    Missing values are handled as described in the module docstring: gaps
    are interpolated and edges trimmed only up to the configured limits, and
    every repair is counted.
    """
    opts = replace(ReadOptions.from_cfg(cfg), missing=missing, half=not needs_errors)
    root, manifest, tables = _source(Path(path), opts, campaigns)
    frames, entries, columns = {}, {}, {}
    for cid, table, entry in tables:
        _collect_roles(columns, table.column_names)
        frames[cid], entries[cid] = _to_frame(table), entry
        del table
    manifest = _starts_from_timestamps(manifest, entries, root, opts)
    report = _dataset_report(_name(path), entries, columns, opts)
    report["ambient"] = _manifest_ambient(manifest, frames)
    for column, entry in report.get("sparse_targets", {}).items():
        logger.info(said(column, entry))
    # the path as given: a one-file record's file, which an error about its splits names
    meta = {"path": str(path), "column_map": report.get("column_map", {}),
            "converted": sorted({c for e in entries.values() for c in e.get("converted", [])}),
            # the lab's headers read in another unit, with the scale and offset applied
            "lab_units": lab_units(entries),
            # data.roles.campaign's header, which a stream of the long file starts runs by
            "run_column": next((e["run_column"] for e in entries.values() if "run_column" in e),
                               None),
            # the header of a time of day joined to the date (data.roles.time: [date, time])
            "time_of_day": next((e["time_of_day"] for e in entries.values() if "time_of_day" in e),
                                None),
            # (lead91) a time of seconds since midnight, days added as it passed (data89b):
            # what an exported stream reads the lab's raw file as
            "seconds_of_day": any(OF_DAY in (e.get("time"), e.get("record_time"))
                                  for e in entries.values()),
            # None: the splits came from no file (a record, a folder of runs): data.*_fraction
            "manifest": str(root / MANIFEST) if Path(path).is_dir() and (root / MANIFEST).is_file()
            else None}
    return Dataset(manifest, frames, _name(path), meta), report


def _name(path) -> str:
    """The dataset's name: its folder's, or a one-file record's stem."""
    path = Path(path)
    return record_id(path) if path.is_file() else path.name


def folder_splits(path: Path, opts: ReadOptions, manifest: pd.DataFrame | None = None
                  ) -> pd.DataFrame:
    """A dataset folder's manifest (``manifest``: as read already) with every campaign's split
    as a read of it assigns them (the manifest, ``data.split_overrides``, the last train
    campaigns held out by ``data.test_fraction``): a group of the folder holds out what the
    whole folder does."""
    manifest = read_manifest(path, opts) if manifest is None else manifest
    if shares(opts) and (run := lone_run(path, opts, manifest)) is not None:
        # a lab's one export put in a folder: its one file is one campaign, nothing to hold out
        # (the refusal named a campaigns.csv that is not there and said to lower the fraction)
        only, errors = run
        if errors is not None:      # (data88; a read cuts it as one record: fleet's groups)
            raise ContractError(f"a folder whose one run is two loggers' files ({only.name}, "
                                f"{errors.name}: one campaign) has none to hold out for "
                                "data.test_fraction / data.val_fraction, and a run of two files "
                                "is not cut in two: put each run's two files in the folder (a "
                                "later run held out), or give one file of the run's columns "
                                "joined on their time", file=path)
        raise ContractError(f"a folder whose one file ({only.name}) is its one campaign has none to "
                            f"hold out for data.test_fraction / data.val_fraction: give the file, "
                            f"data.path={only} (one record: its last share is held out)", file=path)
    if shares(opts):       # before any is read
        try:
            starts = campaign_starts(path, manifest, opts)
        except NoRows as exc:     # refused before any order is said
            raise unrecorded(exc, path) from None
        manifest = hold_out(manifest, opts, path, starts)
    return manifest


def _source(path: Path, opts: ReadOptions, campaigns=None) -> tuple[Path, pd.DataFrame, Iterator]:
    """The folder campaign files are relative to, the manifest and the campaigns read: a
    one-file record's, cut chronologically (:mod:`.record`), or a dataset folder's (or of
    ``campaigns``, a group of it), whose last train campaigns ``data.test_fraction`` holds out
    by their starts (:mod:`.starts`: the files' first timestamps where the manifest gives
    none; a lab's files named otherwise than in time, ``zander.csv`` tested though
    ``klein.csv`` came later)."""
    if not path.exists():     # (a folder's name mistyped was refused for its manifest)
        raise ContractError("no such file or folder (data.path: a dataset folder or one "
                            "record's file)", file=path)
    if opts.roles.get(RUN_ROLE) and opts.runs_at_pauses:
        raise ContractError(f"data.roles.{RUN_ROLE} and data.runs_at_pauses both split one file "
                            "into its runs: give one of them", file=path)
    if path.is_file():         # (a folder's: its manifest read first)
        opts = _recorded_time(path, [path], opts)
    if path.is_file() and (opts.roles.get(RUN_ROLE) or opts.runs_at_pauses):
        check_record_file(path)
        manifest, parts = _run_parts(path, opts)
        ids = list(manifest.index if campaigns is None else campaigns)
        return path.parent, manifest.loc[ids], ((c, *parts.pop(c)) for c in ids)
    if opts.roles.get(RUN_ROLE) or opts.runs_at_pauses:
        key = f"roles.{RUN_ROLE}" if opts.roles.get(RUN_ROLE) else "runs_at_pauses"
        raise ContractError(f"data.{key} splits one long file into its runs: data.path is a "
                            "folder, whose files are a campaign each (leave it out)", file=path)
    if path.is_file() and several_runs(path, opts):     # a workbook of runs, one a sheet
        check_record_file(path)
        manifest, parts = sheet_parts(path, opts, read_campaign)
        _check_runs(parts, path, opts)
        ids = list(manifest.index if campaigns is None else campaigns)
        return path.parent, manifest.loc[ids], ((c, *parts.pop(c)) for c in ids)
    if path.is_file():
        check_record_file(path)
        table, report = _record(path, opts)
        _warn_error_ranges({path.stem: _error_ranges(table, DEAD_ROLES)}, {path.stem: path.name},
                           path.parent)
        manifest, parts = cut(path, table, report, opts)
        del table
        ids = list(manifest.index if campaigns is None else campaigns)
        return path.parent, manifest.loc[ids], ((c, *parts.pop(c)) for c in ids)
    listed = read_manifest(path, opts)
    opts = _recorded_time(path, [path / f for f in listed["file"]], opts)   # before the starts
    if (run := _one_run_of_two(path, opts, listed)) is not None:
        # (data88b) one run of two loggers' files: one record, as a one-file record is (its
        # last share held out, continuing the rest); refused before, "not cut in two"
        table, report = read_campaign(run, opts, one_run=True)
        manifest, parts = cut(run, table, report, opts, paired_id(run))
        del table
        ids = list(manifest.index if campaigns is None else campaigns)
        return path, manifest.loc[ids], ((c, *parts.pop(c)) for c in ids)
    manifest = folder_splits(path, opts, listed)
    if not (path / MANIFEST).is_file():      # said once per read, not per look at the folder
        # (audit99) not "holds the last out" after the hold-out line above: the last by time
        # is held out, which a file named first may be ('Lauf 02.02.2023.csv')
        logger.info(f"{path.name}: no {MANIFEST}; its {len(manifest)} campaign files read as "
                    "campaigns, listed in name order, "
                    + ("train but those held out above" if shares(opts) else
                       "every one train (data.test_fraction holds the last out, by start time "
                       "where each file has one)"))
        below = subfolder_runs(path)
        if below:        # half a lab's runs in a month folder were left out without a word
            logger.warning(f"{path}: its sub-folders hold {sum(below.values())} more run files "
                           f"({said_subfolders(below)}), not read: a folder's runs are the files "
                           f"directly in it (move them up, or list every run in a {MANIFEST})")
    if campaigns is not None:
        manifest = manifest.loc[list(campaigns)]
    return path, manifest, _iter_campaigns(path, manifest, opts)


def _one_run_of_two(path: Path, opts: ReadOptions, listed: pd.DataFrame) -> Path | None:
    """The temperature file of the folder ``path``'s one run where it is two loggers' files
    (:mod:`.loggers`), no manifest, and a fraction asks for a held-out share; else None."""
    run = lone_run(path, opts, listed) if shares(opts) else None
    return run[0] if run is not None and run[1] is not None else None


def lone_run(path: Path, opts: ReadOptions, listed: pd.DataFrame) -> tuple[Path, Path | None] | None:
    """``(file, errors)``: the one data file the folder ``path`` lists (``listed``: as read) where
    it has no manifest, and its errors' file where the run is two loggers' (:mod:`.loggers`),
    else None; None for any other folder.  One look for the read, its held-out share and
    ``init`` (data88, data88b)."""
    if len(listed) != 1 or (path / MANIFEST).is_file():
        return None
    only = path / str(listed["file"].iloc[0])
    return only, partner(only, opts, campaign_files(path))


def _recorded_time(path: Path, files: list[Path], opts: ReadOptions) -> ReadOptions:
    """``opts`` with ``time`` the order of the dates with slashes that the rows of the record
    ``path`` say, every one of its ``files``' (:mod:`.slashed`; ``data.time=auto``: a file's
    first row alone read a folder of a European PC's Keysight exports month first, its 13th
    refused).  A one-file record's read decides from the rows it reads (``order_in_rows``):
    read once, not once for the order and again for the record (small72)."""
    if path.is_file():
        return replace(opts, order_in_rows=opts.time == "auto" and rows_tell(path, opts))
    if opts.dayfirst is None and (said := lab_dayfirst(files, opts.encoding)):
        logger.info(f"{path.name}: dates with slashes read {WAY[said[0]]}, as {said[1].name}'s "
                    f"{said} says, in every file (data.dayfirst={str(said[0]).lower()})")
        opts = replace(opts, dayfirst=said[0])
    return read_in(record_order(files, opts), opts, path, files[0])


def _record(path: Path, opts: ReadOptions) -> tuple[pa.Table, dict]:
    """One record read as one campaign; a column read as a temperature that looks like a run
    counter (:mod:`.runs`) said, in a warning or in the refusal of the file (its time restarting
    at each run: "time decreases")."""
    try:
        table, report = read_campaign(path, opts)
    except ContractError as exc:
        try:
            counter = run_counter(path, opts)
        except ContractError:
            raise exc from None
        if counter is None:
            raise
        raise ContractError(f"{exc.reason}; {run_hint(counter)}", file=exc.file, column=exc.column,
                            row=exc.row, line=exc.line, sheet=exc.sheet) from None
    counter = _run_counter(dict(zip(table.column_names, table.columns)), report.get("columns", {}))
    if counter is not None:
        logger.warning(f"{path.name}: {run_hint(counter)}; read as the temperature "
                       f"{report['columns'][counter]} here")
    return table, report


def run_counter(path: Path, opts: ReadOptions) -> str | None:
    """The header of a one-file record's first column read as a temperature that looks like a
    run counter (:func:`.runs.looks_like_run_counter`), None where there is none; read without
    the checks of time and values (a time restarting at each run)."""
    with as_read(path, opts) as (source, source_opts):
        columns, renamed = _loaded(source, source_opts)[:2]
    return _run_counter(columns, renamed)


def run_column(path: Path, opts: ReadOptions) -> tuple[list[str | None], str]:
    """``(cells as text, header)`` of ``data.roles.campaign``'s column of a one-file record,
    read without the checks of time and values."""
    with as_read(path, opts) as (source, source_opts):
        columns, renamed = _loaded(source, source_opts)[:2]
    header = next(raw for raw, name in renamed.items() if name == RUN)
    return run_values(columns[RUN]), header


def _run_counter(columns: dict, renamed: dict) -> str | None:
    """The header of the first column read as a temperature that looks like a run counter (not
    one whose header gives a unit: a temperature logged in whole degrees); a file's own names
    only (``data.roles``, ``data.columns``: a contract-named file is not looked at)."""
    numbers = None      # every numeric column as floats: built once, when a candidate first asks

    def ends(changes, name):
        nonlocal numbers
        if numbers is None:
            numbers = {n: v for n, c in columns.items() if (v := _numbers(c)) is not None}
        others = [v for n, v in numbers.items() if n not in (name, TIME)]
        return run_ends(changes, numbers.get(TIME), others)

    for raw, name in renamed.items():
        column = columns.get(name)
        if role(name) != "T" or column is None or column.null_count or split_unit(raw)[1]:
            continue
        if looks_like_run_counter(column.to_numpy(zero_copy_only=False), raw,
                                  functools.partial(ends, name=name)):
            return raw
    return None


def _numbers(column) -> np.ndarray | None:
    """A loaded column as floats (a timestamp as seconds since the epoch), None where it is
    text or missing."""
    if column is None:
        return None
    if pa.types.is_timestamp(column.type):
        return column.cast(pa.int64()).to_numpy(zero_copy_only=False) / 1e9
    if pa.types.is_integer(column.type) or pa.types.is_floating(column.type):
        return column.to_numpy(zero_copy_only=False).astype(float)
    return None


def _continuing(columns: dict, renamed: dict, path: Path,
                opts: ReadOptions) -> tuple[np.ndarray | None, bool]:
    """The record's time as numbers where its pauses are found: seconds of the day past
    midnight as a continuing time (the reader's rule, :func:`.timestamps.seconds_of_day`; lead90:
    the raw values split a record at its forward pauses only, a run after a pause across
    midnight joined to the one before), each run then read alone as a file of it is; and
    whether it was read as seconds of the day."""
    seconds = _numbers(columns.get(TIME))
    if seconds is None:
        return None, False
    header = next((raw for raw, name in renamed.items() if name == TIME), None)
    of_day = seconds_of_day(seconds, path, header, pauses_said=False, kind=opts.time,
                            unit=time_unit(header, opts))
    return (seconds, False) if of_day is None else (of_day, True)


def _run_parts(path: Path, opts: ReadOptions) -> tuple[pd.DataFrame, dict]:
    """One long file split into campaigns by ``data.roles.campaign`` or, with
    ``data.runs_at_pauses``, where its time pauses (:mod:`.runs`), each read as a file of that
    run alone; the last runs held out as a folder's are (by their first timestamps, else in
    file order)."""
    with as_read(path, opts) as (source, source_opts):
        columns, renamed, rescaled, lines = _loaded(source, source_opts)
        if opts.runs_at_pauses:
            header, (times, of_day) = None, _continuing(columns, renamed, path, opts)
            blocks = pause_blocks(times, record_id(path), path)
        else:
            header, of_day = next(raw for raw, name in renamed.items() if name == RUN), False
            renamed = {raw: name for raw, name in renamed.items() if name != RUN}
            blocks = run_blocks(run_values(columns.pop(RUN)), header, path)
        parts = {}
        for cid, start, end in blocks:
            part = {name: column.slice(start, end - start) for name, column in columns.items()}
            if is_lab_file(path):   # a channel of other runs (a sensor replaced): not this one's
                part = {name: c for name, c in part.items()
                        if name in (TIME, CLOCK) or c.null_count < len(c)}
            table, report = _derived(*_assembled(part, renamed, rescaled, source, source_opts,
                                                 lines, start), opts, path)
            parts[cid] = table, {
                "file": path.name, "split": "train", **report, "record_rows": [start, end],
                **({"run_column": header} if header else {}),
                # (lead91) the record's time, not only this run's, seconds of the day
                **({"record_time": OF_DAY} if of_day else {})}
    _check_runs(parts, path, opts)
    manifest = pd.DataFrame({"file": path.name, "split": "train"}, index=pd.Index(
        list(parts), name="campaign"))
    apply_split_overrides(manifest, opts.split_overrides, path,
                          listed_by="the file's run column (data.roles.campaign) does not hold")
    # (a run's first timestamp has its offset, data.timezone's where it was read on that clock)
    starts = start_instants(pd.Series({cid: entry.get("time_origin")
                                       for cid, (_, entry) in parts.items()}, dtype=object))
    try:
        manifest = hold_out(manifest, opts, path.parent, starts, listed="in file order")
    except ContractError as exc:          # (about the runs, not a manifest file)
        raise ContractError(exc.reason, file=path, column=header) from None
    by = repr(header) if header else "the time's pauses (data.runs_at_pauses)"
    logger.info(f"{path.name}: {len(parts)} runs by {by} read as campaigns")
    for cid, (_, entry) in parts.items():
        entry["split"] = manifest.at[cid, "split"]
    return manifest, parts


def _check_runs(parts: dict, path: Path, opts: ReadOptions) -> None:
    """One file's runs (a long file's, a workbook's sheets: ``{id: (table, entry)}``) checked
    as a folder's campaigns are: their sample periods compared, their error ranges said."""
    periods = {cid: median_step(table.column(TIME).to_numpy()) for cid, (table, _) in parts.items()}
    ranges = {cid: _error_ranges(table, DEAD_ROLES) for cid, (table, _) in parts.items()}
    files = dict.fromkeys(parts, path.name)
    _check_periods(periods, files, path.parent, opts.max_period_ratio)
    _warn_error_ranges(ranges, files, path.parent)


def _manifest_ambient(manifest: pd.DataFrame, frames: dict) -> dict:
    """Where each campaign's ambient comes from: its ``T_amb*`` sensors, else the manifest's
    ``ambient_c`` (handed on in the frame's ``attrs``), else nowhere; said once per dataset."""

    sources = {}
    for cid, df in frames.items():
        value = manifest.at[cid, AMBIENT_C] if AMBIENT_C in manifest.columns else float("nan")
        if not any(is_ambient(c) for c in df.columns) and pd.notna(value):
            df.attrs[AMBIENT_C] = float(value)
        sources[cid] = ambient_source(df)
    n = sum(v == AMBIENT_C for v in sources.values())
    if n:
        logger.info(f"ambient: {MANIFEST} column {AMBIENT_C} for the {n} campaign(s) without a "
                    "T_amb / T_amb_* sensor")
    return {"source": sorted({str(v) for v in sources.values()}), "campaigns": sources}


def _starts_from_timestamps(manifest: pd.DataFrame, entries: Mapping, root: Path | None = None,
                            opts: ReadOptions | None = None) -> pd.DataFrame:
    """The manifest with ``start`` filled, where it is empty, by the campaign's first timestamp
    (files whose ``time`` is ISO 8601), else by the start its file's ``#`` comment block states
    (``# start: 2027-03-08 06:00:00``, a DAQ script's, over a time in seconds:
    :func:`.starts.commented_start`; a folder ``root``'s files): the optional ``start`` column
    then says when each campaign began, so a record cut into consecutive files is seen as one
    (carry-over)."""
    origins = {cid: e.get("time_origin") for cid, e in entries.items() if e.get("time_origin")}
    if root is not None and opts is not None and "file" in manifest.columns:
        for cid in manifest.index:
            if cid in entries and cid not in origins and (
                    START not in manifest.columns or pd.isna(manifest.at[cid, START])):
                stamp = commented_start(root / str(manifest.at[cid, "file"]), opts)
                if pd.notna(stamp):
                    origins[cid] = stamp.isoformat()
    if not origins:
        return manifest
    out = manifest.copy()
    if START not in out.columns:
        out[START] = pd.Series([None] * len(out), index=out.index, dtype=object)
    out[START] = out[START].astype(object)
    for cid, origin in origins.items():
        if cid in out.index and pd.isna(out.at[cid, START]):
            out.at[cid, START] = start_stamp(origin)
    return out


def ingest(src: str | Path, dest: str | Path, cfg: Mapping | None = None, extra: dict | None = None,
           finish=None) -> dict:
    """Validate a raw dataset and write it as Parquet to ``dest``.

    Campaigns are read, validated and written one at a time as Arrow tables,
    so peak memory is about one campaign.  ``dest`` is replaced atomically:
    after an error nothing new appears there and a previous ``dest`` is left
    as it was.  Files under ``src`` are only read.

    Parameters
    ----------
    src : str or Path
        Raw dataset folder.
    dest : str or Path
        Output folder; receives ``<campaign>.parquet`` files, ``campaigns.csv``
        (splits after overrides) and ``ingest_report.json``.  It must not be
        ``src`` or lie inside it (or contain it).
    cfg : mapping, optional
        The ``data`` config, as for :func:`read_dataset`.
    extra : dict, optional
        More keys of the report (a volumetric dataset's ``dataset`` and ``calibration``).
    finish : callable, optional
        ``finish(dataset) -> dict``: more keys of the report, judged on the dataset as written
        (manifest and ``time`` columns only: a campaign at a time stays the peak memory).

    Returns
    -------
    dict
        The ingest report, as written to ``ingest_report.json`` (format of
        :func:`read_dataset`).

    Raises
    ------
    ContractError
        As :func:`read_dataset`, or if ``dest`` overlaps ``src``.
    """
    opts = ReadOptions.from_cfg(cfg)
    src, dest = Path(src), Path(dest)
    check_separate(src, dest)
    root, manifest, tables = _source(src, opts)
    entries, columns = {}, {}
    with atomic_dir(dest) as tmp:
        for cid, table, entry in tables:
            _collect_roles(columns, table.column_names)
            parquet().write_table(table, tmp / f"{cid}.parquet")
            entries[cid] = entry
            del table
            pa.default_memory_pool().release_unused()
        out = _starts_from_timestamps(manifest, entries, root, opts).assign(
            file=[f"{cid}.parquet" for cid in manifest.index])
        (tmp / MANIFEST).write_text(_manifest_csv(out))
        report = {**_dataset_report(_name(src), entries, columns, opts), **(extra or {})}
        if finish is not None:
            report.update(finish(_clocks(tmp, out, report["dataset"])))
        write_json(tmp / INGEST_REPORT, report, ensure_ascii=False)
    return report


def _clocks(root: Path, manifest: pd.DataFrame, name: str) -> Dataset:
    """The dataset written in ``root`` with each campaign's ``time`` column only."""
    return Dataset(manifest, {cid: _to_frame(parquet().read_table(root / f, columns=[TIME]))
                              for cid, f in manifest["file"].items()}, name, {})


def load_interim(path: str | Path) -> Dataset:
    """Read back a folder written by :func:`ingest`, without re-validating it.

    Parameters
    ----------
    path : str or Path
        Output folder of :func:`ingest`.

    Returns
    -------
    Dataset
        As :func:`read_dataset` returns it; ``meta["ingest_report"]`` holds
        the ingest report, ``meta["digest"]`` the folder's digest
        (:func:`~thermocomp.base.files.folder_digest`) of exactly what was read.

    Raises
    ------
    ContractError
        If the folder has no ``ingest_report.json`` (it was not written by
        :func:`ingest`) or its manifest is invalid.

    Notes
    -----
    Another ``ingest`` may swap the folder while it is read: the digest is
    taken before and after, and the read is repeated until both agree, so the
    dataset is one ingest's, whole, and its digest says which.
    """
    root = Path(path)
    for _ in range(_READ_ATTEMPTS):
        with contextlib.suppress(FileNotFoundError, pa.ArrowInvalid):
            before = folder_digest(root)
            ds = _load_interim_once(root)
            if folder_digest(root) == before:
                ds.meta["digest"] = before
                return ds
    raise ContractError("the folder kept changing while it was read (another ingest writing "
                        "it?)", file=root)


def _load_interim_once(root: Path) -> Dataset:
    report_path = root / INGEST_REPORT
    if not report_path.is_file():
        raise ContractError(f"no {INGEST_REPORT}: not an ingested dataset (run ingest first)",
                            file=root)
    manifest = read_manifest(root)
    campaigns = {cid: _to_frame(parquet().read_table(root / f)) for cid, f in manifest["file"].items()}
    meta = {"path": str(root), "ingest_report": json.loads(report_path.read_text())}
    # named after the dataset it was ingested from, as run names it (not the interim folder)
    return Dataset(manifest, campaigns, meta["ingest_report"].get("dataset") or root.name, meta)


def check_separate(src: Path, dest: Path) -> None:
    a, b = src.resolve(), dest.resolve()
    if a == b or a in b.parents or b in a.parents:
        raise ContractError(f"ingest destination {dest} overlaps the raw dataset {src}; "
                            "raw files are never modified")


def _manifest_csv(manifest: pd.DataFrame) -> str:
    # (a run of two loggers is written joined: its error file is no longer beside it)
    out = manifest.drop(columns=ERROR_FILE, errors="ignore")
    if START in out.columns:
        out[START] = [t.isoformat() if pd.notna(t) else "" for t in out[START]]
    ordered = ["file", "split"] + [c for c in out.columns if c not in ("file", "split")]
    return out[ordered].rename_axis("campaign").reset_index().to_csv(index=False)

