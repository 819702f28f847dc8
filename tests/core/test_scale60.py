"""A year's lag bank at small size: its fit's copies of the design, measured by tracemalloc on a
few thousand rows, with the bounds scaled as on the year (scale60; the timing is
benchmarks/bench_scale60.py, never a test)."""

import tracemalloc

import numpy as np
import pandas as pd
import pytest

from thermocomp.core.model_selection.splitters import ForwardChaining
from thermocomp.core.models import lagbank


def _traced_peak(fn, *args, **kwargs):
    """``(result, bytes allocated at the peak of fn above what was held before it)``."""
    tracemalloc.start()
    try:
        before = tracemalloc.get_traced_memory()[0]
        out = fn(*args, **kwargs)
        return out, tracemalloc.get_traced_memory()[1] - before
    finally:
        tracemalloc.stop()


def _record(n: int, p: int, seed: int = 60):
    """One long record at 1 min: p drifting sensors and an error that lags them."""
    rng = np.random.default_rng(seed)
    X = 20.0 + np.cumsum(rng.normal(0.0, 0.02, (n, 3)), axis=0) @ rng.normal(size=(3, p))
    X += rng.normal(0.0, 0.03, (n, p))
    y = pd.Series(X[:, 0]).ewm(alpha=0.01).mean().to_numpy() - 0.5 * X[:, 1] + rng.normal(0, 0.1, n)
    return X, y, pd.DataFrame({"time": 60.0 * np.arange(n)})


def _forward_splits(n: int):
    splitter = ForwardChaining(5, gap=10, min_train_fraction=0.5)
    return [rows for split in splitter.split(np.zeros((n, 1))) for rows in split]


def test_forward_chaining_grams_in_blocks_equal_each_folds_own(monkeypatch):
    monkeypatch.setattr(lagbank, "PREFIX_BLOCK_BYTES", 8 * 7 * 50, raising=False)   # 50-row blocks
    rng = np.random.default_rng(0)
    Z = rng.normal(size=(1000, 7)) @ rng.normal(size=(7, 7)) + 3.0 * rng.normal(size=7)
    splits = _forward_splits(len(Z))

    for (mean, gram), tr in zip(lagbank._training_grams(Z, splits), splits[::2]):
        centred = Z[tr] - Z[tr].mean(axis=0)
        np.testing.assert_allclose(mean, Z[tr].mean(axis=0), rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(gram, centred.T @ centred, rtol=1e-11, atol=1e-9)


def test_forward_chaining_grams_hold_no_copy_of_a_folds_rows(monkeypatch):
    # a year: each fold copied its training rows (up to 0.9 of 1.2 GB) and held the last fold's
    # while copying the next; the blocks are 16 MB there, here (larger) a twentieth of Z
    Z = np.random.default_rng(1).normal(size=(20000, 30))
    monkeypatch.setattr(lagbank, "PREFIX_BLOCK_BYTES", Z.nbytes / 20, raising=False)
    splits = _forward_splits(len(Z))

    grams, peak = _traced_peak(lambda: list(lagbank._training_grams(Z, splits)))

    assert len(grams) == 5
    assert peak < 0.25 * Z.nbytes, f"{peak / Z.nbytes:.2f} x the design held at once"


def test_a_one_record_fit_holds_the_features_and_one_standardised_copy(monkeypatch):
    # a year: the refit standardised the design again while the CV's copy was still held, three
    # 1.2 GB arrays at once; now the features (remembered) and one copy, and the scaler's fit
    monkeypatch.setattr(lagbank, "_lag_bank_features",
                        lagbank.ArrayMemo(lagbank.lag_features, max_bytes=lagbank.LAG_FEATURES_MAX_BYTES))
    lagbank.LagBank().fit(*_record(300, 2)[:2], context=_record(300, 2)[2])  # imports: not traced
    X, y, context = _record(20000, 6)
    features = X.nbytes * 9                                  # 8 lags and the levels
    monkeypatch.setattr(lagbank, "PREFIX_BLOCK_BYTES", features / 20, raising=False)

    model, peak = _traced_peak(lagbank.LagBank().fit, X, y, context=context)

    assert model.coef_.size == 54
    assert peak < 2.5 * features, f"{peak / features:.2f} x the features held at once"


def test_lag_features_are_written_once_into_their_array():
    # a year: the lags were written apart (1 GB) and copied into the features (1.2 GB)
    from thermocomp.core.models._pooled import lag_features

    X, _, context = _record(20000, 6)
    time_s, taus = context["time"].to_numpy(), np.geomspace(60.0, 172800.0, 8)
    runs = np.repeat([0, 1], 10000)
    lag_features(X[:300], time_s[:300], runs[:300], taus)                # imports: not traced

    F, peak = _traced_peak(lag_features, X, time_s, runs, taus)

    assert F.shape == (20000, 54)
    assert peak < 1.3 * F.nbytes, f"{peak / F.nbytes:.2f} x the features held at once"


@pytest.mark.parametrize("shape", [(1000, 7), (20000, 30), (3, 2)])
def test_the_blocked_standardisation_is_scikit_learns_bit_for_bit(monkeypatch, shape):
    from sklearn.preprocessing import StandardScaler

    monkeypatch.setattr(lagbank, "PREFIX_BLOCK_BYTES", 8 * shape[1] * 97, raising=False)  # 97-row blocks
    rng = np.random.default_rng(shape[0])
    D = rng.normal(size=shape) * rng.uniform(0.1, 1e3, shape[1]) + rng.normal(0.0, 1e4, shape[1])
    D[:, 0] = 2.5                                        # a constant column: scale 1
    ours, theirs = lagbank.standard_scaler(D), StandardScaler().fit(D)

    for name in ("mean_", "var_", "scale_"):
        np.testing.assert_array_equal(getattr(ours, name), getattr(theirs, name))
    assert ours.n_samples_seen_ == theirs.n_samples_seen_
    np.testing.assert_array_equal(lagbank.standardised(D, ours), theirs.transform(D))


def test_the_standardisation_holds_no_copy_of_the_design(monkeypatch):
    # a year: scikit-learn's fit held D - mean and its NaN mask (1.3 of the 1.2 GB design)
    D = np.random.default_rng(2).normal(size=(20000, 30))
    monkeypatch.setattr(lagbank, "PREFIX_BLOCK_BYTES", D.nbytes / 20, raising=False)
    lagbank.standard_scaler(D[:300])                                     # imports: not traced

    scaler, peak = _traced_peak(lagbank.standard_scaler, D)

    assert scaler.mean_.shape == (30,)
    assert peak < 0.25 * D.nbytes, f"{peak / D.nbytes:.2f} x the design held at once"


def _with_speed(n: int):
    X, y, context = _record(n, 4)
    speed = np.where(np.sin(np.arange(n) / 200.0) > 0, 3000.0, 0.0)
    y = y + pd.Series(speed).ewm(alpha=0.005).mean().to_numpy() * 4e-4
    return X, y, context.assign(S_speed=speed)


def test_a_hammerstein_refits_only_its_chosen_lag_bank(monkeypatch):
    # a year: each of the four power sets' lag banks was refitted on every row, three thrown away
    from thermocomp.core.models.hammerstein import Hammerstein

    refits = []
    plain = lagbank.LagBank._refit
    monkeypatch.setattr(lagbank.LagBank, "_refit",
                        lambda self, *a, **k: refits.append(1) or plain(self, *a, **k))
    X, y, context = _with_speed(3000)
    model = Hammerstein(lagbank=lagbank.LagBank(n_taus=4)).fit(X, y, context=context)

    assert len(model.cv_results_) == 4 and len(refits) == 1


def test_the_chosen_lag_bank_is_the_one_fitted_alone():
    from thermocomp.core.models.hammerstein import Hammerstein

    X, y, context = _with_speed(3000)
    model = Hammerstein(lagbank=lagbank.LagBank(n_taus=4)).fit(X, y, context=context)
    assert model.exponents_                       # the speed enters: its powers are columns
    alone = lagbank.LagBank(n_taus=4, rest_columns=list(range(4, 4 + len(model.exponents_)))).fit(
        np.hstack([X, model._basis(context[["S_speed"]].to_numpy(), model.exponents_)]), y,
        context=context)

    np.testing.assert_array_equal(model.lagbank_.coef_, alone.coef_)
    assert model.lagbank_.intercept_ == alone.intercept_
    assert not hasattr(model.lagbank_, "_refit_later") and not hasattr(model.lagbank_, "_pending_design")
    np.testing.assert_array_equal(model.predict(X, context), alone.predict(
        np.hstack([X, model._basis(context[["S_speed"]].to_numpy(), model.exponents_)]), context))
