"""Read, validate and ingest datasets in the contract of ``DATA_FORMAT.md``.

A dataset folder holds a manifest ``campaigns.csv`` and one ``.csv`` or
``.parquet`` file per campaign.  Every campaign goes through the same steps,
column by column on an Arrow table so that memory stays bounded by about one
copy of the campaign:

1. load (``pyarrow.csv.read_csv`` with every data column typed ``float64``, or
   ``pyarrow.parquet.read_table``) and rename columns through ``data.columns``;
2. check names: only ``time``, ``T_*``, ``E_*``, ``S_*``; at least one ``E_``;
3. build ``time`` in seconds (float seconds as given, ISO 8601 timestamps as
   seconds since the first sample, or ``row * sample_period_s``) and require
   it strictly increasing;
4. check values (finite, not all missing, temperatures in °C) and deal with
   missing values (see below);
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

``ReadOptions.missing="keep"`` (not a data config key: the ``monitor`` stage
passes it through ``read_dataset(..., missing="keep")`` to stream a campaign
as the machine saw it) skips both repairs: missing values stay NaN, no row is
trimmed, no gap is refused, and the report counts the cells kept per column
(``missing``).  Everything else is still refused, including a column with no
valid value and a missing ``time``.

Row numbers in error messages are 1-based data rows of the source file,
header excluded.
"""

from __future__ import annotations

import contextlib
import csv
import io
import json
import math
import os
import re
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.compute as pc
import pyarrow.csv as pacsv
import pyarrow.parquet as pq

from ..files import atomic_dir, folder_digest, write_json
from .contract import MANIFEST, MANIFEST_REQUIRED, SPLITS, TIME, ContractError, Dataset, role

INGEST_REPORT = "ingest_report.json"
CAMPAIGN_SUFFIXES = (".csv", ".parquet")
TIME_FORMATS = ("auto", "seconds", "iso8601")
ABSOLUTE_ZERO_C = -273.15
ROLE_ORDER = ("T", "E", "S")
MISSING_MODES = ("repair", "keep")

# Larger blocks than Arrow's 1 MiB default: fewer chunks, faster multithreaded parsing.
_CSV_BLOCK_BYTES = 16 << 20
_PANDAS_INDEX = re.compile(r"__index_level_\d+__")
_ZONE_OFFSET = re.compile(r"\d:\d\d(?::\d\d(?:[.,]\d+)?)?\s*(?:Z|[+-]\d\d(?::?\d\d)?)$")
_UNSAFE_ID = re.compile(r"[/\\\x00-\x1f]|^\.")
_CONVERSION_ERROR = re.compile(r"In CSV column #(\d+)")
_ARROW_SOURCE = re.compile(r"^Could not open Parquet input source '.*?': ")
# A contract name: prefix + identifier-like name (it becomes part of file names: no path
# separators, '..', spaces or control characters).
_NAME = re.compile(r"[TES]_[\w.\-]+")
_OTHER_DELIMITERS = (";", "\t", "|", ",")
MIN_ROWS = 2  # the first sample is the reference: one more is needed to have anything to score
MAX_GRID_ROWS = 5_000_000
_READ_ATTEMPTS = 5
MAX_ABS_T_C = 1e4  # refused whatever data.kelvin_threshold_c says
FAULTY_SHARE = 0.1  # at most this share of a streamed T_ column above the kelvin threshold: faults


# ---------------------------------------------------------------------------
# Options


@dataclass(frozen=True)
class ReadOptions:
    """The ``data`` config keys that steer reading; see :func:`read_dataset`.

    Build it with :meth:`from_cfg`; every field has the default a missing key
    gets.
    """

    columns: dict = field(default_factory=dict)
    sample_period_s: float | None = None
    time: str = "auto"
    split_overrides: dict = field(default_factory=dict)
    max_gap_samples: int = 0
    max_edge_samples: int = 0
    resample_s: float | None = None
    kelvin_threshold_c: float = 200.0
    fahrenheit_threshold_c: float | None = 45.0
    max_abs_error: float = 1e6
    max_abs_state: float = 1e9
    max_period_ratio: float | None = 100.0
    max_duration_days: float | None = 366.0
    max_resample_factor: float = 10.0
    delimiter: str = ","
    decimal: str = "."
    missing: str = "repair"  # internal (no data config key): "keep" leaves missing values NaN

    def __post_init__(self):
        if self.missing not in MISSING_MODES:  # a caller's mistake, not the user's
            raise ValueError(f"missing must be one of {MISSING_MODES}, got {self.missing!r}")

    @classmethod
    def from_cfg(cls, cfg: Mapping | None) -> "ReadOptions":
        """Options from a mapping (dict or OmegaConf ``DictConfig``).

        Raises
        ------
        ContractError
            If a value has the wrong type or range.
        """
        cfg = {} if cfg is None else cfg
        opts = cls(
            columns=_str_mapping(cfg, "columns"),
            sample_period_s=_positive_float(cfg, "sample_period_s"),
            time=str(cfg.get("time", "auto") or "auto"),
            split_overrides=_str_mapping(cfg, "split_overrides"),
            max_gap_samples=_count(cfg, "max_gap_samples"),
            max_edge_samples=_count(cfg, "max_edge_samples"),
            resample_s=_positive_float(cfg, "resample_s"),
            kelvin_threshold_c=_float(cfg, "kelvin_threshold_c", 200.0),
            fahrenheit_threshold_c=_float(cfg, "fahrenheit_threshold_c", 45.0, nullable=True),
            max_abs_error=_positive_float(cfg, "max_abs_error", 1e6),
            max_abs_state=_positive_float(cfg, "max_abs_state", 1e9),
            max_period_ratio=_positive_float(cfg, "max_period_ratio", 100.0, nullable=True),
            max_duration_days=_positive_float(cfg, "max_duration_days", 366.0, nullable=True),
            max_resample_factor=_positive_float(cfg, "max_resample_factor", 10.0),
            delimiter=str(cfg.get("delimiter", ",") or ","),
            decimal=str(cfg.get("decimal", ".") or "."),
        )
        opts._check()
        return opts

    def _check(self) -> None:
        if self.time not in TIME_FORMATS:
            raise ContractError(f"data.time must be one of {', '.join(TIME_FORMATS)}, "
                                f"got {self.time!r}")
        bad_split = {k: v for k, v in self.split_overrides.items() if v not in SPLITS}
        if bad_split:
            cid, split = next(iter(bad_split.items()))
            raise ContractError(f"data.split_overrides.{cid}: split {split!r} is not one of "
                                f"{', '.join(SPLITS)}")
        for key in ("delimiter", "decimal"):
            if len(getattr(self, key)) != 1:
                raise ContractError(f"data.{key} must be one character, "
                                    f"got {getattr(self, key)!r}")


def _str_mapping(cfg: Mapping, key: str) -> dict:
    value = cfg.get(key, None) or {}
    if not hasattr(value, "items"):
        raise ContractError(f"data.{key} must be a mapping, got {value!r}")
    return {str(k): str(v) for k, v in value.items()}


def _float(cfg: Mapping, key: str, default: float | None, nullable: bool = False
           ) -> float | None:
    """``cfg[key]`` as a finite float; a missing key gives ``default``, and so does null
    unless ``nullable`` (then null switches the check it steers off)."""
    if key not in cfg:
        return default
    value = cfg.get(key)
    if value is None:
        return None if nullable else default
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ContractError(f"data.{key} must be a number, got {value!r}") from None
    if isinstance(value, bool) or not math.isfinite(number):
        raise ContractError(f"data.{key} must be a finite number, got {value!r}")
    return number


def _positive_float(cfg: Mapping, key: str, default: float | None = None,
                    nullable: bool = False) -> float | None:
    number = _float(cfg, key, default, nullable)
    if number is not None and number <= 0:
        raise ContractError(f"data.{key} must be > 0, got {number:g}")
    return number


def _count(cfg: Mapping, key: str) -> int:
    value = cfg.get(key, 0)
    value = 0 if value is None else value
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0:
        raise ContractError(f"data.{key} must be an integer >= 0, got {value!r}")
    return int(value)


# ---------------------------------------------------------------------------
# Manifest


def read_manifest(root: str | Path, opts: ReadOptions | None = None) -> pd.DataFrame:
    """Read and validate ``<root>/campaigns.csv``.

    Parameters
    ----------
    root : str or Path
        Dataset folder.
    opts : ReadOptions, optional
        Only ``split_overrides`` is used.

    Returns
    -------
    DataFrame
        Indexed by campaign id (``str``), columns ``file`` and ``split`` (with
        overrides applied), ``start`` as datetimes if present, then every other
        manifest column (numeric where every cell is a number).

    Raises
    ------
    ContractError
        Missing or empty manifest, missing required column, empty or
        duplicate id, invalid split, missing campaign file, a file listed twice, unsupported file
        type, unparseable ``start``, override of an unknown id.
    """
    opts = opts or ReadOptions()
    root = Path(root)
    path = root / MANIFEST
    raw = _load_manifest(path, opts.delimiter)
    _check_manifest_rows(raw, path, root)
    manifest = raw.set_index("campaign")
    _apply_split_overrides(manifest, opts.split_overrides, path)
    for column in manifest.columns.drop(["file", "split"]):
        manifest[column] = _metadata_column(manifest[column], path, column)
    return manifest


def _load_manifest(path: Path, delimiter: str = ",") -> pd.DataFrame:
    if not path.is_file():
        raise ContractError(f"manifest not found (a dataset folder needs {MANIFEST})", file=path)
    text = _utf8_text(path, delimiter)
    header = text.splitlines()[0] if text.strip() else ""
    try:
        raw = pd.read_csv(io.StringIO(text), sep=_manifest_delimiter(header, delimiter, path),
                          dtype=str, keep_default_na=False)
    except pd.errors.EmptyDataError:
        raise ContractError("manifest is empty", file=path) from None
    except pd.errors.ParserError as exc:
        raise ContractError(f"manifest is not valid CSV ({_first_line(exc)})", file=path) from None
    raw.columns = [c.strip() for c in raw.columns]
    for column in MANIFEST_REQUIRED:
        if column not in raw.columns:
            raise ContractError("required manifest column missing", file=path, column=column)
    if raw.empty:
        raise ContractError("manifest lists no campaign", file=path)
    return raw.fillna("").apply(lambda s: s.str.strip())


def _header_cells(line: str, delimiter: str) -> list[str]:
    return [c.strip() for c in next(csv.reader([line], delimiter=delimiter), [])]


def _manifest_delimiter(header: str, delimiter: str, path: Path) -> str:
    """``data.delimiter``, or ``,`` (the contract's own format) when the manifest's header
    only parses with it; a header that only parses with another separator is refused with
    the setting that reads it (instead of a misleading "column 'campaign' missing")."""
    def parses(sep):
        return set(MANIFEST_REQUIRED) <= set(_header_cells(header, sep))

    for sep in dict.fromkeys((delimiter, ",")):
        if parses(sep):
            return sep
    for sep in _OTHER_DELIMITERS:
        if parses(sep):
            raise ContractError(f"{MANIFEST} looks {sep!r}-separated: set data.delimiter={sep!r}",
                                file=path)
    return delimiter


def _utf8_text(path: Path, delimiter: str) -> str:
    """The whole (small) file as text; bytes that are not UTF-8 are refused where they are."""
    data = path.read_bytes()
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise _not_utf8(path, delimiter) from None


def _not_utf8(path: Path, delimiter: str, names: list[str] | None = None) -> ContractError:
    """The error naming the line (data row, or the header) and field of the first byte that
    is not UTF-8."""
    return (_utf8_failure(path, delimiter, names)
            or ContractError("file is not UTF-8 text", file=path))


def _utf8_failure(path: Path, delimiter: str, names: list[str] | None) -> ContractError | None:
    """:func:`_not_utf8`'s error, or None if every line is UTF-8 (read line by line, so a
    large file is never held whole)."""
    with open(path, "rb") as f:
        header = names
        for line_no, line in enumerate(f):
            if header is None:  # the file's own header names the fields
                header = _header_cells(line.decode("utf-8", "replace").lstrip("\ufeff"),
                                       delimiter)
            try:
                line.decode("utf-8")
            except UnicodeDecodeError as exc:
                field = line[:exc.start].count(delimiter.encode())
                column = header[field] if header and field < len(header) else None
                return ContractError(f"byte 0x{line[exc.start]:02x} is not UTF-8 text "
                                     "(save the file as UTF-8)", file=path, column=column,
                                     row=line_no or None)
    return None


def _check_manifest_rows(raw: pd.DataFrame, path: Path, root: Path) -> None:
    seen: dict[str, int] = {}
    files: dict[Path, int] = {}   # one file per campaign: a file under two ids would score twice
    for row, (cid, fname, split) in enumerate(zip(raw["campaign"], raw["file"], raw["split"]), 1):
        problem = None
        if not cid or _UNSAFE_ID.search(cid):
            problem = ("campaign", f"campaign id {cid!r} is empty, contains a path separator "
                                   "or starts with '.'")
        elif cid in seen:
            problem = "campaign", f"duplicate campaign id {cid!r} (first at row {seen[cid]})"
        elif split not in SPLITS:
            problem = "split", f"split {split!r} is not one of {', '.join(SPLITS)}"
        elif os.path.isabs(fname) or os.path.normpath(fname).split(os.sep)[0] == "..":
            problem = "file", (f"campaign file {fname!r} lies outside the dataset folder: "
                               "files are paths relative to it, without '..'")
        elif Path(fname).suffix.lower() not in CAMPAIGN_SUFFIXES:
            problem = "file", f"campaign file {fname!r} is neither .csv nor .parquet"
        elif not (root / fname).is_file():
            problem = "file", f"campaign file {fname!r} not found in {root}"
        elif (root / fname).resolve() in files:
            problem = "file", (f"campaign file {fname!r} is already listed at row "
                               f"{files[(root / fname).resolve()]}: one file per campaign")
        if problem:
            column, message = problem
            raise ContractError(message, file=path, column=column, row=row)
        seen[cid] = row
        files[(root / fname).resolve()] = row


def _apply_split_overrides(manifest: pd.DataFrame, overrides: dict, path: Path) -> None:
    unknown = [cid for cid in overrides if cid not in manifest.index]
    if unknown:
        raise ContractError(f"data.split_overrides names campaign {unknown[0]!r}, "
                            f"which the manifest does not list", file=path, column="campaign")
    for cid, split in overrides.items():
        manifest.loc[cid, "split"] = split


def _metadata_column(values: pd.Series, path: Path, column: str) -> pd.Series:
    if column == "start":
        return _parse_start(values, path)
    if column == "notes":
        return values
    present = values[values != ""]
    numbers = pd.to_numeric(present, errors="coerce")
    if len(present) and numbers.notna().all():
        return pd.to_numeric(values.replace("", np.nan))
    return values


def _parse_start(values: pd.Series, path: Path) -> pd.Series:
    for row, value in enumerate(values, 1):
        if value:
            try:
                pd.to_datetime(value, format="ISO8601")
            except (ValueError, TypeError):
                raise ContractError(f"start {value!r} is not an ISO 8601 time",
                                    file=path, column="start", row=row) from None
    present = values.replace("", None)
    try:
        return pd.to_datetime(present, format="ISO8601")
    except ValueError:  # several zone offsets: keep instants, in UTC
        return pd.to_datetime(present, format="ISO8601", utc=True)


# ---------------------------------------------------------------------------
# Column names


def _contract_names(raw_names: list[str], mapping: dict, file: Path, *,
                    has_period: bool) -> list[str]:
    """Mapped column names, checked against the contract's vocabulary."""
    names = []
    for raw in raw_names:
        name = mapping.get(raw, raw)
        alias = f" (raw name {raw!r})" if name != raw else ""
        if role(name) is None:
            raise ContractError(f"column name{alias} has no contract role: expected 'time' or "
                                "a T_/E_/S_ prefix (map it with data.columns)",
                                file=file, column=name)
        if name != TIME and (not _NAME.fullmatch(name) or ".." in name):
            raise ContractError(f"column name{alias} is not a prefix plus an identifier-like name "
                                "(letters, digits, '_', '-', '.'; no path separator, '..', space "
                                "or control character): map it with data.columns",
                                file=file, column=name)
        if name in names:
            raise ContractError("duplicate column (after data.columns mapping)",
                                file=file, column=name)
        names.append(name)
    if not any(role(n) == "E" for n in names):
        raise ContractError("no E_ column: a campaign needs at least one measured error",
                            file=file)
    if TIME not in names and not has_period:
        raise ContractError("no 'time' column and no data.sample_period_s to build one",
                            file=file)
    return names


def _ordered(names: list[str]) -> list[str]:
    """``time`` first, then ``T_``, ``E_``, ``S_`` columns, each in file order."""
    data = [n for n in names if n != TIME]
    return [TIME] + sorted(data, key=lambda n: ROLE_ORDER.index(role(n)))


# ---------------------------------------------------------------------------
# Loading CSV


def _load_csv(path: Path, opts: ReadOptions) -> dict:
    header, first_row = _peek_csv(path, opts.delimiter)
    if len(header) == 1:
        _check_delimiter(header[0], opts.delimiter.join(first_row), path, opts)
    names = _contract_names(header, opts.columns, path, has_period=opts.sample_period_s is not None)
    if len(first_row) != len(names):
        raise ContractError(f"expected {len(names)} fields, got {len(first_row)}", file=path, row=1)
    types = {n: pa.float64() for n in names if n != TIME}
    if TIME in names:
        types[TIME] = _csv_time_type(path, first_row, names.index(TIME), opts)
    return _columns(_read_csv_typed(path, names, types, opts))


def _check_delimiter(header: str, first: str, path: Path, opts: ReadOptions) -> None:
    """A single column whose name holds another separator: the file was read with the wrong
    ``data.delimiter`` (say which one reads it, rather than a misleading name error)."""
    for sep in _OTHER_DELIMITERS:
        if sep != opts.delimiter and sep in header:
            cells = next(csv.reader([first], delimiter=sep), [])
            comma = sep != "," and opts.decimal != "," and any(
                re.fullmatch(r"[+-]?\d+,\d+", c.strip()) for c in cells)
            hint = " data.decimal=','" if comma else ""
            raise ContractError(f"file looks {sep!r}-separated (one column {header!r}): "
                                f"set data.delimiter={sep!r}{hint}", file=path)


def _peek_csv(path: Path, delimiter: str) -> tuple[list[str], list[str]]:
    """Header (stripped names) and first data row, without reading the file."""
    try:
        with open(path, newline="", encoding="utf-8-sig") as f:
            rows = csv.reader(f, delimiter=delimiter)
            header = next(rows, None)
            first = next((r for r in rows if r), None)
    except UnicodeDecodeError:
        raise _not_utf8(path, delimiter) from None
    if not header:
        raise ContractError("empty file", file=path)
    if first is None:
        raise ContractError("file has a header but no data rows", file=path)
    return [name.strip() for name in header], first


def _csv_time_type(path: Path, first_row: list[str], index: int,
                   opts: ReadOptions) -> pa.DataType:
    value = first_row[index].strip()
    if not value:
        raise ContractError("missing time value", file=path, column=TIME, row=1)
    kind = opts.time
    if kind == "auto":
        kind = "seconds" if _is_number(value, opts.decimal) else "iso8601"
    if kind == "seconds":
        return pa.float64()
    return pa.timestamp("ns", tz="UTC" if _ZONE_OFFSET.search(value) else None)


def _is_number(text: str, decimal: str) -> bool:
    try:
        float(text.replace(decimal, "."))
    except ValueError:
        return False
    return True


def _csv_options(names: list[str], opts: ReadOptions, *, types=None, include=None,
                 use_threads=True, invalid_row_handler=None):
    read = pacsv.ReadOptions(column_names=names, skip_rows=1, use_threads=use_threads,
                             block_size=_CSV_BLOCK_BYTES)
    parse = pacsv.ParseOptions(delimiter=opts.delimiter, invalid_row_handler=invalid_row_handler)
    convert = pacsv.ConvertOptions(column_types=types or {}, include_columns=include or [],
                                   decimal_point=opts.decimal, strings_can_be_null=True)
    return dict(read_options=read, parse_options=parse, convert_options=convert)


def _read_csv_typed(path: Path, names: list[str], types: dict, opts: ReadOptions) -> pa.Table:
    try:
        return pacsv.read_csv(path, **_csv_options(names, opts, types=types))
    except pa.ArrowInvalid as exc:
        raise _locate_csv_error(path, names, types, opts, exc) from None


def _locate_csv_error(path, names, types, opts, exc) -> ContractError:
    """Turn Arrow's row-less CSV error into one naming the column and row."""
    message = _first_line(exc)
    if "UTF8" in message or _CONVERSION_ERROR.search(message):
        # a cell that is not UTF-8 cannot be read back as text to locate it
        bad_bytes = _utf8_failure(path, opts.delimiter, names)
        if bad_bytes is not None:
            return bad_bytes
    match = _CONVERSION_ERROR.search(message)
    if match:
        column = names[int(match.group(1))]
        return _bad_cell_error(path, names, column, types[column], opts)
    if "CSV parse error" in message:
        return _malformed_row_error(path, names, opts, message)
    return ContractError(f"unreadable CSV ({message})", file=path)


def _bad_cell_error(path, names, column, target, opts) -> ContractError:
    text = pacsv.read_csv(path, **_csv_options(names, opts, include=[column],
                                                types={column: pa.string()})).column(column)
    if opts.decimal != "." and pa.types.is_floating(target):
        text = pc.replace_substring(text, opts.decimal, ".")
    found = _first_cast_failure(text, target)
    if found is None:
        return ContractError(f"cannot convert to {target}", file=path, column=column)
    row, value = found
    return ContractError(f"value {value!r} is not {_describe(target)}",
                         file=path, column=column, row=row + 1)


def _malformed_row_error(path, names, opts, message) -> ContractError:
    bad = []

    def remember(row):
        bad.append(row)
        return "error"

    with contextlib.suppress(pa.ArrowInvalid):
        pacsv.read_csv(path, **_csv_options(names, opts, include=[names[0]],
                                            types={names[0]: pa.string()}, use_threads=False,
                                            invalid_row_handler=remember))
    if not bad:
        return ContractError(f"unreadable CSV ({message})", file=path)
    row = bad[0]
    return ContractError(f"expected {row.expected_columns} fields, got {row.actual_columns}",
                         file=path, row=None if row.number is None else row.number - 1)


def _first_cast_failure(values: pa.ChunkedArray, target: pa.DataType) -> tuple[int, object] | None:
    """Position and value of the first element that does not cast to ``target``.

    Bisects inside the first failing chunk, so the cost is a few casts of
    one chunk rather than a Python loop over the column.
    """
    offset = 0
    for chunk in values.chunks:
        if not _casts(chunk, target):
            ok, fails = 0, len(chunk)  # chunk[:ok] casts, chunk[:fails] does not
            while fails - ok > 1:
                mid = (ok + fails) // 2
                ok, fails = (mid, fails) if _casts(chunk[:mid], target) else (ok, mid)
            return offset + fails - 1, chunk[fails - 1].as_py()
        offset += len(chunk)
    return None


def _casts(values, target: pa.DataType) -> bool:
    try:
        pc.cast(values, target)
    except (pa.ArrowInvalid, pa.ArrowNotImplementedError):
        return False
    return True


def _describe(target: pa.DataType) -> str:
    if pa.types.is_timestamp(target):
        zone = "with" if target.tz else "without"
        return f"an ISO 8601 timestamp {zone} zone offset (like the first row)"
    return "a number"


# ---------------------------------------------------------------------------
# Loading Parquet


def _load_parquet(path: Path, opts: ReadOptions) -> dict:
    try:
        table = pq.read_table(path)
    except (pa.ArrowInvalid, OSError) as exc:
        reason = _ARROW_SOURCE.sub("", _first_line(exc))
        raise ContractError(f"unreadable Parquet file ({reason})", file=path) from None
    table = table.drop_columns([c for c in table.column_names if _PANDAS_INDEX.fullmatch(c)])
    names = _contract_names(table.column_names, opts.columns, path,
                            has_period=opts.sample_period_s is not None)
    table = table.rename_columns(names)
    for i, name in enumerate(names):
        column = table.column(i)
        if name == TIME:
            column = _parquet_time(column, path, opts)
        else:
            column = _parquet_numbers(column, name, path)
        table = table.set_column(i, name, column)
    return _columns(table)


def _parquet_numbers(column: pa.ChunkedArray, name: str, path: Path) -> pa.ChunkedArray:
    kind = column.type
    numeric = (pa.types.is_floating(kind) or pa.types.is_integer(kind)
               or pa.types.is_decimal(kind) or (pa.types.is_boolean(kind) and role(name) == "S"))
    if numeric:
        return pc.cast(column, pa.float64())
    found = _first_cast_failure(column, pa.float64()) or _first_valid(column)
    row = None if found is None else found[0] + 1
    raise ContractError(f"Parquet dtype {kind} where numbers are expected",
                        file=path, column=name, row=row)


def _parquet_time(column: pa.ChunkedArray, path: Path, opts: ReadOptions) -> pa.ChunkedArray:
    kind = column.type
    if pa.types.is_string(kind) or pa.types.is_large_string(kind):
        first = _first_valid(column)
        target = _csv_time_type(path, [first[1] if first else ""], 0, opts)
        found = _first_cast_failure(column, target)
        if found is not None:
            raise ContractError(f"value {found[1]!r} is not {_describe(target)}",
                                file=path, column=TIME, row=found[0] + 1)
        return pc.cast(column, target)
    if (pa.types.is_floating(kind) or pa.types.is_integer(kind) or pa.types.is_timestamp(kind)
            or pa.types.is_duration(kind)):
        return column
    raise ContractError(f"Parquet dtype {kind} where seconds or timestamps are expected",
                        file=path, column=TIME)


def _first_valid(column: pa.ChunkedArray) -> tuple[int, object] | None:
    valid = np.flatnonzero(column.is_valid().to_numpy(zero_copy_only=False))
    return (int(valid[0]), column[int(valid[0])].as_py()) if valid.size else None


# ---------------------------------------------------------------------------
# Columns
#
# From here on a campaign is a dict {name: Arrow column}.  Steps replace
# entries in place, so a replaced column is freed at once and memory stays at
# about one copy of the campaign.


def _columns(table: pa.Table) -> dict:
    return dict(zip(table.column_names, table.columns))


def _values(column) -> np.ndarray:
    """A float column as a numpy copy, NaN where missing."""
    if column.null_count:
        column = pc.fill_null(column, np.nan)
    if isinstance(column, pa.ChunkedArray):
        return column.to_numpy()
    return column.to_numpy(zero_copy_only=False)


def _chunks(column) -> list:
    return column.chunks if isinstance(column, pa.ChunkedArray) else [column]


# ---------------------------------------------------------------------------
# Time


def _set_time_seconds(columns: dict, rows: int, path: Path, opts: ReadOptions) -> dict:
    """Replace (or add) ``time`` by float seconds; describe its source."""
    if TIME not in columns:
        columns[TIME] = pa.array(np.arange(rows) * opts.sample_period_s)
        return {"time": "sample_period_s"}
    column = columns[TIME]
    try:
        if column.null_count:
            row = int(np.argmax(column.is_null().to_numpy(zero_copy_only=False))) + 1
            raise ContractError("missing time value", file=path, column=TIME, row=row)
        seconds, info = _seconds(column)
        _check_increasing(seconds, path)
    except ContractError as exc:
        if opts.missing != "keep":
            raise
        raise ContractError(f"{exc.reason} (a test record with bad times streams as on the "
                            "machine when piped: thermocomp monitor monitor.input=- < FILE)",
                            file=exc.file, column=exc.column, row=exc.row) from None
    _check_duration(seconds, path, opts.max_duration_days)
    columns[TIME] = pa.array(seconds)
    return info


def _seconds(column: pa.ChunkedArray) -> tuple[np.ndarray, dict]:
    kind = column.type
    if pa.types.is_timestamp(kind):
        ns = pc.cast(pc.cast(column, pa.timestamp("ns", kind.tz)), pa.int64()).to_numpy()
        origin = pd.Timestamp(ns[0], tz=kind.tz).isoformat()
        return (ns - ns[0]) / 1e9, {"time": "iso8601", "time_origin": origin}
    if pa.types.is_duration(kind):
        ns = pc.cast(pc.cast(column, pa.duration("ns")), pa.int64()).to_numpy()
        return ns / 1e9, {"time": "seconds"}
    return pc.cast(column, pa.float64()).to_numpy(), {"time": "seconds"}


def _check_increasing(seconds: np.ndarray, path: Path) -> None:
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
    what = (f"duplicate time {after:g} s (same as row {i + 1})" if after == before else
            f"time decreases from {before:g} s (row {i + 1}) to {after:g} s")
    raise ContractError(what, file=path, column=TIME, row=i + 2)


def _check_duration(seconds: np.ndarray, path: Path, max_days: float | None) -> None:
    days = (seconds[-1] - seconds[0]) / 86400
    if max_days is not None and days > max_days:
        raise ContractError(f"the campaign lasts {days:.4g} days, more than "
                            f"data.max_duration_days={max_days:g}: is time in ms? it must be "
                            "in seconds", file=path, column=TIME, row=len(seconds))


def _median_period(table: pa.Table) -> float | None:
    time = table.column(TIME).to_numpy()
    return float(np.median(np.diff(time))) if len(time) > 1 else None


def _check_periods(periods: dict, files: Mapping, root: Path, ratio: float | None) -> None:
    """Refuse a campaign whose median sample period is ``ratio`` times (or 1/``ratio``) the
    median of the others': its time column is in another unit (ms, minutes) than theirs."""
    periods = {c: p for c, p in periods.items() if p}
    if ratio is None or len(periods) < 2:
        return
    off = {}
    for cid, p in periods.items():
        r = p / np.median([q for c, q in periods.items() if c != cid])
        if r >= ratio or r <= 1 / ratio:
            off[cid] = r
    if not off:
        return
    cid = max(off, key=off.get)  # two campaigns disagree: ms (a time 1000x too large) is likelier
    r = off[cid]
    unit = ("ms" if r < 3e4 else "µs") if r > 1 else ("minutes" if r > 1 / 600 else "hours")
    raise ContractError(f"median sample period {periods[cid]:g} s is {r:.3g}x the other "
                        f"campaigns' ({periods[cid] / r:g} s): is its time in {unit}? it must be "
                        f"in seconds (data.max_period_ratio={ratio:g})",
                        file=root / files[cid], column=TIME)


# ---------------------------------------------------------------------------
# Values and missing samples


def _check_values(values: np.ndarray, name: str, path: Path, opts: ReadOptions) -> np.ndarray:
    """Refuse impossible values; return the positions of missing ones."""
    finite = np.isfinite(values)
    missing = np.empty(0, dtype=np.intp)
    if not finite.all():
        missing = np.flatnonzero(~finite)
        infinite = missing[np.isinf(values[missing])]
        if infinite.size:
            row = int(infinite[0]) + 1
            raise ContractError(f"infinite value {values[row - 1]}", file=path, column=name,
                                row=row)
        if missing.size == values.size:
            raise ContractError("column has no valid value (every cell is empty)",
                                file=path, column=name)
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
            why = ("temperatures look like kelvin, convert to °C" if median > threshold else
                   f"a faulty reading (the column's median is {median:.4g} °C): a campaign "
                   "fitted on must be clean; replay and monitor stream a test campaign with it")
            raise ContractError(f"{values[row - 1]:g} °C is above data.kelvin_threshold_c="
                                f"{threshold:g}: {why}", file=path, column=name, row=row)
    if lowest < ABSOLUTE_ZERO_C:
        row = int(np.argmax(values < ABSOLUTE_ZERO_C)) + 1
        raise ContractError(f"{values[row - 1]:g} °C is below absolute zero",
                            file=path, column=name, row=row)


def _repair_missing(columns: dict, rows: int, path: Path, opts: ReadOptions) -> dict:
    """Validate every data column; trim incomplete edge rows, interpolate gaps.

    Returns ``{"repairs": {column: n}, "trimmed": {"start": n, "end": n}}``.
    """
    gaps = {}  # column -> sorted positions of its missing values
    for name in columns:
        if name != TIME:
            missing = _check_values(_values(columns[name]), name, path, opts)
            if missing.size:
                gaps[name] = missing
    if not gaps:
        return {"repairs": {}, "trimmed": {"start": 0, "end": 0}}
    start, stop = _complete_span(rows, gaps, path, opts.max_edge_samples)
    for name in columns:
        columns[name] = columns[name].slice(start, stop - start)
    time = _values(columns[TIME])
    repairs = {}
    for name, positions in gaps.items():
        inside = positions[(positions >= start) & (positions < stop)] - start
        if inside.size:
            _check_gap_lengths(inside, name, start, path, opts.max_gap_samples)
            columns[name] = _patched(columns[name], inside, _gap_values(columns[name], time, inside))
            repairs[name] = int(inside.size)
    return {"repairs": repairs, "trimmed": {"start": start, "end": rows - stop}}


def _keep_missing(columns: dict, rows: int, path: Path, opts: ReadOptions) -> dict:
    """Validate every data column and leave its missing values as they are (``missing="keep"``).

    Returns ``{"repairs": {}, "trimmed": {"start": 0, "end": 0}, "missing": {column: n}}``.
    """
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
        raise ContractError(f"gap of {length} missing value{'s' * (length > 1)} ({where}) is "
                            f"longer than data.max_gap_samples={max_gap}",
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


def _resample(columns: dict, step: float, path: Path, max_factor: float) -> None:
    """Linear interpolation of every column onto ``t0, t0 + step, ...``."""
    time = _values(columns[TIME])
    count = (time[-1] - time[0]) / step + 1
    if not count <= min(max_factor * len(time), MAX_GRID_ROWS):  # before allocating it
        raise ContractError(f"data.resample_s={step:g} would make {count:.4g} rows from "
                            f"the file's {len(time)} (at most data.max_resample_factor={max_factor:g} "
                            f"times the file's rows and {MAX_GRID_ROWS:.0e})", file=path)
    count = int(math.floor((time[-1] - time[0]) / step + 1e-9)) + 1
    grid = time[0] + step * np.arange(count)
    for name in columns:
        if name != TIME:
            columns[name] = pa.array(np.interp(grid, time, _values(columns[name])))
    columns[TIME] = pa.array(grid)


def read_campaign(path: str | Path, cfg: Mapping | ReadOptions | None = None
                  ) -> tuple[pa.Table, dict]:
    """Read and validate one campaign file into an Arrow table.

    Parameters
    ----------
    path : str or Path
        A ``.csv`` or ``.parquet`` campaign file.
    cfg : mapping or ReadOptions, optional
        The ``data`` config (see :func:`read_dataset`).

    Returns
    -------
    table : pyarrow.Table
        ``time`` (float seconds), then ``T_``, ``E_``, ``S_`` columns, all
        float64, no missing value (``missing="keep"``: missing values stay,
        as nulls; a resampled grid point next to one is missing too).
    report : dict
        ``rows``, ``source_rows``, ``time`` (``'seconds'``, ``'iso8601'`` or
        ``'sample_period_s'``; ``time_origin`` for timestamps), ``repairs``
        ({column: interpolated samples}), ``trimmed`` ({"start", "end"} rows),
        ``resampled_s`` when resampled and, with ``missing="keep"``,
        ``missing`` ({column: missing cells kept}).

    Raises
    ------
    ContractError
        If the file breaks the contract; see :func:`read_dataset`.
    """
    opts = cfg if isinstance(cfg, ReadOptions) else ReadOptions.from_cfg(cfg)
    path = Path(path)
    if not path.is_file():
        raise ContractError("campaign file not found", file=path)
    if path.stat().st_size == 0:
        raise ContractError("empty file", file=path)
    load = _load_parquet if path.suffix.lower() == ".parquet" else _load_csv
    columns = load(path, opts)
    rows = len(next(iter(columns.values())))
    if rows == 0:
        raise ContractError("file has no data rows", file=path)
    missing = _keep_missing if opts.missing == "keep" else _repair_missing
    report = {"source_rows": rows, **_set_time_seconds(columns, rows, path, opts),
              **missing(columns, rows, path, opts)}
    _check_length(len(columns[TIME]), path, "complete " if opts.missing == "repair" else "")
    _check_fahrenheit(columns, path, opts.fahrenheit_threshold_c, report["trimmed"]["start"])
    if opts.resample_s is not None:
        _resample(columns, opts.resample_s, path, opts.max_resample_factor)
        report["resampled_s"] = opts.resample_s
        _check_length(len(columns[TIME]), path, f"(after data.resample_s={opts.resample_s:g}) ")
    table = pa.table({name: columns.pop(name) for name in _ordered(list(columns))})
    return table, {"rows": table.num_rows, **report}


def _iter_campaigns(root: Path, manifest: pd.DataFrame, opts: ReadOptions
                    ) -> Iterator[tuple[str, pa.Table, dict]]:
    """Every campaign, read and validated; once all are read, their sample periods are
    compared (a campaign timed in another unit is refused)."""
    periods = {}
    for cid, row in manifest.iterrows():
        table, report = read_campaign(root / row["file"], opts)
        periods[cid] = _median_period(table)
        yield cid, table, {"file": row["file"], "split": row["split"], **report}
        del table  # before reading the next campaign
    _check_periods(periods, manifest["file"], root, opts.max_period_ratio)


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
              "settings": {k: v for k, v in asdict(opts).items() if k != "missing"}}
    if opts.missing == "keep":
        report["missing"] = totals("missing")
    return report


def _collect_roles(columns: dict, names: list[str]) -> None:
    for name in names:
        if name != TIME:
            columns.setdefault(role(name), {}).setdefault(name, None)


def _to_frame(table: pa.Table) -> pd.DataFrame:
    return table.to_pandas(split_blocks=True)


# ---------------------------------------------------------------------------
# Public entry points


def read_dataset(path: str | Path, cfg: Mapping | None = None, *, missing: str = "repair",
                 campaigns: Sequence[str] | None = None) -> tuple[Dataset, dict]:
    """Read, validate and repair a dataset folder.

    Parameters
    ----------
    path : str or Path
        Dataset folder with ``campaigns.csv`` and the campaign files.
    cfg : mapping, optional
        The ``data`` config group (dict or ``DictConfig``); every key is
        optional:

        columns : mapping
            Raw column name -> contract name, applied to every campaign file
            before validation (e.g. ``{"delta L": "E_L", "Zeit": "time"}``).
        sample_period_s : float
            Files without a ``time`` column get ``time = row * sample_period_s``.
            A file with a ``time`` column keeps its own.
        time : {'auto', 'seconds', 'iso8601'}
            How to read ``time``; ``'auto'`` decides from the first row.
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
        delimiter, decimal : str, default ',' and '.'
            CSV field separator and decimal mark of the campaign files.
    missing : {'repair', 'keep'}, default 'repair'
        Not a config key: ``'keep'`` leaves missing values NaN (no trim, no
        interpolation, no gap refused) and counts them in the report's
        ``missing``, for a stage that must see the data as it was recorded.

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
        dtypes), infinite values, temperatures that look like kelvin, an
        all-missing column, gaps or incomplete edges beyond the configured
        limits, and invalid config values.

    Notes
    -----
    Missing values are handled as described in the module docstring: gaps
    are interpolated and edges trimmed only up to the configured limits, and
    every repair is counted.
    """
    opts = replace(ReadOptions.from_cfg(cfg), missing=missing)
    root = Path(path)
    manifest = read_manifest(root, opts)
    if campaigns is not None:
        manifest = manifest.loc[list(campaigns)]
    frames, entries, columns = {}, {}, {}
    for cid, table, entry in _iter_campaigns(root, manifest, opts):
        _collect_roles(columns, table.column_names)
        frames[cid], entries[cid] = _to_frame(table), entry
        del table
    report = _dataset_report(root.name, entries, columns, opts)
    manifest = _starts_from_timestamps(manifest, entries)
    return Dataset(manifest, frames, root.name, {"path": str(root)}), report


def _starts_from_timestamps(manifest: pd.DataFrame, entries: Mapping) -> pd.DataFrame:
    """The manifest with ``start`` filled, where it is empty, by the campaign's first timestamp
    (files whose ``time`` is ISO 8601): the optional ``start`` column then says when each
    campaign began, so a record cut into consecutive files is seen as one (carry-over)."""
    origins = {cid: e.get("time_origin") for cid, e in entries.items() if e.get("time_origin")}
    if not origins:
        return manifest
    out = manifest.copy()
    if "start" not in out.columns:
        out["start"] = pd.Series([None] * len(out), index=out.index, dtype=object)
    out["start"] = out["start"].astype(object)
    for cid, origin in origins.items():
        if cid in out.index and pd.isna(out.at[cid, "start"]):
            out.at[cid, "start"] = pd.Timestamp(origin)
    return out


def ingest(src: str | Path, dest: str | Path, cfg: Mapping | None = None, extra: dict | None = None) -> dict:
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
    manifest = read_manifest(src, opts)
    entries, columns = {}, {}
    with atomic_dir(dest) as tmp:
        for cid, table, entry in _iter_campaigns(src, manifest, opts):
            _collect_roles(columns, table.column_names)
            pq.write_table(table, tmp / f"{cid}.parquet")
            entries[cid] = entry
            del table
            pa.default_memory_pool().release_unused()
        out = _starts_from_timestamps(manifest, entries).assign(
            file=[f"{cid}.parquet" for cid in manifest.index])
        (tmp / MANIFEST).write_text(_manifest_csv(out))
        report = {**_dataset_report(src.name, entries, columns, opts), **(extra or {})}
        write_json(tmp / INGEST_REPORT, report, ensure_ascii=False)
    return report


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
        (:func:`~thermocomp.files.folder_digest`) of exactly what was read.

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
    campaigns = {cid: _to_frame(pq.read_table(root / f)) for cid, f in manifest["file"].items()}
    meta = {"path": str(root), "ingest_report": json.loads(report_path.read_text())}
    # named after the dataset it was ingested from, as run names it (not the interim folder)
    return Dataset(manifest, campaigns, meta["ingest_report"].get("dataset") or root.name, meta)


def check_separate(src: Path, dest: Path) -> None:
    a, b = src.resolve(), dest.resolve()
    if a == b or a in b.parents or b in a.parents:
        raise ContractError(f"ingest destination {dest} overlaps the raw dataset {src}; "
                            "raw files are never modified")


def _manifest_csv(manifest: pd.DataFrame) -> str:
    out = manifest.copy()
    if "start" in out.columns:
        out["start"] = [t.isoformat() if pd.notna(t) else "" for t in out["start"]]
    ordered = ["file", "split"] + [c for c in out.columns if c not in ("file", "split")]
    return out[ordered].rename_axis("campaign").reset_index().to_csv(index=False)


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__
