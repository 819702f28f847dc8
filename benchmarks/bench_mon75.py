"""The grinder's hot, healthy spindle and its bed left by a hotter column: mon74's range rule with a
drift hold that lets a real drift go out at once (mon75, issue 34).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_mon75.py healthy [SIM] [ROOT] [SEEDS]
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_mon75.py faults [SIM] [ROOT]
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_mon75.py drift [DEFAULT]

``SIM`` (default ``/tmp/mon75-sim``: bench_mon74's grinder records, ``benchmarks/vgm73.py``, plus
the fresh seeds 7521-7530 exported the same way) and ``ROOT`` (default ``/tmp/mon75-root``) as in
``bench_mon74.py``.  ``healthy`` prints per seed (default 7366-7385, 7426-7435, 7521-7530)
bench_drift74's line (RMSE fixed -> adaptive per target, exclusions, drift exclusions); ``faults``
bench_mon74's (``T_spindle`` 40 samples missing, dead, stuck); ``drift`` the drifts: 1 K/h on the
grinder's ``T_base`` from 20 h of seed 7432, either way (the monitor alone, fitted as in
``tests/apps/test_monitor_drift74.py``: the hours of its exclusions to 26 h, whether out at
22.5 h), and tests/shell/test_monitor.py's
``[drift]`` case, 1 K/h on the most influential sensor of the default scenario (``DEFAULT``: a
``thermocomp simulate`` of it; ``mlr``): per test campaign, samples from onset to the sensor's first
exclusion and the adaptive / healthy RMSE ratios (the test's bar: 1.5).

Trace (2026-12-02, before any scoring)
--------------------------------------
* The drift test mon74 + drift74 failed (bench_drift74: 1.593 > 1.5 on K06).  The sensor is
  ``T_motor2``; its coupled partner ``T_motor1`` (healthy) shows the largest culprit error
  (-1.26 x its band: the drifting partner pulls its prediction up).  Shipped, the culprit rule
  excludes ``T_motor1`` and then ``T_motor2`` as its blind partner, 4-6 samples after onset;
  drift74 rightly sees ``T_motor1``'s reading not moving toward its error (left by the field)
  and holds it -- and with it everything, so ``T_motor2`` went out only on its own error, 1-2
  samples later (K06, K09, K12, K18).  At those holds ``T_motor2`` is 0.85-1.09 x its band, its
  reading moved 0.62-0.90 °C toward its error's side over the memory, its error grew 2.9-5.0 x
  the memory's, and with it out every other judged sensor is within band; no other sensor is.
* The grinder (the monitor alone, the 40 seeds, every hold drift74 makes): the other judged
  sensors that moved toward their error's side, grew past 1.5 x and whose exclusion would put
  ``T_Bett`` back in band are at most 0.18 x their band (7432's ``T_hall``, 16.09 h); ``T_Ständer``
  at most 0.49 x, never grown past 1.5 x.
* Why the false ``T_Bett`` exclusion helped 7384 / 7429 / 7432: "Trace of the benefit" below
  (measured after the rule's commit, before scoring; it changes no rule).

Rule (one, with mon74's two; written and committed before any scoring)
----------------------------------------------------------------------
mon74's (a) range priced and (b) guard following the vouched inputs, as in
``benchmarks/mon74_rule.patch``, unchanged.  The drift hold of drift74, amended: a culprit of the
culprit rule (``new_state`` on) out of its warning band but within its alarm band whose excursion
is not its own since the memory (``EXCURSION_TAU_S``; its reading did not move toward its error's
side, or its error did not outgrow ``EXCURSION_GROWTH`` x the memory's) is held (it warns), unless
another judged sensor's excursion IS its own (moved toward its error's side and grown past
``EXCURSION_GROWTH`` x; v1, see below), its error at least ``READMIT`` (0.5) of its warning
band, and with it out every other judged sensor is within band (``_resolves``): that sensor is
excluded for drift instead (the largest self-prediction error first; the new-state veto as for any
culprit; its
blind partners as before).  Past the alarm band, and where the memory is unknown, as shipped.

Scored, rule v1 above (2026-12-02, commit bbda568c): REFUSED on bar 2
------------------------------------------------------------------------
``bench_monitor_healthy.py`` yearround s5301 mlr, the 1 K/h drift of ``T_bearing_f2``: adaptive
ΣRMSE² 29.881 -> 42.152 (fixed 963.6; first flag as shipped, 30-35 min; one warning and two guard
events more).  On K06 the drifting sensor itself, out of its warning band at 3.17 h (+0.46 °C),
was held as "left by the field" for 25 min until its error passed the alarm band (+0.93 °C,
3.58 h): its reading did not move toward its error's side, the bearing cooling about as fast as
it drifted.  (Before this: the motor drift and the bed as in ``drift`` below for v2, identical
for v1; ``bench_deploy_faults.py`` every line as shipped; healthy grinder seeds 7366-7385 adaptive
= fixed to the digit, no exclusion.)

Rule v2 (written and committed after v1's scoring, before v2's)
---------------------------------------------------------------
v1 with the reading's clause dropped, both where a culprit is held and where another sensor's
excursion is its own: a culprit out of its warning band but within its alarm band is held (it
warns) while its error hovers (no larger on its side than ``EXCURSION_GROWTH`` x the memory's),
unless another judged sensor's error outgrew ``EXCURSION_GROWTH`` x the memory's, is at least
``READMIT`` of its warning band and, with it out, every other judged sensor is within band: that
one is excluded instead.  A drift's error keeps growing whether the field warms or cools under
it.  The bar below, unchanged, for v2.

Bar (written before scoring; the rule is kept only if every point holds, else src reverted)
-------------------------------------------------------------------------------------------
1. ``healthy``, the 40 seeds: no record's adaptive RMSE above 1.05 x fixed on either target, and no
   record with more exclusions (false fault events: every sensor is healthy) than shipped.
2. Faults, none caught later or worse than shipped by > 2 %: ``faults`` (adaptive RMSE, each
   target); ``bench_deploy_faults.py`` (every printed figure); ``drift``: the bed out at
   22.5 h (either sign; shipped: out since its false exclusion at 16.09 h), the motor drift's
   first exclusion no later than shipped on any campaign and its ratios no worse than shipped by
   > 2 %.
3. ``bench_monitor_healthy.py``: no healthy figure worse than shipped (events, exclusions,
   adaptive ΣRMSE², worst ratio), on the record x model pairs that run in the time.
4. ``tests/shell/test_monitor*.py`` and ``tests/apps/test_monitor*.py`` pass (xfails stay xfail).

Trace of the benefit (the fixed model, batch, fed ``T_Bett`` as read or rebuilt from the other
four by the monitor's POD, over the shipped exclusion windows; a scratch trace)
----------------------------------------------------------------------------------------------
The model (``auto`` on seed 7356) answers +10.1 µm/°C on the bed and -10.7 on the column for
E_dZ (a difference of two sensors that rose together in training; the spindle -8.8, the air
+3.3, the oil +2.0).  In the windows the column ran past its training maximum (23.97 °C: 25.0 on
7429 and 7432, 28.0 on 7384, 26.2 on 7375) with the bed not following, and the model
under-predicts E_dZ there (mean error +7.8 / +13.8 / +8.3 / +4.2 µm).  The bed rebuilt from the
column reads 0.97 / 0.98 / 1.39 / 0.95 °C warmer than measured, which adds about 10 µm: window
RMSE 9.14 -> 4.07 (7429), 14.18 -> 4.80 (7432), 12.47 -> 8.13 (7384), but 6.55 -> 7.09 on 7375
(it overshoots); E_dX a little worse on all four (2.57 -> 2.66 on 7429).  So the benefit is
the rebuilt (wrong) bed cancelling the model's error off its training pattern, by chance of
sign and size, not what the reading is: the simulator's bed is healthy.  It is not mon74's
mechanism as priced there (a sensor past its range, the model's extrapolation against a
fallback on training rows): here no sensor is past range + margin, and on training the field
predicts the bed within band, so "read" and "rebuilt" are the same rows -- nothing to price.
Holding the column at its training maximum does not reproduce it (E_dZ window RMSE 9.10,
5.87, 20.34, 13.32).  A rule keeping it would be a projection of the model's inputs onto the
training pattern (the envelope's clamp; the grinder's envelope has no pattern), its own rule.

Scored, rule v2 (2026-12-02, src of commit 303090d3; shipped = this tree before, 960d5025)
---------------------------------------------------------------------------------------
1. ``healthy``, 40 seeds: no exclusion on any (shipped: 50 on 27 records, 6 of them the false
   ``T_Bett`` drift: 7375, 7384, 7429, 7432, 7528, 7529); adaptive = fixed to the digit on 36;
   E_dX 1.028x on 7377 and 7527, 1.019x 7529, 1.010x 7431 (the guard, as mon74); E_dZ 1.000x on
   all (shipped: worst 20.18x, 7430 E_dX; E_dZ up to 7.09x, 7432).  Passes.
2. ``faults``: nan40 22.121 / 0.732, dead 161.074 / 1.775, stuck 160.821 / 1.741 (as shipped);
   ``bench_deploy_faults.py``: every line as shipped (diff empty but CPU); ``drift``: the bed
   out at 22.27 h (+1 K/h) and 21.40 h (-1 K/h), the motor drift out 4-6 samples after onset on
   every campaign with the ratios of shipped to the digit (worst 1.410).  But
   ``bench_monitor_healthy.py`` large_mill s5303 (bar 2's "caught later"): the 1 K/h drift of
   ``T_col_10`` first flagged 3300 -> 3870 s (mlr) and 1290 -> 1500 s (lagbank), stuck mlr
   870 -> 1080 s (lagbank 1020 -> 840), though adaptive ΣRMSE² better (drift mlr 332.3 -> 50.2,
   its healthy ``T_col_03`` excluded at 12.58 h on the way).  FAILS.
3. ``bench_monitor_healthy.py`` (4 of 11 records run, the rest not: time): yearround s5301 and
   column no Q3 s5305 results.json identical to shipped (v1 had moved s5301's drift); large_mill
   s5303: the healthy ``T_col_05`` (+0.45 °C at its band, excluded once shipped) held and warning:
   mlr events 2 -> 10, ΣRMSE² 9.543 -> 10.099; lagbank 2 -> 10, 43.096 -> 41.135.  FAILS.
4. ``tests/shell/test_monitor*.py``, ``tests/apps/test_monitor*.py`` (+ the mon74 tests,
   test_benchmarks_cli, test_imports): 326 passed, 3 xfailed.  Passes.

REFUSED (bars 2 and 3): src reverted to 960d5025; the change (mon74's rules, this hold, docs,
tests: test_monitor_drift74's 3, fallback71's and guard56's, all 5 failing on 960d5025) is
``benchmarks/mon75_rule.patch``.  CPU (user + sys): ``healthy`` 328.2 s (40 records, a loaded
machine; shipped 270.5), ``faults`` 8.0, ``drift`` 5.1 (shipped 3.2), the tests 75.2 + 2.7.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]

from _cli import run_commands  # noqa: E402
from bench_drift74 import healthy as drift74_healthy  # noqa: E402
from bench_mon74 import SEEDS, faults  # noqa: E402
from cpu import cpu_seconds  # noqa: E402

SIM, ROOT, DEFAULT = "/tmp/mon75-sim", "/tmp/mon75-root", "/tmp/mon75-default"
FRESH = tuple(range(7521, 7531))
MONITOR = {"warning_c": 0.4, "alarm_c": 0.8, "window": 10, "confirm": 2}   # conf/monitor's


def healthy(sim: str = SIM, root: str = ROOT, seeds: str = "") -> None:
    """bench_drift74's ``healthy`` on the 40 seeds (or ``SEEDS``, comma-separated)."""
    drift74_healthy(sim, root, seeds or ",".join(map(str, (*SEEDS, *FRESH))))


def _bed(rate: float) -> tuple[list[float], bool]:
    """Seed 7432 with ``rate`` K/h on ``T_base`` from 20 h, the monitor alone: the hours of its
    exclusions up to 26 h, and whether it is out at 22.5 h (test_monitor_drift74's bar)."""
    from vgm73 import lab_record

    from thermocomp.apps.deploy.surveillance import SensorMonitor

    train, service = lab_record(7356), lab_record(7432)
    names = [c for c in train.columns if c.startswith("T_")]
    mon = SensorMonitor.from_training(None, names, {"rec": train[names].to_numpy(float)[
        :int(0.9 * len(train))]}, **MONITOR)
    X = service[names].to_numpy(float).copy()
    t = 15.0 * np.arange(len(X))
    X[:, names.index("T_base")] += rate * np.clip(t - 20 * 3600.0, 0, None) / 3600.0
    out, at = [], False
    for x, time in zip(X[t < 26 * 3600], t):
        out += [time / 3600 for e in mon.update(x, time)[1]
                if e["sensor"] == "T_base" and e["to"] == "excluded"]
        if time == 22.5 * 3600:
            at = "T_base" in mon.excluded
    return out, at


def _motor(default: str) -> None:
    """tests/shell/test_monitor.py's ``[drift]`` case, per test campaign."""
    from hydra.utils import instantiate
    from omegaconf import OmegaConf

    from thermocomp.apps.deploy import StreamingCompensator
    from thermocomp.apps.monitor import AdaptiveCompensator
    from thermocomp.core import io
    from thermocomp.core.compensator import Compensator
    sys.path[:0] = [str(REPO / "tests"), str(REPO / "tests" / "shell")]
    from conftest import influence
    from test_monitor import _faulty, _stream

    ds, _ = io.read_dataset(default, {})
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    test = {c: ds.campaigns[c] for c in ds.ids("test")}
    comp = Compensator(instantiate(OmegaConf.load(REPO / "conf/model/mlr.yaml").estimator)).fit(train)
    adaptive = AdaptiveCompensator.from_training(StreamingCompensator.from_training(comp, train),
                                                 train)
    effect = influence(comp, test)
    sensor = max((c for c in effect if not c.startswith("T_amb")), key=effect.get)
    measured = comp.measured(test)
    worst = 0.0
    for cid, df in test.items():
        faulty, k0 = _faulty(df, sensor, "drift")
        y, events = _stream(adaptive, faulty)
        healthy_y, _ = _stream(adaptive, df)
        m = measured[cid][adaptive.targets_].to_numpy()
        ratio = np.sqrt(np.mean((m - y) ** 2, 0)) / np.sqrt(np.mean((m - healthy_y) ** 2, 0))
        out = [e["row"] - k0 for e in events if e["sensor"] == sensor and e["to"] == "excluded"]
        worst = max(worst, float(ratio.max()))
        print(f"{sensor} {cid}: excluded {out[0] if out else '-'} samples after onset, ratios "
              + " ".join(f"{r:.3f}" for r in ratio), flush=True)
    print(f"worst ratio {worst:.3f} (the test's bar 1.5)")


def drift(default: str = DEFAULT) -> None:
    """The bed's drift on the grinder (either way), then the motor drift of test_monitor."""
    start = cpu_seconds()
    for rate in (1.0, -1.0):
        hours, out = _bed(rate)
        print(f"T_base {rate:+.0f} K/h from 20 h: excluded at "
              + (" ".join(f"{h:.2f}" for h in hours) or "-") + f" h; out at 22.5 h: {out}",
              flush=True)
    _motor(default)
    print(f"CPU s (user + sys): {cpu_seconds() - start:.1f}")


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"healthy": healthy,
                                  "faults": lambda sim=SIM, root=ROOT: faults(sim, root),
                                  "drift": drift}, sys.argv[1:] if argv is None else argv)


if __name__ == "__main__":
    sys.exit(main())
