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

``cpu`` writes OUT/cpu.txt (``TAG SPEC user sys wall result``) and pytest's output to OUT/log/;
paired: a shell starts the base's and the branch's ``cpu`` at once, each on its tree.
"""
from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import run_commands  # noqa: E402
from bench_ci100b import cpu, table  # noqa: E402
from bench_ci101c import asserts, plant  # noqa: E402


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"cpu": cpu, "table": table, "asserts": asserts, "plant": plant},
                        argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
