"""A year's record at small size: what broke at full size (scale58) behaves on a few rows."""

import numpy as np
import pandas as pd
import pytest

from thermocomp.core.io import Dataset, read_dataset, write_dataset


def _late_record(time_s: np.ndarray) -> Dataset:
    manifest = pd.DataFrame({"file": [""], "split": ["train"]},
                            index=pd.Index(["R1"], name="campaign"))
    n = len(time_s)
    frame = pd.DataFrame({"time": time_s, "T_a": np.linspace(20.0, 21.0, n),
                          "E_Z": np.linspace(0.0, 3.0, n)})
    return Dataset(manifest, {"R1": frame}, "late")


@pytest.mark.parametrize("step", [60.0, 0.5])
def test_written_time_keeps_every_sample_past_1e7_s(tmp_path, step):
    # 200 days in: %.6g wrote 60 s steps as 100 s ones, two rows at one time (refused on read)
    time_s = 200 * 86400.0 + step * np.arange(50)
    write_dataset(_late_record(time_s), tmp_path / "ds")

    ds, _ = read_dataset(tmp_path / "ds")

    np.testing.assert_array_equal(ds.campaigns["R1"]["time"].to_numpy(), time_s)


def test_lag_features_in_one_array_equal_the_tiled_and_stacked_ones():
    from thermocomp.core.models._dynamics import first_order_lags
    from thermocomp.core.models._pooled import lag_features

    rng = np.random.default_rng(58)
    X = rng.normal(20.0, 2.0, (300, 4))
    time_s = np.cumsum(rng.choice([30.0, 60.0, 90.0], 300))     # irregular: the recursion path
    runs = np.repeat([0, 1, 2], 100)
    taus = np.geomspace(60.0, 7200.0, 5)

    lags = first_order_lags(X, time_s, runs, taus)
    before = np.hstack([X, lags - np.tile(X, taus.size)])   # the old code, written out

    np.testing.assert_array_equal(lag_features(X, time_s, runs, taus), before)


def test_lag_bank_features_memo_keeps_only_the_newest_past_its_byte_bound(monkeypatch):
    # a year's stack is 1.2 GB of features: four held at once took a run to 7 GB
    from thermocomp.core.models import lagbank
    from thermocomp.core.models._memo import BoundedCache

    memo = lagbank._lag_bank_features
    assert memo.max_bytes is not None and memo.max_bytes <= 1e9
    # the bound, scaled to these few rows
    monkeypatch.setattr(memo, "_results", BoundedCache(memo._results.max_items, max_bytes=20_000))
    rng = np.random.default_rng(0)
    taus = np.geomspace(60.0, 3600.0, 4)
    for _ in range(3):   # 200 rows x 15 columns x 8 bytes = 24 kB each
        X = rng.normal(size=(200, 3))
        memo(X, 60.0 * np.arange(200), None, taus)

    assert len(memo._results) == 1


def test_the_warm_up_says_how_many_rows_it_streams(caplog):
    # a year's test part is warmed on 473,041 rows, minutes of silence without it (scale58)
    import logging
    from types import SimpleNamespace

    from thermocomp.core.continuation import lead_ins

    manifest = pd.DataFrame({"file": ["", ""], "split": ["train", "test"], "continues": ["", "A"]},
                            index=pd.Index(["A", "B"], name="campaign"))
    frames = {c: pd.DataFrame({"time": 60.0 * np.arange(n), "T_a": 20.0, "E_Z": 0.0})
              for c, n in (("A", 120), ("B", 30))}
    ds = Dataset(manifest, frames, "chain")

    with caplog.at_level(logging.INFO, logger="thermocomp"):
        leads = lead_ins(SimpleNamespace(reference="none"), ds, ["B"])

    assert len(leads["B"]) == 120
    assert "B continues A; 120 rows streamed before scoring" in caplog.text


def test_a_large_caller_draws_its_figures_itself(tmp_path, monkeypatch):
    # a worker forked from a run holding 4.8 GB kept it after the run freed it (scale58)
    from thermocomp.core.figures import plots

    monkeypatch.setattr(plots, "_cpus", lambda: 2)
    monkeypatch.setattr(plots, "FORK_MAX_RSS", 0)      # every process is "large"
    path = tmp_path / "r.png"
    with plots.FigurePool() as pool:
        assert pool._pool is None                        # no worker forked
        pool.submit(plots.residual_plot, np.arange(50.0), np.ones(50), np.zeros(50), "E_Z", "K", path)
        assert path.exists()                             # drawn at submit, in this process
    assert pool.paths == [path]


def test_auto_says_each_long_candidate_validation(caplog, monkeypatch):
    # a year's candidates validated for 13 minutes without a line (scale58)
    import logging

    from thermocomp.core.models import auto as auto_module
    from thermocomp.core.models.linear import MLR

    monkeypatch.setattr(auto_module, "SAY_AFTER_S", 0.0)    # every candidate counts as long
    rng = np.random.default_rng(1)
    X = rng.normal(size=(200, 2))
    y = X @ np.array([1.0, -0.5]) + 0.1 * rng.normal(size=200)

    with caplog.at_level(logging.INFO, logger="thermocomp"):
        auto_module.AutoRegressor({"mlr": MLR()}).fit(X, y)

    said = [r for r in caplog.records if r.getMessage().startswith("auto: mlr validated in")]
    assert said and said[0].levelno == logging.INFO and "validation RMSE" in said[0].getMessage()


def test_diagnose_feature_cache_forgets_the_least_recently_used_past_its_bound():
    # every screened candidate kept its features: past 6 GB on a year's record (scale58)
    from thermocomp.apps.diagnose.cv import FEATURE_CACHE_BYTES, CrossValidator
    from thermocomp.core.models._memo import BoundedCache as FeatureCache

    cache = FeatureCache(max_bytes=2 * 800)      # two arrays of 100 floats
    for key in "abc":
        cache[key] = np.zeros(100)
        if key == "b":
            cache["a"]                           # used again: "b" is now the oldest
    assert list(cache) == ["a", "c"] and cache.nbytes == 1600
    cache["big"] = np.zeros(1000)                # over the bound alone: kept, the rest forgotten
    assert list(cache) == ["big"]

    cv = CrossValidator(problem=None, estimator=None)
    assert isinstance(cv._features, FeatureCache) and cv._features.max_bytes == FEATURE_CACHE_BYTES


def test_a_cleared_bounded_cache_counts_its_bytes_from_nothing():
    """After a clear the byte count starts again (hammlags63): it kept the cleared entries'
    bytes, so every later entry was over the bound and evicted the one before."""
    from thermocomp.core.models._memo import BoundedCache

    cache = BoundedCache(max_bytes=3 * 800)
    cache["a"], cache["b"] = np.zeros(100), np.zeros(100)
    cache.clear()
    cache["c"], cache["d"] = np.zeros(100), np.zeros(100)
    assert list(cache) == ["c", "d"] and cache.nbytes == 1600
