"""The ST block follows the C's silent re-reference of a sensor it holds by ``BLIND_OUT`` (st102, issue 34).

st101 (bench_st101.py, applied in ac04b0e9 over its refused bar): one new extra flag on fresh
lr9948, row 3733 ``JUMP T_table``.  Traced (seen, before the bar: its rows stepped one by one): the bump's
rise jumped twice (3684, 3686), held by the block (``mon_jheld``) to the C's ``BACK`` (3696) and
undone; the C's ``BLIND_OUT`` of T_table (3697) named by the block, which holds it out
(``mon_held``).  The bump's fall jumps at 3729 and 3733: the C (watch.py ``_step``: a lone jump
of a sensor not active, no other predicting it, ``blind_jump``) re-references it by its whole step
(``ref0`` kept from its first jump, ``jumps`` counted, ``calm`` 0), flags nothing, and names its
``BACK`` at 3743 (calm 10, its wait), its jumps undone there (``_undone``: two); main's block flags
``JUMP`` at both, ends its judgement (``mon_lost``) and keeps the re-reference (max|C - ST| 6.44 um
after the C's ``BACK``).

RULE (REFUSED: kept as benchmarks/st102_rule.patch, ``git apply`` it on d85f1799 to measure it;
st_watch.py ``BLOCK``, no key; on where the block holds a ``BLIND_OUT``, ``MON_BLIND_JUDGE``):
a lone jump (no other reading jumping, missing or beyond range) of the sensor the block holds out
by its ``BLIND_OUT`` (``mon_held``, its set ``mon_held_set``), one the C holds out for a jump
(``MON_JUMP_HELD``, cmon87's ``blind_jump``), is the C's silent re-reference: not flagged, no rule
named (no spike's return read: the C has none of one no other predicts), re-referenced by its
whole step, counted (``mon_jn``, the shift before the first ``mon_jshift0``), its calm started
again (``mon_calm``, the C's ``calm`` 0) and its settle age too; the hold and the judgement go on.
At the hold's ``BACK`` (st95b/st96's) the C's ``_undone``: st101's undo (its jumps undone where it
jumped more than once, or where its reading on the reference before them is nearer its last
reading in, ``mon_jlast``: the row before the ``BLIND_OUT``), written once for both holds.

BAR (the brief's, st100b/st101's S1-S4; committed before fresh lr/dl 9961-9963 are simulated):

* S1 seen, named / silent as the C on its row (+-2 rows): lr9948 T_table 3733 (and 3729) silent
  as the C; st101's 17 ``BLIND_OUT`` after the block's own JUMP (lr9917 4, dl9917 4, lr9896 3698,
  dl9894 6142, lr9790 4, dl9794 2, dl9845 6150) still named.  lr9917 T_amb 3734, named by the brief
  as a sibling, was traced before this bar and is NOT of the class: the C took T_col_back out at
  3698 (``DRIFT_OUT`` of one others predict, where the block says ``mon_stop``: it cannot follow
  the C's set) and T_amb at 3729 as the second out for its jump (the C's flag, the block's too);
  the block holds nothing there.  The rule leaves it as main; its clause is reported, not scored.
* S2 every ``BLIND_OUT`` named on main (d85f1799) stays named, the same rows.
* S3 bench_st100's healthy sets (32 frames, bench_st101's): 0 rows where the block's (flag, rule,
  sensor) differs from main's.
* S4 fresh :data:`FRESH` (lr/dl 9961-9963), scored once, planted as chosen here before any was
  drawn: bench_st101's jump (the first ``MON_JUMP_HELD`` sensor, +3 jump limits for 2 rows, 100
  rows before the onset), then per sensor no other predicts (a) test_export_st96's bump (+6 C)
  from the onset and (b) :func:`dropped`: the same rise and hold, then back in one row (the
  sensor jumps back while the C holds it out).  >= 75 % of the C's first ``BLIND_OUT`` of each
  window named (sensor, +-2 rows) and 0 extra flags not main's (a block flag whose rule and sensor
  the C does not raise within 2 rows).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st102.py cases ROOT RECORD [RECORD ...]
    python benchmarks/bench_st102.py healthy ROOT RECORD [RECORD ...]
    python benchmarks/bench_st102.py planted ROOT RECORD [RECORD ...]

ROOT holds the records as bench_cmon92's ``made`` makes them (each once; bench_st100's generators,
bench_st101's and this :data:`FRESH`).  bench_st101's lines (its ``Walk``: the block, main's block
d85f1799 and the C), each window then once more as :func:`dropped`: the C's first ``BLIND_OUT``,
the block's, main's, named; on the row it jumps back the C's, the block's and main's (flag, rule);
the C's ``BACK`` of that sensor after it and the block's hold's end; max|C - ST| (um) over the 20
rows from the C's ``BACK``; extra flags.  ``healthy`` and ``planted`` as bench_st101's.

Measured (2026-12-06, 2 cores shared, load 8-19; the rule = bbeda32b's src, the patch, unchanged
after the fresh score; VERDICT REFUSED: S1-S3 met, S4's 0 new extra flags met, S4 named not met):

* S1 MET (``planted /tmp/st102/seen101f lr9948``, st101's fresh, now seen): lr9948 T_table's fall
  jumps 3729 / 3733 silent as the C (main: ``JUMP`` at both); the block held it to the C's
  ``BACK`` at 3743, its two jumps undone there; max|C - ST| on the rows after it 6.44 um (main) ->
  <= 5.5e-14; that window's extra flags main 2 -> 0.  st101's 17 still named on the C's row:
  lr9917 4 (3685, 3686, 3684, 3681), dl9917 4 (6132, 6133, 6132, 6131), lr9896 T_table 3698,
  dl9894 T_table 6142, lr9790 4 (3684, 3681, 3685, 3686), dl9794 2 (6130, 6131), dl9845 T_table
  6150.  lr9917 T_amb (not the class, above): extra flags 7, main 7, 3734 as main.
* S2 MET: on the 11 seen records with windows (lr9917 dl9917 lr9896 dl9894 lr9893 cr9895 dl9897
  lr9790 dl9794 dl9845 lr9948) every window's ``BLIND_OUT`` named by main is named by the rule on
  the same row (33 bumps, 33 dropped; planted lr9896 3 + 3).  Extra flags in those windows main 49
  -> rule 22, none new (planted lr9896: 10 -> 4); in the dropped windows the rule is silent on 21
  jumps back the C re-references silently and main flags, and flags none the C does not.
* S3 MET: 0 rows differing from main, extra flags 0 (main 0), on all 32 healthy frames (st97d's 11,
  bench_mon98's 9, seen99c's 5, lr/dl 9916-9918, fl_thermal).
* S4 fresh, scored once (``planted /tmp/st102/fresh lr9961 lr9962 lr9963``, 33.8 s CPU with the
  simulation; ``... dl9961 dl9962 dl9963``, 54.1 s): the C's first ``BLIND_OUT`` named in 0 of 38
  windows (19 bumps, 19 dropped; main 0 of 38): NOT MET; extra flags 22, main 22, new 0: met.  No
  fresh window held a ``BLIND_OUT`` in the block, so none where the rule acts: traced after the
  score (no change made): on 5 records the block's ``BLIND_OUT`` judgement stopped in the lead-in
  (``mon_stop`` at the C's ``DRIFT_OUT`` of a sensor others predict: lr9961 row 252, lr9962 1371,
  lr9963 589, dl9961 419, dl9962 2284), and the planted T_amb jump read beyond its range
  (``OFF_RANGE``, the C's too) on lr9961, lr9963, dl9961, dl9963 (dl9963: the judgement ended
  there, ``mon_lost``); no planted jump held (``holds -`` on all 6).
* CPU: ``cases`` seen 39.3 s (lr/dl9917), 87.3 s (seen99c's 5), 38.0 s (lr9790 dl9794), 25.4 s
  (dl9845); ``healthy`` 119.8 s (st97d), 66.0 s (mon98), 66.0 s (lr/dl 9916 / 9918, fl_thermal).
* Next: the fresh draw met the block's older limits before this rule's case (a drift exclusion
  of a sensor others predict ends the ``BLIND_OUT`` judgement; the +3 jump limit plant beyond
  range).  A held sensor's reading beyond its range is the C's silence too (the C reads it as
  missing, the block flags ``OFF_RANGE`` and ends: seen on lr9132 while building the test).
"""

from __future__ import annotations

import copy
import functools
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st98  # noqa: E402
import bench_st100  # noqa: E402
import bench_st101  # noqa: E402
from _cli import run_commands  # noqa: E402

BASE = "d85f1799"     # main
AFTER = 20                  # rows from the C's BACK over which max|C - ST| is said


def _fresh() -> dict:
    """bench_st100's :data:`FRESH` (bench_cmon91's lr and dl generators) on seeds 45 further."""
    return {f"{record[:2]}{int(record[2:]) + 45}": [
        f"seed={int(w[5:]) + 45}" if w.startswith("seed=") else w for w in words]
        for record, words in bench_st100.FRESH.items()}


FRESH = _fresh()     # lr9961, dl9961, lr9962, dl9962, lr9963, dl9963 (chosen before any was simulated)


def dropped(frame, sensor: str, start: int):
    """``frame`` with test_export_st96's bump of ``sensor`` from ``start``, its rise and hold, then
    back in one row (a jump); and that row."""
    from test_export_st96 import HOLD, RISE, bumped

    df, _ = bumped(frame, sensor, start)
    back = start + RISE + HOLD
    df.loc[back:back + RISE - 1, sensor] = frame.loc[back:back + RISE - 1, sensor]
    return df, back


def _cell(root: str, record: str):
    """bench_st101's ``_cell`` (main's block :data:`BASE`), :data:`FRESH` too."""
    if record not in FRESH:
        bench_st101.BASE = BASE
        return bench_st101._cell(root, record)
    made = bench_st98.cell(Path(root).resolve(), record, FRESH, BASE)
    return (made[0], made[1].reset_index(drop=True), *made[2:])


class Walk(bench_st101.Walk):
    """bench_st101's, and per row ``(max|C - ST|, the block's mon_held)`` (``kept``)."""

    def __init__(self, ss, block: str, base: str):
        super().__init__(ss, block, base)
        self.kept: list = []

    def step(self, part, first: int = 0) -> None:
        rows = self.three.rows

        def teed(p):
            for got in rows(p):
                self.kept.append((float(np.max(np.abs(got[0][0] - got[0][1]))),
                                  int(self.three.fb.vars["mon_held"])))
                yield got
        self.three.rows = teed
        try:
            super().step(part, first)
        finally:
            del self.three.rows


def _said(s) -> str:
    from thermocomp.apps.deploy.export.watch import RULES

    return RULES[s[1]] if s[1] else ("flag" if s[0] else "-")


def _dropped(kept: Walk, names, sensor: str, frame, start: int) -> None:
    """The :func:`dropped` line of ``sensor`` (module doc)."""
    from thermocomp.apps.deploy.export.watch import BACK, BLIND_OUT

    df, back = dropped(frame, sensor, start)
    if back + 61 >= len(df):
        return
    run = copy.deepcopy(kept)
    run.said, run.kept = [], []
    run.step(df.iloc[start:back + 61], start)
    c, st, main = (bench_st101._first(run.said, w, BLIND_OUT, start) for w in (2, 0, 1))
    hit = bool(c and st and st[1] == c[1] and abs(st[0] - c[0]) <= bench_st101.NEAR)
    show = [f"{x[0]} {names[x[1]]}" if x else "-" for x in (c, st, main)]
    at = run.said[back - start]
    cback = next((i for i, s in enumerate(run.said[back - start:], back) if c and s[2] == (BACK, c[1])), None)
    ended = next((i for i in range(back, back + 61) if run.kept[i - start][1] < 0
                  and run.kept[i - start - 1][1] >= 0), None)
    after = run.kept[cback - start:cback - start + AFTER] if cback else []
    diff = max((d for d, _ in after), default=np.nan)
    print(f"  dropped {sensor} (back at {back}): C BLIND_OUT {show[0]}, block {show[1]}, main {show[2]}, "
          f"named {hit if c else '-'}; at {back} C {_said((0, at[2][0]))}, block {_said(at[0])}, main "
          f"{_said(at[1])}; C BACK {cback if cback else '-'}, block's hold ended {ended if ended else '-'}, "
          f"max|C-ST| {diff:.3g} um over {AFTER} rows from the C's BACK; "
          f"{bench_st101._extra_line(run.said, names, start)}", flush=True)


def _record(root: str, record: str, plant: bool, bumps: bool = True) -> None:
    """bench_st101's lines of ``record`` (its ``_record``), then the :func:`dropped` lines."""
    kept, frame, start, names = bench_st101._record(root, record, plant, bumps, _cell, Walk)
    if not bumps:
        return
    for sensor in [n for n, p in zip(names, kept.three.ss.monitor["predictable"]) if not p]:
        _dropped(kept, names, sensor, frame, start)


def _records(root: str, *records: str, plant: bool = False, bumps: bool = True) -> None:
    """:func:`_record` of each record: the commands (module doc)."""
    for record in records:
        _record(root, record, plant, bumps)


COMMANDS = {"cases": {}, "healthy": {"bumps": False}, "planted": {"plant": True}}


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    commands = {name: functools.partial(_records, **kw) for name, kw in COMMANDS.items()}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
