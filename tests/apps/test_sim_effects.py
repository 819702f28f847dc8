"""Undeclared effects of issue 3: each one leaves an MLR residual that its cause explains.

Every effect is planted on a small year-round dataset (9 campaigns, 3 held
out); an MLR on the declared inputs (every ``T_`` rise) is fitted on train and
its test residual is regressed on the planted cause (a few first-order lags of
it) and, as a control, on the same transform of a random signal of the same
kind.  The cause must explain most of the residual, the control little.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from thermocomp.apps.sim import YearRoundSpindle
from thermocomp.apps.sim.ambient import AmbientModel
from thermocomp.apps.sim.campaign import Programme, run_campaign
from thermocomp.apps.sim.effects import EFFECTS, KINDS, AmbientLaw, LagNode
from thermocomp.apps.sim.sensors import first_order_lag
from thermocomp.apps.sim.vmc import VMC_EFFECTS, vertical_machining_centre
from thermocomp.base.errors import ConfigError

KW = dict(n_campaigns=9, duration_h=(4.0, 6.0), seed=0)
TAUS = (600.0, 1800.0, 3600.0, 7200.0)


@pytest.fixture(scope="session")
def base():
    return YearRoundSpindle(**KW).generate()[0]


def planted(effect, kw=KW, **params):
    gen = YearRoundSpindle(effects=[effect], effect_params={effect: params} if params else None, **kw)
    ds, truth = gen.generate()
    return gen, ds, truth, truth["undeclared_effects"][0]


def test_residual(ds, target):
    """Per test campaign: MLR (T_ rises + intercept, fitted on train) residual of ``target``."""
    sensors = ds.columns_of("T_")

    def design(cid):
        f = ds.campaigns[cid]
        return np.column_stack([np.ones(len(f)), (f[sensors] - f[sensors].iloc[0]).to_numpy()])

    def target_of(cid):
        f = ds.campaigns[cid]
        return (f[target] - f[target].iloc[0]).to_numpy()

    train = ds.ids("train")
    coef, *_ = np.linalg.lstsq(np.vstack([design(c) for c in train]),
                               np.concatenate([target_of(c) for c in train]), rcond=None)
    return {cid: target_of(cid) - design(cid) @ coef for cid in ds.ids("test")}


test_residual.__test__ = False  # a helper, not a test


def explained(residuals: dict, features: dict) -> float:
    """R² of the pooled residual regressed (with an intercept per campaign) on the features."""
    ids = list(residuals)
    y = np.concatenate([residuals[c] - residuals[c].mean() for c in ids])
    x = np.vstack([features[c] - features[c].mean(0) for c in ids])
    coef, *_ = np.linalg.lstsq(x, y, rcond=None)
    return 1.0 - ((y - x @ coef) ** 2).sum() / (y**2).sum()


def refit_ratio(ds, target, features: dict) -> float:
    """Test RMSE of the MLR with ``features`` (campaign id -> rows x k) added, over the MLR's alone."""
    sensors = ds.columns_of("T_")

    def fit_rmse(extra):
        def design(cid):
            f = ds.campaigns[cid]
            x = [np.ones(len(f)), (f[sensors] - f[sensors].iloc[0]).to_numpy()]
            return np.column_stack(x + ([extra[cid]] if extra else []))

        def y(cid):
            f = ds.campaigns[cid]
            return (f[target] - f[target].iloc[0]).to_numpy()

        train, test = ds.ids("train"), ds.ids("test")
        coef, *_ = np.linalg.lstsq(np.vstack([design(c) for c in train]),
                                   np.concatenate([y(c) for c in train]), rcond=None)
        return np.sqrt(np.mean(np.concatenate([y(c) - design(c) @ coef for c in test]) ** 2))

    return fit_rmse(features) / fit_rmse(None)


def check_refit(ds, target, cause: dict, control: dict):
    """The residual is dominated by the cause: adding it cuts the test RMSE, adding the control does not."""
    with_cause, with_control = refit_ratio(ds, target, cause), refit_ratio(ds, target, control)
    print(f"\ntest RMSE with / without: cause {with_cause:.2f}, random control {with_control:.2f}")
    assert with_cause < 0.7 and with_control > 0.9


def lags(signal: np.ndarray, step: float = 300.0) -> np.ndarray:
    x = np.asarray(signal, dtype=float)[:, None]
    return np.column_stack([x] + [first_order_lag(x, [tau], step) for tau in TAUS])


def switching(rng, n, duty=0.2):
    """A random 0/1 signal with runs of a few samples (a door-like control)."""
    out, k = np.zeros(n), 0
    while k < n:
        length = int(rng.integers(1, 5))
        out[k:k + length] = float(rng.random() < duty)
        k += length
    return out


def random_walk(rng, n):
    return np.cumsum(rng.standard_normal(n))


def check(residuals, cause, control):
    r_cause, r_control = explained(residuals, cause), explained(residuals, control)
    print(f"\nR² of the residual: cause {r_cause:.2f}, random control {r_control:.2f}")
    assert r_cause > 0.5 and r_control < 0.25 and r_cause > 3 * r_control


def test_door_residual_follows_the_door(base):
    gen, ds, truth, rec = planted("door")
    assert (rec["kind"], rec["column"]) == ("signal", "S_door") and "S_door" not in ds.columns_of("T_")
    residuals = test_residual(ds, "E_Y")
    rng = np.random.default_rng(1)
    cause = {c: lags(ds.campaigns[c]["S_door"]) for c in residuals}
    control = {c: lags(switching(rng, len(r))) for c, r in residuals.items()}
    check(residuals, cause, control)


def test_hidden_source_residual_follows_the_oil_temperature(base):
    gen, ds, truth, rec = planted("hidden_source")
    column = rec["column"]
    assert rec["kind"] == "signal" and column.startswith("S_") and column in ds.columns
    residuals = test_residual(ds, "E_Y")
    rng = np.random.default_rng(2)
    cause = {c: lags(ds.campaigns[c][column] - ds.campaigns[c][column].iloc[0]) for c in residuals}
    control = {c: lags(random_walk(rng, len(r))) for c, r in residuals.items()}
    check(residuals, cause, control)
    # Only the oil temperature sees it: the declared sensors' rises change by a few per cent of its rise.
    for cid in ds.ids():
        f, b = ds.campaigns[cid], base.campaigns[cid]
        sensors = ds.columns_of("T_")
        change = ((f[sensors] - f[sensors].iloc[0]) - (b[sensors] - b[sensors].iloc[0])).abs().max().max()
        assert change < 0.05 * np.ptp(f[column])


def test_lag_node_residual_follows_the_hidden_mass(base):
    """The lag mass's rise is mostly collinear with the sensors; what they miss, it explains."""
    gen, ds, truth, rec = planted("lag_node")
    assert (rec["kind"], rec["column"]) == ("dynamics", None)
    rng = np.random.default_rng(3)
    mass = {c: gen.node_temperatures_[c]["lag_mass"].to_numpy() for c in ds.ids()}
    cause = {c: (m - m[0])[:, None] for c, m in mass.items()}
    control = {c: random_walk(rng, len(m))[:, None] for c, m in mass.items()}
    check_refit(ds, "E_X", cause, control)


def test_lag_node_delays_the_error_behind_the_sensors():
    """Run 3 h then stop: the sensors peak at the stop, the error the lag mass adds hours later."""
    machine = vertical_machining_centre()
    lagged = LagNode(0, **VMC_EFFECTS["lag_node"]).modify_machine(machine)
    programme = Programme(((0.0, 6000.0), (3 * 3600.0, 0.0)))
    runs = [run_campaign(m, AmbientModel(daily_amplitude_c=0.0, drift_sd_c=0.0), programme, 100 * 86400.0,
                         10 * 3600.0, np.random.default_rng(4))[0] for m in (machine, lagged)]
    added = runs[1]["E_X"] - runs[0]["E_X"]
    sensor_peak = runs[1]["time"][runs[1]["T_box1"].idxmax()]
    error_peak = runs[1]["time"][added.idxmax()]
    assert sensor_peak <= 3.5 * 3600 and error_peak >= sensor_peak + 3600
    assert added.max() > 5.0


def test_axis_position_residual_is_position_times_tilt(base):
    gen, ds, truth, rec = planted("axis_position")
    assert (rec["kind"], rec["column"]) == ("interaction", "S_pos_Z")
    residuals = test_residual(ds, "E_Y")
    rng = np.random.default_rng(5)
    tilt_nodes = rec["params"]["tilt_nodes"]

    def tilt(c):
        n = gen.node_temperatures_[c]
        return sum(w * (n[k] - n[k].iloc[0]) for k, w in tilt_nodes.items()).to_numpy()

    position = {c: ds.campaigns[c]["S_pos_Z"].to_numpy() for c in residuals}
    assert all(p[0] == rec["params"]["home_mm"] for p in position.values())
    cause = {c: (tilt(c) * (p - p[0]))[:, None] for c, p in position.items()}
    # Control: the same tilt through a random position of the same travel.
    control = {c: (tilt(c) * rng.permutation(p - p[0]))[:, None] for c, p in position.items()}
    check(residuals, cause, control)


def test_sensor_drift_residual_follows_the_fault_and_the_sensor_departs():
    """Healthy in training, drifting in the later held-out campaigns (the scenario's default drifts
    the later train campaigns too): the fault is what the MLR misses."""
    kw = {**KW, "n_campaigns": 18}
    base = YearRoundSpindle(**kw).generate()[0]
    gen, ds, truth, rec = planted("sensor_drift", kw=kw, splits=["test"])
    column = rec["column"]
    assert rec["kind"] == "sensor_fault" and column in ds.columns_of("T_")
    residuals = {c: r for c, r in test_residual(ds, "E_Z").items()
                 if "sensor_drift" in truth["campaigns"][c].get("effects", {})}
    rng = np.random.default_rng(6)
    fault = {c: (ds.campaigns[c][column] - base.campaigns[c][column]).to_numpy() for c in residuals}
    assert any(np.ptp(f) > 1.0 for f in fault.values())
    cause = {c: f[:, None] for c, f in fault.items()}
    control = {c: random_walk(rng, len(r))[:, None] for c, r in residuals.items()}
    check(residuals, cause, control)
    # The faulty sensor departs from its neighbour on the same casting, the healthy ones do not.
    affected = [c for c in ds.ids() if "sensor_drift" in truth["campaigns"][c].get("effects", {})]
    assert affected and set(affected) <= set(ds.ids("test"))
    for cid in ds.ids():
        f = ds.campaigns[cid]
        gap = (f[column] - f["T_box2"]) - (f[column] - f["T_box2"]).iloc[0]
        assert (gap.abs().max() > 1.5) == (cid in affected)


def test_ambient_law_residual_follows_the_interval(base):
    gen, ds, truth, rec = planted("ambient_law")
    assert (rec["kind"], rec["column"]) == ("ambient_interval", None)
    law = AmbientLaw(**rec["params"])
    rng = np.random.default_rng(7)
    sensors = ds.columns_of("T_")

    def rises(c):
        f = ds.campaigns[c]
        return (f[sensors] - f[sensors].iloc[0]).to_numpy()

    level = rec["params"]["level_node"]
    factor = {c: law.factor(gen.node_temperatures_[c][level].to_numpy()) for c in ds.ids()}
    above = {c: bool(f.mean() > 0.5 * law.params["gain"]) for c, f in factor.items()}
    assert {above[c] for c in ds.ids("test")} == {True, False}      # both intervals held out
    # Cause: the sensor rises in the upper interval; control: in a random half of the campaigns.
    cause = {c: factor[c][:, None] * rises(c) for c in ds.ids()}
    coin = dict(zip(ds.ids(), rng.permutation([k % 2 for k in range(len(ds.ids()))])))
    control = {c: coin[c] * rises(c) for c in ds.ids()}
    check_refit(ds, "E_Y", cause, control)


def test_truth_records_every_effect_and_pairs_the_data(base):
    ds, truth = YearRoundSpindle(effects=list(EFFECTS), **KW).generate()
    json.dumps(truth)
    records = truth["undeclared_effects"]
    assert [r["name"] for r in records] == list(EFFECTS)
    for r in records:
        assert set(r) >= {"name", "kind", "column", "description", "params", "targets"} and r["kind"] in KINDS
    assert {"S_door", "S_hydraulic_temp_C", "S_pos_Z"} <= set(ds.columns)
    # Effects use their own random streams: one that changes no temperature leaves every sensor as it was.
    moved, _ = YearRoundSpindle(effects=["axis_position"], **KW).generate()
    for cid in base.ids():
        cols = base.columns_of("T_") + ["S_spindle_rpm"]
        np.testing.assert_array_equal(moved.campaigns[cid][cols], base.campaigns[cid][cols])


@pytest.mark.parametrize("kwargs, match", [
    (dict(effects=["doors"]), "unknown effect"),
    (dict(effects=["door"], effect_params={"door": {"rate": 1}}), "unknown key"),
    (dict(effects=["lag_node"], effect_params={"lag_node": {"parent": "spindle_nose"}}), "unknown node"),
    (dict(effects=["sensor_drift"], effect_params={"sensor_drift": {"column": "T_x"}}), "no sensor"),
    (dict(effects=["door", "door"]), "twice"),
    (dict(effects=["door"], effect_params={"door": {"duration_min": 5}}),
     r"door.duration_min=5: must be a pair"),
    (dict(effects=["lag_node"], effect_params={"lag_node": {"capacity_J_per_K": 0}}),
     r"lag_node.capacity_J_per_K=0: must be a number > 0"),
    (dict(effects=["hidden_source"], effect_params={"hidden_source": {"on_min": [5, 1]}}),
     r"hidden_source.on_min=\[5, 1\]: must be a pair \[low, high\]"),
    (dict(effects=["ambient_law"], effect_params={"ambient_law": {"width_c": -0.1}}), r"width_c=-0.1"),
    (dict(effects=["sensor_drift"], effect_params={"sensor_drift": {"mode": "wobble"}}),
     "one of drift, stuck"),
    (dict(effects=["axis_position"], effect_params={"axis_position": {"tilt_nodes": {"column": "a"}}}),
     "a map of names to numbers"),
])
def test_bad_effect_config_is_a_config_error(kwargs, match):
    with pytest.raises(ConfigError, match=match):
        YearRoundSpindle(n_campaigns=3, **kwargs).generate()
