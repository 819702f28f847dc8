"""CI time (issue 34; stop 104, ci104f): the shell slice of calibrate, opcua67, volumetric_run,
monitor_cli, twin, vendor68, serve, twin_shelf, bits85 and ten smaller modules, and what they
compute beyond what their assertions read.

The slice (19 modules; wall s in the morning's CI run of the stop's head, setup + call +
teardown): shell/test_calibrate 37.8, shell/test_opcua67 31.1, shell/test_volumetric_run 24.7,
shell/test_monitor_cli 17.2, shell/test_twin 16.2, shell/test_vendor68 15.9, shell/test_serve 13.9,
apps/test_twin_shelf 13.6, shell/test_bits85 12.6, shell/test_adaptive_deploy 8.1,
shell/test_monitor_settled94b 5.7, shell/test_monitor 5.2, shell/test_volumetric_lab57 4.9,
shell/test_monitor_healthy53 3.6, apps/test_twin_lockstep 3.3, shell/test_monitor_lab57 3.0,
apps/test_volumetric_cost 2.6, apps/test_monitor_bands86 2.2, core/test_bits83 2.2.

BAR (the brief's, written and committed here before any after-measurement):

1. every test of the slice passes (and the neighbouring modules touched through shared fixtures
   or conftest); no assertion deleted that no other test holds, no tolerance or threshold
   loosened, no skip; ``asserts``: no fewer ``assert`` statements per changed module unless an
   assertion moved into a consolidated test (listed in the report);
2. the slice's summed pytest CPU (``cpu``: user + sys incl. children of ``/usr/bin/time nice
   pytest -q -n 0 -p no:cacheprovider -m "not full"``, each module alone, from its tree with
   PYTHONPATH=<tree>/src and the three *_NUM_THREADS=1; base tree = ``git archive c8b21182``
   into /tmp/ci104f_base) down >= 15 %, base and after paired (one after the other); the pair
   repeated once when the difference is under 15 %.  KEPT at >= 15 %; below it the exact cuts
   stay committed and the report says so (the lead decides);
3. tests moved to ``full`` reported apart (how many, their CPU, for each the covering CI test
   and the plant checked with it); a changed test fails on a planted break of what it checks.

No seeds: nothing is scored.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci104f.py cpu TREE TAG OUT SPEC...      # bench_ci100b's cpu
    python benchmarks/bench_ci104f.py table OUT [BEFORE AFTER BAR]   # bench_ci100b's table
    python benchmarks/bench_ci104f.py asserts BASE SPEC...           # bench_ci101c's asserts
    python benchmarks/bench_ci104f.py plant TREE FILE OLD NEW SPEC   # bench_ci101c's plant
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
