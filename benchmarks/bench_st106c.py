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
