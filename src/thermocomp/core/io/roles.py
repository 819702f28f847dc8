"""``data.roles``: a lab's own headers read as contract columns, by glob patterns.

``data.roles.error``/``state``/``ambient``/``ignore`` are fnmatch patterns over a file's headers
(with or without their unit); ``data.roles.time`` names the time column (``auto``: a header such
as ``time``, ``t(s)``, ``時間(s)``, ``Zeit``, or a column of ISO 8601 timestamps). Every other
numeric column takes the role its unit says (:func:`.units.role_by_unit`, the rule ``init``
proposes by: ``dY [µm]`` an error, ``Hydraulics on [-]`` a state), else is a temperature. The
contract name is the role's prefix and the header without its unit (``ch1(um)`` -> ``E_ch1``,
``t1(°C)`` -> ``T_t1``, ``spindle(RPM)`` -> ``S_spindle``; the ambient sensor ``T_amb``, or
``T_amb_<name>`` when there are several), and a unit that is not the contract's (mm, K, °F, ms,
min) is converted. ``data.columns`` (an explicit mapping) wins. Without any role set, headers
are read as before: contract names, or mapped by ``data.columns``. ``data.roles.campaign``
(extension) names the one column numbering the runs of a long file: read as text under
:data:`RUN` and split into campaigns by :mod:`.runs`, never a temperature.
"""

from __future__ import annotations

import fnmatch
import functools
import re
from collections import Counter
from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ...base.errors import config_file_form, listed
from ...base.log import logger
from ..metrics import angular
from . import campbell
from .contract import TIME, ContractError, role
from .options import AUTO, ROLE_PATTERNS, RUN_ROLE, _roles
from .separators import number, reads_as_number
from .timestamps import (
    CLOCK,
    CLOCK_HEADERS,
    DATE,
    ELAPSED_HEADERS,
    EXCEL_DAYS,
    OF_DAY_HEADERS,
    TIME_OF_DAY,
    looks_like_timestamp,
)
from .units import (
    AMBIGUOUS,
    LETTER_UNITS,
    NOTE,
    STATE_UNITS,
    UNITS,
    VOLTS,
    ambiguity,
    bracket_reading,
    is_known_unit,
    note_ambiguity,
    role_by_unit,
)

_UNIT = re.compile(r"^(.*?)\s*[\[(]([^\[\]()]*)[\])]\s*$")
# a unit in brackets followed by a note in brackets, a sign convention ('dX [mm] (+ = Werkzeug
# weg vom Werkstück)'): the unit is the first (the note, a last bracket, read as the unit was refused)
_NOTED = re.compile(r"^(.*?)\s*[\[(]([^\[\]()]*)[\])]\s*[\[(]([^\[\]()]*)[\])]\s*$")
# ISO 80000's "quantity / unit" (``delta L / um``, ``Zeit / s``); without spaces round the slash
# (``dX/um``) only a unit of :data:`UNITS`, so that ``Datum/Zeit`` or ``on/off`` stay names
_SLASHED = re.compile(r"^(.*?\S)(\s*)/(\s*)(\S+)$")
_IN_UNIT = re.compile(r"^(.*?\S)\s+(?:in|en)\s+(\S+)$", re.IGNORECASE)   # 'dX in µm' (a known unit)
# a unit as the header's last word or '_' suffix ('dZ um', 'Spindel °C', 'dX_um', 'time_s'):
# only a unit of two or more characters or a symbol (a single letter is a name as often: 'Zone
# C', 'Sensor K'), a time's only after a time header ('T_min' is no temperature in minutes)
_LAST_WORD = re.compile(r"^(.*?\S)\s+(\S+)$")
_SUFFIX = re.compile(r"^(.*?[^\s_])_([^\s_]+)$")
_UNSAFE = re.compile(r"[^\w.\-]+")
TIME_HEADERS = frozenset({"time", "t", "ts", "zeit", "時間", "时间", "timestamp", "datetime", "date_time",
                          "zeitstempel", "temps", "tiempo", "tempo", "seconds", "timestamp_start",
                          "tmstamp",     # (a Campbell Scientific logger's TOACI1 file, lab74)
                          *ELAPSED_HEADERS, *OF_DAY_HEADERS, *CLOCK_HEADERS})
# HBM catman's time channel, one per rate group: 'Zeit  1 - Standardmessrate', 'Time  2 - 10 Hz'
_RATE_GROUP_TIME = re.compile(r"(?i)(?:time|zeit|temps|tiempo|tempo)\s+\d+\s+-\s+\S.*")
TWIN = "twin"         # a header written twice (:mod:`.twins`): left out, or refused as unnamed
RUN = " campaign"     # data.roles.campaign's column as read: no contract column has this name
LOGGER = "DAQ's own"  # a column a Keysight DAQ writes of its own scans (:func:`logger_columns`)
# a Keysight DAQ's export (BenchLink Data Logger's, the DAQ970A's): ``Alarm <channel>`` beside
# each channel's ``<channel> <label> (<unit>)`` (0, or 1 / 2: below its LO / above its HI
# limit), and the sweep number ``Scan``
_ALARM = re.compile(r"^\s*Alarm\s+(\d{3,4})\s*$", re.IGNORECASE)
_SCAN = frozenset({"scan", "scan number", "sweep", "sweep number"})
# an AmeriFlux table's averaging interval (a Campbell Scientific logger's flux program writes
# both): its start is the time, its end no measurement
_INTERVAL = ("timestamp_start", "timestamp_end")
PREFIX = {"error": "E_", "state": "S_", "temperature": "T_", "ambient": "T_"}


@dataclass
class Naming:
    """What :func:`naming` decided for one file's headers."""

    names: dict[str, str] = field(default_factory=dict)    # raw -> contract (ignored: absent)
    scales: dict[str, tuple[float, float]] = field(default_factory=dict)  # contract -> to its unit
    roles: dict[str, str] = field(default_factory=dict)    # raw -> why (role or "data.columns")
    # raw -> contract: a temperature header whose bracket is a note, no unit (notes100), said
    # by the reader once its column is read (:func:`said_notes`), not of an all-empty one
    noted: dict[str, str] = field(default_factory=dict)


@functools.lru_cache(maxsize=8192)     # pure; a wide record asks it ~5 times per header per read
def split_unit(header: str) -> tuple[str, str | None]:
    """``('t1', '°C')`` for ``t1(°C)``, ``t1 [°C]``, ``t1 / °C`` or ``t1 in °C`` (and ``('dX',
    'mm')`` for ``dX [mm] (+ = away from the spindle)``, a note after the unit); ``(header,
    None)`` without a unit."""
    match = _NOTED.match(header.strip())
    if match and match.group(1).strip() and _a_unit(match.group(2)) and not _a_unit(match.group(3)):
        return match.group(1).strip(), match.group(2).strip()     # (the note left out)
    match = _UNIT.match(header.strip())
    if match and match.group(1).strip():
        return match.group(1).strip(), match.group(2).strip()
    match = _SLASHED.match(header.strip())
    if match and ((match.group(2) and match.group(3)) or _known_unit(match.group(4))):
        return match.group(1).strip(), match.group(4)
    match = _IN_UNIT.match(header.strip())
    if match and _known_unit(match.group(2)):
        return match.group(1).strip(), match.group(2)
    match = _bare_unit(header.strip())
    if match:
        return match
    return header.strip(), None


def time_unit(header: str | None, opts) -> str | None:
    """The unit of a time column of numbers: ``data.units``' (``opts.units``), else its
    header's (:func:`split_unit`); None where neither gives one (or no header)."""
    return None if header is None else opts.units.get(header, split_unit(header)[1])


def _bare_unit(header: str) -> tuple[str, str] | None:
    """``('dZ', 'um')`` for a unit written as the last word (``dZ um``) or, in a header that is
    no contract name (``T_spindle_degC`` keeps its name), as an ``_`` suffix (``dZ_um``)."""
    alone = _UNIT.fullmatch(header)
    if alone and not alone.group(1).strip():
        return "", alone.group(2).strip()     # a unit alone ('[°C]'): no name
    for pattern in (_LAST_WORD, _SUFFIX):
        match = pattern.match(header)
        if match is None or (pattern is _SUFFIX and role(header) is not None):
            continue
        base, unit = match.group(1).strip(), match.group(2)
        known = unit.lower()
        if ((len(known) > 1 or not known.isalpha())
                and (any(known in UNITS[k] for k in ("E", "T", "angle")) or known in STATE_UNITS)
                or base.lower() in TIME_HEADERS and known in UNITS["time"]):
            return base, unit
    return None


# a header written twice (:mod:`.twins`): the k-th occurrence read as '<name>#<k>' before its
# unit, one holding the first's values marked left out with the column it repeats
_TWIN_LEFT_OUT = re.compile(r"^(.*) \[= column (\d+)\]$")
_OCCURRENCE = re.compile(r"#(\d+)$")


def left_out(header: str) -> int | None:
    """The (1-based) column a twin left out repeats; None for any other header."""
    match = _TWIN_LEFT_OUT.match(header)
    return int(match.group(2)) if match else None


def first_of(header: Sequence[str], twin: str) -> int | None:
    """The index in ``header`` of the first occurrence of a twin read as ``<name>#<k>``; None
    for any other header (a lab's own ``Kanal#2`` beside no ``Kanal``)."""
    base = split_unit(twin)[0]
    if left_out(twin) is not None or not _OCCURRENCE.search(base) or not twin.startswith(base):
        return None
    original = _OCCURRENCE.sub("", base) + twin[len(base):]
    return header.index(original) if original in header else None


def named_as_time(header: str) -> bool:
    """A header naming the time (:data:`TIME_HEADERS`, or catman's time channel of a rate group,
    ``Zeit  1 - Standardmessrate``) without another quantity's unit: ``T [°C]`` is a
    temperature, not the time (``Zeit [hh:mm:ss]``, ``timestamp (UTC)`` are times)."""
    base, unit = split_unit(header)
    other = unit is not None and unit.lower().replace(" ", "") not in UNITS["time"] and (
        any(unit.lower() in UNITS[k] for k in ("E", "T", "angle")) or unit.lower() in STATE_UNITS)
    named = base.lower() in TIME_HEADERS or bool(_RATE_GROUP_TIME.fullmatch(base.strip()))
    return named and not other


# a column of dates a spreadsheet shows as numbers: 'Date', 'Datum', 'Fecha' (or a time's name)
DATE_HEADERS = frozenset({"date", "datum", "fecha", "date_time", "datetime", "excel date"})


def excel_days_header(headers, first: Mapping, units: Mapping, decimal: str = ".") -> str | None:
    """The header of a column of Excel's serial day numbers (days since 1899-12-30, a date cell
    saved as a number): named as a date or the time (:data:`DATE_HEADERS`, :func:`named_as_time`),
    no unit (in the header or ``units``), its first cell a number of :data:`.timestamps.EXCEL_DAYS`
    (1954 .. 2119); None where no header is (stranger64: a lab's ``Date`` of 46447.0006944 was
    no time at all, and the refusal said to set ``data.sample_period_s``)."""
    for h in headers:
        base, unit = split_unit(h)
        if unit is not None or h in units or not (base.strip().lower() in DATE_HEADERS
                                                   or named_as_time(h)):
            continue
        if base.strip().lower() in OF_DAY_HEADERS:    # (data89b) 77400 s is 21:30, no date
            continue
        value = number(str(first.get(h) or ""), decimal)
        if value is not None and EXCEL_DAYS[0] <= value <= EXCEL_DAYS[1]:
            return h
    return None


def _letter_unit(header: str, cell, decimal: str) -> tuple[str, str] | None:
    """``('T1', 'K')`` for a temperature's ``T1 K`` (or ``T1_K``, a gateway's tag) where its first value
    ``cell`` reads in the letter's unit (:data:`LETTER_UNITS`: 293 is kelvin, 20 is not), the
    name before it two characters or more (``T K`` reads as a name as often); else None."""
    match = _LAST_WORD.match(header.strip())
    if match is None and role(header.strip()) is None:      # a gateway's 'drum_K' (no contract name)
        match = _SUFFIX.match(header.strip())
    if match is None or len(match.group(1)) < 2:
        return None
    lowest, value = LETTER_UNITS.get(match.group(2).lower()), number(cell or "", decimal)
    return None if lowest is None or value is None or value < lowest else (
        match.group(1).strip(), match.group(2))


def _known_unit(unit: str) -> bool:
    return any(unit.lower() in known for known in UNITS.values())


def _a_unit(text: str) -> bool:
    """``text`` (in brackets) is a unit the reader knows, a state's too (``rpm``)."""
    unit = text.strip().lower().replace(" ", "")
    return _known_unit(unit) or unit in STATE_UNITS


def active(roles: Mapping) -> bool:
    """Any role pattern (or an explicit time column) set: headers are named by role."""
    return (any(roles.get(k) for k in ROLE_PATTERNS) or roles.get("time", AUTO) != AUTO
            or bool(roles.get(RUN_ROLE)))


def contract_columns(headers: Sequence[str], roles: Mapping | None = None,
                     columns: Mapping | None = None, first: Mapping | None = None) -> dict[str, str]:
    """The contract name of each of a file's ``headers`` (raw -> contract; ignored ones left out).

    Parameters
    ----------
    headers : sequence of str
        The file's own column names.
    roles : mapping, optional
        ``data.roles`` (``error``, ``state``, ``ambient``, ``ignore``: glob patterns; ``time``).
    columns : mapping, optional
        ``data.columns``, raw -> contract name; wins over ``roles``.
    first : mapping, optional
        A header's first cell as text: a non-numeric one is not a temperature, an ISO 8601
        timestamp may be the time.

    Raises
    ------
    ContractError
        Listing, in one message, every column that is unmapped, not numeric or ambiguous.
    """
    return naming(headers, _roles({"roles": roles or {}}), dict(columns or {}), first).names


def naming(headers: Sequence[str], roles: Mapping, columns: Mapping, first: Mapping | None = None,
           decimal: str = ".", file: Path | None = None, units: Mapping | None = None) -> Naming:
    """:func:`contract_columns` with the unit conversions (``roles`` as ``ReadOptions.roles``;
    ``units``: ``data.units``, header -> unit, for a header that does not say it)."""
    first, units = first or {}, units or {}
    out, problems = Naming(), []
    every = headers
    out.roles.update({h: TWIN for h in headers if left_out(h) is not None})
    headers = [h for h in headers if h not in out.roles]     # (a channel exported twice: one)
    columns = by_header(headers, columns)
    by_role = active(roles)
    problems += [f"data.units names {h!r}, no header" for h in units if h not in headers]
    time_header, clock_header = (_time_header(headers, roles, columns, first, problems)
                                 + [None, None])[:2]
    ambient = [h for h in headers if h not in columns and matching_roles(h, roles) == ["ambient"]]
    bookkeeping = logger_columns(headers)
    short = shortened(headers, columns)
    run = _run_header(headers, roles, columns, problems)
    in_units: set[str] = set()      # the names before a unit derived so far (:func:`again_in`)
    noted: list[str] = []           # temperature headers whose bracket is a note, no unit
    for header in headers:
        base, unit = split_unit(header)
        unit = units.get(header, unit)
        if header == time_header:    # (one without a header too: pandas' index of timestamps)
            out.names[header], out.roles[header] = TIME, "time" if clock_header is None else "date"
            _scale(out, TIME, "time", unit, header, problems, first.get(header), decimal)
            continue
        if not header.strip() and header not in columns:
            out.roles[header] = "empty"      # Excel's trailing separator: the reader checks it is
            continue
        if header in columns:
            out.names[header], out.roles[header] = columns[header], "data.columns"
            _mapped_scale(out, columns[header], unit)
            continue
        if header == clock_header:             # joined to the date into one timestamp
            out.names[header], out.roles[header] = CLOCK, "time of day"
            continue
        hits = matching_roles(header, roles)
        if header == run:
            if hits:
                problems.append(f"{header!r} is matched by data.roles.{RUN_ROLE} and "
                                + " and ".join(f"data.roles.{k}" for k in hits))
            out.names[header], out.roles[header] = RUN, RUN_ROLE
            continue
        if len(hits) > 1:
            problems.append(f"{header!r} is matched by {' and '.join(f'data.roles.{k}' for k in hits)}")
            continue
        kind = hits[0] if hits else None
        if kind == "ignore":
            continue
        if kind is not None and header not in units:
            unit = pattern_unit(header, roles, kind) or unit
        if kind is None and header in bookkeeping:   # (keysight70: read as temperatures, silently)
            out.roles[header] = LOGGER
            continue
        # a contract name with a unit ('E_S1x1d1_B01_B02 [mm]', a lab's software writing its
        # unit): read as the name, converted, with or without data.roles (volstranger66: a
        # contract file's such header was refused, 'map it with data.columns', one per column)
        if kind is None and unit and role(base) in ("E", "S", "T") and (
                by_role or (not _UNSAFE.search(base) and ".." not in base)):
            kind = {"E": "error", "S": "state", "T": "temperature"}[role(base)]
        twin = (first_of(every, header) if kind is None and (not by_role or role(header))
                else None)
        if twin is not None:       # (T1;T1, different values: the second read as 'T1#2')
            problems.append(f"columns {twin + 1} and {every.index(header) + 1} have the same "
                            f"header {every[twin]!r}, different values: name the second, "
                            f"data.columns={{{header!r}: {PREFIX['temperature']}<name>}}")
            out.roles[header] = TWIN
            continue
        if kind is None and (role(header) is not None or not by_role):
            out.names[header], out.roles[header] = header, "contract"   # its own name, or unmapped
            if role(header) is None:
                out.roles[header] = "unmapped"
                problems.append(f"{header!r} has no role" + (     # (lab75: W/m^2, m/s)
                    f" (unit {unit!r}: no temperature's, displacement's nor machine state's)"
                    if unit and not is_known_unit(unit) else ""))
            elif header in units:
                _scale(out, header, role(header) if role(header) != "S" else None, unit, header,
                       problems, None, decimal)
            continue
        if kind is None:
            if not reads_as_number(first.get(header), decimal):
                problems.append(f"{header!r} is not numeric ({first.get(header)!r})")
                continue
            # no pattern names it: its unit's role, as `init` proposes it (µm: an error, rpm or
            # [-]: a state; a length named by its axis alone is listed), else a temperature
            kind = role_by_unit(base, unit) or "temperature"
            if kind == AMBIGUOUS:
                problems.append(ambiguity(header, base))
                continue
        if kind in ("temperature", "ambient") and header not in units:
            reading = bracket_reading(unit)       # (notes100: 'T1 (front)', a note, no unit)
            if reading == AMBIGUOUS:
                problems.append(note_ambiguity(header, base, unit))
                continue
            if reading == NOTE:
                base, unit = header.strip(), None
                noted.append(header)
        if unit is None and kind in ("temperature", "ambient"):
            base, unit = _letter_unit(header, first.get(header), decimal) or (base, unit)
        if unit is not None:
            base = again_in(base, in_units)
        name = _derived(kind, base, len(ambient) > 1, header in short)
        tilt = kind == "error" and _angle(unit)
        if tilt and not angular(name):
            if role(base) == "E":      # the lab's own contract name: renamed, it would not be
                problems.append(f"{header!r}: unit {unit!r} is an angle, its name a length's "
                                f"(µm): name it as a tilt, data.columns={{{header!r}: "
                                f"E_tilt_{name[2:]}}}, or by ISO 230-1 (E_AX ... E_CZ)")
                continue
            name = f"E_tilt_{name[2:]}"     # (its unit, µm/m, said by its name: core.metrics)
        if not _UNSAFE.sub("", base):
            problems.append(f"{header!r} gives no name" + ("" if base else " (a unit alone: name "
                                                           "it with data.columns)"))
            continue
        out.names[header], out.roles[header] = name, kind
        _scale(out, name, ("angle" if tilt else "E") if kind == "error" else
               "T" if kind != "state" else None, unit, header, problems, None, decimal)
    _duplicates(out.names, problems, by_role)
    if problems:
        raise _refusal(problems, by_role, out.names, out.roles, file)
    out.noted = {header: out.names[header] for header in noted}
    return out


def said_notes(noted: Mapping[str, str], empty: Collection[str] = ()) -> None:
    """Say that each header of ``noted`` (:attr:`Naming.noted`) is named with its bracket, but
    those whose column (contract name) is in ``empty``: an all-empty column is refused as such,
    and the note said before the refusal was of no use (data101: 'Reserve (leer)', read as
    ``T_Reserve_leer``, then refused because every cell is empty)."""
    for header, name in noted.items():
        if name not in empty:
            logger.info("%s: the bracket read as part of the name, no unit: °C assumed (%s)",
                        repr(header), name)


def again_in(base: str, taken: set[str]) -> str:
    """(twins98) ``base``, the name before a header's unit, numbered ``<base>#<k>`` where an
    earlier header read gave it already (``taken``, to which the name given is added): one name
    written in two units, ``Temp [°C]`` and ``Temp [K]`` (two sensors, or one logged twice), is
    read as ``T_Temp`` and ``T_Temp_2``, as the second of a header written twice
    (:func:`.twins.occurrences`, ``Temp#2 [°C]``) is; each header keeps its text, by which
    ``data.columns``, ``data.roles`` and the exported ``stream.c`` address it."""
    name, k = base, 1
    while name in taken:
        k += 1
        name = f"{base}#{k}"
    taken.add(name)
    return name


def logger_columns(headers: Sequence[str]) -> frozenset:
    """The headers of a logger's export that are its bookkeeping, no measurement: a Keysight
    DAQ's ``Alarm <channel>`` beside each channel's column (``Alarm 101`` beside ``101 <Air>
    (C)``) and, in a file with such columns, the sweep number ``Scan``; an AmeriFlux table's
    ``TIMESTAMP_END`` beside its ``TIMESTAMP_START`` (the time; realexport73); a Campbell
    Scientific logger's ``RECORD`` (``RECNBR``) beside its ``TIMESTAMP`` (``TMSTAMP``; lab74).
    Left out by every reader of the headers (a role pattern matching one still gives it that
    role)."""
    bare = {h.strip().lower(): h for h in headers}
    ends = {bare[_INTERVAL[1]]} if all(k in bare for k in _INTERVAL) else set()
    if any(k in bare for k in campbell.TIME_HEADERS):
        ends |= {bare[k] for k in campbell.COUNTERS if k in bare}
    channels = {h.strip().split(" ", 1)[0] for h in headers}
    alarms = {h for h in headers if (m := _ALARM.match(h)) and m[1] in channels}
    if not alarms:
        return frozenset(ends)
    return frozenset(ends | alarms | {h for h in headers if h.strip().lower() in _SCAN})


def by_header(headers: Sequence[str], columns: Mapping) -> dict:
    """``data.columns`` keyed by the file's headers: a key that is no header but the name of
    exactly one header without its unit (``T Wasser`` for ``T Wasser [°C]``, the unit from a
    unit row under the names, as the file's first row shows it) is that header's, as a
    ``data.roles`` pattern matches it (stranger65: such a key was passed over without a word)."""
    out = dict(columns)
    for key, name in columns.items():
        if key in headers:
            continue
        found = [h for h in headers if h != key and split_unit(h)[0] == key]
        if len(found) == 1 and found[0] not in out:
            out[found[0]] = name
    return out


def _mapped_scale(out: Naming, name: str, unit: str | None) -> None:
    """A header mapped by ``data.columns`` to an error or a temperature, in a unit of another
    scale (``dX Sonde [mm]`` -> ``E_dX``): converted as a role's header is (stranger65: it was
    read as written, 1000x too small beside the files whose ``dX [mm]`` a role converted); a
    unit the reader does not know is left as before (read as written)."""
    kind = role(name)
    if unit is None or kind not in ("E", "T"):
        return
    if kind == "E" and _angle(unit):      # a tilt in arcsec mapped to E_AX: to µm/m (iso67)
        kind = "angle"
    scale = UNITS[kind].get(unit.lower().replace(" ", ""))
    if scale is not None and scale != (1.0, 0.0):
        out.scales[name] = scale


def matching_roles(header: str, roles: Mapping) -> list[str]:
    """The roles among ``data.roles``' patterns that match ``header`` (with or without its unit;
    a pattern's own unit, :func:`pattern_unit`, is no part of what it matches)."""
    base = split_unit(header)[0]
    return [k for k in ROLE_PATTERNS if any(fnmatch.fnmatchcase(header, p) or
                                            fnmatch.fnmatchcase(base, p)
                                            for p in map(_without_unit, roles.get(k, ())))]


def idle_patterns(headers: Sequence[str], roles: Mapping) -> list[str]:
    """``data.roles.<kind>=[<pattern>]`` of each role pattern that matches none of ``headers``
    (as :func:`matching_roles` matches): a mistyped pattern, which names nothing."""
    return [f"data.roles.{k}=[{p!r}]" for k in ROLE_PATTERNS for p in roles.get(k, ())
            if not any(matching_roles(h, {k: [p]}) for h in headers)]


# a role pattern ending in the unit its columns' values are in: '*DISP* (um)', a space before
# the brackets and no glob character in them ('Kanal[*]' is a glob)
_PATTERN_UNIT = re.compile(r"^(.*\S)\s+[\[(]([^\[\]()*?]+)[\])]\s*$")


def _without_unit(pattern: str) -> str:
    match = _PATTERN_UNIT.match(pattern)
    return match.group(1) if match and _a_unit(match.group(2)) else pattern


def pattern_unit(header: str, roles: Mapping, kind: str) -> str | None:
    """The unit that the first ``data.roles.<kind>`` pattern matching ``header`` ends in
    (``data.roles.error=['*DISP* (um)']``): the unit its values are in, whatever the header says
    (keysight70: a Keysight DAQ's probe channel scaled to µm by its Mx+B, its label left
    ``VDC``); None where the pattern has none."""
    base = split_unit(header)[0]
    for pattern in roles.get(kind, ()):
        match = _PATTERN_UNIT.match(pattern)
        if match and _a_unit(match.group(2)) and (fnmatch.fnmatchcase(header, match.group(1))
                                                  or fnmatch.fnmatchcase(base, match.group(1))):
            return match.group(2).strip()
    return None


def _time_header(headers, roles, columns, first, problems) -> list[str]:
    """The time column's header, or the date's and the time of day's (``data.roles.time``)."""
    if TIME in columns.values():
        return []
    if roles.get("time", AUTO) != AUTO:
        wanted = roles["time"] if isinstance(roles["time"], list) else [roles["time"]]
        found = [next((h for h in headers if want in (h, split_unit(h)[0])), None)
                 for want in wanted]
        for want, header in zip(wanted, found):
            if header is None:
                problems.append(f"data.roles.time={want!r} names no header")
        return found if None not in found else []
    free = [h for h in headers if h not in columns and not matching_roles(h, roles)]
    pair = date_and_time_of_day(free, first)
    named = [h for h in free if named_as_time(h) and h not in pair]
    if pair and not named:
        return pair
    if len(named) > 1:
        problems.append(f"{' and '.join(map(repr, named))} both look like the time (set "
                        "data.roles.time)")
    if named:
        return named[:1]
    stamped = [h for h in free if role(h) is None and looks_like_timestamp(first.get(h))]
    return stamped[:1]


def _run_header(headers, roles, columns, problems) -> str | None:
    """The header ``data.roles.campaign`` names (a glob over the headers, with or without their
    unit): exactly one, not one ``data.columns`` maps, nor the time."""
    pattern = roles.get(RUN_ROLE)
    if not pattern:
        return None
    found = [h for h in headers if h not in columns and any(
        fnmatch.fnmatchcase(name, pattern) for name in (h, split_unit(h)[0]))]
    if len(found) != 1:
        problems.append(f"data.roles.{RUN_ROLE}={pattern!r} "
                        + (f"matches {' and '.join(map(repr, found))}: name one column" if found
                           else "names no header"))
        return None
    return found[0]


def date_and_time_of_day(headers: Sequence[str], first: Mapping) -> list[str]:
    """``[date, time of day]``: the first header whose first cell is a date (``28.11.2026``)
    followed by one whose first cell is a time of day (``13:05:00``), else ``[]``."""
    for date, clock in zip(headers, headers[1:]):
        if DATE.fullmatch(str(first.get(date) or "")) and TIME_OF_DAY.fullmatch(
                str(first.get(clock) or "")):
            return [date, clock]
    return []


_AMB = re.compile(r"^(T_)?amb(ient)?_", re.I)
# (data94) a temperature's word a lab writes before the sensor's name, in the languages labs
# write (``Temp. headstock``, ``Temperatur Spindel``, ``Temperatura husillo``, ``Température
# broche``, ``Temperatuur spil``; data95: ``Tmp. headstock``): the ``T_`` prefix says it
# already (``T_Temp._headstock`` read as ``T_headstock``); never ``temps`` / ``tempo``, which
# are a time's words
_TEMPERATURE_WORD = r"(?:temp|tmp|temperature|temperatur|temperatura|température|temperatuur)"
_TEMPERATURE_LEAD = re.compile(rf"^{_TEMPERATURE_WORD}[_.\-]+(?=[^\W_])", re.I)
# (data95) the same word after the sensor's name (``headstock temp``, ``Spindel Temperatur``,
# ``bed temperature [°C]``, ``Coolant Temp.``): ``T_headstock``, not ``T_headstock_temp``; not
# after a dot, a historian's or an OPC UA node's path (``MC07.Spindle.Bearing.Temp``: its tag)
_TEMPERATURE_TAIL = re.compile(rf"(?<=[^\W_])[_\-]+{_TEMPERATURE_WORD}\.?$", re.I)


def _safe(base: str) -> str:
    """``base`` as a contract name's part: no character but word ones, ``.`` and ``-``."""
    return _UNSAFE.sub("_", base).strip("_").replace("..", ".")


def _bare(name: str, tail: bool = True) -> str:
    """``name`` (:func:`_safe`) without a temperature's leading word (:data:`_TEMPERATURE_LEAD`)
    and (``tail``) its trailing one (:data:`_TEMPERATURE_TAIL`), or as it is where nothing but
    the word, or an ambient's name, would be left."""
    rest = _TEMPERATURE_LEAD.sub("", name)
    rest = _TEMPERATURE_TAIL.sub("", rest) if tail else rest
    return name if not rest or _AMB.match(f"{rest}_") else rest


def shortened(headers: Sequence[str], columns: Mapping) -> frozenset:
    """(data94) The headers whose temperature word is left out of the name derived from them
    (:func:`_bare`): those it shortens whose short name no other header's, nor a
    ``data.columns`` name, reads as (``Temp. headstock`` beside ``headstock``, or beside
    ``T_headstock``, keeps ``T_Temp._headstock``, as before: the names stay unique without a
    refusal main did not make)."""
    def key(text: str) -> str:
        return _bare(_safe(text).removeprefix(PREFIX["temperature"])).lower()

    # (a lab's own contract name with a unit, 'T_spindle_temp [°C]', is its name: data95)
    short = {h for h in headers if _bare(_safe(split_unit(h)[0])) != _safe(split_unit(h)[0])
             and role(split_unit(h)[0]) is None}
    keys = Counter([key(split_unit(h)[0]) for h in headers]
                   + [key(str(c)) for c in columns.values()])
    return frozenset(h for h in short if keys[key(split_unit(h)[0])] == 1)


def former_names(column_map: Mapping) -> dict[str, tuple[str, str]]:
    """(data95) ``{a name an earlier rule derived: (the name derived now, the header)}`` for the
    headers of ``column_map`` (``{header: contract name}``, a dataset's ``column_map``) whose
    temperature word :func:`shortened` leaves out: before stop 94 every word was kept
    (``T_Temp_Luft``, ``T_Luft_temp``), from stop 94 to 95 the trailing one (``T_Luft_temp``).
    A stored config or model naming one is told the name now (:func:`former_said`)."""
    out: dict[str, tuple[str, str]] = {}
    for raw, name in column_map.items():
        base = split_unit(str(raw))[0]
        safe = _safe(base)
        if role(base) is not None or name != PREFIX["temperature"] + _bare(safe):
            continue
        for before in (safe, _bare(safe, tail=False)):
            former = _derived("temperature", before, False)
            if former != name:
                out.setdefault(former, (str(name), str(raw)))
    return out


def former_said(names: Sequence[str], column_map: Mapping, file) -> str | None:
    """What to say of ``names`` (a config's, a stored model's) that are no column of ``file``
    but an earlier rule's name of one of its headers (:func:`former_names`), else None."""
    former = former_names(column_map)
    hits = [(old, *former[old]) for old in names if old in former]
    if not hits:
        return None
    keep = ", ".join(f"{raw!r}: {old}" for old, _, raw in hits)
    if len(hits) == 1:
        old, new, raw = hits[0]
        said = f"{old} is no column of {file}, the derived name is {new} (header {raw!r})"
    else:
        said = (f"{', '.join(old for old, _, _ in hits)} are no columns of {file}, the derived "
                f"names are {', '.join(f'{new} ({raw!r})' for _, new, raw in hits)}")
    # (data101) a header beyond ASCII ('t1 Temperatur(°C)') is no map key Hydra reads on the
    # command line: the key as a config file's lines, not a second refusal of the key
    filed = "" if all(raw.isascii() for _, _, raw in hits) else (
        ", in a data config file: " + config_file_form("data", f"columns: {{{keep}}}"))
    return (f"{said}: a temperature's word (Temp, Temperatur, ...) is no longer repeated "
            f"after T_; name {'it' if len(hits) == 1 else 'them'} so, or keep the old name"
            f"{'s' * (len(hits) > 1)}, data.columns={{{keep}}}{filed}")


def _derived(kind: str, base: str, several_ambient: bool, short: bool = False) -> str:
    """The contract name of a header's ``base`` read as ``kind`` (``short``: its temperature
    word left out, :func:`shortened`)."""
    name = _safe(base)
    if short and kind in ("temperature", "ambient"):
        name = _bare(name)
    if kind == "ambient":
        # 'amb left' is T_amb_left, not T_amb_amb_left: the header's own 'amb' is the prefix
        return f"T_amb_{_AMB.sub('', name) or name}" if several_ambient else "T_amb"
    prefix = PREFIX[kind]
    return name if name.startswith(prefix) and len(name) > len(prefix) else prefix + name


def _scale(out: Naming, name: str, kind: str | None, unit: str | None, header: str,
           problems: list, cell, decimal: str) -> None:
    if kind is None or unit is None or (kind == "time" and not reads_as_number(cell, decimal)):
        return
    known = UNITS[kind]
    scale = known.get(unit.lower().replace(" ", ""))
    if scale is None:
        what = {"E": "an error's (µm, mm, m, nm; an angle's µrad, mrad, arcsec)",
                "angle": "an angle's (µrad, mrad, arcsec)", "T": "a temperature's (°C, K, °F)",
                "time": "a time's (s, ms, min, h, d)"}[kind]
        problems.append(f"{header!r}: unit {unit!r} is not {what}" + (
            voltage_hint(header, kind) if kind == "E" else
            # (lab75: a flux station's W/m^2, m/s beside the machine's: `init` leaves them out)
            f" nor a displacement's or a machine state's: no sensor of the model? "
            f"data.roles.ignore=[{header_pattern(header)}]" if kind == "T" and not is_known_unit(unit)
            else ""))
    elif scale != (1.0, 0.0) or kind == "time":   # (a time's unit stated: no ms to suspect)
        out.scales[name] = scale


def voltage_hint(*headers: str) -> str:
    """What to say of errors' columns in volts (``201 <DISP_X> (VDC)``): a probe's voltage the
    logger scaled (Keysight's Mx+B) with its unit label left, or its raw volts; '' where no
    header's unit is a voltage."""
    volts = [h for h in headers if (split_unit(h)[1] or "").lower().replace(" ", "") in VOLTS]
    if not volts:
        return ""
    patterns = ", ".join(f"'{header_pattern(h)} (um)'" for h in volts)
    return (f" (a voltage: scaled to µm by the logger, Keysight's Mx+B, its label left "
            f"{split_unit(volts[0])[1]!r}? say the unit its values are in after the pattern, "
            f"data.roles.error=[{patterns}]; raw volts need the probe's scale applied first)")


_GLOB = re.compile(r"([*?\[])")      # a header's glob characters, matched as themselves


def header_pattern(header: str) -> str:
    """The ``data.roles`` pattern that matches ``header`` alone: a role pattern matches a header
    without its unit, so the base, its glob characters escaped."""
    return _GLOB.sub(r"[\1]", split_unit(header)[0] or header)


def _angle(unit: str | None) -> bool:
    """``unit`` is an angle read as an angular error (µrad, mrad, arcsec, ″: :data:`.units.UNITS`)."""
    return unit is not None and unit.lower().replace(" ", "") in UNITS["angle"]


def _duplicates(names: dict, problems: list, by_role: bool) -> None:
    if not by_role:                      # as before: the reader names a duplicate column
        return
    seen: dict[str, str] = {}
    for raw, name in names.items():
        if name in seen:
            problems.append(f"{seen[name]!r} and {raw!r} both give {name}")
        seen.setdefault(name, raw)


def _refusal(problems: list[str], by_role: bool, names: dict, roles: dict, file) -> ContractError:
    unmapped = [raw for raw, why in roles.items() if why == "unmapped"]
    if not by_role and len(unmapped) == 1 and len(problems) == 1:   # the reader's own words
        raw = unmapped[0]
        return ContractError("column name has no contract role: expected 'time' or a T_/E_/S_ "
                             "prefix (map it with data.columns, or give roles with data.roles.*)",
                             file=file, column=names.get(raw, raw))
    # a lab's own headers with no role given: `init` proposes every role from the units
    hint = "; `thermocomp init <data.path>` proposes them" if not by_role else ""
    return ContractError(f"{len(problems)} column(s) not read: {listed(problems, 12)}; give each "
                         "a role (data.roles.error/state/ambient/time, data.roles.ignore to leave "
                         f"it out) or a name (data.columns){hint}", file=file)
