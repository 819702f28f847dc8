"""What the C did before each ``apart`` STEP_OUT of bench_st94b (st95, issue 34, TRACED): how
far a Structured Text block that judges on after a sensor's exclusion, up to the C's
re-admission by ``BACK``, would reach.  A trace on seen records; no block built, src unchanged.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the block measured is that tree's)::

    python benchmarks/bench_st95.py trace ROOT RECORD [RECORD ...]
    python benchmarks/bench_st95.py oracle ROOT RECORD [RECORD ...]
    python benchmarks/bench_st95.py frame ROOT RECORD [RECORD ...]

The cells ``ROOT/reports/RECORD/mlr-none`` are bench_st94b's (``bench_st94b.py fresh ROOT``
makes them: its records lr9681 / dl9682 / lr9684 / dl9685, spent).

``trace``: bench_st94b's ``trace`` (without bench_st93's part), the C's numpy mirror logging every
row where its sensors out (``out``, ``out2``) change or it names an event; each case whose first
C event is ``apart`` (a ``STEP_OUT`` with the field not whole since the campaign's first sample)
printed with that log (row, the row's first C rule, its sensor, the sensors out after it) and
classed:

* ``one-back``: every exclusion before it by a rule the block names (``JUMP``, ``DROPOUT``,
  ``OFF_RANGE``, ``STEP_OUT``), never two out at once, every return by ``BACK`` (or ``SPIKE``,
  which the block follows already), none out at the STEP_OUT's row;
* ``one-other``: one out at most, but an exclusion or a return the block cannot follow
  (``DRIFT_OUT``, ``FREEZE``, ``THAWED``, ``FOLLOWED``, ...);
* ``two``: two out at some row before it.

(The log holds a row's first C rule only: an exclusion and a return in one row would be missed.)

``oracle``: ``trace`` with the block *told* each C re-admission by ``BACK`` that leaves none out
(:meth:`Logged.resumed`: ``mon_lost`` cleared, ``mon_prev_e`` the C's errors of that row): what a
block that followed the return exactly would do, the field counted whole again where the log is
``one-back``.  ``frame``: the same told block over a record's whole healthy frame, every row where
the C names an event or the block flags printed (a block flag without a C event is a false one).

Results (2026-12-06, da11b4dd's block, 2 cores shared; CPU of this process)::

    trace (79.8 s): apart 15 = bench_st94b's 15 (5 bent, 10 pair), every one ``one-back``:
      lr9681  3 (2 bent, 1 pair)  STEP_OUT T_head_right 3195, BACK 3207; the case's STEP_OUT 3674
      dl9682  6 pair              STEP_OUT / BACK T_col_front_top 250/261, T_zdrive 408/420,
                                  T_bed_left 3025/3037, T_head_right 5443/5454; the cases' 6121
      lr9684  1 bent              JUMP T_spindle_front 3501, BACK 3512; the case's STEP_OUT 3674
      dl9685  5 (2 bent, 3 pair)  STEP_OUT T_head_left 1857, BACK 1867; the cases' 6121
    each out 10-12 rows, no C event while it was out, none out at the C's STEP_OUT.

    oracle (86.0 s): the 15 ``agree`` (the block's STEP_OUT at the C's row, its sensor), mismatch
      0, early 0; pair agree 91 / 91 / 91 / 91 (was 90 / 85 / 91 / 88); bent agree 3 / 0 / 1 / 2.
      Every other count of the bent and pair tables as ``trace`` prints them.  (On da11b4dd the
      bent ``other`` / ``none`` differ from bench_st94b's table -- lr9681 10 / 11 against 4 / 17:
      jump94b's SETTLED came after it; its ``apart`` 15 and the pair tables are as printed there.)

    frame (24.6 s): every C exclusion after a BACK named alike by the told block at its row (dl9682's
      STEP_OUT T_zdrive 408, T_bed_left 3025, T_head_right 5443; lr9684's JUMP T_bed_left 4062,
      T_spindle_rear 4097; dl9685's JUMP T_bed_right 6658), 0 block flags on rows without a C
      event.  Where the two part: lr9684's blind T_spindle_front (3501) and T_spindle_rear (4097)
      jump, the block undoes each one row later (its SPIKE, 3502 / 4100) where the C holds it out
      to a BACK (3512 / 4110); lr9681's SETTLED T_table (3948) re-references in the C only.

What it says (readings of watch.CodeMonitor, not measured): the ``BACK`` that re-admitted each of
these is judged with every sensor in -- the whole set's operator the block holds already
(``MON_SELF``, ``MON_SCALE``), the whole set's warning band times ``READMIT`` over the window's
``w x n`` readings, ``calm`` / ``run`` / ``dwell`` (``window 2^outs`` for a STEP_OUT culprit)
counters; no single-out operator is needed to follow these returns (about n + 3 constants, 17
for these 14 sensors, and a ``w x n`` ring, against 14^3 + 3 14^2 = 3332 constants for the
single-out operators and bands).  Those are needed only to know, while one is out, that the C
takes no second out (its stepped and drift judgements on the set without it): none did in these
15.  Next step: the block follows BACK exactly (ring, counters, the whole set's band) and stops
judging at any C judgement it cannot see while one is out (the single-out stepped / drift tests,
or conservatively: stops where any judged sensor's error leaves its warning band), then the bar
of the brief on fresh seeds (9749-9753 were not simulated here).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st94  # noqa: E402
import bench_st94b  # noqa: E402
from _cli import run_commands  # noqa: E402

SEEN = ("JUMP", "DROPOUT", "OFF_RANGE", "STEP_OUT")      # exclusions the block names
BACKS = ("BACK", "SPIKE")                                # returns the rule would follow


class Logged(bench_st94b.Whole):
    """bench_st94b's steppers, the C's outs and events logged (the log rides on each row's rule)."""

    def rows(self, part):
        from thermocomp.apps.deploy.export.watch import RULES

        for c, want, said, (bits, rule, sensor), moved in super().rows(part):
            w = self.sim.watch
            outs = (int(w.out), int(w.out2))
            if outs != self.outs or int(rule):
                self.log = [*self.log, (self.row, RULES[int(rule)], int(sensor), self.outs, outs)]
            rule.log, rule.before = self.log, self.outs
            if ORACLE and outs == (-1, -1):
                self.resumed(rule, bits)
            self.outs, self.row = outs, self.row + 1
            yield c, want, said, (bits, rule, sensor), moved

    log, outs, row = (), (-1, -1), 0

    def resumed(self, rule, bits) -> None:
        """(``oracle``) The block told the C's re-admission by ``BACK`` that leaves none out: it
        judges on from this row with the whole set, its last errors the C's (the state a block
        that followed the return would hold); the field counted whole again where every
        exclusion so far was one the block names, one at a time, each back by BACK or SPIKE."""
        from thermocomp.apps.deploy.export.watch import READMITTED, RULES

        if RULES[int(rule)] == "BACK" and bits & READMITTED:
            v = self.fb.vars
            v["mon_lost"], v["mon_e_known"] = False, True
            v["mon_prev_e"][:] = [float(e) for e in self.sim.watch.prev_e]
            self.kept_whole = classed(self.log, (-1, -1)) == "one-back"


def classed(log, before) -> str:
    """``one-back`` / ``one-other`` / ``two`` (module doc) of an apart case's C log."""
    if any(min(o) >= 0 for *_, o in log) or min(before) >= 0:
        return "two"
    for _, rule, _, was, now in log:
        went_out = sum(k >= 0 for k in now) > sum(k >= 0 for k in was)
        came_back = sum(k >= 0 for k in now) < sum(k >= 0 for k in was)
        if (went_out and rule not in SEEN) or (came_back and rule not in BACKS):
            return "one-other"
    return "one-back"


TALLY: dict = {}
ORACLE = False


def _line(got: dict, names, plain=bench_st94b._line) -> str:
    first = got["first"]
    text = plain(got, names)
    if first is None or bench_st94._first_kind(first) == "other" or not getattr(first[1][0], "log", ()):
        return text
    if not ORACLE and bench_st94b._first_kind(first) != "apart":
        return text
    if ORACLE and first[1][0].log[:-1] == first[1][0].log[:0]:
        return text
    rule = first[1][0]
    kind = classed(rule.log[:-1], rule.before)
    TALLY[kind] = TALLY.get(kind, 0) + 1

    def name(k):
        return names[k] if k >= 0 else "-"

    said = "; ".join(f"{row + 1} {r or '.'} {name(s)} out {'/'.join(name(k) for k in now if k >= 0) or '-'}"
                     for row, r, s, _, now in rule.log)
    return f"{text} [{kind}: {said}]"


def oracle(root: str, *records: str) -> None:
    """``trace`` with the block told the C's BACK returns (module doc)."""
    global ORACLE
    ORACLE = True
    trace(root, *records)


def healthy_frame(root: str, record: str) -> tuple:
    """``(deployed, state space, fed rows)`` of the cell ``ROOT/reports/RECORD/mlr-none``: its
    first test campaign's whole healthy frame, the lead-in first (also bench_st97's)."""
    from thermocomp.apps.deploy.export import state_space
    from thermocomp.apps.deploy.export.pack import fed
    from thermocomp.apps.deploy.report import plain
    from thermocomp.shell.stages.export import lead_ins

    model = Path(root).resolve() / "reports" / record / "mlr-none" / "model.pkl"
    deployed, ds, _, test_ids = bench_st94.deployed_cell(Path(root).resolve(), record, model)
    cid = test_ids[0]
    rows = fed(ds.campaigns[cid], lead_ins(plain(deployed).compensator, ds, [cid]).get(cid))
    return deployed, state_space(deployed, monitor=True), rows


def frame(root: str, *records: str) -> None:
    """The told block and the C over each record's whole healthy frame (module doc)."""
    from thermocomp.apps.deploy.export import exported_files
    from thermocomp.apps.deploy.export.watch import BAND, EXCLUDED, READMITTED, RULES

    global ORACLE
    ORACLE = True
    for record in records:
        deployed, ss, rows = healthy_frame(root, record)
        names = [*[ss.inputs[i] for i in ss.monitor["inputs"]], "-"]
        said = []
        for i, (_, _, (flag, rule, s), (bits, crule, cs), _) in enumerate(
                Logged(ss, exported_files(deployed, "st")["compensator.st"]).rows(rows)):
            event = bits & ~BAND and (int(crule) or bits & (EXCLUDED | READMITTED))
            if flag or event or rule:
                said.append(f"{i + 1} C {RULES[int(crule)] or '.'} {names[cs]} / ST "
                            f"{'flag ' if flag else ''}{RULES[rule] or '.'} {names[s]}")
        print(f"{record} {len(rows)} rows: {'; '.join(said)}", flush=True)


def trace(root: str, *records: str) -> None:
    """The ``trace`` log (module doc)."""
    bench_st94.HELD = (*bench_st94.HELD, "STEP_OUT")
    bench_st94.Both, bench_st94.compared = Logged, bench_st94b._compared
    bench_st94._first_kind, bench_st94._added = bench_st94b._first_kind, bench_st94b._added
    bench_st94._line = _line
    for record in records:
        print(f"== {record}", flush=True)
        bench_st94.trace(root, record)
        print(f"apart so far: {TALLY}", flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"trace": trace, "oracle": oracle, "frame": frame}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
