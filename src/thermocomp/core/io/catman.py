"""HBM catman's ASCII export with its channel header (catman AP / Easy, stranger84) read as its
channels (:mod:`.labfile`), as a Graphtec CSV is.

The file, as written from catman's export options (no file a real installation wrote was at
hand): a header block of ``key:<sep>value`` lines (``File:`` / ``Datei:``, ``Comment:``,
``catman Version:``, ``Export:``), then a block a channel in the table's column order
(``Channel 3:`` / ``Kanal 3:`` and its name, ``Unit:``, ``Comment:``, ``Sample rate:``, ``T0:``
the start of its group, ``Length:`` its samples), then the table: a row of the channels' names
and a row a sample.  Each rate group's time channel (``Time  1 - default sample rate``, ``Zeit
2 - 0,01667 Hz``) comes first in its group, in seconds from its T0; a slower group's cells are
empty under its last sample.  The separator is the first line's (a TAB, ``;`` or ``,``);
decimal commas are read where the cells hold them.  Channels at two rates are two grids (the
historian's path holds them onto one, ``data.resample_s``); a file holding fewer rows than a
channel's ``Length:`` or a row cut short is refused naming its line.
"""

from __future__ import annotations

import re
from datetime import datetime
from pathlib import Path

import numpy as np

from .contract import ContractError
from .dayfirst import parse_with, slashed_order, swapped
from .encoding import UTF8, text_head, text_lines
from .labfile import Channel, Record, marked_values, text_as_csv, with_unit

_FIRST = re.compile(r"^\ufeff?(File|Datei):([\t;,])")
_BLOCK = re.compile(r"^(?:Channel|Kanal) (\d+):$")
_TIME = re.compile(r"^(?:Time|Zeit)\s+\d+\s+-\s")
_MISSING = re.compile(r"nan|NaN|NAN")
_T0 = ("%m/%d/%Y %H:%M:%S", "%d.%m.%Y %H:%M:%S", "%Y-%m-%d %H:%M:%S", "%m/%d/%Y %H:%M:%S.%f",
       "%d.%m.%Y %H:%M:%S.%f", "%Y-%m-%d %H:%M:%S.%f")
_LENGTH = ("length", "länge")


def _is_head(head: str | None) -> bool:
    if head is None or not (said := _FIRST.match(head)):
        return False
    return any(_BLOCK.match(line.split(said.group(2))[0].strip()) for line in head.splitlines())


def is_catman(path) -> bool:
    """``path`` is a text file beginning ``File:`` / ``Datei:`` whose head holds a channel block
    (``Channel 1:``): catman's ASCII export with its channel header."""
    return _is_head(text_head(path, 2048))


def is_catman_text(text: str) -> bool:
    """``text`` (a stream's) is such an export, as :func:`is_catman` tells a file."""
    return _is_head(text[:2048])


def catman_records(path: Path, encoding: str = UTF8, dayfirst: bool | None = None
                   ) -> list[Record]:
    """The one measurement of the export ``path`` (``dayfirst``: ``data.dayfirst``, the order
    of its T0s with slashes, :mod:`.dayfirst`)."""
    return [_record(text_lines(path, encoding), path.stem, path, dayfirst)]


def catman_as_csv(text: str, source: str, dayfirst: bool | None = None) -> str:
    """An export streamed (``monitor.input=-``) as the CSV text its channels are read as from a
    file (:mod:`.labfile`): a slower group's channels held onto the fastest group's times, as
    the file's grid of ``data.resample_s`` holds them (a stream reads no long file)."""
    return text_as_csv(lambda lines, label, path: _held(lines, label, path, dayfirst), text,
                       source)


def _held(lines: list[str], label: str, path: Path, dayfirst: bool | None = None) -> Record:
    """The record, every channel on its fastest group's times: a slower one's value the last
    sample at or before each (sample and hold)."""
    record = _record(lines, label, path, dayfirst)
    grid = max((c.time for c in record.channels), key=len)
    laid = []
    for c in record.channels:
        at = np.searchsorted(c.time, grid, side="right") - 1
        values = np.where(at >= 0, c.values[np.clip(at, 0, None)], np.nan)
        laid.append(Channel(c.header, values, grid, c.where))
    return Record(record.label, laid, utc=False)


def _blocks(lines: list[str], sep: str, path: Path) -> tuple[list[dict], int]:
    """The channel blocks (each ``{key: value}``, ``line``: its first line) and the index of the
    table's column row."""
    blocks: list[dict] = []
    for k, line in enumerate(lines):
        key, _, value = line.partition(sep)
        key = key.strip()
        if _BLOCK.match(key):
            blocks.append({"name": value.strip(), "line": k + 1})
        elif blocks and key.endswith(":") and sep in line:
            blocks[-1][key[:-1].strip().lower()] = value.strip()
            blocks[-1][f"{key[:-1].strip().lower()} line"] = k + 1
        elif blocks and line.strip():
            return blocks, k
    raise ContractError("no table (a row of the channels' names, then the samples) under the "
                        "channel blocks: the file was cut short?", file=path)


def _record(lines: list[str], label: str, path: Path, dayfirst: bool | None = None) -> Record:
    sep = _FIRST.match(lines[0]).group(2)
    blocks, top = _blocks(lines, sep, path)
    t0s = [(b["t0"], b["t0 line"]) for b in blocks if b.get("t0")]
    day_first = bool(slashed_order(t0s, dayfirst, parse_with(_T0), path, "T0"))
    header = [c.strip() for c in lines[top].split(sep)]
    names = [b["name"] for b in blocks]
    if header != names:
        raise ContractError(f"the table's column row ({', '.join(map(repr, header[:4]))} ...) does "
                            f"not name the {len(names)} channel blocks' channels in their order "
                            f"({', '.join(map(repr, names[:4]))} ...)", file=path, line=top + 1)
    body = [(k + 1, line.split(sep)) for k, line in enumerate(lines[top + 1:], start=top + 1)
            if line.strip()]
    try:
        return Record(label, _channels(blocks, body, top, sep, path, swapped(_T0, day_first)),
                      utc=False)
    except ContractError as exc:     # its data row beside the line, the row a sample
        rows = {line: n + 1 for n, (line, _) in enumerate(body)}
        if exc.row is not None or exc.line not in rows:
            raise
        raise ContractError(exc.reason, file=exc.file, column=exc.column, row=rows[exc.line],
                            line=exc.line) from None


def _channels(blocks: list[dict], body: list, top: int, sep: str, path: Path,
              forms: tuple[str, ...]) -> list[Channel]:
    """The channels of the table's rows ``body`` (``(line, cells)``), each on its group's time
    (its T0 read by ``forms``)."""
    names = [b["name"] for b in blocks]
    for n, (line, cells) in enumerate(body):
        if len(cells) != len(names):
            cut = ("the file's last line" if n == len(body) - 1 else f"line {line}")
            raise ContractError(f"{cut} holds {len(cells)} of its {len(names)} fields"
                                + (": cut off while it was written (the PC stopped?); delete "
                                   "that line" if n == len(body) - 1 else ""),
                                file=path, line=line)
    comma = sep != "," and any(re.fullmatch(r"-?\d+,\d*", c.strip()) for c in body[0][1]) if (
        body) else False
    channels, time = [], None
    for j, block in enumerate(blocks):
        length = _length(block, body, j, path)
        rows = body[:length]
        if _TIME.match(block["name"]):
            time = _times(block, rows, j, comma, path, forms)
            continue
        what = f"channel {j + 1} {block['name']!r}"
        values = marked_values(rows, j, what, path, _MISSING, "NaN", comma)
        if time is None or time.size != values.size:
            time = _times(block, rows, None, comma, path, forms)
        channels.append(Channel(with_unit(block["name"], block.get("unit") or block.get("einheit")),
                                values, time, what))
    if not channels:
        raise ContractError("no channel but time channels in the export", file=path, line=top + 1)
    return channels


def _length(block: dict, body: list, j: int, path: Path) -> int:
    """The channel's samples: its ``Length:``, checked against the rows; else its cells up to
    its last one not empty."""
    said = next((block[k] for k in _LENGTH if k in block), None)
    if said is None:
        return max((n + 1 for n, (_, r) in enumerate(body) if r[j].strip()), default=0)
    try:
        length = int(said)
    except ValueError:
        raise ContractError(f"channel {j + 1} {block['name']!r}: its Length {said!r} is no count",
                            file=path, line=block["line"]) from None
    if length > len(body):
        last = body[-1][0] if body else None
        raise ContractError(f"channel {j + 1} {block['name']!r}: the file holds {len(body)} of its "
                            f"{length} samples (its block's Length, line {block['line']}): cut "
                            "short (the file copied while catman wrote it?)", file=path, line=last)
    return length


def _times(block: dict, rows: list, j: int | None, comma: bool, path: Path,
           forms: tuple[str, ...]) -> np.ndarray:
    """The group's times: its T0 plus the time channel's seconds (column ``j``; None: its sample
    rate's steps); seconds alone where the block gives no T0."""
    if j is not None:
        seconds = marked_values(rows, j, f"time channel {block['name']!r}", path, re.compile(r"(?!)"),
                                "", comma)
        if np.isnan(seconds).any():
            line = rows[int(np.flatnonzero(np.isnan(seconds))[0])][0]
            raise ContractError(f"time channel {block['name']!r}: an empty cell among its samples",
                                file=path, line=line)
    else:
        rate = block.get("sample rate") or block.get("abtastrate") or ""
        try:
            seconds = np.arange(len(rows)) / float(rate.replace(",", "."))
        except ValueError:
            raise ContractError(f"channel {block['name']!r}: no time channel before it and its "
                                f"sample rate {rate!r} is no number", file=path,
                                line=block["line"]) from None
    t0 = block.get("t0")
    if not t0:
        return seconds
    for form in forms:
        try:
            start = np.datetime64(datetime.strptime(t0, form), "us")
            break
        except ValueError:
            continue
    else:
        raise ContractError(f"channel {block['name']!r}: its T0 {t0!r} is no date and time",
                            file=path, line=block["line"])
    return start + np.round(seconds * 1e6).astype("timedelta64[us]")
