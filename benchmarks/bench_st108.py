"""The C's ``DRIFT_OUT`` on the ST block's own stop row: dl10178's 20 um traced (st108, issue 34).

st107c (KEPT, in BASE 3a560e8f) left dl10178's ``JUMP`` T_amb 6170 (fresh there) with its 51 after
rows at 20 um off the C, untraced, beside st106's class on dl10127 (after rows 4.4 um).  The brief:
trace it, then the smallest general rule by which the block holds what the C holds after its own
``mon_stop`` or flags every row where it differs.

TRACE (BASE 3a560e8f's src; bench_st107c's records copied from its root; bench_st103b's windows;
2026-12-07, 2 cores shared, load 12-13; CPU user + sys as each command prints it).  VERDICT TRACED:
no src change, no bar committed, fresh 10189-10191 NOT drawn (unspent).

* ``rows`` dl10178 T_amb 6168 6232 (25.9 s): the T_amb JUMP is held as the C's to its BACK 6180
  (<= 5e-14 um).  On 6181 the C takes T_bed_right out by ``DRIFT_OUT`` (its ``_lone_fault``) and,
  on the same row, T_bed_left beside it (``_drift``'s partner loop: with T_bed_right out no other
  predicts it); both are ones the others predict, taken out together (the set of the two solved,
  ``_operator``), both out to the window's end.  The
  block's ``mon_stop`` is that row (``mon_stop_row`` 6182, 1-based), so the block stops judging
  and reads both live: 14.2 um on 6181, 14 .. 18 um on the rows printed (20 the window's max, as
  st107c).  So dl10178's 20 um IS this class, with a partner out: two sensors out, not one.
* ``rows`` dl10127 T_amb (same shape, 24.5 s): T_amb back 6180 as the C, ``DRIFT_OUT`` T_col_back
  (others predict it) 6181 = ``mon_stop_row`` 6182, alone, out to the window's end, 3.9 .. 4.4 um.
* ``oracle`` dl10178 (bench_st106's, on this record; 23.5 + 0.4 s, again 20.2 s): the block fed, on
  each row, the C's own read of every sensor the C holds out and the block does not hold (and the
  C's served set) is within 7.1e-14 um of the C on T_amb 6170's 51 after rows (block 20 um): the
  whole 20 um is the two sensors' reads. The same record's other windows show the class beside JUMPs
  too (T_col_back 6170 with T_bed_right / T_bed_left out: hold 21, after 29 um, oracle <= 4.3e-14;
  three JUMPs beside T_col_front_top 1.5 .. 2.2 um, oracle <= 7.1e-14): 4 events, all closed by the
  oracle.
* st106c's refused rule (benchmarks/st106c_rule.patch: the C's lone fault told in the block,
  ``MON_LONE`` / ``MON_LONE_SELF`` / ``MON_LONE_SCALE``, ``DRIFT_OUT`` named, the sensor held as a
  ``STEP_OUT`` to the block's BACK), applied to 3a560e8f in a scratch copy (src only): on dl10127
  it names ``DRIFT_OUT`` T_col_back at 6181 as the C and holds it to the window's end, but every
  row after stays 3.9 .. 4.4 um off (the C rebuilds T_col_back, the block holds a reading) and
  only the naming row is flagged.  On dl10178 it names nothing (T_bed_right has a partner taken
  beside it: ``MON_LONE`` 0) and stops as BASE (14.2 um on 6181).
* ``stops`` on the healthy records (bench_st105's lr/dl 9964-9967, no fault added; 83.0 s): the block
  stops on 3.  lr9965 at 2470: the C takes nothing out from there (0 rows; its veto or new state).
  dl9965 at 5696 (1-based): the C's ``DRIFT_OUT`` T_spindle_rear on that row (5695), BACK 5715,
  20 rows out, up to 1.24 um off the C, 0 of them flagged.  dl9967 at 3117: the C's ``DRIFT_OUT``
  T_col_back 3116, BACK 3128, then a ``BLIND_OUT`` T_bed_right 3505 .. 3516 and a ``STEP_OUT``
  T_head_left 3817 .. 3827 the stopped block does not follow: 33 rows out, up to 3.17 um, 1
  flagged.  (Rows after the C's BACK are not counted here.)  The class is on healthy streams too.
* What follows for a rule.  (1) A flag from the block's stop to the campaign's end (no test of the
  C's choice) would flag lr9965 from 2470 where the C takes nothing out (its veto or new state):
  new flags on a healthy record.  (2) Any rule that tells the C's lone fault (st106c's naming, or
  more) and flags the rows it cannot follow flags dl9965's 20 rows too: the same class on a
  healthy record, 1.24 um off the C and unflagged on BASE.  The brief's bar asks both "every
  differing row flagged" and "0 new flags on healthy records": on dl9965 only a block that
  computes the C's rows (within 1e-9 um) meets both.  That is st106's list: the lone fault with
  its partner (``_lone_fault``, ``_resolves``, the veto, ``_within_rounding`` / ``_hovers``), the
  rebuild over the one-out and two-out operators (``mon_M``: held or QR at run time), the C's
  BACK (``_returning`` / ``_pass_once_back``, the doubled wait, ``FOLLOWED``).  The flag route is
  refused by the bar itself on dl9965, not by a score; how it would differ from st106c: st106c held
  and named one row; a flag rule would name every held row, and needs the partner case (dl10178).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st108.py rows ROOT RECORD SENSOR FIRST LAST
    python benchmarks/bench_st108.py stops ROOT RECORD [RECORD ...]
    python benchmarks/bench_st108.py oracle ROOT RECORD [RECORD ...]

ROOT holds the records as bench_cmon92's ``made`` makes them (bench_st107c's records: its
``make``).  ``rows``: in ``SENSOR``'s window (bench_st103b's, the sensor bumped and dropped) the
rows FIRST..LAST where the C names an event, the block flags, or every fifth: the C's rule, sensor
and out set (each out sensor ``*`` where others predict it), the block's flag, rule, sensor,
``mon_stop_row``, ``mon_blind_lost``, ``mon_lost``, ``mon_held`` and max|C - ST| (um).
``stops``: per record, the whole stream (no fault added): the block's ``mon_stop_row``, the C's
rows with a sensor out from that row on, their max|C - ST| and how many the block flags, the C's
first events from there.  ``oracle``: bench_st106's ``oracle`` on these records (bench_st107c's
fresh among them).
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st102  # noqa: E402
import bench_st103b  # noqa: E402
import bench_st107  # noqa: E402
import bench_st107c  # noqa: E402,F401  (its fresh records in bench_st107.MADE_BY)
from _cli import run_commands  # noqa: E402

MAIN = "3a560e8f"


def _said(v, names) -> str:
    from thermocomp.apps.deploy.export.watch import RULES

    rule, k = int(v["mon_rule"]), int(v["mon_sensor"])
    return (f"ST flag {int(v['mon_flag'])} {RULES[rule] if rule else '-'}:{names[k] if k >= 0 else ''} "
            f"stop_row {int(v['mon_stop_row'])} blind_lost {int(v['mon_blind_lost'])} "
            f"lost {int(v['mon_lost'])} held {int(v['mon_held'])}")


def rows(root: str, record: str, sensor: str, first: str, last: str) -> None:
    """The ``rows`` lines (module doc)."""
    from thermocomp.apps.deploy.export.watch import RULES

    lo, hi = int(first), int(last)
    bench_st107.MAIN = MAIN

    def window(kept, names, name, frame, start):
        if name != sensor:
            return None
        df, back = bench_st102.dropped(frame, name, start)
        k = copy.deepcopy(kept)
        part = df.iloc[start:back + 61]
        U, t = part[k.ss.inputs].to_numpy(float), part["time"].to_numpy(float)
        told = k.ss.monitor["predictable"]
        for i in range(len(part)):
            a = k.tree(U[i], t[i], k.first)
            c = k.sim.step(U[i], t[i])
            k.first = False
            w, v, row = k.sim.watch, k.tree.vars, start + i
            if lo <= row <= hi and (w.rule or v["mon_flag"] or row % 5 == 0):
                said = f"{RULES[int(w.rule)]}:{names[int(w.sensor)]}" if w.rule else "-"
                gone = [names[g] + ("*" if told[g] else "") for g in w.gone]
                print(f"  {row} C {said} out {gone} | {_said(v, names)} | max|C-ST| "
                      f"{np.max(np.abs(c - a)):.3g}", flush=True)
        return {}

    for _ in bench_st103b.windows(root, [record], window, bench_st107.MADE_BY,
                                  bench_st107._main_of(root, record)):
        pass


def stops(root: str, *records: str) -> None:
    """The ``stops`` lines (module doc)."""
    from test_export import StructuredText
    from thermocomp.apps.deploy.export import Simulator
    from thermocomp.apps.deploy.export.watch import RULES

    for record in records:
        _, ss, frame, _, names, tree, _ = bench_st103b._cell(root, record, bench_st107.MADE_BY,
                                                             lambda _: "    N_LAWS : INT := 0;")
        st, sim = StructuredText(tree), Simulator(ss)
        sim.reset()
        U, t = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
        stop, out, flagged, gap, events = 0, 0, 0, 0.0, []
        for i in range(len(frame)):
            a, c = st(U[i], t[i], i == 0), sim.step(U[i], t[i])
            stop = stop or int(st.vars["mon_stop_row"])
            if stop and sim.watch.gone:
                out += 1
                flagged += bool(st.vars["mon_flag"])
                gap = max(gap, float(np.max(np.abs(c - a))))
            if stop and sim.watch.rule and len(events) < 6:
                events.append(f"{i} {RULES[int(sim.watch.rule)]}:{names[int(sim.watch.sensor)]}")
        print(f"  {record}: {len(frame)} rows; block stop_row {stop}; C rows with a sensor out from it "
              f"{out} (max|C-ST| {gap:.3g} um, flagged by the block {flagged}); C events from it {events}",
              flush=True)


def oracle(root: str, *records: str) -> None:
    """bench_st106's ``oracle`` lines, on bench_st107's records (module doc)."""
    import bench_st105
    import bench_st106

    bench_st105.MADE_BY = bench_st107.MADE_BY
    bench_st106.oracle(root, *records)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"rows": rows, "stops": stops, "oracle": oracle}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
