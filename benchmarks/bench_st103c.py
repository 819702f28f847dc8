"""The ST block serves the C's fallback law set while it holds a JUMP (st103c, issue 34).

st103b (bench_st103b.py, KEPT): the block serves the C's fallback set on the held reading while
it holds a ``BLIND_OUT``.  Its "not clean" class, seen dl9964 and fresh lr9985 T_table: the C's
``JUMP`` of a sensor no other predicts holds it out to its ``BACK`` at its last reading in,
serving its fallback set (5 on dl9964); the block holds it too (st101's ``mon_jheld``) but read
it live and summed the model's laws: 8.4 .. 33 um apart on those rows, and the gap carried by
the guard's rate limit into the ``BLIND_OUT`` hold that follows (29.7, 18.8, 9.0 um).

RULE (src: st.py, no key; on wherever the export has a monitor and fallbacks): while the block
holds a sensor by its jump (``mon_jheld`` >= 0; a ``BLIND_OUT`` hold, ``mon_held``, first) the
model reads it at ``mon_base + mon_jlast`` and the outputs sum its set ``MON_FALLBACK_SET``
(``serving_k`` the sensor served): st103b's path, one more holder.

WINDOWS: bench_st103b's (st102b's rule, the ``mon_stop_row`` / ``mon_lost`` gate, per sensor no
other predicts rows onset .. back + 60).  JUMP-HOLD ROWS: the rows where the tree's block has
``mon_jheld`` >= 0.  A REACHED JUMP HOLD: a window with JUMP-hold rows whose first one the C
names ``JUMP`` of the same sensor within bench_st101.NEAR rows.  BLIND_OUT hold rows, reached
and clean as bench_st103b.  Main: a8719dae's block (st103b's st.py), stepped beside.

SEEN, before this bar (scratch trace, dl9964 T_table, the rule in src): rows 6129-6141 (the C's
``JUMP`` .. before its ``BACK`` 6142, the block's ``mon_jheld`` 11 there) max|C - ST| 5.3e-14 um
(main 8.4 .. 33.2); the ``BLIND_OUT`` hold from 6143 0 .. 5.7e-14 on its first rows (main 39).

BAR (committed before fresh lr/dl 10007-10009 are simulated; scored once):

* S1 seen dl9964 and lr9985 T_table: max|C - ST| <= 1e-6 um on every JUMP-hold row (main 30-33);
* S2 seen dl9964 and the rest of st102b's records (lr9964-9967, dl9965-9967): every clean reached
  ``BLIND_OUT`` hold <= 1e-12 um on its hold rows; 0 rows where the tree's (mon_flag, mon_rule,
  mon_sensor) differs from main's (so st102b's 17 stay silent as the C: the rule touches the
  model's inputs only);
* S3 the healthy streams of st102b's 8 records: 0 rows outside the block's holds (``BLIND_OUT``
  and JUMP) whose c differs from main's (bitwise), 0 flag rows differing;
* S4 fresh lr/dl 10007-10009: every reached JUMP hold max|C - ST| <= 1e-6 um on its JUMP-hold rows
  (VOID under 3 reached: said, the verdict resting on S1-S3); 0 flag rows differing from main.

Measured (2026-12-07, 2 cores shared, load 2-7; the rule = 0dd50736's src, unchanged after the
fresh score; BAR 0dd50736, unchanged; VERDICT KEPT: S1-S4 met).  Main's block, fixed after the bar
(18760083) while the fresh run ran: at 0dd50736 it was a8719dae's st.py on the plain model (no
fallback laws: 9fd4ff7d's serving), now a8719dae's export (:func:`main_block`); the tree's columns
are the same in both; the numbers below are the fixed main's.

* S1 MET (``score /tmp/st103c/seen dl9964 lr9985``, 39.6 s CPU): T_table's JUMP-hold rows max|C -
  ST| dl9964 5.3e-14 um on 13 rows (main 33), lr9985 3.6e-14 on 12 (main 30); their ``BLIND_OUT``
  hold after it 8.5e-14 / 5.7e-14 (main 30 / 18: the rate limit carried the jump hold's gap).
* S2 MET: clean reached ``BLIND_OUT`` holds 10 of 10 (dl9964, lr9985) and 12 of 12 (``score
  /tmp/st103c/seen lr9964 lr9965 lr9966 lr9967 dl9965 dl9966 dl9967``, 114.3 s CPU; gate NOT scored
  lr9965, dl9965, dl9967 as bench_st103b) <= 1.4e-13 um, main the same; flag rows differing from
  main 0 on every window and lead-in.  There, 4 more reached JUMP holds: lr9966 T_amb 8.2e-14 (main
  2.1), T_motor 5e-14 (8.5), T_table 5.7e-14 (27), dl9966 T_table 6.4e-14 (35).
* S3 MET (``healthy /tmp/st103c/seen`` the 8, 138.0 s CPU): 0 rows outside the holds whose c
  differs from main's, 0 flag rows differing; hold rows on lr9964 / dl9964 / dl9967 (10 / 11 / 10)
  <= 7.1e-14 um, main the same.
* S4 MET, scored once (``score /tmp/st103c/fresh lr10007 dl10007 lr10008 dl10008 lr10009
  dl10009``, 92.1 s CPU with the simulation; main's columns again with the fixed main on the 3
  scored, 45.2 s): gate NOT scored dl10008 (``mon_stop_row`` 668), lr10009 and dl10009
  (``mon_lost``); 17 windows, 4 reached JUMP holds (lr10008 T_amb, T_spindle_front, T_motor,
  T_table), max|C - ST| 5e-14, 4.3e-14, 4.4e-14, 5.3e-14 um on their JUMP-hold rows (main 0.42, 33,
  9.9, 30); 6 clean reached ``BLIND_OUT`` holds <= 8.9e-14 (main the same); flag rows differing 0.
* Not reached (the C names ``JUMP``, the block holds none there; not traced), main alike: fresh
  lr10007 T_table (31 um on the window's rows), T_amb (2.0), dl10007 T_amb (3.2), lr10008 T_xdrive
  (8.0); seen lr9985 T_spindle_rear (21), lr9967 T_spindle_front (29), T_motor (5.5), T_xdrive
  (6.4), lr9964 / dl9964 / dl9966 T_amb (3.9 / 4.3 / 1.1).  Reached, but the rows after the JUMP
  hold apart (not traced): seen lr9966 T_table 40 um, dl9966 T_table 36 (main the same).  The
  lead-ins of fresh lr10007 / dl10007: 11 c rows differ from main; on lr10007 (``healthy
  /tmp/st103c/fresh lr10007``, after the score, 13.3 s CPU) they are 11 hold rows, max|C - ST|
  3.7e-14 um (main 0.32), 0 rows outside the holds differing, 0 flag rows (dl10007 not run).
* Size: the ST 2226 -> 2234 lines; ``N_LAWS`` as main's.  The ST tests (tests/shell/test_export_st*.py,
  test_export_step99.py, test_export.py: 54) passed in 122.8 s wall (load 2-7; CPU not measured).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st103c.py score ROOT RECORD [RECORD ...]
    python benchmarks/bench_st103c.py healthy ROOT RECORD [RECORD ...]

ROOT holds the records as bench_cmon92's ``made`` makes them (each once: bench_st102b's FRESH,
bench_st103's, bench_st103b's, this :data:`FRESH`).  ``score``: per record the size line and the
gate line, then per window: the C's first ``JUMP`` and the block's first JUMP-hold row, reached,
JUMP-hold rows and max|C - ST| on them (main's), ``BLIND_OUT`` hold rows (clean) and theirs, the
other rows, flag rows differing from main.  ``healthy``: per record the whole healthy stream:
rows outside the holds whose c differs from main's, hold rows and max|C - ST| on them (main's),
flag rows differing.
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st101  # noqa: E402
import bench_st102  # noqa: E402
import bench_st102b  # noqa: E402
import bench_st103b  # noqa: E402
from _cli import run_commands  # noqa: E402

MAIN = "a8719dae"     # main: st103b's block (the BLIND_OUT hold served, the JUMP hold not)
TOL = bench_st103b.TOL


def _fresh() -> dict:
    """bench_st102b's :data:`FRESH` words on seeds 10007-10009 (chosen before any was simulated)."""
    return {f"{r[:2]}{int(r[2:]) + 43}": [f"seed={int(w[5:]) + 43}" if w.startswith("seed=") else w
                                          for w in words]
            for r, words in bench_st102b.FRESH.items() if int(r[2:]) <= 9966}


FRESH = _fresh()     # lr10007, dl10007, ..., lr10009, dl10009
MADE_BY = {**bench_st103b.MADE_BY, **FRESH}


def main_block(deployed) -> str:
    """``deployed``'s block as :data:`MAIN` exports it: its st.py (loaded as bench_st103b's
    :func:`~bench_st103b.main_block` does) on the system with the fallbacks' laws
    (fallbacks.py ``with_st_fallbacks``, unchanged since)."""
    from thermocomp.apps.deploy.export import state_space
    from thermocomp.apps.deploy.export.fallbacks import with_st_fallbacks
    from thermocomp.apps.deploy.export.watch import monitor_fields

    ss = state_space(deployed)
    watch = monitor_fields(deployed, list(ss.inputs)).get("monitor", {})
    with_st_fallbacks(ss, deployed, watch)
    return bench_st103b.st_module(MAIN).function_block(ss, watch)


def _rows(kept, part):
    """bench_st103b's :meth:`~bench_st103b.Three.rows`, each with the tree's ``mon_jheld``."""
    for r in kept.rows(part):
        yield (*r, int(kept.tree.vars["mon_jheld"]))


def _gap(r, i: int = 0) -> float:
    return float(np.max(np.abs(r[2] - r[i])))


def _top(values) -> str:
    return f"{max(values):.2g}" if values else "-"


def _window(kept, names, sensor: str, frame, start: int) -> dict | None:
    """The window's line (module doc); its counts."""
    from thermocomp.apps.deploy.export.watch import BLIND_OUT, JUMP

    df, back = bench_st102.dropped(frame, sensor, start)
    if back + 61 >= len(df):
        return None
    rows = list(_rows(copy.deepcopy(kept), df.iloc[start:back + 61]))
    at = list(enumerate(rows, start))
    c = next(((i, r[3][1]) for i, r in at if r[3][0] == JUMP), None)
    st = next(((i, r[7]) for i, r in at if r[7] >= 0), None)
    reached = bool(c and st and st[1] == c[1] and abs(st[0] - c[0]) <= bench_st101.NEAR)
    jump = [r for r in rows if r[7] >= 0]
    held = [r for r in rows if r[6]]
    rest = [r for r in rows if r[7] < 0 and not r[6]]
    cb = next(((i, r[3][1]) for i, r in at if r[3][0] == BLIND_OUT), None)
    sb = next(((i, r[4][2]) for i, r in at if r[4][0] and r[4][1] == BLIND_OUT), None)
    into = next((k for k, r in enumerate(rows) if r[6]), len(rows))
    clean = bool(cb and sb and sb[1] == cb[1] and abs(sb[0] - cb[0]) <= bench_st101.NEAR
                 and max([_gap(r) for r in rows[:into]], default=0.0) <= TOL)
    flags = sum(r[4] != r[5] for r in rows)
    show = [f"{x[0]} {names[x[1]]}" if x else "-" for x in (c, st)]
    print(f"  dropped {sensor}: C JUMP {show[0]}, block jump hold {show[1]}, reached {reached}; "
          f"jump-hold rows {len(jump)}: max|C-ST| {_top([_gap(r) for r in jump])} (main "
          f"{_top([_gap(r, 1) for r in jump])}); BLIND_OUT hold rows {len(held)} (clean {clean}): "
          f"{_top([_gap(r) for r in held])} (main {_top([_gap(r, 1) for r in held])}); other rows "
          f"{len(rest)}: {_top([_gap(r) for r in rest])} (main {_top([_gap(r, 1) for r in rest])}); "
          f"flag rows differing from main {flags}", flush=True)
    return {"reached": reached, "jump": max([_gap(r) for r in jump], default=0.0), "clean": clean,
            "held": max([_gap(r) for r in held], default=0.0), "flags": flags}


def score(root: str, *records: str) -> None:
    """The ``score`` lines (module doc)."""
    tally = {"windows": 0, "reached": 0, "met": 0, "clean": 0, "clean_met": 0, "flags": 0}
    for got in bench_st103b.windows(root, records, _window, MADE_BY, main_block):
        tally["windows"] += 1
        tally["flags"] += got["flags"]
        tally["reached"] += got["reached"]
        tally["met"] += got["reached"] and got["jump"] <= TOL
        tally["clean"] += got["clean"]
        tally["clean_met"] += got["clean"] and got["held"] <= 1e-12
    print(f"total: {tally['windows']} windows, {tally['reached']} reached JUMP holds, {tally['met']} "
          f"with max|C-ST| <= {TOL:g} um on their jump-hold rows; {tally['clean']} clean reached "
          f"BLIND_OUT holds, {tally['clean_met']} <= 1e-12 um; flag rows differing from main "
          f"{tally['flags']}", flush=True)


def healthy(root: str, *records: str) -> None:
    """The ``healthy`` lines (module doc)."""
    for record in records:
        _, ss, frame, _, _, tree, main = bench_st103b._cell(root, record, MADE_BY, main_block)
        rows = list(_rows(bench_st103b.Three(ss, tree, main), frame))
        out = [r for r in rows if not r[6] and r[7] < 0]
        held = [r for r in rows if r[6] or r[7] >= 0]
        print(f"  healthy: {len(rows)} rows, outside the holds c rows differing from main "
              f"{sum(bool(np.any(r[0] != r[1])) for r in out)}; hold rows {len(held)}: max|C-ST| "
              f"{_top([_gap(r) for r in held])} (main {_top([_gap(r, 1) for r in held])}) um; flag rows "
              f"differing {sum(r[4] != r[5] for r in rows)}; max|C-ST| elsewhere "
              f"{_top([_gap(r) for r in out])} um", flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"score": score, "healthy": healthy}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
