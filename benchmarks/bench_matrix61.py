"""Deployed against scored, every model x wrapper, on records nobody tuned on (stop 61; prints a
table, no assertions).

Two records simulated for this bench, their seeds written down before any model ran (no test or
benchmark used 6111 or 6112):

- ``ys``: ``simulate sim=yearround_spindle "sim.generator.effects=[door]" seed=6111
  sim.generator.n_campaigns=12 sim.generator.duration_h=[3.0,5.0]`` (8 train campaigns at 4.7-32.4
  °C ambient, test K03, K06, K09, K12; the door ``S_door`` an undeclared signal);
- ``sw``: ``simulate sim=swiss_lathe_door seed=6112 sim.generator.calibration_hours=40
  sim.generator.production_hours=12`` (one 40 h calibration record, one 12 h production run: one
  ambient level, so ``ati=cmeans`` has nothing to span).

Per record, model (``mlr``, ``pcr``, ``arx``, ``arx_rf`` (10 trees), ``lagbank``, ``hammerstein``,
``lstm`` (3 epochs, 4 hidden), ``auto`` (its candidates without ``lstm``)) and wrapper (``plain``;
``ati=cmeans``; ``denoise=emd`` with its causal FIR; ``diag``: ``diagnose`` of the plain model and
its written config re-run as the rerun line says), the route a stranger takes, in a scratch root
(``THERMOCOMP_ROOT``: its own ``mlruns``, ``data``, ``reports``; the checkout's ``conf/`` linked):
``run`` -> ``replay`` (``monitor.adaptive=false`` and ``true``) -> ``promote promote.run_id=<run>
promote.force=true`` -> ``export export.model=<promoted version> export.format=c`` -> ``cc`` of
``compensator.c stream.c``, the test campaigns' CSV streamed through it -> the promoted version
as served (loaded from the registry as ``serve`` loads it, in process) streamed over the same
rows.  Columns (µm, mean over targets of each target's RMSE over the test campaigns):

- ``run``: metrics.json's test RMSE; ``diag``: diagnose's "after" (deployed) test RMSE;
- ``plain``, ``adapt``: replay's RMSE, monitor.adaptive=false / true; ``s-b``: replay's largest
  |stream - batch|; ``ev``: events of the adaptive compensator on the healthy test campaigns;
  ``clamp``: test samples with an input clamped to the training envelope (the adaptive replay);
- ``prom``: promote's "as deployed" test RMSE; ``C``: the compiled C's RMSE;
- ``unexpl``: test rows where the plain deployed stream differs from run's batch prediction
  before any input of its campaign was clamped (a difference the clamp does not explain);
- ``C-rep``: max |C - the adaptive replay stream| (model.pkl made deployable as replay does);
  ``C-rep<ev``: the same before the adaptive compensator's first event or clamp of a campaign
  (the code has its guard, not its sensor monitor);
  ``srv-rep``: max |the served version - that stream|;
- ``faults``: the adaptive stream of the first test campaign with, on the input whose +1 K moves
  the correction most, from its middle row: ``stuck``, ``drift`` (+2 K/h), ``spike`` (+50 K, one
  row), ``dropout`` (16 empty cells), ``time`` (one missing time): the largest |correction| over
  all of them against the guard's bound (``max/bound``), ``!`` if not finite or beyond it;
- ``cpu``: the cell's CPU seconds (this process and its children);
- a refusal: the stage, its exit status and its last line (exit 2 in one line is a refusal;
  anything else is a defect, marked ``DEFECT``).

Run: ``PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_matrix61.py [--root /tmp/matrix61-bench]
[--records ys sw] [--models mlr ...] [--wrappers plain ...] [--serve]`` (``--serve``: one
request batch through a real ``thermocomp serve`` of the last promoted version per record).

Measured 2026-12-01 (stop 61; the three records in three processes, 2 shared cores; CPU of the
whole matrix with its children: ys 349.5 s, sw 513.0 s, cm 794.7 s; 1657 s in all), after the two mends of
matrix61 (below).  Every cell that exports (mlr, pcr, arx, lagbank, hammerstein, auto; plain,
``ati``, ``emd``, ``diag``):

- ``ys`` and ``sw`` (no test input leaves the envelope): run = replay plain = replay adaptive =
  promote "as deployed" = the compiled C's RMSE = diagnose's "after" to the printed digit
  (ys mlr 3.47 / ati 2.32 / emd 3.29 / diag 2.40 µm; sw hammerstein 0.564 ...); max |stream -
  batch| <= 1.3e-12 µm, |C - replay| <= 3.0e-13, the served version = the replay stream (0 in
  process; a real ``serve``: 38 rows (ys) and 721 rows (sw), max |served - stream| 0.0); no event,
  no clamped sample;
- ``cm`` (a source training never saw in the test half, from 36000 s): 135 (141 with ``emd``)
  test samples clamped, 100-108 events, the first at 37200 s in every cell (none on the healthy
  first half); in no cell does the plain stream part from run's batch before its campaign's
  first clamp (``unexpl`` 0); the C equals the adaptive stream to 5.0e-13 before the first
  event, and after it differs by up to 0.79 µm (the code has the guard, not the sensor
  monitor), its RMSE = promote's to the printed digit (mlr 10.1, arx 6.68, lagbank 9.87);
- faults: every adaptive stream finite; within the trained bound, or (cm, emd: stuck and drift
  of ``T_edge1``, 335-361 µm against 325.8) beyond it only where the bound followed inputs on
  the training pattern (without ``monitor.guard.follow_inputs`` it holds 325.8); the adaptive
  deployment's C finite and within its bound on stuck, drift, spike and a missing time;
  ``stream.c`` stops at the 16 empty cells, exit 2 in one line (``stream: row 21: input
  T_motor1 has no finite value``: by design, ``tc_step`` itself repeats the last correction);
  the plain stream's C = the plain stream in process, the clamp acting, to 8.0e-13 µm.

Refused, exit 2 in one line each: ``export`` of ``arx_rf``, ``lstm`` and their diagnosed models
(``... (lstm) cannot be exported as c: model LSTM is not one of the linear families that
export ...``); ``run model=auto ati=cmeans`` (ati is auto's candidate); ``diagnose model=auto``.
``ati=cmeans`` on ``sw``/``cm`` (one train campaign) falls back to one model, said in a warning.
Not mended, a diagnosis and not a deployment: on ``cm`` the diagnosed ``lstm`` is 13.1 µm where
the plain one is 9.58 (both as deployed; ``diagnose``'s CV ran on the train cycle alone).

Mended (each with a test failing before): ``diagnose`` scored "before"/"after" through the plain
stream whatever ``monitor.adaptive`` said, while ``promote`` registers the adaptive compensator:
on ``cm`` the diagnosed mlr / arx / lagbank were "after" 5.46 / 5.61 / 9.92 µm and promoted at
6.20 / 6.36 / 9.87; now "after" is promote's figure in every cell
(``tests/shell/test_diagnose_deployed60.py``); ``export`` of a model.pkl that cannot be
exported, without ``data.path``, was refused for the missing default data folder, and only once
given the data for its family (``tests/shell/test_export_refused_early.py``).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import subprocess
import sys
import time
import traceback
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
_ROOT_ARG = next((a.split("=", 1)[1] for a in sys.argv if a.startswith("--root=")), None)
if "--root" in sys.argv:
    _ROOT_ARG = sys.argv[sys.argv.index("--root") + 1]
ROOT = Path(_ROOT_ARG or "/tmp/matrix61-bench")
os.environ["THERMOCOMP_ROOT"] = str(ROOT)            # before thermocomp resolves its root
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
sys.path[:0] = [str(REPO / "benchmarks")]

import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from cpu import cpu_seconds  # noqa: E402

RECORDS = {
    "ys": ["sim=yearround_spindle", "sim.generator.effects=[door]", "seed=6111",
           "sim.generator.n_campaigns=12", "sim.generator.duration_h=[3.0,5.0]"],
    "sw": ["sim=swiss_lathe_door", "seed=6112", "sim.generator.calibration_hours=40",
           "sim.generator.production_hours=12"],
    # added before its models ran: a test half with a source training never saw (the clamp acts)
    "cm": ["sim=column_moving_source", "seed=6111", "sim.generator.train_hours=30",
           "sim.generator.test_hours=20"],
}
MODELS = {
    "mlr": [], "pcr": [], "arx": [], "lagbank": [], "hammerstein": [],
    "arx_rf": ["model.estimator.forest.n_estimators=10"],
    "lstm": ["model.estimator.max_epochs=3", "model.estimator.hidden_size=4", "model.estimator.chunk=16"],
    "auto": ["model.candidates=[mlr,pcr,arx,lagbank,hammerstein,ati]"],
}
WRAPPERS = {"plain": [], "ati": ["ati=cmeans"], "emd": ["denoise=emd"], "diag": [],
            # (not in the default matrix) diagnose around the other wrappers
            "diag-ati": ["ati=cmeans"], "diag-emd": ["denoise=emd"]}
DEFAULT_WRAPPERS = ["plain", "ati", "emd", "diag"]
FAULTS = ("stuck", "drift", "spike", "dropout", "time")


def stage(*args: str) -> tuple[int, str, int]:
    """``thermocomp <args>`` in process: (exit status, its last line on stderr, how many lines of
    it say ``error``); an exception that escapes is exit -1 with its traceback's last line."""
    from thermocomp.shell.cli import main

    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        try:
            rc = main(list(args)) or 0
        except SystemExit as exc:
            rc = int(exc.code or 0)
        except Exception:                  # noqa: BLE001  (a crash is what the bench looks for)
            rc, err = -1, io.StringIO(traceback.format_exc())
    lines = [x for x in err.getvalue().splitlines() if x.strip()]
    said = [x for x in lines if "error" in x.lower()]
    return rc, lines[-1] if lines else "", len(said)


def last_run_id() -> str:
    import mlflow

    mlflow.set_tracking_uri(f"sqlite:///{ROOT}/mlruns/mlflow.db")
    runs = mlflow.search_runs(experiment_names=["thermocomp"], order_by=["start_time DESC"],
                              max_results=1, filter_string="tags.stage = 'run'")
    return str(runs.iloc[0]["run_id"])


def compose(data: Path, *overrides: str):
    from hydra import compose as hydra_compose
    from hydra import initialize_config_dir

    with initialize_config_dir(config_dir=str(ROOT / "conf"), version_base="1.3"):
        return hydra_compose(config_name="config",
                             overrides=[f"data.path={data}", "track=false", *overrides])


def test_frames(data: Path) -> dict[str, pd.DataFrame]:
    """The test campaigns as recorded (the files: what a machine's log would hand the code)."""
    listed = pd.read_csv(data / "campaigns.csv")
    return {r.campaign: pd.read_csv(data / r.file) for r in listed.itertuples() if r.split == "test"}


def deployed_of(data: Path, source: str, adaptive: bool = True, *overrides: str):
    """``source`` (a model.pkl or a registered version) made deployable as replay makes it."""
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    cfg = compose(data, f"monitor.adaptive={str(adaptive).lower()}", *overrides)
    ds, train_ids, _, _ = read_streamed(cfg)
    return deployable_model(cfg, ds, train_ids, source, "replay.model")[0]


def streamed(deployed, frames: dict) -> np.ndarray:
    """The correction (C = -prediction) of every test row, campaign after campaign."""
    from thermocomp.apps.deploy.report import stream_rows

    return np.vstack([-stream_rows(deployed, df, cid).y for cid, df in frames.items()])


def flagged_stream(deployed, frames: dict) -> tuple[np.ndarray, np.ndarray]:
    """The correction of every test row and, per row, whether its campaign has had a clamped
    input or an event of the adaptive compensator at or before it (what explains a difference
    from the batch prediction)."""
    from thermocomp.apps.deploy.report import stream_rows

    ys, flags = [], []
    for cid, df in frames.items():
        s = stream_rows(deployed, df, cid)
        since = df["time"].to_numpy(float) - float(df["time"].iloc[0])
        first = min([len(df)] + [int(np.argmax(s.clamped > 0))] * bool((s.clamped > 0).any())
                    + [int(np.searchsorted(since, e["time"])) for e in s.events])
        ys.append(-s.y)
        flags.append(np.arange(len(df)) >= first)
    return np.vstack(ys), np.concatenate(flags)


def unexplained(data: Path, pkl: str, frames: dict, targets: list[str]) -> int:
    """Test rows where the plain deployed stream differs from run's batch prediction (by more
    than 1e-9 µm) before any clamp of its campaign."""
    from thermocomp.shell.model_store import load_model
    from thermocomp.shell.source import read_streamed

    ds, _, _, _ = read_streamed(compose(data))
    predicted = load_model(pkl).predict({c: ds.campaigns[c] for c in frames})
    batch = np.vstack([predicted[c][targets].to_numpy(float) for c in frames])
    y, explained = flagged_stream(deployed_of(data, pkl, adaptive=False), frames)
    return int(((np.abs(y + batch).max(axis=1) > 1e-9) & ~explained).sum())


def compiled(folder: Path, frames: dict, inputs: list[str]) -> np.ndarray:
    """The exported C's stream over the test campaigns (a blank line between campaigns)."""
    subprocess.run(["cc", "-std=c99", "-O2", "compensator.c", "stream.c", "-lm", "-o", "stream"],
                   cwd=folder, check=True, capture_output=True)
    parts = [df[["time", *inputs]].to_csv(index=False, float_format="%.17g") for df in frames.values()]
    text = parts[0] + "".join("\n" + p.split("\n", 1)[1] for p in parts[1:])
    out = subprocess.run([str(folder / "stream")], input=text, text=True, capture_output=True,
                         check=True)
    return pd.read_csv(io.StringIO(out.stdout))


def rmse(measured: np.ndarray, correction: np.ndarray) -> float:
    """Mean over targets of the RMSE of measured + correction (rows with a measurement)."""
    r = measured + correction
    return float(np.mean([np.sqrt(np.nanmean(r[:, j] ** 2)) for j in range(r.shape[1])]))


def measured_errors(data: Path, frames: dict, targets: list[str], pkl: str) -> np.ndarray:
    """The errors as run scores them: the model's frame (the change since each campaign's first
    sample where it is referenced so), the test campaigns read as run reads them."""
    from thermocomp.shell.model_store import load_model
    from thermocomp.shell.source import read_streamed

    ds, _, _, _ = read_streamed(compose(data))
    measured = load_model(pkl).measured({c: ds.campaigns[c] for c in frames})
    return np.vstack([measured[c][targets].to_numpy(float) for c in frames])


def faulted(df: pd.DataFrame, column: str) -> dict[str, pd.DataFrame]:
    """The campaign with each fault on ``column`` from its middle row."""
    h, out = len(df) // 2, {}
    t = df["time"].to_numpy(float)
    for kind in FAULTS:
        f = df.copy()
        f[column] = f[column].astype(float)
        f["time"] = f["time"].astype(float)
        if kind == "stuck":
            f.loc[h:, column] = f.loc[h, column]
        elif kind == "drift":
            f.loc[h:, column] += 2.0 * (t[h:] - t[h]) / 3600.0
        elif kind == "spike":
            f.loc[h, column] += 50.0
        elif kind == "dropout":
            f.loc[h:h + 15, column] = np.nan
        else:
            f.loc[h, "time"] = np.nan
        out[kind] = f
    return out


def fault_cell(deployed, frames: dict, bound, fixed_bound=None) -> str:
    """The adaptive stream under each fault (module doc): ``max|C| / bound``.  Beyond the trained
    bound, the guard's bound may have followed inputs beyond their training range on the
    training pattern (``monitor.guard.follow_inputs``): ``fixed_bound()`` gives the same
    deployment without it, which must then stay within the trained bound."""
    from thermocomp.apps.deploy.report import plain, stream_rows

    cid, df = next(iter(frames.items()))
    base = -stream_rows(deployed, df, cid).y
    temps = [c for c in plain(deployed).columns_ if c.startswith("T_") and c != "T_amb"]
    moved = {}
    for c in temps:
        f = df.copy()
        f[c] = f[c] + 1.0
        moved[c] = float(np.max(np.abs(-stream_rows(deployed, f, cid).y - base)))
    column = max(moved, key=moved.get)
    worst, bad, followed = 0.0, [], []
    lo, hi = (np.asarray(b, float) for b in zip(*bound)) if bound else (None, None)
    for kind, f in faulted(df, column).items():
        try:
            y = stream_rows(deployed, f, cid).y
        except Exception as exc:                # noqa: BLE001
            bad.append(f"{kind} raised {type(exc).__name__}")
            continue
        if not np.isfinite(y).all():
            bad.append(f"{kind} NaN")
        elif lo is not None and ((y < lo - 1e-9) | (y > hi + 1e-9)).any():
            fixed = stream_rows(fixed_bound(), f, cid).y if fixed_bound else y
            within = not ((fixed < lo - 1e-9) | (fixed > hi + 1e-9)).any()
            followed.append(kind) if within else bad.append(f"{kind} beyond the bound")
        worst = max(worst, float(np.nanmax(np.abs(y))))
    edge = float(np.max(np.abs(bound))) if bound else float("nan")
    return (f"{worst:.1f}/{edge:.1f} {column}" + (" ! " + ", ".join(bad) if bad else "")
            + (f" (bound followed the inputs: {', '.join(followed)})" if followed else "")), column


def c_faults(folder: Path, frames: dict, inputs: list[str], column: str, bound, order) -> str:
    """The compiled C's stream of the first test campaign under each fault on ``column``: its
    largest |C|, ``!`` where not finite, beyond the guard's bound, or stopped (its exit, line)."""
    cid, df = next(iter(frames.items()))
    lo, hi = (np.asarray(b, float)[order] for b in zip(*bound))
    worst, bad, refusals = 0.0, [], []
    for kind, f in faulted(df, column).items():
        text = f[["time", *inputs]].to_csv(index=False, float_format="%.17g")
        p = subprocess.run([str(folder / "stream")], input=text, text=True, capture_output=True)
        if p.returncode:
            lines = p.stderr.strip().splitlines()
            clear = p.returncode == 2 and len(lines) == 1
            said = f"{kind} refused (exit 2): {lines[0][:80]}" if clear else \
                f"{kind} exit {p.returncode} DEFECT: {p.stderr[-200:]}"
            (refusals if clear else bad).append(said)
            continue
        got = pd.read_csv(io.StringIO(p.stdout))
        c = got[[c for c in got.columns if c.startswith("C_")]].to_numpy(float)
        if len(c) != len(f) or not np.isfinite(c).all():
            bad.append(f"{kind}: {len(c)} of {len(f)} rows, finite {np.isfinite(c).all()}")
        elif ((-c < lo - 1e-9) | (-c > hi + 1e-9)).any():
            bad.append(f"{kind} beyond the bound")
        worst = max(worst, float(np.nanmax(np.abs(c))) if c.size else 0.0)
    return f"C {worst:.1f}" + (" ! " + ", ".join(bad) if bad else "") + "".join(
        f" ({r})" for r in refusals)


def plain_code_vs_stream(folder: Path, data: Path, pkl: str, frames: dict, column: str) -> str:
    """The plain stream (``monitor.adaptive=false``) exported as C from ``pkl`` against the plain
    stream in process, on the test campaigns and on the first one under each fault the plain
    stream takes (a dropout it refuses): max |C - stream| (the clamp acting alike in both)."""
    deployed = deployed_of(data, pkl, adaptive=False)
    spec = json.loads((folder / "compensator.json").read_text())
    order = [list(deployed.targets_).index(t) for t in spec["targets"]]
    cid, df = next(iter(frames.items()))
    cases = {"healthy": frames, **{k: {cid: f} for k, f in faulted(df, column).items()
                                   if k != "dropout"}}
    worst = {}
    for kind, fr in cases.items():
        c = compiled(folder, fr, spec["inputs"])
        c = c[[f"C_{t[2:]}" for t in spec["targets"]]].to_numpy(float)
        worst[kind] = float(np.max(np.abs(c - streamed(deployed, fr)[:, order])))
    return f"plain C-stream {max(worst.values()):.1e} (" + ", ".join(
        f"{k} {v:.0e}" for k, v in worst.items() if v > 1e-9) + ")"


def refused(stage_name: str, rc: int, said: str, n_error_lines: int) -> str:
    clear = rc == 2 and n_error_lines <= 1
    return f"{stage_name} exit {rc}{'' if clear else ' DEFECT'}: {said[:150]}"


def run_cell(record: str, family: str, wrapper: str, data: Path) -> dict:
    name = f"{record}-{family}-{wrapper}"
    out = ROOT / "reports" / name
    row: dict = {"cell": name}
    model_args = [f"model={family}", *MODELS[family]]
    if wrapper.startswith("diag"):
        rc, said, n = stage("diagnose", f"data.path={data}", f"out={out}-diagnose", "plots=none",
                            *model_args, *WRAPPERS[wrapper])
        if rc:
            return {**row, "note": refused("diagnose", rc, said, n)}
        diagnosis = json.loads((out.parent / f"{name}-diagnose" / "diagnosis.json").read_text())
        after = {diagnosis["target"]: diagnosis["after"]["test_rmse"],
                 **{t: v["after_test_rmse"] for t, v in diagnosis["other_targets"].items()}}
        row["diag"] = float(np.mean(list(after.values())))
        accepted = [e["transform"] for e in diagnosis["effects"]] + [
            a for v in diagnosis["other_targets"].values() for a in v["accepted"]]
        row["effects"] = len(accepted)
        conf = out.parent / f"{name}-diagnose" / "diagnosis" / "conf"
        args = ["run", f"hydra.searchpath=[file://{conf}]", "experiment=diagnosed"]
    else:
        args = ["run", *model_args, *WRAPPERS[wrapper]]
    rc, said, n = stage(*args, f"data.path={data}", f"out={out}", "plots=none")
    if rc:
        return {**row, "note": refused("run", rc, said, n)}
    metrics = json.loads((out / "metrics.json").read_text())
    targets = list(metrics["targets"])
    row["run"] = float(np.mean([metrics["targets"][t]["test"]["rmse"] for t in targets]))
    pkl = str(out / "model.pkl")
    notes = []
    for adaptive in ("false", "true"):
        rc, said, n = stage("replay", f"data.path={data}", f"out={out}-replay-{adaptive}",
                            f"replay.model={pkl}", f"monitor.adaptive={adaptive}")
        if rc:
            notes.append(refused(f"replay adaptive={adaptive}", rc, said, n))
            continue
        rep = json.loads((out.parent / f"{name}-replay-{adaptive}" / "replay.json").read_text())
        row["plain" if adaptive == "false" else "adapt"] = float(
            np.mean([rep["targets"][t]["rmse"] for t in targets]))
        row["s-b"] = max(row.get("s-b", 0.0), max(rep["targets"][t]["max_abs_stream_minus_batch"]
                                                  for t in targets))
        if adaptive == "true":
            row["ev"] = len(rep["events"])
            row["clamp"] = max(rep["targets"][t]["clamped_samples"] for t in targets)
            bound = [rep["targets"][t]["bound"] for t in targets]
    run_id = last_run_id()
    rc, said, n = stage("promote", f"data.path={data}", f"out={out}-promote",
                        f"promote.run_id={run_id}", "promote.force=true")
    if rc:
        return {**row, "note": "; ".join([*notes, refused("promote", rc, said, n)])}
    promoted = json.loads((out.parent / f"{name}-promote" / "promote.json").read_text())
    row["prom"] = float(promoted["candidate"]["test_reported"]["rmse"])
    uri = promoted["model_uri"]
    frames = test_frames(data)
    measured = measured_errors(data, frames, targets, pkl)
    try:
        replayed, after_event = flagged_stream(deployed_of(data, pkl), frames)
        row["unexpl"] = unexplained(data, pkl, frames, targets)
        served = streamed(deployed_of(data, uri), frames)
        row["srv-rep"] = float(np.max(np.abs(served - replayed)))
        row["faults"], column = fault_cell(
            deployed_of(data, pkl), frames, bound if "adapt" in row else None,
            lambda: deployed_of(data, pkl, True, "monitor.guard.follow_inputs=false"))
    except Exception as exc:                       # noqa: BLE001
        notes.append(f"in-process stream DEFECT: {type(exc).__name__}: {str(exc)[:120]}")
        replayed = column = None
    rc, said, n = stage("export", f"data.path={data}", f"export.model={uri}", "export.format=c",
                        f"out={out}-c")
    if rc:
        notes.append(refused("export", rc, said, n))
    else:
        spec = json.loads((out.parent / f"{name}-c" / "compensator.json").read_text())
        got = compiled(out.parent / f"{name}-c", frames, spec["inputs"])
        order = [targets.index(t) for t in spec["targets"]]
        c = got[[f"C_{t[2:]}" for t in spec["targets"]]].to_numpy(float)
        row["C"] = rmse(measured[:, order], c)
        if replayed is not None:
            row["C-rep"] = float(np.max(np.abs(c - replayed[:, order])))
            gap = np.abs(c - replayed[:, order]).max(axis=1)
            row["C-rep<ev"] = float(gap[~after_event].max(initial=0.0))
        if column is not None and "adapt" in row:
            row["faults"] += "; " + c_faults(out.parent / f"{name}-c", frames, spec["inputs"], column,
                                             bound, order)
        rc, said, n = stage("export", f"data.path={data}", f"export.model={pkl}", "export.format=c",
                            "monitor.adaptive=false", f"out={out}-plain-c")
        if rc:
            notes.append(refused("export plain", rc, said, n))
        elif column is not None:
            row["faults"] += "; " + plain_code_vs_stream(out.parent / f"{name}-plain-c", data, pkl,
                                                         frames, column)
    return {**row, "note": "; ".join(notes)}


def serve_once(data: Path, uri: str) -> str:
    """One request batch (the first test campaign) through ``thermocomp serve`` of ``uri``;
    max |served - the in-process registered stream|."""
    import requests

    sys.path[:0] = [str(REPO / "tests")]
    from conftest import free_port

    port = free_port()
    log = open(ROOT / "serve.log", "w")
    env = dict(os.environ, PYTHONPATH=str(REPO / "src"))
    server = subprocess.Popen([sys.executable, "-m", "thermocomp", "serve", f"serve.model={uri}",
                               f"serve.port={port}", f"data.path={data}"], cwd=ROOT, env=env, stdout=log,
                              stderr=subprocess.STDOUT, start_new_session=True)
    try:
        deadline = time.monotonic() + 180
        while time.monotonic() < deadline and server.poll() is None:
            with contextlib.suppress(requests.RequestException):
                if requests.get(f"http://127.0.0.1:{port}/ping", timeout=2).status_code == 200:
                    break
            time.sleep(1)
        else:
            return f"serve did not come up (exit {server.poll()})"
        frames = test_frames(data)
        cid, df = next(iter(frames.items()))
        deployed = deployed_of(data, uri)
        cols = ["time", *deployed.columns_] if hasattr(deployed, "columns_") else list(df.columns)
        body = {"dataframe_split": df[cols].to_dict(orient="split"),
                "params": {"session": "m61", "reset": True}}
        body["dataframe_split"].pop("index")
        resp = requests.post(f"http://127.0.0.1:{port}/invocations", json=body, timeout=120)
        if resp.status_code != 200:
            return f"serve HTTP {resp.status_code}: {resp.text[:150]}"
        got = pd.DataFrame(resp.json()["predictions"])
        want = streamed(deployed, {cid: df})
        outs = [c for c in got.columns if c.startswith("C_")]
        gap = np.max(np.abs(got[outs].to_numpy(float) - want))
        return f"served {len(got)} rows, max|served - stream| {gap:.2e}"
    finally:
        import signal
        if server.poll() is None:
            os.killpg(server.pid, signal.SIGTERM)
            server.wait(timeout=60)
        log.close()


COLUMNS = ["run", "diag", "plain", "adapt", "s-b", "ev", "clamp", "unexpl", "prom", "C", "C-rep",
           "C-rep<ev", "srv-rep", "cpu"]


def show(row: dict) -> str:
    def fmt(c):
        v = row.get(c)
        if v is None:
            return f"{'-':>9}"
        return f"{v:>9.1e}" if c in ("s-b", "C-rep", "C-rep<ev", "srv-rep") else f"{v:>9.3g}"
    return (f"{row['cell']:<24}" + "".join(fmt(c) for c in COLUMNS)
            + f"  {row.get('faults', '')}  {row.get('note', '')}")


def main_bench() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--root", default=str(ROOT))
    parser.add_argument("--records", nargs="*", default=list(RECORDS))
    parser.add_argument("--models", nargs="*", default=list(MODELS))
    parser.add_argument("--wrappers", nargs="*", default=DEFAULT_WRAPPERS)
    parser.add_argument("--serve", action="store_true")
    opts = parser.parse_args()
    ROOT.mkdir(parents=True, exist_ok=True)
    if not (ROOT / "conf").exists():
        (ROOT / "conf").symlink_to(REPO / "conf")
    start = cpu_seconds(children=True)
    print(f"{'cell':<24}" + "".join(f"{c:>9}" for c in COLUMNS) + "  faults  note", flush=True)
    for record in opts.records:
        data = ROOT / "data" / record
        if not data.exists():
            rc, said, _ = stage("simulate", *RECORDS[record], f"data.path={data}")
            assert rc == 0, said
        for family in opts.models:
            for wrapper in opts.wrappers:
                before = cpu_seconds(children=True)
                try:
                    row = run_cell(record, family, wrapper, data)
                except Exception as exc:           # noqa: BLE001
                    row = {"cell": f"{record}-{family}-{wrapper}",
                           "note": f"bench DEFECT? {type(exc).__name__}: {str(exc)[:200]}"}
                    traceback.print_exc()
                row["cpu"] = cpu_seconds(children=True) - before
                print(show(row), flush=True)
        if opts.serve:
            promoted = sorted((ROOT / "reports").glob(f"{record}-*-promote/promote.json"),
                              key=lambda p: p.stat().st_mtime)
            if promoted:
                uri = json.loads(promoted[-1].read_text())["model_uri"]
                print(f"{record} serve {uri}: {serve_once(data, uri)}", flush=True)
    print("CPU s (user + sys) of the whole matrix:", round(cpu_seconds(children=True) - start, 1))


if __name__ == "__main__":
    main_bench()
