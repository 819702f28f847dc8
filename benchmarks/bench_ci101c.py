"""CI time (issue 34; stop 101, ci101c): the same computation made once per module in the
heaviest non-export test modules.

ci100b (bench_ci100b.py) found no command repeated across the docs pages; this bench looks
WITHIN a module: a test that repeats a run, fit or stream another test of the module (or its
fixture) already makes with the same overrides, or runs more than its assertions need.

Rule (tests only, no src change): where two tests of one module make the same computation, a
module- or session-scoped fixture makes it once and both read it (read-only: a test that edits
data copies it first).  No key.

BAR (the brief's, written and committed here before any after-measurement; the base run of the
candidate modules, with --durations=0, is the trace):

1. every assertion kept: ``asserts`` shows, per changed module, no fewer ``assert`` statements
   and ``refused(...)`` calls than BASE, the diff shows none removed or weakened, and the same
   test ids pass (``-n 0 -p no:cacheprovider -m "not full"``);
2. the changed modules' summed pytest CPU (user + sys incl. children, ``/usr/bin/time``, each
   module alone, ``-n 0``, ``nice``; base tree = ``git archive`` of BASE) down >= 20 %, base and
   after paired (run side by side under the same load);
3. one planted break per changed module (``plant``: a one-line change of src the shared
   computation feeds) still fails a test of that module.

No seeds: the computation is exact (the same commands, the same numbers).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci101c.py cpu TREE TAG OUT SPEC...      # bench_ci100b's cpu
    python benchmarks/bench_ci101c.py table OUT [BEFORE AFTER BAR]   # bench_ci100b's table
    python benchmarks/bench_ci101c.py asserts BASE SPEC...           # asserts per module
    python benchmarks/bench_ci101c.py plant TREE FILE OLD NEW SPEC   # a break, the tests on it

Rule built (tests only; REFUSED, saved as benchmarks/ci101c_rule.patch, which applies to f93f592e;
the three modules are back to f93f592e on the branch):

- test_monitor: a module fixture ``healthy_streams`` streams each test campaign through the
  deployed compensator once (``_stream`` resets it first; arrays read-only); the 29 tests that
  streamed it again (the healthy test, 6 + 12 fault cases, 6 out-of-range, the offset, 3
  missing/noisy) read it; ``second_sensor`` ranks the influence once, not in each of the 12
  other-shape cases.
- test_model_auto: the ``two_targets`` run validated (``eval.validation=true``: the model and
  the test scores are the same, the validation reuses the choice's folds), so the validation
  test reads it instead of running it again; ``pair_fitted`` fits the PAIR auto compensator in
  this process once for the refit test and the mutual-prediction test (each clones the template).
- test_volumetric_run: the two-parameter run with figures (``two_parameters``) read by the
  figures test and by the stages test's ``prior=null`` case (its numbers are plots=none's).

Trace (f93f592e, each module alone, ``-n 0``, ``nice``, load 14-22, one run, CPU s): calibrate
45.0, hostile_procs 36.7, replay 34.3, volumetric_run 28.2, tracking 26.0, evaluate_report 23.2,
monitor 20.0, model_auto 14.5; wall shares from --durations: test_monitor's fault tests stream
every test campaign twice (faulty, then healthy); volumetric's figures (plots=summary) are most
of its figures test, the run itself little.

Measured (2026-12-06 19:09-19:23, base = git archive of f93f592e, after = 55b726ea; paired: base
and after started together, by a shell loop with ``cpu``'s command line; CPU s user + sys incl.
children)::

  module                 rep 1 (load ~20)   rep 2 (load 9-14)  mean            same tests pass
  test_model_auto        14.52 -> 14.32     13.50 -> 12.95     14.0 -> 13.6  -2.7 %   38 / 38
  test_monitor           21.37 -> 16.35     17.82 -> 14.47     19.6 -> 15.4  -21.4 %  39 + 2 xfail
  test_volumetric_run    30.95 -> 30.63     26.62 -> 26.79     28.8 -> 28.7  -0.3 %   11 / 11
  sum (the means, bench_ci100b's table)                         62.4 -> 57.8  -7.4 %

Against the bar: (1) kept: ``asserts`` on 55b726ea: asserts 104/61/57, refused( 1/0/4, tests
29/17/10 on both sides; no assert edited (the diff moves computations into fixtures only); the
same counts pass.  (2) NOT met: -7.4 % of the three modules' CPU against >= 20 %.  test_monitor
alone reached -21.4 % (-23.5 % and -18.8 % in the two reps), but choosing it after the
measurement would be a rule changed after its scoring: not kept. (3) met: plants on 55b726ea's copy,
one per module, each failed the changed test that reads the shared computation: auto.py
``as_chosen`` returning the template unchosen ->
test_the_run_refits_the_chosen_families_not_the_whole_choice failed; surveillance/monitor.py warning
bands x0.01 -> test_healthy_test_campaigns_raise_no_event_and_change_nothing failed; results.py
headline ``vce_rms_after`` x1.001 -> test_figures_headline_and_every_key_documented failed. Bench
CPU: ~229 s of trace runs, ~240 s of paired runs (10), 3 plants (one test each, 3.6-4.4 min wall);
wall 19:01-19:24.

Why so little: the shared runs were the cheap part of their tests (wall shares, base2 rep 1:
volumetric's stages test [null] 30.8 of 451 s, its run's part ~5 s, the figures test 75 s is
mostly figures; model_auto's validation test 11.5 of 306 s, the two in-process fits 5.0 + 4.2);
the rest of these modules' time is computations already made once or made on edited inputs.

``cpu`` / ``table``: bench_ci100b's (``cpu`` writes OUT/cpu.txt, pytest's output to OUT/log/).
``asserts``: per SPEC (a module path under tests/), the ``assert`` statements and ``refused(``
calls in BASE (a commit) and in the working tree.  ``plant``: a copy of TREE's src/ and tests/
with the first OLD in FILE (under TREE) replaced by NEW, the SPEC's tests run on it.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import run_commands  # noqa: E402
from bench_ci100b import THREADS, cpu, table  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def _counts(text: str) -> tuple[int, int, int]:
    """(assert statements, refused( calls, test functions) of a module's text."""
    return (len(re.findall(r"^\s*assert\b", text, re.M)), len(re.findall(r"\brefused\(", text)),
            len(re.findall(r"^def test_", text, re.M)))


def asserts(base: str, *specs: str) -> None:
    """Per module: asserts, refused( calls and tests in ``base`` and in the working tree."""
    for spec in specs:
        old = subprocess.run(["git", "show", f"{base}:tests/{spec}"], cwd=ROOT, capture_output=True,
                             text=True, check=True).stdout
        new = (ROOT / "tests" / spec).read_text()
        (a0, r0, t0), (a1, r1, t1) = _counts(old), _counts(new)
        ok = a1 >= a0 and r1 >= r0 and t1 == t0
        print(f"{spec:45s} asserts {a0} -> {a1}, refused {r0} -> {r1}, tests {t0} -> {t1}: "
              f"{'kept' if ok else 'CHECK'}")


def plant(tree: str, file: str, old: str, new: str, spec: str) -> None:
    """Run ``spec``'s tests on a copy of ``tree`` with OLD -> NEW (first one) in ``file``."""
    tree_path = Path(tree).resolve()
    with tempfile.TemporaryDirectory(prefix="ci101c-plant-") as scratch:
        copy = Path(scratch) / "tree"
        for item in ("src", "tests", "conf", "benchmarks", "docs", "datasets", "pyproject.toml",
                     "README.md", "Makefile", "dvc.yaml", ".dvc", "pipelines"):  # (copy_project's)
            source = tree_path / item
            if source.is_dir():
                shutil.copytree(source, copy / item, ignore=shutil.ignore_patterns("__pycache__"))
            elif source.exists():
                shutil.copy2(source, copy / item)
        target = copy / file
        text = target.read_text()
        if old not in text:
            raise SystemExit(f"{file}: {old!r} not found")
        target.write_text(text.replace(old, new, 1))
        env = {**os.environ, **THREADS, "PYTHONPATH": str(copy / "src")}
        run = subprocess.run(["nice", sys.executable, "-m", "pytest", "-q", "-n", "0", "-p",
                              "no:cacheprovider", "-m", "not full", "-x",
                              f"--basetemp={Path(scratch) / 'bt'}", f"tests/{spec}"],
                             cwd=copy, env=env, capture_output=True, text=True)
        tail = (run.stdout.strip().splitlines() or ["?"])[-1]
        failed = [ln for ln in run.stdout.splitlines() if ln.startswith("FAILED")]
        print(f"plant {file} {old!r} -> {new!r} on {spec}: exit {run.returncode}, {tail}")
        for line in failed:
            print("  ", line[:150])


def measured(doc: str, argv: list[str]) -> int:
    """The command line of a CI-time bench whose docstring is ``doc`` (its rule, bar and numbers):
    this module's ``cpu``, ``table``, ``asserts`` and ``plant`` (the ci102 benches share it)."""
    return run_commands(doc, {"cpu": cpu, "table": table, "asserts": asserts, "plant": plant},
                        argv, cpu=sys.stdout)


def main(argv: list[str]) -> int:
    return measured(__doc__, argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
