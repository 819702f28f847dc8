"""What ranks a sweep on an ISO 230-3 test week (isoleft67): the mean over targets of one unit.

    PYTHONPATH=$PWD/src:$PWD/benchmarks .venv/bin/python benchmarks/bench_isoleft67.py ROOT iso_a

ROOT holds ``bench_iso67.py write ROOT`` and ``init ROOT iso_a data.test_fraction=0.2`` (the
sensor nest's X1, Y1, Z in µm, its tilts A, B in µm/m).  One sweep, ``run -m`` over the families
mlr, pcr, arx, lagbank, hammerstein (plain), then ``compare``'s ranking by ``val_rmse`` of
``compare.target=mean`` two ways, from the same runs' ``metrics.json``:

* before: the mean over all five targets (µm and µm/m added);
* the rule (written here before any sweep ran): the mean over the µm targets alone (X1, Y1, Z),
  where µm/m targets stand beside them; one unit: every target, as before.

The rule is adopted on its units, not on a score: a mean adds no two units.  Measured: which run
each ranks first, how far the tilts moved the ranking (the ranks of both), and the test RMSE
per target of the two firsts, reported beside (never used to choose); the CPU of the sweep.

Measured (2026-12-01, 2 shared cores; val_rmse of the five families, best first)
--------------------------------------------------------------------------------
iso_a (seed 6701, µrad): the same order both ways, arx 11.59 / mlr 12.48 / pcr 14.16 / lagbank
19.18 / hammerstein 20.79 (all five) and arx 7.21 / mlr 7.34 / pcr 10.40 / lagbank 12.00 /
hammerstein 15.48 (µm): arx first.  iso_b (6702, arcsec): all five mlr 13.41 / arx 13.42 /
hammerstein 15.33 / pcr 17.16 / lagbank 20.46, mlr first; the µm mean hammerstein 10.00 / arx
10.11 / mlr 10.12 / lagbank 13.13 / pcr 13.41, hammerstein first: the tilts' µm/m had chosen.
Reported beside, test RMSE X1 / Y1 / Z µm, tilt A / B µm/m: mlr 0.15 / 0.47 / 1.55 / 0.63 / 0.32,
hammerstein 0.19 / 0.32 / 0.15 / 1.02 / 0.17.  The sweep (5 runs + its compare) 12.2 / 10.9 s
CPU, the bench 13.9 / 12.6 s (user + sys).  ``compare.json``'s ``ranked_by.mean_over``: "mean
of E_X1, E_Y1, E_Z (µm; E_Tilt_A, E_Tilt_B in µm/m left out)".
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from lab_matrix import data_args, project, stage  # noqa: E402

from thermocomp.core.scoring.leaderboard import mean_over, summary  # noqa: E402

FAMILIES = "mlr,pcr,arx,lagbank,hammerstein"


def main(root: Path, name: str) -> None:
    project(root)
    sweep = root / f"sweep-{name}"
    rc, said, cpu = stage("run", "-m", *data_args(root, name), f"model={FAMILIES}", "plots=none",
                          f"hydra.sweep.dir={sweep}")
    print(json.dumps({"sweep": name, "rc": rc, "said": said[:200], "cpu": round(cpu, 1)}))
    rows = []
    for metrics_file in sorted(sweep.glob("*/metrics.json")):
        m = json.loads(metrics_file.read_text())
        targets = m["targets"]
        everything = float(np.mean([summary(targets, t)["val_rmse"] for t in targets]))
        rows.append({"job": metrics_file.parent.name, "model": m["model"],
                     "mean_all": everything, "mean_um": summary(targets)["val_rmse"],
                     "over": mean_over(targets),
                     "test_rmse": {t: round(targets[t]["test"]["rmse"], 3) for t in targets}})
    for key in ("mean_all", "mean_um"):
        order = sorted(rows, key=lambda r: r[key])
        print(json.dumps({"ranked_by": key, "order": [(r["model"], round(r[key], 3))
                                                      for r in order],
                          "first_test_rmse": order[0]["test_rmse"]}))


if __name__ == "__main__":
    main(Path(sys.argv[1]).resolve(), sys.argv[2])
