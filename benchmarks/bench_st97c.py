"""Why the Structured Text block misses the C's ``BLIND_OUT`` in lr9823's 3 bent ``mismatch`` cases
(st97c, issue 34; follow-up of st97b, whose fresh lr9823 -- bench_cmon91's lr generator, seed 9823,
now SEEN, spent -- left bent a/m/ap/o/n 10/3/0/1/10 on st97b's rule and on 02b2e099's block alike:
T_spindle_front 2x, T_motor 2x / 2.9x, the C's ``BLIND_OUT`` of the stepped sensor at the case's
second row, the block silent).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the block measured is that tree's;
ROOT holds the record as bench_st97b's ``fresh ROOT lr9823`` made it)::

    python benchmarks/bench_st97c.py ended ROOT RECORD [RECORD ...]
    python benchmarks/bench_st97c.py kept ROOT RECORD [RECORD ...]

``ended``: the block and the C's numpy mirror over the record's whole fed frame (bench_st94's
``Both``, told nothing); each row where the block's ``BLIND_OUT`` judgement (st96) ends or starts
again (``mon_blind_lost``), with the C's drift judgement on that row: its level, ``_explaining``'s
answer, ``_lone_fault``'s ``(sensor, resolves)``, the judged sensors out of band, whether it
declared a new thermal state (``novel``), and the rows its new state lasts; then the block's flags
on rows without a C event (``false``).  ``kept``: bench_st94's bent cases (each sensor no other
predicts, stepped 0.5 / 1 / 2 / 2.9 x its largest training step from a quarter of the test
campaign on), each case's first C event and the block's at its row (agree / mismatch / other /
none, bench_st94's classes with ``BLIND_OUT`` and ``SETTLED`` held as bench_st96b), on the block
as it is and with its judgement kept (``mon_blind_lost`` set FALSE at the case's first row: a
measurement of what following the C there would name, not a rule).

No rule is built (TRACED): the bar a mend would have had to meet (the brief's): lr9823's 3
mismatch -> 0; dl9768 / 9790-9794 / 9820-9822 / 9824's tables (bench_st97b fresh, bench_st96b)
unchanged but for those cases; healthy frames 0 false.  No fresh seed is drawn in this task.

Results (2026-12-06, 2 cores shared by up to 8 helpers; lr9823 rebuilt into /tmp/st97c by
bench_st97b's ``fresh ROOT lr9823``, 38.6 s CPU, which on 8ee16d2b's src printed st97b's lr9823
again: bent 10/3/0/1/10 with the same 3 mismatch rows, pair 91 agree, healthy false 0, max|ST-C|
before the C's first event (380) 9.59e-14 µm, 0 holds of st97b's class; its planted freeze ``other``
14 where st97b printed 6 on 02b2e099, misses 0 false 0 both: the served monitor's src changed
between them, not looked into).  ``ended lr9823`` (4321 fed rows, 3457
lead-in; window 10, confirm 2, exclude_level 1 (warning band), min_active 10, new_state_others 2;
14 monitored, all in; 12.0 s CPU)::

    row   C level out of band               explaining  lone fault           C then        block
    380   T_head_right T_xdrive T_zdrive    none        T_head_right, no     new state     lost
    391   none                              -           -                    state ends    lost
    2800  + T_bed_right (4)                 none        T_zdrive, resolves   nothing (*)   lost (**)
    2801  the same                          none        T_zdrive, resolves   nothing (*)   lost

(*) the veto: 3 other judged sensors out of band, at least new_state_others.  (**) judging on
after the C's new state (``mon_blind_lost`` set FALSE at 391, the measurement's second pass): on
from 391, lost again at 2800, lost at the campaign's end; false 0 on both passes.  The C's rows
380-390 carry NOVEL (flags 72 / 64, no rule; 380-381 the band too): the C's only events in the
healthy frame, none a rule the block names.

So the C's drift judgement with every sensor in goes on after row 391 (none out), and at the bent
case's second row (frame row 3675) takes the stepped blind sensor out by ``_explaining``
(``BLIND_OUT``, the rule the block mirrors); the block's st96 judgement ended at 380, where the
C's drift judgement reached the band with no blind sensor explaining it (``mon_reach`` and no
candidate: "the C's lone fault, veto or new state: not here", st_watch.py BLOCK) and does not come
back for the rest of the campaign (380 is in the lead-in: R1a, which the test campaign R1b
continues; the bent cases start at 3674).  ``kept lr9823`` (10.0 s CPU; the case's first C event /
the block's at its row)::

    case                  block as is                   judgement kept       max|ST-C| µm
    T_spindle_front 2x    row 2 BLIND_OUT / - mismatch  BLIND_OUT alike      3.55e-14
    T_motor 2x            row 2 BLIND_OUT / - mismatch  BLIND_OUT alike      2.31e-14
    T_motor 2.9x          row 2 BLIND_OUT / - mismatch  BLIND_OUT alike      5.33e-15
    24 bent cases a/m/o/n 7/3/4/10                      10/0/4/10 (no other case changes)

(bench_st94's classes: the 3 cases whose first C event is a STEP_OUT at row 1 count ``other``
here, ``agree`` in bench_st96b's ``trace``, which read 10/3/0/1/10; ``early`` is not counted here.)

Why no mend: to judge on where the C does, the block must tell, where the C's drift judgement
reaches the band and no blind sensor explains it, which of the C's outcomes it took -- a lone
fault out (``DRIFT_OUT``, a sensor the others predict: the POD's, not the block's), nothing (the
veto: ``new_state_others`` others out; ``_hovers``; ``_within_rounding``), or a new thermal state
declared for a window (no drift exclusion until ``calm_field`` reaches it).  That is the C's
``_lone_fault`` (``_resolves`` with a leave-one-out operator per judged sensor and ``alone``'s
likelier-fault test), ``_hovers`` / ``_within_rounding`` (the field's slow memory over
``EXCURSION_TAU_S``) and the new state's window: several mechanisms and an n x n x n operator
table, not the one rule the block already mirrors.  Setting the judgement back at the new state's
end alone does not mend lr9823: the veto at 2800 ends it again before the cases (``ended``'s (**)).
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st94  # noqa: E402
from _cli import run_commands  # noqa: E402


def _cell(root: str, record: str):
    """``(deployed, ss, names, frame, start, block)`` of ``record``'s test campaign, as bench_st94's
    ``trace`` builds them (the fed frame with its lead-in, the bent cases' first row)."""
    from thermocomp.apps.deploy.export import exported_files, state_space
    from thermocomp.apps.deploy.export.pack import fed
    from thermocomp.apps.deploy.report import plain
    from thermocomp.shell.stages.export import lead_ins

    root_path = Path(root).resolve()
    model = root_path / "reports" / record / "mlr-none" / "model.pkl"
    deployed, ds, _, test_ids = bench_st94.deployed_cell(root_path, record, model)
    ss = state_space(deployed, monitor=True)
    cid = test_ids[0]
    frame = fed(ds.campaigns[cid], lead_ins(plain(deployed).compensator, ds, [cid]).get(cid))
    lead = len(frame) - len(ds.campaigns[cid])
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    block = exported_files(deployed, "st")["compensator.st"]
    return deployed, ss, names, frame, lead + (len(frame) - lead) // 4, block


def ended(root: str, *records: str) -> None:
    """The ``ended`` lines (module doc)."""
    from thermocomp.apps.deploy.export.watch import BAND, CodeMonitor

    said: list[str] = []
    explaining, lone_fault = CodeMonitor._explaining, CodeMonitor._lone_fault

    def told_explaining(self, level, field):
        got = explaining(self, level, field)
        said.append(f"explaining {got}")
        return got

    def told_lone_fault(self, j, z, level, err, judged):
        got = lone_fault(self, j, z, level, err, judged)
        said.append(f"lone fault ({got[0]}, {'resolves' if got[1] else 'no'}), "
                    f"{int((judged & (level >= 1)).sum())} out")
        return got

    CodeMonitor._explaining, CodeMonitor._lone_fault = told_explaining, told_lone_fault
    try:
        for record, again in [(r, a) for r in records for a in (False, True)]:
            _, ss, names, frame, _, block = _cell(root, record)
            both, lost, novel, false = bench_st94.Both(ss, block), False, False, 0
            how = "judging on after the C's new state" if again else "block as is"
            for i, (_, _, (flag, _, _), (bits, _, _), _) in enumerate(both.rows(frame)):
                w = both.sim.watch
                if again and novel and not w.novel:
                    both.fb.vars["mon_blind_lost"] = False      # (the measurement: not a rule)
                now, level = bool(both.fb.vars["mon_blind_lost"]), w._judge()[0]
                if now != lost or w.novel != novel or any(s.startswith("lone") for s in said):
                    print(f"{record} ({how}) row {i + 1}: block judgement "
                          f"{'lost' if now else 'on'}, C level "
                          f"{[names[k] for k in np.flatnonzero(level)]}, {'; '.join(said) or '-'}, "
                          f"new state {w.novel} (flags {bits})", flush=True)
                lost, novel = now, w.novel
                false += flag and not bits & ~BAND
                said.clear()
            print(f"{record} ({how}) {len(frame)} rows: block judgement lost at the end {lost}, "
                  f"false {false}", flush=True)
    finally:
        CodeMonitor._explaining, CodeMonitor._lone_fault = explaining, lone_fault


def kept(root: str, *records: str) -> None:
    """The ``kept`` lines (module doc)."""
    from thermocomp.apps.deploy.export.watch import RULES

    held = bench_st94.HELD
    bench_st94.HELD = (*held, "BLIND_OUT", "SETTLED")
    try:
        for record in records:
            deployed, ss, names, frame, start, block = _cell(root, record)
            base = bench_st94.Both(ss, block)
            for _ in base.rows(frame.iloc[:start]):
                pass
            part = frame.iloc[start:start + bench_st94.ROWS + bench_st94.AFTER]
            for keep in (False, True):
                tally: dict[str, int] = {}
                for k in [k for k, b in enumerate(ss.monitor["bend_lim"]) if np.isfinite(b)]:
                    for f in bench_st94.STEPS:
                        run, stepped = copy.deepcopy(base), part.copy()
                        if keep:
                            run.fb.vars["mon_blind_lost"] = False
                        stepped[names[k]] += f * float(deployed.monitor.max_step_c[k])
                        got = bench_st94.compared(list(run.rows(stepped)))
                        kind = bench_st94._first_kind(got["first"])
                        tally[kind] = tally.get(kind, 0) + 1
                        first = got["first"]
                        row = "-" if first is None else (
                            f"row {first[0] + 1} C {RULES[first[1][0]]} / ST {RULES[first[2][0]]}")
                        print(f"{record} {'kept' if keep else 'as is'} {names[k]} {f:g}x: {kind}, "
                              f"{row}, max|ST-C| {got['diff']:.3g} µm", flush=True)
                print(f"{record} {'kept' if keep else 'as is'}: {tally}", flush=True)
    finally:
        bench_st94.HELD = held


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"ended": ended, "kept": kept}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
