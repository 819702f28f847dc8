"""The dataset contract of ``shared/spec/DATA_FORMAT.md`` as Python objects.

A :class:`Dataset` is a manifest (one row per campaign) plus one DataFrame per
campaign.  Every campaign frame has a float ``time`` column (seconds since the
campaign start) followed by ``T_``/``E_``/``S_`` columns, all float64.

This module owns the vocabulary (prefixes, roles, the error type) and the
writer; :mod:`thermocomp.core.io.read` owns parsing and validation.
"""

from __future__ import annotations

import fnmatch
import functools
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from ...base.errors import ContractError  # noqa: F401  (re-exported: the contract's error type)
from ...base.files import atomic_dir

TIME = "time"
PREFIXES = ("T_", "E_", "S_")
SPLITS = ("train", "val", "test")
MANIFEST = "campaigns.csv"
MANIFEST_REQUIRED = ("campaign", "file", "split")
# Manifest extension: a campaign's ambient (°C) where no ambient sensor (T_amb*) was recorded;
# ``read_dataset`` hands it on as the campaign frame's ``attrs[AMBIENT_C]``
AMBIENT_C = "ambient_c"


def is_ambient(column: str) -> bool:
    """``T_amb`` or ``T_amb_<name>`` (DATA_FORMAT.md)."""
    return column == "T_amb" or column.startswith("T_amb_")


def manifest_ambient(df: pd.DataFrame) -> float:
    """The manifest's ``ambient_c`` of a campaign without an ambient sensor (NaN: none)."""
    return float(df.attrs.get(AMBIENT_C, float("nan")))


def ambient_source(df: pd.DataFrame) -> str | None:
    """Where :func:`thermocomp.core.frame.initial_ambient` takes a campaign's ambient from: ``T_amb``
    (its sensors), ``ambient_c`` (the manifest) or None."""
    if any(is_ambient(c) for c in df.columns):
        return "T_amb"
    return AMBIENT_C if np.isfinite(manifest_ambient(df)) else None


@functools.lru_cache(maxsize=4096)    # asked ~20 times per column read: 1430 distances a file
def role(column: str) -> str | None:
    """``'time'``, ``'T'``, ``'E'``, ``'S'`` or ``None`` for a column name."""
    if column == TIME:
        return "time"
    for p in PREFIXES:
        if column.startswith(p) and len(column) > len(p):
            return p[0]
    return None


def match_columns(columns, patterns) -> list[str]:
    """Columns matching any glob pattern, in the order of ``columns``."""
    if isinstance(patterns, str):
        patterns = [patterns]
    return [c for c in columns if any(fnmatch.fnmatchcase(c, p) for p in patterns)]


@dataclass
class Dataset:
    """A set of campaigns in the contract's frame.

    Parameters
    ----------
    manifest : DataFrame
        Indexed by campaign id; columns ``file``, ``split`` and any metadata
        (``start``, ``notes``, ``ambient_c`` ...).
    campaigns : dict of DataFrame
        Campaign id -> samples (``time`` in s, then ``T_``/``E_``/``S_`` columns).
    name : str
        Short name (the dataset folder's name).
    """

    manifest: pd.DataFrame
    campaigns: dict[str, pd.DataFrame]
    name: str = ""
    meta: dict = field(default_factory=dict)

    def file_path(self, cid: str) -> Path:
        """The file campaign ``cid`` was read from (what an error names); its id for a dataset
        made in memory."""
        if "file" not in self.manifest.columns:
            return Path(cid)
        path = Path(self.meta.get("path", ""))
        # a one-file record (its parts or runs): the path is the file ('spindle_test.csv' had been
        # joined to itself, 'spindle_test.csv/spindle_test.csv', in every refusal naming it)
        return path if path.is_file() else path / self.manifest.loc[cid, "file"]

    def rows_named(self, cid: str) -> str:
        """What a refusal of campaign ``cid``'s row N names: its file, and (faults71) for a run
        of two loggers whose rows the second's are (:mod:`.joined`), that file: the plain
        stream's refusal named the temperature file's 'data row 145' of its line 722."""
        paired = (self.meta.get("read_report") or {}).get("campaigns", {}).get(cid, {}).get("paired")
        where = str(self.file_path(cid))
        return where if not paired else (f"{where} (its rows: {paired['errors']}'s samples, the "
                                         "temperatures' last sample at or before each)")

    def ids(self, split: str | None = None) -> list[str]:
        if split is None:
            return list(self.manifest.index)
        return list(self.manifest.index[self.manifest["split"] == split])

    @property
    def columns(self) -> list[str]:
        """Union of the campaign columns (without ``time``), first-seen order."""
        seen: dict[str, None] = {}
        for df in self.campaigns.values():
            for c in df.columns:
                if c != TIME:
                    seen.setdefault(c, None)
        return list(seen)

    def columns_of(self, prefix: str) -> list[str]:
        return [c for c in self.columns if c.startswith(prefix)]

    def subset(self, ids) -> "Dataset":
        ids = list(ids)
        return Dataset(self.manifest.loc[ids], {i: self.campaigns[i] for i in ids},
                       self.name, dict(self.meta))


def exact_time(frame: pd.DataFrame) -> pd.DataFrame:
    """``frame`` with its ``time`` column written in full by ``to_csv(float_format=...)``.

    Six significant digits suit the measured values, not the clock: a record's time passes
    1e7 s after 116 days, where ``%.6g`` writes 60 s steps as 100 s ones (two rows at one
    time).  Whole seconds become integers, other times keep every digit (``repr``).
    """
    if "time" not in frame.columns or not pd.api.types.is_float_dtype(frame["time"]):
        return frame
    time_s = frame["time"].to_numpy()
    finite = np.isfinite(time_s)
    exact = frame.copy()
    if finite.all() and np.array_equal(time_s, np.round(time_s)):
        exact["time"] = time_s.astype(np.int64)
    else:
        exact["time"] = frame["time"].astype(object)   # str(float): the shortest exact text
    return exact


def write_dataset(ds: Dataset, path: str | os.PathLike, fmt: str = "csv",
                  files: dict[str, str] | None = None) -> Path:
    """Write ``ds`` as a dataset folder in the contract (atomically).

    ``fmt`` is ``'csv'`` or ``'parquet'`` for the campaign files; the manifest
    is always ``campaigns.csv``.  ``files``: more files of the folder, name -> text
    (a volumetric dataset's ``volumetric.json``).
    """
    if fmt not in ("csv", "parquet"):
        raise ValueError(f"unknown campaign file format {fmt!r}")
    path = Path(path)
    manifest = ds.manifest.copy()
    manifest.index.name = "campaign"
    manifest["file"] = [f"{cid}.{fmt}" for cid in manifest.index]
    # (a run of two loggers is written joined: its error file (pair70) no longer beside it)
    manifest = manifest.drop(columns="error_file", errors="ignore")
    with atomic_dir(path) as tmp:
        for cid in manifest.index:
            df = ds.campaigns[cid]
            if fmt == "csv":
                exact_time(df).to_csv(tmp / f"{cid}.csv", index=False, float_format="%.6g")
            else:
                df.to_parquet(tmp / f"{cid}.parquet", index=False)
        cols = ["file", "split"] + [c for c in manifest.columns if c not in ("file", "split")]
        manifest[cols].reset_index().to_csv(tmp / MANIFEST, index=False)
        for name, text in (files or {}).items():
            (tmp / name).write_text(text)
    return path
