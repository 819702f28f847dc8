"""Learning from reference measurements (``adapt``) against the frozen model (prints numbers).

Two datasets of the default scenario with the same seed, paired sample by sample: one where
nothing changes, one where the machine ages after training (``sim.generator.effects=[ageing]``:
in the test campaigns the sensitivities grow by up to 40 %).  MLR is fitted on the train split
(where both datasets are the same machine), deployed as the plain streaming compensator, and
the test campaigns are streamed in their order with one reference measurement every
``every_s`` seconds (the measured error of that sample) for each ``adapt.method``.

Acceptance (issue 36): with a reference every 2 h, ``adapt`` lowers the test RMSE after the
change of law by >= 30 % against the frozen model, and costs <= 5 % where nothing changed.
The figure is the RMSE pooled over the targets (every sample of every target once).

Run: ``.venv/bin/python benchmarks/bench_adapt.py [EVERY_S]`` (default 7200).
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from thermocomp.apps.deploy import StreamingCompensator
from thermocomp.apps.deploy.adapt import Adaptation, ReferenceAdapter, ReferenceSchedule
from thermocomp.apps.deploy.report import replay_report
from thermocomp.core.compensator import Compensator
from thermocomp.core.io.read import read_dataset
from thermocomp.core.models import MLR

# label -> (method, parameters other than the defaults of conf/adapt/default.yaml)
SETTINGS = {"none": ("none", {}), "bias": ("bias", {}), "rls": ("rls", {}),
            "rls f=0.9": ("rls", {"forgetting": 0.9})}


def simulate(folder: Path, effects: str) -> None:
    exe = Path(sys.executable).with_name("thermocomp")
    subprocess.run([str(exe), "simulate", "track=false", "plots=none", f"data.path={folder}",
                    f"sim.generator.effects=[{effects}]"], check=True, capture_output=True)


def pooled_rmse(report: dict, frozen: bool) -> float:
    """RMSE over every target's samples (equal counts: the mean of the squares)."""
    values = [(r["adapt"]["rmse_frozen"] if frozen else r["rmse"]) for r in report["targets"].values()]
    return float(np.sqrt(np.mean(np.square(values))))


def scores(folder: Path, every_s: float) -> dict:
    ds, _ = read_dataset(folder)
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    test = {c: ds.campaigns[c] for c in ds.ids("test")}
    stream = StreamingCompensator.from_training(Compensator(MLR()).fit(train), train)
    out = {}
    for label, (method, params) in SETTINGS.items():
        adapter = ReferenceAdapter(len(stream.targets_), method, **params)
        report = replay_report(stream, test, adapt=Adaptation(adapter, ReferenceSchedule(every_s)))
        out[label] = {"rmse": pooled_rmse(report, frozen=False),
                       "per_target": {t: r["rmse"] for t, r in report["targets"].items()},
                       "references": next(iter(report["targets"].values()))["adapt"]["n_references"]}
    return out


def main() -> None:
    every_s = float(sys.argv[1]) if len(sys.argv) > 1 else 7200.0
    with tempfile.TemporaryDirectory() as tmp:
        results = {}
        for name, effects in (("unchanged", ""), ("ageing", "ageing")):
            simulate(Path(tmp) / name, effects)
            results[name] = scores(Path(tmp) / name, every_s)
    print(f"reference every {every_s:g} s; pooled test RMSE (µm), per target in brackets")
    for name, res in results.items():
        frozen = res["none"]["rmse"]
        for method, r in res.items():
            per = ", ".join(f"{t} {v:.3f}" for t, v in r["per_target"].items())
            change = 100 * (r["rmse"] / frozen - 1)
            print(f"  {name:<10} {method:<9} {r['rmse']:.3f}  ({change:+.1f} % vs frozen; "
                  f"{r['references']} references)  [{per}]")


if __name__ == "__main__":
    main()
