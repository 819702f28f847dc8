"""Two sensors' wires exchanged mid-stream: what the served monitor does with them (issue 34; stop
99, wires99; audit98's finding 3).

audit98 (``bench_audit98.py faults ROOT pt9851``, the ``swap`` line, 16d3b58d's src, W3 streamed
warm after W1 + W2): T_motor <-> T_bed exchanged from the fault row (38.22 / 13.88 °C); "only
T_bed (beyond range) flagged; T_motor, now reading 13.88 °C, stays in: served 12.2 µm off the
healthy corrections over all 120 rows".

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_wires99.py swaps ROOT RECORD [RECORD ...]
    python benchmarks/bench_wires99.py exchanged ROOT RECORD [RECORD ...]   # the rule's shape, patched

``swaps``: per record (:data:`SEEN` or :data:`FRESH`, simulated into ``ROOT/data`` and ``run
model=mlr`` into ``ROOT/reports`` by this tree, each once; bench_cmon92's ``made`` /
``faulted_cell``: the first test campaign after its lead-in, the fault row a quarter in), the
served model and the C's numpy mirror stepped together (bench_dup99's ``_stepped``) over the
healthy frame, then per case of :func:`cases` :data:`ROWS` rows from the fault row: ``far``
(bench_audit98's swap: the two monitored sensors that differ most at the fault row, exchanged),
``near`` (the two that differ most among the pairs whose readings, exchanged, stay within each
other's range widened by the margin and step past both jump limits: no range rule can see
them), and for each ``drop`` (the same two sensors missing from the fault row: what the
monitor's rebuilt field gives without them, the floor of any rule that excludes them).  Per
case: what the monitor said at the fault row of each swapped sensor (its step, jump limit, the
change the others predicted, its reason), its re-admissions, who is out at the end, max|served
- healthy| per target (µm), max|served - drop| and max|C - served|.
``exchanged``: the same healthy frame and cases, the served model with the rule's shape of the
TRACE below patched into :class:`SensorMonitor` in this process only (:func:`exchange_wires`;
no src change, no C): whether it fires on the healthy frame, and |served - healthy| per case.

TRACE (seen; pt9851 on 9392d903's src, W3 read as a restart since restart98: no lead-in; by
hand, /tmp/wires99/trace*.py).  The finding's premise does not hold: T_motor IS excluded at the
swap sample, on 9392d903 and on 16d3b58d alike.  At row 0 the served monitor excludes T_bed
(out of range: 38.22 °C outside [9.73, 15.6] ± 10 °C) and T_motor ("jump: -24.3 °C in one
sample (largest step in training 0.4 °C); re-referenced", limit 1.2 °C); T_motor's
re-reference takes as its true change the others' prediction (``_instant``'s one-jump path,
the active set's leave-one-out field, T_bed still in it with its +24.3 °C): -6.65 °C, so its
self-prediction error after it is -6.6 to -7.0 °C against a 0.69 °C band and it never returns
while swapped.  Served over the 120 rows = served with both sensors missing (NaN), per target
max 5.73 / 0.257 / 9.497 µm on 9392d903 (16d3b58d warm: 2.975 / 1.425 / 12.162, the old model
on 16d3b58d's src, T_ram out too since W3's first row): the 9.5 (12.2) µm is the cost of
rebuilding two sensors from the field of the others, not a sensor left in.  C - served 1.36e-12
µm.  No exclusion rule can go below it (W1 as briefed is out of reach of an exclusion); only a
rule that reads the two wires exchanged (each reading where the other's field prediction is,
both at one sample) could.  T_motor stays out by luck: with the jump's expected change taken
from the sensors within range (as ``_unjumped_change`` does for several jumps; monkeypatched,
/tmp/wires99/trace3.py) the others cannot predict T_motor without T_bed (NaN), T_motor is
re-referenced by its whole step, re-admitted at row 10 reading T_bed's dynamics, and served
goes 143 µm off.  Hence the ``near`` case: a swap inside each other's range is seen by the jump
rule alone, re-referenced as an offset, and re-admitted when the other's dynamics follow the
field.  Seen, pt9851 near: T_spindle <-> T_hall (30.73 / 18.28 °C; steps -12.4 / +12.4 °C
against limits 0.72 / 0.63): both out at row 0 as jumps, re-referenced (``_instant`` with two
jumping: ``_unjumped_change``); T_hall (no other predicts it, held) re-admitted at row 37 ("no
detector fired for 13 samples and its leak onto the others within 0.5 of their warning
bands"), reading the spindle's warming: out of range at row 53 (30.89 °C); T_spindle re-admitted
at row 72 ("within ±0.2 °C for 72 samples", reading the hall's dynamics on its re-reference),
then T_motor / T_ram / T_spindle warn and alarm from row 75, nobody excluded.  |served -
healthy| per target 54.868 / 3.161 / 77.66 µm (drop: 4.301 / 0.241 / 6.02); the mirror flags
from row 0 and parts from served by 29.9 µm at row 0, 73.7 µm max.  The place: the jump rule
(``surveillance/faults.py`` ``_instant``) reads every jump as an offset of that sensor; two
sensors jumping at one sample by opposite amounts (-12.4 / +12.4, each landing where the
other's field was) are no two offsets but two readings exchanged.  The rule's shape (next
stop, one mechanism with the jump / ``_unjumped_change``): where two sensors jump in one
sample, judge each one's reading against the field the sensors without BOTH predict for the
OTHER (``_unjumped_change``'s base, its value not its change); if each lands within its
re-admission band there, the pair is read exchanged (an event ``wires exchanged``), neither
re-referenced; else as now.  It must be carried to the C and its numpy mirror
(``export/watch.py``, ``watch_c.py``) and the ST, or sit behind a key off by default.

BAR (written and committed BEFORE fresh seeds 9890-9892 were simulated).  No rule is built this
stop (TRACED), so the bar is the trace's claims, scored once on the fresh records; W1-W3 of the
brief are what a rule would have to meet next:
T1. far swap: both sensors out from the swap sample (within 1 row) and never re-admitted over
    the 120 rows; served = drop to 1e-9 µm (the exclusion's floor is reached); C = served to
    1e-9 µm.
T2. near swap (where a pair qualifies): either both out for the 120 rows with served = drop to
    1e-6 µm, or a sensor re-admitted and max|served - healthy| above drop's (the finding to
    carry: a swap the jump rule re-references as an offset).  Reported, not passed or failed.
T3. healthy frame: 0 served sensor events, 0 mirror flags, C = served (the record is healthy).
W1 (for a rule, next stop): the far swap's |served - healthy| lower than drop's by >= 50 % (only
by reading the wires exchanged); W2 no new event on the healthy records (bench_mon98's seen,
fl_thermal), bench_mon98 / bench_dep98 lines unchanged; W3 fresh once, C = served.

FRESH: pt9890 (portal64), tr9891 (trunnion63), cr9892 (the climate room of bench_mon97).

Status: the bar above was committed in dffa38a3 before 9890-9892 were simulated; unchanged.
``exchanged`` was added after the scoring (a measurement of the rule's shape, not scored).

Scored (2026-12-06 12:33 UTC, 9392d903's src, once; ``swaps ROOT pt9890 tr9891 cr9892``, 24.4 s
CPU).  Every healthy frame: 0 served sensor events, 0 mirror flags, C = served 0 µm (T3
holds).  Per case (|served - healthy| max over targets, µm; drop the same two missing)::

  record  case  pair (at the fault row, °C)                    re-admitted   served   drop  C - served
  pt9890  far   T_rail_drive 34.98 <-> T_bed 12.89              rail_drive 1  12.487  25.89   109
  pt9890  near  T_col_L 13.95 <-> T_spindle 26.87               none           9.712  9.712   1.6e-12
  tr9891  far   T_spindle_motor 30.41 <-> T_amb 19.76           both 1x        3.075  0.681   157
  tr9891  near  (the same pair)                                 both 1x        3.075  0.681   157
  cr9892  far   T_amb 30.91 <-> T_nc_spindle_motor 42.69        motor 1x       2.502  1.99    2.8e-14
  cr9892  near  T_toolholder2 32.69 <-> T_nc_spindle_motor 42.69 motor 1x      1.194  2.068   7.1e-15

T1 fails on 3 of 3 fresh records: pt9851's "both out, served = drop" held there because both
sensors are predicted by the others; a sensor no other predicts (pt9890's T_rail_drive,
tr9891's T_amb, cr9892's T_nc_spindle_motor) is re-admitted after its window (rows 10 / 24 /
10: "no detector fired for 10 samples ... no band judges its reading"), reading its partner's
wire on its jump's re-reference; on tr9891 the partner T_spindle_motor follows at row 26
("within ±2.41 °C for 26 samples": against a field that now holds the exchanged T_amb).  T2
(reported): the near swap re-admitted a sensor in 2 of 3 (tr9891 above drop, cr9892 below it:
the motor's re-referenced reading of the toolholder beat holding it).  Beside the bar, the
mirror parts from served on 2 of 3 fresh records by 109 / 157 µm (pt9890 far: at the swap row
the C flags OFF_RANGE T_bed alone while served excludes T_rail_drive for its jump too, 64.8 µm
there; seen pt9851 near: the C flags COMMON T_spindle at row 0, 29.9 µm): deployed != scored
under a swap, whatever rule comes next.

``exchanged`` (after the scoring, the rule's shape patched in, served only): two sensors
flagged in one sample (a one-sample step past the jump limit or a reading out of range), every
sensor in before it, each reading within the OTHER's jump limit of the reading the sensors
without both predict for the other (its last reading plus the change they predict; its last
reading where they cannot predict it) -> the two readings exchanged from that sample on, before
every check.  The POD of pt9851 has 8 modes for 10 sensors: with two out, 8 left, below the
monitor's ``min_active_`` 9 (``_unjumped_change`` gives NaN there), so the prediction is taken
at any count.  Measured: healthy frames 0 fires (pt9851, pt9890, tr9891, cr9892); every far /
near case of the four records fires at the swap sample and served = healthy to 0.0 µm (seen
pt9851 9.497 / 77.66 -> 0; the fresh records post hoc, not scored).  At the swap sample the
prediction was within 0.03 °C of the exchanged readings (pt9851: T_motor's predicted 38.253
for T_bed's 38.22, T_bed's 13.911 for 13.88).  W2 for the shape (bench_dup99's ``healthy`` lines
with and without the patch, /tmp/wires99/w2.py; bench_mon98's seen records and fl_thermal's
served test campaign): fl 1112 rows, cr9763 221, lr9376 4321 (its own 6 events, 35 flagged
rows), sw9776 1441, pt9851 10080: 0 fires, served / events / mirror digests identical (fl
1fd9f6ec900b1c01, lr9376 534cdecc8e59936b ...).  Not measured: the shape in the C / ST, a second
exchange (wires put back), a swap where the two readings are not each other's exactly.

VERDICT: TRACED (no src change).  Next stop: the rule above as one mechanism with the jump rule
(``faults.py``; an event ``wires exchanged``), in the C + numpy mirror + ST the same stop or
behind a key off by default; and the mirror's parting from served at a two-sensor sample.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_audit97 import TRUNNION  # noqa: E402
from bench_audit98 import FAULTED, PORTAL, fault_cases  # noqa: E402
from bench_dup99 import _stepped, _targets_env  # noqa: E402
from bench_mon97 import CR  # noqa: E402

SEEN = dict(FAULTED)
FRESH = {"pt9890": [*PORTAL, "seed=9890"], "tr9891": [*TRUNNION[1:], "seed=9891"],
         "cr9892": [*CR, "seed=9892"]}
ROWS = 120


def near_pair(mon, at: pd.Series) -> tuple[str, str] | None:
    """The two monitored sensors that differ most at the fault row (``at``: its readings) among
    the pairs whose readings, exchanged, stay within each other's range widened by the margin
    and step past both jump limits; None if no pair does."""
    names = list(mon.names)
    best, gap = None, 0.0
    for i, a in enumerate(names):
        for j in range(i + 1, len(names)):
            xa, xb = float(at[a]), float(at[names[j]])
            inside = (mon._lo_lim[j] <= xa <= mon._hi_lim[j]) and (mon._lo_lim[i] <= xb <= mon._hi_lim[i])
            if inside and abs(xa - xb) > max(mon._jump_lim[i], mon._jump_lim[j]) and abs(xa - xb) > gap:
                best, gap = (a, names[j]), abs(xa - xb)
    return best


def cases(frame: pd.DataFrame, start: int, mon) -> dict[str, tuple[tuple[str, str], pd.DataFrame]]:
    """``{kind: ((a, b), rows from the fault row with a and b exchanged)}`` (module doc)."""
    names = list(mon.names)
    part = frame.iloc[start:start + ROWS]
    (what, far), = [v for k, v in fault_cases(frame, start, names).items() if k == "swap"]
    a, b = what.split(" (")[0].split(" <-> ")
    out = {"far": ((a, b), far)}
    pair = near_pair(mon, frame.iloc[start])
    if pair is not None:
        near = part.copy()
        near[list(pair)] = part[list(pair[::-1])].to_numpy()
        out["near"] = (pair, near)
    return out


def framed_cases(frame: pd.DataFrame, start: int, mon):
    """Per case of :func:`cases`: ``(kind, (a, b), the frame to the fault row then the case's
    rows, the same with a and b missing from the fault row: the drop)``."""
    for kind, ((a, b), part) in cases(frame, start, mon).items():
        drop = part.copy()
        drop[[a, b]] = np.nan
        yield kind, (a, b), pd.concat([frame.iloc[:start], part]), pd.concat([frame.iloc[:start], drop])


def _cell(root: Path, record: str, generators: dict | None = None):
    """``(deployed, state space, frame to the fault row + ROWS, lead-in rows, fault row, test
    campaign)`` of ``record``, simulated (its words in ``generators``, default :data:`SEEN` and
    :data:`FRESH`) and run by this tree once (module doc)."""
    from bench_cmon92 import faulted_cell, made

    _targets_env(record)
    made(root, record, "mlr", generators or {**SEEN, **FRESH})
    deployed, ss, frame, lead, start, cid = faulted_cell(root, record, "mlr-none")
    return deployed, ss, frame.iloc[:start + ROWS].reset_index(drop=True), lead, start, cid


def headline(record, cid, frame, lead, start, events, flagged, parted) -> None:
    """A record's first line: its cell, the fault row, the healthy frame's served sensor
    ``events``, mirror ``flagged`` rows and max|C - served| (``parted``, µm)."""
    print(f"{record} mlr, test campaign {cid}: {len(frame)} rows fed ({lead} lead-in), fault "
          f"row {start}; healthy: served sensor events {events}, mirror flagged rows {flagged}, "
          f"max|C - served| {parted:.3g} µm", flush=True)


def _said(events: list[dict], sensor: str) -> str:
    return "; ".join(f"{e['to']}: {e.get('reason', '')[:70]}" for e in events
                     if e.get("sensor") == sensor) or "nothing"


def swaps(root: str, *records: str) -> None:
    """The ``swaps`` lines (module doc)."""
    base = Path(root).resolve()
    for record in records:
        deployed, ss, frame, lead, start, cid = _cell(base, record)
        mon = deployed.monitor
        names = list(mon.names)
        healthy = _stepped(deployed, ss, frame)
        headline(record, cid, frame, lead, start, sum(map(len, healthy["events"])),
                 int((healthy["flags"] != 0).sum()), np.abs(healthy["c"] - healthy["served"]).max())
        want = healthy["served"][start:]
        for kind, (a, b), swapped, dropped in framed_cases(frame, start, mon):
            part = swapped.iloc[start:]
            got = _stepped(deployed, ss, swapped)
            out_end = list(mon.excluded)
            gone = _stepped(deployed, ss, dropped)
            served, floor = got["served"][start:], gone["served"][start:]
            ev = got["events"][start:]
            back = {s: sum(1 for r in ev for e in r if e.get("sensor") == s and e["to"] == "ok"
                           and e.get("reason", "").startswith("re-admitted")) for s in (a, b)}
            x0, x1 = frame.iloc[start - 1], part.iloc[0]
            print(f"  {kind:<4} {a} <-> {b} ({frame.iloc[start][a]:.2f} / "
                  f"{frame.iloc[start][b]:.2f} °C)", flush=True)
            for s in (a, b):
                j = names.index(s)
                print(f"       {s}: step {x1[s] - x0[s]:+.3g} °C (jump limit {mon._jump_lim[j]:.3g},"
                      f" range [{mon._lo_lim[j]:.3g}, {mon._hi_lim[j]:.3g}]); at the swap: "
                      f"{_said(ev[0], s)}; re-admitted {back[s]}x", flush=True)
            print(f"       out at the end {out_end}; |served - healthy| per target "
                  f"{np.round(np.abs(served - want).max(axis=0), 3).tolist()} µm (drop "
                  f"{np.round(np.abs(floor - want).max(axis=0), 3).tolist()}); max|served - drop| "
                  f"{np.abs(served - floor).max():.3g} µm; max|C - served| "
                  f"{np.abs(got['c'] - got['served']).max():.3g} µm", flush=True)


def exchange_wires() -> list[tuple]:
    """Patch the rule's shape (module doc, ``exchanged``) into :class:`SensorMonitor` for this
    process: its ``update`` takes the readings through the monitor's permutation (none at a
    reset), first exchanging two flagged sensors' readings where each lands where the other's
    field is.  Returns the list the patch appends ``(time, a, b)`` to where it fires."""
    from thermocomp.apps.deploy.surveillance.monitor import SensorMonitor

    update, reset, fired = SensorMonitor.update, SensorMonitor.reset, []

    def predicted(mon, x, base, j):
        with_j = base.copy()
        with_j[j] = True
        if mon._operator(with_j)[1][j] >= mon.pod.max_leverage:
            return mon._ref[j] + mon._prev[j]          # no other predicts it: its last reading
        M, _ = mon._operator(base)
        return mon._ref[j] + mon._prev[j] + M[j] @ ((x - mon._ref)[base] - mon._prev[base])

    def exchanged(mon, reading, time=float("nan")):
        raw = np.asarray(reading, float)
        perm = getattr(mon, "_perm", None)
        x = raw if perm is None else raw[perm]
        if mon._count and mon._ref is not None and mon._active.all() and np.isfinite(x).all():
            flagged = ((np.abs(x - mon._ref - mon._prev) > mon._jump_lim * mon._gap)
                       | (x < mon._lo_lim) | (x > mon._hi_lim))
            if flagged.sum() == 2:
                a, b = np.flatnonzero(flagged)
                base = ~flagged
                if (abs(x[b] - predicted(mon, x, base, a)) < mon._jump_lim[a]
                        and abs(x[a] - predicted(mon, x, base, b)) < mon._jump_lim[b]):
                    perm = np.arange(len(x)) if perm is None else perm.copy()
                    perm[[a, b]] = perm[[b, a]]
                    mon._perm, x = perm, raw[perm]
                    fired.append((time, mon.names[a], mon.names[b]))
        return update(mon, x, time)

    def reset_too(mon):
        reset(mon)
        mon._perm = None

    SensorMonitor.update, SensorMonitor.reset = exchanged, reset_too
    return fired


def exchanged(root: str, *records: str) -> None:
    """The ``exchanged`` lines (module doc)."""
    fired = exchange_wires()
    base = Path(root).resolve()
    for record in records:
        deployed, ss, frame, _, start, _ = _cell(base, record)
        fired.clear()
        healthy = _stepped(deployed, ss, frame)
        print(f"{record} mlr: healthy frame, the patch fired {len(fired)}x", flush=True)
        for kind, ((a, b), part) in cases(frame, start, deployed.monitor).items():
            fired.clear()
            got = _stepped(deployed, ss, pd.concat([frame.iloc[:start], part]))
            off = np.abs(got["served"][start:] - healthy["served"][start:]).max(axis=0)
            print(f"  {kind:<4} {a} <-> {b}: fired {fired[:2]}; served sensor events "
                  f"{sum(len(r) for r in got['events'][start:])}; |served - healthy| per target "
                  f"{np.round(off, 3).tolist()} µm; out at the end {deployed.monitor.excluded}",
                  flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"swaps": swaps, "exchanged": exchanged}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
