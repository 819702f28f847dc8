"""Time of the whole residual diagnosis on the default year-round dataset (issue 6: <= 60 s).

Usage::

    python benchmarks/bench_diagnose.py [MODEL] [EFFECT]   # default: mlr, no planted effect

Simulates the default ``yearround_spindle`` scenario (24 campaigns, 10 sensors,
E_X/E_Y/E_Z; ``EFFECT`` plants one undeclared effect, e.g. ``door``), then times

1. the core, :func:`thermocomp.apps.diagnose.diagnose` on every target (before fit,
   leave-campaigns-out residual, candidates, screening, CV refits, after fit
   and test scores), with the number of candidates screened and refitted;
2. the whole stage as a user runs it, ``thermocomp diagnose data.path=...
   track=false`` (reading and validating the CSVs, the search, figures,
   Markdown/HTML reports and the diagnosed config), wall time of the process.

Prints the machine load next to the times (the machine may be shared).
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from hydra import compose, initialize_config_dir
from hydra.utils import instantiate

from thermocomp.apps.diagnose import diagnose
from thermocomp.base.paths import conf_dir
from thermocomp.core.io.contract import write_dataset
from thermocomp.shell.builders import build_compensator


def load() -> str:
    one, five, fifteen = os.getloadavg()
    return f"load average (1, 5, 15 min): {one:.2f} {five:.2f} {fifteen:.2f} on {os.cpu_count()} cores"


def main(model: str = "mlr", effect: str | None = None) -> None:
    overrides = [f"model={model}"] + ([f"++sim.generator.effects=[{effect}]"] if effect else [])
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=overrides)
    ds, _ = instantiate(cfg.sim.generator).generate()
    rows = sum(len(df) for df in ds.campaigns.values())
    print(f"dataset: yearround_spindle{' + ' + effect if effect else ''}, {len(ds.ids())} campaigns "
          f"({len(ds.ids('train'))} train / {len(ds.ids('test'))} test), {rows} rows; model {model}")
    t0 = time.perf_counter()
    d = diagnose(ds, build_compensator(cfg), model_name=model)
    core = time.perf_counter() - t0
    for t, td in d.targets.items():
        rounds = td.search.rounds
        refits = sum(len(r.evaluated) for r in rounds)
        screened = sum(r.n_candidates for r in rounds)
        accepted = ", ".join(f"{ev.effect.kind}:{ev.effect.column or '-'}" for ev in td.accepted) or "none"
        print(f"  {t}: {len(rounds)} rounds, {screened} candidates screened, {refits} refitted by CV, "
              f"test RMSE {td.before['test']['rmse']:.2f} -> "
              f"{td.after['test']['rmse']:.2f} µm; accepted: {accepted}")
    print(f"core diagnose(), all {len(d.targets)} targets: {core:6.1f} s   ({load()})")
    with tempfile.TemporaryDirectory() as tmp:
        path = write_dataset(ds, Path(tmp) / "data")
        cmd = [str(Path(sys.executable).parent / "thermocomp"), "diagnose", f"data.path={path}",
               f"out={Path(tmp) / 'out'}", "track=false", f"model={model}"]
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, capture_output=True, text=True)
        stage = time.perf_counter() - t0
        if proc.returncode != 0:
            raise SystemExit(proc.stderr)
    print(f"`thermocomp diagnose` (process, CSV read .. reports): {stage:6.1f} s   ({load()})")


if __name__ == "__main__":
    args = sys.argv[1:]
    main(args[0] if args else "mlr", args[1] if len(args) > 1 else None)
