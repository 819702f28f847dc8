"""Issue 34's closed-loop acceptance counts the test error AS DEPLOYED (stop 76, diag76): a change
``diagnose`` accepts must not leave the served model (envelope clamp, monitor, guard) worse.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag76.py removal ROOT SEED    # tcm74's record: the deployed CV check

``removal``: bench_diag75's ``removal`` (bench_stranger74's ``write ROOT SEED 24 60`` record,
tcm74, 22 sensors, one record cut 70/30, ``thermocomp diagnose`` at the defaults), then the
deployed CV figures the rule computed (``diagnosis.json`` ``deployed_cv``), and the diagnosis'
own seconds.

Found at stop 75: on tcm74 seed 7442 the health step removes the healthy ``T_Hydraulik`` (jump
3.58); as run the targets are no worse (0.865 / 0.242 / 1.010 -> 0.685 / 0.241 / 0.998 µm),
deployed they are (1.428 / 0.389 / 1.720 -> 1.485 / 0.435 / 2.194): the envelope refitted on 21
inputs clamps 109 -> 260 test rows.  ``diagnose`` already scores before / after as deployed
(diagafter60: ``before.test_rmse`` / ``after.test_rmse``, run's as ``*_as_run``); what it
weighs when it accepts is the CV of the model as run.

The rule ``deployedcv`` (written before scoring)
-------------------------------------------------
After the search, the search's CV is run once more with every fold's model *deployed*: the fold's
model (the diagnosed configuration, the hyper-parameters chosen on all train rows) fitted on the
fold's train rows, deployed through the same ``stream_of`` the test figures use (promote's
envelope fitted on that part, with ``monitor.adaptive`` the monitor and guard around it), its
held-out rows streamed from their campaign's start (forward: through the record up to the block),
pooled RMSE over the rows the CV scores, per target; before and after.  Tolerance
``min_gain_pct`` (5 %, the removals' own non-inferiority margin):

1. sensors excluded and some target's deployed CV RMSE > 1.05 x before's -> every exclusion
   withdrawn (the effects kept, refitted on every input), the check run again;
2. a target still > 1.05 x before's -> its effects withdrawn (the target as before).

Withdrawn changes are said (a warning, ``effects[].withdrawn``, ``deployed_cv``).

The bar (adopt only if all hold; else src reverted, this bench and ``diag76_rule.patch`` kept,
REFUSED):

1. tcm74 7442 (``removal``): the harmful removal withdrawn, or no target's test RMSE as deployed
   worse than before diagnose.
2. bench_diag75's fresh draws: planted 7573-7584 found 11 of 12, clean 7561-7572 accepting 0 of
   12 (as shipped).
3. bench_diagnose_faults58 / bench_diag75: planted faults found unchanged (16 cases).
4. Fresh draws 7681-7695 (clean 7681-7688, planted 7689-7695, bench_diag75's ``fresh`` kinds):
   no target's test RMSE as deployed > 2 % worse after diagnose.
5. CPU of ``diagnose`` on tcm74 7442 not above 1.5x shipped.

Scored: below, after this rule and bar are committed.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import made_folder, run_commands  # noqa: E402


def removal(root: str, seed: str) -> None:
    """bench_diag75's ``removal``, then the deployed CV check's figures."""
    import bench_diag75

    folder = made_folder(root)
    bench_diag75.removal(str(folder), seed)
    d = json.loads((folder / "diag" / "diagnosis.json").read_text())
    print(f"  deployed CV: {d.get('deployed_cv')}")
    print(f"  diagnosis seconds: {d['seconds']:.2f}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"removal": removal}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
