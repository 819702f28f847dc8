"""What ``thermocomp init`` shows of a run logged by two loggers (:mod:`.loggers`,
:mod:`.joined`): one header, the temperature file's then the error file's (its time left out),
whose roles it proposes, and a line per run saying what it paired."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from .loggers import partner
from .manifest import campaign_files
from .roles import named_as_time
from .separators import reads_as_number
from .timestamps import looks_like_timestamp


def paired_head(sample: Path, opts, head: Callable) -> tuple | None:
    """``(header, first row, layout line, same separators)`` of ``sample`` and the error file
    it pairs with, ``head`` (:func:`.detect.head`) reading each; None where it pairs with none."""
    errors = partner(sample, opts, campaign_files(sample.parent))
    if errors is None:
        return None
    t_opts, header, first, layout = head(sample, opts)
    e_opts, e_header, e_first, e_layout = head(errors, opts)
    cells = dict(zip(e_header, e_first))
    for h in e_header:
        if h in header or named_as_time(h) or looks_like_timestamp(cells.get(h)):
            continue       # (its time: the run's rows are put on the temperature file's clock)
        cell = str(cells.get(h) or "")
        if e_opts.decimal != t_opts.decimal and reads_as_number(cell, e_opts.decimal):
            cell = cell.replace(e_opts.decimal, t_opts.decimal)   # (as the first file's)
        header, first = [*header, h], [*first, cell]
    same = (e_opts.delimiter, e_opts.decimal) == (t_opts.delimiter, t_opts.decimal)
    return header, first, f"{layout}; {e_layout}", same


def paired_lines(report: dict) -> list[str]:
    """A line per run of two loggers in the read ``report``: its files, their periods, the
    clock offset and the rows cut."""
    out = []
    for cid, entry in report["campaigns"].items():
        pair = entry.get("paired")
        if not pair:
            continue
        cut = {k: n for k, n in pair["cut"].items() if n}
        out.append(f"{cid}: two loggers, {pair['temperatures']} (every {pair['periods_s'][0]:g} s)"
                   f" + {pair['errors']} (every {pair['periods_s'][1]:g} s): one run, its rows "
                   f"the errors' times, temperatures interpolated onto them (data.join.offset_s="
                   f"{pair['offset_s']:g}); {entry['rows']} rows"
                   + (f", {sum(cut.values())} error sample(s) cut ("
                      + ", ".join(f"{n} {k}" for k, n in cut.items()) + ")" if cut else ""))
    return out
