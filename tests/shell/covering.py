"""A covering set of a parametrized cross product, chosen by a rule (not by hand).

``make test`` keeps a Latin pairing of two axes (the k-th value of each, cycling the shorter):
every value of every axis runs at least once.  The other combinations, and only they, are marked
``full`` with a reason naming the kept cases that cover each of their values; ``make test-all``
runs them all.  Combinations a past bug lived in are passed as ``keep``.
"""

from __future__ import annotations

import pytest


def latin(first: list, second: list) -> set[tuple]:
    """``(first[k % n1], second[k % n2])`` for k < max(n1, n2): each value of each axis once at least."""
    return {(first[k % len(first)], second[k % len(second)])
            for k in range(max(len(first), len(second)))}


def covering(first, second, why: str, keep=(), join=lambda a, b: f"{a}-{b}") -> list:
    """``pytest.param(a, b, id=join(a, b))`` for every pair of the cross product (``first``
    varying slowest); outside ``latin(first, second) | keep``, marked ``full`` with ``why`` and
    the ids of the kept pairs that hold its ``a`` and its ``b``."""
    first, second = list(first), list(second)
    kept = latin(first, second) | set(keep)
    params = []
    for a in first:
        for b in second:
            marks = ()
            if (a, b) not in kept:
                by_a = next(join(a, y) for y in second if (a, y) in kept)
                by_b = next(join(x, b) for x in first if (x, b) in kept)
                marks = pytest.mark.full(reason=f"{why}; in make test: {by_a}, {by_b}")
            params.append(pytest.param(a, b, id=join(a, b), marks=marks))
    return params
