"""A Graphtec midi logger's CSV file (GL220 / GL240 / GL840: its SD card's ``.CSV``, stranger82)
read as its channels (:mod:`.labfile`), as a TwinCAT Scope export is.

The file, as Graphtec's manuals describe it: a header block (``"Model","GL840"``, ``"Title"``,
``"Trigger Time"`` ...), an ``"Amp settings"`` table, a row a channel (``CH``, ``Signal name``,
``Input``, ``Range`` ... and, scaling on, its ``Unit``): the only place the lab's names for the
channels are written; then ``"Data"``: the column row (``NO.``, ``Time``, ``ms``, ``CH1`` ..,
``Alarm1-10`` ..., ``AlarmOut``), a unit row (``degC``, ``V``, a scaled channel's unit), a row a
sample: its number, the logger's date-time (``2027/06/07 07:00:20``, its own clock: no zone)
and milliseconds, values with their sign (``+21.3``).  A broken thermocouple's ``BURNOUT`` and
an input out of range (``+++++++`` / ``-------``) are missing values, said once a channel.
A channel is named by its ``Signal name`` where it has one, else by its ``CH``; the sample
number and the alarm columns are no channels.
"""

from __future__ import annotations

import csv
import re
from datetime import datetime
from pathlib import Path

import numpy as np

from .contract import ContractError
from .encoding import UTF8, text_head, text_lines
from .labfile import Channel, Record, marked_values, text_as_csv, with_unit

_FIRST = re.compile(r'^\ufeff?"?Model"?\s*,\s*"?GL\d')
_MISSING = re.compile(r"BURNOUT|\+{3,}|-{3,}", re.IGNORECASE)   # a broken TC, out of range
_NOT_CHANNELS = re.compile(r"NO\.?|Time|ms|Alarm.*|AlarmOut", re.IGNORECASE)
_TIMES = ("%Y/%m/%d %H:%M:%S", "%Y-%m-%d %H:%M:%S", "%y/%m/%d %H:%M:%S", "%y-%m-%d %H:%M:%S")


def is_graphtec(path) -> bool:
    """``path`` is a text file whose first line is a Graphtec logger's ``"Model","GL..."``."""
    head = text_head(path)
    return head is not None and bool(_FIRST.match(head))


def graphtec_records(path: Path, encoding: str = UTF8) -> list[Record]:
    """The one run of the Graphtec CSV ``path``."""
    return [_record(text_lines(path, encoding), path.stem, path)]


def is_graphtec_text(text: str) -> bool:
    """``text`` (a stream's) is a Graphtec CSV, as :func:`is_graphtec` tells a file."""
    return bool(_FIRST.match(text[:256]))


def graphtec_as_csv(text: str, source: str) -> str:
    """A Graphtec CSV streamed (``monitor.input=-``) as the CSV text its channels are read as
    from a file (:func:`.labfile.text_as_csv`)."""
    return text_as_csv(_record, text, source)


def _record(lines: list[str], label: str, path: Path) -> Record:
    """The file's channels (``lines``: its text), one record."""
    rows = list(csv.reader(lines))
    names = _signal_names(rows)
    data = _line_of(rows, "Data")
    if data is None or data + 2 >= len(rows):
        raise ContractError('no "Data" block (its column row, a unit row, the samples) under the '
                            "logger's header block: the file was cut short?", file=path)
    header = [c.strip() for c in rows[data + 1]]
    units = [c.strip() for c in rows[data + 2]]
    where = {h.lower(): j for j, h in enumerate(header)}
    if "time" not in where:
        raise ContractError("the Data block's column row has no 'Time' column", file=path,
                            line=data + 2)
    body = [(k + 1, r) for k, r in enumerate(rows[data + 3:], start=data + 3) if any(r)]
    if not body:
        raise ContractError('no sample under the "Data" block', file=path, line=data + 3)
    time = _times(body, where["time"], where.get("ms"), path)
    channels = []
    for j, head in enumerate(header):
        if not head or _NOT_CHANNELS.fullmatch(head):
            continue
        name = names.get(head) or head
        unit = units[j] if j < len(units) else ""
        values = marked_values(body, j, f"channel {head!r} ({name})", path, _MISSING, "BURNOUT")
        channels.append(Channel(with_unit(name, unit), values, time, f"channel {head!r}"))
    if not channels:
        raise ContractError("no channel column (CH1 ...) in the Data block", file=path,
                            line=data + 2)
    return Record(label, channels, utc=False)


def _line_of(rows: list[list[str]], key: str) -> int | None:
    return next((k for k, r in enumerate(rows) if len(r) >= 1 and r[0].strip() == key
                 and not any(c.strip() for c in r[1:])), None)


def _signal_names(rows: list[list[str]]) -> dict[str, str]:
    """``{CH: Signal name}`` of the Amp settings table (empty where the file has none)."""
    start = next((k for k, r in enumerate(rows) if r[:2] and r[0].strip() == "CH"
                  and r[1].strip().lower() == "signal name"), None)
    if start is None:
        return {}
    out = {}
    for r in rows[start + 1:]:
        if len(r) < 2 or not r[0].strip():
            break
        if r[1].strip():
            out[r[0].strip()] = r[1].strip()
    return out


def _times(body, j: int, ms: int | None, path: Path) -> np.ndarray:
    out = np.empty(len(body), dtype="datetime64[us]")
    for i, (line, r) in enumerate(body):
        text = r[j].strip().lstrip("'") if j < len(r) else ""
        for form in _TIMES:
            try:
                t = np.datetime64(datetime.strptime(text, form), "us")
                break
            except ValueError:
                continue
        else:
            raise ContractError(f"column 'Time': {text!r} is no date-time of the logger's "
                                "(yyyy/mm/dd hh:mm:ss)", file=path, line=line)
        if ms is not None and ms < len(r) and r[ms].strip():
            try:
                t = t + np.timedelta64(int(round(float(r[ms]) * 1000)), "us")
            except ValueError:
                raise ContractError(f"column 'ms': {r[ms]!r} is no number", file=path,
                                    line=line) from None
        out[i] = t
    return out
