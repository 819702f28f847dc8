"""tests/covering.py: what `make test` keeps of a parametrized set of cases, and what it says."""

from __future__ import annotations

from itertools import product

import pytest

from covering import covering, covering_of, kept

# a pairwise design of four axes (3 x 2 x 2 x 2) in 6 cases: every pair of values of two axes met
PAIRWISE = [("a", "x", "p", "u"), ("a", "y", "q", "v"), ("b", "x", "q", "v"),
            ("b", "y", "p", "u"), ("c", "x", "p", "v"), ("c", "y", "q", "u")]


def _reason(param) -> str:
    (mark,) = param.marks
    assert mark.name == "full"
    return mark.kwargs["reason"]


def _check(params: list, cases: list[tuple], keep=()) -> None:
    """Ids unchanged; every value of every axis and every ``keep`` case in `make test`; each
    ``full`` reason names kept ids, together holding each of its case's values."""
    by_id = {"-".join(case): case for case in cases}
    assert [p.id for p in params] == list(by_id)
    in_make_test = {p.id for p in params if not p.marks}
    for axis in range(len(cases[0])):
        assert {by_id[i][axis] for i in in_make_test} == {case[axis] for case in cases}
    assert {"-".join(case) for case in keep} <= in_make_test
    for p in params:
        if p.marks:
            why, named = _reason(p).split("; in make test: ")
            named = named.split(", ")
            assert why == "why" and set(named) <= in_make_test, p.id
            held = [{by_id[i][axis] for i in named} for axis in range(len(cases[0]))]
            assert all(value in held[axis] for axis, value in enumerate(by_id[p.id])), p.id


def _latin(ids: list[list]) -> set[tuple]:
    """Case ``i`` with each axis's value ``i`` modulo its length, ``i`` < the longest axis."""
    return {tuple(a[i % len(a)] for a in ids) for i in range(max(map(len, ids)))}


@pytest.mark.parametrize("shape", [(1,), (3, 2), (2, 5), (4, 4), (5, 3, 2), (2, 3, 4, 2)])
def test_a_product_keeps_its_latin_pairing(shape):
    axes = {f"axis{k}": {f"v{k}{i}": (k, i) for i in range(n)} for k, n in enumerate(shape)}
    cases = list(product(*axes.values()))
    params = covering("why", **axes)
    _check(params, cases)
    latin = _latin([list(a) for a in axes.values()])
    assert {p.id for p in params if not p.marks} == {"-".join(case) for case in latin}
    # the values, in the parametrize's argument order
    assert [p.values for p in params] == [tuple(axes[n][i] for n, i in zip(axes, c)) for c in cases]


def test_the_rule_is_the_latin_pairing_on_every_small_product():
    shapes = [s for k in (1, 2, 3) for s in product(range(1, 6), repeat=k)]
    shapes += product(range(1, 4), repeat=4)
    for shape in shapes:
        ids = [[f"{k}.{i}" for i in range(n)] for k, n in enumerate(shape)]
        assert set(kept(list(product(*ids)))) == _latin(ids), shape


def test_keep_adds_the_cases_a_test_is_named_after():
    axes = {"reading": ["hot", "cold", "open"], "sensor": ["ambient", "spindle"]}
    plain = {p.id for p in covering("why", **axes) if not p.marks}
    params = covering("why", keep=[("cold", "ambient")], **axes)
    _check(params, list(product(*axes.values())), keep=[("cold", "ambient")])
    assert {p.id for p in params if not p.marks} == plain | {"cold-ambient"} != plain
    with pytest.raises(AssertionError, match="keep names no case"):
        covering("why", keep=[("warm", "ambient")], **axes)


def test_a_given_list_of_cases_keeps_a_subset_covering_every_value():
    params = covering_of("why", {case: case for case in PAIRWISE})
    _check(params, PAIRWISE)
    picked = kept(PAIRWISE)
    assert {p.id for p in params if not p.marks} == {"-".join(case) for case in picked}
    seen: set = set()
    for case in picked:                 # each pick brings a value not run yet: none is spare
        assert not set(enumerate(case)) <= seen, case
        seen |= set(enumerate(case))
    assert picked[0] == PAIRWISE[0] and kept(PAIRWISE[::-1])[0] == PAIRWISE[-1]  # the order breaks ties


def test_the_ids_and_values_are_the_callers():
    params = covering_of("why", {("m", "a-b"): ("m", "a", "b")}, join=lambda ids: "+".join(ids))
    assert [(p.id, p.values, p.marks) for p in params] == [("m+a-b", ("m", "a", "b"), ())]
