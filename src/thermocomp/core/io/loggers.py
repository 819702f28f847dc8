"""A folder whose files split one record's columns between loggers (temperatures from one,
displacements from another): each file of a folder is a campaign, never columns of another
file's samples, so the file without an error is refused saying so and naming the file that
holds the errors (not asking for an error column the file cannot have)."""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from ...base.errors import listed
from .contract import MANIFEST, ContractError, role
from .options import ReadOptions
from .plain import as_read, is_converted
from .starts import named_head
from .workbook import HEAD_ROWS

NO_ERROR = "no E_ column"     # the refusal of a campaign file without a measured error


def errors_elsewhere(exc: ContractError, root: Path, manifest: pd.DataFrame, cid: str,
                     opts: ReadOptions) -> ContractError:
    """``exc`` (campaign ``cid`` of the folder ``root`` refused) as it is, or, where it has no
    error column and another file of ``manifest`` holds errors but no temperature, a refusal
    naming that file and saying that files are not joined; a file without data rows, said
    to be left out (:func:`unrecorded`)."""
    if exc.reason.endswith("no data rows") and exc.row is None:
        return unrecorded(exc, root)
    if not exc.reason.startswith(NO_ERROR):
        return exc
    for other, file in manifest["file"].items():
        errors = [] if other == cid else _errors_only(root / file, opts)
        if errors:
            return ContractError(
                f"{NO_ERROR}, and {file} beside it holds errors ({listed(errors)}) without a "
                "temperature: the errors and the temperatures of one run in two files (two "
                "loggers)? Each file of a folder is a campaign of its own; files are not joined "
                "by time: join them into one file first, one row per time (pandas.merge_asof), "
                "and give data.path that file", file=exc.file)
    return exc


def unrecorded(exc: ContractError, root: Path) -> ContractError:
    """``exc``, the refusal of a file of the folder ``root`` without data rows, saying to leave
    it out: a run not recorded (its logger's header alone) among a lab's runs (messy58)."""
    where = (f"its row out of {MANIFEST}" if (root / MANIFEST).is_file() else
             "the file out of the folder")
    return ContractError(f"{exc.reason}: a run not recorded? a campaign needs samples; leave "
                         f"{where}", file=exc.file, column=exc.column, sheet=exc.sheet)


def _errors_only(path: Path, opts: ReadOptions) -> list[str]:
    """The ``E_`` columns of the file ``path`` as its header is named, where it has no ``T_``
    column; [] otherwise, or where its header does not read (its own read says why)."""
    try:
        if is_converted(path, opts):      # a workbook's sheet, a UTF-16 text: its head as read
            with as_read(path, opts, rows=HEAD_ROWS) as (source, source_opts):
                return _errors_only(source, source_opts)
        names = [n for n in named_head(path, opts)[2] if n]
    except (ContractError, OSError):
        return []
    kinds = {role(n) for n in names}
    return [n for n in names if role(n) == "E"] if "T" not in kinds else []
