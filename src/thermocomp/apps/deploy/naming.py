"""Column names of the deployed model: the lab's own, and the corrections it gives.

A record read with ``data.columns`` (``{raw: contract}``, e.g. ``{T0: T_0, "delta L": E_L}``)
is modelled under contract names; the machine that calls the deployed model
still sends its logger's names.  The model keeps ``lab_names`` (core.io.own_headers) and reads
any name of a column (:func:`to_contract`): a record whose runs came from two loggers may
name one column two ways (``Zeit [s]`` and ``Zeit``), and each is that column.  A header whose
unit sits in a unit row under it is named by the reader with the unit joined (``Temperatura
ambiente [°C]``); the machine's logger sends it bare (``Temperatura ambiente``), and the model
takes that too (:func:`accepted_names`, as the exported ``stream.c`` does), unless two columns
are alike but for their unit (``T [°C]``, ``T [K]``): then the bare name is refused, naming both.
"""

from __future__ import annotations

from collections.abc import Mapping

import pandas as pd

from ...base.errors import ContractError
from ...core.io.layout import bare_header

CORRECTION_PREFIX = "C_"


def correction_column(target: str) -> str:
    """``E_X`` -> ``C_X``: the correction for the error ``E_X``."""
    return CORRECTION_PREFIX + (target[2:] if target.startswith("E_") else target)


def lab_units(ds=None) -> dict[str, list]:
    """``{the lab's header: [contract name, scale, offset]}`` of the columns ``ds`` was read in
    another unit (``data.units``, a unit in the header: mm, nm, °F, K, min), which
    ``lab_names`` leaves out: the exported ``stream.c`` reads them as the lab wrote them
    and converts each cell (``value * scale + offset``) as the reader did.  The served model
    takes such a column by its contract name only."""
    return dict((ds.meta.get("lab_units") or {}) if ds is not None else {})


def raw_names(names: Mapping, contract: str) -> list[str]:
    """The lab's names of ``contract`` in ``names`` (``lab_names``; a model pickled before
    a column could have several holds one name as a string)."""
    raws = names.get(contract, [])
    return [raws] if isinstance(raws, str) else list(raws)


def bare_names(names: Mapping, converted: Mapping | None = None
               ) -> tuple[dict[str, list[str]], dict[str, list[str]]]:
    """``({contract name: its headers' bare forms}, {bare form: the headers it may be})`` of
    ``names`` (``lab_names``) and ``converted`` (:func:`lab_units`, read in another unit):
    the header ``Temperatura ambiente [°C]`` is also ``Temperatura ambiente``, as the lab's
    logger writes it above its unit row (:func:`~thermocomp.core.io.layout.bare_header`).  A
    name that is some column's header or contract name as it is stays that column's; a bare
    form two columns share, or one a header read in another unit shares (``T [°C]`` and ``T
    [K]``), is in the second mapping: it names no column for sure."""
    converted = converted or {}
    exact = {str(c) for c in names} | {r for c in names for r in raw_names(names, c)} \
        | {str(h) for h in converted}
    claims: dict[str, dict[str, str]] = {}       # bare form -> {header: contract name}
    for contract in names:
        for raw in raw_names(names, contract):
            bare = bare_header(raw)
            if bare is not None and bare not in exact:
                claims.setdefault(bare, {})[raw] = str(contract)
    for header, (contract, *_) in converted.items():
        if (bare := bare_header(header)) in claims:
            claims[bare][str(header)] = str(contract)
    bare, ambiguous = {}, {}
    for form, headers in claims.items():
        if len(set(headers.values())) > 1 or any(h in converted for h in headers):
            ambiguous[form] = list(headers)
        else:
            bare.setdefault(next(iter(headers.values())), []).append(form)
    return bare, ambiguous


def accepted_names(names: Mapping, converted: Mapping | None = None
                   ) -> tuple[dict[str, list[str]], dict[str, list[str]]]:
    """``({contract name: every name the model takes it by}, {bare form: the headers it may
    be})``: ``names`` (``lab_names``) with the bare forms :func:`bare_names` finds certain,
    and those it does not (to refuse by name).  A refusal of a lacking column names the lab's
    headers as the reader named them (``names``: the joined form, stranger74)."""
    bare, unsure = bare_names(names, converted)
    return {str(c): [*raw_names(names, c), *bare.get(str(c), [])] for c in names}, unsure


def to_contract(frame: pd.DataFrame, names: Mapping, converted: Mapping | None = None
                ) -> pd.DataFrame:
    """``frame`` with the lab's names of ``names`` (``lab_names``; bare or with the unit
    row's unit joined, :func:`accepted_names`) renamed to contract names; a frame may use one
    name of a column, not two (two columns for one input), nor a bare name two columns share."""
    if not names:
        return frame
    names, unsure = accepted_names(names, converted)
    sent = [form for form in unsure if form in frame.columns]
    if sent:
        raise ContractError("the input's column(s) " + "; ".join(
            f"{form!r} may be {' or '.join(map(repr, unsure[form]))}" for form in sent)
            + ": two columns alike but for their unit; send the header with its unit")
    both = []
    for contract in names:
        given = [n for n in (*raw_names(names, contract), contract) if n in frame.columns]
        if len(given) > 1:
            both.append(" and ".join(map(repr, given)))
    if both:
        raise ContractError(f"the input names one column twice, by the lab's name and the "
                            f"contract's or by two of the lab's ({'; '.join(both)}): send one "
                            "of them")
    raw_to_contract = {raw: contract for contract in names for raw in raw_names(names, contract)}
    return frame.rename(columns={c: raw_to_contract[c] for c in frame.columns if c in raw_to_contract})
