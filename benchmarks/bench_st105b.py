"""The ST block follows the C's lone fault one step: its ``DRIFT_OUT`` and ``BACK`` (st105b, issue 34).

st97d made the block say where its ``BLIND_OUT`` judgement ends (``mon_stop``, ``mon_stop_row``);
st102b's gate found dl9965 (row 5696) and dl9967 (3117) stopped before the onset, the C naming 9
``BLIND_OUT`` in their windows that neither block named; st103 found dl9975's second class (a
second sensor no other predicts jumping while a ``BLIND_OUT`` is held).

TRACE (seen: dl9965, dl9967, dl9975, ``/tmp/st105b/trace.py`` steps the block and the C over the
healthy stream, the C's drift branches logged; 4b70457f's src, before this bar).

* dl9965 row 5695 (0-based; ``mon_stop_row`` 5696) and dl9967 row 3116 (3117): the field reaches
  its band, no sensor no other predicts explains it (the block's ``mon_take_set`` < 0), and the C's
  ``_lone_fault`` returns the culprit (T_spindle_rear / T_col_back, both ones the others predict)
  as resolving; its ``_within_rounding`` is False, so ``_hovers`` is not asked: the C takes it out
  by ``DRIFT_OUT`` (rebuilt by the POD: |C - ST| 1.2 / 1.9 um on the row), and lets it ``BACK`` 20
  / 12 rows later (5715 / 3128).  From there the C is all in, not in a new state, as the block.
  The block stopped for the campaign: it lacks the C's ``_lone_fault`` (which sensor, whether the
  rest are within band with it out: the set's operator without it), the veto count and the
  rounding test (the memory ``slow`` only where the culprit is within its rounding of the band).
* After it the C names on dl9967 (healthy stream) ``BLIND_OUT T_bed_right`` at 3505 (BACK 3516),
  the block silent; and the windows' ``BLIND_OUT`` st102b counted.
* dl9975 (second class): no stop in the healthy stream; in its T_col_back window the C holds
  T_table by ``BLIND_OUT`` (6128), T_col_back jumps at 6129: the C takes it out as its second
  (cmon88's second jump, the set without both solved), holds both, lets T_table back at 6138 with
  T_col_back out (its ``_pass_once_back`` in the set without T_col_back) and T_col_back at 6144.
  The block holds one ``BLIND_OUT`` and one jump, never both, and judges a ``BLIND_OUT``'s back
  with every other in: following it needs the pair's operator and bands per pair of sensors no
  other predicts, and the two-out serving.  No rule here (TRACED for that class).

RULE (src: st_watch.py, no key; wherever the block judges ``BLIND_OUT``): where the field reaches
its band, no candidate explains it, not in st100's pause and fewer than ``MON_FOLLOW_OTHERS`` + 1
at their warning band, the block tells the C's lone fault where it can with bounded state: the
culprit ``j`` the judged sensor with the largest mean stored error (the C's ``_drift`` z), ``j``
one the C holds out alone (``MON_LONE``: ported, its set solved, no partner it would take beside),
at its warning band and past the field's band by more than its rounding (so ``_within_rounding``
is False whatever the memory), and with ``j`` out every other judged sensor's mean error over the
last ``confirm`` rows within its warning band (``_resolves``: ``MON_LONE_SELF`` / ``MON_LONE_SCALE``,
the operator of the set without ``j``, constants).  Then the C takes ``j`` out by ``DRIFT_OUT``:
the block flags it (``mon_rule`` ``DRIFT_OUT``, ``mon_sensor`` ``j``) and holds it as st95b's
``STEP_OUT`` (its wait doubled per exclusion, back where its error with every sensor in is within
``READMIT`` times its warning band over the window: the C's ``_pass_once_back``, ``hid`` False as
``j`` was at its band), judging on from the ``BACK``.  Anything else at such a reach stops the
judgement as before (``mon_stop``).  Not followed: the correction while ``j`` is out (the C
rebuilds it; the block reads it live, as in a ``STEP_OUT`` hold); the C's ``FOLLOWED`` of ``j``
(a new state) inside the hold.

BAR (committed before fresh lr/dl 10016-10018 are simulated; scored once).  Tree = this branch,
main = 4b70457f's export (its src in a scratch copy, the block text made there), the C beside.
Per record: the healthy stream whole, and (``windows``) bench_st103b's windows of every record
the tree's gate scores (``mon_stop_row`` 0, not ``mon_lost`` at the onset).

* L1 (claimed): every row the tree names ``DRIFT_OUT`` the C names ``DRIFT_OUT`` of the same sensor;
  the tree's hold of it ends on the row the C lets it ``BACK``.
* L2 (the next step): every ``BLIND_OUT`` the tree names where main's judgement had stopped, the C
  names on the same row (same sensor); on its hold rows max|C - ST| <= 1e-12 um.
* L3 (nothing else moved): every row where the tree's (mon_flag, mon_rule, mon_sensor) differs from
  main's is an L1 / L2 naming row or a row of their holds where the tree's (rule, sensor) is the
  C's; every row where the tree's c differs from main's (bitwise) is an L2 hold row; on the
  windows of records main's gate scores too, 0 flag rows differing and every clean reached
  ``BLIND_OUT`` hold <= 1e-12 um as before (st103c's S2).
* Seen records: dl9965, dl9967, dl9975 and st102b's others (lr9964-9967, dl9964, dl9966), healthy;
  windows of dl9965, dl9967 (now gated in) and dl9964.  Fresh: lr/dl 10016-10018, healthy and
  windows.  L1-L3 on seen and fresh: KEPT.  VOID on fresh (no ``DRIFT_OUT`` followed there): said,
  the verdict resting on seen and L3 fresh.  L1 or L2 not met on seen: REFUSED.

Measured (2026-12-07, 2 cores shared, load 14-18; the rule = f0a9c5f8's src, c08b9953's with one
line split; BAR c08b9953, unchanged; VERDICT REFUSED: L1 and L3 not met on seen windows; fresh
10016-10018 NOT drawn, unspent).

* Healthy (``healthy /tmp/st105b/seen dl9965 dl9967``, 38.0 s CPU; the other 8, 7 in one run):
  dl9965 ``DRIFT_OUT T_spindle_rear`` 5695 named as the C, back on its row 5715; dl9967 ``DRIFT_OUT
  T_col_back`` 3116, back 3128, then ``BLIND_OUT T_bed_right`` 3505 named as the C (main silent),
  its 11 hold rows max|C - ST| 5e-14 um, back 3516 as the C.  L1 2 of 2, L2 1 of 1.  dl9975,
  lr9964-9967, dl9964, dl9966: nothing followed, 0 flag rows and 0 c rows moved.  lr9965 still
  stops at 2470: the C's ``_lone_fault`` returns -1 there (the likelier fault out of band, its
  ``_hovers`` False: nothing taken out), which the block cannot tell without the memory.
* Windows (``windows ... dl9965 dl9967 dl9964``, gate now scoring dl9965 and dl9967): 19 windows,
  14 clean reached ``BLIND_OUT`` holds, all <= 9.9e-14 um; 8 ``BLIND_OUT`` named where main had
  stopped, all on the C's row and <= 1e-12 um on their holds (L2 8 of 8).  3 ``DRIFT_OUT``
  followed (the T_amb windows of dl9965 6127, dl9967 6130, dl9964 6129: the C's lone fault
  T_col_back), named as the C; L1 1 of 3: on dl9965 / dl9964 the C takes T_amb out as its second
  (``JUMP``) while T_col_back is out; the block flags the same ``JUMP`` and its judgement ends
  there (``mon_lost``), the C's ``BACK`` of T_col_back past the window: NOT MET by the letter.
* L3 NOT MET: dl9965's T_col_front_low window: the block's ``BLIND_OUT T_motor`` 6130 (= the C,
  1.8e-14 um) meets the C's ``FOLLOWED`` at 6133 (the field followed the exclusion: a new thermal
  state); the block's hold judgement ends (st99's rule), silent, so at 6179 it misses the C's
  ``SETTLED T_col_front_low`` that main names (1 flag row); its c differs from main's on 52 rows
  (2.4 um off the C, main 2.7).  dl9965's T_table window: 11 c rows differ from main's (the C's
  ``JUMP`` hold, st101, now reached: 2.8e-14 um off the C, main 28): better, but not L2 rows.
* Test (in benchmarks/st105b_rule.patch): test_export_st97d +1 case, 1.2 s CPU added (paired, 2
  reps: 4.0 / 4.4 -> 5.3 / 5.6 s for the module); fails on 4b70457f.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st105b.py healthy ROOT RECORD [RECORD ...]
    python benchmarks/bench_st105b.py windows ROOT RECORD [RECORD ...]

ROOT holds the records as bench_cmon92's ``made`` makes them (:data:`MADE_BY`, each once); main's
block is made once per record by 4b70457f's src (``git archive`` into ROOT/base).
"""

from __future__ import annotations

import copy
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st102  # noqa: E402
import bench_st102b  # noqa: E402
import bench_st103b  # noqa: E402
import bench_st103c  # noqa: E402
from _cli import run_commands  # noqa: E402

MAIN = "4b70457f"
TOL = 1e-12     # um


def _fresh() -> dict:
    """bench_st102b's :data:`FRESH` words on seeds 10016-10018 (chosen before any was simulated)."""
    return {f"{r[:2]}{int(r[2:]) + 52}": [f"seed={int(w[5:]) + 52}" if w.startswith("seed=") else w
                                          for w in words]
            for r, words in bench_st102b.FRESH.items() if int(r[2:]) <= 9966}


FRESH = _fresh()     # lr10016, dl10016, ..., lr10018, dl10018
MADE_BY = {**bench_st103c.MADE_BY, **FRESH}

_MAIN_TEXT = """
import sys
sys.path[:0] = ["benchmarks", "tests/shell", "tests"]
from pathlib import Path
from bench_cmon92 import faulted_cell
from thermocomp.apps.deploy.export import exported_files
deployed = faulted_cell(Path(sys.argv[1]), sys.argv[2], "mlr-none")[0]
Path(sys.argv[3]).write_text(exported_files(deployed, "st")["compensator.st"])
"""


def main_block(root: Path, record: str) -> str:
    """``record``'s block as :data:`MAIN` exports it (its src in ``root/base``, made once)."""
    base, out = root / "base", root / "main_st" / f"{record}.st"
    if not base.exists():
        base.mkdir(parents=True)
        archive = subprocess.run(["git", "archive", MAIN], cwd=HERE.parent, check=True, capture_output=True)
        subprocess.run(["tar", "-x", "-C", str(base)], input=archive.stdout, check=True)
    if not out.exists():
        out.parent.mkdir(exist_ok=True)
        subprocess.run([sys.executable, "-c", _MAIN_TEXT, str(root), record, str(out)], cwd=base, check=True,
                       env={"PYTHONPATH": str(base / "src"), "PATH": "/usr/bin:/bin", "OMP_NUM_THREADS": "1"})
    return out.read_text()


def _cell(root: str, record: str):
    """bench_st103b's cell with main = :func:`main_block`."""
    base = Path(root).resolve()
    return bench_st103b._cell(root, record, MADE_BY, lambda _: main_block(base, record))


def _rows(kept, part):
    """Per row: bench_st103b's row, then the tree's ``mon_held``, the C's sensors out, its flags."""
    for r in kept.rows(part):
        yield (*r, int(kept.tree.vars["mon_held"]), list(kept.sim.watch.gone))


def _judge(rows, first: int, names) -> dict:
    """L1-L3 over ``rows`` (row numbers from ``first``): the counts, each case's line printed."""
    from thermocomp.apps.deploy.export.watch import BLIND_OUT, DRIFT_OUT

    got = {"drift": 0, "l1": 0, "blind": 0, "l2": 0, "moved": 0, "c_moved": 0, "hold_gap": 0.0}
    claimed: set = set()       # the rows of L1 / L2 namings and their holds
    held: set = set()          # L2 hold rows
    for i, r in enumerate(rows):
        tree, main, c_said = r[4], r[5], r[3]
        new = tree != main and tree[0] and tree[1] in (DRIFT_OUT, BLIND_OUT)
        if not new:
            continue
        k = tree[2]
        end = next((x for x in range(i + 1, len(rows)) if rows[x][7] != k), len(rows))
        back = next((x for x in range(i + 1, len(rows)) if k not in rows[x][8]), len(rows))
        claimed.update(range(i, end))
        as_c = c_said == (tree[1], k)
        if tree[1] == DRIFT_OUT:
            got["drift"] += 1
            got["l1"] += as_c and end == back
            what = f"back tree {first + end} C {first + back}"
        else:
            got["blind"] += 1
            held.update(range(i, end))
            gap = max(float(np.max(np.abs(rows[x][2] - rows[x][0]))) for x in range(i, end))
            got["hold_gap"] = max(got["hold_gap"], gap)
            got["l2"] += as_c and gap <= TOL
            what = f"hold rows {end - i}, max|C-ST| {gap:.2g} um, back tree {first + end} C {first + back}"
        print(f"    {first + i}: tree {names[k]} rule {tree[1]}, C rule {c_said[0]} "
              f"{names[c_said[1]] if c_said[1] >= 0 else '-'}: {what}", flush=True)
    for i, r in enumerate(rows):
        if r[4] != r[5] and not (i in claimed and (r[4][1], r[4][2]) in (r[3], (0, -1))):
            got["moved"] += 1
            print(f"    moved flag row {first + i}: tree {r[4]} main {r[5]} C {r[3]}", flush=True)
        if bool(np.any(r[0] != r[1])) and i not in held:
            got["c_moved"] += 1
    return got


def healthy(root: str, *records: str) -> None:
    """Per record the healthy stream whole: L1-L3's counts (module doc)."""
    for record in records:
        _, ss, frame, _, names, tree, main = _cell(root, record)
        rows = list(_rows(bench_st103b.Three(ss, tree, main), frame))
        got = _judge(rows, 0, names)
        print(f"  healthy {record}: DRIFT_OUT followed {got['drift']} (L1 met {got['l1']}), BLIND_OUT named "
              f"past main's stop {got['blind']} (L2 met {got['l2']}, max|C-ST| on their holds "
              f"{got['hold_gap']:.2g} um); other flag rows moved {got['moved']}, c rows moved off L2 "
              f"holds {got['c_moved']}", flush=True)


def _window(kept, names, sensor: str, frame, start: int) -> dict | None:
    """bench_st103b's window line, then L1-L3 on the window's rows."""
    said = bench_st103b._window(kept, names, sensor, frame, start)
    if said is None:
        return None
    df, back = bench_st102.dropped(frame, sensor, start)
    rows = list(_rows(copy.deepcopy(kept), df.iloc[start:back + 61]))
    got = _judge(rows, start, names)
    moved = [start + i for i, r in enumerate(rows) if bool(np.any(r[0] != r[1]))]
    if got["c_moved"]:
        gaps = [(float(np.max(np.abs(r[2] - r[0]))), float(np.max(np.abs(r[2] - r[1])))) for r in rows
                if bool(np.any(r[0] != r[1]))]
        print(f"    c rows moved off L2 holds {got['c_moved']} (rows {moved[0]}..{moved[-1]}): max|C-ST| "
              f"{max(g[0] for g in gaps):.2g}, main {max(g[1] for g in gaps):.2g}", flush=True)
    return {**said, **got}


def windows(root: str, *records: str) -> None:
    """bench_st103b's windows of the records the tree's gate scores, with L1-L3 (module doc)."""
    keys = ("flags", "drift", "l1", "blind", "l2", "moved", "c_moved")
    tally = dict.fromkeys(("windows", "clean", "clean_met", *keys), 0)
    base = Path(root).resolve()
    for record in records:
        for got in bench_st103b.windows(root, [record], _window, MADE_BY, lambda _: main_block(base, record)):
            tally["windows"] += 1
            tally["clean"] += got["clean"]
            tally["clean_met"] += got["clean"] and got["hold"] <= TOL
            for key in keys:
                tally[key] += got[key]
    print(f"total: {tally}", flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"healthy": healthy, "windows": windows}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))

