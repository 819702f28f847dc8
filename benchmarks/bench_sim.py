"""Digital twin scenarios: generation time, and how strongly each undeclared effect shows.

    .venv/bin/python benchmarks/bench_sim.py                 # all scenarios, all effects
    .venv/bin/python benchmarks/bench_sim.py --scenario yearround_spindle --effect door

For each scenario: seconds to generate at default size (best of ``--repeat``).
For each scenario x effect: test RMSE (µm) of an MLR on the declared inputs
(every ``T_`` column, referenced to the first sample, fitted on the train
split) on the effect's target(s), "before"; and "after", the same MLR with the
true effect signal added:

* door: first-order lags (2 min .. 2 h) of the door's heat flow into each
  exposed node, :math:`S_{door}\\,g_j\\,(T_a + \\Delta T_{air} - T_j)`; also
  ``obs``: lags of ``S_door`` alone;
* hidden_source: the controller's oil temperature column and its lags (15 min .. 4 h);
* lag_node: the lag mass's rise (true node); ``obs``: a lag of the parent's
  best sensor with the true time constant;
* axis_position: tilt x (p - p0) from the true node rises; ``obs``: products
  of ``S_pos`` (referenced) with every declared sensor;
* sensor_drift: the faulty column repaired (the paired healthy reading);
  ``obs``: the faulty column dropped;
* ambient_law: every sensor rise times the true interval factor.

Every scenario x effect pair is generated with the same seed as the scenario
without effect, so the data differ by the effect only.  Numbers are printed,
never asserted; report them with ``uptime`` (2 shared cores).
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

from thermocomp.apps.sim.effects import EFFECTS
from thermocomp.apps.sim.sensors import first_order_lag

SCENARIOS = {
    "yearround_spindle": "thermocomp.apps.sim.yearround:YearRoundSpindle",
    "large_mill_week": "thermocomp.apps.sim.large_mill:LargeMillWeek",
    "swiss_lathe_door": "thermocomp.apps.sim.swiss_lathe:SwissLatheDoor",
    "column_moving_source": "thermocomp.apps.sim.column:ColumnMovingSource",
}


def generator(name, **kw):
    module, cls = SCENARIOS[name].split(":")
    return getattr(__import__(module, fromlist=[cls]), cls)(**kw)


def _lags(x: np.ndarray, step: float, taus) -> np.ndarray:
    x = np.atleast_2d(x.T).T
    return np.column_stack([first_order_lag(x, [tau] * x.shape[1], step) for tau in taus])


def _design(ds, cid, sensors, extra):
    f = ds.campaigns[cid]
    x = (f[sensors] - f[sensors].iloc[0]).to_numpy()
    return x if extra is None else np.column_stack([x, extra(cid, f)])


def mlr_test_rmse(ds, targets, extra=None, drop=()):
    """RMSE on the test split of least squares (+ intercept) fitted on train."""
    sensors = [c for c in ds.columns if c.startswith("T_") and c not in drop]

    def stack(split):
        ids = ds.ids(split)
        x = np.vstack([_design(ds, cid, sensors, extra) for cid in ids])
        y = np.vstack([(ds.campaigns[c][targets] - ds.campaigns[c][targets].iloc[0]).to_numpy() for c in ids])
        return np.column_stack([np.ones(len(x)), x]), y

    (a, b), (c, d) = stack("train"), stack("test")
    coef, *_ = np.linalg.lstsq(a, b, rcond=None)
    return np.sqrt(((d - c @ coef) ** 2).mean(axis=0))


def true_signals(name, rec, gen, ds, base_ds):
    """(after-features, observable features or None, drop) for one planted effect."""
    nodes = gen.node_temperatures_
    p = rec["params"]

    def step(f):
        return float(f["time"].iloc[1] - f["time"].iloc[0])

    if name == "door":
        def door(cid, f):
            n = nodes[cid]
            flows = np.column_stack([n[p["column"]] * g * (n["ambient"] + p["air_offset_c"] - n[node])
                                     for node, g in p["nodes"].items()])
            return _lags(flows, step(f), (120, 300, 900, 1800, 3600, 7200))
        def door_signal(cid, f):
            return _lags(f[[p["column"]]].to_numpy(), step(f), (120, 300, 900, 1800, 3600, 7200))
        return door, door_signal, ()
    if name == "hidden_source":
        def oil(cid, f):
            x = (f[[rec["column"]]] - f[rec["column"]].iloc[0]).to_numpy()
            return np.column_stack([x, _lags(x, step(f), (900, 1800, 3600, 7200, 14400))])
        return oil, None, ()
    if name == "lag_node":
        array, index = gen.machine().sensor_array, gen.machine().network.index
        parent_sensor = array.columns[int(np.argmax(array.weights[:, index[p["parent"]]]))]

        def mass(cid, f):
            m = nodes[cid]["lag_mass"].to_numpy()
            return (m - m[0])[:, None]

        def obs(cid, f):
            x = (f[[parent_sensor]] - f[parent_sensor].iloc[0]).to_numpy()
            return first_order_lag(x, [p["time_constant_s"]], step(f))
        return mass, obs, ()
    if name == "axis_position":
        def product(cid, f):
            n = nodes[cid]
            tilt = sum(w * (n[node] - n[node].iloc[0]) for node, w in p["tilt_nodes"].items())
            return (tilt * (f[rec["column"]] - f[rec["column"]].iloc[0]) / 1000.0).to_numpy()[:, None]

        def obs(cid, f):
            temps = [c for c in f.columns if c.startswith("T_")]
            dp = (f[rec["column"]] - f[rec["column"]].iloc[0]).to_numpy()[:, None] / 1000.0
            return dp * (f[temps] - f[temps].iloc[0]).to_numpy()
        return product, obs, ()
    if name == "sensor_drift":
        col = rec["column"]

        def repaired(cid, f):   # healthy reading minus the faulty one, so X + this = healthy X
            g = base_ds.campaigns[cid]
            return ((g[col] - g[col].iloc[0]) - (f[col] - f[col].iloc[0])).to_numpy()[:, None]
        return repaired, None, (col,)
    if name == "ambient_law":
        from thermocomp.apps.sim.effects import AmbientLaw
        law = AmbientLaw(**p)

        def interval(cid, f):
            temps = [c for c in f.columns if c.startswith("T_")]
            n = nodes[cid]
            level = law.level(n.to_numpy(), n["ambient"].to_numpy(), f["time"].to_numpy(),
                              {c: i for i, c in enumerate(n.columns)})
            factor = law.factor(level)[:, None]
            return factor * (f[temps] - f[temps].iloc[0]).to_numpy()
        return interval, None, ()
    raise KeyError(name)


# sensor_faults changes test readings, not the physics: nothing for an MLR residual to show;
# ageing changes the law after training (the test campaigns only): no feature of the train
# campaigns shows it, the reference measurements of `adapt` do (bench_adapt.py).
MEASURED = [e for e in EFFECTS if e not in ("sensor_faults", "ageing")]

# Q3 (test-only source of column_moving_source) would dominate every test residual: the effects
# are measured on that scenario without it.
EFFECT_KW = {"column_moving_source": {"q3": False}}


def measure(scenario, effect, base=None, **kw):
    """Before/after RMSE of one effect on one scenario (dict of arrays per target)."""
    base_ds = base if base is not None else generator(scenario, **kw).generate()[0]
    gen = generator(scenario, effects=[effect], **kw)
    ds, truth = gen.generate()
    rec = next(e for e in truth["undeclared_effects"] if e["name"] == effect)
    targets = rec["targets"]
    after_features, obs_features, drop = true_signals(effect, rec, gen, ds, base_ds)
    out = {"targets": targets, "before": mlr_test_rmse(ds, targets),
           "baseline": mlr_test_rmse(base_ds, targets)}
    if effect == "sensor_drift":   # after: the faulty column repaired = the paired healthy data
        out["after"] = out["baseline"]
        out["obs"] = mlr_test_rmse(ds, targets, drop=drop)
    else:
        out["after"] = mlr_test_rmse(ds, targets, extra=after_features)
        if obs_features is not None:
            out["obs"] = mlr_test_rmse(ds, targets, extra=obs_features)
    return out


def _fmt(values):
    return "/".join(f"{v:.2f}" for v in values)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", choices=list(SCENARIOS), action="append")
    parser.add_argument("--effect", choices=MEASURED, action="append")
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--no-effects", action="store_true")
    args = parser.parse_args(argv)
    print(f"load: {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f} {os.getloadavg()[2]:.2f} (1/5/15 min), "
          f"{os.cpu_count()} cores")
    for scenario in args.scenario or list(SCENARIOS):
        times = []
        for _ in range(args.repeat):
            t0 = time.perf_counter()
            base, _ = generator(scenario).generate()
            times.append(time.perf_counter() - t0)
        rows = sum(len(f) for f in base.campaigns.values())
        print(f"\n{scenario}: generated in {min(times):.2f} s (best of {args.repeat}), {len(base.campaigns)} "
              f"campaigns, {rows} rows, {len(base.columns)} columns")
        if args.no_effects:
            continue
        print(f"  {'effect':15s} {'targets':10s} {'baseline':>13s} {'before':>13s} {'after':>13s} "
              f"{'ratio':>11s} {'obs':>13s} {'obs ratio':>11s}")
        kw = EFFECT_KW.get(scenario, {})
        if kw:
            print(f"  (effects measured with {kw})")
            base, _ = generator(scenario, **kw).generate()
        for effect in args.effect or MEASURED:
            r = measure(scenario, effect, base=base, **kw)
            ratio = r["after"] / r["before"]
            obs = r.get("obs")
            print(f"  {effect:15s} {','.join(r['targets']):10s} {_fmt(r['baseline']):>13s} "
                  f"{_fmt(r['before']):>13s} "
                  f"{_fmt(r['after']):>13s} {_fmt(ratio):>11s} "
                  f"{_fmt(obs) if obs is not None else '-':>13s} "
                  f"{_fmt(obs / r['before']) if obs is not None else '-':>11s}")


if __name__ == "__main__":
    main()
