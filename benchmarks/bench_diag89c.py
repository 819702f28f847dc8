"""Diagnose's family-wise p of one input's start lag: how the family is formed, and whether counting
one effect's variants as one member would let lag:9288 / 9289 E_X accept it (stop 89, diag89c;
issue 34: "diagnose accepts a planted position effect with 8 train campaigns, accepts nothing on
clean data, and never leaves a record's test error more than 2 % worse").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag89c.py trace CASES TARGET   # each round's family, every way of forming it

``trace``: each case of ``CASES`` (``kind:seed`` of bench_diag86's draws, comma separated; 12
campaigns, every 3rd test, 8 train) diagnosed by bench_diag89's :func:`diagnosed` (MLR, every
target, ``max_effects=2``, as bench_diag88b's ``trace``); for ``TARGET``, every round's
family-wise test as :meth:`~thermocomp.apps.diagnose.search.Search._family_bar` forms it (the gains
it hands to :func:`~thermocomp.apps.diagnose.cv.sign_flip_maxt`, captured, nothing changed): each
member's t, its own sign-flip p, its family-wise p, its margin p and whether it saturates; then
the family-wise p of the round's best one-input start lag (the best t among the unsaturated lags of
one input from the initial state) with the family formed each way (:func:`family_ways`), and what
each other effect of the round costs alone with it (``with KIND:COLUMN``):

* ``alone``        -- a family of one (its own sign-flip p: the floor of any counting rule);
* ``variants``     -- its own input's start lags (time constants x directions x +init);
* ``one-input``    -- the start lags of every single input (one "start lag of one input" effect);
* ``per column``   -- one member per (kind, column), its best variant;
* ``grouped``      -- Westfall-Young step-down over effects (:func:`grouped_maxt`): an effect's
  statistic in every sign pattern the largest t of its variants, whole effects stepped down, so
  correlated variants cost what they are worth -- the brief's rule;
* ``unsaturated``  -- the members that can clear at all (:meth:`Search.saturates` is a property
  of the design, not of the gains, so leaving them out keeps the test exact);
* ``main``         -- the family as it is (:func:`sign_flip_maxt` over the shortlist).

The question (the brief): is the family-wise p of T_box1's start lag (0.03-0.05 on lag:9288 /
9289 E_X, fresh in diag89) the price of its own correlated variants counted as members, so that
the more variants generated the harsher the correction?

The bar (written after the trace below was first read -- said plainly -- and before any rule was
scored; no FRESH seed spent):  a member-counting rule is worth scoring on the fresh seeds
9336-9345 (bench_diag88d's generators: clean 9336-9339, planted 9340-9342, lag 9343-9345) only if
on lag:9288 and lag:9289 E_X (seen now) the rule's p of the best one-input start lag is <= alpha
(0.01) AND that read passes every other check of :meth:`Search._clears` (its margin p <= alpha:
the blocks are ranked); else nothing in how members are counted can accept it: TRACED, src as
main, the fresh seeds left unspent.  (Were it scored: no (draw, target) more than 2 % worse than
main, clean accept nothing, planted found wherever main finds it, lag:9288 / 9289 better than main,
tests/*/test_diag*.py pass.)

Measured (2026-12-05, src = main 92dc744b, 2 cores shared by seven helpers; ``trace
lag:9288,lag:9289 E_X``: CPU 4.5 s)
--------------------------------------------------------------------------------------
Round 1 of E_X is the only round (nothing accepted).  The test units are ranked validation blocks
(12 on lag:9288, 10 on lag:9289: 4,096 / 1,024 sign patterns, exact).  The family is the round's
shortlist, 12 members of 223 screened candidates (the best 8 by screening, at most 2 per (kind,
column), then the best of every other kind): the lag of every input from the initial state (2
reads, saturated: 12-13 regressors against 7 trained campaigns), T_box2 / T_box1 / T_nose's start
lags (2 and 3 directions each: 6 reads, their block gains correlated 0.89-0.99 / 0.92-1.00), and 4 other
effects (an ambient interval law and the spindle's product, both saturated; T_box1's square; a
spindle lag).  The best one-input read (T_box2 14400 s, 2 directions, 3 regressors; tied in t with
T_box1's; 11 of 12 / 9 of 10 blocks gain) and its family-wise p, each way::

  family                                    lag:9288   lag:9289
  alone (its own p)                         0.0081     0.0068
  variants (its input's 2 reads)            0.0107     0.0098
  one-input (the 6 reads)                   0.0144     0.0127
  with one other effect (each of the 4)     0.0154-0.0161  0.0107-0.0137
  per column (best read of each)            0.0344     0.0303
  unsaturated (8 members)                   0.0281     0.0244
  grouped (the brief's rule)                0.0366     0.0312
  main                                      0.0366     0.0312
  its margin p (gain >= 5 %, ranked)        0.0317     0.0078  (T_box1's: 0.0312 / 0.0068)

1. ``grouped`` = ``main`` (and :func:`grouped_maxt` with one effect per member gives
   :func:`sign_flip_maxt`'s p exactly, every round of lag:9288 / 9289's three targets and a
   Monte Carlo case: checked): :func:`sign_flip_maxt` IS Westfall-Young's max-T already; its null is
   the largest t of every member in each sign pattern, and the largest over effects of the largest
   over their variants is the same maximum, so counting an effect's variants as one member changes
   no p here (it can change a later effect's step only: lag:9233 / 9270 round 2, 0.609 / 0.597
   against 0.637 / 0.648, nowhere near alpha; and the monotone p keeps T_box1 at T_box2's).
   Correlated variants already cost what they are worth: all 6 one-input reads together raise
   0.0081 -> 0.0144 (x1.8, not x6).  The shortlist admits at most 2 reads per (kind, column), so
   generating more time constants or directions does not enlarge the family at all.
2. The cost is the OTHER effects of the round: each of the 4 alone with the read costs as much as
   its 5 correlated rivals (0.008 -> 0.015-0.016 on lag:9288); all of them 0.037 / 0.031.  Leaving
   out what cannot clear (saturation is a property of the design, not of the gains, so the test
   stays exact) gives 0.028 / 0.024.  (The 211 candidates screened out are not charged at all, so
   the family p is if anything generous.)
3. Even a family of one is at 0.0081 / 0.0068 (the evidence: 11 of 12 / 9 of 10 ranked blocks),
   and on lag:9288 the read fails the margin test as well (0.0317 / T_box1 0.0312 that its gain
   reaches 5 %): no way of forming the family accepts it there.  On lag:9289 only a family of its
   own input's reads (0.0098, margin 0.0078) would: that drops the other effects the round tests,
   i.e. the family-wise control itself.  The all-inputs lag's 0.0017 / 0.0117 is that read's own t
   (6.2 / 4.9 against 3.1 / 3.5) and it saturates (its held-out gains can be a chance alignment of
   8 campaign offsets: bench_diagnose_saturated), so lending its p to one input's read would undo
   the saturation check (diag88c's rule 2 territory; and on lag:9289 it is above 0.01 itself).
4. Where a one-input start lag clears on main (seen lag:9233 / 9235 / 9268 / 9269 / 9270 E_X,
   ``trace lag:9233,lag:9235,lag:9268,lag:9269,lag:9270,clean:9281 E_X``, CPU 13.1 s), round 1
   gives the same p every way on 9233 / 9235 / 9269 / 9270 and 0.0002-0.0013 on 9268 (all below
   alpha): nothing to gain where the read already clears.  clean:9281 E_X: the best start lag is
   at 0.64 alone.

The bar fails on both rows (lag:9288: no family puts the read at <= 0.01, and its margin p is
0.032 whatever the family; lag:9289: only a family without the round's other effects):
**TRACED**, src as main, fresh 9336-9345 unspent.

Left: the start lags' evidence, not their count: 10-12 ranked blocks of 8 campaigns give a real
one-input start lag p 0.007-0.008 alone and a margin p 0.03 on lag:9288; a statistic that reads
more of the same units (the test blocks' gains as shares, not signed ranks, or finer blocks:
diag89b's topic) is the next thing to try, with lag:9288's margin test in view.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_diag89  # noqa: E402
from _cli import run_commands  # noqa: E402


def _t(D: np.ndarray, signs: np.ndarray) -> np.ndarray:
    """t of every row's mean gain in every sign pattern (patterns x rows); a flip keeps squares."""
    n = D.shape[1]
    mean, square = signs @ D.T / n, (D ** 2).sum(axis=1)
    return mean / np.sqrt(np.maximum(square - n * mean ** 2, 1e-300) / ((n - 1) * n))


def grouped_maxt(D, groups, seed: int = 0) -> np.ndarray:
    """Westfall-Young step-down max-T over effects: ``groups[c]`` names row ``c``'s effect; an
    effect's statistic is the largest t of its rows, observed and in every sign pattern, and whole
    effects step down.  Returns each row's p (its effect's), monotone in the effects' order."""
    from thermocomp.apps.diagnose.cv import EXACT_UNITS, RESAMPLES, _sign_chunks

    D = np.nan_to_num(np.atleast_2d(np.asarray(D, dtype=float)))
    names = list(dict.fromkeys(groups))
    member = np.array([names.index(g) for g in groups])
    n = D.shape[1]
    observed = _t(D, np.ones((1, n)))[0]
    best = np.array([observed[member == g].max() for g in range(len(names))])
    order = np.argsort(-best)
    bar = best[order] - 1e-9 * np.maximum(np.abs(best[order]), 1.0)
    hits, count = np.zeros(len(names), dtype=np.int64), 0
    for signs in _sign_chunks(n, RESAMPLES, seed):
        count += len(signs)
        flipped = _t(D, signs)
        per_group = np.stack([flipped[:, member == g].max(axis=1) for g in order], axis=1)
        tail = np.maximum.accumulate(per_group[:, ::-1], axis=1)[:, ::-1]
        hits += (tail >= bar).sum(axis=0)
    p = hits / count if n <= EXACT_UNITS else (1 + hits) / (count + 1)
    out = np.empty(len(names))
    out[order] = np.maximum.accumulate(p)
    return out[member]


def family_ways(D, keys, saturated) -> tuple[int, dict]:
    """The best one-input start lag's row and its family-wise p with the family formed each way
    (module docstring).  ``keys[c]``: (kind, column, title) of row ``c``; ``saturated[c]``: whether
    it can clear at all."""
    from thermocomp.apps.diagnose.cv import sign_flip_maxt

    t = _t(np.asarray(D, float), np.ones((1, np.shape(D)[1])))[0]
    start = [c for c, (kind, col, title) in enumerate(keys)
             if kind == "dynamics" and col not in (None, "-") and "initial" in title and not saturated[c]]
    if not start:
        return -1, {}
    best = max(start, key=lambda c: t[c])
    per_column = [max((c for c in range(len(keys)) if keys[c][:2] == g), key=lambda c: t[c])
                  for g in dict.fromkeys(k[:2] for k in keys)]

    def p_of(rows):
        rows = list(dict.fromkeys([best, *rows]))
        return float(sign_flip_maxt(D[rows])[0])

    ways = {"alone": p_of([]),
            "variants": p_of([c for c in start if keys[c][1] == keys[best][1]]),
            "one-input": p_of(start),
            "per column": p_of(per_column),
            "grouped": float(grouped_maxt(D, [k[:2] for k in keys])[best]),
            "unsaturated": p_of([c for c in range(len(keys)) if not saturated[c]]),
            "main": float(sign_flip_maxt(D)[best])}
    for c, (kind, col, title) in enumerate(keys):     # what each other effect costs, alone with it
        if kind != "dynamics" or "initial" not in title:
            ways[f"with {kind}:{col}"] = p_of([c])
    return best, ways


def capture_families(rounds: list):
    """Wrap ``Search._family_bar``: each family-wise test appends ``(search, members, D)`` to
    ``rounds`` (the gains it hands to ``sign_flip_maxt``, nothing changed); the original returned,
    to be put back."""
    from thermocomp.apps.diagnose import search as search_module

    family_bar = search_module.Search._family_bar

    def captured(self, evals, current):
        maxt = search_module.sign_flip_maxt

        def record(D, **kw):
            members = [ev for ev in evals if not ev.control and ev.effect.transform != "remove"]
            rounds.append((self, members, np.array(D)))
            return maxt(D, **kw)

        search_module.sign_flip_maxt = record
        try:
            family_bar(self, evals, current)
        finally:
            search_module.sign_flip_maxt = maxt

    search_module.Search._family_bar = captured
    return family_bar


def trace(cases: str, target: str) -> None:
    """Every round of ``target`` in each case: the family as ``_family_bar`` forms it, each way."""
    from thermocomp.apps.diagnose import search as search_module
    from thermocomp.apps.diagnose.cv import sign_flip_pvalues

    rounds = []
    family_bar = capture_families(rounds)
    try:
        for case in cases.split(","):
            rounds.clear()
            d = bench_diag89.diagnosed(case, target)
            screened = [r.n_candidates for r in d.targets[target].search.rounds if r.step > 0]
            for step, (search, members, D) in enumerate(r for r in rounds if r[0].problem.target == target):
                keys = [(ev.effect.kind, ev.effect.column, ev.effect.title) for ev in members]
                saturated = [search.saturates(ev.n_features) and not search.problem.shared_ranked
                             for ev in members]
                own, t = sign_flip_pvalues(D), _t(D, np.ones((1, D.shape[1])))[0]
                print(f" round {step + 1}: {D.shape[1]} test units, {len(members)} members of "
                      f"{screened[step]} candidates screened")
                for c in np.argsort(-t):
                    ev = members[c]
                    print(f"   t {t[c]:5.2f}  own p {own[c]:.4f}  family p {ev.p_family:.4f}  margin p "
                          f"{ev.p_margin:.4f}  {'saturated ' if saturated[c] else ''}"
                          f"{'clears ' if ev.clears_bar else ''}{ev.effect.title[:80]}")
                best, ways = family_ways(D, keys, saturated)
                if best >= 0:
                    start = [c for c, k in enumerate(keys) if k[0] == "dynamics" and k[1] not in (None, "-")
                             and "initial" in k[2] and not saturated[c]]
                    r = np.corrcoef(D[start])[np.triu_indices(len(start), 1)] if len(start) > 1 else [1.0]
                    print(f"   best one-input start lag: {members[best].effect.title[:80]} "
                          f"({len(start)} such reads, gains correlated {np.min(r):.2f}-{np.max(r):.2f})")
                    for others in (False, True):     # the ways, then what each other effect costs
                        print("   " + ", ".join(f"{k} {v:.4f}" for k, v in ways.items()
                                                if k.startswith("with") == others))
    finally:
        search_module.Search._family_bar = family_bar


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
