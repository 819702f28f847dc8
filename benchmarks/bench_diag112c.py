"""A low-pass copy of the inputs in the forward scheme must gain on the train runs ahead (stop 112,
diag112c).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag112c.py planted ROOT LABEL SEED...   # climate draws: each target's accepts

diag112b's fresh 10247 (hidden_source, 3 runs, 2 train, ``diagnose.cv=forward``) E_Z took a 4 h
``lowpass_inputs`` copy on the flips alone: CV gain 43 %, test 4.28 -> 8.62 µm.  Its 16 validation
blocks all lie in the second train run.  The rule (:mod:`thermocomp.apps.diagnose.runs_ahead`,
called from ``shift_null.shift_pvalue``): each train run after the first is predicted by the fit
on the runs before it; the copy, at its best penalty, must gain 5 % on that over the kept model at
its own best, else p_refit 1; where it does, its copies are shifted in time as drivers are (99
shifts).  ``planted``: :data:`FRESH` draws (10246-10248 as bench_diag112b; 10270-10272 its shape;
10273-10274 bench_diag106's CLIMATE, 12 runs, 8 train, cv=auto: the campaigns scheme), each
target's accepts.  The bar: ``benchmarks/diag112c_bar.md``; the figures: the diag112c report.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_diag106 as d106  # noqa: E402
import bench_diag112b as d112b  # noqa: E402
from _cli import run_commands  # noqa: E402

FORWARD = {**d112b.FRESH, 10270: ["sim.generator.effects=[hidden_source]"],
           10271: ["sim.generator.effects=[lag_node]"], 10272: ["++sim.generator.clean=true"]}
CAMPAIGNS = {10273: ["sim.generator.effects=[lag_node]"], 10274: ["++sim.generator.clean=true"]}


def planted(root: str, label: str, *seeds: str) -> None:
    """Each draw SEED (simulated once into ROOT/data) diagnosed into ROOT/out/LABEL."""
    folder = Path(root)
    (folder / "logs").mkdir(parents=True, exist_ok=True)
    for seed in map(int, seeds):
        forward = seed in FORWARD
        shape, kind = (d112b.SHAPE, FORWARD[seed]) if forward else (d106.CLIMATE, CAMPAIGNS[seed])
        data, out = folder / "data" / str(seed), folder / "out" / label / str(seed)
        if not data.exists():
            d106._thermocomp(["simulate", *shape, f"seed={seed}", f"data.path={data}", "track=false", *kind],
                             folder / "logs" / f"{seed}-simulate.log")
        cpu = d106._thermocomp(["diagnose", f"data.path={data}", f"out={out}", "plots=none", "track=false"]
                               + (["diagnose.cv=forward"] if forward else []),
                               folder / "logs" / f"{seed}-{label}.log")
        for path in sorted((out / "diagnosis").glob("diagnosis_*.json")):
            j = json.loads(path.read_text())
            taken = [(e["kind"], e["column"], e["transform"], round(e["evidence"]["cv_rmse_gain_pct"], 1),
                      e["evidence"].get("p_value_family"), e["evidence"].get("p_value_refit"))
                     for e in j["effects"] if e["accepted"] and e["kind"] != "sensor_fault"]
            print(f"  {seed} {path.stem.removeprefix('diagnosis_')} ({j['cv']['scheme']}): test "
                  f"{j['before']['test_rmse']:.3f} -> {j['after']['test_rmse']:.3f}; accepted {taken} "
                  f"(diagnose {cpu:.1f} s CPU)", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"planted": planted}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
