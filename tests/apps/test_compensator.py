import pickle

import numpy as np
import pandas as pd
import pytest
from sklearn.utils.estimator_checks import check_estimator

from thermocomp.core.compensator import Compensator
from thermocomp.core.io.contract import ContractError
from thermocomp.core.models import MLR


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


@pytest.mark.parametrize("family", ["mlr", "pcr", "arx", "arx_ar"])
def test_dropped_offsets_leave_the_first_samples_error_out_of_every_prediction(family):
    """A target referenced to a noisy first sample carries that sample's error on every row of
    the campaign; offsets='drop' fits the intercept (the gains stay unbiased) and predicts
    without it, in batch and streamed alike."""
    from thermocomp.apps.deploy import StreamingCompensator
    from thermocomp.apps.deploy.streaming import streaming_deviation
    from thermocomp.core.models import ARX, PCR

    make = {"mlr": MLR, "pcr": lambda: PCR(variance=0.999), "arx": lambda: ARX(ar=False),
            "arx_ar": lambda: ARX(ar=True)}[family]
    rng = np.random.default_rng(3)
    camps = {"A": _campaign(rng)}
    camps["A"].loc[0, "E_Z"] += 4.0                  # the reference sample's error
    kept = Compensator(make(), targets=["E_Z"]).fit(camps)
    dropped = Compensator(make(), targets=["E_Z"], offsets="drop").fit(camps)
    # every later row is 4 below its law: the intercept learns it (row 0 pulls it a little)
    if family != "arx_ar":      # with y(t-1) the intercept is (1 - a) times the offset
        assert dropped.offsets_["E_Z"] == pytest.approx(-4.0, abs=1.0)   # row 0 itself is 0
    np.testing.assert_allclose(dropped.estimators_["E_Z"].coef_, kept.estimators_["E_Z"].coef_)
    test = {"B": _campaign(np.random.default_rng(4), offset=25)}
    with_offset = kept.predict(test)["B"]["E_Z"].to_numpy()
    without = dropped.predict(test)["B"]["E_Z"].to_numpy()
    if family != "arx_ar":      # an AR model's intercept path: c (1 - a^k) / (1 - a)
        np.testing.assert_allclose(with_offset - without, dropped.offsets_["E_Z"], atol=1e-9)
    truth = kept.measured(test)["B"]["E_Z"].to_numpy()
    rmse = {k: np.sqrt(np.mean((truth - p) ** 2)) for k, p in (("kept", with_offset), ("dropped", without))}
    assert rmse["dropped"] < rmse["kept"] / 3
    streaming = StreamingCompensator.from_training(dropped, camps, policy="off")
    assert streaming_deviation(streaming, test["B"], chunk=5) < 1e-9


def test_offsets_are_checked_and_a_family_without_an_intercept_keeps_its_predictions():
    from sklearn.ensemble import RandomForestRegressor

    from thermocomp.core.models.arx_rf import ARXRF

    def make():
        return ARXRF(state_column=None, forest=RandomForestRegressor(n_estimators=5, random_state=0))

    rng = np.random.default_rng(5)
    camps = {"A": _campaign(rng)}
    with pytest.raises(ValueError, match="offsets must be one of"):
        Compensator(MLR(), offsets="zero").fit(camps)
    a = Compensator(make(), targets=["E_Z"]).fit(camps)
    b = Compensator(make(), targets=["E_Z"], offsets="drop").fit(camps)
    assert b.offsets_ == {}
    pd.testing.assert_frame_equal(a.predict(camps)["A"], b.predict(camps)["A"])
