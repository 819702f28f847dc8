"""The ST block judges on after its own ``JUMP``: held to the C's ``BACK`` (st101, issue 34).

st100b (bench_st100b.py, TRACED): after the block's own JUMP of a sensor no other predicts
(st_watch.py ``BLOCK``: ``mon_gone OR mon_jumps > 0`` sets ``mon_lost``), ``IF MON_STEP_JUDGE AND
NOT mon_lost`` skipped the whole field to the campaign's end, while the C holds the sensor out
(cmon87), names its ``BACK`` ``dwell`` rows after its last jump and judges on: its ``BLIND_OUT``
after the onset missed (lr9917, dl9917 4 each; lr9896 3698, dl9894 6142).  An oracle resuming at
the C's BACK on the state left at the JUMP named 16 of 17, but raised 1-2 extra flags in 10 windows.

RULE (REFUSED: kept as benchmarks/st101_rule.patch, ``git apply`` it on 7676398c to measure it;
st_watch.py ``BLOCK``, no key, on wherever the block judges the field, ``MON_STEP_JUDGE``).
(a) The block's own ``JUMP`` of one sensor the C holds out alone for a jump (``MON_JUMP_HELD``:
cmon87's, no other predicts it), its field whole before it (not ``mon_lost``), none held, no
pause, ``BLIND_OUT`` judged: the sensor held (``mon_jheld``) and the field computed on through the
hold (``mon_d``, the rings, the settle ring, the self-prediction errors, the freeze predictions,
the sample count), nothing judged from it; anything else named or flagged in the hold (but BENT)
ends it as before.  (b) The C's ``BACK``: ``mon_jcalm`` rows since its last jump (its own return
counts as one, as the C's calm) at least the C's wait (``MON_WINDOW``, doubled per earlier drift
exclusion of it, ``mon_jdwell``), a full window counted, its reading moving (the C's run 0); one
no other predicts passes.  (c) The C's ``_undone`` there: its jumps undone where it jumped more
than once or its reading on the reference before them is nearer its last one in (the block's
spike return has undone a spike already).  ``mon_lost`` cleared: judged from the next row.

BAR (st100b's S1-S4, committed before fresh lr/dl 9947-9949 are simulated):

* S1 seen: the C's ``BLIND_OUT`` after the block's own JUMP that main misses (st100b's 17: lr9917
  4, dl9917 4, lr9896 T_table 3698, dl9894 T_table 6142, lr9790 4, dl9794 2, dl9845 T_table 6150)
  named on the C's row and sensor (+-2 rows) on >= 75 %.
* S2 every ``BLIND_OUT`` named on main (7676398c) stays named, the same rows.
* S3 bench_st100's healthy sets: 0 rows where the block's (flag, rule, sensor) differs from main's.
* S4 fresh :data:`FRESH` (lr/dl 9947-9949), scored once: a jump planted (:func:`planted_jump`:
  the first sensor of ``MON_JUMP_HELD``, +3 jump limits for 2 rows, 100 rows before the onset),
  then test_export_st96's bump (+6 C) of each sensor no other predicts from the onset (chosen
  before any was drawn): >= 75 % of the C's ``BLIND_OUT`` named (sensor, +-2 rows) and 0 extra
  flags (a block flag whose rule and sensor the C does not raise within 2 rows, not main's).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st101.py cases ROOT RECORD [RECORD ...]
    python benchmarks/bench_st101.py healthy ROOT RECORD [RECORD ...]
    python benchmarks/bench_st101.py planted ROOT RECORD [RECORD ...]

ROOT holds the records as bench_cmon92's ``made`` makes them (each once; bench_st100's generators
and :data:`FRESH`).  ``cases``: per record its healthy fed frame stepped by the block, main's
block and the C: the block's holds (its JUMP row, its BACK, the C's BACK of that sensor), the rows
where its (flag, rule, sensor) differs from main's, extra flags (rule, main; the rule's not
main's); then each bump from the onset: the C's first ``BLIND_OUT``, the block's, main's, named,
extra flags.  ``healthy``: the record's line alone (``fl_thermal``: tests/conftest.py's
``fl_thermal_served``, its test campaign).  ``planted``: ``cases`` on the frame with
:func:`planted_jump` first.

Measured (2026-12-06, 2 cores shared, load 12-22; the rule = e48f5e0e's src, the patch; VERDICT
REFUSED: S1-S3 met, S4 named met, S4's 0 extra flags not met by 1):

* S1 MET, seen (``cases``): the C's ``BLIND_OUT`` after the block's own JUMP named on its row and
  sensor 17 of 17 (main 0): lr9917 4 (3685, 3686, 3684, 3681), dl9917 4 (6132, 6133, 6132, 6131),
  lr9896 T_table 3698, dl9894 T_table 6142, lr9790 4 (3684, 3681, 3685, 3686), dl9794 2 (6130,
  6131), dl9845 T_table 6150 (st100b's oracle: 16, 6184 there).  Each hold's BACK on the C's row:
  lr9917 T_amb 3554->3566, dl9917 5923->5935, lr9790 T_motor 3607->3618, dl9794 T_table 6047->6060.
* S2 MET: the 12 named on main stay named on the same rows (lr9896 3686 x2, dl9894 6137 / 6132,
  lr9893 3692 / 3683 / 3697, dl9897 6133 / 6128 / 6136, dl9845 6128 / 6133).
* S3 MET: 0 rows differing from main, extra flags 0 (main 0), on all 32 of bench_st100's healthy
  frames: st99c's 5, st97d's 11, bench_mon98's 9, fl_thermal, lr/dl 9916-9918.  Holds in them end
  at the C's BACK (dl9768 T_spindle_front 6646->6658, lr9790's second T_spindle_rear 3753->3767).
* Runs: the first of S1-S3 (``healthy`` st97d 112.4 s CPU, mon98 66.7 s, lr/dl 9916 / 9918 +
  fl_thermal 76.1 s; ``cases`` 16-42 s a call) partly on the rule before its last seen change
  (uncommitted: its BACK cleared ``mon_out`` always, the errors' last row not redone after an
  undo); lr9917 dl9894 lr9896 lr9790 dl9794 dl9845 dl9768 run again on e48f5e0e: the same lines
  but dl9894 T_table's new extra flag (6179 JUMP T_table) gone (13.6-37.7 s a call).
* New extra flags in seen bumped windows: lr9917 T_amb 3734 JUMP T_amb (main there SPIKE): the
  C undoes the bump's jumps at its BACK (several: ``_undone``), so do the rule's block; the fall's
  jumps of the sensor the C holds out then are flagged by both blocks (main 6, the rule 7).
* S4 fresh, scored once (``planted /tmp/st101/fresh lr9947 lr9948 lr9949``, 42.0 s CPU with the
  simulation; ``... dl9947 dl9948 dl9949``, 61.6 s): the planted T_amb held and back on the C's
  row on 5 of 6 (dl9948: no hold, its field not whole before it, main alike).  The C's
  ``BLIND_OUT`` named 20 of 21 (95 %; main 0): lr9947 1/1, lr9948 4/4, lr9949 7/7, dl9947 4/4,
  dl9948 0/1 (T_table at 6130, the rule silent as main), dl9949 4/4.  Extra flags: 1 new, lr9948
  T_table 3733 JUMP T_table (main: SPIKE there): the bump's rise jumped twice (3684, 3686), the C
  undid them at its BACK (3696), as the block; the C's BLIND_OUT (3697) holds T_table out, and its
  fall's jumps (3729, 3733) the C does not flag, the blocks do (main at 3729 only: its stale
  shift made 3733 a spike's return).  NOT MET: "0 extra flags".
* Next rule: a jump of the sensor the block holds out by BLIND_OUT is the C's silent re-reference
  (out already): not flagged, its hold followed (calm from the jump, its ``_undone`` at the BACK).
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

BASE = "7676398c"     # main
NEAR = 2              # rows: a block flag the C raises this near is the C's
JUMP_LIMITS, SPIKE_ROWS, BEFORE = 3.0, 2, 100    # the planted jump: size, rows out, before the onset


def _fresh() -> dict:
    """bench_st100's :data:`FRESH` (bench_cmon91's lr and dl generators) on seeds 31 further."""
    return {f"{record[:2]}{int(record[2:]) + 31}": [
        f"seed={int(w[5:]) + 31}" if w.startswith("seed=") else w for w in words]
        for record, words in bench_st100.FRESH.items()}


FRESH = _fresh()     # lr9947, dl9947, lr9948, dl9948, lr9949, dl9949 (chosen before any was simulated)


def planted_jump(ss, frame, start: int):
    """``frame`` with a spike on the first sensor the C holds out alone for a jump (the rule's
    ``MON_JUMP_HELD``, :file:`st101_rule.patch`): up
    :data:`JUMP_LIMITS` times its jump limit for :data:`SPIKE_ROWS` rows, :data:`BEFORE` rows
    before the onset ``start``; and the sensor's name."""
    watch = ss.monitor    # (cmon87's: one no other predicts, out alone for a jump in the C)
    held = bool(watch.get("blind_drop")) and bool(watch.get("blind_jump"))
    held = held and len(watch["inputs"]) - 1 >= watch["min_active"]
    k = int((~np.asarray(watch["predictable"], bool) & held).argmax())
    name = ss.inputs[ss.monitor["inputs"][k]]
    df = frame.copy()
    at = start - BEFORE
    df.loc[at:at + SPIKE_ROWS - 1, name] += JUMP_LIMITS * float(ss.monitor["jump_lim"][k])
    return df, name


class Walk:
    """The block, main's block and the C stepped; per row ``(the block's (flag, rule, k), main's,
    the C's (rule, k))``, and the holds: ``[the block's JUMP row, its BACK, the C's BACK]``."""

    def __init__(self, ss, block: str, base: str):
        self.three = bench_st98.Three(ss, block, base)
        self.said: list = []
        self.holds: list = []
        self.held = -1

    def step(self, part, first: int = 0) -> None:
        from thermocomp.apps.deploy.export.watch import BACK

        v = self.three.fb.vars
        for i, ((_, _, st, (_, crule, ck), _), (_, main)) in enumerate(self.three.rows(part), first):
            self.said.append((st, main, (crule, ck)))
            now = int(v.get("mon_jheld", -1))
            if now >= 0 and self.held < 0:
                self.holds.append([i, None, None, now])
            elif self.held >= 0 and now < 0:
                self.holds[-1][1] = i if not v["mon_lost"] else f"ended {i}"
            if self.holds and crule == BACK and ck == self.holds[-1][3] and self.holds[-1][2] is None:
                self.holds[-1][2] = i
            self.held = now


def _extra(said: list, which: int) -> set:
    """``(row, rule, k)`` where the block (``which`` 0: the rule's, 1: main's) flags a rule and
    sensor the C does not raise within :data:`NEAR` rows (rows of ``said``)."""
    raised = [s[2] for s in said]
    return {(i, s[which][1], s[which][2]) for i, s in enumerate(said) if s[which][0] and (
        s[which][1], s[which][2]) not in raised[max(i - NEAR, 0):i + NEAR + 1]}


def _extra_line(said: list, names, first: int) -> str:
    from thermocomp.apps.deploy.export.watch import RULES

    rule, main = _extra(said, 0), _extra(said, 1)
    new = " ".join(f"{i + first} {RULES[r]} {names[k]}" for i, r, k in sorted(rule - main))
    return f"extra flags rule {len(rule)}, main {len(main)} [new: {new or '-'}]"


def _first(said: list, which: int, rule: int, first: int):
    for i, s in enumerate(said, first):
        got = s[which]
        if (got[0] == rule) if which == 2 else (got[0] and got[1] == rule):
            return i, got[-1]
    return None


def _cell(root: str, record: str):
    """bench_st98's ``cell`` (:data:`FRESH` too, main's block :data:`BASE`); fl_thermal's test
    campaign whole (no lead-in; its onset the end)."""
    if record != "fl_thermal":
        made = bench_st98.cell(Path(root).resolve(), record, bench_st100.generators() | FRESH, BASE)
        return (made[0], made[1].reset_index(drop=True), *made[2:])
    import bench_st97d

    from conftest import fl_thermal_served
    from thermocomp.apps.deploy.export import exported_files

    deployed, ss, frame = fl_thermal_served()
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    block = exported_files(deployed, "st")["compensator.st"]
    return (ss, frame, 0, len(frame), "test", names, block, bench_st97d.base_block(deployed, BASE))


def _record(root: str, record: str, plant: bool, bumps: bool = True, cell=None, walker=None):
    """The lines of ``record`` (module doc; ``cell`` / ``walker`` for :func:`_cell` / :class:`Walk`:
    bench_st102's); and ``(the walk at the onset, the frame, the onset, the names)``."""
    from test_export_st96 import bumped
    from thermocomp.apps.deploy.export.watch import BLIND_OUT

    ss, frame, lead, start, cid, names, block, base = (cell or _cell)(root, record)
    said = ""
    if plant:
        frame, jumped = planted_jump(ss, frame, start)
        said = f"; planted {jumped} at {start - BEFORE}"
    walk = (walker or Walk)(ss, block, base)
    walk.step(frame.iloc[:start])
    kept = copy.deepcopy(walk) if bumps else None
    walk.step(frame.iloc[start:], start)
    holds = [f"{names[k]} {j}->{b} (C {c})" for j, b, c, k in walk.holds]
    differ = [i for i, s in enumerate(walk.said) if s[0] != s[1]]
    print(f"{record} {cid}: {len(frame)} rows ({lead} lead-in), onset {start}{said}; holds "
          f"{holds or '-'}; rows differing from main {len(differ)} {differ[:6] or ''}; "
          f"{_extra_line(walk.said, names, 0)}", flush=True)
    for sensor in [n for n, p in zip(names, ss.monitor["predictable"]) if not p and bumps]:
        df, end = bumped(frame, sensor, start)
        if end + 30 >= len(df):
            continue
        run = copy.deepcopy(kept)
        run.said = []
        run.step(df.iloc[start:end + 31], start)
        c, st, main = (_first(run.said, w, BLIND_OUT, start) for w in (2, 0, 1))
        hit = bool(c and st and st[1] == c[1] and abs(st[0] - c[0]) <= NEAR)
        show = [f"{x[0]} {names[x[1]]}" if x else "-" for x in (c, st, main)]
        print(f"  bumped {sensor}: C BLIND_OUT {show[0]}, block {show[1]}, main {show[2]}, named "
              f"{hit if c else '-'}; {_extra_line(run.said, names, start)}", flush=True)
    return kept, frame, start, names


def cases(root: str, *records: str) -> None:
    """The ``cases`` lines (module doc)."""
    for record in records:
        _record(root, record, False)


def healthy(root: str, *records: str) -> None:
    """The ``healthy`` lines (module doc)."""
    for record in records:
        _record(root, record, False, bumps=False)


def planted(root: str, *records: str) -> None:
    """The ``planted`` lines (module doc)."""
    for record in records:
        _record(root, record, True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    commands = {"cases": cases, "healthy": healthy, "planted": planted}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
