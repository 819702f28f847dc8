"""The Structured Text block holds the C's BENT and its pair jump (st94, issue 34; follow-up of
st93 / st93b, whose block read a blind sensor's sub-limit step as heat and flagged two sensors
jumping in one sample ``COMMON``, where the C, since step93b and cmon93, re-references them).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the block measured is that tree's)::

    python benchmarks/bench_st94.py trace ROOT RECORD
    python benchmarks/bench_st94.py fresh ROOT [RECORD ...]

``trace``: the cell ``ROOT/reports/RECORD/mlr-none`` deployed as ``export`` deploys it
(bench_cmon91's ``deployed_cell``), its ST block (``FB_ThermoComp`` run by the tests' interpreter)
and the numpy mirror of its C (:class:`Simulator`, the code's monitor in it) stepped together
from a reset over the fed rows of its first test campaign (its lead-in, then the campaign):

* ``healthy``: the whole fed frame.  ``false``: the block's flags where the served monitor
  excluded nothing (bench_st93's ``scored``); ``rows`` compared, ``max|ST-C|`` over them, the
  rows up to the C's first event that is not a BENT re-reference (``c_event``: any flag bit but
  the band's, or a re-reference of another rule); ``bent`` the C's BENT re-references on those
  rows, ``matched`` those the block names at its row with the sensor (``mon_rule`` BENT,
  ``mon_sensor``); ``rerefs`` the rows, those and the first event's, where the C moved a
  sensor's reference (``watch.ref``), ``rematched`` those where the block moved the same
  sensors' ``mon_shift`` (the same set; the amount compared through ``max|ST-C|``).
* ``bent``: from a quarter of the campaign on, per monitored sensor no other predicts (a finite
  ``bend_lim``) and per ``k`` of :data:`STEPS`, copies of both stepped over the next
  :data:`ROWS` + :data:`AFTER` rows with the sensor read ``k`` x its largest training step
  (``max_step_c``) higher from there on (bench_step93's planted step, under the jump limit of 3 x
  that step).  Per case ``rows`` / ``max|ST-C|`` / ``bent`` / ``matched`` as above, and ``first``:
  the C's first other event in the case named by the block at its row (rule, sensor) where it is
  of a rule the block holds (:data:`HELD`); ``other`` where it is not.
* ``pair``: from the same row, per pair of monitored sensors, copies of both stepped over the
  next rows with both read :data:`SPIKE_C` higher for :data:`SPIKE_ROWS` rows (bench_cmon92's
  spike, both at once), :data:`AFTER` rows past.  ``held``: the cases where the C takes the pair
  (its first event ``JUMP``, excluded: the pair, or one sensor where the other's spike is under
  its jump limit), ``common`` where it flags ``COMMON``, ``other_rule`` another first event;
  ``first``, ``rerefs`` / ``rematched`` as above; ``max|ST-C|`` over the rows before the C's
  first event.

``fresh``: ``trace`` on the fresh records of :data:`FRESH` (bench_st93b's generators: bench_cmon91's
lr / dl / cr / lr / dl, seeds 9666-9670, given for this rule), each simulated and ``run
model=mlr`` once under ``ROOT`` by bench_cmon92's ``made``.

What the block does (src/thermocomp/apps/deploy/export/st_watch.py): a step of a sensor no other
predicts off its own last one by more than ``MON_BEND_LIM`` (the C's ``bend_lim``), under its
jump limit, read, no gap: re-referenced by the departure and kept in, ``mon_rule`` BENT (26, not
``mon_flag``: the C's ``REREFERENCED``, as a common step); a second one since it was re-referenced a
jump.  Two sensors jumping in one sample, every reading there and in range, not at the sample
after the reference, each one the C takes out (``MON_PAIR_FIRST`` / ``MON_PAIR_SECOND``, from the
export's ``ported_out`` / ``predictable`` / ``blind_drop`` / ``blind_jump`` / ``second_jump`` /
``second_instant``): ``JUMP`` flagged on the first jumper in, both re-referenced by their whole
step (the block's path for every jump: it holds no POD, so it neither predicts their change nor
rebuilds them as the C does after excluding them -- ST = C up to that row, not after); where both
were re-referenced already each is first tried as a spike's return.

The BAR (written and committed before any of 9666-9670 was simulated)::

1. Healthy, every fresh record: 0 false flags, ``max|ST-C|`` <= 1e-9 µm over the compared rows,
   matched = bent and rematched = rerefs.
2. ``bent`` cases, every fresh record: ``max|ST-C|`` <= 1e-9 µm over every case's compared rows,
   matched = bent (every C BENT re-reference named by the block at its row and sensor),
   rematched = rerefs, and ``first`` mismatches 0 (a C first event of a rule the block holds
   named alike).
3. ``pair`` cases, every fresh record: ``max|ST-C|`` <= 1e-9 µm before the C's row; ``first``
   mismatches 0 (held pairs: ``JUMP`` and the C's sensor; ``COMMON`` where the C flags it);
   rematched = rerefs.
4. No case st93b's bench passed changes: ``bench_st93b.py fresh`` on 9614-9618 (spent, re-simulated)
   with this block prints its docstring's table again (served / hits / misses / stepped / other /
   false, per record and kind; max|ST-C| <= 1e-9).
KEPT if 1-4 hold on all five fresh records; REFUSED with the cases named otherwise (src as on
main, the rule's diff in benchmarks/st94_rule.patch); TRACED if it cannot be scored by the deadline.

Seen before the bar was written (lr9614, st93b's spent seed; the bench's development record):
healthy false 0, ST = C to 9.2e-14 µm over 3447 rows (the C's first event a drift exclusion in
the lead-in, row 3448); bent 32 cases (8 blind sensors x 4), C BENT 3 matched 3, re-referenced
4 / 4, ST = C to 6.8e-14 µm, first events: 1 agree (a 2.9x step past the jump limit: JUMP), 6 of
rules the block does not hold (stepped error, drift, blind exclusion); pair 91 cases, held 88,
first agree 88, re-referenced 88 / 88, 3 other (stepped error).

Results (2026-12-05; 2 cores shared by 8 helpers).  ``fresh /tmp/st94/fresh`` scored once with
this branch's block (82.8 s of this process's CPU for the five, each record's simulation and
``run model=mlr`` a few seconds more), then, the same models, with main's (4f0fc94a's src,
``git archive``; 69.7 s): main -> rule::

    record  healthy  max|ST-C| µm   bent  C BENT     re-ref     max|ST-C| µm       first agree/
            false    (rows)        cases matched    matched                       other/mismatch
    lr9666  0 -> 0   1.14e-13 (4321)  20  0/3 -> 3/3  0/3 -> 3/3  8.71 -> 1.1e-13    0/6/0 -> 0/6/0
    dl9667  0 -> 0   9.95e-14 (5970)  16  0/2 -> 2/2  0/2 -> 2/2  2.05 -> 9.9e-14    0/3/0 -> 0/3/0
    cr9668  0 -> 0   7.11e-15 (219)    8  0/3 -> 3/3  0/3 -> 3/3  2.30 -> 1.1e-14    0/0/0 -> 0/0/0
    lr9669  0 -> 0   1.07e-13 (2277)  20  0/2 -> 2/2  0/2 -> 2/2  5.83 -> 7.8e-14    0/5/0 -> 0/5/0
    dl9670  0 -> 0   8.13e-14 (21)    28  0/1 -> 1/1  4/6 -> 6/6  1.57 -> 8.5e-14    4/3/1 -> 5/3/0

    record  pair: cases  C held (JUMP)  first agree            mismatch (COMMON)  other  re-ref matched
    lr9666        91     90             24 -> 90               66 -> 0            1      90/90 both
    dl9667        91     91             13 -> 91               78 -> 0            0      91/91 both
    cr9668        66     66              0 -> 66               66 -> 0            0      66/66 both
    lr9669        91     90             24 -> 90               66 -> 0            1      90/90 both
    dl9670        91     90             24 -> 90               66 -> 0            1      90/90 both

Healthy identical under both blocks (the rules do not fire on them; the C's first healthy event, a
stepped error / drift / jump, named or not as before; dl9670's at row 22, in the lead-in).  The
"C held" pairs include the cases where one of the two spiked sensors stays under its jump limit
(a single jump: main flagged those alike, its 24 / 13 agreements); the C flagged ``COMMON`` on
none of the 430 (every monitored sensor ``MON_PAIR_FIRST`` / ``_SECOND`` on these exports).
``other``: the C's first event a stepped self-prediction error (not in the ST), 3 pairs and 17
bent cases; main's dl9670 bent mismatch: T_motor 2x, the C's second bend a jump, main's block
re-referencing nothing at the first.

Bar item 4, ``bench_st93b.py fresh`` on copies of st93b's 9614-9618 records and models (this
block; 36.1 s CPU): every count of its docstring's table again (healthy served / hits / misses /
stepped / other / false 0 0 0 1 1 0, 0 0 0 1 1 0, 0s, 3 3 0 0 0 0, 2 2 0 1 0 0; spike served
11 / 11 / 12 / 14 / 12 all hit, stepped 2 / 2 / 0 / 0 / 2, other 0 / 1 / 0 / 0 / 0; dropout,
range 14 / 14 / 12 / 14 / 14 hit; freeze other 8 / 7 / 10 / 4 / 9; false 0 everywhere), max|ST -
C| 9.24e-14 / 9.95e-14 / 1.07e-14 / 9.24e-14 / 1.03e-13 µm, the same digits.

Verdict by the bar as written (unchanged since its commit 305f1dff): 1-4 hold on all five: KEPT.
"""

from __future__ import annotations

import copy
import itertools
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_cmon92  # noqa: E402
import bench_st93  # noqa: E402
from _cli import run_commands  # noqa: E402
from bench_cmon91 import FRESH as CMON91_FRESH  # noqa: E402
from bench_cmon91 import deployed_cell  # noqa: E402

# bench_cmon91's generators (lr / dl / cr / lr / dl) on the seeds given, chosen before any was simulated
FRESH = {f"{record[:2]}{seed}": [f"seed={seed}" if w.startswith("seed=") else w for w in words]
         for (record, words), seed in zip(CMON91_FRESH.items(), range(9666, 9671))}
STEPS = (0.5, 1.0, 2.0, 2.9)       # bench_step93's planted steps, x the sensor's largest training step
SPIKE_C, SPIKE_ROWS, AFTER = bench_cmon92.SPIKE_C, bench_cmon92.SPIKE_ROWS, bench_cmon92.AFTER
ROWS = SPIKE_ROWS
TOL_UM = 1e-9
HELD = ("JUMP", "GLITCH", "COMMON", "COMMON_STEP", "DROPOUT", "MISSING_FIRST", "OFF_RANGE", "RANGE",
        "SPIKE", "BENT")        # the rules the block names (st_watch)


class Both:
    """The ST block and the C's numpy mirror stepped together (rows from the states they are in)."""

    def __init__(self, ss, block: str):
        from test_export import StructuredText
        from thermocomp.apps.deploy.export import Simulator

        self.ss, self.fb, self.sim = ss, StructuredText(block), Simulator(ss)
        self.sim.reset()
        self.first = True

    def rows(self, part):
        """Per row ``(ST c, C c, the block's (flag, rule, sensor), the C's (bits, rule, sensor),
        (the monitored sensors the block re-referenced, those the C did))``."""
        U, t = part[self.ss.inputs].to_numpy(float), part["time"].to_numpy(float)
        idx = self.ss.monitor["inputs"]
        for i in range(len(part)):
            shift = np.array(self.fb.vars["mon_shift"], float)[idx]
            ref = None if self.sim.watch.ref is None else self.sim.watch.ref.copy()
            c = self.fb(U[i], t[i], self.first)
            want = self.sim.step(U[i], t[i])
            w, v = self.sim.watch, self.fb.vars
            moved = (set(np.flatnonzero(np.array(v["mon_shift"], float)[idx] != shift)),
                     set() if self.first else set(np.flatnonzero(w.ref != ref)))
            self.first = False
            yield (c, want, (bool(v["mon_flag"]), int(v["mon_rule"]), int(v["mon_sensor"])),
                   (int(w.flags), int(w.rule), int(w.sensor)), moved)


def c_event(bits: int, rule: int) -> bool:
    """Whether the C's sample is an event the block is not compared past (module doc)."""
    from thermocomp.apps.deploy.export.watch import BAND, BENT, REREFERENCED

    bits &= ~BAND
    return bool(bits) and not (bits == REREFERENCED and rule == BENT)


def compared(rows) -> dict:
    """``rows`` (``Both.rows``'s, listed) up to the C's first event: ``n``, ``diff``, ``bent``,
    ``matched``, ``first`` (its row, the C's (rule, sensor), the block's) or None, and ``rerefs``
    / ``rematched``: the rows the C re-referenced a sensor on, up to and with its first event's,
    and of them those where the block re-referenced the same sensors."""
    from thermocomp.apps.deploy.export.watch import BENT

    out = {"n": 0, "diff": 0.0, "bent": 0, "matched": 0, "first": None, "rerefs": 0, "rematched": 0}
    for i, (c, want, (_, rule, sensor), (bits, crule, csensor), (st_moved, c_moved)) in enumerate(rows):
        if c_moved:
            out["rerefs"] += 1
            out["rematched"] += st_moved == c_moved
        if c_event(bits, crule):
            out["first"] = (i, (crule, csensor), (rule, sensor))
            break
        out["n"] += 1
        out["diff"] = max(out["diff"], float(np.max(np.abs(c - want))))
        if crule == BENT:
            out["bent"] += 1
            out["matched"] += (rule, sensor) == (crule, csensor)
    return out


def _first_kind(first) -> str:
    """``agree`` / ``mismatch`` / ``other`` (a C rule the block does not hold) / ``none``."""
    from thermocomp.apps.deploy.export.watch import RULES

    if first is None:
        return "none"
    _, want, got = first
    if RULES[want[0]] not in HELD:
        return "other"
    return "agree" if want == got else "mismatch"


def trace(root: str, record: str) -> None:
    """The ``trace`` tables (module doc)."""
    from thermocomp.apps.deploy.export import exported_files, state_space
    from thermocomp.apps.deploy.export.pack import fed
    from thermocomp.apps.deploy.export.watch import JUMP, RULES
    from thermocomp.apps.deploy.report import plain
    from thermocomp.shell.stages.export import lead_ins

    root = Path(root).resolve()
    model = root / "reports" / record / "mlr-none" / "model.pkl"
    deployed, ds, _, test_ids = deployed_cell(root, record, model)
    ss = state_space(deployed, monitor=True)
    m = ss.monitor
    block = exported_files(deployed, "st")["compensator.st"]
    cid = test_ids[0]
    frame = fed(ds.campaigns[cid], lead_ins(plain(deployed).compensator, ds, [cid]).get(cid))
    lead = len(frame) - len(ds.campaigns[cid])
    start = lead + (len(frame) - lead) // 4
    names = [ss.inputs[i] for i in m["inputs"]]
    # healthy: the whole frame, the block's flags against the served monitor (bench_st93's count)
    served = bench_st93.Stepped(copy.deepcopy(deployed), ss, block)
    tally, cases = bench_st93.scored(list(served.rows(frame)))
    whole = compared(list(Both(ss, block).rows(frame)))
    print(f"{record} {cid}: {len(frame)} fed rows ({lead} lead-in), {len(names)} monitored, blind "
          f"{[n for n, p in zip(names, m['predictable']) if not p]}; healthy false {tally['false']} "
          f"(served {tally['served']}, hits {tally['hits']}, misses {tally['misses']}); "
          f"{_line(whole, names)} {'; '.join(cases)}", flush=True)
    base = Both(ss, block)
    for _ in base.rows(frame.iloc[:start]):
        pass
    part = frame.iloc[start:start + ROWS + AFTER]
    # bent: a lasting step under the jump limit on each sensor no other predicts
    mon = deployed.monitor
    total, said = {}, []
    for k in [k for k, b in enumerate(m["bend_lim"]) if np.isfinite(b)]:
        for f in STEPS:
            run, stepped = copy.deepcopy(base), part.copy()
            stepped[names[k]] += f * float(mon.max_step_c[k])
            got = _added(total, compared(list(run.rows(stepped))))
            said.append(f"{names[k]} {f:g}x: {_line(got, names)}")
    print(f"bent  {total}", flush=True)
    for line in said:
        print(f"    {line}", flush=True)
    # pair: two sensors spiked in one sample
    total, said = {"held": 0, "common": 0, "other_rule": 0}, []
    for a, b in itertools.combinations(range(len(names)), 2):
        run, spiked = copy.deepcopy(base), part.copy()
        cols = [spiked.columns.get_loc(names[a]), spiked.columns.get_loc(names[b])]
        spiked.iloc[:SPIKE_ROWS, cols] += SPIKE_C
        got = _added(total, compared(list(run.rows(spiked))))
        if got["first"] is not None:
            crule = got["first"][1][0]
            total["held" if crule == JUMP else "common" if RULES[crule] == "COMMON" else "other_rule"] += 1
        if got["kind"] != "agree" or got["diff"] > TOL_UM or got["rematched"] != got["rerefs"]:
            said.append(f"{names[a]}+{names[b]}: {_line(got, names)}")
    print(f"pair  {total}", flush=True)
    for line in said:
        print(f"    {line}", flush=True)


def _added(total: dict, got: dict) -> dict:
    """``got`` (:func:`compared`'s) with its ``kind`` (:func:`_first_kind`), added to ``total``."""
    got["kind"] = _first_kind(got["first"])
    for key in ("n", "bent", "matched", "rerefs", "rematched"):
        total[key] = total.get(key, 0) + got[key]
    total["diff"] = max(total.get("diff", 0.0), got["diff"])
    total["cases"] = total.get("cases", 0) + 1
    total[got["kind"]] = total.get(got["kind"], 0) + 1
    return got


def _line(got: dict, names) -> str:
    return (f"rows {got['n']}, max|ST-C| {got['diff']:.3g} µm, C BENT {got['bent']} matched "
            f"{got['matched']}, C re-referenced {got['rerefs']} matched {got['rematched']}, first "
            f"{_said(got['first'], names)} {_first_kind(got['first'])}")


def _said(first, names) -> str:
    from thermocomp.apps.deploy.export.watch import RULES

    if first is None:
        return "none"
    i, (crule, cs), (rule, s) = first
    return (f"row {i + 1} C {RULES[crule]} {names[cs] if cs >= 0 else '-'} / ST {RULES[rule]} "
            f"{names[s] if s >= 0 else '-'}")


def fresh(root: str, *chosen: str) -> None:
    """The ``fresh`` tables (module doc): bench_st93's ``fresh`` with this bench's records and trace."""
    bench_st93.fresh(root, *chosen, records=FRESH, traced=trace)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "fresh": fresh}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
