"""The Structured Text block reads two exchanged wires as the C does (issue 34; stop 100,
stwires100; wires100's rule, applied to main, mirrored in the ST).

wires100 (bench_wires100.py): served, the numpy mirror and the C read two sensors' wires exchanged
from the swap row (``WIRES_EXCHANGED``); the ST block (no monitor out set) flagged the swap row
and compensated with the swapped readings after it (ST - served 0.25-98 µm).

RULE (st_watch.py ``BLOCK``, its constants ``exchange_constants``; st.py reads ``u_last`` as read).
The C's ``mon_exchange`` on what the block computes: where the export has ``exchange`` and the
block knows the C has no sensor out (its field whole, ``NOT mon_lost``, none held, ``mon_held <
0``; not the campaign's first sample): exactly two monitored sensors flagged (a step from the
last reading past the jump limit times the samples it spans, or a reading beyond range), every
reading finite, each reading within the OTHER's jump limit of the other's last reading plus the
change the sensors without both predict for it (``MON_XCH_CHANGE[i, k, ]``: row ``i`` of the
mirror's operator of the set without ``i`` and ``k``, zero where ``i``'s leverage without ``k`` is
at the limit; ``MON_XCH_SOLVED[i, k]`` 0 where the C cannot solve a set: flagged there, as the C's
``NOT_IN_CODE``): the two read exchanged from that sample on (``mon_perm``, the C's ``mon_perm``:
the block's monitored inputs ``u`` rewritten in that order before every check and the model),
named ``WIRES_EXCHANGED`` on the first of the two, not flagged (the C's ``REREFERENCED``).  Where
the block cannot tell the C's outs (after its first exclusion, ``mon_lost``) it does as before:
the jumps flagged.  No key (the export's ``exchange``).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_stwires100.py swaps ROOT RECORD [RECORD ...]
    python benchmarks/bench_stwires100.py healthy ROOT RECORD [RECORD ...]

``swaps``: bench_wires100's cells and cases (its ``SEEN`` / ``FRESH`` and :data:`FRESH`), per
case the rows where the mirror C names ``WIRES_EXCHANGED`` and max|ST - C| on them (µm, max over
targets), max|ST - C| from the swap row to the frame's end, the block's (flag, rule) at the swap
row and its flagged rows after it.  ``healthy``: bench_st100's ``healthy`` lines, main's block
063630e6's (its ``BLOCK`` / ``OUTPUTS``, bench_st97d's ``base_block``): per record the rows where
the block's (flag, rule, sensor) differ from main's.

BAR (written and committed BEFORE fresh 9937-9939 are simulated; scored once):
B1 seen (bench_wires100's seen and fresh swap cases: pt9851, pt9890, tr9891, cr9892, pt9910,
   tr9911, cr9912, far and near): ST = C to <= 1e-9 µm on every row where the C names
   ``WIRES_EXCHANGED``.
B2 healthy: bench_st100's healthy records that time allows (its seen lr9893 dl9894 cr9895 lr9896
   dl9897 first, then its fresh), 0 rows where the block's (flag, rule, sensor) differ from main's.
B3 fresh pt9937 / tr9938 / cr9939 (bench_wires100's FRESH generators on new seeds; the swap rows
   bench_wires99's, a quarter into the first test campaign, fixed before drawing): B1's clause on
   every case where the C names ``WIRES_EXCHANGED``.
B4 the swap-row-on tail (max|ST - C| from the swap row) reported, not the bar.
PARSED_DIGEST updated; tests/shell/test_export_stwires100.py fails on 063630e6.

Status: the bar above committed in 0a550f05 before 9937-9939 were simulated; unchanged, the rule
unchanged after the fresh run.  Measured 2026-12-06 (2 cores, load 10-16), main = 063630e6's src
extracted (``PYTHONPATH``), the rule this tree's, the same data and models.

B1 MET, seen (``swaps /tmp/stwires100/seen pt9851 pt9890 tr9891 cr9892 pt9910 tr9911 cr9912``,
bench_wires100's data and models copied; 51.5 s CPU, main 45.3 s).  max|ST - C| (µm, max over targets) on the
row where the C names ``WIRES_EXCHANGED`` (the swap row, the only one), main -> rule, and from
the swap row to the frame's end; the block at the swap row main -> rule::

  record  case  pair                                   at the row       from it          block
  pt9851  far   T_motor <-> T_bed                      1.39 -> 8.5e-14  35.5 -> 2.6e-13  OFF_RANGE -> WE
  pt9851  near  T_spindle <-> T_hall                   0.965 -> 8.5e-14 78.1 -> 2.6e-13  COMMON -> WE
  pt9890  far   T_rail_drive <-> T_bed                 6.94 -> 2.8e-14  65.1 -> 2.6e-13  OFF_RANGE -> WE
  pt9890  near  T_col_L <-> T_spindle                  0.157 -> 2.8e-14 53.2 -> 2.6e-13  JUMP -> WE
  tr9891  far   T_spindle_motor <-> T_amb (= near)     0.0708 -> 3.6e-15 59.6 -> 2.8e-14 COMMON -> WE
  cr9892  far   T_amb <-> T_nc_spindle_motor           0.517 -> 7.1e-15 5.84 -> 2.8e-14  OFF_RANGE -> WE
  cr9892  near  T_toolholder2 <-> T_nc_spindle_motor   0.0332 -> 7.1e-15 2.57 -> 2.8e-14 JUMP -> WE
  pt9910  far   T_rail_drive <-> T_bed                 3.71 -> 5.7e-14  29 -> 2.8e-13    OFF_RANGE -> WE
  pt9910  near  T_motor <-> T_hall                     4.21 -> 5.7e-14  98.3 -> 2.8e-13  COMMON -> WE
  tr9911  far   T_bed <-> T_trunnion (= near)          0.123 -> 4.4e-16 0.254 -> 2.8e-14 JUMP -> WE
  cr9912  near  T_nc_z1_drive <-> T_nc_cabinet         0.328 -> 2.8e-17 2.77 -> 8.9e-16  JUMP -> WE

(WE: ``WIRES_EXCHANGED`` named, not flagged; the rule's block flags no row after it on any of
these, main's 0-119 of 119.)  cr9912's far swap: the C names no exchange (wires100's X1 case, a
BENT sensor): the block as main's, 1.41 µm from the swap row, flagged BENT there.

B2 MET on what was run: ``healthy /tmp/stwires100/st lr9893 dl9894 cr9895 lr9896 dl9897
fl_thermal`` (bench_st100's data and models copied; 69.5 s CPU): 0 rows where the block's (flag,
rule, sensor) differ from main's on each, extra flags 0 / 0, lr9896's two pauses as main's;
bench_st100's fresh ``healthy ... lr9916 dl9916 lr9917 dl9917 lr9918 dl9918`` (95.7 s CPU): the same,
0 rows on each.  bench_st100's other healthy sets (st97d's 11, bench_mon98's 9) not run (time).

B3 MET, fresh scored once (``swaps /tmp/stwires100/fresh pt9937 tr9938 cr9939``, 16:45-16:49
UTC, 26.7 s CPU; main on the same data after it, 19.9 s)::

  pt9937  far   T_rail_drive <-> T_bed                 1.39 -> 4.3e-14  61.9 -> 1.4e-13  OFF_RANGE -> WE
  pt9937  near  T_motor <-> T_hall                     1.73 -> 4.3e-14  69.2 -> 1.4e-13  COMMON -> WE
  tr9938  far   T_spindle_motor <-> T_amb (= near)     0.039 -> 3.6e-15 2.54 -> 1.4e-14  COMMON -> WE
  cr9939  far   T_frame1 <-> T_nc_spindle_motor (= near) 0.123 -> 3.6e-15 9.81 -> 2.8e-14 JUMP -> WE

B4: from the swap row on, the block = the C to <= 2.8e-13 µm on every case the C names (main
2.54-98.3 µm).  VERDICT: KEPT (B1-B3 met).  Not followed: a swap after the block's first
exclusion (``mon_lost``: it cannot tell the C's outs), read as jumps and flagged, as main.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests"), str(HERE.parent / "tests" / "shell")]
from _cli import run_commands  # noqa: E402
from bench_wires100 import FRESH as WIRES100  # noqa: E402
from bench_wires100 import SEEN, _rows  # noqa: E402

BASE = "063630e6"     # main: the block that reads exchanged wires as read
FRESH = {f"{kind}{seed}": [w if not w.startswith("seed=") else f"seed={seed}" for w in WIRES100[name]]
         for (kind, name), seed in zip((("pt", "pt9910"), ("tr", "tr9911"), ("cr", "cr9912")),
                                       (9937, 9938, 9939))}


def swaps(root: str, *records: str) -> None:
    """The ``swaps`` lines (module doc)."""
    from bench_wires99 import _cell, framed_cases

    from thermocomp.apps.deploy.export import exported_files
    from thermocomp.apps.deploy.export.watch import RULES, WIRES_EXCHANGED

    base = Path(root).resolve()
    for record in records:
        deployed, ss, frame, lead, start, cid = _cell(base, record, {**SEEN, **WIRES100, **FRESH})
        block = exported_files(deployed, "st")["compensator.st"]
        print(f"{record} {cid}: {len(frame)} rows ({lead} lead-in), swap row {start}", flush=True)
        for kind, (a, b), swapped, _ in framed_cases(frame, start, deployed.monitor):
            got = _rows(deployed, ss, swapped, block)
            named = [i for i, (_, rule, _) in enumerate(got["said"]) if rule == WIRES_EXCHANGED]
            gap = np.abs(got["st"] - got["c"])
            at = f"{gap[named].max():.3g}" if named else "-"
            flag, rule = got["st_said"][start]
            print(f"  {kind:<4} {a} <-> {b}: C names WIRES_EXCHANGED at {named or 'none'}; "
                  f"max|ST - C| there {at} µm, from the swap row {gap[start:].max():.3g} µm; ST at "
                  f"the swap ({flag}, {RULES[rule] or rule}), flagged after it "
                  f"{sum(f for f, _ in got['st_said'][start + 1:])}", flush=True)


def healthy(root: str, *records: str) -> None:
    """The ``healthy`` lines (module doc): bench_st100's walk against :data:`BASE`'s block."""
    import bench_st100

    bench_st100.BASE = BASE      # (its main, read by its _cell when called)
    bench_st100.healthy(root, *records)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"swaps": swaps, "healthy": healthy}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
