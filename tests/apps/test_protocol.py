"""The one side-input and streaming protocol (thermocomp.core.context), for every estimator and wrapper."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import sklearn
from sklearn.base import clone
from sklearn.model_selection import GroupKFold, cross_val_score
from sklearn.utils.estimator_checks import check_estimator

from conftest import stream_context
from thermocomp.apps.diagnose import AugmentedRegressor, Effect
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import ARX, ARXRF, LSTM, MLR, PCR, Hammerstein, LagBank
from thermocomp.core.models.ati import ATIRegressor
from thermocomp.core.select import PearsonSelector

# Checks a model with memory cannot pass: its output at t depends on the rows before t.
ORDER_CHECKS = {"check_methods_sample_order_invariance": "depends on earlier rows by design",
                "check_methods_subset_invariance": "depends on earlier rows by design"}


def _forest():
    from sklearn.ensemble import RandomForestRegressor

    return RandomForestRegressor(n_estimators=5, min_samples_leaf=5, random_state=0)


ESTIMATORS = {
    "MLR": (MLR(), {}),
    "PCR": (PCR(), {}),
    "ARX": (ARX(), {}),
    "ARX-dynamic": (ARX(ar=True, delays=(0, 2)), ORDER_CHECKS),
    "LSTM": (LSTM(hidden_size=4, max_epochs=3), ORDER_CHECKS),
    "LagBank": (LagBank(), ORDER_CHECKS),
    "Hammerstein": (Hammerstein(lagbank=LagBank(n_taus=3)), ORDER_CHECKS),
    "ARXRF": (ARXRF(state_column=None, forest=_forest()), {}),
    "ATI(MLR)": (ATIRegressor(MLR()), {}),
    "ATI(ARXRF)": (ATIRegressor(ARXRF(state_column=None, forest=_forest())), {}),
    "Augmented(MLR)": (AugmentedRegressor(MLR()), {}),
    "Augmented(ATI(ARX))": (AugmentedRegressor(ATIRegressor(ARX())), {}),
}


@pytest.mark.parametrize("name", sorted(ESTIMATORS))
def test_check_estimator_with_metadata_routing_on(name):
    """scikit-learn's checks pass for every estimator and wrapper, with routing enabled: each
    requests its ``context`` side input for fit/predict/score by default."""
    est, expected = ESTIMATORS[name]
    with sklearn.config_context(enable_metadata_routing=True):
        check_estimator(clone(est), expected_failed_checks=expected)
        routing = est.get_metadata_routing()
        for method in ("fit", "predict", "score"):
            assert routing.consumes(method, ["context"]) == {"context"}, method


def _door_problem(seed=0, n_campaigns=8, n=60):
    rng = np.random.default_rng(seed)
    groups = np.repeat([f"C{i}" for i in range(n_campaigns)], n)
    ambient = np.repeat(rng.uniform(5, 30, n_campaigns), n)
    X = np.cumsum(rng.normal(0, 0.1, (len(groups), 3)), axis=0)
    door = (rng.random(len(groups)) > 0.85).astype(float)
    time = np.tile(np.arange(n) * 60.0, n_campaigns)
    y = X @ [1.0, -2.0, 0.5] * (1 + 0.03 * (ambient - 15)) - 8.0 * door + rng.normal(0, 0.05, len(groups))
    context = pd.DataFrame({"campaign": groups, "time": time, "ambient_c0": ambient, "S_door": door})
    return X, y, context


def test_context_is_routed_through_nested_wrappers_by_scikit_learn_cross_validation():
    """cross_val_score slices the context per fold and hands it down ATI -> ARX+RF: the door
    signal (only in the context) is what makes the wrapped model good."""
    X, y, context = _door_problem()
    groups = context["campaign"].to_numpy()
    with sklearn.config_context(enable_metadata_routing=True):
        def cv(est):
            return cross_val_score(est, X, y, cv=GroupKFold(4),
                                   params={"context": context, "groups": groups}).mean()
        with_door = cv(ATIRegressor(ARXRF(forest=_forest()), n_intervals=2))
        without = cv(ATIRegressor(ARXRF(state_column=None, forest=_forest()), n_intervals=2))
    assert with_door > without + 0.05


WRAPPED = {
    "ATI(ARXRF)": lambda: ATIRegressor(ARXRF(forest=_forest()), n_intervals=2),
    "ATI(ARX ar)": lambda: ATIRegressor(ARX(ar=True), n_intervals=3),
    "Augmented(ATI(ARXRF))": lambda: AugmentedRegressor(
        ATIRegressor(ARXRF(forest=_forest()), n_intervals=2),
        [Effect("signal", "first_order_lag", "S_door", tau_s=600).to_dict(),
         Effect("ambient_interval", "ambient_linear").to_dict()]),
    "Augmented(LSTM)": lambda: AugmentedRegressor(
        LSTM(hidden_size=4, max_epochs=2),
        [Effect("signal", "raw", "S_door").to_dict()]),
    "PCR": PCR,
    "ATI(LagBank ar)": lambda: ATIRegressor(LagBank(ar=True, n_taus=3), n_intervals=2),
    "ATI(Hammerstein)": lambda: ATIRegressor(Hammerstein(lagbank=LagBank(n_taus=3), states=["S_door"]),
                                             n_intervals=2),
}


@pytest.mark.parametrize("name", sorted(WRAPPED))
def test_wrappers_forward_streaming_and_declare_what_they_read(name):
    X, y, context = _door_problem(seed=1)
    train = context["campaign"].isin([f"C{i}" for i in range(6)]).to_numpy()
    est = WRAPPED[name]().fit(X[train], y[train], context=context[train].reset_index(drop=True))
    test_ctx = context[~train].reset_index(drop=True)
    batch = est.predict(X[~train], context=test_ctx)
    np.testing.assert_allclose(stream_context(est, X[~train], test_ctx), batch, rtol=0, atol=1e-9)
    reads = est.context_columns_
    if "ARXRF" in name or "Hammerstein" in name:
        assert {"time", "S_door"} <= set(reads)
    if name.startswith("ATI") or "ATI(" in name:
        assert "ambient_c0" in reads
    if name == "PCR":
        assert reads == []


def test_compensator_is_an_estimator(tmp_path):
    comp = Compensator(ATIRegressor(ARX()), selector=PearsonSelector(k=2), inputs=["T_*"])
    params = comp.get_params(deep=True)
    assert params["estimator__base_estimator__criterion"] == "bicc"
    assert params["selector__k"] == 2
    copy = clone(comp).set_params(estimator__base_estimator__max_inputs=3)
    assert copy.estimator.base_estimator.max_inputs == 3 and comp.estimator.base_estimator.max_inputs == 10
    assert not hasattr(clone(copy), "estimators_")
