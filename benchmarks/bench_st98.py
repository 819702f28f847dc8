"""The Structured Text block judges a frozen sensor as the C does (st98, issue 34; the note's
"ST: freeze": before st98 the block judged no freeze at all, and since mon97 the C takes a
dithered reading constant past ``dither_run`` out as frozen too).

The rule (st_watch.py ``BLOCK``, ``freeze_constants``; no key, on where the block judges the
stepped error, ``MON_STEP_JUDGE``): per monitored sensor the run of samples whose reading, in
range, equals its last one (``mon_frun``, DINT: the C's ``run``), and at the run's first sample
the others' prediction of it with every sensor in (``mon_fpred``: ``d - e`` of the block's
``MON_SELF`` / ``MON_SCALE``, the C's ``run_pred``).  While the block's field is whole and none
is held out, a sensor is frozen, as in the C's ``frozen``, where its run passes ``dither_run``
(``MON_DITHER_RUN``: mon97's dithered reading), or, one no other predicts, ``blind_run``
(``MON_BLIND_RUN``), or, one the others predict, it reaches ``seen_run`` (``MON_SEEN_RUN``) with
their prediction moved by its warning band (``MON_WARN``) since the run began.  The first frozen
sensor of the sample is named ``FREEZE`` (``mon_rule`` 2, the C's code; ``BLIND`` where the C
does not hold it out: ``MON_FREEZE_HELD``) and flagged, the block's judgement ending there
(``mon_lost``: the C rebuilds it or holds it, a set the block does not follow).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the block measured is that tree's;
the BASE block is 16d3b58d's st_watch.py ``OUTPUTS`` / ``BLOCK`` read from git into this tree's
export, bench_st97d's ``base_block``)::

    python benchmarks/bench_st98.py cases ROOT RECORD [RECORD ...]

``cases``: per record (:data:`SEEN`, :data:`FRESH`, or bench_st97d's seen records; simulated into
``ROOT/data`` and ``run model=mlr`` into ``ROOT/reports`` by bench_cmon92's ``made``, each once)
its first test campaign's fed frame (bench_cmon92's ``faulted_cell``: its lead-in, faults from a
quarter of the campaign in), the block, the BASE block and the C's numpy mirror stepped together.
``healthy``: the whole frame: ``diff rows`` (rows where ``c``, ``n_clamped``, ``refused``,
``mon_flag``, ``mon_rule`` or ``mon_sensor`` differ from BASE's, bit for bit), the block's and
the C's FREEZE rows, the C's first event and ``max|ST-C|`` before it.  ``frozen``: from the
onset, per monitored sensor, its reading held at its onset value for 60 rows, 60 past
(bench_cmon92's ``planted`` freeze, mon97's ``frozen`` case on each sensor in turn): the C's
first event (row from the onset, rule, sensor), the block's first flag and BASE's, the class
``agree`` (a C FREEZE or BLIND named alike, row, rule and sensor), ``mismatch`` (a C FREEZE /
BLIND not so named), ``other`` (the C's first event of another rule), ``false`` (a block flag
before the C's first event), ``ended`` (a C FREEZE / BLIND not named where the block's judgement
had ended before the onset: ``mon_lost`` at the case's start, marked by an earlier flag of the
block), ``max|ST-C|`` before it.

Records.  SEEN (spent): sw9776 / cr9763 / lr9376 (mon97's seen), tr9828 (audit97's stuck
``T_ram``).  FRESH (never simulated before this bench's bar): sw9853, cr9854, lr9855 (mon97's
generators), tr9856 (audit97's trunnion63), sw9857.

Seen, traced before the bar (``cases /tmp/st98/seen``: mon97's seen data and models, tr9828
kelvin97's; 5.0 s + 73.6 s CPU): every healthy frame 0 diff rows, no FREEZE of either; frozen
cases: cr9763 11 agree (10 at row 11, T_headstock at row 5: the field's rule), 1 other (a C
BLIND_OUT of T_nc_spindle_motor at row 5, named alike); sw9776 12 agree; lr9376 14 agree (the
block judging at the onset though the C took T_col_back out and back in the lead-in); tr9828 9
agree (T_ram: row 11, FREEZE); max|ST-C| <= 1.99e-13 um before the C's first event.  bench_st97d's
seen lr9790: the block's judgement ended at row 3607 (its JUMP of T_motor, a C JUMP), before the
onset: 14 C FREEZE unnamed (the block's flags there the reading's return, JUMP, as BASE's): the
class ``ended``.

BAR (written and committed BEFORE any of 9853-9857 was simulated; scored once, this tree's block)
---
1. Frozen, every fresh record, every monitored sensor: every case whose C first event is a FREEZE
   or BLIND (the C's freeze of one it does not hold) is named by the block at that row with that
   rule and sensor (``agree``), ``mismatch`` 0 where the block judges at the onset; ``false`` 0;
   ``max|ST-C|`` <= 1e-9 um before the C's first event in every case.  ``ended`` (the block's
   judgement ended before the onset by an earlier flag of its own) counted and reported, not
   scored: the rule judges while the field is whole, as the stepped error (st94b).
2. Healthy, every fresh record: 0 diff rows against the BASE block over the whole fed frame (so
   0 new block events); no block FREEZE row.
3. The existing ST benches unchanged: ``cases`` on bench_st97d's 11 seen records (their first
   test campaign): 0 healthy diff rows against BASE; ``bench_st97d.py cases`` on the same records
   prints its docstring's classes (a/m/o/n per record) with 0 diff rows and 0 stop rows.
4. Seen (above, already traced, restated): sw9776 / cr9763 / lr9376 / tr9828 mismatch 0, false 0.
KEPT if 1-4 hold (with the test failing on BASE, PARSED_DIGEST, docs); REFUSED otherwise
(benchmarks/st98_rule.patch, src as on BASE).

Scored (2026-12-06, 2 cores shared by up to 8 helpers, load 12-22; the bar unchanged since its
commit 00cf7e5e, the fresh records simulated after it by this bench, ``cases /tmp/st98/fresh
sw9853 cr9854 sw9857`` and ``... lr9855 tr9856`` in two processes, once; 17.8 + 74.0 s CPU)::

    record  test  rows (lead-in)  healthy diff rows  C first event (ST alike)   frozen    max|ST-C| um
    sw9853  prod  1441 (0)        0                  none                       12 agree  3.55e-14
    cr9854  C07   236 (0)         0                  none                       12 agree  2.13e-14
    lr9855  R1b   4321 (3457)     0                  2688 STEP_OUT T_head_left  14 agree  1.19e-13
    tr9856  W3    30240 (20160)   0                  none                       9 agree   1.85e-13
    sw9857  prod  1441 (0)        0                  none                       12 agree  4.97e-14

1 MET: 59 of 59 frozen cases agree (the C's FREEZE, every one held, named at its row with the
sensor: row 11 from the onset 50, row 10 8, row 9 1), mismatch 0, false 0, ended 0 (the block
judging at the onset on every fresh record), max|ST-C| <= 1.85e-13 um before the C's first event.
BASE on the same cases: no FREEZE; the reading's return a JUMP at row 60 on 20, nothing on 39.  2
MET: 0 diff rows on the five healthy frames, no FREEZE row of either.  3 MET: ``cases
/tmp/st98/st97d`` on bench_st97d's 11 records (154.6 s CPU): 0 healthy diff rows on each;
``bench_st97d.py cases`` on them (147.6 s CPU): its docstring's a/m/o/n again, lr9823 7/3/4/10,
lr9790 2/4/0/14, dl9768 9/0/5/18, dl9791 3/7/3/7, cr9792 1/0/0/23, lr9793 5/0/2/13, dl9794
1/4/0/11, lr9820 5/0/3/12, dl9821 5/0/3/16, cr9822 0/0/0/24, dl9824 6/0/0/14, 0 diff rows, 0
mon_stop rows (both on 00cf7e5e's block).  4 MET (above).  VERDICT: KEPT.

Changed after the scoring, said: the block's freeze flag now goes through the stepped error's
culprit path (the frozen sensor the culprit, one flag / rule path: duplicates' pair), the same
outputs by construction; ``cases`` reprinted sw9853 / cr9854 / sw9857 / lr9855 line for line
(31.8 s CPU, copies of the records) and the seen sw9776 / cr9763.

Beside the bar, bench_st97d's records (seen; frozen cases): dl9768 14, cr9792 11, lr9793 14,
lr9820 14, dl9821 13, cr9822 12, lr9823 14, dl9824 14 agree; ``ended`` 42: lr9790, dl9791 and
dl9794 (14 each), whose block judgement ended before the onset (its own JUMP at 3607, STEP_OUT at
986 / 4263): the freeze unnamed there as before (the block silent or the return's JUMP);
``other`` 2 (cr9792 T_nc_z1_drive, dl9821 T_xdrive): the C's first event a new thermal state
(flags 72, no rule) a row or two before its FREEZE, which the block names alike at its row (11).
Seen cr9763 T_nc_z1_drive (``other``): the C's BLIND_OUT of T_nc_spindle_motor at row 5 (named
alike), then its FREEZE of T_nc_z1_drive at row 10 as the second out: the block, one held out,
judges no freeze (said in the rule) and is silent there.

Traced after the verdict (seen only, not the rule, not in src): benchmarks/st98_after_lost.patch
judges the two run rules (``MON_DITHER_RUN``; ``MON_BLIND_RUN`` of one no other predicts) also
after the block's judgement ended, once a run (at run + 1), of a sensor the block does not hold
re-referenced out (``mon_out``), where no rule named the row.  ``cases /tmp/st98/exprec lr9790
dl9791 dl9794`` on it (48.8 s CPU): the 42 ``ended`` cases all ``agree`` (FREEZE at the C's row
10-11), healthy diff rows 0 on the three.  A candidate for a next stop, with its own bar and fresh
seeds: the C may hold a sensor out there that the block cannot see (its freeze then not the C's).
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st94  # noqa: E402
import bench_st97d  # noqa: E402
from _cli import run_commands  # noqa: E402

BASE = "16d3b58d"


def generators() -> dict:
    """Every record's simulate words: :data:`SEEN`, :data:`FRESH` and bench_st97d's."""
    import bench_audit97
    import bench_mon97

    fresh = {"sw9853": [*bench_mon97.SW, "seed=9853"], "cr9854": [*bench_mon97.CR, "seed=9854"],
             "lr9855": [*bench_mon97.LR, "seed=9855"],
             "tr9856": [*bench_audit97.TRUNNION[1:], "seed=9856"],
             "sw9857": [*bench_mon97.SW, "seed=9857"]}
    return {**bench_st97d.generators(), **bench_mon97.SEEN, **bench_audit97.FAULTED, **fresh}


class Three(bench_st97d.Three):
    """The block, the BASE block and the C stepped together (bench_st97d's)."""

    def rows(self, part):
        """Per row ``Both.rows``'s, then ``(whether an output differs from BASE's, BASE's (flag,
        rule, sensor))``."""
        for got, (differs, *_) in super().rows(part):
            b = self.base.vars
            yield got, (differs, (bool(b["mon_flag"]), int(b["mon_rule"]), int(b["mon_sensor"])))


def _first(rows) -> dict:
    """``rows`` (:meth:`Three.rows`'s, listed): the C's first event (row, rule, sensor), the
    block's and BASE's first flag, max|ST-C| before the C's, diff rows, FREEZE rows of each."""
    from thermocomp.apps.deploy.export.watch import FREEZE

    out = {"c": None, "st": None, "base": None, "diff": 0.0, "rows": 0, "st_freeze": [],
           "c_freeze": []}
    for i, ((c, want, (flag, rule, sensor), (bits, crule, csensor), _), (differs, b)) in enumerate(rows):
        out["rows"] += differs
        if out["c"] is None and bench_st94.c_event(bits, crule):
            out["c"] = (i, crule, csensor)
        if out["c"] is None:
            out["diff"] = max(out["diff"], float(np.max(np.abs(c - want))))
        if out["st"] is None and flag:
            out["st"] = (i, rule, sensor)
        if out["base"] is None and b[0]:
            out["base"] = (i, b[1], b[2])
        out["st_freeze"] += [i] if rule == FREEZE else []
        out["c_freeze"] += [i] if crule == FREEZE and bits else []
    return out


def _kind(got: dict) -> str:
    from thermocomp.apps.deploy.export.watch import BLIND, FREEZE

    if got["st"] is not None and (got["c"] is None or got["st"][0] < got["c"][0]):
        return "false"
    if got["c"] is None:
        return "none"
    if got["c"][1] not in (FREEZE, BLIND):
        return "other"
    return "agree" if got["st"] == got["c"] else "mismatch"


def _said(event, names) -> str:
    from thermocomp.apps.deploy.export.watch import RULES

    if event is None:
        return "-"
    i, rule, sensor = event
    return f"{i} {RULES[rule] if rule else '-'} {names[sensor] if sensor >= 0 else '-'}"


def cell(root: Path, record: str, made_by: dict, base_rev: str = BASE):
    """``record`` made under ``root`` (bench_cmon92's ``made`` with ``made_by``'s words, once) and
    its first test campaign as bench_cmon92's ``faulted_cell``: ``(ss, fed frame, lead-in rows,
    onset, campaign, monitored names, block, ``base_rev``'s block)``."""
    import bench_audit97
    from bench_cmon92 import faulted_cell, made

    from thermocomp.apps.deploy.export import exported_files

    if record.startswith("tr"):
        bench_audit97._trunnion_env()
    made(root, record, "mlr", made_by)
    deployed, ss, frame, lead, start, cid = faulted_cell(root, record, "mlr-none")
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    block = exported_files(deployed, "st")["compensator.st"]
    return ss, frame, lead, start, cid, names, block, bench_st97d.base_block(deployed, base_rev)


def cases(root: str, *records: str) -> None:
    """The ``cases`` lines (module doc)."""
    from bench_cmon92 import planted

    base_root = Path(root).resolve()
    for record in records:
        ss, frame, lead, start, cid, names, block, base = cell(base_root, record, generators())
        three = Three(ss, block, base)
        head = list(three.rows(frame.iloc[:start]))
        at_start = copy.deepcopy(three)
        whole = _first(head + list(three.rows(frame.iloc[start:])))
        blind = [n for n, p in zip(names, ss.monitor["predictable"]) if not p]
        print(f"{record} {cid}: {len(frame)} fed rows ({lead} lead-in), onset {start}; blind {blind}; "
              f"dithered {int(np.sum(np.isfinite(ss.monitor.get('dither_run', []))))} of {len(names)}; "
              f"healthy: diff rows {whole['rows']}, ST FREEZE rows {whole['st_freeze'] or '-'}, C FREEZE "
              f"rows {whole['c_freeze'] or '-'}, C first {_said(whole['c'], names)}, ST first "
              f"{_said(whole['st'], names)}, BASE first {_said(whole['base'], names)}, max|ST-C| "
              f"before the C's {whole['diff']:.3g} um; block state at onset lost "
              f"{bool(at_start.fb.vars['mon_lost'])}", flush=True)
        tally = {}
        for sensor in names:
            run = copy.deepcopy(at_start)
            got = _first(list(run.rows(planted(frame, start, (sensor,), "freeze"))))
            kind = _kind(got)
            kind = "ended" if kind == "mismatch" and at_start.fb.vars["mon_lost"] else kind
            tally[kind] = tally.get(kind, 0) + 1
            print(f"  frozen {sensor:<20} C {_said(got['c'], names):<28} ST {_said(got['st'], names):<28} "
                  f"BASE {_said(got['base'], names):<28} {kind:<8} max|ST-C| {got['diff']:.3g} um",
                  flush=True)
        print(f"  {record} frozen: {tally}", flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"cases": cases}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
