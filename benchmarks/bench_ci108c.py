"""CI time (issue 34; stop 108, ci108c): group C of the test suite (tests/apps, tests/core,
tests/base, tests/data and the tests/shell modules the brief leaves to this group: 297 modules,
listed by ``group``) made cheaper in CPU without losing what it checks.

Cuts, in the brief's order of preference: work done twice (a fit / run / C build / export per
test where one module fixture serves several tests that only read it), data or report extras
bigger than the assertion needs, a subprocess where the process boundary is not the subject,
parametrized cases or tests asserting the same claim on the same computation.

BAR (the brief's, written and committed here before any after-measurement):

1. no test lost without a named replacement; every assertion kept (same or stronger); where a
   test's data are shrunk, the shrunk test is shown to fail on what it guards (the src before
   the test was added, or the mutation its docstring names);
2. KEPT when the group's CPU (user + sys incl. children, ``/usr/bin/time``; the three
   *_NUM_THREADS=1; ``python -m pytest -q -n 0 -p no:cacheprovider -m "not full"``; base tree =
   ``git archive 0dd05741``) falls >= 30 %: the group as one pytest process (``group``), base
   and after one after the other, and each changed module alone, paired (``cpu``), repeated
   where the difference is under 10 %;
3. tests/test_lint.py, tests/test_durations.py, tests/test_docs.py pass; ruff clean.

Measured (2026-12-07 14:39-14:58 UTC, load 11-17 on 2 cores: other helpers' runs; CPU s user +
sys incl. children, ``cpu``, nice; base = ``git archive 0dd05741`` in /tmp/ci108c/base).  The
group as one process (``group``) was started and stopped at 55 s of CPU: under that load it
would have taken over an hour of wall time; the group's base is not measured.  The three changed
modules paired, base then after, two pairs each::

  apps/test_diagnose_scenarios    24.84 / 26.01 -> 22.67 / 24.42   25.4 -> 23.5   -7.4 %
  shell/test_calibrate            45.61 / 46.41 -> 48.19 / 44.52   46.0 -> 46.4   +0.7 % (noise)
  shell/test_diagnose_deployed60   9.12 /  7.47 ->  7.86 /  6.94    8.3 ->  7.4  -10.8 %
  sum                                                              79.7 -> 77.3   -3.0 %

Against the bar: (1) met: every test of the three modules passes (16 + 70 + 3), none lost, no
assertion weakened (diagnose_scenarios' ambient_law case asserts on both targets, deployed60
asserts that the plain stream's diagnosis writes the default one's model); no data shrunk.
(2) NOT met: the 2.4 s saved is under 0.5 % of the group (the ci7 run's durations give the
group 1060 of the suite's 2280 test-seconds).  (3) met: test_lint, test_durations, test_docs
pass (50), ruff clean.  Verdict REFUSED; the cuts stay on the branch (benchmarks/
ci108c_rule.patch): exact, the lead can merge them.

Why so little (traced, py-spy profile /tmp/prof1.raw of this morning's suite, the group's 266
modules it sampled, 834 s): Hydra's per-command composition is 15 % of it (125 s), the diagnose
searches 12 % (98 s), apps/volumetric (the calibrations) 8 % (63 s), parquet/csv reading and writing
5 % (40 s).  The runs, fits and exports left are each a test's own claim (one family x wrapper,
one fault, one refusal) or were shared at stops 98-104 (module fixtures in deployed_as_scored44,
replay, volumetric_run, frames62, hostile_numeric, hostile_procs, opcua67); the process tests
serve their OPC UA machines in threads already.  The lever left is generic, not per test:
Hydra's per-command work (ci104's note: a wider compose cache and no config copies).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci108c.py group TREE OUT            # the group's module list
    python benchmarks/bench_ci108c.py cpu TREE TAG OUT SPEC...   # each spec alone, /usr/bin/time
    python benchmarks/bench_ci108c.py table OUT [BEFORE AFTER BAR]
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_ci100b  # noqa: E402
from _cli import made_folder, run_commands  # noqa: E402

# tests/shell modules other helpers of stop 108 own (the brief's list of prefixes)
OTHERS = ("dvc|sweep|tracking|team|optuna|lab_sweep|stage|denoise_stages|validation|evaluate|report|promote|"
          "compare|run|hydra|config|data|init|own|ingest|export|deploy|serve|repeat|bits|monitor|st|restart|"
          "stdin|mon")


def modules(tree: Path) -> list[str]:
    """The group's test modules under ``tree``, as paths relative to its root."""
    tests = tree / "tests"
    mine = [p for d in ("apps", "core", "base", "data") for p in sorted((tests / d).rglob("test_*.py"))]
    shell = sorted((tests / "shell").glob("test_*.py"))
    mine += [p for p in shell if not re.match(f"test_({OTHERS})", p.name)]
    return [str(p.relative_to(tree)) for p in mine]


def group(tree: str, out: str) -> None:
    """The group's modules, one a line, on OUT/group.txt (and printed)."""
    listed = modules(Path(tree).resolve())
    (made_folder(out) / "group.txt").write_text("\n".join(listed) + "\n")
    print(f"{len(listed)} modules")


COMMANDS = {"group": group, "cpu": bench_ci100b.cpu, "table": bench_ci100b.table}


def main(argv: list[str]) -> int:
    return run_commands(__doc__, COMMANDS, argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
