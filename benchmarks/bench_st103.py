"""The ST block's correction after the ``BACK`` of a ``BLIND_OUT`` hold, against the C (st103, issue 34).

st102b (bench_st102b.py, traced after its score): dl9964 T_spindle_rear (the C's ``BLIND_OUT``
6156, no jump at the back row 6170, the C's ``BACK`` 6175) has max|C - ST| 5.07 um over the 20 rows
from the C's ``BACK``, on main and on d85f1799 alike; the brief read it as the block not following
the C at that hold's ``BACK``.

TRACE (seen: dl9964, now spent; ``trace /tmp/st103/seen dl9964``, rows stepped one by one before
this bar was written).  The block follows the C at that ``BACK``: its hold (``mon_held``) ends on
the C's row 6175, neither has a jump to undo (the C's ``jumps`` 0, the block's ``mon_jn`` 0), and
max|C - ST| is 2.1e-14 .. 3.6e-14 um on 6175-6178; at 6179 both name ``SETTLED T_spindle_rear``
(the C re-references it by -6.09, the block too: |C - ST| 1.4e-14); at 6180 both name a second
``BLIND_OUT T_spindle_rear``, and from there |C - ST| is 4.58 .. 5.23 um: the 5.07 um lies inside
the C's second hold, as 4.21 .. 4.66 um does on every row of its first (6156-6174).  Inside a hold
the C (watch.py ``_rebuilt``, statespace ``serving``) reads the sensor at its last reading in and
sums its fallback model's law set (dl9964's monitor: ``fallback_set`` 3 for T_spindle_rear; every
sensor no other predicts has one in the lr and dl records); the ST block reads the sensor live and
sums the model's laws (st.py: ``exported_files`` builds the ST's state space without the monitor,
so without :func:`~thermocomp.apps.deploy.export.fallbacks.with_fallbacks`).  Measured on the
same rows: the C with its ``serving`` forced to 0 (the model's laws, the held reading) against the
block with the held reading (:data:`HELD`: the model reads ``mon_base + mon_jlast`` of the sensor
the block holds by ``BLIND_OUT``, three lines after st.py's ``uu`` loop; not in src): <= 7.1e-14
um on 6150-6199; the C against the C at serving 0: 4.21 .. 5.23 um on every hold row, 0 elsewhere.
The whole gap is the fallback model the ST does not carry (and the held reading).  The held
reading alone is no step toward the C: on 6170-6174 (the sensor back, the C still holding it) the
live block is 0.063 .. 0.166 um off the C, the held one 4.25 .. 4.33 um.

No rule is built here: the release the brief asks for is already the C's, and what makes the rows
after it differ (the fallback law sets in the ST, with their serving and guard bound per set) is
another mechanism than st101/st102's hold path.  The brief's S1-S4 are for such a rule; they are
not scored.

PREDICTION (the trace's bar, committed before fresh lr/dl 9973-9975 are simulated; scored once).
Windows: st102b's rule, its gate read right (``mon_stop_row`` 0 and not ``mon_lost`` at the onset,
the healthy stream alone), per sensor no other predicts :func:`bench_st102.dropped`.  A REACHED
BACK: the C's first ``BLIND_OUT`` of the window named by the block (sensor, +-2 rows) and the C's
``BACK`` of that sensor after it in the window.  Over the 20 rows from it (fewer at the window's
end):

* P1 the block's hold ends on the C's ``BACK`` row, in every reached BACK;
* P2 max|C - ST| <= 1e-6 um on the rows where the C serves the model's laws (``serving`` 0);
* P3 max|C0 - ST held| <= 1e-6 um on all the rows (C0: the C at serving 0; ST held: :data:`HELD`);
* reported, not scored: the brief's S4 (max|C - ST| <= 1e-6 um on all 20 rows), the rows where
  the C serves a fallback set, max|C - C0| on them.

P1-P3 met: the trace explains every reached BACK (TRACED); one not met: the explanation is
incomplete there, said.  VOID: fewer than 3 reached BACKs over the scored fresh records (dl9964
reached 1 of its 7 windows): said, the trace resting on the seen rows.  Seen (``trace
/tmp/st103/seen dl9964``, 22.4 s CPU): dl9964 T_spindle_rear P1 6175, P2 <= 3.6e-14, P3 <= 6.4e-14
(15 of its 20 rows serving a fallback set, max|C - C0| 5.1 um); no other of its windows reached.

Scored once (2026-12-07, 2 cores shared, load 8.5-9.8; the tree = 4a21da2b's src, no change; the
prediction a0e623a6 unchanged; ``trace /tmp/st103/fresh lr9973 dl9973 lr9974 dl9974 lr9975
dl9975``, 99.4 s CPU with the simulation).  The gate scored all 6; 34 windows, 17 with the C's
first ``BLIND_OUT`` named by the block, 2 reached BACKs (both dl9975): VOID (under 3).  VERDICT
TRACED (no src change), on the seen rows; the fresh two said below.

* dl9975 T_xdrive: ``BLIND_OUT`` 6158, the C's ``BACK`` 6201, the block's hold ended 6201 (P1 met);
  20 rows, none serving a fallback set: max|C - ST| 5.0e-14 (P2 met), max|C0 - ST held| 5.0e-14
  (P3 met); the brief's S4 met there.
* dl9975 T_col_back (the C's ``BLIND_OUT`` is of T_table, 6128, named alike): the C's ``BACK`` of
  T_table 6138, the block's hold ended 6129: P1 NOT met; 20 rows, 6 serving a fallback set: max|C -
  ST| 5.1 um (serving 0: 3.2e-14, P2 met), max|C0 - ST held| 0.91 um: P3 NOT met; S4 not met.
  Traced after the score (rows 6125-6160, seen now): at 6129 the bumped T_col_back jumps while
  T_table is held; the C takes it out as its second out (``JUMP``, held to its ``BACK`` at 6144,
  serving its fallback set 5), the block flags ``JUMP T_col_back``, which ends its hold and its
  judgement (``mon_lost``: anything named in a hold, st95b's rule).  The 0.91 um is on 6138-6143,
  the C holding T_col_back at its last reading in, the block reading it re-referenced by its
  step; from 6144 |C - ST| <= 3.2e-14.  A second class, not the fallback's: a jump of another
  sensor no other predicts while a ``BLIND_OUT`` is held (st101 holds one only where none is).
* Seen, the rest of st102b's records (``trace /tmp/st103/seen lr9964 lr9965 lr9966 lr9967 dl9965
  dl9966 dl9967``, 96.5 s CPU): no reached BACK (gate: lr9965 2470, dl9965 5696, dl9967 3117 not
  scored, as st102b's traced gate read right).
* Size of the next step (seen dl9964, its MLR): the ST's state space has 1 law; with the monitor's
  fallbacks (``state_space(..., monitor=True)``, the C's) 8, in law sets 0-7.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st103.py trace ROOT RECORD [RECORD ...]

ROOT holds the records as bench_cmon92's ``made`` makes them (each once; bench_st102b's FRESH and
this :data:`FRESH`).  Per record the gate line, then per dropped window: the C's first
``BLIND_OUT`` and the block's, the C's ``BACK`` of that sensor and the block's hold's end, and over
the 20 rows from the C's ``BACK``: rows counted, rows serving a fallback set, max|C - ST| (all
rows, rows at serving 0), max|C0 - ST held|, max|C - C0| (fallback rows).
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
from _cli import run_commands  # noqa: E402

AFTER = bench_st102.AFTER     # rows from the C's BACK
# st.py's model inputs: after the loop that writes uu, the sensor the block holds by BLIND_OUT
# read at its last reading in (the C's _rebuilt of one no other predicts): the trace's variant
ANCHOR = """            uu[j] := 0.0;
        END_IF;
    END_FOR;
"""
HELD = """    IF mon_held >= 0 AND mon_held_set >= 0 THEN
        uu[MON_INPUT[mon_held]] := mon_base[mon_held] + mon_jlast;
    END_IF;
"""


def _fresh() -> dict:
    """bench_st102b's :data:`FRESH` words on seeds 9973-9975 (chosen before any was simulated)."""
    return {f"{r[:2]}{int(r[2:]) + 9}": [f"seed={int(w[5:]) + 9}" if w.startswith("seed=") else w
                                         for w in words]
            for r, words in bench_st102b.FRESH.items() if int(r[2:]) <= 9966}


FRESH = _fresh()     # lr9973, dl9973, ..., lr9975, dl9975


class Four:
    """The block, the block with :data:`HELD`, the C and the C serving the model's laws (C0),
    stepped together from the states they are in."""

    def __init__(self, ss, block: str):
        from test_export import StructuredText
        from thermocomp.apps.deploy.export import Simulator

        assert block.count(ANCHOR) == 1, "st.py's uu loop moved: HELD has no place"
        self.ss, self.first = ss, True
        self.fb = StructuredText(block)
        self.held = StructuredText(block.replace(ANCHOR, ANCHOR + HELD))
        self.sim, self.c0 = Simulator(ss), Simulator(ss)
        for sim in (self.sim, self.c0):
            sim.reset()
        self.c0.watch.serving = lambda: 0

    def rows(self, part):
        """Per row ``(ST c, ST held c, C c, C0 c, the C's (rule, k), its serving, the block's
        (flag, rule, k), mon_held)``."""
        U, t = part[self.ss.inputs].to_numpy(float), part["time"].to_numpy(float)
        for i in range(len(part)):
            st, held = (fb(U[i], t[i], self.first) for fb in (self.fb, self.held))
            c, c0 = (sim.step(U[i], t[i]) for sim in (self.sim, self.c0))
            self.first = False
            w, v = self.sim.watch, self.fb.vars
            yield (st, held, c, c0, (int(w.rule), int(w.sensor)), int(self.sim.serving),
                   (bool(v["mon_flag"]), int(v["mon_rule"]), int(v["mon_sensor"])), int(v["mon_held"]))


def _top(values) -> str:
    return f"{max(values):.2g}" if values else "-"


def _window(kept: Four, names, sensor: str, frame, start: int) -> None:
    """The dropped window's line (module doc)."""
    from thermocomp.apps.deploy.export.watch import BACK, BLIND_OUT

    df, back = bench_st102.dropped(frame, sensor, start)
    if back + 61 >= len(df):
        return
    run = copy.deepcopy(kept)
    rows = list(run.rows(df.iloc[start:back + 61]))
    c = next(((i, r[4][1]) for i, r in enumerate(rows, start) if r[4][0] == BLIND_OUT), None)
    st = next(((i, r[6][2]) for i, r in enumerate(rows, start) if r[6][0] and r[6][1] == BLIND_OUT), None)
    named = bool(c and st and st[1] == c[1] and abs(st[0] - c[0]) <= bench_st101.NEAR)
    cback = next((i for i, r in enumerate(rows, start) if c and i > c[0] and r[4] == (BACK, c[1])), None)
    ended = next((i for i, r in enumerate(rows, start) if st and i > st[0] and r[7] < 0), None)
    show = [f"{x[0]} {names[x[1]]}" if x else "-" for x in (c, st)]
    said = f"  dropped {sensor}: C BLIND_OUT {show[0]}, block {show[1]}, named {named if c else '-'}"
    if not (named and cback):
        print(f"{said}; no reached BACK (C BACK {cback or '-'})", flush=True)
        return
    after = rows[cback - start:cback - start + AFTER]
    diff = [float(np.max(np.abs(r[2] - r[0]))) for r in after]
    model = [d for d, r in zip(diff, after) if r[5] == 0]
    held = [float(np.max(np.abs(r[3] - r[1]))) for r in after]
    fell = [float(np.max(np.abs(r[2] - r[3]))) for r in after if r[5] != 0]
    print(f"{said}; C BACK {cback}, block's hold ended {ended or '-'} (P1 {ended == cback}); "
          f"{len(after)} rows, {len(fell)} serving a fallback set: max|C-ST| {_top(diff)} (serving 0: "
          f"{_top(model)}), max|C0-ST held| {_top(held)}, max|C-C0| {_top(fell)} um", flush=True)


def trace(root: str, *records: str) -> None:
    """The ``trace`` lines (module doc)."""
    bench_st102.FRESH = {**bench_st102b.FRESH, **FRESH}
    for record in records:
        ss, frame, lead, start, cid, names, block, _ = bench_st102._cell(root, record)
        kept = Four(ss, block)
        for _ in kept.rows(frame.iloc[:start]):
            pass
        v = kept.fb.vars
        stop, lost = int(v["mon_stop_row"]), bool(v["mon_lost"])
        print(f"{record} {cid}: {len(frame)} rows ({lead} lead-in), onset {start}; gate: mon_stop_row "
              f"{stop}, mon_lost {lost}: {'NOT scored' if stop or lost else 'scored'}", flush=True)
        for sensor in [n for n, p in zip(names, ss.monitor["predictable"]) if not p]:
            _window(kept, names, sensor, frame, start)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
