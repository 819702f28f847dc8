"""What a lab's text files' number cells say, for ``thermocomp init`` (initone65): the thousands
separator (``data.thousands``), the marks written for a value not measured
(``data.missing_values``) and the gaps they leave (``data.max_gap_samples``,
``data.max_edge_samples``).  Each is written to the config only where the cells leave no doubt,
and said with why; a doubt is said, never guessed.

The rules (every text file of the record or folder read as text, its header written again left
out as the reader leaves it out, :mod:`.again`):

- a number column is one whose header is not a time and at least half of whose non-empty cells
  read as numbers (with the file's decimal mark, or grouped by three with a mark): a column
  mostly of text is no number column, so a token filling much of it is no mark;
- a thousands separator ``m`` (one of :data:`.separators.GROUP_MARKS`, not the decimal mark):
  every number cell holding ``m`` groups its digits by three with it after the sign (``1.200,0``,
  ``-12.345``), and the decimal mark is shown to be the other character: ``m`` is no ``,``/``.``
  (an apostrophe, a no-break space), or a cell holds ``m`` twice or the decimal mark after its
  groups, or another number cell holds the decimal mark with other than three digits after it.
  ``m`` in a cell that does not group by three, or only ``1.200`` and no other evidence: said,
  not written (the reader then refuses the cell, naming the setting);
- the decimal mark followed by exactly three digits in every cell of a column that holds it,
  beside integers in that column (``980``, ``1.200``): a thousands separator or decimals? said,
  read as decimals (as the reader reads it);
- a mark: a cell's text in a number column that is no number and either holds no digit
  (``---``, ``n/a``, ``#N/A``) or is a formula's error (``Err:502``, ``#DIV/0!``); the text
  the reader reads as missing already (``NaN``, empty) is no mark to list but a missing value;
  a number cell is one where its value is a Keysight DAQ's overload ``+9.90000000E+37`` (an
  open thermocouple on a 34970A / DAQ970A; stranger83) or a mark given by value
  (``data.missing_values``), its runs a gap as a mark's;
- its gap: the longest run of missing cells in a number column (empty, a mark, a NaN written
  out as a Campbell Scientific logger's ``NAN``: lab74; empty cells alone too: stranger74, a
  row empty in every column left out as the reader leaves it), inside the file
  (``max_gap_samples``) or at its start or end (``max_edge_samples``); an error column
  measured now and then (a probe cycle, :mod:`.sparse`) has none: the reader keeps its empty
  cells empty, a mark's too (:meth:`Cells.longest`, told the error columns by ``init``).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.compute as pc
import pyarrow.csv as pacsv

from .again import header_again, without
from .contract import ContractError
from .encoding import arrow_encoding, own
from .footer import footer, source
from .layout import header_line
from .marks import AMERIFLUX, INFINITE, value_of, values
from .roles import named_as_time
from .separators import GROUP_MARKS, NO_BREAK_SPACES, UNICODE_MINUS, grouped
from .sniff import head_lines
from .sparse import intermittent
from .tables import EXCEL_ERROR, MISSING_TOKENS, is_mark  # the reader's own rules

NUMBER_SHARE = 0.5       # a number column: at least this share of its non-empty cells numbers
AMERIFLUX_TIME = "timestamp_start"      # the header that says an AmeriFlux table
_NINES = r"^-9999(?:[.,]0*)?$"          # AmeriFlux's -9999, as a program writes it
_INFINITE = rf"^\s*(?i:{INFINITE.pattern})\s*$"    # INF, -INF, Infinity (lab75: missing as read)
KEYSIGHT_OVERLOAD = 9.9e37   # a Keysight 34970A / DAQ970A's reading of an overload, an open input


@dataclass
class Cells:
    """What the cells say: the keys to write and a line of why for each, and the doubts."""

    thousands: str | None = None
    marks: dict = field(default_factory=dict)        # mark -> {column header: cells}
    said: list = field(default_factory=list)
    runs: list = field(default_factory=list)         # a marked column's :class:`Runs`, per file

    def merged(self, other: Cells) -> Cells:
        """These cells' findings and ``other``'s (another logger's files, scanned with their
        own separators: pair70): one thousands separator where only one says one or both say
        the same (two: none written, said), the marks and their runs of both."""
        said, both = [*self.said, *other.said], (self.thousands, other.thousands)
        thousands = self.thousands or other.thousands
        if None not in both and both[0] != both[1]:
            said.append(f"the two loggers' files group thousands apart ({both[0]!r} and "
                        f"{both[1]!r}): no data.thousands written (one key reads both)")
            thousands = None
        marks = {m: dict(c) for m, c in self.marks.items()}
        for mark, columns in other.marks.items():
            marks.setdefault(mark, {}).update(columns)
        return Cells(thousands, marks, said, [*self.runs, *other.runs])

    def longest(self, errors, sparse_targets: str = "auto",
                grid: dict | None = None) -> tuple[int, int, list, dict]:
        """``(longest run of missing cells inside a file, at a file's start or end, lines said,
        {"gap" / "edge": the header of the column holding it})``
        over the marked columns but an error column (a header in ``errors``) read as measured
        now and then (``data.sparse_targets``, :mod:`.sparse`): its empty cells, a mark's too,
        are a probe cycle's rows between readings, kept empty, never interpolated, so no gap
        (its run between two readings set data.max_gap_samples to the probe's spacing, and every
        column's gap was then interpolated up to it: leftovers66).  ``grid``: header -> the grid
        rows one of its samples is held over (its interval / data.resample_s), where the
        channels are held onto a grid: a run counted in grid rows, the rows the read checks
        (stranger80: a TDMS log's 6 missing samples at 30 s, proposed as 6, were 18 rows of its
        10 s grid, and init's own read refused its own proposal); a run of a historian's long
        file's value column, its tag not known to the scan, as the slowest tag's (the safe
        side); a historian's text file is scanned on its grid, each tag's runs its own
        (:func:`.historian.grid_runs`, lab83)."""
        gap = edge = 0
        where: dict = {}
        cycles: dict = {}                    # header -> the probe's spacing in each file
        for r in self.runs:
            cycle = intermittent(r.missing, r.rows, sparse_targets) if r.header in errors else None
            if cycle is None:
                # (a historian's long file's value column: its runs' tag unknown here, the
                # slowest tag's; a lab file's channels are scanned each on its own)
                each = grid.get(r.header, max(grid.values(), default=1.0)) if grid else 1.0
                r_gap, r_edge = (int(np.ceil(n * each - 1e-9)) for n in (r.gap, r.edge))
                where.update({"gap": r.header, "gap_at": r.gap_at} if r_gap > gap else {})
                where.update({"edge": r.header, "edge_at": r.edge_at} if r_edge > edge else {})
                gap, edge = max(gap, r_gap), max(edge, r_edge)
            elif r.gap or r.edge:
                cycles.setdefault(r.header, []).append(cycle["every"])
        said = []
        for header, every in cycles.items():      # (said once a column, however many files)
            lo, hi = min(every), max(every)
            said.append(f"{header!r} measured on 1 row in {lo}{f'-{hi}' if hi > lo else ''}"
                        f"{f' ({len(every)} files)' if len(every) > 1 else ''}: its marks are a "
                        "probe cycle's readings not taken, kept empty as the rows between its "
                        "readings are (no gap: data.max_gap_samples not set by them)")
        return gap, edge, said, where


@dataclass
class Runs:
    """A marked column's longest run of missing cells holding a mark, inside the file (``gap``)
    and at its start or end (``edge``), and its missing cells (empty or a mark) of ``rows``."""

    header: str
    gap: int
    edge: int
    missing: np.ndarray
    rows: int
    gap_at: str = ""             # where each run begins, said (a historian's: the long row)
    edge_at: str = ""


def _table(path: Path, delimiter: str, encoding: str, skip: int, preamble: int,
           width: int) -> pa.Table | None:
    """The file's data rows as text (None where Arrow cannot split them: the reader says why)."""
    spans = header_again(path, preamble, skip > preamble + 1, delimiter)
    cut = footer(path, delimiter, width, encoding)[1]
    spans = tuple((a, b) for a, b in spans if a < cut)
    data = without(path, cut, spans) if spans else source(path, cut)
    names = [f"c{i}" for i in range(width)]
    try:
        return pacsv.read_csv(data, read_options=pacsv.ReadOptions(
            column_names=names, skip_rows=skip, encoding=arrow_encoding(encoding)),
            parse_options=pacsv.ParseOptions(delimiter=delimiter),
            convert_options=pacsv.ConvertOptions(column_types=dict.fromkeys(names, pa.string()),
                                                 strings_can_be_null=False, null_values=[]))
    except (pa.ArrowInvalid, UnicodeDecodeError):
        return None


def _texts(column: pa.ChunkedArray) -> pa.ChunkedArray:
    text = pc.utf8_trim_whitespace(column)
    return pc.replace_substring(text, UNICODE_MINUS, "-")


def _plain(decimal: str) -> str:
    d = re.escape(decimal)
    return rf"^[+-]?(?:\d+(?:{d}\d*)?|{d}\d+)(?:[eE][+-]?\d+)?$"


def _matches(text, pattern: str) -> np.ndarray:
    return pc.match_substring_regex(text, pattern).to_numpy(zero_copy_only=False)


def _holds(text, mark: str) -> np.ndarray:
    return pc.match_substring(text, mark).to_numpy(zero_copy_only=False)


@dataclass
class _Column:
    header: str
    path: Path
    text: pa.ChunkedArray
    missing: np.ndarray          # read as missing already (empty, NaN)
    plain: np.ndarray            # a number with the decimal mark
    grouped: dict                # mark -> grouped by three with it
    ameriflux: bool = False      # the file is an AmeriFlux table (its TIMESTAMP_START)
    blank: np.ndarray | bool = False    # the file's rows empty in every column (left out)
    tags: np.ndarray | None = None      # a lab file's channels written long: each row's channel
    again: np.ndarray | bool = False    # the file's rows that write its header again (no marks)

    def first(self, mask: np.ndarray) -> str:
        return str(self.text[int(np.argmax(mask))].as_py())


def _empty(text) -> np.ndarray:
    """The cells the reader reads as missing already (empty, a NaN written out)."""
    return pc.is_in(text, value_set=pa.array(list(MISSING_TOKENS))).to_numpy(zero_copy_only=False)


def _column(header: str, path: Path, text, decimal: str) -> _Column | None:
    """The column's masks, or None where it is no number column (:data:`NUMBER_SHARE`)."""
    missing = _empty(text)
    filled = int((~missing).sum())
    if not filled:
        return None
    plain = _matches(text, _plain(decimal))
    marks = {m: _matches(text, f"^{grouped(m, decimal)}$") for m in GROUP_MARKS if m != decimal}
    numeric = plain | np.logical_or.reduce([*marks.values(), np.zeros_like(plain)])
    if int((numeric & ~missing).sum()) < NUMBER_SHARE * filled:
        return None
    return _Column(header, path, text, missing, plain, marks)


def scanned(files: list[Path], delimiter: str, decimal: str, encoding: str,
            thousands: str | None, missing_values: list, peek, decimal_given: bool = False
            ) -> Cells:
    """:class:`Cells` of the text ``files`` (``peek``: :func:`.tables.peek_csv`; the keys
    given, ``thousands`` and ``missing_values``, are kept and not said again, nor a doubt of
    the decimal mark where ``decimal_given``)."""
    numbers: list[_Column] = []
    for path in files:
        code = own(path, encoding)       # (data87: data.encoding=auto, the file's own)
        try:
            header, _, skip = peek(path, delimiter, code)
        except ContractError:          # (no rows, no text: the reader refuses it, saying why)
            continue
        preamble = header_line(head_lines(path, code), delimiter) or 0
        table = _table(path, delimiter, code, skip, preamble, len(header))
        if table is None:
            continue
        ameriflux = any(h.strip().lower() == AMERIFLUX_TIME for h in header)
        blank = np.logical_and.reduce([_empty(_texts(column)) for column in table.columns])
        # a row holding most of the header's names (a second export pasted under the first):
        # the read refuses it as the header written again; its names are no marks (audit86)
        again = 2 * np.sum([pc.equal(pc.utf8_trim_whitespace(_texts(column)), h.strip())
                            .fill_null(False).to_numpy(zero_copy_only=False)
                            for h, column in zip(header, table.columns)], axis=0) > len(header)
        # a lab file's channels at their own rates, written long (labfile.write_long): each
        # run of missing values is its channel's (stranger80: one 'value' column's runs)
        tags = (_texts(table.columns[1]).to_numpy(zero_copy_only=False)
                if [h.strip() for h in header[1:]] == ["channel", "value"] else None)
        for h, column in zip(header, table.columns):
            if h.strip() and not named_as_time(h):
                found = _column(h, path, _texts(column), decimal)
                if found is not None:
                    numbers.append(replace(found, ameriflux=ameriflux, blank=blank, again=again,
                                           tags=tags if h.strip() == "value" else None))
    found = Cells(thousands=thousands)
    if thousands is None:
        found.thousands = _thousands(numbers, decimal, found.said)
    if not decimal_given:
        _decimal_doubt(numbers, decimal, found)
    _marks(numbers, decimal, found, missing_values)
    return found


def _valued(c: _Column, decimal: str, given: list) -> np.ndarray:
    """The number cells of ``c`` whose value is a mark's: a Keysight DAQ's overload, or a
    number ``given`` in ``data.missing_values`` (matched by value, as the reader matches it)."""
    text = np.asarray(c.text.to_pylist(), dtype=object)[c.plain]
    found = np.zeros(c.plain.size, dtype=bool)
    if text.size:
        read = pd.to_numeric(pd.Series(text, dtype=str).str.replace(decimal, ".", regex=False),
                             errors="coerce").to_numpy()
        found[c.plain] = np.isin(read, [KEYSIGHT_OVERLOAD, *values(given)])
    return found


def _thousands(numbers: list[_Column], decimal: str, said: list) -> str | None:
    d = re.escape(decimal)
    # the decimal mark shown as one: with other than three digits after it (21,35)
    shows = rf"^[+-]?\d*{d}(?:\d{{1,2}}|\d{{4,}})(?:[eE][+-]?\d+)?$"
    as_decimal = [c for c in numbers if _matches(c.text, shows).any()]
    for mark in GROUP_MARKS:
        if mark == decimal:
            continue
        # (a cell without a digit, 'n.d.', is a mark, not a number the mark groups: audit96,
        # one made init refuse the speeds' '5.000' at row 1, far from it)
        holding = [(c, _holds(c.text, mark) & _matches(c.text, r"\d")) for c in numbers]
        holding = [(c, h) for c, h in holding if h.any()]
        if not holding:
            continue
        shown = repr(holding[0][0].first(holding[0][1]))
        bad = [(c, h & ~c.grouped[mark]) for c, h in holding if (h & ~c.grouped[mark]).any()]
        if bad:
            good = [c.first(h & c.grouped[mark]) for c, h in holding if (h & c.grouped[mark]).any()]
            if good:    # (audit112: shown was the first cell holding it, the odd one itself at times)
                said.append(f"{mark!r} groups digits by three in {good[0]!r} but not in "
                            f"{bad[0][0].first(bad[0][1])!r}: no thousands separator guessed "
                            "(data.thousands)")
            continue
        name = "a no-break space" if mark in NO_BREAK_SPACES else repr(mark)
        m = re.escape(mark)
        twice = [(c, h & _matches(c.text, f"{m}.*{m}")) for c, h in holding]
        twice = [c.first(t) for c, t in twice if t.any()]
        after = [(c, h & _holds(c.text, decimal)) for c, h in holding]
        after = [c.first(t) for c, t in after if t.any()]
        evidence = (
            f"{name} is no decimal mark" if mark not in ",." else
            f"{twice[0]!r} holds it twice" if twice else
            f"{after[0]!r} has the decimal mark {decimal!r} after its groups" if after else
            f"{_shown(as_decimal[0], shows)!r} has the decimal mark {decimal!r}" if as_decimal
            else None)
        if evidence is None:
            said.append(f"{shown}: {mark!r} groups digits by three in every cell that holds it, "
                        f"but no cell shows {decimal!r} as the decimal mark: a thousands "
                        f"separator or the decimal mark? not guessed: set data.thousands={mark!r} "
                        f"or data.decimal={mark!r}")
            return None
        n = sum(int(h.sum()) for _, h in holding)
        said.append(f"thousands separator {name}: every one of {n} cells holding it "
                    f"groups digits by three ({shown}), and {evidence}: data.thousands={mark!r}")
        return mark
    return None


def _runs(header: str, missing: np.ndarray) -> Runs:
    """The longest run of ``missing`` inside and at an end of one column's (a channel's) cells."""
    gap, edge, _ = run_starts(missing)
    return Runs(header, gap, edge, np.flatnonzero(missing), len(missing))


def run_starts(missing: np.ndarray) -> tuple[int, int, dict]:
    """The longest run of ``missing`` inside and at an end, and where each begins
    (``{"gap": index, "edge": index}``, the first of the longest)."""
    edges = np.flatnonzero(np.diff(np.concatenate([[0], missing.astype(np.int8), [0]])))
    longest = {"gap": 0, "edge": 0}
    starts: dict = {}
    for a, b in zip(edges[::2], edges[1::2]):
        kind = "edge" if a == 0 or b == len(missing) else "gap"
        if b - a > longest[kind]:
            longest[kind], starts[kind] = int(b - a), int(a)
    return longest["gap"], longest["edge"], starts


def _shown(column: _Column, pattern: str) -> str:
    return column.first(_matches(column.text, pattern))


def _decimal_doubt(numbers: list[_Column], decimal: str, found: Cells) -> None:
    """Say a column whose every cell with the decimal mark has three digits after it, beside
    integers: ``1.200`` read as 1.2, or grouped?"""
    if found.thousands is not None:
        return
    d = re.escape(decimal)
    for c in numbers:
        holding = _holds(c.text, decimal)
        integers = _matches(c.text, r"^[+-]?\d+$")
        three = _matches(c.text, rf"^[+-]?\d{{1,3}}{d}\d{{3}}$")
        if holding.any() and integers.any() and not (holding & ~three).any():
            found.said.append(f"{c.header!r} ({c.path.name}): {c.first(holding)!r} beside "
                              f"{c.first(integers)!r}: {decimal!r} with three digits after it in "
                              "every cell: a thousands separator or decimals? not guessed, read "
                              f"as decimals (data.thousands={decimal!r} with the other decimal "
                              "mark if grouped)")
            return


def _marks(numbers: list[_Column], decimal: str, found: Cells, given: list) -> None:
    thousands = found.thousands
    nines_said: dict = {}         # a -9999 in a file that is no AmeriFlux table: header -> cells
    for c in numbers:
        numeric = c.plain | (c.grouped[thousands] if thousands in c.grouped else False)
        # an infinite reading (a Campbell logger's INF, lab75): missing as read, no mark to list;
        # not said here (lab76): the read says each column's with its rows
        infinite = _matches(c.text, _INFINITE)
        other = ~numeric & ~c.missing & ~infinite & ~c.again
        # a NaN written out (a Campbell logger's NAN, lab74): missing as read, its runs a mark's
        written = c.missing & _matches(c.text, ".")
        counts = pc.value_counts(pc.filter(c.text, pa.array(other))).to_pylist()
        marks = {v["values"]: v["counts"] for v in counts
                 if v["values"] in given or is_mark(v["values"])}
        nines = _matches(c.text, _NINES)       # AmeriFlux's mark, however written (lab74)
        if nines.any() and not c.ameriflux:    # (a reading, maybe: said, not written)
            nines_said.setdefault(c.header, int(nines.sum()))
            nines[:] = False
        if nines.any():
            marks[AMERIFLUX] = int(nines.sum())
        # (stranger83: an open thermocouple's +9.90000000E+37 on a Keysight DAQ was refused by
        # the read, and given in data.missing_values its 3 scans refused as a gap)
        valued = _valued(c, decimal, given)
        if valued.any() and value_of(first := c.first(valued)) not in values(given):
            marks[first] = marks.get(first, 0) + int(valued.sum())
        for mark, n in marks.items():
            found.marks.setdefault(mark, {})
            found.marks[mark][c.header] = found.marks[mark].get(c.header, 0) + n
        marked = valued | written | infinite | nines | pc.is_in(
            c.text, value_set=pa.array(list(marks), pa.string())).to_numpy(zero_copy_only=False)
        # a run of empty cells is a gap as a mark's is (stranger74: an hour of a sensor's
        # cells left empty, refused by the config init wrote); a row empty in every column is
        # none: the reader leaves it out, as a blank line
        missing = (c.missing | marked)[~c.blank]
        if not missing.any():
            continue
        if c.tags is None:
            found.runs.append(_runs(c.header, missing))
            continue
        tags = c.tags[~c.blank]
        cuts = np.concatenate([[0], np.flatnonzero(tags[1:] != tags[:-1]) + 1, [tags.size]])
        for a, b in zip(cuts[:-1], cuts[1:]):
            if missing[a:b].any():
                found.runs.append(_runs(str(tags[a]), missing[a:b]))
    for mark, where in found.marks.items():
        if mark in given:
            continue
        cells = sum(where.values())
        found.said.append(f"{mark!r} in {cells} cell{'s' * (cells > 1)} of number column"
                          f"{'s' * (len(where) > 1)} {', '.join(map(repr, list(where)[:4]))}"
                          f"{', ...' if len(where) > 4 else ''}: "
                          + ("AmeriFlux's mark, in an AmeriFlux table (its TIMESTAMP_START)"
                             if mark == AMERIFLUX else "no number, a formula's error"
                             if EXCEL_ERROR.fullmatch(mark) else "a Keysight DAQ's overload (an "
                             "open input)" if value_of(mark) == KEYSIGHT_OVERLOAD
                             else "no number, no digit")
                          + ": a mark for a value not measured, read as missing "
                          "(data.missing_values)")
    if nines_said and not any(value_of(m) == -9999.0 for m in given):
        cells = sum(nines_said.values())
        found.said.append(f"-9999 in {cells} cell{'s' * (cells > 1)} of "
                          f"{', '.join(map(repr, list(nines_said)[:4]))}"
                          f"{', ...' if len(nines_said) > 4 else ''}: AmeriFlux's mark for a value "
                          "not measured? not written: the file is no AmeriFlux table (no "
                          "TIMESTAMP_START), so it may be a reading; data.missing_values=[-9999] "
                          "if it is the mark")
