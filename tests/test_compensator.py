import pickle

import numpy as np
import pandas as pd
import pytest
from sklearn.utils.estimator_checks import check_estimator

from thermocomp.compensator import Compensator
from thermocomp.io.contract import ContractError
from thermocomp.models import MLR


def _campaign(rng, n=50, offset=20.0):
    t = np.arange(n) * 300.0
    T1 = offset + np.linspace(0, 8, n) + rng.normal(0, 0.01, n)
    T2 = offset + np.sin(t / 5000) + rng.normal(0, 0.01, n)
    df = pd.DataFrame({"time": t, "T_1": T1, "T_2": T2, "S_rpm": 4000.0})
    df["E_Z"] = 3.0 * (T1 - T1[0]) - 1.5 * (T2 - T2[0]) + rng.normal(0, 0.05, n)
    df["E_X"] = 0.5 * (T2 - T2[0])
    return df


def test_mlr_passes_sklearn_checks():
    check_estimator(MLR())


def test_compensator_recovers_coefficients_in_referenced_frame():
    rng = np.random.default_rng(0)
    camps = {f"K{i}": _campaign(rng, offset=5 + 3 * i) for i in range(4)}
    comp = Compensator(MLR()).fit(camps)
    est = comp.estimators_["E_Z"]
    assert comp.selected_["E_Z"] == ["T_1", "T_2"]
    np.testing.assert_allclose(est.coef_, [3.0, -1.5], atol=0.05)
    pred = comp.predict(camps)
    meas = comp.measured(camps)
    assert meas["K0"]["E_Z"].iloc[0] == 0.0  # referenced to the first sample
    resid = meas["K1"]["E_Z"] - pred["K1"]["E_Z"]
    assert resid.std() < 0.1


def test_compensator_pickle_round_trip_identical_predictions():
    rng = np.random.default_rng(1)
    camps = {"A": _campaign(rng), "B": _campaign(rng, offset=30)}
    comp = Compensator(MLR(), targets=["E_Z"]).fit(camps)
    again = pickle.loads(pickle.dumps(comp))
    pd.testing.assert_frame_equal(comp.predict(camps)["B"], again.predict(camps)["B"])


def test_bad_inputs_or_targets_are_contract_errors():
    rng = np.random.default_rng(2)
    camps = {"A": _campaign(rng)}
    with pytest.raises(ContractError, match="matches no column"):
        Compensator(MLR(), inputs=["X_*"]).fit(camps)
    with pytest.raises(ContractError, match="E_Q"):
        Compensator(MLR(), targets=["E_Q"]).fit(camps)
