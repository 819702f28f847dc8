"""The applied st102 rule scored on fresh windows that reach it (st102b, issue 34; no src change).

st102 (bench_st102.py, applied by the lead in 67a9c7e6 over its refused bar): a lone jump of the
sensor the ST block holds out by ``BLIND_OUT`` is the C's silent re-reference (not flagged,
re-referenced, its calm restarted; the C's ``_undone`` at the hold's ``BACK``).  Its fresh draw
(lr/dl 9961-9963) was void: on 5 of 6 records the block's ``BLIND_OUT`` judgement had stopped in
the lead-in (``mon_stop``: the C's ``DRIFT_OUT`` of a sensor others predict) and its planted
+3-limit jump of T_amb read ``OFF_RANGE``; no window held a ``BLIND_OUT``.

Here: THE TREE's block (main, the rule applied) against the rule's parent d85f1799 (:data:`BASE`,
"main" in bench_st102's lines), the C beside both.  No planted jump (it read beyond range).

WINDOW RULE (chosen before any fresh record was drawn, applied blind): a record of :data:`FRESH`
(bench_cmon91's lr and dl generators, seeds 9964-9967) is SCORED iff, stepped healthy through its
lead-in to the onset, the tree's block has neither stopped (``mon_stop``) nor lost its field
(``mon_lost``); the gate is read from the healthy stream alone, before any window.  In a scored
record the windows are bench_st102's ``cases``: per sensor no other predicts, test_export_st96's
bump (+6 C) from the onset, and :func:`bench_st102.dropped` (the same rise and hold, then back
in one row).  A REACHED case is a dropped window where the C's first ``BLIND_OUT`` is of the
bumped sensor before the back row, the tree's block names it (sensor, +-2 rows), and the block's
hold has not ended before the back row: the sensor jumps while the block holds it out.

BAR (committed before lr/dl 9964-9967 are simulated; scored once):

* F1 >= 75 % of reached cases as the C on the back row (the C silent there: the block silent; the
  C names a rule: the block the same rule).
* F2 0 new extra flags in the scored records' windows (a tree block flag whose rule and sensor the
  C does not raise within 2 rows and d85f1799's block does not raise: bench_st101's ``new``).
* F3 every ``BLIND_OUT`` d85f1799 names in a window, the tree names on the same row.
* F4 the healthy stream of each scored record: 0 rows where the tree's (flag, rule, sensor)
  differs from d85f1799's, or each such row one where the C is silent and d85f1799 flags.
* VOID: fewer than 3 reached cases over all scored records: TRACED (said why), no verdict on F1.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st102b.py fresh ROOT RECORD [RECORD ...]

ROOT holds the records as bench_cmon92's ``made`` makes them (each once).  Per record bench_st101's
record line and bump lines, then bench_st102's dropped lines, then the gate line: ``mon_stop``
(its row) and ``mon_lost`` at the onset, and whether the record is scored.

Measured (2026-12-06, 2 cores shared, load 0.5-3.5; the tree = 14ea84f3, st102's rule as applied in
67a9c7e6; BAR b1ffa009 unchanged; scored once; VERDICT KEPT: F1-F4 met):

* ``fresh /tmp/st102b/fresh lr9964 lr9965 lr9966 lr9967`` (52.4 s CPU with the simulation);
  ``... dl9964 dl9965`` (44.5 s), ``... dl9966 dl9967`` (41.4 s).  The gate scored all 8.
* F1 MET: 17 reached cases (lr9964 6, lr9967 2, dl9964 6, dl9966 3), the tree as the C on the back
  row 17 of 17 (the C silent on all 17; d85f1799 flags ``JUMP`` on 11, as the C on 6).  Not
  reached: lr9966 T_motor (the C's ``BLIND_OUT`` 3764, after the back row 3723); lr9965 (no
  ``BLIND_OUT`` in any window); dl9965 and dl9967, 9 of the C's ``BLIND_OUT`` named by neither block.
* F2 MET: 106 windows' lines, new extra flags 0; extra flags the tree 21, d85f1799 37.
* F3 MET: every ``BLIND_OUT`` d85f1799 names, the tree names on the same row (35 windows, both).
* F4 MET: 0 rows differing from d85f1799 on the 8 healthy streams; extra flags 0 (d85f1799 0).
* The gate as written read ``mon_stop``, TRUE on the one sample where the judgement ends
  (st_watch.py doc), not ``mon_stop_row`` (> 0 from there): it passed lr9965 (judgement ended at
  2470), dl9965 (5696) and dl9967 (3117), read after the score.  None of the 17 is on them; gated on
  ``mon_stop_row`` 0 the score is the same 17 of 17 on 5 records.
* Traced after the score (seen now; ``PYTHONPATH=<d85f1799>/src ... fresh ROOT dl9964``, 20.9 s):
  dl9964 T_spindle_rear (``BLIND_OUT`` 6156, no jump at the back row, the C's ``BACK`` 6175) has
  max|C - ST| 5.07 um over the 20 rows from the C's ``BACK`` in both trees: not st102's; next step.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st100  # noqa: E402
import bench_st101  # noqa: E402
import bench_st102  # noqa: E402
from _cli import run_commands  # noqa: E402

BASE = bench_st102.BASE     # d85f1799: the rule's parent


def _fresh() -> dict:
    """bench_st100's :data:`FRESH` words (bench_cmon91's lr and dl generators) on seeds 9964-9967."""
    lr, dl = (next(words for record, words in bench_st100.FRESH.items() if record.startswith(kind))
              for kind in ("lr", "dl"))
    return {f"{kind}{seed}": [f"seed={seed}" if w.startswith("seed=") else w for w in words]
            for seed in range(9964, 9968) for kind, words in (("lr", lr), ("dl", dl))}


FRESH = _fresh()     # lr9964, dl9964, ..., lr9967, dl9967 (chosen before any was simulated)


def fresh(root: str, *records: str) -> None:
    """The ``fresh`` lines (module doc)."""
    bench_st102.FRESH = FRESH    # bench_st102's _cell makes these as its own fresh records
    for record in records:
        kept, frame, start, names = bench_st101._record(
            root, record, False, True, bench_st102._cell, bench_st102.Walk)
        for sensor in [n for n, p in zip(names, kept.three.ss.monitor["predictable"]) if not p]:
            bench_st102._dropped(kept, names, sensor, frame, start)
        v = kept.three.fb.vars
        stop, lost = bool(v["mon_stop"]), bool(v["mon_lost"])
        print(f"  gate {record}: at the onset {start} mon_stop {stop} (row {int(v['mon_stop_row'])}), "
              f"mon_lost {lost}: {'NOT scored' if stop or lost else 'SCORED'}", flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"fresh": fresh}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
