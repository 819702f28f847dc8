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

Scored: (below, after the fresh seeds)
"""

from __future__ import annotations

import sys

from _cli import run_commands
from bench_data89 import score, write


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "score": score}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
