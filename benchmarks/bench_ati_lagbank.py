"""``ati+lagbank`` (the lag bank inside the ATI wrapper) as one of ``model=auto``'s candidates.

Usage::

    python benchmarks/bench_ati_lagbank.py ROOT        # records + runs into ROOT, then the table

Records where ATI applies (train campaigns starting at 3 or more ambient levels) and ``auto`` was
never tuned, seeds fixed before any result: ``sim=climate_room`` seeds 5501 / 5502,
``sim=yearround_spindle`` seeds 5521 / 5522 (24 campaigns), ``benchmarks/bench_other_machine.py``'s
``lathe43`` (its ``init`` config), ``lathe43m`` and ``rig40`` (seed 0).  Per record: ``model=auto``
with the default candidates and with ``model.candidates=[mlr,pcr,arx,lagbank,hammerstein,lstm,ati,
ati+lagbank]``, and the single families (``mlr pcr arx lagbank hammerstein``; ``lstm`` left out: it
was never the best single family on these records' tables).  CPU: user + sys of one
``thermocomp run`` process (``track=false plots=none``), s, on 2 cores shared with other agents.
Also ``model=mlr|lagbank ati=cmeans``, the ATI wrappers alone.

Results (2026-11-30; test RMSE µm per target; ``auto+AL``: the candidates above; best single:
the lowest of the five plain families per target; the ATI wrappers alone for comparison)::

    record            auto              auto+AL           MLR               best single        CPU s
    climate_room 5501 0.43 0.83         0.32 0.54         1.63 2.94         1.40 2.84          41 / 92
    climate_room 5502 0.64 0.92         0.46 0.89         1.51 2.50         1.40 2.46          41 / 82
    yearround 5521    0.93 1.05 1.21    0.90 0.79 0.99    0.94 1.45 4.90    0.87 0.94 4.39     19 / 38
    yearround 5522    0.63 0.94 1.11    0.64 0.94 0.77    0.72 1.86 7.41    0.57 1.19 5.40     16 / 37
    lathe43           0.40 0.76         0.40 0.84         0.42 1.23         0.42 0.95          61 / 187
    lathe43m          0.41 0.55         0.41 0.51         0.43 1.05         0.42 0.93          56 / 154
    rig40             0.71 0.80         0.71 0.99         0.56 0.84         0.56 0.84          10 / 20

    (yearround: E_X E_Y E_Z; mlr ati=cmeans 1.04 1.15 1.21 / 0.64 0.92 1.11, lagbank ati=cmeans
    0.77 0.72 0.99 / 0.74 0.94 0.77; climate_room lagbank ati=cmeans = auto+AL.)

Against ``auto``, ``auto+AL`` is lower on climate_room (-26 / -35 / -28 / -3 %), yearround 5521
E_X / E_Y (-3 / -25 %), yearround E_Z (-18 / -31 %) and lathe43m E_Z (-7 %); equal elsewhere but
yearround 5522 E_X (+2 %), and worse on lathe43 E_dZ (0.84 against 0.76, +11 %: 68 % of the
weight to ati+lagbank) and rig40 E_Z (0.99 against 0.80, +24 %, and worse than MLR's 0.84 where
``auto`` was not: its 5 forward folds over 6 train runs gave ati+lagbank 90 % of the vote).  CPU: 2-3x
``auto``'s (yearround, lathe43m, rig40 measured before the elbow's model reuse and the shared
factorisations: lathe43 then 260 s).  So ``ati+lagbank`` is not a default candidate (the rule:
better or equal on every record, none newly worse than MLR); ``model.candidates=[...,ati+lagbank]``
adds it where the data are many runs at held ambient levels.

Its cost before the lag bank's pooled fit (thermocomp.core.models._pooled): ``model=lagbank
ati=cmeans`` on climate_room 5501 189.1 s CPU (5501 / 5502 196.0 / 193.4 in bench_climate_room.py),
now 52.8 / 53.4 s (metrics.json equal to
4e-11 relative; ``mlr ati=cmeans`` 19.8 / 19.0 s); ``auto+AL`` there 223.5 / 236.7 s before
(bench_climate_room.py), 92 / 82 s now.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

CANDIDATES = "model.candidates=[mlr,pcr,arx,lagbank,hammerstein,lstm,ati,ati+lagbank]"
FAMILIES = ("mlr", "pcr", "arx", "lagbank", "hammerstein")
QUIET = ("track=false", "plots=none")
HERE = Path(__file__).resolve().parent


def thermocomp(*args) -> float:
    """Run one command; its CPU s (user + sys of the child)."""
    before = os.times()
    subprocess.run([sys.executable, "-m", "thermocomp", *args], check=True, capture_output=True)
    after = os.times()
    return (after.children_user - before.children_user) + (after.children_system - before.children_system)


def records(root: Path) -> dict:
    """Record name -> the data overrides of ``thermocomp run``."""
    data = root / "data"
    out = {}
    for seed in (5501, 5502):
        path = data / f"climate{seed}"
        if not path.exists():
            thermocomp("simulate", "sim=climate_room", f"seed={seed}", f"data.path={path}")
        out[f"climate_room {seed}"] = ["sim=climate_room", f"data.path={path}", f"seed={seed}"]
    for seed in (5521, 5522):
        path = data / f"yearround{seed}"
        if not path.exists():
            thermocomp("simulate", "sim=yearround_spindle", f"seed={seed}", f"data.path={path}")
        out[f"yearround_spindle {seed}"] = [f"data.path={path}", f"seed={seed}"]
    other = data / "other"
    if not (other / "init").exists():
        subprocess.run([sys.executable, str(HERE / "bench_other_machine.py"), "write", str(other)],
                       check=True)
        thermocomp("init", str(other / "lathe43"), "data.max_gap_samples=2", f"out={other}/init")
    out["lathe43"] = [f"hydra.searchpath=[file://{other}/init/conf]", "data=lathe43"]
    out["lathe43m"] = [f"data.path={other / 'lathe43m'}"]
    out["rig40"] = [f"data.path={other / 'rig40'}"]
    return out


def scores(out: Path) -> dict:
    metrics = json.loads((out / "metrics.json").read_text())
    return {t: round(m["test"]["rmse"], 2) for t, m in metrics["targets"].items()}


def main(argv=None) -> int:
    root = Path((argv or sys.argv[1:])[0]).resolve()
    for name, data in records(root).items():
        runs = {"auto": ["model=auto"], "auto + ati+lagbank": ["model=auto", CANDIDATES],
                **{f: [f"model={f}"] for f in FAMILIES},
                "mlr ati": ["model=mlr", "ati=cmeans"], "lagbank ati": ["model=lagbank", "ati=cmeans"]}
        for label, model in runs.items():
            out = root / "out" / f"{name.replace(' ', '-')}-{label.replace(' ', '')}"
            cpu = thermocomp("run", *data, *model, *QUIET, f"out={out}")
            print(f"{name:22s} {label:20s} {scores(out)} CPU {cpu:.1f} s", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
