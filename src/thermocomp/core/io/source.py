"""A dataset opened for a batch or a stream, with its digest: the one door data come in by.

``open_dataset(root, options)`` reads a folder as a batch sees it (every gap repaired within
``data.max_gap_samples``/``max_edge_samples``, else refused); ``stream=True`` as a deployed
compensator sees it: test (and val) campaigns as recorded (a dropout streams as NaN), train
campaigns repaired or refused, since models and the sensor monitor are fitted on complete
records.  ``meta["digest"]`` is :func:`~thermocomp.base.files.folder_digest` of ``root`` (the
``dataset_hash`` a run is tagged with, the digest ``load_interim`` records of ``data.interim``),
``meta["read_report"]`` the reader's report and, for a stream, ``meta["missing"]`` the cells
kept missing per test campaign.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

from ...base.files import folder_digest
from .contract import ContractError, Dataset
from .loggers import named_error_file
from .options import ReadOptions
from .own_headers import with_own_header
from .read import read_campaign, read_dataset, repaired_part
from .roles import former_said


def open_dataset(root: str | Path, options: Mapping | None = None, *, stream: bool = False,
                 campaigns: Sequence[str] | None = None, digest: str | None = None,
                 needs_errors: bool = True) -> Dataset:
    """The dataset in ``root`` read with the ``data`` options, for a batch or a ``stream``;
    ``campaigns``: only those (a fleet's group), ``digest``: ``root``'s, when known (a fleet
    reads its folder a group at a time, digested once); ``needs_errors``: False, a file
    without an error column read too (:func:`.read.read_dataset`)."""
    root = Path(root)
    ds, report = read_dataset(root, options, missing="keep" if stream else "repair",
                              campaigns=campaigns, needs_errors=needs_errors)
    if stream:
        _repair_train(ds, report, options)
        ds.meta["missing"] = {c: report["campaigns"][c]["missing"] for c in ds.ids("test")
                              if report["campaigns"][c].get("missing")}
    ds.meta.update(digest=digest or folder_digest(root), read_report=report)
    return ds


def _repair_train(ds: Dataset, report: dict, options: Mapping | None) -> None:
    """The train campaigns of a stream read as a batch reads them where they lack a value or
    look like kelvin (what ``missing="keep"`` lets through); of a one-file record, its train
    part as a batch cuts the record (there is no file of the part alone)."""
    hot = ReadOptions.from_cfg(options).kelvin_threshold_c
    for cid in ds.ids("train"):
        df = ds.campaigns[cid]
        faulty = any(df[c].max() > hot for c in df.columns if c.startswith("T_"))
        entry = report["campaigns"][cid]
        if entry.get("missing") or faulty:
            try:
                if "record_rows" in entry:    # a part of one record: that part repaired
                    # (the record is the file: ds.file_path joined its name to itself,
                    # 'messung.csv/messung.csv', in a lab's refusal)
                    table = repaired_part(df, Path(ds.meta["path"]), options,
                                          entry["record_rows"][0])
                else:
                    errors = named_error_file(Path(ds.meta["path"]), ds.manifest, cid)
                    table, _ = read_campaign(ds.file_path(cid), options, one_run=True,
                                             errors=errors)
            except ContractError as exc:
                # the lab's own header of the column, as a batch's refusal names it
                exc = with_own_header(exc, ds.meta.get("column_map", {}))
                raise ContractError(f"train campaign {cid}: {exc.reason} (models and the sensor "
                                    "monitor are fitted on complete train records)",
                                    file=exc.file, column=exc.column, row=exc.row,
                                    line=exc.line, sheet=exc.sheet) from None
            ds.campaigns[cid] = table.to_pandas(split_blocks=True)


def check_streamed_columns(ds: Dataset, ids, columns, what: str, bits=None) -> None:
    """Every campaign ``ids`` of ``ds`` holds every column ``what`` reads: else a ContractError
    naming the first campaign's file and the columns it lacks (one: as its ``column``; several:
    counted and listed, not joined into one column's name).  ``bits``: the status words the
    model was fitted with (its ``data.bits``, bits85): a lacking bit names the key to give."""
    for cid in ids:
        absent = [c for c in columns if c not in ds.campaigns[cid].columns]
        former = former_said(absent, ds.meta.get("column_map") or {}, ds.file_path(cid))
        if former:       # (data95) a model fitted before the temperature word was left out
            raise ContractError(f"test campaign {cid}, {what}: {former}",
                                file=ds.file_path(cid), column=absent[0])
        hint = _bits_said(absent, bits or {})
        if len(absent) == 1:
            raise ContractError(f"test campaign {cid} lacks a column {what} reads{hint}",
                                file=ds.file_path(cid), column=absent[0])
        if absent:
            raise ContractError(f"test campaign {cid} lacks {len(absent)} columns {what} reads: "
                                f"{', '.join(absent)}{hint}", file=ds.file_path(cid))


def _bits_said(absent: list[str], bits) -> str:
    """Where ``absent`` holds bits of a status word the model declares: the declaration, to
    give as the model's data config gave it (the word, undeclared, is read as one number)."""
    words = {w: named for w, named in bits.items()
             if any(f"S_{n}" in absent for n in named.values())}
    if not words:
        return ""
    key = "; ".join(f"{w}: {{{', '.join(f'{b}: {n}' for b, n in named.items())}}}"
                    for w, named in words.items())
    return (f" (bits of the PLC status word{'s' * (len(words) > 1)} "
            f"{', '.join(map(repr, words))} the model was fitted with: give data.bits={{{key}}})")
