"""The refit null as a second acceptance gate (stop 111, diag111): its p honest on clean rooms.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag111.py first FIRST N   # bench_diag108's null rooms: round 1's best candidate
    python benchmarks/bench_diag111.py null FIRST N    # the same rooms: the best level-law pair
    python benchmarks/bench_diag111.py planted ROOT LABEL SEED...   # climate draws: diagnose's accepts

diag109 (``bench_diag109.py first``): on 200 clean rooms round 1's best single candidate reached a
flip p <= .01 on 12, the best pair on 9: the sign flips over 8 held-out campaigns are not the null
of a candidate fitted on those campaigns.  The rule (src: :mod:`thermocomp.apps.diagnose.refit_null`,
``Search._refit_p``): a candidate (or pair) that clears the flips is refitted with its drivers moved
among the train campaigns, 99 permutations (p floor .01); it needs p <= alpha on both.  Here each
room's FLIP p (bench_diag109's statistic: max-T of the campaigns' gain shares over round 1's
candidates, or over the law's round's pairs) and, where it is <= .01, the REFIT p; the GATED p is the
larger.  Printed: the count of rooms with the best flip / gated p <= .01, .05.
The bar and the scored figures: ``benchmarks/diag111_bar.md`` and the diag111 report.
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_diag108 as d108  # noqa: E402
from _cli import run_commands  # noqa: E402

ALPHA = 0.01


def _search(seed: int):
    from bench_diag105 import _searches

    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.apps.diagnose.candidates import CandidateOptions
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    families = ("ambient_interval", "signal")
    options = SearchOptions(max_effects=2, candidates=CandidateOptions(families=families))
    store = {}
    with _searches(store):
        diagnose(d108.null_room(seed), Compensator(MLR()), options=options, targets=["E_X"])
    s = store["E_X"]
    s.effects = []
    return s


def _gated(search, family, current, kept) -> tuple[float, float]:
    """(best flip p, best gated p) over ``family`` (each with its ``tested`` effects)."""
    from thermocomp.apps.diagnose.cv import sign_flip_maxt
    from thermocomp.apps.diagnose.refit_null import refit_pvalue

    if not family:
        return 1.0, 1.0
    D = [np.clip(1.0 - ev.result.unit_mse / np.maximum(current.unit_mse, 1e-300), -1, 1) for ev, _ in family]
    flips = sign_flip_maxt(D)
    gated = []
    for (ev, tested), pf in zip(family, flips):
        pr = (refit_pvalue(search.cv, search.inputs(), kept, tested, ev.result.rmse, alpha=ALPHA)
              if pf <= ALPHA else None)
        gated.append(pf if pr is None else max(pf, pr))     # None: not gated (no driver)
    return float(min(flips)), float(min(gated))


def _count(name: str, reads: list) -> None:
    for i, key in enumerate(("flip", "gated")):
        ps = np.array([r[i] for r in reads])
        print(f"  {name} best {key} p <= .01 / .05: {int((ps <= .01).sum())} / {int((ps <= .05).sum())} "
              f"of {len(ps)} rooms")


def first(first_room: str, count: str) -> None:
    """Round 1's candidate effects (not the control, no sensor fault) on each null room."""
    warnings.filterwarnings("ignore")
    reads = []
    for seed in range(int(first_room), int(first_room) + int(count)):
        s = _search(seed)
        evals, current, _, _ = s._round(s.cv.run(s.inputs(), []), s._read_columns(), 1)
        family = [(ev, [ev.effect]) for ev in evals if not ev.control and ev.effect.transform != "remove"]
        reads.append(_gated(s, family, current, []))
        print(f"  room {seed}: best flip p {reads[-1][0]:.4f} gated {reads[-1][1]:.4f}", flush=True)
    _count("round 1", reads)


def null(first_room: str, count: str) -> None:
    """The lean level law of most gain taken, its next round's pairs (bench_diag109's BASE family)."""
    from thermocomp.apps.diagnose import search as sm

    warnings.filterwarnings("ignore")
    reads = []
    for seed in range(int(first_room), int(first_room) + int(count)):
        s = _search(seed)
        evals, current, _, _ = s._round(s.cv.run(s.inputs(), []), s._read_columns(), 1)
        lean = [ev for ev in evals if ev.effect.transform in sm.LEAN_LEVEL]
        if not lean:
            reads.append((1.0, 1.0))
            continue
        law = max(lean, key=lambda ev: ev.gain)
        s.effects = [law.effect]
        evals2, _, _, _ = s._round(law.result, s._read_columns(), 2)
        s.effects = []
        family = [(ev, [law.effect, ev.effect]) for ev in evals2
                  if not ev.control and ev.effect.transform != "remove"]
        reads.append(_gated(s, family, current, []))
        print(f"  room {seed}: best pair flip p {reads[-1][0]:.4f} gated {reads[-1][1]:.4f}", flush=True)
    _count("pair", reads)


# the planted draws bench_diag109 scored (N2) and this stop's fresh ones (N3, kinds named before drawing)
FRESH = {10218: ["sim.generator.effects=[axis_position]"], 10219: ["sim.generator.effects=[axis_position]"],
         10220: ["sim.generator.effects=[lag_node]"], 10221: ["sim.generator.effects=[hidden_source]"],
         10222: ["++sim.generator.clean=true"]}


def planted(root: str, label: str, *seeds: str) -> None:
    """Each climate draw SEED (simulated once into ROOT/data) diagnosed by this tree's ``thermocomp
    diagnose`` into ROOT/out/LABEL: every target's accepted effects, with their flip and refit p."""
    import json

    import bench_diag106 as d106
    import bench_diag107 as d107
    import bench_diag107d as d107d

    kinds = {**{s: k[1] for s, k in {**d107.KINDS, **d107d.KINDS, **d108.KINDS}.items()}, **FRESH}
    folder = Path(root)
    (folder / "logs").mkdir(parents=True, exist_ok=True)
    for seed in map(int, seeds):
        data, out = folder / "data" / str(seed), folder / "out" / label / str(seed)
        if not data.exists():
            d106._thermocomp(["simulate", *d106.CLIMATE, f"seed={seed}", f"data.path={data}", "track=false",
                              *kinds[seed]], folder / "logs" / f"{seed}-simulate.log")
        cpu = d106._thermocomp(["diagnose", f"data.path={data}", f"out={out}", "plots=none", "track=false"],
                               folder / "logs" / f"{seed}-{label}.log")
        for path in sorted((out / "diagnosis").glob("diagnosis_*.json")):
            j = json.loads(path.read_text())
            taken = [(e["kind"], e["column"], round(e["evidence"]["cv_rmse_gain_pct"], 1),
                      e["evidence"].get("p_value_family"), e["evidence"].get("p_value_refit"))
                     for e in j["effects"] if e["accepted"] and e["kind"] != "sensor_fault"]
            print(f"  {seed} {path.stem.removeprefix('diagnosis_')}: test {j['before']['test_rmse']:.3f} -> "
                  f"{j['after']['test_rmse']:.3f}; accepted {taken} (diagnose {cpu:.1f} s CPU)", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"first": first, "null": null, "planted": planted}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
