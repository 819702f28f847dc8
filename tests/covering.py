"""A cross product of test axes cut to a covering set for `make test` (the scope rule, stop 110).

Every case of the product stays collected; the first ``max(len(axis))`` cases of a Latin pairing
(case ``i`` takes each axis's value ``i`` modulo its length) run in `make test`, so every value of
every axis runs there at least once, chosen by that rule and not by cost.  The others are marked
``full`` (`make test-all`), their reason naming the kept cases that run their values.
"""

from __future__ import annotations

from itertools import product

import pytest


def covering(why: str, keep: tuple = (), **axes: dict) -> list:
    """``pytest.param``s of the cross product of ``axes`` (name -> ``{id: value}``, in the
    parametrize's argument order), ids joined by ``-``.  ``keep``: the id tuples of the cases a
    test exists for by name (a past bug's), kept in `make test` beside the pairing's."""
    ids = [list(a) for a in axes.values()]
    kept = {tuple(a[i % len(a)] for a in ids) for i in range(max(map(len, ids)))} | set(keep)
    cases = []
    for case in product(*ids):
        values = [axes[name][key] for name, key in zip(axes, case)]
        marks = ()
        if case not in kept:
            cover = sorted({"-".join(k) for k in kept if any(a == b for a, b in zip(k, case))})
            marks = pytest.mark.full(reason=f"{why}; in make test: {', '.join(cover)}")
        cases.append(pytest.param(*values, marks=marks, id="-".join(case)))
    return cases
