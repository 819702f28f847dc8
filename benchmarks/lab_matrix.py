"""The stranger passes' matrix (bench_stranger63 ... bench_stranger66): each family x wrapper of a
lab's record ``run`` -> ``replay`` -> ``promote`` -> C ``export`` with its check pack, in process,
on a project root ``<root>/tc`` of its own (its MLflow store, ``conf`` linked to the repository's);
a saved model's ``monitor`` (healthy, then with faults planted), ``diagnose`` -> its rerun ->
replay -> C, and the matrix's table.  Also the benches' common steps: their machine's
``thermocomp simulate``, the families they pass, and the command line (``STEP ROOT ...``).

Usage is through the benches: ``bench_stranger64.py matrix ROOT [names] [--families ...]``.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
from _cli import run_commands

from thermocomp.core.metrics import unit
from thermocomp.core.scoring.leaderboard import mean_over

REPO = Path(__file__).resolve().parents[1]


def matrix_families(**extra: list) -> dict:
    """The families a stranger passes -> their overrides (the LSTM kept short), ``extra`` (a bench's
    own) before ``auto``."""
    return {"mlr": [], "pcr": [], "arx": [], "lagbank": [], "hammerstein": [],
            "lstm": ["model.estimator.max_epochs=3", "model.estimator.hidden_size=4",
                     "model.estimator.chunk=16"],
            **extra,
            "auto": ["model.candidates=[mlr,pcr,arx,lagbank,hammerstein,ati]"]}


def simulate_scenario(scenario: str, conf: str, seed: int, path: Path, *extra: str) -> None:
    """``thermocomp simulate`` of ``benchmarks/<scenario>.py`` with ``benchmarks/<conf>/sim/<scenario>.yaml``
    (the documented own-machine route), ``extra`` overrides after the bench's."""
    env = dict(os.environ, THERMOCOMP_TARGETS=f"{scenario}.",
               PYTHONPATH=f"{REPO / 'src'}:{REPO / 'benchmarks'}")
    subprocess.run([sys.executable, "-m", "thermocomp", "simulate",
                    f"hydra.searchpath=[file://{REPO / 'benchmarks' / conf}]", f"sim={scenario}",
                    f"seed={seed}", f"data.path={path}", "track=false", *extra], env=env, check=True)


def simulated(root: Path, seeds: dict, simulate):
    """Per record ``name -> seed`` of ``seeds``: ``(name, ROOT/sim/<name>, ROOT/<name>)``, the
    record simulated there once (``simulate(seed, folder)``, kept if it is there), the lab's
    folder made for its files."""
    for name, seed in seeds.items():
        sim = root / "sim" / name
        if not (sim / "campaigns.csv").exists():
            simulate(seed, sim)
        folder = root / name
        folder.mkdir(parents=True, exist_ok=True)
        yield name, sim, folder


def project(root: Path) -> None:
    """The project root ``<root>/tc`` the stages run in (``conf`` linked to the repository's)."""
    os.environ["THERMOCOMP_ROOT"] = str(root / "tc")
    (root / "tc").mkdir(parents=True, exist_ok=True)
    if not (root / "tc" / "conf").exists():
        (root / "tc" / "conf").symlink_to(REPO / "conf")


def initialised(root: Path, name: str, extra: list[str], path: Path | None = None) -> None:
    """``thermocomp init`` of the record ``name`` (its folder ``ROOT/<name>``, or ``path``) with
    ``extra`` (one try, as a stranger types it): a row of its exit status, its last line on
    stderr and its CPU, into ``ROOT/init-<name>`` (keysight70, catman70)."""
    project(root)
    rc, said, cpu = stage("init", str(path or root / name), *extra, f"out={root / f'init-{name}'}")
    print(json.dumps({"init": name, "extra": extra, "rc": rc, "said": said[:600],
                      "cpu": round(cpu, 2)}), flush=True)


def data_args(root: Path, name: str) -> list[str]:
    return [f"hydra.searchpath=[file://{root}/init-{name}/conf]", f"data={name}"]


def stage(*args: str) -> tuple[int, str, float]:
    """``thermocomp <args>`` in process: (exit status, its last line on stderr, CPU s)."""
    import contextlib
    import io
    import traceback

    from cpu import cpu_seconds

    from thermocomp.shell.cli import main as cli

    before = cpu_seconds(children=True)
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        try:
            rc = cli(list(args)) or 0
        except SystemExit as exc:
            rc = int(exc.code or 0)
        except Exception:                  # noqa: BLE001  (a crash is what the bench looks for)
            rc, err = -1, io.StringIO(traceback.format_exc())
    lines = [x for x in err.getvalue().splitlines() if x.strip()]
    return rc, lines[-1] if lines else "", cpu_seconds(children=True) - before


def last_run_id(root: Path) -> str:
    import mlflow

    mlflow.set_tracking_uri(f"sqlite:///{root}/tc/mlruns/mlflow.db")
    runs = mlflow.search_runs(experiment_names=["thermocomp"], order_by=["start_time DESC"],
                              max_results=1, filter_string="tags.stage = 'run'")
    return str(runs.iloc[0]["run_id"])


def exported(data: list, model: str, code: Path, *extra: str) -> dict:
    """``export`` as C with its check pack, compiled, ``check/check.sh``."""
    rc, said, cpu = stage("export", *data, f"export.model={model}", "export.format=c",
                          "export.check=true", *extra, f"out={code}")
    if rc:
        return {"export": f"exit {rc}: {said[:160]}"}
    cc = subprocess.run(["cc", "-O2", "compensator.c", "stream.c", "-lm", "-o", "stream"],
                        cwd=code, capture_output=True, text=True)
    check = subprocess.run(["sh", "check/check.sh"], cwd=code, capture_output=True, text=True)
    return {"cc": cc.returncode, "check": check.returncode,
            "check_said": (check.stdout + check.stderr).strip().splitlines()[-1:]}


def replayed(data: list, model: str, out: Path, targets, *extra: str) -> dict:
    rc, said, cpu = stage("replay", *data, f"replay.model={model}", *extra, f"out={out}")
    if rc:
        return {"replay": f"exit {rc}: {said[:160]}"}
    rep = json.loads((out / "replay.json").read_text())
    return {"replay": {t: rep["targets"][t]["rmse"] for t in targets},
            "stream-batch": max(rep["targets"][t]["max_abs_stream_minus_batch"] for t in targets),
            "events": len(rep["events"]), "replay_cpu": round(cpu, 1)}


def diagnosed(root: Path, name: str, family: str, *extra: str, accepted: bool = False
              ) -> tuple[dict, Path]:
    """``diagnose`` as the docs say (``extra``: more overrides), its rerun line run, the rerun
    model replayed and exported as C with the check pack: ``(row of figures, diagnose's out
    folder)`` (``accepted``: the row lists diagnosis.json's accepted effects too)."""
    os.environ["THERMOCOMP_ROOT"] = str(root / "tc")
    data = data_args(root, name)
    out = root / "diag" / f"{name}-{family}"
    rc, said, cpu = stage("diagnose", *data, f"model={family}", "plots=none", *extra,
                          f"out={out}")
    row: dict = {"diagnose": f"{name}-{family}", "rc": rc, "cpu": round(cpu, 1)}
    if rc:
        return {**row, "said": said}, out
    report = json.loads((out / "diagnosis.json").read_text())
    if accepted:        # (stranger68: diagnosis.json has no 'accepted' list: this said [] always)
        row["accepted"] = {report["target"]: [s["effect"] for s in report["steps"] if s["effect"]]}
        row["accepted"].update({t: v.get("accepted", [])
                                for t, v in (report.get("other_targets") or {}).items()})
    row["targets"] = {report["target"]: (report["before"]["test_rmse"],
                                         report["after"]["test_rmse"])}
    row["targets"].update({t: (v["before_test_rmse"], v["after_test_rmse"])
                           for t, v in (report.get("other_targets") or {}).items()})
    conf = f"hydra.searchpath=[file://{root}/init-{name}/conf,file://{out}/diagnosis/conf]"
    rc, said, cpu = stage("run", conf, f"data={name}", "experiment=diagnosed", "plots=none",
                          f"out={out / 'diagnosed'}")
    if rc:
        return {**row, "rerun": f"exit {rc}: {said}"}, out
    metrics = json.loads((out / "diagnosed" / "metrics.json").read_text())
    targets = list(metrics["targets"])
    row["rerun"] = {t: metrics["targets"][t]["test"]["rmse"] for t in targets}
    model = str(out / "diagnosed" / "model.pkl")
    row.update(replayed(data, model, out / "replay", targets))
    row.update(exported(data, model, out / "c"))
    return row, out


def cell(root: Path, name: str, family: str, wrapper: str, options: dict) -> dict:
    """One matrix cell: ``run`` (``options[family]``: the family's overrides) -> ``replay`` ->
    ``promote`` -> C ``export`` with its check pack, as a row of figures."""
    data = data_args(root, name)
    tag = f"{name}-{family}-{'plain' if wrapper in ('bias', 'rls') else wrapper}"
    out = root / "out" / tag
    row: dict = {"cell": f"{name}-{family}-{wrapper}"}
    if wrapper in ("plain", "ati"):
        rc, said, cpu = stage("run", *data, f"model={family}", *options[family],
                              *(["ati=cmeans"] if wrapper == "ati" else []), "plots=none",
                              f"out={out}")
        row["run_cpu"] = round(cpu, 1)
        if rc:
            return {**row, "run": f"exit {rc}: {said[:200]}"}
        row["run_id"] = last_run_id(root)
    if not (out / "metrics.json").exists():
        return {**row, "run": "no plain run"}
    metrics = json.loads((out / "metrics.json").read_text())
    targets = list(metrics["targets"])
    row["run"] = {t: metrics["targets"][t]["test"]["rmse"] for t in targets}
    adapt = [] if wrapper in ("plain", "ati") else [f"adapt.method={wrapper}"]
    pkl = str(out / "model.pkl")
    row.update(replayed(data, pkl, root / "out" / f"{row['cell']}-replay", targets, *adapt))
    if isinstance(row.get("replay"), dict):
        row["replay-run"] = max(abs(row["replay"][t] - row["run"][t]) for t in targets)
    if wrapper in ("plain", "ati"):
        rc, said, _ = stage("promote", *data, f"promote.run_id={row['run_id']}",
                            "promote.force=true", f"out={root / 'out' / (row['cell'] + '-promote')}")
        if rc:
            row["promote"] = f"exit {rc}: {said[:160]}"
        else:
            promoted = json.loads((root / "out" / f"{row['cell']}-promote" / "promote.json"
                                   ).read_text())
            row["promote"] = promoted["candidate"]["test_reported"]["rmse"]
            # promote's figure is the mean over the targets of one unit (the µm ones beside µm/m)
            row["run_mean"] = float(np.mean([row["run"][t] for t in mean_over(row["run"])[0]]))
    row.update(exported(data, pkl, root / "out" / f"{row['cell']}-c", *adapt))
    return row


def matrix(root: Path, names, families, wrappers, options: dict) -> None:
    """Every cell of ``names`` x ``families`` x ``wrappers`` into ``matrix-<names>.jsonl``."""
    project(root)
    path = root / f"matrix-{'-'.join(names)}.jsonl"
    for name in names:
        for family in families:
            for wrapper in wrappers:
                if family == "auto" and wrapper == "ati":
                    continue                     # ati is one of auto's candidates
                row = cell(root, name, family, wrapper, options)
                print(json.dumps(row, default=str), flush=True)
                with open(path, "a") as f:
                    f.write(json.dumps(row, default=str) + "\n")


def matrix_step(root: Path, rest: list, seeds, families, wrappers, options: dict) -> None:
    """A bench's ``matrix ROOT [names] [--families ...] [--wrappers ...]``: :func:`matrix` of the
    names given (default: every record of ``seeds``) and the families / wrappers given."""
    cut = [i for i, a in enumerate(rest) if a.startswith("--")]
    groups = {rest[i]: rest[i + 1:(cut + [len(rest)])[k + 1]] for k, i in enumerate(cut)}
    names = rest[:cut[0]] if cut else rest
    matrix(root, names or list(seeds), groups.get("--families") or list(families),
           groups.get("--wrappers") or list(wrappers), options)


def monitored(root: Path, name: str, family: str, out: Path, *extra: str) -> dict:
    rc, said, cpu = stage("monitor", *data_args(root, name), *extra,
                          f"monitor.model={root / 'out' / f'{name}-{family}-plain' / 'model.pkl'}",
                          f"out={out}")
    if rc:
        return {"monitor": f"exit {rc}: {said[:200]}"}
    report = json.loads((out / "monitor.json").read_text())
    ev = [e for e in report["events"] if e.get("sensor")]
    return {"events": len(report["events"]),
            "first": [(e["sensor"], e["to"], round(e["time"] / 3600, 2)) for e in ev[:3]],
            "guard": sum(1 for e in report["events"] if e.get("target")),
            "rmse": {t: (round(r["rmse_fixed"], 3), round(r["rmse_adaptive"], 3))
                     for t, r in report["targets"].items()},
            "max_corr/bound": {t: (round(r["max_abs_correction"], 1), r["bound"],
                                   r["all_finite"]) for t, r in report["targets"].items()},
            "cpu": round(cpu, 1)}


def monitoring(root: Path, name: str, family: str, sensors, plant, kinds=("jump",)) -> None:
    """``monitor`` of the saved model on the healthy test record, then per sensor of ``sensors``
    (a header as written) and fault of ``kinds``: ``plant(src, dst, header, kind)`` writes the
    lab's folder ``src`` with that fault into ``dst`` and returns its onset (s); the rows into
    ``monitor-<name>.json``."""
    os.environ["THERMOCOMP_ROOT"] = str(root / "tc")
    rows = [{"case": "healthy", **monitored(root, name, family, root / "mon" / f"{name}-healthy")}]
    print(json.dumps(rows[-1]), flush=True)
    for header in sensors:
        for kind in kinds:
            folder = root / "faulted" / f"{name}-{kind}-{header.split(' [')[0].replace(' ', '_')}"
            onset = plant(root / name, folder, header, kind)
            row = monitored(root, name, family, root / "mon" / folder.name, f"data.path={folder}")
            rows.append({"case": f"{kind} {header}", "onset_h": onset / 3600, **row})
            print(json.dumps(rows[-1]), flush=True)
    (root / f"monitor-{name}.json").write_text(json.dumps(rows, indent=1))


def main(doc: str | None, argv: list[str], seeds, families, wrappers, steps: dict) -> int:
    """A bench's command line ``STEP ROOT [args]`` (:func:`_cli.run_commands`; ``doc``: the bench's
    usage): ``matrix ROOT [names] [--families ...] [--wrappers ...]`` (:func:`matrix_step`), ``table
    ROOT name``, ``diagnose ROOT name family [override ...]`` (:func:`diagnosed`), or the bench's own
    ``steps`` (name -> function of ``(root, args)``)."""
    shared = {"matrix": lambda root, rest: matrix_step(root, rest, seeds, families, wrappers,
                                                        families),
              "table": lambda root, rest: print(table(root, rest[0])),
              # diagnose ROOT name family [override ...]: the row with the accepted effects
              "diagnose": lambda root, rest: print(json.dumps(
                  diagnosed(root, rest[0], rest[1], *rest[2:], accepted=True)[0], default=str))}
    return run_commands(doc, {name: lambda root, *rest, step=step: step(Path(root).resolve(), list(rest))
                              for name, step in {**shared, **steps}.items()}, argv)


def table(root: Path, name: str) -> str:
    """The matrix's last row per cell: run's test RMSE per target, replay's, the largest
    |replay - run| and |stream - batch|, promote's mean against run's, the check pack."""
    rows = {}
    for line in (root / f"matrix-{name}.jsonl").read_text().splitlines():
        row = json.loads(line)
        rows[row["cell"]] = row
    # each target's unit (isoleft67: a tilt's in µm/m, where the head said µm of every one)
    named = next((list(r["run"]) for r in rows.values() if isinstance(r.get("run"), dict)), [])
    kept, left = mean_over(named)
    out = [f"run and replay: test RMSE of {' / '.join(f'{t} {unit(t)}' for t in named)}"
           + (f"; promote/run: the mean over {', '.join(kept)} (µm)" if left else ""),
           f"{'cell':28s} {'run':20s} {'replay':20s} {'|rep-run|':>9s} {'|s-b|':>8s} "
           f"{'promote/run':>13s} {'C check':>8s}"]

    def fig(v):
        return " / ".join(f"{x:.2f}" for x in v.values()) if isinstance(v, dict) else str(v)[:60]
    for cell, r in rows.items():
        prom = (f"{r['promote']:.3f}/{r['run_mean']:.3f}" if isinstance(r.get("promote"), float)
                else str(r.get("promote", "")))
        check = ("passed" if r.get("check") == 0 else r.get("export", f"check {r.get('check')}"))
        rep = r.get("replay-run")
        out.append(f"{cell:28s} {fig(r.get('run')):20s} {fig(r.get('replay')):20s} "
                   f"{'-' if rep is None else f'{rep:.1e}':>9} "
                   f"{r.get('stream-batch', float('nan')):8.1e} {prom:>13s} {str(check)[:90]}")
    return "\n".join(out)
