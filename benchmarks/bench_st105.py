"""The C's JUMPs the ST block does not hold: traced, classed; the block's own JUMP held while its
``BLIND_OUT`` judgement is stopped or paused (st105, issue 34).

st103c (bench_st103c.py, KEPT) left "not reached": the C names ``JUMP`` of a sensor no other
predicts and holds it out (its fallback set served on its last reading in), the block flags
``JUMP`` and holds nothing (st101's ``mon_jheld`` not entered): fresh lr10007 T_table 31 um, seen
lr9985 T_spindle_rear 21, lr9967 T_spindle_front 29, T_amb 1.1-5.1; "reached but apart after the
hold": lr9966 / dl9966 T_table 40 / 36 (a second JUMP, at the bump's drop).

TRACE (a scratch trace on 4b70457f before any rule; the classes ``trace`` prints on main's
columns; st103c's windows and gate, every C ``JUMP`` of a window, not only its first; seen = lr9985
dl9964 and st102b's lr/dl 9964-9967, st103c's fresh lr/dl 10007-10009 (scored there, seen here);
the gate scores lr9985 dl9964 lr9964 lr9966 lr9967 dl9966 dl10007
lr10007 lr10008): 30 C JUMPs, 11 held by the block, 19 not.  Why not: st101's entry asks ``NOT
mon_pause AND NOT mon_blind_lost`` (and ``NOT mon_lost``); the C's JUMP rule is
the block's (same row, same sensor on all 19: the block flags ``JUMP`` there and loses its field).

* STOP (13): the block's ``BLIND_OUT`` judgement had ended (``mon_stop``: a drift reach it cannot
  follow, the C's lone fault, veto or new state) earlier in the window.  Of them, A (10): the C
  holds another out too, a ``DRIFT_OUT`` of a sensor others predict (T_col_back x7, T_head_right,
  T_col_front_top), which the C's model reads rebuilt by the POD: the block is 0.0022 .. 4.7 um
  off the C on the row before the JUMP already (lr9985 / dl9964 x2 / lr9964 / dl9966 / dl10007
  / lr10007 T_amb, lr10007 T_table 31 um, lr9967 T_spindle_front 29, T_motor 5.5).  B (3): the C
  holds the jumped sensor alone (the C's drift judgement vetoed, or its ``DRIFT_OUT`` readmitted
  by ``FOLLOWED``), the block = the C to 5e-14 on the row before: lr9985 T_spindle_rear (21 um on
  the C's hold), lr9967 T_xdrive 3685 (6.3), lr10008 T_xdrive (4.8).
* PAUSE (4): the block paused (st100, the C's veto / new state), the C holds it alone, the block =
  the C before: the second JUMP (the drop) of lr9966 T_amb (2.7 um) and T_table (40), dl9966
  T_table (36), lr10008 T_amb (0.58).
* LOST (2): the block's own earlier unheld JUMP in the window (lost): lr9967 T_xdrive 3723 (after
  B's), lr10007 T_table 3723 (after A's, 5.7 um off before).

The largest class is the STOP (13), by the gate that refuses the hold.  Its A part is out of reach
of any rule in the block alone: there the C's model reads a sensor others predict rebuilt by the
POD (no POD in the ST, :mod:`st_watch` doc), and the C's choice of that culprit (``_lone_fault``,
``_resolves``) needs the operators with it out.  The rest (B, PAUSE, and LOST after them) the
block can hold exactly: the C holds the jumped sensor alone, its JUMP and BACK rules the block's.

RULE (src: st_watch.py ``BLOCK``, no key): the block's own ``JUMP`` of a ``MON_JUMP_HELD`` sensor,
its field not lost, none held, is held (st101's ``mon_jheld``, st103c's serving) whether or not
its ``BLIND_OUT`` judgement is paused or stopped (the gate ``NOT mon_pause AND NOT
mon_blind_lost`` dropped).  A pause meets the hold as st100 meets a sensor out in a pause: the
``BLIND_OUT`` judgement stops there (said, ``mon_stop``).  Everything else as st101 / st103c.

WINDOWS: st103c's (bench_st103b.windows: the gate, the dropped bump per sensor no other predicts,
rows onset .. back + 60).  EVENT: a C ``JUMP`` of the window (row i, sensor s); its HOLD ROWS: i
.. the row before the C's next event of s (its ``BACK``); its AFTER ROWS: from there to the next C
``JUMP`` of s or the window's end.  Its class as main's block sees it (main = 4b70457f's export,
:func:`main_block`): ``held`` (main's ``mon_jheld`` = s within bench_st101.NEAR rows), else A /
B / PAUSE / LOST as above (A: the C's out set on row i has another; else by main's state on row
i - 1: held ``BLIND_OUT``, lost, stopped, paused).  ALONE: an event not held on main where the C
holds s alone and main's block = the C on row i - 1 (max|C - ST| <= 1e-6 um).

BAR (committed before fresh lr/dl 10013-10015 are simulated; scored once):

* S1 seen: every ALONE event max|C - ST| <= 1e-12 um on its hold rows (main 0.58 .. 40 um on the
  7 of B and PAUSE; the LOST one after B counts where main's block = the C before it).
* S2 seen (st103c's S2 unchanged): every clean reached ``BLIND_OUT`` hold (bench_st103c's
  ``_window``: clean) <= 1e-12 um on its hold rows, and 0 flag rows where the tree's (mon_flag,
  mon_rule, mon_sensor) differs from main's in the windows that hold one.
* S3 (st103c's S3 unchanged) the healthy streams of st102b's 8 records: 0 rows outside the holds
  (the tree's ``BLIND_OUT`` and JUMP holds) whose c differs from main's (bitwise), 0 flag rows
  differing.
* S4 fresh lr/dl 10013-10015 (bench_st102b's words, seeds +49, as st103c made 10007-10009): S1 on
  every ALONE event (VOID under 3: said, the verdict resting on S1-S3), S2 on every clean reached
  ``BLIND_OUT`` hold.
* Reported, no bar: A events (main vs tree on their hold rows), flag rows differing from main and
  new extra flags (a tree flag the C does not raise within NEAR rows, not main's) per window.

Measured (2026-12-07, 2 cores shared, load 7-19; the rule and the bar = 61a08e53, unchanged after
the fresh score; VERDICT KEPT: S1-S4 met; CPU user + sys of each command, /usr/bin/time):

* S1 MET (``score /tmp/st105/seen lr9985 dl9964 lr9964 lr9966 lr9967 dl9966 dl10007 lr10007
  lr10008``, 129.2 s CPU): 54 windows, 30 C JUMPs (main's classes as the trace: held 11, A 10, B 3,
  PAUSE 4, LOST 2); 8 ALONE, all held by the tree, max|C - ST| on their hold rows <= 6e-14 um
  (main): lr9985 T_spindle_rear 6e-14 (21), lr9967 T_xdrive 5e-14 (6.3) and its LOST 2.8e-14
  (6.4), lr10008 T_xdrive 4.3e-14 (4.8), lr9966 T_amb 5.2e-14 (2.7), T_table 5.2e-14 (40), dl9966
  T_table 2.5e-14 (36), lr10008 T_amb 4.6e-14 (0.58); their after rows <= 8.5e-14 (main to 15).
* S2 MET: 28 clean reached ``BLIND_OUT`` holds <= 1.1e-13 um; 0 flag rows differing from main on
  every window (54), 0 new extra flags.
* S3 MET (``healthy /tmp/st105/seen`` st102b's 8, 119.2 s CPU): 0 rows outside the holds whose c
  differs from main's, 0 flag rows differing; hold rows (lr9964 10, dl9964 11, dl9967 10) <= 7.1e-14.
* S4 MET, scored once (``score /tmp/st105/fresh lr10013 dl10013 lr10014 dl10014 lr10015
  dl10015``, 81.1 s CPU; simulated before by bench_cmon92's ``made``): gate NOT scored lr10014
  (``mon_stop_row`` 160); 27 windows, 18 C JUMPs; 3 ALONE, all <= 7.6e-14 um (main): dl10013
  T_table PAUSE 5.7e-14 (38), dl10014 T_amb B 2.8e-14 (2.2), lr10015 T_table B 7.6e-14 (30); 15
  clean reached ``BLIND_OUT`` holds <= 1e-13; 0 flag rows differing, 0 new extra flags.
* A (reported): the tree holds the jump, still off the C (the POD's rebuild): seen 10 events 0.18 ..
  1.26 um (main 0.4 .. 30.6), 9 nearer, lr10007 T_amb farther (0.91, main 0.71); fresh 8: 0.32 ..
  2.0 (main 0.44 .. 36.9), all nearer.  Not ALONE, B: fresh dl10014 T_spindle_front (off by 1.6 um
  before the JUMP): 1.6 (main 31).
* Tests: test_export_st100 +1 case (fails on 4b70457f: no hold); the module 5.7-6.1 s CPU without
  it, 6.3-6.6 with it (two paired runs: +0.2, +0.9 s).  The ST line count 2234 -> 2235.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st105.py trace ROOT RECORD [RECORD ...]
    python benchmarks/bench_st105.py score ROOT RECORD [RECORD ...]
    python benchmarks/bench_st105.py healthy ROOT RECORD [RECORD ...]

ROOT holds the records as bench_cmon92's ``made`` makes them (each once: :data:`MADE_BY`) and
main's src (``ROOT/main-src``, ``git archive`` of :data:`MAIN`).  ``trace``: per record the size and
gate lines, per C JUMP its line (class on main, the tree's hold, max|C - ST| on the hold and
after rows, tree (main)); then the counts.  ``score``: ``trace``'s lines, each window's clean
reached ``BLIND_OUT`` hold and flag lines, and the totals S1 / S2 read.  ``healthy``:
bench_st103c's healthy lines against :func:`main_block`.
"""

from __future__ import annotations

import copy
import os
import pickle
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st101  # noqa: E402
import bench_st102  # noqa: E402
import bench_st102b  # noqa: E402
import bench_st103b  # noqa: E402
import bench_st103c  # noqa: E402
from _cli import run_commands  # noqa: E402

MAIN = "4b70457f"     # main: st103c's block (a JUMP held only while BLIND_OUT is judged)
TOL, EXACT = 1e-6, 1e-12     # um
ROOT: list[Path] = []     # the ROOT the command was given (main's src beside the records)


def _fresh() -> dict:
    """bench_st102b's :data:`FRESH` words on seeds 10013-10015 (chosen before any was simulated)."""
    return {f"{r[:2]}{int(r[2:]) + 49}": [f"seed={int(w[5:]) + 49}" if w.startswith("seed=") else w
                                          for w in words]
            for r, words in bench_st102b.FRESH.items() if int(r[2:]) <= 9966}


FRESH = _fresh()     # lr10013, dl10013, ..., lr10015, dl10015
MADE_BY = {**bench_st103c.MADE_BY, **FRESH}


def main_block(deployed) -> str:
    """``deployed``'s block as :data:`MAIN` exports it (its src, ``ROOT/main-src``, in a child)."""
    src = ROOT[0] / "main-src"
    if not (src / "src").exists():
        src.mkdir(parents=True, exist_ok=True)
        tar = subprocess.run(["git", "archive", MAIN, "src"], cwd=HERE.parent, check=True,
                             capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(src)], input=tar, check=True)
    with tempfile.NamedTemporaryFile(suffix=".pkl") as f:
        pickle.dump(deployed, f)
        f.flush()
        code = ("import pickle, sys; from thermocomp.apps.deploy.export import exported_files; "
                "sys.stdout.write(exported_files(pickle.load(open(sys.argv[1], 'rb')), 'st')"
                "['compensator.st'])")
        env = {**os.environ, "PYTHONPATH": str(src / "src")}
        return subprocess.run([sys.executable, "-c", code, f.name], env=env, check=True,
                              capture_output=True, text=True).stdout


STATE = ("mon_lost", "mon_held", "mon_jheld", "mon_pause", "mon_blind_lost")


def _stepped(kept, part) -> list:
    """Per row ``(bench_st103b.Three's row, main's STATE before it, the tree's and main's
    mon_jheld after it, the C's sensors out after it)``."""
    rows, before = [], {x: int(kept.main.vars[x]) for x in STATE}
    for r in kept.rows(part):
        after = {x: int(kept.main.vars[x]) for x in STATE}
        rows.append((r, before, int(kept.tree.vars["mon_jheld"]), after["mon_jheld"],
                     list(kept.sim.watch.gone)))
        before = after
    return rows


def _class(row, s: int, went: dict) -> str:
    """The event's class on main (module doc)."""
    _, was, _, _, gone = row
    if [k for k in gone if k != s]:
        return "A"
    if was["mon_held"] >= 0:
        return "HELD_OUT"
    if was["mon_lost"]:
        return "LOST"
    if was["mon_blind_lost"]:
        return "B"
    return "PAUSE" if was["mon_pause"] else "OTHER"


def _gap(r, i: int = 0) -> float:
    return float(np.max(np.abs(r[2] - r[i])))


def _top(values) -> str:
    return f"{max(values):.2g}" if values else "-"


def _events(rows, names, sensor: str, start: int) -> list[dict]:
    """Each C JUMP of the window: its line (module doc) and its numbers."""
    from thermocomp.apps.deploy.export.watch import JUMP, RULES

    out, went = [], {}
    for n, (r, *_rest) in enumerate(rows):
        rule, s = r[3]
        if rule and s >= 0:
            went.setdefault(s, RULES[rule])
        if rule != JUMP:
            continue
        near = range(max(n - bench_st101.NEAR, 0), min(n + bench_st101.NEAR + 1, len(rows)))
        on_main = any(rows[m][3] == s for m in near)
        cls = "held" if on_main else _class(rows[n], s, went)
        ends = next((m for m in range(n + 1, len(rows)) if rows[m][0][3][1] == s and rows[m][0][3][0]),
                    len(rows))
        stop = next((m for m in range(ends + 1, len(rows)) if rows[m][0][3] == (JUMP, s)), len(rows))
        hold, after = [x[0] for x in rows[n:ends]], [x[0] for x in rows[ends:stop]]
        before = _gap(rows[n - 1][0], 1) if n else float("nan")
        alone = not on_main and rows[n][4] == [s] and before <= TOL
        got = {"cls": cls, "alone": alone, "tree": max(_gap(x) for x in hold),
               "main": max(_gap(x, 1) for x in hold), "held": any(rows[m][2] == s for m in near)}
        others = [f"{names[k]} {went.get(k, '?')}" for k in rows[n][4] if k != s]
        print(f"  window {sensor}: C JUMP {start + n} {names[s]} [{cls}{', alone' if alone else ''}"
              f"{'; the C holds ' + ', '.join(others) if others else ''}]: main before "
              f"{before:.2g}; tree holds it {got['held']}; hold rows {len(hold)} max|C-ST| "
              f"{got['tree']:.2g} (main {got['main']:.2g}); after rows {len(after)} "
              f"{_top([_gap(x) for x in after])} (main {_top([_gap(x, 1) for x in after])})", flush=True)
        out.append(got)
    return out


def _window(kept, names, sensor: str, frame, start: int) -> dict | None:
    """The window's event lines, its clean reached ``BLIND_OUT`` hold and flag line."""
    df, back = bench_st102.dropped(frame, sensor, start)
    if back + 61 >= len(df):
        return None
    rows = _stepped(copy.deepcopy(kept), df.iloc[start:back + 61])
    events = _events(rows, names, sensor, start)
    said = [(x[0][4], x[0][5], x[0][3]) for x in rows]
    new = bench_st101._extra(said, 0) - bench_st101._extra(said, 1)
    clean = _clean(rows, start)
    flags = sum(s[0] != s[1] for s in said)
    print(f"  window {sensor}: clean reached BLIND_OUT hold {clean['clean']} (its rows max|C-ST| "
          f"{clean['held']:.2g}); flag rows differing from main {flags}; new extra flags "
          f"{sorted((i + start, k) for i, _, k in new) or '-'}", flush=True)
    return {"events": events, **clean, "flags": flags, "new": len(new)}


def _clean(rows, start: int) -> dict:
    """bench_st103c's clean reached ``BLIND_OUT`` hold of the window and max|C - ST| on its rows."""
    from thermocomp.apps.deploy.export.watch import BLIND_OUT

    rs = [x[0] for x in rows]
    at = list(enumerate(rs, start))
    cb = next(((i, r[3][1]) for i, r in at if r[3][0] == BLIND_OUT), None)
    sb = next(((i, r[4][2]) for i, r in at if r[4][0] and r[4][1] == BLIND_OUT), None)
    into = next((k for k, r in enumerate(rs) if r[6]), len(rs))
    clean = bool(cb and sb and sb[1] == cb[1] and abs(sb[0] - cb[0]) <= bench_st101.NEAR
                 and max([_gap(r) for r in rs[:into]], default=0.0) <= TOL)
    return {"clean": clean, "held": max([_gap(r) for r in rs if r[6]], default=0.0)}


def _run(root: str, records) -> list[dict]:
    ROOT[:] = [Path(root).resolve()]
    return list(bench_st103b.windows(root, records, _window, MADE_BY, main_block))


def trace(root: str, *records: str) -> None:
    """The ``trace`` lines (module doc)."""
    got = [e for w in _run(root, records) for e in w["events"]]
    counts = {c: sum(e["cls"] == c for e in got) for c in dict.fromkeys(e["cls"] for e in got)}
    print(f"total: {len(got)} C JUMPs; on main {counts}; ALONE {sum(e['alone'] for e in got)}", flush=True)


def score(root: str, *records: str) -> None:
    """The ``score`` lines and totals (module doc)."""
    wins = _run(root, records)
    events = [e for w in wins for e in w["events"]]
    alone = [e for e in events if e["alone"]]
    a = [e for e in events if e["cls"] == "A"]
    clean = [w for w in wins if w["clean"]]
    print(f"total: {len(wins)} windows, {len(events)} C JUMPs; S1 ALONE {len(alone)}, "
          f"<= {EXACT:g} um on their hold rows {sum(e['tree'] <= EXACT for e in alone)} (tree max "
          f"{_top([e['tree'] for e in alone])}, main {_top([e['main'] for e in alone])}); S2 clean "
          f"reached BLIND_OUT holds {len(clean)}, <= {EXACT:g} um {sum(w['held'] <= EXACT for w in clean)}, "
          f"flag rows differing there {sum(w['flags'] for w in clean)}; A {len(a)}: tree "
          f"{[round(e['tree'], 3) for e in a]} um vs main {[round(e['main'], 3) for e in a]}; all "
          f"windows: flag rows differing {sum(w['flags'] for w in wins)}, new extra flags "
          f"{sum(w['new'] for w in wins)}", flush=True)


def healthy(root: str, *records: str) -> None:
    """bench_st103c's ``healthy`` lines against :func:`main_block` (module doc)."""
    ROOT[:] = [Path(root).resolve()]
    bench_st103c.main_block = main_block
    bench_st103c.MADE_BY = MADE_BY
    bench_st103c.healthy(root, *records)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"trace": trace, "score": score, "healthy": healthy}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
