"""ARX + random forest on the logistic-smoothed door signal (paper 004)."""

import pickle

import numpy as np
import pandas as pd
import pytest
from scipy.special import expit
from sklearn.ensemble import RandomForestRegressor
from sklearn.utils.estimator_checks import check_estimator

from thermocomp.core.compensator import Compensator
from thermocomp.core.io.contract import ContractError
from thermocomp.core.models import ARX, ARXRF
from thermocomp.core.models._dynamics import free_run
from thermocomp.core.models.arx_rf import logistic_switching


def door_campaign(rng, n=480, dt=60.0, door_um=-6.0, tau_door_s=900.0):
    """8 h at 1 min: heating seen by T_1, ambient wave T_2, and door openings no sensor sees.

    The door cools the measured error through a first-order lag (``tau_door_s``).
    """
    t = np.arange(n) * dt
    a_heat = np.exp(-dt / 3600)
    load = np.r_[np.full(n // 2, 8.0), np.full(n - n // 2, 3.0)]
    T1 = 20 + free_run(a_heat, (1 - a_heat) * load, None) + rng.normal(0, 0.02, n)
    T2 = 20 + 0.5 * np.sin(t / 7000) + rng.normal(0, 0.02, n)
    door = np.zeros(n)
    for start in rng.choice(np.arange(30, n - 40), size=4, replace=False):
        door[start:start + rng.integers(5, 25)] = 1.0
    a_door = np.exp(-dt / tau_door_s)
    E = (3.0 * (T1 - T1[0]) - 2.0 * (T2 - T2[0]) + door_um * free_run(a_door, (1 - a_door) * door, None)
         + rng.normal(0, 0.1, n))
    return pd.DataFrame({"time": t, "T_1": T1, "T_2": T2, "T_3": 20 + rng.normal(0, 0.05, n),
                         "S_door": door, "E_X": E})


@pytest.fixture(scope="session")
def door_data():
    rng = np.random.default_rng(0)
    train = {f"K{i}": door_campaign(rng) for i in range(6)}
    test = {f"V{i}": door_campaign(rng) for i in range(3)}
    return train, test


def small_forest():
    return RandomForestRegressor(n_estimators=20, min_samples_leaf=5, random_state=0)


def test_logistic_switching_ramps_from_each_switch_and_is_causal():
    t = np.arange(10) * 60.0
    door = np.array([0, 0, 1, 1, 1, 1, 0, 0, 0, 0], dtype=float)
    s = logistic_switching(door, t, tau_s=60.0)[:, 0]
    np.testing.assert_allclose(s[:2], 0.0)                         # no switch yet: the state itself
    np.testing.assert_allclose(s[2:6], expit((t[2:6] - 120.0) / 60.0))   # opening at 120 s: rise
    np.testing.assert_allclose(s[6:], expit(-(t[6:] - 360.0) / 60.0))   # closing at 360 s: fall
    assert s[2] == 0.5 and s[6] == 0.5
    # causal: changing the future never changes the past
    future = door.copy()
    future[7:] = 1.0
    np.testing.assert_array_equal(logistic_switching(future, t)[:7], logistic_switching(door, t)[:7])
    # restarts per campaign; one column per time scale
    two = logistic_switching(np.r_[door, door], np.r_[t, t], groups=np.repeat(["a", "b"], 10),
                             tau_s=[60.0, 600.0])
    assert two.shape == (20, 2)
    np.testing.assert_allclose(two[10:, 0], s)


def test_arx_rf_passes_sklearn_checks_without_a_state_signal():
    # check_estimator cannot pass a context; state_column=None is the documented configuration for it
    check_estimator(ARXRF(state_column=None, forest=small_forest()))


def test_arx_rf_beats_arx_on_door_openings(door_data):
    train, test = door_data
    scores = {}
    for name, est in {"arx": ARX(), "arx_rf": ARXRF(forest=small_forest())}.items():
        comp = Compensator(est).fit(train)            # S_door reaches ARXRF through the context
        pred, meas = comp.predict(test), comp.measured(test)
        resid = np.concatenate([(meas[c]["E_X"] - pred[c]["E_X"]).to_numpy() for c in test])
        scores[name] = np.sqrt(np.mean(resid ** 2))
    assert scores["arx_rf"] < 0.6 * scores["arx"], scores


def test_arx_rf_one_step_uses_its_own_forest(door_data):
    train, _ = door_data
    comp = Compensator(ARXRF(arx=ARX(ar=True), forest=small_forest())).fit(train)
    est = comp.estimators_["E_X"]
    assert est.forest_one_step_ is not None
    one = comp.predict(train, mode="one_step")["K0"]["E_X"]
    sim = comp.predict(train)["K0"]["E_X"]
    meas = comp.measured(train)["K0"]["E_X"]
    assert np.sqrt(np.mean((meas - one) ** 2)) < np.sqrt(np.mean((meas - sim) ** 2))


def test_streaming_reproduces_simulation_predict(door_data):
    train, _ = door_data
    camps = {c: train[c] for c in ("K0", "K1")}
    comp = Compensator(ARXRF(arx=ARX(ar=True), forest=small_forest(), tau_s=[60.0, 600.0])).fit(camps)
    est = comp.estimators_["E_X"]
    for cid, df in list(camps.items())[1:]:          # the second campaign: states restart
        X = (df[comp.selected_["E_X"]] - df[comp.selected_["E_X"]].iloc[0]).to_numpy()
        batch = comp.predict({cid: df})[cid]["E_X"].to_numpy()
        state, stream = est.stream_init({}), []
        for t in range(len(df)):
            y_hat, state = est.stream_step(X[t], state, context={"time": df["time"].iloc[t],
                                                                 "S_door": df["S_door"].iloc[t]})
            stream.append(y_hat)
        np.testing.assert_allclose(stream, batch, rtol=0, atol=1e-9)


def test_pickle_round_trip_identical_predictions(door_data):
    train, test = door_data
    comp = Compensator(ARXRF(forest=small_forest())).fit(train)
    again = pickle.loads(pickle.dumps(comp))
    for mode in ("simulation", "one_step"):
        pd.testing.assert_frame_equal(comp.predict(test, mode=mode)["V0"],
                                      again.predict(test, mode=mode)["V0"])


def test_missing_state_column_is_a_clear_contract_error(door_data):
    train, _ = door_data
    no_door = {c: df.drop(columns="S_door") for c, df in train.items()}
    with pytest.raises(ContractError, match="S_door"):
        Compensator(ARXRF(forest=small_forest())).fit(no_door)
