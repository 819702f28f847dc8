"""Two sensors jumping in one sample in the exported C's monitor (cmon93, issue 34): held as the
served monitor holds them, or flagged as before; against bench_cmon92's trace, per row, with the
code's monitor as main has it (BASE) and with the rule (NEW) stepped side by side.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_cmon93.py trace ROOT RECORD CELLS [SIZES]
    python benchmarks/bench_cmon93.py fresh ROOT [RECORD ...]
    python benchmarks/bench_cmon93.py compiled ROOT RECORD CELL SENSORS KIND

``trace``: bench_cmon92's ``trace`` (the same cells, lead-in, fault row, cases: every single
sensor, every pair and bench_cmon92's triples spiked or frozen at once; ``SIZES`` default
``1,2,3``) with two numpy mirrors of the exported C stepped beside the served model on every
row: NEW, the export as this tree makes it, and BASE, the same arrays with ``pair_jump`` 0 (an
export before the rule: the code as main 5fe17063 has it).  Per (cell, size, kind) and per
mirror the cases counted as bench_cmon92 counts them: ``same`` (C = served on every row, the
pack's tolerance 1e-9 µm + 1e-9 x |served|), ``flagged`` (they part and ``NOT_IN_CODE`` was flagged
at or before the first parting row), ``silent`` (they part, nothing flagged before); after them
NEW's first rules flagged in the cases that part.  ``pair`` the cases of two sensors (size 2)
that part whose first flagged rule is "several sensors jumping in one sample" (``COMMON``), the
kind the rule is for.
Every silent case is printed (cell, kind, sensors, row, |C - served|).

``fresh``: the same on fresh records: bench_cmon92's generators (bench_cmon91's lr / dl / cr /
lr / dl) on the seeds of :data:`FRESH` (9526-9530, given for this rule, never drawn before),
simulated once under ``ROOT/data``, ``run`` of mlr, arx, lagbank, arx_rf once (bench_deploy88's
settings, bench_cmon92's ``made``), every cell traced (sizes 1, 2, 3); the healthy rows before the
faults checked C = served for both mirrors.

``compiled``: bench_cmon92's ``compiled`` (one case through the compiled C, ``-Werror``, against
the NEW mirror on every row, and ``stream.c``'s "not in the code" lines).

The rule (src, export key ``pair_jump``, C ``MON_PAIR_JUMP``; an export before it flags as main):
two monitored sensors jumping in one sample, no common step, no reading missing or beyond its
range in it, not the reference's next sample, as the served monitor reads a sample's instant
faults (surveillance ``_spike_back``, ``_instant``, ``_unjumped_change``): where both jumpers
are out, each is first tried as a spike's return (mon89's rule, in the monitor's order, the
field's prediction redone after a return); every jumper left is re-referenced by its step less
its change as the active sensors that did not jump predict it (one operator on that set, none
where its leverage with that set reaches the limit: its whole step), and those in are excluded
in the monitor's order, the second where the code holds a second out (cmon88's rule).  Where the
code cannot (a third out, a set it cannot solve, a sensor it does not hold out) it flags
``COMMON`` as before and changes nothing.

The bar (written before the rule was scored on any fresh seed; seeds 9526-9530 never drawn)::

    On fresh 9526-9530 (``fresh``, cells mlr / arx / lagbank / arx_rf, sizes 1-3, spike and
    freeze; BASE and NEW on the same models):
    1. NEW ``silent`` = 0 in every (record, cell, size, kind) row, and the healthy rows before
       the faults C = served (the bench asserts it).
    2. The pair kind falls to near 0: NEW ``pair`` summed over the records and cells at most
       5 % of BASE's, and no (record, size, kind) row has NEW ``pair`` above BASE's.
    3. No kind's flag count rises: NEW ``flagged`` <= BASE ``flagged`` in every (record, size,
       kind) row summed over the cells.
    4. Single sensors unchanged: size 1 ``same`` = ``cases`` for NEW as for BASE.
    And the compiled C (``compiled``, -Werror) equal to the NEW mirror to 1e-9 µm on the seen
    cases below.  KEPT if all hold; else REFUSED (src as main, the rule's diff in
    benchmarks/cmon93_rule.patch).  If the fresh run cannot finish by the deadline: TRACED.

Changed after the seen trace (lr9212, below), before any fresh seed was drawn: ``pair`` counted
on size-2 cases only (as first written it counted three sensors spiked together too, which stay
``COMMON`` by design: the C holds two out; the seen trace showed it, 40 of 50 triples per cell).
Nothing else of the bar changed.

Results (2026-12-05; NEW this tree, BASE the same arrays with ``pair_jump`` 0; 2 cores shared by
eight helpers, load 13-15).

Seen, lr9212 (bench_cmon92's seen cells, ``trace /tmp/.../seen lr9212
mlr-none,arx-none,lagbank-none,arx_rf-none``; 197.9 s CPU, both mirrors).  BASE equals bench_cmon92's
main table in every row (the mirror with ``pair_jump`` 0 is main's code); per cell::

    cell         n kind    cases  BASE same flagged silent   NEW same flagged silent  NEW's first rule
    (all four)   1 both       14          14       0      0         14       0      0
    mlr/lagbank  2 spike      91          12      79      0         90       1      0  drift with one out 1
    arx/arx_rf   2 spike      91          17      74      0         90       1      0  drift with one out 1
    (all four)   2 freeze     91          91       0      0         91       0      0
    (all four)   3 spike      50           0      50      0          2      48      0  several jumping 40,
                                                                                      a second out 8
    mlr/lagbank  3 freeze     50          46       4      0         46       4      0  a second out 4
    arx/arx_rf   3 freeze     50          47       3      0         47       3      0  a second out 3

Compiled (``compiled``, lr9212, -Werror; 4-7 s CPU each): arx_rf T_amb+T_motor spiked (two sensors
no other predicts, each with its fallback), lagbank T_head_left+T_bed_left spiked, mlr
T_spindle_front+T_col_back spiked (one no other predicts beside one the others predict), arx
T_amb+T_motor frozen: compiled C = NEW mirror to 1.1e-13 / 6.3e-13 / 8.5e-14 / 1.1e-13 µm on every
row (3743-3793); the three spiked pairs = served on every row, nothing flagged (BASE flagged
``COMMON`` at the fault row); the frozen pair as main (a second sensor out, flagged at row 12).

Fresh 9526-9530 (``fresh /tmp/.../fresh``, the records split over four processes to meet the
deadline, every (record, cell, size, kind) row traced once; ~1200 s CPU): per (record, size, kind)
summed over the four cells, BASE then NEW::

    record    n    kind  cases   BASE same flag silent pair   NEW same flag silent pair
    lr9526    1   spike     56          56    0      0    0         56    0      0    0
    lr9526    1  freeze     56          56    0      0    0         56    0      0    0
    lr9526    2   spike    364         106  258      0  258        364    0      0    0
    lr9526    2  freeze    364         364    0      0    0        364    0      0    0
    lr9526    3   spike    200           6  194      0    0          8  192      0    0
    lr9526    3  freeze    200         196    4      0    0        196    4      0    0
    dl9527    1   spike     56          56    0      0    0         56    0      0    0
    dl9527    1  freeze     56          56    0      0    0         56    0      0    0
    dl9527    2   spike    364         138  226      0  218        356    8      0    0
    dl9527    2  freeze    364         352   12      0    0        352   12      0    0
    dl9527    3   spike    384          32  352      0    0        172  212      0    0
    dl9527    3  freeze    384         290   94      0    0        290   94      0    0
    cr9528    1   spike     48          48    0      0    0         48    0      0    0
    cr9528    1  freeze     48          48    0      0    0         48    0      0    0
    cr9528    2   spike    264           0  264      0  264        264    0      0    0
    cr9528    2  freeze    264         224   40      0   40        256    8      0    8
    cr9528    3   spike    160           0  160      0    0          0  160      0    0
    cr9528    3  freeze    160          84   76      0    0        112   48      0    0
    lr9529    1   spike     56          56    0      0    0         56    0      0    0
    lr9529    1  freeze     56          56    0      0    0         56    0      0    0
    lr9529    2   spike    364         144  220      0  176        320   44      0    0
    lr9529    2  freeze    364         364    0      0    0        364    0      0    0
    lr9529    3   spike    200          48  152      0    0         48  152      0    0
    lr9529    3  freeze    200         194    6      0    0        194    6      0    0
    dl9530    1   spike     56          56    0      0    0         56    0      0    0
    dl9530    1  freeze     56          56    0      0    0         56    0      0    0
    dl9530    2   spike    364         104  260      0  260        364    0      0    0
    dl9530    2  freeze    364         306   58      0    8        318   46      0    0
    dl9530    3   spike    384          26  358      0    0        224  160      0    0
    dl9530    3  freeze    384          88  296      0    0         96  288      0    0
    all                    6640        3610 3030      0 1224       5206 1434      0    8

By the bar: 1. silent 0 in all 120 rows, BASE and NEW, and the healthy rows before the faults C =
served (asserted); 2. the pair kind 1224 -> 8 (0.65 %, the bar's <= 5 %; the 8 are cr9528 frozen
pairs read again in one sample where the code cannot hold them: flagged as before), no row above
BASE's; 3. no row's flag count rises (the two-sensor spikes 1228 -> 52 flagged, those left a drift
or a second sensor out setting in later, no longer the pair; the triples 1692 -> 1316 where two of
three jump past their limit); 4. size 1 544 of 544 C = served in both.  Compiled C = NEW mirror
(seen, above).  VERDICT: KEPT.  C = served in 6640 cases 3610 -> 5206.  The bar was written
before any fresh seed; its pair count was narrowed to two-sensor cases after the seen trace
(said above), before any fresh seed was drawn.
"""

from __future__ import annotations

import copy
import dataclasses
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_cmon92 import CELLS, compiled, fault_sets, faulted_cell, made, planted  # noqa: E402
from bench_cmon92 import FRESH as CMON92_FRESH  # noqa: E402

# bench_cmon92's generators (lr / dl / cr / lr / dl) on the seeds given for this rule
FRESH = {f"{record[:2]}{seed}": [f"seed={seed}" if w.startswith("seed=") else w for w in words]
         for (record, words), seed in zip(CMON92_FRESH.items(), range(9526, 9531))}
MIRRORS = ("BASE", "NEW")


class Stepped:
    """The served model and the code's arithmetic, BASE and NEW (module doc), stepped together."""

    def __init__(self, deployed, ss):
        from thermocomp.apps.deploy.export import Simulator

        base = dataclasses.replace(ss, monitor={**ss.monitor, "pair_jump": 0})
        self.served, self.ss = deployed, ss
        self.sims = {"BASE": Simulator(base), "NEW": Simulator(ss)}
        for sim in self.sims.values():
            sim.reset()
        deployed.reset()

    def rows(self, part):
        """Per row ``(served C, {mirror: (C, flags, rule missed)})`` of ``part``'s rows from the
        states they are in."""
        from thermocomp.apps.deploy.export.pack import corrections

        served, ss = self.served, self.ss
        X = part[served.columns_].to_numpy(float)
        U, t = part[ss.inputs].to_numpy(float), part["time"].to_numpy(float)
        for i in range(len(part)):
            y = served._step(X[i], t[i])[0]
            codes = {}
            for name, sim in self.sims.items():
                c = sim.step(U[i], t[i])
                codes[name] = (c, sim.watch.flags, sim.watch.missed)
            yield corrections(ss, y[None, :])[0], codes


def _case(run: Stepped, part) -> dict:
    """Per mirror ``(first parting row, |C - served| there, first NOT_IN_CODE (row, rule))``."""
    from thermocomp.apps.deploy.export.pack import beyond
    from thermocomp.apps.deploy.export.watch import NOT_IN_CODE

    parted = {m: None for m in MIRRORS}
    flag = {m: None for m in MIRRORS}
    for i, (want, codes) in enumerate(run.rows(part)):
        for m, (c, flags, missed) in codes.items():
            if flag[m] is None and flags & NOT_IN_CODE:
                flag[m] = (i, missed)
            if parted[m] is None and beyond(c, want).any():
                parted[m] = (i, float(np.max(np.abs(c - want))))
    return {m: (parted[m], flag[m]) for m in MIRRORS}


def trace_cell(root: Path, record: str, cell: str, sizes: list[int], out: list) -> None:
    """One cell's table rows (module doc) appended to ``out``; silent cases printed."""
    from thermocomp.apps.deploy.export.pack import beyond
    from thermocomp.apps.deploy.export.watch import COMMON, REASONS

    deployed, ss, frame, lead, start, cid = faulted_cell(root, record, cell)
    base = Stepped(deployed, ss)
    for want, codes in base.rows(frame.iloc[:start]):
        for m, (c, *_) in codes.items():
            assert not beyond(c, want).any(), f"{cell} {m}: C and served part before the faults"
    sets = fault_sets(deployed)
    print(f"{cell}: {len(deployed.monitor.names)} monitored, min_active {ss.monitor['min_active']}; "
          f"faults from test row {start - lead + 1} of {cid}", flush=True)
    for size in sizes:
        for kind in ("spike", "freeze"):
            tally = {m: {"same": 0, "flagged": 0, "silent": 0, "pair": 0} for m in MIRRORS}
            why: dict = {}
            for sensors in sets[size]:
                got = _case(copy.deepcopy(base), planted(frame, start, sensors, kind))
                for m, (parted, flag) in got.items():
                    t = tally[m]
                    if parted is None:
                        t["same"] += 1
                        continue
                    if flag is not None and flag[0] <= parted[0]:
                        t["flagged"] += 1
                    else:
                        t["silent"] += 1
                        print(f"  SILENT {m} {cell} {kind} {'+'.join(sensors)}: parts at fault row "
                              f"{parted[0] + 1} by {parted[1]:.3g} µm, first flag {flag}", flush=True)
                    if flag is not None:
                        t["pair"] += flag[1] == COMMON and size == 2
                        if m == "NEW":
                            rule = REASONS[flag[1]].split(": ", 1)[-1][:44]
                            why[rule] = why.get(rule, 0) + 1
            out.append((record, cell, size, kind, len(sets[size]), tally))
            print(f"{cell:<14}{size:>3}{kind:>8}{len(sets[size]):>6}" + "".join(
                f"{tally[m][k]:>7}" for m in MIRRORS for k in tally[m]) + "  " + ", ".join(
                f"{k} {n}" for k, n in sorted(why.items(), key=lambda kv: -kv[1])), flush=True)


HEAD = f"{'cell':<14}{'n':>3}{'kind':>8}{'cases':>6}" + "".join(
    f"{m[0] + ':' + k:>7}" for m in MIRRORS for k in ("same", "flag", "silent", "pair"))


def trace(root: str, record: str, cells: str, sizes: str = "1,2,3", *, head: str = HEAD,
          cell_rows=trace_cell) -> list:
    """The ``trace`` table (module doc): ``head``, then each cell's rows by ``cell_rows``."""
    out: list = []
    print(head, flush=True)
    for cell in cells.split(","):
        cell_rows(Path(root).resolve(), record, cell, [int(s) for s in sizes.split(",")], out)
    return out


def traced_records(root: Path, chosen: tuple, generators: dict, traced) -> list:
    """The rows of each record of ``generators`` (those ``chosen``; none chosen: all), made
    (bench_cmon92's ``made``: simulated, each family of :data:`CELLS` run) and its cells traced by
    ``traced(root, record, cells)``."""
    rows: list = []
    for record in [r for r in generators if r in chosen] or list(generators):
        for family in CELLS:
            made(root, record, family, generators)
        print(f"== {record}", flush=True)
        rows += traced(str(root), record, ",".join(f"{f}-none" for f in CELLS))
    return rows


def fresh(root: str, *chosen: str) -> None:
    """The ``fresh`` tables and the bar's sums (module doc)."""
    rows = traced_records(Path(root).resolve(), chosen, FRESH, trace)
    summed: dict = {}
    for record, _, size, kind, cases, tally in rows:
        s = summed.setdefault((record, size, kind), {m: dict.fromkeys(tally[m], 0) for m in MIRRORS})
        s["cases"] = s.get("cases", 0) + cases
        for m in MIRRORS:
            for k, v in tally[m].items():
                s[m][k] += v
    print("\nsummed over the cells (record, size, kind): cases, then BASE / NEW same flagged "
          "silent pair")
    for (record, size, kind), s in summed.items():
        print(f"{record:<8}{size:>3}{kind:>8}{s['cases']:>6}  " + "   ".join(
            f"{m} " + " ".join(f"{s[m][k]:>5}" for k in ("same", "flagged", "silent", "pair"))
            for m in MIRRORS), flush=True)
    total = {m: {k: sum(s[m][k] for s in summed.values()) for k in ("same", "flagged", "silent", "pair")}
             for m in MIRRORS}
    print(f"all: {total}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "fresh": fresh, "compiled": compiled}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
