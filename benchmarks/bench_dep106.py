"""The freeze rule's rate window at a fast logger (issue 34; stop 106, dep106).

mon105c/d read a sensor out for a freeze by its run alone at its held value while the rate fitted
(least squares) to its own readings over the ``EXCURSION_TAU_S`` = 1800 s before its run began
projects a drift within its stand-in's training spread.  Those readings live in a ring of
``TREND_ROWS`` = 128 rows, one per sample: at the records' 60 s period the ring spans 7680 s and
the fit sees its 1800 s, but at a 10 s logger it spans 1280 s and at 1 s 128 s, less the run
itself: the rate is fitted over what is left of the ring, not ``tau``.

Usage (``PYTHONPATH=<tree>/src``; the code measured is that tree's)::

    python benchmarks/bench_dep106.py cost ROOT RECORD [RECORD ...]

``cost``: per record (:data:`RECORDS`; simulated and ``run model=mlr`` into ROOT once, bench_cmon92's
``made``) and per bench_mon105c frozen sensor (frozen from a quarter into the first test campaign
for :data:`FREEZE_S` seconds, then read again for as long), the served model stepped over the
campaign (served only: ``AdaptiveCompensator._step``) four ways: ``ring`` (the tree as it is),
``full`` (the ring made long enough for tau and the run at this period: what the rule says),
``stand-in`` (never the held value) and ``held`` (the held value whenever excluded, bench_mon97b's
``hold``).  Per way: the RMSE over the case (µm, mean over targets), the rows whose held value the
model read, and the rule's fitted span (s: its oldest reading fitted to its newest) at the freeze.

WHAT THE SHORT WINDOW COSTS (measured 2026-12-07 on 898240b4's src, ``cost`` on the dev records
below: seen cr9763 / sw9776 and mon97's spent 9815/9816/9818/9819 re-simulated at 10 s, cr9763 and
sw9776 at 1 s; bench_mon105c's frozen sensors; RMSE µm ring / full / stand-in / held):
the fitted span is 1170 s (118 rows) at 10 s and 117 s at 1 s on every case, 1800 s with the full
ring.  The held-or-stand-in choice parts in 4 of 16 cases, the full window never worse:
sw9776p10 T_amb ring 0 held rows 0.8930 / full 225 held 0.8804 (-1.4 %) / 0.8930 / 0.8693;
sw9818p10 T_amb 211 rows 1.8194 / 350 rows 1.8181 / 1.8188 / 1.8181; sw9776p1 T_amb 165 rows
1.4054 / 0 rows 1.4051 / 1.4051 / 1.3921; sw9776p1 T_headstock (a structure sensor, read held on
a 117 s fit) 188 rows / 0, both 1.4292.  The other 12 read alike both ways (cr9763p10 T_amb and
cr9816p10 T_amb held 349 rows, cr9763p1 T_amb 3589, sw9815p10 T_amb 349; the rest 0).  Known
before the bar: on cr9763p1 T_amb both windows hold and the held value is worse than the stand-in
(2.1165 vs 2.0862, +1.5 %): mon105c's rule there, whatever the window.  CPU (user + sys): 10 s
records 11.8 s (2, simulation and fit included), 1 s cr 24.9 s, rest 44.8 s.

FIX (dep106; src/thermocomp/apps/deploy/surveillance/frozen_hold.py, served monitor.py, mirror
export/watch.py, C export/watch_c.py): the ring keeps one row per ``tau / (TREND_ROWS // 2)`` =
28.125 s (the first row of each such step of time; a row without a time always), each with its
sample's number; the fit ends at the newest row kept up to the run's first reading (by number).
Half the ring spans tau, half the run.  At a period >= 28.125 s every row is kept: as before.

BAR (written and committed BEFORE the fix was measured and before any fresh seed was simulated)
---
B1. span: on every fast-logger case (the dev records above and the fresh ones) where the rule fits,
    its fitted span is within one ring step of tau: tau - (28.125 s + the period) < span <= tau.
B2. error: on every fast-logger case where the fix reads the held value on other rows than the
    128-row ring did, its RMSE <= the stand-in's; on every fast-logger case the fix's RMSE no worse
    than the 128-row ring's by more than 1 %.  (cr9763p1 T_amb's +1.5 % above, the same under the
    ring and the full window, is reported as it comes, not scored against the fix.)
B3. default period: bench_mon105d ``agree`` on mon105c's 11 records (60 s): its rows identical to
    898240b4's (diff), every |served - mirror| and |served - C| <= 1e-9 µm.
B4. fast logger, the code: bench_mon105d ``agree`` on cr9763p10 and sw9776p10: |served - mirror|
    and |served - C| <= 1e-9 µm on every row, held rows as served's.
B5. the C's state: sizeof(tc_state) with 12 monitored sensors (gcc) stated, base and fix.
B6. tests: tests/apps/test_warm_batch59.py passes; a new test (<= ~3 s CPU) fails on 898240b4;
    every neighbour module passes.
KEPT if B1-B6 hold; else REFUSED (src reverted, benchmarks/dep106_rule.patch).
Fresh (chosen before drawing, scored once): cr10057p10 (climate_room at 10 s), sw10058p10
(swiss_lathe_door at 10 s), cr10059p1 (climate_room at 1 s, 2-3 h runs).

Measured (2026-12-07, after the bar; ``cost`` with 898240b4's src (``git archive``) and this
branch's, one after the other on one ROOT, /tmp/dep106/root; RMSE µm, rows read held):
B1 met: the fitted span 1800 s (65 rows) on all 16 dev and 6 fresh cases, 10 s and 1 s alike
    (898240b4: 1170 s / 117 s).
B2 met.  Dev: the fix parts from the 128-row ring on the same 4 cases the full window did:
    sw9776p10 T_amb 0 -> 181 rows, 0.8930 -> 0.8813 (stand-in 0.8930); sw9818p10 T_amb 211 -> 350,
    1.8194 -> 1.8181 (stand-in 1.8188); sw9776p1 T_amb 165 -> 0, 1.4054 -> 1.4051 (= stand-in);
    sw9776p1 T_headstock 188 -> 0, 1.4292 both.  The other 12 read identically (cr9763p1 T_amb
    still 2.1165 held vs 2.0862 stand-in, as disclosed).  Fresh (scored once): cr10057p10 both
    cases and sw10058p10 T_headstock identical; sw10058p10 T_amb 186 -> 237 rows, 1.0489 ->
    1.0488 (stand-in 1.0492); cr10059p1 T_amb 138 -> 0 rows, 1.0947 -> 1.0958 (+0.10 %, = the
    stand-in and the full window); cr10059p1 T_headstock 2236 -> 3589 rows, 0.9796 -> 0.9687
    (-1.1 %; stand-in 0.9847, = the full window).  Worst fix vs ring: +0.10 %.
B3 met: ``agree`` on the 11 records at 60 s: output identical to 898240b4's (diff); worst
    |served - mirror| 2.8e-14, |served - C| 1.6e-13 µm.
B4 met: ``agree`` cr9763p10 / sw9776p10: |served - mirror| <= 1.4e-14, |served - C| <= 3.6e-14 µm
    on every row; sw9776p10 T_amb now read held (49 rows; 0 on 898240b4), served = mirror = C.
B5: sizeof(tc_state), cr9763's mlr-none export (12 monitored), gcc: 22,176 -> 23,208 bytes
    (+128 sample numbers and the row count: 8 x 129).
B6: see the report (tests).  CPU (user + sys): dev cost 898240b4 11.8 + 24.9 + 44.8 s, fix
    (8 records) 69.0 s; fresh 898240b4 32.1 s (simulations and fits included) / fix 26.6 s.
    Served per row: ``SensorMonitor.update`` 20000 rows at 60 s, 2 pairs 898240b4 / fix 2.09 /
    2.16, 2.22 / 2.17 s.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_mon97 import CR, SW  # noqa: E402

FREEZE_S = 3600.0   # bench_cmon92's 60-row freeze at the records' 60 s period, and as long after
# fast-logger records (seen seeds re-simulated at another period; bench_mon97's words)
SW1 = ["sim.generator.calibration_hours=16.0", "sim.generator.production_hours=6.0"]
CR1 = ["sim.generator.duration_h=[2.0,3.0]"]


def _at(period: int, words: list[str]) -> list[str]:
    """``words`` at a logger of ``period`` seconds (the probes as often, the swiss lathe's at 5x)."""
    probe = [f"sim.generator.error_period_s={5 * period}"] if "sim=swiss_lathe_door" in words else []
    return [*words, f"sim.generator.sample_period_s={period}", *probe]


RECORDS = {**{f"cr{s}p10": _at(10, [*CR, f"seed={s}"]) for s in (9763, 9816, 9819)},
           **{f"sw{s}p10": _at(10, [*SW, f"seed={s}"]) for s in (9776, 9815, 9818)},
           "cr9763p1": _at(1, [*CR, "seed=9763", *CR1]), "sw9776p1": _at(1, [*SW, "seed=9776", *SW1]),
           # fresh (dep106's bar): simulated only after it was committed
           "cr10057p10": _at(10, [*CR, "seed=10057"]), "sw10058p10": _at(10, [*SW, "seed=10058"]),
           "cr10059p1": _at(1, [*CR, "seed=10059", *CR1])}


def _fitted(*args):
    """The times (s, the fit's newest at 0) the rule fits on: the tree's own where it names them
    (``frozen_hold.fitted``, dep106's), else mon105d's 128-row selection."""
    from thermocomp.apps.deploy.surveillance import frozen_hold

    if hasattr(frozen_hold, "fitted"):
        return frozen_hold.fitted(*args)[0]
    past_t, past, pos, run, tau = args
    rows = len(past_t)
    order = (pos + np.arange(rows)) % rows
    first = rows - int(run)
    if first < 2:
        return np.zeros(0)
    t, x = past_t[order[:first + 1]], past[order[:first + 1]]
    use = np.isfinite(t) & np.isfinite(x) & (t >= t[-1] - tau)
    return t[use] - t[-1]


class Way:
    """One way of reading a frozen sensor, patched into the served monitor's modules."""

    def __init__(self, name: str, rows: int | None = None):
        self.name, self.rows, self.fits = name, rows, []

    def __enter__(self):
        from thermocomp.apps.deploy.surveillance import frozen_hold, monitor

        self.saved = (monitor.TREND_ROWS, frozen_hold.TREND_ROWS, monitor.held_until)
        if self.rows:
            monitor.TREND_ROWS = frozen_hold.TREND_ROWS = self.rows
        rule = self.saved[2]

        def traced(*args):     # (past_t, past[, past_n], pos, run or first_n, tau, spread)
            t = _fitted(*args[:-1])
            until = -np.inf if self.name == "stand-in" else rule(*args)
            self.fits.append((float(-t[0]) if len(t) else 0.0, len(t), until))
            return until

        monitor.held_until = traced
        return self

    def __exit__(self, *exc):
        from thermocomp.apps.deploy.surveillance import frozen_hold, monitor

        monitor.TREND_ROWS, frozen_hold.TREND_ROWS, monitor.held_until = self.saved


def _served(deployed, frame, sensor: str, held_always: bool):
    """``(served corrections per row, rows the model read the sensor's held value)``."""
    col = list(deployed.columns_).index(sensor)
    j = list(deployed.monitor.names).index(sensor)
    X, t = frame[deployed.columns_].to_numpy(float), frame["time"].to_numpy(float)
    inputs, held = deployed._inputs, [0]

    def seen(x, tt, events, dt=None):
        row = inputs(x, tt, events, dt)
        mon = deployed.monitor
        if not mon._active[j]:
            if held_always:
                row = row.copy()
                row[col] = x[col]
            held[0] += bool(row[col] == x[col])
        return row

    deployed.reset()
    deployed._inputs = seen
    try:
        out = np.array([-deployed._step(X[i], t[i])[0] for i in range(len(frame))])
    finally:
        del deployed._inputs
    return out, held[0]


def cost(root: str, *records: str) -> None:
    """The ``cost`` rows (module doc)."""
    from bench_cmon92 import faulted_cell, made
    from bench_mon105c import frozen_sensors

    from thermocomp.apps.deploy.surveillance.states import EXCURSION_TAU_S

    base = Path(root).resolve()
    for record in records:
        made(base, record, "mlr", RECORDS)
        deployed, ss, frame, lead, start, cid = faulted_cell(base, record, "mlr-none")
        period = float(np.median(np.diff(frame["time"].to_numpy(float))))
        rows = int(round(FREEZE_S / period))
        full = int(math.ceil(EXCURSION_TAU_S / period)) + rows + 8
        targets = list(deployed.targets_)
        print(f"{record} campaign {cid}: period {period:g} s, freeze {rows} rows from row {start}, "
              f"full ring {full} rows", flush=True)
        for sensor in frozen_sensors(deployed.monitor):
            part = frame.iloc[start:start + 2 * rows].copy()
            part.iloc[:rows, part.columns.get_loc(sensor)] = part.iloc[0, part.columns.get_loc(sensor)]
            whole = pd.concat([frame.iloc[:start], part])
            E = part[targets].to_numpy(float)
            line = []
            for way in (Way("ring"), Way("full", full), Way("stand-in"), Way("held")):
                with way:
                    C, held = _served(deployed, whole, sensor, way.name == "held")
                rmse = float(np.mean(np.sqrt(np.nanmean((E + C[start:]) ** 2, axis=0))))
                fit = (f" span {way.fits[0][0]:.0f} s ({way.fits[0][1]} rows)" if way.fits and
                       way.name in ("ring", "full") else "")
                line.append(f"{way.name} {rmse:.4f} held {held}{fit}")
            print(f"  {sensor:<16} " + "; ".join(line), flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"cost": cost}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
