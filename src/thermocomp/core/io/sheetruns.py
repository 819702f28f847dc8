"""A workbook of runs, one sheet each (extension, stranger68): a lab's macro writes a test's runs
into one workbook behind a cover sheet of notes, ``Info``, then ``Run 1`` ... ``Run 8``.

``data.path=<file>.xlsx`` without ``data.sheet`` reads every sheet holding a table of the first
such table's header (:func:`.workbook.run_sheets`) as a campaign, named by its sheet (``Run 1``
is ``Run_1``), each read as that sheet alone would be (its preamble, unit row, summary rows and
every check its own; a message names the workbook, the sheet and its row); the runs are train
campaigns, and ``data.test_fraction`` (``data.val_fraction``) holds the last out, by their first
timestamps (else in the sheets' order), as for a folder of runs or a long file's runs
(:mod:`.runs`).  The sheets left out (a cover, a summary of another header) are said.  Before,
the first sheet alone was read: the cover, refused as holding no error column.
"""

from __future__ import annotations

import re
from dataclasses import replace
from pathlib import Path

import pandas as pd

from ...base.errors import listed
from ...base.log import logger
from .contract import ContractError
from .instants import start_instants
from .manifest import apply_split_overrides
from .record import hold_out
from .workbook import is_workbook, run_sheets

_UNSAFE = re.compile(r"[^\w.-]+")


def campaign_id(title: str) -> str:
    """A sheet's title as a campaign id (``Run 1`` -> ``Run_1``)."""
    return _UNSAFE.sub("_", title).strip("._") or "sheet"


def several_runs(path: Path, opts) -> bool:
    """``path`` is a workbook whose runs are its sheets: no ``data.sheet``, two or more sheets
    of one table's header."""
    return opts.sheet is None and is_workbook(path) and len(run_sheets(path).runs) > 1


def sheet_parts(path: Path, opts, read) -> tuple[pd.DataFrame, dict]:
    """The manifest (``file``, ``split``, ``sheet``) and ``{id: (table, entry)}`` of the workbook
    ``path``'s run sheets, each read by ``read(path, opts)`` (``read_campaign``; the caller
    checks them as a file's runs)."""
    sheets = run_sheets(path)
    ids = {campaign_id(t): t for t in sheets.runs}
    if len(ids) < len(sheets.runs):
        raise ContractError("two sheets give one campaign id ("
                            + listed([repr(t) for t in sheets.runs], most=8)
                            + "): rename one", file=path)
    parts = {}
    for cid, title in ids.items():
        table, report = read(path, replace(opts, sheet=title))
        parts[cid] = table, {"file": path.name, "sheet": title, "split": "train", **report}
    manifest = pd.DataFrame({"file": path.name, "split": "train", "sheet": list(ids.values())},
                            index=pd.Index(list(ids), name="campaign"))
    apply_split_overrides(manifest, opts.split_overrides, path,
                          listed_by="the workbook's run sheets do not hold")
    starts = start_instants(pd.Series({cid: entry.get("time_origin")
                                       for cid, (_, entry) in parts.items()}, dtype=object))
    manifest = hold_out(manifest, opts, path.parent, starts, listed="in the sheets' order")
    left = f"; left out: {listed([repr(t) for t in sheets.other], most=6)}" if sheets.other else ""
    logger.info(f"{path.name}: its {len(ids)} sheets of one table "
                f"({listed([repr(t) for t in sheets.runs], most=4)}) read as campaigns, one run "
                f"a sheet{left}")
    for cid, (_, entry) in parts.items():
        entry["split"] = manifest.at[cid, "split"]
    return manifest, parts
