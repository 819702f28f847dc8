"""Day or month first: the order of a lab file's dates with slashes, decided from the file itself
(dates84), for the readers that parse a date of their own (a catman T0, a Scope View start or
time column, a LabVIEW segment's Date); a CSV table's time column is decided by its record's rows
(:mod:`.slashed`).

``05/03/2027`` is the 3rd of May on an en-US PC and the 5th of March on an en-GB one; catman read
it month first wherever the day was 12 or less (stranger84).  So: ``data.dayfirst`` (true /
false) where the config says it; else a field past 12 in any of the file's dates fixes the order
for the whole file (one date past 12 each way: refused, naming both); else an order is possible
where the file's dates, read so, never go back and never step 27 days or more at once (where
the date turns a day in one order it turns a month in the other: a run of samples across
midnight tells); one order possible is taken, both (a file whose dates are one day's) are
refused naming the file, the column, the row and ``data.dayfirst``: never a guess.  A folder's
files are one record, read in one order: a date past 12 in any of them decides for all
(:func:`record_dayfirst`; ``init`` writes it as ``data.dayfirst``).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from datetime import datetime, timedelta
from pathlib import Path

from .contract import ContractError

_FIELDS = re.compile(r"^\s*(\d{1,2})/(\d{1,2})/\d{2,4}\b")
_MONTH = timedelta(days=27)      # the least step a day turned into a month makes (28-31 days)
WAY = {True: "day first", False: "month first"}
KEY = "data.dayfirst"


def swapped(forms: Sequence[str], day_first: bool) -> tuple[str, ...]:
    """The strptime formats ``forms`` (written month first, ``%m/%d/``) in the order chosen."""
    return tuple(f.replace("%m/%d/", "%d/%m/") for f in forms) if day_first else tuple(forms)


def slashed_order(dates: Sequence[tuple[str, int | None]], dayfirst: bool | None, parse: Callable,
                  file, column: str) -> bool | None:
    """``True`` (day first) or ``False`` (month first) for a file's dates with slashes.

    Parameters
    ----------
    dates : sequence of (str, int or None)
        The file's date cells in the order it writes them, each with its line (None: unknown);
        cells that are no date with slashes are passed over.
    dayfirst : bool or None
        ``data.dayfirst`` (None: not set, the file decides).
    parse : callable
        ``parse(cell, day_first)``: the cell as a ``datetime``, None where it does not read so.
    file, column
        What a refusal names.

    Returns
    -------
    bool or None
        None where no cell is a date with slashes.

    Raises
    ------
    ContractError
        Where the file says both orders, or gives no way to tell and ``data.dayfirst`` is unset.
    """
    slashed = [(cell, line, _FIELDS.match(cell)) for cell, line in dates]
    slashed = [(cell, line, int(m[1]), int(m[2])) for cell, line, m in slashed if m]
    if not slashed:
        return None
    if dayfirst is not None:
        return bool(dayfirst)
    day = next(((c, ln) for c, ln, a, b in slashed if a > 12), None)
    month = next(((c, ln) for c, ln, a, b in slashed if b > 12), None)
    if day and month:
        raise ContractError(f"date {day[0]!r} (line {day[1]}) is day first and {month[0]!r} "
                            f"month first: one file's dates are written in one order; set "
                            f"{KEY}=true|false to the one the PC wrote", file=file, column=column,
                            line=month[1])
    if day or month:
        return bool(day)
    possible = [order for order in (True, False) if _runs(slashed, order, parse)]
    if len(possible) == 1:
        return possible[0]
    cell, line = slashed[0][:2]
    why = ("read in neither order as a run that never goes back" if not possible else
           "read either way (no day past 12, and no change of date that only one order "
           "makes a small step)")
    raise ContractError(f"date {cell!r} is day or month first? the file's dates {why}: set "
                        f"{KEY}=true (day first, 05/03 the 5th of March) or {KEY}=false (month "
                        "first, the 3rd of May) to the order of the PC that wrote it",
                        file=file, column=column, line=line)


def _runs(slashed: list, day_first: bool, parse: Callable) -> bool:
    """The dates read ``day_first`` parse, never go back, and never step a month at once."""
    times = [parse(cell, day_first) for cell, *_ in slashed]
    if any(t is None for t in times):
        return False
    steps = [b - a for a, b in zip(times, times[1:])]
    return all(timedelta(0) <= s < _MONTH for s in steps)


def parse_with(forms: Sequence[str]) -> Callable[[str, bool], datetime | None]:
    """A ``parse`` for :func:`slashed_order`: the first of ``forms`` (month first, swapped for
    day first) that reads the cell."""
    def parse(cell: str, day_first: bool) -> datetime | None:
        for form in swapped(forms, day_first):
            try:
                return datetime.strptime(cell.strip(), form)
            except ValueError:
                continue
        return None
    return parse


_ANY = re.compile(r"(?<![\d/])(\d{1,2})/(\d{1,2})/\d{2,4}(?![\d/])")


def record_dayfirst(files, dated: Callable[[Path], bool], encoding: str = "utf-8"
                    ) -> tuple[bool, Path, str] | None:
    """The order one file of a record's says by a field past 12, for all its files (a catman
    folder whose tests of the 13th say month first, the 3rd's alike): ``(day_first, file,
    date)``, None where none says one.  ``dated``: a file read by a reader of its own dates.

    Raises
    ------
    ContractError
        Where one file says day first and another month first, naming both.
    """
    said: dict[bool, tuple[Path, str]] = {}
    for path in files:
        if not dated(path):
            continue
        with open(path, encoding=encoding, errors="replace") as f:
            for m in _ANY.finditer(f.read()):
                a, b = int(m[1]), int(m[2])
                if (a > 12) != (b > 12):
                    said.setdefault(a > 12, (Path(path), m[0]))
    if len(said) == 2:
        (day, d), (month, m) = said[True], said[False]
        raise ContractError(f"date {d!r} is day first, but file {month}'s {m!r} month first: "
                            f"the files of one record are read in one order; set {KEY}=true|false "
                            "to the one the PC wrote, or read each as a record of its own",
                            file=day)
    return next(((order, *where) for order, where in said.items()), None)
