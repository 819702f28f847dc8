"""What is deployed against what was scored, every family x wrapper, on fresh records (stop 86,
audit86b; issue 34's "what is deployed = what was scored").

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_audit86b.py sweep ROOT [RECORD|FAMILY ...]   # the table below

``sweep``: in a scratch project root ROOT (made anew, the tree's ``conf/`` linked in;
``THERMOCOMP_ROOT``), per record of :data:`RECORDS` (``simulate`` with this stop's seeds) and per
family (:data:`FAMILIES`) x wrapper (none, ``ati=cmeans``: the only wrapper ``conf/`` holds; the
door is a state input of ``arx_rf``, a diagnosed model is ``diagnose``'s, not ``run``'s):
``run`` -> ``replay`` of its ``model.pkl`` -> ``promote promote.run_id=<run> promote.force=true``
-> ``export`` of the promoted version as C (``export.check=true``: its check pack built and run,
``sh check/check.sh``) and as ``compensator.json`` stepped through the numpy reference. Then the
faults (:data:`FAULTS`) written into a copy of the record's test campaigns and ``replay``ed
through the same ``model.pkl``.  Columns (µm, mean over targets): ``run`` metrics.json's test
RMSE; ``batch`` model.pkl's batch prediction scored as run scores it; ``replay`` replay.json's;
``promo`` promote.json's "as deployed" (``candidate.test_reported``); ``C`` the compiled C's
RMSE; ``C+run`` max |C correction + batch prediction|; ``C-json`` max |C - json|; ``pack``
check.sh's exit; ``cpu`` the cell's CPU s (this process, user + sys).

The bar (written before scoring): every exporting cell has replay = run = promo to 1 %, C+run
<= 1e-9 µm, its pack passing; every fault a clear outcome (exit 0 with finite figures and, for
a frozen / jumping sensor, the adaptive compensator's event, or exit 2 naming file / column /
row), never exit 1 or a traceback.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from cpu import cpu_seconds  # noqa: E402

# this stop's seeds (9031-9045): a climate room (12 runs at their own ambient: ATI applies) and
# one long shop-floor record whose test campaign continues the train one (cut by its test_fraction)
RECORDS = {
    "cr9031": ["sim=climate_room", "seed=9031", "sim.generator.n_runs=12",
               "sim.generator.duration_h=[3.0,4.0]", "sim.generator.test_fraction=0.25"],
    "lr9032": ["sim=long_record", "seed=9032", "sim.generator.duration_days=3.0",
               "sim.generator.test_fraction=0.2"],
}
RUN_EXTRA = {"lr9032": ["data.reference=none"]}
FAMILIES = {
    "mlr": [], "pcr": [], "arx": [], "lagbank": [], "hammerstein": [],
    "arx_rf": ["model.estimator.forest.n_estimators=10", "model.estimator.state_column=S_spindle_rpm"],
    "lstm": ["model.estimator.max_epochs=3", "model.estimator.hidden_size=4", "model.estimator.chunk=16"],
    "auto": ["model.candidates=[mlr,pcr,arx,lagbank,hammerstein,ati]"],
}
WRAPPERS = {"none": [], "ati": ["ati=cmeans"]}
FAULTS = ("frozen", "nan_row", "jump")
FAULT_CELLS = ("mlr-none", "arx-ati", "auto-none")


def stage(*args: str) -> tuple[int, str]:
    """``thermocomp <args>`` in process; (exit status, the last line said on stderr)."""
    from thermocomp.shell.cli import main

    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        try:
            rc = main(list(args))
        except SystemExit as exc:
            rc = int(exc.code or 0)
        except Exception as exc:  # noqa: BLE001  (what a user would see as a traceback)
            rc, err = 99, io.StringIO(f"traceback: {type(exc).__name__}: {exc}")
    lines = [x for x in err.getvalue().splitlines() if x.strip()]
    return rc, lines[-1] if lines else ""


def last_run_id(root: Path) -> str:
    import mlflow

    mlflow.set_tracking_uri(f"sqlite:///{root}/mlruns/mlflow.db")
    runs = mlflow.search_runs(experiment_names=["thermocomp"], order_by=["start_time DESC"],
                              max_results=1, filter_string="tags.stage = 'run'")
    return str(runs.iloc[0]["run_id"])


def test_frames(data: Path) -> dict[str, tuple[str, pd.DataFrame]]:
    manifest = pd.read_csv(data / "campaigns.csv")
    return {r.campaign: (r.file, pd.read_csv(data / r.file)) for r in manifest.itertuples()
            if r.split == "test"}


def with_lead_ins(data: Path) -> list[tuple[pd.DataFrame, int]]:
    """Each test campaign as the deployed stream sees it: after the campaign it continues
    (manifest ``continues``, on the test campaign's clock), and how many rows are its own."""
    manifest = pd.read_csv(data / "campaigns.csv").set_index("campaign")
    out = []
    for cid, (_, df) in test_frames(data).items():
        lead = manifest.loc[cid].get("continues") if "continues" in manifest else None
        if isinstance(lead, str) and lead:
            shift = manifest.loc[lead, "record_offset_s"] - manifest.loc[cid, "record_offset_s"]
            head = pd.read_csv(data / manifest.loc[lead, "file"]).assign(time=lambda d: d["time"] + shift)
            out.append((pd.concat([head, df], ignore_index=True), len(df)))
        else:
            out.append((df, len(df)))
    return out


def tails(rows: np.ndarray, streamed: list[tuple[pd.DataFrame, int]]) -> np.ndarray:
    """The rows of ``rows`` (streamed over ``streamed``'s frames in order) that are test rows."""
    ends = np.cumsum([len(f) for f, _ in streamed])
    return np.vstack([rows[end - n:end] for end, (_, n) in zip(ends, streamed)])


def batch(root: Path, model: Path, data: Path, extra: list[str]) -> tuple[dict, dict]:
    """run's test predictions and the errors it scores them against, read as ``run`` reads them."""
    from hydra import compose, initialize_config_dir

    from thermocomp.shell.model_store import load_model
    from thermocomp.shell.source import read_streamed

    with initialize_config_dir(config_dir=str(root / "conf"), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[f"data.path={data}", "track=false", *extra])
    ds, _, test_ids, _ = read_streamed(cfg)
    comp = load_model(model)
    tests = {c: ds.campaigns[c] for c in test_ids}
    return comp.predict(tests), comp.measured(tests)


def compiled(folder: Path, frames: list[pd.DataFrame], inputs: list[str]) -> np.ndarray:
    subprocess.run(["gcc", "-O2", "compensator.c", "stream.c", "-lm", "-o", "stream"], cwd=folder,
                   check=True, capture_output=True)
    parts = [df[["time", *inputs]].to_csv(index=False, float_format="%.17g") for df in frames]
    text = parts[0] + "".join("\n" + p.split("\n", 1)[1] for p in parts[1:])
    out = subprocess.run([str(folder / "stream")], input=text, text=True, capture_output=True, check=True)
    return pd.read_csv(io.StringIO(out.stdout)).to_numpy(float)


def stepped_json(spec: dict, frames: list[pd.DataFrame], inputs: list[str]) -> np.ndarray:
    from thermocomp.apps.deploy.export import Simulator
    from thermocomp.apps.deploy.export.statespace import StateSpace

    sim = Simulator(StateSpace.from_dict({k: v for k, v in spec.items() if k != "provenance"}))
    rows = []
    for df in frames:
        sim.reset()
        rows += [sim.step(u, t) for u, t in zip(df[inputs].to_numpy(float), df["time"])]
    return np.array(rows, float)


def faulted(data: Path, kind: str, column: str) -> Path:
    """A copy of ``data`` with ``kind`` written into ``column`` of its test campaigns."""
    out = data.parent / f"{data.name}-{kind}"
    shutil.copytree(data, out)
    for file, df in test_frames(data).values():
        n = len(df)
        if kind == "frozen":
            df.loc[n // 3:, column] = df.loc[n // 3, column]
        elif kind == "nan_row":
            df.loc[n // 2, column] = np.nan
        else:
            df.loc[n // 2:, column] += 5.0
        df.to_csv(out / file, index=False)
    return out


def fault_rows(root: Path, name: str, model: Path, data: Path, base: dict) -> list[str]:
    column = [c for c in next(iter(test_frames(data).values()))[1].columns if c.startswith("T_")][0]
    lines = []
    for kind in FAULTS:
        bad = faulted(data, kind, column)
        out = root / "reports" / f"{name}-{kind}"
        rc, said = stage("replay", f"data.path={bad}", f"out={out}", f"replay.model={model}",
                         *RUN_EXTRA.get(data.name, []))
        if rc == 0:
            rep = json.loads((out / "replay.json").read_text())
            rmse = np.mean([v["rmse"] for v in rep["targets"].values()])
            lines.append(f"{name:<22}{kind:<8}{column:<14} exit 0  rmse {rmse:.3g} (healthy "
                         f"{base['replay']:.3g}), {len(rep['events'])} events, excluded "
                         f"{rep['excluded_inputs']}")
        else:
            lines.append(f"{name:<22}{kind:<8}{column:<14} exit {rc}: {said[:160]}")
        shutil.rmtree(bad)
    return lines


def cell(root: Path, record: str, family: str, wrapper: str, data: Path) -> dict:
    start = cpu_seconds()
    name = f"{record}/{family}-{wrapper}"
    out = root / "reports" / record / f"{family}-{wrapper}"
    extra = RUN_EXTRA.get(record, [])
    rc, said = stage("run", f"data.path={data}", f"out={out}", "plots=none", f"model={family}",
                     *FAMILIES[family], *WRAPPERS[wrapper], *extra)
    if rc:
        return {"cell": name, "note": f"run exit {rc}: {said[:150]}", "cpu": cpu_seconds() - start}
    metrics = json.loads((out / "metrics.json").read_text())
    targets = list(metrics["targets"])
    row = {"cell": name, "run": np.mean([metrics["targets"][t]["test"]["rmse"] for t in targets])}
    frames = test_frames(data)
    predicted, scored = batch(root, out / "model.pkl", data, extra)
    measured = np.vstack([scored[c][targets].to_numpy(float) for c in frames])
    run_pred = np.vstack([predicted[c][targets].to_numpy(float) for c in frames])
    row["batch"] = np.mean(np.sqrt(np.nanmean((measured - run_pred) ** 2, axis=0)))
    rc, said = stage("replay", f"data.path={data}", f"out={out}-replay", f"replay.model={out / 'model.pkl'}",
                     *extra)
    if rc:
        return {**row, "note": f"replay exit {rc}: {said[:150]}", "cpu": cpu_seconds() - start}
    rep = json.loads((out.parent / f"{family}-{wrapper}-replay" / "replay.json").read_text())
    row["replay"] = np.mean([rep["targets"][t]["rmse"] for t in targets])
    row["events"] = len(rep["events"])
    rc, said = stage("promote", f"data.path={data}", f"out={out}-promote",
                     f"promote.run_id={last_run_id(root)}", "promote.force=true", *extra)
    if rc:
        return {**row, "note": f"promote exit {rc}: {said[:150]}", "cpu": cpu_seconds() - start}
    promoted = json.loads((out.parent / f"{family}-{wrapper}-promote" / "promote.json").read_text())
    row["promo"] = promoted["candidate"]["test_reported"]["rmse"]
    uri = promoted["model_uri"]
    rc, said = stage("export", f"export.model={uri}", "export.format=c", f"out={out}-c", "export.check=true",
                     f"data.path={data}", *extra)
    if rc:
        return {**row, "note": f"export exit {rc}: {said[:150]}", "cpu": cpu_seconds() - start}
    rc, said = stage("export", f"export.model={uri}", "export.format=json", f"out={out}-json")
    spec = json.loads((out.parent / f"{family}-{wrapper}-json" / "compensator.json").read_text())
    inputs, order = spec["inputs"], spec["targets"]
    streamed = with_lead_ins(data)
    got_c = tails(compiled(out.parent / f"{family}-{wrapper}-c", [f for f, _ in streamed], inputs), streamed)
    got_json = tails(stepped_json(spec, [f for f, _ in streamed], inputs), streamed)
    pack = subprocess.run(["sh", "check/check.sh"], cwd=out.parent / f"{family}-{wrapper}-c",
                          capture_output=True, text=True)
    run_order = [targets.index(t) for t in order]
    row["C+run"] = float(np.nanmax(np.abs(got_c + run_pred[:, run_order])))
    row["C-json"] = float(np.nanmax(np.abs(got_c - got_json)))
    row["C"] = float(np.mean(np.sqrt(np.nanmean((measured[:, run_order] + got_c) ** 2, axis=0))))
    row["pack"] = pack.returncode
    laws = spec["provenance"].get("laws") or {}
    note = ", ".join(f"{t}: {law}" for t, law in laws.items())
    if pack.returncode:
        note = f"pack: {(pack.stdout + pack.stderr).strip().splitlines()[-1][:120]}; {note}"
    return {**row, "note": note, "cpu": cpu_seconds() - start}


def sweep(root: Path, chosen: list[str]) -> None:
    os.environ["THERMOCOMP_ROOT"] = str(root)
    if root.exists():
        shutil.rmtree(root)
    root.mkdir(parents=True)
    (root / "conf").symlink_to(REPO / "conf")
    records = [r for r in RECORDS if r in chosen] or list(RECORDS)
    families = [f for f in FAMILIES if f in chosen] or list(FAMILIES)
    cols = ["run", "batch", "replay", "promo", "C", "C+run", "C-json", "pack", "events", "cpu"]
    print(f"{'cell':<22}" + "".join(f"{c:>9}" for c in cols) + "  note", flush=True)
    faults = []
    for record in records:
        data = root / "data" / record
        rc, said = stage("simulate", *RECORDS[record], f"data.path={data}")
        assert rc == 0, said
        for family in families:
            for wrapper in WRAPPERS:
                r = cell(root, record, family, wrapper, data)
                cells = "".join(f"{r[c]:>9.3g}" if c in r else f"{'-':>9}" for c in cols)
                print(f"{r['cell']:<22}{cells}  {r.get('note', '')}", flush=True)
                if f"{family}-{wrapper}" in FAULT_CELLS and "replay" in r:
                    model = root / "reports" / record / f"{family}-{wrapper}" / "model.pkl"
                    faults += fault_rows(root, f"{record}/{family}-{wrapper}", model, data, r)
    print("\n".join(faults))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "sweep": lambda root, *chosen: sweep(Path(root).resolve(), list(chosen)),
    }, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
