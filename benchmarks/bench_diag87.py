"""Diagnose's start lags: a lag from the initial state (k >= 1 directions) accepted only where its
start block adds over the same lag with no start block, a nested sign-flip test (stop 87, diag87;
issue 34: "diagnose accepts a planted position effect with 8 train campaigns, accepts nothing on
clean data, and never leaves a record's test error more than 2 % worse").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag87.py fresh ROOT LABEL    # FRESH + SEEN draws -> ROOT/fresh-LABEL.jsonl
    python benchmarks/bench_diag87.py seen ROOT LABEL     # SEEN rows -> ROOT/{cases,real}-LABEL.jsonl
    python benchmarks/bench_diag87.py compare ROOT A B    # two labels' rows: the bar's counts

``fresh``: bench_diag86's ``fresh`` (year-round VMC, every 3rd campaign by date test, MLR, every
target, ``max_effects=2``, test figures as deployed) on :data:`FRESH` -- this stop's seeds
9101-9115: ``planted`` (``axis_position`` on Y), ``clean``, ``lag`` (``lag_node``: an unmeasured
slow mass, the start lag's real case) -- and the SEEN draws planted:9046 (diag86b's fresh
2-direction harm), planted:9050 (a real 3-direction start lag, 12 train) and lag:8980 (diag86's
real 3-direction start lag, 8 train).  ``seen`` and ``compare``: bench_diag86's (``cases`` 8457 /
8178 / 8075 / 8170 / 8885, ``real`` planted:6 / 959, grinders 5687 / 5682 from ``ROOT/lag`` and
``ROOT/grinder568x``).

The rule (written and committed before scoring)
-----------------------------------------------
In each round, after the family-wise test (``Search._nested_starts``): a lag from the initial
state with k >= 1 directions that clears the bar clears only if its start block adds over the same
lag with NO start block (``initial_state`` and ``initial_directions`` dropped: the round's own
plain candidate): the family's statistic (each test block's gain of the start lag over the plain
lag, as a share of the plain lag's block MSE clipped to [-1, 1], or signed ranks on finer blocks),
sign-flipped (``sign_flip_maxt`` with one row: p of the mean gain > 0), p (``p_nested``) at most
the family's ``alpha`` (0.01).  The plain lag is refitted when the round did not shortlist it.  If
the nested p exceeds alpha: the start lag does not clear and is never a rival of the
one-standard-error choice; the plain lag, if shortlisted, is judged as it was; if not, it is judged
in the refused one's place: its family-wise p from the family with its row in place of the refused
one's (the family's size unchanged, the other members keep their p), the same bar and within
checks, eligible (where it clears itself) and a rival.  Every start variant of one lag (2 and 3
directions) is tested against the same plain lag.  No campaign count; train campaigns only;
nothing chosen by a test figure.  Not changed: the candidates, screening, the shortlist, the
deployed model, every other kind.  Known beforehand (bench_diag83b's trace, not this rule's run):
on the SEEN harms the plain lag gained far less than its start variant (8457 7.5 against 46.5 %,
8075 0.0 against 50.5 %, 8170 0.0 against 22.4 %), with 7-8 of 8 held-out campaigns gaining: the
nested test may well pass there and mend nothing.

The bar (all must hold, else REFUSED: src reverted, this bench and ``diag87_rule.patch`` kept).
Main = 25b18da6's src, rule = this tree's src at the commit that implements it, exported apart,
the two runs alternated on the same rows:

1. SEEN harms (8457 E_X, 8178 E_Z, 8170 E_X, 8075 E_Y, grinder 5682 dY, planted:9046 E_X): the
   rule's after not above main's; where the rule changes the row, no more than 2 % above its before.
2. Every other SEEN row (8885 E_Y, planted:6, planted:959, grinder 5687, planted:9050, the other
   targets of these records, ``bench_diagnose_faults58.py``'s rows): the rule's after no more than
   2 % above main's.
3. lag:8980 E_X (8 train; main 0.805 in diag86b): the rule's after no more than 2 % above main's.
4. FRESH (9101-9115, 8-16 train): no (draw, target) more than 2 % above main's after.
5. FRESH clean: nothing accepted on any target with the rule.
6. tests/apps/test_diagnose*.py and tests/shell/test_diagnose*.py pass with the rule.
Unscored by 20:50 UTC: REFUSED as unscored.  KEPT additionally asks docs (docs/diagnose*.md) and a
test failing on main.  Reported, not the bar: CPU, the planted draws' position found (8 train),
where the nested test acted.

Scored (2026-12-04, 2 cores shared by six helpers; main = 25b18da6's src, rule = 4d6d74c6's src,
both exported apart; ``seen``, ``fresh`` then ``bench_diagnose_faults58.py``, each run for main then
the rule; CPU of the commands main / rule: seen 16.1 / 15.4 s, fresh 27.5 / 24.9 s (diagnose alone
20.2 / 18.4 s))
----------------------------------------------------------------------------------------------------
Test RMSE as deployed (µm), every row where the two differ::

  row / target (train)          before  main                                rule
  clean:8178 E_Z (harm)         0.6377  0.7747 T_bearing_f3 900 s +init (3) 0.6377 nothing (-17.7 %)
  planted:959 E_Y (seen)        4.2298  0.9934 position + T_motor2 7200 s   1.1084 position + plain lag
                                        +init (2)                           (+11.6 %)
  grinder 5687 dY (seen)        0.5433  0.4306 T_Ständer_Bohrung 900 s      0.5433 nothing (+26.2 %)
                                        +init (2)
  faults58 climate_room:drift   0.3721  0.3262 inputs 900 s +init (3)       0.3405 inputs 900 s, plain
  and :contact E_Z (before 0.3866)                                          (+4.4 %)
  faults58 climate_room:stuck   0.599   0.5146 inputs 900 s +init (2)       0.5269 inputs 900 s, plain
  E_X                                                                       (+2.4 %)
  faults58 climate_room:stuck   0.5273  0.4779 T_nc_tool_motor 900 s +init  0.5005 inputs 900 s, plain
  E_Z                                   (3)                                 (+4.7 %)
  planted:9103 E_Y (8, fresh)   2.908   1.477 position + T_motor2 3600 s    2.159 position (+46.2 %)
                                        +init (3)
  lag:9112 E_X (10, fresh)      1.774   0.913 T_box1 14400 s +init (2)      1.027 T_box2 14400 s +init
                                                                            (3) (+12.5 %)

1. **Holds, but mends one harm of six.**  8178 E_Z mended to its before (the only SEEN harm the
   nested test refuses); 8457 E_X 0.9239, 8075 E_Y 0.7010, 8170 E_X 0.9158, grinder 5682 dY 0.7943
   and planted:9046 E_X 0.845 (before 0.655, +29.0 %) identical to main: their start blocks add
   over the plain lag in every held-out campaign.  Traced (the rule's src, the target alone):
   8457 round 1, T_amb 7200 / 14400 s (3) over their plain lags p_nested 0.0039 = 1/256 (T_bearing_f2
   900 s (3) 0.0195, refused, its plain lag 41.4 % clears too); 8075, T_box1 3600 s (3) and the
   7200 s T_bearing_r / T_nose / T_bearing_f2 (3) at 0.0039, T_box2 3600 s at 0.0078.
2. **Fails.**  planted:959 E_Y +11.6 % (round 2: T_motor2 7200 s (2) over its plain lag p_nested
   0.239 -- a real start lag the campaigns cannot confirm over the plain one; the plain lag, 19.3 %
   against 18.8 %, is taken), grinder 5687 dY +26.2 % (nothing taken), faults58 climate_room's E_Z
   on drift / contact +4.4 %, stuck +4.7 % and stuck E_X +2.4 % (real start lags replaced by the
   plain inputs' 900 s lag; all still below their before); 17 of 20 faults58 rows identical (45
   targets, faults found 10 in both).  8885 E_Y 1.4571, planted:6 1.2652, planted:9050 E_X 0.502
   and every other target of these records identical to main.
3. **Holds.**  lag:8980 E_X 0.805 in both (its 3-direction T_box1 14400 s start lag passes).
4. **Fails.**  planted:9103 E_Y (8 train) +46.2 % (main's second effect, a T_motor2 3600 s start
   lag, refused; nothing takes its place); lag:9112 E_X (10 train) +12.5 % (a 3-direction T_box2
   lag instead of main's 2-direction T_box1).  The other 13 fresh draws identical (lag 9111, 9114,
   9115 keep their start lags: 1.73 -> 0.79, 1.12 -> 0.70, 2.07 -> 0.88; 9110, 9113 nothing in
   either).
5. **Holds.**  Clean 9106-9109 (8-14 train): nothing accepted on any target, either tree; the
   control clears nowhere.  (Reported: the position found on 9101-9105, 9046 and 9050 in both.)
6. **Holds.**  129 of 129 (tests/apps/test_diagnose*.py, tests/shell/test_diagnose*.py, the rule's
   src; 402 s wall).

**REFUSED** (items 2 and 4).  src reverted to 25b18da6's; the rule's src in ``diag87_rule.patch``;
no test written, docs unchanged.  What the numbers say: the nested test separates the wrong way
round.  On clean 8-campaign draws the start block IS the spurious gain and it adds over the plain
lag in every held-out campaign (p 1/256 on 8457, 8075; bench_diag83b: 88-91 % of it in the
held-out campaigns' means), so the test passes it; on the real start lags the rule lost (959,
5687, climate_room, 9103) it refused the start block -- traced on 959 only: the plain lag carries
nearly all of the CV gain (19.3 against 18.8 %) and the start block's increment, real on test, is
not confirmed campaign by campaign (p 0.239).  The optional leak trace (by reading the code, not
run): no leak found -- the learned directions come from the fold's training rows only
(``CrossValidator.features``: ``principal_directions(offsets[train_rows(fold)])``), each
campaign's offsets from its own first sample (what a deployed compensator has), the lags causal;
why the clean start blocks gain 45-50 % in CV and lose on test (the test campaigns' start states
outside the span of 8 training campaigns' directions?) is not measured.  What I would try next:
measure that -- each test campaign's initial offsets against the training campaigns' span of
directions -- before any other start rule; a campaign-level test cannot tell these start blocks
apart (k over k - 1: diag86b; k over 0: here).  The seeds 9101-9115 are spent.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_diag86  # noqa: E402
from _cli import run_commands  # noqa: E402

# (kind, seed, campaigns): every 3rd test, so 12 -> 8 train, 14 -> 10, 16 -> 11, 18 -> 12, 24 -> 16
FRESH = ([("planted", s, 12) for s in range(9101, 9105)] + [("planted", 9105, 18)]
         + [("clean", s, n) for s, n in zip(range(9106, 9110), (12, 14, 16, 20))]
         + [("lag", s, n) for s, n in zip(range(9110, 9116), (12, 12, 14, 15, 18, 24))]
         # SEEN: diag86b's 2-direction harm and real 3-direction lag, diag86's real start lag
         + [("planted", 9046, 12), ("planted", 9050, 18), ("lag", 8980, 12)])


def fresh(root: str, label: str) -> None:
    """:data:`FRESH` through bench_diag86's ``fresh``."""
    bench_diag86.FRESH = FRESH
    bench_diag86.fresh(root, label)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"fresh": fresh, "seen": bench_diag86.seen, "compare": bench_diag86.compare},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
