"""The ST's one-out hold past a window of its ``BLIND_OUT`` as the C's ``_follow_field`` (st107c, issue 34).

st107 (bench_st107.py, its rule in BASE) traced its one gap on fresh dl10127 (the C's ``JUMP`` T_amb
6131 beside the ``BLIND_OUT`` T_bed_right of 6130): from 6141 the block holds T_bed_right alone as the
C and judges the set without it; at 6152 two judged sensors reach that set's warning band
(``MON_FOLLOW_OTHERS`` 2) and the one-out hold's own stop (st96 / st99: "where the C could act")
ends the hold, where the C keeps T_bed_right out and names nothing: after rows 0.016 .. 0.089 um.

WHAT THE C DOES (watch.py, the served ``Judgement._follow_field`` it ports).  A ``BLIND_OUT`` is a
drift exclusion (``_by_drift``: ``by_field``, ``since`` = its row).  With one out by the field the
drift judgement's level is the alarm band (``field = ALARM``), so ``MON_FOLLOW_OTHERS`` sensors at
the warning band move nothing there; they move ``_follow_field`` only: it lets the sensor back
(``FOLLOWED``, a new thermal state) while ``count - since <= window``, and clears ``since`` past it.
Past a window of its exclusion the C keeps the sensor out and names nothing for that count.

RULE (src: st_watch.py; no key, no constant).  The one-out hold's warning-band stop
(``mon_warned >= MON_FOLLOW_OTHERS``) only within ``MON_WINDOW`` rows of the hold's exclusion
(``mon_hsince``, set where the hold starts; the block's ``mon_count`` and the C's ``count`` differ by
one on both sides).  Past them the hold goes on as the C's.  The alarm-band stop and the stepped
error's stop are unchanged (the C may act there: ``_drift`` with ``field = ALARM``), so no
``DRIFT_OUT`` is followed (st106's class stays out).  Within the window the stop stays (the C's
``FOLLOWED`` return is not ported: the block ends its judgement there, as on BASE).  Not st107's
rule (two outs held at once, in BASE) nor a refused one: st105b / st106c's patches (lone-fault
rebuild, DRIFT_OUT return) are not touched.

BAR (committed before any score of this rule, and before fresh lr/dl 10178-10180 are made; scored
once).  Tree = this branch, BASE = :data:`MAIN`'s block (02d5ff8f), the C beside; windows, events,
hold / after rows and COVERED as bench_st107 (its ``score`` / ``healthy``, run here with this MAIN
and these records).

* B1 dl10127's C ``JUMP`` T_amb 6131 (covered): max|C - tree| <= 1e-9 um on its hold rows and its
  after rows.
* B2 every other C ``JUMP`` event of the records below (st106's 18 among them): max|C - tree| <=
  max|C - BASE| + 1e-9 um on its row before, hold rows and after rows; every covered event other
  than dl10127's: no further from the C than on BASE either; the healthy streams (bench_st105's
  ``healthy`` records lr/dl 9964-9967, and fresh lr/dl 10178-10180's): no row with |C - tree| >
  |C - BASE| + 1e-9 um.
* B3 0 rows (windows, healthy) where the tree flags, its (flag, rule, sensor) not BASE's, and the C
  names nothing on that row.
* B4 the ST modules pass, ``PARSED_DIGEST`` re-asked (blark parses the block); a test (<= ~3 s CPU,
  on test_export_st100's fixtures) that fails on BASE.
* Records: bench_st107's seen (dl9975, lr9985 dl9964 lr9964 lr9966 lr9967 dl9966 dl10007 lr10007
  lr10008, lr/dl 10013-10015) and its fresh lr/dl 10127-10129 (now seen: dl10127 built this rule);
  healthy lr/dl 9964-9967.  Fresh lr/dl 10178-10180 (bench_st102b's words, seeds +214; made by
  bench_cmon92's ``made``): windows and healthy, B2 / B3 (and B1's "no further" for any covered
  event), scored once.
* KEPT where B1-B4 hold on seen and fresh; else REFUSED (src reverted, the rule in
  benchmarks/st107c_rule.patch).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st107c.py score ROOT RECORD [RECORD ...]
    python benchmarks/bench_st107c.py healthy ROOT RECORD [RECORD ...]
    python benchmarks/bench_st107c.py make ROOT RECORD [RECORD ...]

As bench_st107's commands, with :data:`MAIN` 02d5ff8f (ROOT/base made from it, so a ROOT of its own)
and the fresh records below.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st102b  # noqa: E402
import bench_st107  # noqa: E402
from _cli import run_commands  # noqa: E402

MAIN = "02d5ff8f"


def _fresh() -> dict:
    """bench_st102b's :data:`FRESH` words on seeds 10178-10180 (chosen before any was simulated)."""
    return {f"{r[:2]}{int(r[2:]) + 214}": [f"seed={int(w[5:]) + 214}" if w.startswith("seed=") else w
                                           for w in words]
            for r, words in bench_st102b.FRESH.items() if int(r[2:]) <= 9966}


FRESH = _fresh()     # lr10178, dl10178, ..., lr10180, dl10180
bench_st107.MAIN = MAIN
bench_st107.MADE_BY = {**bench_st107.MADE_BY, **FRESH}


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    commands = {"score": bench_st107.score, "healthy": bench_st107.healthy, "make": bench_st107.make}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
