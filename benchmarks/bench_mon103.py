"""A slow one-sensor drift named late, priced by the model's lean on that sensor (mon103, issue
34; the strict xfail SLOW_DRIFT of tests/shell/test_monitor.py; mon101's next step).

THE GAP (seen: the default scenario ``yearround_spindle``, default seed, adaptive MLR as
tests/shell/test_monitor.py's ``deployed`` fixture builds it).  ``T_motor2`` drifts +0.5 / +0.2 K/h
from mid-campaign; it is named 7-11 / 18-30 rows (300 s) after onset and costs 1.793 / 1.847x the
healthy error (worst campaign and target).  mon101 showed the cost sits in the rows before the
exclusion, where the model reads the drift as temperature.

TRACE (seen; ``bands`` below).  The model's step gains (``adaptive.input_gains``, the guard's)
per °C on E_Z: T_motor2 -24.6, T_motor1 +17.0, T_bearing_f2 -17.1, T_bearing_f3 +16.6,
T_bearing_r +16.8 (collinear pairs), T_box1 -7.1, T_nose +6.9, T_bearing_f1 -4.8, T_box2 +1.0;
training's residual RMS (simulation mode) 0.61 / 1.45 / 4.38 um (E_X / E_Y / E_Z).  The lean
(gain / residual RMS, largest over targets; 1/°C): T_motor2 5.62, f2 3.99, motor1 3.88, r 3.83,
f3 3.78, box1 3.38, box2 2.75, f1 1.67, T_amb 1.61, nose 1.58.  Every band is the configured
0.4 °C (training-spread floors 0.18-0.33); test campaigns' largest |judged error| of T_motor2 is
0.151 °C, the drift's cost per row at the band 24.6 x 0.4 = 9.9 um on E_Z (2.3 residual RMS).
T_motor2's band alone (seen, worst +0.5 / +0.2 K/h): 0.3 -> 1.793 / 1.744; 0.273 (its floor) ->
1.594 / 1.744; 0.25 -> 1.488 / 1.744; 0.2 -> 1.326 / 1.463; every band at its floor 1.368 / 1.580.

RULE (in ``benchmarks/mon103_rule.patch``, not in src; served only: ``surveillance/lean.py``,
``SensorMonitor.price_bands``, called by ``AdaptiveCompensator.from_training``; constants
``states.LEAN_HARM`` = 1, ``LEAN_FLOOR`` = 0.8).
Each non-ambient sensor's warning band is at most ``LEAN_HARM / lean`` (the drift it lets through
costs at most one training residual RMS of the worst target), never below ``LEAN_FLOOR`` x its
training-spread floor (``floor_c``), never above its band as fitted.  The bands are the monitor's
``warning_c``: the export carries them, so C = served by construction.  A monitor pickled before:
its bands as they were.

Tuned on SEEN cases only, before this bar (``drift`` worst +0.5 / +0.2 K/h; ``column``: flags --
sensor alarm / exclusion / new thermal state -- before Q3's onset, main 0):
  harm 1, floor 2/3 -> 1.326 / 1.408; column T_right2 out at 14000 s (its band 0.4 -> 0.23)
  harm 1.5, floor 2/3 -> 1.594 / 1.744;  harm 0.5, floor 2/3 -> 6.503 (+0.5: partners out) / 1.362
  harm 1, floor 1 -> 1.368 / 1.580; column 0 before onset
  harm 1, floor 0.8 -> 1.326 / 1.415; column: no alarm / exclusion before onset, a new thermal
                       state at 11.97 h (onset 20 h)                                   <- judged
No point meets M1 and the column's clause of M2 together (mon101's finding again, by another
road): the column's MLR leans on nearly every sensor (floor 2/3: 17 of 20 bands priced below
0.4 °C, T_left2 0.4 -> 0.112), so a band priced by lean is a tightening of the whole set there.
The judged point meets M1; the bar below is scored on it as it stands.

BAR (committed before any of the fresh seeds 9953-9955 is simulated; scored once)
---
M1. the xfail's case: tests/shell/test_monitor.py drift_0.5 and drift_0.2 worst ratio <= 1.5,
    SLOW_DRIFT removed (the test passes).
M2. healthy records: 0 new flags (alarm / excluded / new thermal state) against main -- the
    default scenario's 8 test campaigns (``drift``: 0 events), the column before Q3's onset
    (``column``), bench_mon98's seen healthy frames (tr9828 sw9776 cr9763 lr9376: served events
    as main's) and fl_thermal healthy (bench_jump94b ``fl``: events as main's).
M3. main's named faults on bench_mon98's seen drift / ambient lines and bench_jump94b's fl cells
    stay named, same rows +-2.
M4. fresh 9953-9955 (yearround_spindle, ``seed=``; +0.2 K/h on the most influential non-ambient
    sensor, conftest's ``influence``, from mid-campaign; chosen before drawing): named in every
    test campaign, worst ratio <= main's, no flag before onset.
Plus: every test that passes on 4a21da2b passes (tests/shell/test_monitor.py first).

Usage (repository root; ``PYTHONPATH=<tree>/src``: the monitor measured is that tree's)::

    python benchmarks/bench_mon103.py bands ROOT            # the trace: gains, leans, bands
    python benchmarks/bench_mon103.py drift ROOT            # the xfail's cases (bench_mon101's)
    python benchmarks/bench_mon103.py column ROOT           # flags before Q3's onset
    python benchmarks/bench_mon103.py fresh ROOT SEED ...   # M4 on yearround_spindle seeds

``bands`` / ``drift`` simulate ``yearround_spindle`` into ``ROOT/default`` once; ``column``
simulates ``column_moving_source`` into ``ROOT/column`` and monitors it into ``ROOT/column-mon``;
``fresh`` simulates each seed into ``ROOT/seed<SEED>`` and prints per test campaign the first
exclusion's row after onset and sensors, the flags before onset, the worst ratio.

MEASURED (2026-12-07, after the bar 1b22164f; main = 4a21da2b's src (``git archive``), the rule =
1b22164f's).  VERDICT: REFUSED -- M2 and M3 fail on SEEN records, so the fresh seeds 9953-9955
were NOT simulated (unspent: scoring them could not change the verdict).  The rule and the xfail's
removal: ``benchmarks/mon103_rule.patch`` (``git apply`` on 4a21da2b); src is 4a21da2b's.
---
M1 MET: ``drift`` worst ratio main -> rule 1.793 -> 1.326 (+0.5 K/h), 1.847 -> 1.415 (+0.2);
   named +6-9 rows after onset (main 7-11), +9-18 (main 18-30); no flag before onset; healthy
   test campaigns 0 events.  tests/shell/test_monitor.py on the rule: drift_0.5 / 0.2 pass; 35
   passed, 6 failed (the two column tests; out-of-range T_amb x3: it never comes back, its leak
   judged against the tightened bands of the others; K12's T_motor2 first-row-missing + noise
   1.5: excluded at row 0 against its band 0.218).
M2 NOT MET (0 new flags asked):
   column (``column``): 15 of 20 bands priced below main's (T_left2 0.4 -> 0.134, T_edge2 ->
   0.114, T_front1 -> 0.164); a new thermal state at 43100 s (T_left2, T_right4), Q3 on at 72000 s
   (main: none before it; first exclusion T_right2 at 72600 s, main T_right3 at 73000 s).
   bench_mon98 ``cases`` healthy frames, served events main -> rule: tr9828 0 -> 0, sw9776 0 -> 14
   (two new thermal states, rows 397 / 679: T_guidebush, T_nc_x1_drive), cr9763 0 -> 0, lr9376
   6 -> 22 (T_col_back out at 3871 as main; 431 / 3141 now five-sensor warnings).
   fl_thermal healthy (bench_jump94b ``fl``): 0 -> 6 events (T_t13 excluded at 5490 s, T_t14
   warning), Sigma^2 83.90 -> 83.92 um^2.
   tests/apps (``-k test_monitor_``): 2 failed, 66 passed, 1 xfailed (deployed_as_scored44's
   silent healthy test part, blame44).
M3 NOT MET as a whole (same rows +-2): bench_mon98 named rows main -> rule: tr9828 T_ram 817 ->
   817, T_amb 708 -> 708 (but T_column, healthy, out at 700 first; RMSE 1.12 -> 2.54 um); sw9776
   T_headstock 920 -> 920, T_amb 744 -> 744; cr9763 none -> none; lr9376 T_head_left 27 -> 21 (C 21).
   fl_thermal's 15 T_t16 steps: the re-reference at 9 in every cell as main (+1 degC at 556
   neither); drift exclusions added (+1/+2/+3 degC at 240: row 312; +5 at 240: row 1; +2/+3 at 556:
   row 11; +5 at 556: row 3); Sigma^2 within 0.4 um^2 of main's in every cell.
M4 not scored (fresh 9953-9955 unspent).
C = served HELD in every bench_mon98 case (rows mirror != served 0, max|C - served| <= 2.9e-12 um):
   the priced bands are the monitor's ``warning_c`` and the export carries them.
CPU: ``drift`` 1.4 s (its simulate subprocess not counted), ``column`` ~7 s + the monitor
   subprocess, bench_mon98 ``cases`` main 49.5 s / rule 50.4 s.
What the trace says: a band priced by the model's lean is a global tightening on a collinear MLR
(the default: 7 of 10 bands; the column: 15 of 20), and a band tight enough for M1 (T_motor2's
0.218 = 1.4x its healthy test maximum 0.151) is the band healthy regimes elsewhere cross.  The
price is right (the column's reported undetected-offset cost 13.4 -> 6.36 um), the action is
not: what to do with a leaned-on sensor's offset inside the band is a model-side question (a
fit that spreads the lean over coupled partners, or the without-sensor fallback while its error
is past the price, no exclusion, no flag) -- not another band.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests"), str(HERE.parent / "tests" / "shell")]
from _cli import run_commands  # noqa: E402
from bench_mon101 import _cli, _deployed, _drifted  # noqa: E402
from bench_mon101 import drift as _drift_cases  # noqa: E402

from test_monitor import _stream  # noqa: E402  (the xfail's own stream, events per row)

FLAGS = ("alarm", "excluded", "new thermal state")
FRESH_RATE = 0.2     # K/h, the xfail's slower kind


def _simulated(root: str, name: str, *overrides: str) -> Path:
    path = Path(root) / name
    if not path.exists():
        _cli("simulate", f"data.path={path}", *overrides)
    return path


def bands(root: str) -> None:
    """Per monitored sensor: its step gain per target, lean, warning band and floor."""
    from thermocomp.apps.deploy.adaptive import input_gains

    adaptive, _, _, sensor = _deployed(_simulated(root, "default"))
    mon, cols = adaptive.monitor, adaptive.columns_
    gains = input_gains(adaptive.streaming)
    print(f"most influential {sensor}; targets {adaptive.targets_}")
    for j, name in enumerate(mon.names):
        print(f"{name:14s} gains {np.round(gains[:, cols.index(name)], 2)} warning "
              f"{mon.warning_c[j]:.3f} floor {mon.floor_c[j]:.3f}")


def drift(root: str) -> None:
    """bench_mon101's ``drift`` on this tree (per kind and campaign, the worst ratio)."""
    _simulated(root, "default")
    _drift_cases(root)


def column(root: str) -> None:
    """The healthy column's flags before Q3's onset (M2)."""
    path, out = _simulated(root, "column", "sim=column_moving_source"), Path(root) / "column-mon"
    _cli("monitor", "sim=column_moving_source", f"data.path={path}", f"out={out}", "plots=none")
    truth = json.loads(path.with_name(path.name + ".truth.json").read_text())
    on = truth["campaigns"]["test_cycle"]["q3_on_s"][0][0]
    report = json.loads((out / "monitor.json").read_text())
    early = [e for e in report["events"] if e["to"] in FLAGS and e["time"] < on]
    print(f"Q3 on at {on:.0f} s; flags before it: {len(early)}; warning bands "
          f"{dict(zip(report['sensors'], np.round(report['bands']['warning_c'], 3)))}")
    for e in early:
        print(f"  {e['time']:.0f} s {e['sensor']} {e['from']} -> {e['to']}: {e['reason'][:100]}")


def fresh(root: str, *seeds: str) -> None:
    """M4: +0.2 K/h on the most influential sensor of each seed's scenario, from mid-campaign."""
    for seed in seeds:
        adaptive, comp, test, sensor = _deployed(_simulated(root, f"seed{seed}", f"seed={seed}"))
        measured, worst, quiet = comp.measured(test), 0.0, 0
        for cid, df in test.items():
            healthy, calm = _stream(adaptive, df)
            quiet += sum(e["to"] in FLAGS for e in calm)
            faulty, k0 = _drifted(df, sensor, FRESH_RATE)
            y, events = _stream(adaptive, faulty)
            m = measured[cid][adaptive.targets_].to_numpy()
            ratio = np.sqrt(np.mean((m - y) ** 2, 0)) / np.sqrt(np.mean((m - healthy) ** 2, 0))
            worst = max(worst, float(ratio.max()))
            out = [e for e in events if e["to"] == "excluded" and e["sensor"] == sensor]
            early = [e for e in events if e["row"] < k0 and e["to"] in FLAGS]
            named = f"+{out[0]['row'] - k0}" if out else "never"
            print(f"seed {seed} {sensor} {cid} onset {k0} named {named} flags before onset "
                  f"{len(early)} ratio {np.round(ratio, 3)}")
        print(f"seed {seed} {sensor}: worst {worst:.3f}; healthy flags {quiet}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"bands": bands, "drift": drift, "column": column,
                                  "fresh": fresh}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
