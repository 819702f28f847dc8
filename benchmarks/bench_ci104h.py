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

Rule built (tests only, no src change; commits 8d9196b5, 71458920; the same diff saved as
benchmarks/ci104h_rule.patch): one run read by every test that only reads it (module fixtures):
catman70's Easy folder init + run (easy_run), issue34_rest's monitor of B from the file
(from_file), stable67's tracked ``run model=mlr`` (tracked_mlr: the message test reads it, the
promote test promotes it), deployed_as_scored's run per model (run_rmse: the lag bank's read by
its replay case and the monitor test), leftovers67's lag bank on the plain export (plain_run:
the comment test compares with it, lab_stream exports it); test_results' literal scan walks
each tree once (the same literal sets of all 303 src modules).

Measured (2026-12-07 03:49-04:31 UTC, load 12-21 on 2 cores; CPU s user + sys incl. children,
``cpu``, nice): the slice's base (git archive c8b21182), every module once (``slice``; two
twice, where a second runner took the tail: their mean): 297.9 s over 33 modules.
The 6 changed modules paired (base then after, one after the other; 2 reps, deployed_as_scored
too)::

  catman70            9.03 / 8.86 -> 8.84 / 8.69     8.95 -> 8.77   -2.0 %
  issue34_rest       11.49 / 11.14 -> 11.01 / 10.80 11.32 -> 10.91  -3.6 %
  stable67           12.20 / 12.51 -> 11.54 / 11.80 12.36 -> 11.67  -5.5 %
  deployed_as_scored 10.46 / 9.89 -> 10.02 / 9.41   10.18 -> 9.71  -4.5 %
  leftovers67         8.92 / 8.50 -> 8.67 / 8.88     8.71 -> 8.78   +0.7 % (noise: ~0.3 s cut)
  results             4.93 / 4.81 -> 4.68 / 4.39     4.87 -> 4.54   -6.9 %

The slice (unchanged modules at their base CPU: their files are c8b21182's): the 6 modules'
paired means save 2.01 s, 297.9 -> 295.9 s, -0.7 %.
Against the bar: (1) met: every test passes (the 6 modules 11 + 14 + 7 + 8 + 8 + 7; the
modules importing the changed ones collect); tests per module unchanged, asserts unchanged but
catman70 28 -> 26 and leftovers67 35 -> 34 (a command's exit-0 assert each test made is the
fixture's, once); no tolerance or threshold touched.  (2) NOT met: far under 15 %.  (3) no test
moved to ``full``.  Verdict REFUSED; as the brief asks, the exact cuts stay committed on the
branch for the lead to decide.

Why so little: measured module by module, a module's fixed cost (pytest, conftest, thermocomp's
and scikit-learn's imports, the session datasets) is most of a small module's CPU, and the 33
modules were cut at stops 98-102 already (one_step, replay, sim_cli, promote_adapt63,
evaluate_report): the duplicated runs left are small in-process commands (~0.3-0.7 s each).
The profile of the suite (/tmp/prof1.raw, py-spy, this morning) puts the slice's big costs in
work each test exists for (py-spy's sampled s): test_replay's 28 covering cases (fits 12.9,
Hydra compositions 7.0: 28 distinct group overrides, each a miss of tests/hydra_cache.py),
evaluate_report's figures and its dvc/MLflow test, denoise_stages' EMD (four denoiser fits,
each a stage's own).

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
