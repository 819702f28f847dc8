"""A sensor excluded in service: its reconstruction, or the same family fitted without it (sub71).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_sub71.py score [ROOT] [FAULTS_ROOT] [CANDIDATE]

``ROOT`` (default ``/tmp/sub71-root``) gets bench_deploy_faults' record (``yearround_spindle``
seed 5353, 9 campaigns of 3-5 h, K03/K06/K09 held out) and its fits; ``FAULTS_ROOT`` (default
``/tmp/faults71-root``, read only) is bench_faults71's, its records and fits made by
``bench_faults71.py write``.

Found by faults71: on keysight70's ``dmu_a`` (seed 7041) with the spindle thermocouple unplugged
from the test run's middle row (``+9.90000000E+37`` listed in ``data.missing_values``), the
adaptive compensator excludes ``T_105_Spindle`` and feeds the model its POD reconstruction from
the other sensors, none of which follows the spindle: test RMSE E_Z 4.84 -> 66.06 µm (mlr),
4.28 -> 36.44 (lagbank).

Cases (the fault from the test campaign's middle row ``h``; RMSE from ``h`` to the end of the
measured minus the adaptive stream's error, over rows and targets, µm): ``dmu_a``
``unplugged_listed`` (the spindle) and ``rig_a`` ``unplugged`` (catman70, ``T Lager vorn``
emptied), mlr and lagbank; bench_deploy_faults' ``nan_end``, ``stuck`` and ``nan_16`` on
``T_motor2`` of K06, mlr, arx and lagbank.  Healthy: the same test campaigns unfaulted (and
bench_deploy_faults' K03 and K09).

Candidate (the only one; :mod:`thermocomp.apps.deploy.fallback`): ``priced`` -- at deploy build,
for each monitored sensor the model reads, the same family refitted on the train campaigns with
that sensor out of every target's inputs (the fallback); it is kept where its training RMSE is
below the model's own with the sensor replaced by its POD reconstruction from the others (the
monitor's operator).  The fallback streams beside the model from the campaign's start; while a
sensor with a fallback is excluded, the correction (before the guard) is its fallback's.  Fitted
at deploy build for every family (lagbank too: its CPU stated below).

Rule and bar (written and committed before any candidate was scored)
--------------------------------------------------------------------
``priced`` is merged as the adaptive compensator's default when all hold, else the src change is
reverted (REFUSED):

1. the unplugged cases (``dmu_a`` mlr and lagbank; ``rig_a`` mlr and lagbank): RMSE after the
   fault at least 50 % below today's on ``dmu_a`` (both families); ``rig_a`` not worse by > 5 %;
2. no injected-fault case of bench_deploy_faults (``nan_end``, ``stuck``, ``nan_16`` x mlr, arx,
   lagbank) worse than today by more than 5 %;
3. every healthy stream byte-unchanged (max |priced - today| == 0 on every row), so replay = run
   where it was;
4. the deploy build's extra CPU (the fallbacks' fits and pricing) stated per family.

Measured (2026-12-02, ``priced``; 27.8 s user + 0.5 s sys of CPU, fits made)
---------------------------------------------------------------------------
RMSE after the fault (µm; exclusions), today -> priced:

=========================  =========  ==================  ======================
case                       family     today -> priced     change
=========================  =========  ==================  ======================
dmu_a unplugged_listed     mlr        93.562 -> 7.574     -91.9 %
dmu_a unplugged_listed     lagbank    52.116 -> 6.426     -87.7 %
rig_a unplugged            mlr        11.415 -> 2.943     -74.2 %
rig_a unplugged            lagbank    11.282 -> 0.755     -93.3 %
nan_end / nan_16 T_motor2  mlr        6.318 -> 7.686      +21.7 %
stuck T_motor2             mlr        8.730 -> 9.439      +8.1 %
nan_end / nan_16 T_motor2  arx        6.822 -> 9.849      +44.4 %
stuck T_motor2             arx        7.620 -> 9.198      +20.7 %
nan_end / nan_16 T_motor2  lagbank    6.559 -> 8.386      +27.9 %
stuck T_motor2             lagbank    8.288 -> 8.072      -2.6 %
=========================  =========  ==================  ======================

Healthy streams (K03, K06, K09 x 3 families; dmu_a, rig_a x 2): byte-unchanged.  Build: +0.5
(mlr), +0.8 (arx, lagbank) s CPU on the 6 train campaigns of 10 sensors; dmu_a +0.8 / +3.2,
rig_a +0.9 / +2.1.  The in-sample price kept a fallback for nearly every sensor (all 10 for mlr
on the simulated record, where ``T_motor2``'s reconstruction from ``T_motor1`` is the better
stand-in).  Bar 2 fails (up to +44 %): ``priced`` REFUSED.

Second rule and bar (written and committed after ``priced`` was scored, before these two were)
------------------------------------------------------------------------------------------------
The in-sample price favours the fallback, fitted on the rows it is priced on.  Two candidates,
scored with the same bar 1-4 above, the first of them in this order that passes merged:

* ``heldout``: each train campaign held out in turn; the fallback fitted on the others against
  the model refitted on the others (the same inputs) fed the sensor's reconstruction by a POD
  fitted on the others (the monitor's settings); a fallback kept where its summed squared error
  over the held-out campaigns is lower (none with fewer than 3 train campaigns);
* ``unobservable``: a fallback only for a sensor no other predicts (leverage in the monitor's
  POD at least ``max_leverage``, the sensor the monitor judges by its own detectors only and
  holds at its last good reading when out).

Measured (2026-12-02; ``heldout`` 63.7 s user + 0.8 s sys, ``unobservable`` 15.4 + 0.5, fits
made).  RMSE after the fault, today -> candidate (µm):

========================================  =====================  =====================
case                                      heldout                unobservable
========================================  =====================  =====================
dmu_a mlr / lagbank                       -91.9 % / -87.7 %      -91.9 % / -87.7 %
rig_a mlr / lagbank                       -74.2 % / -93.3 %      -74.2 % / -93.3 %
nan_end, nan_16 T_motor2 mlr/arx/lagbank  +0.0 / +44.4 / +27.9   +0.0 / +0.0 / +0.0
stuck T_motor2 mlr/arx/lagbank            +0.0 / +20.7 / -2.6    +0.0 / +0.0 / +0.0
healthy streams                           byte-unchanged         byte-unchanged
build CPU (sim mlr/arx/lagbank; dmu_a,    +2.3 / 4.7 / 5.4;      +0.0 / 0.0 / 0.1;
rig_a mlr/lagbank)                        3.5/19.7, 3.5/8.6 s    0.1/0.9, 0.1/0.4 s
========================================  =====================  =====================

``heldout`` REFUSED (bar 2: arx +44.4 %).  ``unobservable`` passes bars 1-4: it keeps fallbacks
for ``T_amb`` only on the simulated record (``T_motor2``, predicted by ``T_motor1``, is
reconstructed as before), for ``T_101_Air``, ``T_104_Headstock`` and ``T_105_Spindle`` on
``dmu_a`` (the spindle was held at its last good reading, not reconstructed: no other sensor
predicts it) and ``T_Lager_vorn``, ``T_amb`` on ``rig_a``.  Merged (``monitor.fallbacks``, default
``unobservable``).  The whole ``bench_deploy_faults.py`` with it: only ``T_amb``'s lines move
(every other line identical): ``amb_offset5`` largest change from healthy mlr 1.8 -> 1.0, arx
1.1 -> 0.8, lagbank 1.1 -> 1.2 µm; RMS from the step on (adaptive), real +5 K 10.77 / 10.57 /
7.20 -> 10.29 / 10.19 / 6.70, +2 K 6.30 / 6.58 / 3.92 -> 5.87 / 6.43 / 3.60, +5 K/30 min 7.90 /
8.37 / 5.57 -> 6.21 / 7.39 / 3.93, offset +5 K and +2 K 4.70 / 5.78 / 3.99 -> 4.37 / 5.81 / 3.72.

Its refinement (written after the project's tests ran on it, before it was scored again): four
tests failed, two on what the fallback did.  A logger row with no temperature at all
(``tests/shell/test_hostile_stream.py``: the correction held; ``test_monitor_lab57.py``: one empty
row cost 1.35 against 1.30 µm, the bar 1.02x): every sensor out for a dropout, the unobservable
ones' fallbacks took over.  So a fallback gives the correction only while the monitor has enough
sensors in to rebuild the field, and not for a sensor out for a dropout that reads again (its
held reading, at most a window old, is the better stand-in while it waits out its window).  The
bar is the same; scored again below.

Scored again (2026-12-02, 15.6 s user + 0.6 s sys): every line as the unrefined ``unobservable``
above (dmu_a 93.562 -> 7.574 mlr, 52.116 -> 6.426 lagbank; rig_a 11.415 -> 2.943, 11.282 ->
0.755; the nine ``T_motor2`` cases +0.0 %; every healthy stream byte-unchanged; build +0.1 s mlr,
+0.2 s lagbank on dmu_a and rig_a), and ``bench_deploy_faults.py`` prints what it printed
unrefined.  Passes: merged.  ``tests/apps/test_monitor_blame44.py``'s drifting ``T_table`` (no
other predicts it) now reads its fallback: E_Z adaptive 19.61 -> 15.29 µm (fixed 20.57), the
switch rate-limited for one sample (two guard events the test now allows).  The exported code
(C, ST, json) has no sensor monitor and so no fallback.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
import pandas as pd

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]

from _cli import run_commands  # noqa: E402

LAB = {"dmu_a": ("unplugged_listed", ["data.missing_values=['+9.90000000E+37']"]),
       "rig_a": ("unplugged", [])}
SIM_FAULTS = ("nan_end", "stuck", "nan_16")


def _cpu() -> float:
    import resource
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


CANDIDATE = ["unobservable"]


def _residuals(comp, campaigns) -> np.ndarray:
    """Measured minus ``comp``'s simulation on ``campaigns`` (rows x targets)."""
    predicted = comp.predict(campaigns, mode="simulation")
    measured = comp.measured(campaigns, predicted=predicted)
    return np.concatenate([(measured[c][comp.targets_] - predicted[c][comp.targets_])
                           .to_numpy(float) for c in campaigns])


def _reconstructed(monitor, campaigns, sensor: str, pod=None) -> dict:
    """``campaigns`` with ``sensor`` replaced by its reconstruction from the others by ``pod``
    (the monitor's by default), each campaign referenced to its first sample."""
    names = list(monitor.names)
    j = names.index(sensor)
    active = np.ones(len(names), dtype=bool)
    active[j] = False
    M, _ = (pod or monitor.pod).operator(active)
    out = {}
    for cid, df in campaigns.items():
        T = df[names].to_numpy(float)
        out[cid] = df.assign(**{sensor: T[0, j] + (T - T[0])[:, active] @ M[j]})
    return out


def _without(comp, sensor) -> dict:
    return {t: [c for c in comp.selected_[t] if c != sensor] for t in comp.targets_}


def priced_fallbacks(streaming, monitor, campaigns) -> dict:
    """Refused candidate ``priced`` (module doc): in-sample training RMSE."""
    from thermocomp.apps.deploy.fallback import without_sensor

    comp, out = streaming.compensator, {}
    for sensor in monitor.names:
        fallback = without_sensor(streaming, campaigns, sensor)
        if fallback is None:
            continue
        own = np.sqrt(np.nanmean(_residuals(fallback.compensator, campaigns) ** 2))
        if own < np.sqrt(np.nanmean(_residuals(comp, _reconstructed(monitor, campaigns, sensor)) ** 2)):
            out[sensor] = fallback
    return out


def heldout_fallbacks(streaming, monitor, campaigns) -> dict:
    """Refused candidate ``heldout`` (module doc): each train campaign held out in turn."""
    from sklearn.base import clone

    from thermocomp.apps.deploy.fallback import without_sensor

    comp, ids, names = streaming.compensator, list(campaigns), list(monitor.names)
    sensors = [s for s in names if _without(comp, s) != _without(comp, None)
               and all(_without(comp, s).values())]
    if len(ids) < 3 or not sensors:
        return {}
    cost = {s: np.zeros(2) for s in sensors}        # squared error: reconstruction, fallback
    for held in ids:
        rest = {c: campaigns[c] for c in ids if c != held}
        one = {held: campaigns[held]}
        model = clone(comp).set_params(selection=_without(comp, None)).fit(rest)
        raw = [df[names].to_numpy(float) for df in rest.values()]
        pod = clone(monitor.pod).fit(np.vstack([a - a[0] for a in raw]), groups=np.concatenate(
            [np.full(len(a), k) for k, a in enumerate(raw)]))
        for s in sensors:
            fallback = clone(comp).set_params(selection=_without(comp, s)).fit(rest)
            cost[s] += [np.nansum(_residuals(model, _reconstructed(monitor, one, s, pod)) ** 2),
                        np.nansum(_residuals(fallback, one) ** 2)]
    out = {}
    for s in sensors:
        if cost[s][1] < cost[s][0]:
            fallback = without_sensor(streaming, campaigns, s)
            if fallback is not None:
                out[s] = fallback
    return out


def unobservable_fallbacks(streaming, monitor, campaigns) -> dict:
    """The merged candidate (:func:`thermocomp.apps.deploy.fallback.sensor_fallbacks`)."""
    from thermocomp.apps.deploy.fallback import sensor_fallbacks
    return sensor_fallbacks(streaming, monitor, campaigns)


def _deployables(cfg, ds, train_ids, model: str):
    """(today's adaptive deployable, no fallback; the same with the candidate's fallbacks; their
    build CPU s)."""
    from thermocomp.shell.builders import deployable_model

    chosen = globals()[f"{CANDIDATE[0]}_fallbacks"]

    today = deployable_model(cfg, ds, train_ids, model, "replay.model")[0]
    today.fallbacks_ = {}                   # today's compensator: none
    today.reset()
    priced = deployable_model(cfg, ds, train_ids, model, "replay.model")[0]
    train = {c: ds.campaigns[c] for c in train_ids}
    start = _cpu()
    priced.fallbacks_ = chosen(priced.streaming, priced.monitor, train)
    cpu = _cpu() - start
    priced.reset()
    return today, priced, cpu


def _after(deployed, df: pd.DataFrame, cid: str, h: int, errors: pd.DataFrame):
    """(RMSE from row ``h`` on, the stream's corrections, exclusions)."""
    from thermocomp.apps.deploy.report import stream_rows

    s = stream_rows(deployed, df, cid)
    r = errors[deployed.targets_].to_numpy(float)[h:] - s.y[h:]
    return (float(np.sqrt(np.nanmean(np.nansum(r ** 2, axis=1)))), s.y,
            sum(e.get("to") == "excluded" for e in s.events))


def _measured(deployed, df: pd.DataFrame, cid: str) -> pd.DataFrame:
    comp = deployed.compensator
    return comp.measured({cid: df})[cid]


def _line(case, family, today, priced, cpu, falls, h_today, h_priced) -> str:
    same = "0" if np.array_equal(h_today, h_priced) else f"{np.max(np.abs(h_today - h_priced)):.3g}"
    change = 100.0 * (priced[0] / today[0] - 1.0)
    return (f"{case:24s} {family:8s} today {today[0]:8.3f} ({today[2]})  {CANDIDATE[0]} {priced[0]:8.3f} "
            f"({priced[2]})  {change:+7.1f} %  healthy |diff| {same}  fallbacks {falls} "
            f"build +{cpu:.1f} s CPU")


def lab(faults_root: Path, families=("mlr", "lagbank"), model_of=None) -> None:
    """``dmu_a`` and ``rig_a``'s unplugged sensor, mlr and lagbank (``families``; ``model_of(name,
    family)``: the model.pkl, by default faults71's)."""
    import lab_matrix
    from hydra import compose, initialize_config_dir

    from thermocomp.shell.source import read_streamed

    for name, (fault, hint) in LAB.items():
        folder = faults_root / "faulted" / f"{name}-{fault}"
        with initialize_config_dir(config_dir=str(REPO / "conf"), version_base="1.3"):
            cfg = compose(config_name="config", overrides=[
                *lab_matrix.data_args(faults_root, name), f"data.path={folder}", *hint,
                "track=false", "monitor.adaptive=true"])
            healthy_cfg = compose(config_name="config", overrides=[
                *lab_matrix.data_args(faults_root, name), *hint, "track=false"])
        ds, train_ids, test_ids, _ = read_streamed(cfg)
        hds = read_streamed(healthy_cfg)[0]
        cid = test_ids[-1]
        df, healthy = ds.campaigns[cid], hds.campaigns[cid]
        for family in families:
            model = str(model_of(name, family) if model_of else
                        faults_root / "out" / f"{name}-{family}-plain" / "model.pkl")
            today, priced, cpu = _deployables(cfg, ds, train_ids, model)
            errors = _measured(today, healthy, cid)
            cols = [c for c in today.columns_ if c.startswith("T_")]
            bad = ~np.isfinite(df[cols].to_numpy(float)).all(axis=1)
            h = int(np.argmax(bad)) if bad.any() else len(df) // 2
            a, b = _after(today, df, cid, h, errors), _after(priced, df, cid, h, errors)
            ha, hb = _after(today, healthy, cid, h, errors), _after(priced, healthy, cid, h, errors)
            print(_line(f"{name} {fault}", family, a, b, cpu, sorted(priced.fallbacks_), ha[1],
                        hb[1]), flush=True)


def simulated(root: Path, families=None) -> None:
    """bench_deploy_faults' nan_end, stuck, nan_16 on K06's T_motor2, mlr, arx, lagbank
    (``families``), each fitted into ``root / family`` where it is not there yet."""
    import bench_deploy_faults as bdf

    from thermocomp.shell.cli import main
    from thermocomp.shell.source import read_streamed

    data = root / "ys"
    if not data.exists():
        main(["simulate", "sim=yearround_spindle", "seed=5353", "sim.generator.n_campaigns=9",
              "sim.generator.duration_h=[3.0,5.0]", f"data.path={data}", f"out={root / 'sim'}"])
    cfg = bdf._cfg(data, "monitor.adaptive=true")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    raw = ds.campaigns[bdf.CAMPAIGN]
    h = len(raw) // 2
    for family in families or bdf.FAMILIES:
        model = root / family / "model.pkl"
        if not model.exists():
            main(["run", f"data.path={data}", f"model={family}", "track=false", "plots=none",
                  f"out={root / family}"])
        today, priced, cpu = _deployables(cfg, ds, train_ids, str(model))
        for cid in test_ids:
            df = ds.campaigns[cid]
            errors = _measured(today, df, cid)
            ha, hb = _after(today, df, cid, 0, errors), _after(priced, df, cid, 0, errors)
            print(_line(f"healthy {cid}", family, ha, hb, cpu, sorted(priced.fallbacks_), ha[1],
                        hb[1]), flush=True)
        errors = _measured(today, raw, bdf.CAMPAIGN)
        faults = bdf.faults(raw.reset_index(drop=True))
        for fault in SIM_FAULTS:
            df = faults[fault]
            a, b = _after(today, df, bdf.CAMPAIGN, h, errors), _after(priced, df, bdf.CAMPAIGN, h, errors)
            print(_line(f"{fault} {bdf.SENSOR}", family, a, b, cpu, sorted(priced.fallbacks_),
                        a[1][:0], b[1][:0]), flush=True)


def score(root: str = "/tmp/sub71-root", faults_root: str = "/tmp/faults71-root",
          candidate: str = "unobservable") -> None:
    CANDIDATE[0] = candidate
    start = time.process_time()
    simulated(Path(root).resolve())
    lab(Path(faults_root).resolve())
    print(f"CPU {time.process_time() - start:.1f} s")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"score": score}, argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
