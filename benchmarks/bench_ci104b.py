"""CI time (issue 34; stop 104, ci104b): the CPU of the export-monitor slice of the suite and
what its tests compute twice.

The slice (28 modules, wall s in this morning's CI run): tests/shell/test_export_{cmon86, cmon89,
cmon87, mon98b, cmon89b, cmon88, cmon93, cmon85, spike89, bent93, mon85b, st100, st99, mon86,
cmon84, spike54, st98, st97d, cmon91, mon88, st95b, st96b, cmon92b, st94, cmon83, st96, st94b,
st93}.py (``SLICE`` below).

Rule (candidates, in the brief's order): (1) exact: the same tests and assertions, less work (a
record, build, pack or stream made once per module and read by the tests that only read it; an
exact src speed-up, bitwise the same outputs); (2) consolidation: tests paying for the same run
become one run with all their assertions; (3) a ``full`` mark only where a cheaper ``make test``
test fails on the same planted break.  No key, no seeds: nothing is scored.

BAR (the brief's, written and committed here before any after-measurement):

1. every test of the slice passes on both sides (``-n 0 -p no:cacheprovider -m "not full"``), and
   the modules outside the slice that share a changed fixture/helper pass too; no assertion
   deleted unless another test holds it, none loosened (``asserts``: no fewer ``assert``
   statements per changed module, or each missing one named with the test that holds it);
2. the slice's summed CPU (user + sys incl. children, ``/usr/bin/time`` of ``nice python -m
   pytest -q -n 0 -p no:cacheprovider -m "not full" --durations=0 MODULE``, each module alone,
   run from its tree with PYTHONPATH=<tree>/src and OMP/OPENBLAS/MKL_NUM_THREADS=1: ``cpu``) falls
   >= 15 %: base tree = ``git archive c8b21182`` into /tmp/ci104b/base, after = this branch,
   measured paired (base then after, the same command, back to back); a second paired rep when
   the difference is under 15 %: KEPT when met, otherwise the exact cuts are still committed
   for the lead to decide (said so);
3. a changed test still fails on a planted break of what it checks (``plant``); tests moved to
   ``full`` are reported apart (count, CPU, covering test, plant).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci104b.py cpu TREE TAG OUT SPEC...      # bench_ci100b's cpu
    python benchmarks/bench_ci104b.py table OUT [BEFORE AFTER BAR]   # bench_ci100b's table
    python benchmarks/bench_ci104b.py asserts BASE SPEC...           # bench_ci101c's asserts
    python benchmarks/bench_ci104b.py plant TREE FILE OLD NEW SPEC   # bench_ci101c's plant

SPEC for the slice: ``shell/test_export_NAME.py`` for each NAME of ``SLICE``.
"""
from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_ci101c import measured  # noqa: E402

SLICE = ("cmon86", "cmon89", "cmon87", "mon98b", "cmon89b", "cmon88", "cmon93", "cmon85", "spike89",
         "bent93", "mon85b", "st100", "st99", "mon86", "cmon84", "spike54", "st98", "st97d", "cmon91",
         "mon88", "st95b", "st96b", "cmon92b", "st94", "cmon83", "st96", "st94b", "st93")


def main(argv: list[str]) -> int:
    return measured(__doc__, argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
