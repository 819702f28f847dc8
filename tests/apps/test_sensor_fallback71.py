"""A sensor no other predicts, excluded in service: the same family fitted without it (sub71).

On keysight70's ``dmu_a`` the spindle thermocouple, unplugged mid-run, was excluded and held at
its last good reading (no other sensor predicts it); the model leaned on it and went 93.6 µm RMS
off after the fault (``benchmarks/bench_sub71.py``).  The adaptive compensator now streams, beside
the model, the same family fitted without each such sensor, and gives its correction while the
sensor is out.  Here a spindle with its own fast response and a head that follows it slowly, five
structure sensors warming together; the spindle reads nothing from the test campaign's middle on.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from thermocomp.apps.deploy import AdaptiveCompensator, StreamingCompensator
from thermocomp.apps.deploy.report import stream_rows
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR

N, DT = 240, 60.0


def _campaign(seed: int) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    t = np.arange(N) * DT
    warm = 3 * (1 - np.exp(-t / 5000)) + 0.5 * np.sin(t / 3000 + seed)
    temps = 20 + warm[:, None] * np.linspace(0.8, 1.2, 5) + rng.normal(0, 0.02, (N, 5))
    speed = np.repeat(rng.uniform(0, 1, N // 40), 40)
    spindle, head = np.zeros(N), np.zeros(N)
    for i in range(1, N):
        spindle[i] = spindle[i - 1] + (8 * speed[i] - spindle[i - 1]) * DT / 600
        head[i] = head[i - 1] + (spindle[i] - head[i - 1]) * DT / 3000
    frame = pd.DataFrame(temps, columns=[f"T_{j}" for j in range(5)])
    frame["T_spindle"] = 20 + spindle + rng.normal(0, 0.02, N)
    frame["T_head"] = 20 + 0.5 * warm + head + rng.normal(0, 0.02, N)
    frame.insert(0, "time", t)
    frame["E_Z"] = (3.0 * spindle + 2.0 * head + (frame["T_1"] - frame["T_1"][0])
                    + rng.normal(0, 0.05, N))
    return frame


@pytest.fixture(scope="module")
def deployed():
    train = {f"K{i}": _campaign(i) for i in range(4)}
    comp = Compensator(MLR()).fit(train)

    def adaptive(**kw):
        return AdaptiveCompensator.from_training(StreamingCompensator.from_training(comp, train),
                                                 train, **kw)
    return adaptive(), adaptive(fallbacks="none"), train


def test_the_correction_while_an_unpredictable_sensor_is_out_is_the_model_fitted_without_it(deployed):
    with_fallbacks, held, train = deployed
    assert sorted(with_fallbacks.fallbacks_) == ["T_head", "T_spindle"]   # no other predicts them
    assert held.fallbacks_ == {}
    test = _campaign(7232)
    h = N // 2
    out = test.copy()
    out.loc[h:, "T_spindle"] = np.nan
    error = (test["E_Z"] - test["E_Z"][0]).to_numpy()

    def after(deployed):
        s = stream_rows(deployed, out, "T")
        assert [e["sensor"] for e in s.events if e.get("to") == "excluded"] == ["T_spindle"]
        return s.y[:, 0], float(np.sqrt(np.mean((error[h:] - s.y[h:, 0]) ** 2)))
    y, rmse = after(with_fallbacks)
    rmse_held = after(held)[1]
    assert rmse < 0.5 * rmse_held                     # 4.40 against 11.43 µm
    # the rows after the exclusion are the fallback's, a model of the same family without it
    fitted = Compensator(MLR(), selection={"E_Z": [c for c in train["K0"].columns
                                                   if c.startswith("T_") and c != "T_spindle"]})
    batch = fitted.fit(train).predict({"T": test})["T"]["E_Z"].to_numpy()
    np.testing.assert_allclose(y[h + 1:], batch[h + 1:], atol=1e-9)
    # in one go (replay) as row by row (served), and from a saved state as streamed on
    with_fallbacks.reset()
    X, t = out[with_fallbacks.columns_].to_numpy(float), out["time"].to_numpy(float)
    np.testing.assert_allclose(with_fallbacks.run_rows(X, t)[0][:, 0], y, atol=1e-9)
    with_fallbacks.reset()
    with_fallbacks.run_rows(X[:h + 5], t[:h + 5])
    saved = with_fallbacks._snapshot()
    rest = with_fallbacks.run_rows(X[h + 5:], t[h + 5:])[0]
    with_fallbacks._restore(saved)
    np.testing.assert_array_equal(with_fallbacks.run_rows(X[h + 5:], t[h + 5:])[0], rest)


def test_a_healthy_stream_is_the_models_to_the_bit(deployed):
    with_fallbacks, held, _ = deployed
    test = _campaign(7233)
    np.testing.assert_array_equal(stream_rows(with_fallbacks, test, "T").y,
                                  stream_rows(held, test, "T").y)


def test_an_unknown_choice_is_refused(deployed):
    train = deployed[2]
    stream = StreamingCompensator.from_training(Compensator(MLR()).fit(train), train)
    with pytest.raises(ValueError, match="monitor.fallbacks"):
        AdaptiveCompensator.from_training(stream, train, fallbacks="all")


def test_under_auto_the_fallback_is_the_chosen_family_refitted_as_chosen():
    """model=auto (autofb72): the fallback refits, per target, what auto chose with the
    hyper-parameters it chose (no candidate validated, the family's own CV not run again);
    before, auto had no fallback and the spindle was held."""
    from thermocomp.core.models import LagBank
    from thermocomp.core.models.auto import AutoRegressor

    train = {f"K{i}": _campaign(i) for i in range(4)}
    comp = Compensator(AutoRegressor({"lagbank": LagBank(n_taus=3)}, n_folds=2)).fit(train)
    stream = StreamingCompensator.from_training(comp, train)
    deployed = AdaptiveCompensator.from_training(stream, train)
    held = AdaptiveCompensator.from_training(stream, train, fallbacks="none")
    assert sorted(deployed.fallbacks_) == ["T_head", "T_spindle"]
    chosen = comp.estimators_["E_Z"].estimator_
    refitted = deployed.fallbacks_["T_spindle"].compensator.estimators_["E_Z"]
    assert type(refitted) is LagBank                          # not auto: nothing validated again
    assert refitted.get_params()["alphas"] == [chosen.alpha_]  # its CV's choice, fixed
    test = _campaign(7277)
    h = N // 2
    out = test.copy()
    out.loc[h:, "T_spindle"] = np.nan
    error = (test["E_Z"] - test["E_Z"][0]).to_numpy()

    def after(compensator):
        y = stream_rows(compensator, out, "T").y[:, 0]
        return float(np.sqrt(np.mean((error[h:] - y[h:]) ** 2)))
    assert after(deployed) < 0.5 * after(held)                # 1.98 against 7.99 µm
    # the chosen family as chosen, fitted without the spindle (the guard then bounds it)
    without = {"E_Z": [c for c in train["K0"].columns if c.startswith("T_") and c != "T_spindle"]}
    batch = Compensator(LagBank(n_taus=3, **chosen.chosen_params()), selection=without).fit(train)
    fallback = deployed.fallbacks_["T_spindle"].compensator
    np.testing.assert_array_equal(fallback.predict({"T": test})["T"]["E_Z"],
                                  batch.predict({"T": test})["T"]["E_Z"])
    np.testing.assert_array_equal(stream_rows(deployed, test, "T").y, stream_rows(held, test, "T").y)
