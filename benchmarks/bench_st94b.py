"""The Structured Text block judges a sensor's self-prediction error (the C's ``STEP_OUT``) while
the field is whole (st94b, issue 34; follow-up of st94, whose block held BENT and the pair jump
but counted the C's stepped exclusions apart: 3 healthy and 6 under spikes on 9614-9618, 3 of 430
pairs and 17 bent cases on 9666-9670).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the block measured is that tree's)::

    python benchmarks/bench_st94b.py trace ROOT RECORD
    python benchmarks/bench_st94b.py fresh ROOT [RECORD ...]

``trace``: bench_st94's ``trace`` (its module doc: the cell ``ROOT/reports/RECORD/mlr-none``
deployed as ``export`` deploys it, its ST block and the C's numpy mirror stepped together from a
reset over the fed rows of its first test campaign: ``healthy``, then ``bent`` and ``pair``
cases) with the C's ``STEP_OUT`` among the rules the block names, each case's first C event
classed:

* ``agree`` / ``mismatch``: a C event of a rule the block holds -- now ``STEP_OUT`` too -- named
  alike (rule, sensor) at its row by the block, or not;
* ``apart``: a C ``STEP_OUT`` where the C's field was not whole since the campaign's first sample
  (a sensor out before it, by a rule the block does not see: a drift, a freeze in the lead-in;
  or re-admitted by a band);
* ``other``: a C rule the block does not hold (drift, freeze, ...);

and ``early``: the block's flags (``mon_flag``, or ``mon_rule`` ``STEP_OUT``) on rows before the
C's first event (the C silent: each a false flag).  Then bench_st93's ``trace`` (healthy and
planted spike / dropout / range / freeze per monitored sensor, served / hits / misses / stepped /
other / false against the served monitor) on the same cell.

``fresh``: both on the fresh records of :data:`FRESH` (bench_st93b's generators: bench_cmon91's lr
/ dl / cr / lr / dl, seeds 9681-9685, given for this rule), each simulated and ``run model=mlr``
once under ``ROOT`` (bench_cmon92's ``made``).

What the block does (src/thermocomp/apps/deploy/export/st_watch.py): while no monitored reading
has been missing, beyond its range or jumping since the campaign's first sample, nor a stepped
error flagged (a BENT re-reference keeps it whole), it computes each judged sensor's
self-prediction error ``e = (d - M d) / (1 - h)`` with ``M`` / ``h`` the POD's operator and
leverages with every sensor in -- the fixed first operator the C holds (``MON_SELF``,
``MON_SCALE``) -- on the readings against their references (the first sample's, moved by the
block's re-references), and where ``|e|`` and ``|e - e_prev|`` reach the alarm band
(``MON_ALARM``) flags the C's culprit (largest ``|de| sqrt(1 - h)``) ``STEP_OUT`` (``BLIND``
where the C does not hold it out).  It reads the sensor on (no POD rebuild) and judges no more.

The BAR (written and committed before any of 9681-9685 was simulated)::

1. Healthy, every fresh record: 0 false flags (bench_st93's ``false`` and this trace's
   ``early``); ``max|ST-C|`` <= 1e-9 µm over the rows before the C's first event.
2. Every C ``STEP_OUT`` first event with the field whole since the campaign's first sample
   (healthy, bent and pair cases, every fresh record) named by the block at its row with the
   sensor and ``STEP_OUT``: ``mismatch`` 0 over all cases; ``early`` 0 in every case;
   ``max|ST-C|`` <= 1e-9 µm before each case's first C event.
3. bench_st93's planted kinds on every fresh record: ``misses`` 0 and ``false`` 0.
4. No case bench_st93b / bench_st94 passed changes: ``bench_st93b.py fresh`` on copies of
   9614-9618 and ``bench_st94.py fresh`` on copies of 9666-9670 (spent; their models) with this
   block print their docstring tables again, except that ``other`` first events that are C
   ``STEP_OUT`` with the field whole may become ``agree``.
The field whole as the block can know it: "since the campaign's first sample" -- the block
cannot tell when the C re-admits a sensor (a calm window, a band judged by the POD of a set
with it out), so C ``STEP_OUT`` after a re-admission are counted ``apart``, reported, not
misses (the brief's "field whole" read so, said here before scoring).
KEPT if 1-4 hold on all five fresh records; REFUSED with the cases named otherwise (src as on
main, the rule's diff in benchmarks/st94b_rule.patch); TRACED if it cannot be scored by the
deadline.

The bar is unchanged since its commit (f1813acf, before 9681-9685 were simulated); nothing was
tuned on them.  Seen before (development, spent lr9666 of st94): healthy 0 flags; bent T_table
2x / 2.9x the C's ``STEP_OUT`` of T_col_back named alike (2), one pair too; early 0.

Results (2026-12-05; 2 cores shared by 7-8 helpers).  ``fresh /tmp/st94b/fresh`` scored once
(111.9 s of this process's CPU for the five, each record's simulation and ``run model=mlr`` a few
seconds more)::

    record  healthy: false early  max|ST-C| µm (rows)  C's first event (row) = the block's
    lr9681           0     0      1.05e-13 (3194)      STEP_OUT T_head_right (3195, lead-in)
    dl9682           0     0      6.22e-14 (249)       STEP_OUT T_col_front_top (250, lead-in)
    cr9683           0     0      1.78e-14 (189)       none
    lr9684           0     0      1.21e-13 (3500)      JUMP T_spindle_front (3501)
    dl9685           0     0      1.07e-13 (1856)      STEP_OUT T_head_left (1857, lead-in)

    record  bent cases: agree/mismatch/apart/other/none  early  max|ST-C|   pair: agree/mismatch/apart  early
    lr9681  24          1/0/2/4/17                       0      1.0e-13     91: 90/0/1                  0
    dl9682  16          0/0/0/0/16                       0      1.0e-13     91: 85/0/6                  0
    cr9683   8          1/0/0/0/7                        0      2.1e-14     66: 66/0/0                  0
    lr9684  24          0/0/1/1/22                       0      8.3e-14     91: 91/0/0                  0
    dl9685  20          0/0/2/3/15                       0      9.9e-14     91: 88/0/3                  0

    bench_st93's kinds (served / hits / misses / stepped / other / false), every record:
    spike   12/10/12/13/11 served, all hit, misses 0, stepped 1/4/0/0/3, other 1/0/0/1/0, false 0
    dropout 14/14/12/14/14 all hit, false 0;  range 14/14/12/14/14 all hit, false 0
    freeze  other 6/13/11/6/14, false 0;  healthy served 0/0/0/3/1 all hit, stepped 1/4/0/0/1, false 0

Every C ``STEP_OUT`` with the field whole since the campaign's start is named by the block at
its row with the sensor: the three healthy ones (lr9681, dl9682, dl9685, in the lead-in), 0
mismatches, 0 early flags in the 5 healthy runs and 522 cases. ``apart`` 15 (5 bent, 10 pair):
on lr9681 / dl9682 / dl9685 every case starts after the lead-in's stepped error, on lr9684 after
its jump at row 3501; the C took the sensor out, re-admitted it by its band (or holds one out),
and judges on; the block, flagged there, judges no more. No bent or pair case on a fresh record
reached a C ``STEP_OUT`` with the field whole from the start (the bent and pair ``agree`` are
JUMPs): the rule's reach beyond the lead-in is measured by the test and lr9666 (seen), not by
these draws.

Bar item 4 (this block): ``bench_st93b.py fresh`` on copies of 9614-9618 (38.9 s CPU) printed its
docstring's table again, every count and max|ST-C| 9.24e-14 / 9.95e-14 / 1.07e-14 / 9.24e-14 /
1.03e-13 µm; ``bench_st94.py fresh`` on copies of 9666-9670 (75.2 s CPU) its table again (bent
C BENT 3/3, 2/2, 3/3, 2/2, 1/1, re-ref 6/6 on dl9670; first agree/other 0/6, 0/3, 0/0, 0/5, 5/3;
pairs agree 90 / 91 / 66 / 90 / 90, other 1 / 0 / 0 / 1 / 1; max|ST-C| to the digit): bench_st94
counts a ``STEP_OUT`` first event ``other`` by its own HELD, so nothing it passed changed.

After scoring, measurement only (spent 9666-9670, st94's models; this bench's ``trace`` without
bench_st93's part, ~80 s CPU): of st94's 20 stepped ``other`` cases, the C ``STEP_OUT`` with the
field whole named alike 3 (lr9666: T_table 2x / 2.9x, one pair), plus lr9669's healthy one (row
2278); 6 apart (lr9669, dl9670: after the lead-in's stepped error); 0 mismatches, 0 early.

Verdict by the bar as written: 1-4 hold on all five fresh records: KEPT -- with the limit above:
the block's judgement ends at the campaign's first exclusion, and 15 fresh C ``STEP_OUT`` after
a re-admission stay with the C.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st93  # noqa: E402
import bench_st94  # noqa: E402
from _cli import run_commands  # noqa: E402
from bench_cmon91 import FRESH as CMON91_FRESH  # noqa: E402

# bench_cmon91's generators (lr / dl / cr / lr / dl) on the seeds given, chosen before any was simulated
FRESH = {f"{record[:2]}{seed}": [f"seed={seed}" if w.startswith("seed=") else w for w in words]
         for (record, words), seed in zip(CMON91_FRESH.items(), range(9681, 9686))}


class Rule(int):
    """A C rule code that knows whether the C's field was whole since the campaign's start."""

    whole = True


class Whole(bench_st94.Both):
    """bench_st94's pair of steppers, the C's rule marked with its field's wholeness (no sensor
    out at any row since the reset, before this one's step)."""

    def rows(self, part):
        for c, want, said, (bits, rule, sensor), moved in super().rows(part):
            rule = Rule(rule)
            rule.whole = self.kept_whole
            w = self.sim.watch
            self.kept_whole = self.kept_whole and w.out < 0 and w.out2 < 0
            yield c, want, said, (bits, rule, sensor), moved

    kept_whole = True


def _first_kind(first, plain=bench_st94._first_kind) -> str:
    from thermocomp.apps.deploy.export.watch import RULES

    if first is not None and RULES[first[1][0]] == "STEP_OUT" and not getattr(first[1][0], "whole", True):
        return "apart"
    return plain(first)


def _compared(rows, plain=bench_st94.compared) -> dict:
    """bench_st94's ``compared`` with ``early``: the block's flags before the C's first event."""
    from thermocomp.apps.deploy.export.watch import STEP_OUT

    out = plain(rows)
    stop = out["first"][0] if out["first"] is not None else len(rows)
    out["early"] = sum(1 for _, _, (flag, rule, _), *_ in rows[:stop] if flag or rule == STEP_OUT)
    return out


def _added(total: dict, got: dict, plain=bench_st94._added) -> dict:
    total["early"] = total.get("early", 0) + got["early"]
    return plain(total, got)


def _line(got: dict, names, plain=bench_st94._line) -> str:
    return f"{plain(got, names)}, early {got['early']}"


def fresh(root: str, *chosen: str) -> None:
    """Both traces on :data:`FRESH` (module doc), each record made once by bench_st93's ``fresh``."""
    bench_st93.fresh(root, *chosen, records=FRESH, traced=trace)


def trace(root: str, record: str) -> None:
    """The ``trace`` tables (module doc)."""
    bench_st94.HELD = (*bench_st94.HELD, "STEP_OUT")
    bench_st94.Both, bench_st94.compared = Whole, _compared
    bench_st94._first_kind, bench_st94._added, bench_st94._line = _first_kind, _added, _line
    bench_st94.trace(root, record)
    bench_st93.trace(root, record)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"trace": trace, "fresh": fresh}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
