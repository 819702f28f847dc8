"""CI time (issue 34; stop 104, ci104d): the diagnose / stranger slice of the suite (27 modules).

The slice (wall s per module in the lead's CI run of the stop): test_diagnose_pde66 24.1,
apps/test_diagnose_scenarios 19.7, test_model_auto 13.3, test_stranger66 13.2,
test_diagnose_sparse61 11.4, test_diagnose_cli 7.7, test_sparse_targets61 7.3,
apps/test_diagnose_few 6.6, test_volstranger66 5.3, test_diagnose_deployed60 5.0, test_diagnose
4.4, test_audit87 4.1, test_stranger80 4.0, test_deploy_diagnosed 3.7, test_volumetric_auto96 3.5,
test_stranger84 3.4, test_stranger76 3.4, test_stranger63 3.0, apps/test_diagnose_record 3.0,
test_stranger65 3.0, test_clamp_diagnosed60 2.9, test_stranger83 2.8, test_stranger82 2.8,
test_diagnose57 2.6, apps/test_diagnose_choices74 2.6, test_stranger50 2.2, test_audit86 2.0
(tests/shell/ unless apps/).

BAR (the brief's, written and committed here before any after-measurement):

1. the slice's summed pytest CPU (user + sys incl. children of ``/usr/bin/time nice pytest -q -n 0
   -p no:cacheprovider -m "not full"``, each module alone, run from its tree with
   ``PYTHONPATH=<tree>/src`` and the three ``*_NUM_THREADS=1``: ``cpu`` below) down >= 15 %,
   base (``git archive c8b21182`` into /tmp/ci104d/base) and after measured paired, one after
   the other; the pair repeated once when the difference is under 15 %;
2. every test of the slice passes on both sides (and the neighbouring modules reached through a
   changed shared fixture); no assertion deleted that no other test holds, no tolerance or
   threshold loosened, no skip; a test moved to ``full`` only where a named cheaper test in
   ``make test`` fails on the same planted break (reported apart, with its CPU);
3. a cut is exact (the same assertions on the same figures: a changed command's figures shown
   equal to the base's) or a consolidation (the assertions and their messages kept).

KEPT when (1) and (2) hold; below 15 % the exact cuts are still committed and the lead decides.

Cuts built (tests only, exact; 6506e60c, 45ffccb3; saved as benchmarks/ci104d_rule.patch):
the 8 ``diagnose`` calls of test_diagnose_cli (door fixture, the one_step pair, the lab rerun),
test_diagnose_sparse61, test_deploy_diagnosed and test_diagnose57's ATI header stream the plain
deployed stream (conftest.PLAIN_DIAGNOSE): each run both ways on its record, every figure of
diagnosis_<target>.json equal (970-2038 keys a call; only paths, seconds and the absent
test_rows_guarded differ); test_stranger66's plain-CSV run made once for its two readers;
test_sparse_targets61's sparse FAST run per family made once (the lagbank one read twice).

Measured (2026-12-07, load 6-17; ``cpu``'s command line; CPU s user + sys incl. children):
rep 0, the whole slice, base (03:45-04:02) then after (04:02-04:17): 209.5 -> 205.6 s (-1.8 %;
unchanged modules -9 % .. +10 %: the load's noise).  Reps 1-2, the 6 changed modules, base and
after interleaved module by module: 52.7 -> 50.1 (-4.9 %), 52.1 -> 49.7 (-4.6 %); mean of reps
0-2: diagnose_sparse61 8.21 -> 6.96 (-15.2 %), diagnose57 5.15 -> 4.80, deploy_diagnosed 5.66
-> 5.34, diagnose_cli 12.01 -> 11.42, sparse_targets61 9.56 -> 9.19, stranger66 11.94 -> 11.67;
sum 52.5 -> 49.4 s: 3.1 s saved, 1.5 % of the slice.  Bar (1) NOT met: REFUSED.

Trace: pytest's start and collection is 1.2-2.3 s CPU of each module run alone (``--co``), ~40 s
of the 209.5 (paid per module in this bench, once per xdist worker in CI); a diagnosis of
test_diagnose_few (cProfile) spreads over the search's fits with no hot spot (2.3 s, 0.7 of it
scipy.signal's import).  The acceptance modules (diagnose_scenarios, diagnose_few, pde66) compute
what their premises state; no ``full`` move was made (none planted and checked in the time).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci104d.py cpu TREE TAG OUT SPEC...      # bench_ci100b's cpu
    python benchmarks/bench_ci104d.py table OUT [BEFORE AFTER BAR]   # bench_ci100b's table
    python benchmarks/bench_ci104d.py asserts BASE SPEC...           # bench_ci101c's asserts
    python benchmarks/bench_ci104d.py plant TREE FILE OLD NEW SPEC   # bench_ci101c's plant
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
