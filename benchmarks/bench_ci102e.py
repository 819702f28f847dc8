"""CI time (issue 34; stop 102, ci102e): the heaviest in-process test modules compute less than
before where their tests computed more than their assertions read.

ci100b and ci101c (bench_ci100b.py, bench_ci101c.py) took the cuts of "the same computation
twice"; this bench takes the computations no assertion reads, in three of the thirteen heaviest
in-process modules (the brief's group; the other ten were read and left: see the numbers below).

Rule (tests only, no src change, no key):

- test_replay: the 28 all-pairs cases' configs from 7 Hydra compositions instead of 28.  Each
  case names other config groups (model, ati, denoise, select), so each was a miss of the
  suite's composition cache (tests/hydra_cache.py; ~0.17 s of CPU a miss).  Each model is
  composed once, with one of the 5 non-default wrapper options; a case's config is its model's
  with the case's wrapper nodes (and SMALL_ATI's value).  Seen: the 28 assembled configs equal
  Hydra's to the last key (``OmegaConf.to_container`` and ``to_yaml``, 28 of 28, base d85f1799);
  test_the_cases_cover_every_pair_of_values composes one case (lstm, cmeans, emd, cluster_grey)
  and asserts the equality, so a group that came to depend on another fails there.
- test_volumetric_run: the session run of every parameter without the validation folds (no test
  reads them; seen: model.pkl and ingest_report.json the same bytes, the volumetric section and
  every target's test scores equal, metrics.json differs only in ``validation`` and
  ``fit_time_s``; ~1 s of CPU); the mis-probed-distance test models two parameters (as the
  ``two_parameters`` run it is compared with): the calibration that flags the distance is the
  whole dataset's whatever is modelled, and the 1 mm shows in the distance errors either way.
- test_calibrate: the ``run`` helper models one parameter (E_ZZ1): what its two tests assert is
  the calibration's (a unit warning; an interpolated cell) and that the run fits.

BAR (the brief's, written and committed here before any after-measurement):

1. every test id stays and passes (``-n 0 -p no:cacheprovider -m "not full"``: replay 33,
   volumetric_run 11, calibrate 70); every assertion stays (``asserts``: no fewer ``assert``
   statements or ``refused(`` calls per module, none weakened in the diff; replay gains two);
   each shrunk subject still holds its subject (the 1 mm distance, the unit warning, the
   interpolated cell), its docstring says what the smaller data holds;
2. the changed modules' summed pytest CPU (user + sys incl. children of ``/usr/bin/time nice
   pytest -q -n 0 -p no:cacheprovider -m "not full"`` per module; base tree = ``git archive
   d85f1799``) down >= 30 %, base and after started together (paired); 1 rep for the set, a 2nd
   rep for the modules changed most if time allows;
3. every plant caught: one planted break per changed test or fixture (``plant``: a copy of the
   tree with one line changed in src or in the changed helper) fails a changed test.

No seeds: nothing is scored (the computations asserted are the same).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci102e.py cpu TREE TAG OUT SPEC...      # bench_ci100b's cpu
    python benchmarks/bench_ci102e.py table OUT [BEFORE AFTER BAR]   # bench_ci100b's table
    python benchmarks/bench_ci102e.py asserts BASE SPEC...           # bench_ci101c's asserts
    python benchmarks/bench_ci102e.py plant TREE FILE OLD NEW SPEC   # bench_ci101c's plant

Rule built (tests only; REFUSED, saved as benchmarks/ci102e_rule.patch, which applies to d85f1799;
the three modules are back to d85f1799 on the branch).

Trace (d85f1799, cProfile and --durations under load 5-20, wall shares): test_replay's cases
spend about as long composing as fitting (41 of 106 profiled s; 28 compositions 4.8-6.0 s of
CPU, the 7 that replace them 1.7); test_calibrate is ~92 in-process commands, the run that the
helper makes ~0.6 s of CPU with every parameter, ~0.23 with one (the calibration of a folder
is cached by its digest in the process); the volumetric session run's validation folds ~1.0 s
of CPU (1.88 -> 0.82 s with the calibration cached). Of the other ten modules: test_monitor_cli
and test_hostile spend their time in per-command Hydra work (OmegaConf deep copies 13 % of
monitor_cli's profile: ci102f's concern), test_hostile_numeric's [defaults] case in 27 compositions and
~600 config checks, test_diagnose_pde66 cannot diagnose E_Y alone (its CV design follows the
slowest target: 196 blocks, not the 15 asserted, and another winner), test_diagnose_scenarios,
test_adaptive_deploy, test_evaluate_report and test_hostile_units were read (their costly
parts tuned before: short data, FAST, one target) and left; test_model_auto and test_monitor
were not looked at again (ci101c's cuts are in d85f1799).

Measured (2026-12-06 22:01-22:23, base = git archive of d85f1799 in /tmp, after = 3b3f730a;
paired: base and after started together, each with ``cpu``; load 9-20; CPU s user + sys incl.
children)::

  module                 rep 1             rep 2             mean                  same tests pass
  test_replay            38.99 -> 35.90    32.94 -> 28.84    36.0 -> 32.4  -10.0 %   33 / 33
  test_volumetric_run    27.10 -> 25.10    26.78 -> 24.64    26.9 -> 24.9   -7.7 %   11 / 11
  test_calibrate         43.60 -> 41.96    (one rep)         43.6 -> 42.0   -3.8 %   70 / 70
  sum (the means, ``table``)                                 106.5 -> 99.2  -6.9 %

Against the bar: (1) kept: ``asserts`` on 3b3f730a: asserts 26 -> 28 / 57 / 113, refused( 0 /
4 / 14, tests 6 / 10 / 33 as on d85f1799; no assert edited; the same ids pass. (2) NOT met:
-6.9 % of the three modules' CPU against >= 30 %. (3) met after a change: each plant on a copy
failed a changed test -- ati.py's stream pinned to interval 0 -> the matrix's
[mlr-cmeans-emd-cluster_grey]; section.py's flagged distances scored -> the mis-probe test;
validation.py's d_after = d_before -> the twin-halves test (reads the session run); source.py's
cached warnings not said again -> the residual-scatter test (its run's part); but the replay
guard as measured, on (lstm, cmeans, emd, cluster_grey), passed a plant that drops the select
node (lstm's own composition picks cluster_grey).  After rep 1 the guard was moved to
(hammerstein, cmeans, emd, pearson), whose wrapper nodes and SMALL_ATI value are all other
compositions' (49eef37c; the same one composition): the select, ati and SMALL_ATI plants each
fail it.  A change after the measurement: reported, not kept.

Why so little: the cuts are whole computations no assertion reads (21 compositions, 25
targets' fits, validation folds) but each is a small share of its module; what these modules
spend is in-process commands on edited inputs (each a calibration or a fit that differs) and
Hydra's per-command work, which is another helper's (ci102f) this stop.

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
