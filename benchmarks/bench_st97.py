"""Where the C takes a second sensor out while one is out, and what the Structured Text block does
there (st97, issue 34, TRACED; follow-up of st96 / st96b, whose block follows one sensor out alone
-- STEP_OUT or BLIND_OUT to BACK, SETTLED -- and ends its judgement where the C could take a second
out).  A trace on seen records; no rule built, src unchanged, fresh seeds 9820-9824 not drawn.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the block measured is that tree's)::

    python benchmarks/bench_st97.py seconds ROOT RECORD [RECORD ...]
    python benchmarks/bench_st97.py frame ROOT RECORD [RECORD ...]

``seconds``: bench_st96b's ``trace`` without bench_st93's planted part (healthy, bent and pair
cases, each case's first C event classed ``agree`` / ``mismatch`` / ``apart`` / ``other`` /
``none``: its tables), and per case whose rows hold one where the C, one sensor out (``out``),
takes a second out (``out2``), a line at the first such row: the case, that row and the case's
first C event's, the C's rule and sensor and its two out, the block's output at that row (flag,
rule, sensor) and the C's last log rows (bench_st95's: row, rule, sensor, out after it); then per
record the count by (C rule, block rule) and the constants a block would hold to judge as the C
with one out and take a second out (:func:`_cost`).  ``frame``: the block, told nothing, and the C
over each record's whole healthy frame, every row where the C's outs change or either says
something (the C's outs after the row), the rows with two out counted, and ``max|ST-C|`` over the
rows a sensor is out by the rule that took it out.

Seen (2026-12-06; b77996ba's block; st96's fresh dl9768 under /tmp/st96/fresh, st96b's fresh
9790-9794 under /tmp/st96b/fresh, all spent).  ``seconds`` printed bench_st96b's tables again to
the digit (bent a/m/ap/o/n dl9768 14/0/0/0/18, lr9790 2/0/4/0/14, dl9791 3/0/8/2/7, cr9792
0/0/0/0/8, lr9793 7/0/0/0/13, dl9794 1/0/4/0/11; pair agree 91 / 91 / 88 / 66 / 91 / 91) and 31
cases where the C takes a second out, none on lr9790, cr9792, dl9794 (CPU 48.1 s, 77.8 s for three,
70.3 s for two; 2 cores under a load of 13-18)::

    record  cases  first out (the case's first C event, row 1)  second out (C rule: n)         block
    dl9768  17     JUMP 14, STEP_OUT 3                           BLIND_OUT 14, DRIFT_OUT 2,     silent 16,
                                                                 STEP_OUT 1                     SPIKE 1
    dl9791   6     JUMP 6                                        DRIFT_OUT 6                    silent 6
    lr9793   8     JUMP 6, STEP_OUT 2                            BLIND_OUT 6, FREEZE 2          silent 8

The second out comes 1-10 rows after the first (rows 2-11 of the case).  26 of the 31 follow a C
JUMP of one of a pair's spikes (the C takes one of the two out, its drift, freeze or stepped
judgement then a second), 5 a C STEP_OUT the block holds alone (dl9768 T_head_left
2x / 2.9x: STEP_OUT T_bed_left, then BLIND_OUT T_head_left; T_head_left+T_head_right: STEP_OUT
T_zdrive, then BLIND_OUT T_spindle_front; lr9793 T_spindle_front 2x / 2.9x: STEP_OUT T_col_back,
then FREEZE T_zdrive).  None follows a BLIND_OUT the block holds.  The block names none of the 31:
30 rows say nothing (its judgement ended at the JUMP, or held off by the STEP_OUT hold), one its
SPIKE of the jumper (dl9768 T_head_right+T_table, row 11, the C's STEP_OUT T_zdrive).  The first
C event of each of the 31 is the block's already (JUMP / STEP_OUT, ``agree``): the case tables do
not see the second out.  ``frame``: 0 rows with two out in the six healthy frames (14.5 s + 40.6 s
CPU; cr9792 in the command's first form, 43.2 s for the five of 9790-9794).

Why no rule here (what following them needs, read from watch.CodeMonitor and measured):

* every one of the 31 two-out sets is solved by the C at run time (``solve``: the Cholesky of the
  POD basis, ``_solved``), none is among the export's held pairs (3 / 5 / 3 on dl9768 / dl9791 /
  lr9793).  Held as constants, a one-out operator, leverages and bands (``n^2 + 3 n``) per sensor
  the C can hold out first and per (first, candidate no other predicts) set: 28084 constants on
  dl9768 (14 first outs, 104 sets), 18802 on dl9791 and lr9793 (65 sets), against at most 1904 /
  1190 for the block's one-out sets today (``_cost``); or the C's Cholesky in the ST (the basis is
  14 x 10 here): the C's whole pair machinery;
* 26 of 31 follow a JUMP, which ends the block's judgement: the C re-references a jumper the others
  predict by its step less their predicted change and rebuilds it, holds one no other predicts at
  its last reading to ``BACK`` (no ``SPIKE`` for it), then undoes its jump (``_undone``); the block
  re-references by the whole step and takes the return as its ``SPIKE`` (``frame``: lr9790 C JUMP
  T_motor 3608, block SPIKE 3609, C BACK 3619; dl9768 T_spindle_front 6647 / 6648 / 6659; dl9794
  T_table 6048 / 6051 / 6061).  ``max|ST-C|`` while a C JUMP holds a sensor out: 1.42 µm dl9768,
  0.332 lr9790, 0.0626 dl9791, 2.46 dl9794 (the correction path parts, not the monitor alone);
* 8 seconds are DRIFT_OUT (the C's lone fault, veto, new state: the drift judgement, not in the
  ST) and 2 FREEZE (not in the ST).

The returns after a JUMP on the same records (``seconds``' tables, bench_st95's logs of the apart
cases): st96b's 13 SETTLED-first ``apart`` are 6 after a C JUMP of one no other predicts held to
BACK (lr9790 4: T_motor 3608-3619; dl9794 2: T_table 6048-6061) and 7 after a C JUMP of one the
others predict back by SPIKE at the next row (dl9791: T_col_front_top 5931 / 5932, the block's SPIKE
there too); the same logs precede dl9791's 3 other apart (STEP_OUT) and dl9794's 2 (BLIND_OUT).
The second kind reads the jump row's errors of the set without the jumper (the C's ``prev_e`` at
the SPIKE row: its one-out operator, ``M[j + 1]``) and the C's re-reference of a predicted jumper.

Rerun after the per-line ``held`` / ``solved`` mark was added (``seconds`` on dl9768, then dl9791 and
lr9793; 49.1 s and 75.8 s CPU): every line as above, each two-out set ``solved``.

So the second out needs the C's pair machinery and, first, the returns after a JUMP, which need the
C's held reading on the correction path (st.py's inputs, not st_watch's monitor alone): neither fits
this stop's time (06:08 to 07:50 UTC), and a bar on 9820-9824 would have scored a class
of 3 seen cases (the BLIND_OUT seconds after a held STEP_OUT).  Next step, in that order: the
returns after a lone JUMP (the C's re-reference of a predicted jumper with MON_SELF, a blind one
held at its last reading in the model's input to BACK and ``_undone``), then the C's ``_solved``
in the ST (the basis, ``n x r`` constants, a Cholesky per set) and with it the second out.
"""

from __future__ import annotations

import copy
import itertools
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st94  # noqa: E402
import bench_st94b  # noqa: E402
import bench_st95  # noqa: E402
import bench_st96  # noqa: E402
import bench_st96b  # noqa: E402
from _cli import run_commands  # noqa: E402

TWOS: list = []        # the cases with two out (``seconds``), each (kind, line)
NAMES: list = []       # the record's monitored sensors' names (for the lines)
CASES: list = []       # the record's cases in bench_st94's order, the next one's index last


class Outs(bench_st95.Logged):
    """bench_st95's logged steppers, each row's C rule also carrying the C's outs after the row."""

    def rows(self, part):
        for c, want, said, (bits, rule, sensor), moved in super().rows(part):
            w = self.sim.watch
            rule.after = (int(w.out), int(w.out2))
            # (two out) whether the export holds the set's operator (a pair) or the C solves it
            rule.held = w._op_of(~w._active()) is not None
            yield c, want, said, (bits, rule, sensor), moved


def _name(k: int) -> str:
    return NAMES[k] if 0 <= k < len(NAMES) else "-"


def _compared(rows, plain=bench_st94b._compared) -> dict:
    """bench_st94b's ``compared`` (the case to its first C event), and the case's whole rows scanned
    for the first where the C takes a second sensor out with one out (module doc)."""
    from thermocomp.apps.deploy.export.watch import RULES

    out = plain(rows)
    case = CASES[CASES[-1]]
    CASES[-1] += 1
    for i, (_, _, (flag, rule, s), (bits, crule, cs), _) in enumerate(rows):
        after, before = getattr(crule, "after", (-1, -1)), getattr(crule, "before", (-1, -1))
        if sum(k >= 0 for k in after) == 2 and sum(k >= 0 for k in before) == 1:
            first = out["first"][0] if out["first"] is not None else None
            log = "; ".join(
                f"{row + 1} {r or '.'} {_name(k)} out {'/'.join(_name(o) for o in now if o >= 0) or '-'}"
                for row, r, k, was, now in crule.log[-6:-1] if now != was)
            TWOS.append((f"C {RULES[int(crule)]}, ST {RULES[rule] or '.'}",
                         f"{case}: row {i + 1} (first C event row {None if first is None else first + 1}): "
                         f"C {RULES[int(crule)]} {_name(cs)} out {'/'.join(_name(o) for o in after)} "
                         f"({'held' if crule.held else 'solved'}) / "
                         f"ST {'flag ' if flag else ''}{RULES[rule] or '.'} {_name(s)}; log {log}"))
            break
    return out


def _cost(m: dict) -> str:
    """The constants a block would hold to judge as the C with one out and take a second out: per
    sensor the C can hold out first (``ported_out``, or one no other predicts held for a jump) its
    set's operator, leverages and two bands (``n^2 + 3 n``), and per such sensor and candidate no
    other predicts (a second ``BLIND_OUT``) the two-out set's (the C holds ``pairs``, solves the
    rest by Cholesky at run time); against the block's ``MON_OUT_SELF`` etc. of one out today."""
    n = len(m["inputs"])
    ported, blind = np.asarray(m["ported_out"], bool), ~np.asarray(m["predictable"], bool)
    spikes = blind & bool(m.get("blind_drop")) & bool(m.get("blind_jump")) & (n - 1 >= m["min_active"])
    firsts = int((ported | spikes).sum())
    seconds_ = sum(int((blind & (np.arange(n) != j)).sum()) for j in np.flatnonzero(ported | spikes))
    per = n * n + 3 * n
    return (f"n {n}, first outs {firsts}, (first, blind second) sets {seconds_}, pairs held "
            f"{len(m.get('pairs', []))}: {firsts * per + seconds_ * per} constants (one out today: "
            f"{int(blind.sum()) * per} at most)")


def seconds(root: str, *records: str) -> None:
    """The ``seconds`` lines (module doc)."""
    from thermocomp.apps.deploy.export import state_space

    bench_st96b._hooked()
    bench_st95.ORACLE = False
    bench_st95.Logged = Outs
    if "BLIND_OUT" not in bench_st94.HELD:
        bench_st94.HELD = (*bench_st94.HELD, "BLIND_OUT")
    bench_st94b._first_kind, bench_st94b._added = bench_st96._first_kind, bench_st96._added
    bench_st94b._compared = _compared
    for record in records:
        model = Path(root).resolve() / "reports" / record / "mlr-none" / "model.pkl"
        deployed, *_ = bench_st94.deployed_cell(Path(root).resolve(), record, model)
        ss = state_space(deployed, monitor=True)
        NAMES[:] = [ss.inputs[i] for i in ss.monitor["inputs"]]
        TWOS.clear()
        bent = [f"{NAMES[k]} {f:g}x" for k, b in enumerate(ss.monitor["bend_lim"]) if np.isfinite(b)
                for f in bench_st94.STEPS]
        CASES[:] = ["healthy", *bent, *(f"{a}+{b}" for a, b in itertools.combinations(NAMES, 2)), 0]
        bench_st95.trace(root, record)
        kinds: dict = {}
        for kind, _ in TWOS:
            kinds[kind] = kinds.get(kind, 0) + 1
        print(f"{record} cases where the C takes a second out: {len(TWOS)} {kinds}; {_cost(ss.monitor)}",
              flush=True)
        for _, line in TWOS:
            print(f"    {line}", flush=True)


def frame(root: str, *records: str) -> None:
    """The block, told nothing, and the C over each whole healthy frame, the C's outs (module doc)."""
    from thermocomp.apps.deploy.export import exported_files
    from thermocomp.apps.deploy.export.watch import BAND, RULES

    for record in records:
        deployed, ss, rows = bench_st95.healthy_frame(root, record)
        NAMES[:] = [ss.inputs[i] for i in ss.monitor["inputs"]]
        both = bench_st94.Both(ss, exported_files(copy.deepcopy(deployed), "st")["compensator.st"])
        said, outs, two, by = [], (-1, -1), 0, ""
        part: dict = {}       # max|ST-C| (µm) over the rows a sensor is out, by the rule that took it out
        for i, (c, want, (flag, rule, s), (bits, crule, cs), _) in enumerate(both.rows(rows)):
            w = both.sim.watch
            now = (int(w.out), int(w.out2))
            two += min(now) >= 0
            if max(now) >= 0 and max(outs) < 0:
                by = RULES[int(crule)]
            if max(now) >= 0:
                part[by] = max(part.get(by, 0.0), float(np.max(np.abs(c - want))))
            if flag or rule or (bits & ~BAND and crule) or now != outs:
                said.append(f"{i + 1} C {RULES[int(crule)] or '.'} {_name(cs)} out "
                            f"{'/'.join(_name(k) for k in now if k >= 0) or '-'} / ST "
                            f"{'flag ' if flag else ''}{RULES[rule] or '.'} {_name(s)}")
            outs = now
        print(f"{record} {len(rows)} rows, {two} with two out; max|ST-C| while out, by the rule that took "
              f"it out: {', '.join(f'{k} {v:.3g} µm' for k, v in part.items()) or '-'}: {'; '.join(said)}",
              flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"seconds": seconds, "frame": frame}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
