"""A Yokogawa recorder's data converted to ASCII by its viewer (SMARTDAC+ GX / GP / GM through
Universal Viewer, stranger82b), read as its channels (:mod:`.labfile`), as a Graphtec CSV is.

The file, as Yokogawa's Universal Viewer manual describes its ASCII conversion (no file the
viewer wrote was at hand): a header block of ``"key","value"`` rows (``"Universal Viewer"``,
``"Model","GX20"``, ``"Serial No."``, ``"File Name"``, ``"Start Time"`` ...), the channel table
(a row ``"Channel"`` naming each column's channel, ``0001`` or a communication channel
``C001``, a row ``"Tag"``: the lab's names, written here only; ``"Tag Comment"``, ``"Unit"``),
then the data: its column row (``"Date Time"`` or ``"Date","Time"``, then the channels), a row
a sample (``2027/09/06 06:00:20.0``: the recorder's clock, no zone).  ``Burnout`` (a broken
thermocouple) and ``+Over`` / ``-Over`` (out of range) are missing values, said once a channel;
an empty cell is a value not recorded (a communication channel between the writes of a probing
cycle: read as missing, never held).  A channel is named by its tag where it has one, else by
its channel number.  The separator is the first line's (``,``; a PC whose list separator is
``;`` writes ``;`` and decimal commas, ``21,3``; or a tab).
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

_FIRST = re.compile(r'^\ufeff?"?(Universal Viewer|DAQSTANDARD Viewer|DXAdvanced)"?\s*([,;\t])', re.I)
_MISSING = re.compile(r"[+-]?(Burnout|Over|Error|Skip)", re.IGNORECASE)
_TIMES = ("%Y/%m/%d %H:%M:%S.%f", "%Y/%m/%d %H:%M:%S", "%Y-%m-%d %H:%M:%S.%f",
          "%Y-%m-%d %H:%M:%S")
_UNITS = {"c": "degC", "°c": "degC", "degc": "degC", "f": "degF", "°f": "degF"}  # the recorder's


def is_yokogawa(path) -> bool:
    """``path`` is a text file whose first line names Yokogawa's viewer (``"Universal Viewer"``)."""
    head = text_head(path)
    return head is not None and bool(_FIRST.match(head))


def is_yokogawa_text(text: str) -> bool:
    """``text`` (a stream's) is such an export, as :func:`is_yokogawa` tells a file."""
    return bool(_FIRST.match(text[:256]))


def yokogawa_records(path: Path, encoding: str = UTF8) -> list[Record]:
    """The one run of the export ``path``."""
    return [_record(text_lines(path, encoding), path.stem, path)]


def yokogawa_as_csv(text: str, source: str) -> str:
    """An export streamed (``monitor.input=-``) as the CSV text its channels are read as from a
    file (:mod:`.labfile`)."""
    return text_as_csv(_record, text, source)


def _record(lines: list[str], label: str, path: Path) -> Record:
    said = _FIRST.match(lines[0]) if lines else None
    sep = said.group(2) if said else ","
    rows = list(csv.reader(lines, delimiter=sep))
    keyed = {r[0].strip().lower(): r for r in rows if r and r[0].strip()}
    top = next((k for k, r in enumerate(rows) if r and r[0].strip().lower() in ("date time", "date")
                and len(r) > 1), None)
    if top is None or top + 1 >= len(rows):
        raise ContractError("no data (a 'Date Time' column row and samples) under the viewer's "
                            "header block: the file was cut short?", file=path)
    header = [c.strip() for c in rows[top]]
    split = header[0].lower() == "date" and len(header) > 1 and header[1].lower() == "time"
    first = 2 if split else 1
    chans = keyed.get("channel", [])
    tags = {c.strip(): t.strip() for c, t in zip(chans[1:], keyed.get("tag", [])[1:])}
    units = {c.strip(): u.strip() for c, u in zip(chans[1:], keyed.get("unit", [])[1:])}
    body = [(k + 1, r) for k, r in enumerate(rows[top + 1:], start=top + 1) if any(r)]
    if not body:
        raise ContractError("no sample under the data's column row", file=path, line=top + 2)
    time = _times(body, split, path)
    channels = []
    for j, head in enumerate(header[first:], start=first):
        if not head:
            continue
        unit = units.get(head, "")
        name = tags.get(head) or head
        values = marked_values(body, j, f"channel {head!r} ({name})", path, _MISSING, "Burnout",
                               sep == ";")
        channels.append(Channel(with_unit(name, _UNITS.get(unit.lower(), unit)), values, time,
                                f"channel {head!r}"))
    if not channels:
        raise ContractError("no channel column in the data's column row", file=path, line=top + 1)
    return Record(label, channels, utc=False)


def _times(body, split: bool, path: Path) -> np.ndarray:
    out = np.empty(len(body), dtype="datetime64[us]")
    for i, (line, r) in enumerate(body):
        text = (f"{r[0].strip()} {r[1].strip()}" if split and len(r) > 1 else r[0].strip())
        for form in _TIMES:
            try:
                out[i] = np.datetime64(datetime.strptime(text, form), "us")
                break
            except ValueError:
                continue
        else:
            raise ContractError(f"column 'Date Time': {text!r} is no date-time of the recorder's "
                                "(yyyy/mm/dd hh:mm:ss.f)", file=path, line=line)
    return out
