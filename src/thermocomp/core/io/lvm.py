"""A LabVIEW Measurement File (``.lvm``: the text NI's "Write To Measurement File" writes) read as
its CSV export (:mod:`.labfile`), as a TDMS log is: its channels, each with its unit and time.

The file: a header (``LabVIEW Measurement``; ``Separator`` ``Tab`` or ``Comma``,
``Decimal_Separator`` -- a German LabVIEW's ``,`` --, ``X_Columns`` ``No`` / ``One`` / ``Multi``,
``Time_Pref``, ``Date``, ``Time`` ...) ending in ``***End_of_Header***``, then segments, one per
write where the VI writes a header per segment: a segment header (``Channels``, ``Samples``,
``Date``, ``Time``, ``Y_Unit_Label``, ``X0``, ``Delta_X``, a cell per channel) ending in
``***End_of_Header***``, the names line (``X_Value`` over an X column, the channel names,
``Comment``) and the rows.

A channel's time is NI's waveform, as a TDMS channel's (``wf_start_time`` / ``wf_increment``):
its segment's ``Date`` and ``Time`` (the clock the VI ran on, no offset said) plus, for each
row, its X value less the segment's ``X0`` where an X column is written, else ``Delta_X`` times
the row within the segment.  So ``Time_Pref`` (X relative to the start or since 1904) and the
``Decimal_Separator`` in the time (``06:00:00,0000000000``) do not change the time read.  A
file without any ``Date`` and ``Time`` is timed in seconds (its X values, or ``X0`` plus
``Delta_X`` steps); without those either, untimed (``data.sample_period_s``).  A unit label is
the header's unit (``Luft [Deg C]``), read by the CSV header rules; the ``Comment`` column is
left out.  The segments of one file are one run; the CSV reader's checks (a time that goes
back, a gap) then see them as one.  A VI run again appending to the file writes the file header
again before its segments: each such session is a run (realexport73: refused before, "a
segment begins with its 'Channels' line"), read as the runs of a TDMS log are.  With
``X_Columns No`` LabVIEW still heads an ``X_Value`` column and leaves its cells empty: the time
is then ``Delta_X`` steps (realexport73: read as no time at all before, ``NaT``).
"""

from __future__ import annotations

from datetime import datetime, timedelta
from pathlib import Path

import numpy as np

from .contract import ContractError
from .dayfirst import parse_with, slashed_order, swapped
from .encoding import UTF8, check_text, first_undecodable, text_codec
from .labfile import Channel, Record, records_as_csv, with_unit

LVM_SUFFIXES = (".lvm",)
MAGIC = "LabVIEW Measurement"
END = "***End_of_Header***"
SEPARATORS = {"tab": "\t", "comma": ",", "semicolon": ";", "space": " "}
X_HEADER = "X_Value"
COMMENT = "Comment"
_STARTS = ("%Y/%m/%d %H:%M:%S", "%Y-%m-%d %H:%M:%S", "%d.%m.%Y %H:%M:%S", "%m/%d/%Y %H:%M:%S")


def is_lvm(path) -> bool:
    return Path(path).suffix.lower() in LVM_SUFFIXES


def lvm_records(path: Path, encoding: str = UTF8, dayfirst: bool | None = None) -> list[Record]:
    """The runs of the LabVIEW Measurement File ``path``: one, or one per session that
    appended to it (each writes its own file header, ``LabVIEW Measurement`` again);
    ``dayfirst``: ``data.dayfirst``, the order of its ``Date`` s with slashes (:mod:`.dayfirst`)."""
    raw = path.read_bytes()
    check_text(raw[:1 << 16], encoding, path)
    try:
        text = raw.decode(text_codec(encoding))
    except UnicodeDecodeError:
        raise first_undecodable(path, "\t", None, encoding) or ContractError(
            f"file is not {encoding} text (set data.encoding)", file=path) from None
    return _records(text.splitlines(), path, dayfirst)


def is_lvm_text(text: str) -> bool:
    """``text`` (a stream's) is a LabVIEW Measurement File, as its first line says."""
    return text.startswith(MAGIC)


def lvm_as_csv(text: str, source: str, dayfirst: bool | None = None,
               sessions: str | None = None) -> str:
    """A LabVIEW Measurement File streamed (``monitor.input=-``) as the CSV text its channels
    are read as from a file (data86b: refused before, "not a CSV table with a header"); a file
    of more than one session (a run each) is refused where a stream is one campaign, and with
    ``sessions`` (data87: ``monitor``, which streams a campaign per run) written with a
    :data:`.labfile.RUN_HEADER` column, the sessions ``<sessions>_1``, ``<sessions>_2``, ...:
    each begins with its own 'LabVIEW Measurement' header, no gap taken for one."""
    path = Path(source)
    records = _records(text.splitlines(), path, dayfirst)
    if len(records) > 1:
        if sessions is None:
            raise ContractError(f"the LabVIEW Measurement File streamed holds {len(records)} "
                                "sessions (a 'LabVIEW Measurement' header each), a run each: "
                                "stream one run", file=path)
        records = [Record(f"{sessions}_{i}", r.channels, r.time_header, r.utc)
                   for i, r in enumerate(records, start=1)]
    with records_as_csv(records, path) as table:
        return table.read_text(encoding=UTF8)


def _records(lines: list[str], path: Path, dayfirst: bool | None) -> list[Record]:
    """:func:`lvm_records` of the file's ``lines``."""
    if not lines or not lines[0].startswith(MAGIC):
        raise ContractError(f"not a LabVIEW Measurement File: its first line is not {MAGIC!r}",
                            file=path, line=1)
    sep = _separator(lines)
    header, k = _block(lines, 1, sep, path)
    decimal = _decimal(header)
    runs, segments = [], []
    while (k := _next_text(lines, k)) < len(lines):
        if lines[k].startswith(MAGIC) and segments:    # a later session appending: a run
            runs.append((header, segments))
            header, k = _block(lines, k + 1, sep, path)
            decimal = _decimal(header)
            segments = []
            continue
        if _cells(lines[k], sep)[0] != "Channels":
            raise ContractError(f"a segment begins with its 'Channels' line, not "
                                f"{lines[k][:40]!r}", file=path, line=k + 1)
        seg_header, k = _block(lines, k, sep, path)
        k = _next_text(lines, k)
        names = segments[-1]["names"] if segments else None
        if k < len(lines) and not _is_number(_cells(lines[k], sep)[0], decimal):
            names, k = _cells(lines[k], sep), k + 1
        if names is None:
            raise ContractError("a segment's rows without a names line", file=path, line=k + 1)
        rows, first_line, k = _rows(lines, k, sep)
        segments.append({"header": seg_header, "names": names, "rows": rows, "line": first_line})
    if not segments:
        raise ContractError("no segment with rows in the LabVIEW Measurement File", file=path)
    runs.append((header, segments))
    labels = [path.stem] if len(runs) == 1 else [f"{path.stem}_{i + 1}" for i in range(len(runs))]
    dates = [(d, line) for k, line in enumerate(lines, start=1) if lines[k - 1].startswith("Date")
             for d in _cells(lines[k - 1], sep)[1:2]]
    order = slashed_order(dates, dayfirst, parse_with(("%m/%d/%Y",)), path, "Date")
    forms = swapped(_STARTS, bool(order))
    return [_record(path, label, *run, sep, forms) for label, run in zip(labels, runs)]


def lvm_layout(path: Path, encoding: str = UTF8) -> str:
    """What ``thermocomp init`` says of the file's own text: ``encoding cp1252 (not UTF-8),
    Separator Tab, Decimal_Separator ','``."""
    with open(path, encoding=text_codec(encoding), errors="replace") as f:
        lines = [f.readline() for _ in range(40)]
    charset = "" if encoding == UTF8 else f"encoding {encoding} (not UTF-8), "
    return (f"{charset}Separator {_said(lines, 'Separator', 'Tab')}, "
            f"Decimal_Separator {_said(lines, 'Decimal_Separator', '.')!r}")


def _separator(lines: list[str]) -> str:
    """The ``Separator`` key's character (tab where not said)."""
    said = _said(lines, "Separator", "Tab")
    return SEPARATORS.get(said.lower(), said[:1])


def _said(lines: list[str], key: str, default: str) -> str:
    """The file header's ``key`` line's value, the rest of its line: read before the lines are
    split, as its ``Separator`` splits them (``default`` where not said)."""
    for line in lines[1:40]:
        if line.startswith(END):
            break
        if line.startswith(key) and len(line) > len(key):
            return line[len(key) + 1:].strip() or default
    return default


def _cells(line: str, sep: str) -> list[str]:
    cells = [c.strip() for c in line.split(sep)]
    while len(cells) > 1 and cells[-1] == "":
        cells.pop()                  # (LabVIEW ends a header line with a separator)
    return cells


def _next_text(lines: list[str], k: int) -> int:
    while k < len(lines) and not lines[k].strip():
        k += 1
    return k


def _block(lines: list[str], k: int, sep: str, path: Path) -> tuple[dict, int]:
    """The ``key value...`` lines from ``k`` to the next ``***End_of_Header***``; ``(keys, the
    line after it)``."""
    keys: dict[str, list[str]] = {}
    for j in range(k, len(lines)):
        cells = _cells(lines[j], sep)
        if cells[0] == END:
            return keys, j + 1
        if cells[0]:
            keys.setdefault(cells[0], cells[1:])
    raise ContractError(f"a header block from line {k + 1} without its {END!r}", file=path)


def _rows(lines: list[str], k: int, sep: str) -> tuple[list[tuple[int, list[str]]], int, int]:
    """The rows from ``k`` to a blank line, the next segment's ``Channels`` or the end:
    ``([(line, cells)], first line, the line after them)``."""
    first, rows = k + 1, []
    while k < len(lines) and lines[k].strip():
        cells = lines[k].split(sep)
        if cells[0].strip() == "Channels":
            break
        rows.append((k + 1, cells))
        k += 1
    return rows, first, k


def _number(cell: str, decimal: str) -> float:
    """A cell written with the file's ``Decimal_Separator``."""
    return float(cell.replace(decimal, "."))


def _is_number(cell: str, decimal: str) -> bool:
    try:
        _number(cell, decimal)
        return True
    except ValueError:
        return False


def _decimal(header: dict) -> str:
    """The decimal mark a file header declares (``Decimal_Separator``; ``.`` without one)."""
    return header.get("Decimal_Separator", ["."])[0] or "."


def _record(path: Path, label: str, header: dict, segments: list[dict], sep: str,
            forms: tuple[str, ...] = _STARTS) -> Record:
    """The segments' channels joined, each with its time."""
    decimal = _decimal(header)
    names = segments[0]["names"]
    if COMMENT in names:
        names = names[:names.index(COMMENT)]
    x_at = [j for j, n in enumerate(names) if n == X_HEADER]
    columns = [j for j, n in enumerate(names) if n != X_HEADER]
    values = {j: [] for j in columns}
    times: dict[int, list] = {j: [] for j in columns}
    timed = {"dated": False, "seconds": False, "untimed": False}
    for s, seg in enumerate(segments):
        seg_names = seg["names"][:len(names)]
        if seg_names != names:
            raise ContractError(f"segment {s + 1} holds other channels than the first "
                                f"({', '.join(map(repr, seg_names[:6]))}): one file is one run "
                                "of the same channels", file=path, line=seg["line"] - 1)
        table = _numbers(path, seg, names, decimal)
        keys = seg["header"]
        for c, j in enumerate(columns):
            x_col = max((i for i in x_at if i < j), default=None)
            x = table[:, x_col] if x_col is not None else None
            if x is not None and np.isnan(x).all():
                x = None     # (X_Columns No: LabVIEW still heads an X_Value column, empty)
            t, kind = _time(path, header, keys, c, x, len(table), decimal, seg["line"], forms)
            timed[kind] = True
            values[j].append(table[:, j])
            times[j].append(t)
    if sum(timed.values()) > 1:
        raise ContractError("the segments are timed unlike (some by their Date and Time, others "
                            "by seconds or not at all): give every segment its Date and Time",
                            file=path)
    units = segments[0]["header"].get("Y_Unit_Label", [])
    channels = []
    for c, j in enumerate(columns):
        unit = units[c] if c < len(units) else None
        t = None if timed["untimed"] else np.concatenate(times[j])
        channels.append(Channel(with_unit(names[j], unit), np.concatenate(values[j]), t,
                                f"channel {names[j]!r}"))
    return Record(label, channels, utc=False)


def _numbers(path: Path, seg: dict, names: list[str], decimal: str) -> np.ndarray:
    """The segment's rows as numbers (an empty cell: missing); a cell that is none refused with
    its line and channel."""
    width = len(names)
    out = np.full((len(seg["rows"]), width), np.nan)
    for r, (line, cells) in enumerate(seg["rows"]):
        if len(cells) < width:
            raise ContractError(f"the line holds {len(cells)} of the segment's {width} fields",
                                file=path, line=line)
        for j in range(width):
            cell = cells[j].strip()
            if not cell:
                continue
            try:
                out[r, j] = _number(cell, decimal)
            except ValueError:
                raise ContractError(f"cell {cell!r} is no number (the file's Decimal_Separator "
                                    f"is {decimal!r})", file=path, column=names[j],
                                    line=line) from None
    return out


def _time(path: Path, header: dict, keys: dict, c: int, x: np.ndarray | None, n: int,
          decimal: str, line: int, forms: tuple[str, ...] = _STARTS) -> tuple[np.ndarray | None, str]:
    """Channel ``c``'s time in a segment: ``(times, 'dated' | 'seconds' | 'untimed')``."""
    def key(name: str, of: dict):
        cells = of.get(name, [])
        return cells[c] if c < len(cells) and cells[c] else (cells[0] if cells else None)

    x0 = key("X0", keys)
    x0 = _number(x0, decimal) if x0 else None
    step = key("Delta_X", keys)
    step = _number(step, decimal) if step else None
    if x is not None:
        offsets = x - (x0 if x0 is not None else x[0])
    elif step is not None and step > 0:
        offsets = step * np.arange(n)
    else:
        return None, "untimed"
    date, clock = key("Date", keys) or key("Date", header), key("Time", keys) or key("Time", header)
    if date and clock:
        start = _start(path, date, clock, decimal, line, forms)
        return np.datetime64(start, "us") + (offsets * 1e6).round().astype("timedelta64[us]"), \
            "dated"
    return offsets + (x0 or 0.0) if x is None else x, "seconds"


def _start(path: Path, date: str, clock: str, decimal: str, line: int,
           forms: tuple[str, ...] = _STARTS) -> datetime:
    """A segment's ``Date`` (``2027/09/06``) and ``Time`` (``06:00:00,0000000000``)."""
    whole, _, fraction = clock.replace(decimal, ".").partition(".")
    for form in forms:
        try:
            start = datetime.strptime(f"{date} {whole}", form)
            break
        except ValueError:
            continue
    else:
        raise ContractError(f"its segment's Date {date!r} and Time {clock!r} are no date and "
                            "time (yyyy/mm/dd hh:mm:ss)", file=path, line=line)
    return start + timedelta(seconds=float(f"0.{fraction}") if fraction.isdigit() else 0.0)
