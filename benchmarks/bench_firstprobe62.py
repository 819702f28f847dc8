"""A probe cycle whose first reading comes after the campaign's first sample (firstprobe62).

    PYTHONPATH=src .venv/bin/python benchmarks/bench_firstprobe62.py DIR [families] [cases]

One record of ``sim=swiss_lathe_door`` seed 61 (80 h train, 24 h test, the error at every 60 s
sample: ``dense``) and copies whose ``E_`` cells are kept on 1 row in N from row F only
(``eNfF``: N = 10, 30; F = 0, 15, 29), read in the first-sample frame.  Per copy and family:
``run``'s test RMSE, ``replay``'s (stream and batch), and ``truth``: the RMSE of the deployed
correction ``y_hat(t)`` against the TRUE error from the stream's start (the dense record's
``E(t) - E(0)``) on the copy's measured test rows -- what the machine is left with, which no lab
measures.  Run it with the code before and after the change (PYTHONPATH) to compare.  Writes
``DIR/firstprobe62.json``.  Figures: docs/data-format.md ("A target measured now and then").
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np

from thermocomp.apps.sim.probe import probe_cycle_copy
from thermocomp.core.io.read import read_dataset
from thermocomp.shell.model_store import load_model

CASES = ("e30f15", "e10f15", "e30f29", "e30f0", "e10f0")
FAST = ("track=false", "plots=none")


def tc(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "thermocomp", *args], check=True, capture_output=True)


def copies(work: Path) -> Path:
    """The dense record and its late-probe copies (made once)."""
    dense = work / "dense"
    if not (dense / "campaigns.csv").is_file():
        tc("simulate", "sim=swiss_lathe_door", "seed=61", f"data.path={dense}",
           "sim.generator.error_period_s=60.0", "track=false")
    for every, first in ((10, 0), (10, 15), (30, 0), (30, 15), (30, 29)):
        dest = work / f"e{every}f{first}"
        if not (dest / "campaigns.csv").is_file():
            probe_cycle_copy(dense, dest, lambda r, e=every, f=first: (r >= f) & ((r - f) % e == 0))
    return dense


def truth(model: Path, dense: Path, sparse: Path) -> dict[str, float]:
    """RMSE of the deployed correction against the dense record's E(t) - E(0) on the sparse
    copy's measured test rows."""
    comp = load_model(model)
    dd, _ = read_dataset(dense)
    sd, _ = read_dataset(sparse)
    ids = sd.ids("test")
    pred = comp.predict({c: dd.campaigns[c] for c in ids})
    out = {}
    for t in comp.targets_:
        res = []
        for c in ids:
            error = dd.campaigns[c][t].to_numpy(float)
            keep = np.isfinite(sd.campaigns[c][t].to_numpy(float))
            res.append((error - error[0] - pred[c][t].to_numpy())[keep])
        out[t] = float(np.sqrt(np.mean(np.concatenate(res) ** 2)))
    return out


def one(work: Path, dense: Path, case: str, family: str) -> dict:
    data, out = work / case, work / f"out-{case}-{family}"
    tc("run", f"data.path={data}", f"model={family}", f"out={out}/run", *FAST)
    tc("replay", f"data.path={data}", f"replay.model={out}/run/model.pkl", f"out={out}/replay",
       *FAST)
    run = json.loads((out / "run" / "metrics.json").read_text())["targets"]
    replay = json.loads((out / "replay" / "replay.json").read_text())["targets"]
    return {"case": case, "family": family,
            "run": {t: run[t]["test"]["rmse"] for t in run},
            "rms_before": {t: run[t]["test"]["rms_before"] for t in run},
            "replay": {t: replay[t]["rmse"] for t in run},
            "replay_batch": {t: replay[t]["rmse_batch"] for t in run},
            "truth": truth(out / "run" / "model.pkl", dense, data)}


def main(work: Path, families, cases) -> None:
    work.mkdir(parents=True, exist_ok=True)
    dense = copies(work)
    rows = []
    for case in cases:
        for family in families:
            rows.append(one(work, dense, case, family))
            print(json.dumps({k: ({t: round(v, 3) for t, v in x.items()} if isinstance(x, dict)
                                  else x) for k, x in rows[-1].items()}), flush=True)
    (work / "firstprobe62.json").write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "/tmp/firstprobe62-bench"),
         sys.argv[2].split(",") if len(sys.argv) > 2 else ("mlr", "lagbank"),
         sys.argv[3].split(",") if len(sys.argv) > 3 else CASES)
