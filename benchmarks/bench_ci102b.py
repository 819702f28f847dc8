"""CI time (issue 34; stop 102, ci102b): the export family's tests, gcc's driver build and the
plain MLR every diagnosed model refitted.

Trace (d85f1799, the fresh-clone CI profile /work/notes/prof102: 212 s of CPU in the 18 export
modules, ~90 s of it gcc's children).  A proof of an exported model builds ``compensator.c`` and
``stream.c`` at ``-O2`` (test_export's ``_compiled``, CONTROL), ~0.7 s of gcc a build; measured on
one diagnosed model's folder (rest60's door record, 2 runs each, user + sys s): the whole program
at -O2 0.66-0.76, at -O0 0.37-0.40; ``compensator.c`` alone at -O2 (``-c``) 0.10-0.11, linked with
``stream.c`` at -O0 0.16.  ``stream.c``, the driver, is one text for every model (the same md5 on
mlr/lagbank/arx_ar/a diagnosed lag/a cascade), and test_export's proofs build it at -O2 for every
family.  Each diagnosed model (test_export_diagnosed59's ``_diagnosed``, read by effects59, rest60,
ati60, ati63, diaglstm63/64, clamp_diagnosed60, banner_59, leftovers66, stranger66) fitted and
deployed the same plain MLR again, composed and read the record again: ~0.18 s of ~0.3 s of
Python a model (cell trace, warm).

Rule (tests only, no src, no key; REFUSED: saved as benchmarks/ci102b_rule.patch, which applies
to d85f1799 (its tests and docs/layout.md); the modules are back to d85f1799 on the branch):

- test_export's ``_compiled(stream, folder, driver=CONTROL)``: ``driver=LEVEL`` builds the
  model's code at CONTROL (``-c compensator.c``: its -O2 warnings and arithmetic) and links it
  with the driver at the tests' level.  test_export's proofs keep the whole -O2 build once per
  family (``select=all``), the other 15 cases and the proofs of auto57 (``_proved``, read by 11
  modules), guard, atiprod65, inputs_product62, forest62 take ``driver=LEVEL``.
- test_export_diagnosed59's ``_plain``: the plain MLR, its config and train campaigns made once
  per dataset; every ``_diagnosed`` gets copies (tests, train frames) and a clone.

BAR (the brief's, written and committed here before the after-measurement; one unpaired look at
rest60 was taken while building: 26.0 s base -> 17.9 s):

1. every test id stays and passes (the same counts, ``-n 0 -p no:cacheprovider -m "not full"``);
   no assertion removed or weakened (``asserts``: no fewer ``assert`` / ``refused(`` per changed
   module than d85f1799); the one check moved: gcc's -O2 warnings on ``stream.c`` beside each of
   these models' headers (held at -O2 by test_export's proofs, once per family);
2. the changed modules' summed pytest CPU (user + sys incl. children, ``/usr/bin/time nice
   pytest -q -n 0 -p no:cacheprovider -m "not full"``, each module alone; base tree = ``git
   archive d85f1799`` in /tmp/ci102b/base) down >= 30 %, base and after started together
   (``paired``); 1 rep for the whole set, a 2nd for the most changed modules if time allows;
   changed = a module edited or one reading an edited helper (auto57's ``_proved``,
   diagnosed59's ``_diagnosed``, test_export's proofs): the group's 15 + ati57, banner_59,
   leftovers66, stranger66, apps/test_diagnose_over72;
3. every plant caught: one planted break (``plant``, bench_ci101c's: a one-line change of src
   in a scratch copy) per changed helper fails a test reading it: the C's lag (split build via
   auto57's ``_proved``), the C's clamp (test_export's split cases), a diagnosed effect's law
   (``_diagnosed`` via ``_plain``).

No seeds: nothing is scored (the same commands on the same data).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci102b.py paired BASE AFTER OUT SPEC...   # both trees at once
    python benchmarks/bench_ci102b.py cpu TREE TAG OUT SPEC...        # bench_ci100b's cpu
    python benchmarks/bench_ci102b.py table OUT [BEFORE AFTER BAR]    # bench_ci100b's table
    python benchmarks/bench_ci102b.py asserts BASE SPEC...            # bench_ci101c's asserts
    python benchmarks/bench_ci102b.py plant TREE FILE OLD NEW SPEC    # bench_ci101c's plant

Measured (2026-12-06 21:56-22:33, base = git archive d85f1799, after = e8efb468 archived; paired:
``paired`` over all 23 modules (load 9-19), a 2nd ``paired`` rep of the three largest changed
modules started 22:23; CPU s, user + sys incl. children, mean of the reps; ``table``)::

  module (changed)                   base -> after          module (changed)          base -> after
  test_export (2 reps)               38.1 -> 30.9  -18.9 %  ati60                     11.2 ->  6.9  -38.5 %
  atiprod65 (2 reps)                 35.1 -> 28.1  -20.0 %  forest62                  10.5 ->  8.2  -21.5 %
  guard (2 reps)                     24.8 -> 20.2  -18.3 %  lstm62                    13.5 -> 12.2   -9.5 %
  rest60                             26.1 -> 13.5  -48.1 %  diagnosed59                7.3 ->  5.8  -20.5 %
  effects59                          24.1 -> 11.8  -51.2 %  diaglstm63                10.9 -> 10.5   -3.5 %
  diaglstm64                         24.5 -> 17.7  -27.9 %  ati57                      9.2 ->  7.2  -21.4 %
  auto57                             14.2 -> 10.2  -27.8 %  banner_59                  4.6 ->  4.4   -4.9 %
  ati63                              17.3 -> 15.7   -9.0 %  leftovers66                6.6 ->  6.9   +5.2 %
  inputs_product62                   13.9 -> 10.8  -22.4 %  stranger66                12.1 -> 13.2   +9.0 %
  clamp_diagnosed60                  12.5 ->  7.5  -39.9 %  apps/diagnose_over72       6.2 ->  6.1   -1.8 %
  sum of the 20 changed: 322.6 -> 247.9 s, -23.2 % (rep 1 alone: 329.3 -> 254.3, -22.8 %)
  unchanged, same code both sides (the noise): deployed_as_scored44 33.1 -> 34.5 (+4.4 %),
  deployed_as_scored 9.8 -> 10.5 (+6.5 %), check61 6.8 -> 7.3 (+7.1 %); all 23: 372.3 -> 300.2

Against the bar: (1) met: the same test ids pass on both sides (30 + 1 deselected, 21, 12, 18,
18, 15, 11, 8, 8, 9, 6, 7, 7, 4, 3, 5, 3, 5, 8, 5; 40, 8, 5 unchanged); ``asserts``: every edited
module the same asserts / refused( / tests as d85f1799 (44/3/10, 25/1/7, 25/0/5, 31/0/7, 19/0/5,
18/0/6, 3/1/2).  (2) NOT met: -23.2 % of the changed modules' CPU against >= 30 %.  (3) met:
4 plants on e8efb468's copy (c.py, the C text only), each failed its test: the transient's
``1.0 - exp`` -> ``1.001 - exp`` -> rest60 [signal-direction] (auto57's ``_proved``, split);
the lag's decay x1.001 -> test_export [lagbank-emd-pearson] (split case); AMBIENT_CENTRE + 0.001
-> diagnosed59 [ambient-law] (``_plain``); the bias update x1.001 -> guard [mlr-bias].
The cut is real but smaller than traced: -0.4 s of gcc a build, ~150 builds; the modules with
diagnosed models (rest60, effects59, ati60, clamp_diagnosed60) lost 38-51 %, those whose tests
are mostly Python (ati63, lstm62, diaglstm63: fits, the LSTM's network) 4-10 %.  Bench CPU: ~700
s of paired runs, 4 plants (~30-55 s wall each); wall 21:56-22:33.

``paired``: :func:`bench_ci100b.cpu` of BASE (tag ``base``) and of AFTER (tag ``after``) started
together, each spec alone in turn, both writing OUT/cpu.txt.
"""
from __future__ import annotations

import sys
import threading
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import run_commands  # noqa: E402
from bench_ci100b import cpu, table  # noqa: E402
from bench_ci101c import asserts, plant  # noqa: E402


def paired(base: str, after: str, out: str, *specs: str) -> None:
    """``cpu`` of ``base`` and of ``after`` over ``specs``, the two started together."""
    runs = [threading.Thread(target=cpu, args=(tree, tag, out, *specs))
            for tree, tag in ((base, "base"), (after, "after"))]
    for run in runs:
        run.start()
    for run in runs:
        run.join()


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"paired": paired, "cpu": cpu, "table": table,
                                  "asserts": asserts, "plant": plant}, argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
