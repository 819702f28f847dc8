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
                     "README.md", "Makefile", "dvc.yaml"):
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


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"cpu": cpu, "table": table, "asserts": asserts, "plant": plant},
                        argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
