"""A refusal about a column the file names otherwise (a lab's ``Kanal 7 [°C]``, read as
``T_Kanal_7``) names the file's header too, and a ``data.roles`` pattern in its fix is one that
matches that header: ``data.roles.ignore=[T_Kanal_7]``, the contract name, matches no header of
the file, and the same refusal came back."""

from __future__ import annotations

import re
from collections.abc import Mapping

from .contract import ContractError
from .roles import split_unit

_GLOB = re.compile(r"([*?\[])")      # a header's glob characters, matched as themselves


def with_own_header(exc: ContractError, renamed: Mapping[str, str]) -> ContractError:
    """``exc`` as it is, or, where the column it names is the file's header ``raw`` renamed
    (``renamed``: raw -> contract name), with that header and a pattern matching it."""
    raw = next((r for r, name in renamed.items() if name == exc.column), None)
    if exc.column is None or raw is None:
        return exc
    pattern = _GLOB.sub(r"[\1]", split_unit(raw)[0] or raw)   # (roles match a header's base)
    reason = exc.reason.replace("=[<header>]", f"=['{pattern}']").replace(
        "(data.roles.ignore)", f"(data.roles.ignore=['{pattern}'])")
    return ContractError(f"{reason} (its header in the file: {raw!r})", file=exc.file,
                         column=exc.column, row=exc.row, line=exc.line, sheet=exc.sheet)
