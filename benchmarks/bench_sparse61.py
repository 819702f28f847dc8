"""A reference error measured now and then (a probe cycle) on a dense temperature log (prints numbers).

One record of ``sim=swiss_lathe_door`` with its error measured at every 60 s sample (dense:
``sim.generator.error_period_s=60``), and copies of it whose ``E_`` cells are blanked on every
row but every N-th (N = 10, 30, 120: a probe every 10 min, 30 min, 2 h), read as a probe cycle
(``data.sparse_targets=auto``).  Per family, ``thermocomp run`` fits the dense record and each
sparse copy; every model is scored on the SAME rows, the sparse copy's measured test rows:

* ``dense``: the model fitted on every row, predicting the sparse copy's test campaign;
* ``sparse``: the model fitted on the measured rows only (its ``metrics.json`` test RMSE).

The ratio sparse / dense is what measuring 1 row in N costs (measured: docs/data-format.md,
"A target measured now and then"; at 1 in 30, seed 6121: mlr 1.08-1.09, arx 1.09-1.11,
lagbank 1.23, hammerstein 1.32-1.49, auto 1.12-1.17).  CPU: user + sys of the
``thermocomp run`` process (imports included, ~2.5 s).

Run: ``PYTHONPATH=src .venv/bin/python benchmarks/bench_sparse61.py [WORK_DIR] [families] [seed]``
(``auto`` with the candidates mlr, arx, lagbank).
"""

from __future__ import annotations

import json
import resource
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from thermocomp.apps.sim.probe import probe_cycle_copy
from thermocomp.core.io.read import read_dataset
from thermocomp.shell.model_store import load_model

SEED = 6121
EVERY = (10, 30, 120)
FAMILIES = ("mlr", "pcr", "arx", "lagbank", "hammerstein", "arx_rf")
FAST = ("track=false", "plots=none", "eval.mutual_prediction=false", "eval.ati_baselines=false",
        "eval.iso10791_a3=false", "eval.validation=false")


def thermocomp(*args: str) -> float:
    """Run ``thermocomp args``; its CPU seconds (user + sys)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, "-m", "thermocomp", *args], check=True, capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def rmse_on(model_path: Path, folder: Path) -> dict[str, float]:
    """Test RMSE per target of the model at ``model_path`` on ``folder``'s measured test rows."""
    comp = load_model(model_path)
    ds, _ = read_dataset(folder)
    test = {c: ds.campaigns[c] for c in ds.ids("test")}
    pred, meas = comp.predict(test), comp.measured(test)
    out = {}
    for t in comp.targets_:
        r = np.concatenate([(meas[c][t] - pred[c][t]).to_numpy() for c in test])
        out[t] = float(np.sqrt(np.nanmean(r ** 2)))
    return out


def main(work: Path, families, seed: int = SEED) -> None:
    dense = work / "dense"
    if not (dense / "campaigns.csv").is_file():
        thermocomp("simulate", "sim=swiss_lathe_door", f"seed={seed}", f"data.path={dense}",
                   "sim.generator.error_period_s=60.0", "track=false")
    for every in EVERY:
        if not (work / f"every{every}" / "campaigns.csv").is_file():
            probe_cycle_copy(dense, work / f"every{every}", every)
    rows = []
    for family in families:
        out = work / f"out-{family}-dense"
        extra = ["model.candidates=[mlr,arx,lagbank]"] if family == "auto" else []   # (cheap)
        cpu_dense = thermocomp("run", f"model={family}", f"data.path={dense}", f"out={out}", *FAST,
                               *extra)
        for every in EVERY:
            folder = work / f"every{every}"
            sparse_out = work / f"out-{family}-{every}"
            cpu = thermocomp("run", f"model={family}", f"data.path={folder}", f"out={sparse_out}",
                             *FAST, *extra)
            metrics = json.loads((sparse_out / "metrics.json").read_text())
            on_dense = rmse_on(out / "model.pkl", folder)
            for t, figures in metrics["targets"].items():
                rows.append({"family": family, "every": every, "target": t,
                             "measured_test_rows": figures["test"].get("measured_rows"),
                             "dense": on_dense[t], "sparse": figures["test"]["rmse"],
                             "ratio": figures["test"]["rmse"] / on_dense[t],
                             "cpu_dense_s": cpu_dense, "cpu_sparse_s": cpu})
            print(pd.DataFrame(rows[-len(metrics["targets"]):]).round(3).to_string(index=False),
                  flush=True)
    table = pd.DataFrame(rows)
    print(table.round(3).to_string(index=False))
    print(table.groupby(["family", "every"])["ratio"].agg(["min", "max"]).round(3).to_string())
    (work / "bench_sparse61.json").write_text(table.to_json(orient="records", indent=1))


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "/tmp/sparse61-bench"),
         sys.argv[2].split(",") if len(sys.argv) > 2 else FAMILIES,
         int(sys.argv[3]) if len(sys.argv) > 3 else SEED)
