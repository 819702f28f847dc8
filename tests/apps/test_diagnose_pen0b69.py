"""A diagnosed MLR whose CV chose no penalty is fitted scale-fair (pen0b69): LinearRegression's
fit and relative cut-off (1e-6) on the design's columns scaled to unit spread.  Before, the base
MLR fitted the raw design, whose cut-off dropped the temperatures beside a state logged in a
large unit (a spindle power in mW, ~1e7: coefficients ~1e-14), so the deployed law was not the
one the CV had scored.  A collinear direction is still cut (test_stranger66's initial state
without an ambient: stream == batch)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from thermocomp.apps.diagnose.augmented import AugmentedRegressor
from thermocomp.apps.diagnose.features import Effect
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR


def _campaigns(seed: int = 6806, n_campaigns: int = 6, n: int = 240) -> dict:
    """E_Z = -3 (T_front rise) + 2 (T_head rise) + 4e-7 (spindle power in mW) + probe noise."""
    rng = np.random.default_rng(seed)
    out = {}
    for c in range(n_campaigns):
        power_mw = np.repeat(rng.uniform(0.0, 2.0e7, n // 40), 40)
        front = 20 + np.cumsum(rng.normal(0.0, 0.05, n)) + 1e-7 * np.cumsum(power_mw) / n
        head = 20 + np.cumsum(rng.normal(0.0, 0.04, n))
        amb = 20 + np.cumsum(rng.normal(0.0, 0.01, n))
        e = -3 * (front - front[0]) + 2 * (head - head[0]) + 4e-7 * power_mw
        out[f"C{c}"] = pd.DataFrame({"time": np.arange(n) * 60.0, "T_front": front, "T_head": head,
                                     "T_amb": amb, "S_power_mW": power_mw,
                                     "E_Z": e + rng.normal(0.0, 0.05, n)})
    return out


def test_no_penalty_fits_the_law_the_cv_scored_beside_a_large_valued_state():
    campaigns = _campaigns()
    effect = Effect("signal", "raw", "S_power_mW", frame="referenced")
    comp = Compensator(AugmentedRegressor(MLR(), [effect.to_dict()], alpha=0.0),
                       inputs=["T_front", "T_head", "T_amb"]).fit(campaigns)
    coef = comp.estimators_["E_Z"].estimator_.coef_
    # the temperatures' laws kept (before: ~1e-14 each, cut off beside 1e7 mW)
    np.testing.assert_allclose(coef[:2], [-3.0, 2.0], atol=0.1)    # -2.97, 1.95 (noise)
    held = _campaigns(seed=6807, n_campaigns=1)
    label = held["C0"]["E_Z"] - held["C0"]["E_Z"].iloc[0]       # the first-sample frame's
    residual = label - comp.predict(held)["C0"]["E_Z"]
    assert float(np.sqrt(np.mean(residual ** 2))) < 0.15           # the probe noise's order
