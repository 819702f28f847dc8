"""A dataset's campaigns as the rows the exported ``stream.c`` and a served block read
(``thermocomp rows``, extension lab78; pure core).

The conformance pack (:mod:`.pack`) writes a test campaign's rows as the code takes them; this
writes any campaign of any file the reader takes (a TwinCAT Scope export, a TOA5 table, a TDMS
log, a workbook, ...) the same way: ``time`` (s) then the columns under their contract names
(``T_``, ``S_``; ``E_`` on request: reference measurements an adaptive model learns from), in
the pack's CSV (:func:`.pack.csv_text`).  A campaign that continues others (``reference``
``none``: the model carries its state over) is written after them as the pack feeds it
(:func:`.pack.fed`), one block; blocks are parted by a blank line, where ``stream.c`` starts a
campaign.  A manifest's ``ambient_c`` is an ``ambient_c`` column on each row of its campaign.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ....core.continuation import chain, lead_in, predecessors
from ....core.io.contract import AMBIENT_C, TIME, manifest_ambient, role
from .pack import csv_text, fed


def blocks(ds, ids: list[str], reference: str) -> list[tuple[list[str], pd.DataFrame]]:
    """``[(chain, rows)]``: each campaign of ``ids`` with the campaigns it continues before it
    (``reference`` ``none``), a campaign another of ``ids`` continues left to that one's block."""
    links = predecessors(ds) if reference == "none" else {}
    chains = {c: chain(ds, c, links) for c in ids}
    inside = {p for c in ids for p in chains[c][:-1]}
    out = []
    for cid in ids:
        if cid in inside:
            continue
        ids_ = chains[cid]
        lead = lead_in(ds, ids_) if len(ids_) > 1 else None
        frame = fed(ds.campaigns[cid], lead)
        frame.attrs = dict(ds.campaigns[ids_[0]].attrs)    # (the chain's first's ambient)
        out.append((ids_, frame))
    return out


def rows_text(ds, ids: list[str], reference: str, errors: bool = False
              ) -> tuple[str, list[dict]]:
    """``(CSV text, [{campaigns, rows}, ...])`` of :func:`blocks`: one header (``time``, the
    ``T_``/``S_`` columns (and ``E_`` with ``errors``) in first-seen order, ``ambient_c`` where
    a campaign has the manifest's), a block's rows under it, a blank line between blocks; a
    column a campaign lacks is empty there (``stream.c`` names it where it needs it)."""
    kinds = ("T", "S", "E") if errors else ("T", "S")
    parts = blocks(ds, ids, reference)
    columns = list(dict.fromkeys(c for _, f in parts for c in f.columns if role(c) in kinds))
    ambient = [manifest_ambient(f) for _, f in parts]
    given = any(np.isfinite(a) for a in ambient)
    header = [*([TIME] if any(TIME in f.columns for _, f in parts) else []), *columns,
              *[AMBIENT_C] * given]
    texts, listed = [], []
    for (ids_, frame), a0 in zip(parts, ambient):
        frame = frame.reindex(columns=[c for c in header if c != AMBIENT_C])
        if TIME in frame.columns:
            frame[TIME] = from_zero(frame[TIME])
        if given:
            frame[AMBIENT_C] = a0
        text = csv_text(frame)
        texts.append(text if not texts else text.split("\n", 1)[1])
        listed.append({"campaigns": ids_, "rows": len(frame)})
    return "\n".join(texts), listed


def from_zero(time: pd.Series) -> pd.Series:
    """(dep107b) A block's time from its first (s): each block then starts at a time not after the
    last of the one before, the boundary every reader of the rows (``stream.c``, a stream on
    stdin) tells from a logger's stray blank line within a run, its time going on (read as
    nothing, as ``run`` and ``replay`` read it).  A file's runs under one clock (a run column's)
    went on across the blank line, one period on: no time told it from a stray one."""
    seconds = pd.to_numeric(time, errors="coerce")
    first = seconds[np.isfinite(seconds)]
    return seconds - first.iloc[0] if len(first) else seconds
