"""A separation robust to noisy extremes for the settled-step rule? fl_thermal's +1 degC T_t16
step at mid-test (settle96, issue 34; follow-up of ``bench_settle95.py``, whose fault (2) was
traced, not mended: separation 0.354 < limit 0.362 degC, "noisy extremes").
TRACED: no separation of the monitor's two 10-sample windows tried here, its limit derived as
main's (3 x its largest training value), catches it: the robust ones raise T_t16's training
limit more than the cell's separation (below).  Src as main; fresh seeds not simulated.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_settle96.py candidates [W]               # the statistics, offline
    python benchmarks/bench_settle96.py fl ROOT STAT                 # fl_thermal, STAT patched in
    python benchmarks/bench_settle96.py flbar MAIN_ROOT RULE_ROOT    # clause (c) of the bar
    python benchmarks/bench_settle96.py trace ROOT RECORDS STAT      # bench_step93's trace
    python benchmarks/bench_settle96.py healthy ROOT RECORDS STAT    # bench_step93's healthy
    python benchmarks/bench_settle96.py steps MAIN_ROOT RULE_ROOT    # clause (a) / (d)
    python benchmarks/bench_settle96.py events MAIN_ROOT RULE_ROOT   # clause (b) / (d)

``STAT``: the two windows' separation the served monitor's ``settled`` rule reads, both for each
blind sensor's training limit (``jump_factor`` 3 x its largest training value,
``settled.largest_separation``) and for the test (``settled.level_shift``), patched onto the
tree's ``settled.separation`` in this process and in the ``thermocomp`` children it runs:
``minmax`` (main's: one window's minimum less the other's maximum), ``trimK`` (K = 1, 2, 3:
the (K+1)-th smallest of one window less the (K+1)-th largest of the other: K extremes of each
window ignored), ``medmadC`` (the windows' median difference less C x the sum of their median
absolute deviations; C = 2.28: a window of 10 Gaussian samples' expected half range is 2.28
MADs, so ``medmad2.28`` is the min/max separation the windows would have without their
extremes; ``medmad0``: the median difference alone).  ``candidates``: every STAT on fl_thermal's
columns offline (train = the first 10003 rows, ``data=fl_thermal``'s cut): T_t16's largest
training value and where, the limit, the 15 planted T_t16 cells (bench_jump94's SIZES x ONSETS)
caught or not with settle95's steadiness (median difference past 6 x the larger MAD) within 2 W
samples of the onset (W: each window's length, the monitor's 10 unless given), the +1 degC at 556
against its limit, and the healthy test parts of the three blind sensors (T_t16, T_t4, T_t5):
samples where the rule would fire.  ``fl`` / ``trace`` /
``healthy``: bench_jump94b's with STAT patched (``fl`` -> ``ROOT/fl-main.json``); ``flbar``,
``steps``, ``events``: bench_jump94b's / bench_settle95's comparisons.  Main's src for MAIN_ROOT:
``git archive bd118abf src conf | tar -x -C /tmp/main`` and a ``datasets`` link to the tree's.

BAR (the brief's; written after the offline ``candidates`` trace of the seen fl_thermal, before
any STAT ran in the monitor and before any fresh seed; fresh = lr9754-9758 and cr9769-9773,
bench_settle95's design; main = bd118abf):
(c) seen fl_thermal (``fl`` / ``flbar``): the +1 degC T_t16 step at 556 caught; the healthy
    record 0 sensor events (Σ² = main's 83.90 to 0.01 µm²); main's 14 caught cells caught, none
    with d past main's + log(1.02);
(d) seen ``trace lr9699-9703,cr9704-9708``: detected not below main's 175, no cell past main's
    d + log(1.02), mean d not above main's (4 dp); ``healthy`` on bench_step93b's 15 seen
    records: 0 new sensor events;
(r) the seen ramp (bench_settle95 ``ramp``, cmon82c/91 ``T_u``): not re-referenced;
(a) fresh ``trace``: detected not below main's, no cell past main's d + log(1.02);
(b) fresh ``healthy`` on the 10 fresh true records: 0 sensor events, 0 new.
Seen before fresh: a STAT that fails (c) on the seen record is not taken to the fresh seeds (they
stay unspent for a later stop).  KEPT only with all five, src in served, mirror and C (1e-9),
tests failing on bd118abf and docs/monitoring.md; else REFUSED (``benchmarks/settle96_rule.patch``)
or TRACED.

Trace (seen, before the bar; ``candidates``).  Where main would fire (onset + 9) on the +1 degC
at 556 the separation is set by two samples: the window before holds one at +0.38 degC off its
median (its next highest +0.24), the window after its first at 0.73 above that median (the rest
0.96-1.38); its MADs 0.158 / 0.150 degC (0.093 / 0.098 at 240): a noisy stretch.  Dropping one
extreme of each window (``trim1``) lifts the cell to 0.715, but lifts T_t16's largest training
value too, from 0.121 (row 3644: a quiet +0.205 degC level change, MAD 0.020) to 0.280 (row
3869: +0.339, MAD 0.050): limit 0.362 -> 0.841, the cell 0.98 -> 0.85 x its limit.  T_t16's
training limit is set by quiet, short level changes whose windows spread little: a statistic that
discounts the windows' spread gains more on them than on the noisy cell.  One that reads the
medians alone (``medmad0``) meets the training bursts (row 4654: -1.202 degC); even among windows
settle95's steadiness passes, T_t16's largest training median shift is 0.628 degC, and the
cell's 1.086 is 1.73 x it, under the factor 3.  ``candidates`` (W 10; T_t16's limit, the cell /
its limit, cells caught offline; 0 fires on the healthy test parts of T_t16 / T_t4 / T_t5 for
every STAT):

    STAT        T_t16 train max (row, median diff, MAD)  limit  +1@556  caught (of main's 14)
    minmax      0.121 (3644, +0.205, 0.020)              0.362  0.98    14 (14)
    trim1       0.280 (3869, +0.339, 0.050)              0.841  0.85    13 (+1@900 lost)
    trim2       0.382 (4655, -1.202, 0.709)              1.145  0.69    12 (+1@240, +1@900 lost)
    trim3       0.475 (6387, -0.628, 0.094)              1.425  0.69    12 (+1@240, +1@900 lost)
    medmad0     1.202 (4654, -1.202, 0.709)              3.605  0.30     3
    medmad1.5   0.378 (6387, -0.628, 0.094)              1.133  0.55    12 (+1@240, +1@900 lost)
    medmad2.28  0.247 (6387, -0.628, 0.094)              0.742  0.52    12 (+1@240, +1@900 lost)
    medmad3     0.139 (4450, +0.311, 0.033)              0.417  0.38    14 (14)

Measured (2026-12-06; main = bd118abf's src under /tmp, the STATs patched onto this branch's
src = main's; under a load of 7-15 on 2 cores)
---
(c) ``fl`` + ``flbar``, the served monitor with the STAT as limit and test: main's 16 lines as
    bench_settle95's (healthy 83.90 µm², 0 sensor events; 14 caught at +9; +1@556 missed, d x 100
    21.11); ``fl ROOT minmax`` (the patch with main's statistic) equal on all 16 (the harness is
    neutral).  ``trim1``: fires at +8; +1@556 missed, +1@900 lost (d x 100 0.67 -> 3.62, past main's
    + log(1.02)); healthy 83.90, 0 events; mean d x 100 3.39 -> 3.48.  ``medmad2.28``: fires at +5
    (6 of the window after past the step: a partial shift taken out); +1@556 missed, +1@240 and
    +1@900 lost; 5 cells past main's d + log(1.02); mean d x 100 3.39 -> 6.42.  (c) FAILS for
    both: neither taken to (d), (a), (b); fresh lr9754-9758 / cr9769-9773 not simulated (unspent).
(d, part) ``healthy`` on bench_step93b's 15 seen records: main (bd118abf) column9316's 188,
    lr9430's 3 (d x 100 41.965), every other 0; ``trim1`` and ``medmad2.28`` the same on every
    record: 0 new.  (main's seen ``trace`` was started and stopped unread: no STAT passed (c).)
Longer windows (``candidates W``, offline, the limit derived the same way): at W = 15 no STAT
catches the cell (minmax 1.04 x its limit offline but under it at every steady sample); at W = 20
medmad1.5 / 2.28 / 3 and trim3 catch all 15 (medmad2.28 1.21 x, limit 0.416 degC), minmax's
limit falls to 0.050 degC (training windows of 20 part by 0.017 at most); at W = 30 minmax's
limit is 0.  0 healthy fires on the three blind sensors at every W.  A window of the rule's own is
a lead, not a result: chosen here it would be chosen on this one cell (15 fails, 20 passes), it
delays the re-reference to up to 2 W - 1 samples after the step (not run in the monitor here)
and the monitor's window is shared by its other rules; it needs a derivation from training alone
and records other than fl_thermal.
CPU: ``candidates`` 0.2-0.5 s; ``fl`` 2.9-3.1 s of this process (its fit and 16 monitor runs are
children, not counted; a few minutes wall each); ``healthy`` 15 records 19.6 (main) / 20.2 / 21.3 s.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_jump94 as jump94  # noqa: E402
import bench_jump94b as jump94b  # noqa: E402
from _cli import run_commands  # noqa: E402

N_TRAIN = 10003                 # data=fl_thermal's train part (test_fraction 0.1: 1112 test rows)
BLIND = ("t16(°C)", "t4(°C)", "t5(°C)")     # fl_thermal's sensors no other predicts
STATS = ("minmax", "trim1", "trim2", "trim3", "medmad0", "medmad1.5", "medmad2.28", "medmad3")


def statistic(name: str):
    """The separation ``f(a, w)`` STAT ``name`` names (module doc), rows and columns as
    ``settled.separation``'s."""
    if name == "minmax" or name.startswith("trim"):
        k = 0 if name == "minmax" else int(name[4:])

        def ordered(a: np.ndarray, w: int) -> np.ndarray:
            win = np.sort(sliding_window_view(np.asarray(a, float), w, axis=0), -1)
            lo, hi = win[..., k], win[..., w - 1 - k]
            return np.maximum(lo[w:] - hi[:-w], lo[:-w] - hi[w:])
        return ordered
    if name.startswith("medmad"):
        c = float(name[6:])

        def robust(a: np.ndarray, w: int) -> np.ndarray:
            win = sliding_window_view(np.asarray(a, float), w, axis=0)
            med = np.median(win, -1)
            mad = np.median(np.abs(win - med[..., None]), -1)
            return np.abs(med[w:] - med[:-w]) - c * (mad[w:] + mad[:-w])
        return robust
    raise SystemExit(f"STAT must be one of {', '.join(STATS)}, got {name!r}")


def _steady(a: np.ndarray, w: int) -> np.ndarray:
    """settle95's steadiness test (``settled.steadiness``, ``STEADY``), rows as the statistics'."""
    from thermocomp.apps.deploy.surveillance.settled import STEADY, steadiness
    shift, spread = steadiness(a, w)
    return np.abs(shift) > STEADY * spread


def candidates(window: str = "10") -> None:
    """Every STAT on fl_thermal offline, two windows of ``window`` samples (module doc)."""
    import pandas as pd
    df = pd.read_csv(jump94.RECORD)
    w = int(window)
    print("STAT        T_t16 train max (row, median diff, larger MAD)  limit | +1@556 / limit; "
          "cells caught (main's 14); healthy test fires T_t16 / T_t4 / T_t5")
    for name in STATS:
        f = statistic(name)
        lims, fires = {}, []
        for col in BLIND:
            x = df[col].to_numpy(float)[:, None]
            tr = f(x[:N_TRAIN], w)[:, 0]
            lims[col] = 3 * max(tr.max(), 0.0)
            te = x[N_TRAIN:]
            fires.append(int(((f(te, w)[:, 0] > lims[col]) & _steady(te, w)[:, 0]).sum()))
            if col == jump94.SENSOR:
                r = int(np.argmax(tr))
                win = x[r:r + 2 * w, 0]
                md = np.median(win[w:]) - np.median(win[:w])
                mad = max(np.median(np.abs(v - np.median(v))) for v in (win[:w], win[w:]))
                where = f"{tr[r]:6.3f} (row {r + 2 * w - 1}, {md:+.3f}, {mad:.3f})"
        x = df[jump94.SENSOR].to_numpy(float)[N_TRAIN:, None]
        caught, at556 = [], None
        for onset in jump94.ONSETS:
            for size in jump94.SIZES:
                y = x.copy()
                y[onset:] += size
                span = slice(onset - 2 * w + 1, onset + 1)     # windows ending at onset .. +19
                s = f(y, w)[span, 0]
                if (onset, size) == (556, 1.0):
                    at556 = s.max() / lims[jump94.SENSOR]
                if ((s > lims[jump94.SENSOR]) & _steady(y, w)[span, 0]).any():
                    caught.append(f"{size:+g}@{onset}")
        main14 = len([c for c in caught if c != "+1@556"])
        print(f"{name:<11} {where}  {lims[jump94.SENSOR]:.3f} | {at556:.2f}; {len(caught)} caught "
              f"({main14} of main's 14{', +1@556 in' if '+1@556' in caught else ''}; missed "
              f"{sorted(set(_cells()) - set(caught))}); fires {fires}", flush=True)
    x = df[jump94.SENSOR].to_numpy(float)[:N_TRAIN, None]
    md = statistic("medmad0")(x, w)[:, 0]
    steady = _steady(x, w)[:, 0]
    print(f"T_t16 training: largest |median difference| {md.max():.3f} degC, {md[steady].max():.3f} "
          f"where steady (settle95's steadiness; {int(steady.sum())} windows)")


def _cells() -> list[str]:
    return [f"{size:+g}@{onset}" for onset in jump94.ONSETS for size in jump94.SIZES]


def _patch(stat: str) -> None:
    """STAT as ``settled.separation`` in this process (limit and test alike)."""
    from thermocomp.apps.deploy.surveillance import settled
    settled.separation = statistic(stat)


def _child(stat: str):
    """bench_jump94's ``thermocomp`` child, run as this bench's ``_tc STAT``."""
    def run(rule: str, *args: str) -> None:
        subprocess.run([sys.executable, str(Path(__file__).resolve()), "_tc", stat, *args,
                        "plots=none", "track=false"], check=True, capture_output=True,
                       cwd=jump94.REPO)
    return run


def fl(root: str, stat: str) -> None:
    """bench_jump94b's ``fl`` with STAT patched into every ``thermocomp`` child -> ``ROOT/fl-main.json``."""
    statistic(stat)
    jump94._thermocomp = _child(stat)
    jump94b.fl(root)


def flbar(main_root: str, rule_root: str) -> None:
    """Clause (c): bench_jump94b's table, then this bar's (the +1 degC at 556 caught too)."""
    import json
    jump94b.flbar(main_root, rule_root)
    a, b = (json.loads((Path(r) / "fl-main.json").read_text()) for r in (main_root, rule_root))
    cells = [k for k in a if k != "healthy"]
    hit = {k: [any(e[1] != "ok" for e in x[k]["events"]) for x in (a, b)] for k in cells}
    lost = [k for k in cells if hit[k][0] and not hit[k][1]]
    far = [k for k in cells if b[k]["d"] > a[k]["d"] + np.log(1.02)]
    quiet = (not b["healthy"]["sensor_events"]
             and abs(b["healthy"]["sigma2"] - a["healthy"]["sigma2"]) < 0.01)
    ok = quiet and hit["+1@556"][1] and not lost and not far
    print(f"main caught {sum(h[0] for h in hit.values())}, rule {sum(h[1] for h in hit.values())}; "
          f"+1@556 {'caught' if hit['+1@556'][1] else 'missed'}; lost {lost}; past {far}; "
          f"healthy quiet {quiet}: (c) of settle96 {'MET' if ok else 'FAILS'}")


def trace(root: str, labels: str, stat: str) -> None:
    """bench_step93b's ``trace`` with STAT patched -> ``ROOT/trace-main.json``."""
    _patch(stat)
    jump94b.trace(root, labels)


def healthy(root: str, labels: str, stat: str) -> None:
    """bench_step93b's ``healthy`` with STAT patched -> ``ROOT/healthy-main.json``."""
    _patch(stat)
    jump94b.healthy(root, labels)


def _tc(stat: str, *args: str) -> int:
    """(child) ``thermocomp ARGS`` with STAT patched in."""
    _patch(stat)
    from thermocomp.shell.cli import main as cli
    return cli(["-q", *args])


def main(argv: list[str]) -> int:
    if argv[:1] == ["_tc"]:
        return _tc(argv[1], *argv[2:])
    return run_commands(__doc__, {"candidates": candidates, "fl": fl, "flbar": flbar,
                                  "trace": trace, "healthy": healthy, "steps": jump94b.steps,
                                  "events": jump94b.events}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
