"""The Structured Text block follows the C's ``BACK`` of one sensor out alone by its own
``STEP_OUT`` and judges on (st95b, issue 34; follow-up of st95, which traced bench_st94b's 15
``apart`` C STEP_OUT to a lone exclusion re-admitted by BACK 10-12 rows earlier).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the block measured is that tree's)::

    python benchmarks/bench_st95b.py trace ROOT RECORD [RECORD ...]
    python benchmarks/bench_st95b.py frame ROOT RECORD [RECORD ...]
    python benchmarks/bench_st95b.py fresh ROOT [RECORD ...]

``trace``: bench_st95's ``trace`` (bench_st94b's: healthy, bent and pair cases, each case's first
C event classed ``agree`` / ``mismatch`` / ``apart`` / ``other``, ``early`` the block's flags
before it) where an ``apart`` case whose C log is ``step-back`` -- every exclusion before it a
``STEP_OUT``, one out at a time, each back by ``BACK``, none out at its row -- is scored as any
held rule (``agree`` / ``mismatch``), not set apart; then bench_st93's ``trace`` (planted spike /
dropout / range / freeze per monitored sensor and healthy: served / hits / misses / false).
``frame``: the block (not told anything) and the C over each record's whole healthy frame, every
row where either says something printed (a block flag on a row without a C event is false).
``fresh``: ``trace`` and ``frame`` on :data:`FRESH` (bench_cmon91's lr / dl / cr / lr / dl
generators on seeds 9749-9753), each simulated and ``run model=mlr`` once (bench_cmon92's ``made``).

The rule (src/thermocomp/apps/deploy/export/st_watch.py): where the block's own ``STEP_OUT``
takes out a sensor the C holds out (``MON_STEP_HELD``) with nothing else in that row, the block
holds it out alone (``mon_held``) instead of ending its judgement: its wait is the C's, the window
doubled at each such exclusion of it (at most ``MON_MAX_BACKOFF`` times); it keeps every row's
readings on their references in a ``w x n`` ring (``mon_ring``, the C's ``hist``) and each
sensor's error with every sensor in; after the wait, with ``w`` samples counted, the sensor is
back where its error with every sensor in (``MON_SELF``, ``MON_SCALE``) is within
``MON_BACK_BAND`` (``READMIT`` times the whole set's warning band) on every row of the ring, as
the C's ``_pass_once_back`` with all in.  It judges none while one is out; its last errors on
return are those with every sensor in, as the C's.  Anything else while one is out -- a rule the
block names, any monitored reading equal to its last (the C's freeze / run counts) -- ends its
judgement to the campaign's end, as before.  A second sensor the C takes out (its single-out
stepped / drift judgements) the block cannot see.

The BAR (committed before any of 9749-9753 was simulated)::

1. Healthy, every fresh record: 0 false flags (bench_st93's ``false``, this trace's ``early``,
   and ``frame``: no block flag on a row without a C event); ``max|ST-C|`` <= 1e-9 µm over the
   rows before the C's first event (bench_st94's first unmatched one).
2. bench_st93's planted kinds on every fresh record: ``misses`` 0 and ``false`` 0.
3. Seen (bench_st94b's lr9681 / dl9682 / lr9684 / dl9685, spent): the 14 ``step-back`` of the 15
   apart become ``agree`` with ``mismatch`` 0, ``early`` 0.  lr9684's one (its exclusion a blind
   JUMP, undone by the block's SPIKE a row later where the C holds it to BACK: st95 ``frame``)
   stays ``apart``: the brief's "15 apart -> agree" read so, said here before scoring.
4. Fresh: every case whose first C event is a ``STEP_OUT`` after a lone ``STEP_OUT`` re-admitted
   by ``BACK`` (``step-back``) named at its row with its sensor (``agree``): ``mismatch`` 0 over
   all cases, ``early`` 0 in every case.
KEPT if 1-4 hold; REFUSED with the cases named otherwise (src as on 674a868c, the rule's diff in
benchmarks/st95b_rule.patch); TRACED / not scored if fresh cannot be scored by the deadline
(02:45 UTC; the seeds then left undrawn).

The bar is unchanged since its commit (dfeae4a1, with the rule, before 9749-9753 were simulated);
nothing was tuned on them.  Seen before it (development): lr9681's first follow lost at 3196 under a
first guard (any monitored reading equal to its last: the readings are quantized), narrowed to the
held sensor's own run (the C's ``run`` / freeze), then T_head_right back at 3207 as the C.

Results (2026-12-06, 2 cores shared; CPU of this process).  Seen ``trace`` on bench_st94b's
records (71.5 s + 92.9 s, two processes)::

    record  bent agree/apart (674a868c)  pair agree/apart (674a868c)  mismatch early
    lr9681  3/0 (1/2)                    91/0 (90/1)                  0        0
    dl9682  0/0 (0/0)                    91/0 (85/6)                  0        0
    lr9684  0/1 (0/1)                    91/0 (91/0)                  0        0
    dl9685  2/0 (0/2)                    91/0 (88/3)                  0        0

14 of the 15 apart named alike at their row; lr9684's stays apart (as written in bar 3);
bench_st93's planted kinds misses 0 false 0 on all four.

Fresh ``fresh`` (scored once; 115.1 s + 105.6 s, two processes, with the simulations)::

    record  false early max|ST-C| µm (rows)  C first event (row) = block  bent a/m/ap/o/n  pair a/m/ap/o
    lr9749  0     0     9.59e-14 (1438)      BLIND_OUT (1439), other      1/0/4/10/9       85/0/5/1
    dl9750  0     0     8.53e-14 (1677)      STEP_OUT (1678) agree        6/0/0/8/14       90/0/0/1
    cr9751  0     0     1.42e-14 (205)       none                         0/0/0/0/8        66/0/0/0
    lr9752  0     0     9.24e-14 (3090)      STEP_OUT (3091) agree        1/0/0/4/11       91/0/0/0
    dl9753  0     0     1.21e-13 (3609)      STEP_OUT (3610) agree        4/0/0/10/14      90/0/0/1

bench_st93's spike / dropout / range / freeze on every record: misses 0, false 0.  ``frame``: every
block flag on a C event named alike (lr9749 STEP_OUT 3183; dl9750 1678; lr9752 3091 and JUMP 4049,
SPIKE 4052; dl9753 3610), 0 block flags on rows without a C event; the C's BACK 10-11 rows after
each STEP_OUT.  The bent cases whose first C event is a STEP_OUT after the lead-in's step-back:
dl9750 3, lr9752 1, dl9753 3 named alike (per-case lines); ``mismatch`` 0, ``early`` 0 over all
cases.  lr9749's 9 apart are ``one-other`` (the C's BLIND_OUT of T_spindle_rear 1439 and
T_spindle_front 2916 before them, not in the block): not reached.

674a868c's block on the same fresh cells (this ``trace``, PYTHONPATH at 674a868c's src, after the
scoring): the step-back cases it leaves silent (``mismatch`` here, ``apart`` in bench_st94b) --
dl9750 bent 3 + pair 5, lr9752 bent 1, dl9753 bent 3 + pair 2: 14, every one named alike by the
rule (bent agree 3 -> 6 / 0 -> 1 / 1 -> 4, pair 85 -> 90 / 91 / 88 -> 90); lr9749 and the rest
of every table as above, to the digit.

Verdict by the bar as written: 1-4 hold: KEPT.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st93  # noqa: E402
import bench_st94b  # noqa: E402
import bench_st95  # noqa: E402
from _cli import run_commands  # noqa: E402
from bench_cmon91 import FRESH as CMON91_FRESH  # noqa: E402

# bench_cmon91's generators (lr / dl / cr / lr / dl) on the seeds given, chosen before any was simulated
FRESH = {f"{record[:2]}{seed}": [f"seed={seed}" if w.startswith("seed=") else w for w in words]
         for (record, words), seed in zip(CMON91_FRESH.items(), range(9749, 9754))}

_PLAIN = bench_st94b._first_kind.__defaults__[0]      # bench_st94's: agree / mismatch / other


def step_back(log, before) -> bool:
    """Whether an apart case's C log (bench_st95's) is ``step-back`` (module doc)."""
    if bench_st95.classed(log, before) != "one-back":
        return False
    for _, rule, _, was, now in log:
        went_out = sum(k >= 0 for k in now) > sum(k >= 0 for k in was)
        came_back = sum(k >= 0 for k in now) < sum(k >= 0 for k in was)
        if (went_out and rule != "STEP_OUT") or (came_back and rule != "BACK"):
            return False
    return True


def _first_kind(first, st94b=bench_st94b._first_kind) -> str:
    kind = st94b(first)
    if kind == "apart" and step_back(first[1][0].log[:-1], first[1][0].before):
        return _PLAIN(first)
    return kind


def trace(root: str, *records: str) -> None:
    """The ``trace`` tables (module doc)."""
    bench_st95.ORACLE = False
    bench_st94b._first_kind = _first_kind
    for record in records:
        bench_st95.trace(root, record)
        bench_st93.trace(root, record)


def frame(root: str, *records: str) -> None:
    """The block, told nothing, and the C over each whole healthy frame (module doc)."""
    bench_st95.Logged.resumed = lambda self, rule, bits: None
    bench_st95.frame(root, *records)


def fresh(root: str, *chosen: str) -> None:
    """``trace`` and ``frame`` on :data:`FRESH` (module doc), each record made once."""
    def both(root, record):
        trace(root, record)
        frame(root, record)

    bench_st93.fresh(root, *chosen, records=FRESH, traced=both)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"trace": trace, "frame": frame, "fresh": fresh}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
