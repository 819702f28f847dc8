"""What ``thermocomp init`` shows of a run logged by two loggers (:mod:`.loggers`,
:mod:`.joined`): one header, the temperature file's then the error file's (its time left out),
whose roles it proposes, and a line per run saying what it paired.  Its detections cover both
files (pair70): the marks and thousands separators of the error files' cells too
(:func:`error_files`), and a time since each logger's start, ``h:mm:ss``, in both
(:func:`pair_time`)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import NamedTuple

import pandas as pd

from .contract import ContractError
from .loggers import named_error_file, partner
from .manifest import campaign_files
from .roles import date_and_time_of_day, named_as_time
from .separators import reads_as_number
from .timestamps import ELAPSED, looks_like_timestamp, maybe_elapsed


class PairedHead(NamedTuple):
    header: list
    first: list
    layout: str
    same_separators: bool
    errors: Path                 # the error file
    error_time: tuple | None     # (its time's header, its first cell), or None


def error_files(src: Path, manifest: pd.DataFrame | None, opts) -> list[Path]:
    """The error files of the runs of two loggers of the folder ``src`` (``manifest``: as
    read), each named by the manifest's ``error_file`` or found by its name; [] for a record."""
    if manifest is None:
        return []
    files = campaign_files(src)
    found = [named_error_file(src, manifest, cid) or partner(src / str(f), opts, files)
             for cid, f in manifest["file"].items()]
    return [f for f in found if f is not None]


def paired_head(sample: Path, cid: str, manifest: pd.DataFrame, opts,
                head: Callable) -> PairedHead | None:
    """The header, first row, layout line and whether both files have the same separators of
    ``sample`` (campaign ``cid``'s file) and the error file it pairs with, ``head``
    (:func:`.detect.head`) reading each; None where it pairs with none."""
    errors = named_error_file(sample.parent, manifest, cid) or partner(
        sample, opts, campaign_files(sample.parent))
    if errors is None:
        return None
    t_opts, header, first, layout = head(sample, opts)
    e_opts, e_header, e_first, e_layout = head(errors, opts)
    cells = dict(zip(e_header, e_first))
    # (stranger83: an NC's probe log's DATE and TIME: the date was proposed as left out, its
    # time of day alone then refused as the run's time)
    clock = date_and_time_of_day(e_header, cells)
    error_time = (clock[0], " ".join(str(cells[h]) for h in clock)) if clock else None
    for h in e_header:
        if h in header or h in clock or named_as_time(h) or looks_like_timestamp(cells.get(h)):
            if error_time is None and h not in header:
                error_time = (h, str(cells.get(h) or ""))
            continue       # (its time: the run's rows are put on the temperature file's clock)
        cell = str(cells.get(h) or "")
        if e_opts.decimal != t_opts.decimal and reads_as_number(cell, e_opts.decimal):
            cell = cell.replace(e_opts.decimal, t_opts.decimal)   # (as the first file's)
        header, first = [*header, h], [*first, cell]
    same = (e_opts.delimiter, e_opts.decimal) == (t_opts.delimiter, t_opts.decimal)
    return PairedHead(header, first, f"{layout}; {e_layout}", same, errors, error_time)


def pair_time(pair: PairedHead, sample: Path, header: list, first: dict, opts) -> str | None:
    """``elapsed`` where the error file's time is ``h:mm:ss`` (a logger's time since its start)
    and so is the temperature file's: read so in both (a time of day alone is refused, and one
    file's header saying ``Elapsed`` left the other's ``Zeit`` refused); None otherwise.  An
    error file's ``h:mm:ss`` beside temperatures' timestamps is refused naming both: the join
    puts no time since a start on a clock (:mod:`.joined`)."""
    if pair.error_time is None or opts.time != "auto" or opts.roles.get("time", "auto") != "auto":
        return None
    name, cell = pair.error_time
    if not maybe_elapsed(cell, "auto"):
        return None
    if any(maybe_elapsed(str(first.get(h) or ""), "auto") for h in header):
        return ELAPSED
    stamped = next((h for h in header if looks_like_timestamp(first.get(h))), None)
    if stamped is not None:
        raise ContractError(
            f"its time {name!r} ({cell!r}) is h:mm:ss, a logger's time since its start, and "
            f"{sample.name}'s {stamped!r} timestamps ({first[stamped]!r}): the two loggers' rows "
            "are joined on one clock, the timestamps' or each logger's time from its start; "
            "export both files with timestamps (or both with the time since the start)",
            file=pair.errors, column=name)
    return None


def paired_lines(report: dict) -> list[str]:
    """A line per run of two loggers in the read ``report``: its files, their periods, the
    clock offset and the rows cut.  A run cut into parts (``data.test_fraction``) is one run:
    one line naming its parts, their rows summed (data88b: it was said once per part)."""
    runs: dict[tuple, list] = {}
    for cid, entry in report["campaigns"].items():
        pair = entry.get("paired")
        if pair:
            runs.setdefault((pair["temperatures"], pair["errors"]), []).append((cid, entry))
    out = []
    for parts in runs.values():
        pair = parts[0][1]["paired"]
        cut = {k: n for k, n in pair["cut"].items() if n}
        out.append(f"{', '.join(cid for cid, _ in parts)}: two loggers, {pair['temperatures']} "
                   f"(every {pair['periods_s'][0]:g} s) + {pair['errors']} (every "
                   f"{pair['periods_s'][1]:g} s): one run, its rows the errors' times, the "
                   f"temperatures' last sample at or before each (data.join.offset_s="
                   f"{pair['offset_s']:g}); {sum(entry['rows'] for _, entry in parts)} rows"
                   + (f", {sum(cut.values())} error sample(s) cut ("
                      + ", ".join(f"{n} {k}" for k, n in cut.items()) + ")" if cut else ""))
    return out
