"""Diagnose's one-SE choice: a cleared read of the same column as the round's uncleared best rival
counts as its effect whatever the kind (a ``signal`` on S_pos_Y against the ``interaction`` on
S_pos_Y; stop 89, diag89d; issue 34: "diagnose accepts a planted position effect with 8 train
campaigns, accepts nothing on clean data, and never leaves a record's test error more than 2 %
worse").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag89d.py write ROOT           # the records ``seen`` reads (bench_diag88's)
    python benchmarks/bench_diag89d.py seen ROOT LABEL      # bench_diag88's SEEN -> ROOT/*-seen-LABEL.jsonl
    python benchmarks/bench_diag89d.py draws ROOT LABEL     # SEEN_DRAWS -> ROOT/fresh-draws-LABEL.jsonl
    python benchmarks/bench_diag89d.py fresh ROOT LABEL     # FRESH draws -> ROOT/fresh-LABEL.jsonl
    python benchmarks/bench_diag89d.py compare ROOT A B     # two labels' rows: the bar's counts
    python benchmarks/bench_diag89d.py one CASE TARGET      # one draw diagnosed: TARGET's test and effects

``write``, ``seen``: bench_diag88's (the records 8457 / 8178 / 8075 / 8170 / 8885, planted:6 /
959, grinders 5687 / 5682 and the draws planted:9046 / 9103 / 9150, lag:8980).  ``draws``:
:data:`SEEN_DRAWS` -- bench_diag89's 40 seen draws, the rest of bench_diag89b's 23 planted draws
(8966-8969, 9047-9049, 9101 / 9102 / 9104) and bench_diag89's fresh draws 9281-9290 (spent) --
through bench_diag86's ``fresh`` (12 campaigns, every 3rd test, 8 train; MLR, every target,
``max_effects=2``, test figures as deployed).  ``fresh``: :data:`FRESH` the same way.
``compare``: bench_diag89's (bench_diag88's SEEN and FRESH rows, then the draws').  ``one``:
bench_diag89's ``diagnosed``.  All imported, nothing copied.

Why (bench_diag89b, cause B): planted:9265 E_Y (83 ranked blocks): the position products
(``interaction`` on S_pos_Y) gain 19.9 % but do not clear (family-wise p 0.63 / 0.16 by ranks);
S_pos_Y itself (``signal``, 11.8 %, p_fam 0.0009; its 900 s lag 10.0 %, p_fam 5e-5) passes every
check but lies outside one SE of the uncleared product and is another kind, so ``choose`` takes
nothing (test 3.558 µm).

The rule (src: :func:`thermocomp.apps.diagnose.search._same_effect`, used by ``choose`` only in
diag89's branch: the band's best did not clear and no cleared candidate is within its band): a
cleared candidate on the same column as that best is its effect whatever the kind; where the
best has no column, only a candidate of its kind is (the lag of every model input against one
input's, diag88c); an ambient law (no column) keeps its veto.

The bar (the brief's; written here before ANY fresh score of the rule, after the seen draws below;
all must hold, else REFUSED: src reverted, this bench and ``diag89d_rule.patch`` kept).  Main =
9e764979's src and conf (``git archive``), rule = this tree's src:

1. FRESH (:data:`FRESH`: ``clean`` 9326-9329, ``planted`` 9330-9335, bench_diag86's generators as
   bench_diag88d; 12 campaigns, every 3rd test, 8 train; every target diagnosed): the planted
   position (an ``interaction`` on S_pos_Y accepted for E_Y) found on at least as many draws as
   main.
2. The clean draws 9326-9329 accept nothing on any target (rule).
3. No FRESH (draw, target) row's test RMSE (after, as deployed) more than 2 % above main's.
4. No SEEN row (``seen``: bench_diag88's records and draws; ``draws``: :data:`SEEN_DRAWS`) more
   than 2 % above main's.
5. tests/apps/test_diag*.py and tests/shell/test_diag*.py pass with the rule (in parts, -n 2).

Measured on SEEN data (2026-12-05, before any FRESH run of either tree; 2 cores shared by seven
helpers)
-----------------------------------------------------------------------------------------------
``draws`` (60 draws, 180 rows): one row differs, test RMSE as deployed (µm)::

  row              before  main      rule
  planted:9265 E_Y 3.558   3.558 []  3.006 signal:S_pos_Y raw   -15.5 %

The other 179 rows identical.  Planted position found on 18 of 23 in both (missed: 8966 / 8968 /
8969 / 9048 / 9265; 9265 now takes S_pos_Y's raw signal, not the product, so it does not count as
found); the 22 clean draws accept nothing in both; no control clears; one row above diagnose's
own before in both (planted:8969 E_X +21.7 %, as main).  Diagnose CPU 66.5 s main / 67.8 s rule.
``seen`` (bench_diag88's cases 8457 / 8178 / 8075 / 8170 / 8885, real planted:6 / 959, grinders
5687 / 5682, draws planted:9046 / 9103 / 9150, lag:8980): every JSON row identical to main's (the
six spurious start lags as main, 8885 E_Y 1.4571, 8885 E_Z 6.0040: the ambient law still vetoes).

Scored on FRESH (2026-12-05, once, after the bar and the SEEN rows above were committed: 70c895eb;
``fresh ROOT rule`` / ``fresh ROOT main``, CPU of the processes 17.7 / 16.5 s, diagnose 12.4 / 11.5)
-----------------------------------------------------------------------------------------------
All 30 (draw, target) rows identical in both trees.  Clean 9326-9329 accept nothing on any target;
planted found on 5 of 6 in both (E_Y 3.371 -> 2.056, 5.952 -> 1.721, 4.858 -> 1.821, 2.699 ->
1.543, 3.931 -> 1.557 on 9330 / 9331 / 9332 / 9333 / 9335); 9334 E_Y 4.167 nothing in both:
bench_diag89b's cause A (8 test blocks, the position products' p_fam 0.0156 > 0.01, ``bench_diag89b.py
round1 9334``), where no candidate clears and the choice is never asked; no control clears; no
row above diagnose's own before.

1. **Holds** (5 of 6 = main).  2. **Holds** (clean: nothing).  3. **Holds** (no row differs).
4. **Holds** (one seen row differs: planted:9265 E_Y 3.558 -> 3.006, -15.5 %).  5. **Holds**:
tests/apps/test_diag*.py 78 passed, tests/shell/test_diag*.py 56 passed (run with
tests/test_benchmarks_cli.py: 475 in all; -n 2).  **KEPT.**
Tests (tests/apps/test_diagnose_choice89d.py, both fail on 9e764979): :func:`choose` takes a
cleared ``signal`` on S_pos_Y past an uncleared ``interaction`` on S_pos_Y outside its band, but
not a signal on another column, nor past an ambient law; planted:9265 E_Y (E_Y alone) accepts a
read of S_pos_Y of another kind than the uncleared best product, and the test error falls.

Left: the rule is exercised on one seen row only (9265) and on no fresh row; its cost is nil
(the choice reorders a list).  9265 takes S_pos_Y's raw signal (3.006), not the product x T_motor1
that ``bench_diag89b.py round1 9265 1`` reaches (2.753): the position itself is still missed there
(ranks over 83 blocks).  The design floor (cause A: 8966 / 8968 / 8969, fresh 9334) remains.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_diag86  # noqa: E402
import bench_diag88  # noqa: E402
import bench_diag89  # noqa: E402
from _cli import run_commands  # noqa: E402

# (kind, seed, campaigns): every 3rd campaign test, so 12 -> 8 train
SEEN_DRAWS = (bench_diag89.SEEN_DRAWS
              + [("planted", s, 12) for s in (8966, 8967, 8968, 8969, 9047, 9048, 9049, 9101, 9102, 9104)]
              + bench_diag89.FRESH)
FRESH = [("clean", s, 12) for s in range(9326, 9330)] + [("planted", s, 12) for s in range(9330, 9336)]


def draws(root: str, label: str) -> None:
    """:data:`SEEN_DRAWS` through bench_diag86's ``fresh`` -> ``ROOT/fresh-draws-LABEL.jsonl``."""
    bench_diag86.FRESH = SEEN_DRAWS
    bench_diag86.fresh(root, f"draws-{label}")


def fresh(root: str, label: str) -> None:
    """:data:`FRESH` through bench_diag86's ``fresh`` -> ``ROOT/fresh-LABEL.jsonl``."""
    bench_diag86.FRESH = FRESH
    bench_diag86.fresh(root, label)


def main(argv: list[str]) -> int:
    commands = {"write": bench_diag88.write, "seen": bench_diag88.seen, "draws": draws, "fresh": fresh,
                "compare": bench_diag89.compare, "one": bench_diag89.diagnosed}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
