"""A covering set of a test's parametrized cases for `make test` (the scope rule, stop 110).

Every case stays collected.  `make test` runs the ``keep`` cases (those a test is named after) and
the cases :func:`kept` picks: again and again the first case bringing the most values not yet
picked (ties: the one whose values were picked the fewest times), until every value of every axis
is.  On a full product that is the Latin pairing (case ``i`` takes each axis's value ``i`` modulo
its length; checked up to 4 axes in tests/base/test_covering.py).  So every value of every axis
runs in `make test`, chosen by that rule, not by cost.  The other cases are marked ``full``
(`make test-all`), their reason naming a kept case per value.
"""

from __future__ import annotations

from collections import Counter
from itertools import product

import pytest


def kept(cases: list[tuple]) -> list[tuple]:
    """The rule's pick of ``cases`` (tuples of one id per axis), in the order picked."""
    every = {(axis, key) for case in cases for axis, key in enumerate(case)}
    picked, times = [], Counter()
    while set(times) != every:
        def gain(case: tuple) -> tuple:
            values = list(enumerate(case))
            return (-sum(v not in times for v in values), sum(times[v] for v in values))
        best = min((c for c in cases if c not in picked), key=gain)
        picked.append(best)
        times.update(enumerate(best))
    return picked


def covering_of(why: str, cases: dict[tuple, tuple], keep=(), join="-".join) -> list:
    """``pytest.param(*values, id=join(ids))`` per ``ids -> values`` of ``cases`` (``ids``: one
    per axis), those past :func:`kept` and ``keep`` marked ``full`` with ``why`` and the ids of
    the kept cases holding each of their values."""
    chosen = kept(list(cases))
    for case in map(tuple, keep):
        assert case in cases, f"keep names no case: {case}"
        chosen += [case] * (case not in chosen)
    params = []
    for ids, values in cases.items():
        marks = ()
        if ids not in chosen:
            cover = dict.fromkeys(join(next(k for k in chosen if k[axis] == key))
                                  for axis, key in enumerate(ids))
            marks = pytest.mark.full(reason=f"{why}; in make test: {', '.join(cover)}")
        params.append(pytest.param(*values, marks=marks, id=join(ids)))
    return params


def covering(why: str, keep=(), join="-".join, **axes) -> list:
    """:func:`covering_of` the cross product of ``axes`` (name -> ``{id: value}``, or a list of
    ids that are their own values; in the parametrize's argument order)."""
    axes = {name: axis if isinstance(axis, dict) else dict(zip(axis, axis)) for name, axis in axes.items()}
    return covering_of(why, {ids: tuple(axes[name][key] for name, key in zip(axes, ids))
                             for ids in product(*axes.values())}, keep, join)
