"""A sensor removal weighed where the sensor itself breaks: does the self-prediction per unit tell
the campaigns a removal should be judged on (stop 106, diag106d; issue 34: "``diagnose`` ...
never leaves a record's test error more than 2 % worse")?

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag106d.py units              # seen 10076: per train campaign
    python benchmarks/bench_diag106d.py split ROOT CASE ... # faults58 CASEs (data under ROOT)

``units``: the year-round VMC of seed 10076 (8 train / 4 test campaigns, ``sensor_drift`` on
``T_box1``), diagnosed at the defaults with ``max_effects=0`` (the health step only).  Per train
campaign: the planted drift at its end (the reading minus the clean twin's, same seed: the truth,
read here only to label), ``T_box1``'s self-prediction error over its own lower quartile (the
``own_ratio`` the nomination uses, per campaign), and the removal's held-out RMSE change per target
(+ worse without the sensor).  Then per target the removal's summed MSE change over the units
labelled broken / healthy, once by the self-prediction (own ratio >= ``fault_ratio``) and once
by the truth.  ``split``: bench_diagnose_faults58's CASEs (``bench_fault70 write`` makes ROOT),
every removal the health step weighed: units broken by the self-prediction, the keep-model's mean
MSE there over the healthy units', and the relative MSE change without the sensor on each side.

The rule asked (diag106b's "next"): take a removal only where its gain on the units where the
sensor breaks outweighs its cost where it is healthy.  No rule was committed and nothing scored:
the trace below, run first, shows that no weighting of the CV units by where the sensor breaks can
keep ``T_box1`` on 10076 (bar item 1), so the fresh seeds 10100-10104 were NOT drawn (unspent).

Measured 2026-12-07 (src b3391dc3; ``OMP_NUM_THREADS=1``, 2 shared cores; CPU user + sys by
``/usr/bin/time``: ``units`` 2.3 s, ``split`` 56.7 s)
---------------------------------------------------------------------------------------------
``units``: drift at the end 0 K in K01-K06, 2.3-3.6 K in K07-K12 (train K07 K08 K10 K11; test
K09 K12).  Per train campaign (K01 K02 K04 K05 | K07 K08 K10 K11)::

    own ratio (T_box1)   1.0  1.0  3.0  1.0 | 2.5  2.1  3.0  1.6
    E_Z change %         +10    0  -37   -3 | +39  +14  -35  -11

1. The self-prediction does not locate the fault when it is in half the train campaigns: the
   healthy K04 scores as high as the drifting K10 (3.0; its fold's fit is trained on 4 drifting
   of 7), the drifting K11 1.6, K07/K08 2.5/2.1.  (diag106: the same absorption hid 10077's jump.)
2. With the truth's labels the CV still favours the removal: E_Z's summed MSE changes by -9.17
   um^2 (-9.8 %) on the healthy train campaigns (K04 -37 %) and +0.66 (+0.6 %) on the drifting
   ones; by the self-prediction's split (broken: K10 only) -57.2 % broken, -1.0 % healthy; E_X /
   E_Y gain where broken (-30.7 / -35.8 %) and cost +5.7 / +2.9 % where healthy.  Yet on test the
   healthy K03 / K06 lose 35 / 56 % and the drifting K09 72 % (diag106; E_Z 4.565 -> 5.430 um).
   The harm is a CV-to-test gap on HEALTHY campaigns, which no weighting of the CV units by
   where the sensor breaks can see: every such rule removes ``T_box1`` (bar item 1 fails).
3. faults58 (``split``, 16 cases the shipped code finds or removes on, 56.7 s): a rule that asks
   the gain where broken would lose found faults whose CV costs there: climate_room:offset E_X
   +20.9 % broken / +0.3 % healthy, E_Z +10.7 % / -0.1 % (test 0.360 / 0.376 -> 0.361 / 0.372 um
   removed); climate_room:drift E_Z +1.6 % / +2.9 % (test 0.372 -> 0.326 removed).  twin_lathe:drift
   E_Z2 saves most where the sensor reads healthy (-55.5 % broken, -89.8 % healthy; test 1.105 ->
   0.331).  The keep-model's MSE broken / healthy runs 0.17 (that case) ... 109 (yearround
   stuck1 E_Z): neither side's CV change nor where the keep-model errs tells a saving removal from
   10076's.

Verdict: TRACED, no src change.  Next: a self-prediction fitted on the sensor's healthiest units
(not on all the others, which a fault in half the campaigns corrupts), or the drift's own shape
within each campaign (onset, then a ramp), before any weighting by it.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import run_commands  # noqa: E402

SEED, SENSOR, TARGETS = 10076, "T_box1", ("E_X", "E_Y", "E_Z")


def _year_round(effect: str | None, seed: int):
    """test_diagnose_few's machine: 12 campaigns (8 train, 4 test), ``effect`` planted (None: clean)."""
    from hydra import compose, initialize_config_dir
    from hydra.utils import instantiate

    from thermocomp.base.paths import conf_dir

    overrides = [f"seed={seed}", "sim.generator.n_campaigns=12",
                 f"++sim.generator.effects=[{effect}]" if effect else "++sim.generator.clean=true"]
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=overrides)
    return instantiate(cfg.sim.generator).generate()[0]


def unit_own_ratio(problem, inputs, sensor: str) -> np.ndarray:
    """``sensor``'s held-out self-prediction RMS per CV unit over its own lower quartile."""
    from thermocomp.apps.diagnose.sensors import _errors

    sensors = [c for c in inputs if c.startswith("T_")]
    j = sensors.index(sensor)
    E, _ = _errors(problem, problem.X[sensors].to_numpy(float), [j],
                   {j: [i for i in range(len(sensors)) if i != j]})
    ok = (problem.unit_index >= 0) & np.isfinite(E[:, 0])
    idx = problem.unit_index[ok]
    rms = np.sqrt(np.bincount(idx, weights=E[ok, 0] ** 2, minlength=problem.n_units)
                  / np.maximum(np.bincount(idx, minlength=problem.n_units), 1))
    return rms / np.quantile(rms, 0.25)


def _traced(report):
    """diagnose with its health step wrapped: ``report(first_search, target, evaluation, before)``
    for every removal weighed."""
    import thermocomp.apps.diagnose.diagnosis as dg

    shipped = dg.sensor_health

    def traced(searches, options=None, start=None):
        out = shipped(searches, options=options, start=start)
        first = next(iter(searches.values()))
        for t, rnd in out[2].items():
            for ev in (rnd.evaluated if rnd else []):
                report(first, t, ev, out[3][t].unit_mse, options)
        return out

    return dg, shipped, traced


def units() -> None:
    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    ds, clean = _year_round("sensor_drift", SEED), _year_round(None, SEED)
    drift = {k: float(ds.campaigns[k][SENSOR].to_numpy()[-1] - clean.campaigns[k][SENSOR].to_numpy()[-1])
             for k in ds.campaigns}
    print("drift at the end (K):", {k: round(v, 2) for k, v in drift.items()})

    def report(first, t, ev, before, options):
        p = first.problem
        names = list(p.unit_names)
        own = unit_own_ratio(p, first.inputs([]), ev.effect.column)
        after = ev.result.unit_mse
        change = 100.0 * (np.sqrt(after / before) - 1.0)
        print(f"{t} without {ev.effect.column}: pooled gain {ev.gain_pct:+.2f} %, excluded {ev.accepted}")
        print("  ", "  ".join(f"{n} own {o:.1f} {c:+.0f} %" for n, o, c in zip(names, own, change)))
        d = after - before
        labels = {"self-prediction": own >= options.candidates.fault_ratio,
                  "truth": np.array([drift[n] > 0 for n in names])}
        for how, broken in labels.items():
            sides = [f"{side} {d[m].sum():+.3g} ({d[m].sum() / before[m].sum():+.1%})"
                     for side, m in (("broken", broken), ("healthy", ~broken))]
            print(f"   {how}: MSE change " + ", ".join(sides))

    dg, shipped, traced = _traced(report)
    dg.sensor_health = traced
    try:
        d = diagnose(ds, Compensator(MLR()), targets=list(TARGETS), options=SearchOptions(max_effects=0))
    finally:
        dg.sensor_health = shipped
    for t in TARGETS:
        j = d.to_json(t)
        print(f"test {t}: {j['before']['test_rmse']:.3f} -> {j['after']['test_rmse']:.3f} um, "
              f"excluded {j['excluded_inputs']}")


def split(root: str, *cases: str) -> None:
    import bench_diagnose_faults58 as f58

    from thermocomp.apps.diagnose import diagnose

    def report(first, t, ev, before, options):
        own = unit_own_ratio(first.problem, first.inputs([]), ev.effect.column)
        broken = own >= options.candidates.fault_ratio
        d = ev.result.unit_mse - before
        ratio = (np.mean(before[broken]) / np.mean(before[~broken])) if broken.any() else float("nan")
        rel = [d[m].sum() / before[m].sum() if m.any() else float("nan") for m in (broken, ~broken)]
        print(f"{case} {t} {ev.effect.column}: pooled gain {ev.gain_pct:+.2f} %, broken units "
              f"{int(broken.sum())}, keep-model MSE broken/healthy {ratio:.3f}, MSE change broken "
              f"{rel[0]:+.1%} healthy {rel[1]:+.1%}, excluded {ev.accepted}")

    dg, shipped, traced = _traced(report)
    dg.sensor_health = traced
    try:
        for case in cases:
            ds, comp, options, _ = f58.case_data(case, Path(root))
            d = diagnose(ds, comp, None, "simulation", options)
            for t in d.targets:
                j = d.to_json(t)
                print(f"  test {case} {t}: {j['before']['test_rmse']:.4f} -> {j['after']['test_rmse']:.4f}")
    finally:
        dg.sensor_health = shipped


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"units": units, "split": split}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
