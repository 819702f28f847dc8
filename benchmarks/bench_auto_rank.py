"""Does the validation rank model families the way the held-out test campaigns do?

Usage::

    python benchmarks/bench_auto_rank.py NAME [OVERRIDE ...]
    # e.g. NAME=yr data.path=data/raw/yearround_spindle
    # BEFORE="eval.validation_scheme=interleaved" python benchmarks/bench_auto_rank.py ...

Runs ``thermocomp run`` once per family (mlr, pcr, arx, lagbank, lstm; the run's
validation, ``targets.<t>.validation``, with the overrides in ``$BEFORE``) and once
``model=auto`` with those five candidates (its ``targets.<t>.auto.candidates``), in
``$OUT`` (default ``/tmp/bench_auto_rank``)/NAME; finished runs are reused.  Per
target it prints the test RMSE of each family, the two validations, the Spearman and
Kendall rank correlations of each validation with the test ranking, the family each
one picks and auto's test RMSE against MLR's and the best family's.  The test split
is only read here, to score the choice after the fact.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from scipy.stats import kendalltau, spearmanr

FAMILIES = ["mlr", "pcr", "arx", "lagbank", "lstm"]
ROOT = Path(__file__).resolve().parents[1]
LIGHT = ["track=false", "plots=none", "eval.mutual_prediction=false", "eval.ati_baselines=false",
         "eval.iso10791_a3=false"]


def _run(out: Path, model: str, extra: list[str], overrides: list[str]) -> dict | None:
    path = out / "metrics.json"
    if not path.is_file():
        t0 = time.perf_counter()
        env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
        done = subprocess.run([str(ROOT / ".venv/bin/thermocomp"), "run", *LIGHT, *overrides,
                               f"model={model}", f"out={out}", *extra],
                              cwd=ROOT, env=env, capture_output=True, text=True)
        if done.returncode:
            print(f"{model}: failed\n{done.stderr[-800:]}")
            return None
        (out / "wall.json").write_text(json.dumps({"wall_s": time.perf_counter() - t0}))
    return json.loads(path.read_text())


def main(name: str, overrides: list[str]) -> None:
    out = Path(os.environ.get("OUT", "/tmp/bench_auto_rank")) / name
    before = os.environ.get("BEFORE", "").split()
    runs = {f: _run(out / f, f, ["eval.validation=true", *before], overrides) for f in FAMILIES}
    auto = _run(out / "auto", "auto", ["eval.validation=false",
                                       f"model.candidates=[{','.join(FAMILIES)}]"], overrides)
    rows = []
    for t, m in auto["targets"].items():
        test = [runs[f]["targets"][t]["test"]["rmse"] for f in FAMILIES]
        old = [runs[f]["targets"][t]["validation"]["rmse"] for f in FAMILIES]
        new = [m["auto"]["candidates"][f] for f in FAMILIES]
        rows.append([spearmanr(old, test)[0], spearmanr(new, test)[0],
                     kendalltau(old, test)[0], kendalltau(new, test)[0]])
        print(f"{name} {t}: test " + " ".join(f"{f} {v:.3g}" for f, v in zip(FAMILIES, test)))
        print(f"  validation {runs['mlr']['targets'][t]['validation']['method']}: "
              + " ".join(f"{v:.3g}" for v in old) + f" -> auto ({m['auto']['scheme']}): "
              + " ".join(f"{v:.3g}" for v in new))
        print(f"  spearman {rows[-1][0]:+.2f} -> {rows[-1][1]:+.2f}, kendall {rows[-1][2]:+.2f} -> "
              f"{rows[-1][3]:+.2f}; picks {FAMILIES[int(np.argmin(old))]} -> {m['auto']['chosen']} "
              f"(test {m['test']['rmse']:.3g}; mlr {test[0]:.3g}, best {min(test):.3g})")
    r = np.nanmean(np.array(rows), axis=0)
    walls = {k: json.loads((out / k / "wall.json").read_text())["wall_s"]
             for k in [*FAMILIES, "auto"] if (out / k / "wall.json").is_file()}
    print(f"{name} mean: spearman {r[0]:+.2f} -> {r[1]:+.2f}, kendall {r[2]:+.2f} -> {r[3]:+.2f}; "
          "wall s " + " ".join(f"{k} {v:.0f}" for k, v in walls.items()))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
