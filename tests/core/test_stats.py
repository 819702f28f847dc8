"""One-way ANOVA and the mutual prediction matrix against hand-computed cases."""

import warnings

import numpy as np
import pandas as pd
import pytest

from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR
from thermocomp.core.scoring.stats import anova_oneway, mutual_prediction


def test_anova_hand_computed_table():
    # means 2 and 5, grand mean 3.5: S_A = 3(1.5²) + 3(1.5²) = 13.5, S_E = 2 + 2 = 4,
    # F = (13.5 / 1) / (4 / 4) = 13.5; F_crit(0.05; 1, 4) = 7.71 from the F table.
    a = anova_oneway({"K1": [1.0, 2.0, 3.0], "K2": [4.0, 5.0, 6.0]}, alpha=0.05)
    assert a["ss_between"] == pytest.approx(13.5) and a["ss_within"] == pytest.approx(4.0)
    assert (a["df_between"], a["df_within"]) == (1, 4)
    assert a["F"] == pytest.approx(13.5)
    assert a["F_crit"] == pytest.approx(7.7086, abs=1e-4)
    assert a["significant"] is True
    # p = P(F_{1,4} >= 13.5); F_{1,4} = t_4², so p is the two-sided t_4 tail at sqrt(13.5)
    from scipy.stats import t
    assert a["p_value"] == pytest.approx(2 * t.sf(np.sqrt(13.5), 4))
    strict = anova_oneway({"K1": [1.0, 2.0, 3.0], "K2": [4.0, 5.0, 6.0]}, alpha=0.001)
    assert strict["F_crit"] > 13.5 and strict["significant"] is False


def test_anova_equal_means_is_not_significant_and_nan_is_dropped():
    a = anova_oneway({"A": [1.0, -1.0, np.nan], "B": [2.0, -2.0], "C": [0.5, -0.5]})
    assert a["F"] == pytest.approx(0.0, abs=1e-12) and a["significant"] is False
    assert a["df_within"] == 3


def test_anova_needs_two_campaigns():
    a = anova_oneway({"only": [1.0, 2.0, 3.0]})
    assert a["F"] is None and "two campaigns" in a["reason"]


def _campaign(k, n=30, seed=0):
    rng = np.random.default_rng(seed)
    t = np.arange(n) * 300.0
    T = 20 + np.cumsum(rng.uniform(0.05, 0.2, n))
    return pd.DataFrame({"time": t, "T_1": T, "E_Z": k * (T - T[0])})


def test_mutual_prediction_closed_form():
    # campaign i follows E = k_i ΔT exactly; a model of campaign i predicts campaign j with
    # residual (k_j - k_i) ΔT_j, so Rsd_ij = |k_j - k_i| sqrt(sum ΔT_j² / (n - 1)).
    ks = {"A": 1.0, "B": 2.0, "C": 4.0}
    camps = {c: _campaign(k, seed=i) for i, (c, k) in enumerate(ks.items())}
    mats = mutual_prediction(camps, lambda: Compensator(MLR()))
    m = mats["E_Z"]
    assert list(m.index) == list(m.columns) == ["A", "B", "C"]
    for i in ks:
        for j in ks:
            dT = camps[j]["T_1"] - camps[j]["T_1"].iloc[0]
            want = abs(ks[j] - ks[i]) * np.sqrt((dT**2).sum() / (len(dT) - 1))
            assert m.loc[i, j] == pytest.approx(want, abs=1e-8)


def test_mutual_prediction_fits_one_model_per_campaign_and_no_more():
    # each fit may be a blend with an LSTM member on a record's whole train part: no extra fit
    # to find the columns (there was one on the first campaign, then that campaign again)
    fits = []

    class Counted(MLR):
        def fit(self, X, y, context=None):
            fits.append(len(y))
            return super().fit(X, y, context=context)

    camps = {c: _campaign(k, seed=i) for i, (c, k) in enumerate({"A": 1.0, "B": 2.0, "C": 4.0}.items())}
    mats = mutual_prediction(camps, lambda: Compensator(Counted()))
    assert fits == [len(camps[c]) for c in camps] and mats["E_Z"].shape == (3, 3)


def test_mutual_prediction_keeps_quiet_about_single_campaign_fallbacks():
    # each model sees one campaign by design: an ATI model falling back to one model there is
    # no news (a lab saw "1 training campaign(s)" from a run on 36); a fit on one campaign warns
    from thermocomp.base.errors import FallbackWarning
    from thermocomp.core.models.ati import ATIRegressor

    camps = {c: _campaign(1.0 + i, seed=i).assign(T_amb=15.0 + 5 * i) for i, c in enumerate("ABCD")}
    make = lambda: Compensator(ATIRegressor(MLR()), inputs=["T_1", "T_amb"])   # noqa: E731
    with warnings.catch_warnings():
        warnings.simplefilter("error", FallbackWarning)
        m = mutual_prediction(camps, make)["E_Z"]
    assert m.shape == (4, 4) and np.isfinite(m.to_numpy()).all()
    with pytest.warns(FallbackWarning, match="1 training campaign"):
        make().fit({"A": camps["A"]})
