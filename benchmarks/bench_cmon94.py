"""Three or more sensors jumping in one sample in the exported C's monitor (cmon94, issue 34):
what the served monitor does with them, and what the code could hold of it (a trace).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_cmon94.py trace ROOT RECORD CELLS [SIZES]
    python benchmarks/bench_cmon94.py fresh ROOT SIZES [RECORD ...]

``trace``: bench_cmon92's cells, lead-in, fault row and cases (``SIZES`` default ``3``: its
triples, every triple of sensors with a fallback and 40 drawn with seed 92; ``1,2,3`` adds every
single sensor and pair), spiked or frozen at once, the served model and the numpy mirror of the
exported C (bench_cmon92's :class:`Stepped`: the export as the tree on ``PYTHONPATH`` makes it)
stepped side by side.  Per (cell, size, kind) the cases: ``same`` (C = served on every row, the
pack's tolerance), ``flagged`` (they part and ``NOT_IN_CODE`` was flagged at or before the first
parting row), ``silent`` (they part, nothing flagged before), ``common`` (the cases whose first
``NOT_IN_CODE`` flag is ``COMMON``, several sensors jumping in one sample), ``over2`` (of those,
the cases where the served monitor has three or more sensors out right after that sample) and
``outs`` (the most sensors the served monitor had out at once in any case).  ``common - over2`` is
the most a rule for k jumpers within the code's two places out (``mon_out``, ``mon_out2``) could
hold.  Every silent case is printed.

``fresh``: the same on the fresh seeds of :data:`FRESH` (9654-9658, given for this brief, never
drawn before: bench_cmon93's generators lr / dl / cr / lr / dl, each simulated once under
``ROOT/data``, ``run`` of mlr, arx, lagbank, arx_rf once, bench_cmon92's ``made``), ``SIZES``
(as scored: ``3``; the bar as written: ``1,2,3``), then the sums per (record, size, kind) over
the cells and over all.

The k-jump rule the brief asks for is measured as a tree: ``benchmarks/cmon94_rule.patch`` (the
mirror's two conditions ``== 2`` -> ``>= 2``: every sample with two or more jumpers, no common
step, read as cmon93's pair; the C not changed, since the pack holds the C to the mirror) applied
to a copy of ``src``, the same commands run with ``PYTHONPATH`` on that copy (KJUMP) and on this
tree (MAIN, 4f0fc94a), the counts compared per row.

The trace (by reading; before any number).  The served monitor reads k >= 2 jumpers in one sample
(after the common step, ``_common_step``, and the bend, ``_bent``) as one rule for every k: where
no jumper is in, each is first tried as a spike's return (``_spike_back``, only then); every
jumper left is re-referenced by its step less its change as the active sensors that did not jump
predict it (``_unjumped_change``: one operator on that set), and every jumper in is excluded, in
index order (``_instant``'s dict, then ``_exclude``, which has no bound on how many are out).  So
the pair rule generalised, yes; and every jumper ends the sample out.  The C holds two sensors
out (``mon_out``, ``mon_out2``; fixed-size state, no allocation): with k >= 3 jumpers at least one
is in before the sample (two at most are out), so none returns as a spike, and after it k >= 3 are
out, one more than the code can hold.  A k-jump rule bounded by the code's two places therefore
holds no sample of three or more jumpers: its bound is k = 2, cmon93's rule.  What would hold
them is a third (k-th) place out, a rule on every path that reads ``mon_out`` / ``mon_out2``
(re-admission, the second's operator, fallbacks, thaw, judgement), not a change of the jump rule.

The bar (written before any fresh seed was drawn; seeds 9654-9658 never run before)::

    On fresh 9654-9658 (``fresh``, cells mlr / arx / lagbank / arx_rf, sizes 1-3, spike and
    freeze), MAIN and KJUMP on the same models:
    1. silent = 0 in every (record, cell, size, kind) row for both, and the healthy rows before
       the faults C = served (the bench asserts it).
    2. The number stated before scoring: KJUMP's triple cases flagged = MAIN's, in every row (the
       reading above: the k-jump rule within two places holds none; MAIN's summed triple flags
       are what both show), and over2 = common in every row for MAIN (no triple flagged COMMON
       leaves the served monitor with two or fewer out).
    3. No kind's flag count rises and single sensors and pairs unchanged: KJUMP = MAIN in
       every size-1 and size-2 row (same, flagged, silent).
    If 1-3 hold: TRACED, no src change (the k-jump rule holds nothing; the patch kept to show it);
    the next rule is a third place out, worth at most the ``common`` cases.  If KJUMP holds
    triples MAIN flags with 1 and 3 holding: TRACED too with the cases named (no time left for
    the C, its tests and a second fresh draw by the deadline), the rule named as the next.
    A silent case: TRACED with the case named.

Changed after the bar was committed (9be1cf8b), before any KJUMP number on a fresh seed was seen
(MAIN's first cell, lr9654 mlr, had printed): KJUMP is traced on the fresh records for triples
alone (``trace ROOT RECORD CELLS 3`` per record), beside MAIN's whole ``fresh``, so that both end
by the deadline (one cell took ~3 min under a load of 10); bar 3 (KJUMP = MAIN for one and two
sensors) is then by reading only: where fewer than three sensors jump the patch's code is main's
(``big.sum() == 2`` gives ``left.sum() <= 2``).  The fresh records were simulated and run (no
monitor stepped, no number seen) before the bar was committed.

Results (2026-12-05; MAIN this tree = 4f0fc94a's src, KJUMP a copy of it with
``cmon94_rule.patch``; 2 cores shared by eight helpers, load 9-15).

Seen, lr9526 (bench_cmon93's fresh record, simulated again under /tmp; ``trace ROOT lr9526
mlr-none,arx-none 3``, 26 / 25 s CPU): MAIN = KJUMP in all four rows; spiked triples 50 per cell,
same 1 / 3, flagged 49 / 47, common 38 = over2 38; frozen 49 same, 1 flagged (not COMMON).

Fresh (``trace ROOT RECORD CELLS 3`` per record, cells mlr / arx / lagbank / arx_rf; MAIN and
KJUMP side by side, 830 s CPU for both trees' 40 cell runs; the table summed over the cells, MAIN's, and
KJUMP's equal to it in every (record, cell, kind) row)::

    record      kind   cases    same flagged  silent  common   over2    outs
    lr9654     spike     300     204      96       0      92      92       3
    lr9654    freeze     300     120     180       0       0       0       3
    dl9655     spike     240      72     168       0     168     168       3
    dl9655    freeze     240     168      72       0       8       4       4
    cr9656     spike     160       0     160       0     160     160       3
    cr9656    freeze     160      72      88       0       8       8       4
    lr9657     spike     176       4     172       0     108     108       3
    lr9657    freeze     176     124      52       0       0       0       3
    dl9658     spike     300      72     228       0     140     140       4
    dl9658    freeze     300     200     100       0       0       0       3
    all          2352    1036    1316       0     684     680

By the bar: 1. silent 0 in every row, MAIN and KJUMP, and the healthy rows before the faults C =
served (asserted in every cell); of sizes 1-2 only lr9654 mlr / arx were traced fresh (MAIN's whole
``fresh`` cut for time, above): 12 rows, every case C = served. 2. KJUMP's triple flags = MAIN's in
every row (the bar stated it as "MAIN's", not as a count; MAIN's is 1316 of 2352; none held by the
k-jump rule), as the reading says. over2 = common fails in dl9655's freeze rows (4 cases, one a
cell: T_head_left + T_head_right + T_table frozen, at the sample they are read again two jump, both
in, T_table out for its freeze: cmon93's pair with a third out, refused, where the served monitor
takes the pair out and then thaws T_table in the same sample, two out after it; traced by hand on
dl9655 mlr; the other three cells' one each not traced by hand). No sample of three or more jumpers
found that left the served monitor with two or fewer out. 3. by reading (KJUMP not run at sizes
1-2). VERDICT: TRACED, src as main. The next rule: a third place out (``mon_out3``, or a set of outs
of fixed size), worth at most the ``common`` cases (684 here); and, smaller, a pair jump beside a
frozen sensor out that thaws in the same sample (dl9655's 4).
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_cmon92 import Stepped, fault_sets, faulted_cell, planted  # noqa: E402
from bench_cmon93 import FRESH as CMON93_FRESH  # noqa: E402
from bench_cmon93 import trace as cmon93_trace  # noqa: E402
from bench_cmon93 import traced_records  # noqa: E402

# bench_cmon93's generators (lr / dl / cr / lr / dl) on the seeds given for this brief
FRESH = {f"{record[:2]}{seed}": [f"seed={seed}" if w.startswith("seed=") else w for w in words]
         for (record, words), seed in zip(CMON93_FRESH.items(), range(9654, 9659))}
COUNTS = ("same", "flagged", "silent", "common", "over2", "outs")


def _case(run: Stepped, part) -> tuple:
    """``(first parting row, |C - served| there)`` or None, and ``(row, rule, served out count
    there)`` of the first ``NOT_IN_CODE`` flag or None, and the most sensors served had out."""
    from thermocomp.apps.deploy.export.pack import beyond
    from thermocomp.apps.deploy.export.watch import NOT_IN_CODE

    parted = flag = None
    most = 0
    for i, (c, want, flags, missed, _, outs, _) in enumerate(run.rows(part)):
        most = max(most, outs)
        if flag is None and flags & NOT_IN_CODE:
            flag = (i, missed, outs)
        if parted is None and beyond(c, want).any():
            parted = (i, float(np.max(np.abs(c - want))))
    return parted, flag, most


def trace_cell(root: Path, record: str, cell: str, sizes: list[int], out: list) -> None:
    """One cell's table rows (module doc) appended to ``out``; silent cases printed."""
    from thermocomp.apps.deploy.export.pack import beyond
    from thermocomp.apps.deploy.export.watch import COMMON

    deployed, ss, frame, lead, start, cid = faulted_cell(root, record, cell)
    base = Stepped(deployed, ss)
    for c, want, *_ in base.rows(frame.iloc[:start]):
        assert not beyond(c, want).any(), f"{cell}: C and served part before the faults"
    sets = fault_sets(deployed)
    print(f"{cell}: {len(deployed.monitor.names)} monitored, min_active {ss.monitor['min_active']}; "
          f"faults from test row {start - lead + 1} of {cid}", flush=True)
    for size in sizes:
        for kind in ("spike", "freeze"):
            tally = dict.fromkeys(COUNTS, 0)
            for sensors in sets[size]:
                parted, flag, most = _case(copy.deepcopy(base), planted(frame, start, sensors, kind))
                tally["outs"] = max(tally["outs"], most)
                if parted is None:
                    tally["same"] += 1
                elif flag is not None and flag[0] <= parted[0]:
                    tally["flagged"] += 1
                else:
                    tally["silent"] += 1
                    print(f"  SILENT {cell} {kind} {'+'.join(sensors)}: parts at fault row "
                          f"{parted[0] + 1} by {parted[1]:.3g} µm, first flag {flag}", flush=True)
                if flag is not None and flag[1] == COMMON:
                    tally["common"] += 1
                    tally["over2"] += flag[2] >= 3
            out.append((record, cell, size, kind, len(sets[size]), tally))
            print(f"{cell:<14}{size:>3}{kind:>8}{len(sets[size]):>6}"
                  + "".join(f"{tally[k]:>8}" for k in COUNTS), flush=True)


HEAD = f"{'cell':<14}{'n':>3}{'kind':>8}{'cases':>6}" + "".join(f"{k:>8}" for k in COUNTS)


def trace(root: str, record: str, cells: str, sizes: str = "3") -> list:
    """The ``trace`` table (module doc)."""
    return cmon93_trace(root, record, cells, sizes, head=HEAD, cell_rows=trace_cell)


def fresh(root: str, sizes: str, *chosen: str) -> None:
    """The ``fresh`` tables and their sums (module doc)."""
    rows = traced_records(Path(root).resolve(), chosen, FRESH,
                          lambda at, record, cells: trace(at, record, cells, sizes))
    summed: dict = {}
    for record, _, size, kind, cases, tally in rows:
        s = summed.setdefault((record, size, kind), dict.fromkeys(("cases", *COUNTS), 0))
        s["cases"] += cases
        for k, v in tally.items():
            s[k] = max(s[k], v) if k == "outs" else s[k] + v
    print("\nsummed over the cells (record, size, kind): " + " ".join(("cases", *COUNTS)))
    for (record, size, kind), s in summed.items():
        print(f"{record:<8}{size:>3}{kind:>8}" + "".join(f"{s[k]:>8}" for k in ("cases", *COUNTS)),
              flush=True)
    print("all: " + ", ".join(f"{k} {sum(s[k] for s in summed.values())}"
                              for k in ("cases", *COUNTS[:-1])))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "fresh": fresh}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
