"""The exported C holds an out SET of any size, as served does: a logger card of 3 sensors
beyond range (dep99, issue 34: deployed as scored; dep98b's mend).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's
served model and numpy mirror of the C)::

    python benchmarks/bench_dep99.py card ROOT [RECORD ...]    # the card cases, every row

``card``: per RECORD (bench_dep98b's :data:`~bench_dep98b.RECORDS` and :data:`FRESH`; ROOT its
scratch, the record simulated and its mlr model run there where missing), the healthy frame
from the fault row, then bench_dep98's ``card_blind`` and ``card_pred`` parts (3 sensors in
kelvin for 30 samples from the fault row, then in °C again, 200 rows after the return),
stepped through the served model and the C's numpy mirror together (bench_cmon92's
``Stepped``).  Per case: served's out sets, max |C - served| (µm) over the kelvin rows, the
HOLD (the return to served's re-admission) and AFTER it, and the rows > 1e-9 µm.

The rule (dep99).  The C's monitor holds a SET of sensors out (any k, bounded by the sensor
count, fixed arrays), in place of ``mon_out`` / ``mon_out2``: several readings beyond range in
one sample are each read as missing and out (the numpy mirror ``CodeMonitor._beyond``, C
``mon_beyond``), as served (``_instant``: every one excluded, no cap), where the set's operator is
had (held or solved: ``mon_operator``); the model reads each one out by ``mon_rebuilt``'s rule
(one no other predicts held at its last reading in, one the others predict rebuilt by the set's
operator); ``mon_serving`` counts the set (no fallback below ``min_active``); re-admission of the
set judged together (``_returning``).  The one / two-out paths are the k = 1 / 2 cases of the
same state; the other rules that take a second sensor out still take at most two (a third by
them flagged, as before).

BAR (written and committed BEFORE fresh seed 9873 is simulated; the fresh record scored ONCE):
D1. seen tr9828 and tr9852, card_blind and card_pred: max |C - served| <= 1e-9 µm on every row
    of the part (kelvin rows, hold and the 200 rows after the return).
D2. bench_dep98 ``back`` tr9828, bench_kelvin97 ``faults`` (tr9828) and bench_mon98b ``cases``
    dl9845: every line as main's (4fafc59a's src via ``git archive``), CPU lines aside, but the
    card lines of ``back``, which may only come nearer served (dep98's D1: these cases).
D3. healthy frames (tr9828, tr9852 and the fresh record): max |C - served| 0 µm (<= 1e-9).
D4. fresh tr9873 (trunnion63 seed 9873, bench_audit97's TRUNNION kind: the card cases need blind
    and predicted sensors), card_blind and card_pred, simulated and scored once: D1's clause.
KEPT only with the mirror AND the C built, D1-D4 met and the compiled C = mirror on a card case
(a test); else the rule saved as ``benchmarks/dep99_rule.patch`` and TRACED / REFUSED.
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_audit97  # noqa: E402
import bench_dep98  # noqa: E402
import bench_dep98b  # noqa: E402
from _cli import run_commands  # noqa: E402

FRESH = {"tr9873": [*bench_audit97.TRUNNION[1:], "seed=9873"]}
RECORDS = {**bench_dep98b.RECORDS, **FRESH}
CARDS = ("card_blind", "card_pred")


def _rows(big: list[float]) -> str:
    """The max of ``big`` and its rows beyond 1e-9 (µm)."""
    return f"{max(big, default=0.0):.3g} ({sum(b > 1e-9 for b in big)} rows > 1e-9)"


def card_lines(root: str, record: str) -> None:
    """One record's healthy and card lines (module doc)."""
    deployed, ss, frame, lead, start, cid, run = bench_dep98.stepped_cell(root, record, RECORDS)
    mon = deployed.monitor
    names = list(mon.names)
    for _ in run.rows(frame.iloc[:start]):
        pass
    healthy = [float(np.max(np.abs(c - want))) for c, want, *_ in
               copy.deepcopy(run).rows(frame.iloc[start:])]
    print(f"{record} mlr-none, test campaign {cid}: fault row {start}, monitored {names}, "
          f"predictable {[bool(p) for p in mon._predictable]}, fallbacks "
          f"{list(deployed.fallbacks_)}, min_active {mon.min_active_}; healthy from the fault row "
          f"({len(healthy)} rows): max|C - served| {_rows(healthy)} µm", flush=True)
    parts = bench_dep98.cases(frame, start, names, mon._predictable)
    K = bench_dep98.K_ROWS
    for key in CARDS:
        r = copy.deepcopy(run)
        dif, outs = [], []
        for c, want, *_ in r.rows(parts[key]):
            dif.append(float(np.max(np.abs(c - want))))
            outs.append(tuple(n for n, a in zip(names, r.served.monitor._active) if not a))
        ins = next((i for i in range(K, len(outs)) if not outs[i]
                    and not any(outs[i:])), len(outs))
        sets = list(dict.fromkeys(o for o in outs if o))
        print(f"  {key:<10} served out sets {sets} (re-admitted at row {ins}): max|C - served| "
              f"kelvin {_rows(dif[:K])}, hold {_rows(dif[K:ins])}, after "
              f"{_rows(dif[ins:])} µm", flush=True)


def card(root: str, *records: str) -> None:
    """The ``card`` lines (module doc) of ``records`` (default tr9828, tr9852: the seen)."""
    for record in records or ("tr9828", "tr9852"):
        card_lines(root, record)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"card": card}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
