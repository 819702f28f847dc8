"""``model=auto``'s votes with held-out runs re-referenced at their first samples (issue 34, stop 65).

With ``data.reference=first_sample`` a held-out run's label carries its first sample's noise as an
offset of the whole run; scored as it is, that one draw entered every candidate's fold error and
could hand the votes to a candidate that is wrong over the run (``hmc`` E_Y).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from thermocomp.core.metrics import rmse
from thermocomp.core.models import MLR
from thermocomp.core.models.auto import AutoRegressor
from thermocomp.core.models.blend import REREFERENCE_MAX, rereferenced_squares


class HalfGain(MLR):
    """MLR whose prediction misses half the thermal gain: wrong by more the warmer the run."""

    def predict(self, X, context=None):
        return 0.5 * super().predict(X, context=context)


def _runs(n_runs: int, spiked, spike: float, seed: int, n: int = 300):
    """Warm-up runs in the first-sample frame: the error is twice the sensor's rise, plus noise;
    the runs of ``spiked`` read ``spike`` high at their first sample (the zeroing)."""
    rng = np.random.default_rng(seed)
    xs, ys, runs = [], [], []
    for r in range(n_runs):
        rise = 5.0 * (1.0 - np.exp(-np.arange(n) / 100.0)) + rng.normal(0.0, 0.02, n)
        x = rise - rise[0]
        e = 2.0 * x + rng.normal(0.0, 0.05, n)
        e[0] += spike if r in spiked else 0.0
        xs.append(x)
        ys.append(e - e[0])
        runs += [f"R{r:02d}"] * n
    context = pd.DataFrame({"campaign": runs, "time": np.tile(np.arange(n) * 60.0, n_runs)})
    return np.concatenate(xs)[:, None], np.concatenate(ys), context


def test_a_spike_at_the_held_out_runs_first_samples_does_not_hand_the_votes_to_the_wrong_family():
    # ten runs, the last five held out one per fold (blocked forward); those five zeroed on a
    # probe reading 4 µm high: scored as they were, half the gain won every fold (its error
    # grows from 0 towards the run's end, and so met the runs' -4 µm offset halfway)
    X, y, context = _runs(10, range(5, 10), spike=4.0, seed=0)
    auto = AutoRegressor({"mlr": MLR(), "half": HalfGain()}).fit(X, y, context=context)
    assert auto.scheme_ == "blocked forward"
    assert auto.validation_["half"] < auto.validation_["mlr"]      # the plain fold RMSE misleads
    assert auto.weights_ == {"mlr": 1.0}
    assert "5 held-out run(s) referenced to their first sample re-referenced" in auto.reason_
    # and MLR is the right one: on fresh runs without the spike
    Xf, yf, cf = _runs(3, (), spike=0.0, seed=1)
    mlr = MLR().fit(X, y, context=context)
    half = HalfGain().fit(X, y, context=context)
    assert rmse(yf - auto.predict(Xf, context=cf)) == rmse(yf - mlr.predict(Xf, context=cf))
    assert rmse(yf - mlr.predict(Xf, context=cf)) < 0.5 * rmse(yf - half.predict(Xf, context=cf))


def test_each_run_is_re_referenced_at_its_first_k_samples_and_only_a_run_referenced_to_its_first():
    rng = np.random.default_rng(3)
    lengths = [400, 100, 30, 50]                 # k: 10 (capped), 5, 1, and a run not referenced
    campaign = np.repeat(np.arange(4), lengths)
    y = rng.normal(0.0, 1.0, campaign.size)
    starts = np.cumsum([0, *lengths[:-1]])
    y[starts[:3]] = 0.0                          # the first three referenced to their first sample
    residual = rng.normal(0.0, 1.0, (campaign.size, 3))
    got = rereferenced_squares(residual, y, campaign)
    for c, (start, n) in enumerate(zip(starts, lengths)):
        rows = slice(start, start + n)
        if c == 3:
            np.testing.assert_array_equal(got[rows], residual[rows] ** 2)
            continue
        k = min(REREFERENCE_MAX, max(1, int(0.05 * n)))
        assert k == [10, 5, 1][c]
        r = residual[rows]
        want = np.mean([(r - r[j]) ** 2 for j in range(k)], axis=0)
        np.testing.assert_allclose(got[rows], want, rtol=1e-12, atol=1e-12)
