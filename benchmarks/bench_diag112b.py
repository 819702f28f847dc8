"""The forward scheme's refit null: the candidate's drivers shifted in time (stop 112, diag112b).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag112b.py forward FIRST N [ARM]    # bench_diag111d's null records
    python benchmarks/bench_diag112b.py planted ROOT LABEL SEED...  # 3-run climate draws, cv=forward

diag111d: on 200 clean records (bench_diag108's null room cut to one 80 h train record) the forward
scheme's flips took 4 (18: signal S_hyd; 31, 114: lags of T_6; 169: T_amb's).  The rule
(:mod:`thermocomp.apps.diagnose.shift_null`): the candidate a round would take is refitted with its
drivers shifted circularly in time, 99 offsets at least one test block from the identity; it needs
p <= alpha.  ``forward``: round 1's take per record (bench_diag111d's read) with its shift p; ARM
``A`` leaves lags of the model inputs (kind ``dynamics``) to the flips (refit_null's drivers), ``B``
(the default, the rule) shifts their column too.  ``planted``: ``thermocomp diagnose diagnose.cv=forward``
on climate draws of 3 runs (2 train, 1 test; the kinds in :data:`FRESH`), each target's accepts.
The bar: ``benchmarks/diag112b_bar.md``.

Scored (2026-12-08, once; BASE = 277c06b1's src, RULE = this tree's; CPU user + sys per pass)
* F1 ``forward 0 200``: taken BASE 4 (18, 31, 114, 169; 35.5 s), arm A 4 (the same; 47.0 s), arm B
  1 (18: S_hyd's lag, p_shift .01; 51.2 s).  B refuses the three dynamics lags at p_shift >= .02.
* F2 fresh 10246 axis_position, 10247 hidden_source, 10248 lag_node (3 runs, cv=forward): accepts
  identical both ways: 10246 E_Z S_pos_Z product + T_nc_spindle_motor square (p_shift .01 each),
  10247 E_X S_hydraulic_temp_C lag 900 s (.01), 10247 E_Z a lowpass of the inputs (reads X: flips
  alone, None; test 4.28 -> 8.62 both ways); 10248 nothing either way.
* F3 fresh clean 10249, 10250: no effect accepted either way (10249 E_Z removes a sensor: both).
* F4 ``diagnose diagnose.cv=forward`` on SHORT, 3 runs interleaved: clean BASE 3.63 / RULE 3.65 s
  (x1.01), door BASE 3.78 / RULE 4.43 s (x1.17; S_door taken both ways, p_shift .01).
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_diag111d as d111d  # noqa: E402
from _cli import run_commands  # noqa: E402

FAMILIES = ("signal", "ambient_interval", "dynamics", "interaction", "nonlinear")
SHAPE = ["sim=climate_room", "sim.generator.n_runs=3", "sim.generator.test_fraction=0.34"]
FRESH = {10246: ["sim.generator.effects=[axis_position]"], 10247: ["sim.generator.effects=[hidden_source]"],
         10248: ["sim.generator.effects=[lag_node]"], 10249: ["++sim.generator.clean=true"],
         10250: ["++sim.generator.clean=true"]}


def _arm(arm: str) -> None:
    """Arm A: the campaigns scheme's drivers (no lag of the model inputs shifted); B: the rule."""
    try:
        from thermocomp.apps.diagnose import refit_null, shift_null
    except ImportError:             # BASE: no shift null
        return
    if arm == "A":
        shift_null.drivers = refit_null.drivers


def forward(first_room: str, count: str, arm: str = "B") -> None:
    """Round 1's take on each null record, with its shift p (None: not gated)."""
    warnings.filterwarnings("ignore")
    _arm(arm)
    taken = []
    for seed in range(int(first_room), int(first_room) + int(count)):
        s = d111d._search(d111d.null_record(seed), FAMILIES)
        assert s.problem.scheme == "forward", s.problem.scheme
        family, _, eligible = d111d._round1(s)
        refused = ", ".join(f"{ev.effect.title} p_shift {ev.p_refit:.2f}" for ev in family
                            if ev.p_refit is not None and not ev.clears_bar)
        if eligible:
            taken.append(seed)
        took = (f"TAKE {eligible[0].effect.title} (p_fam {eligible[0].p_family:.4f}, p_shift "
                f"{eligible[0].p_refit})" if eligible else "-")
        print(f"  record {seed}: {took}{'; refused ' + refused if refused else ''}", flush=True)
    print(f"  records where round 1 takes an effect: {len(taken)} of {int(count)} {taken}")


def planted(root: str, label: str, *seeds: str) -> None:
    """Each draw SEED (simulated once into ROOT/data) diagnosed forward into ROOT/out/LABEL."""
    import json

    import bench_diag106 as d106

    folder = Path(root)
    (folder / "logs").mkdir(parents=True, exist_ok=True)
    for seed in map(int, seeds):
        data, out = folder / "data" / str(seed), folder / "out" / label / str(seed)
        if not data.exists():
            d106._thermocomp(["simulate", *SHAPE, f"seed={seed}", f"data.path={data}", "track=false",
                              *FRESH[seed]], folder / "logs" / f"{seed}-simulate.log")
        cpu = d106._thermocomp(["diagnose", f"data.path={data}", f"out={out}", "plots=none", "track=false",
                                "diagnose.cv=forward"], folder / "logs" / f"{seed}-{label}.log")
        for path in sorted((out / "diagnosis").glob("diagnosis_*.json")):
            j = json.loads(path.read_text())
            taken = [(e["kind"], e["column"], e["transform"], round(e["evidence"]["cv_rmse_gain_pct"], 1),
                      e["evidence"].get("p_value_family"), e["evidence"].get("p_value_refit"))
                     for e in j["effects"] if e["accepted"] and e["kind"] != "sensor_fault"]
            print(f"  {seed} {path.stem.removeprefix('diagnosis_')}: test {j['before']['test_rmse']:.3f} -> "
                  f"{j['after']['test_rmse']:.3f}; accepted {taken} (diagnose {cpu:.1f} s CPU)", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"forward": forward, "planted": planted}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
