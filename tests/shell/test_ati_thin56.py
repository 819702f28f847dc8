"""ATI: no interval model is fitted on one campaign (``min_campaigns``; few train campaigns).

With 4 train campaigns (``yearround_spindle`` with 6, seed 5411) the elbow's folds and the refit
made intervals of one campaign: that run's model alone predicted its neighbours (E_Y's fold 4.53
µm against MLR's 2.13; ``benchmarks/bench_auto_losses56.py``).
"""

import numpy as np
import pandas as pd
import pytest

from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR
from thermocomp.core.models.ati import ATIRegressor, merge_thin_intervals


def run(ambient, seed, n=60, together=False):
    """A campaign whose error is T_1 + T_2 rises at every ambient; ``together``: one programme
    that heats both sensors alike (T_2 follows T_1 within 0.002 K), so a model of this run alone
    cannot tell their gains apart."""
    rng = np.random.default_rng(seed)
    t1 = np.cumsum(rng.uniform(0.0, 0.3, n))
    t2 = t1 + rng.normal(0.0, 0.002, n) if together else np.cumsum(rng.uniform(0.0, 0.3, n))
    return pd.DataFrame({"time": np.arange(n) * 300.0, "T_1": ambient + t1, "T_2": ambient + t2,
                         "T_amb": ambient + rng.normal(0.0, 0.01, n),
                         "E_Z": t1 + t2 + rng.normal(0.0, 0.05, n)})


def test_an_interval_of_one_campaign_is_merged_into_its_neighbour():
    # the coldest run alone at 5 °C, three warm ones: two intervals asked
    errors = []
    for seed in range(8):
        train = {"K01": run(5.0, seed, together=True), **{
            f"K0{k}": run(a, 10 * seed + k) for k, a in ((2, 25.0), (3, 28.0), (4, 31.0))}}
        test = {"C": run(6.0, 100 + seed)}          # cold, its sensors apart
        with pytest.warns(UserWarning, match="min_campaigns"):
            comp = Compensator(ATIRegressor(MLR(), n_intervals=2), inputs=["T_1", "T_2"]).fit(train)
        est = comp.estimators_["E_Z"]
        assert est.n_intervals_ == 1 and all(len(iv["campaigns"]) >= 2 for iv in est.intervals_)
        error = comp.measured(test)["C"]["E_Z"] - comp.predict(test)["C"]["E_Z"]
        errors.append(np.sqrt(np.mean(error ** 2)))
    # the noise is 0.05 µm; the cold run's own model (the interval of one, before) split the
    # gains by the noise: measured 0.09-6.6 µm RMSE over these seeds, median 1.3
    assert max(errors) < 0.15


def test_merge_thin_intervals_by_hand():
    a = [5.0, 10.0, 27.0, 30.0]
    np.testing.assert_allclose(merge_thin_intervals(a, [7.5, 18.5]), [18.5])     # the cold end
    np.testing.assert_allclose(merge_thin_intervals(a, [18.5, 28.5]), [18.5])    # the warm end
    # a middle interval of one joins the neighbour across the smaller gap (12 -> 10, not 27)
    a = [5.0, 10.0, 12.0, 27.0, 30.0]
    np.testing.assert_allclose(merge_thin_intervals(a, [11.0, 19.5]), [19.5])
    np.testing.assert_allclose(merge_thin_intervals(a, [11.0, 19.5], least=1), [11.0, 19.5])
    assert merge_thin_intervals([5.0, 30.0], [17.5]).size == 0                  # one left
