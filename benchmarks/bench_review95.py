"""Two review defects left by stop 94 (review95, issue 34): the tests' "fit, then deploy as
``replay`` does" written out in 13 modules, and bench_mon88's ``_root`` deleting what an earlier
command wrote into the same ROOT.  No src change; no seed drawn (fresh or seen: none needed).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_review95.py keep ROOT     # two commands into one ROOT, as the benches do

``keep``: bench_mon88's ``_root`` as bench_step93 reaches it (``trace`` then ``healthy``, the
order that cost jump94b its ``trace-main.json``): the first call writes ``trace-main.json``, the
second must find it; then bench_mon88's ``_drawn`` simulates cr9031 (a climate room of 12 runs)
twice into ROOT: an existing record is replaced whole by its own command (``simulate`` writes the
dataset folder atomically), the same bytes.  Prints what it finds and the verdict.

The rules
---------
1. Tests: ``conftest.deployed_as_replay(cfg)`` -> ``(deployed, ds, test_ids)`` (read_streamed,
   the configured compensator fitted on the train split, ``builders.deploy_stream``,
   ``builders.deployable``), and ``conftest.fl_thermal_served()`` -> ``(deployed, system with the
   monitor, test campaign)`` for ``data=fl_thermal`` adaptive MLR (test_export_mon85b, mon86,
   test_monitor_settled94b).  The modules keep their own compose, records and assertions;
   test_export_first_time (the plain stream where not adaptive: ``deployable`` would add the lab's
   names to it) and test_export_inputs_product62 (an augmented compensator of its own) are not
   this build and are left.
2. Benches: ``_cli.project_root(word)``: ROOT made where missing, the measured tree's ``conf/``
   linked where none is, ``THERMOCOMP_ROOT`` set; nothing deleted.  bench_mon88's ``_root`` (its
   users: bar91, freeze90, mon89, mon89b, mon91b, monb92, quiet93b, step93 and so step93b, jump94,
   jump94b) and bench_auto87's (auto88, auto89; it never deleted) call it.

BAR (the brief's, given before the change; this docstring written after it and after the
before run, no number tuned): (1) every test file touched, and those importing a
changed helper, pass before and after with the same counts per file; tests/test_durations.py,
tests/test_lint.py and tests/test_benchmarks_cli.py pass; ``duplicates --change --base 34af1fcb``
shows nothing added; (2) ``keep`` finds the first command's file; a test in
tests/test_benchmarks_cli.py fails on 34af1fcb.

Measured (2026-12-06, 2 cores shared with other helpers, ``-n 0``, ``OMP_NUM_THREADS=1``, nice)
---
(1) 26 files (the 14 touched + 12 importing adaptive_mlr, deployed_mlr, column_system, _adaptive,
cmon82c's _deployed): 117 passed on 34af1fcb (547.6 s wall under load, 216 s CPU user + sys), 117
passed after (232.1 s wall, 198 s CPU), every file's count equal (test_export 30, guard 12, hammerstein54
8, cmon83 6, check61 / cmon84 / spike54 5, ...; none xfailed).  test_lint + test_durations +
test_benchmarks_cli 584 passed.  ``duplicates --change``: none added; the mon85b ~ settled94b
fixture pair (D6 of ``duplicates`` in tests/) gone.  MET.
(2) ``keep /tmp/review95/keep``: same ROOT, ``trace-main.json`` kept; cr9031 drawn twice, the
same digest (6d8a2e81d500): MET (1.2 s CPU, 3.5 s wall).  The same bench over 34af1fcb's
benchmarks/ (``git archive``): ``trace-main.json`` kept False, FAILS.  test_benchmarks_cli's
``test_a_commands_project_root_keeps_what_an_earlier_command_wrote`` fails on 34af1fcb (no
``project_root``), passes here.
"""

from __future__ import annotations

import hashlib
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_mon88 as mon88  # noqa: E402
from _cli import run_commands  # noqa: E402


def _digest(folder: Path) -> str:
    """One hash of every file of ``folder`` (names and bytes)."""
    h = hashlib.sha256()
    for path in sorted(p for p in folder.rglob("*") if p.is_file()):
        h.update(path.relative_to(folder).as_posix().encode() + path.read_bytes())
    return h.hexdigest()[:12]


def keep(root: str) -> None:
    """Two commands into one ROOT (module doc)."""
    import bench_step93 as step93

    first = mon88._root(root)
    (first / "trace-main.json").write_text('{"written": "by trace"}')
    second = step93.mon88._root(root)          # healthy's call, as bench_step93 makes it
    kept = (second / "trace-main.json").is_file()
    print(f"same ROOT {second == first}; trace-main.json kept {kept}", flush=True)
    seed, sim, _, _ = mon88.TRACED["cr9031"]
    digests = [_digest(mon88._drawn("cr9031", seed, sim, second)) for _ in range(2)]
    print(f"cr9031 drawn twice into ROOT: {digests[0]} / {digests[1]}; same {digests[0] == digests[1]}")
    print(f"verdict: {'MET' if kept and digests[0] == digests[1] else 'FAILS'}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"keep": keep}, argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
