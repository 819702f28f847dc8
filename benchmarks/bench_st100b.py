"""The ST block's ``BLIND_OUT`` after its own ``JUMP`` (``mon_lost``): what the C does (st100b, issue 34).

st100 (bench_st100.py, fresh lr9917 / dl9917): the block's JUMP of T_amb in the lead-in (lr9917
row 3554, dl9917 5923; the C's JUMP on the same row) set ``mon_lost`` (st_watch.py ``BLOCK``: any
exclusion since the campaign's first sample), and from there the whole field judgement (``IF
MON_STEP_JUDGE AND NOT mon_lost``) is skipped: no ``mon_d``, no error ring, no ``BLIND_OUT`` to the
campaign's end, while the C names 4 each after the onset.  st99c: lr9896 3681 and dl9894 6131, a
planted T_table whose C's first event is a JUMP, the same class.

Question (``trace``): what is the C's state between the JUMP and its ``BLIND_OUT`` -- the jumped
sensor still out (the C judging the set without it, an operator the block has only for the
``BLIND_OUT`` it holds itself) or back (every sensor in, the block's own set), its re-reference
kept or undone -- and so what the block would need to judge on.

BAR (the brief's, committed before fresh lr/dl 9940-9942 are drawn; seen numbers below):

* S1 seen: the misses after a JUMP (lr9917, dl9917 4 each; lr9896 3681, dl9894 6131) named on the
  C's row and sensor (+-2 rows) on >= 75 %.
* S2 every ``BLIND_OUT`` named on main (063630e6) stays named, the same rows.
* S3 bench_st100's healthy sets: 0 rows differ from main.
* S4 fresh lr/dl 9940-9942 (a jump planted, then blind-outs; chosen before drawing), scored once:
  >= 75 % of the C's ``BLIND_OUT`` after the jump named, 0 extra flags.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st100b.py trace ROOT RECORD [RECORD ...]

ROOT holds the records as bench_cmon92's ``made`` makes them (each once; bench_st100's
generators: its FRESH, bench_st99c's seen).  ``trace``: per record its healthy fed frame
(bench_cmon92's ``faulted_cell``) stepped by the block and the C's mirror to the onset: every
JUMP (the block's, the C's), each sensor's exclusion and ``BACK`` in the C with its wait
(``dwell``), whether the C kept the jump's re-reference at its return, the block's ``mon_lost``
and ``mon_shift`` against the C's reference shift at the onset; then test_export_st96's bump
(+6 °C) of each sensor no other predicts from the onset, each: the C's first ``BLIND_OUT`` (row,
sensor), the C's out set on that row, and the block's flag.

Measured: below (filled in after the trace).
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st98  # noqa: E402
import bench_st100  # noqa: E402
from _cli import run_commands  # noqa: E402

BASE = "063630e6"     # main


def _c_state(watch, names) -> str:
    """The C's out set and each out sensor's jumps."""
    out = [f"{names[j]} (jumps {int(watch.jumps[j])})" for j in watch.gone]
    return "[" + ", ".join(out) + "]"


def _walk(three, part, names, first: int, log: list) -> None:
    """Step ``part`` (rows numbered from ``first``), appending to ``log`` the JUMPs, the C's
    exclusions and returns, and the block's ``mon_lost`` onset."""
    from thermocomp.apps.deploy.export.watch import RULES

    w, v = three.sim.watch, three.fb.vars
    for i, ((_, _, st, (_, crule, ck), _), _) in enumerate(three.rows(part), first):
        gone = set(w.gone)
        if st[0] and RULES[st[1]] == "JUMP" or crule and RULES[crule] in ("JUMP", "BACK"):
            log.append(f"{i}: block {RULES[st[1]] if st[1] else '-'} "
                       f"{names[st[2]] if st[2] >= 0 else '-'}, C {RULES[crule] if crule else '-'} "
                       f"{names[ck] if ck >= 0 else '-'}, C out {_c_state(w, names)}")
        if bool(v["mon_lost"]) and not three.lost_said:
            three.lost_said = True
            log.append(f"{i}: block mon_lost")
        three.gone_rows.append(gone)


def trace(root: str, *records: str) -> None:
    """The ``trace`` lines (module doc)."""
    from test_export_st96 import bumped
    from thermocomp.apps.deploy.export.watch import BLIND_OUT

    for record in records:
        ss, frame, lead, start, cid, names, block, base = bench_st98.cell(
            Path(root).resolve(), record, bench_st100.generators(), BASE)
        frame = frame.reset_index(drop=True)
        three = bench_st98.Three(ss, block, base)
        three.lost_said, three.gone_rows = False, []
        log: list = []
        _walk(three, frame.iloc[:start], names, 0, log)
        w, v = three.sim.watch, three.fb.vars
        idx = ss.monitor["inputs"]
        shift = np.array(v["mon_shift"], float)[idx]
        moved = [f"{names[j]} C {w.ref[j] - w.ref0[j]:+.3f} block {shift[j]:+.3f}"
                 for j in range(len(names)) if w.ref[j] != w.ref0[j] or shift[j] != 0.0]
        print(f"{record} {cid}: {len(frame)} fed rows ({lead} lead-in), onset {start}; C dwell "
              f"{w.dwell.tolist()}, window {w.window}", flush=True)
        for line in log:
            print("  " + line, flush=True)
        print(f"  at the onset: C out {_c_state(w, names)}; block mon_lost {bool(v['mon_lost'])}, "
              f"mon_blind_lost {bool(v['mon_blind_lost'])}; re-references (C ref - ref0, block "
              f"mon_shift): {', '.join(moved) or '-'}", flush=True)
        kept = copy.deepcopy(three)
        blind = [n for n, p in zip(names, ss.monitor["predictable"]) if not p]
        for sensor in blind:
            df, end = bumped(frame, sensor, start)
            if end + 30 >= len(df):
                continue
            run = copy.deepcopy(kept)
            run.gone_rows, said = [], []
            before = [names[j] for j in run.sim.watch.gone]     # the C's out set before each row
            for i, ((_, _, st, (_, crule, ck), _), _) in enumerate(
                    run.rows(df.iloc[start:end + 31]), start):
                said.append((i, st, crule, ck, before))
                before = [names[j] for j in run.sim.watch.gone]
            c = next(((i, names[k], g) for i, _, r, k, g in said if r == BLIND_OUT), None)
            s = next(((i, names[t[2]]) for i, t, _, _, _ in said if t[0] and t[1] == BLIND_OUT), None)
            jumped = next(((i, names[k]) for i, _, r, k, _ in said if r == 1), None)
            print(f"  planted {sensor} +6 C from {start}: C BLIND_OUT "
                  f"{f'{c[0]} {c[1]}, C out before it {c[2]}' if c else '-'}; C's first JUMP after the "
                  f"onset {jumped or '-'}; block BLIND_OUT {s or '-'}", flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
