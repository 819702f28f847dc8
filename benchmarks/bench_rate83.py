"""A two-logger record scored on what a control feeds (rate83; issue 34: what is deployed = what
was scored).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_stranger83.py write ROOT SEED        # the bridge mill's record
    thermocomp init ROOT/bridge<SEED> out=ROOT/init<SEED> data.roles.ignore=[SPHERE]
    python benchmarks/bench_rate83.py trace ROOT SEED CONF

``trace``: per family (mlr, arx, lagbank, hammerstein, auto), ``thermocomp run`` on the data
config ``CONF`` (init's) into ``ROOT/rate<SEED>/<family>``; the test run (its last) scored as
``run`` scores it (``metrics.json``: the probe's rows, the DAQ's temperatures joined onto them),
that campaign's joined rows streamed (``thermocomp rows``, the folder, through the fitted
model's streaming compensator, envelope off: must give the scored figure), then what a control
is fed: ``thermocomp rows`` of the test run's DAQ file alone (its 60 s scans; ``S_Y``, the axis
a control knows, from the simulator's position at each scan) streamed through the same model,
its correction read at each probe's instant as the control has it then (the last scan at or
before the probe) and the RMSE of the probe's error (referenced at its first probe) less that
correction (referenced at the first probe's scan).  Also printed: how far the joined rows'
temperatures are from that last scan (the join's look into the scan after the probe).
"""
from __future__ import annotations

import io
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import yaml

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import run_commands  # noqa: E402

FAMILIES = ("mlr", "arx", "lagbank", "hammerstein", "auto")
TEST = "MCR_L12"
TARGETS = ("E_dX", "E_dY", "E_dZ")


def _cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "thermocomp", *args], capture_output=True,
                          text=True)


def _rows(*args: str) -> pd.DataFrame:
    out = _cli("rows", *args)
    if out.returncode:
        raise SystemExit(f"rows exit {out.returncode}: {out.stderr[-600:]}")
    return pd.read_csv(io.StringIO(out.stdout))


def _streamed(model: Path, joined: pd.DataFrame, frame: pd.DataFrame, rows=None
              ) -> dict[str, float]:
    """Test RMSE per target of ``frame`` streamed from its start through ``model`` (envelope
    off), its corrections at ``rows`` (all) against the joined rows' errors as ``replay``
    references them (:meth:`Compensator.measured`)."""
    from thermocomp.apps.deploy.streaming import StreamingCompensator
    from thermocomp.shell.model_store import load_model

    comp = load_model(model)
    deployed = StreamingCompensator(comp, None, "off")
    deployed.reset()
    y = deployed.predict(frame)
    y = y if rows is None else y.iloc[rows].reset_index(drop=True)
    measured = comp.measured({TEST: joined})[TEST]
    return {t: float(np.sqrt(np.mean((measured[t].to_numpy() - y[t].to_numpy()) ** 2)))
            for t in deployed.targets_}


def trace(root: str, seed: str, conf: str) -> None:
    """Scored vs. fed per family on seed ``seed``'s record (module docstring)."""
    import bench_stranger83 as s83

    root_p, conf_p = Path(root).resolve(), Path(conf).resolve()
    folder = Path(yaml.safe_load(conf_p.read_text())["path"])
    common = [f"hydra.searchpath=[file://{conf_p.parent.parent}]", f"data={conf_p.stem}"]
    joined = _rows(str(folder), *common, f"rows.campaigns=[{TEST}]", "rows.errors=true")
    scans = _rows(str(folder / f"{TEST}_daq.csv"), *common)
    r, runs_ = s83.runs(int(seed))
    scans["S_Y"] = r["y"][runs_[-1][2]]
    start = pd.Timestamp(runs_[-1][1])
    probes = pd.read_csv(folder / f"{TEST}_probe.csv", skiprows=1)
    at = (pd.to_datetime(probes["DATE"] + " " + probes["TIME"]) - start).dt.total_seconds()
    held = np.searchsorted(scans["time"].to_numpy(), at.to_numpy(), side="right") - 1
    temps = [c for c in joined if c.startswith("T_")]
    ahead = scans["time"].to_numpy()[np.minimum(held + 1, len(scans) - 1)] - at.to_numpy()
    gap = np.abs(joined[temps].to_numpy() - scans[temps].to_numpy()[held])
    print(f"seed {seed}: {len(joined)} probe rows; the join reads the scan {np.median(ahead):.1f} s "
          f"(median) after the probe; |joined - last scan| median {np.median(gap):.4f} K, "
          f"max {gap.max():.4f} K ({temps[int(gap.max(axis=0).argmax())]})")
    for family in FAMILIES:
        out = root_p / f"rate{seed}" / family
        if not (out / "metrics.json").exists():
            ran = _cli("run", *common, f"model={family}", "plots=none", "track=false", f"out={out}")
            if ran.returncode:
                print(f"{family}: run exit {ran.returncode}: {ran.stderr[-400:]}")
                continue
        scored = json.loads((out / "metrics.json").read_text())["targets"]
        on_rows = _streamed(out / "model.pkl", joined, joined)
        fed = _streamed(out / "model.pkl", joined, scans, held)
        line = "; ".join(f"{t[2:]} {scored[t]['test']['rmse']:.3f} / {on_rows[t]:.3f} / "
                         f"{fed[t]:.3f}" for t in TARGETS if t in fed)
        print(f"{family}: (scored / its rows streamed / fed the scans) {line}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
