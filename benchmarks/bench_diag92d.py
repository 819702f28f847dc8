"""Diagnose's round block length set by the family members that could clear (stop 92, diag92d;
issue 34: "diagnose accepts a planted position effect with 8 train campaigns"; bench_diag92b's
"left").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag92d.py draws ROOT LABEL SET   # SET's draws -> ROOT/SET-LABEL.jsonl
    python benchmarks/bench_diag92d.py compare ROOT SET A B   # two labels' rows of SET: the bar's counts

``draws`` / ``compare``: bench_diag91b's (12 campaigns, every 3rd test, 8 train; MLR,
``max_effects=2``, every target; ``few:4004`` E_Y only), on :data:`SETS`: ``trace`` and ``seen``
bench_diag91b's, ``fresh`` the unspent seeds 9486-9495 (clean 9486-9489, planted 9490-9492, lag
9493-9495) drawn as bench_diag91b draws them.  bench_diag92b's ``trace CASE...`` shows one
draw's E_Y gates.

The rule (``Search._recut_on_gains`` / ``Search._could_clear``)
--------------------------------------------------------------
diag91b re-cuts each round's test blocks as long as the LONGEST decorrelation length of the
per-sample gains over the round's family.  On planted 8969 E_Y that was S_pos_Y raw (51
samples; p 0.09 on the current blocks: it cannot clear), which kept the position members (32-33
samples, p 0.008) on one block per campaign, the family-wise floor 3/256 = 0.0117 > 0.01.  The
rule: the length is the longest over the members that clear the bar on the current blocks by
their own p (``clears_bar`` before the family-wise p: gain floor, p and p_margin <= alpha, in
range, not saturating), or over the whole family where none does (main's).  Nothing else moves:
the max-T null is still over the whole family.

The bar (the brief's; written here BEFORE any run of either tree on the fresh seeds 9486-9495;
all must hold, else REFUSED: src reverted, this bench and ``diag92d_rule.patch`` kept):

1. FRESH 9486-9495: no (draw, target) row more than 2 % worse than main.
2. FRESH clean 9486-9489 accept nothing on any target; no control clears on any fresh draw.
3. FRESH planted 9490-9492: the position found on at least main's draws.
4. SEEN (``trace`` + ``seen``): no row more than 2 % worse than main; few:4004 accepts nothing.
5. ALL tests/*/test_diag*.py pass (three parts, ``-n 2``).

Scored
------
(below, filled in after the runs)
"""

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402
from bench_diag91 import compare, diagnose_cases  # noqa: E402 (the same rows)
from bench_diag91b import SETS as SEEN_SETS  # noqa: E402
from bench_diag91b import _dataset  # noqa: E402

SETS = {"trace": SEEN_SETS["trace"], "seen": SEEN_SETS["seen"],
        "fresh": ([("clean", s) for s in range(9486, 9490)] + [("planted", s) for s in range(9490, 9493)]
                  + [("lag", s) for s in range(9493, 9496)])}


def draws(root: str, label: str, name: str) -> None:
    """:data:`SETS` ``name`` diagnosed (module doc) -> ``ROOT/NAME-LABEL.jsonl``."""
    diagnose_cases(root, label, name, SETS[name], _dataset)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"draws": draws, "compare": compare}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
