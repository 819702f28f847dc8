"""A refusal about a column the file names otherwise (a lab's ``Kanal 7 [°C]``, read as
``T_Kanal_7``) names the file's header too, and a ``data.roles`` pattern in its fix is one that
matches that header: ``data.roles.ignore=[T_Kanal_7]``, the contract name, matches no header of
the file, and the same refusal came back."""

from __future__ import annotations

import re
from collections.abc import Mapping

from .contract import ContractError
from .roles import RUN, header_pattern
from .timestamps import CLOCK

__all__ = ["as_named", "header_pattern", "lab_names", "with_own_header"]

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


def lab_names(cfg, ds=None) -> dict[str, list[str]]:
    """``{contract name: the lab's raw names}``: the one place that knows how a record's
    headers map to contract names -- as the dataset ``ds`` was read (``data.columns`` and
    ``data.roles``, :func:`thermocomp.core.io.roles.contract_columns`, every campaign's
    headers), else ``data.columns``.  A column read in another unit (``ch1(mm)`` -> ``E_ch1``
    in µm) is left out: under the lab's name it would carry the lab's unit, so the model takes
    it by its contract name only.  The run-number column of a long file
    (``data.roles.campaign``, ``ds.meta["run_column"]``) comes under :data:`RUN`: a stream of
    the lab's file starts a campaign at each of its values (the exported code, a model from
    the registry too, which has no dataset to ask); a time of day joined to the date
    (``data.roles.time: [date, time]``, found by ``auto`` too) under :data:`CLOCK`."""
    columns = dict(cfg.data.get("columns") or {})
    converted = set()
    if ds is not None:
        columns.update(ds.meta.get("column_map") or {})
        converted = set(ds.meta.get("converted") or ())
        if ds.meta.get("run_column"):
            columns[ds.meta["run_column"]] = RUN
        if ds.meta.get("time_of_day"):     # joined to the date: what export refuses by name
            columns[ds.meta["time_of_day"]] = CLOCK
    names: dict[str, list[str]] = {}
    for raw, contract in columns.items():
        if str(raw) != str(contract) and str(contract) not in converted:
            names.setdefault(str(contract), []).append(str(raw))
    return names
