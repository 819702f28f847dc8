"""Every parameter of the configurable estimators, denoiser and selectors has a rule
(``param_rules``), and ``fit`` refuses a value outside it naming the class and the key."""

from __future__ import annotations

import inspect

import numpy as np
import pandas as pd
import pytest

from thermocomp.base.errors import ParameterError
from thermocomp.core.denoise import EMDDenoiser
from thermocomp.core.models.arx import ARX
from thermocomp.core.models.arx_rf import ARXRF
from thermocomp.core.models.ati import ATIRegressor
from thermocomp.core.models.hammerstein import Hammerstein
from thermocomp.core.models.lagbank import LagBank
from thermocomp.core.models.linear import MLR
from thermocomp.core.models.lstm import LSTM
from thermocomp.core.models.pcr import PCR
from thermocomp.core.select import ClusterGreySelector, GreedyResidualSelector, PearsonSelector

CLASSES = [MLR, PCR, ARX, ARXRF, LSTM, LagBank, Hammerstein, ATIRegressor, EMDDenoiser, PearsonSelector,
           GreedyResidualSelector, ClusterGreySelector]
# held estimators check themselves (and the shell checks them under their own key)
UNRULED = {"arx", "forest", "base_estimator", "lagbank"}

# one value outside each rule, of the kinds a config override produces: text for a number,
# text for a flag, a number off its range, an empty list
HOSTILE = {
    "fit_intercept": "maybe", "variance": 0, "criterion": "foo", "max_inputs": 0, "ar": 1,
    "delays": [], "search": "random", "selection_error": "exact", "state_column": "",
    "tau_s": [], "hidden_size": 0, "num_layers": 1.5, "dropout": 1.0, "chunk": "abc",
    "learning_rate": -1e-3, "weight_decay": -1e-3, "batch_size": 0, "max_epochs": -1, "patience": 0,
    "validation_fraction": 1.0, "n_threads": 0, "n_taus": 0, "tau_min_s": -1, "tau_max_s": 0,
    "alphas": [], "n_splits": 1, "sample_period_s": float("nan"), "level_penalty": -0.5,
    "n_intervals": "knee",
    "candidates": [0], "clustering": "spectral", "fuzziness": 1.0, "elbow_tolerance": -0.1,
    "ambient_interaction": "yes", "min_campaigns": 0, "n_imfs": 0, "sensors": "T_*", "stopping": "never",
    "max_siftings": 0, "s_number": 0, "sd_threshold": 0, "end_effect": "none", "pad": -1,
    "spline": "quintic", "causal": "foo", "causal_taps": 0, "causal_window": 3, "online": "no",
    "states": [], "exponents": [0.0], "choose_exponents": "sometimes", "k": 0, "k_max": 0, "m": 1.0,
    "rho": 1.5, "random_state": float("nan"), "rest_columns": [-1], "state_start": "cold",
}


@pytest.mark.parametrize("cls", CLASSES, ids=lambda c: c.__name__)
def test_every_parameter_has_a_rule_and_the_defaults_keep_it(cls):
    names = set(inspect.signature(cls).parameters) - UNRULED
    assert names == set(cls.param_rules), names ^ set(cls.param_rules)
    est = cls()
    for name, rule in cls.param_rules.items():
        assert rule(getattr(est, name)), (name, getattr(est, name), rule.says)


def _data(n=60):
    rng = np.random.default_rng(0)
    X = pd.DataFrame({"T_0": np.cumsum(rng.normal(0, 0.1, n)), "T_1": rng.normal(20, 1, n)})
    return X, X["T_0"].to_numpy() * 2 + rng.normal(0, 0.1, n)


CASES = [(cls, name) for cls in CLASSES for name in cls.param_rules]


@pytest.mark.parametrize("cls, name", CASES, ids=[f"{c.__name__}.{n}" for c, n in CASES])
def test_fit_refuses_a_value_outside_the_rule_naming_class_and_key(cls, name):
    value = HOSTILE[name]
    assert not cls.param_rules[name](value), f"{name}={value!r} is not hostile"
    est = cls(**{name: value})
    X, y = _data()
    with pytest.raises(ParameterError, match=f"^{cls.__name__}.{name}="):
        est.fit(X) if cls is EMDDenoiser else est.fit(X, y)
