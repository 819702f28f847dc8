"""A lab's data in (stop 89, data89b): data89's leftovers, a time column of seconds since
midnight (``Seconds of day``: 77400 ... 86100, 0, 300 ...), one pause warned of once, and
``ingest_report.json``'s ``settings`` under the data config's keys; then a stranger's pass over
bench_data89's exports, its seconds-of-day file among them, on fresh seeds.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_data89b.py write ROOT SEED           # bench_data89's exports of SEED
    python benchmarks/bench_data89b.py score ROOT SEED [LABELS]   # init + run + replay of each

``write``: bench_data89's ``write`` (``thermocomp simulate seed=SEED``, its longest campaign as
a lab's one record from 21:30:00, past midnight: ``contract.csv`` and ``excel2``,
``tabcomment``, ``midnight``, ``latin1``, ``groups``, ``catman``, ``trace`` and ``daysec``, the
time as a logger's seconds since midnight, ``Seconds of day``).
``score``: bench_data89's ``score``: per export ``init <path>`` then ``run model=mlr
data.test_fraction=0.25`` on the data config it wrote (a refusal's own key typed once where it
names one, bench_data88's FOLLOWED), the test RMSE per target against ``contract.csv``'s, then
``replay`` against the contract's replay; ``LABELS`` (comma-separated): only those.

The rule (src): a numeric time column whose values are all within a day, [0, 86400) s, is read
by the time of day's rule (data88b's ``past_midnight``: a day added where the clock goes back by
more than half a day) where its header says seconds of the day (``Seconds of day``, ``seconds
since midnight``, ``Tagessekunden`` ...: a time header for ``init`` too, never Excel's serial
days) or its values do (each step back, a day added, no longer than a step the clock takes
elsewhere: an elapsed time started again after half a day is no midnight, and its refusal,
"time decreases", says what reads seconds of the day); the report's ``time``: ``seconds of
day``.  A pause is warned of once: a time written as ``h:mm:ss`` has its pauses said as it is
read (a dateless clock's "a day lost", data89's; an elapsed time's "runs joined? one file per
run, data.roles.campaign", not ``data.runs_at_pauses``, which refuses a text time), the
record's "one record, yet it pauses" only where ``data.runs_at_pauses`` can split the time.
``ingest_report.json``'s ``settings``: ``join.offset_s`` / ``join.tolerance_s`` (the data
config's keys, as ``ingested_with.settings`` name them, less the ``data.`` prefix).

BAR (written before the fresh seeds 9346-9350 were scored; dev seed 4242 only before): KEPT
where on 5 of 5 seeds (a) every export is accepted, or refused with exit 2 naming the file,
the column and the row (or the file and the key to give); (b) each accepted one has the test
RMSE of ``contract.csv`` to 1e-6 µm on every target and its replay the contract's replay's to
1e-6, ``daysec`` accepted so (main: refused); (c) the tests of tests/shell/test_data89b.py
fail on main 2f23e004 and pass here (one or more per mended defect).  Any export read silently
wrong (exit 0, RMSE not the contract's) refuses the branch.

Scored (2026-12-05, fresh seeds 9346-9350, each ``write`` once by fix/data89b, then ``score`` of
every export on fix/data89b and, on a copy of ``contract.csv`` and ``daysec.csv``, on main
2f23e004; dev seed 4242 only before; the bar unchanged)
------------------------------------------------------------------------------------------
Test RMSE (µm, E_X / E_Y / E_Z; mlr, the last quarter held out) of contract.csv, then its
replay, alike on main and here: 9346 0.314643 / 1.334922 / 1.144470, replay 0.366982 /
1.063568 / 0.864122; 9347 0.949734 / 0.981478 / 0.702237, replay 0.869634 / 1.499886 /
1.882908; 9348 0.616862 / 0.738383 / 0.963744, replay 0.613922 / 0.737440 / 0.960453; 9349
0.512090 / 0.393918 / 0.653974, replay 0.400119 / 1.408720 / 1.313115; 9350 0.690166 /
0.946382 / 1.055114, replay 0.504895 / 0.668072 / 1.080630.

==========  ==========================================  =============================================
export      main 2f23e004 (5 of 5 seeds alike)          fix/data89b (5 of 5 seeds alike)
==========  ==========================================  =============================================
excel2,     (data88 / data88b / data89: accepted)       accepted, RMSE and replay = contract (1e-6)
tabcomment,
midnight,
latin1,
groups,
trace
catman      (data89: as here)                           refused exit 2 (file, column T0, line 11,
                                                        data.dayfirst=true|false); with
                                                        data.dayfirst=false: RMSE and replay =
                                                        contract
daysec      refused exit 2: file, "no 'time' column     accepted (init: 'Seconds of day', the time,
            ... set data.sample_period_s" (dev 4242,    in seconds), RMSE and replay = contract
            with data.roles.time='Seconds of day':      (1e-6)
            "time decreases from 86100 s (row 30) to
            0 s: ... sort them by their time")
==========  ==========================================  =============================================

Tests (tests/shell/test_data89b.py, 6): all fail on a checkout of main 2f23e004 (no time
column, or "time decreases ... sort them"; the restarted time's refusal says nothing of seconds
of the day; the dateless clock's pause warned twice, the second naming data.runs_at_pauses;
the elapsed time's pause named data.runs_at_pauses=true, which then refuses it; settings said
``join_offset_s``) and pass here; tests/shell/test_audit88b.py's settings test now expects
``join.offset_s`` (it fails on main, by design: the naming changed).

Against the BAR: (a) every export accepted, or refused exit 2 naming file, column and row
(catman; its key typed, accepted); (b) 40 of 40 accepted runs and replays = the contract's to
1e-6, daysec 5 of 5 (main: 0 of 5, refused); (c) tests as said.  KEPT.  CPU: the rule reads a
numeric time's min / max and steps once (no cost seen: the runs' CPU as main's).
Seen, not in the bar (by hand, seed 9346 only): ``daysec.csv`` piped into ``monitor
monitor.input=-`` on daysec's init config = ``contract.csv`` piped on contract's (rmse_fixed /
rmse_adaptive / n_samples: E_X 0.383565 / 0.375497 / 57, E_Y 0.593624 / 0.598824 / 57, E_Z
0.654234 / 0.637792 / 57, alike).  Not measured: ``data.runs_at_pauses`` on a seconds-of-day
record (it splits the raw values: a pause across midnight would not be found).
"""

from __future__ import annotations

import sys

from _cli import run_commands
from bench_data89 import score, write


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "score": score}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
