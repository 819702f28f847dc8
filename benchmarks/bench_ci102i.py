"""CI time (issue 34; stop 102, ci102i): the long tail's tests (306 modules under 3.5 s of CPU
each, 311 s together in the fresh-clone profile of stop 101's head) compute less than before
where a test computes more than its assertions read.

ci100b and ci101c (bench_ci100b.py, bench_ci101c.py) took the cuts of "the same computation
twice"; this bench takes, in the tail's heaviest modules, the computations no assertion reads or
that a smaller subject shows as well: a full-length simulated scenario where a shorter one holds
the planted effect, the default report extras (figures, mutual prediction, validation folds,
ATI baselines, the ISO test) on a run whose assertions read none of them (conftest's FAST).

Rule (tests only, no src change, no key): per changed test, the smaller data or the FAST keys,
its docstring saying what the smaller data holds.

BAR (the brief's, written and committed here before any after-measurement; the base run of the
candidate modules, with --durations=0, is the trace):

1. every test id stays and passes (``-n 0 -p no:cacheprovider -m "not full"``, the same counts
   as on BASE 506ffb01); every assertion stays (``asserts``: no fewer ``assert`` statements or
   ``refused(`` calls per changed module, none weakened in the diff); each shrunk subject still
   holds its subject (the planted effect, the rule's trigger) and its docstring says so; no
   ``full`` mark added;
2. the changed modules' summed pytest CPU (user + sys incl. children of ``/usr/bin/time nice
   pytest -q -n 0 -p no:cacheprovider -m "not full"`` per module; base tree = ``git archive
   506ffb01``) down >= 30 %, base and after started together (paired); 1 rep for the set, a 2nd
   rep for the modules changed most if time allows;
3. every plant caught: one planted break per changed test or fixture (``plant``: a copy of the
   tree with one line changed in src) fails a changed test.

No seeds: nothing is scored (the same assertions on the same kind of computation).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci102i.py cpu TREE TAG OUT SPEC...      # bench_ci100b's cpu
    python benchmarks/bench_ci102i.py table OUT [BEFORE AFTER BAR]   # bench_ci100b's table
    python benchmarks/bench_ci102i.py asserts BASE SPEC...           # bench_ci101c's asserts
    python benchmarks/bench_ci102i.py plant TREE FILE OLD NEW SPEC   # bench_ci101c's plant

Rule built (tests only; REFUSED, saved as benchmarks/ci102i_rule.patch, which applies to
506ffb01; the four modules are back to 506ffb01 on the branch):

- test_sim_cli: the three scenarios' ``run`` with FAST (was track=false plots=none: mutual
  prediction, ATI baselines, the ISO test and the validation folds, none read);
- test_bits83: the export test's ``run`` with FAST (its assertions read the export's header and
  message);
- test_volumetric_auto96: LargeMillVolumetric 8 h train + 4 h test (was 24 + 12): every
  candidate is still fitted and one chosen per parameter, what the volumetric section read;
- test_promote_adapt63: the lathe 20 h calibration + 8 h production (was 80 + 24): the bias
  adaptation still moves the replayed figure (0.922 against 0.723 frozen; 1.568 / 1.461 on the
  whole record) and promote tags the adapted one.

Trace (506ffb01 = BASE, each module alone, ``cpu``, load 7-13, CPU s user + sys): deploy88 9.14,
promote_adapt63 9.12, fleet57 9.10, lstm 8.90, machine_routes 8.70, restart69 6.82, alarms 6.17,
sim_cli 5.91, volfleet63 5.89, volumetric_auto96 5.88, monitor_healthy53 5.72, bits83 5.15,
diagnose_choices74 4.86, sensor_faults 4.71, monitor_blind84b 4.43, monitor_hides84c 4.10.  A
module's floor alone: ``--co`` of test_sim_cli 1.36 s, with one small in-process command (the
cli's imports) 2.11 s; in-process CPU of promote_adapt63's four commands 4.04 s (80 + 24 h) ->
3.37 (20 + 8 h); sim_cli's runs, default then FAST on the same data in one process:
lathe 0.28 -> 0.16, column 0.48 -> 0.22 (large_mill 1.66 -> 0.38, the first also paying the
first fit's imports).  The others were read and left: their costly part is
their subject (seed-specific records whose statistics are asserted: alarms, monitor_*; served
processes and mlflow's pyfunc: machine_routes, restart69; sklearn's estimator checks: lstm).

Measured (2026-12-06 22:34-22:38, base = git archive of 506ffb01 in /tmp, after = 4ed307d4;
paired: base and after started together, each with ``cpu``; load 9-13; one rep)::

  module                      base -> after   (CPU s)   same tests pass
  test_promote_adapt63         9.1 ->  8.5    -6.2 %    1 / 1
  test_volumetric_auto96       6.5 ->  6.1    -6.8 %    2 / 2
  test_bits83                  5.5 ->  5.5    -0.2 %    11 / 11
  test_sim_cli                 5.7 ->  5.1   -11.4 %    4 / 4
  sum                         26.8 -> 25.1    -6.2 %

A 2nd paired rep of the two modules changed most (22:39-22:41, after = git archive of 4ed307d4,
load ~13): test_sim_cli 6.24 -> 5.77 (-7.5 %), test_promote_adapt63 9.45 -> 9.41 (-0.4 %); the
two reps' means: sim_cli 5.98 -> 5.42 (-9.4 %), promote_adapt63 9.27 -> 8.97 (-3.2 %).

Against the bar: (1) met: ``asserts`` 7/23/3/2 asserts, 0/1/0/0 refused(, as on 506ffb01, no
assert edited, the same ids pass, no ``full`` mark. (2) NOT met: -6.2 % against >= 30 %. (3)
met: each plant on a copy failed a changed test -- promotion.py's test figures streamed with
``adapt=None`` -> promote_adapt63; section.py's ``_chosen`` taking any ``chosen_`` ->
volumetric_auto96[[mlr]]; export.py's "(bit b of 'Status')" said as "in" -> bits83's export
test; effects.py's axis_position kind "signal" and results.py's metrics.json written without
its targets -> sim_cli[large_mill_week].

Why so little: a tail module's CPU alone is ~1.4-2.1 s of pytest start and imports that no test
edit cuts, and what is left is mostly its subject; the computations no assertion reads were
0.0-0.7 s of CPU a module here (paired).  The xdist profile (modules_cpu.txt) counts the imports
once per worker, so a tail module's measured CPU alone is its profile CPU plus that floor: -30 %
of it asks for more than half of a module's own computation.

``cpu`` writes OUT/cpu.txt (``TAG SPEC user sys wall result``) and pytest's output to OUT/log/;
paired: a shell starts the base's and the branch's ``cpu`` at once, each on its tree.
"""
from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_ci101c import measured  # noqa: E402


def main(argv: list[str]) -> int:
    return measured(__doc__, argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
