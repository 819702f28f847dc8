"""What ``thermocomp init`` detects in a lab's record: the file whose header is shown, the
roles proposed from the units in the headers, and the data config that reads it (plain values
in: the data keys as given, the defaults of ``conf/data/default.yaml``).

Roles not given (``data.roles.*``: for every header the patterns given do not match) are
proposed from the units in the headers (µm/mm: an error, unless named as a position; °C/K/°F: a
temperature; rpm, %, ``[-]`` ...: a state); a text column is proposed ``ignore``; in one file,
a column that would be a temperature but counts runs (:mod:`.runs`) is proposed
``data.roles.campaign``.
"""

from __future__ import annotations

import fnmatch
import re
from dataclasses import replace
from difflib import get_close_matches
from pathlib import Path

import numpy as np
import pandas as pd

from ..metrics import angular
from ..timerule import median_step
from . import campbell
from .catman import is_catman
from .contract import MANIFEST, TIME, ContractError, is_ambient, role
from .encoding import AUTO, UTF8, WINDOWS, ascii_only, detect, own
from .fixedwidth import is_fixed_width
from .graphtec import is_graphtec
from .hdf5 import is_hdf5
from .historian import held_wide, long_as_wide, wide_options
from .historian_layout import long_layout
from .jsonlines import is_json_lines
from .layout import header_line
from .lvm import is_lvm, lvm_layout
from .manifest import is_text, read_manifest
from .matfile import is_mat, is_v73
from .options import ROLE_PATTERNS, RUN_ROLE
from .plain import as_read, is_converted, is_lab_file, lab_as_csv
from .rates import period_groups
from .read import run_column, run_counter
from .record import check_record_file
from .roles import (
    LOGGER,
    RUN,
    date_and_time_of_day,
    excel_days_header,
    header_pattern,
    left_out,
    logger_columns,
    matching_roles,
    named_as_time,
    naming,
    split_unit,
    time_unit,
    voltage_hint,
)
from .runs import looks_like_run_labels, says_run
from .scope import is_scope, scope_layout
from .separators import number, reads_as_number
from .sinumerik import is_trace
from .sniff import head_lines, resolved
from .tables import parquet, peek_csv, without_pandas_index
from .tdm import is_tdm
from .timestamps import (
    CLOCK,
    OF_DAY,
    OF_DAY_KIND,
    day_fraction_too,
    excel_days,
    hours_of_day,
    looks_like_timestamp,
    maybe_elapsed,
    names_time_of_day,
)
from .tob1 import described, is_tob
from .units import AMBIGUOUS, UNITS, ambiguity, foreign_unit, is_flag, is_humidity, role_by_unit
from .utf16 import is_utf16, utf8_options, utf16_as_utf8
from .values import EPOCH_MS
from .workbook import HEAD_ROWS, csv_options, is_workbook, sheet_as_csv
from .yokogawa import is_yokogawa

HELD_OUT = 0.1    # the test share init writes for a record or runs without test campaigns

_GLOB = re.compile(r"([*?\[])")
# (a Keysight label in angle brackets: `101 <Air>`; a header's second occurrence, `Halle#2`)
_WORDS = re.compile(r"[\s_.\-<>#]+")
_CAMEL = re.compile(r"([a-zäöü])([A-ZÄÖÜ])")    # 'RoomTemp', 'AirSpindleHousing': two words
# a header word that says "the air around the machine"; an Italian / French / Spanish lab's
# 'ambiente', 'ambiante', 'capannone' (the shop's hall); the place the air is in: a French
# 'atelier', a Spanish 'nave' or 'taller', 'sala' / 'salle', a gateway's 'shop_air'
AMBIENT_WORDS = {"amb", "ambient", "umgebung", "umgebungstemperatur", "raum", "raumtemperatur",
                 "room", "hall", "halle", "hallentemperatur", "ambiente", "ambiante", "capannone",
                 "atelier", "nave", "taller", "sala", "salle", "officina", "werkstatt", "workshop",
                 "shop", *("raumluft", "hallenluft", "umgebungsluft", "lufttemperatur")}
# the air itself ('T Luft', 'T air'; amb70), as a whole word ('Luftlager', 'Airbag' are not),
# unless another word says whose air it is: an air bearing's, the cooling's, a supply's
AIR_WORDS = {"air", "luft"}
NOT_THE_AIRS = {"bearing", "bearings", "lager", "cooling", "coolant", "cooler", "kühlung",
                "kuehlung", "compressed", "pressure", "druck", "supply", "exhaust", "inlet",
                "outlet", "intake", "flow", "gap", "spalt", "blast", "blow", "purge"}
# a compound of the air's place (stranger74: 'Hallenmitte' was a temperature beside 'Halle'
# the ambient): a German compound, or an English one written as one word, told by its first
# stem ('Hallenmitte', 'Raumtemperatur2', 'Umgebungsluft', 'ambientT', 'roomtemp', 'hallwest');
# not where the rest names a surface or a thing in the hall ('Hallenboden', 'Hallenkran') or a
# part of the machine ('Raumachse'): :func:`air_words`
_PLACE = re.compile(r"^(umgebungs?|hallen|halle|raum|ambient|room|hall)(.+)$")
NOT_THE_HALLS = ("boden", "wand", "decke", "kran", "tor", "tür", "tuer", "fundament", "floor",
                 "wall", "ceiling", "crane", "door", "gate", "sensor")
# a part of the machine: the air's word beside one is that part's ('Air_spindle_housing', an
# aerostatic spindle's housing; 'Luft Spindel'), the place's is not ('Umgebung Spindel' is air)
PART_WORDS = {"spindle", "spindel", "housing", "gehäuse", "gehaeuse", "motor", "bed", "bett",
              "column", "ständer", "staender", "ram", "stößel", "stoessel", "head", "kopf",
              "table", "tisch", "slide", "schlitten", "saddle", "screw", "axis", "achse", "guide",
              "führung", "fuehrung", "nut", "mutter", "frame", "gestell"}
AIR_COMPOUNDS = {"airtemp", "airtemperature", "lufttemp"}     # the air's own, one word
_WHERE = ("interim", "processed")     # where stages write: the project's, not the data's


def folder_manifest(src: Path, opts) -> pd.DataFrame | None:
    """A folder's manifest, read once for all ``init`` asks of it (in its own encoding where
    ``data.encoding`` is not given); None for a record."""
    if not src.exists():       # (a mistyped file was looked for as a folder's manifest)
        raise ContractError(f"no such file or folder{_closest(src)}", file=src)
    if src.is_file():
        check_record_file(src)
        return None
    listed = src / MANIFEST
    if opts.encoding == UTF8 and listed.is_file():
        opts = replace(opts, encoding=detect(listed))
    if opts.test_fraction is None and opts.val_fraction is None:
        # a lab's manifest without `split` lists train runs: the config holds a tenth out
        # (data_config), so `split` is as optional here as to a run given that fraction
        opts = replace(opts, test_fraction=HELD_OUT)
    return read_manifest(src, opts)


def _closest(src: Path) -> str:
    """``: did you mean 'lab.csv'?`` where the folder holds a name close to ``src``'s (a case or
    a letter mistyped), else ''."""
    try:
        names = [p.name for p in src.parent.iterdir()]
    except OSError:
        return ""
    lower = {n.lower(): n for n in names}
    found = [lower[src.name.lower()]] if src.name.lower() in lower else get_close_matches(
        src.name, names, n=1, cutoff=0.8)
    return f": did you mean {found[0]!r}?" if found else ""


def sample_file(src: Path, manifest: pd.DataFrame | None) -> Path:
    """The file whose header is shown: the record itself, or a folder's first campaign
    (``manifest``: :func:`folder_manifest`)."""
    return src if manifest is None else src / manifest["file"].iloc[0]


def encoding(src: Path, opts, manifest: pd.DataFrame | None) -> str:
    """``data.encoding`` as given, or, given none (UTF-8), ``cp1252`` where the record, or a
    folder's manifest or campaign files, are not UTF-8 text (a Windows export); ``auto`` where
    some of them are and others are not (data87: a file Excel saved again beside a logger's UTF-8
    ones), each file then read in its own."""
    if opts.encoding != UTF8:
        return opts.encoding
    files = [src] if manifest is None else [src / str(f) for f in manifest["file"]]
    if (src / MANIFEST).is_file():
        files.append(src / MANIFEST)
    # (UTF-16: its mark; an .lvm and a Scope export are text; a Campbell binary table's .dat is
    # none: lab76, its bytes were taken for a Windows export's, data.encoding: cp1252 written)
    found = {f: detect(f) for f in files
             if (is_text(f) or is_lvm(f) or is_scope(f) or is_graphtec(f) or is_yokogawa(f)
                 or is_catman(f))
             and not is_utf16(f) and not is_tob(f)}
    if WINDOWS not in found.values():
        return UTF8
    # (an ASCII file reads in cp1252 too: only a UTF-8 one beyond ASCII needs its own)
    return AUTO if any(code == UTF8 and not ascii_only(f) for f, code in found.items()) else WINDOWS


def head(sample: Path, opts) -> tuple[object, list[str], list[str], str]:
    """``(options with the separators detected, header, first row, layout)`` of ``sample`` (a
    workbook's: of its sheet's first rows written as CSV, once for all four); ``layout`` says
    how it is read (:func:`detection_lines`' first line)."""
    if is_workbook(sample):
        with sheet_as_csv(sample, opts, rows=HEAD_ROWS) as sheet:
            opts, header, first, _ = head(sheet.csv, csv_options(opts))
            return (opts, header, first,
                    f"{sample.name}: sheet {sheet.name!r}" + _table_start(sheet.csv, opts, "row"))
    if is_utf16(sample):
        with utf16_as_utf8(sample) as text:
            opts, header, first, layout = head(text, utf8_options(opts))
            return opts, header, first, layout.replace(
                f"{text.name}: ", f"{sample.name}: encoding UTF-16 (its byte-order mark), ", 1)
    if is_lab_file(sample):         # a TDMS log, a MATLAB file: the CSV its channels are written to
        kind = ("a MATLAB file" + (" saved -v7.3" if is_v73(sample) else "") if is_mat(sample)
                else "a LabVIEW Measurement File" if is_lvm(sample)
                else "a TwinCAT Scope export" if is_scope(sample)
                else "a Graphtec logger's CSV (its Amp settings' signal names)" if is_graphtec(sample)
                else "a Yokogawa viewer's ASCII export (its tags)" if is_yokogawa(sample)
                else "HBM catman's ASCII export (its channel blocks)" if is_catman(sample)
                else "an HDF5 file" if is_hdf5(sample)
                else "a DIAdem TDM/TDX pair" if is_tdm(sample)
                else "a SINUMERIK trace" if is_trace(sample)
                else described(sample) if is_tob(sample)
                else "a TDMS log") + " (its channels as columns)"
        encoding = opts.encoding                 # (the file's: the temporary CSV is UTF-8)
        with lab_as_csv(sample, encoding=encoding, dayfirst=opts.dayfirst) as text:
            opts, header, first, layout = head(text, csv_options(opts))
            layout = layout.replace("a historian's long file (", "channels at their own rates, "
                                    "written long (", 1)
            # (stranger69: the temporary CSV's ',' and '.' were said as the file's)
            own = (lvm_layout(sample, encoding) if is_lvm(sample)
                   else scope_layout(sample, encoding) if is_scope(sample) else "")
            layout = re.sub(r"delimiter '[^']*', decimal '[^']*'", own, layout, count=1)
            return opts, header, first, layout.replace(
                f"{text.name}: ", f"{sample.name}: {kind}" + (", " if own else ""), 1)
    if is_json_lines(sample) or is_fixed_width(sample, opts.encoding):
        kind = "JSON Lines (nested keys joined with '.')" if is_json_lines(sample) else \
            "a fixed-width table (its columns told by the numbers)"
        with as_read(sample, opts, rows=HEAD_ROWS) as (text, text_opts):
            opts, header, first, layout = head(text, text_opts)
            return opts, header, first, layout.replace(f"{text.name}: ", f"{sample.name}: {kind}, ", 1)
    layout = long_layout(sample, opts) if is_text(sample) else None
    if layout is not None:    # a historian's long file: the head of the wide grid it is read as
        with long_as_wide(sample, opts, layout, rows=HEAD_ROWS) as wide:
            _, header, first, _ = head(wide, wide_options(opts, layout))
        held = held_wide(sample, opts, layout)
        names = layout.header
        opts = replace(opts, delimiter=layout.delimiter, decimal=layout.decimal)
        kind = ("an InfluxDB annotated CSV (each table a series: its tags and _field its name, "
                "a unit tag its unit; _time, _value its samples)" if layout.influx else
                f"a historian's long file ({names[layout.tag]!r} the tag, {names[layout.value]!r} "
                f"the value" + (f", {names[layout.quality]!r} its quality" if layout.quality is
                                not None else ", no quality column") + ")")
        return (opts, header, first, _separators(sample, opts) + (
            f", {kind}: {len(header) - 1} tags held onto a grid of data.resample_s="
            f"{held.period:g} s, {len(held.frame)} rows"))
    if not is_text(sample):
        table = without_pandas_index(parquet().read_table(sample).slice(0, 1))
        return (opts, table.column_names, [str(v[0].as_py()) for v in table.columns],
                f"{sample.name}: a Parquet file (its columns typed: no delimiter, no decimal)")
    opts = resolved(sample, opts)
    header, first, skip = peek_csv(sample, opts.delimiter, opts.encoding)
    opts = replace(opts, skip_rows=skip)
    layout = _separators(sample, opts) + _table_start(sample, opts)
    kind = campbell.said(next(iter(head_lines(sample, opts.encoding)), None))   # (its preamble)
    return opts, header, first, layout.replace(f"{sample.name}: ", f"{sample.name}: {kind}, ", 1
                                               ) if kind else layout


def epoch_ms_column(header: list[str], first: dict, opts) -> str | None:
    """The header of a time column without a unit (none in ``data.units``) whose first value is
    milliseconds since 1970 (:data:`~.values.EPOCH_MS`: 2000 .. 2099), as a gateway stamps its
    messages (read as seconds: a record of 21 days lasts 21,000 years): written to the config as
    ``data.units={<header>: ms}``; None where no such column is."""
    for h in header:
        if not named_as_time(h) or split_unit(h)[1] is not None or h in opts.units:
            continue
        try:
            value = float(str(first.get(h) or "").strip())
        except ValueError:
            continue
        if EPOCH_MS[0] <= value <= EPOCH_MS[1]:
            return h
    return None


def excel_days_column(sample: Path, opts, header: list[str], first: dict) -> str | None:
    """The header of a column of Excel's serial days (:func:`.roles.excel_days_header`, read
    from its first cell) whose first rows in a text ``sample`` step as the reader's own rule
    says days do (:func:`.timestamps.excel_days`: a fraction of a day, whole seconds); None
    otherwise.  Why: a plain ``time`` of seconds since a logger started 8 h 20 min before its
    first row (30000, 30060, ...) lies in the day numbers' range, and read as days its 240 rows
    lasted 14,340 days (init's own read refused it).  A file read through a converter, or of one
    row, is judged by its first cell."""
    days = excel_days_header(header, first, opts.units, opts.decimal)
    if days is None or not is_text(sample) or is_converted(sample, opts):
        return days
    cells = _column_cells(sample, opts, header.index(days), rows=HEAD_ROWS)
    if cells is None:
        return days                     # (its own read says why)
    values = np.array([v for c in cells if (v := number(str(c), opts.decimal)) is not None])
    period = median_step(values) if len(values) > 1 else None
    return days if period is None or excel_days(values[0], period) else None


def elapsed_column(src: Path, manifest: pd.DataFrame | None, opts, header: list[str],
                   first: dict) -> str | None:
    """The header of a text file's ``h:mm:ss`` time column where a file of ``src`` (the record,
    or any file of a folder, ``manifest``) holds an hour past 23 in it: a logger's time since its
    start, written to the config as ``data.time=elapsed`` so that each file of a folder is read
    so (a run shorter than a day too, refused as a time of day otherwise); None where
    ``data.time`` is given, no column's first cell is ``h:mm:ss`` or no file says it."""
    if opts.time != "auto":
        return None
    files = [src] if manifest is None else [src / str(f) for f in manifest["file"]]
    if not all(is_text(f) and not is_converted(f) for f in files):
        return None
    for i, h in enumerate(header):
        if not maybe_elapsed(str(first.get(h) or ""), opts.time):
            continue
        for file in files:
            column = _column_cells(file, opts, i)
            if column is None:
                continue                    # (its own read says why)
            hours = pd.to_numeric(column.str.extract(r"^\s*(\d+):", expand=False), errors="coerce")
            if hours.max() > 23:
                return h
        return None
    return None


def _lone_clock_left(header: list[str], first: dict, opts) -> bool:
    """Whether the time is left to ``init`` to read (``data.time`` and ``data.roles.time`` not
    given) and no date column stands beside a time of day (:func:`.roles.date_and_time_of_day`:
    the pair is one timestamp): where a time-of-day column alone may be found."""
    return opts.time == "auto" and opts.roles.get("time", "auto") == "auto" and \
        not date_and_time_of_day(header, first)


def clock_column(header: list[str], first: dict, opts) -> str | None:
    """(data92b) The header of the time column a time-of-day header names (``Uhrzeit``,
    ``Heure``: :func:`.timestamps.names_time_of_day`) whose first cell is ``h:mm:ss``, with no
    date column beside it (:func:`.roles.date_and_time_of_day`: the pair is one timestamp), for
    ``data.time=of_day``; None where ``data.time`` or ``data.roles.time`` is given."""
    if not _lone_clock_left(header, first, opts):
        return None
    return next((h for h in header if names_time_of_day(h)
                 and maybe_elapsed(str(first.get(h) or "").strip(), opts.time)), None)


def hours_column(sample: Path, opts, header: list[str], first: dict) -> str | None:
    """(data93) The header of a text ``sample``'s time column in a lab's decimal hours of the
    day (:func:`.timestamps.hours_of_day`: ``Hora`` 21.5, 21.58 ..., no unit), to be written as
    ``data.units={<header>: h}`` and ``data.time=of_day``; None where ``data.time`` or
    ``data.roles.time`` is given, a date column stands beside it, the file is read through a
    converter, or its values may as well be a fraction of a day
    (:func:`.timestamps.day_fraction_too`: left to the reader's refusal, which names both)."""
    if not _lone_clock_left(header, first, opts) or not is_text(sample) or \
            is_converted(sample, opts):
        return None
    for i, h in enumerate(header):
        if not names_time_of_day(h) or number(str(first.get(h) or ""), opts.decimal) is None:
            continue
        cells = _column_cells(sample, opts, i)
        if cells is None:
            return None                     # (its own read says why)
        values = np.array([v if (v := number(str(c), opts.decimal)) is not None else np.nan
                           for c in cells])
        return h if hours_of_day(values, h, time_unit(h, opts)) and not day_fraction_too(values) else None
    return None


def _column_cells(file: Path, opts, index: int, rows: int | None = None) -> pd.Series | None:
    """The cells of a text ``file``'s column ``index`` as text, from its first line under the
    lines ``opts.skip_rows`` skips (its first ``rows``; every one where None); None where the
    file does not read so (the record's own read says why)."""
    try:
        return pd.read_csv(file, sep=opts.delimiter, header=None, skiprows=opts.skip_rows,
                           usecols=[index], dtype=str, nrows=rows,
                           encoding=own(file, opts.encoding)).iloc[:, 0]
    except (ValueError, OSError, pd.errors.ParserError):
        return None


def _separators(sample: Path, opts) -> str:
    charset = ("" if opts.encoding == UTF8 else "encoding each file's own (UTF-8 and cp1252 "
               "files), " if opts.encoding == AUTO else f"encoding {opts.encoding} (not UTF-8), ")
    return f"{sample.name}: {charset}delimiter {opts.delimiter!r}, decimal {opts.decimal!r}"


def proposed_roles(header: list[str], first: dict, opts, stated: bool = False) -> dict:
    """``data.roles`` as given, and for every header none of its patterns (nor ``data.columns``,
    the time, the campaign) names, a pattern proposed from its unit (:func:`.units.role_by_unit`:
    µm/mm an error, rpm or ``[-]`` a state; ``run`` reads such a header so too), its words (the
    air's temperature: ambient, where no ambient is given) or its cell (``true`` / ``false``: a
    state; other text: ignore); a date column followed by a time of day: the time, ``[date,
    time of day]``.  A length named by its axis alone (``X [mm]``) is proposed nothing: the
    reading lists it.  A unit of no sensor of the model (``W/m^2``, ``m/s``: :func:`.units.
    foreign_unit`, ``stated``: the file's unit row says the units) is proposed ``ignore``
    (lab75: the reader read it as a temperature and refused it), and so is a relative humidity in
    ``%`` (lab76: :func:`.units.is_humidity`; no thermal input, proposed a state before)."""
    roles = {k: list(opts.roles.get(k, [])) for k in ROLE_PATTERNS}
    roles["time"] = opts.roles.get("time", "auto")
    if opts.roles.get(RUN_ROLE):
        roles[RUN_ROLE] = opts.roles[RUN_ROLE]
    if roles["time"] == "auto":               # a date and a time of day: said, as one time
        roles["time"] = date_and_time_of_day(header, first) or "auto"
    taken = [h for h in header if _named(h, roles, opts)]
    air_given = bool(roles["ambient"])
    for h in filter(str.strip, header):       # (no header: left out if empty, else refused)
        if h in taken or left_out(h) is not None:     # (a channel exported twice: read once)
            continue
        base, unit = _unit_of(h, opts)
        if not base:                          # a unit alone ('[°C]'): the reader refuses it
            continue
        pattern = _GLOB.sub(r"[\1]", base)
        if any(fnmatch.fnmatchcase(t, pattern) or fnmatch.fnmatchcase(split_unit(t)[0], pattern)
               for t in taken):               # (the user's header of the same name: theirs)
            continue
        kind = role_by_unit(base, unit)
        if is_humidity(base, unit):           # (lab76: '%' proposed it a state)
            roles["ignore"].append(pattern)
        elif kind in ("error", "state"):
            roles[kind].append(pattern)
        elif kind == AMBIGUOUS:
            continue
        elif foreign_unit(unit, stated):
            roles["ignore"].append(pattern)
        elif not air_given and _may_be_air(base) and AMBIENT_WORDS & air_words(base) and (
                not unit or unit.replace(" ", "").lower() in UNITS["T"]):
            roles["ambient"].append(pattern)
        elif is_flag(first.get(h)):          # 'true' / 'false': an on/off flag, a state
            roles["state"].append(pattern)
        elif not (reads_as_number(first.get(h), opts.decimal, opts.thousands)
                  or str(first.get(h) or "").strip() in opts.missing_values     # ('---')
                  or looks_like_timestamp(first.get(h)) or named_as_time(h)):
            # (the reader reads 'Dauer' 25:30:00)
            roles["ignore"].append(pattern)
    return _by_role(roles, header, first)


def stated_units(sample: Path, opts) -> bool:
    """The units under ``sample``'s header are a unit row's, each a unit whatever it spells
    (a Campbell Scientific TOA5 table's line 3).  A file read through a converted copy (a
    workbook, Excel's UTF-16 'Unicode Text', a TDMS log) has none: its head is not lines of text
    (head_lines refused a UTF-16 export that the reader converts); a TOB1 / TOB2 / TOB3 table's
    is."""
    if is_converted(sample) and not is_tob(sample):
        return False
    return campbell.has_unit_row(head_lines(sample, opts.encoding))


def foreign_said(header: list[str], roles: dict, opts, stated: bool) -> list[str]:
    """What ``init`` says of the headers ``roles`` leave out for their unit (:func:`proposed_roles`;
    lab76: a relative humidity for its name and unit)."""
    out = []
    for h in header:
        base, unit = _unit_of(h, opts)
        if not base or not matching_roles(h, {"ignore": roles["ignore"]}):
            continue
        pattern = header_pattern(h)
        if is_humidity(base, unit):
            out.append(f"{h!r}: a relative humidity (its name, unit '%'), no temperature nor "
                       "machine state: it drives no thermal error, and what it says of the "
                       "machine the air's temperature says; proposed data.roles.ignore "
                       f"(data.roles.state=[{pattern}] reads it as a machine state)")
        elif foreign_unit(unit, stated):
            out.append(f"{h!r}: unit {unit!r} is no temperature's, displacement's nor machine "
                       "state's (°C, µm, W, rpm ...): not a sensor of the model, proposed "
                       f"data.roles.ignore (data.roles.state=[{pattern}] if it is a machine state)")
    return out


def without_own_names(header: list[str], first: dict, roles: dict, opts) -> tuple[dict, list[str]]:
    """``(roles, headers)``: ``roles`` without the ``error`` / ``state`` patterns proposed for a
    contract name with a unit (``E_S2x1d1_B01_B02 [mm]``), which the reader reads as that name,
    converted, without them, where the reading names and scales every header the same without
    them (:func:`.roles.naming`, one rule); ``headers`` those left to their names (none: as
    given).  A volumetric export's 420 distances were each written into data.roles.error."""
    prefix = {"error": "E", "state": "S"}
    own = {k: [p for p in roles[k] if p not in opts.roles.get(k, []) and role(p) == prefix[k]
               and any(split_unit(h)[0] == p and split_unit(h)[1] for h in header)]
           for k in prefix}
    if not any(own.values()):
        return roles, []
    short = {**roles, **{k: [p for p in roles[k] if p not in own[k]] for k in prefix}}
    try:
        same = (naming(header, short, opts.columns, first, opts.decimal, None, opts.units)
                == naming(header, roles, opts.columns, first, opts.decimal, None, opts.units))
    except ContractError:
        return roles, []
    if not same:
        return roles, []
    return short, [h for h in header if split_unit(h)[0] in own["error"] + own["state"]]


def _may_be_air(base: str) -> bool:
    """A header that may be proposed the ambient: no contract name, or a ``T_`` one that is not
    the contract's ambient already (stranger81: a PLC's variable ``T_HALLE``, the hall's air, was
    kept a machine temperature by its contract-like prefix)."""
    return role(base) is None or (role(base) == "T" and not is_ambient(base))


def air_words(name: str) -> set[str]:
    """The words of a header's ``name``, and of a word that is a ``T`` before an air's word
    (MATLAB's field ``Troom``, ``Tamb``: a name cannot hold a space) that word too; with
    ``ambient`` where a word is the air (:data:`AIR_WORDS`) and none an air bearing's, the
    cooling's (:data:`NOT_THE_AIRS`) nor a part's (:data:`PART_WORDS`), or a compound of the
    air's place (:data:`_PLACE`, ``Hallenmitte``)."""
    words = set(_WORDS.split(_CAMEL.sub(r"\1 \2", name).lower()))
    words |= {w[1:] for w in words if w.startswith("t") and w[1:] in AMBIENT_WORDS | AIR_WORDS}
    if any(_a_place(w) for w in words):
        words.add("ambient")                  # 'Hallenmitte': the hall's air, its middle
    if words & (AIR_WORDS | AIR_COMPOUNDS) and not words & (NOT_THE_AIRS | PART_WORDS):
        words.add("ambient")                  # the air, not an air bearing's nor a part's
    return words


def _a_place(word: str) -> bool:
    """``word`` is a compound of the air's place (:data:`_PLACE`) naming no thing in it."""
    match = _PLACE.match(word)
    rest = match.group(2) if match else ""
    return bool(rest) and not rest.startswith((*NOT_THE_HALLS, *PART_WORDS, *NOT_THE_AIRS))


def _over_campaigns(ds, name: str) -> np.ndarray:
    """The measured values of the column ``name`` over every campaign of ``ds``."""
    values = pd.concat([df[name] for df in ds.campaigns.values() if name in df]).dropna()
    return values.to_numpy(float)


def flag_headers(ds, names: dict) -> list[str]:
    """The headers (``names``: header -> contract name) proposed as a temperature whose column
    holds two values one apart and nothing else over the whole of ``ds`` (0 / 1, or -1 / 0 once
    referenced to its first sample): an on/off flag the header did not say, a historian's
    ``VTL01.Part.Loaded`` (historian60: proposed a temperature, and ``Hall.Door`` the hall's
    air by its word)."""
    flags = []
    for header, name in names.items():
        if not str(name).startswith("T_"):
            continue
        seen = np.unique(np.round(_over_campaigns(ds, name), 9))
        if seen.size == 2 and seen[1] - seen[0] == 1.0:
            flags.append(header)
    return flags


# a logger's day of the week: ISO's 1 (Monday) ... 7 (Sunday), or a 0-6 count
_WEEKDAY = re.compile(r"(iso[ _-]?)?(week[ _-]?day|day[ _-]?of[ _-]?(the[ _-]?)?week|dow|wochentag|"
                      r"jour[ _-]?de[ _-]?la[ _-]?semaine|giorno[ _-]?della[ _-]?settimana)",
                      re.IGNORECASE)


def weekday_headers(ds, names: dict, opts) -> list[str]:
    """The headers proposed as a temperature that name the day of the week (``Weekday``,
    ``Wochentag``, ``DOW``) and hold whole numbers 0-7 over ``ds``: a calendar number, no
    reading (stranger75: a logger's ISO weekday was read as the temperature ``T_Weekday``,
    unsaid, and fitted: Monday's 1 after Sunday's 7 a step of 6 "K")."""
    days = []
    for header, name in names.items():
        if not str(name).startswith("T_") or not _WEEKDAY.fullmatch(_unit_of(header, opts)[0].strip()):
            continue
        v = _over_campaigns(ds, name)
        if v.size and np.all(v == np.round(v)) and v.min() >= 0 and v.max() <= 7:
            days.append(header)
    return days


def ignored(roles: dict, headers: list[str]) -> dict:
    """``roles`` with each of ``headers`` left out (``data.roles.ignore``)."""
    return {**roles, "ignore": [*roles["ignore"], *map(header_pattern, headers)]}


def flags_as_states(roles: dict, headers: list[str], opts) -> dict:
    """``roles`` with each of ``headers`` a state (out of the ambient and error patterns)."""
    roles = {k: (list(v) if isinstance(v, list) else v) for k, v in roles.items()}
    for h in headers:
        pattern = _GLOB.sub(r"[\1]", _unit_of(h, opts)[0])
        roles["ambient"] = [p for p in roles["ambient"] if p != pattern]
        roles["error"] = [p for p in roles["error"] if p != pattern]
        roles["state"].append(pattern)
    return roles


# A machine tool's thermal error stays within a few tenths of a millimetre (the largest portal
# mills' reach ~0.5 mm over a day in an unheated hall); an axis travels tens to thousands
TRAVEL_UM = 5000.0


def axis_lengths(header: list[str], roles: dict, opts) -> list[str]:
    """The patterns of the headers no role names that are a length named by its axis alone
    (``X-Achse [mm]``: its error or its position, :data:`.units.AMBIGUOUS`): ``init`` reads them
    as errors for a look at their span (:func:`travel_headers`), never keeps them so."""
    return [_GLOB.sub(r"[\1]", _unit_of(h, opts)[0]) for h in header if h.strip()
            and not _named(h, roles, opts) and role_by_unit(*_unit_of(h, opts)) == AMBIGUOUS]


def travel_headers(ds, names: dict, given_roles: dict, opts) -> dict:
    """Header -> its span (mm) for each header proposed as an error by its length unit (no
    ``data.roles.error`` pattern of the user names it), or named by its axis alone
    (:func:`axis_lengths`, stranger69: ``X-Achse [mm]``, 150-500 mm, was refused as either),
    whose values span more than :data:`TRAVEL_UM` over ``ds``: an axis position, not a thermal
    error (stranger64: a portal mill's ``Z ram [mm]``, 0-800 mm, was proposed the error
    ``E_Z_ram``)."""
    out = {}
    for header, name in length_errors(names, given_roles, opts).items():
        values = _over_campaigns(ds, name)
        span = float(values.max() - values.min()) if values.size else 0.0
        if span > TRAVEL_UM:
            out[header] = span / 1000.0
    return out


def length_errors(names: dict, given_roles: dict, opts) -> dict:
    """Header -> contract name of each header proposed as an error by its length unit alone
    (no ``data.roles.error`` pattern of the user names it): an error or an axis' position,
    which :func:`travel_headers` tells apart by its span once read."""
    given = {k: list(v) for k, v in given_roles.items() if k == "error" and isinstance(v, list)}
    return {header: name for header, name in names.items()
            if str(name).startswith("E_") and role(header) != "E"
            and not (given and matching_roles(header, given))
            and role_by_unit(*_unit_of(header, opts)) in ("error", AMBIGUOUS)}


def beyond(ds, names: dict, limit: float | None) -> bool:
    """A column of ``names`` (header -> contract name) holds a value beyond ``limit``."""
    return limit is not None and any(
        float(np.nanmax(np.abs(df[n].to_numpy(float)), initial=0.0)) > limit
        for df in ds.campaigns.values() for n in names.values() if n in df)


def _named(header: str, roles: dict, opts) -> bool:
    """``header`` is named by the user (a ``data.roles`` pattern, ``data.columns``, the time or
    the campaign): nothing is proposed for it."""
    time = roles["time"] if isinstance(roles["time"], list) else [] if roles["time"] == "auto" \
        else [roles["time"]]
    campaign = roles.get(RUN_ROLE)
    return bool(header in opts.columns or header in time or split_unit(header)[0] in time
                or matching_roles(header, roles) or campaign and any(
                    fnmatch.fnmatchcase(n, campaign) for n in (header, split_unit(header)[0])))


def _by_role(roles: dict, header: list[str], first: dict) -> dict:
    """``roles`` with the ``E_`` headers named ``error`` where nothing else is proposed and a
    header is no contract name (``Spindelkopf [°C]`` beside ``E_X``): headers are read by role
    only where a role is set, and without one such a temperature was refused as unmapped."""
    if any(roles[k] for k in ROLE_PATTERNS) or isinstance(roles["time"], list):
        return roles
    own = [h for h in filter(str.strip, header) if role(h) is None and not (
        named_as_time(h) or looks_like_timestamp(first.get(h)))]
    errors = [_GLOB.sub(r"[\1]", h) for h in header if role(h) == "E"]
    return {**roles, "error": errors} if own and errors else roles


def proposed_campaign(src: Path, roles: dict, opts) -> dict:
    """``roles`` with ``campaign`` proposed where ``src`` is one file (not a folder's) and, read
    with ``roles``, a column it would make a temperature counts runs, or a text column it
    leaves out names them (:func:`_run_labels`); as given otherwise (a file that does not read
    is refused by the read that follows, naming why)."""
    if not src.is_file() or roles.get(RUN_ROLE):
        return roles
    try:
        counter = run_counter(src, replace(opts, roles=roles))
    except ContractError:
        return roles
    if counter is None:
        return _run_labels(src, roles, opts)
    return {**roles, RUN_ROLE: _GLOB.sub(r"[\1]", split_unit(counter)[0])}


def _run_labels(src: Path, roles: dict, opts) -> dict:
    """``roles`` with ``campaign`` the first left-out (``ignore``) text column that names the
    runs (:func:`.runs.looks_like_run_labels`: ``Versuch`` K01, K02 ...), taken out of
    ``ignore``: left out, the runs were read as one record, its test part cut inside the last."""
    for pattern in (p for p in roles["ignore"] if says_run(p)):
        trial = {**roles, "ignore": [p for p in roles["ignore"] if p != pattern], RUN_ROLE: pattern}
        try:
            values, header = run_column(src, replace(opts, roles=trial))
        except ContractError:
            continue
        if looks_like_run_labels(values, header):
            return trial
    return roles


def check_an_error_is_named(header: list[str], first: dict, roles: dict, opts, file: Path) -> None:
    """Refuse, naming the setting and the numeric columns, a file where no column is a measured
    error: none has a length unit in its header, an ``E_`` name, ``data.roles.error`` or
    ``data.columns`` to one.  Which of ``dX``, ``Spindle`` ... is the error is never guessed."""
    named = [*header, *opts.columns.values()]
    if roles["error"] or any(role(h) == "E" for h in named):
        return
    bookkeeping = logger_columns(header)
    numeric = [h for h in header if h.strip() and reads_as_number(first.get(h), opts.decimal)
               and not named_as_time(h) and h not in bookkeeping]
    either = [ambiguity(h, split_unit(h)[0]) for h in header if h.strip() and not _named(
        h, roles, opts) and role_by_unit(*_unit_of(h, opts)) == AMBIGUOUS]
    # a MATLAB field or a TDMS channel has no header a lab can edit: its unit goes in data.units
    unit_hint = ("data.units={dX: um}" if is_lab_file(file)
                 else "in the header ('dX [µm]') or data.units={dX: um}")
    raise ContractError("no column reads as a measured error (no length unit in a header, µm or "
                        "mm, no E_ name): name it, data.roles.error=[<header>], or give its unit, "
                        f"{unit_hint}; the numeric columns: "
                        f"{', '.join(map(repr, numeric)) or 'none'}"
                        + "".join(f"; {line}" for line in either)
                        + (f"; {voltage_hint(*numeric)[2:-1]}" if voltage_hint(*numeric) else ""),
                        file=file)


def _unit_of(header: str, opts) -> tuple[str, str | None]:
    """``(name, unit)`` of ``header``, its unit from ``data.units`` where given there."""
    base, unit = split_unit(header)
    return base, opts.units.get(header, unit)


def data_config(src: Path, given: dict, opts, roles: dict, defaults: dict,
                manifest: pd.DataFrame | None = None) -> dict:
    """The data config that reads ``src``: the separators, the roles, and every other key the
    user set away from its default (``data.thousands``, ``data.time``, ...); ``manifest``: a
    folder's, as read (:func:`folder_manifest`; read here if not given)."""
    if manifest is None and src.is_dir():
        manifest = read_manifest(src, opts)
    # a sheet, a Parquet, TDMS or MATLAB file has no separators (a CSV file beside them: detected)
    sample = sample_file(src, manifest)
    separators = {} if not is_text(sample) or is_lab_file(sample) else {
        "delimiter": opts.delimiter, "decimal": opts.decimal}
    config = {"path": str(src), **separators, "roles": roles}
    for key, value in given.items():
        if key not in config and key not in _WHERE and key in defaults and value != defaults[key]:
            config[key] = value
    # one record, or a folder without test campaigns (no manifest, or one without `split`:
    # every run train): nothing is held out unless a fraction says so, and `run` needs a test
    unsplit = manifest is None or not (manifest["split"] == "test").any()
    if unsplit and given.get("test_fraction") is None:
        config["test_fraction"] = HELD_OUT   # its last tenth (of samples; of runs) is the test
    return config


def _periods(ds) -> str:
    """'', or, for campaigns logged at periods :data:`RATE_CHANGE` times apart, each period with
    its number of campaigns (the median step of every row alone said 10 s for a folder whose
    23 runs of 32 were logged at 60 s)."""
    periods = {c: median_step(df[TIME].to_numpy(float)) for c, df in ds.campaigns.items()}
    groups = period_groups({c: p for c, p in periods.items() if p})
    if not groups:
        return ""
    return (" (the median step of every row; campaigns logged at " +
            ", ".join(f"{p:g} s: {len(ids)}" for p, ids in groups.items()) + ")")


def _time_line(times: list, origin, read_as, opts) -> str:
    """``init``'s line on the time: its columns and how they were read (``origin``: the first
    timestamp, where timestamps; ``read_as``: the ingest report's ``time``)."""
    if not times:
        return "time: none in the file, data.sample_period_s rows apart"
    named = f"time: {' + '.join(repr(h) if h else 'the column without a header' for h in times)}"
    if origin:
        return f"{named}, timestamps from {origin}"
    if opts.time == OF_DAY_KIND or read_as == OF_DAY:
        # (data91) seconds since midnight, passing it: said, with the key where it took one (its
        # h:mm:ss is read as a duration first, data92b: the report says "elapsed" then)
        key = f", data.time={opts.time}" if opts.time == OF_DAY_KIND else ""
        unit = opts.units.get(times[0]) if times[0] else None     # (data93: decimal hours)
        key += f", data.units={{{times[0]!r}: {unit}}}" if unit else ""
        return f"{named}, {OF_DAY} (since midnight, a day added where it passes midnight{key})"
    return f"{named}, elapsed h:mm:ss" if read_as == "elapsed" else \
        f"{named}{_seconds_unit(times[0], opts)}"


def detection_lines(layout: str, opts, header, plan, ds, report, period_s: float, path: Path,
                    name: str, scans: dict | None = None) -> list[str]:
    """What ``thermocomp init`` prints: separators, time, sample period, each column's role
    and contract name, the campaigns, and the command to run next (``scans``: as
    :func:`jumpy_temperatures` takes them)."""
    times = [h for h, n in plan.names.items() if n in ("time", CLOCK)]
    # timestamps: the first as read, so that a day read as the month shows
    origin = report["campaigns"][ds.ids()[0]].get("time_origin")
    read_as = report["campaigns"][ds.ids()[0]].get("time")
    lines = [layout, _time_line(times, origin, read_as, opts),
             f"sample period: {period_s:g} s, {report['rows']} rows{_periods(ds)}"]
    width = max(len(h or "(no header)") for h in header)
    for h in header:
        contract = plan.names.get(h)
        role = plan.roles.get(h, "ignore") if contract else "ignore (left out)"
        if plan.roles.get(h) == LOGGER:       # (an alarm flag, the sweep number)
            role = LOGGER
        if plan.roles.get(h) == "empty":
            h, role = "(no header)", "empty (left out)"
        h = h or "(no header)"
        shown = {CLOCK: "time", RUN: "(each run a campaign)"}.get(contract, contract or "-")
        if role == LOGGER:
            shown = "- (left out: no measurement)"
        if contract and plan.roles.get(h) == "error" and angular(contract):   # (iso67)
            unit, scale = split_unit(h)[1], plan.scales.get(contract, (1.0, 0.0))[0]
            shown += (" (an angle, in µm/m = µrad" + (f": {unit} x {scale:.6g}" if unit and
                                                      scale != 1.0 else "") + ")")
        lines.append(f"  {h:<{width}}  {role:<12} {shown}")
    for cid in ds.ids():
        lines.append(f"campaign {cid}: {ds.manifest.loc[cid, 'split']}, "
                     f"{report['campaigns'][cid]['rows']} rows")
    # (a target measured now and then: the read itself says it once, io.sparse.said)
    groups = group_columns(ds.manifest)
    said = [f"manifest column '{c}': {len(labels)} groups of campaigns ({', '.join(labels[:3])}"
            f"{', ...' if len(labels) > 3 else ''}); `run data.group_by={c}` fits and scores one "
            "model per value" for c, labels in groups.items()]
    nxt = f"next: thermocomp run 'hydra.searchpath=[file://{path.parent.parent}]' data={name}"
    if groups:
        nxt += f" (or with data.group_by={next(iter(groups))}: one model per value)"
    return lines + [f"data config written to {path}", *said, *jumpy_temperatures(plan, ds, scans), nxt]


# a healthy sensor's steps are hundredths of a kelvin, a motor's warm-up a few tenths a minute:
# no tenth of a record's steps reach 1 K
JUMPY_K, JUMPY_SHARE = 1.0, 0.1


def jumpy_temperatures(plan, ds, scans: dict | None = None) -> list[str]:
    """A warning for each column proposed as a temperature a tenth of whose steps from a sample
    to the next (:data:`JUMPY_SHARE`) are :data:`JUMPY_K` or more: no mass's temperature moves
    so (a gateway's spindle number 1-6 under ``probe.spindle``, a count, a code, read as °C:
    silent before).  ``scans``: contract name -> its own file's samples per run, where the
    record's rows are another file's (two loggers: a DAQ's columns judged on its 60 s scans, not
    on the probe's 15 min rows they are held onto: stranger83's motor was said to be a
    count)."""
    out = []
    for header, name in plan.names.items():
        if plan.roles.get(header) != "temperature":
            continue
        own = (scans or {}).get(name)
        steps = [np.abs(np.diff(np.asarray(v, dtype=float))) for v in own] if own else [
            np.abs(np.diff(df[name].to_numpy(float))) for df in ds.campaigns.values() if name in df]
        steps = np.concatenate(steps) if steps else np.array([])
        finite = steps[np.isfinite(steps)]
        share = float(np.mean(finite >= JUMPY_K)) if finite.size else 0.0
        if share >= JUMPY_SHARE:
            out.append(f"warning: {header!r} is proposed as a temperature, but {share:.0%} of its "
                       f"steps from a sample to the next are {JUMPY_K:g} K or more: a number, a "
                       f"count or an index (a state)? data.roles.state=['{header}'] (or "
                       "data.roles.ignore)")
    return out


# manifest columns that are the contract's or say one campaign, not a group of them
NOT_GROUPS = {"campaign", "file", "split", "start", "notes", "continues", "error_file"}


def group_columns(manifest: pd.DataFrame) -> dict[str, list[str]]:
    """``{column: its labels}`` of the manifest columns of text labels that group the campaigns
    (a fleet's ``machine``: at least two labels, each on two campaigns or more): init wrote a
    config that pools every machine into one model and said nothing of the column."""
    out = {}
    for column in manifest.columns:
        values = manifest[column]
        if str(column) in NOT_GROUPS or pd.api.types.is_numeric_dtype(values) or values.isna().any():
            continue
        counts = values.astype(str).value_counts(sort=False)
        if len(counts) >= 2 and counts.min() >= 2:
            out[str(column)] = list(counts.index)
    return out


def _table_start(sample: Path, opts, unit: str = "line") -> str:
    """Where the table starts, said when not on the first line (a preamble, a unit row)."""
    if opts.skip_rows == 1 or not is_text(sample):
        return ""
    preamble = header_line(head_lines(sample, opts.encoding), opts.delimiter) or 0
    units = f", units from {unit} {preamble + 2}" if opts.skip_rows > preamble + 1 else ""
    left = f" ({preamble} {unit}(s) above it left out)" if preamble else ""
    return (f", header on {unit} {preamble + 1}{left}{units}; rows counted from {unit} "
            f"{opts.skip_rows + 1}")


def _seconds_unit(header: str, opts) -> str:
    """The unit a numeric time column is read in, said where the header does not give it."""
    unit = time_unit(header, opts)
    if unit:
        return f", in {unit}"
    return f", in seconds: no unit in the header (data.units={{{header!r}: ms}} if not seconds)"
