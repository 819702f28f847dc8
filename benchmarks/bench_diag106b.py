"""A sensor removal judged on a bound, not on a point estimate 8 campaigns cannot carry (stop 106,
diag106b; issue 34: "``diagnose`` ... never leaves a record's test error more than 2 % worse").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag106b.py seen ROOT            # 10076 (diag106's draw) -> ROOT/rows.jsonl
    python benchmarks/bench_diag106b.py fresh ROOT           # 10082-10086 + clean twins -> ROOT/rows.jsonl
    python benchmarks/bench_diag106b.py table ROOT           # bench_diag106's table of ROOT's rows
    python benchmarks/bench_diagfault72.py faults ROOT STEM  # bar item 2 (faults58's 36 cases)
    python benchmarks/bench_diag75.py removal ROOT 7442      # bar item 3 (tcm74 7442)
    python benchmarks/bench_diagfault72.py record WORK STEM "90/10 mlr" "60/20/20 mlr" \\
        "60/20/20 hammerstein E_ch4"                         # bar item 5 (fl_thermal, the docs' rows)
    python benchmarks/bench_diagfault72.py score WORK ROOT SHIPPED NEW  # items 2 and 5 counted

``seen`` / ``fresh``: bench_diag106's ``audit`` (the user's commands: simulate, diagnose at the
defaults, the rerun, replay; test RMSE as diagnose scores it, deployed) on :data:`KINDS`.

The harm (diag106, 1707a192): fresh 10076 (year-round VMC, ``sensor_drift`` on ``T_box1`` in the
later campaigns, train and test) -- diagnose excludes ``T_box1`` and ``E_Z`` goes 4.565 -> 5.430 um
(+18.9 %).  ``E_Z`` reads ``T_box1`` (MLR coefficient -2.15 um/K).  The removal's non-inferiority
(``search.Search._evaluate``: no target >= ``min_gain_pct`` worse in CV) passed on its pooled point
estimate (5.00 -> 4.89 um) while the 8 held-out campaigns' changes ran -38 ... +39 % (K07 +39 %,
K08 +14 %); on test 3 of 4 campaigns got 35-72 % worse.

The rule ``notworse`` (form and level chosen before any scoring; no constant fitted on 10076)
---------------------------------------------------------------------------------------------
A removal's non-inferiority is a TEST, not a point estimate: on every target, besides the shipped
clauses (jump ratio >= ``fault_ratio``; pooled and in-range CV not ``min_gain_pct`` worse), the
held-out units' MSEs (``CVResult.unit_mse``: the campaigns; forward, the validation blocks) must
show at ``alpha`` that the removal costs less than ``min_gain_pct``: the one-sided sign-flip p of
``e_k = (1 + m)^2 MSE_k - MSE+_k`` (m = ``min_gain_pct`` / 100; mean <= 0 under "worse by m or
more") <= ``alpha`` -- the margin test the effects pass (``margin_pvalue``), the margin on the cost
side (``search.not_worse_pvalue``).  Level: the project's ``alpha`` (0.01), the one the effects
use; no new key.  Where the units cannot reach ``alpha`` (fewer than 7: smallest p 2^-n > alpha)
the level is their smallest p: every unit within the margin.  Every target must pass (an
intersection-union test: no multiplicity correction).  How it differs from the refused rules:
diag75 ``onealpha`` asked a GAIN at p <= alpha on some target (superiority, margin 0); fault70
EARN asked a 5 % gain.  This asks no gain: a removal the model already discounts (each unit
changed by less than the margin) passes at the design's smallest p.

Kinds of the fresh draws (chosen before drawing; bench_diag106's): 10082, 10084, 10086
``vmc_drift_later`` (10076's kind), 10083, 10085 ``vmc_jump_some`` (10077's kind); each with its
clean twin; 8 train campaigns each.

BAR (all must hold, else REFUSED: src reverted, this bench and ``diag106b_rule.patch`` kept):

1. seen 10076: ``E_Z`` no longer > 2 % worse (diagnose's after vs before, deployed).
2. bench_diagnose_faults58's 36 cases (bench_diagfault72 ``faults``, shipped = ``git archive`` of
   1707a192): every planted fault the shipped code excludes still excluded; no healthy sensor
   removed that shipped keeps.
3. tcm74 7442: the healthy ``T_Hydraulik`` kept.
4. tests/apps/test_diagnose*.py and tests/**/test_diagnose* pass.
5. fl_thermal, the docs' diagnose rows ("90/10 mlr", "60/20/20 mlr", "60/20/20 hammerstein
   E_ch4"): no channel's after > 2 % worse than shipped's after.
6. fresh 10082-10086 (scored once, after this bar is committed): no (draw, target) > 2 % worse
   (after vs before); the clean twins accept nothing (no effect, no sensor excluded).
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_diag106 as d106  # noqa: E402
from _cli import run_commands  # noqa: E402

SEEN = "10076"
FRESH = "10082-10086"
KINDS = {10082: d106.KINDS[10076], 10083: d106.KINDS[10077], 10084: d106.KINDS[10076],
         10085: d106.KINDS[10077], 10086: d106.KINDS[10076]}


def audit(root: str, seeds: str) -> None:
    d106.KINDS.update(KINDS)
    d106.audit(root, seeds)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"seen": lambda root: audit(root, SEEN),
                                  "fresh": lambda root: audit(root, FRESH),
                                  "table": d106.table}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
