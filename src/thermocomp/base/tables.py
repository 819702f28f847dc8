"""The printed tables' first column: a target's name, as long as a lab's names make it."""

from __future__ import annotations

from collections.abc import Iterable

LEAST = 8    # the contract's names (E_X, E_XX1) keep the tables the docs show


def name_width(names: Iterable[str], least: int = LEAST) -> int:
    """The width of a table's name column: its longest name (a lab's ``E_X-Verlagerung``; a
    fixed 8 shifted that row's figures under the next header), at least ``least``."""
    return max([least, *(len(str(n)) for n in names)])
