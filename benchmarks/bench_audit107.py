"""Thermocomp run as a stranger would on stop 106's head (stop 107, audit107; issue 34), off the
happy path, at angles audit103 / audit105 / audit106 did not take: every figure of the README's
tables against what its commands print today in a fresh clone at BASE; a lab's raw export of a
kind not tried (Windows-1252, CRLF, ``;`` with decimal commas, one day-first timestamp column
``07.12.2026 13:05:00``, a units row, a trailing empty column, an operator's comment column of
text, one unplugged sensor that reads a constant) through ``init``, run, replay, ``monitor`` and
``export c``; a simulated kind none of the three ran (``column_moving_source``: 7 targets, 19+1
sensors, 100 s, ``S_pos_Z``) with every family x wrapper through run, replay and the C; faults fed
to the deployed compensator none of them tried (columns reordered or an unknown column in the C's
input, the served JSON and stdin; a sensor value as text with a decimal comma; a timestamp in
another format than training's; the sample period 10x longer mid-stream); a healthy draw through
``monitor``, the C and the ST.  The bar was written first.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_audit107.py readme CLONE              # cell R (a clone at BASE)
    python benchmarks/bench_audit107.py fltable CLONE [FAMILIES]  # cell T (the same clone)
    python benchmarks/bench_audit107.py models ROOT [WORD ...]    # cell M (fresh col10133)
    python benchmarks/bench_audit107.py faults ROOT PORT [CELL]   # cell F (col10133's cells)
    python benchmarks/bench_audit107.py healthy ROOT              # cell H (fresh col10134)
    python benchmarks/bench_audit107.py lab ROOT [FAMILIES]       # cell L (fresh lab 10135)

Kinds (conf/sim): yearround_spindle, large_mill_week, swiss_lathe_door, column_moving_source,
long_record, climate_room, large_mill_volumetric, fleet.  Each is named in some earlier audit bench
(audit86-100); audit103 ran large_mill_week, audit105 a declared wire EDM, audit106 climate_room.
``column_moving_source`` is in none of audit103/105/106 and no audit ran it through every family x
wrapper, replay and the code (audit89 / audit91 ran it in their sweeps, other seeds): chosen.

``readme``: bench_audit105's cell R at :data:`BASE` (bench_audit97's ``.venv/bin`` shims: the
shared venv's python on the clone's ``src``; ``make run``'s install would take > 5 min on the
shared cores, so nothing is installed; every block of README.md and docs/own-data.md as
tests/test_readme.py runs it; ports moved).
``fltable``: in CLONE, per family of the README's table, ``run data=fl_thermal`` on the 90/10 cut
and on the authors' 60/20/20 split (docs/own-data.md's keys), ``track=false plots=none``: mean
test RMSE (90/10) and mean test MAE (60/20/20) over ch1..ch5 against :data:`FL_TABLE`.
``models``: bench_audit105's cell M (bench_deploy88's cell + ``sim`` / ``dmax``) on :data:`RECORD`
per family x :data:`WRAPPERS` (arx_rf's state ``S_pos_Z``).
``faults``: CELL (default ``mlr-none``, then ``lagbank-none`` for the period) of :data:`RECORD`:
its compiled ``stream --flags``, the served model on PORT and ``monitor monitor.input=-`` fed the
test file with each fault of :data:`FAULTS` (:func:`faulted`); per route the exit / HTTP status,
the message, the first flagged row / events and |correction - reference| where the reference is
the healthy correction (the period fault: ``replay``'s batch on the same rows).
``healthy``: bench_audit106's cell H on :data:`HEALTHY`.
``lab``: seed 10135's swiss production campaign (bench_audit91's ``contract.csv``, 1441 rows at
60 s from 2026-12-07 13:05) written as ``export.csv`` (:func:`write_export`), then bench_audit100's
``lab_against_contract`` (init with no key, the keys its refusals name; run, plain, replay, export
C + pack, the C fed the raw bytes and ``rows``) and ``monitor`` of init's config.

Records (fresh seeds of this brief, chosen before any was simulated)::

  col10133  column_moving_source, the scenario's defaults (one train cycle, one test cycle): M, F
  col10134  the same kind, another draw: H
  lab 10135 the lab's export.csv: L

BAR (written and committed BEFORE seeds 10133-10135 were simulated; a BREAK is: a traceback or
exit 1, exit 0 on bad input taken silently (a wrong value used without a flag or event), the
deployed figure (replay, promote's "as deployed", the C) differing from the scored one by more than
1 % unexplained by the monitor's events, a false alarm on a healthy record, an unclear message
(no file, column or row where one is at fault), a README / docs command that fails as written,
a README figure that its command no longer prints)
-----------------------------------------------------------------------------------------------
R1. Every block of README.md and docs/own-data.md, run as tests/test_readme.py runs it in a clone
    at BASE, exits 0 and meets its expectation; the make-run table printed line by line as quoted.
T1. Every figure of the README's family table (60/20/20 MAE and 90/10 RMSE per family, 16.7
    before) = what ``run`` prints today, to the digits written.
L1. export.csv goes in: ``init`` with no key reads it or refuses in one message naming the key;
    with at most the keys its refusals name: the day-first stamps read as 2026-12-07 (60 s steps,
    not as July), the cp1252 bytes read (no replacement character; ``°C`` a unit), the units row
    not data, the trailing empty column and the comment column not sensors (left out and said),
    the unplugged sensor not a silent input (left out and said, or kept with no effect on any
    figure); never a traceback, never a silent wrong value.
L2. Per family (mlr, lagbank) run, plain, replay, the C by ``rows`` and fed the raw bytes = the
    contract's to 1e-6 µm (or a documented refusal of the raw bytes, exit 2 in one line naming the
    line); export C + pack 0; ``monitor`` exit 0 with the contract's events (none on the comment
    or the unplugged sensor).
M1. Per family x wrapper of col10133 that runs: ``sim`` = ``replay`` = ``promo`` = ``C`` to 1 %
    (``dmax`` <= 0.01; a difference the monitor's events explain noted), ``cold`` = ``Craw`` to 1 %,
    pack 0, ``st`` 0; ``onnx`` exit 2 in one line, ``auto`` with a wrapper exit 2 in one line; no
    cell exits 1 or with a traceback; where ``ati`` / ``interval`` keep one model, the run says why.
F1. Each fault into the C, the served model and stdin: the same corrections as healthy (to
    1e-9 µm) where the fault carries the same values (columns reordered, an unknown extra column,
    a timestamp format the reader takes), else the fault flagged (C ``--flags`` / an event / a
    warning naming it) or refused (exit 2 / HTTP 4xx) naming the column and the row/line; never a
    traceback, exit 1, 5xx or a signal; never a value read wrongly without a word (``21,53`` read
    as 21 or 2153), never a correction off the reference by > 1 µm at an unflagged row.
F2. The 10x period from row :data:`FAULT_ROW` on (every 10th row kept: the record sampled 10x
    sparser): each route = ``replay``'s batch of the same rows to 1e-6 µm, or the change flagged
    or said naming the row.
H1. col10134 (mlr, healthy): ``monitor`` 0 events; export C + pack 0; the C fed the raw test file
    exit 0 with 0 flagged rows, its mirror 0; the ST block 0 false flags and ST = the C's mirror
    to 1e-6 µm.
Each break: named with command, file, row and numbers; mended where small and clear (a test
failing on BASE, < 3 s of CPU, in the module of the code at fault), else listed for the lead with
the reason it was left.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE), str(REPO / "tests")]
from _cli import run_commands  # noqa: E402

BASE = "570d5a78"
RECORD = "col10133"
HEALTHY = "col10134"
LAB_SEED = 10135
FAULT_ROW = 200
FAULTS = ("reordered", "extra", "comma", "isotime", "dayfirst", "period10")
FL_TABLE = {"mlr": (9.18, 4.06), "pcr": (3.17, 6.48), "arx": (10.96, 4.81), "lagbank": (3.08, 4.78),
            "hammerstein": (2.48, 2.95), "lstm": (9.07, 2.96), "auto": (2.12, 2.48)}


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
