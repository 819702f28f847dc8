"""The units a lab writes in its headers, and the role a header's unit says.

One rule for ``thermocomp init``'s proposals and for ``run``'s reading of a header that no
``data.roles`` pattern matches (:func:`role_by_unit`): a length is an error, unless its name
says a position (a machine state) or only an axis, over mm (``X [mm]``, ``X-Achse [mm]``: its
position or its error, listed, never guessed); a small angle (``Tilt A [µrad]``, ``[arcsec]``,
``[″]``: a sensor nest's tilt) an angular error; a speed, a power, a current, an on/off flag, an
angle (``Eje A [°]``) is a state; anything else says no role (a temperature, or, without a unit,
a name).
"""

from __future__ import annotations

import re

from ...base.errors import config_file_form
from .contract import role

# unit (lower case, no spaces) -> (scale, offset) to the contract's unit; a micrometre as a
# keyboard without µ spells it, 'um', 'mu m' ('mum' once its space is gone: audit100), 'micron'
UNITS = {
    "E": {**dict.fromkeys(("µm", "μm", "um", "mum", "micron", "microns"), (1.0, 0.0)), "mm": (1e3, 0.0),
          "m": (1e6, 0.0), "nm": (1e-3, 0.0)},
    # (the degree sign as a lab's keyboard gives it: º, U+00BA on a Spanish or Italian one, and
    # ˚, U+02DA, look like ° in a header and in the message refusing them)
    "T": {**dict.fromkeys(("°c", "ºc", "˚c", "c", "degc", "℃", "celsius", "deg.c"), (1.0, 0.0)),
          **dict.fromkeys(("k", "kelvin"), (1.0, -273.15)),
          **dict.fromkeys(("°f", "ºf", "˚f", "f", "degf", "℉", "fahrenheit"),
                          (5 / 9, -32 * 5 / 9))},
    "time": {**dict.fromkeys(("s", "sec", "secs", "seconds"), (1.0, 0.0)), "ms": (1e-3, 0.0),
             "min": (60.0, 0.0), **dict.fromkeys(("h", "hr", "hours"), (3600.0, 0.0)),
             **dict.fromkeys(("d", "day", "days"), (86400.0, 0.0))},     # (Excel's serial days)
    # extension (iso67): an angle small enough to be an error, a sensor nest's tilt (ISO 230-3),
    # read as an angular error in the contract's µm/m (= µrad); a degree is a state (an axis')
    "angle": {**dict.fromkeys(("µrad", "μrad", "urad", "µm/m", "μm/m", "um/m"), (1.0, 0.0)),
              **dict.fromkeys(("mrad", "mm/m"), (1e3, 0.0)),
              **dict.fromkeys(("arcsec", "″", '"', "''", "asec"), (4.84813681109536, 0.0))},
}

# a temperature's unit as one letter after a space ('T1 K', 'Probe F'), read as the unit where
# the first value is one in it, from this value (a °C reading below: 'Sensor K' is a name)
LETTER_UNITS = {"k": 150.0, "f": 45.0}

# units that say "a machine state" (speeds, loads, positions, on/off); a speed as labs spell
# revolutions per minute in their language (audit96: an Italian PC's unit row 'giri/min' was no
# unit, so the row was read as data and every column refused as text): German U/min, Italian
# giri/min, French tr/min, English rev/min, r/min
STATE_UNITS = {"rpm", "krpm", "1/min", "min-1", "u/min", "giri/min", "tr/min", "rev/min", "r/min",
               "%", "hz", "a", "w", "kw", "nm", "bar", "v", "on/off", "0/1", "mm/min"}
# a voltage as a DAQ labels a DC or AC volts channel (Keysight's VDC, VAC): a probe's signal
VOLTS = {"v", "vdc", "vac", "mv", "mvdc"}
# a dimensionless unit in brackets, '[-]' or '[1]' (DIN 1313's "no unit"): an on/off flag, a
# ratio, a count, never a temperature, so a state (the contract's S_door, 0 closed, 1 open).
# Not among STATE_UNITS: as a header's last word ('Sensor 1') it is part of a name
DIMENSIONLESS = {"-", "–", "1"}
# an on/off flag as a gateway, pandas or Excel writes it in a CSV cell ('true' / 'false'): a
# state, read as 1 / 0 (as a workbook's boolean cell is); the words Arrow's reader reads so
FLAG_WORDS = {"true": 1, "True": 1, "TRUE": 1, "false": 0, "False": 0, "FALSE": 0}
NEWTON_METRES = ("Nm", "N.m", "N·m")   # a torque, a state: not nanometres (nm)
# an angle (a tilt or rotary axis, 'Eje A [°]'): a state.  The degree sign alone is the angle's
# (ISO 80000-3; a temperature's is °C), unless the name says a temperature ('Temp [°]': refused
# as a temperature without its scale, as before)
ANGLE_UNITS = {"°", "º", "˚", "deg", "rad"}
STATE_WORDS = {"state", "states", "status", "zustand", "estado", "stato", "etat", "état"}
_TEMPERATURE_WORD = re.compile(r"t\d*|temp.*|.*temperat.*")
# a name that says "a set point" (stranger69: a chiller's 'Sollwert Ölkühler [Deg C]' was read
# as a temperature sensor, and said a dead channel): what the control is told, not a reading,
# so a state whatever its unit; 'set point' / 'set-point' joined, a German 'Soll...' word
_SET_POINT = re.compile(r"setpoints?|soll.*|consigna|consigne|sollwert")

# a name that says "the air's relative humidity" (lab76): with '%' no machine state, and no
# thermal input of a compensation model (what it says of the machine the air's temperature says)
_HUMIDITY_WORD = re.compile(r"rh|rf|hum|.*humid.*|.*feucht.*|humedad|umidit.*")

AMBIGUOUS = "error or state"
_WORDS = re.compile(r"[\s_.\-]+")
# a name that says "measured displacement": dX, ΔZ, delta, error, Fehler, Abweichung ... (it
# wins over a position word: 'Positionsfehler', 'Querachse dZ' are errors)
_ERROR_WORD = re.compile(r"[dδ][xyzuvw]\d*|δ.*|delta.*|err|errors?|.*fehler|.*abweichung|deviation"
                         r"|displacement|.*verlagerung|verschiebung|drift|deformation")
# a name that says "where the axis is": position, Pos., Ypos, Istposition, an Italian or Spanish
# lab's posizione, posición, corsa (an axis' travel) (a machine state)
_POSITION_WORD = re.compile(r".*positions?|pos|[xyzuvw]pos|coordinates?|koordinaten?|posizion[ei]"
                            r"|posici[oó]n|corsa")
# a name that says only "which axis": X, Y2, X-Achse, Querachse, axis (its position or, as
# a lab names a probe by the axis it measures along, its error)
_AXIS_WORD = re.compile(r"[xyzuvw]\d*|.*achse|axis")


# a unit written as one (lab75): per second, metre, hour, square or cubic metre, or a power,
# W/m^2, m/s, g/m³, as a flux station's logger writes its radiation and wind beside the
# machine's channels; a TOA5 program's "unitless" ('T1 (front/left)' is a note: no unit)
_UNIT_FORM = re.compile(r"[^\s/]+(?:/(?:s|m|h|min|kg|l|mol|m\^?[23²³]))+|\S*(?:\^\d|[²³])\S*"
                        r"|unitless")


def is_known_unit(unit: str) -> bool:
    """``unit`` is one the reader reads (a length, a temperature, a time, an angle, a state's)."""
    known = unit.lower().replace(" ", "")
    return (any(known in table for table in UNITS.values()) or known in STATE_UNITS
            or known in VOLTS or known in DIMENSIONLESS or known in ANGLE_UNITS)


def foreign_unit(unit: str | None, stated: bool = False) -> bool:
    """``unit`` is a unit, but of no sensor of the model (W/m^2, m/s, unitless: no temperature,
    displacement or machine state): a unit the reader does not know, written as one, or stated
    by the file's unit row (``stated``: Campbell's units line says units, where a header's
    parentheses may hold a note, ``T1 (front)``)."""
    if not unit or is_known_unit(unit):
        return False
    return stated or bool(_UNIT_FORM.fullmatch(unit.strip().lower()))


def is_humidity(base: str, unit: str | None) -> bool:
    """``base`` in ``unit`` is a relative humidity: ``%`` under a name that says so (``RH``,
    ``rel. hum.``, ``Luftfeuchte``, ``humidity``); a spindle's load in ``%`` is a state."""
    return (unit or "").strip() == "%" and any(
        _HUMIDITY_WORD.fullmatch(w) for w in _WORDS.split(base.lower()) if w)


def is_flag(cell) -> bool:
    """``cell`` is an on/off flag's word (:data:`FLAG_WORDS`)."""
    return str(cell).strip() in FLAG_WORDS


def role_by_unit(base: str, unit: str | None) -> str | None:
    """The role a header's ``unit`` says (``base``: the header without it): ``'error'``,
    ``'state'``, :data:`AMBIGUOUS` (a length in mm or m named by its axis alone, ``X``,
    ``X-Achse``: its error or its position) or None (no role from the unit: a temperature's, a
    time's, none)."""
    written = (unit or "").replace(" ", "")
    known = written.lower()
    if role(base) is None and says_set_point(base):
        return "state"
    if known in UNITS["E"] and written not in NEWTON_METRES:      # (Nm: a torque)
        return _length_role(base, known)
    if known in UNITS["angle"]:        # a tilt in µrad or arcsec: an (angular) error
        return "error"
    if known in STATE_UNITS or known in DIMENSIONLESS:
        return "state"
    words = [w for w in _WORDS.split(base.lower()) if w]
    said_hot = any(_TEMPERATURE_WORD.fullmatch(w) for w in words)
    if known in ANGLE_UNITS:
        return None if said_hot else "state"
    # a gateway's group of machine states ('state.cycle_s', 'status.door'), a lab's 'Spindle
    # state': no temperature, whatever its number looks like
    if known not in UNITS["T"] and not said_hot and any(w in STATE_WORDS for w in words):
        return "state"
    return None


def says_set_point(base: str) -> bool:
    """A header's name says a set point (:data:`_SET_POINT`): ``Sollwert Ölkühler``,
    ``Oil set point``, ``Chiller setpoint``."""
    words = [w for w in _WORDS.split(base.lower()) if w]
    joined = ["".join(pair) for pair in zip(words, words[1:])]     # ('set', 'point')
    return any(_SET_POINT.fullmatch(w) for w in words + joined)


def _length_role(base: str, unit: str) -> str:
    prefix = role(base)
    if prefix in ("E", "S"):           # a contract name says it ('S_pos [mm]' is no error)
        return "error" if prefix == "E" else "state"
    words = [w for w in _WORDS.split(base.lower()) if w]
    if any(_ERROR_WORD.fullmatch(w) for w in words):
        return "error"
    if any(_POSITION_WORD.fullmatch(w) for w in words):
        return "state"
    # an axis' readout is in mm and a thermal error rarely is: 'X [mm]', 'X-Achse [mm]' could
    # be either; in µm it is the error, as every other length is ('ch1 (um)', 'Messuhr [mm]')
    named_by_axis = words and all(_AXIS_WORD.fullmatch(w) for w in words)
    return AMBIGUOUS if unit in ("mm", "m") and named_by_axis else "error"


def ambiguity(header: str, base: str) -> str:
    """What a message says of an :data:`AMBIGUOUS` header, with the two settings to choose."""
    return (f"{header!r} is a length named by its axis alone: the error "
            f"(data.roles.error=[{base!r}]) or its position (data.roles.state=[{base!r}])?")


# notes100 (audit100): a lab's note in a temperature header's brackets, where the sensor sits
# or what it is on ('T1 (front)', 'Spindel (Gehäuse)', 'T1 (front/left)'): a word of three or
# more letters that is no unit, read as part of the column's name
NOTE = "note"
# what a refusal says of such a bracket read both ways (init looks past it: shell/stages/gathered)
TWO_READINGS = "reads as a unit the reader does not know or as a note"
_NOTE_WORD = re.compile(r"[^\W\d_]{3,}")
_NOTE_SPLIT = re.compile(r"[\s/,;+.\-]+")


def bracket_reading(unit: str | None) -> str | None:
    """How a temperature header's bracket ``unit`` reads: None where it is a unit (known, or one
    written as a unit, :func:`foreign_unit`: today's reading), :data:`NOTE` where it is a note
    (a word that is no unit), :data:`AMBIGUOUS` where it could be either (a temperature's unit
    beside a word, ``(K Kühlung)``, ``(°C front)``; a token of one or two letters or figures
    that is no unit, ``(R)``, ``(li)``: a unit the reader does not know, or an abbreviation)."""
    if not unit or not unit.strip() or is_known_unit(unit) or foreign_unit(unit):
        return None
    words = [w for w in _NOTE_SPLIT.split(unit.strip().lower()) if w]
    if any(w in UNITS["T"] for w in words):
        return AMBIGUOUS
    return NOTE if any(_NOTE_WORD.search(w) for w in words) else AMBIGUOUS


def note_ambiguity(header: str, base: str, unit: str) -> str:
    """What a refusal says of a temperature header whose bracket :func:`bracket_reading` finds
    :data:`AMBIGUOUS`: the two readings and the key for each."""
    return (f"{header!r}: ({unit}) {TWO_READINGS}, part "
            f"of the name: give its unit, data.units={{{header!r}: °C}} (or K, °F), or its name, "
            f"data.columns={{{header!r}: T_<name>}}: in a data config file, "
            + config_file_form("data", f"columns: {{{header!r}: T_<name>}}"))
