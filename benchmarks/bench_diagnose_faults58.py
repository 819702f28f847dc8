"""Planted sensor FAULTS in train campaigns: does ``diagnose``'s health step find them, and does it
leave the healthy sensors of a new thermal state alone (issue 34, session 58)?

Usage::

    python benchmarks/bench_diagnose_faults58.py write ROOT            # the twin lathe + init
    python benchmarks/bench_diagnose_faults58.py [CASE ...] [--root ROOT]   # JSON lines
    # CASE: SCENARIO:KIND, SCENARIO of SCENARIOS, KIND of KINDS (KIND1: in one unit only, below)
    # or "clean"; none: every one but the KIND1 ones

A fault is planted by post-processing the campaigns as read (what a lab's CSV would hold): one
non-ambient ``T_`` sensor, drawn by ``numpy.random.default_rng(seed)`` from the sorted sensors, in
the TRAIN campaigns only (the test split healthy: a sensor mended before the test), from an onset
on to the campaign's end.  Kinds (magnitudes fixed before any run):

* ``drift``   -- the reading gains 0.3 K/h from the onset (a degrading contact);
* ``offset``  -- +1.0 K from the onset (a connector's resistance step);
* ``stuck``   -- frozen at its reading at the onset;
* ``contact`` -- the element comes loose and reads mostly its housing's air:
  ``0.3 T + 0.7 T_amb`` from the onset.

Where: with several train campaigns, those from two thirds of the train calendar on, onset at
30 % of each; with one train campaign (forward chaining), from 60 % of it on.  ``KIND1`` (the
same sensor and fault in ONE unit): the last train campaign only, or from 95 % of the one on (the
last of the health step's 8 blocks of the record's second half).  Scenarios (seeds
fixed before any run; ``climate_room`` has extreme runs beyond the others, ``swiss_lathe_door``
no diagnose bench had used, ``twin_lathe`` is ``bench_new_machines57``'s record with its new
thermal state, the Saturday afternoon)::

    yearround_spindle   sim seed 0      24 campaigns, 16 train (leave campaigns out)
    climate_room        sim seed 5820   43 campaigns, 39 train
    swiss_lathe_door    sim seed 5820   one train campaign (forward)
    twin_lathe          bench_new_machines57 seed 5772, init's config (forward)

Sensor seeds: ``5831 + 10 * scenario index + kind index`` (scenario and kind in the orders above).
MLR base; the sim scenarios diagnose every target with ``max_effects=1`` (the health step is what
is scored), the twin lathe with its config (as ``bench_new_machines57``).  Row: per target the
excluded sensors, the accepted effects, test RMSE before / after; ``found``: the planted sensor
is excluded; ``healthy_removed``: other sensors excluded; ``planted_jump``: its self-prediction
jump ratio (first pass of the health step: nominated at ``fault_ratio``, 3); ``others_nominated``:
the other sensors at or above it (a removal is accepted only when no target needs the sensor).

Run on the code to compare (``PYTHONPATH=.../src``).

Measured 2026-11-30 (2 shared cores; 63 s CPU for the 20 cases on the shipped code)
------------------------------------------------------------------------------------
Shipped code: found / jump ratio of the planted sensor / healthy sensors removed besides::

    scenario            drift         offset        stuck         contact       clean
    yearround_spindle   no  3.9       no  4.1       no  6.1       no  8.7       -
    climate_room        yes 3.6       yes 3.5       yes 8.2       yes 5.8       -
    swiss_lathe_door    yes 6.3       no  1.6       yes 3.1       no  2.8       -
    twin_lathe          yes 4.5 +2    yes 3.1 +2    yes 3.8 +2    yes 3.7 +2    +2

10 of 16 found.  The year-round misses are nominated (ratio >= 3) but kept: a target's CV is
>= 5 % worse without the sensor (it is healthy in 11 of the 16 train campaigns; e.g. drift: E_Y
-5.4 %).  The swiss lathe's offset (1 K on a frame sensor) and lost contact of its spindle motor
sensor are not nominated.  Every twin-lathe case also removes the two healthy sensors of the
clean record (T_Bed_left_rear, T_Chuck_hydraulics: the Saturday afternoon, a new state).

The same faults in ONE unit (``KIND1``): 5 of 16 found (year-round drift1, offset1, stuck1; Swiss
lathe offset1, contact1), none on the climate room (ratios 1.5-15.5: nominated ones are kept, a
target needs the sensor) or the twin lathe.

Three rules to tell a new thermal state from a fault, each written down before it was scored
(the second and third after the first failed on the twin lathe), all REFUSED (no src change):

* **in-range rows**: a sensor's self-prediction error counts only on the rows where its
  predictors (the other sensors) lie within the range of the fold's fit rows (leverage,
  ``within_range`` on the predictors alone).  Faults found unchanged (10/16, the same cases), but
  the twin lathe still removes both healthy sensors: T_Chuck_hydraulics' predictors are in range on
  52 % of the Saturday block, and on those rows its error is still 0.56 degC (0.14-0.32 in the
  other blocks; ratio 3.5 >= 3).  CPU 100 s (the leverage per sensor and fold).
* **dynamic self-prediction**: each sensor predicted from the other sensors AND their first-order
  lags (``diagnose.taus_s``), the field's recent history carrying a new state.  The 108 lagged
  predictors overfit: the clean twin lathe removes 4 healthy sensors (E_Z2 0.3745 -> 0.4202 with
  ``families=[sensor_fault]``), the clean swiss lathe 1; found 8/16 (swiss stuck, twin offset and
  contact lost; swiss contact gained).
* **persistence**: the jump ratio on the sensor's SECOND-worst health unit (a fault stays; a state
  met once breaks one unit).  The clean twin lathe keeps its sensors (E_Z2 0.374 -> 0.572: the lag
  alone), but faults found 8/16 (swiss stuck, twin offset lost) and of the one-unit faults 0/16
  (5 before).  A fault met in one campaign and a state met once are the same evidence here.

Why the climate room's one-campaign faults are missed: offset1, stuck1, contact1 are nominated
(ratio 3.5-15.5) and their removal gains 22-80 % of CV RMSE, but on the rows where no fold
extrapolates it loses 5-18 %, and a removal must not lose 5 % there: those rows are judged on the
declared inputs WITH the suspect, whose fault takes its own campaign beyond the range.  A fourth
rule (written before scoring; not a new-state rule): judge them on the inputs the model without
the sensor keeps.  Only those three cases change (112 s CPU for the 36): all found, test RMSE
stuck1 E_X 0.589 -> 0.518, contact1 E_Z 0.381 -> 0.332, but offset1 E_X 0.336 -> 0.361 (+7.4 %),
E_Z 0.322 -> 0.371 (+15.2 %): the sensor is healthy in the test split, and removing it costs more
than the one faulty campaign did.  REFUSED by the 2 % bar of issue 34.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))

from thermocomp.apps.diagnose import SearchOptions, diagnose  # noqa: E402
from thermocomp.core.compensator import Compensator  # noqa: E402
from thermocomp.core.models import MLR  # noqa: E402

SCENARIOS = {"yearround_spindle": 0, "climate_room": 5820, "swiss_lathe_door": 5820, "twin_lathe": 5772}
KINDS = ["drift", "offset", "stuck", "contact"]
DRIFT_K_PER_H, OFFSET_K, CONTACT_SHARE = 0.3, 1.0, 0.3


def sensor_of(scenario: str, kind: str, sensors: list[str]) -> str:
    """The faulty sensor: drawn by the case's seed from the sorted non-ambient sensors."""
    seed = 5831 + 10 * list(SCENARIOS).index(scenario) + KINDS.index(kind)
    return str(np.random.default_rng(seed).choice(sorted(sensors)))


def break_sensor(frame, column: str, kind: str, onset_fraction: float):
    """``frame`` with ``column`` failing by ``kind`` from ``onset_fraction`` of its time on."""
    out = frame.copy()
    t = out["time"].to_numpy(float)
    t0 = t[0] + onset_fraction * (t[-1] - t[0])
    after = t >= t0
    x = out[column].to_numpy(float).copy()
    if kind == "drift":
        x[after] += DRIFT_K_PER_H * (t[after] - t0) / 3600.0
    elif kind == "offset":
        x[after] += OFFSET_K
    elif kind == "stuck":
        x[after] = x[np.argmax(after)]
    elif kind == "contact":
        x[after] = CONTACT_SHARE * x[after] + (1 - CONTACT_SHARE) * out["T_amb"].to_numpy(float)[after]
    else:
        raise ValueError(kind)
    out[column] = x
    return out


def plant(ds, scenario: str, kind: str) -> str:
    """Break the case's sensor in ``ds``'s train campaigns (in place); returns its name."""
    train = list(ds.ids("train"))
    first = ds.campaigns[train[0]]
    sensors = [c for c in first.columns if c.startswith("T_") and not c.startswith("T_amb")]
    once = kind.endswith("1")          # KIND1: the fault in one unit only
    kind = kind.rstrip("1")
    column = sensor_of(scenario, kind, sensors)
    if len(train) == 1:
        hit, onset = train, (0.95 if once else 0.6)
    else:
        hit, onset = (train[-1:] if once else train[int(np.ceil(2 * len(train) / 3)):]), 0.3
    for c in hit:
        ds.campaigns[c] = break_sensor(ds.campaigns[c], column, kind, onset)
    return column


def simulated(scenario: str):
    from hydra import compose, initialize_config_dir
    from hydra.utils import instantiate

    from thermocomp.base.paths import conf_dir

    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[f"sim={scenario}", f"seed={SCENARIOS[scenario]}",
                                                       "++sim.generator.clean=true"])
    return instantiate(cfg.sim.generator).generate()[0]


def case_data(case: str, root: Path):
    """(dataset, compensator, options, planted sensor or None) of ``SCENARIO:KIND``."""
    scenario, kind = case.split(":")
    if scenario == "twin_lathe":
        import bench_diagnose_lag57 as lag
        ds, comp, options = lag.machine_data(root, "twin_lathe")
    else:
        ds, comp, options = simulated(scenario), Compensator(MLR()), SearchOptions(max_effects=1)
    planted = plant(ds, scenario, kind) if kind != "clean" else None
    return ds, comp, options, planted


def row(case: str, root: Path) -> dict:
    ds, comp, options, planted = case_data(case, root)
    d = diagnose(ds, comp, None, "simulation", options)
    out = {"case": case, "planted": planted, "targets": {}}
    for t in d.targets:
        j = d.to_json(t)
        out["targets"][t] = {
            "excluded": j["excluded_inputs"],
            "accepted": [f'{e["kind"]} {e["column"]} {e["transform"]}' for e in j["effects"]
                         if e["accepted"] and e["kind"] != "sensor_fault"],
            "test_rmse": [round(j["before"]["test_rmse"], 4), round(j["after"]["test_rmse"], 4)],
            # the health step's removals tried: sensor, CV gain % (all rows, in range), accepted
            "health": [(e["column"], round(e["evidence"]["cv_rmse_gain_pct"], 2),
                        round(e["evidence"]["cv_rmse_gain_pct_in_range"], 2), e["accepted"])
                       for r in j["rounds"] if r["step"] == 0 for e in r["evaluated"]]}
    first = d.to_json(next(iter(d.targets)))
    excluded, table = first["excluded_inputs"], first["self_prediction"]
    jumps = {s["sensor"]: round(s["jump_ratio"], 2) for s in table}
    tol = options.candidates.fault_ratio
    out["found"] = planted in excluded if planted else None
    out["healthy_removed"] = [c for c in excluded if c != planted]
    out["planted_jump"] = jumps.get(planted) if planted else None
    out["others_nominated"] = {c: r for c, r in jumps.items() if r >= tol and c != planted}
    return out


def write(root: Path) -> None:
    import bench_new_machines57 as nm57
    nm57.write_twin_lathe(root / "nm57" / "twin_lathe", nm57.SEEDS["twin_lathe"])
    status, *_ = nm57.thermocomp("init", str(root / "nm57" / "twin_lathe"), *nm57.INIT_ARGS["twin_lathe"],
                                 f"out={root}/nm57/init-twin_lathe")
    assert status == 0


CASES = [f"{s}:{k}" for s in SCENARIOS for k in ["clean", *KINDS]]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("what", nargs="*")
    parser.add_argument("--root", type=Path, default=Path("/tmp/bench_diagnose_faults58"))
    args = parser.parse_intermixed_args(argv)
    root = args.root.resolve()
    if args.what[:1] == ["write"]:
        write(Path(args.what[1]).resolve() if len(args.what) > 1 else root)
        return 0
    for case in args.what or CASES:
        print(json.dumps(row(case, root)), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
