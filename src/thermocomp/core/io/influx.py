"""InfluxDB 2.x annotated CSV (extension): what ``influx query --raw`` and the UI's download write,
read as a historian's long file (:mod:`.historian`: one reader of tag samples, not two).

The file is a run of TABLES: each block starts with its annotation rows (``#group``,
``#datatype``, ``#default``), then its header ``,result,table,_start,_stop,_time,_value,_field,
_measurement,<tags...>``, then its rows; a blank line ends a block, and a new one begins where the
columns or their types change (a series whose field was written as a float one day and as an
integer the next comes back as two tables, in two blocks).  Each table is one SERIES: its
``_measurement``, its tags and its ``_field``.  The samples are the rows' ``_time`` (RFC3339, UTC
``Z``) and ``_value`` (typed by ``#datatype``: a ``double``, ``long`` or ``unsignedLong`` as its
number, a ``boolean`` as 1 / 0; a ``string`` series is no signal: left out, said).  Without the
annotation rows a series' values say their type.

The PIVOTED form (``|> pivot(rowKey: ["_time"], columnKey: ["_field"], valueColumn: "_value")``)
has no ``_value``: one column per field (``#group`` false), an empty cell where the field has no
point at that stamp; each field column is a series (with the table's tags), its non-empty cells
its samples.

A series is named by what tells it from the others (so a tag every series shares, the machine,
is left out): the values of the tags that differ between series, then its field where the tags
alone do not tell it (or there are none), then its measurement where names still clash; a
``unit`` tag (``unit``, ``units``, ``uom``) is no part of the name but its unit, written as a
header's, ``Rail_top [degC]``, read as any header's unit is.  The samples go to the historian's
reader (each series held onto the grid of ``data.resample_s``); a message about a sample names the
file's own line.  Refused (exit 2, file and line): an error table (a failed query's ``error``,
``reference``), a block without ``_time``, a block with neither ``_value`` nor a field column.
"""

from __future__ import annotations

import io
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from ...base.errors import listed
from ...base.log import logger
from .contract import ContractError
from .csvline import SPLIT, split_line
from .encoding import text_codec

ANNOTATIONS = ("#group", "#datatype", "#default")
# the columns Flux writes that are no tag: the result's name, the table's number, the query's
# range, the sample's time and value, the series' field and measurement
RESERVED = frozenset({"result", "table", "_start", "_stop", "_time", "_value", "_field",
                      "_measurement"})
UNIT_TAGS = frozenset({"unit", "units", "uom", "einheit", "unite", "unidad"})
NUMBER_TYPES = frozenset({"double", "long", "unsignedlong"})
BOOLEAN = "boolean"
TIME, SERIES, VALUE = "_time", "_field", "_value"       # the long layout's header


def is_influx(lines: list[str]) -> bool:
    """The first (non-blank) lines of a file are Flux's annotated CSV (an annotation row
    first), or its header without annotations (``,result,table,...,_time``)."""
    first = next((ln for ln in lines if ln.strip()), "")
    if first.split(",", 1)[0].strip() in ANNOTATIONS:
        return True
    cells = [c.strip() for c in first.split(",")]
    return "_time" in cells and {"result", "table"} <= set(cells[:3])


@dataclass
class _Block:
    """One annotated block: its header line (1-based), header, annotations, data line range."""

    header_line: int
    header: list[str]
    annotations: dict = field(default_factory=dict)
    first: int = 0              # (0-based indices into the file's lines, end excluded)
    end: int = 0


def _blocks(lines: list[str], path) -> list[_Block]:
    blocks, annotations, current = [], {}, None
    for k, line in enumerate(lines):
        if not line.strip():
            current, annotations = None, {}
            continue
        head = line.split(",", 1)[0].strip()
        if head.startswith("#"):
            if current is not None:              # annotations after rows: a new block
                current, annotations = None, {}
            annotations[head] = split_line(line, ",", SPLIT)
            continue
        if current is None:
            cells = [c.strip() for c in split_line(line, ",", SPLIT)]
            current = _Block(k + 1, cells, annotations, k + 1, k + 1)
            blocks.append(current)
            annotations = {}
            continue
        current.end = k + 1
    if not blocks:
        raise ContractError("an InfluxDB CSV export without a table (its annotation rows and no "
                            "header): the query returned nothing", file=path)
    return blocks


def _annotation(block: _Block, name: str) -> dict:
    """Column -> the ``name`` annotation's cell (``#datatype``: lower case)."""
    cells = block.annotations.get(name)
    if cells is None:
        return {}
    out = dict(zip(block.header, (c.strip() for c in cells)))
    return {k: v.lower() for k, v in out.items()} if name == "#datatype" else out


def _frame(lines: list[str], block: _Block) -> pd.DataFrame:
    """The block's rows as text (empty cells its ``#default``'s), ``line`` the file's line."""
    text = "\n".join(lines[block.first:block.end])
    names = [h if h else f"#{i}" for i, h in enumerate(block.header)]
    frame = pd.read_csv(io.StringIO(text), header=None, names=names, dtype=str,
                        keep_default_na=False, skip_blank_lines=False, index_col=False)
    frame = frame.apply(lambda s: s.str.strip())
    for column, default in _annotation(block, "#default").items():
        if column and default and column in frame:
            frame.loc[frame[column] == "", column] = default
    frame["#line"] = np.arange(block.first + 1, block.end + 1)
    return frame


def _kind(declared: str | None, cells: pd.Series) -> str:
    """A series' type: its ``#datatype``, else what its cells say (numbers, true / false)."""
    if declared:
        return declared
    filled = cells[cells != ""]
    if filled.str.lower().isin(["true", "false"]).all():
        return BOOLEAN
    return "double" if pd.to_numeric(filled, errors="coerce").notna().all() else "string"


def _series_key(measurement: str, tags: dict, field_name: str) -> tuple:
    return (measurement, tuple(sorted(tags.items())), field_name)


def _samples_of(block: _Block, frame: pd.DataFrame, path, keys: dict, left_out: dict
                ) -> list[pd.DataFrame]:
    """The block's samples per series: ``#line``, ``_time``, ``_value`` (text), ``key`` (the
    series' number in ``keys``, series key -> number, which it extends)."""
    header = [h for h in block.header if h]
    if header[:2] == ["error", "reference"] or header == ["error"]:
        said = frame["error"].iloc[0] if len(frame) else ""
        raise ContractError(f"the export holds InfluxDB's error {said!r}, not a table: the query "
                            "failed; run it again", file=path, line=block.first + 1)
    if TIME not in header:
        raise ContractError(f"a table without {TIME!r} (its columns: {listed(header, 8)}): each "
                            "sample needs its time; an aggregate keeps it with |> aggregateWindow"
                            "(), not with |> mean()", file=path, line=block.header_line)
    types, group = _annotation(block, "#datatype"), _annotation(block, "#group")
    others = [h for h in header if h not in RESERVED]
    if VALUE in header:                                        # the long form: one value column
        fields, tags = None, others
    else:                                                      # pivoted: a column per field
        fields = [h for h in others if (group.get(h) == "false" if group else
                                        types.get(h, "double") != "string")]
        tags = [h for h in others if h not in fields]
        if not fields:
            raise ContractError(f"a table with neither {VALUE!r} nor a field column (its "
                                f"columns: {listed(header, 8)})", file=path,
                                line=block.header_line)
    by = [c for c in ("_measurement", *tags, *(["_field"] if fields is None else []))
          if c in frame]
    out = []
    groups = frame.groupby(by, sort=False) if by else [((), frame)]
    for values, rows in groups:
        named = dict(zip(by, values if isinstance(values, tuple) else (values,)))
        measurement = named.pop("_measurement", "")
        field_name = named.pop("_field", "")
        for column in ([VALUE] if fields is None else fields):
            cells = rows[column]
            rows_of = rows if fields is None else rows[cells != ""]
            key = _series_key(measurement, named, field_name if fields is None else column)
            kind = _kind(types.get(column), rows_of[column])
            if kind not in NUMBER_TYPES and kind != BOOLEAN:
                left_out.setdefault(key, kind)
                continue
            value = rows_of[column]
            if kind == BOOLEAN:
                value = value.str.lower().map({"true": "1", "false": "0"}).fillna(value)
            number = keys.setdefault(key, len(keys))
            out.append(pd.DataFrame({"#line": rows_of["#line"].to_numpy(),
                                     TIME: rows_of[TIME].to_numpy(), VALUE: value.to_numpy(),
                                     "key": np.full(len(rows_of), number)}))
    return out


def series_names(keys) -> dict:
    """Each series' name: the values of the tags that differ between the series, then its field
    where those do not tell it (or there are none), then its measurement where names still
    clash; `` [<unit>]`` its unit tag's (see the module)."""
    keys = list(dict.fromkeys(keys))
    tags_of = {k: {t: v for t, v in k[1] if t.lower() not in UNIT_TAGS} for k in keys}
    unit_of = {k: next((v for t, v in k[1] if t.lower() in UNIT_TAGS and v), None) for k in keys}
    tag_names = sorted({t for tags in tags_of.values() for t in tags})
    varying = [t for t in tag_names if len({tags_of[k].get(t) for k in keys}) > 1]
    base = {k: ".".join(tags_of[k][t] for t in varying if tags_of[k].get(t)) for k in keys}
    fields = {}
    for k in keys:
        fields.setdefault(base[k], set()).add(k[2])
    names = {k: base[k] if base[k] and len(fields[base[k]]) == 1 else
             ".".join(p for p in (base[k], k[2]) if p) for k in keys}
    for rule in (lambda k: ".".join(p for p in (k[0], names[k]) if p),
                 lambda k: ".".join(p for p in (names[k], unit_of[k] or "") if p)):
        clash = pd.Series(list(names.values())).duplicated(keep=False).to_numpy()
        names = {k: rule(k) if c else names[k] for k, c in zip(keys, clash)}
    return {k: (names[k] or VALUE) + (f" [{unit_of[k]}]" if unit_of[k] else "") for k in keys}


def influx_samples(path: Path, encoding: str) -> pd.DataFrame:
    """The file's samples as a long file's rows: ``_time``, ``_field`` (the series' name),
    ``_value`` (text), indexed by the file's line less one (a message names the line)."""
    with open(path, encoding=text_codec(encoding), newline="") as f:
        lines = f.read().splitlines()
    keys: dict = {}
    left_out: dict = {}
    parts = []
    for block in _blocks(lines, path):
        if block.end > block.first:
            parts.extend(_samples_of(block, _frame(lines, block), path, keys, left_out))
    if not parts:
        raise ContractError("an InfluxDB CSV export without a numeric series"
                            + (f" (left out, of type string: {listed(_said(left_out), 8)})"
                               if left_out else ""), file=path)
    samples = pd.concat(parts, ignore_index=True)
    names = series_names([*keys, *left_out])
    if left_out:        # (once, though init reads it twice: log.said_once)
        logger.warning("%s: %d series of another type than a number or a boolean left out: %s",
                       path, len(left_out), listed([f"{names[k]} ({v})" for k, v in
                                                    left_out.items()], 8))
    number_names = np.array([names[k] for k in keys], dtype=object)
    samples[SERIES] = number_names[samples.pop("key").to_numpy()]
    samples.index = samples.pop("#line").to_numpy() - 1
    return samples[[TIME, SERIES, VALUE]]


def _said(left_out: dict) -> list[str]:
    return [".".join(p for p in (k[0], *(v for _, v in k[1]), k[2]) if p) for k in left_out]
