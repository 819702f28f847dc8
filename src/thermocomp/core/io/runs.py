"""One long file holding many runs (extension): ``data.roles.campaign=<header>`` splits it into
campaigns by that column's value, and a column that looks like a run counter is pointed out.

Each value is one campaign, in file order, read as a file of that run alone would be (its time
in seconds as given, restarting or not; timestamps as seconds since the run's first sample;
gaps, edges and checks per run).  A value that comes back after another is refused naming the
row: the rows of a run stand together, and a number used twice (``Messung`` 1, 2, 3 each day)
needs a value of its own.  The id is the value where it holds a letter (``K07``), else the
header's name before it (``Lauf_3``).

A file without such a column, its runs appended one after the other with the logger silent
between them (catman70: a lab's week of ISO 230-3 tests in one catman export), is split where
its time pauses for more than :data:`.timestamps.PAUSE_PERIODS` sample periods with
``data.runs_at_pauses=true`` (extension; :func:`pause_blocks`): the runs ``<file>_1``,
``<file>_2`` ..., read as those of a run column are.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np
import pyarrow as pa
import pyarrow.compute as pc

from ..timerule import median_step
from .contract import ContractError
from .options import RUN_ROLE
from .roles import split_unit
from .timestamps import PAUSE_PERIODS, pauses

MIN_RUN_ROWS = 10        # a run counter holds each value this many rows on average at least
_UNSAFE_ID = re.compile(r"[^\w.\-]+")
_WORDS = re.compile(r"[\s_.\-]+")
# header words that say "the run's number" (a counter stepping by other than one is one too)
# (a Spanish lab's 'Ensayo', 'Medición', a French one's 'Mesure': newmachine58)
RUN_WORDS = {"lauf", "run", "runs", "versuch", "messung", "campaign", "kampagne", "test", "trial",
             "cycle", "zyklus", "durchlauf", "essai", "prueba", "prova", "serie", "series",
             "batch", "charge", "job", "nr", "no", "id", "ensayo", "medición", "medicion", "mesure"}


def run_values(column) -> list[str | None]:
    """The run column's cells as text (a Parquet number 3.0 as ``3``), None where empty."""
    if pa.types.is_floating(column.type):
        numbers = column.to_numpy(zero_copy_only=False)
        return [None if np.isnan(v) else f"{v:.0f}" if v == int(v) else repr(v) for v in numbers]
    text = pc.utf8_trim_whitespace(pc.cast(column, pa.string())).to_pylist()
    return [v or None for v in text]


def run_blocks(values: Sequence[str | None], header: str, path: Path | str
               ) -> list[tuple[str, int, int]]:
    """``(campaign id, first row, end row)`` of each run in file order (0-based, end excluded).

    Raises
    ------
    ContractError
        A row without a value (its row), a value that comes back after another (the row where
        it does), two values giving one id.
    """
    blocks: list[tuple[str, int, int]] = []
    seen: dict[str, int] = {}
    for row, value in enumerate(values):
        if value is None:
            raise ContractError(f"no run in the data.roles.{RUN_ROLE} column: every row says its "
                                "run", file=path, column=header, row=row + 1)
        if blocks and value == blocks[-1][0]:
            continue
        if value in seen:
            raise ContractError(f"run {value!r} comes back after {blocks[-1][0]!r} (its rows "
                                f"began at row {seen[value] + 1}): the rows of a run stand "
                                "together; sort the file by run, or give the later rows a run "
                                "of their own", file=path, column=header, row=row + 1)
        seen[value] = row
        blocks.append((value, row, row))
    ends = [start for _, start, _ in blocks[1:]] + [len(values)]
    ids = [campaign_id(value, header) for value, _, _ in blocks]
    twice = next((i for i in ids if ids.count(i) > 1), None)
    if twice is not None:
        raise ContractError(f"two runs give the campaign id {twice!r}: give them values that "
                            "differ in letters or digits", file=path, column=header)
    return [(cid, start, end) for cid, (_, start, _), end in zip(ids, blocks, ends)]


def pause_blocks(seconds: np.ndarray, stem: str, path: Path | str
                 ) -> list[tuple[str, int, int]]:
    """``(campaign id, first row, end row)`` of each stretch of ``seconds`` (the record's time)
    between pauses longer than :data:`.timestamps.PAUSE_PERIODS` sample periods; ids ``<stem>_<k>``
    from 1.

    Raises
    ------
    ContractError
        No pause: one run (``data.runs_at_pauses`` splits nothing); ``seconds`` None, a time
        written as text the file's read parses later (data89: a time of day without its date
        crashed here).
    """
    if seconds is None:
        raise ContractError("data.runs_at_pauses finds the pauses in a time of seconds or of "
                            "timestamps with their date; this one is written otherwise (a time "
                            "of day without its date?): give the date column with it, "
                            "data.roles.time=[<date column>, <time column>], or a column "
                            "numbering the runs, data.roles.campaign=<header>", file=path,
                            column="time")
    found = pauses(seconds) + 1
    if not found.size:
        raise ContractError(f"data.runs_at_pauses: the time never pauses for more than "
                            f"{PAUSE_PERIODS} sample periods ({median_step(seconds) or 0:g} s): "
                            "one run, nothing to split (leave the key out)", file=path,
                            column="time")
    edges = [0, *map(int, found), len(seconds)]
    return [(f"{stem}_{k}", a, b) for k, (a, b) in enumerate(zip(edges, edges[1:]), 1)]


def campaign_id(value: str, header: str) -> str:
    """``K07`` for a value with a letter, ``Lauf_3`` for the number 3 under ``Lauf [-]``."""
    name = value if re.search(r"[^\W\d_]", value) else f"{split_unit(header)[0]}_{value}"
    return _UNSAFE_ID.sub("_", name).strip("._") or "run"


def looks_like_run_counter(values: np.ndarray, header: str,
                           ends: Callable[[np.ndarray], np.ndarray | None] | None = None) -> bool:
    """A column numbering runs: whole numbers, never decreasing, at least two of them, each held
    :data:`MIN_RUN_ROWS` rows on average, and either under a header that says so
    (:data:`RUN_WORDS`: ``Lauf``, ``Run``, ``Versuch``, ``run_id``, ``Messung`` ...) or stepping
    by one only where a run may end: ``ends(changes)``, :func:`run_ends` of the record's time
    and other columns at the steps where the value changes (asked of a column that passes
    every other check: it reads the whole record).  A temperature logged in whole degrees
    (``T5`` 20, 21, 22, rising slowly) steps by one too, but in the middle of a run."""
    values = np.asarray(values, dtype=float)
    if values.size < 2 * MIN_RUN_ROWS or values[0] != np.round(values[0]) or values[-1] <= values[0]:
        return False            # (the look at every value is for what passes this one)
    if not np.isfinite(values).all():
        return False
    steps = np.diff(values)
    if not (values == np.round(values)).all() or (steps < 0).any():
        return False
    runs = int((steps > 0).sum()) + 1
    if runs < 2 or values.size / runs < MIN_RUN_ROWS:
        return False
    if says_run(header):
        return True
    if not (steps[steps > 0] == 1).all():
        return False
    at = None if ends is None else ends(steps > 0)
    return at is None or bool(at.all())


def says_run(header: str) -> bool:
    """Whether ``header`` (its unit dropped) holds a word that names a run (:data:`RUN_WORDS`)."""
    return bool(set(_WORDS.split(split_unit(header)[0].lower())) & RUN_WORDS)


def looks_like_run_labels(values: Sequence[str | None], header: str) -> bool:
    """A text column naming the runs (``Versuch`` K01, K02 ...), as a run counter numbers them:
    under a header that says so (:func:`says_run`), every row a value holding a letter, each
    value's rows together (none coming back after another), at least two values, each held
    :data:`MIN_RUN_ROWS` rows on average.  A comment column, or one label for the whole file,
    is no such column."""
    if not says_run(header) or not values or any(
            v is None or not re.search(r"[^\W\d_]", v) for v in values):
        return False
    labels = [v for i, v in enumerate(values) if i == 0 or v != values[i - 1]]
    return (len(labels) >= 2 and len(set(labels)) == len(labels)
            and len(values) / len(labels) >= MIN_RUN_ROWS)


JUMP = 3.0     # a step over this many times a column's largest within the runs is a run's end


def run_ends(changes: np.ndarray, time: np.ndarray | None = None,
             others: Sequence[np.ndarray] = ()) -> np.ndarray | None:
    """Whether a run may end at each step between rows where ``changes`` (a candidate run
    counter changes value): the ``time`` (s) goes back or jumps (over twice its median step),
    or a column of ``others`` jumps (over :data:`JUMP` times its largest step elsewhere: a
    machine warm at a run's end, cold at the next one's start).  A whole-degree sensor's step
    is no such place.  None where nothing tells (no time, no other column moving)."""
    ends, told = np.zeros(int(changes.sum()), bool), False
    if time is not None and np.isfinite(time).sum() > 2:
        dt = np.diff(np.asarray(time, float))
        period = median_step(time) or np.nan
        ends |= ((dt <= 0) | (dt > 2 * period))[changes]
        told = True
    for column in others:
        step = np.abs(np.diff(np.asarray(column, float)))
        within = step[~changes & np.isfinite(step)]
        if within.size == 0 or not within.max() > 0:   # constant within the runs: tells nothing
            continue
        ends |= step[changes] > JUMP * within.max()
        told = True
    return ends if told else None


def run_hint(header: str) -> str:
    """What a message says of a column that looks like a run counter."""
    header = split_unit(header)[0]
    return (f"column {header!r} looks like a run number (whole numbers, rising, each held over "
            f"many rows): data.roles.{RUN_ROLE}={header} reads each run as a campaign "
            f"(data.roles.ignore=[{header}] leaves it out)")
