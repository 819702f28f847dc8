"""A slow one-sensor drift told by the sum of its self-prediction errors (mon101, issue 34; the
strict xfail SLOW_DRIFT of tests/shell/test_monitor.py, "a slow one-sensor drift named late").

THE GAP (seen: the default scenario ``yearround_spindle``, its 8 test campaigns, adaptive MLR as
tests/shell/test_monitor.py's ``deployed`` fixture builds it; ``drift`` below).  The most
influential sensor ``T_motor2`` drifts +0.5 or +0.2 K/h from mid-campaign (300 s rows).  Its
leave-one-out error follows the drift one to one (K03 +0.2 K/h: +0.10 after 8 rows, +0.33 after
18, healthy errors within +-0.06 there; training's largest |error| of T_motor2 0.195, of
T_motor1 0.245) and the band is 0.4 degC: the drift is named 7-11 rows after onset at +0.5 K/h,
18-30 rows at +0.2 K/h, and its coupled partner ``T_motor1`` goes out with it (blind once
T_motor2 is out).  Worst per-campaign RMSE ratio to the healthy stream 1.793 (+0.5, K06 E_Z) and
1.847 (+0.2, K21 E_Z) against the test's 1.5.  Where the cost sits (``drift``'s split): the
stream healthy after the exclusion row still 1.81 (K03 +0.2 E_Z), the stream healthy before it
at most 1.13, and T_motor2 dropped out at onset 1.09: the cost is the rows the drift is read as
temperature, not the pair's exclusion.

RULE (served only: ``surveillance/trend.py``; ``states.TREND_ALLOW`` / ``TREND_SUM`` /
``TREND_GROWTH``; monitor keys ``trend_allow`` / ``trend_sum``, a monitor pickled before:
``trend_sum`` inf, never).  A one-sided CUSUM per judged sensor of its leave-one-out error beyond
``TREND_ALLOW`` = 0.5 x its warning band; once the sum reaches ``TREND_SUM`` = 0.5 x the band and
the error grows (beyond the field memory's own error on its side, excursion.py's 1800 s memory,
by ``TREND_GROWTH`` = 0.125 x the band) the sensor is judged as out of its warning band
(``_judge``), and the band's judgement (culprit, lone fault, blind partner, new thermal state)
decides.  The sums restart when the active set changes; the fast path and the block path take a
row only while every sum is zero and no judged error passes the allowance.  Not in the export
(watch.py mirror, C, ST): C = served is not claimed where the rule fires.

Tuned on SEEN cases only, before this bar (``drift`` worst ratio +0.5 / +0.2 K/h; ``column``:
sensor alarms / exclusions before Q3's onset, main 0):
  allow 1/3, sum 1, no growth gate      -> 1.326 / 1.408; column T_right2 out at 13700 s
  allow 0.5, sum 1, no gate             -> 1.488 / 1.531
  allow 0.5, sum 0.5, no gate           -> 1.326 / 1.463; column T_right2 out at 14000 s
  gate by excursion.py's share-of-rise   -> 1.326 / 1.847 (a linear drift "hovers" after 3 tau)
  allow 0.5, sum 0.5, growth 0.125      -> 1.326 / 1.463; column 1 (T_right2 14000 s)  <- judged
  allow 0.5, sum 0.5, growth 0.25       -> 1.326 / 1.561; column 1
  allow 0.5, sum 1, growth 0.125 / 0.25 -> 1.488 / 1.531, 1.561; column 1 (14400 s)
  allow 0.55 / 0.58, sum 0.5, g 0.125   -> 1.326 / 1.531, 1.368 / 1.531; column 1 (14400, 15000 s)
  allow 0.6, sum 0.5, g 0.125 / 0.25   -> 1.368 / 1.531, 1.561; column 0
  allow 0.6, sum 1, g 0.125 / 0.25     -> 1.488 / 1.638, 1.786; column 0
No point of the grid meets M1 and the column's clause of M2 together: the column's healthy
T_right2 steps to -0.23 degC (0.57 of its band, 100 s rows) within half an hour and hovers there
for hours; at the sum's firing its error -0.228 stands 0.13 beyond its memory's -0.099, as the
drift's does (the trace: the same two numbers, seen, at count 141).  The judged point meets M1;
the bar below is scored on it as it stands.

BAR (committed before any of the fresh seeds 9953-9955 is simulated; scored once)
---
M1. the xfail's case passes: tests/shell/test_monitor.py drift_0.5 and drift_0.2, worst ratio
    <= 1.5, SLOW_DRIFT removed.
M2. healthy records the monitor is quiet on: 0 new flags (alarm / excluded / new state) -- the
    default scenario's 8 test campaigns (``drift``: healthy events 0), the healthy column
    (``column``: no sensor alarm or exclusion before Q3's onset, 72000 s, as main), bench_mon98's
    seen healthy frames and fl_thermal (monitor quiet as main).
M3. main's named faults on bench_mon98 / bench_jump94b lines stay named, same rows +-2.
M4. fresh 9953-9955 (yearround_spindle seeds, +0.2 K/h on the most influential sensor from
    mid-campaign, chosen before drawing): named in every test campaign, no flag before onset.
Plus the project's rule: every test that passes on 7676398c passes (tests/shell/test_monitor.py
the first; C = served where the export's tests hold it).

Usage (repository root; ``PYTHONPATH=<tree>/src``: the monitor measured is that tree's)::

    python benchmarks/bench_mon101.py drift ROOT     # the xfail's cases, healthy, split
    python benchmarks/bench_mon101.py column ROOT    # the healthy column before Q3's onset

``drift``: simulates ``yearround_spindle`` (default seed) into ``ROOT/default`` once; per kind and
test campaign the first exclusion's row and sensors, the RMSE ratio per target, the worst; the
healthy campaigns' event count; with ``split``'s three stand-ins (healthy after / before the
exclusion row, the sensor dropped at onset).  ``column``: simulates ``column_moving_source`` into
``ROOT/column``, runs ``monitor`` into ``ROOT/column-mon`` and prints the sensor alarms and
exclusions before the source's onset.

MEASURED (2026-12-06, after the bar 1053102d; main = 7676398c's src (``git archive``), the rule
= 1053102d's; load 15-22 on 2 cores).  VERDICT: REFUSED -- M2 and M3 fail on SEEN records, so
the fresh seeds 9953-9955 were NOT simulated (unspent: scoring them could not change the verdict).
The rule and the xfail's removal: ``benchmarks/mon101_rule.patch`` (``git apply`` on 7676398c);
src is 7676398c's.
---
M1 MET: ``drift`` worst ratio main -> rule 1.793 -> 1.326 (+0.5 K/h), 1.847 -> 1.463 (+0.2 K/h);
   named 5-8 rows after onset at +0.5 (main 7-11), 9-18 at +0.2 (main 18-30); T_motor1 still
   goes out with T_motor2 (its blind partner), no flag before onset; healthy test campaigns 0
   events.  tests/shell/test_monitor.py: 39 passed, 2 failed (the column's two tests).
M2 NOT MET (healthy, 0 new flags asked):
   column (``column``): T_right2 excluded at 14000 s, Q3 on at 72000 s (main: none before it).
   bench_mon98 ``cases`` healthy frames, served events main -> rule: tr9828 0 -> 12 (T_table out
   row 1943, a new thermal state, T_coolant_return out row 4856), sw9776 0 -> 163, cr9763 0 -> 0,
   lr9376 6 -> 8 (T_col_back out rows 430, 3140, 3871).
   fl_thermal (bench_jump94b ``fl``), healthy: 0 -> 16 events (T_t16 out at 1875 s, T_t9 at
   2100 s, ...), Sigma^2 83.90 -> 142.84 um^2.
   tests/apps/test_monitor_*.py: 22 failed, 45 passed, 1 xfailed (all pass on main: freeze84
   checked, 2 passed) -- healthy sensors excluded early (regime73's hovering offset, hotter56,
   ambient_one_campaign94), new states read as exclusions (new_state48), leak81, lone84, ...
M3 NOT MET as a whole (named faults, same rows +-2), bench_mon98 drift / ambient lines, served
   named row main -> rule: tr9828 T_ram 817 -> 817, T_amb 708 -> 708 (but T_column out at 508
   first); sw9776 T_headstock 920 -> 920, T_amb 744 -> 744; cr9763 none -> none; lr9376
   T_head_left 27 -> 19 (C 27: not in the export).  fl_thermal's 15 planted T_t16 steps: the
   re-reference at 9 in every cell as main (+1 degC at 556 neither); main's drift exclusion at 1
   of -3 degC at 240 / 556 gone, one added at -3 degC at 900 (and +5 degC at 900, at 7); every
   cell's Sigma^2 up 53-66 um^2 (the healthy record's exclusions).
M4 not scored (fresh 9953-9955 unspent).
C = served: not held where the rule fires (tr9828 healthy 2.41 um over 40 rows; sw9776 ambient
   14.9 um / 7052 rows); the rule was not put in the export.
CPU: ``drift`` 3.9 s (its simulate / monitor subprocesses not counted); bench_mon98 ``cases``
   main 56.1 s, rule 59.0 s; ``column`` ~4 s + ~18 s wall of subprocesses.
What the trace says for a next try: at the sum's firing the column's healthy T_right2 (-0.228,
memory -0.099) and the drifting T_motor2 look alike; what separates them comes later (the drift
keeps growing, the regime stays).  A rule that waits for that is the band's own timing.  The
cost sits before the exclusion, in the model's lean on T_motor2 (4.9 um on E_Z for half the band),
so a model-side answer (a smaller lean on one sensor; an offset priced in training) may be the
reachable one, not an earlier detector.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests"), str(HERE.parent / "tests" / "shell")]
from _cli import run_commands  # noqa: E402

from conftest import influence  # noqa: E402
from test_monitor import _stream  # noqa: E402  (the xfail's own stream, events per row)

KINDS = {"drift_0.5": 0.5, "drift_0.2": 0.2}


def _cli(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "thermocomp", *args, "track=false", "-q"], check=True)


def _deployed(path: Path):
    """The adaptive MLR of tests/shell/test_monitor.py's ``deployed`` fixture, its test campaigns
    and most influential sensor (tests/conftest.py's ``influence``)."""
    from hydra.utils import instantiate
    from omegaconf import OmegaConf

    from thermocomp.apps.deploy import StreamingCompensator
    from thermocomp.apps.monitor import AdaptiveCompensator
    from thermocomp.core import io
    from thermocomp.core.compensator import Compensator

    ds, _ = io.read_dataset(path, {})
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    test = {c: ds.campaigns[c] for c in ds.ids("test")}
    comp = Compensator(instantiate(OmegaConf.load(HERE.parent / "conf/model/mlr.yaml").estimator))
    comp.fit(train)
    adaptive = AdaptiveCompensator.from_training(StreamingCompensator.from_training(comp, train), train)
    effect = influence(comp, test)
    sensor = max((s for s in effect if not s.startswith("T_amb")), key=effect.get)
    return adaptive, comp, test, sensor


def _drifted(df, sensor, k_per_h):
    k0 = len(df) // 2
    t = df["time"].to_numpy(float)
    v = df[sensor].to_numpy(float).copy()
    v[k0:] += k_per_h * (t[k0:] - t[k0]) / 3600
    return df.assign(**{sensor: v}), k0


def drift(root: str) -> None:
    path = Path(root) / "default"
    if not path.exists():
        _cli("simulate", f"data.path={path}")
    adaptive, comp, test, sensor = _deployed(path)
    measured = comp.measured(test)
    quiet = 0
    for cid, df in test.items():
        quiet += len(_stream(adaptive, df)[1])
    print(f"sensor {sensor}; healthy test campaigns: {quiet} events")
    for kind, rate in KINDS.items():
        worst = 0.0
        for cid, df in test.items():
            faulty, k0 = _drifted(df, sensor, rate)
            y, events = _stream(adaptive, faulty)
            healthy, _ = _stream(adaptive, df)
            m = measured[cid][adaptive.targets_].to_numpy()
            rms = np.sqrt(np.mean((m - healthy) ** 2, 0))

            def ratio(z):
                return np.sqrt(np.mean((m - z) ** 2, 0)) / rms

            out = [e for e in events if e["to"] == "excluded"]
            first = out[0]["row"] if out else len(df)
            before = [e for e in events if e["row"] < k0 and e["to"] in ("alarm", "excluded")]
            drop = faulty.copy()
            drop.loc[drop.index[k0:], sensor] = np.nan
            r = ratio(y)
            worst = max(worst, float(r.max()))
            print(f"{kind} {cid} onset {k0} out {first} (+{first - k0}) "
                  f"{sorted({e['sensor'] for e in out if e['row'] == first})} before onset {len(before)} "
                  f"ratio {np.round(r, 2)} | healthy after "
                  f"{np.round(ratio(np.vstack([y[:first], healthy[first:]])), 2)}"
                  f" before {np.round(ratio(np.vstack([healthy[:first], y[first:]])), 2)}"
                  f" dropped {np.round(ratio(_stream(adaptive, drop)[0]), 2)}")
        print(f"{kind} worst {worst:.3f}")


def column(root: str) -> None:
    path, out = Path(root) / "column", Path(root) / "column-mon"
    if not path.exists():
        _cli("simulate", "sim=column_moving_source", f"data.path={path}")
    _cli("monitor", "sim=column_moving_source", f"data.path={path}", f"out={out}", "plots=none")
    truth = json.loads(path.with_name(path.name + ".truth.json").read_text())
    on = truth["campaigns"]["test_cycle"]["q3_on_s"][0][0]
    report = json.loads((out / "monitor.json").read_text())
    early = [e for e in report["events"] if e["to"] in ("alarm", "excluded")
             and e["sensor"] in report["sensors"] and e["time"] < on]
    print(f"Q3 on at {on:.0f} s; sensor alarms / exclusions before it: {len(early)}")
    for e in early:
        print(f"  {e['time']:.0f} s {e['sensor']} {e['from']} -> {e['to']}: {e['reason'][:100]}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"drift": drift, "column": column}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
