"""Campbell Scientific's ASCII tables (extension, lab74): TOA5, what LoggerNet writes by default
for a CR1000 / CR6 logger, and TOACI1, the older one.

A TOA5 file's first line is its environment, ``"TOA5","<station>","<logger model>","<serial>",
"<OS>","<program>","<signature>","<table>"``; the field names follow (``"TIMESTAMP","RECORD",
"T_spindle_Avg"``), then their units (``"TS","RN","Deg C"``) and how each was processed
(``"","","Avg"``), then the rows.  TOACI1 writes ``"TOACI1","<station>","<table>"`` and the
names alone.  The environment line is the preamble above the header (:mod:`.layout`), the units
row the header's unit row whatever its units say (a program's own spelling, ``Volts``: joined to
its header, and a unit the reader does not know is refused as in any file), Campbell's ``TS`` /
``RN`` (a timestamp, a record number) joined to none, and the processing row a row describing
the channels (:func:`.layout.property_rows`).  ``TIMESTAMP`` (``TMSTAMP``) is the time and
``RECORD`` (``RECNBR``) the logger's counter, left out (:func:`.roles.logger_columns`); the
logger's ``NAN`` is a missing value (:data:`.tables.MISSING_TOKENS`).
"""

from __future__ import annotations

from .csvline import EMPTY, split_line

# the format a file's first field names -> whether a units row (and a processing row) follow
# the names
# (TOB1: its rows binary, :mod:`.tob1`; TOB2 / TOB3: binary frames, :mod:`.tob3`)
FORMATS = {"TOA5": True, "TOACI1": False, "TOB1": True, "TOB2": True, "TOB3": True}
TIME_HEADERS = ("timestamp", "tmstamp")
COUNTERS = ("record", "recnbr")         # the logger's record number beside its timestamp
_NO_UNIT = {"TS", "RN"}                 # the units row's marks of the timestamp and the counter
_SPELLED = {"volts": "V", "millivolts": "mV"}    # CRBasic's manual spells a logger's battery so
# the environment line's fields after the format's, by format
_FIELDS = {**dict.fromkeys(("TOA5", "TOB1"), ("station", "logger", "serial", "os", "program",
                                                "signature", "table")),
           "TOACI1": ("station", "table"),
           # (TOB2 / TOB3: the table is named on line 2, the file's creation time here)
           **dict.fromkeys(("TOB2", "TOB3"), ("station", "logger", "serial", "os", "program",
                                               "signature", "created"))}


def environment(line: str | None) -> dict[str, str] | None:
    """The fields of a Campbell file's first ``line`` by name (``format``, ``station``,
    ``table`` ...); None where ``line`` is no TOA5 / TOACI1 environment line."""
    fields = split_line(line or "", ",", EMPTY)
    if not fields or fields[0].strip() not in FORMATS:
        return None
    return {"format": fields[0].strip(), **dict(zip(_FIELDS[fields[0].strip()], fields[1:]))}


def has_unit_row(lines: list[str]) -> bool:
    """The line under the header of a file whose first ``lines`` these are is Campbell's units
    row (a TOA5 file's third line)."""
    found = environment(lines[0] if lines else None)
    return found is not None and FORMATS[found["format"]]


def units(row: list[str]) -> list[str]:
    """A TOA5 units row as a unit row is joined to the headers: ``TS`` / ``RN`` no unit,
    ``Volts`` the reader's ``V``."""
    return ["" if cell.strip() in _NO_UNIT else _SPELLED.get(cell.strip().lower(), cell)
            for cell in row]


def said(line: str | None, table: str | None = None) -> str:
    """How ``init`` names the file: ``a Campbell Scientific TOA5 table 'Therm10min' of station
    'MZ_Halle3' (CR1000X, serial 12345, program 'CPU:thermo.CR1X')``; '' for any other file
    (``table``: its name where another line gives it, a TOB3 file's line 2)."""
    found = environment(line)
    if found is None:
        return ""
    if table is not None:
        found["table"] = table
    logger = ", ".join(f"program {found[k]!r}" if k == "program" else
                       f"serial {found[k]}" if k == "serial" else found[k]
                       for k in ("logger", "serial", "program") if found.get(k, "").strip())
    return (f"a Campbell Scientific {found['format']} table {found.get('table', '')!r} of "
            f"station {found.get('station', '')!r}" + (f" ({logger})" if logger else ""))
