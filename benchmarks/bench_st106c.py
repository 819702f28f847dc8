"""The ST block follows the C's lone ``DRIFT_OUT``: st105b's rule re-scored on 07b7fbfb (st106c, issue 34).

st106 (TRACED, bench_st106.py) found the ST's whole gap on the C's held JUMPs beside another out
(18 events: seen lr9985 dl9964 lr9964 lr9966 lr9967 dl9966 dl10007 lr10007 lr10008, st105's fresh
lr/dl 10013-10015; 0.18 .. 2.0 um on the hold rows) is one input: the sensor the C takes out by
``DRIFT_OUT`` (``_lone_fault``) on the block's ``mon_stop_row``.  st105b (REFUSED,
benchmarks/st105b_rule.patch) built the block's ``DRIFT_OUT`` (``MON_LONE``, ``MON_LONE_SELF`` /
``MON_LONE_SCALE``, ``MON_ROUNDING``); since then st105 and st106b are in main.  The rule tried
here is that patch applied to 07b7fbfb as it is (its test_export.py digest conflict resolved to
main's, then re-asked).

BAR (committed before any score of this rule and before fresh lr/dl 10119-10121 are simulated;
scored once).  Tree = this branch, main = :data:`MAIN`'s export, the C beside.

* B1: on st106's 18 events (``events``: bench_st106's ``oracle`` lines, the block's column) the
  block within 1e-9 um of the C on every hold row and every after row.
* B2: every row the tree names ``DRIFT_OUT`` (``windows`` / ``healthy``: bench_st105b's lines) the
  C names ``DRIFT_OUT`` of the same sensor on that row.
* B3: 0 rows where the tree's flag differs from main's and the C names nothing there.
* B4 (healthy: bench_st105's 8 records lr/dl 9964-9967, the stream whole): 0 flag rows and 0 c
  rows differing from main, except a B2 naming and its hold (where the C's ``DRIFT_OUT`` is named
  main stopped; said per row).
* B5: the ST modules pass (test_export_st93..st100, st97d), ``PARSED_DIGEST`` re-asked (blark
  parses the block).
* Fresh lr/dl 10119-10121 (bench_st102b's FRESH words, seeds +155): B1 on their C JUMPs beside
  another out, B2-B4 alike.  All met: KEPT; B1 or B2 or B3 not met on seen: REFUSED.

MEASURED (2026-12-07, 2 cores shared, load 4-11; rule = benchmarks/st106c_rule.patch on 07b7fbfb,
made in a scratch src; BAR 0344cf7b, unchanged; CPU user + sys as each command prints it).
VERDICT REFUSED: B1 not met on seen, st105's fresh nor new fresh; B2-B5 met.

* B1 (``events``; seen 108.1 s, st105's fresh 81.3 s): the 10 seen events, block hold rows main
  0.18 .. 1.3 -> tree 0.31 .. 5.5 um (worse on 5, equal on 4, 0.91 -> 0.71 on lr10007), after rows
  main <= 5.1 -> tree <= 5.1; st105's fresh 8: hold main 0.32 .. 2.0 -> tree 0.44 .. 37 (dl10015
  T_table 6170: 2.0 -> 37, after 2.3 -> 22).  A C JUMP with none beside (lr9985 T_spindle_rear
  3723) goes 6e-14 -> 21 um.  Fresh 10119-10121 (scored once, 79.9 s; main 76.0 s): 8 events,
  hold main 0.28 .. 2.8 -> tree 0.28 .. 9.7 (worse on 4: lr10120 T_motor 1.2 -> 9.7, T_xdrive
  1.1 -> 8.5).  Far from 1e-9 um.
* Why (``windows`` seen 32.8 + 90.5 s): the block names the C's DRIFT_OUT on its row 9 of 9 (B2),
  0 flag rows where the C names nothing (B3); but its hold is the C's on 1 of 9 only.  5 end on
  the C's JUMP of another sensor (3723 / 6130, the block's ``mon_rule <> 0`` ends a STEP_OUT hold;
  the C keeps its DRIFT_OUT out to 3784 / 6231: st105b's L1, still there after st105); 3 end off
  the C's BACK (lr9985 T_head_left 3723 vs 3687, lr10008 T_bed_right 3723 vs 3690, T_col_back 3784
  vs 3686: the block's READMIT test is not the C's ``_pass_once_back``).  And while it holds the
  sensor the block reads it live: the C rebuilds it (``mon_M d``, st106), so the gap st106 found
  stays on those rows, and where the hold ends at the JUMP the block loses st105's JUMP hold too
  (21 / 37 um).
* B4 (``healthy``, 101.7 s): 8 records, 0 flag rows and 0 c rows moved off the C's own namings;
  dl9965 DRIFT_OUT T_spindle_rear 5695 back 5715 and dl9967 T_col_back 3116 + BLIND_OUT T_bed_right
  3505 (5e-14 um) as the C, as in st105b.
* Fresh B2-B4 (scored once; ``windows`` 88.0 s, ``healthy`` 81.6 s): 4 DRIFT_OUT named, all the
  C's on its row, 0 flag rows where the C names nothing; every hold ends on the C's next JUMP
  (6170 / 3723), the C's BACK 6231 / 3784 (0 of 4); healthy 6 records 0 flag / 0 c rows moved.
* B5: with the rule test_export_st97d + st100 7 passed, st93..st99 + counters97 + cmon82/85 +
  dep100 24 passed; PARSED_DIGEST 92997e7e... (blark parsed the block, 26.7 s); st97d's new case
  fails on 07b7fbfb (block silent where the C names DRIFT_OUT) and costs +1.0 s CPU (paired, 2
  reps: 3.39 / 3.37 -> 4.34 / 4.32 s for the module).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st106c.py events ROOT RECORD [RECORD ...]
    python benchmarks/bench_st106c.py windows ROOT RECORD [RECORD ...]
    python benchmarks/bench_st106c.py healthy ROOT RECORD [RECORD ...]
    python benchmarks/bench_st106c.py make ROOT RECORD [RECORD ...]

ROOT holds the records as bench_cmon92's ``made`` makes them (:data:`MADE_BY`; ``make`` makes them,
each once); main's block is made by :data:`MAIN`'s src (``git archive`` into ROOT/base).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st102b  # noqa: E402
import bench_st105  # noqa: E402
import bench_st105b  # noqa: E402
import bench_st106  # noqa: E402
import bench_st106b  # noqa: E402
from _cli import run_commands  # noqa: E402

MAIN = "07b7fbfb"


def _fresh() -> dict:
    """bench_st102b's :data:`FRESH` words on seeds 10119-10121 (chosen before any was simulated)."""
    return {f"{r[:2]}{int(r[2:]) + 155}": [f"seed={int(w[5:]) + 155}" if w.startswith("seed=") else w
                                           for w in words]
            for r, words in bench_st102b.FRESH.items() if int(r[2:]) <= 9966}


FRESH = _fresh()     # lr10119, dl10119, ..., lr10121, dl10121
MADE_BY = {**bench_st106b.MADE_BY, **FRESH}


def _use() -> None:
    """The benches read :data:`MADE_BY` and :data:`MAIN`."""
    bench_st105.MADE_BY = MADE_BY
    bench_st105b.MADE_BY = MADE_BY
    bench_st105b.MAIN = MAIN


def events(root: str, *records: str) -> None:
    """B1: bench_st106's ``oracle`` lines (the block's column is the tree's)."""
    _use()
    bench_st106.oracle(root, *records)


def windows(root: str, *records: str) -> None:
    """B2 / B3: bench_st105b's ``windows`` against :data:`MAIN`."""
    _use()
    bench_st105b.windows(root, *records)


def healthy(root: str, *records: str) -> None:
    """B2 - B4 on the healthy stream: bench_st105b's ``healthy`` against :data:`MAIN`."""
    _use()
    bench_st105b.healthy(root, *records)


def make(root: str, *records: str) -> None:
    """The records, as bench_cmon92's ``made`` (model mlr)."""
    from bench_cmon92 import made

    for record in records:
        made(Path(root).resolve(), record, "mlr", MADE_BY)
        print("made", record, flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"events": events, "windows": windows, "healthy": healthy, "make": make},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
