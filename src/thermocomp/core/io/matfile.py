"""A MATLAB ``.mat`` file read as its CSV export (:mod:`.labfile`): a file saved by MATLAB up
to ``-v7`` through SciPy (``scipy.io.loadmat``), one saved ``-v7.3`` (HDF5) through h5py (the
``matlab`` extra; MATLAB stores an array column by column, HDF5 row by row: each array is
transposed back to MATLAB's rows and columns).

What a lab saves, each read as channels:

* a struct whose fields are vectors of one length (``data.T1``, ``data.dX``, ``data.t``): a
  channel per field (a field of one value or of text, ``data.name``, is no channel; a struct
  field ``units`` of text fields gives their units: ``data.units.T1 = 'degC'``);
* a numeric matrix and a cell array of names, one per column (``X`` and ``names``; a name may
  carry its unit: ``'Spindle nose [degC]'``);
* a struct array or a cell array of such structs: one run each (a campaign each; its ``name``
  field, else ``runs(k)``, names it).

Names say units as a CSV header's do (``dX_um``, ``T1 [degC]``).  A time field (named as a
time, or of rising datenums whatever its name) whose values are MATLAB datenums (days since the
year 0: 7.4e5 for 2026) is read as timestamps, and said: on the clock MATLAB's ``now`` and
``datenum`` give (no zone: ``data.timezone``'s, as a CSV file's time without an offset), to the
millisecond.  A MATLAB ``table``, ``timetable`` or ``datetime`` saved in a ``.mat`` is an object neither SciPy
nor h5py reads: refused, saying how to save it.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ...base.extras import require
from ...base.log import logger
from .contract import ContractError
from .labfile import Channel, Record, with_unit
from .roles import named_as_time

MAT_SUFFIXES = (".mat",)
_HDF5 = b"\x89HDF\r\n\x1a\n"
DATENUM_1970 = 719529.0                       # MATLAB's datenum of 1970-01-01
DATENUMS = (693962.0, 767011.0)               # 1900 .. 2100: a time field read as datenums
OBJECTS = ("table", "timetable", "datetime", "duration", "string", "categorical")
SAVE_TABLE = ("save it as a struct of vectors (S = table2struct(T, 'ToScalar', true); "
              "save('f.mat', 'S')) or as CSV (writetable(T, 'f.csv'))")
NAME_FIELDS = ("name", "Name", "label", "id", "run")
UNIT_FIELDS = ("units", "Units", "unit", "Unit")


class Opaque:
    """A MATLAB object (a ``table``, a ``datetime`` ...) neither library reads."""

    def __init__(self, kind: str):
        self.kind = kind


def is_mat(path) -> bool:
    return Path(path).suffix.lower() in MAT_SUFFIXES


def is_v73(path: Path) -> bool:
    """Saved ``-v7.3``: an HDF5 file behind MATLAB's 512-byte header."""
    with open(path, "rb") as f:
        f.seek(512)
        return f.read(8) == _HDF5


def mat_records(path: Path) -> list[Record]:
    """The runs of the ``.mat`` file ``path``."""
    variables = _v73(path) if is_v73(path) else _v5(path)
    for name, value in variables.items():
        kind = _opaque(value)
        if kind:
            raise ContractError(f"variable {name!r} is a MATLAB {kind}, an object neither SciPy nor "
                                f"h5py reads: {SAVE_TABLE}", file=path)
    records: list[Record] = []
    for name, value in variables.items():
        records += _records(name, value, variables, path)
    if not records:
        raise ContractError("no struct of equal-length vectors, no matrix with a cell array of "
                            f"its column names in it (variables: {', '.join(variables) or 'none'})",
                            file=path)
    return records


def _opaque(value) -> str | None:
    if isinstance(value, Opaque):
        return value.kind
    if isinstance(value, dict):
        return next((k for v in value.values() if (k := _opaque(v))), None)
    if isinstance(value, list):
        return next((k for v in value if (k := _opaque(v))), None)
    return None


# --- a file's variables as Python values (arrays in MATLAB's orientation, str, dict, list) ---

def _v5(path: Path) -> dict:
    import scipy.io as sio
    from scipy.io.matlab import MatlabOpaque

    try:
        raw = sio.loadmat(path, squeeze_me=False, struct_as_record=True, chars_as_strings=True)
    except Exception as exc:         # SciPy's errors of a file it does not read
        raise ContractError(f"not a MATLAB file that is read ({type(exc).__name__}: {exc})",
                            file=path) from None

    def value(v):
        if isinstance(v, MatlabOpaque) or (isinstance(v, np.ndarray) and v.dtype.names
                                           and set(v.dtype.names) == {"s0", "s1", "s2", "arr"}):
            return Opaque(_class_name(v))
        if isinstance(v, np.ndarray) and v.dtype.names:          # a struct (array)
            items = [{f: value(e[f]) for f in v.dtype.names} for e in v.ravel(order="F")]
            return items[0] if v.size == 1 else items
        if isinstance(v, np.ndarray) and v.dtype == object:      # a cell array
            return [value(e) for e in v.ravel(order="F")]
        if isinstance(v, np.ndarray) and v.dtype.kind in "US":
            return " ".join(str(s) for s in v.ravel())
        if isinstance(v, str):
            return v
        return np.asarray(v)

    return {k: value(v) for k, v in raw.items() if not k.startswith("__")}


def _class_name(opaque) -> str:
    """The class of a MATLAB object SciPy gives as an opaque record (its ``s2`` field:
    ``table``, ``datetime``), ``object`` where it does not say."""
    try:
        name = np.asarray(opaque["s2"]).ravel()[0]
        name = np.asarray(name).ravel()[0] if isinstance(name, np.ndarray) else name
    except (IndexError, KeyError, ValueError, TypeError):
        return "object"
    return name.decode(errors="replace") if isinstance(name, bytes) else str(name) or "object"


def _v73(path: Path) -> dict:
    require("h5py")
    import h5py

    try:
        f = h5py.File(path, "r")
    except Exception as exc:
        raise ContractError(f"not a MATLAB -v7.3 file that is read ({type(exc).__name__}: {exc})",
                            file=path) from None

    def kind(node) -> str:
        c = node.attrs.get("MATLAB_class", b"")
        return c.decode() if isinstance(c, bytes) else str(c)

    def value(node):
        k = kind(node)
        if isinstance(node, h5py.Group):
            if k in OBJECTS:
                return Opaque(k)
            fields = _field_order(node)
            arrays = {n: node[n] for n in fields}
            if fields and all(isinstance(a, h5py.Dataset) and a.dtype == h5py.ref_dtype
                              for a in arrays.values()):     # a struct array: references
                refs = {n: a[()].T.ravel(order="F") for n, a in arrays.items()}
                count = len(next(iter(refs.values())))
                return [{n: value(f[refs[n][i]]) for n in fields} for i in range(count)]
            return {n: value(a) for n, a in arrays.items()}
        if k in OBJECTS or node.attrs.get("MATLAB_object_decode") is not None:
            return Opaque(k or "object")
        data = node[()]
        if node.dtype == h5py.ref_dtype:                            # a cell array
            return [value(f[r]) for r in data.T.ravel(order="F")]
        if k == "char":
            return "".join(chr(c) for c in np.asarray(data).T.ravel(order="F") if c)
        if node.attrs.get("MATLAB_empty"):
            return np.zeros((0, 0))
        return np.asarray(data).T                                  # MATLAB's rows and columns

    try:
        return {n: value(f[n]) for n in f.keys() if not n.startswith("#")}
    finally:
        f.close()


def _field_order(group) -> list[str]:
    """A struct's fields in MATLAB's order (its ``MATLAB_fields`` attribute), else HDF5's."""
    names = list(group.keys())
    said = group.attrs.get("MATLAB_fields")
    if said is None:
        return names
    order = [b"".join(np.asarray(f).astype("S1").tolist()).decode() for f in said]
    return [n for n in order if n in names] + [n for n in names if n not in order]


# --- variables as runs --------------------------------------------------------------------

def _records(name: str, value, variables: dict, path: Path) -> list[Record]:
    if isinstance(value, dict) and _vectors(value):
        return [_struct(name, value, path)]
    if isinstance(value, list) and value and all(isinstance(v, dict) and _vectors(v) for v in value):
        return [_struct(f"{name}({i + 1})", v, path, _label(v, f"{name}({i + 1})"))
                for i, v in enumerate(value)]
    if isinstance(value, np.ndarray) and value.ndim == 2 and value.dtype.kind in "fiub" and min(
            value.shape) > 1:
        names = _names_for(value, variables)
        if names is not None:
            return [_matrix(name, value, names, path)]
    return []


def _vectors(struct: dict) -> dict[str, np.ndarray]:
    """The fields of ``struct`` that are numeric vectors of two values or more."""
    return {f: v.ravel(order="F") for f, v in struct.items() if isinstance(v, np.ndarray)
            and v.dtype.kind in "fiub" and v.size > 1 and min(v.shape) == 1}


def _label(struct: dict, fallback: str) -> str:
    for f in NAME_FIELDS:
        v = struct.get(f)
        if isinstance(v, str) and re.search(r"[^\W\d_]", v):
            return v
    return fallback


def _struct(where: str, struct: dict, path: Path, label: str | None = None) -> Record:
    fields = _vectors(struct)
    units = next((u for f in UNIT_FIELDS if isinstance(u := struct.get(f), dict)), {})
    n = max(v.size for v in fields.values())
    short = {f: v.size for f, v in fields.items() if v.size != n}
    if short:
        f, size = next(iter(short.items()))
        raise ContractError(f"variable {where!r}: field {f!r} has {size} values, the struct's "
                            f"others {n}: its channels are read as one table of rows (resample "
                            f"the field to the others' rate, or save it apart)", file=path)
    channels, time, time_header = [], None, "time"
    for f, v in fields.items():
        header = with_unit(f, units.get(f) if isinstance(units.get(f), str) else None)
        if time is None and _is_time(header, v):
            time, time_header = _time(v, f"{where}.{f}", path), header
            continue
        channels.append(Channel(header, v.astype(float), None, f"variable '{where}.{f}'"))
    return _timed(label or where, channels, time, time_header)


def _timed(label: str, channels: list[Channel], time, time_header: str) -> Record:
    """A record of ``channels`` on ``time`` (timestamps: under ``time``, on no clock said)."""
    for c in channels:
        c.time = time
    if time is not None and np.issubdtype(time.dtype, np.datetime64):
        time_header = "time"
    return Record(label, channels, time_header, utc=False)


def _is_time(header: str, values: np.ndarray) -> bool:
    """A field named as a time (``t``, ``time``, ``Zeit``), or of datenums rising (``date``,
    ``dn``: no sensor reads 7.4e5)."""
    v = np.asarray(values, float)
    return named_as_time(header) or bool(
        v.size > 1 and np.isfinite(v).all() and (np.diff(v) > 0).all()
        and DATENUMS[0] <= v.min() and v.max() <= DATENUMS[1])


def _time(values: np.ndarray, where: str, path: Path) -> np.ndarray:
    """A time field: seconds as given, or MATLAB datenums (days since year 0) as timestamps."""
    v = values.astype(float)
    finite = v[np.isfinite(v)]
    if finite.size and DATENUMS[0] <= finite.min() and finite.max() <= DATENUMS[1]:
        said = re.sub(r"\(\d+\)", "(k)", where)   # (one text for every run: log.said_once)
        logger.info(f"{path.name}: {said} read as MATLAB datenums (days since the year 0), "
                    "timestamps to the millisecond (a datenum holds about 10 µs)")
        milli = np.round((v - DATENUM_1970) * 86400e3).astype("int64")
        return milli.astype("datetime64[ms]")
    return v


def _names_for(matrix: np.ndarray, variables: dict) -> list[str] | None:
    """A cell array of text naming each column of ``matrix`` (or each row: channels in rows)."""
    for value in variables.values():
        if isinstance(value, list) and value and all(isinstance(v, str) for v in value):
            if len(value) in matrix.shape:
                return value
    return None


def _matrix(name: str, matrix: np.ndarray, names: list[str], path: Path) -> Record:
    if matrix.shape[1] != len(names):           # channels in rows: transposed to columns
        matrix = matrix.T
    channels, time, time_header = [], None, "time"
    for i, header in enumerate(names):
        column = matrix[:, i].astype(float)
        if time is None and _is_time(header, column):
            time, time_header = _time(column, f"{name}(:, {i + 1})", path), header
            continue
        channels.append(Channel(header, column, None, f"variable {name!r}, column {i + 1}"))
    return _timed(name, channels, time, time_header)
