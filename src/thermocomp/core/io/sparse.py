"""A target measured now and then (``data.sparse_targets``): a probe cycle on a dense log.

A lab logs its temperatures every 10-60 s and measures the error only every N samples (a
touch-probe or laser cycle every 5-30 min, a few times a shift), the cells in between empty.
Such an ``E_`` column is no gap to repair: interpolating it would make the models fit (and be
scored on) a straight line nobody measured.  It is kept as it is, NaN between the
measurements; every model family fits and is scored on the measured rows only, its inputs'
dynamics computed on the dense stream.

``auto`` reads a column so where its measured cells are a minority of the campaign's rows and
no two of them (as a rule) are neighbours: the median spacing between measured rows is
:data:`MIN_SPACING` rows or more.  A dense column with one long gap (a probe that died) has its
measured cells side by side, a median spacing of 1: a gap, repaired or refused as before.

The edges (frames62). The rows before an error's first measurement and after its last are the
campaign's own rows, kept by every read (``run``'s batch, ``replay``, ``monitor``, ``promote``,
``export``'s check pack, the cut of a one-file record), never trimmed as incomplete edges: the
temperatures were measured there, so a stream warms on them (lag filters, delays, states), and
the error, NaN there, is scored on its measured rows only. A deployed compensator starts at the
first sample it is given (the logger's first row, the machine's power-on), not at the first
probe cycle it never sees; a batch that trimmed those rows scored a stream that started later
than the one deployed (probe61's grinder, lagbank E_X: run 0.563 against replay 0.672 um). In
the first-sample frame (``data.reference=first_sample``) the temperatures are referenced at the
campaign's first row, the deployed stream's first sample, and the error at its first
measurement, the only value of it known: the drift before the first probe cycle is not measured
(a record read absolute, ``data.reference=none``, has no such offset). A dense column's missing
cells at an end are incomplete edge rows as before (``data.max_edge_samples``, else refused).
"""

from __future__ import annotations

import numpy as np

MIN_SPACING = 2        # median rows between two measurements: 1 is a dense column
MAX_SHARE = 0.5        # at most this share of the rows measured (auto)


def intermittent(missing: np.ndarray, rows: int, mode: str) -> dict | None:
    """``{"measured": rows measured, "every": median spacing (rows)}`` when the ``E_`` column
    whose empty cells are at the sorted positions ``missing`` is read as measured now and then
    (``mode``: ``data.sparse_targets``), else None (its empty cells are gaps)."""
    if mode == "false" or not missing.size:
        return None
    measured = np.setdiff1d(np.arange(rows), missing, assume_unique=True)
    if measured.size < 2 and mode == "auto":
        return None
    every = _spacing(measured, rows)
    if mode == "auto" and (measured.size > MAX_SHARE * rows or every < MIN_SPACING):
        return None
    return {"measured": int(measured.size), "every": int(round(every))}


def _spacing(measured: np.ndarray, rows: int) -> float:
    """The median number of rows between the measured rows ``measured`` (``rows``, all of them,
    where fewer than two are measured)."""
    return float(np.median(np.diff(measured))) if measured.size > 1 else float(rows)


def probe_cycle(name: str, missing: np.ndarray, rows: int, mode: str) -> dict | None:
    """:func:`intermittent` of an ``E_`` column ``name`` (its empty cells at ``missing``), None
    for any other column: the one test, for a batch read and a stream's cut of a record alike,
    of a column whose empty cells are no gap and no incomplete edge (the module's rule)."""
    return intermittent(missing, rows, mode) if name.startswith("E_") else None


def said(column: str, entry: dict) -> str:
    """What ``init`` and a run say of one such column."""
    return (f"{column} measured on 1 row in {entry['every']} ({entry['measured']} rows): read "
            "as a probe cycle; the models fit and are scored on the measured rows only")


def sparse_totals(entries: dict) -> dict:
    """``{column: {"measured": rows, "rows": rows, "every": rows, "campaigns": {id: measured}}}``
    over the campaigns' reports (``entries``) of every column read as measured now and then."""
    out: dict = {}
    for cid, entry in entries.items():
        for column, one in entry.get("sparse_targets", {}).items():
            total = out.setdefault(column, {"measured": 0, "rows": 0, "campaigns": {},
                                            "spacings": []})
            total["measured"] += one["measured"]
            total["rows"] += entry["rows"]
            total["campaigns"][cid] = one["measured"]
            total["spacings"].append(one["every"])
    for total in out.values():      # the campaigns' median spacing (a ratio of rows rounds off)
        total["every"] = int(round(float(np.median(total.pop("spacings")))))
    return out


def on_grid(grid: np.ndarray, time: np.ndarray, values: np.ndarray) -> np.ndarray:
    """A target measured now and then moved onto a resampling ``grid`` (``data.resample_s``):
    each measurement on the grid point nearest its time (the last where two share one), NaN
    elsewhere; never interpolated between measurements."""
    out = np.full(grid.size, np.nan)
    measured = np.isfinite(values)
    if grid.size < 2:
        out[:] = values[measured][:1] if measured.any() else np.nan
        return out
    step = grid[1] - grid[0]
    nearest = np.clip(np.rint((time[measured] - grid[0]) / step).astype(int), 0, grid.size - 1)
    out[nearest] = values[measured]
    return out


def measured_on(values: np.ndarray) -> dict:
    """``{"measured": rows, "every": median spacing}`` of a sparse column as it stands."""
    rows = np.flatnonzero(np.isfinite(values))
    return {"measured": int(rows.size), "every": int(round(_spacing(rows, values.size)))}
