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

Rule built (tests only, no src change; exact: the same tests, assertions and computed values):

- test_export_st94.resumed (st94's ``_both``, st96's ``_stepped``): a pass of the ST block and the
  C mirror over rows an earlier pass of the module (same system, block and per-row read) already
  stepped resumes from that pass's state (deep copies every 50 rows); st94's blind loop, st97d's
  healthy/drifted pair, st98's healthy part + 2 freezes, st99's bump + 2 freezes.  Bitwise
  check: st99's three passes resumed = stepped whole (np.array_equal, lists equal).
- cmon85's ``_mirror(rows=, each=)``: the "export before" tests of cmon85/86/88/89/89b/92b and
  mon98b step the old mirror only to the row their assertions read (a row reads no later row);
  cmon86's ``_outs`` and cmon93's ``_readmitted`` read the pass ``_mirror`` / ``held_as_served``
  already makes.  mon85b's pass without the mark stops at the served return it reads.
- cmon84: the model fitted once per ``monitor.fallbacks`` value (5 fits of 2 models before).

Measured (2026-12-07, load 8-21 from other helpers; ``cpu``; base = /tmp/ci104b/base (git archive
c8b21182), after = git archive of 7b9a6242; paired per module, base then after; CPU s)::

  rep 1  st98 6.9 -> 4.7 (-30.9 %)  st99 7.0 -> 5.8 (-17.7)  st97d 5.7 -> 4.7 (-16.7)
         st94 5.0 -> 4.4 (-12.4)   cmon92b 6.0 -> 5.2 (-14.2)  cmon89 10.8 -> 10.0 (-7.4)
         cmon93 9.5 -> 8.8 (-7.1)  cmon84 6.6 -> 6.3 (-5.7)  mon98b 12.3 -> 11.8 (-3.5)
         mon85b 6.4 -> 6.2 (-2.8)  cmon89b 12.2 -> 12.1  cmon85 10.2 -> 10.2  cmon86 11.7 -> 11.9
         cmon88 9.6 -> 9.7  st96 5.3 -> 5.4  st100 6.9 -> 7.0  st96b 5.1 -> 5.1  st95b 5.6 -> 5.7
         18 changed/reading modules: 142.8 -> 135.1 (-5.4 %)
  trace  the whole slice on base, each module once: 206.2 s (cmon86 11.6 ... st94 4.8)
  rep 2  (load 3-8; 16 of them, st100/st96b not repeated) 107.6 -> 100.2 (-6.9 %): st98 -31.1 %,
         st99 -26.5, st97d -15.8, st94 -11.4, cmon84 -7.0, cmon86 -6.3, cmon92b -6.2, cmon93 -4.7,
         cmon88 -4.6, cmon89b -4.5, mon85b -4.1, cmon89 -0.9, mon98b -0.7, st95b -0.8, cmon85 +0.3,
         st96 +4.1

Against the bar: (1) met: the slice's 28 modules pass (changed ones and st98b/quiet94c beside
them); ``asserts`` no fewer per changed module.  (2) NOT met: the 18 modules' -7.7 s (rep 1) is -3.7 %
of the slice's 206.2 s (the 10 unchanged modules taken as equal), rep 2's -7.4 s about -4 %,
against >= 15 %.  (3) plants
(``plant``): watch.py ``by_field[j] = False`` -> cmon86's held test fails (its ``each`` read);
``without`` keeping the feature -> cmon89b's before test fails (its ``rows`` cut); the C mirror's
freeze excluded as ``JUMP`` -> st98 and st99 fail (their resumed passes).  REFUSED: the cuts stay
committed (tests only) for the lead; benchmarks/ci104b_rule.patch is their diff.

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
