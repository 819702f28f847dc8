"""The steps the new-machine benchmarks share (``bench_new_machines56/57/58.py``): write the
lab's files, ``init`` them as a stranger would, ``run`` each model family, ``diagnose``,
``replay`` a deployed model, ``monitor`` the healthy test part, print the table (or a bench's own
forensics).

Each bench describes its machines in a :class:`Machines` and calls :func:`main` with it; the
steps are the same code for every bench (each had its own copy of the runner).
"""

from __future__ import annotations

import argparse
import io
import json
import os
import re
import subprocess
import time
from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from bench_monitor_healthy import monitor as monitor_run
from bench_other_machine import QUIET, scores, thermocomp
from bench_other_machine import diagnose as other_diagnose

ArgsOf = Callable[[Path, str], list]


@dataclass(frozen=True)
class Machines:
    """What one bench gives the steps.

    Attributes
    ----------
    doc : str
        The bench's docstring (its ``--help``).
    write : callable
        ``write(root)``: the lab's files under ``root``.
    records, families : sequence of str
        The records (``--data``'s default) and model families (``--families``'s).
    init_args : mapping
        Record -> what a stranger adds to ``init DIR`` (the test share).
    data_args : callable
        ``data_args(root, record)``: the data overrides of a record (init's config).
    folders : mapping
        Record -> its folder under the root, where it is not the record's name.
    variants : mapping
        Variant (``record-what``) -> its overrides: more records ``diagnose`` takes (``all``:
        those of the records run).
    ati_records : collection of str
        Records also run with ``mlr ati=cmeans`` (a shop's seasons).
    monitored : sequence of str
        The families ``monitor`` streams (none: no monitor step).
    replayed : str or None
        The family whose ``run`` model ``replay`` streams (none: no replay step).
    forensics : callable or None
        ``forensics(root)``: the bench's own look at a result (step ``forensics``, not in ``all``).
    diagnose_file : str
        The diagnose step's JSON under the root (``{names}``: the records, joined by ``-``).
    lab_file : callable or None
        ``lab_file(root, record)``: a test campaign's file as the lab has it, which step
        ``export`` feeds the compiled C (none: no export step).
    """

    doc: str
    write: Callable[[Path], None]
    records: Sequence[str]
    families: Sequence[str]
    init_args: Mapping[str, tuple]
    data_args: ArgsOf
    folders: Mapping[str, str] = field(default_factory=dict)
    variants: Mapping[str, list] = field(default_factory=dict)
    ati_records: Collection[str] = ()
    monitored: Sequence[str] = ()
    replayed: str | None = None
    forensics: Callable[[Path], None] | None = None
    diagnose_file: str = "diagnose-{names}.json"
    lab_file: Callable[[Path, str], Path] | None = None


def run_models(root: Path, name: str, families, extra=(), args_of: ArgsOf | None = None
               ) -> list[dict]:
    """``run`` each family on a record (``args_of(root, name)``: its data overrides): test RMSE
    per target, CPU s, ``auto.json``'s choice."""
    rows = []
    for family in families:
        tag = f"{name}-{family}" + ("-" + "-".join(extra) if extra else "")
        out = root / "out" / tag
        status, cpu, _, err = thermocomp("run", *args_of(root, name), f"model={family}",
                                         *QUIET, *extra, f"out={out}")
        row = {"data": name, "model": family + (" " + " ".join(extra) if extra else ""),
               "status": status, "cpu_s": round(cpu, 1)}
        if status == 0:
            row["scores"] = scores(out)
            picked = out / "auto.json"
            if picked.exists():
                row["auto"] = json.loads(picked.read_text())
        else:
            row["error"] = err.strip().splitlines()[-1] if err.strip() else "?"
        print({k: v for k, v in row.items() if k != "auto"}, flush=True)
        rows.append(row)
    return rows


def table(rows: list[dict]) -> str:
    """Per record: each model's test RMSE per target, the ratio to MLR's, CPU s; persistence."""
    mlr = {r["data"]: r["scores"] for r in rows if r["model"] == "mlr"}
    lines = []
    for name, base in mlr.items():
        lines.append(f"{name} ({' / '.join(base)})")
        for r in (r for r in rows if r["data"] == name):
            got = " / ".join(f"{v[0]:.2f}" for v in r["scores"].values())
            ratio = " / ".join(f"{v[0] / base[t][0]:.2f}" for t, v in r["scores"].items())
            lines.append(f"  {r['model']:16s} {got:15s} {ratio:13s} {r['cpu_s']}")
        got = " / ".join(f"{v[1]:.2f}" for v in base.values())
        ratio = " / ".join(f"{v[1] / v[0]:.2f}" for v in base.values())
        lines.append(f"  {'persistence':16s} {got:15s} {ratio}")
    return "\n".join(lines)


def monitor(root: Path, name: str, model: str, args_of: ArgsOf) -> dict:
    """``monitor`` on the healthy test part (the model fitted on the train split, the defaults):
    events, exclusions, RMSE fixed / adaptive per target (``bench_monitor_healthy``'s summary),
    the CPU s of the process."""
    before = os.times()
    row = monitor_run([*args_of(root, name), f"model={model}"],
                      root / "out" / f"{name}-monitor-{model}")
    after = os.times()
    row.update(data=name, model=model,
               cpu_s=round(after.children_user - before.children_user
                           + after.children_system - before.children_system, 1))
    print(row, flush=True)
    return row


def replay(root: Path, name: str, model: str, args_of: ArgsOf) -> dict:
    """``replay`` of the ``run``'s fitted ``model.pkl`` (the deployed form, the defaults): per
    target the stream's RMSE, the batch's, the largest |stream - batch|, and the events."""
    out = root / "out" / f"{name}-replay-{model}"
    status, cpu, _, err = thermocomp("replay", *args_of(root, name), *QUIET,
                                     f"replay.model={root / 'out' / f'{name}-{model}' / 'model.pkl'}",
                                     f"out={out}")
    row = {"data": name, "model": model, "status": status, "cpu_s": round(cpu, 1)}
    if status == 0:
        report = json.loads((out / "replay.json").read_text())
        keys = ("rmse", "rmse_batch", "max_abs_stream_minus_batch", "n_samples")
        row["targets"] = {t: {k: r.get(k) for k in keys} for t, r in report["targets"].items()}
        row["events"] = len(report["events"])
    else:
        row["error"] = err.strip().splitlines()[-1] if err.strip() else "?"
    print(row, flush=True)
    return row


def _parser(bench: Machines) -> argparse.ArgumentParser:
    steps = ["write", "init", "run", "diagnose", *(["replay"] if bench.replayed else []),
             *(["monitor"] if bench.monitored else []), *(["export"] if bench.lab_file else []),
             "replay-each",
             "table", *(["forensics"] if bench.forensics else []), "all"]
    parser = argparse.ArgumentParser(description=bench.doc,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("what", choices=steps)
    parser.add_argument("root")
    also = f"; diagnose also takes {', '.join(bench.variants)}" if bench.variants else ""
    parser.add_argument("--data", nargs="+", default=list(bench.records), help=f"records{also}")
    parser.add_argument("--families", nargs="+", default=list(bench.families))
    return parser


def main(bench: Machines, argv=None) -> int:
    """Run the step ``what`` (or ``all`` but the forensics) of ``bench`` on ``root``."""
    args = _parser(bench).parse_args(argv)
    root = Path(args.root).resolve()
    every = args.what == "all"
    if args.what == "write" or every:
        t0 = time.perf_counter()
        bench.write(root)
        print(f"records written to {root} in {time.perf_counter() - t0:.1f} s")
    if args.what == "init" or every:
        for name in args.data:
            status, cpu, out, err = thermocomp("init", str(root / bench.folders.get(name, name)),
                                               *bench.init_args[name], f"out={root}/init-{name}")
            print(out, err[-3000:], f"exit {status}, CPU {cpu:.1f} s", sep="\n")
    if args.what == "run" or every:
        for name in args.data:
            rows = run_models(root, name, args.families, args_of=bench.data_args)
            if name in bench.ati_records:
                rows += run_models(root, name, ("mlr",), ("ati=cmeans",), args_of=bench.data_args)
            (root / f"families-{name}.json").write_text(json.dumps(rows, indent=1))
    if args.what == "diagnose" or every:
        names = [*args.data, *(v for v in bench.variants if v.partition("-")[0] in args.data)] \
            if every else args.data
        rows = [other_diagnose(root, name, bench.data_args) for name in names]
        path = root / bench.diagnose_file.format(names="-".join(names))
        path.write_text(json.dumps(rows, indent=1))
    if args.what == "replay-each":     # every family's run model (not in all)
        rows = [replay(root, name, family, bench.data_args) for name in args.data
                for family in args.families
                if (root / "out" / f"{name}-{family}" / "model.pkl").exists()]
        (root / f"replay-each-{'-'.join(args.data)}.json").write_text(json.dumps(rows, indent=1))
    if bench.replayed and (args.what == "replay" or every):
        rows = [replay(root, name, bench.replayed, bench.data_args) for name in args.data]
        (root / f"replay-{'-'.join(args.data)}.json").write_text(json.dumps(rows, indent=1))
    if bench.monitored and (args.what == "monitor" or every):
        rows = [monitor(root, name, model, bench.data_args) for name in args.data
                for model in bench.monitored]
        (root / f"monitor-{'-'.join(args.data)}.json").write_text(json.dumps(rows, indent=1))
    if bench.lab_file and (args.what == "export" or every):
        rows = [export_c(root, name, bench.data_args, bench.lab_file(root, name))
                for name in args.data]
        (root / f"export-{'-'.join(args.data)}.json").write_text(json.dumps(rows, indent=1))
    if args.what == "table" or every:
        rows = [r for name in args.data
                for r in json.loads((root / f"families-{name}.json").read_text())]
        print(table([r for r in rows if "scores" in r]))
        for r in rows:
            if "scores" not in r:
                print(f"{r['data']} {r['model']}: exit {r['status']}: {r['error']}")
    if args.what == "forensics":
        bench.forensics(root)
    return 0


def export_c(root: Path, name: str, args_of: ArgsOf, lab: Path) -> dict:
    """``export`` the MLR run's model as C, compile it with ``stream.c``, feed it the lab's own
    file ``lab`` as it is (stdin); where the stream refuses it, :func:`as_read`."""
    code = root / "out" / f"{name}-code"
    status, cpu, _, err = thermocomp("export", *args_of(root, name), *QUIET,
                                     f"export.model={root / 'out' / f'{name}-mlr' / 'model.pkl'}",
                                     "export.format=c", f"out={code}")
    row = {"data": name, "export_status": status, "cpu_s": round(cpu, 1)}
    if status != 0:
        row["error"] = err.strip().splitlines()[-1] if err.strip() else "?"
        print(row, flush=True)
        return row
    cc = subprocess.run(["cc", "-O2", "compensator.c", "stream.c", "-lm", "-o", "stream"], cwd=code,
                        capture_output=True, text=True)
    row["cc_status"] = cc.returncode
    if cc.returncode == 0:
        with open(lab, "rb") as f:
            run = subprocess.run(["./stream"], cwd=code, stdin=f, capture_output=True)
        row["stream_status"] = run.returncode
        row["stream_stderr"] = run.stderr.decode(errors="replace").strip()[-600:]
        (code / "corrections.csv").write_bytes(run.stdout)
        row["stream_rows"] = max(0, run.stdout.count(b"\n") - 1)
        if run.returncode != 0:
            row.update(as_read(root, name, code, args_of))
    print(row, flush=True)
    return row


def as_read(root: Path, name: str, code: Path, args_of: ArgsOf) -> dict:
    """What a stranger does when ``stream.c`` refuses the lab's own file: the test campaigns as
    thermocomp reads them (contract names, °C, µm, s) written as the stream's CSV (a blank row
    between campaigns), streamed; against the served model's ``replay`` of the same campaigns."""
    import numpy as np
    import pandas as pd

    from thermocomp.apps.deploy.streaming import replay as replayed
    from thermocomp.shell.builders import deploy_stream
    from thermocomp.shell.config.overrides import compose
    from thermocomp.shell.model_store import load_model
    from thermocomp.shell.source import read_streamed

    cfg = compose([*args_of(root, name), "model=mlr", "track=false"])
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    stream = deploy_stream(cfg, load_model(root / "out" / f"{name}-mlr" / "model.pkl"),
                           {c: ds.campaigns[c] for c in train_ids})
    want = np.vstack([-replayed(stream, ds.campaigns[c])[stream.targets_].to_numpy(float)
                      for c in test_ids])
    header = (code / "compensator.h").read_text()
    names = re.search(r"TC_INPUT_NAMES\[\w*\] = \{([^}]*)\}", header).group(1)
    inputs = re.findall(r'"([^"]*)"', names)
    columns = ["time", *inputs] if "time" in ds.campaigns[test_ids[0]] else inputs
    text = "\n\n".join(ds.campaigns[c][columns].to_csv(index=False, header=i == 0,
                                                        float_format="%.17g").strip()
                        for i, c in enumerate(test_ids)) + "\n"
    (code / "as_read.csv").write_text(text)
    run = subprocess.run(["./stream"], cwd=code, input=text.encode(), capture_output=True)
    out = {"as_read_status": run.returncode, "as_read_stderr": run.stderr.decode()[-300:]}
    if run.returncode == 0:
        got = pd.read_csv(io.BytesIO(run.stdout)).to_numpy(float)
        out["as_read_rows"] = len(got)
        out["c_minus_replay_max"] = float(np.abs(got - want).max()) if got.shape == want.shape else \
            f"shapes {got.shape} {want.shape}"
    return out
