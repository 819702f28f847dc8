"""The Structured Text block's sensor-fault flags scored on fresh seeds, under a bar that counts what
the ST holds (st93b, issue 34; follow-up of st93).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_st93b.py fresh ROOT [RECORD ...]

``fresh``: bench_st93's ``trace`` (its module doc: the block's ``mon_flag`` / ``mon_rule`` /
``mon_sensor`` stepped beside the served model from a reset over the first test campaign,
healthy, then per monitored sensor a planted spike / dropout / range / freeze; columns
``served`` / ``hits`` / ``misses`` / ``stepped`` / ``other`` / ``false``; ``max |ST - C|``
before the C mirror's first event) on fresh records: bench_cmon91's generators (lr / dl / cr / lr
/ dl) with the seeds of :data:`FRESH`, 9614-9618, never simulated before, each simulated and
``run model=mlr`` once under ``ROOT``.  Only the seeds differ from ``bench_st93.py fresh``.

The bar -- RESTATED after st93 scored the same rule on 9581-9585, and written and committed here
before any of 9614-9618 was simulated.  Why restated: st93's bar counted every served exclusion
whose reason begins ``jump`` as a jump the block must flag, and so counted as misses (15) the
served monitor's stepped self-prediction-error exclusions (``InstantFaults._check_stepped``, the
C's ``STEP_OUT``), which are judged by the others' prediction (the POD) -- a rule the ST does not
hold and that st93's brief never asked it to hold.  Restated:

1. Healthy, every fresh record: 0 false flags; ST = C mirror to 1e-9 µm on every row before the
   mirror's first monitor event (st93's bar said 1e-6; tightened).
2. Every served exclusion by a rule the ST holds -- dropout, reading beyond range, instant jump
   (bench_st93's ``served``: reasons ``dropout`` / ``out of range`` / ``jump`` but not the
   stepped error) -- flagged by the block at its row with the sensor and the rule (misses 0), in
   the healthy run and under planted spike, dropout, range and freeze on every monitored sensor of
   every fresh record; false 0 in all of them.
3. The POD-judged stepped exclusions (``stepped``) and the other served kinds the ST does not
   hold (``other``: freeze, drift ...) are counted apart, NOT as misses, and reported.
KEPT if 1-2 hold on all five records; else REFUSED with the cases named (src as on main, the
rule's diff in benchmarks/st93_rule.patch).

The bar is unchanged since it was committed (511fa196); nothing was tuned on 9614-9618.

Results (2026-12-05; 2 cores shared by 8 helpers; ``fresh /tmp/st93b/fresh``, scored once: 34.7 s
of this process's CPU for the five, each record's simulation and ``run model=mlr`` a few seconds
more)::

    record  healthy: served hits misses stepped other false   max|ST-C| µm (before the C's 1st event)
    lr9614           0      0    0      1       1     0       9.24e-14
    dl9615           0      0    0      1       1     0       9.95e-14
    cr9616           0      0    0      0       0     0       1.07e-14
    lr9617           3      3    0      0       0     0       9.24e-14
    dl9618           2      2    0      1       0     0       1.03e-13

    kind     (cases per record 14 / 14 / 12 / 14 / 14)
             served          hits       misses  stepped     other       false
    spike    11/11/12/14/12  = served   0       2/2/0/0/2   0/1/0/0/0   0
    dropout  14/14/12/14/14  = served   0       0           0           0
    range    14/14/12/14/14  = served   0       0           0           0
    freeze   0/0/0/0/0       -          0       0           8/7/10/4/9  0

Verdict: KEPT.  1 holds (0 false flags healthy on all five; ST = C to at most 1.03e-13 µm, bar
1e-9); 2 holds (every served dropout / range / instant jump, 5 healthy + 60 spike + 68 dropout +
68 range, flagged at its row with the sensor and the rule; false 0 in every run); 3: the
POD-judged stepped exclusions (3 healthy, 6 spike) and the freezes (38) reported apart, not in
the ST (docs/monitoring.md says so, the stepped error now named there).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_st93  # noqa: E402
from _cli import run_commands  # noqa: E402
from bench_cmon91 import FRESH as CMON91_FRESH  # noqa: E402

# bench_cmon91's generators (lr / dl / cr / lr / dl) on the seeds given, chosen before any was simulated
FRESH = {f"{record[:2]}{seed}": [f"seed={seed}" if w.startswith("seed=") else w for w in words]
         for (record, words), seed in zip(CMON91_FRESH.items(), range(9614, 9619))}


def fresh(root: str, *chosen: str) -> None:
    """The ``fresh`` tables (module doc): bench_st93's on this bench's seeds."""
    bench_st93.FRESH.clear()
    bench_st93.FRESH.update(FRESH)
    bench_st93.fresh(root, *chosen)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"fresh": fresh}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
