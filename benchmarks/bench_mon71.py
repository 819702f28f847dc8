"""The sensor monitor excluded a healthy drive sensor on a lathe's joined 300 s rows (mon71).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_mon71.py cause ROOT
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_mon71.py write ROOT
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_mon71.py init ROOT lathe_7211 data.join.offset_s=7
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_mon71.py matrix ROOT [names] [--families ...]

Found by pair70: bench_twolog70's Swiss-type lathe at seed 7141 (two loggers, joined onto the
probes' 300 s rows, ``data.join.offset_s=7``): ``replay`` excluded the healthy ``T_NC_X1_drive``
twice, dX 2.175 against run's 1.827 µm (mlr); the simulator's own 60 s run had no event.

Why (``cause``: the monitor fitted on the simulated calibration run and fed its production run,
both at 60 s and every 5th row, the calibration started at its row 0 or a few rows later)
-----------------------------------------------------------------------------------------------
Not the sample period.  The DAQ started 2 min late, so the join's first row of the calibration
(its reference: the monitor's snapshots are changes since it) is the probes' 07:05 row, 5 min
into a warm-up; the 60 s run starts cold.  Started 5 min late at 60 s the monitor excludes the
same sensor (at 41 min); from row 0 at 300 s it excludes nothing.  The production run (a steady
5000 rpm no calibration hour held) keeps ``T_Tool_holder_1`` 0.4-0.6 °C off the others' field for
24 h whatever the basis (from row 0 or 5: the same errors to 0.05 °C); its band is 3 x its training
spread, and that spread moves with the reference: 0.89 °C from a cold start, 0.539 from 5 min in
(the healthy peak of the judged statistic 0.558).  Every error of a campaign is its sample's
error less its first sample's, and the first sample lies in the start-up transient the basis fits
least: over the training's first window of samples ``T_Tool_holder_1`` errs -0.18 °C and
``T_NC_X1_drive`` +0.17 on average, against ±0.006 over the whole campaign.  A training campaign
referenced at a cold start carries that offset in every training error (wide bands); one
referenced 5 min in carries a smaller share, while the test, started cold, carries it whole.
The culprit rule then takes out ``T_NC_X1_drive`` (+0.37 °C, within its 0.528 band), whose
exclusion leaves ``T_Tool_holder_1`` unjudged.

The rule (written before scoring)
---------------------------------
The training spread that floors each sensor's bands (``SensorMonitor.from_training``: the 99.5th
percentile of the windowed leave-one-out error) is also learnt with each training campaign's
errors taken against the mean error of its first window (the campaign's start as a window, not
one sample), the larger of the two per sensor.  Nothing else changes.

The bar (written before scoring)
--------------------------------
1. seed 7141, bench_pair70's ``base_mm`` and ``lathe_mm`` (``matrix`` mlr and lagbank,
   ``data.join.offset_s=7``): no monitor event in replay, replay = run (<= 1e-9 µm).
2. ``bench_monitor_healthy.py`` (its records, every mode): no new event in any pair.
3. the monitor's fault modules (``pytest tests -k monitor``) pass, and
   ``bench_deploy_faults.py``'s adaptive column is unchanged or better.
4. fresh healthy seeds 7211-7216 of bench_twolog70's lathe (this bench's ``write`` / ``init`` /
   ``matrix``, mlr and lagbank, offset 7), scored once after this commit: no event in replay.
Missing any: the src change is reverted (REFUSED, with the numbers).

Measured (2026-12-02, 2 shared cores, user + sys CPU): REFUSED, reverted
-------------------------------------------------------------------------
``cause`` (5.8 s), today's code: at 60 s from row 0 / 2 min no event (T_Tool_holder_1's band
0.882 / 0.802 °C), from 3 / 5 / 10 min ``T_NC_X1_drive`` excluded (2 / 1 / 1 times; bands 0.851 /
0.573 / 0.4); at 300 s from 0 / 2 / 3 min none (0.887 / 0.725 / 0.813), from 5 min twice (0.539,
the joined record's case), from 10 min once (0.4).  Whether a record fires turns on where its
first row falls, at either period.  With the rule:

1. MET: 7141 ``base_mm`` / ``lathe_mm``, mlr and lagbank: no event, replay - run <= 8.9e-16 µm
   (before: 4 events, dX 2.175 against 1.827 mlr; 25.4 s for the 4 cells).
2. not run (3 had missed; the rule only widens bands).
3. MISSED: ``pytest tests -k monitor`` (149.8 s) 3 failed of 220.  ``test_monitor_blame44``: the
   1 K/h drift of ``T_table``, which no other sensor predicts, leaks onto ``T_xdrive`` and was
   flagged there; with the wider bands nothing is flagged at all (no event).  ``test_monitor_healthy53``'s
   strict xfail (the column's false alarm) passes: quiet now.  (``test_promote``'s
   ``test_monitor_adaptive_false_registers_the_plain_stream_once`` fails alone on today's code too:
   it needs its module's earlier tests.)  ``bench_deploy_faults.py``: every line the same (8.3 s).
4. MET: fresh seeds 7211-7216, mlr and lagbank (56.6 s): no event in any of the 12 cells, replay -
   run <= 2.2e-15.  Today's code on them (44.1 s): seed 7212 fires the same way (``T_NC_X1_drive``
   out twice, then ``T_Tool_holder_2``; 11 events), replay dX 3.804 against run's 3.372 µm (mlr),
   3.389 against 3.353 (lagbank); the other five quiet.  With 7141, 2 of 7 records of this lathe.

Tried before the rule, not scored: the POD basis fitted on each campaign's snapshots less their
mean (no reference sample privileged): seed 7141 quiet from 5 min, not from 10; the Swiss lathe's
dropout in ``tests/shell/test_monitor_cli.py`` then costs 4.9x the healthy error (bound 1.5x).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pandas as pd

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]

import bench_twolog70 as twolog  # noqa: E402
import lab_matrix  # noqa: E402

from thermocomp.apps.deploy.surveillance import SensorMonitor  # noqa: E402

SEEDS = {f"lathe_{s}": s for s in range(7211, 7217)}
CAUSE_SEED = 7141
OPTIONS = {"warning_c": 0.4, "alarm_c": 0.8, "window": 10, "confirm": 2}   # conf/monitor's


def write(root: Path) -> None:
    """The two loggers' files of each fresh seed, as bench_twolog70 writes them."""
    for name, sim_dir, folder in lab_matrix.simulated(root, SEEDS, twolog.simulate):
        for row in pd.read_csv(sim_dir / "campaigns.csv").itertuples(index=False):
            sim = pd.read_csv(sim_dir / row.file)
            temp, disp = twolog.lab_files(sim, pd.Timestamp(row.start), row.campaign)
            temp.to_csv(folder / f"{row.campaign}_temp.csv", index=False)
            disp.to_csv(folder / f"{row.campaign}_disp.csv", index=False, sep=";")
        print(json.dumps({"wrote": name}), flush=True)


def cause(root: Path) -> None:
    """Seed 7141's simulated runs through the monitor: calibration from row ``skip`` (60 s rows),
    every ``step``-th row; events, exclusions and two sensors' bands."""
    sim_dir = root / "sim" / "cause"
    if not (sim_dir / "campaigns.csv").exists():
        twolog.simulate(CAUSE_SEED, sim_dir)
    cal, pro = (pd.read_csv(sim_dir / f) for f in ("calibration.csv", "production.csv"))
    names = [c for c in cal.columns if c.startswith("T_")]
    for step in (1, 5):
        for skip in (0, 2, 3, 5, 10):
            train = cal[names].to_numpy(float)[skip::step]
            mon = SensorMonitor.from_training(None, names, {"calibration": train}, **OPTIONS)
            events = []
            for x, t in zip(pro[names].to_numpy(float)[::step], pro["time"].to_numpy(float)[::step]):
                events += mon.update(x, t)[1]
            band = {n: round(float(mon.warning_c[names.index(n)]), 3)
                    for n in ("T_toolholder1", "T_nc_x1_drive")}
            print(json.dumps({"period_s": 60 * step, "from_min": skip, "events": len(events),
                              "excluded": [(e["sensor"], e["time"]) for e in events
                                           if e["to"] == "excluded"][:3], "bands": band}), flush=True)


FAMILIES = {k: v for k, v in lab_matrix.matrix_families().items() if k in ("mlr", "lagbank")}


def main(argv: list[str]) -> int:
    np.seterr(all="ignore")
    return lab_matrix.main(__doc__, argv, SEEDS, FAMILIES, ("plain",),
                           {"write": lambda root, rest: write(root),
                            "cause": lambda root, rest: cause(root),
                            "init": lambda root, rest: lab_matrix.initialised(root, rest[0], rest[1:])})


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
