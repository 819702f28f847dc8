"""model_selection: information criteria, the greedy Gram search, campaign splitters."""

import numpy as np
import pandas as pd
import pytest
import sklearn
import statsmodels.api as sm
from sklearn.linear_model import LinearRegression
from sklearn.model_selection import cross_val_score

from conftest import ctx
from thermocomp.apps.sim import YearRoundSpindle
from thermocomp.base.errors import ParameterError
from thermocomp.core.frame import stack
from thermocomp.core.model_selection import (
    CampaignHoldOut,
    ForwardChaining,
    LeaveCampaignsOut,
    LeaveOneCampaignOut,
    TrainOnEachCampaign,
    greedy_path,
    information_criteria,
    information_criterion,
    scaled_gram,
    unit_labels,
)
from thermocomp.core.models import ARX, LSTM
from thermocomp.core.select import GreedyResidualSelector


def linear_data(n_campaigns=2, n=200, p=8, seed=0, noise=0.05):
    """Random-walk sensors per campaign; y = 2 x1 - x4 + noise."""
    rng = np.random.default_rng(seed)
    X = np.vstack([np.cumsum(rng.normal(0, 0.1, (n, p)), axis=0) for _ in range(n_campaigns)])
    y = 2.0 * X[:, 1] - X[:, 4] + rng.normal(0, noise, len(X)) if noise else 2.0 * X[:, 1] - X[:, 4]
    return X, y, np.repeat([f"K{c}" for c in range(n_campaigns)], n)


def centred_gram(X, y):
    A = np.column_stack([X, y])
    A = A - A.mean(axis=0)
    return A.T @ A


# -- information criteria ---------------------------------------------------------------------------

def test_criteria_formulas_and_undefined_values():
    n, rss, tss = 100, 4.0, 50.0
    base = n * np.log(rss / n)
    ic = information_criteria(rss, n, 3, tss=tss)
    assert ic["aic"] == pytest.approx(base + 6)
    assert ic["aicc"] == pytest.approx(base + 6 + 2 * 3 * 4 / 96)
    assert ic["bic"] == pytest.approx(base + 3 * np.log(n))
    assert ic["bicc"] == pytest.approx(base + n * 3 * np.log(n) / 95)
    assert information_criterion(rss, n, 3, "bicc", tss=tss) == ic["bicc"]
    small = information_criteria(rss, 5, 3, tss=tss)     # N - k - 2 = 0: the corrections are undefined
    assert small["bicc"] == np.inf and np.isfinite(small["aicc"])
    assert information_criteria(rss, 4, 3, tss=tss)["aicc"] == np.inf
    assert information_criteria(rss, 0, 3, tss=tss) == dict.fromkeys(ic, np.inf)
    assert information_criteria(np.inf, n, 3, tss=tss)["aic"] == np.inf      # an unstable free run
    with pytest.raises(ValueError, match="criterion must be one of"):
        information_criterion(rss, n, 3, "hqc", tss=tss)


def test_criterion_differences_match_statsmodels_likelihood():
    X, y, _ = linear_data(seed=5)
    tss = float(np.sum((y - y.mean()) ** 2))
    small, big = sm.OLS(y, sm.add_constant(X[:, :2])).fit(), sm.OLS(y, sm.add_constant(X[:, :5])).fit()
    ic_small = information_criteria(small.ssr, len(y), 3, tss=tss)
    ic_big = information_criteria(big.ssr, len(y), 6, tss=tss)
    assert ic_big["aic"] - ic_small["aic"] == pytest.approx(big.aic - small.aic, rel=1e-9)
    assert ic_big["bic"] - ic_small["bic"] == pytest.approx(big.bic - small.bic, rel=1e-9)
    # the corrections only add penalty, and vanish as n grows
    assert ic_small["bicc"] > ic_small["bic"] and ic_small["aicc"] > ic_small["aic"]
    far = information_criteria(1.0, 10**9, 3, tss=1e9)
    assert far["bicc"] - far["bic"] == pytest.approx(0.0, abs=1e-3)


def test_rss_floor_makes_perfect_fits_tie_and_leaves_real_fits_alone():
    tss, n = 1e4, 500
    at_floor = information_criteria(1e-15 * tss, n, 3, tss=tss)
    for rounding_noise in (0.0, 1e-30, 1e-13):
        assert information_criteria(rounding_noise, n, 3, tss=tss) == at_floor
    assert information_criteria(1e-9, n, 3, tss=tss)["bic"] > at_floor["bic"]
    # every criterion is finite for a perfect fit, and the larger perfect model scores worse
    assert all(np.isfinite(v) for v in at_floor.values())
    bigger = information_criteria(0.0, n, 4, tss=tss)
    assert all(bigger[c] > at_floor[c] for c in at_floor)


def test_the_smallest_exact_model_wins_a_noise_free_target_in_arx_and_the_selector():
    """y = 2 x1 - x4 exactly: every larger model fits to rounding noise; the floor makes them
    tie, so both callers of the criteria keep exactly the two true inputs."""
    X, y, g = linear_data(n_campaigns=3, seed=7, noise=0.0)
    arx = ARX().fit(X, y, context=ctx(g))
    assert sorted(arx.inputs_) == ["x1", "x4"] and not arx.chosen_["ar"]
    sel = GreedyResidualSelector().fit(pd.DataFrame(X).add_prefix("x"), y)
    assert sorted(sel.selected_) == ["x1", "x4"] and sel.ic_.idxmin() == 2


# -- greedy search ----------------------------------------------------------------------------------

def test_greedy_path_rss_equals_least_squares_refit():
    X, y, _ = linear_data(seed=3)
    M = centred_gram(X, y)
    for search in ("residual", "forward"):
        order, rss, _ = greedy_path(M, X.shape[1], range(X.shape[1]), max_inputs=5, search=search)
        assert len(order) == 5 and len(set(order)) == 5
        for k in range(1, 6):
            design = sm.add_constant(X[:, order[:k]])
            assert rss[k - 1] == pytest.approx(sm.OLS(y, design).fit().ssr, rel=1e-8)


def test_residual_search_is_the_papers_split_greedy():
    """Each step: one-input fit of the current residual per remaining sensor, keep the best, subtract."""
    X, y, _ = linear_data(seed=4)
    X = X + 0.7 * X[:, [1]]                       # correlated sensors: residual != forward search
    path = greedy_path(centred_gram(X, y), 8, range(8), max_inputs=4, search="residual")
    resid, expected = y.copy(), []
    for _ in range(4):
        fits = {j: np.polyfit(X[:, j], resid, 1) for j in range(8) if j not in expected}
        mse = {j: np.mean((resid - np.polyval(c, X[:, j])) ** 2) for j, c in fits.items()}
        best = min(mse, key=mse.get)
        resid = resid - np.polyval(fits[best], X[:, best])
        expected.append(best)
    assert path.order == expected
    assert path.order != greedy_path(centred_gram(X, y), 8, range(8), max_inputs=4, search="forward").order


def test_sensor_groups_collinear_candidates_and_forced_terms():
    X, y, _ = linear_data(seed=8)
    # delayed copies share their sensor: one delay per sensor, then the search stops
    lagged = np.vstack([X[:1], X[:-1]])
    Z = np.hstack([X, lagged])
    path = greedy_path(centred_gram(Z, y), 16, range(16), list(range(8)) * 2, max_inputs=16)
    assert sorted(j % 8 for j in path.order) == list(range(8))
    # a constant candidate is never picked, nor an exact twin of a picked one
    Z = np.hstack([X, 3.0 * X[:, [1]] + 1.0, np.ones((len(y), 1))])
    path = greedy_path(centred_gram(Z, y), 10, range(10), max_inputs=10)
    assert 9 not in path.order and not {1, 8} <= set(path.order) and len(path.order) == 8
    # a forced term (the AR regressor) is in every model the RSS describes
    Z = np.hstack([X, np.r_[0.0, y[:-1]][:, None], np.ones((len(y), 1))])
    M = centred_gram(Z, y)
    path = greedy_path(M, 10, range(8), forced=(8,), max_inputs=4)
    for k in range(1, 5):
        ols = sm.OLS(y, sm.add_constant(Z[:, path.order[:k] + [8]])).fit()
        assert path.rss[k - 1] == pytest.approx(ols.ssr, rel=1e-8)
    with pytest.raises(np.linalg.LinAlgError):
        greedy_path(M, 10, range(8), forced=(9,))           # a constant forced term


def _replayed_split_greedy(X: np.ndarray, y: np.ndarray, steps: int):
    """The selector's search replayed on the data with np.polyfit: order and MSE removed."""
    n, p = X.shape
    r, order, gain = y - y.mean(), [], np.zeros(p)

    def removed(j):
        return (r @ r - np.sum((r - np.polyval(np.polyfit(X[:, j], r, 1), X[:, j])) ** 2)) / n

    for _ in range(steps):
        scores = {j: removed(j) for j in range(p) if j not in order}
        best = max(scores, key=scores.get)
        gain[best] = scores[best]
        order.append(best)
        r = r - np.polyval(np.polyfit(X[:, best], r, 1), X[:, best])
    for j in set(range(p)) - set(order):
        gain[j] = removed(j)
    return order, gain


def _simulated_train(seed: int):
    ds, _ = YearRoundSpindle(n_campaigns=6, seed=seed).generate()
    inputs = [c for c in ds.columns if c.startswith("T_")]
    m = stack(ds.campaigns, inputs, ["E_X", "E_Y", "E_Z"])
    return m


@pytest.mark.parametrize("source", ["random", "simulated"])
def test_greedy_selector_order_and_scores_are_the_split_greedy_on_the_data(source):
    """The selector runs on the Gram matrix; replaying the search on the data gives the same
    order and the same MSE removed per sensor (to rounding)."""
    cases = []
    if source == "random":
        for seed in range(3):
            rng = np.random.default_rng(seed)
            X = rng.normal(size=(300, 12)) @ rng.normal(size=(12, 12))   # correlated columns
            cases.append((X, X[:, :3] @ rng.normal(size=3) + rng.normal(0, 1.0, 300)))
    else:
        m = _simulated_train(seed=1)
        cases += [(m.X.to_numpy(float), m.Y[t].to_numpy(float)) for t in m.Y]
    for X, y in cases:
        sel = GreedyResidualSelector(k=None, k_max=10).fit(X, y)
        order, gain = _replayed_split_greedy(X, y, steps=len(sel.ic_))
        assert list(sel.support_order_) == order[:len(sel.selected_)]
        np.testing.assert_allclose(sel.scores_.to_numpy(), gain, rtol=1e-7, atol=1e-9 * np.var(y))


def test_scaled_gram_has_a_unit_diagonal_and_keeps_constant_columns_zero():
    A = np.column_stack([np.arange(5.0) * 1e3, np.zeros(5), np.arange(5.0) ** 2 * 1e-3])
    M, scale = scaled_gram(A - A.mean(axis=0))
    np.testing.assert_allclose(np.diag(M), [1.0, 0.0, 1.0])
    assert scale[1] == 1.0
    np.testing.assert_allclose(M * np.outer(scale, scale), (A - A.mean(0)).T @ (A - A.mean(0)))


# -- splitters --------------------------------------------------------------------------------------

def campaigns_problem(sizes=(30, 20, 25, 40, 15), seed=0):
    rng = np.random.default_rng(seed)
    n = sum(sizes)
    X = rng.normal(size=(n, 3))
    y = X @ [1.0, -2.0, 0.5] + rng.normal(0, 0.1, n)
    groups = np.concatenate([[f"C{i}"] * s for i, s in enumerate(sizes)])
    return X, y, groups


def _manual_scores(est, X, y, splits):
    return [est.fit(X[tr], y[tr]).score(X[te], y[te]) for tr, te in splits]


@pytest.mark.parametrize("cv", [LeaveCampaignsOut(n_folds=3), LeaveCampaignsOut(), LeaveOneCampaignOut(),
                                TrainOnEachCampaign(), CampaignHoldOut(0.4), ForwardChaining(3, gap=5)])
def test_splitters_work_with_cross_val_score(cv):
    X, y, g = campaigns_problem()
    g = None if isinstance(cv, ForwardChaining) else g      # one time-ordered record
    scores = cross_val_score(LinearRegression(), X, y, groups=g, cv=cv)
    splits = list(cv.split(X, y, groups=g))
    assert len(scores) == len(splits) == cv.get_n_splits(X, y, groups=g)
    np.testing.assert_allclose(scores, _manual_scores(LinearRegression(), X, y, splits))
    assert np.all(scores > 0.9)


def test_campaign_splitters_request_groups_under_metadata_routing():
    X, y, g = campaigns_problem()
    with sklearn.config_context(enable_metadata_routing=True):
        for cv in (LeaveCampaignsOut(3), LeaveOneCampaignOut(), TrainOnEachCampaign(), CampaignHoldOut()):
            scores = cross_val_score(LinearRegression(), X, y, params={"groups": g}, cv=cv)
            assert len(scores) == cv.get_n_splits(groups=g)


@pytest.mark.parametrize("cv", [LeaveCampaignsOut(n_folds=3), LeaveCampaignsOut(n_folds=2),
                                LeaveOneCampaignOut()])
@pytest.mark.parametrize("single", [False, True])
def test_every_unit_is_tested_exactly_once_on_disjoint_parts(cv, single):
    X, y, g = campaigns_problem()
    if single:
        g = np.full(len(y), "L")
    units = unit_labels(g, 8)
    seen = []
    for tr, te in cv.split(X, y, groups=g):
        assert not set(tr) & set(te) and len(tr) + len(te) == len(y)
        held = set(units[te])
        assert not held & set(units[tr])                    # whole units only
        seen += sorted(held)
    assert sorted(seen) == sorted(set(units))               # each unit once


@pytest.mark.parametrize("n_blocks", [2, 5, 8])
def test_a_single_campaign_is_cut_into_contiguous_near_equal_blocks(n_blocks):
    units = unit_labels(np.full(103, "L"), n_blocks)
    names = list(dict.fromkeys(units))
    assert names == [f"L#{k}" for k in range(1, n_blocks + 1)]
    changes = np.flatnonzero(units[1:] != units[:-1])
    assert len(changes) == n_blocks - 1                     # each block is one contiguous run
    sizes = pd.Series(units).value_counts()
    assert sizes.max() - sizes.min() <= 1
    # groups=None is one campaign too; every test fold of LeaveOneCampaignOut is one block
    folds = list(LeaveOneCampaignOut(n_blocks=n_blocks).split(np.zeros((103, 1))))
    assert len(folds) == n_blocks and all(np.all(np.diff(te) == 1) for _, te in folds)
    assert unit_labels(np.array(["a", "a", "b"]), n_blocks).tolist() == ["a", "a", "b"]


@pytest.mark.parametrize("sizes", [(5, 5, 5), (3,) * 12, (4, 7, 2, 9, 1, 3, 6)])
@pytest.mark.parametrize("n_folds", [1, 2, 3, 10])
def test_fold_assignment_is_the_diagnosis_rule(sizes, n_folds):
    """Unit i (in order of appearance) -> fold i mod max(2, min(n_folds, n_units)), as
    diagnose/cv.py assigned its folds before the splitters."""
    _, _, g = campaigns_problem(sizes)
    g = g[::-1].copy()                                      # order of appearance, not sorted order
    order = list(dict.fromkeys(g))
    k = max(2, min(n_folds, len(order)))
    expected = np.array([order.index(c) % k for c in g])
    np.testing.assert_array_equal(LeaveCampaignsOut(n_folds).fold_index(g), expected)
    assert LeaveOneCampaignOut().get_n_splits(groups=g) == len(order)


def test_leave_one_campaign_out_holds_campaigns_out_in_order_of_appearance():
    """The ATI elbow's folds: one per campaign, in the order the campaigns come."""
    _, _, g = campaigns_problem()
    g = g[::-1].copy()
    held = [g[te][0] for _, te in LeaveOneCampaignOut().split(g, groups=g)]
    assert held == list(dict.fromkeys(g))


def test_train_on_each_campaign_trains_on_one_and_tests_on_all():
    X, y, g = campaigns_problem()
    splits = list(TrainOnEachCampaign().split(X, y, groups=g))
    assert [g[tr][0] for tr, _ in splits] == list(dict.fromkeys(g))
    assert all(set(g[tr]) == {g[tr][0]} and (g == g[tr][0]).sum() == len(tr) for tr, _ in splits)
    assert all(np.array_equal(te, np.arange(len(y))) for _, te in splits)
    assert len(list(TrainOnEachCampaign().split(np.zeros((9, 1))))) == 1   # one campaign: its self-fit


def _segment_holdout(groups, n, frac, random_state):
    """LSTM's validation rows as models/lstm.py drew them before the splitters."""
    val = np.zeros(n, dtype=bool)
    if frac == 0 or n < 2:
        return val
    starts = [0] if groups is None else list(np.flatnonzero(np.r_[True, groups[1:] != groups[:-1]]))
    bounds = list(zip(starts, starts[1:] + [n]))
    if len(bounds) >= 2:
        n_val = min(len(bounds) - 1, max(1, round(frac * len(bounds))))
        for i in np.random.default_rng(random_state).choice(len(bounds), size=n_val, replace=False):
            val[slice(*bounds[i])] = True
    elif 1 <= round(frac * n) <= n - 1:
        val[n - round(frac * n):] = True
    return val


@pytest.mark.parametrize("frac", [0.0, 0.1, 0.2, 0.5, 0.9])
@pytest.mark.parametrize("random_state", [0, 1, 7])
def test_hold_out_is_lstm_early_stopping_split(frac, random_state):
    for g in (campaigns_problem((30, 20, 25, 40, 15))[2], np.repeat([0, 1, 2, 3], 10), None):
        n = 40 if g is None else len(g)
        cv = CampaignHoldOut(frac, random_state=random_state)
        expected = _segment_holdout(g, n, frac, random_state)
        mask = cv.test_mask(g, np.zeros((n, 1)))
        np.testing.assert_array_equal(mask, expected)
        np.testing.assert_array_equal(LSTM(validation_fraction=frac, random_state=random_state)
                                      ._validation_rows(g, n), expected)
        (tr, te), = cv.split(np.zeros((n, 1)), groups=g)
        assert np.array_equal(np.sort(np.r_[tr, te]), np.arange(n)) and set(te) == set(np.flatnonzero(mask))
        if g is not None and frac > 0:                      # whole campaigns, never all of them
            assert not set(np.asarray(g)[te]) & set(np.asarray(g)[tr]) and len(tr)


@pytest.mark.parametrize("gap", [0, 3, 10])
def test_forward_chaining_respects_time_order_and_the_gap(gap):
    n = 120
    splits = list(ForwardChaining(n_splits=4, gap=gap).split(np.zeros((n, 1))))
    assert len(splits) == 4
    previous = 0
    for tr, te in splits:
        assert np.array_equal(tr, np.arange(len(tr))) and np.all(np.diff(te) == 1)   # contiguous
        assert te[0] - tr[-1] - 1 == gap                    # exactly `gap` samples between them
        assert len(tr) > previous                           # an expanding window
        previous = len(tr)
    assert splits[-1][1][-1] == n - 1


def test_splitter_parameters_and_degenerate_inputs_raise():
    X, y, g = campaigns_problem()
    with pytest.raises(ParameterError):
        list(LeaveCampaignsOut(n_blocks=1).split(X, y, groups=g))
    with pytest.raises(ParameterError):
        list(LeaveCampaignsOut(n_folds=0).split(X, y, groups=g))
    with pytest.raises(ParameterError):
        CampaignHoldOut(1.0).test_mask(g)
    with pytest.raises(ParameterError):
        list(ForwardChaining(gap=-1).split(X))
    with pytest.raises(ValueError, match="at least 2 units"):
        list(LeaveCampaignsOut().split(X[:1], y[:1], groups=g[:1]))
