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
