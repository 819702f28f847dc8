"""One-step prediction of a target measured now and then (sparse62): from the last measured
error, a probe cycle ahead, the law as it was fitted (its increments span the same cycle)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from thermocomp.core.context import CAMPAIGN, Y_MEASURED
from thermocomp.core.models.one_step import OneStepLaw


def _record(rng, n=300, every=10):
    s = np.cumsum(rng.normal(0, 0.3, n))              # a model's free run
    y = 0.8 * s + np.cumsum(rng.normal(0, 0.05, n))   # the error, drifting off the model
    y[np.arange(n) % every != 0] = np.nan             # measured on 1 row in `every`
    return s, y


def test_each_row_is_predicted_from_the_last_measured_error():
    rng = np.random.default_rng(62)
    s, y = _record(rng)
    groups = np.repeat(["a", "b"], len(s) // 2)
    context = pd.DataFrame({Y_MEASURED: y, CAMPAIGN: groups})
    law = OneStepLaw().fit(s.reshape(-1, 1), y, context=context)
    assert law.every_ == 10
    out = law.predict(s.reshape(-1, 1), context=context)
    for t in range(len(s)):
        start = 0 if t < len(s) // 2 else len(s) // 2
        measured = [u for u in range(start, t) if np.isfinite(y[u])]
        if not measured:                 # nothing read yet in the campaign: the model's own run
            assert out[t] == s[t]
            continue
        u = measured[-1]
        expected = y[u] + law.k_ * (s[t] - s[u]) - law.g_ * (y[u] - s[u])
        assert np.isclose(out[t], expected, rtol=0, atol=1e-12), t


def test_dense_records_are_predicted_as_before():
    """Every sample measured: the previous sample's error, t - 1 (the law's classic form)."""
    rng = np.random.default_rng(7)
    s = np.cumsum(rng.normal(0, 0.3, 200))
    y = 0.9 * s + rng.normal(0, 0.1, 200)
    context = pd.DataFrame({Y_MEASURED: y})
    law = OneStepLaw().fit(s.reshape(-1, 1), y, context=context)
    out = law.predict(s.reshape(-1, 1), context=context)
    expected = y[:-1] + law.k_ * (s[1:] - s[:-1]) - law.g_ * (y[:-1] - s[:-1])
    assert out[0] == s[0] and np.allclose(out[1:], expected, rtol=0, atol=1e-12)
