"""One frame for run and replay on the probe bench (session 62): what was scored is what is deployed.

    .venv/bin/python benchmarks/bench_frames62.py DIR [--data grinder grinder_b] [--families ...]

``DIR`` is a root ``benchmarks/bench_probe61.py`` wrote, joined and ``init``-ed (``write``,
``join``, ``init``).  For each record and family: ``run`` (tracked in ``DIR/mlflow-frames-<record>
.db``), ``replay`` of its ``model.pkl``, ``promote`` of that run (``promote.run_id``: its test
figures as deployed), ``export`` of the registered version as C with its conformance pack,
compiled and checked (``check/check.sh``), and the pack's expected corrections scored against
the test campaign's measured errors (its own rows, the lead-in dropped).  Per target: run's test
RMSE, replay's deployed and batch RMSE, the pack's (promote's: the mean over the targets,
``promote.target=mean``), and the largest difference from
run's.  Writes ``DIR/frames-<records>.json``.

Measured 2026-12-01 (each step once, 2 shared cores), the rule of :mod:`thermocomp.core.io.sparse`
(the rows before a week's first probe read by every command): for mlr, arx, lagbank, hammerstein,
auto and auto-linear on both records, |x - run| <= 4.7e-15 um for replay's batch, replay's stream,
the pack (``check/check.sh`` passed, 20160 rows, no cut) and promote's mean; but default auto on
grinder, whose deployed stream's correction guard bounded 12 rows of dY (1.6e-4 um on the RMSE),
and default auto's lstm member, which C does not export (auto-linear exports).  Before (the rows
trimmed by run, streamed by replay; ``data.max_edge_samples=1000``): lagbank and hammerstein
parted by up to 0.56 um (grinder E_dZ: run 5.04 against replay's and the pack's 4.48; promote's
mean 1.91 against run's 2.05).  CPU (s, grinder; run / replay / promote / export): mlr 4.7 / 4.4
/ 7.8 / 14.7, lagbank 6.7 / 7.4 / 11.8 / 18.2, auto 37.7 / 23.3 / 40.0 (export refused).
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).parent))
from bench_probe61 import SEEDS, _tc, data_args  # noqa: E402

FAMILIES = ("mlr", "arx", "lagbank", "hammerstein", "auto", "auto-linear")
# model=auto among the families that export to C (its default candidates' lstm does not: a blend
# with an lstm member is refused by export.format=c, the served model runs it)
VARIANTS = {"auto-linear": ("model=auto", "model.candidates=[mlr,pcr,arx,lagbank,hammerstein]")}
MODEL_NAME = "thermocomp-compensator"


def _rmse(values: np.ndarray) -> float:
    values = values[np.isfinite(values)]
    return float(np.sqrt(np.mean(values ** 2)))


def pack_rmse(root: Path, name: str, code: Path) -> dict:
    """Per target, the RMSE of the measured test error plus the pack's expected correction (C
    is minus the predicted error) on the test campaign's own measured rows."""
    from thermocomp.shell.config.overrides import compose
    from thermocomp.shell.model_store import load_model  # noqa: F401  (the package's import)
    from thermocomp.shell.source import read_streamed

    check = json.loads((code / "check" / "check.json").read_text())
    cfg = compose([*data_args(root, name), "model=mlr", "track=false"])
    ds, _, test_ids, _ = read_streamed(cfg)
    out = {"cuts": [e["cut"] for e in check["campaigns"] if e["cut"]]}
    for entry in check["campaigns"]:
        cid = entry["campaign"]
        if cid not in test_ids:
            continue
        want = pd.read_csv(code / entry["folder"] / "expected.csv").iloc[entry["lead_in_rows"]:]
        test = ds.campaigns[cid].iloc[:len(want)]
        for column in want.columns:
            target = "E_" + column[2:]
            residual = test[target].to_numpy(float) + want[column].to_numpy(float)
            out.setdefault(target, []).append(residual)
    return {**{t: _rmse(np.concatenate(r)) for t, r in out.items() if t != "cuts"},
            "cuts": out["cuts"], "rows": int(sum(len(r) for r in next(
                v for k, v in out.items() if k != "cuts")))}


def one(root: Path, name: str, family: str) -> dict:
    """Run, replay, promote, export + check of one family on one record."""
    uri = f"sqlite:///{root}/mlflow-frames-{name}.db"
    common = [*data_args(root, name), f"tracking_uri={uri}", "plots=none"]
    out = root / "out" / f"frames-{name}-{family}"
    row = {"data": name, "model": family}
    model = VARIANTS.get(family, (f"model={family}",))
    status, cpu, _, err = _tc("run", *common, *model, f"out={out}", cwd=root)
    row["run"] = {"status": status, "cpu_s": cpu}
    if status:
        row["run"]["error"] = err.strip().splitlines()[-1]
        return row
    run_id = re.search(r"MLflow run (\w+)", err).group(1)
    metrics = json.loads((out / "metrics.json").read_text())
    targets = list(metrics["targets"])
    row["run"]["rmse"] = {t: metrics["targets"][t]["test"]["rmse"] for t in targets}
    row["run"]["warnings"] = metrics.get("warnings")
    status, cpu, _, err = _tc("replay", *data_args(root, name), "track=false", "plots=none",
                              f"replay.model={out / 'model.pkl'}", f"out={out}-replay", cwd=root)
    row["replay"] = {"status": status, "cpu_s": cpu}
    if status == 0:
        report = json.loads((out.parent / f"{out.name}-replay" / "replay.json").read_text())
        row["replay"].update({k: {t: report["targets"][t][k] for t in targets}
                              for k in ("rmse", "rmse_batch", "max_abs_stream_minus_batch")})
        # the deployed stream's own acts (the correction guard bounding a correction, the
        # envelope): where it acted, its RMSE is not the model's arithmetic
        row["replay"]["events"] = len(report["events"])
    status, cpu, _, err = _tc("promote", *common, f"promote.run_id={run_id}",
                              f"out={out}-promote", cwd=root)
    row["promote"] = {"status": status, "cpu_s": cpu}
    if status:
        row["promote"]["error"] = err.strip().splitlines()[-1]
        return row
    promoted = json.loads((out.parent / f"{out.name}-promote" / "promote.json").read_text())
    reported = promoted["candidate"]["test_reported"]
    # promote.target=mean (compare.target's default): the mean of the targets' test RMSE
    row["promote"]["rmse_mean"] = reported["rmse"]
    code = out.parent / f"{out.name}-c"
    status, cpu, _, err = _tc("export", *common,
                              f"export.model=models:/{MODEL_NAME}/{promoted['version']}",
                              "export.format=c", "export.check=true", f"out={code}", cwd=root)
    row["export"] = {"status": status, "cpu_s": cpu}
    if status:
        row["export"]["error"] = err.strip().splitlines()[-1]
        return row
    cc = subprocess.run(["cc", "-O2", "compensator.c", "stream.c", "-lm", "-o", "stream"],
                        cwd=code, capture_output=True, text=True)
    check = subprocess.run(["sh", "check/check.sh"], cwd=code, capture_output=True, text=True)
    row["export"].update(cc=cc.returncode, check=check.returncode,
                         check_said=(check.stdout + check.stderr).strip()[-300:],
                         rmse=pack_rmse(root, name, code))
    figures = [row["replay"].get("rmse", {}), row["replay"].get("rmse_batch", {}),
               row["export"]["rmse"]]
    mean = float(np.mean([row["run"]["rmse"][t] for t in targets]))
    row["max_abs_minus_run"] = max([abs(f[t] - row["run"]["rmse"][t]) for f in figures
                                    for t in targets if isinstance(f.get(t), float)]
                                   + [abs(row["promote"]["rmse_mean"] - mean)])
    return row


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("root")
    parser.add_argument("--data", nargs="+", default=list(SEEDS))
    parser.add_argument("--families", nargs="+", default=list(FAMILIES))
    args = parser.parse_args(argv)
    root = Path(args.root).resolve()
    rows = []
    for name in args.data:
        for family in args.families:
            rows.append(one(root, name, family))
            print(json.dumps(rows[-1], default=str)[:1500], flush=True)
    (root / f"frames-{'-'.join(args.data)}.json").write_text(json.dumps(rows, indent=1,
                                                                        default=str))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
