"""CI time (issue 34; stop 104, ci104g): the CPU of one slice of the test suite (33 modules:
apps/test_deployed_as_scored44, shell/test_cli, shell/test_validation, shell/test_promote,
test_hydra_cache and 28 smaller ones, listed in SLICE), cut where a module computes the same
thing twice or more than its assertions read.

BAR (the brief's, written and committed here before any after-measurement):

1. every test id of the slice stays and passes (``-n 0 -p no:cacheprovider -m "not full"``), and
   the neighbouring modules reached through a changed shared fixture or conftest pass; every
   assertion kept (``asserts``: no fewer ``assert`` statements and ``refused(`` calls, the diff
   shows none removed or weakened); no tolerance loosened, no skip;
2. the slice's summed pytest CPU (user + sys incl. children, ``/usr/bin/time``, each module
   alone, ``-n 0``, ``nice``, the three ``*_NUM_THREADS=1``; base tree = ``git archive`` of
   c8b21182 in /tmp/ci104g/base) down >= 15 %, base and after paired (one after the other under
   the same load); the pair repeated once when the cut is under 15 %;
3. one planted break per changed module (``plant``: a one-line change of src the shared
   computation feeds) still fails a changed test of that module.

KEPT when (1)-(3) hold; below 15 % the exact cuts stay committed and the lead decides.  Tests
moved to ``full`` are reported apart (their CPU, the covering test, the plant that shows it).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``), bench_ci100b's CPU runs::

    python benchmarks/bench_ci104g.py cpu TREE TAG OUT SPEC...      # each spec alone, /usr/bin/time
    python benchmarks/bench_ci104g.py table OUT [BEFORE AFTER BAR]   # means, sum, the bar

and bench_ci101c's assertion counts and planted breaks (a copy of TREE, OLD -> NEW in FILE)::

    python benchmarks/bench_ci104g.py asserts BASE SPEC...
    python benchmarks/bench_ci104g.py plant TREE FILE OLD NEW SPEC

SLICE (the specs, for ``cpu``): ``python -c "import bench_ci104g; print(*bench_ci104g.SLICE)"``.
"""
from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_ci101c import measured  # noqa: E402

SLICE = (
    "apps/test_deployed_as_scored44.py", "shell/test_cli.py", "shell/test_validation.py",
    "shell/test_promote.py", "test_hydra_cache.py", "shell/test_frames62.py", "shell/test_repeat99.py",
    "shell/test_restart69.py", "shell/test_restart66.py", "shell/test_joinfit62.py",
    "shell/test_alarms.py", "shell/test_machine_routes.py", "test_benchmarks_cli.py",
    "shell/test_lab_file.py", "shell/test_iso67.py", "core/test_denoise.py", "shell/test_design.py",
    "shell/test_volfleet63.py", "shell/test_config_schema.py", "shell/test_config_compose.py",
    "shell/test_promote_dropout59.py", "shell/test_sepline96.py", "shell/test_guarded_everywhere70.py",
    "shell/test_deploy88b.py", "shell/test_initone65.py", "test_imports.py", "shell/test_pair70.py",
    "shell/test_pipeline_commands.py", "apps/test_protocol.py", "shell/test_messy_lab58.py",
    "shell/test_derive71.py", "shell/test_download66.py", "shell/test_lstm.py",
)


def main(argv: list[str]) -> int:
    return measured(__doc__, argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
