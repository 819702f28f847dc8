"""A low-pass copy of the inputs in the forward scheme must gain on the train runs ahead (stop 112,
diag112c; REFUSED: the rule is ``benchmarks/diag112c_rule.patch``, not in src).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's; apply
the patch to a tree of bb6514a9 to measure the rule)::

    python benchmarks/bench_diag112c.py planted ROOT LABEL SEED...   # climate draws: each target's accepts

diag112b's fresh 10247 (hidden_source, 3 runs, 2 train, ``diagnose.cv=forward``) E_Z took a 4 h
``lowpass_inputs`` copy on the flips alone: CV gain 43 %, flip p .0005, shrink 0, test 4.28 -> 8.62
µm.  Trace: its 16 validation blocks all lie in the second train run; fitted on C01 alone the copy
predicts C02 at 10.2-54 µm RMSE over the penalty path against the base's 10.2; its copies shifted in
time (99 shifts) do not match it (p .01): the shift null cannot refuse it.  The rule
(``runs_ahead.py`` in the patch, called from ``shift_null.shift_pvalue``): each train run after the
first is predicted by the fit on the runs before it; the copy, at its best penalty, must gain 5 %
there over the kept model at its own best, else p_refit 1; then its copies are shifted as drivers
are.  ``planted``: :data:`FORWARD` (10246-10248 as bench_diag112b; 10270-10272 its shape) and
:data:`CAMPAIGNS` (10273-10274: bench_diag106's CLIMATE, 12 runs, 8 train, cv=auto) draws.

Scored (2026-12-08, once per tree; BASE = bb6514a9's src, RULE = the patch's):
* 10247 E_Z: BASE 4.28 -> 8.62 (the copy), RULE 4.28 -> 4.28 (refused, p_refit 1).  10246-10248's
  other accepts identical.
* Fresh 10270 hidden_source: identical (E_X S_hyd raw, 3.089 -> 3.093).  10271 lag_node E_Z: BASE
  takes a 4 h copy, 3.415 -> 2.895; RULE refuses it (ahead: best -0.3 %), 3.415: a planted gain
  lost.  10272 clean E_X: BASE takes a 1 h copy, 0.306 -> 0.780; RULE nothing.  10273-10274
  (campaigns scheme): identical (the rule does not reach it).
* ``bench_diag112b.py forward 0 200``: 1 of 200 both (18), CPU 32.0 / 32.2 s.
* diagnose cv=forward on SHORT, 3 interleaved: 2.29 / 2.31 s CPU (x1.01).
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
