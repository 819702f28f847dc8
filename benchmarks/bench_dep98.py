"""The exported C after a unit comes back (K -> °C): deployed = scored on the rows after it
(dep98, issue 34: deployed as scored; kelvin97's "not measured" rows).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's
served model and numpy mirror of the C)::

    python benchmarks/bench_dep98.py back ROOT [RECORD]    # the K-then-back cases

``back``: on RECORD (default tr9828: trunnion63 seed 9828, spent by audit97 / kelvin97; ROOT a
copy of their scratch, or the record simulated and its mlr model run into ROOT where missing;
:data:`RECORDS`), from the fault row of bench_cmon92's ``faulted_cell`` (a quarter into the
first test campaign), some ``T_`` inputs read in kelvin (+273.15) for :data:`K_ROWS` samples,
then in °C again, :data:`AFTER` samples after the return, stepped through the served model and
the C's numpy mirror together (bench_cmon92's ``Stepped``, from one copy of the state at the
fault row).  Cases: ``all`` every ``T_`` input; ``card_blind`` / ``card_pred`` a logger card of
3 sensors (the first three monitored sensors no other predicts / that the others predict; the
rest good); ``stagger`` every input in kelvin, back one sensor a sample (monitored order).  Per
case: max |C - served| over the kelvin rows, the HOLD (the return to the row where served has
re-admitted every sensor) and AFTER it; the rows of the C's settled re-references (jump94b's
``SETTLED``) after the return; served's and the C's max |correction - healthy| in the hold.

Traced on tr9828 (seen) before the bar, on 16d3b58d's src: in every case the C parts from served
for good once served re-admits the sensors: the C re-references ``T_spindle_motor`` (no other
predicts it) by -3.15 °C as a settled level shift 10 samples after the return (SETTLED), and its
corrections stay 0.141 / 0.245 / 0.070 µm (E_X / E_Y / E_Z) off served's (= the healthy
frame's) to the part's end (200 rows).  Why: a sample that passes the C's monitor by (several
readings beyond their range: not in the code) leaves its window as it was, and the settled rule's
ring took the window's last row again for each (30 rows of one value), where the served ring
holds the sample as read, NaN beyond range; the return then reads as a step off a flat window.
Besides: while a card is in kelvin the C reads its kelvin values (card_blind: C E_Z 186.8 µm,
served 115.1, the latter on the spindle sensors' fallback model) -- the C holds at most two
sensors out and no fallback switch for several; and from the return until served re-admits
(10-11 samples) served holds the last field (all: E_Z 115.2 µm where the healthy frame reads
78.8-102.6) while the C reads the readings (= healthy).

The rule (mend): the settled ring's row of a sample that passes the C's monitor by is the sample
as the served monitor reads it (each reading less its reference, NaN beyond its range), not the
window's last row: numpy mirror ``CodeMonitor.step``, C ``monitor_step``.  No new key; the ST
has no settled rule (jump94b).

BAR (written and committed BEFORE the rule's run on the fresh record and before the kelvin97
re-run; the rule was traced on tr9828 above and below):
D1. (the brief's whole bar) every case, tr9828 and fresh tr9852: max |C - served| <= 1e-9 µm on
    every row (kelvin rows, hold, after).  Reported clause by clause; not what the rule is kept
    on (the kelvin rows of a card and the hold need the C to hold any set of sensors out and
    served's fallbacks: not small; TRACED with the numbers).
D2. (the rule) every case, tr9828 and tr9852: C and served equal again (<= 1e-9 µm) within 10
    rows of served's last re-admission and on every row from there to the part's end (main on
    tr9828: 190 rows parted by up to 0.246 µm to the end), and no SETTLED re-reference by the C
    after the return.
D3. bench_kelvin97 ``faults`` on tr9828 (K1-K3 and audit97's fault lines): every line's max
    |C - served| and first flags (row, sensor, rule) as on 16d3b58d.
D4. tr9852 healthy frame (no fault): C = served <= 1e-9 µm on every row, main and rule alike.
KEPT if D2-D4 hold (src: mirror + C, a test failing on 16d3b58d, docs), D1 reported as it is;
REFUSED if D2, D3 or D4 fails.

Seen, tr9828 (2026-12-06 ~09:20 UTC, 28 s CPU each; main = 16d3b58d's src, rule = the mirror
mended; "after": from served's last re-admission, rows 40 / 39 / 40 / 50)::

  case        max|C - served| kelvin / hold / after (µm)   after: rows > 1e-9   C SETTLED rows
  all         0 / 31.7 / 0.246 -> 0 / 31.7 / 0              190 -> 0             [39] -> []
  card_blind  71.7 / 51.9 / 0.246 -> 71.7 / 51.9 / 0         191 -> 0             [39] -> []
  card_pred   35.1 / 9.88 / 2.26 -> 35.1 / 9.88 / 2.02       190 -> 2 (rows 40-41: served's guard
                                                                   still rate-limited from the hold)
  stagger     0 / 39.3 / 0 -> 0 / 39.3 / 0                   0 -> 0               [] -> []

Hold (return -> re-admission): served holds the last field, all: E_Z 115.2 µm where the healthy
frame reads 78.8-97.9 (max |served - healthy| 36.4 µm), the C 16.8 µm (its first row back, the
guard's rate); a user would rather have the readings back at once, but that is served's scored
behaviour (readmit88: a whole window calm), left alone here.

Records: tr9828 (seen); tr9852 = trunnion63 seed 9852 (fresh, the kind picked before it was
simulated: the machine whose blind sensors carry the settled rule), scored once after the bar.

Status: the bar above committed in 4e7d88d6 with the settled ring's mend traced on tr9828.  After
it and BEFORE the fresh run the rule grew by one part, found on test_export_cmon82c's machine
(seen, the test's record; not a bench record): the C's passed sample also counts in each step's
span, as served (a reading beyond range one sample more of its sensor's gap, one in range its last
reading), where the return after 20 kelvin samples had been read as one sample's COMMON_STEP and
every sensor re-referenced (3.28 µm to the end; tests/shell/test_export_unit_back98.py).  The
rule's description above says the ring only; the commit 88606d95 both.  Bar unchanged.

Scored once (2026-12-06 09:19-09:50 UTC, ``nice``, 2 cores shared, load 5-24; main = 16d3b58d's
src, rule = 88606d95's, both by ``git archive``; tr9852 simulated and run once, on the rule's src:
simulate / run do not touch the export)::

  tr9852      max|C - served| kelvin / hold / after (µm)   after: rows > 1e-9 (first equal row)
  (fresh)     main -> rule                                   main -> rule
  all         0 / 7.22 / 0 -> the same                       0 (41) -> 0 (41)
  card_blind  114 / 93.4 / 0 -> the same                     0 (40) -> 0 (40)
  card_pred   20.5 / 14.9 / 1.07 -> the same                 2 (43) -> 2 (43): rows 41-42, served's
                                                             guard still rate-limited from the hold
  stagger     0 / 10.9 / 0 -> the same                       0 (47) -> 0 (47)
  healthy     max|C - served| 0 µm on all 30240 rows, main and rule; no SETTLED after any return

D1 fails as traced: a card of three in kelvin, the C reads their kelvin values (tr9852 card_blind
C E_Z 185.6 µm where served, on the spindle sensors' fallback model, gives 72.0; tr9828 186.8
against 115.1), and from the return to served's re-admission the two read different fields (all:
served holds the last field, 7.22 µm off the healthy frame on tr9852, 36.4 on tr9828; the C = the
healthy frame).  D2 holds on both records (tr9852: main too -- on this seed no sensor moved past
its settled limit nor a common step's over the 30 samples: the fresh record does not part main).
D3 holds: bench_kelvin97 ``faults`` on tr9828, its 16 lines identical main -> rule (healthy,
spike, frozen, dropout, step, drift, kelvin with its rows, whole; 184.5 / 194.1 s CPU).  D4 holds.
VERDICT: KEPT on D2-D4 (mirror ``CodeMonitor.step`` / ``_step``, C ``monitor_step`` /
``mon_sample``; no key; test_export_unit_back98 fails on 16d3b58d), D1 TRACED (not met: a card in
kelvin, and served's hold until re-admission, need the C to hold any set out with fallbacks).
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_audit97  # noqa: E402
from _cli import run_commands  # noqa: E402

K_ROWS = 30
AFTER = 200
KELVIN = 273.15
RECORDS = {**bench_audit97.FAULTED, "tr9852": [*bench_audit97.TRUNNION[1:], "seed=9852"]}


def cases(frame, start: int, names: list[str], predictable) -> dict[str, pd.DataFrame]:
    """The K-then-back parts (module doc) from row ``start``, :data:`AFTER` rows after the return."""
    part0 = frame.iloc[start:start + K_ROWS + AFTER]
    temps = [c for c in part0.columns if c.startswith("T_")]
    chosen = {"all": temps,
              "card_blind": [n for n, p in zip(names, predictable) if not p][:3],
              "card_pred": [n for n, p in zip(names, predictable) if p][:3]}
    out = {}
    for key, cols in chosen.items():
        part = part0.copy()
        part.iloc[:K_ROWS, [part.columns.get_loc(c) for c in cols]] += KELVIN
        out[key] = part
    part = part0.copy()
    for k, c in enumerate(temps):        # back one sensor a sample, from the return row
        part.iloc[:K_ROWS + k, part.columns.get_loc(c)] += KELVIN
    out["stagger"] = part
    return out


def stepped(run, part) -> list[tuple]:
    """Per row of ``part`` ``(C, served, served's excluded count, C settled re-reference?)``."""
    from thermocomp.apps.deploy.export import watch

    rows = []
    for c, want, flags, missed, fell, out, serving in run.rows(part):
        w = run.sim.watch
        rows.append((c, want, out, bool(flags & watch.REREFERENCED)
                     and w.rule == getattr(watch, "SETTLED", -1)))
    return rows


def _max(a) -> str:
    return f"{max(a):.3g}" if len(a) else "-"


def stepped_cell(root: str, record: str, records: dict | None = None):
    """RECORD's mlr-none cell under ROOT (simulated and run where missing; ``records``: the
    record table, :data:`RECORDS`): ``(deployed, ss, frame, lead, start, cid, run)``, ``run``
    bench_cmon92's ``Stepped`` of the served model and the C's mirror, both reset."""
    from bench_cmon92 import Stepped, faulted_cell, made

    bench_audit97._trunnion_env()
    base = Path(root).resolve()
    made(base, record, "mlr", records or RECORDS)
    deployed, ss, frame, lead, start, cid = faulted_cell(base, record, "mlr-none")
    return deployed, ss, frame, lead, start, cid, Stepped(deployed, ss)


def back(root: str, record: str = "tr9828") -> None:
    """The K-then-back lines (module doc)."""
    deployed, ss, frame, lead, start, cid, run = stepped_cell(root, record)
    mon = deployed.monitor
    names = list(mon.names)
    lead_in = max(float(np.max(np.abs(c - want))) for c, want, *_ in run.rows(frame.iloc[:start]))
    healthy = stepped(copy.deepcopy(run), frame.iloc[start:])
    print(f"{record} mlr-none, test campaign {cid}: fault row {start} ({lead} lead-in), monitored "
          f"{names}, predictable {[bool(p) for p in mon._predictable]}, window {mon.window}; "
          f"healthy: max|C - served| {lead_in:.3g} µm before the fault row, from it ({len(healthy)} rows) "
          f"{max(float(np.max(np.abs(r[0] - r[1]))) for r in healthy):.3g} µm", flush=True)
    for key, part in cases(frame, start, names, mon._predictable).items():
        rows = stepped(copy.deepcopy(run), part)
        dif = [float(np.max(np.abs(r[0] - r[1]))) for r in rows]
        ret = K_ROWS + (len(names) - 1 if key == "stagger" else 0)   # the last sensor back
        ins = next((i for i in range(ret, len(rows)) if rows[i][2] == 0
                    and all(r[2] == 0 for r in rows[i:])), len(rows))
        h = [float(np.max(np.abs(r[0]))) for r in healthy[:len(rows)]]
        hold = range(K_ROWS, ins)
        served_off = [float(np.max(np.abs(rows[i][1] - healthy[i][1]))) for i in hold]
        c_off = [float(np.max(np.abs(rows[i][0] - healthy[i][1]))) for i in hold]
        settled = [i for i in range(K_ROWS, len(rows)) if rows[i][3]]
        agree = next((i for i in range(ins, len(rows)) if dif[i] <= 1e-9), len(rows))
        print(f"  {key:<10} kelvin rows 0-{K_ROWS - 1}, back {K_ROWS}"
              f"{'-' + str(ret) if ret > K_ROWS else ''}, served all in from row {ins}: "
              f"max|C - served| kelvin {_max(dif[:K_ROWS])}, hold {_max(dif[K_ROWS:ins])}, "
              f"after {_max(dif[ins:])} µm (rows > 1e-9 after: {sum(d > 1e-9 for d in dif[ins:])}; "
              f"first equal row {agree}, rows > 1e-9 from it: {sum(d > 1e-9 for d in dif[agree:])}); "
              f"C settled re-references after the return at rows {settled}; hold: served - healthy "
              f"{_max(served_off)}, C - healthy {_max(c_off)} µm (healthy max|correction| "
              f"{max(h):.4g})", flush=True)
        for i in (K_ROWS - 1, K_ROWS, ins, len(rows) - 1):
            if i < len(rows):
                print(f"    row {i}: C {np.round(rows[i][0], 3)} served {np.round(rows[i][1], 3)} "
                      f"healthy {np.round(healthy[i][1], 3)}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"back": back}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
