"""CI time (issue 34; stop 104, ci104c): the CPU of the export slice of the test suite.

The slice (the brief's, 22 modules, wall s in the morning's CI run): test_export, atiprod65, guard,
rest60, effects59, ati63, diaglstm64, first_time, auto57, inputs_product62, hammerstein54, lstm62,
forest62, check61, ambient62, cadence72, ati60, core/test_utf16_exports49, diaglstm63,
day_seconds91, ati57, lab_export53 (``SLICE`` below).

BAR (the brief's, written and committed here before any after-measurement):

1. every test id of the slice stays and passes (``-n 0 -p no:cacheprovider -m "not full"``), and
   the neighbouring modules touched through shared fixtures pass; no assertion removed or
   loosened (bench_ci101c's ``asserts`` counts, per changed module, against c8b21182);
2. KEPT when the slice's summed CPU (user + sys incl. children, ``/usr/bin/time -f '%U %S'`` of
   ``python -m pytest -q -n 0 -p no:cacheprovider -m "not full" MODULE``, each module alone, run
   from its tree with PYTHONPATH=<tree>/src and OMP/OPENBLAS/MKL_NUM_THREADS=1) falls >= 15 %,
   base (``git archive c8b21182`` in /tmp/ci104c/base) and after measured paired, one after the
   other; the pair repeated once when the difference is under 15 %.  Below 15 %: the exact cuts
   are still committed (the lead decides) and the verdict says the bar was not met.
3. tests moved to ``full`` are reported apart (count, their CPU, the covering test, the plant).

The cuts (tests only, no src; commits 6bc34089, 71d5a244, a3018430, ce8040da; also saved as
benchmarks/ci104c_rule.patch, which applies to c8b21182's tests): test_export's split builds link
a driver object (``stream.c`` with the model's header) compiled once per text and level; its
``_fitted`` and ``_trained`` once per dataset, model and overrides (ati63, ambient62, check61 made
the same fit or run twice); the -O0/-O2 test takes the pack's own -O0 build; fits shared by deep
copies: guard's monitor/tight cases, first_time's (and cadence72's) six readers of two fits,
atiprod65's three readers of one, diaglstm63's two, diaglstm64's ATI-lstm record and plain fit,
inputs_product62's plain MLR.  No test moved to ``full``, none removed; ``asserts``: the same.

Measured (2026-12-07, load 8-21 on the 2 cores; ``cpu`` of bench_ci100b, CPU s user + sys incl.
children, each module alone, both trees cold at their first module): pair 1, base = ``git
archive c8b21182`` 03:45-04:09, after = ``git archive ce8040da`` 04:09-04:24, the 22 modules::

  test_export 26.5 -> 24.2 (-8.7 %)   atiprod65 22.2 -> 19.2 (-13.3 %)  guard 18.5 -> 17.5 (-5.3 %)
  rest60 12.2 -> 11.5 (-5.6 %)        effects59 10.5 -> 9.4 (-10.4 %)   ati63 13.1 -> 12.2 (-6.6 %)
  diaglstm64 16.2 -> 14.2 (-12.3 %)   first_time 9.5 -> 8.8 (-7.5 %)    auto57 9.4 -> 8.9 (-4.6 %)
  inputs_product62 11.0 -> 9.4 (-14.3 %)  hammerstein54 8.3 -> 8.0      lstm62 11.0 -> 10.9
  forest62 7.7 -> 7.4   check61 7.1 -> 6.6   ambient62 5.8 -> 5.4   cadence72 6.9 -> 6.6
  ati60 6.7 -> 6.6   utf16_exports49 6.2 -> 6.2   diaglstm63 9.2 -> 9.3   day_seconds91 5.3 -> 5.6
  ati57 6.2 -> 6.5   lab_export53 5.8 -> 6.0
  sum 235.3 -> 220.3 s, -6.4 %: the bar (>= 15 %) NOT met.

Pair 2 (the brief's repeat, under 15 %; not of the whole slice, 40 min of wall at this load, but
of the six most changed modules; base 04:25-04:30, after 04:30-04:34, both trees warm)::

  atiprod65 22.9 -> 19.1 (-16.8 %)   guard 19.5 -> 16.7 (-14.4 %)   diaglstm64 15.6 -> 13.8 (-11.1 %)
  inputs_product62 9.5 -> 8.5 (-10.9 %)   first_time 8.9 -> 7.9 (-11.5 %)   diaglstm63 9.1 -> 8.3 (-8.5 %)
  sum 85.5 -> 74.2 s, -13.1 % (the same six in pair 1: 86.6 -> 78.4, -9.5 %)

Against the bar: (1) met: every test id passes on both sides (the same counts); the asserts /
refused( / tests of the 7 edited modules as c8b21182's; the neighbours reading the edited helpers
(apps/diagnose_over72, dropout53, spike54, repeat99, restart66, banner59, audit87,
envelope_pattern, dates85, guard_follows_inputs56, stranger66): 56 passed.  (2) NOT met: -6.4 %.
Why so little: each module alone pays pytest's start, the imports and the collection, 2.2-3.4 s
of CPU (``--collect-only`` of test_export, atiprod65, lab_export53 on c8b21182), some 60 s of the
235 s, which the CI's three xdist workers pay once each; the rest is mostly gcc (two or three
builds a proof), the LSTMs' training and the check packs, each case its own model.

Usage (from the repository root)::

    python benchmarks/bench_ci104c.py BASE AFTER OUT    # paired: BASE's slice, then AFTER's
    python benchmarks/bench_ci104c.py OUT               # the table of OUT/cpu.txt

Each run appends ``TAG MODULE user sys wall result`` lines to OUT/cpu.txt (bench_ci100b's ``cpu``).
"""
from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_ci100b import cpu, table  # noqa: E402

SLICE = tuple(f"shell/test_export{m}.py" for m in (
    "", "_atiprod65", "_guard", "_rest60", "_effects59", "_ati63", "_diaglstm64", "_first_time",
    "_auto57", "_inputs_product62", "_hammerstein54", "_lstm62", "_forest62", "_check61",
    "_ambient62", "_cadence72", "_ati60")) + (
    "core/test_utf16_exports49.py", "shell/test_export_diaglstm63.py",
    "shell/test_export_day_seconds91.py", "shell/test_export_ati57.py", "shell/test_lab_export53.py")


def main(argv: list[str]) -> int:
    if len(argv) == 3:
        base, after, out = argv
        cpu(base, "base", out, *SLICE)
        cpu(after, "after", out, *SLICE)
        table(out, "base", "after", 15.0)
        return 0
    if len(argv) == 1:
        table(argv[0], "base", "after", 15.0)
        return 0
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
