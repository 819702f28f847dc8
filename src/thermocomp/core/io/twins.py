"""A header written twice (a lab's export of one sensor under two channels: ``Halle (°C)`` at
columns 18 and 19): each occurrence after the first is read as ``<name>#<k>`` (``Halle#2
(°C)``, the unit kept after it), the name ``data.columns`` and ``data.roles`` address it by;
one whose cells are those of the first, row for row, is the same channel exported twice and
left out (``Halle#2 (°C) [= column 18]``), said by the reader (both read back by :func:`.roles.
left_out` / :func:`.roles.first_of`, which name the headers).  A header holding no name (an
empty one, Excel's trailing separators) is left as it is.  (twins98) One name written in two
units (``T [°C]``, ``T [K]``) keeps its headers, unique already; the second's contract name is
numbered as a twin's (:func:`.roles.again_in`: ``T_T``, ``T_2``), said here too.
(cin103) :func:`copy_refused` asks the reader whether it refuses a header's copy holding other
values: the exported stream.c refuses the file where the reader does and reads it where it reads.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Sequence

from .contract import ContractError
from .roles import first_of, left_out, naming, split_unit


def occurrences(header: Sequence[str]) -> tuple[list[str], dict[int, int]]:
    """``(names, twins)``: ``header`` with the k-th occurrence of a name (k >= 2) renamed
    ``<name>#<k>`` before its unit, and ``{its index: the first occurrence's index}``."""
    names, first, twins = list(header), {}, {}
    for i, h in enumerate(header):
        if not h.strip():
            continue
        if h not in first:
            first[h] = i
            continue
        twins[i] = first[h]
        k = sum(1 for j in twins.values() if j == first[h]) + 1
        names[i] = _numbered(h, k, set(header) | set(names))
    return names, twins


def _numbered(header: str, k: int, taken: set) -> str:
    """``header`` numbered ``#k`` before its unit, the next k where a header already holds it."""
    base = split_unit(header)[0]
    while True:
        name = (base + f"#{k}" + header[len(base):] if base and header.startswith(base)
                else f"{header}#{k}")
        if name not in taken:
            return name
        k += 1


def same_cells(names: list[str], twins: dict[int, int], rows: Iterable[Sequence[str]]) -> list[str]:
    """``names`` with each twin whose cells equal its first occurrence's in every one of
    ``rows`` (as text, stripped) marked as left out (:func:`left_out`)."""
    alike = dict.fromkeys(twins, True)
    for row in rows:
        for i, j in twins.items():
            if alike[i] and _cell(row, i) != _cell(row, j):
                alike[i] = False
        if not any(alike.values()):
            break
    return [f"{n} [= column {twins[i] + 1}]" if alike.get(i) else n for i, n in enumerate(names)]


def copy_refused(header: str) -> bool:
    """(cin103) Whether the reader refuses a file writing ``header`` twice, the copy's values
    apart from the first's, with no ``data.roles`` pattern nor ``data.columns`` entry to read the
    copy (``columns 2 and 57 have the same header ..., different values``): a file of contract
    names, the one an exported model reads without its lab's roles (which it does not carry; a
    roles-read lab file's copy, ``T Luft#2 [°C]``, is read as ``T_Luft_2``, the input from the
    first column)."""
    names, _ = occurrences([header, header])
    try:
        naming(names, {}, {}, first=dict.fromkeys(names, "0"))
    except ContractError as exc:
        return f"have the same header {header!r}, different values" in exc.reason
    return False


def _cell(row: Sequence[str], i: int) -> str:
    return row[i].strip() if i < len(row) else ""


def said(header: Sequence[str], names: dict) -> list[str]:
    """What the reader says of ``header``'s twins (``names``: header -> contract name as read)."""
    lines = []
    for i, h in enumerate(header):
        column = left_out(h)
        if column is not None:
            lines.append(f"columns {column} and {i + 1} have the same header and the same "
                         f"values ({header[column - 1]!r}): column {i + 1} left out")
        elif (first := first_of(header, h)) is not None and h in names:
            lines.append(f"columns {first + 1} and {i + 1} have the same header "
                         f"{header[first]!r}, different values: column {i + 1} read as "
                         f"{h!r} ({names[h]}; data.columns / data.roles name it so)")
        elif (first := _in_another_unit(header, i, names)) is not None:
            lines.append(f"columns {first + 1} and {i + 1} hold one name in two units "
                         f"({header[first]!r}, {h!r}): column {i + 1} read as {names[h]} "
                         f"(data.columns names it otherwise)")
    return lines


def _in_another_unit(header: Sequence[str], i: int, names: dict) -> int | None:
    """(twins98) The index of the first header whose name ``header[i]`` holds in another unit
    (or spelling), the second read numbered (:func:`.roles.again_in`: ``T_Temp`` and
    ``T_Temp_2``); None for any other header."""
    base, unit = split_unit(header[i])
    if unit is None or header[i] not in names:
        return None
    if not _NUMBERED.search(str(names[header[i]])):
        return None
    return next((j for j, h in enumerate(header[:i]) if h in names and split_unit(h)[1] is not None
                 and split_unit(h)[0] == base and names[h] != names[header[i]]), None)


_NUMBERED = re.compile(r"_\d+$")      # ('T_2', 'T_Temp_2': a name numbered by again_in)
