"""A Beckhoff TwinCAT Scope CSV export (stranger76) read as its channels (:mod:`.labfile`), as a
LabVIEW Measurement File is: each channel with its unit and its own time.

The file: a preamble of ``key<sep>value`` lines (``Name``, ``File``, ``StartTime`` -- Windows
FILETIME, 100 ns ticks since 1601 UTC, then the local date --, ``EndTime`` ...), a blank line,
then one row per channel property, each channel a few columns wide, its cells under the
property's key (``Name``, ``SymbolComment``, ``Data-Type``, ``SampleTime[ms]``, ``SymbolName``,
``Unit`` ...), a blank line, optionally a ``Time<sep>Value`` row, then the samples: every
channel its own time (ms since ``StartTime``) and value columns, a slow channel's cells empty
below its last sample. A German Windows writes ``;`` and decimal commas.

A channel is named by its ``Name`` and ``Unit`` (``Temp Bett 1 vorn [°C]``, read by the CSV
header rules); the Scope's other properties (``SymbolName`` ...) are left out. Its time is
``StartTime`` plus its time column, in ms where its steps are its ``SampleTime[ms]`` (else
seconds, the step times 1000); or (lab77: Scope View's absolute time format) a date-time per
row, on the PC's clock (a clock the file does not say: ``data.timezone``), the channels timed
from ``StartTime`` then counted from its local date.  The channels are laid on the union of
their times (:func:`.labfile.on_union_grid`), a channel's cells at the others' times empty,
never held: a slower channel on the same clock (a laser tracker every 5 min beside temperatures
every 10 s) is read as measured now and then (``data.sparse_targets``); channels on different
clocks (another task's cycle, another target) share no row.  A ``BOOL`` channel's
``True`` / ``False`` is 1 / 0, a state (its unit ``-``)."""

from __future__ import annotations

import re
from datetime import datetime, timedelta
from pathlib import Path

import numpy as np

from ...base.log import logger
from .contract import ContractError
from .dayfirst import parse_with, slashed_order, swapped
from .encoding import UTF8, text_head, text_lines
from .labfile import Channel, Record, on_union_grid, text_as_csv, with_unit

SAMPLE_KEY = "SampleTime[ms]"
_FIRST = re.compile(r"^\ufeff?(Name|ScopeName)([;\t,])")
_TICKS_TO_1970 = 116444736000000000          # FILETIME of 1970-01-01 UTC
_DATES = ("%d.%m.%Y %H:%M:%S,%f", "%d.%m.%Y %H:%M:%S.%f", "%d.%m.%Y %H:%M:%S",
          "%Y-%m-%d %H:%M:%S.%f", "%Y-%m-%dT%H:%M:%S.%f", "%Y-%m-%d %H:%M:%S,%f",
          "%Y-%m-%d %H:%M:%S", "%Y-%m-%dT%H:%M:%S",
          "%m/%d/%Y %I:%M:%S.%f %p", "%m/%d/%Y %I:%M:%S %p", "%m/%d/%Y %H:%M:%S.%f",
          "%m/%d/%Y %H:%M:%S")
_BOOL = {"true": 1.0, "false": 0.0}            # a BOOL channel's values


def is_scope(path) -> bool:
    """``path`` is a text file whose first line is a Scope export's ``Name`` and whose head
    holds the channels' ``SampleTime[ms]`` row."""
    head = text_head(path, 1 << 16)
    if head is None or not _FIRST.match(head):
        return False
    sep = _FIRST.match(head).group(2)
    return any(line.startswith(SAMPLE_KEY + sep) for line in head.splitlines()[:60])


_PAIRS = re.compile(r"^\ufeff?Time([;\t,])Value\1")


def headerless(path) -> bool:
    """``path`` is a Scope export written without its header blocks (Scope View's *Include
    header* off): its first line ``Time<sep>Value<sep>`` over each channel, or (no row of them)
    samples in triples of a time, a value and an empty cell, two channels or more."""
    if Path(path).suffix.lower() not in (".csv", ".txt"):
        return False
    try:
        with open(path, "rb") as f:
            head = f.read(1 << 12).decode("latin-1").lstrip("\ufeff").splitlines()[:2]
    except OSError:
        return False
    if not head:
        return False
    if _PAIRS.match(head[0]):     # (two channels or more: a lab's 'Time;Value' table is one)
        cells = [c.strip() for c in head[0].split(_PAIRS.match(head[0]).group(1))]
        return sum(p == ("Time", "Value") for p in zip(cells, cells[1:])) > 1
    return len(head) == 2 and any(_triples(line, sep) for line in head[:1] for sep in ";\t") \
        and any(_triples(head[1], sep) for sep in ";\t")


def _triples(line: str, sep: str) -> bool:
    """``line``: cells in triples (a time: a date-time or a number; a value; an empty cell)."""
    cells = line.rstrip("\r\n").split(sep)
    if len(cells) < 6 or len(cells) % 3 or any(c.strip() for c in cells[2::3]):
        return False
    return all(_number(t, ",") is not None or _number(t, ".") is not None or _form(t)
               for t in cells[0::3] if t.strip()) and any(t.strip() for t in cells[0::3])


def refuse_headerless(path: Path) -> None:
    """Refuse the Scope export ``path`` written without its header blocks (:func:`headerless`),
    naming its first line and its channels' columns: no channel has a name to read it by (which
    sensor is which?), and its times count from a ``StartTime`` it does not hold."""
    with open(path, "rb") as f:
        first = f.read(1 << 12).decode("latin-1").lstrip("\ufeff").splitlines()[0]
    sep = next(s for s in ";\t," if s in first)
    cells = first.split(sep)
    pairs = [j for j in range(len(cells) - 1) if (cells[j].strip(), cells[j + 1].strip()) ==
             ("Time", "Value")] or [j for j in range(0, len(cells) - 1, 3)]
    said = ", ".join(f"{j + 1}-{j + 2}" for j in pairs[:6]) + (", ..." if len(pairs) > 6 else "")
    what = ("'Time" + sep + "Value' over each channel" if _PAIRS.match(first)
            else "samples, a time and a value a channel")
    raise ContractError(f"a TwinCAT Scope export without its header blocks (Scope View's "
                        f"'Include header' off): {what}, {len(pairs)} channel(s) in columns "
                        f"{said}, none named (no 'Name' row: which sensor is which?) and no "
                        "StartTime its times count from; export it again with the header "
                        "included", file=path, line=1)


def scope_layout(path: Path, encoding: str = UTF8) -> str:
    """What ``thermocomp init`` says of the file's own text."""
    with open(path, "rb") as f:
        head = f.read(1 << 16).decode("latin-1")
    sep = _FIRST.match(head).group(2)
    charset = "" if encoding == UTF8 else f"encoding {encoding} (not UTF-8), "
    return f"{charset}delimiter {sep!r}, decimal {_decimal(head.splitlines(), sep)!r}"


def scope_records(path: Path, encoding: str = UTF8, dayfirst: bool | None = None
                  ) -> list[Record]:
    """The one run of the Scope export ``path`` (``dayfirst``: ``data.dayfirst``, the order of
    its dates with slashes, :mod:`.dayfirst`)."""
    return [_record(text_lines(path, encoding), path.stem, path, dayfirst)]


def is_scope_text(text: str) -> bool:
    """``text`` (a stream's) is a Scope export, as :func:`is_scope` tells a file."""
    found = _FIRST.match(text[:200])
    return found is not None and any(line.startswith(SAMPLE_KEY + found.group(2))
                                     for line in text[:1 << 16].splitlines()[:60])


def scope_as_csv(text: str, source: str, dayfirst: bool | None = None) -> str:
    """A Scope export streamed (``monitor.input=-``) as the CSV text its channels are read as
    from a file (:mod:`.labfile`: a ``time`` of UTC timestamps, each channel a column)."""
    return text_as_csv(lambda lines, label, path: _record(lines, label, path, dayfirst), text,
                       source)


def _record(lines: list[str], label: str, path: Path, dayfirst: bool | None = None) -> Record:
    """The export's channels, each on its own time (laid onto one grid where they fit one)."""
    sep = _FIRST.match(lines[0]).group(2)
    k, preamble = _keys(lines, 0, sep)
    k = _blank(lines, k)
    first_prop = k
    k, props = _keys(lines, k, sep, whole=True)
    names = props.get("Name")
    if names is None:
        raise ContractError("the channels' 'Name' row is missing after the preamble", file=path,
                            line=first_prop + 1)
    cols = [j for j, cell in enumerate(names) if cell == "Name" and j + 1 < len(names)]
    k = _blank(lines, k)
    if k < len(lines) and lines[k].split(sep)[0].strip().lower() == "time":
        k += 1                                      # the Time;Value row over each channel
    decimal = _decimal(lines[k:k + 50], sep)
    rows = [(i + 1, line.split(sep)) for i, line in enumerate(lines[k:], start=k) if line.strip()]
    # the order of its dates with slashes: the StartTime's and the first time column's decide
    said = [(c, _line_of(lines, "StartTime")) for c in preamble.get("StartTime", [])]
    said += [(r[cols[0]], line) for line, r in rows if cols and cols[0] < len(r)]
    column = ("StartTime" if any("/" in c for c, _ in said[:len(preamble.get("StartTime", []))])
              else f"Time of {names[cols[0] + 1].strip()!r}" if cols else "Time")
    order = slashed_order(said, dayfirst, parse_with(_DATES), path, column)
    forms = _DATES if order is None else swapped(_DATES, order)
    start, utc = _start(preamble, path, forms=forms)
    read = [(j, names[j + 1].strip(), *_column(rows, j, decimal, path, names[j + 1].strip(),
                                               forms)) for j in cols]
    if not read:
        raise ContractError("no channel under the 'Name' row", file=path, line=first_prop + 1)
    if utc and any(np.issubdtype(t.dtype, np.datetime64) for *_, t, _, _ in read):
        # "Time format: absolute": the PC's date-times, on a clock the file does not say; the
        # channels timed from StartTime counted from its local date alike
        start, utc = _start(preamble, path, local=True, forms=forms)
    channels = []
    for j, name, times, values, bool_ in read:
        if np.issubdtype(times.dtype, np.datetime64):
            stamp = times
        else:
            seconds = times / 1000.0 if _in_ms(times, _said(props, SAMPLE_KEY, j)) else times
            stamp = start + (seconds * 1e6).round().astype("timedelta64[us]")
        unit = _said(props, "Unit", j)
        if bool_:
            logger.info(f"{path}: channel {name!r} is a BOOL (True / False): read as 0 / 1, "
                        "a state")
            unit = unit or "-"
        channels.append(Channel(with_unit(name, unit), values, stamp,
                                f"channel {name!r} (column {j + 1})"))
    return Record(label, on_union_grid(channels), utc=utc)


def _keys(lines: list[str], k: int, sep: str, whole: bool = False) -> tuple[int, dict]:
    """The ``key<sep>...`` lines from ``k`` to a blank line: ``(the blank line, {key: cells})``
    (``whole``: every cell of the line, a channel's keys repeated across it)."""
    keys = {}
    while k < len(lines) and lines[k].strip():
        cells = [c.strip() for c in lines[k].lstrip("\ufeff").split(sep)]
        keys.setdefault(cells[0], cells if whole else cells[1:])
        k += 1
    return k, keys


def _blank(lines: list[str], k: int) -> int:
    while k < len(lines) and not lines[k].strip():
        k += 1
    return k


def _said(props: dict, key: str, j: int) -> str | None:
    cells = props.get(key) or []
    return cells[j + 1] if j + 1 < len(cells) and cells[j] == key else None


def _line_of(lines: list[str], key: str) -> int | None:
    return next((k + 1 for k, line in enumerate(lines[:60]) if line.lstrip("\ufeff").startswith(key)),
                None)


def _start(preamble: dict, path: Path, local: bool = False,
           forms: tuple[str, ...] = _DATES) -> tuple[np.datetime64, bool]:
    """``(StartTime, in UTC)``: its FILETIME ticks (UTC), else (or ``local``: where the file
    gives it) the local date after them (on a clock the file does not say)."""
    cells = preamble.get("StartTime") or []
    for cell in cells[1:] if local and cells and cells[0].isdigit() else []:
        if (found := _date(cell, forms=forms)) is not None:
            return found, False
    if cells and cells[0].isdigit():
        micro = (int(cells[0]) - _TICKS_TO_1970) // 10
        return np.datetime64(datetime(1970, 1, 1) + timedelta(microseconds=micro), "us"), not local
    for cell in cells:
        if (found := _date(cell, forms=forms)) is not None:
            return found, False
    raise ContractError(f"the preamble's StartTime {cells[:2]!r} is no Windows FILETIME nor date: "
                        "the channels' time counts from it", file=path)


def _date(cell: str, first: str | None = None, forms: tuple[str, ...] = _DATES
          ) -> np.datetime64 | None:
    """A Scope View date-time (German ``15.02.2027 06:00:00,000``, or ISO), None if none
    (``first``: the format tried first, the one the column's first cell was read by)."""
    for form in (first, *forms) if first else forms:
        try:
            return np.datetime64(datetime.strptime(cell.strip(), form), "us")
        except ValueError:
            continue
    return None


def _form(cell: str, forms: tuple[str, ...] = _DATES) -> str | None:
    """The format of ``forms`` (:data:`_DATES`, in the file's order) that reads ``cell``."""
    return next((f for f in forms if _fits(cell, f)), None)


def _fits(cell: str, form: str) -> bool:
    try:
        datetime.strptime(cell.strip(), form)
        return True
    except ValueError:
        return False


def _decimal(lines: list[str], sep: str) -> str:
    """``,`` where a number cell is written with a comma (a German Windows), else ``.``."""
    for line in lines:
        if any(re.fullmatch(r"-?\d+,\d+", c.strip()) for c in line.split(sep)):
            return ","
    return "."


def _column(rows: list, j: int, decimal: str, path: Path, name: str,
            forms: tuple[str, ...] = _DATES) -> tuple[np.ndarray, np.ndarray, bool]:
    """Channel ``name``'s time and value columns ``j``, ``j + 1`` down to its last sample (an
    empty value under a time: missing) and whether it is a BOOL: its times as numbers (ms or s
    since StartTime) or, where the first is a date-time (an absolute time format), datetime64;
    its values numbers, or ``True`` / ``False`` read as 1 / 0."""
    times, values, dated, bools = [], [], None, None
    for line, cells in rows:
        t = cells[j].strip() if j < len(cells) else ""
        if not t:
            continue
        v = cells[j + 1].strip() if j + 1 < len(cells) else ""
        if dated is None:
            form = _form(t, forms) if _number(t, decimal) is None else None
            dated = form is not None
        if bools is None and v:
            bools = v.lower() in _BOOL
        stamp = _date(t, form, forms) if dated else _number(t, decimal)
        value = np.nan if not v else _BOOL.get(v.lower()) if bools else _number(v, decimal)
        if stamp is None or value is None:
            bad, what = (t, "no date-time" if dated else "no time") if stamp is None else (
                v, "no True / False (a BOOL channel)" if bools else
                f"no number (decimal {decimal!r})")
            raise ContractError(f"cell {bad!r} is {what}", file=path, column=name,
                                line=line) from None
        times.append(stamp)
        values.append(value)
    if dated:
        return np.asarray(times, dtype="datetime64[us]"), np.asarray(values, float), bool(bools)
    return np.asarray(times, float), np.asarray(values, float), bool(bools)


def _number(cell: str, decimal: str) -> float | None:
    try:
        return float(cell.replace(decimal, "."))
    except ValueError:
        return None


def _in_ms(times: np.ndarray, step: str | None) -> bool:
    """The time column is in ms (the Scope's) unless its step is the SampleTime[ms] / 1000."""
    if times.size < 2 or not step:
        return True
    try:
        said = float(step.replace(",", "."))
    except ValueError:
        return True
    return not np.isclose(np.median(np.diff(times)) * 1000.0, said)
