"""A fresh drift exclusion judged against the field with the excluded sensors put back in
(mon83d, issue 34): an unseen heat source setting in is a new thermal state, not a drifting pair.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_mon83d.py trace [ROOT] [SEED] [FIRST] [LAST]
    python benchmarks/bench_mon83d.py score [ROOT] [SEEDS] [KINDS]

bench_mon83c's ``trace`` and ``score`` (its docstring: column_moving_source, MLR on the train
split, deployed adaptive with ``monitor.fallbacks=unobservable``; ``score`` per record the E_*
test RMSE fixed / served, the sensors out as row spans, a drift's first row out), here by default
on ``/tmp/mon83d-bench`` and this task's fresh seeds 8611-8620.  The stranger machines' healthy
draws are bench_mon83's ``trunnion`` / ``lathe`` / ``jig`` (``ROOT LABEL SEEDS healthy``) and its
``table``.

The case (bench_mon83c): column_moving_source seed 8546, healthy.  The unseen source Q3 sets in at
row ~721; at row 731 ``T_left1`` (leverage 0.82) is the only sensor out of band and goes out as a
lone fault, ``T_left3`` with it as its blind partner; with the pair out the others stay in band,
so the field does not follow within the window (10 samples; it does at 744) and the pair stays
out to 1247: served E_Y 71.260 µm against the fixed model's 16.489.  Judge only (the pair kept
in), ``T_right4`` leaves its band at 732 and a new thermal state is named at 734: the exclusion
itself, changing the operator, held the others in band.

The rule (written and committed before scoring).  ``Judgement._follow_field``: a drift exclusion
is followed by the field (the sensor re-admitted, a new thermal state declared) where, within a
window of it, ``new_state_others`` other judged sensors are out of their warning band (every
error of the last ``confirm`` samples beyond it, as ``_judge``) with the sensor out, as before,
*or with every fresh drift exclusion (within its window) put back in the fit* (their readings in
the operator, ``_left_with``; the fresh sensors themselves not counted).  A true drift's exclusion
was allowed only where fewer than ``new_state_others`` others were out with it in (the veto),
and within a window its drift adds little: it stays out.  The exported monitor follows it
(``export/watch.py``'s ``_follow_field``, ``watch_c.py``'s ``mon_judgement``: the operator of the
set with the fresh ones back in, which the code always holds: every sensor in, one out, or the
pair itself), C = numpy mirror = served.

Bar (written before scoring; REFUSED if any part fails: the source reverted, the rule kept as
``benchmarks/mon83d_rule.patch``; "main": the sources of 70656590, alternated with the rule):
1. s8546 healthy: every E_* target's served RMSE no more than 2 % above the fixed model's.
2. Fresh healthy column_moving_source 8611-8620: no served E_* RMSE more than 2 % above main's.
3. Drift (bench_cmon82's ``+1 K/h`` from the middle row) on 8611-8620: the drifting sensor first
   out no later than on main, no served E_* RMSE more than 2 % above main's.
4. Healthy trunnion 8621-8622, lathe 8623-8624, jig 8625-8626 (bench_mon83's harness): no
   exclusion or new thermal state that main does not have, adaptive RMSE not above main's.
5. tests/shell/test_monitor*.py, tests/apps/test_monitor*.py, tests/shell/test_export*.py pass.
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_mon83c  # noqa: E402
from _cli import run_commands  # noqa: E402


def trace(root: str = "/tmp/mon83d-bench", seed: str = "8546", first: str = "725",
          last: str = "770") -> None:
    """bench_mon83c's trace (docstring)."""
    bench_mon83c.trace(root, seed, first, last)


def score(root: str = "/tmp/mon83d-bench", seeds: str = "8611-8620",
          kinds: str = "healthy,drift") -> None:
    """bench_mon83c's score on this task's fresh seeds (docstring)."""
    bench_mon83c.score(root, seeds, kinds)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"trace": trace, "score": score},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
