"""Why diagnose removed a healthy sensor on the wire EDM's spreadsheet export (issue 34; stop 65,
diagfault65), and a rule against it, scored.

Usage::

    python benchmarks/bench_stranger65.py write ROOT && ... init ROOT   # edm_a2, edm_b (stranger65)
    python benchmarks/bench_diagfault65.py forensics ROOT              # the cause, in numbers
    python benchmarks/bench_remeasure62.py write RM                    # the diagnose set (once)
    python benchmarks/bench_remeasure62.py diagnose RM                 # shipped rows (shipped src)
    python benchmarks/bench_diagfault65.py faults RM OUT.jsonl         # bench_diagnose_faults58's
                                                                       # 36 cases (run on each src)
    python benchmarks/bench_diagfault65.py edm ROOT OUT.jsonl          # edm_a2 + edm_b, mlr
    python benchmarks/bench_diagfault65.py score RM SHIPPED NEW        # the bar (file stems)

The shipped rows are written from an archive of the base commit's tree (``PYTHONPATH``), the new
ones from this branch's src; ``RM/diagnose.jsonl`` and ``RM/<NEW>.jsonl`` are bench_remeasure62's
runner (92 cases, 139 case x target), ``RM/faults-<stem>.jsonl`` and ``RM/edm-<stem>.jsonl`` the
others.  Nothing chooses on the test split: it is only scored.

The cause (forensics; stranger65's records rebuilt by its ``write``, seeds 6501 / 6502)
------------------------------------------------------------------------------------
(see "Measured" below for the numbers.)  The jump ratio is physics: the generator cabinet is
heated 300 W while the machine is powered (an unlogged state), its node is fast (5e4 J/K, ~1 h),
and at Saturday 12:00 (132 h) the machine goes off: the cabinet falls ~22 K in 4 h while the
other, slow nodes follow in hours to days, so its self-prediction from them errs by 10-17 K for
~6 h.  Not the ``Err:502`` cell, not a seam, not the frame.

The rule (written and committed before anything was scored; not tuned afterwards)
------------------------------------------------------------------------------------
A sensor fault is ONE sensor leaving the field; a change of the machine's regime (a power-off,
a new thermal state) moves the whole field away from what the self-prediction learnt, and every
sensor's error rises in that unit, the fast, source-driven one most.  So the own ratio is taken
against the field's own rise in the same unit: with ``q_k`` sensor k's lower-quartile unit RMS
(``sensors.self_prediction``, as shipped) and ``u*`` sensor j's worst unit,

    field_j = max(1, median over the other judged sensors k of r_{k,u*} / q_k)
    J_j     = min(cross_j, own_j / field_j)

(``cross_j`` and ``own_j`` as shipped; both passes; also for ``test_sensor_warnings``, which read
the same table).  ``field_j >= 1``: the rule only ever lowers a ratio, it nominates nothing new.

Adoption bar (written before scoring), new against shipped:
(1) no case x target of bench_remeasure62's diagnose set, of edm_a2 / edm_b (mlr, both targets)
    or of bench_diagnose_faults58's 36 cases ends > 2 % worse (test RMSE after diagnose) than
    shipped;
(2) planted found (remeasure62, the planted effect accepted first) does not fall (19 of 23);
(3) clean + null accepting (remeasure62) does not rise (1 of 44);
(4) faults58's planted sensor faults found does not fall (10 of 16; of the one-unit ones 5 of 16).
All four: adopted (src, a test failing on the old code, docs/diagnose.md); else refused (this
bench, a docs/diagnose.md paragraph with the numbers, src reverted).  CPU reported.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
