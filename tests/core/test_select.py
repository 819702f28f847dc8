"""TSP selectors: recovery of the driving sensors, criteria, clustering, sklearn contract."""

import pickle

import numpy as np
import pandas as pd
import pytest
from scipy.signal import lfilter
from sklearn.utils.estimator_checks import check_estimator

from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR
from thermocomp.core.select import ClusterGreySelector, GreedyResidualSelector, PearsonSelector

DRIVERS = {"T_g0_1": 2.0, "T_g2_0": -1.5}


def _lag(x, tau, dt=60.0):
    a = np.exp(-dt / tau)
    return lfilter([1 - a], [1, -a], x)


def _heat_source(rng, n, every):
    """Temperature of a node heated by a random step programme (°C)."""
    steps = np.repeat(rng.uniform(0, 10, n // every + 1), every)[:n]
    return _lag(steps, rng.uniform(2000, 8000))


def _sensors(seed=0, n=2000, groups=3, per_group=4):
    """Three groups of collinear sensors (shared slow trajectory + own slow part + noise)."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 1, n)
    cols = {}
    for g in range(groups):
        latent = np.cumsum(rng.normal(0, 1, n)) / np.sqrt(n) * 5 + (g + 1) * np.sin((g + 1) * 3 * t)
        for s in range(per_group):
            own = np.cumsum(rng.normal(0, 1, n)) / np.sqrt(n) * 1.5
            cols[f"T_g{g}_{s}"] = latent * rng.uniform(0.8, 1.2) + own + rng.normal(0, 0.02, n)
    X = pd.DataFrame(cols)
    y = sum(c * X[name] for name, c in DRIVERS.items()) + rng.normal(0, 0.1, n)
    return X, y.to_numpy(), rng


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_greedy_residual_finds_the_sensors_that_drive_the_error(seed):
    """Ten sensors, each behind its own heat source (lagged step programme); the error is
    driven by three of them plus 0.3 µm noise.  BICc picks exactly those three."""
    rng = np.random.default_rng(seed)
    n, truth = 3000, {"T_3": 2.0, "T_5": -1.0, "T_6": 0.7}
    X = pd.DataFrame({f"T_{i}": _lag(_heat_source(rng, n, 100), rng.uniform(300, 3000))
                      + rng.normal(0, 0.03, n) for i in range(10)})
    y = sum(c * X[k] for k, c in truth.items()) + rng.normal(0, 0.3, n)
    sel = GreedyResidualSelector(k=None, criterion="bicc").fit(X, y.to_numpy())
    assert sorted(sel.selected_) == sorted(truth)
    assert sel.ic_.idxmin() == 3 and list(sel.ic_.index) == list(range(1, 11))
    assert sel.scores_[sel.selected_[0]] == sel.scores_.max()
    assert GreedyResidualSelector(k=1).fit(X, y).selected_ == sel.selected_[:1]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_greedy_residual_finds_the_driving_heat_sources_among_collinear_sensors(seed):
    """Four near-collinear sensors per source (r ~ 0.99): the first two greedy picks cover
    exactly the two sources that drive the error (which sibling comes first may vary)."""
    rng = np.random.default_rng(seed)
    n, cols = 3000, {}
    for s in range(3):
        node = _heat_source(rng, n, 300)
        for j in range(4):
            cols[f"T_s{s}_{j}"] = _lag(node, rng.uniform(300, 6000)) + rng.normal(0, 0.03, n)
    X = pd.DataFrame(cols)
    y = 2.0 * X["T_s0_1"] + 1.0 * X["T_s2_0"] + rng.normal(0, 0.2, n)
    sel = GreedyResidualSelector(k=2).fit(X, y.to_numpy())
    assert sorted(name.split("_")[1] for name in sel.selected_) == ["s0", "s2"]


def test_greedy_steps_are_one_input_fits_on_the_running_residual():
    X, y, _ = _sensors(3)
    sel = GreedyResidualSelector(k=3).fit(X, y)
    r = y - y.mean()
    for name in sel.selected_:  # replay the algorithm with np.polyfit
        sse = {c: np.sum((r - np.polyval(np.polyfit(X[c], r, 1), X[c])) ** 2)
               for c in X if c not in sel.selected_[:sel.selected_.index(name)]}
        assert min(sse, key=sse.get) == name
        r = r - np.polyval(np.polyfit(X[name], r, 1), X[name])


def test_pearson_keeps_the_top_k_by_absolute_correlation():
    X, y, _ = _sensors(4)
    X["T_neg"] = -y + np.random.default_rng(0).normal(0, 0.01, len(y))  # anti-correlated with y
    sel = PearsonSelector(k=3).fit(X, y)
    r = np.abs([np.corrcoef(X[c], y)[0, 1] for c in X])
    np.testing.assert_allclose(sel.scores_.to_numpy(), r, atol=1e-12)
    assert sel.selected_ == list(X.columns[np.argsort(-r, kind="stable")[:3]])
    assert sel.selected_[0] == "T_neg"
    assert sel.get_support().sum() == 3 and sel.ic_ is None


def test_cluster_grey_takes_one_representative_per_group_of_collinear_sensors():
    X, y, _ = _sensors(5)
    sel = ClusterGreySelector(k=3).fit(X, y)
    groups = {name: name.split("_")[1] for name in X}
    assert sorted(groups[s] for s in sel.selected_) == ["g0", "g1", "g2"]
    by_cluster = {}
    for name, c in sel.clusters_.items():
        by_cluster.setdefault(c, set()).add(groups[name])
    assert all(len(v) == 1 for v in by_cluster.values())  # clusters are the true groups
    for s in sel.selected_:  # each representative has the best grey degree of its cluster
        mates = [n for n, c in sel.clusters_.items() if c == sel.clusters_[s]]
        assert sel.scores_[mates].idxmax() == s
    auto = ClusterGreySelector(k=None, k_max=6).fit(X, y)
    assert list(auto.ic_.index) == list(range(1, 7)) and len(auto.selected_) in auto.ic_.index


@pytest.mark.parametrize("selector", [PearsonSelector(), PearsonSelector(k=None),
                                      GreedyResidualSelector(), ClusterGreySelector(k=2)])
def test_sklearn_checks(selector):
    check_estimator(selector)


@pytest.mark.parametrize("selector", [PearsonSelector(k=2), GreedyResidualSelector(k=None),
                                      ClusterGreySelector(k=3)])
def test_pickle_round_trip_and_compensator_use(selector):
    X, y, rng = _sensors(6, n=400)
    sel = selector.fit(X, y)
    again = pickle.loads(pickle.dumps(sel))
    assert again.selected_ == sel.selected_
    pd.testing.assert_frame_equal(again.set_output(transform="pandas").transform(X),
                                  sel.set_output(transform="pandas").transform(X))
    df = X.assign(time=np.arange(len(X)) * 30.0, E_Z=y)
    camps = {"A": df.iloc[:200], "B": df.iloc[200:].reset_index(drop=True)}
    comp = Compensator(MLR(), selector=selector).fit(camps)
    assert 1 <= len(comp.selected_["E_Z"]) <= 10
    assert set(comp.selected_["E_Z"]) <= set(X.columns)


def test_bad_parameters_are_refused():
    X, y, _ = _sensors(7, n=100)
    for sel in (PearsonSelector(k=0), GreedyResidualSelector(criterion="hqc"),
                ClusterGreySelector(m=1.0), GreedyResidualSelector(k_max=0)):
        with pytest.raises(ValueError):
            sel.fit(X, y)
