"""The ST block pauses at the C's veto to a calm window, then judges ``BLIND_OUT`` on (st100, issue 34).

st99c (bench_st99c.py, TRACED): on lr9896 the block's drift judgement with every sensor in reaches
the band at lead-in row 1867, no sensor no other predicts explains it (``mon_take_set < 0``), and
st_watch.py BLOCK set ``mon_blind_lost`` (st96's rule, st97d's ``mon_stop``): no ``BLIND_OUT``
judged for the rest of the campaign.  The C there vetoed (its lone fault T_head_left resolves, 2
others at their warning band >= ``new_state_others``) and judged on: its ``BLIND_OUT`` of a bumped
T_spindle_front and T_motor at 3686 the block missed; lr9823 (a new thermal state at 379) the same
at 3690 / 3684.

RULE (st_watch.py ``BLOCK``; no key, on wherever the block judges ``BLIND_OUT``, ``MON_BLIND_JUDGE``).
Where that reach comes with at least ``MON_FOLLOW_OTHERS`` + 1 (the C's ``new_state_others`` + 1)
judged sensors at their warning band (``mon_field_warned``: the block's own ``mon_min`` with every
sensor in, the smallest ``|error|`` over the last ``MON_CONFIRM`` rows, at or past ``MON_WARN``: the
count the C's ``_follow_field`` and ``_others`` read), whatever the C's culprit its ``_others``
vetoes it or the C declares a new thermal state: nothing goes out, no ``DRIFT_OUT``.  The block then
pauses (``mon_pause``) instead of stopping: no ``BLIND_OUT`` judged until a calm window,
``MON_WINDOW`` rows in a row with ``mon_field_warned`` = 0 (``mon_quiet``; the C's ``calm_field``,
the end of its new state), and judges on from the next row.  In the pause such a reach pauses on;
any other reach (a sensor that explains it: the C, if not in a new state, takes it out; fewer
warned: a ``DRIFT_OUT`` may follow) or a sensor out (a stepped error, a freeze: the C's calm with
one out is not the block's) stops it as before (``mon_stop``, ``mon_stop_row``).

BAR (committed before the fresh records are simulated; seen numbers below were taken before it):

* S1 seen: the 4 missed ``BLIND_OUT`` (lr9896 T_spindle_front and T_motor, the C at 3686; lr9823
  T_spindle_front 3690, T_table 3684) named by the block: the C's sensor, within 2 rows of its row.
* S2 seen: the 8 named on main (lr9893 3692 / 3683 / 3697, dl9894 6137 / 6132, dl9897 6133 / 6128
  / 6136) stay named, the same rows and sensors.
* S3: no block flag the C does not raise (``extra``: a block flag whose rule and sensor the C does
  not raise within 2 rows), 0 new against main (9bbbb214's block), on the healthy frames of
  bench_st99c's seen records (lr9893 dl9894 cr9895 lr9896 dl9897), st97d's 11 (dl9768 lr9790
  dl9791 cr9792 lr9793 dl9794 lr9820 dl9821 cr9822 lr9823 dl9824), bench_mon98's healthy (sw9776
  cr9763 lr9376 tr9828 sw9841 lr9842 cr9843 tr9844 dl9845), fl_thermal, the fresh records, and in
  every planted window.
* S4 fresh, scored once: :data:`FRESH` (bench_cmon91's lr and dl generators on seeds 9916-9918,
  chosen before any was simulated).  Planted (``cases``): test_export_st96's bump (+6 °C) of each
  sensor no other predicts, from the onset, and from 50 rows after each of the rule's first 3
  pauses past the onset (where the frame holds the bump and 30 rows more).  Of the C's
  ``BLIND_OUT`` in the cases where main's block had stopped before the plant, the block names
  >= 90 % (sensor, within 2 rows); extra flags 0.  If no fresh case has main stopped before it, S4
  is void (said so), and the fresh records count for S3 only.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st100.py cases ROOT RECORD [RECORD ...]
    python benchmarks/bench_st100.py healthy ROOT RECORD [RECORD ...]

ROOT holds the records as bench_cmon92's ``made`` makes them (each once); RECORD any of
bench_st99c's, bench_st98's (st97d's, bench_mon98's seen) or :data:`FRESH`, bench_mon98's fresh
(``MON98``) or ``fl_thermal`` (tests/conftest.py's ``fl_thermal_served``; ``healthy`` only).
``healthy``: per record the healthy fed frame (bench_cmon92's ``faulted_cell``, lead-in with it)
stepped by the block, main's block and the C's mirror: the rule's pauses (row, the C's drift
outcome there, the judged at their warning band) and where each ended, the rule's stop and main's,
the rows where the block's flag / rule / sensor differ from main's, extra flags (rule, main).
``cases``: that, then the planted lines: the C's first ``BLIND_OUT`` to the bump's end + 30 rows,
the block's and main's, whether main's judgement had stopped before the plant, extra flags.

Measured (2026-12-06, 2 cores shared by up to 8 helpers, load 8-30).  Seen, before the BAR's
commit (8639fec5; ``cases /tmp/st100/seen lr9896 lr9893 dl9894 cr9895 dl9897``, 68.4 s CPU;
``cases /tmp/st100/st97d lr9823 dl9821``, 32.6 s: copies of st99c's records): lr9896 pauses at
1867 (the C's veto, 3 warned) and 2900 (a new state, 4), resumed 1877 / 2910, never stops (main:
1867); lr9823 pauses at 379 (new state, 3) and 2799 (veto, 4), resumed 390 / 2810 (main stops at
379); dl9821 stops at 4543 as main (a new state, 1 warned: not paused).

* S1 MET: lr9896 T_spindle_front and T_motor named at 3686, lr9823 T_spindle_front 3690, T_table
  3684, each on the C's row and sensor: 4 of 4 (main 0).
* S2 MET: lr9893 3692 / 3683 / 3697, dl9894 6137 / 6132, dl9897 6133 / 6128 / 6136: 8 of 8 as
  main, the same rows and sensors.  (Unnamed by both, out of scope: the T_table bumps whose C's
  first event is a JUMP, lr9896 3698, dl9894 6142.)
* S3 MET: every healthy frame 0 rows where the block's flag / rule / sensor differ from main's,
  extra flags 0 (rule and main): the 7 above, ``healthy`` on st97d's other 9 (107.1 s), bench_mon98's
  9 (``healthy /tmp/st100/mon98 ...``, 89.6 s; lr9376 stops at 431 as main, a DRIFT_OUT with fewer
  warned; no pause on any), fl_thermal (6.3 s; no pause), the 6 fresh.  In every
  planted window the rule's extra flags = main's (0 new; the T_amb / T_table windows' 1-9 are
  main's too, not traced).
* S4 VOID, fresh scored once (``cases /tmp/st100/fresh lr9916 lr9917 lr9918``, 42.4 s; ``... dl9916
  dl9917 dl9918``, 64.2 s): no pause and no stop on any of the 6 (rule and main), so no case after
  a main stop.  The C's ``BLIND_OUT`` in 18 planted cases; the rule names 9, main the same 9, at
  the C's rows (lr9916 2 / 2, dl9916 4 / 4, lr9918 3 / 4, dl9917 0 / 4, lr9917 0 / 4, dl9918 none).
  lr9917's 4: the block's JUMP of T_amb at lead-in row 3554 (the C's too) ended its judgement
  (``mon_lost`` at the onset; st94b's class, not this rule's), dl9917's 4 the same (its JUMP of
  T_amb at 5923); lr9918's T_table not traced (main's alike).
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st98  # noqa: E402
import bench_st99c  # noqa: E402
from _cli import run_commands  # noqa: E402

BASE = "9bbbb214"     # main: the block that stops at every reach it cannot follow
NEAR = 2              # rows: a block flag the C raises this near is the C's
AFTER_PAUSE = 50      # rows from a pause to its plant
PAUSES = 3            # the rule's pauses past the onset planted after, at most


def _fresh() -> dict:
    from bench_cmon91 import FRESH as CMON91

    lr, dl = (next(words for record, words in CMON91.items() if record.startswith(kind))
              for kind in ("lr", "dl"))
    return {f"{kind}{seed}": [f"seed={seed}" if w.startswith("seed=") else w for w in words]
            for seed in range(9916, 9919) for kind, words in (("lr", lr), ("dl", dl))}


FRESH = _fresh()     # lr9916, dl9916, lr9917, dl9917, lr9918, dl9918 (chosen before any was simulated)


def generators() -> dict:
    """Every record's simulate words: :data:`FRESH`, bench_st99c's, bench_st98's, bench_mon98's."""
    import bench_mon98

    return {**bench_st98.generators(), **bench_st99c.generators(), **bench_mon98.FRESH, **FRESH}


def _cell(root: Path, record: str):
    """``(ss, frame, lead-in rows, onset, campaign, names, block, main's block)``; fl_thermal's
    test campaign whole (no lead-in, no onset)."""
    if record != "fl_thermal":
        made = bench_st98.cell(root, record, generators(), BASE)
        return (*made[:1], made[1].reset_index(drop=True), *made[2:])
    import bench_st97d

    from conftest import fl_thermal_served
    from thermocomp.apps.deploy.export import exported_files

    deployed, ss, frame = fl_thermal_served()
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    block = exported_files(deployed, "st")["compensator.st"]
    return ss, frame, 0, None, "test", names, block, bench_st97d.base_block(deployed, BASE)


class Walk:
    """The block, main's block and the C stepped over a frame (``step``), tallying what the
    ``healthy`` line says; ``plants``: the rows to keep its state before (deep copies)."""

    def __init__(self, ss, block: str, base: str):
        self.three = bench_st98.Three(ss, block, base)
        self.said: list = []             # per row: (rule's (flag, rule, k), main's, the C's (rule, k))
        self.pauses: list = []           # (row, the C's outcome, warned, new_state_others)
        self.resumed: list = []
        self.stop = self.main_stop = None
        self.paused = False

    def step(self, part, log: list, names, first: int = 0):
        """Step ``part`` (its rows numbered from ``first``), yielding each row's number."""
        for i, ((_, _, st, (_, crule, ck), _), _) in enumerate(self.three.rows(part), first):
            v, b = self.three.fb.vars, self.three.base.vars
            main = (bool(b["mon_flag"]), int(b["mon_rule"]), int(b["mon_sensor"]))
            self.said.append((st, main, (crule, ck)))
            if v["mon_pause"] and not self.paused:
                said = bench_st99c._outcome(log, names)
                self.pauses.append((i, said, *bench_st99c._warned(self.three.sim.watch)))
            elif self.paused and not v["mon_pause"] and not v["mon_stop"]:
                self.resumed.append(i)
            self.paused = bool(v["mon_pause"])
            self.stop = self.stop if self.stop is not None or not v["mon_stop"] else (
                i, bench_st99c._outcome(log, names))
            self.main_stop = self.main_stop if self.main_stop is not None or not b["mon_stop"] else i
            log.clear()
            yield i


def _extra(said: list, which: int) -> list:
    """The rows (of ``said``) where the block (``which`` 0: the rule's, 1: main's) flags a rule and
    sensor the C does not raise within :data:`NEAR` rows."""
    raised = [s[2] for s in said]
    return [i for i, s in enumerate(said) if s[which][0] and (s[which][1], s[which][2]) not in
            raised[max(i - NEAR, 0):i + NEAR + 1]]


def _walked(root: Path, record: str, log: list, plant: bool = False):
    """A record's healthy walk: ``(cell, walk, {row: the walk's deep copy before it})``, where
    ``plant``, for the onset and 50 rows after each of the first :data:`PAUSES` pauses past it."""
    cell = _cell(root, record)
    ss, frame, _, start, _, names, block, base = cell
    walk, kept, want = Walk(ss, block, base), {}, {start} if plant else set()
    for i in walk.step(frame, log, names):
        if plant and walk.pauses and walk.pauses[-1][0] == i and i + AFTER_PAUSE >= start \
                and sum(p[0] + AFTER_PAUSE >= start for p in walk.pauses) <= PAUSES:
            want.add(i + AFTER_PAUSE)
        if i + 1 in want:
            kept[i + 1] = copy.deepcopy(walk)
    return cell, walk, kept


def _healthy_line(record: str, cell, walk) -> str:
    ss, frame, lead, start, cid, names, _, _ = cell
    pauses = ", ".join(f"{r}: {c.split(' (')[0]} ({w} warned)" for r, c, w, _ in walk.pauses) or "-"
    differ = [i for i, s in enumerate(walk.said) if s[0] != s[1]]
    stop = f"{walk.stop[0]} ({walk.stop[1].split(' (')[0]})" if walk.stop else "never"
    return (f"{record} {cid}: {len(frame)} fed rows ({lead} lead-in), onset {start}; "
            f"pauses {len(walk.pauses)} "
            f"[{pauses}], resumed {walk.resumed or '-'}; stop: rule {stop}, main "
            f"{walk.main_stop if walk.main_stop is not None else 'never'}; rows differing from main "
            f"{len(differ)} {differ[:6] or ''}; extra flags rule {len(_extra(walk.said, 0))}, main "
            f"{len(_extra(walk.said, 1))}")


def healthy(root: str, *records: str) -> None:
    """The ``healthy`` lines (module doc)."""
    with bench_st99c.Logged([]) as log:
        for record in records:
            cell, walk, _ = _walked(Path(root).resolve(), record, log)
            print(_healthy_line(record, cell, walk), flush=True)


def _named(said: list, which: int, rule: int, names, first: int):
    """The first row of ``said`` where ``which`` (0 the rule's block, 1 main's, 2 the C) names
    ``rule``: ``(row, sensor)`` or None."""
    for i, s in enumerate(said, first):
        got = s[which]
        hit = got[0] == rule if which == 2 else got[0] and got[1] == rule
        if hit:
            return i, names[got[-1]]
    return None


def cases(root: str, *records: str) -> None:
    """The ``cases`` lines (module doc)."""
    from test_export_st96 import bumped
    from thermocomp.apps.deploy.export.watch import BLIND_OUT

    with bench_st99c.Logged([]) as log:
        for record in records:
            cell, walk, kept = _walked(Path(root).resolve(), record, log, plant=True)
            print(_healthy_line(record, cell, walk), flush=True)
            ss, frame, _, start, _, names, _, _ = cell
            blind = [n for n, p in zip(names, ss.monitor["predictable"]) if not p]
            for at in sorted(kept):
                stopped = bool(kept[at].three.base.vars["mon_blind_lost"])
                for sensor in blind:
                    df, end = bumped(frame, sensor, at)
                    if end + 30 >= len(df):
                        continue
                    run = copy.deepcopy(kept[at])
                    run.said = []
                    for _ in run.step(df.iloc[at:end + 31], log, names, at):
                        pass
                    c, st, main = (_named(run.said, w, BLIND_OUT, names, at) for w in (2, 0, 1))
                    hit = bool(c and st and st[1] == c[1] and abs(st[0] - c[0]) <= NEAR)
                    print(f"  planted {sensor} +6 C from {at} (main stopped before: {stopped}): "
                          f"C BLIND_OUT "
                          f"{c or '-'}, ST {st or '-'}, main {main or '-'}; named {hit if c else '-'}; extra "
                          f"flags rule {len(_extra(run.said, 0))}, main {len(_extra(run.said, 1))}",
                          flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"cases": cases, "healthy": healthy}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
