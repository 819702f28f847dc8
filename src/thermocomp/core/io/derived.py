"""``data.derive`` (extension, derive71): targets computed from a campaign's error columns.

A lab reports an ISO 230-3 spindle test as displacements and tilts: ``tilt_X = (X1 - X2) / d``
of two probes ``d`` apart.  ``data.derive: {E_tilt_X: "(E_X1 - E_X2) / 0.1"}`` adds that
column to every campaign as it is read, after the roles and units made the contract's names,
before anything else sees it: a derived column is a target like a measured one (fitted,
scored, deployed; ``replay`` and ``monitor`` score it against the same arithmetic of the
record, ``data.reference`` then applies to it as to any error).

An expression is arithmetic only: ``E_`` columns the file has, numbers, ``+ - * /``, a sign
and parentheses, parsed with :mod:`ast` and evaluated node by node (never ``eval``).  The
unit is the name's, as for any error (DATA_FORMAT.md): µm, or µm/m where the name says a
tilt (``E_tilt_X``): a µm difference divided by the spacing in metres.
"""

from __future__ import annotations

import ast
import operator
import re
from collections.abc import Callable, Mapping
from pathlib import Path

import numpy as np
import pyarrow as pa

from .contract import ContractError
from .sparse import measured_on

KEY = "data.derive"
_NAME = re.compile(r"^E_\w+$")
_OPS = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
        ast.Div: operator.truediv}
_ROLE_WORDS = {"T_": "a temperature", "S_": "a state", "time": "the time"}


def parsed(value) -> dict[str, str]:
    """``data.derive`` checked: ``{derived name: its expression}``, each name a new ``E_``
    column, each expression arithmetic of ``E_`` columns and numbers (no derived one among
    them: each is computed from the columns read); a ContractError naming the key else."""
    value = value or {}
    if not hasattr(value, "items"):
        raise ContractError(f"{KEY} must be a mapping of a new error column to its arithmetic, "
                            f"e.g. {{E_tilt_X: '(E_X1 - E_X2) / 0.1'}}, got {value!r}")
    out = {}
    for name, text in value.items():
        name, key = str(name), f"{KEY}.{name}"
        if not _NAME.match(name):
            raise ContractError(f"{key}: a derived column is a target, named E_<name> "
                                "(E_tilt_X), letters, digits and _")
        if not isinstance(text, str):
            raise ContractError(f"{key} must be an expression in quotes, e.g. "
                                f"'(E_X1 - E_X2) / 0.1', got {text!r}")
        used = columns_of(_tree(key, text), key)
        derived = sorted(set(used) & {str(n) for n in value})
        if derived:
            raise ContractError(f"{key}: {derived[0]} is derived too: write each from the "
                                "columns read")
        out[name] = text
    return out


def columns_of(tree: ast.Expression, key: str) -> list[str]:
    """The ``E_`` columns an expression reads, in order; ContractError for anything but
    arithmetic of error columns and numbers, or a division by a constant zero."""
    names: list[str] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Name):
            if not _NAME.match(node.id):
                what = next((w for p, w in _ROLE_WORDS.items() if node.id.startswith(p)),
                            "no error column")
                raise ContractError(f"{key}: {node.id} is {what}; a derived target is arithmetic "
                                    "of error columns (E_...) and numbers")
            if node.id not in names:
                names.append(node.id)
        elif isinstance(node, ast.Constant):
            if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
                raise ContractError(f"{key}: {node.value!r} is no number")
        elif isinstance(node, ast.BinOp):
            if type(node.op) not in _OPS:
                raise ContractError(f"{key}: only + - * / and parentheses, not "
                                    f"{ast.unparse(node)!r}")
            if isinstance(node.op, ast.Div) and _constant(node.right) == 0:
                raise ContractError(f"{key}: divides by zero ({ast.unparse(node.right)})")
        elif isinstance(node, ast.UnaryOp):
            if not isinstance(node.op, (ast.USub, ast.UAdd)):
                raise ContractError(f"{key}: only + - * / and parentheses, not "
                                    f"{ast.unparse(node)!r}")
        elif not isinstance(node, (ast.Expression, ast.Load, ast.operator, ast.unaryop)):
            raise ContractError(f"{key}: only + - * / and parentheses over error columns "
                                f"and numbers, not {ast.unparse(node)!r}")
    if not names:
        raise ContractError(f"{key}: reads no error column (E_...)")
    return names


def sources(name: str, text: str) -> list[str]:
    """The error columns the derived column ``name``'s expression ``text`` reads, in order."""
    key = f"{KEY}.{name}"
    return columns_of(_tree(key, text), key)


def _tree(key: str, text: str) -> ast.Expression:
    try:
        return ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        raise ContractError(f"{key}: {text!r} is no expression ({exc.msg})") from None


def _constant(node: ast.AST) -> float | None:
    """The value of a sub-expression of numbers alone, None where it reads a column."""
    try:
        return _value(node, {})
    except KeyError:
        return None
    except ZeroDivisionError:
        return 0.0


def _value(node: ast.AST, columns: Mapping):
    if isinstance(node, ast.Expression):
        return _value(node.body, columns)
    if isinstance(node, ast.Constant):
        return float(node.value)
    if isinstance(node, ast.Name):
        return columns[node.id]
    if isinstance(node, ast.UnaryOp):
        inner = _value(node.operand, columns)
        return -inner if isinstance(node.op, ast.USub) else inner
    return _OPS[type(node.op)](_value(node.left, columns), _value(node.right, columns))


def rendered(name: str, text: str, column: Callable[[str], str],
             number: Callable[[float], str]) -> str:
    """``data.derive``'s expression ``text`` of ``name`` written in another language's
    arithmetic (C's: export), fully parenthesised, node by node as :func:`_value` computes it:
    ``column`` writes a source column, ``number`` a constant (small72: the exported stream's
    reference of a derived target)."""
    def written(node: ast.AST) -> str:
        if isinstance(node, ast.Expression):
            return written(node.body)
        if isinstance(node, ast.Constant):
            return number(float(node.value))
        if isinstance(node, ast.Name):
            return column(node.id)
        if isinstance(node, ast.UnaryOp):
            return f"({'-' if isinstance(node.op, ast.USub) else '+'}{written(node.operand)})"
        sign = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.Div: "/"}[type(node.op)]
        return f"({written(node.left)} {sign} {written(node.right)})"

    sources(name, text)             # (checked: arithmetic of error columns and numbers only)
    return written(_tree(f"{KEY}.{name}", text))


def evaluated(name: str, text: str, columns: Mapping[str, np.ndarray], path: Path) -> np.ndarray:
    """The column ``name`` of a campaign whose error columns are ``columns`` (NaN where a
    source is missing); ContractError naming the file where one is not there, or where a
    division by a column gives no number (its row)."""
    key = f"{KEY}.{name}"
    tree = _tree(key, text)
    absent = [c for c in columns_of(tree, key) if c not in columns]
    if absent:
        errors = ", ".join(c for c in columns if c.startswith("E_")) or "none"
        raise ContractError(f"{key}: the campaign has no column {absent[0]} (its error columns, "
                            f"contract names: {errors})", file=path)
    with np.errstate(divide="ignore", invalid="ignore"):
        values = np.broadcast_to(np.asarray(_value(tree, columns), float),
                                 len(next(iter(columns.values())))).copy()
    sources = np.all([np.isfinite(columns[c]) for c in columns_of(tree, key)], axis=0)
    bad = np.flatnonzero(sources & ~np.isfinite(values))
    if bad.size:
        raise ContractError(f"{key}: {text} is no number (a division by zero?)", file=path,
                            column=name, row=int(bad[0]) + 1)
    return values


def with_derived(table: pa.Table, derive: Mapping[str, str], path: Path) -> pa.Table:
    """``table`` with the columns ``derive`` defines, after its error columns (missing where a
    source is: a stream's dropout stays one)."""
    if not derive:
        return table
    clash = next((n for n in derive if n in table.column_names), None)
    if clash is not None:
        raise ContractError(f"{KEY}.{clash}: the campaign has a column {clash} already (name "
                            "the derived one otherwise)", file=path)
    columns = {n: _floats(table.column(n)) for n in table.column_names if n.startswith("E_")}
    added = {n: pa.array(evaluated(n, text, columns, path), from_pandas=True)
             for n, text in derive.items()}
    last_error = max(i for i, n in enumerate(table.column_names) if n.startswith("E_"))
    for offset, (name, values) in enumerate(added.items(), 1):
        table = table.add_column(last_error + offset, name, values)
    return table


def sparse_derived(table: pa.Table, derive: Mapping[str, str], sparse: Mapping, path: Path
                   ) -> dict:
    """``{name: {"measured": rows, "every": rows}}`` of each derived column of ``table`` that
    reads a target measured now and then (``sparse``: the campaign's ``sparse_targets``): a
    target like them, measured on the rows where all its sources are (small72), fitted and
    scored there; ContractError naming the key where its sources are each measured but never on
    one row (no row to fit or score: 'MLR: the target is measured on no row' before)."""
    out = {}
    for name, text in derive.items():
        read = sources(name, text)
        if not any(c in sparse for c in read):
            continue
        out[name] = measured_on(_floats(table.column(name)))
        if not out[name]["measured"] and all(
                np.isfinite(_floats(table.column(c))).any() for c in read):
            cycles = ", ".join(f"{c} on 1 row in {sparse[c]['every']}" for c in read
                               if c in sparse)
            raise ContractError(f"{KEY}.{name}: {text} is measured on no row: its error columns "
                                f"are never measured on the same row ({cycles}); derive it from "
                                "columns measured together (one probe cycle)", file=path,
                                column=name)
    return out


def on_frame(frame, derive: Mapping[str, str], source) -> object:
    """A stream's ``frame`` (pandas: stdin's rows, a served block) with each derived column
    whose errors it carries (a reference measurement, a scored stream) and does not carry
    itself; one it cannot compute is left out, as a measurement not taken."""
    todo = {n: t for n, t in derive.items() if n not in frame.columns
            and all(c in frame.columns for c in columns_of(_tree(f"{KEY}.{n}", t), KEY))}
    if not todo:
        return frame
    columns = {c: frame[c].to_numpy(float) for c in frame.columns if str(c).startswith("E_")}
    return frame.assign(**{n: evaluated(n, t, columns, source) for n, t in todo.items()})


def probe_pairs(errors) -> list[tuple[str, str, str]]:
    """``(first, second, tilt name)`` of each pair of error columns named alike but for a last
    1 and 2 (``E_Sonde_X1``, ``E_Sonde_X2`` -> ``E_tilt_Sonde_X``): two probes of a sensor
    nest along the spindle, whose difference over their spacing is a tilt (ISO 230-3)."""
    names = set(errors)
    return [(n, f"{n[:-1]}2", f"E_tilt_{n[2:-1]}") for n in errors
            if n.endswith("1") and not n[-2].isdigit() and f"{n[:-1]}2" in names
            and f"E_tilt_{n[2:-1]}" not in names]


def proposal(pairs) -> str:
    """``data.derive``'s entries for ``pairs`` as YAML comment lines (the spacing left to say)."""
    return "\n".join(["# the probe pairs' tilts as targets (data.derive, µm/m): give the spacing "
                      "in metres", "# derive:"]
                     + [f"#   {t}: ({a} - {b}) / <spacing_m>" for a, b, t in pairs]) + "\n"


def without_derived(names, derive: Mapping[str, str]) -> list[str]:
    """``names`` less the derived columns (what a repair reads, the derived computed after)."""
    return [n for n in names if n not in derive]


def _floats(column) -> np.ndarray:
    """A float column as numpy, NaN where missing."""
    return np.asarray(column.to_pandas(), float)
