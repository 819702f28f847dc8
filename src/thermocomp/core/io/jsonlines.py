"""JSON Lines (``.jsonl``, ``.ndjson``: one JSON object a line, as an MQTT bridge or an IoT
gateway writes its messages) read as its CSV export: each object flattened (a nested object's
keys joined to its own with ``.``: ``{"temps": {"drum_K": 296.1}}`` is the column
``temps.drum_K``), written into a temporary UTF-8 CSV file that the CSV reader reads (as a
workbook's sheet, :mod:`.workbook`), so that roles, units and every check work as on a CSV file.

The columns are every key met, in the order met; a key a message lacks is an empty cell (a value
not measured).  ``true`` / ``false`` are written so (read as 1 / 0, an on/off state), ``null`` empty, a list
as its JSON text.  A line that is no JSON object is refused with its line; an empty line is
skipped.  A message about a row of the CSV file names the file's line instead.
"""

from __future__ import annotations

import csv
import json
import re
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from .contract import ContractError
from .converted import named_as
from .encoding import UTF8

JSON_LINES_SUFFIXES = (".jsonl", ".ndjson")
_LINE = re.compile(r"\bline (\d+)")


def is_json_lines(path) -> bool:
    return Path(path).suffix.lower() in JSON_LINES_SUFFIXES


def flat(message: dict, prefix: str = "") -> dict:
    """``message``'s values by their keys joined with ``.`` (a nested object's)."""
    out = {}
    for key, value in message.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            out.update(flat(value, name + "."))
        else:
            out[name] = value
    return out


def _cell(value) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):         # a flag's words, read as 1 / 0 and proposed a state
        return "true" if value else "false"
    if isinstance(value, (list, dict)):
        return json.dumps(value)
    if isinstance(value, float):
        return repr(value)
    return str(value)


def messages(path: Path, rows: int | None = None) -> tuple[list[str], list[dict], list[int]]:
    """The keys met (in order), the flattened messages and each one's line (1-based) of the
    file's first ``rows`` messages (None: all)."""
    keys: dict[str, None] = {}
    found, lines = [], []
    with open(path, encoding="utf-8-sig") as f:
        for number, line in enumerate(f, 1):
            if not line.strip():
                continue
            try:
                message = json.loads(line)
            except json.JSONDecodeError as exc:
                raise ContractError(f"no JSON object ({exc.msg}, character {exc.pos + 1}): a JSON "
                                    "Lines file holds one object a line", file=path, line=number) from None
            if not isinstance(message, dict):
                raise ContractError(f"a JSON {type(message).__name__}, not an object: a JSON Lines "
                                    "file holds one object a line", file=path, line=number)
            message = flat(message)
            keys.update(dict.fromkeys(message))
            found.append(message)
            lines.append(number)
            if rows is not None and len(found) >= rows:
                break
    if not found:
        raise ContractError("no JSON object in the file", file=path)
    return list(keys), found, lines


@contextmanager
def json_lines_as_csv(path: Path, rows: int | None = None) -> Iterator[Path]:
    """The JSON Lines file ``path`` as a temporary UTF-8 CSV file (a header of the keys, a row a
    message; its first ``rows`` only, where given), removed after; a :class:`ContractError` or a
    warning about it names ``path`` and the file's line."""
    keys, found, lines = messages(path, rows)
    with tempfile.TemporaryDirectory(prefix="thermocomp-jsonl-") as tmp:
        out = Path(tmp) / (path.stem + ".csv")
        with open(out, "w", encoding=UTF8, newline="") as f:
            writer = csv.writer(f, lineterminator="\n")
            writer.writerow(keys)
            for message in found:
                writer.writerow([_cell(message.get(k)) for k in keys])
        file_line = {i + 2: n for i, n in enumerate(lines)}      # the CSV's line -> the file's
        with named_as(out, str(path), lambda exc: _located(exc, out, path, file_line),
                      line_of=lambda n: file_line.get(n, n)):
            yield out


def _located(exc: ContractError, temp: Path, path: Path, file_line: dict) -> ContractError:
    if exc.file is None or Path(exc.file) != temp:
        return exc
    reason = _LINE.sub(lambda m: f"line {file_line.get(int(m.group(1)), m.group(1))}",
                       exc.reason.replace(str(temp), str(path)))
    return ContractError(reason, file=path, column=exc.column, row=exc.row,
                         line=file_line.get(exc.line, exc.line) if exc.line else exc.line,
                         sheet=exc.sheet)
