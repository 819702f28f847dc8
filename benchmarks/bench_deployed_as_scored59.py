"""What is deployed against what was scored, per family x wrapper (stop 59; prints a table).

A stranger's route, in a scratch project root (``THERMOCOMP_ROOT``, the repository's ``conf/``
linked in; nothing is written under the checkout): ``simulate`` a cut-short ``climate_room``
record (its runs start at their own ambient levels, so ``ati=cmeans`` applies), then per family
(``mlr``, ``pcr``, ``arx``, ``arx_rf``, ``lagbank``, ``hammerstein``, ``lstm`` small, ``auto``
without ``lstm``) x wrapper (none, ``ati=cmeans``; the CLI has no other per-interval wrapper):

``run`` -> ``replay`` of its ``model.pkl`` -> ``promote promote.run_id=<run> promote.force=true``
-> ``export export.model=<the promoted version> export.format=c|st|json`` (every format the CLI
offers; ``onnx`` is refused by design) -> the exported artefact stepped over the test campaigns:
the C compiled with ``gcc`` and fed the campaigns' CSV, the Structured Text through the test
suite's transpiler (``tests/shell/test_export.py``), ``compensator.json`` through the numpy
reference (``Simulator``).  Columns (µm):

- ``run``: mean over targets of ``metrics.json``'s test RMSE (what ``run`` scored);
- ``C-run``: max |C correction + run's batch prediction| over the test rows (0: deployed as
  scored; the deployed compensator is the adaptive one, whose guard may bound it);
- ``C-ST``, ``C-json``: max |difference| between the artefacts;
- ``C rmse`` against ``promote``'s ``test_reported`` RMSE ("as deployed") and ``replay``'s.

Run: ``.venv/bin/python benchmarks/bench_deployed_as_scored59.py [ROOT] [FAMILY ...]``
(ROOT default ``/tmp/deploy59-bench``, made where missing: made anew until review96).  Measured
2026-11-30 (stop 59, 166 s of CPU,
2 shared cores; climate_room seed 5901, 12 runs of 3-4 h, test C10-C12 starting at 26.4 / 23.2 /
30.0 °C ambient)::

    cell               run   batch  replay promoted  C rmse     C-run   C-ST    C-json
    mlr-none          1.69    1.69    1.69    1.69    1.69   1.42e-14      0  1.78e-14
    mlr-ati          0.917   0.917   0.917   0.917   0.917   1.42e-14      0  1.42e-14
    pcr-none           2.3     2.3     2.3     2.3     2.3   1.07e-14      0  7.11e-15
    pcr-ati           1.76    1.76    1.76    1.76    1.76   1.42e-14      0  1.07e-14
    arx-none          1.89    1.89    1.89    1.89    1.89   1.42e-14      0  1.42e-14
    arx-ati          0.996   0.996   0.996   0.996   0.996   1.07e-14      0  1.07e-14
    lagbank-none      1.91    1.91    1.91    1.91    1.91   3.94e-13      0  3.73e-13
    lagbank-ati      0.636   0.636   0.636   0.636   0.636   1.07e-13      0  8.17e-14
    hammerstein-none  1.91    1.91    1.91    1.91    1.91   3.94e-13      0  3.73e-13
    hammerstein-ati  0.636   0.636   0.636   0.636   0.636   1.07e-13      0  8.17e-14
    arx_rf-none       1.93    1.93    1.93    1.93    export refused (exit 2, names what exports)
    arx_rf-ati           1       1       1       1    export refused
    lstm-none         1.66    1.66    1.66    1.66    export refused
    lstm-ati         0.916   0.916   0.916   0.916    export refused
    auto-none         1.07    1.07    1.07    1.07    1.07   3.91e-14      0  4.62e-14
    auto-ati          run refused (exit 2): ati is auto's candidate (model.candidates), not its wrapper

Every ATI cell kept one interval with its interaction (``ati (any A0 +interaction)``);
auto kept ``blend mlr 0.78 + arx 0.05 + lagbank 0.06 + ati 0.11`` for E_X and the ATI model
for E_Z; ``hammerstein`` is the lag bank here (its CV took no power of the spindle speeds).
``run`` (metrics.json), the batch prediction of ``model.pkl``, ``replay``, ``promote``'s "as
deployed" figure and the exported C agree to the printed digit in every cell that exports; the
healthy test runs raised no event of the adaptive compensator (``replay.json``: 0 events,
0 exclusions over 10.2 h in every cell).
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

REPO = Path(__file__).resolve().parents[1]
ROOT = Path(sys.argv[1]) if len(sys.argv) > 1 and "/" in sys.argv[1] else Path("/tmp/deploy59-bench")
os.environ["THERMOCOMP_ROOT"] = str(ROOT)          # before thermocomp resolves its root
sys.path[:0] = [str(REPO / "tests"), str(REPO / "tests" / "shell")]

from _cli import project_root  # noqa: E402

from test_export import StructuredText  # noqa: E402  (the suite's ST transpiler)
from thermocomp.apps.deploy.export import Simulator  # noqa: E402
from thermocomp.apps.deploy.export.statespace import StateSpace  # noqa: E402
from thermocomp.shell.cli import main  # noqa: E402
from thermocomp.shell.model_store import load_model  # noqa: E402

SIM = ["sim=climate_room", "seed=5901", "sim.generator.n_runs=12", "sim.generator.duration_h=[3.0,4.0]",
       "sim.generator.test_fraction=0.25"]
FAMILIES = {
    "mlr": [], "pcr": [], "arx": [], "lagbank": [], "hammerstein": [],
    "arx_rf": ["model.estimator.forest.n_estimators=10", "model.estimator.state_column=S_spindle_rpm"],
    "lstm": ["model.estimator.max_epochs=3", "model.estimator.hidden_size=4", "model.estimator.chunk=16"],
    "auto": ["model.candidates=[mlr,pcr,arx,lagbank,hammerstein,ati]"],
}
WRAPPERS = {"none": [], "ati": ["ati=cmeans"]}
FORMATS = ("c", "st", "json")


def stage(*args: str) -> tuple[int, str]:
    """``thermocomp <args>`` in process; (exit status, the last line said on stderr)."""
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        try:
            rc = main(list(args))
        except SystemExit as exc:          # a refusal may exit
            rc = int(exc.code or 0)
    lines = [x for x in err.getvalue().splitlines() if x.strip()]
    return rc, lines[-1] if lines else ""


def last_run_id() -> str:
    import mlflow

    mlflow.set_tracking_uri(f"sqlite:///{ROOT}/mlruns/mlflow.db")
    runs = mlflow.search_runs(experiment_names=["thermocomp"], order_by=["start_time DESC"],
                              max_results=1, filter_string="tags.stage = 'run'")
    return str(runs.iloc[0]["run_id"])


def test_campaigns(data: Path) -> dict[str, pd.DataFrame]:
    manifest = pd.read_csv(data / "campaigns.csv")
    return {r.campaign: pd.read_csv(data / r.file) for r in manifest.itertuples() if r.split == "test"}


def batch(model: Path, data: Path) -> tuple[dict, dict]:
    """run's test predictions and the errors it scores them against (in the model's frame: the
    change since the first sample where referenced), per test campaign, read as ``run`` reads
    them (the manifest's ambient, the reference)."""
    from hydra import compose, initialize_config_dir

    from thermocomp.shell.source import read_streamed

    with initialize_config_dir(config_dir=str(ROOT / "conf"), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[f"data.path={data}", "track=false"])
    ds, _, test_ids, _ = read_streamed(cfg)
    comp = load_model(model)
    tests = {c: ds.campaigns[c] for c in test_ids}
    return comp.predict(tests), comp.measured(tests)


def compiled(folder: Path, tests: dict, inputs: list[str]) -> np.ndarray:
    subprocess.run(["gcc", "-O2", "compensator.c", "stream.c", "-lm", "-o", "stream"], cwd=folder,
                   check=True, capture_output=True)
    parts = [df[["time", *inputs]].to_csv(index=False, float_format="%.17g") for df in tests.values()]
    text = parts[0] + "".join("\n" + p.split("\n", 1)[1] for p in parts[1:])
    out = subprocess.run([str(folder / "stream")], input=text, text=True, capture_output=True, check=True)
    return pd.read_csv(io.StringIO(out.stdout)).to_numpy(float)


def stepped(step, reset, tests: dict, inputs: list[str]) -> np.ndarray:
    rows = []
    for df in tests.values():
        reset()
        for k, (u, t) in enumerate(zip(df[inputs].to_numpy(float), df["time"])):
            rows.append(step(u, t, k == 0))
    return np.array(rows, float)


def cell(family: str, wrapper: str, data: Path) -> dict:
    name = f"{family}-{wrapper}"
    out = ROOT / "reports" / name
    rc, said = stage("run", f"data.path={data}", f"out={out}", "plots=none", f"model={family}",
                     *FAMILIES[family], *WRAPPERS[wrapper])
    if rc:
        return {"cell": name, "note": f"run exit {rc}: {said}"}
    metrics = json.loads((out / "metrics.json").read_text())
    targets = list(metrics["targets"])
    row = {"cell": name, "run": np.mean([metrics["targets"][t]["test"]["rmse"] for t in targets])}
    tests = test_campaigns(data)
    predicted, scored = batch(out / "model.pkl", data)
    measured = np.vstack([scored[c][targets].to_numpy(float) for c in tests])
    run_pred = np.vstack([predicted[c][targets].to_numpy(float) for c in tests])
    row["batch"] = np.mean(np.sqrt(np.mean((measured - run_pred) ** 2, axis=0)))
    rc, said = stage("replay", f"data.path={data}", f"out={out}-replay", f"replay.model={out / 'model.pkl'}")
    if not rc:
        rep = json.loads((out.parent / f"{name}-replay" / "replay.json").read_text())["targets"]
        row["replay"] = np.mean([rep[t]["rmse"] for t in targets])
    rc, said = stage("promote", f"data.path={data}", f"out={out}-promote",
                     f"promote.run_id={last_run_id()}", "promote.force=true")
    if rc:
        return {**row, "note": f"promote exit {rc}: {said}"}
    promoted = json.loads((out.parent / f"{name}-promote" / "promote.json").read_text())
    row["promoted"] = promoted["candidate"]["test_reported"]["rmse"]
    uri = promoted["model_uri"]
    for fmt in FORMATS:
        rc, said = stage("export", f"export.model={uri}", f"export.format={fmt}", f"out={out}-{fmt}")
        if rc:
            return {**row, "note": f"export exit {rc}: {said}"}
    spec = json.loads((out.parent / f"{name}-json" / "compensator.json").read_text())
    inputs, order = spec["inputs"], spec["targets"]
    got_c = compiled(out.parent / f"{name}-c", tests, inputs)
    fb = StructuredText((out.parent / f"{name}-st" / "compensator.st").read_text())
    got_st = stepped(fb, lambda: None, tests, inputs)
    sim = Simulator(StateSpace.from_dict({k: v for k, v in spec.items() if k != "provenance"}))
    got_json = stepped(lambda u, t, first: sim.step(u, t), sim.reset, tests, inputs)
    run_order = [targets.index(t) for t in order]
    row["C-run"] = float(np.max(np.abs(got_c + run_pred[:, run_order])))
    row["C-ST"] = float(np.max(np.abs(got_c - got_st)))
    row["C-json"] = float(np.max(np.abs(got_c - got_json)))
    row["C rmse"] = float(np.mean(np.sqrt(np.mean((measured[:, run_order] + got_c) ** 2, axis=0))))
    laws = spec["provenance"].get("laws") or {}
    return {**row, "note": ", ".join(f"{t}: {law}" for t, law in laws.items())}


def main_bench() -> None:
    project_root(str(ROOT), REPO / "conf")      # kept: made anew until review96
    data = ROOT / "data" / "cr"
    rc, said = stage("simulate", *SIM, f"data.path={data}")
    assert rc == 0, said
    chosen = [a for a in sys.argv[1:] if a in FAMILIES] or list(FAMILIES)
    rows = [cell(f, w, data) for f in chosen for w in WRAPPERS]
    cols = ["run", "batch", "replay", "promoted", "C rmse", "C-run", "C-ST", "C-json"]
    print(f"{'cell':<18}" + "".join(f"{c:>10}" for c in cols) + "  note")
    for r in rows:
        cells = "".join(f"{r[c]:>10.3g}" if c in r else f"{'-':>10}" for c in cols)
        print(f"{r['cell']:<18}{cells}  {r.get('note', '')}")


if __name__ == "__main__":
    main_bench()
