r"""CI time (issue 34; stop 102, ci102d): the docs pages' commands (tests/test_readme.py) made to
compute no more than their pages show.

ci100b (bench_ci100b.py) traced the pages: no command runs twice, so the cost is what the
commands compute.  This bench measures the group's modules (tests/test_readme.py, test_docs.py,
shell/test_stage_imports.py) on d85f1799 and the pages' cuts against them.

Rule (docs pages + their test; no src change): a page's example computes only what the page
shows, its commands still what a user runs and the page still true:

- sweeps.md: the sweep of 2 jobs (``model=mlr,arx``) instead of 4 (``select=all,pearson`` too):
  a sweep, its comparison and promotion (twice: no new version) need two runs; the page's CPU
  figure of the 4-job sweep said of that sweep;
- own-data.md: the fl_thermal roles run is README.md's ``run data=fl_thermal`` (the page says
  ``data=fl_thermal`` says the same; conf/data/fl_thermal.yaml holds these keys, out the same):
  shown, not run (``skip`` with that reason); README's block runs it and checks its E_ch5;
- ``plots=none`` where the page never shows the run's figures: README.md's fl_thermal run,
  own-data.md's lab run, diagnose.md's diagnosed rerun, simulation.md's diagnose (its page
  names no file the diagnose writes); never the pages that show them (diagnose.md's report,
  monitoring.md's figures) and never README's ``make run``.

BAR (the brief's, written and committed here before any after-measurement; the base run of
the three modules, d85f1799 alone, is the trace):

1. every test id stays and passes (test_readme's 9: 7 pages + 2), every assertion of
   test_readme.py stays (``asserts``: no fewer asserts, the same tests), every page's
   ``expect``/``output`` directive stays (its regex and table unchanged), each page still holds
   its subject (a sweep compared and promoted twice; the door diagnosed and re-run; the column
   diagnosed; the lab and the fl_thermal record run) and says what the smaller example holds;
2. the changed modules' summed pytest CPU (user + sys of ``/usr/bin/time nice pytest -q -n 0 -p
   no:cacheprovider -m "not full"``, per module; base = a git clone of d85f1799 in
   /tmp/ci102d/base, a clone since test_readme copies the tree with ``git ls-files``) down
   >= 30 %, base and after started together (paired); 1 rep for the whole set;
3. every plant caught: one planted break of src per changed page (a changed constant, a skipped
   branch in what that page's commands run), each failing that page's test (``plant``).

No seeds (nothing is scored: the same commands give the same numbers).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci102d.py cpu TREE TAG OUT SPEC...       # bench_ci100b's cpu
    python benchmarks/bench_ci102d.py table OUT [BEFORE AFTER BAR]    # bench_ci100b's table
    python benchmarks/bench_ci102d.py blocks OUT                      # bench_ci100b's blocks
    python benchmarks/bench_ci102d.py asserts BASE SPEC...            # bench_ci101c's asserts
    python benchmarks/bench_ci102d.py plant TREE FILE OLD NEW SPEC OUT  # a break, in a git clone

``plant``: ``cpu`` (tag ``plant``) of SPEC in a ``git clone`` of TREE's HEAD (test_readme lists
the files it copies with git, so bench_ci101c's copy of the tree would not do) with OLD -> NEW
(the first one) in FILE; the failed tests from its log.

Trace (d85f1799 alone, 2026-12-06 21:44-21:58, load 5-15, ``cpu``; CPU s user + sys incl.
children): test_readme 144.1 (9 passed; blocks: sweeps.md sweep + compare + 2 promotes 25.7,
its lathe replay 7.9), test_docs 10.6 (45 passed), shell/test_stage_imports 11.2 (9 passed).
Single commands in a page's copy (probe, load 5-15): the 4-job sweep 11.5 / 23.1 s, the 2-job
one 17.7 / 16.8 s, compare 2.8, promote 4.1 and 4.0; ``run data=fl_thermal`` 7.0, with
``plots=none`` 4.4; simulation.md's diagnose 14.7, with ``plots=none`` 10.7 (the same table);
its scenario at half the hours (simulate + diagnose) 12.9: not taken (its numbers would change
for ~3 s).

Rule built (docs pages + a comment of test_readme.py; REFUSED, saved as
benchmarks/ci102d_rule.patch, which applies to d85f1799; README.md, docs/ and test_readme.py are
back to d85f1799 on the branch).

Measured (2026-12-06 21:57-22:14, paired: base = git clone of d85f1799, after = cc491ff4,
started together by two ``cpu`` processes, load 14-21; CPU s user + sys incl. children, 1 rep)::

  module            base     after    cut      tests
  test_readme.py    150.3 -> 128.3    -14.6 %  9 passed / 9 passed
  its blocks (``blocks``, commands only)  139.2 -> 117.3 (-21.9 s)

Per changed block, base -> after (CPU s, that pair): sweeps.md's sweep + compare + 2 promotes
27.7 -> 23.0; README's fl_thermal run 7.9 -> 6.2; own-data.md's lab run 5.7 -> 3.8, its
fl_thermal roles run 6.7 -> 0 (shown, not run); simulation.md's simulate + diagnose 16.1 -> 10.4;
diagnose.md's rerun 7.5 -> 5.4.  The unchanged blocks moved by -1.6 .. +1.3 s (load).

Against the bar: (1) met: the same 9 test ids pass; ``asserts``: test_readme 12 -> 12 asserts,
3 -> 3 tests (only a comment changed); every ``expect``/``output`` directive kept but
own-data.md's ``expect E_ch5`` on the fl_thermal run, whose computation README's block runs with
the stronger ``expect E_ch5\s.*->\s+3\.0\d`` (the same keys, out and numbers); each page still
holds its subject and says what the smaller example holds.  (2) NOT met: -14.6 % against
>= 30 %.  (3) met, 5 of 5 (``plant``, one per changed page; each failed at the changed block):
results.py ``val_rsd_mean`` renamed -> sweeps.md line 3 failed; units.py ``"um"`` dropped ->
README.md line 75 failed; tables.py ``decimal_point="."`` -> own-data.md line 27 failed;
diagnose outputs.py the experiment written under another name -> diagnose.md line 758 failed;
outputs.py ``else None`` for the figures of ``plots=none`` -> simulation.md line 79 failed.

Why so little: what the pages' commands compute beyond what they show was ~22 s of ~139; the
rest is the commands a page shows, most of each one its process's start (``ingest`` 3.9 s CPU in
a page's copy: ``import mlflow`` 2.0 s, sklearn + scipy + pandas 2.3 s), ~25 processes.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import run_commands  # noqa: E402
from bench_ci100b import _key, blocks, cpu, table  # noqa: E402
from bench_ci101c import asserts  # noqa: E402


def plant(tree: str, file: str, old: str, new: str, spec: str, out: str) -> None:
    """``cpu``'s run of ``spec`` (tag ``plant``, into OUT) on a git clone of ``tree``'s HEAD with
    OLD -> NEW (the first one) in ``file``; the failed tests from its log."""
    with tempfile.TemporaryDirectory(prefix="ci102d-plant-") as scratch:
        copy = Path(scratch) / "tree"
        subprocess.run(["git", "clone", "-q", str(Path(tree).resolve()), str(copy)], check=True)
        target = copy / file
        text = target.read_text()
        if old not in text:
            raise SystemExit(f"{file}: {old!r} not found")
        target.write_text(text.replace(old, new, 1))
        print(f"plant {file} {old!r} -> {new!r}")
        cpu(str(copy), "plant", out, spec)
    log = Path(out) / "log" / f"plant-{_key(spec)}.txt"
    print("\n".join(f"   {line[:160]}" for line in log.read_text().splitlines() if line.startswith("FAILED")))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"cpu": cpu, "table": table, "blocks": blocks, "asserts": asserts,
                                  "plant": plant}, argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
