"""qr103's rule 2 (the C's POD solve by Gram-Schmidt twice, Q's rows for the sensors in) scored
on fresh portal, trunnion and climate-room records (issue 34; stop 103, qr103b).

qr103 (bench_qr103.py, REFUSED) measured the bar's rule (one modified Gram-Schmidt pass, ``w_k =
R^-T phi_k`` on every row) past 1e-9 µm on seen sets (pt9890 far ``third`` 1.32e-6 µm), then built
rule 2 after that run (benchmarks/qr103_rule2.patch, a6a53721), so not kept: on the same 80 seen
cases every max|C - served| <= 1.12e-10 µm (main: 7 past 1e-9, <= 1.05e-6), 1.02 x CPU per row.

RULE (rule 2 as the patch has it, applied unchanged to a8719dae: ``watch_c.py`` ``mon_operator``
and its mirror ``export/watch.py`` ``_solved_operator``): ``Q R`` of ``Phi_a`` (``s x r``, ``r =
min(modes, s)``) by Gram-Schmidt twice (each column projected off the earlier ones two times),
``w_k`` Q's row for a sensor in, ``R^-T phi_k`` for one out, ``M[k, m] = w_k . w_m``; refused
where ``R[p, p]^2`` is not above 1e-12 ``G[p, p]`` (the Cholesky pivot test's meaning).  No key;
the ST (no solve of its own) untouched.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_qr103b.py fresh ROOT RECORD [RECORD ...]

``fresh``: per record (:data:`FRESH`, simulated into ``ROOT/data`` and ``run model=mlr`` into
``ROOT/reports`` by this tree, each once) bench_dep103's ``returns`` lines (the healthy frame; the
plants ``back``, ``beside``, ``third`` of the cases ``far`` / ``near``) then bench_dep101's
``drops`` lines (the pair missing from the fault row on), as those benches print them.  Main's
log against the rule's: bench_qr103.py ``compare``; CPU per row: bench_qr103.py ``cpu``.

BAR (written and committed WITH the rule BEFORE fresh seeds 10004-10006 are simulated; scored
once; main = ``git archive a8719dae src``, its watch.py / watch_c.py / pod.py 8afba209's; the
rule = this branch's src.  The fresh records are simulated and run by main's tree into one ROOT;
the rule reads a copy of its ``data`` and ``reports``, every stream built anew)
---
Q1. Fresh pt10004 (portal64, bench_audit98's PORTAL, seed 10004), tr10005 (trunnion63,
    bench_audit97's TRUNNION, seed 10005), cr10006 (the climate room, bench_mon97's CR, seed
    10006), dep103's kinds; plants fixed here before drawing: bench_dep101's ``drop`` and
    bench_dep103's ``back`` (return), ``beside``, ``third``, as those benches plant them.  Every
    case on the rule: max|C - served| <= 1e-9 µm, 0 rows past it, 0 rows ``NOT_IN_CODE``, and no
    case farther from served than main's (``compare``: 0 lines FARTHER by > 1e-9 µm).  No rounding
    clause.
Q2. The seen lines of qr103's benches as rule 2 measured them: bench_dep103 ``returns`` re-run on
    this tree on pt9851 pt9890 pt9910 (the records of qr103's cases past 1e-9 on main; copies of
    /tmp/qr103/Sd's data and reports) gives the numbers of /tmp/qr103/log/returns_R2.log's lines
    for those records (max|C - served|, rows past, ``NOT_IN_CODE`` rows; a compiled number that
    moves is listed).
Q3. The healthy frames of the fresh and these seen records: 0 rows flagged, max|C - served| 0 µm.
Q4. qr103's export list on this tree: tests/shell/test_export.py (PARSED_DIGEST) and
    test_export_{wires100,dep100,dep99b,freezeu100,cmon85,cmon86,cmon88,cmon89,cmon93,step99}.py
    pass (52 with the cmon85 square-set case, which fails on a8719dae).
Q5. bench_qr103 ``cpu`` on pt9890, REPEATS 20, main's tree and the rule's alternately, twice
    each: the rule's per-row CPU (the lower of its two) <= 1.1 x main's (the lower of its two).
Compiled C = mirror is measured (``max|compiled - mirror|``) and reported, not a clause (qr103:
its 7.32e-11 µm gap lies outside the solve, on main the same).
KEPT if Q1-Q5 hold (src: rule 2, its cmon85 test, docs/to-the-machine.md naming the solve); else
REFUSED (benchmarks/qr103b_rule.patch, src as a8719dae), the numbers kept here.

SCORED (bar e1c23c02, unchanged, committed 01:22:10 UTC before any fresh seed was simulated;
2026-12-07 01:22-01:31 UTC, load 5-9 on 2 cores; main = /tmp/qr103b/base/src simulated and ran the
three into /tmp/qr103b/fM, the rule read a copy, /tmp/qr103b/fR; ``fresh`` CPU 101.3 s main, 91.1 s
rule).  Q1 MET: 30 lines (18 ``returns`` cases, 6 ``drops``, 6 healthy headlines), every case on
the rule <= 1.12e-11 µm, 0 rows past 1e-9, 0 rows ``NOT_IN_CODE``; ``compare`` main -> rule: 0
lines farther by > 1e-9, the 6 headlines identical.  max|C - served| (µm), main -> rule::

  pt10004 far (T_rail_drive + T_bed; + T_col_L, cond 586.9 / 334.6)
          back 6.62e-11 -> 1.86e-12, beside 5.37e-10 -> 1.09e-11, third 5.67e-10 -> 1.12e-11,
          drop 8.74e-11 -> 2.15e-12 (pair's M apart 7.5e-9 -> 4.1e-12)
  pt10004 near (cond 2.42 / 28.8)      <= 8.53e-13 -> <= 5.68e-13
  tr10005 far / near (cond 4.8-22.5)   <= 2.22e-12 -> <= 5.68e-13
  cr10006 far / near (cond 16.0)       returns 3.55e-14..2.59e-13 -> 3.55e-14..2.56e-13;
          drops 3.55e-14 -> 3.91e-14 (farther by 3.6e-15, under the clause's 1e-9)

Main too was within 1e-9 on every fresh case (its worst 5.67e-10): these draws have no set as
ill-conditioned as seen pt9890's (cond 2.05e4), so they tell no failure of main's apart; the rule
is 50 x closer on pt10004 far.  compiled - mirror <= 7.01e-12 µm on the rule (main 6.95e-12).
Q2 MET: ``returns`` pt9851 pt9890 pt9910 on this tree (/tmp/qr103b/Q2, CPU 42.5 s): its 20
lines ``diff``-identical to those records' lines of /tmp/qr103/log/returns_R2.log (compiled
numbers too; worst 1.12e-10, pt9890 far ``third``).  Q3 MET: 9 healthy headlines (fresh x 2
commands, the 3 seen), 0 flagged rows, 0 µm.  Q4 MET: 52 passed (243.5 s wall, 01:22-01:26);
the cmon85 square-set case fails on a8719dae (AssertionError).  Q5 MET: ``cpu`` pt9890 far
``third``, 20 x 2640 rows, alternately: main 4.38 / 4.21, rule 4.02 / 4.60 µs per row; lower
4.02 against 4.21 (0.95 x).  VERDICT: KEPT.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests"), str(HERE.parent / "tests" / "shell")]
import bench_dep101  # noqa: E402
import bench_dep103  # noqa: E402
from _cli import run_commands  # noqa: E402
from bench_audit97 import TRUNNION  # noqa: E402
from bench_audit98 import PORTAL  # noqa: E402
from bench_mon97 import CR  # noqa: E402

FRESH = {"pt10004": [*PORTAL, "seed=10004"], "tr10005": [*TRUNNION[1:], "seed=10005"],
         "cr10006": [*CR, "seed=10006"]}


def fresh(root: str, *records: str) -> None:
    """The ``fresh`` lines (module doc): dep103's ``returns``, then dep101's ``drops``."""
    # both benches look their records up in their module's FRESH at call time
    bench_dep103.FRESH.update(FRESH)
    bench_dep101.FRESH.update(FRESH)
    bench_dep103.returns(root, *records)
    bench_dep101.drops(root, *records)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"fresh": fresh}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
