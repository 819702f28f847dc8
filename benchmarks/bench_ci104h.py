"""CI time (issue 34; stop 104, ci104h): one slice of the test suite (33 modules, the tail of
the fresh-clone run's per-module wall times from test_replay's 24.5 s down to test_names97's
2.1 s) made cheaper in CPU.

Cuts, in the brief's order of preference: exact (the same tests and assertions, less work: a
run shared by the tests that only read it, a process replaced where the boundary is not the
subject), consolidation (one run, all its assertions), and last a move to ``full`` of a test
whose every assertion a cheaper test holds (checked by a plant).

BAR (the brief's, written and committed here before any after-measurement):

1. every test of the slice passes on the branch (``-n 0 -p no:cacheprovider -m "not full"``),
   and the modules outside the slice that share a changed fixture or helper too; no assertion
   is deleted that no other test holds, no tolerance loosened, no ``skip`` (``asserts`` counts
   the assert statements and tests per changed module against c8b21182);
2. KEPT when the slice's summed CPU (user + sys incl. children, ``/usr/bin/time``; each module
   alone, ``python -m pytest -q -n 0 -p no:cacheprovider -m "not full" MODULE`` run from the
   tree with PYTHONPATH=<tree>/src and the three *_NUM_THREADS=1; base tree = ``git archive
   c8b21182`` in /tmp/ci104h/base) falls >= 15 %; base and after measured one after the other
   (paired), and the pair repeated once when the difference is under 15 %.  Below 15 %: the
   exact cuts stay committed for the lead to decide, and the report says so;
3. tests moved to ``full`` reported apart (count, their CPU, the covering test, the plant).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci104h.py slice TREE TAG OUT       # every module of SLICE, as cpu
    python benchmarks/bench_ci104h.py cpu TREE TAG OUT SPEC...  # each spec alone, /usr/bin/time
    python benchmarks/bench_ci104h.py table OUT [BEFORE AFTER BAR]
    python benchmarks/bench_ci104h.py asserts BASE SPEC...
    python benchmarks/bench_ci104h.py plant TREE FILE OLD NEW SPEC
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_ci100b  # noqa: E402
import bench_ci101c  # noqa: E402
from _cli import run_commands  # noqa: E402

# the slice, as the brief lists it (largest wall time first; paths under tests/)
SLICE = """
shell/test_replay.py shell/test_evaluate_report.py shell/test_denoise_stages.py shell/test_catman70.py
shell/test_stable67.py shell/test_workbook48.py shell/test_streamraw65.py shell/test_deploy89.py
shell/test_leftovers67.py shell/test_keysight70.py core/test_dataset_source.py shell/test_deploy88.py
shell/test_one_step.py shell/test_issue34_rest.py shell/test_deployed_as_scored.py shell/test_data86b.py
shell/test_promote_adapt63.py core/test_lstm_lazy_torch52.py shell/test_results.py
shell/test_guard_follows_inputs56.py shell/test_choose_by_simulation.py shell/test_stream_units60.py
shell/test_promote_adapt_59.py shell/test_dates85.py shell/test_promote_example59.py
shell/test_lab_promote57.py shell/test_mixed_units_rank.py shell/test_data87.py shell/test_sim_cli.py
core/test_plots.py shell/test_data86.py shell/test_leftovers66.py shell/test_names97.py
""".split()


def whole_slice(tree: str, tag: str, out: str) -> None:
    """bench_ci100b's ``cpu`` of every module of SLICE, in order."""
    bench_ci100b.cpu(tree, tag, out, *SLICE)


COMMANDS = {"slice": whole_slice, "cpu": bench_ci100b.cpu, "table": bench_ci100b.table,
            "asserts": bench_ci101c.asserts, "plant": bench_ci101c.plant}


def main(argv: list[str]) -> int:
    return run_commands(__doc__, COMMANDS, argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
