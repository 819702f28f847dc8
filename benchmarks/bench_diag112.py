"""The refit null's cost on the families without a closed form (stop 112, diag112).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag112.py family MODEL              # test_diagnose_scenarios' case
    python benchmarks/bench_diag112.py first MODEL FIRST N       # bench_diag111 ``first``, MODEL's base
    python benchmarks/bench_diag112.py planted ROOT LABEL MODEL SEED...   # climate draws, model=MODEL

diag111's gate refitted the whole model 99 times for the candidate a round would take; with ARX+RF
that was 47 of 52 s of CPU of test_diagnose_scenarios' arx_rf case.  The attempt, REFUSED and kept
as ``benchmarks/diag112_rule.patch`` (``git apply`` it in a scratch tree to measure it): a base
without a closed form tests its CV residual's least-squares fit, fitted once (observed and moved
alike), on the inputs and the candidate's features (``residual_fit_rmse``).  Its first form (the
features alone) refused BASE's planted hydraulic source on draw 10122 with model=arx (refit p .02).
``family``: the scenario test's ``every_model_family`` case (hidden source, one round): accepted
effects, test RMSE, CPU.  ``first``: null rooms' round 1 with MODEL (mlr, arx, pcr) as the base: the
best flip and gated p.  ``planted``: ``thermocomp diagnose model=MODEL`` on climate draws (arx_rf
without a state column, as the test's).  The bar and the figures: ``benchmarks/diag112_bar.md``
and the diag112 report.
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_diag111 as d111  # noqa: E402
from _cli import run_commands  # noqa: E402
from cpu import cpu_seconds  # noqa: E402

# the draws this stop scored fresh (kinds named before drawing)
FRESH = {10243: ["sim.generator.effects=[axis_position]"], 10244: ["sim.generator.effects=[lag_node]"],
         10245: ["++sim.generator.clean=true"]}
MODEL_WORDS = {"arx_rf": ["model=arx_rf", "model.estimator.state_column=null"]}


def _estimator(model: str):
    from thermocomp.core.models import ARX, MLR, PCR

    return {"mlr": MLR, "arx": ARX, "pcr": PCR}[model]()


def family(model: str) -> None:
    """test_diagnose_scenarios' ``diagnosis("hidden_source", MODEL, max_effects=1)``."""
    tests = Path(__file__).resolve().parents[1] / "tests"
    sys.path[:0] = [str(tests / "apps"), str(tests)]
    import test_diagnose_scenarios as t

    warnings.filterwarnings("ignore")
    start = cpu_seconds()
    _, result = t.diagnosis("hidden_source", model, max_effects=1)
    j = next(iter(result.values()))
    taken = [(e["kind"], e.get("columns", [e["column"]]), e["evidence"].get("p_value_family"),
              e["evidence"].get("p_value_refit")) for e in t._accepted(j)]
    print(f"  {model}: accepted {taken}; test {j['before']['test_rmse']:.3f} -> {j['after']['test_rmse']:.3f}"
          f" (diagnosis {cpu_seconds() - start:.1f} s CPU)")


def first(model: str, first_room: str, count: str) -> None:
    """bench_diag111 ``first`` with MODEL as the rooms' base."""
    from thermocomp.core import compensator

    made = compensator.Compensator
    # the Compensator bench_diag111._search builds (imported there at each call) gets MODEL
    compensator.Compensator = lambda estimator, *args, **kwargs: made(_estimator(model), *args, **kwargs)
    try:
        d111.first(first_room, count)
    finally:
        compensator.Compensator = made


def planted(root: str, label: str, model: str, *seeds: str) -> None:
    """Each climate draw SEED (simulated once into ROOT/data) diagnosed with ``model=MODEL``."""
    import json

    import bench_diag106 as d106

    folder = Path(root)
    (folder / "logs").mkdir(parents=True, exist_ok=True)
    for seed in map(int, seeds):
        data, out = folder / "data" / str(seed), folder / "out" / label / str(seed)
        if not data.exists():
            d106._thermocomp(["simulate", *d106.CLIMATE, f"seed={seed}", f"data.path={data}", "track=false",
                              *FRESH[seed]], folder / "logs" / f"{seed}-simulate.log")
        words = MODEL_WORDS.get(model, [f"model={model}"])
        cpu = d106._thermocomp(["diagnose", f"data.path={data}", f"out={out}", "plots=none", "track=false",
                                *words], folder / "logs" / f"{seed}-{label}.log")
        for path in sorted((out / "diagnosis").glob("diagnosis_*.json")):
            j = json.loads(path.read_text())
            taken = [(e["kind"], e["column"], round(e["evidence"]["cv_rmse_gain_pct"], 1),
                      e["evidence"].get("p_value_family"), e["evidence"].get("p_value_refit"))
                     for e in j["effects"] if e["accepted"] and e["kind"] != "sensor_fault"]
            print(f"  {seed} {path.stem.removeprefix('diagnosis_')}: test {j['before']['test_rmse']:.3f} -> "
                  f"{j['after']['test_rmse']:.3f}; accepted {taken} (diagnose {cpu:.1f} s CPU)", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"family": family, "first": first, "planted": planted}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
