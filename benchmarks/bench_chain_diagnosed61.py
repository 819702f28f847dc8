"""diagnose -> run -> promote -> export of a diagnosed lag bank, the compiled C against replay
and against diagnose's deployed "after" (gain61).

``thermocomp simulate sim=yearround_spindle "sim.generator.effects=[ambient_law]" seed=6003``
(24 campaigns, a planted ambient law); ``diagnose model=lagbank``; ``thermocomp run`` of the config
it wrote (``experiment=diagnosed``); ``promote`` of that run (the registry's champion, the correction
guard of ``monitor.adaptive``); ``export`` of ``models:/thermocomp-compensator@champion`` to C and
ST.  ``stream.c`` (``cc -std=c99 -Wall -Wextra -Werror``) streams the test campaigns one after the
other; its corrections are compared with ``replay`` of the registered model and its test RMSE
(the error referenced to each campaign's first sample, as scored) with ``diagnose``'s deployed
``after.test_rmse`` (and its batch ``test_rmse_as_run``).  Everything in a scratch root.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_chain_diagnosed61.py

Measured (2026-12-01; 43 s of CPU): diagnose accepted ``x [A0 > 17.24 °C]`` for E_X and E_Y and
the ambient law ``x (A0 - 20)`` for E_Z; one test row clamped; the code's clamp gains on 6 laws
(none outright); C = replay to 4.3e-14 µm over 581 rows; the C's test RMSE 0.8295 / 0.8126 /
0.6664 µm, diagnose's deployed "after" to 4.4e-16 (as run in batch: 0.8293 / 0.8095 / 0.6616).
"""

from __future__ import annotations

import io
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(os.environ.get("BENCH_ROOT", "/tmp/chain61-root"))
REPO = Path(__file__).resolve().parents[1]
DATA = "data/raw/year6003"
MODEL = "models:/thermocomp-compensator@champion"


def tc(*args: str) -> str:
    env = dict(os.environ, THERMOCOMP_ROOT=str(ROOT), PYTHONPATH=str(REPO / "src"))
    p = subprocess.run([sys.executable, "-m", "thermocomp", *args], cwd=ROOT, env=env,
                       capture_output=True, text=True)
    if p.returncode:
        raise RuntimeError(f"thermocomp {' '.join(args)}: exit {p.returncode}\n{p.stderr[-2000:]}")
    return p.stdout + p.stderr


def chain() -> Path:
    """The exported code's folder, after the whole chain (module doc)."""
    ROOT.mkdir(parents=True, exist_ok=True)
    if not (ROOT / "conf").exists():
        (ROOT / "conf").symlink_to(REPO / "conf")
    tc("simulate", "sim=yearround_spindle", "sim.generator.effects=[ambient_law]", "seed=6003",
       f"data.path={DATA}", "track=false")
    tc("diagnose", f"data.path={DATA}", "model=lagbank", "track=false", "out=diagnosed", "plots=none")
    ran = tc("run", f"hydra.searchpath=[file://{ROOT / 'diagnosed' / 'diagnosis' / 'conf'}]",
             "experiment=diagnosed", f"data.path={DATA}", "out=run", "plots=none")
    run_id = ran.split("MLflow run ")[1].split()[0]
    tc("promote", f"promote.run_id={run_id}", f"data.path={DATA}", "out=promoted")
    for fmt in ("c", "st"):
        tc("export", f"export.model={MODEL}", f"export.format={fmt}", f"data.path={DATA}", "out=code")
    subprocess.run(["cc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "compensator.c",
                    "stream.c", "-lm", "-o", "stream"], cwd=ROOT / "code", check=True)
    return ROOT / "code"


def main() -> None:
    code = chain()
    os.environ["THERMOCOMP_ROOT"] = str(ROOT)
    os.chdir(ROOT)
    from hydra import compose, initialize_config_dir

    from thermocomp.apps.deploy.streaming import replay
    from thermocomp.base.paths import conf_dir
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[f"data.path={DATA}"])
    deployed = deployable_model(cfg, None, [], MODEL, "export.model")[0]
    ds, _, test_ids, _ = read_streamed(cfg)
    tests = [ds.campaigns[c].reset_index(drop=True) for c in test_ids]
    replayed = [replay(deployed, df) for df in tests]
    targets = [t for t in replayed[0].columns if t.startswith("E_")]
    predicted = np.vstack([r[targets].to_numpy(float) for r in replayed])
    measured = np.vstack([df[targets].to_numpy(float) - df[targets].to_numpy(float)[0] for df in tests])
    cols = ["time", *json.loads((code / "compensator.json").read_text())["inputs"]]
    parts = [df[cols].to_csv(index=False, float_format="%.17g") for df in tests]
    text = parts[0] + "".join("\n" + p.split("\n", 1)[1] for p in parts[1:])
    out = pd.read_csv(io.StringIO(subprocess.run([str(code / "stream")], input=text, check=True,
                                                 capture_output=True, text=True).stdout))
    c = out[[f"C_{t[2:]}" for t in targets]].to_numpy(float)
    ss = json.loads((code / "compensator.json").read_text())
    print(f"rows {len(c)}, clamped {int(sum(r['n_clamped'].gt(0).sum() for r in replayed))}, laws "
          f"{len(ss['law_lo'])}, outright {ss['clamp_outright']}; max |C - replay| "
          f"{np.max(np.abs(c + predicted)):.2g} um")
    rmse = np.sqrt(np.nanmean((measured + c) ** 2, axis=0))
    for t, r in zip(targets, rmse):
        after = json.loads((ROOT / "diagnosed" / "diagnosis" / f"diagnosis_{t}.json").read_text())["after"]
        print(f"{t}: C test RMSE {r:.4f} um, diagnose deployed {after['test_rmse']:.4f} "
              f"(diff {r - after['test_rmse']:.2g}), as run {after['test_rmse_as_run']:.4f}")


if __name__ == "__main__":
    main()
