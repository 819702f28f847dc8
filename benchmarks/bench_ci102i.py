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
