"""A dataset without a test split: ``data.test_fraction`` and ``data.val_fraction``.

One record (``data.path`` a CSV or Parquet file or an Excel workbook, no manifest) is cut
chronologically into parts, each a campaign that ``continues`` the one before
(:mod:`thermocomp.core.continuation`), in the order ``data.split_order`` (default train, val,
test).  In a folder of campaigns without a test (or val) split, the chronologically last
campaigns (by ``start``, else manifest order) are held out.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa

from ...base.log import logger
from .contract import MANIFEST, ContractError
from .manifest import BINARY_KINDS, RECORD_SUFFIXES
from .sinumerik import not_a_trace
from .sparse import probe_cycle
from .timestamps import ELAPSED, OF_DAY, PAUSE_PERIODS, pauses
from .workbook import not_read

SAID_AS_READ = (ELAPSED, OF_DAY)    # a time whose pauses the reading of it says
MIN_PART_ROWS = 2          # as a campaign: a reference sample and one to score
_UNSAFE_ID = re.compile(r"[^\w.\-]+")


def shares(opts) -> dict[str, float]:
    """``{split: share}`` of the splits a fraction asks for, ``train`` the rest."""
    out = {"test": opts.test_fraction, "val": opts.val_fraction}
    out = {k: v for k, v in out.items() if v is not None}
    return {"train": 1.0 - sum(out.values()), **out} if out else {}


def _counts(n: int, opts) -> dict[str, int]:
    """Whole samples (campaigns) per split: val and test rounded half up (at least one), train
    the rest."""
    wanted = shares(opts)
    counts = {k: max(1, math.floor(n * v + 0.5)) for k, v in wanted.items() if k != "train"}
    counts["train"] = n - sum(counts.values())
    return {k: counts[k] for k in opts.split_order if k in counts}


def check_record_file(path: Path) -> None:
    """A one-file record is delimited text, Parquet or an Excel workbook, told by its suffix
    (an Excel workbook was read as Parquet and crashed in the reader)."""
    if path.suffix.lower() == ".tdx":       # (stranger78: the pair's values, given for the pair)
        raise ContractError(f"a DIAdem TDX file holds the values its TDM header describes: give "
                            f"the header, {path.with_suffix('.tdm').name} (beside it)", file=path)
    if (why := not_a_trace(path)) is not None:    # (stranger81: a traceback of pyarrow's)
        raise ContractError(why, file=path)
    if path.suffix.lower() not in RECORD_SUFFIXES:
        kind = not_read(path)
        known = BINARY_KINDS.get(path.suffix.lower())
        raise ContractError(kind or f"a record's file is {', '.join(RECORD_SUFFIXES)}, not "
                            f"{path.suffix or 'a file without a suffix'}"
                            + (f"; {path.suffix}: {known}" if known else ""), file=path)


def record_id(path: Path) -> str:
    """The campaign id of a one-file record: its stem, in characters an id may hold."""
    return safe_id(path.stem)


def safe_id(text: str) -> str:
    """``text`` in characters an id (a campaign's, a config's name) may hold."""
    return _UNSAFE_ID.sub("_", text).strip("._") or "record"


def cut(path: Path, table: pa.Table, report: dict, opts, stem: str | None = None
        ) -> tuple[pd.DataFrame, dict]:
    """The one-file record ``path`` (read as ``table``) as campaigns, their ids ``stem`` (the
    file's, :func:`record_id`) and the part's split (data88b: a run of two loggers' files,
    ``path`` its temperature file, ``stem`` the run's).

    Returns
    -------
    manifest : DataFrame
        Indexed by campaign id: ``file`` (the record's name), ``split``, ``continues``.
    parts : dict
        Campaign id -> (table, report entry with the record's ``rows`` ``[from, to)``).
    """
    stem = stem or record_id(path)
    _warn_pauses(path, table, report.get("time"))
    lead, trail = _batch_edges(table, report, opts)
    counts = _counts(table.num_rows - lead - trail, opts) or {"train": table.num_rows - lead - trail}
    short = {k: v for k, v in counts.items() if v < MIN_PART_ROWS}
    if short:
        split, rows = next(iter(short.items()))
        n = table.num_rows - lead - trail
        if n < MIN_PART_ROWS * len(counts):      # no fraction gives every part enough
            raise ContractError(f"the record's {n} samples are too few for {len(counts)} parts "
                                f"of at least {MIN_PART_ROWS} ({', '.join(counts)}): a longer "
                                "record", file=path)
        # (audit86: a short train part was told to raise data.test_fraction, shortening it)
        fix = (" and ".join(f"data.{k}_fraction" for k in counts if k != "train")
               if split == "train" else f"data.{split}_fraction")
        raise ContractError(f"the {split} part would have {rows} sample(s) of the record's "
                            f"{table.num_rows}: at least {MIN_PART_ROWS} ("
                            f"{'lower' if split == 'train' else 'raise'} {fix})", file=path)
    if len(counts) > 1:
        logger.info(f"{path.name}: cut chronologically into "
                    + ", ".join(f"{s} {c} rows" for s, c in counts.items()))
    # a stream keeps the incomplete edge rows a batch trims: in the first and last parts, so
    # that every part starts where the batch's does (what is streamed is what `run` scored)
    counts = dict(counts)
    first, last = next(iter(counts)), list(counts)[-1]
    counts[first] += lead
    counts[last] += trail
    rows, parts, previous, start = [], {}, "", 0
    for split, count in counts.items():
        cid = stem if len(counts) == 1 else f"{stem}_{split}"
        entry = {**report, "file": path.name, "split": split, "rows": count, "source_rows": count,
                 "record_rows": [start, start + count]}
        if start:             # the record's repairs and trimmed start are counted once, first
            entry.update(repairs={}, trimmed={"start": 0, "end": report["trimmed"]["end"]})
        if start + count < table.num_rows:
            entry["trimmed"] = {**entry["trimmed"], "end": 0}
        part = table.slice(start, count)
        if "missing" in report:   # kept missing cells are each part's own, not the record's
            entry["missing"] = _missing_cells(part, report["missing"])
        parts[cid] = (part, entry)
        rows.append({"campaign": cid, "file": path.name, "split": split, "continues": previous})
        previous, start = cid, start + count
    return pd.DataFrame(rows).set_index("campaign"), parts


def _warn_pauses(path: Path, table: pa.Table, kind: str | None = None) -> None:
    """Say where one record stops for hours between samples a minute apart: a lab's runs
    exported into one file read as one campaign (absolute, every run continuing the last, one
    ambient level for ATI) where a folder of one file per run reads each as a campaign.
    (data89b) Not of a time ``kind`` whose pauses were said as it was read, once each, with
    what works for it (:func:`.timestamps.elapsed_seconds`, :func:`.timestamps.past_midnight`):
    ``h:mm:ss`` (``elapsed``, which ``data.runs_at_pauses`` cannot split) or seconds of the day
    past midnight (a pause there may as well be a day longer)."""
    if "time" not in table.column_names or table.num_rows < 3 or kind in SAID_AS_READ:
        return
    time = table.column("time").to_numpy(zero_copy_only=False).astype(float)
    steps, found = np.diff(time), pauses(time)
    if len(found):
        k = int(found[np.argmax(steps[found])])
        logger.warning(f"{path.name}: one record, yet it pauses {len(found)} "
                       f"time(s) for more than {PAUSE_PERIODS} sample periods (the longest "
                       f"{steps[k] / 3600:.3g} h, after data row {k + 1}): runs joined in one "
                       "file? One file per run in a folder, a column numbering the runs "
                       "(data.roles.campaign=<header>), or data.runs_at_pauses=true (each stretch "
                       "between the pauses a run) reads each as a campaign (referenced to its "
                       "first sample, the last runs held out by data.test_fraction)")


def _batch_edges(table: pa.Table, report: dict, opts) -> tuple[int, int]:
    """Incomplete rows a batch read trims at the record's start and end (within
    ``max_edge_samples``), in a record read as kept (``missing="keep"``); (0, 0) otherwise."""
    if opts.missing != "keep" or not report.get("missing"):
        return 0, 0
    incomplete = np.zeros(table.num_rows, dtype=bool)
    for c in report["missing"]:
        empty = np.isnan(table.column(c).to_numpy(zero_copy_only=False))
        # a probe cycle's empty rows are no edge: the batch keeps them too (the rule: .sparse)
        if not probe_cycle(c, np.flatnonzero(empty), table.num_rows, opts.sparse_targets):
            incomplete |= empty
    if incomplete.all():
        return 0, 0
    lead, trail = int(np.argmin(incomplete)), int(np.argmin(incomplete[::-1]))
    edge = opts.max_edge_samples
    return (lead if lead <= edge else 0), (trail if trail <= edge else 0)


def _missing_cells(part: pa.Table, columns) -> dict[str, int]:
    """``{column: missing cells}`` of ``part`` among ``columns``, those with at least one."""
    counts = {c: int(np.isnan(part.column(c).to_numpy(zero_copy_only=False)).sum()) for c in columns}
    return {c: n for c, n in counts.items() if n}


def _too_few(manifest: pd.DataFrame, pool: pd.Index, counts: dict[str, int], root: Path) -> str:
    """The refusal of :func:`hold_out` where the train campaigns ``pool`` are fewer than the
    splits of ``counts`` (train and those held out, a whole campaign each): what to give
    instead; the file of a manifest's one campaign, cut in time as one record's is."""
    said = (f"{len(pool)} train campaign(s) are too few to hold out whole campaigns for "
            f"{', '.join(s for s in counts if s != 'train')} and keep one for train, whatever "
            "data.test_fraction / data.val_fraction")
    only = root / str(manifest.loc[pool[0], "file"]) if len(manifest) == 1 else None
    if only is not None and (root / MANIFEST).is_file() and only.is_file():
        return (f"{said}: give the campaign's file, data.path={only} (one record: its last share "
                "is held out, continuing the rest)")
    return f"{said}: a folder of more campaigns, or their split set in {MANIFEST}"


def hold_out(manifest: pd.DataFrame, opts, root: Path, starts: pd.Series | None = None,
             listed: str = "in the order listed") -> pd.DataFrame:
    """``manifest`` with the chronologically last train campaigns made test (and val) as the
    fractions ask, by ``starts`` (:func:`.starts.campaign_starts`) where every train campaign
    has one, else in manifest order (``listed`` says which order that is, in the log line);
    refused where the manifest has that split already."""
    wanted = shares(opts)
    if not wanted:
        return manifest
    for split in ("test", "val"):
        if split in wanted and (manifest["split"] == split).any():
            # (iso67: a split given by data.split_overrides, in a folder without campaigns.csv:
            # the refusal named that file, which is not there, and its split column)
            given = [str(c) for c, s in (opts.split_overrides or {}).items()
                     if str(s) == split and c in manifest.index]
            if given:
                raise ContractError(
                    f"data.{split}_fraction is set and data.split_overrides makes "
                    f"{', '.join(given[:5])} {split} already: drop one of them (data.{split}"
                    f"_fraction=null keeps the overrides' {split} campaigns)", file=root)
            raise ContractError(f"data.{split}_fraction is set but the manifest has {split} "
                                "campaigns already: drop one of them", file=root / MANIFEST,
                                column="split")
    pool = manifest.index[manifest["split"] == "train"]
    order = f"{listed} (no start time for each)"
    if starts is not None and starts[pool].notna().all():
        pool, order = starts[pool].sort_values(kind="stable").index, "by start time"
    counts = _counts(len(pool), opts)
    if len(pool) < len(counts):
        # (audit99) no fraction helps: each held-out split takes one whole campaign at least,
        # where "lower data.test_fraction" was said of a manifest's one campaign (a simulated
        # one-record machine's folder), which any fraction leaves with no train campaign
        raise ContractError(_too_few(manifest, pool, counts, root), file=root / MANIFEST)
    if min(counts.values()) < 1:
        raise ContractError(f"{len(pool)} train campaign(s) cannot be split "
                            + ", ".join(f"{s} {c}" for s, c in counts.items())
                            + ": lower data.test_fraction / data.val_fraction", file=root / MANIFEST)
    out, at = manifest.copy(), 0
    for split, count in counts.items():
        out.loc[pool[at:at + count], "split"] = split
        at += count
    logger.info(f"held out {order}: " + ", ".join(
        f"{s} {list(pool[sum(list(counts.values())[:i]):][:c])}" for i, (s, c) in
        enumerate(counts.items()) if s != "train"))
    return out
