"""The sample period a logger's preamble states above the table (``Abtastrate 15 s``,
``Sample interval: 500 ms``, ``Sampling rate = 2 Hz``, ``Messintervall;00:01:00``).

A file without a time column needs ``data.sample_period_s`` (never a guess); a preamble line
that states it, a keyword and a number WITH its unit, is evidence: ``thermocomp init`` writes it
into the config saying the line, and the reader's refusal quotes it (stranger73: a lab's export
said ``Abtastrate 15 s`` on its first line, and both said only "set data.sample_period_s").
A number without a unit, or lines stating different periods, propose nothing.

A file NAME is weaker evidence (``spindle_60s.csv``: 60 s between rows, or a 60 s run?): the
refusal mentions it as a question and nothing is written (audit98: the name went unmentioned).
Hours are left out: ``lathe_48h.csv`` names a test's length far more often than its period.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from .layout import header_line
from .sniff import head_lines
from .suffixes import is_text

_KEYWORD = (r"\b(?:sampl\w*[ _-]?(?:period|interval|rate|time)|scan[ _-]?(?:rate|interval)|"
            r"log(?:ging)?[ _-]?(?:interval|rate)|abtast\w*|mess(?:intervall|takt|rate)|"
            r"speicher(?:intervall|rate)|aufzeichnungs\w*|intervall?|takt|rate)")
_SEP = r"[\s:=;,\t]*"
_AMOUNT = re.compile(_KEYWORD + _SEP + r"(?P<value>\d+(?:[.,]\d+)?)\s*(?P<unit>ms|s|secs?|seconds?|"
                     r"sekunden?|min|minutes?|minuten?|h|hours?|stunden?|khz|hz)\b(?!\s*/)", re.I)
# (a unit before a slash is a rate's numerator: NI's "Sample rate: 10 S/s" is 10 samples a
# second, not a 10 s period)
_CLOCK = re.compile(_KEYWORD + _SEP + r"(?P<h>\d{1,2}):(?P<m>\d{2}):(?P<s>\d{2}(?:[.,]\d+)?)\b",
                    re.I)
_SECONDS = {"ms": 1e-3, "s": 1.0, "sec": 1.0, "secs": 1.0, "second": 1.0, "seconds": 1.0,
            "sekunde": 1.0, "sekunden": 1.0, "min": 60.0, "minute": 60.0, "minutes": 60.0,
            "minuten": 60.0, "h": 3600.0, "hour": 3600.0, "hours": 3600.0, "stunde": 3600.0,
            "stunden": 3600.0}


@dataclass(frozen=True)
class StatedPeriod:
    seconds: float
    line: int          # 1-based, as an editor shows it
    text: str

    def said(self) -> str:
        return f"line {self.line} says {self.text.strip()!r}"


def _seconds(line: str) -> float | None:
    m = _CLOCK.search(line)
    if m:
        return int(m["h"]) * 3600.0 + int(m["m"]) * 60.0 + float(m["s"].replace(",", "."))
    m = _AMOUNT.search(line)
    if not m:
        return None
    value, unit = float(m["value"].replace(",", ".")), m["unit"].lower()
    if unit.endswith("hz"):
        return (1.0 / (value * (1000.0 if unit == "khz" else 1.0))) if value > 0 else None
    return value * _SECONDS[unit]


def stated_period(path: Path, delimiter: str, encoding: str) -> StatedPeriod | None:
    """The period the lines above the header of text file ``path`` state, None where none
    does, where two lines state different ones, or for a file that is no text."""
    if not is_text(path) or len(delimiter) != 1:
        return None
    lines = head_lines(path, encoding)
    top = header_line(lines, delimiter) or 0
    found = [StatedPeriod(s, k + 1, lines[k]) for k in range(top)
             if (s := _seconds(lines[k])) is not None and s > 0]
    if not found or any(abs(f.seconds - found[0].seconds) > 1e-9 * found[0].seconds
                        for f in found[1:]):
        return None
    return found[0]


# a number with its unit as one token of a file's stem: 'spindle_60s', 'rig-10Hz', 'log 1,5min'
_NAMED = re.compile(r"(?:^|[\s_.-])(?P<token>(?P<value>\d+(?:[.,]\d+)?)\s?(?P<unit>ms|s|secs?|min|"
                    r"khz|hz))(?=$|[\s_.-])", re.I)


def named_period(path: Path) -> tuple[str, float] | None:
    """``(token, seconds)`` of the one period-like token of ``path``'s stem ('60s' in
    ``spindle_60s.csv``), None where none or several differ (a hint only, never adopted)."""
    found = {(m["token"], _seconds(f"rate {m['value']} {m['unit']}"))
             for m in _NAMED.finditer(path.stem)}
    found = {(t, s) for t, s in found if s is not None and s > 0}
    return found.pop() if len({s for _, s in found}) == 1 and len(found) == 1 else None


def period_hint(path: Path, delimiter: str, encoding: str) -> str:
    """``; line 1 says 'Abtastrate 15 s': data.sample_period_s=15`` for a refusal, else the file
    name's question (``; the file name says '60s': if that is the time between rows,
    data.sample_period_s=60``), or ''."""
    said = stated_period(path, delimiter, encoding)
    if said:
        return f"; {said.said()}: data.sample_period_s={said.seconds:g}"
    named = named_period(path)
    return (f"; the file name says {named[0]!r}: if that is the time between rows, "
            f"data.sample_period_s={named[1]:g}" if named else "")
