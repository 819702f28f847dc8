"""The C and the served model say what the file reader says of the same rows (stop 107,
dep107c; issue 34 "deployed as scored").  audit107 (bench_audit107, cell F on col10133) left:
(1) a logger set to another sample rate mid-stream (100 s rows, then 1000 s from data row 202):
``replay`` (the file reader) and ``monitor.input=-`` warn naming the row, ``stream.c`` and the
served model say nothing, though their corrections match replay's; (2) the C's refusal of
``22,61`` (a decimal comma in a ','-separated stream) suggests a missing-value mark; (3) one more
such gap, chosen here: a stretch without rows (a gateway's outage: the file reader's
``rates.said_if_rows_missing``, "N stretch(es) without rows ... before line L").

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dep107c.py faults CELLS OUT [CELL ...]   # cells P, D, G, H

CELLS: bench_audit107's root (``data/col10133``, ``reports/col10133/<cell>`` and ``<cell>-c``,
made by its ``models`` command; read only).  OUT: scratch.  CELL: ``mlr-none`` ``lagbank-none``
by default.  Per CELL, the test file of col10133 (1441 rows at 100 s) as written (``healthy``)
and faulted by bench_audit107.faulted (``period10``, ``comma``) and here (``gap``: data rows
301-305 left out, a stretch of 6 periods): fed to (a) the cell's ``stream`` as audit107 built it
(570d5a78's stream.c: the base) and (b) this tree's ``stream.c`` (export.driver.DRIVER) built by
tests/cbuild.py beside the cell's compensator.c/.h, both ``--flags``; and to the served model in
process (pyfunc.CompensatorModel around the cell's model.pkl, the code ``serve`` runs) as one
block and as blocks of 50 rows in one session; per route: exit / status, what it says (stderr
lines, log warnings, events) and max |correction - base| over the rows.

BAR (written and committed BEFORE any of the figures below was measured; not to move after):
P. period10 (both cells): this tree's C says on stderr the period change, naming line 203 (data
   row 202, as the file reader names it) and both periods (100 s, 1000 s); the served model says
   it in a warning (session, the row of its block) and, for the adaptive model, an event of that
   row (``sensor`` time); served as one block and as blocks of 50 alike.  The C's stdout (--flags
   included: no new column) = the base's byte for byte; served corrections = BASE's served to
   1e-9 um; |served - C| <= 1e-9 um (audit107: 1.4e-13).
D. comma: the C exit 2 naming line 202 and input T_front1 and a decimal comma (not a
   missing-value mark); stdin exit 2 naming row 201, T_front1 and a decimal comma; the served
   400 naming row 201 and T_front1 (JSON: a number is sent as a number).
G. gap: the file reader says the stretch (replay of the rows); the C and the served model say it
   naming its row and its length in periods (or, where they say it already on BASE, traced); the
   corrections unchanged as in P.
H. healthy (both cells): no period nor gap line said by the C or served (no false alarm), the C's
   stdout = the base's byte for byte.
Each mend: a test failing on 1e995de3, passing here, <= ~3 s CPU (tests/cbuild.py for the C).
KEPT where P, D, G, H hold; else REFUSED (src reverted, the rule kept as
benchmarks/dep107c_rule.patch).
"""

from __future__ import annotations

import sys

from _cli import run_commands


def faults(cells: str, out: str, *chosen: str) -> None:
    """Cells P, D, G, H (module doc)."""
    raise NotImplementedError


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"faults": faults}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
