"""The Structured Text block says when it stops judging a blind sensor (st97d, issue 34; follow-up
of st97c, which traced lr9823's 3 bent mismatches to the block's ``BLIND_OUT`` judgement ending
for good, ``mon_blind_lost``, at lead-in row 380 where the C declares a new thermal state, the
block silent from there where the C names faults).

The rule (st_watch.py ``OUTPUTS`` / ``BLOCK``; no key, always on where the block judges
``BLIND_OUT``): two new outputs of ``FB_ThermoComp``, ``mon_stop`` (BOOL, TRUE on the one sample
where the block's ``BLIND_OUT`` judgement ends for the campaign: a drift judgement with every
sensor in reaching the band with no blind sensor explaining it, the C's lone fault, veto or new
thermal state, which the block does not follow) and ``mon_stop_row`` (INT, that sample's number
in the campaign, 1 the first; 0 while the block judges).  Nothing else in the block reads them:
a status for the operator, so that a silent block is not read as "all healthy".

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the block measured is that tree's;
ROOT holds the records as bench_cmon92's ``made(root, record, "mlr", ...)`` makes them, the
generators of :data:`SEEN`; the BASE block is 8ee3ec81's st_watch.py ``OUTPUTS`` / ``BLOCK`` read
from git into this tree's export)::

    python benchmarks/bench_st97d.py stops ROOT [RECORD ...]
    python benchmarks/bench_st97d.py cases ROOT [RECORD ...]

``stops``: per record (all of :data:`SEEN` where none is named) and test campaign, the block, the
BASE block and the C's numpy mirror over the healthy fed frame (its lead-in with it): the rows
where ``mon_blind_lost`` turns TRUE (1-based), the rows ``mon_stop`` is TRUE, ``mon_stop_row`` at
the end and whether it was 0 before the stop and the stop's row from there; the C there (flags,
rule, sensor, ``novel``); the rows where any other output of the block (``c``, ``n_clamped``,
``refused``, ``mon_flag``, ``mon_rule``, ``mon_sensor``) differs from BASE's (``diff rows``);
``max|ST-C|`` before the C's first event and block flags on rows without a C event (``false``).
``cases``: bench_st94's bent cases (each sensor no other predicts, stepped 0.5 / 1 / 2 / 2.9 x
its largest training step from a quarter of the test campaign on; bench_st97c's ``kept``), on
both blocks from the state at the case's start: each case's class (bench_st94's, ``BLIND_OUT``
and ``SETTLED`` held), the rows where an output other than the two new differs from BASE's, the
``mon_stop`` rows in the case and ``mon_stop_row`` at its start.

The BAR (committed before any record was scored; seen records only, all spent: dl9768 (st96),
lr9790 dl9791 cr9792 lr9793 dl9794 (st96b), lr9820 dl9821 cr9822 lr9823 dl9824 (st97b); no
fresh seed in this task)::

1. Where the judgement stops: on every seen healthy frame, ``mon_stop`` TRUE on exactly the rows
   where ``mon_blind_lost`` turns TRUE (at most one a campaign), ``mon_stop_row`` 0 before it and
   that row from it on; lr9823: the row 380 st97c traced (1-based, its fed frame).  In the bent
   cases: ``mon_stop`` TRUE on exactly the case rows where ``mon_blind_lost`` turns TRUE.
2. Where it never stops: ``mon_stop`` 0 times, ``mon_stop_row`` 0 on every row.
3. Nothing else changed: 0 rows, over every healthy frame and every bent case, where ``c``,
   ``n_clamped``, ``refused``, ``mon_flag``, ``mon_rule`` or ``mon_sensor`` differ from the BASE
   block's (bit for bit): so ``max|ST-C|`` and every case table as before.
4. Reported, not scored: on which healthy frames it stops, how often, and what the C does on that
   row (a new thermal state, a lone fault, a veto: st97c's classes).
KEPT if 1-3 hold (with src, test and docs); REFUSED otherwise.

Results (2026-12-06, 2 cores shared by up to 8 helpers; the bar unchanged since its commit
c3930258, the rule not changed after it; the records made into /tmp/st97d by ``made``, 10.7 s
CPU, lr9823 st97c's own).  KEPT: 1-3 hold.

``stops`` on the 11 seen records, 17 healthy frames (cr: 3 test campaigns each; 118.4 s CPU)::

    frame        rows  lost -> TRUE   mon_stop   C on that row                diff rows  C first  max|ST-C|
    lr9823 R1b   4321  380            380        new state (flags 72, no rule)  0        380      9.59e-14
    dl9821 R1b   7200  4544           4544       new state (flags 72, no rule)  0        607      1.14e-13
    15 others          never          never      -                              0        -        <= 1.07e-13

``mon_stop_row`` wrong on 0 rows of any frame (0 before the stop, its row from it on); false 0
everywhere; dl9768 / lr9790's first C event and max|ST-C| as bench_st96 / st97b printed them
(503, 9.24e-14; 3608, 1.07e-13).  Both stops are in the lead-in (lr9823: 3457 rows; dl9821: 5760)
at a new thermal state the C declares on a healthy frame (NOVEL, no rule): the block arrives at
the test campaign with its BLIND_OUT judgement ended, and now says so (``mon_stop_row`` 380 /
4544); 2 of 17 healthy frames raise it, each once.  That is right as a status, not a fault: from
that row the block does not judge what the C judges (st97c: lr9823's 3 bent mismatches follow).

``cases`` (bent cases from the state at their start; 22.4 + 116.5 s CPU), 244 cases, every one with
0 diff rows and 0 ``mon_stop`` rows (no stop inside a case; lr9823 / dl9821 start stopped,
``mon_stop_row`` 380 / 4544), the classes a/m/o/n as on BASE: lr9823 7/3/4/10 (st97c's), lr9790
2/4/0/14 (st97b's 4 ``apart`` counted mismatch here), dl9768 9/0/5/18, dl9791 3/7/3/7, cr9792
1/0/0/23, lr9793 5/0/2/13, dl9794 1/4/0/11, lr9820 5/0/3/12, dl9821 5/0/3/16, cr9822 0/0/0/24,
dl9824 6/0/0/14.

Reported, not scored (st95b's seen lr9749 dl9750 cr9751 lr9752 dl9753, made and run after the
others, 62.4 s CPU): 7 healthy frames, never stops, diff rows 0, false 0.
"""

from __future__ import annotations

import ast
import copy
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st94  # noqa: E402
from _cli import run_commands  # noqa: E402

BASE = "8ee3ec81"
WATCH = "src/thermocomp/apps/deploy/export/st_watch.py"
OUTPUTS = ("n_clamped", "refused", "mon_flag", "mon_rule", "mon_sensor")
SEEN = ("dl9768", "lr9790", "dl9791", "cr9792", "lr9793", "dl9794",
        "lr9820", "dl9821", "cr9822", "lr9823", "dl9824")


def generators() -> dict:
    """The seen records' simulate words (bench_st95b / st96 / st96b / st97b's ``FRESH``)."""
    import bench_st95b
    import bench_st96
    import bench_st96b
    import bench_st97b

    return {**bench_st95b.FRESH, **bench_st96.FRESH, **bench_st96b.FRESH, **bench_st97b.FRESH}


def base_block(deployed, base: str = BASE) -> str:
    """``deployed``'s block as ``base``'s st_watch.py wrote it (its ``OUTPUTS`` and ``BLOCK``)."""
    from thermocomp.apps.deploy.export import exported_files, st

    text = subprocess.run(["git", "show", f"{base}:{WATCH}"], cwd=HERE.parent, check=True,
                          capture_output=True, text=True).stdout
    said = {t.id: ast.literal_eval(node.value) for node in ast.parse(text).body
            if isinstance(node, ast.Assign) for t in node.targets
            if isinstance(t, ast.Name) and t.id in ("OUTPUTS", "BLOCK")}
    now = st.MONITOR_OUTPUTS, st.MONITOR_BLOCK
    st.MONITOR_OUTPUTS, st.MONITOR_BLOCK = said["OUTPUTS"], said["BLOCK"]
    try:
        return exported_files(deployed, "st")["compensator.st"]
    finally:
        st.MONITOR_OUTPUTS, st.MONITOR_BLOCK = now


def cells(root: str, records: tuple[str, ...]):
    """Per record and test campaign ``(record, cid, deployed, ss, names, fed frame, its bent
    cases' first row, block, BASE block)``, each record made once under ``root``."""
    import bench_cmon92

    from thermocomp.apps.deploy.export import exported_files, state_space
    from thermocomp.apps.deploy.export.pack import fed
    from thermocomp.apps.deploy.report import plain
    from thermocomp.shell.stages.export import lead_ins

    root_path = Path(root).resolve()
    for record in records or SEEN:
        bench_cmon92.made(root_path, record, "mlr", generators())
        model = root_path / "reports" / record / "mlr-none" / "model.pkl"
        deployed, ds, _, test_ids = bench_st94.deployed_cell(root_path, record, model)
        ss = state_space(deployed, monitor=True)
        names = [ss.inputs[i] for i in ss.monitor["inputs"]]
        block, base = exported_files(deployed, "st")["compensator.st"], base_block(deployed)
        leads = lead_ins(plain(deployed).compensator, ds, list(test_ids))
        for cid in test_ids:
            frame = fed(ds.campaigns[cid], leads.get(cid))
            lead = len(frame) - len(ds.campaigns[cid])
            yield record, cid, deployed, ss, names, frame, lead + (len(frame) - lead) // 4, block, base


class Three(bench_st94.Both):
    """The block, the BASE block and the C stepped together (the BASE block's first row a
    campaign's first, as the block's)."""

    def __init__(self, ss, block: str, base: str):
        from test_export import StructuredText

        super().__init__(ss, block)
        self.base, self.base_first = StructuredText(base), True

    def rows(self, part):
        """Per row ``Both.rows``'s, then ``(whether an output but the new differs from BASE's,
        mon_blind_lost, mon_stop, mon_stop_row)``."""
        U, t = part[self.ss.inputs].to_numpy(float), part["time"].to_numpy(float)
        for i, got in enumerate(super().rows(part)):
            old = self.base(U[i], t[i], self.base_first)
            self.base_first = False
            v, b = self.fb.vars, self.base.vars
            differs = not np.array_equal(np.asarray(got[0]), old, equal_nan=True) or any(
                v[k] != b[k] for k in OUTPUTS)
            yield got, (differs, bool(v["mon_blind_lost"]), bool(v["mon_stop"]), int(v["mon_stop_row"]))


def stops(root: str, *records: str) -> None:
    """The ``stops`` lines (module doc)."""
    from thermocomp.apps.deploy.export.watch import BAND, RULES

    for record, cid, _, ss, names, frame, _, block, base in cells(root, records):
        three = Three(ss, block, base)
        lost, turned, said, rows, first_c, diff, false, stop_rows = False, [], [], 0, None, 0.0, 0, []
        bad_row = 0
        for i, ((c, want, (flag, _, _), (bits, rule, sensor), _), (differs, now, stop, row)) in \
                enumerate(three.rows(frame)):
            if now and not lost:
                w = three.sim.watch
                turned.append(i + 1)
                said.append(f"row {i + 1}: C flags {bits} rule {RULES[rule] if rule else '-'} sensor "
                            f"{names[sensor] if sensor >= 0 else '-'} new state {w.novel}")
            lost = now
            stop_rows += [i + 1] if stop else []
            bad_row += row != (turned[-1] if turned else 0)
            rows += differs
            if first_c is None and bench_st94.c_event(bits, rule):
                first_c = i + 1
            if first_c is None:
                diff = max(diff, float(np.max(np.abs(c - want))))
            false += flag and not bits & ~BAND
        print(f"{record} {cid} ({len(frame)} rows): lost turns TRUE at {turned or '-'}, mon_stop at "
              f"{stop_rows or '-'}, mon_stop_row wrong on {bad_row} rows (last {row}); "
              f"{'; '.join(said) or 'never stops'}; diff rows {rows}; C first event "
              f"{first_c or '-'}, max|ST-C| before it {diff:.3g} um, false {false}", flush=True)


def cases(root: str, *records: str) -> None:
    """The ``cases`` lines (module doc)."""
    held = bench_st94.HELD
    bench_st94.HELD = (*held, "BLIND_OUT", "SETTLED")
    try:
        for record, cid, deployed, ss, names, frame, start, block, base in cells(root, records):
            lead = Three(ss, block, base)
            for _ in lead.rows(frame.iloc[:start]):
                pass
            at_start = int(lead.fb.vars["mon_stop_row"])
            part = frame.iloc[start:start + bench_st94.ROWS + bench_st94.AFTER]
            tally, rows, stops_wrong, stopped = {}, 0, 0, 0
            for k in [k for k, b in enumerate(ss.monitor["bend_lim"]) if np.isfinite(b)]:
                for f in bench_st94.STEPS:
                    run, stepped = copy.deepcopy(lead), part.copy()
                    stepped[names[k]] += f * float(deployed.monitor.max_step_c[k])
                    got, lost = [], bool(run.fb.vars["mon_blind_lost"])
                    for i, (row, (differs, now, stop, _)) in enumerate(run.rows(stepped)):
                        got.append(row)
                        rows += differs
                        stops_wrong += stop != (now and not lost)
                        stopped += stop
                        lost = now
                    kind = bench_st94._first_kind(bench_st94.compared(got)["first"])
                    tally[kind] = tally.get(kind, 0) + 1
            print(f"{record} {cid}: mon_stop_row at the cases' start {at_start}; bent cases "
                  f"{tally}; diff rows {rows}; mon_stop rows {stopped}, where lost does not turn "
                  f"{stops_wrong}", flush=True)
    finally:
        bench_st94.HELD = held


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"stops": stops, "cases": cases}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
