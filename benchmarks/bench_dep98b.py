"""The exported C with a logger card of sensors beyond range: what served does with k >= 2 out,
and what the C would need to do the same (dep98b, issue 34: deployed as scored; dep98's D1).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's
served model and numpy mirror of the C)::

    python benchmarks/bench_dep98b.py trace ROOT [RECORD]    # the card cases, traced

``trace``: on RECORD (bench_dep98's :data:`~bench_dep98.RECORDS`; ROOT its scratch, the record
simulated and its mlr model run there where missing), bench_dep98's ``card_blind`` and
``card_pred`` parts (3 sensors in kelvin for 30 samples from the fault row, then in °C again),
stepped through the served model and the C's numpy mirror together (bench_cmon92's ``Stepped``).
Per case: served's out set, whether it rebuilds the field (``_rebuilds``: at least
``min_active`` in) and the fallback it serves (``_fallen_back``), over the kelvin rows and the
HOLD (the return to served's re-admission); max |C - served| there (main); and the STAND-IN
counterfactual: the same C, its model fed on those rows (kelvin and hold) the card's stand-ins
as served makes them (one no other predicts held at its last reading in, one the others predict
rebuilt from the sensors in by the operator the C already solves, ``CodeMonitor._solved``),
everything else the C's own -- what a C that holds any set out as served would give, the
re-admission row taken from served.

Traced on tr9828 (seen) before any bar: served serves NO fallback with a card of three out: 6 of
9 in is fewer than ``min_active`` 8, so ``_rebuilds`` is False and ``_fallen_back`` None on every
kelvin and hold row (dep98's "served takes its fallback" is wrong: its 115.1 µm E_Z is the model
reading the three spindle sensors held).  card_blind: held at their last readings in;
card_pred (T_ram, T_column, T_bed): rebuilt by the POD from the 6 in.  The C's monitor holds at
most two out (``mon_out`` / ``mon_out2``, ``CodeMonitor._active``): a third or more beyond range
passes the monitor by (``NOT_IN_CODE`` RANGE) and the model reads the kelvin values.

Seen, tr9828 (2026-12-06 10:07 UTC, 20.3 s CPU; the tree's src = 9f59f14f's)::

  case        served out (rows)      rebuilds  fallback  max|C - served| kelvin / hold / after (µm)
  card_blind  3 blind (0-38)         False     none      main 71.67 / 51.89 / 0
                                                         stand-in C 0 / 0 / 0 (next 10 rows)
  card_pred   T_ram, T_column,       False     none      main 35.05 / 9.883 / 2.02
              T_bed (0-39)                               stand-in C 6.3e-13 / 8.0e-13 / 1.9e-13

The stand-in C meets D1 below on every row (and card_pred's 2 rows after re-admission, dep98's
guard rate, vanish): what the C lacks is only the state, not arithmetic -- the operator
(``_solved`` / ``mon_operator``) and the guard already agree.

BAR (a rule, were one built; written before fresh seed 9864 is traced, unchanged):
D1. card_blind and card_pred on tr9828 and tr9852 (seen): C = served <= 1e-9 µm on every row
    while the card is out (kelvin rows and hold).
D2. bench_dep98 / bench_kelvin97's other lines unchanged; tr9852 healthy frame 0 µm.
D3. fresh tr9864 (trunnion63 seed 9864, the same kind: the card cases need blind and predicted
    sensors) scored once.
Verdict rule: KEPT only with a built C + mirror rule meeting D1-D3; TRACED where the mend is not
small (the trace says where it lives).

Seen tr9852 (10:08 UTC, 21.9 s CPU) and fresh tr9864 (trunnion63 seed 9864, simulated and its mlr
run into ROOT by this command, traced ONCE at 10:09-10:10 UTC, 23.4 s CPU; its predictable set
differs: T_spindle_front predicted, T_amb blind, so its cards are motor / coolant / amb and
front / ram / column)::

  record  case        served out sets (rows)            max|C - served| kelvin / hold (µm)
                                                        main            stand-in C (rows > 1e-9)
  tr9852  card_blind  the 3, then front alone         113.6 / 93.38   0 / 8.218 (1 of 40)
  tr9852  card_pred   the 3 (rows 0-40)                 20.47 / 14.91   5.1e-13 / 4.0e-13 (0 of 41)
  tr9864  card_blind  the 3, then coolant alone       9.382 / 0.8248  0 / 0.5637 (1 of 40)
  tr9864  card_pred   the 3, then column alone        125 / 102       1.1e-13 / 1.331 (1 of 40)

No fallback is served while the three are out (rebuilds False, every record and case); served's
re-admission judges the three together and may leave the worst one out longer (the printed sets;
the stand-in's one row off says one sample): then 8 are in (= min_active), the field is rebuilt
and that sensor's fallback served where it has one (tr9852 card_blind: T_spindle_front's; tr9864
card_blind: T_coolant_return's; tr9864 card_pred: T_column rebuilt from the 8, no fallback).  The
stand-in counterfactual keeps the three out to the last re-admission and serves no fallback, hence
its one row off on those three cases.  On the 10 rows after served's re-admission the stand-in C
= served (<= 2e-13 µm) in every case; main there: card_pred 2.02 (tr9828) / 1.07 (tr9852) µm,
dep98's guard rate, 0 elsewhere.

VERDICT: TRACED (no rule built; src unchanged, so D2 holds trivially).  D1 on main fails on every
record and case (above).  What a C = served needs is state, not arithmetic: the operator of any set
(``_solved`` / ``mon_operator``) and the guard already agree to 1e-12 µm once the model reads
served's stand-ins.  Where it lives: the C's monitor holds at most two out (``mon_out`` /
``mon_out2``; mirror ``CodeMonitor._active`` / ``_outs``), and a sample with several readings
beyond range is passed by (``CodeMonitor._beyond`` -> None, C ``mon_beyond`` < 0, flagged RANGE).
The mend: an out SET (any k), excluded as dropouts at the sample, stand-ins by
``mon_rebuilt``'s rule (already per sensor: blind held ``mon_last``, predicted ``pred`` of the
set's solved operator), ``mon_serving`` counting the set (no fallback below ``min_active``),
re-admission of the set judged together as served (mirror ``_returning`` / ``_pass_once_back``;
the C's readmission, the leak rule of blind ones out for range, cmon89b), a partial return handing
the rest to the one / two-out paths -- and every other rule's behaviour while 3+ are out (judged
with the set out, or flagged).  It touches the 36 uses of ``mon_out2`` in watch_c.py and the
mirror's two-out paths: not small.
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
from _cli import run_commands  # noqa: E402

RECORDS = {**bench_dep98.RECORDS, "tr9864": [*bench_audit97.TRUNNION[1:], "seed=9864"]}


def stand_in(run, card: list[int], rows: range):
    """Wrap ``run``'s C monitor so that on ``rows`` (step counts from the wrap) the model reads
    ``card``'s stand-ins as served makes them (module doc); returns the wrapped run."""
    w = run.sim.watch
    step, count, held = w.step, [0], {}

    def wrapped(u, first, dt):
        i = count[0]
        count[0] += 1
        if i == rows.start:
            held["last"] = w.last.copy()
        v = step(u, first, dt)
        if i in rows:
            ins = np.ones(w.n, bool)
            ins[card] = False
            M, _ = w._solved(ins)
            d = np.where(ins, u[w.idx] - w.ref, 0.0)
            pred = M @ d
            for j in card:
                v[w.idx[j]] = w.base[j] + (pred[j] if w.predictable[j] else held["last"][j])
        return v

    w.step = wrapped
    return run


def trace(root: str, record: str = "tr9828") -> None:
    """The card lines (module doc)."""
    deployed, ss, frame, lead, start, cid, run = bench_dep98.stepped_cell(root, record, RECORDS)
    mon = deployed.monitor
    names = list(mon.names)
    for _ in run.rows(frame.iloc[:start]):
        pass
    print(f"{record} mlr-none, test campaign {cid}: fault row {start}, monitored {names}, predictable "
          f"{[bool(p) for p in mon._predictable]}, fallbacks {list(deployed.fallbacks_)}, min_active "
          f"{mon.min_active_}", flush=True)
    parts = bench_dep98.cases(frame, start, names, mon._predictable)
    chosen = {"card_blind": [j for j, p in enumerate(mon._predictable) if not p][:3],
              "card_pred": [j for j, p in enumerate(mon._predictable) if p][:3]}
    K = bench_dep98.K_ROWS
    for key, card in chosen.items():
        part = parts[key]
        main, outs, fells, rebuilds = [], [], [], []
        r = copy.deepcopy(run)
        for c, want, flags, missed, fell, nout, serving in r.rows(part):
            m = r.served.monitor
            main.append(float(np.max(np.abs(c - want))))
            outs.append(tuple(n for n, a in zip(names, m._active) if not a))
            fells.append(fell)
            rebuilds.append(bool(m._rebuilds))
        ins = next(i for i in range(K, len(outs)) if not outs[i])
        r2 = stand_in(copy.deepcopy(run), card, range(0, ins))
        alt = [float(np.max(np.abs(c - want))) for c, want, *_ in r2.rows(part.iloc[:ins + 10])]
        print(f"  {key} {[names[j] for j in card]}: served out sets {sorted(set(outs[:ins]))} "
              f"(rows 0-{ins - 1}), rebuilds {sorted(set(rebuilds[:ins]))}, fallback served "
              f"{sorted(set(map(str, fells[:ins])))}; re-admitted at row {ins}\n"
              f"    max|C - served| main: kelvin {max(main[:K]):.4g}, hold {max(main[K:ins]):.4g}, "
              f"after {max(main[ins:]):.3g} µm; stand-in C: kelvin {max(alt[:K]):.4g}, hold "
              f"{max(alt[K:ins]):.4g}, next 10 rows {max(alt[ins:]):.3g} µm (rows > 1e-9 before "
              f"re-admission: {sum(a > 1e-9 for a in alt[:ins])} of {ins})", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
