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

``resume``: an oracle, not a rule: per record the block, main's block and the C stepped (the
healthy frame, then each bump from the onset), the block's ``mon_lost`` cleared on the row the C
names ``BACK`` of the sensor whose JUMP set it (the block's rings as it left them): the C's first
``BLIND_OUT``, the block's and main's, named (sensor, within 2 rows), the rows resumed, extra flags
(a block flag whose rule and sensor the C does not raise within 2 rows; resumed, main, and the
resumed block's not main's).

Measured (2026-12-06, 2 cores shared, load 8-13; seen records only, no src change; VERDICT TRACED):

* ``trace`` lr9917 / dl9917 (copies of /tmp/st100/fresh, st100's fresh, now spent; 11.6 / 17.4 s
  CPU): the block's JUMP of T_amb at 3554 / 5923 is the C's too; the C takes T_amb out (cmon87's
  path) and names its ``BACK`` 12 rows on (3566 / 5935: ``dwell`` = the window, 10, after the
  return's jump); at the onset (3673 / 6120) the C has none out and its reference back on
  ``ref0``, the block's ``mon_shift`` 0 (its spike's return): both read every sensor on the same
  references.  The block's only difference is ``mon_lost``: st_watch.py ``IF MON_STEP_JUDGE AND
  NOT mon_lost`` skips the whole field (no ``mon_d``, no rings, no drift judgement) to the end.
  lr9896 / dl9894 (st99c's seen; 13.8 / 19.8 s): the bumped T_table JUMPs at 3681 / 6131 (after
  the onset), the C's BACK follows, its ``BLIND_OUT`` of T_table at 3698 / 6142 with none out.
* ``resume`` (the oracle; lr9917 14.6 s, lr9896 + dl9894 37.4 s CPU): the C's ``BLIND_OUT`` after
  the block's own JUMP named on the C's row and sensor: lr9917 4 of 4 (3685, 3686, 3684, 3681),
  dl9917 4 of 4 (6132, 6133, 6132, 6131), lr9896 T_table 3699 (the C 3698), dl9894 T_table 6142: the
  brief's 10 of 10 (main 0). More of the class on st97d's / bench_mon98's records (``resume
  /tmp/st100b/st97d lr9790 ... dl9768``, ``... /tmp/st100b/mon98 sw9776 ... tr9844``, 98.4 s CPU,
  st97d's 157.1 s): lr9790 (its JUMP before the onset, resumed 3618) 4 of 4, dl9794 (resumed 6060) 2
  of 2 (main 0 each); dl9845 T_table 0 of 1 (the C 6150, 9 rows after its BACK at 6141; the resumed
  block 6184): 16 of 17. The ones main names stay named on the same rows (lr9896 3686 x2, dl9894
  6137 / 6132). Healthy frames, whole: extra flags 0 (main 0) on all 24 records run (lr9917
  dl9917 lr9896 dl9894; lr9790 dl9791 cr9792 lr9793 dl9794 lr9820 dl9821 cr9822 lr9823 dl9824
  dl9768; sw9776 cr9763 sw9841 cr9843 lr9376 lr9842 dl9845 tr9828 tr9844).
* Not a rule: in 10 bumped windows the resumed block raises 1-2 flags the C does not (where the
  row is printed, 1-37 rows after a resume at a BACK inside the bump): lr9917 T_amb (3734 JUMP
  T_amb) and T_table (3697 BLIND_OUT T_motor); lr9896 T_table (3751 BLIND_OUT T_table, resumed
  3749); dl9894 T_table +2; dl9845 T_amb +2 (6151 BLIND_OUT T_table), T_table +1; dl9794 T_table
  (6165 BLIND_OUT T_motor); lr9823 T_table +1; dl9824 T_amb +1, T_table +1.  Not traced row by
  row; the likely cause: the oracle resumes on the state the block left at its JUMP (``mon_d``,
  the rings, the ``MON_CONFIRM`` evidence, 12+ rows old, its ``mon_out``), where the C kept its
  window through the hold (the set without the sensor, ``hist`` shifted back at ``_undone``).
  A rule needs (a) the block's field computed through the hold (its rings current), judging nothing
  or the set without the sensor (``MON_OUT_SELF`` exists for each ``MON_BLIND`` candidate); (b) the
  C's BACK of a sensor no other predicts out for a jump (watch.py l.982: ``calm >= dwell``, the
  window doubled per earlier drift exclusion, its reading moving that row; ``_pass_once_back``
  passes one no other predicts); (c) the C's ``_undone`` at the BACK (the block's spike's return
  undoes it earlier: same references from the BACK on, lr9917 / dl9917).
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


class Oracle:
    """(``resume``) The block and the C stepped; where the block's judgement ended at its own
    JUMP of a sensor (``mon_lost`` set on that row, not before), ``mon_lost`` cleared on the row
    the C names that sensor's ``BACK`` with none out: what a rule following the C's return would
    start from (the block's rings as it left them)."""

    def __init__(self, three):
        self.three, self.jumped, self.resumed, self.said = three, -1, [], []

    def step(self, part, first: int):
        """Step ``part`` (rows numbered from ``first``), keeping per row ``(row, the block's
        (flag, rule, sensor), the C's (rule, sensor), main's block's (flag, rule, sensor))``."""
        from thermocomp.apps.deploy.export.watch import BACK, JUMP

        v, w = self.three.fb.vars, self.three.sim.watch
        for i, ((_, _, st, (_, crule, ck), _), (_, main)) in enumerate(self.three.rows(part), first):
            if st[0] and st[1] == JUMP and bool(v["mon_lost"]) and not self.was_lost:
                self.jumped = st[2]
            if self.jumped >= 0 and crule == BACK and ck == self.jumped and not w.gone:
                v["mon_lost"], self.jumped = False, -1
                self.resumed.append(i)
            self.was_lost = bool(v["mon_lost"])
            self.said.append((i, st, (crule, ck), main))

    was_lost = False


def _extra(said: list, names) -> str:
    """The block's flags whose rule and sensor the C does not raise within 2 rows: resumed, main;
    the resumed block's not main's (row rule sensor)."""
    from thermocomp.apps.deploy.export.watch import RULES

    raised = [s[2] for s in said]
    got = [{(s[0], s[which][1], s[which][2]) for n, s in enumerate(said) if s[which][0] and (
        s[which][1], s[which][2]) not in raised[max(n - 2, 0):n + 3]} for which in (1, 3)]
    new = " ".join(f"{i} {RULES[r]} {names[k]}" for i, r, k in sorted(got[0] - got[1]))
    return f"{len(got[0])}, main {len(got[1])} [{new or '-'}]"


def resume(root: str, *records: str) -> None:
    """The ``resume`` lines (module doc)."""
    from test_export_st96 import bumped
    from thermocomp.apps.deploy.export.watch import BLIND_OUT

    for record in records:
        ss, frame, lead, start, cid, names, block, base = bench_st98.cell(
            Path(root).resolve(), record, bench_st100.generators(), BASE)
        frame = frame.reset_index(drop=True)
        walk = Oracle(bench_st98.Three(ss, block, base))
        walk.step(frame.iloc[:start], 0)
        kept = copy.deepcopy(walk)
        walk.step(frame.iloc[start:], start)
        print(f"{record}: healthy frame resumed at {walk.resumed or '-'}, extra flags "
              f"{_extra(walk.said, names)}, block flags {sum(s[1][0] for s in walk.said)}", flush=True)
        for sensor in [n for n, p in zip(names, ss.monitor["predictable"]) if not p]:
            df, end = bumped(frame, sensor, start)
            if end + 30 >= len(df):
                continue
            run = copy.deepcopy(kept)
            run.said = []
            run.step(df.iloc[start:end + 31], start)
            c = next(((i, k) for i, _, (r, k), _ in run.said if r == BLIND_OUT), None)
            s = next(((i, t[2]) for i, t, _, _ in run.said if t[0] and t[1] == BLIND_OUT), None)
            m = next(((i, t[2]) for i, _, _, t in run.said if t[0] and t[1] == BLIND_OUT), None)
            hit = bool(c and s and s[1] == c[1] and abs(s[0] - c[0]) <= 2)
            print(f"  planted {sensor}: C BLIND_OUT {f'{c[0]} {names[c[1]]}' if c else '-'}, block "
                  f"{f'{s[0]} {names[s[1]]}' if s else '-'}, main {f'{m[0]} {names[m[1]]}' if m else '-'}, "
                  f"named {hit if c else '-'}; resumed at "
                  f"{run.resumed or '-'}; extra flags {_extra(run.said, names)}", flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"resume": resume, "trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
