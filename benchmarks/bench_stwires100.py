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
