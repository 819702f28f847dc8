"""A slow sensor drift caught by a CUSUM of its self-prediction error (cusum70): rule and bar.

    PYTHONPATH=src .venv/bin/python benchmarks/bench_cusum70.py ROOT [--jobs 2] [--part fresh|healthy|all]

The gap (docs/monitoring.md, tests/shell/test_monitor.py ``SLOW_DRIFT``): a drift of 0.5 or
0.2 K/h on ``T_motor2`` of the default record is read as temperature until its self-prediction
error leaves the 0.4 °C warning band (10 / 18-21 samples of 5 min after the onset), and the
MLR leans on it: worst test campaign 1.79x / 1.74x the healthy RMSE, the bar 1.5x.

Measured first, offline (the default record's 8 test campaigns, MLR, the drift planted from
each campaign's middle row; ``/tmp`` scratch, not in this file's code): excluding ``T_motor2``
by hand k samples after the onset, and keeping it out, gives a worst ratio of 1.09 / 1.19 / 1.79
(0.5 K/h, k = 0 / 6 / 12, the monitor itself at 10-11) and 1.09 / 1.25 / 1.69 / 1.74 (0.2 K/h,
k = 6 / 12 / 18 / 24): the drift must be out within about an hour (12 samples), at 0.2 °C,
half the band.  The sensor's leave-one-out error is close to white (sd 0.043-0.063 °C, one
sample to the next 0.05 °C), so no rule on its slope helps; a level rule against zero flags a
constant offset of half the band too, which ``test_an_offset_inside_the_band...`` prices as
unseen.  A CUSUM against the sensor's own level at the campaign's start separates them: the
constant offset sits in that level, a drift leaves it.  Its largest value on healthy rows, in
band x samples, K = 0.25 (below): default record train 0.28 / test 0.22, yearround s5301 2.06 /
0.22, s5302 0.25 / 0.19, swiss_lathe s5304 5.40 / 1.40, column no Q3 s5305 23.4 / 14.1,
long_record s5306 15.2 / 5.1, large_mill s5303 (48 h March train, June test) 186 / 764 -- the
mill's test leaves its training (its known false alarm), with 5 sensors at half the limit
together when the first passes it.

Rule ``cusum`` v1 (written before scoring, commit aa1ee203; ``SensorMonitor``, on by default,
``monitor.detectors.cusum_k=null`` turns it off):

* For each sensor the others predict (leverage below ``pod.max_leverage`` with every sensor in),
  its error against the leave-one-out prediction of the POD operator with EVERY sensor in
  (fixed, whatever is excluded: a drifting sensor's own error stays exactly its drift), on the
  readings referenced to the campaign's first sample.
* Its baseline: the mean of that error over the campaign's samples 1..``window`` (the reference
  sample's is 0); from sample ``window`` + 1 on, two one-sided CUSUMs of (error - baseline) with
  reference ``k_j`` = ``cusum_k`` (0.25) x the sensor's warning band; the statistic is the larger,
  divided by the warning band.  A sample with any reading missing leaves the sums as they are.
* Limit ``h`` (one for all sensors): ``cusum_factor`` (2) x the largest statistic any judged
  sensor reached over the training campaigns (in sample, learned in ``from_training``), at least
  0.5 band x samples.
* A sensor is excluded for drift on this evidence when its statistic exceeds ``h``, every sensor
  is active, no new thermal state is declared, no other exclusion happened on the sample, at
  most one other judged sensor's statistic is at ``h``/2 or more (a lone fault, its coupled
  partner allowed; several sensors leaving their levels together are a field training never saw,
  the mill) and the new-state check of the band rule does not refuse it (``_drift_vetoed``).  The
  exclusion is a drift exclusion as the band's (the field may follow it: a new thermal state),
  without the band rule's blind-partner exclusion (once the drifting sensor is out, a partner no
  other sensor predicts is no longer judged and stays in).
* A sensor out on this evidence comes back only when its error's mean over the last ``window``
  samples is within ``k_j`` of its baseline (and the usual re-admission holds); its sums restart.

v1 FAILED bar 1-2 at its first test run (tests/shell/test_monitor.py): the sensor past the limit
was the coupled partner, ``T_motor1`` (a drift of ``T_motor2`` moves ``T_motor1``'s deleted
residual more: 0.111 against 0.080 °C over the window on K03 at 0.2 K/h), excluded alone; with
``T_motor2`` then unjudged, a 1 K/h drift of it was never reported on K03
(``test_a_fault_on_the_most_influential_sensor...[drift]`` failed; the slow drifts still
xfailed); and the column's shipped record (40 h train, one campaign) had 4 CUSUM exclusions on
its healthy part before Q3 (3.92-20.19 h, statistics 2.93-3.31 against a limit of 2.89:
``test_column_*`` failed twice).  The in-sample limit of one long training campaign is one draw.

Rule ``cusum`` v2 (written after v1's failure, before v2 is scored; the fresh records of bar 4
were not built for v1): v1, but

* the sensor excluded is, among the (at most two) judged sensors at ``h``/2 or more, paper 002's
  culprit as the bands pick it: the largest |departure| x (1 - h_j), the departure being the
  full-set error's mean over the window less the baseline; a judged sensor whose sums are above
  0 and that no other sensor predicts once it is out goes out with it (the band rule's blind
  partner: a coupled pair is a near tie for self-prediction);
* the limit: ``cusum_factor`` (2) x the largest statistic over the training campaigns in sample
  AND over held-out blocks (the training campaigns, or with fewer than 3 each cut in 4
  contiguous pieces; each block referenced to its first row and predicted by a basis of the
  same r fitted on the other blocks), at least 0.5.  Offline (K = 0.25, held-out): default
  record 0.28 (test 0.22), column shipped 66 (its in-sample 1.4), yearround s5301 6.7 / s5302
  0.19, swiss s5304 176, column s5305 82, long_record s5306 80, large_mill s5303 1078 (test 764).

v2 scored on bar 1-2 (the 15 monitor test modules, 90 s CPU): the slow drifts pass (worst
1.26 at 0.5 K/h, 1.31 at 0.2 K/h; the marks removed) and so does the column, but
``tests/apps/test_monitor_hotter56.py`` failed twice: its line warmed 16 °C beyond training along
its two trained modes had ``T_6`` excluded on CUSUM evidence at sample 234 (the basis's small
error grows with the distance from training, persistently, as a drift does).

Rule ``cusum`` v3 (written after v2's failure, before v3 is scored): v2, but the sums run only
while every reading is within its training range (absolute, ``lo_c``..``hi_c``, no margin);
beyond it they are held at 0, as while a sensor is out or a new thermal state is declared.

The bar is the same for v2 and v3.

v3 scored (2026-12-02, stop 70) -- REFUSED, bar 4 failed; src reverted, the rule (src, conf, its
test module ``tests/apps/test_monitor_cusum70.py``, the SLOW_DRIFT marks removed, the cli.md rows)
in ``benchmarks/cusum70_rule.patch`` (applies to 48af5bfc; this bench's ``--part`` runs need it,
its ``cusum_k=null`` is the rule off):

1. held: ``drift_0.5`` worst campaign 1.26x the healthy RMSE (was 1.79), ``drift_0.2`` 1.31x (was
   1.74); ``T_motor2`` and ``T_motor1`` out 3-5 samples after the onset at 0.5 K/h, 7-11 at
   0.2 K/h (the bands: 9-11 and 18-21).  Both fail on 48af5bfc (1.793, 1.744).
2. held: the 15 monitor modules, 135 passed, 2 xfailed (``test_monitor_healthy53``'s column and
   ``test_ambient_step54``'s real step, as before); 92 s user + 3 s sys of CPU.  The docs'
   frozen-``T_motor2`` example changes (E_Z adaptive 5.799 -> 5.619 um, first exclusion 4.08 ->
   3.92 h, 15 -> 16 events): the freeze leaves the field's level earlier than the band sees.
3. held: ``bench_monitor_healthy.py``'s 11 records x (mlr, lagbank), adaptive from the files: 22
   of 22 monitor.json identical with the rule on and off (no CUSUM exclusion); 177 s user + 28 s
   sys of CPU (``--part healthy --jobs 1``).
4. FAILED: fresh records 7101-7110 (MLR): 9 of 10 identical on and off; ``yearround s7102``'s
   healthy ``T_bearing_r`` was excluded on CUSUM evidence on K03 at 6.50 h (statistic 1.95 band x
   samples against its limit 1.83) and on K09 at 5.42 h (1.86), out to the end of each; adaptive
   sum over E_X, E_Y, E_Z of RMSE^2 12.725 -> 12.782 um^2 (fixed 12.725).  88 s user + 16 s sys
   of CPU (``--part fresh --jobs 1``).

What it says: the limit, 2x the largest statistic of 8 held-out training campaigns, is a maximum
over a few draws, and a healthy test campaign went 6 % beyond it; a limit high enough for every
healthy record would have to be set on records the rule was not scored on.

Bar (all must hold, else REFUSED, the src change reverted, the rule in
``benchmarks/cusum70_rule.patch``):

1. ``tests/shell/test_monitor.py``: both ``SLOW_DRIFT`` cases pass with their xfail marks removed
   (worst test campaign <= 1.5x the healthy RMSE on every target).
2. Every other monitor test passes: ``tests/shell/test_monitor*.py``, ``tests/apps/test_monitor*.py``,
   ``tests/shell/test_ambient_step54.py``; ``tests/shell/test_monitor_healthy53.py`` keeps its
   xfail or passes.
3. ``bench_monitor_healthy.py``'s 11 healthy records x (mlr, lagbank), adaptive from the files:
   no exclusion on CUSUM evidence (every monitor.json as with ``cusum_k=null``).
4. Fresh healthy records, seeds 7101-7110 (never used), MLR, adaptive from the files: no
   exclusion on CUSUM evidence.  Records (written before any was built):
   7101, 7102 ``yearround_spindle`` (12 campaigns); 7103, 7104 ``swiss_lathe_door`` (40 h
   calibration); 7105, 7106 ``column_moving_source`` without Q3 (shipped 40 h / 40 h);
   7107, 7108 ``large_mill_week`` (120 h train, 24 h test); 7109, 7110 ``long_record``
   (4 days, 25 % test).
Reported beside the bar (not part of it): the detection delay of 0.5 / 0.2 K/h on the default
record's ``T_motor2``, and the drift faults of ``bench_monitor_healthy.py`` where run.
"""

from __future__ import annotations

import argparse
import json
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_monitor_healthy as healthy  # noqa: E402

FRESH = {
    "yearround s7101": ["sim=yearround_spindle", "seed=7101", "sim.generator.n_campaigns=12"],
    "yearround s7102": ["sim=yearround_spindle", "seed=7102", "sim.generator.n_campaigns=12"],
    "swiss_lathe s7103": ["sim=swiss_lathe_door", "seed=7103", "sim.generator.calibration_hours=40"],
    "swiss_lathe s7104": ["sim=swiss_lathe_door", "seed=7104", "sim.generator.calibration_hours=40"],
    "column no Q3 s7105": ["sim=column_moving_source", "seed=7105", "sim.generator.q3=false"],
    "column no Q3 s7106": ["sim=column_moving_source", "seed=7106", "sim.generator.q3=false"],
    "large_mill s7107": ["sim=large_mill_week", "seed=7107", "sim.generator.train_hours=120",
                         "sim.generator.test_hours=24"],
    "large_mill s7108": ["sim=large_mill_week", "seed=7108", "sim.generator.train_hours=120",
                         "sim.generator.test_hours=24"],
    "long_record s7109": ["sim=long_record", "seed=7109", "sim.generator.duration_days=4",
                          "sim.generator.test_fraction=0.25"],
    "long_record s7110": ["sim=long_record", "seed=7110", "sim.generator.duration_days=4",
                          "sim.generator.test_fraction=0.25"],
}
OFF = "monitor.detectors.cusum_k=null"


def fresh_records(root: Path) -> dict:
    """``{record: data overrides}`` of the fresh records, written in ``root``."""
    records = {}
    for name, sim in FRESH.items():
        path = root / "fresh" / name.replace(" ", "_")
        if not (path / "campaigns.csv").exists():
            assert healthy.thermocomp("simulate", *sim, f"data.path={path}",
                                      *healthy.QUIET).returncode == 0, name
        extra = ["sim=long_record"] if name.startswith("long_record") else []
        records[name] = [f"data.path={path}", *extra]
    return records


def cusum_events(out: Path) -> list:
    """The monitor.json's exclusions on CUSUM evidence."""
    report = json.loads((out / "monitor.json").read_text())
    return [e for e in report["events"] if e["to"] == "excluded" and "CUSUM" in e["reason"]]


def on_off(root: Path, name: str, args: list, model: str) -> dict:
    """One record x model, adaptive from the files, the rule on and off."""
    key = f"{name.replace(' ', '_')}-{model}"
    row = {"record": name, "model": model}
    for mode, extra in (("on", []), ("off", [OFF])):
        out = root / "out" / key / mode
        proc = healthy.thermocomp("monitor", *args, f"model={model}", *extra, *healthy.QUIET,
                                  f"out={out}")
        if proc.returncode:
            row[mode] = {"error": proc.stderr.decode(errors="replace").strip().splitlines()[-1:]}
            continue
        report = json.loads((out / "monitor.json").read_text())
        row[mode] = healthy.summary(report)
        row[mode]["cusum"] = [(e["campaign"], e["sensor"], e["time"]) for e in cusum_events(out)]
        row[mode]["events_list"] = report["events"]
    row["identical"] = (row["on"].get("events_list") == row["off"].get("events_list")
                        and row["on"].get("rmse") == row["off"].get("rmse"))
    for mode in ("on", "off"):
        row[mode].pop("events_list", None)
    print(json.dumps(row), flush=True)
    return row


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("root")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--part", choices=("fresh", "healthy", "all"), default="all")
    a = parser.parse_args(argv)
    root = Path(a.root)
    jobs = []
    if a.part in ("fresh", "all"):
        jobs += [(n, args, "mlr") for n, args in fresh_records(root).items()]
    if a.part in ("healthy", "all"):
        jobs += [(n, args, m) for n, (args, _) in healthy.build(root).items()
                 for m in ("mlr", "lagbank")]
    with ThreadPoolExecutor(a.jobs) as pool:
        rows = list(pool.map(lambda j: on_off(root, *j), jobs))
    (root / "results.json").write_text(json.dumps(rows, indent=1))
    print(f"\n{'record':20s} {'model':8s} exclusions on/off  CUSUM exclusions  identical")
    for r in rows:
        on, off = r["on"], r["off"]
        print(f"{r['record']:20s} {r['model']:8s} {on.get('exclusions', 'err')!s:>6}/"
              f"{off.get('exclusions', 'err')!s:<8} {len(on.get('cusum', []))!s:>5}  "
              f"{r['identical']}  {on.get('cusum', '')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
