"""The manifest ``campaigns.csv``: its delimiter, encoding, rows, splits and start times."""

from __future__ import annotations

import io
import os
import re
from collections import Counter
from pathlib import Path

import numpy as np
import pandas as pd

from ...base.log import logger
from .contract import AMBIENT_C, MANIFEST, MANIFEST_REQUIRED, SPLITS, ContractError
from .encoding import UTF8, check_text, fields, own, text_codec, undecodable
from .hdf5 import HDF5_SUFFIXES
from .instants import on_clock, start_instants, start_stamp
from .jsonlines import JSON_LINES_SUFFIXES
from .loggers import ERROR_FILE, logger_pairs, paired_id
from .lvm import LVM_SUFFIXES
from .matfile import MAT_SUFFIXES
from .options import _OTHER_DELIMITERS, AUTO, ReadOptions, _first_line
from .sinumerik import TRACE_SUFFIXES, not_a_trace
from .suffixes import TEXT_SUFFIXES, is_text
from .tdm import TDM_SUFFIXES
from .tdms import TDMS_SUFFIXES
from .workbook import WORKBOOK_SUFFIXES, not_read

# a folder's runs without a manifest (a workbook is read as its CSV export, :mod:`.workbook`; a
# TDMS log, a MATLAB file or a LabVIEW Measurement File as its channels', :mod:`.labfile`)
LAB_SUFFIXES = (*TDMS_SUFFIXES, *MAT_SUFFIXES, *LVM_SUFFIXES, *HDF5_SUFFIXES, *TDM_SUFFIXES,
                *TRACE_SUFFIXES)
CAMPAIGN_SUFFIXES = (".csv", ".parquet", *WORKBOOK_SUFFIXES, *JSON_LINES_SUFFIXES, *LAB_SUFFIXES)
RECORD_SUFFIXES = (*TEXT_SUFFIXES, ".parquet", *WORKBOOK_SUFFIXES, *LAB_SUFFIXES)
EXCEL_OWNER = "~$"     # the lock file Excel leaves beside a workbook it has open
_UNSAFE_ID = re.compile(r"[/\\\x00-\x1f]|^\.")


# ---------------------------------------------------------------------------
# Manifest


def read_manifest(root: str | Path, opts: ReadOptions | None = None) -> pd.DataFrame:
    """Read and validate ``<root>/campaigns.csv``.

    Parameters
    ----------
    root : str or Path
        Dataset folder.
    opts : ReadOptions, optional
        Its ``split_overrides``, ``delimiter``, ``decimal`` and ``encoding`` are used.

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
    held_out = opts.test_fraction is not None or opts.val_fraction is not None
    files = [] if path.is_file() else campaign_files(root)
    if files:    # a lab's folder of runs: every file a train campaign, in natural name order
        _check_no_manifest_among(files)
        _check_no_sheet_unread(root, len(files))
        pairs = logger_pairs(files, opts)     # a run of two loggers: its temperature file
        files = [f for f in files if f not in set(pairs.values())]
        raw = pd.DataFrame({"campaign": [paired_id(f) if f in pairs else f.stem for f in files],
                            "file": [f.name for f in files]})
    else:
        raw = _load_manifest(path, opts.delimiter, optional=("split",) if held_out else (),
                             encoding=opts.encoding)
    if "split" not in raw.columns:    # every campaign train: data.test_fraction holds some out
        raw.insert(2, "split", "train")
    _check_manifest_rows(raw, path, root)
    _check_error_files(raw, path, root)
    _check_continues(raw, path)
    manifest = raw.set_index("campaign")
    apply_split_overrides(manifest, opts.split_overrides, path)
    for column in manifest.columns.drop(["file", "split"]):
        manifest[column] = _metadata_column(manifest[column], path, column, opts.decimal,
                                            opts.timezone)
    return manifest


def campaign_files(folder: Path) -> list[Path]:
    """The campaign files of a folder without a manifest, in natural order (``run_2`` before
    ``run_10``): a lab's export of one file per run."""
    def natural(p: Path):
        return [(0, int(t), "") if t.isdigit() else (1, 0, t.lower())
                for t in re.split(r"(\d+)", p.name)]
    if not folder.is_dir():
        return []
    files = [p for p in folder.iterdir() if p.is_file() and not p.name.startswith((".", EXCEL_OWNER))]
    # (stranger81: an .xml beside the traces that is none, a trace's settings, crashed init)
    runs = [p for p in files if p.suffix.lower() in CAMPAIGN_SUFFIXES and not not_a_trace(p)]
    # a folder of text exports alone (a logger's .dat, Excel's 'Unicode Text' .txt): those are
    # its runs; beside CSV, Parquet or workbooks a .txt is a note, not a run
    return sorted(runs or [p for p in files if p.suffix.lower() in TEXT_SUFFIXES], key=natural)


def subfolder_runs(folder: Path) -> dict[str, int]:
    """The campaign files below each sub-folder of ``folder`` (a lab's runs sorted into month
    folders), by sub-folder: a folder without a manifest reads only the files directly in it."""
    found = {}
    for sub in sorted(p for p in folder.iterdir() if p.is_dir() and not p.name.startswith(".")):
        n = sum(1 for p in sub.rglob("*") if p.suffix.lower() in CAMPAIGN_SUFFIXES
                and p.is_file() and not p.name.startswith((".", EXCEL_OWNER)))
        if n:
            found[sub.name] = n
    return found


def said_subfolders(found: dict[str, int]) -> str:
    """``found`` (:func:`subfolder_runs`) said: ``2023-01/ (16), 2023-02/ (16)``."""
    return ", ".join(f"{name}/ ({n})" for name, n in found.items())


def _check_no_manifest_among(files: list[Path]) -> None:
    """A lab's list of its runs saved under another name (``Versuchsplan.csv``) is no run: its
    header names ``campaign`` and ``file`` (read otherwise, its ids are "not numeric")."""
    for f in files:
        if not is_text(f):
            continue
        with open(f, encoding="utf-8", errors="replace") as handle:
            header = handle.readline().lstrip("\ufeff")
        if any({"campaign", "file"} <= set(fields(header, sep)) for sep in _OTHER_DELIMITERS):
            raise ContractError(f"a manifest under another name (its header names campaign and "
                                f"file): rename it {MANIFEST} to read the folder through it",
                                file=f)


def _check_no_sheet_unread(folder: Path, runs: int) -> None:
    """A run saved as a spreadsheet the reader does not read (``.xls``, ``.xlsb``, ``.ods``)
    beside the folder's run files (audit87: left out unsaid, the record a campaign short and
    another one held out), refused as that file named as ``data.path`` is."""
    for p in sorted(folder.iterdir()):
        said = not_read(p) if p.is_file() and not p.name.startswith((".", EXCEL_OWNER)) else None
        if said:
            raise ContractError(f"{said} (beside the folder's {runs} run file(s) it was left out; "
                                f"not a run: move it out of the folder)", file=p)


def _other_files(folder: Path) -> str:
    """What a folder without a manifest and without a run file holds instead, by suffix, and the
    suffixes a run file has (stranger69: a folder of LabVIEW's ``.lvm`` runs was "manifest not
    found" alone, its files not named)."""
    if not folder.is_dir():
        return ""
    kinds = Counter(p.suffix.lower() or "(no suffix)" for p in folder.iterdir()
                    if p.is_file() and not p.name.startswith("."))
    if not kinds:
        return ""
    said = ", ".join(f"{k} ({n})" for k, n in kinds.most_common(5))
    known = "".join(f"; {k}: {BINARY_KINDS[k]}" for k in kinds if k in BINARY_KINDS)
    return (f"; its files, {said}, are no kind read as a run ("
            f"{', '.join(sorted(set(RECORD_SUFFIXES)))}){known}")


# a logger's own binary record, its CSV export the run file (stranger82: a folder of a GL840's
# .gbd files was "no kind read as a run" alone, the way to a file read not said)
BINARY_KINDS = {".gbd": "a Graphtec logger's binary record: save its runs as CSV, which is read "
                        "(the logger writes CSV to its card, its PC software converts a .gbd)"}


def _load_manifest(path: Path, delimiter: str = ",", optional: tuple = (),
                   encoding: str = UTF8) -> pd.DataFrame:
    if not path.is_file():
        below = subfolder_runs(path.parent) if path.parent.is_dir() else {}
        if below:    # a lab's runs sorted into sub-folders (it was "manifest not found" alone)
            raise ContractError(
                f"manifest not found, and no run file directly in the folder; its sub-folders "
                f"hold {sum(below.values())} ({said_subfolders(below)}), not read: move them "
                f"into one folder, give a sub-folder as data.path, or list every run in a "
                f"{MANIFEST} (its file column a path such as {next(iter(below))}/<run>.csv)",
                file=path)
        raise ContractError(f"manifest not found (a dataset folder needs {MANIFEST})"
                            + _other_files(path.parent), file=path)
    text = _text(path, "," if delimiter == AUTO else delimiter, own(path, encoding))
    header = text.splitlines()[0] if text.strip() else ""
    try:
        raw = pd.read_csv(io.StringIO(text), sep=_manifest_delimiter(header, delimiter, path,
                                                                      optional),
                          dtype=str, keep_default_na=False)
    except pd.errors.EmptyDataError:
        raise ContractError("manifest is empty", file=path) from None
    except pd.errors.ParserError as exc:
        raise ContractError(f"manifest is not valid CSV ({_first_line(exc)})", file=path) from None
    raw.columns = [c.strip() for c in raw.columns]
    for column in MANIFEST_REQUIRED:
        if column not in raw.columns and column not in optional:
            hint = (" (or data.test_fraction=F: every campaign train, the last F held out)"
                    if column == "split" else "")
            raise ContractError(f"required manifest column missing{hint}", file=path,
                                column=column)
    raw = raw.fillna("").apply(lambda s: s.str.strip())
    # rows of empty cells under the table (Excel's `;;;`, rows touched below it): left out as
    # a campaign file's are, said; one among the campaigns is still refused at its row
    filled = np.flatnonzero((raw != "").any(axis=1).to_numpy())
    end = int(filled[-1]) + 1 if filled.size else 0
    if end < len(raw):
        rows = f"row {end + 1}" if end + 1 == len(raw) else f"rows {end + 1}-{len(raw)}"
        logger.warning(f"{path}: data {rows} of empty cells under its campaigns (a "
                       "spreadsheet's empty rows): left out")
        raw = raw.iloc[:end]
    if raw.empty:
        raise ContractError("manifest lists no campaign", file=path)
    return raw


def _manifest_delimiter(header: str, delimiter: str, path: Path, optional: tuple = ()) -> str:
    """``data.delimiter``, or ``,`` (the contract's own format) when the manifest's header
    only parses with it; a header that only parses with another separator is refused with
    the setting that reads it (instead of a misleading "column 'campaign' missing"), and one
    that lacks a required column is split by the separator naming the most of them, so that
    the message names the column it lacks (a lab's manifest without ``split``)."""
    def parses(sep):
        return set(MANIFEST_REQUIRED) - set(optional) <= set(fields(header, sep))

    def named(sep):            # how many required columns the header names with it
        return len(set(MANIFEST_REQUIRED) & set(fields(header, sep)))

    if delimiter == AUTO:      # detected: the first separator whose header names the columns,
        # else the one naming the most of them, so that the one missing is named
        seps = (",", *_OTHER_DELIMITERS)
        return next((sep for sep in seps if parses(sep)), max(seps, key=named))
    for sep in dict.fromkeys((delimiter, ",")):
        if parses(sep):
            return sep
    given = max(dict.fromkeys((delimiter, ",")), key=named)
    other = max(_OTHER_DELIMITERS, key=named)
    if parses(other) or named(other) > named(given):
        raise ContractError(f"{MANIFEST} looks {other!r}-separated: set data.delimiter={other!r}",
                            file=path)
    return given


def _text(path: Path, delimiter: str, encoding: str) -> str:
    """The whole (small) file as text; bytes ``data.encoding`` does not read are refused where
    they are."""
    data = path.read_bytes()
    check_text(data, encoding, path)
    try:
        return data.decode(text_codec(encoding))
    except UnicodeDecodeError:
        raise undecodable(path, delimiter, encoding=encoding) from None


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
        elif Path(fname).suffix.lower() not in RECORD_SUFFIXES:
            problem = "file", (f"campaign file {fname!r} is not "
                               f"{', '.join(RECORD_SUFFIXES[:-1])} nor {RECORD_SUFFIXES[-1]}")
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


def _check_error_files(raw: pd.DataFrame, path: Path, root: Path) -> None:
    """The ``error_file`` column (a run's other logger's file, pair70), where there is one: each
    name a file of the folder, neither a campaign's file nor another run's error file."""
    if ERROR_FILE not in raw.columns:
        return
    listed = {(root / str(f)).resolve(): row for row, f in enumerate(raw["file"], 1)}
    seen: dict[Path, int] = {}
    for row, name in enumerate(raw[ERROR_FILE], 1):
        name = "" if pd.isna(name) else str(name).strip()
        if not name:
            continue           # (a run of one file, or its pair found by name)
        where = (root / name).resolve()
        problem = _error_file_problem(name, root, listed.get(where), seen.get(where))
        if problem:
            raise ContractError(problem, file=path, column=ERROR_FILE, row=row)
        seen[where] = row


def _error_file_problem(name: str, root: Path, campaign_row: int | None,
                        earlier_row: int | None) -> str | None:
    if os.path.isabs(name) or os.path.normpath(name).split(os.sep)[0] == "..":
        return (f"error file {name!r} lies outside the dataset folder: files are paths relative "
                "to it, without '..'")
    if not (root / name).is_file():
        return f"error file {name!r} not found in {root}"
    if campaign_row is not None:
        return (f"error file {name!r} is the campaign file of row {campaign_row}: the "
                f"{ERROR_FILE} column names the run's other logger's file")
    if earlier_row is not None:
        return f"error file {name!r} is already listed at row {earlier_row}: one run per file"
    return None


def _check_continues(raw: pd.DataFrame, path: Path) -> None:
    """The optional ``continues`` column names, per row, the campaign the row's record continues
    (empty: none): another campaign of the manifest, and no chain of them back to itself (an
    unknown id or a cycle was ignored, or carried state round the cycle)."""
    if "continues" not in raw.columns:
        return
    rows = {cid: row for row, cid in enumerate(raw["campaign"], 1)}
    links = {cid: prev for cid, prev in zip(raw["campaign"], raw["continues"]) if prev}
    for cid, prev in links.items():
        why = ("names itself" if prev == cid else
               f"names campaign {prev!r}, which the manifest does not list" if prev not in rows else None)
        if why is None:
            seen, at = [cid], prev
            while at in links and at not in seen:
                seen.append(at)
                at = links[at]
            if at == cid:
                why = f"closes a cycle: {' -> '.join([*seen, cid])}"
        if why:
            raise ContractError(f"'continues' {why}: a record continues an earlier, other one",
                                file=path, column="continues", row=rows[cid])


def apply_split_overrides(manifest: pd.DataFrame, overrides: dict, path: Path,
                          listed_by: str = "the manifest does not list") -> None:
    """Set ``data.split_overrides`` (``{campaign: split}``) in ``manifest``, in place; a
    campaign it does not list is refused naming ``path`` (a manifest, a long file's runs) and
    the campaigns there are (``listed_by`` says what lists them)."""
    unknown = [cid for cid in overrides if cid not in manifest.index]
    if unknown:
        known = ", ".join(map(str, manifest.index[:8])) + (" ..." if len(manifest) > 8 else "")
        raise ContractError(f"data.split_overrides names campaign {unknown[0]!r}, which "
                            f"{listed_by} (campaigns: {known})", file=path, column="campaign")
    for cid, split in overrides.items():
        manifest.loc[cid, "split"] = split


def _metadata_column(values: pd.Series, path: Path, column: str, decimal: str = ".",
                     zone: str | None = None) -> pd.Series:
    if column == "start":
        return _parse_start(values, path, zone)
    if column == "notes":
        return values
    if column == AMBIENT_C:      # a campaign's ambient (°C): a number or empty, never text
        cells = values.astype(str).str.strip()
        if decimal != ".":       # the files' decimal mark (data.decimal) holds here too;
            # detected (auto): a comma inside one cell can only be a decimal comma
            cells = cells.str.replace("," if decimal == AUTO else decimal, ".", regex=False)
        numbers = pd.to_numeric(cells.replace("", np.nan), errors="coerce").astype(float)
        for row, (value, number) in enumerate(zip(values, numbers), 1):
            if str(value).strip() and not np.isfinite(number):
                raise ContractError(f"ambient_c {value!r} is not a temperature in °C (a number, "
                                    "or empty where unknown)", file=path, column=column, row=row)
        return numbers
    present = values[values != ""]
    numbers = pd.to_numeric(present, errors="coerce")
    if len(present) and numbers.notna().all():
        return pd.to_numeric(values.replace("", np.nan))
    return values


def _parse_start(values: pd.Series, path: Path, zone: str | None = None) -> pd.Series:
    """The ``start`` column as written (one offset, or none), else as instants in UTC (several
    offsets, or a start with one and one without: :func:`.instants.start_instants`); with
    ``zone`` (``data.timezone``) a start without an offset is on its clock."""
    instants = start_instants(values, path, zone)     # refuses a cell that is no ISO 8601 time
    stamps = pd.Series([start_stamp(v) if zone is None else on_clock(start_stamp(v), zone)
                        for v in values], index=values.index, dtype=object)
    if len({str(s.tzinfo) for s in stamps if pd.notna(s)}) > 1:
        return instants
    return pd.to_datetime(stamps)
