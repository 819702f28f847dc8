"""Campbell Scientific's framed binary tables TOB3 and TOB2 (extension, lab76): what a CR1000 /
CR3000 / CR6 writes to its card, read as its CSV export (:mod:`.labfile`), as a TOB1 table is
(:mod:`.tob1`, whose data types and FP2 these share).

The layout, as csiio-py 0.4.0 (MIT) and camp2ascii 1.1.1 (GPL-3.0-or-later; read, no code
taken) read it: six ASCII lines, each ending CRLF: the environment (``"TOB3","<station>",
"<logger>","<serial>","<OS>","<program>","<signature>","<created>"``), the table (``"<table>",
"<interval>","<frame bytes>","<table size>","<validation stamp>","<time resolution>",...``:
``"10 MIN"``, ``"Sec100Usec"``), the field names, units, processing and data types; then
frames of ``<frame bytes>`` each, right after the header: a frame header (little-endian: the
seconds since 1990-01-01 and the sub-seconds in the resolution's units; TOB3 then its first
record's number, 12 bytes; TOB2 none, 8 bytes), records at the table's interval, and a 4-byte
footer (little-endian: bits 0-10 an offset, 11 a file mark, 12 a remove (ring) mark, 13 an
empty frame, 14 a minor frame, 16-31 the validation stamp).

- A frame whose stamp is neither the file's nor its ones' complement was written for an earlier
  table (a stale frame left on the card): left out, said.  An empty frame holds no record.
- A minor frame (a frame written before it filled, a *partial frame*): its footer's offset is
  the bytes after its last minor frame, its own footer included; before them one or more minor
  frames, each a frame header, records and a footer whose offset is its own size, walked back
  to the frame's start (camp2ascii's reading; csiio-py reads the first alone).  Sizes that do
  not add up to the frame are refused naming it.
- Each record's time is its frame's (or minor frame's) time + its index x the interval.
- A file mark ends a run: the frames after it are the next run (each a campaign, as a TDMS
  log's groups; ``init`` proposes ``data.roles.campaign=run``), as CardConvert can start a new
  file there.  So does a remove mark (lab77: the card taken out, logging to it stopped until
  one was put in; before, the table went on over the pause): CardConvert's *Use RemoveMarks*
  starts a new file there too; said.  A minor frame's mark ends its last part.
- A ring: a table kept in ring mode on a full card goes on at the card's start, so in file order
  the newest frames come first.  They are put in the logger's order, by their first record
  number (TOB2: their time), said: each frame states both, so the order is read, not guessed
  (refusing would refuse every full card); frames whose records overlap are refused.
- Bytes at the end that make no whole frame (a file copied while the logger wrote it) are
  refused naming the frame: a frame without its footer cannot be told written from stale.
TOB2's 8-byte frame header is the brief's and Campbell's description (no record number);
camp2ascii 1.1.1 takes 4 bytes there, our reading differs.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...base.log import logger
from .campbell import COUNTERS
from .campbell import units as campbell_units
from .contract import ContractError
from .labfile import Channel, Record, with_unit
from .tob1 import EPOCH, HEADER_LINES, channel_values, header_lines, record_type, tob1_records, tob_format

FRAME_HEAD = {"TOB3": 12, "TOB2": 8}      # seconds, sub-seconds (, TOB3: the first record)
FOOTER = 4
FILE_MARK, REMOVE_MARK, EMPTY, MINOR = 1 << 11, 1 << 12, 1 << 13, 1 << 14
OFFSET = 0x7FF
# a frame time resolution -> nanoseconds per sub-second unit
RESOLUTION_NS = {"SECMSEC": 1_000_000, "SEC100USEC": 100_000, "SEC10USEC": 10_000,
                 "SECUSEC": 1_000, "SECNSEC": 1}
# an interval's unit (line 2: '10 MIN', '100 MSEC') -> nanoseconds
INTERVAL_NS = {"NSEC": 1, "USEC": 1_000, "MSEC": 1_000_000, "SEC": 10**9, "MIN": 60 * 10**9,
               "HR": 3600 * 10**9, "HOUR": 3600 * 10**9, "DAY": 86400 * 10**9}
SHOWN = 6                                  # frames named in a message


def tob_records(path: Path) -> list[Record]:
    """The runs of a Campbell binary table: a TOB1 file's one, a TOB2 / TOB3 file's frames'."""
    return tob1_records(path) if tob_format(path) == "TOB1" else frame_records(path)


def frame_records(path: Path) -> list[Record]:
    """The runs of the TOB2 / TOB3 file ``path`` (one, or one per file mark), each record timed
    by its frame's time and the table's interval, in the logger's order."""
    path = Path(path)
    kind = tob_format(path)
    data = path.read_bytes()
    lines, start = header_lines(data, path, HEADER_LINES + 1)
    table, (names, units, _, types) = lines[1], lines[2:]
    record = record_type(path, names, units, types)
    size, stamp, resolution, interval = _table(path, table)
    head = FRAME_HEAD[kind]
    per_frame = (size - head - FOOTER) // record.itemsize
    if per_frame < 1:
        raise ContractError(f"line 2: frames of {size} bytes hold no record of {record.itemsize} "
                            "bytes (line 6's data types)", file=path)
    body = data[start:]
    frames, cut = divmod(len(body), size)
    if cut:
        raise ContractError(f"frame {frames + 1} (from byte {start + frames * size}) is cut short: "
                            f"{cut} of its {size} bytes, no footer to tell it written or stale (a "
                            "file copied while the logger wrote it?): cut the file after frame "
                            f"{frames}", file=path)
    pieces, stale = [], []
    for i in range(frames):
        frame = body[i * size:(i + 1) * size]
        word = int.from_bytes(frame[-FOOTER:], "little")
        if (word >> 16) not in (stamp, stamp ^ 0xFFFF):
            stale.append(i + 1)
        elif not word & EMPTY:
            parts = _minor(path, frame, i + 1, word, head, stamp) if word & MINOR else [frame]
            # (lab77) a mark ends the frame's last part, not each minor frame of it
            pieces += [(i + 1, p, _mark(word) if k == len(parts) - 1 else "")
                       for k, p in enumerate(parts)]
    if stale:
        logger.warning(f"{path}: {len(stale)} of {frames} frames ({_frames(stale)}) carry another "
                       f"validation stamp than the file's {stamp} (frames of an earlier table "
                       "left on the card): left out")
    pieces = _in_order(path, kind, pieces, record, head, resolution, interval)
    return _runs(path, names, campbell_units(units), types, pieces, record, head, interval)


def _table(path: Path, table: list[str]) -> tuple[int, int, int, int]:
    """``(frame bytes, validation stamp, ns per sub-second unit, interval ns)`` of line 2."""
    try:
        size, stamp = int(table[2]), int(table[4])
        resolution = RESOLUTION_NS[table[5].strip().upper()]
        amount, unit = table[1].split()
        interval = round(float(amount) * INTERVAL_NS[unit.upper()])
    except (IndexError, ValueError, KeyError):
        raise ContractError(f"line 2 ({', '.join(table[:6])}) gives no table interval, frame "
                            "size, validation stamp and time resolution as a TOB3 file's does "
                            f"(resolutions read: {', '.join(RESOLUTION_NS)})", file=path) from None
    if interval <= 0:
        raise ContractError(f"line 2: interval {table[1]!r}: an event table's records are not "
                            "timed at an interval, and its frames time only their first: not "
                            "read", file=path)
    return size, stamp, resolution, interval


def _minor(path: Path, frame: bytes, number: int, word: int, head: int, stamp: int) -> list[bytes]:
    """The minor frames of a frame written before it filled, walked back from its footer."""
    end, parts = len(frame) - (word & OFFSET), []
    while end > 0:
        footer = int.from_bytes(frame[end - FOOTER:end], "little") if end >= FOOTER else 0
        length = footer & OFFSET
        if length < head + FOOTER or length > end or (footer >> 16) not in (stamp, stamp ^ 0xFFFF):
            raise ContractError(f"frame {number} is a minor frame whose parts do not add up to it "
                                f"(at its byte {end}: a footer giving {length} bytes): a frame "
                                "written in part and broken; not read", file=path)
        parts.insert(0, frame[end - length:end])
        end -= length
    return parts


def _start(piece: bytes, resolution: int) -> tuple[int, int | None]:
    """``(ns since 1990, first record number or None)`` of a frame's header."""
    seconds, sub = (int.from_bytes(piece[k:k + 4], "little") for k in (0, 4))
    number = int.from_bytes(piece[8:12], "little") if len(piece) >= 12 else None
    return seconds * 10**9 + sub * resolution, number


def _in_order(path: Path, kind: str, pieces: list, record: np.dtype, head: int, resolution: int,
              interval: int) -> list:
    """``[(frame, first ns, records, file mark)]`` in the logger's order (a ring: sorted, said)."""
    out = []
    for number, piece, mark in pieces:
        count = (len(piece) - head - FOOTER) // record.itemsize
        first, rec = _start(piece, resolution)
        key = rec if kind == "TOB3" else first
        rows = np.frombuffer(piece, record, count=count, offset=head)
        out.append((key, number, first, rows, mark))
    keys = [p[0] for p in out]
    if keys != sorted(keys):
        back = next(i for i in range(1, len(keys)) if keys[i] < keys[i - 1])
        logger.warning(f"{path}: frame {out[back][1]} follows frame {out[back - 1][1]} in the file "
                       f"but comes before it ({'record' if kind == 'TOB3' else 'time'} "
                       f"{_said(out[back], kind)} < {_said(out[back - 1], kind)}): the table wrapped "
                       "around its ring on the card; its frames read in the logger's order, by "
                       + ("their record numbers" if kind == "TOB3" else "their times"))
        out.sort(key=lambda p: (p[0], p[1]))
    for prev, this in zip(out, out[1:]):
        ends = prev[2] + (len(prev[3]) - 1) * interval
        if this[2] <= ends:
            raise ContractError(f"frames {prev[1]} and {this[1]} overlap in time (up to "
                                f"{_when(ends)}, from {_when(this[2])}): two passes of the ring "
                                "or a clock set back; not read", file=path)
    return [(number, first, rows, mark) for _, number, first, rows, mark in out]


def _mark(word: int) -> str:
    """The mark a frame's footer ``word`` sets: ``'file'``, ``'remove'`` or ``''``."""
    return "file" if word & FILE_MARK else "remove" if word & REMOVE_MARK else ""


def _runs(path: Path, names, units, types, pieces: list, record: np.dtype, head: int,
          interval: int) -> list[Record]:
    """The frames' records as runs, a file mark or a remove mark closing each."""
    runs, current, removed = [], [], []
    for piece in pieces:
        current.append(piece)
        if piece[3]:
            runs.append(current)
            current = []
            if piece[3] == "remove":
                removed.append(piece[0])
    runs = [r for r in [*runs, current] if any(len(p[2]) for p in r)]
    if removed and len(runs) > 1:
        logger.warning(f"{path}: a remove mark (the card taken out, logging to it stopped) in frame "
                    f"{_frames(removed)}: the records after it are the next run, as after a file "
                    "mark (CardConvert's 'Use RemoveMarks' starts a new file there)")
    if not runs:
        raise ContractError("no frame of the file's validation stamp holds a record", file=path)
    out = []
    for k, run in enumerate(runs):
        time = EPOCH + np.concatenate([first + interval * np.arange(len(rows), dtype=np.int64)
                                       for _, first, rows, _ in run]).astype("timedelta64[ns]")
        table = np.concatenate([rows for _, _, rows, _ in run])
        channels = [Channel(with_unit(name.strip(), unit), channel_values(table, i, kind), time,
                            f"field {i + 1} {name.strip()!r} ({kind.strip()})")
                    for i, (name, unit, kind) in enumerate(zip(names, units, types))
                    if name.strip().lower() not in COUNTERS]
        label = path.stem if len(runs) == 1 else f"{path.stem}_{k + 1}"
        out.append(Record(label, channels, utc=False))
    return out


def _frames(numbers: list[int]) -> str:
    return ", ".join(map(str, numbers[:SHOWN])) + (", ..." if len(numbers) > SHOWN else "")


def _when(ns: int) -> str:
    return str(EPOCH + np.timedelta64(ns, "ns"))[:23]


def _said(piece: tuple, kind: str) -> str:
    return str(piece[0]) if kind == "TOB3" else _when(piece[2])
