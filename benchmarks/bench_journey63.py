"""The journey after the model, as a lab makes it (session 63, journey63): sweep, compare,
promote, serve, twin/connect, export and its check pack, DVC, and bad input on that path.

    .venv/bin/python benchmarks/bench_journey63.py all DIR      # every step below, in DIR
    (or one step: sweep | serve | export | twin | dvc | bad DIR; each after sweep)

Everything from the docs as written (README, docs/sweeps.md, dvc.md, to-the-machine.md), on the
vendored measured record (``data=fl_thermal``: one CSV, its last 10 % the test part, which
continues the train part) and on a simulated record nobody used (``simulate
sim=swiss_lathe_door seed=6311``: 80 h calibration train, 24 h production test, 1-min log),
the MLflow store ``DIR/mlruns/mlflow.db`` (never the project's), ports 5763/5764/4863.

1. ``run -m model=mlr,arx,lagbank eval.mode=simulation,one_step hydra/launcher=joblib
   plots=none`` on the lathe (``model=mlr,pcr,lagbank`` on fl_thermal), ``compare``, ``promote``
   (alias ``champion``), promote's "as deployed" figures against the chosen run's test figures.
2. ``serve`` the champion (and fl_thermal's version with ``continues``), the test file streamed
   through it in one block and row by row; ``export export.format=c export.check=true``, ``cc``,
   ``sh check/check.sh``; ``twin`` + ``connect`` (lockstep) on the champion.
3. ``dvc repro`` in a clone of the repository (its ``.venv`` a link): again; a model param
   changed; an eval param changed; both set back; ``metrics.json`` against a direct ``run``.
4. Bad input: promote without a store / without a sweep; a sweep with failing jobs, compared
   and promoted; the data moved; the champion on another record; a served block with a column
   missing, renamed, a text value, a text time.

Measured (2026-12-01, every step once, 2 shared cores, CPU s user + sys):

    sweep, lathe (6 jobs)      17.2 + 1.7 s   val_rmse lagbank 1.074, mlr 1.338, arx 1.487 (both
                                              modes alike: the simulation-mode validation ranks)
    sweep, fl_thermal (6 jobs) 20.0 + 1.9 s   val_rmse lagbank 6.566, mlr 7.613, pcr 9.662
    promote (lathe)             5.6 + 0.9 s   lagbank, eval.mode=simulation run: as deployed
        rmse 1.0776439473893116 = the run's 1.0776439473893116 (rms reduction, E_P95 within
        1e-14); the one_step run of the same lagbank promoted: as deployed 1.0776 (its own
        one_step test 0.7075: promote streams in simulation), "already champion: version 1"
    promote (fl_thermal)        5.0 + 0.9 s   lagbank: as deployed 4.782947981877418, run
        4.782947981877416; version 2 registered, champion stays (another dataset_hash)
    served champion (lathe)    |served - replay| 0 um (one block of 1441 rows and row by row),
        RMSE 1.2301 / 0.9252 um = run's 1.23 / 0.93 (replay rmse_batch 1.2300997603164374);
        |served + run's model column| <= 5.0e-5 um (the residual CSV's 6 digits); replay's
        |stream - batch| 4.3e-14 / 2.1e-14 um
    served fl_thermal v2       test part with "continues": "spindle_test_train": |served -
        replay| 0 um over 1112 rows x 5 channels
    export + pack (lathe)       3.5 + 0.8 s   check passes, 1441 rows, largest 1.63e-13 um
    export + pack (fl v2)       5.8 + 0.5 s   check passes (gcc -O2), 11,115 rows (10,003 of
        lead-in), largest 4.85e-13 um
    twin + connect (lathe)      connect 6.4 + 1.0 s   twin's offsets = -C_<axis> of the pack
        exactly (0 um), RMS 28.136 -> 1.230 um (E_X), 20.308 -> 0.925 (E_Y) = replay's
    dvc repro, clean clone     28.3 + 4.2 s   7 stages; again: nothing (0.9 + 0.1 s);
        metrics.json = a direct `run` bit for bit (fit_time_s apart: evaluate has none);
        mlr fit_intercept=false: train, evaluate, diagnose (15.6 + 2.0 s); eval
        validation_folds 5 -> 4: evaluate alone (6.5 + 0.9 s); both set back: train from
        DVC's cache, evaluate and diagnose rerun (their outs are cache: false; 13.1 + 1.6 s),
        test and validation RMSE = the direct run's to 0
    bad input                   every refusal exit 2, no output folder written; before the
        mends: a sweep's failed jobs unsaid by compare / promote; the champion replayed on
        fl_thermal named 'spindle_test.csv/spindle_test.csv' and one column
        'T_amb,T_headstock,...'; a served text value named its column but not its row; a served
        text time said 'file <stdin>'; a sweep whose every job failed was refused as 'no child
        runs'; a replay of the lag-bank champion was tracked as 'mlr-fl_thermal'
    `all` (this script, run again after the mends) 229.3 s CPU, the commands included; it
    printed the figures above again (the seed-6311 record digests alike wherever written)
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import numpy as np
import pandas as pd
from cpu import cpu_seconds

ROOT = Path(__file__).resolve().parents[1]
ENV = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
LATHE = ["sim=swiss_lathe_door", "seed=6311"]
SWEEPS = {"lathe": "model=mlr,arx,lagbank", "fl": "model=mlr,pcr,lagbank"}


def tc(*args, check=True, **kw) -> subprocess.CompletedProcess:
    """``.venv/bin/thermocomp <args>`` (this checkout's code first), its output captured."""
    proc = subprocess.run([str(ROOT / ".venv/bin/thermocomp"), *map(str, args)], env=ENV,
                          cwd=ROOT, capture_output=True, text=True, **kw)
    if check and proc.returncode:
        raise SystemExit(f"thermocomp {' '.join(map(str, args))}: exit {proc.returncode}\n"
                         f"{proc.stderr[-2000:]}")
    return proc


def store(d: Path) -> str:
    return f"tracking_uri=sqlite:///{d / 'mlruns' / 'mlflow.db'}"


def data_of(d: Path, which: str) -> list[str]:
    return [f"data.path={d / 'swiss_lathe_door'}"] if which == "lathe" else ["data=fl_thermal"]


def sweep(d: Path) -> None:
    """Simulate, sweep both records, compare, promote; as deployed against the chosen run."""
    tc("simulate", *LATHE, f"data.path={d / 'swiss_lathe_door'}")
    for which, models in SWEEPS.items():
        tc("run", "-m", models, "eval.mode=simulation,one_step", *data_of(d, which),
           "hydra/launcher=joblib", "plots=none", store(d), f"hydra.sweep.dir={d / ('sweep-' + which)}",
           check=False)
        tc("compare", store(d), f"compare.sweep={d / ('sweep-' + which)}")
        tc("promote", *data_of(d, which), store(d), f"compare.sweep={d / ('sweep-' + which)}",
           f"out={d / ('promote-' + which)}")
        report = json.loads((d / f"promote-{which}" / "promote.json").read_text())
        table = pd.read_csv(d / f"sweep-{which}" / "compare.csv").set_index("run_id")
        deployed, run = report["candidate"]["figures"]["rmse"], float(table.loc[report["run_id"], "rmse"])
        print(f"{which}: promoted {table.loc[report['run_id'], 'model']} "
              f"({table.loc[report['run_id'], 'settings']}), version {report['version']}: as "
              f"deployed rmse {deployed!r}, the run's {run!r} ({report['reason']})")


def _post(url: str, frame: pd.DataFrame, params: dict) -> pd.DataFrame:
    body = {"dataframe_split": {"columns": list(frame.columns),
                                "data": frame.astype(object).where(frame.notna(), None).values.tolist()},
            "params": params}
    req = urllib.request.Request(url, json.dumps(body).encode(), {"Content-Type": "application/json"})
    with urllib.request.urlopen(req) as answer:
        return pd.DataFrame(json.load(answer)["predictions"])


def _served(d: Path, model: str, port: int):
    """A started ``thermocomp serve`` of ``model`` (a Popen), once it answers."""
    proc = subprocess.Popen([str(ROOT / ".venv/bin/thermocomp"), "serve", f"serve.model={model}",
                             f"serve.port={port}", store(d)], env=ENV, cwd=ROOT,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    for _ in range(120):
        try:
            urllib.request.urlopen(f"http://127.0.0.1:{port}/health", timeout=1)
            return proc
        except OSError:
            time.sleep(0.5)
    proc.send_signal(signal.SIGTERM)
    raise SystemExit(f"serve {model}: no answer on port {port}")


def export(d: Path) -> None:
    """The champion (lathe) and version 2 (fl_thermal) as C with their check packs, built, checked."""
    for which, model in (("lathe", "@champion"), ("fl", "/2")):
        out = d / f"code-{which}"
        tc("export", f"export.model=models:/thermocomp-compensator{model}", *data_of(d, which),
           "export.format=c", "export.check=true", f"out={out}", store(d))
        subprocess.run("cc -O2 compensator.c stream.c -lm -o stream", shell=True, cwd=out, check=True)
        done = subprocess.run(["sh", "check/check.sh"], cwd=out, capture_output=True, text=True)
        print(which, "check:", done.returncode, done.stdout.strip().splitlines()[-1],
              done.stderr.strip()[-160:])


def serve(d: Path) -> None:
    """The served champion against the pack's expected corrections (replay's), in one block and
    row by row; fl_thermal's version fed its test part with ``continues``."""
    expected = pd.read_csv(d / "code-lathe/check/production/expected.csv")
    rows = pd.read_csv(d / "swiss_lathe_door/production.csv")
    server = _served(d, "models:/thermocomp-compensator@champion", 5763)
    try:
        url = "http://127.0.0.1:5763/invocations"
        whole = _post(url, rows, {"session": "block", "reset": True})
        single = pd.concat([_post(url, rows.iloc[[i]], {"session": "rows", "reset": i == 0})
                            for i in range(len(rows))], ignore_index=True)
        for c in ("C_X", "C_Y"):
            print(f"lathe {c}: max |served - replay| block {np.abs(whole[c] - expected[c]).max():.3g}"
                  f", rows {np.abs(single[c] - expected[c]).max():.3g} um")
    finally:
        server.send_signal(signal.SIGTERM)
        server.wait()
    pack = d / "code-fl/check/spindle_test_test"
    lead = json.loads((d / "code-fl/check/check.json").read_text())["campaigns"][0]["lead_in_rows"]
    server = _served(d, "models:/thermocomp-compensator/2", 5764)
    try:
        test = pd.read_csv(pack / "rows.csv").iloc[lead:]
        got = _post("http://127.0.0.1:5764/invocations", test,
                    {"session": "fl", "continues": "spindle_test_train"})
        want = pd.read_csv(pack / "expected.csv").iloc[lead:].reset_index(drop=True)
        worst = max(np.abs(got[c] - want[c]).max() for c in want.columns if c.startswith("C_"))
        print(f"fl_thermal: max |served - replay| {worst:.3g} um over {len(test)} rows")
    finally:
        server.send_signal(signal.SIGTERM)
        server.wait()


def twin(d: Path) -> None:
    """The lathe's test campaign over OPC UA, the champion as the client, in lockstep."""
    server = subprocess.Popen([str(ROOT / ".venv/bin/thermocomp"), "twin", *data_of(d, "lathe"),
                               "twin.port=4863", "twin.speed=100", "twin.lockstep=true",
                               f"out={d / 'twin'}", store(d)], env=ENV, cwd=ROOT,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(3)
    tc("connect", "connect.endpoint=opc.tcp://127.0.0.1:4863",
       "connect.model=models:/thermocomp-compensator@champion", *data_of(d, "lathe"),
       f"out={d / 'connect'}", store(d))
    server.wait(timeout=120)
    report = json.loads((d / "twin/twin.json").read_text())
    expected = pd.read_csv(d / "code-lathe/check/production/expected.csv")
    for t, figures in report["targets"].items():
        offsets = np.asarray(report["offsets"][t])
        print(f"twin {t}: RMS {figures['rms_uncompensated']:.3f} -> {figures['rms_compensated']:.3f} um,"
              f" max |offset + C| {np.abs(offsets + expected['C_' + t[2:]]).max():.3g} um")


def dvc(d: Path) -> None:
    """``dvc repro`` in a clone: from clean, again, a model and an eval param, set back."""
    clone = d / "clone"
    subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
    (clone / ".venv").symlink_to(ROOT / ".venv")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}

    def repro(label: str) -> None:
        done = subprocess.run([str(clone / ".venv/bin/dvc"), "repro"], cwd=clone, env=env,
                              capture_output=True, text=True)
        ran = [ln.split("'")[1] for ln in done.stdout.splitlines() if ln.startswith("Running stage")]
        print(f"dvc repro ({label}): exit {done.returncode}, ran {ran or 'nothing'}")

    repro("clean clone")
    repro("again")
    subprocess.run([str(clone / ".venv/bin/thermocomp"), "run", f"out={d / 'direct'}",
                    f"model_path={d / 'direct/model.pkl'}", "track=false"], cwd=clone, env=env,
                   capture_output=True, check=True)
    staged = json.loads((clone / "reports/default/metrics.json").read_text())
    direct = json.loads((d / "direct/metrics.json").read_text())
    direct.pop("fit_time_s", None)
    print("metrics.json = direct run's:", staged == direct)
    for conf, old, new in (("conf/model/mlr.yaml", "fit_intercept: true", "fit_intercept: false"),
                           ("conf/eval/default.yaml", "validation_folds: 5 ", "validation_folds: 4 ")):
        path = clone / conf
        path.write_text(path.read_text().replace(old, new))
        repro(f"{conf}: {new}")
    subprocess.run(["git", "checkout", "conf/"], cwd=clone, check=True)
    repro("set back")


BAD = {
    "promote, no store": ["promote", "tracking_uri=sqlite:///{d}/none/mlflow.db"],
    "promote, data moved": ["promote", "data.path={d}/moved", "compare.sweep={d}/sweep-lathe"],
    "replay, the champion on another record": [
        "replay", "replay.model=models:/thermocomp-compensator@champion", "data=fl_thermal"],
    "export, the champion's data moved": [
        "export", "export.model=models:/thermocomp-compensator@champion", "export.check=true",
        "data.path={d}/moved"],
}


def bad(d: Path) -> None:
    """Each refusal: its exit status, its line, and that it wrote no output folder."""
    for what, args in BAD.items():
        out = d / ("bad-" + what.split(",")[0])
        args = [a.format(d=d) for a in args]
        uri = [] if any(a.startswith("tracking_uri=") for a in args) else [store(d)]
        proc = tc(*args, *uri, f"out={out}", check=False)
        print(f"{what}: exit {proc.returncode}, output written: {out.exists()}\n    "
              f"{proc.stderr.strip().splitlines()[-1][:300]}")
    proc = tc("run", "-m", "model=mlr,arx", f"data.path={d / 'swiss_lathe_door'},{d / 'moved'}",
              "plots=none", "eval.validation=false", store(d), f"hydra.sweep.dir={d / 'sweep-bad'}",
              check=False)
    shown = tc("compare", store(d), f"compare.sweep={d / 'sweep-bad'}").stdout.splitlines()[0]
    print(f"sweep with failing jobs: exit {proc.returncode}; compare: {shown[:110]}")


STEPS = {"sweep": sweep, "export": export, "serve": serve, "twin": twin, "dvc": dvc, "bad": bad}


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 2 or argv[0] not in (*STEPS, "all"):
        print(__doc__.split("\n\n")[1])
        return 2
    d = Path(argv[1]).resolve()
    d.mkdir(parents=True, exist_ok=True)
    for name in STEPS if argv[0] == "all" else [argv[0]]:
        STEPS[name](d)
    print("CPU s (user + sys, with the commands run):", round(cpu_seconds(children=True), 1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
