"""`connect` (OPC UA) says a sample period that changes and a stretch without rows as the file
reader does (stop 108, dep108b; issue 34 "deployed as scored").  dep107c made the C, the served
model and stdin read the rows' time with ``rates.StepWatch``; ``connect`` said neither (its
``clock_gap`` reads the server's clock against ``connect.period_s``: a period change is a gap at
every sample after it, and on a ``time`` node, the twin's, nothing at all).  Second gap (dep107b's
"named, not mended"): without a time column a stray blank line restarted the stream.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dep108b.py faults CELLS OUT [CELL ...]     # cells P, G, H
    python benchmarks/bench_dep108b.py compare OUT_BASE OUT_THIS        # corrections, both trees
    python benchmarks/bench_dep108b.py blank OUT                        # cell B

CELLS: bench_audit107's root (``data/col10133``, ``reports/col10133/<cell>/model.pkl``; read
only).  CELL: ``mlr-none`` ``lagbank-none`` by default.  Per CELL and feed (bench_dep107c's
``healthy``, ``period10`` (100 s rows, 1000 s from data row 202) and ``gap`` (data rows 301-305
left out, a step of 6 periods); ``comma`` is not a feed of connect: an OPC UA node holds a number):
the test file's rows served by tests/shell/vendor_machine.py (a vendor's server, lockstep, its
clock the record's time, offsets as Double nodes) to ``thermocomp connect`` of the cell's
model.pkl (``connect.clock=server``); what connect says of the rows' time (its log's warnings,
connect.json's events) beside what the file reader says of the same rows (``read_dataset``), and
the offsets the machine held at each row saved as OUT/<cell>-<feed>.npy.

BAR (written and committed BEFORE any figure below was measured; not to move after):
P. period10 (both cells): connect says the period change (100 s -> 1000 s) naming the campaign's
   data row 202, the row the file reader names, in a warning and a connect.json event (``time``,
   ``to: period changed``); on BASE it says no period change.
G. gap: connect says the stretch without rows (6 periods of 100 s) naming data row 301, the row
   the file reader names ("before data row 301"), warning and event (``rows missing``).
H. healthy (both cells): no period nor rows-missing word from connect (no false alarm).
C. every feed, both cells: the offsets the machine held = BASE's (same bench on 0dd05741's src) to
   1e-12 um (the watch says; it changes no correction).
B. blank: a stream without a time column (``data.sample_period_s``) with a stray blank line among
   its rows: the file reader, stdin (``monitor.input=-``) and stream.c read it alike, as the data
   contract (docs/data-format.md) says of a file: the blank line left out, said, the rows after it
   one period on, no new campaign; the corrections of stdin and the C then = those of the same
   rows without the blank line (to 1e-9 um).  On BASE at least one reader restarts there.
Each mend: a test failing on 0dd05741, passing here; the tests added cost <= 3 s CPU in all.
KEPT where P, G, H, C (and B, or B traced as a separate verdict) hold; else REFUSED.
"""
