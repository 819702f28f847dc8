"""A refusal about a column the file names otherwise (a lab's ``Kanal 7 [°C]``, read as
``T_Kanal_7``) names the file's header too, and a ``data.roles`` pattern in its fix is one that
matches that header: ``data.roles.ignore=[T_Kanal_7]``, the contract name, matches no header of
the file, and the same refusal came back."""

from __future__ import annotations

import re
from collections.abc import Mapping

from .contract import ContractError
from .roles import header_pattern

__all__ = ["as_named", "header_pattern", "with_own_header"]

_QUOTED = re.compile(r"'([^']+)'")


def with_own_header(exc: ContractError, renamed: Mapping[str, str]) -> ContractError:
    """``exc`` as it is, or, where the column it names (and any other column its reason quotes,
    several empty ones) is a header of the file renamed (``renamed``: raw -> contract name),
    with those headers and the patterns matching them."""
    raws = {name: raw for raw, name in renamed.items()}
    if exc.column is None or exc.column not in raws:
        return exc
    names = [exc.column, *(n for n in _QUOTED.findall(exc.reason) if n in raws)]
    names = list(dict.fromkeys(names))
    headers = [raws[n] for n in names]
    patterns = ", ".join(repr(header_pattern(h)) for h in headers)
    reason = exc.reason.replace("=[<header>]", f"=[{patterns}]").replace(
        "(data.roles.ignore)", f"(data.roles.ignore=[{patterns}])")
    said = (f"its header in the file: {headers[0]!r}" if len(headers) == 1 else
            f"their headers in the file: {', '.join(map(repr, headers))}")
    return ContractError(f"{reason} ({said})", file=exc.file, column=exc.column, row=exc.row,
                         line=exc.line, sheet=exc.sheet)


def as_named(columns, names: Mapping) -> str:
    """``columns`` (contract names) listed as the lab named them, ``names`` being ``{contract
    name: the lab's header(s)}`` (a deployed model's ``lab_names_``): a stream lacking a sensor
    was refused naming ``T_Hydraulik``, a name none of the lab's files holds ('Hydraulik (°C)')."""
    return f"[{', '.join(named_one(column, names) for column in columns)}]"


def named_one(column: str, names: Mapping) -> str:
    """``column`` as :func:`as_named` lists it: ``'t1(°C)' (read as T_t1)``, or ``'T_t1'``
    where ``names`` holds no header of it."""
    raws = names.get(column) or []
    raws = [raws] if isinstance(raws, str) else list(raws)
    return " or ".join(map(repr, raws)) + f" (read as {column})" if raws else repr(column)
