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

Verdict: REFUSED against the bar (-0.4 % of the slice, bar -15 %); the two exact cuts stay
committed on the branch (the brief: below 15 % they stay, the lead decides), and are also saved
as benchmarks/ci104g_rule.patch (applies to c8b21182).  No src change, nothing moved to full.

Rule built (tests only):

- test_frames62: the lag bank's run on the late-probe record made once (module fixture
  ``lagbank_run``, the replay test's overrides); ``test_run_scores_what_replay_streams[lagbank]``
  and the export-pack test read its model.pkl and metrics (the export test made its own FAST run
  of the same family on the same data); the record without S_ columns written once (``plain``).
- test_cli: the foreign-mapping test's run with ``plots=none`` (no assertion of it reads a
  figure; test_simulate_then_run_writes_valid_metrics keeps the default figures).
- tried and withdrawn: test_repeat99's adaptive lag bank deployed once for the burst's forms and
  the no-time case (passed in either order, its plant caught) -- paired 8.92 -> 8.99 and 9.04 ->
  9.11 s CPU, no gain, so not kept.

Measured (2026-12-07 03:49-04:29, base = git archive of c8b21182 in /tmp/ci104g/base, after =
87ce2dff; 2 cores shared with the lead and 7 helpers, load 2-21; CPU s user + sys incl.
children, each module alone, ``cpu``'s command line; all 33 modules passed on base)::

  base slice, one run (the trace)                       282.4 s over 33 modules
  deployed_as_scored44 30.5, cli 15.8, validation 12.4, promote 11.2, protocol 11.0, frames62
  9.8, joinfit62 9.4, design 9.5, restart66 9.3, deploy88b 9.3, lstm 9.2, repeat99 9.1, the
  other 21: 3.1-8.9 each
  changed modules, paired (base then after, back to back), 2 reps:
  shell/test_frames62     10.42 -> 10.30,  9.49 -> 9.26    mean 10.0 -> 9.8   -1.8 %
  shell/test_cli          16.48 -> 14.95, 15.64 -> 15.35   mean 16.1 -> 15.1  -5.7 %
  test_benchmarks_cli      6.19 ->  5.90 (1 rep; +2 tests: bench_ci104g's probe)
  slice: 282.4 -> ~281.3 (the unchanged modules' base figures on both sides): -0.4 %

Against the bar: (1) kept: ``asserts`` frames62 18 -> 18 (tests 7 -> 7), cli 42 -> 42 (refused
1 -> 1, tests 9 -> 9); frames62 8 passed, cli 27 passed, benchmarks_cli 838 passed; no shared
fixture or conftest changed (no module imports from the two).  (2) NOT met: -0.4 %.  (3) met:
plants on a copy, each failed its changed test: pack.py ``lead`` + 1 ->
test_the_export_packs_corrections_are_what_run_scored; metrics.py ``window_s`` n (not n - 1)
periods -> test_foreign_headerless_time_csv_through_mapping_config; (withdrawn repeat99)
adaptive.py's repeat not skipped -> [served].

Trace, why so little (cProfile of deployed_as_scored44's 24 replay cells on this tree before
any cut, shares of its 205 s): the run stage 31 %, replay 25 % (of it the adaptive wrapper's
build, 7 %: sensor fallbacks refit without each sensor), Hydra's composition 20 % (misses: each
command's group overrides differ), deep copies 14 %, imports 14 %: each cell's run and replay is
of another model, nothing computed twice.  The other modules' commands are each their own
subject (a refusal, a restart, a promotion order, a process boundary).  Each module alone pays
pytest's collection (``--co`` of pair70 / messy_lab58: 1.21 / 1.22 s CPU), ~40 s of the 282 s
over 33 modules, and its first command's imports (the smallest module, test_imports, is 3.1 s).
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
