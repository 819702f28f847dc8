"""Can the machine's states bound the drift of a sensor no other temperature predicts? (mon91b,
issue 34; audit89's drift row: 0 of 6 detected)

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_audit89.py healthy ROOT RECORDS  # first: simulate, run, monitor, healthy
    python benchmarks/bench_mon91b.py rooms ROOT SEEDS       # or: bench_mon88's records, healthy
    python benchmarks/bench_mon91b.py trace ROOT RECORDS     # each blind sensor's band, offline
    python benchmarks/bench_mon91b.py served ROOT RECORDS    # the served monitor fed its estimate

``RECORDS``: bench_audit89's (``9316-9325``, ``fl``), or ``all`` (every record of ``ROOT`` with a
monitor report).  ``rooms``: bench_mon88's ``FRESH`` records (9196-9200 long records, R1b
continuing R1a, ``data.reference=none``; 9201-9205 climate rooms), drawn healthy (nothing
planted), ``run model=mlr`` -> ``monitor`` into ``ROOT`` (kept).

``trace``: for every sensor the healthy monitor calls not observable (``observable: false`` in
monitor.json: the POD's leverage above ``max_leverage``, "no other sensor predicts it"; the one
audit89 faults, the costliest, marked ``*``), a prediction of its change since its test part's
first row, three variants (:data:`VARIANTS`):

* A (the brief's): the machine's STATE columns (the contract's ``S_*``) and, where the record has
  one and it is not the sensor itself, the ambient ``T_amb``: each one's first-order low-pass
  response at the fixed time constants :data:`TAUS` (exact discretisation; a state's filter
  starts settled at 0, the machine cold at a campaign's start; the ambient's at its first
  reading), the ambient's reading too; B: A's and every other temperature's reading; C: every
  other temperature's reading only.  Each referenced to the part's first row, as the sensor is.
  No time constant, alpha or threshold is chosen on a test part.
* fit: ``StandardScaler`` + ``RidgeCV`` (alphas :data:`ALPHAS`) on the train campaigns; its
  cross-validated residual over campaigns (one train campaign out where there are >= 3, else
  :data:`BLOCKS` contiguous blocks of the train rows: column, swiss, long records have ONE).
* band: the monitor's own rule for a warning band (``from_training``): ``max(warning_c,
  spread_factor x spread)``, 0.4 degC and 3, ``spread`` the 99.5th percentile of the windowed
  (``window`` 10) |CV residual|; crossed where ``confirm`` (2) windowed residuals in a row are
  beyond it.  ``probe``: the same with factor 1 (not a rule: shown for what a band of the bare CV
  spread would do).
* scored on each test part (a test campaign; fl: its last 10 %; a continuing one read after its
  predecessor): healthy, the largest windowed |residual| and whether it crosses the band
  ("false"); drifted (bench_audit89's ``drift``, +0.5 degC/h from the part's middle row), the
  first crossing after the fault's row ("found" in every test part, the median delay, h).

``served``: the costliest blind sensor, the ``monitor`` stage (the healthy run's model.pkl) on
copies of the record whose test files carry: the truth; the drift; the drift replaced by a
variant's estimate from its band's first crossing on (``drift->estimate``; what a rule that
substitutes the estimate would feed the model at best); the truth replaced by the estimate from
the middle row on (``truth->estimate``: the estimate's own cost).  RMSE fixed / adaptive (mean over
targets, um) and the monitor's events naming the sensor.

What separates (written before the trace was run on any record, 8c45a961): a sensor is bounded by
its states where (a) the healthy test parts cross the band nowhere and (b) the drifted copies
cross it in every test campaign.  The rule (a band from a state-driven prediction where its CV
error is tight enough, else unbounded as today) is worth building only where (a) and (b) hold on
most of the seen records whose faulted sensor no other predicts (col9316, swiss9317, yr9318,
col9322, swiss9323, yr9324); else TRACED with the rows below, fresh seeds 9396-9405 left unspent.
(Variants B / C, ``probe``, ``served`` and ``rooms`` were added after the first trace of A, to
see where a bound could come from; none of them feeds a verdict.)

Bar for a rule (the brief's, written before any fresh score; unused: no rule was built): fresh
seeds 9396-9405 (bench_audit89's generators, a drift injected into a sensor no other predicts, and
the same records healthy): drift detected on >= 5 of 10 where main detects 0, no row's error more
than 2 % worse than main; healthy: no new events on any of 10 + bench_mon88's seen healthy rows +
datasets/fl_thermal; monitor / export / replay tests + tests/test_readme.py pass.

Traced (2026-12-05, src = main 277a181d; seen records only: audit89's 9316-9325 + fl, bench_mon88's
9196-9205 drawn healthy; bench_audit89 ``healthy`` reproduces audit89's table to the digit,
col9316 9.4267, swiss9317 1.6395, ...)
------
The costliest blind sensor of audit89's six records (healthy max: the largest windowed |residual|
on the healthy test parts, degC; drift: its size at the part's end; found: in every test part
under the band, delay h):

| record | sensor | drift | A: CV R2 / band / healthy max / found | B: CV R2 / band / healthy max / found |
|---|---|---|---|---|
| col9316 | T_front3 | 10.0 | -4.83 / 29.4 / 6.38 / no | 0.73 / 7.57 / 5.74 / yes, 13.9 h |
| swiss9317 | T_nc_spindle_motor | 6.0 | 0.97 / 10.57 / 2.17 / no | 1.00 / 5.36 / 0.48 / yes, 11.4 h |
| yr9318 | T_amb | 1.96 | 0.34 / 9.16 / 1.45 / 0 of 8 | 0.67 / 4.85 / 1.03 / 0 of 8 |
| col9322 | T_front3 | 10.0 | -8.48 / 44.9 / 4.79 / no | 0.51 / 7.95 / 4.84 / yes, 12.8 h |
| swiss9323 | T_nc_spindle_motor | 6.0 | 0.97 / 9.43 / 2.72 / no | 0.99 / 10.19 / 0.82 / no |
| yr9324 | T_amb | 1.92 | 0.42 / 5.99 / 1.92 / 0 of 8 | 0.91 / 2.22 / 2.02 / 1 of 8 |

- A (the states and ambient) separates on NONE of the six: the column has one state,
  ``S_pos_Z``, that does not drive ``T_front3`` (its sources are no state column); yearround's
  blind sensor is the air itself, which no state drives; swiss's spindle-motor sensor is
  predicted (CV R2 0.97) but its blocked CV spread over the one 80 h calibration run (3.1-3.5 degC
  windowed) makes a 9.4-10.6 degC band the +6 degC drift never reaches.  Over the 10 blind sensors
  of these records: 0 false crossings, 0 drifts found; fl's three (T_t4, T_t5, T_t16): 0 / 0 (the
  drift reaches 1.16 degC in fl's 4.6 h test part).
- bench_mon88's records (rooms; 41 blind sensor-records, 10 costliest): A found the drift in
  every test part on 13 of 41 (3 of 10 costliest: lr9196 ``T_table`` 3.5 h, lr9197 ``T_table``
  2.0 h, lr9198 ``T_spindle_front`` 7.0 h), 0 false crossings; no climate room (3-4 h runs: the
  drift reaches <= 1 degC) under any variant.
- B (a ridge over the states' responses AND the other temperatures) is what bounds: "no other
  predicts" is the POD's leverage over its r modes, not what a regression on the others can do
  (col9316 ``T_front3``: POD leverage > 0.9; a ridge on the other temperatures alone CV R2 0.83,
  with the states 0.73).  0 false crossings on all 54 blind
  sensor-records (audit89 10, fl 3, rooms 41); found in every test part: audit89 3 of 10 (3 of 6
  costliest, late: 11-14 h, 5.7-7 degC into the drift), fl 0 of 3, rooms 29 of 41 (5 of 10
  costliest).  C (the other temperatures alone) crosses on healthy parts (col9316 / col9322
  ``T_front3``, col9322 ``T_amb``: the column's never-trained source Q3 moves the others).
- Served (``served``, costliest sensor; fixed RMSE, adaptive in brackets where it differs; main's
  monitor names the drifting sensor in no event on any of the six, as audit89 found):

| record | truth | drift | B drift->estimate (rule band) | B truth->estimate | A truth->estimate |
|---|---|---|---|---|---|
| col9316 | 9.427 | 13.626 (12.974) | 11.144 (13.466) | 11.079 (11.061) | 14.384 |
| swiss9317 | 1.640 | 1.892 | 1.872 (1.888) | 1.651 | 1.730 |
| yr9318 | 2.799 | 2.952 | 2.952 (not found) | 2.802 | 2.990 |
| col9322 | 8.555 (8.546) | 13.752 (13.302) | 10.482 (12.622) | 10.957 (10.947) | 10.369 (14.271) |
| swiss9323 | 1.418 | 1.496 | 1.496 (not found) | 1.425 | 1.424 |
| yr9324 | 3.105 | 3.765 | 3.646 (3.645) | 2.781 (2.911) | 2.829 (2.876) |

  Fed for a drifting sensor once found, B's estimate cuts the column's cost (13.63 -> 11.14,
  13.75 -> 10.48 um fixed), but in place of the HEALTHY sensor it costs the column +17 % / +28 %
  (the Q3 regime: a false alarm would be paid); swiss +0.7 %.  Written into the data the estimate
  steps at the crossing row and today's monitor reads a jump (adaptive 13.47 > the drift's
  12.97): a rule must substitute inside the monitor, where that step is no reading.
- Served on bench_mon88's records (costliest blind sensor; main's monitor names the drifting sensor
  in no event on any of the ten, lr9197's two events being a jump at 25020 s the truth has too):

| record | sensor | truth | drift | A drift->estimate | B drift->estimate | B truth->estimate |
|---|---|---|---|---|---|---|
| lr9196 | T_table | 1.045 | 9.457 | 2.991 (6.223) | 1.821 (4.531) | 0.763 |
| lr9197 | T_table | 1.724 (1.763) | 7.190 (6.987) | 1.873 (2.233) | 1.756 (1.436) | 1.792 (1.829) |
| lr9198 | T_spindle_front | 1.851 | 6.354 | 6.075 (6.112) | 2.198 (4.152) | 1.010 |
| lr9199 | T_table | 0.993 (0.930) | 8.713 (8.809) | not found | 3.064 (6.256) | 0.642 (0.605) |
| lr9200 | T_spindle_front | 1.293 | 6.228 | not found | 2.187 (4.187) | 0.647 |

  cr9201-9205 (``T_nc_spindle_motor``): the drift (<= 1 degC) costs -9 % .. +10 % (1.246 -> 1.292,
  2.216 -> 2.016, 2.914 -> 3.059, 2.333 -> 2.331, 1.299 -> 1.430) and no variant finds it; B's
  estimate in place of the healthy sensor 1.224 / 2.182 / 2.827 / 2.319 / 1.358.
  On the long records an undetected +3.6 degC drift multiplies the error 4-9 x and B's estimate
  from its crossing (2.4-4.1 h in) takes most of it back (fixed 1.76-3.06 um); in place of the
  HEALTHY sensor B's estimate beats the sensor itself on 4 of 5 long records (lr9198 1.851 ->
  1.010, lr9200 1.293 -> 0.647) and 4 of 5 rooms (cr9205 +4.6 %): stop 89's question (the field's
  estimate a better model input than the reading) again.  Adaptive > fixed in every substituted
  cell: the estimate written into the data is read as a jump.

Verdict: TRACED (no src change).  (1) The brief's rule (A, the states and ambient) separates on
none of audit89's six records (criterion above, written before the trace).  (2) The brief's bar
cannot be met on its seeds by any rule: 9396-9405 draw (``KINDS[(s - 9316) % 6]``) yearround,
lmw, fleet, lmv, column, swiss, yearround, lmw, fleet, lmv, and on every seen draw of lmw / fleet /
lmv (9319-9321, 9325) the monitor judges all sensors observable: at most 4 of the 10 records
carry a blind sensor to drift, the bar asks >= 5.  (3) B, which does bound, needs the states and
time inside ``SensorMonitor`` (it is fitted and streamed on temperatures only), the estimate in
place of ``_last_good`` for an excluded blind sensor, the warm snapshot and the C behind a key:
not this session's size.  Fresh seeds 9396-9405 unspent.  CPU: ``trace`` 1-5 s a set, ``served``
56 s (audit89's six), 77 s (bench_mon88's ten); ``healthy`` 158 s as audit89, ``rooms`` 17 s.
"""

from __future__ import annotations

import json
import os
import shutil
import sys
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.signal import lfilter
from sklearn.linear_model import RidgeCV
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands, seed_list  # noqa: E402
from bench_audit89 import (  # noqa: E402
    FL,
    FL_TEST,
    QUIET,
    _costliest,
    _mean_rmse,
    _named,
    _read,
    _traced,
    _write,
    faulted,
    label_of,
    records_of,
)
from bench_deploy87 import stage  # noqa: E402

TAUS = (900.0, 3600.0, 14400.0)   # s: a quarter hour to four hours, a machine's thermal range
ALPHAS = np.logspace(-3, 3, 13)
BLOCKS = 5
WARNING_C, SPREAD_FACTOR, WINDOW, CONFIRM = 0.4, 3.0, 10, 2   # conf/monitor/default.yaml's


def _fl_frame(path: Path) -> pd.DataFrame:
    """fl_thermal under the contract's names (data=fl_thermal's roles): time, S_spindle, T_t*."""
    raw = pd.read_csv(path)
    names = {raw.columns[0]: "time"}
    for c in raw.columns[1:]:
        stem = c.split("(")[0]
        names[c] = "S_" + stem if stem.startswith("spindle") else ("T_" + stem if stem.startswith("t")
                                                                    else "E_" + stem)
    return raw.rename(columns=names)


def campaigns(root: Path, label: str) -> tuple[list[pd.DataFrame], list[tuple[pd.DataFrame, int]]]:
    """(train frames, [(test frame, first row of its test part)]): a test campaign that continues
    another (fl's test part, a manifest's ``continues``) is read after it in one frame (the
    filters run on through it)."""
    data = root / "data" / label
    if label == "fl_thermal":
        frame = _fl_frame(data / FL.name)
        cut = len(frame) - int(round(FL_TEST * len(frame)))
        return [frame.iloc[:cut]], [(frame, cut)]
    manifest = pd.read_csv(data / "campaigns.csv")
    frames = {c: _read(data / f) for c, f in zip(manifest["campaign"], manifest["file"])}
    after = dict(zip(manifest["campaign"], manifest.get("continues", pd.Series(index=manifest.index))))
    train = [frames[c] for c, s in zip(manifest["campaign"], manifest["split"]) if s != "test"]
    test = []
    for c in manifest.loc[manifest["split"] == "test", "campaign"]:
        before = after[c] if isinstance(after[c], str) else None
        test.append((frames[c], 0) if before is None else
                    (pd.concat([frames[before], frames[c]], ignore_index=True), len(frames[before])))
    return train, test


def low_pass(x: np.ndarray, dt: float, tau: float, start: float) -> np.ndarray:
    """First-order response to ``x`` (exact for a zero-order hold) from a settled ``start``."""
    a = np.exp(-dt / tau)
    y, _ = lfilter([1 - a], [1, -a], x, zi=[a * start])
    return y


VARIANTS = {"A": "states (+ ambient)", "B": "states (+ ambient) + other temperatures",
            "C": "other temperatures"}


def features(frame: pd.DataFrame, sensor: str, first: int = 0, variant: str = "A") -> np.ndarray:
    """Variant A: the states' (and ambient's) low-pass responses at :data:`TAUS` (and the ambient's
    reading); B: those and every other temperature's reading; C: every other temperature's reading
    (the ambient's too); each referenced at row ``first``."""
    t = frame["time"].to_numpy(float)
    dt = float(np.median(np.diff(t)))
    drivers = [c for c in frame.columns if c.startswith("S_")] if variant in "AB" else []
    if "T_amb" in frame.columns and sensor != "T_amb" and variant in "AB":
        drivers.append("T_amb")
    cols = []
    for c in drivers:
        x = frame[c].to_numpy(float)
        if c == "T_amb":
            cols.append(x)
        # a machine starts cold (its states settled at 0), the air settled at its first reading
        rest = x[0] if c == "T_amb" else 0.0
        cols += [low_pass(x, dt, tau, rest) for tau in TAUS]
    if variant in "BC":
        cols += [frame[c].to_numpy(float) for c in frame.columns
                 if c.startswith("T_") and c != sensor and (variant == "C" or c != "T_amb")]
    F = np.column_stack(cols) if cols else np.zeros((len(frame), 0))
    return (F - F[first])[first:]


def target(frame: pd.DataFrame, sensor: str, first: int = 0) -> np.ndarray:
    y = frame[sensor].to_numpy(float)
    return (y - y[first])[first:]


def windowed(r: np.ndarray) -> np.ndarray:
    """Trailing mean over :data:`WINDOW` samples (fewer at the start), as the monitor's."""
    c = np.cumsum(np.insert(r, 0, 0.0))
    n = np.minimum(np.arange(1, len(r) + 1), WINDOW)
    return (c[1:] - c[np.arange(1, len(r) + 1) - n]) / n


def first_crossing(w: np.ndarray, band: float, start: int = 0) -> int | None:
    """First row >= ``start`` ending :data:`CONFIRM` windowed residuals in a row beyond ``band``."""
    beyond = np.abs(w) > band
    run = np.convolve(beyond, np.ones(CONFIRM, int), "full")[:len(w)] >= CONFIRM
    hits = np.flatnonzero(run[start:])
    return int(hits[0]) + start if hits.size else None


def cv_residual(F: list[np.ndarray], Y: list[np.ndarray], blocks: int = BLOCKS) -> np.ndarray:
    """Out-of-fold residual over the train rows (campaign order): one train campaign out where
    there are >= 3, else ``blocks`` contiguous blocks (bench_monb92b varies the count)."""
    X, y = np.vstack(F), np.concatenate(Y)
    if len(F) >= 3:
        groups = np.concatenate([np.full(len(f), k) for k, f in enumerate(F)])
    else:
        groups = np.minimum(np.arange(len(y)) * blocks // len(y), blocks - 1)
    out = np.empty_like(y)
    for g in np.unique(groups):
        held = groups == g
        out[held] = y[held] - _fit(X[~held], y[~held]).predict(X[held])
    return out


def _fit(X: np.ndarray, y: np.ndarray):
    return make_pipeline(StandardScaler(), RidgeCV(alphas=ALPHAS)).fit(X, y)


def trace_sensor(train, test, sensor: str, variant: str = "A") -> dict:
    """One sensor's band from ``variant``'s prediction (:data:`VARIANTS`) on the train campaigns and
    its test parts, healthy and drifted (module doc)."""
    F = [features(f, sensor, variant=variant) for f in train]
    Y = [target(f, sensor) for f in train]
    if F[0].shape[1] == 0:
        return {"sensor": sensor, "variant": variant, "note": "no driver"}
    r = cv_residual(F, Y)
    starts = np.cumsum([0] + [len(y) for y in Y])
    w = np.concatenate([windowed(r[a:b]) for a, b in zip(starts[:-1], starts[1:])])
    spread = float(np.quantile(np.abs(w), 0.995))
    bands = {"rule": max(WARNING_C, SPREAD_FACTOR * spread), "probe": max(WARNING_C, spread)}
    y_all = np.concatenate(Y)
    model = _fit(np.vstack(F), y_all)
    row = {"sensor": sensor, "variant": variant, "n_train": len(train),
           "cv_rmse": float(np.sqrt(np.mean(r ** 2))),
           "cv_r2": float(1 - np.sum(r ** 2) / np.sum((y_all - y_all.mean()) ** 2)),
           "spread": spread, **{f"band_{k}": v for k, v in bands.items()}, "parts": []}
    for frame, first in test:
        Xt, yt = features(frame, sensor, first, variant), target(frame, sensor, first)
        fit = model.predict(Xt)
        wt = windowed(yt - fit)
        t = frame["time"].to_numpy(float)
        drifted = faulted(frame[sensor].to_numpy(float), t, first, "drift")[0]
        mid = first + (len(frame) - first) // 2
        wd = windowed(drifted[first:] - drifted[first] - fit)
        part = {"healthy_max": float(np.max(np.abs(wt))), "mid": mid, "drifted": drifted,
                "drift_end": float(drifted[-1] - frame[sensor].iloc[-1]),
                # the sensor as the variant estimates it in the test part (its reading before)
                "estimate": np.concatenate([frame[sensor].to_numpy(float)[:first],
                                            frame[sensor].iloc[first] + fit])}
        for k, band in bands.items():
            hit = first_crossing(wd, band, start=mid - first)
            part[f"false_{k}"] = first_crossing(wt, band) is not None
            part[f"delay_{k}"] = None if hit is None else float((t[first + hit] - t[mid]) / 3600.0)
            part[f"row_{k}"] = None if hit is None else first + hit
        row["parts"].append(part)
    return row


def labels_of(folder: Path, records: str) -> list[str]:
    """bench_audit89's records, or (``all``) every record of ``folder`` with a monitor report."""
    if records == "all":
        return sorted(p.parent.parent.name for p in (folder / "reports").glob("*/monitor/monitor.json"))
    return [label_of(r) for r in records_of(records)]


def _overrides(label: str) -> tuple:
    """The data overrides bench_mon88 runs its record ``label`` with (none for audit89's)."""
    from bench_mon88 import FRESH

    seed = label.lstrip("lrc")
    return FRESH[int(seed)][2] if label[:2] in ("lr", "cr") and seed.isdigit() else ()


def rooms(root: str, seeds: str) -> None:
    """bench_mon88's fresh records (``FRESH``: 9196-9200 long records, R1b continuing R1a, 9201-9205
    climate rooms) drawn HEALTHY (nothing planted) into ROOT (kept): ``run model=mlr`` ->
    ``monitor`` (its overrides); then ``trace ROOT all`` traces them."""
    from bench_mon88 import FRESH, _root

    folder = _root(root)
    for seed in seed_list(seeds):
        kind, sim, extra = FRESH[seed]
        drawn_run_monitored(folder, f"{kind}{seed}", seed, sim, extra)


def drawn_run_monitored(folder: Path, label: str, seed: int, sim: tuple, extra: tuple) -> None:
    """``simulate seed=<seed> <sim>`` into ``folder/data/label`` -> ``run model=mlr`` ->
    ``monitor`` (the run's model), each with the data overrides ``extra``."""
    from bench_mon88 import _drawn

    data, out = _drawn(label, seed, sim, folder), folder / "reports" / label
    model = f"monitor.model={out / 'run' / 'model.pkl'}"
    for name, more in (("run", ["model=mlr"]), ("monitor", [model])):
        rc, said = stage(name, f"data.path={data}", f"out={out / name}", *QUIET, *extra, *more)
        assert rc == 0, said
    print(f"{label}: drawn, run, monitored", flush=True)


def trace(root: str, records: str) -> None:
    """The state-driven band of every sensor no other predicts (module doc) -> ROOT/trace91b.json."""
    folder = Path(root).resolve()
    rows = []
    print(f"{'record':<15}{'sensor':<21}{'v':>2}{'ntr':>4}{'cv_rmse':>8}{'cv_r2':>7}{'spread':>7}{'band':>7}"
          f"{'healthy':>8}{'drift':>6}{'false':>6}{'found':>6}{'delay h':>8}"
          f"{'| probe: false':>15}{'found':>6}{'delay h':>8}", flush=True)
    for label in labels_of(folder, records):
        mon = json.loads((folder / "reports" / label / "monitor" / "monitor.json").read_text())
        costliest = _costliest(mon)
        train, test = campaigns(folder, label)
        for sensor in [s for s, v in mon["sensors"].items() if not v["observable"]]:
            for variant in VARIANTS:
                row = {"record": label, "costliest": sensor == costliest,
                       **trace_sensor(train, test, sensor, variant)}
                name = sensor + ("*" if row["costliest"] else "")
                if "note" in row:
                    print(f"{label:<15}{name:<21}  {row['note']}", flush=True)
                    rows.append(row)
                    continue
                parts = row.pop("parts")
                row.update(healthy_max=max(p["healthy_max"] for p in parts),
                           drift_end=max(p["drift_end"] for p in parts),
                           **{f"{w}_{k}": [p[f"{w}_{k}"] for p in parts]
                              for w in ("false", "delay") for k in ("rule", "probe")})
                rows.append(row)

                def said(k):
                    d = [x for x in row[f"delay_{k}"] if x is not None]
                    return (f"{sum(row[f'false_{k}']):>6}{len(d):>3}/{len(parts):<2}"
                            f"{(f'{np.median(d):.2f}' if d else '-'):>8}")
                print(f"{label:<15}{name:<21}{row['variant']:>2}{row['n_train']:>4}{row['cv_rmse']:>8.3f}"
                      f"{row['cv_r2']:>7.2f}{row['spread']:>7.2f}{row['band_rule']:>7.2f}"
                      f"{row['healthy_max']:>8.2f}{row['drift_end']:>6.2f}{said('rule')}{'|':>7}"
                      f"{said('probe')}", flush=True)
    (folder / "trace91b.json").write_text(json.dumps(rows, indent=1))


def _copy_fed(root: Path, label: str, name: str, sensor: str, columns: list[np.ndarray]) -> Path:
    """A copy of the record whose test files read ``columns`` (one per test campaign) as ``sensor``."""
    data, copy = root / "data" / label, root / "data" / f"{label}-91b-{name}"
    if copy.exists():
        shutil.rmtree(copy)
    shutil.copytree(data, copy)
    manifest = pd.read_csv(copy / "campaigns.csv")
    for f, x in zip([f for f, s in zip(manifest["file"], manifest["split"]) if s == "test"], columns):
        frame = _read(copy / f)
        frame[sensor] = x[len(x) - len(frame):]
        _write(frame, copy / f)
    return copy


def _replaced(x: np.ndarray, estimate: np.ndarray, row: int | None) -> np.ndarray:
    """``x`` with ``estimate`` in its place from ``row`` on (None: ``x``)."""
    return x if row is None else np.where(np.arange(len(x)) >= row, estimate, x)


def served(root: str, records: str) -> None:
    """The served monitor (``monitor`` with the healthy run's model.pkl) fed the costliest sensor
    no other predicts as: the truth; drifted (+0.5 degC/h from each test campaign's middle row);
    drifted, replaced by a variant's estimate from the band's first crossing on (the rule's band,
    3 x spread; the probe's, 1 x); the truth replaced by it from the middle row on (the estimate's
    own cost).  RMSE fixed / adaptive (mean over targets, um) -> ROOT/served91b.json."""
    folder = Path(root).resolve()
    os.environ["THERMOCOMP_ROOT"] = str(folder)
    rows = []
    print(f"{'record':<15}{'sensor':<21}{'case':<26}{'fixed':>9}{'adaptive':>9}{'events':>7}  crossing rows"
          "  the monitor's first event naming the sensor", flush=True)
    for label in labels_of(folder, records):
        out = folder / "reports" / label
        mon = json.loads((out / "monitor" / "monitor.json").read_text())
        sensor = _costliest(mon)
        if label == "fl_thermal" or mon["sensors"][sensor]["observable"]:
            continue     # fl's costliest sensor is predicted
        train, test = campaigns(folder, label)
        truth = [f[sensor].to_numpy(float) for f, _ in test]
        cases = {"truth": (truth, "")}
        for variant in VARIANTS:
            parts = trace_sensor(train, test, sensor, variant)["parts"]
            cases["drift"] = ([p["drifted"] for p in parts], "")
            for k in ("rule", "probe"):
                cases[f"{variant}_drift->estimate_{k}"] = (
                    [_replaced(p["drifted"], p["estimate"], p[f"row_{k}"]) for p in parts],
                    ",".join(str(p[f"row_{k}"]) for p in parts))
            cases[f"{variant}_truth->estimate"] = (
                [_replaced(x, p["estimate"], p["mid"]) for x, p in zip(truth, parts)], "")
        for name, (columns, crossings) in cases.items():
            word = name.replace(">", "")
            copy = _copy_fed(folder, label, word, sensor, columns)
            rc, said = stage("monitor", f"data.path={copy}", f"out={out / ('mon91b-' + word)}", *QUIET,
                             *_overrides(label), f"monitor.model={out / 'run' / 'model.pkl'}")
            shutil.rmtree(copy)
            r = {"record": label, "sensor": sensor, "case": name, "rows": crossings}
            if rc:
                rows.append({**r, "note": f"monitor exit {rc}: {said[:200]}"})
                print(f"{label:<15}{sensor:<21}{name:<26}{rows[-1]['note']}", flush=True)
                continue
            got = json.loads((out / f"mon91b-{word}" / "monitor.json").read_text())
            named = [e for e in got["events"] if sensor in _named(e)]
            rows.append({**r, "rmse_fixed": _mean_rmse(got, "rmse_fixed"),
                         "rmse_adaptive": _mean_rmse(got, "rmse_adaptive"), "events": len(named),
                         "first_event": _traced(named[0]) if named else ""})
            print(f"{label:<15}{sensor:<21}{name:<26}{rows[-1]['rmse_fixed']:>9.4f}"
                  f"{rows[-1]['rmse_adaptive']:>9.4f}{len(named):>7}  {crossings[:40]}"
                  f"  {rows[-1]['first_event'][:70]}", flush=True)
    (folder / "served91b.json").write_text(json.dumps(rows, indent=1))


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"rooms": rooms, "trace": trace, "served": served},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
