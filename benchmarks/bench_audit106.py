"""Thermocomp run as a stranger would on stop 105's head (stop 106, audit106; issue 34), off the
happy path, at angles audit103 / audit105 did not take: the new default of ``model=auto``
(``model.estimator.hedge=campaigns``, auto105b) end to end through a Hydra multirun sweep (two
models x two ``eval.mode``), ``compare``, ``promote`` and the exported code, and ``dvc repro`` in
a fresh clone as docs/dvc.md writes it; a lab's raw export of a kind not tried (tab-delimited,
units in brackets in the headers, ISO-8601 timestamps with their offset across a daylight saving
change, a row written twice, a gap of hours; a Parquet copy); a simulated kind neither audit ran
(``climate_room``) with every family x wrapper through run, replay, promote and the code; faults
fed to the deployed compensator that neither audit tried; a healthy draw through ``monitor``, the
C and the ST.  The bar was written first.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_audit106.py auto ROOT                 # cell A (fresh cr10066)
    python benchmarks/bench_audit106.py dvc CLONE                 # cell D (a clone at BASE)
    python benchmarks/bench_audit106.py models ROOT [WORD ...]    # cell M (fresh cr10066)
    python benchmarks/bench_audit106.py faults ROOT PORT          # cell F (cr10066's mlr-none)
    python benchmarks/bench_audit106.py healthy ROOT              # cell H (fresh cr10067)
    python benchmarks/bench_audit106.py lab ROOT [FAMILIES]       # cell L (fresh lab 10068)

``auto``: in project root ROOT, :data:`RECORD` simulated, then as docs/sweeps.md writes it
``run -m model=auto,mlr eval.mode=simulation,one_step plots=none`` (one parent run, 4 jobs),
``compare``, ``promote data.path=<record>`` (twice: the second registers nothing new),
``replay`` of the champion, ``export`` of it as ``c`` (+ check pack), ``st``, ``onnx``, the
compiled C fed the raw test files; per job its test figure in simulation mode against
``promote``'s "as deployed", replay's and the C's (µm, mean over targets).
``dvc``: CLONE is ``git clone /work/main CLONE`` at :data:`BASE` with bench_audit97's ``.venv/bin``
shims (the shared venv's python on the clone's ``src``); docs/dvc.md's three commands as written.
``models``: bench_audit105's cell M (bench_deploy88's cell: run -> replay -> plain -> promote ->
export st / onnx / C + pack -> the C fed the chain and the raw test files) on :data:`RECORD`
per family x :data:`WRAPPERS`.
``faults``: cr10066's ``mlr-none`` C (``stream --flags``) fed its first test file with one fault of
:data:`FAULTS` planted each from data row :data:`FAULT_ROW`, then the same model served on PORT
fed each fault's rows up to 20 past it as one block from a reset, and the HTTP faults of
:data:`HTTP_FAULTS`; per fault the exit / HTTP status, the message, the first flagged row and the
largest |correction - healthy correction| at the faulted row and after it (µm).
``healthy``: cr10067 ``run model=mlr``, ``monitor`` on the test runs, export C + pack, the C fed the
first raw test file (``--flags``) and its numpy mirror, bench_st93's ``trace`` (the ST block
stepped beside the C's mirror).
``lab``: seed 10068's swiss production campaign (bench_audit91's ``contract.csv``, 1441 rows at
60 s) written as ``export.tsv`` and ``export.parquet`` (:func:`write_export`) and compared with
the contract's rows (the gap's rows left out, the time kept) through bench_audit100's
``lab_against_contract``; then ``monitor`` of the init's config.

Records (fresh seeds of this brief, chosen before any was simulated)::

  cr10066   climate_room (no audit ran it; deploy88's cr9215 was 12 runs), 16 runs of 4-6 h,
            the last 20 % (3 runs) test: cells A, M, F
  cr10067   the same kind and size, another draw: cell H
  lab 10068 the lab's export.tsv / export.parquet: cell L

BAR (written and committed BEFORE seeds 10066-10068 were simulated; a BREAK is: a traceback or
exit 1, exit 0 on bad input taken silently, the deployed figure (promote's "as deployed", replay,
the C) differing from the scored one by more than 1 % unexplained by the monitor's events, a false
alarm on a healthy record, an unclear message (no file, column or row where one is at fault), a
docs command that fails as written)
-----------------------------------------------------------------------------------------------
A1. The sweep exits 0 with 4 child runs; auto's metrics.json says the hedge (campaign folds) where
    the train runs give >= 3 campaign folds; ``compare`` exits 0 ranking by validation; ``promote``
    exits 0, chooses by validation in simulation mode and says so where a one_step job is in the
    sweep; the champion's "as deployed" = replay = the C (raw test files) to 1 %, and = its
    job's simulation-mode test figure to 1 % (a difference the monitor's events explain noted);
    ``st`` exit 0, ``onnx`` exit 2 in one line; the second ``promote`` registers no new version.
D1. docs/dvc.md's ``dvc repro`` / ``dvc repro`` / ``dvc metrics show`` in a fresh clone exit 0, the
    second running no stage.
L1. export.tsv and export.parquet go in: ``init`` with no key reads each or refuses in one message
    naming the key (file, column, row); with at most the keys its refusals name: the time read
    across the daylight saving change as 60 s steps (no hour lost or added), the gap kept as a
    gap (not closed), the row written twice refused naming its row or left out and said, the
    bracketed units read as units (targets in µm, no unit text in a name's role), never a
    traceback, never a silent wrong value.
L2. Per family (mlr, lagbank) every figure (run, plain, replay, the C by ``rows`` and fed the raw
    bytes) = the contract's to 1e-6 µm (or a documented refusal, exit 2 in one line naming the
    line); ``monitor`` exit 0 with the contract's events.
M1. Per family x wrapper of cr10066 that runs: ``sim`` = ``replay`` = ``promo`` = ``C`` to 1 %
    (``dmax`` <= 0.01; a difference the monitor's events explain noted), ``cold`` = ``Craw`` to 1 %,
    pack 0, ``st`` 0; ``onnx`` exit 2 in one line, ``auto`` with a wrapper exit 2 in one line;
    no cell exits 1 or with a traceback; where ``ati`` / ``interval`` keep one model, the run
    says why.
F1. Each fault fed to the compiled C: exit 0 with the fault flagged (``--flags``' non-zero column
    at or after the faulted row) or said on stderr naming the line, or exit 2 naming the line
    (and the column where one is at fault); never a signal or exit 1; never a correction off
    healthy by > 1 µm at an unflagged row, never a non-finite correction.
F2. Each fault sent to the served model: 200 with the fault named in the answer's events, or 4xx
    naming the column (and the row where one is at fault; for a body that is no JSON, saying
    so); never 5xx, never a traceback in the body or on the server's stderr, never a non-finite
    correction, never corrections off healthy by > 1 µm without an event; concurrent requests
    of distinct sessions each answered as the same request alone (to 1e-9 µm); the server
    answers a healthy block as before after every fault.
H1. cr10067 (mlr, healthy): ``monitor`` 0 events; export C + pack 0; the C fed the raw test file
    exit 0 with 0 flagged rows, its mirror 0; the ST block 0 false flags and ST = the C's mirror
    to 1e-6 µm.
Each break: named with command, file, row and numbers; mended where small and clear (a test
failing on BASE, < 3 s of CPU, in the module of the code at fault), else listed for the lead with
the reason it was left.

Status: the bar above was committed in cbeebfcc before any of 10066-10068 was simulated; unchanged.
Harness changes after it (no rule, no figure chosen): cell L's contract is the whole record with
the gap's rows left out (``whole.csv`` kept), and, as both files' refusal of the row written twice
says to delete it, ``once.tsv`` / ``once_pq.parquet`` are the same files without the copy (the
files with it go through ``init`` alone); cell A's job listing read the sweep folder (its first
glob read a job's: its figures were read again from the jobs' metrics.json).  Probes by hand,
outside the bench (commands in the report): the served model of cell L's ``once`` across its gap,
``monitor.input=-`` of ``once.tsv``, unit and timestamp variants of ``once.tsv``.

Scored (2026-12-07, 08:36-09:30 UTC; 2 cores shared, load 5-12, every job ``nice``; 898240b4's
src, then this branch's mends where said):

A1 (cr10066, 13 train / 3 test runs): the sweep exit 0, 4 jobs, 0 failed; auto's E_Z "hedged
towards MLR by the nested weight 0.852 (5 campaign folds)" (E_X: ati 1.00, no hedge said);
``compare`` exit 0 (val_mode simulation for every job, test_mode each job's own); ``promote`` #1
exit 0, v1 @champion: "ranked by val_rmse of the simulation-mode validation (the deployed mode,
whatever eval.mode a run was scored in)", the auto simulation job (val 0.7449); #2 "already
registered, no new version".  As deployed 0.8984394 = replay 0.8984394 (0 events) = the C fed the
raw test files 0.8984394 = the job's test figure 0.8984394 (dmax 3.7e-16); pack 0; st 0; onnx exit
2 in one line.  A1 holds.
D1 (clone at 898240b4, shims): ``dvc repro`` exit 0 (simulate .. diagnose), again "Data and
pipelines are up to date.", ``dvc metrics show`` exit 0 (test_rmse 0.75043 / 1.42353 / 5.80191,
the README's table).  D1 holds.
L1-L2 (lab 10068): export.tsv and export.parquet: ``init`` exit 2, "file .../export.tsv, column
'time', line 603 (data row 602): duplicate time 2027-03-28T11:00:00+02:00 = 2027-03-28 09:00:00
UTC (same as row 601): ... delete the row written twice"; the Parquet's named the instant at the
first row's offset, "2027-03-28T10:00:00+01:00", a time the lab's clock never showed: MENDED
(335b2807, values._zoned_cell: as the TSV's).  Without the copy, ``init`` with no key: tab, the
bracketed units read (dX [µm] -> E_dX; mm, K, °F, um variants converted: test RMSE the same to
1e-9), the time across the change to summer time in 60 s steps, the 3 h gap a pause
(runs_at_pauses: true written, 2 runs, said).  mlr, lagbank: run, plain, replay, the C by rows and
fed the raw bytes = the contract's to 0 (mlr E_X 2.230013729, the C scored against the run's
first-sample reference; the Parquet's raw bytes refused by the C, documented); lagbank's replay
1.9195 vs run 1.8202 (+5.5 %, the contract's too): 4 "correction bounded" envelope events, said;
``monitor`` 0 events.  BREAKS: (1) ``monitor.input=-`` of once.tsv streamed one campaign, E_dX
1.494 um where its two runs give 1.685, the pause unsaid: MENDED (6617bef1, stdin._pause_runs);
(2) the served model across the gap (data rows 880-960 as one block): 2.82 um off the C, no event:
MENDED (a16ebcdc, pyfunc: a session starts a campaign at a pause of the model's ``pause_s_``, said; the C
from the registry gets TC_PAUSE_S from it too): 8.9e-16 um, event "new campaign".
M1 (cr10066, 898240b4's src but hammerstein-interval run again with the mend; every cell: run = sim
= replay = promo = C = cold = Craw to 7 digits, dmax <= 6.6e-15, pack 0, st 0, onnx 2, 0 events;
ati: mlr's E_X one interval with the ambient interaction; interval: mlr 5, hammerstein 4
intervals of E_X, the 13 train runs starting at 15.8-33.2 °C)::

  family        none       ati        interval
  mlr           1.110744   0.8876381  1.120702
  pcr           2.369369   1.567839   1.115048
  arx           1.112251   0.8028852  0.6697127
  lagbank       0.8209203  0.6747787  0.6387432
  hammerstein   0.8209203  0.6036422  0.7138839 (base: export c / st exit 2, below)
  arx_rf        0.9454528  0.5711252  0.5804958
  lstm          1.057008   0.8131621  1.01385
  auto          0.8984384  run exit 2 in one line (name ati in model.candidates): documented

BREAK: hammerstein-interval: export c and st exit 2, "a machine state's power starts at rest in
one model and steady in another; one exported power has one start" (one interval's model saw the
spindle stopped, another's not): MENDED (56270234, laws._powered: two powers, each with its start): pack 0,
st 0, C = replay 0.7138839.
F1-F2 (cr10066 mlr-none, T_headstock from C14's data row 200): C: nan / NaN / three empty cells
exit 0, flagged row 200 (dropout), re-admitted at 210/212; negperiod exit 0, time_read 2 at row
200, said, |dC| 0; adcmax (327.67, held) exit 0, out of range at row 200; |dC| <= 0.179 um, 0 at
unflagged rows, all finite.  By hand: stuck at 150 / 100 / 85 / 0 / -327.68 the same; a time of
NaN / nan / inf / empty: time_read 1; data.sample_period_s / resample_s / sim.generator's period
-60, 0, nan: exit 2 naming the key.  Served: every fault 200 with its event (a JSON NaN too);
a CSV body / truncated JSON / empty: 400 "Invalid input. Ensure that input is a valid JSON
formatted string", the next healthy block = healthy; 8 sessions at once = each alone (0 um);
two blocks of one session at once, 4 times: = in order; 0 tracebacks.  F1, F2 hold.
H1 (cr10067, mlr): monitor 0 events; export C + pack 0 (2.13e-14 um); the C --flags fed C14, C15,
C16: 0 flagged; the mirror 0; the ST 0 false flags, max |ST - C| 2.13e-14 um.  H1 holds.
"""

from __future__ import annotations

import io
import json
import os
import signal
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE), str(REPO / "tests")]
import bench_audit99  # noqa: E402
import bench_audit100  # noqa: E402
import bench_audit103  # noqa: E402
import bench_audit105  # noqa: E402
import bench_deploy88  # noqa: E402
from _cli import project_root, run_commands  # noqa: E402

BASE = "898240b4"
MAIN = Path("/work/main")
RECORD = "cr10066"
HEALTHY = "cr10067"
LAB_SEED = 10068
CLIMATE = ["sim=climate_room", "sim.generator.n_runs=16", "sim.generator.duration_h=[4.0,6.0]",
           "sim.generator.test_fraction=0.2"]
WRAPPERS = bench_audit105.WRAPPERS
FAULT_ROW = 200
FAULTS = ("nan_lower", "nan_upper", "empty", "negperiod", "adcmax")
ADC_MAX = "327.67"            # a 16-bit converter's full scale at 0.01 degC a count
HTTP_FAULTS = ("notjson", "truncated", "concurrent")


def simulated(root: Path, record: str) -> Path:
    """``record``'s runs under ROOT/data (made once)."""
    from bench_audit86b import stage

    data = root / "data" / record
    if not data.exists():
        rc, said = stage("simulate", *CLIMATE, f"seed={record[2:]}", f"data.path={data}")
        assert rc == 0, said
    return data


def cli(*args: str) -> subprocess.CompletedProcess:
    import bench_audit97

    return bench_audit97._cli(*args)


def _ends(done: subprocess.CompletedProcess, n: int = 12) -> str:
    return "\n    ".join((done.stdout + done.stderr).strip().splitlines()[-n:])


def auto(root: str) -> None:
    """Cell A (module doc)."""
    base = project_root(root, REPO / "conf")
    data = simulated(base, RECORD)
    done = cli("run", "-m", f"data.path={data}", "model=auto,mlr", "eval.mode=simulation,one_step",
               "plots=none")
    print(f"sweep exit {done.returncode}\n    {_ends(done, 20)}", flush=True)
    sweeps = sorted(p for p in (base / "reports" / "multirun").glob("*") if p.is_dir())
    sweep = sweeps[-1] if sweeps else None
    jobs = {}
    for metrics in sorted(sweep.rglob("metrics.json")) if sweep else []:
        over = (metrics.parent / ".hydra" / "overrides.yaml")
        said = over.read_text().replace("\n", " ") if over.exists() else metrics.parent.name
        targets = json.loads(metrics.read_text())["targets"]
        sim = np.mean([(m.get("test_simulation") or m["test"])["rmse"] for m in targets.values()])
        one = np.mean([m["test"]["rmse"] for m in targets.values()])
        hedge = {t: (m.get("auto") or {}).get("hedge") for t, m in targets.items() if m.get("auto")}
        jobs[metrics.parent] = sim
        print(f"  job {metrics.parent.name} {said}: test sim {sim:.7g} reported {one:.7g}; hedge "
              f"{str(hedge)[:300]}", flush=True)
    done = cli("compare")
    print(f"compare exit {done.returncode}\n    {_ends(done, 14)}", flush=True)
    for k in (1, 2):
        done = cli("promote", f"data.path={data}", f"out={base / f'promote{k}'}")
        print(f"promote #{k} exit {done.returncode}\n    {_ends(done, 14)}", flush=True)
    said = json.loads((base / "promote1" / "promote.json").read_text())
    cand = said["candidate"]
    shown = str({k: v for k, v in cand.items() if k != "params"})[:800]
    print(f"  promote.json keys {sorted(said)}; candidate {shown}", flush=True)
    uri = said["model_uri"]
    out = base / "champion"
    done = cli("replay", f"data.path={data}", f"replay.model={uri}", f"out={out}-replay")
    rep = {} if done.returncode else json.loads((out.parent / "champion-replay" / "replay.json").read_text())
    replay = np.mean([v["rmse"] for v in rep.get("targets", {}).values()]) if rep else np.nan
    print(f"replay exit {done.returncode}: rmse {replay:.7g}, events {len(rep.get('events', []))}",
          flush=True)
    for fmt in ("st", "onnx"):
        done = cli("export", f"export.model={uri}", f"export.format={fmt}", f"out={out}-{fmt}")
        print(f"export {fmt} exit {done.returncode}: {_ends(done, 2)}", flush=True)
    c_dir = out.parent / "champion-c"
    done = cli("export", f"export.model={uri}", "export.format=c", "export.check=true", f"data.path={data}",
               f"out={c_dir}")
    print(f"export c exit {done.returncode}: {_ends(done, 2)}", flush=True)
    if done.returncode:
        return
    subprocess.run(["gcc", "-O2", "compensator.c", "stream.c", "-lm", "-o", "stream"], cwd=c_dir, check=True)
    pack = subprocess.run(["sh", "check/check.sh"], cwd=c_dir, capture_output=True, text=True)
    from bench_audit86b import batch, test_frames

    frames = test_frames(data)
    job = _job_of(base, said)
    _, scored = batch(base, job / "model.pkl", data, [])           # the errors as run scores them
    targets = list(rep["targets"])
    measured = np.vstack([scored[c][targets].to_numpy(float) for c in frames])
    raw = np.vstack([bench_deploy88.raw_stream(c_dir, data / file) for file, _ in frames.values()])
    c_fig = bench_deploy88.rmse(measured, raw[:, :len(targets)])
    promo = cand["test_reported"]["rmse"]
    chosen = jobs.get(job, np.nan)
    print(f"pack exit {pack.returncode}; as deployed {promo:.7g}, replay {replay:.7g}, C raw {c_fig:.7g}, "
          f"the job {job.name} sim {chosen:.7g}; dmax "
          f"{max(abs(x - replay) / replay for x in (promo, c_fig, chosen)):.2g}",
          flush=True)


def _job_of(base: Path, promoted: dict) -> Path:
    """The sweep job folder of the promoted run (its ``out`` param)."""
    import mlflow

    mlflow.set_tracking_uri(f"sqlite:///{base}/mlruns/mlflow.db")
    run_id = promoted["candidate"].get("run_id") or promoted.get("run_id")
    return Path(mlflow.get_run(run_id).data.params["out"])


def dvc(word: str) -> None:
    """Cell D (module doc)."""
    import bench_audit97

    clone = Path(word).resolve()
    if not clone.exists():
        subprocess.run(["git", "clone", "-q", str(MAIN), str(clone)], check=True)
        subprocess.run(["git", "-C", str(clone), "checkout", "-q", BASE], check=True)
    bench_audit97.clone_of(str(clone))
    for cmd in (".venv/bin/dvc repro", ".venv/bin/dvc repro", ".venv/bin/dvc metrics show"):
        done = subprocess.run(["bash", "-c", cmd], cwd=clone, capture_output=True, text=True)
        print(f"{cmd}: exit {done.returncode}\n    {_ends(done, 8)}", flush=True)


def models(root: str, *chosen: str) -> None:
    """Cell M (module doc)."""
    base = project_root(root, REPO / "conf")
    simulated(base, RECORD)
    bench_audit105.RECORD = RECORD
    bench_audit105.simulated = lambda b, r: simulated(b, r)
    bench_audit105.models(root, *chosen)


def faulted_rows(frame: pd.DataFrame, fault: str, sensor: str, period: float) -> pd.DataFrame:
    """``frame`` (a test file's rows as text) with ``fault`` planted from data row FAULT_ROW:
    ``nan_lower`` / ``nan_upper`` the sensor's cell ``nan`` / ``NaN`` (one row); ``empty`` three
    empty cells; ``negperiod`` the time running backwards one period a row from there; ``adcmax``
    the sensor stuck at :data:`ADC_MAX` to the end."""
    out = frame.astype(object).copy()
    r = FAULT_ROW
    if fault == "nan_lower":
        out.loc[r, sensor] = "nan"
    elif fault == "nan_upper":
        out.loc[r, sensor] = "NaN"
    elif fault == "empty":
        out.loc[r:r + 2, sensor] = ""
    elif fault == "negperiod":
        t0 = float(frame.loc[r - 1, "time"])
        out.loc[r:, "time"] = [repr(t0 - period * (k + 1)) for k in range(len(out) - r)]
    elif fault == "adcmax":
        out.loc[r:, sensor] = ADC_MAX
    return out


def faults(root: str, port: str) -> None:
    """Cell F (module doc)."""
    base = project_root(root, REPO / "conf")
    data, cell = base / "data" / RECORD, base / "reports" / RECORD / "mlr-none"
    c_dir = cell.parent / "mlr-none-c"
    manifest = pd.read_csv(data / "campaigns.csv")
    file = data / manifest.loc[manifest.split == "test", "file"].iloc[0]
    frame = pd.read_csv(file, dtype=str, keep_default_na=False)
    period = float(np.median(np.diff(frame["time"].astype(float))))
    inputs = [c for c in frame.columns if not c.startswith("E_")]
    sensor = next(c for c in inputs if c.startswith("T_") and not c.startswith("T_amb"))

    def fed(rows: pd.DataFrame) -> tuple[subprocess.CompletedProcess, pd.DataFrame]:
        text = rows.to_csv(index=False)
        done = subprocess.run([str(c_dir / "stream"), "--flags"], input=text.encode(), capture_output=True)
        try:
            got = pd.read_csv(io.BytesIO(done.stdout)) if done.stdout.strip() else pd.DataFrame()
        except ValueError:
            got = pd.DataFrame()
        return done, got

    _, healthy = fed(frame)
    corr = [c for c in healthy.columns if c.startswith("C_")]
    flag_cols = [c for c in healthy.columns if c not in corr and c != "time"]
    first, _ = bench_audit105._first_flag(healthy, flag_cols)
    print(f"C healthy {file.name}: {len(healthy)} rows, flag columns {flag_cols}, first flagged {first}; "
          f"sensor {sensor}, row {FAULT_ROW}, period {period:g} s", flush=True)
    bench_audit105.FAULT_ROW = FAULT_ROW
    for fault in FAULTS:
        done, got = fed(faulted_rows(frame, fault, sensor, period))
        first, flagged = bench_audit105._first_flag(got, flag_cols) if len(got) else (None, None)
        ok = set(corr) <= set(got) and len(got) == len(healthy)
        at, after, quiet = (bench_audit105._off(got[corr].to_numpy(float), healthy[corr].to_numpy(float),
                                                flagged.to_numpy()) if ok else (np.nan,) * 3)
        said = {c: got.loc[first, c] for c in flag_cols if first is not None and got.loc[first, c] != 0}
        finite = bool(np.isfinite(got[corr].to_numpy(float)).all()) if set(corr) <= set(got) else "-"
        err = bench_audit103._ends(done.stderr.decode(errors="replace"))
        print(f"  C [{fault}] exit {done.returncode}: {err!r}"
              f"; {len(got)} rows; first flagged {first} {said}; |C - healthy| at {at:.3g} after {after:.3g} "
              f"after-unflagged {quiet:.3g} um; finite {finite}", flush=True)
    served(cell / "model.pkl", data, frame, inputs, sensor, healthy[corr].to_numpy(float), int(port),
           base / "faults", period)


def _json_block(rows: pd.DataFrame, inputs: list[str], session: str = "m1") -> str:
    """The block as a client writes it: text cells as JSON strings where they are no number
    (``nan`` / ``NaN`` kept as the client's strings), empty ones as null."""
    data = [[(None if v == "" else (float(v) if _number(v) else v)) for v in r]
            for r in rows[inputs].itertuples(index=False)]
    return json.dumps({"dataframe_split": {"columns": inputs, "data": data},
                       "params": {"session": session, "reset": True}})


def _number(v: str) -> bool:
    try:
        return np.isfinite(float(v))
    except ValueError:
        return False


def served(model: Path, data: Path, frame: pd.DataFrame, inputs: list[str], sensor: str,
           healthy_c: np.ndarray, port: int, scratch: Path, period: float) -> None:
    """Cell F2 (module doc)."""
    scratch.mkdir(exist_ok=True)
    end = FAULT_ROW + 20
    log = scratch / "serve.err"
    with log.open("w") as err:
        proc = subprocess.Popen(["nice", sys.executable, "-m", "thermocomp", "serve", f"serve.model={model}",
                                 f"serve.port={port}", f"data.path={data}"], stdout=err, stderr=err,
                                start_new_session=True)
    post = bench_audit100._post
    try:
        print(f"  serve up after {bench_audit99._wait_port(port, proc):.0f} s", flush=True)
        healthy_body = _json_block(frame.iloc[:end], inputs)
        for fault in ("healthy", *FAULTS, "nan_json"):
            rows = frame.iloc[:end] if fault in ("healthy", "nan_json") else \
                faulted_rows(frame, fault, sensor, period).iloc[:end]
            body = _json_block(rows, inputs)
            if fault == "nan_json":          # Python's json writes a NaN float as the bare NaN
                obj = json.loads(body)
                obj["dataframe_split"]["data"][FAULT_ROW][inputs.index(sensor)] = float("nan")
                body = json.dumps(obj)
            status, text = post(port, body.encode())
            print(f"  served [{fault}] {bench_audit105._said(status, text, healthy_c)}", flush=True)
        for fault in ("notjson", "truncated"):
            body = (frame.iloc[:5].to_csv(index=False) if fault == "notjson"
                    else healthy_body[:len(healthy_body) // 2])
            status, text = post(port, body.encode())
            print(f"  served [{fault}] HTTP {status}: {text[:300]!r}", flush=True)
            status, text = post(port, healthy_body.encode())
            print(f"    then healthy: {bench_audit105._said(status, text, healthy_c)[:120]}", flush=True)
        _concurrent(port, frame, inputs, end)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGTERM)
            proc.wait(timeout=60)
    text = log.read_text(errors="replace")
    print(f"  server stderr: {len(text.splitlines())} lines; tracebacks {text.count('Traceback')}",
          flush=True)


def _concurrent(port: int, frame: pd.DataFrame, inputs: list[str], end: int, n: int = 8) -> None:
    """n sessions, each a different slice of the file from a reset, posted alone then at once."""
    bodies = [_json_block(frame.iloc[k * 10:k * 10 + end], inputs, session=f"s{k}") for k in range(n)]
    alone = [bench_audit100._post(port, b.encode()) for b in bodies]
    together: list = [None] * n

    def send(k: int) -> None:
        together[k] = bench_audit100._post(port, bodies[k].encode())

    threads = [threading.Thread(target=send, args=(k,)) for k in range(n)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    worst, statuses = 0.0, []
    for (s1, t1), (s2, t2) in zip(alone, together):
        statuses.append((s1, s2))
        if s1 == s2 == 200:
            a = pd.DataFrame(json.loads(t1).get("predictions", json.loads(t1)))
            b = pd.DataFrame(json.loads(t2).get("predictions", json.loads(t2)))
            c = [k for k in a if k.startswith("C_")]
            worst = max(worst, float(np.max(np.abs(a[c].to_numpy(float) - b[c].to_numpy(float)))))
    print(f"  served [concurrent] {n} sessions: statuses (alone, together) {statuses}; max |together - "
          f"alone| {worst:.3g} um", flush=True)


def healthy(root: str) -> None:
    """Cell H (module doc)."""
    import bench_st93
    from bench_audit86b import stage

    base = project_root(root, REPO / "conf")
    data = simulated(base, HEALTHY)
    model = base / "reports" / HEALTHY / "mlr-none" / "model.pkl"
    if not model.exists():
        rc, said = stage("run", f"data.path={data}", "model=mlr", "plots=none", "track=false",
                         f"out={model.parent}")
        assert rc == 0, said
    bench_audit99.CUT[:] = []
    bench_st93.deployed_cell = lambda *_: bench_audit99._deployed_cell(data, model)
    bench_st93.trace(str(base), HEALTHY)
    c_dir = bench_audit99.monitored_and_exported(base / "reports" / HEALTHY, data, model, [])
    if c_dir is None:
        return
    manifest = pd.read_csv(data / "campaigns.csv")
    for name in manifest.loc[manifest.split == "test", "file"]:
        with (data / name).open("rb") as raw:
            fed = subprocess.run([str(c_dir / "stream"), "--flags"], stdin=raw, capture_output=True)
        got = pd.read_csv(io.BytesIO(fed.stdout)) if not fed.returncode else pd.DataFrame()
        flag_cols = [c for c in got.columns if not c.startswith("C_") and c != "time"]
        first, flagged = (bench_audit105._first_flag(got, flag_cols) if len(got)
                          else (None, pd.Series(dtype=bool)))
        print(f"  C --flags fed {name}: exit {fed.returncode}, {len(got)} rows; flagged rows "
              f"{int(flagged.sum())} (first {first}); {fed.stderr.decode(errors='replace').strip()[-300:]}",
              flush=True)
    bench_audit100.mirror_flags(data, model)


ZONE = "Europe/Berlin"
START_UTC = pd.Timestamp("2027-03-27 23:00:00", tz="UTC")     # 00:00 local, 2 h before the change
DUPLICATE_ROW = 600                                           # data row written twice
GAP = (900, 1080)                                             # data rows left out: 3 h at 60 s
LAB_NAMES = {"E_X": "dX [µm]", "E_Y": "dY [µm]", "S_spindle_rpm": "n_spindle [1/min]",
             "S_tool_rpm": "n_tool [1/min]", "S_door": "door [-]"}


def _export_name(column: str) -> str:
    return LAB_NAMES.get(column) or f"{column} [°C]"


def write_export(base: Path, seed: int) -> pd.DataFrame:
    """``contract.csv`` (bench_audit91's, its rows GAP left out, saved as ``truth.csv``) and the
    lab's ``export.tsv`` / ``export.parquet``: ``Timestamp`` local ISO-8601 with its offset (the
    change to summer time at 02:00 on 2027-03-28 inside), the bracketed names, data row
    DUPLICATE_ROW written twice; the truth's rows."""
    import bench_audit91

    if not (base / "whole.csv").exists():
        bench_audit91.lab_files(base, seed)
        (base / "contract.csv").rename(base / "whole.csv")
    rows = pd.read_csv(base / "whole.csv")
    rows = rows.drop(index=range(*GAP)).reset_index(drop=True)
    rows.to_csv(base / "contract.csv", index=False, float_format="%.17g")
    cols = [c for c in rows.columns if c != "time"]
    stamps = (START_UTC + pd.to_timedelta(rows["time"].round(), unit="s")).dt.tz_convert(ZONE)
    out = rows[cols].rename(columns=_export_name)
    out.insert(0, "Timestamp", stamps)
    dup = DUPLICATE_ROW - (GAP[1] - GAP[0] if DUPLICATE_ROW >= GAP[1] else 0)
    # the lab's files, and each with its copy deleted, as the reader's refusal tells the lab to
    for name, frame in (("export", pd.concat([out.iloc[:dup + 1], out.iloc[[dup]], out.iloc[dup + 1:]],
                                             ignore_index=True)), ("once", out)):
        text = frame.assign(Timestamp=frame["Timestamp"].map(lambda t: t.isoformat())).to_csv(
            sep="\t", index=False, float_format="%.17g", lineterminator="\n")
        (base / f"{name}.tsv").write_text(text, encoding="utf-8")
        frame.to_parquet(base / f"{name}{'' if name == 'export' else '_pq'}.parquet", index=False)
    out = frame
    lines = text.splitlines()
    print(f"wrote export.tsv / export.parquet: {len(out)} rows; {lines[0]!r}; row 1 {lines[1][:60]!r}; "
          f"around the change {[ln.split(chr(9))[0] for ln in lines[120:123]]}; the copy at data row "
          f"{dup + 2}", flush=True)
    return rows


def lab(root: str, families: str = "mlr,lagbank") -> None:
    """Cell L (module doc)."""
    import bench_audit91

    base = bench_audit91.lab_root(root, str(LAB_SEED))
    rows = write_export(base, LAB_SEED)
    for path in (base / "export.tsv", base / "export.parquet"):        # the copy in: init alone
        done = cli("init", str(path), f"out={base / path.stem}-{path.suffix[1:]}-init")
        print(f"== {path.name}: init exit {done.returncode}\n    {_ends(done, 6)}", flush=True)
    for path in (base / "once.tsv", base / "once_pq.parquet", base / "contract.csv"):
        print(f"== {path.name}", flush=True)
        if path.name != "contract.csv":
            bench_audit100.lab_against_contract(base, rows, path, families, _export_name)
        init = base / f"{path.stem}-init"
        conf = next((init / "conf" / "data").glob("*.yaml"), None) if init.exists() else None
        if conf is None:
            continue
        print("  init's data config:\n    " + "\n    ".join(conf.read_text().splitlines()[:40]), flush=True)
        search = [f"hydra.searchpath=[file://{init / 'conf'}]", f"data={conf.stem}",
                  "data.test_fraction=0.25"]
        model = base / f"{path.stem}-mlr" / "model.pkl"
        done = cli("monitor", *search, f"monitor.model={model}", "track=false", f"out={base / path.stem}-mon")
        mon = base / f"{path.stem}-mon" / "monitor.json"
        events = json.loads(mon.read_text()).get("events", []) if mon.exists() else []
        print(f"  monitor exit {done.returncode}: {len(events)} events {str(events)[:400]}\n    "
              f"{_ends(done, 4)}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"auto": auto, "dvc": dvc, "models": models, "faults": faults,
                                  "healthy": healthy, "lab": lab}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
