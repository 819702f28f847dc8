"""PCR: component choice, mapping back to sensor coefficients, sklearn contract."""

import pickle

import numpy as np
import pytest
from sklearn.decomposition import PCA
from sklearn.linear_model import LinearRegression
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler
from sklearn.utils.estimator_checks import check_estimator

from thermocomp.core.models import MLR, PCR


def _collinear(seed=0, n=500):
    """Six sensors driven by two heat paths (plus small independent noise), error in µm."""
    rng = np.random.default_rng(seed)
    z = np.column_stack([np.linspace(0, 8, n) + rng.normal(0, 0.3, n),
                         3 * np.sin(np.linspace(0, 6, n))])
    W = rng.uniform(0.5, 1.5, (2, 6)) * np.array([[1, 1, 1, 0.1, 0.1, 0.1], [0.1, 0.1, 0.1, 1, 1, 1]])
    X = 20 + z @ W + rng.normal(0, 0.02, (n, 6))
    y = 4.0 * z[:, 0] - 2.0 * z[:, 1] + rng.normal(0, 0.2, n)
    return X, y


def test_pcr_passes_sklearn_checks():
    check_estimator(PCR())
    check_estimator(PCR(variance=1.0))


def test_keeps_components_up_to_the_cumulative_variance_and_maps_back_to_sensors():
    X, y = _collinear()
    pcr = PCR(variance=0.95).fit(X, y)
    ratios = PCA().fit(StandardScaler().fit_transform(X)).explained_variance_ratio_
    g = int(np.searchsorted(np.cumsum(ratios), 0.95) + 1)
    assert pcr.n_components_ == g == 2  # two heat paths
    assert np.sum(pcr.explained_variance_ratio_) >= 0.95
    ref = make_pipeline(StandardScaler(), PCA(n_components=0.95, svd_solver="full"),
                        LinearRegression()).fit(X, y)
    np.testing.assert_allclose(pcr.predict(X), ref.predict(X), atol=1e-9)
    np.testing.assert_allclose(pcr.predict(X), X @ pcr.coef_ + pcr.intercept_)
    assert pcr.coef_.shape == (6,)


def test_all_components_is_ordinary_least_squares_and_fewer_shrink_the_collinear_fit():
    X, y = _collinear(1)
    full = PCR(variance=1.0).fit(X, y)
    mlr = MLR().fit(X, y)
    np.testing.assert_allclose(full.coef_, mlr.coef_, rtol=1e-6, atol=1e-8)
    assert full.intercept_ == pytest.approx(mlr.intercept_, abs=1e-6)
    # on standardised inputs PCR projects the OLS coefficients onto the kept components
    s = X.std(axis=0)
    assert np.linalg.norm(PCR(0.95).fit(X, y).coef_ * s) < np.linalg.norm(mlr.coef_ * s)


def test_pickle_round_trip_identical_predictions():
    X, y = _collinear(2)
    pcr = PCR().fit(X, y)
    np.testing.assert_array_equal(pickle.loads(pickle.dumps(pcr)).predict(X), pcr.predict(X))


@pytest.mark.parametrize("variance", [0.0, -0.1, 1.5])
def test_bad_variance_is_refused(variance):
    X, y = _collinear(3, 50)
    with pytest.raises(ValueError, match="variance"):
        PCR(variance=variance).fit(X, y)
