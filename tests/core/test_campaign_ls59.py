"""The ATI elbow's MLR folds from per-campaign QR factors: the fits on the rows, up to rounding.

``diagnose ati=cmeans`` on 14 climate-room runs spent 40x the CPU of plain ``diagnose`` in the
elbow's 11,644 leave-one-campaign-out MLR fits (stop 58).  The fast path
(:class:`thermocomp.core.models._campaign_ls.CampaignLeastSquares`) must give what
``LinearRegression`` gives on the rows -- full rank, rank deficient (minimum norm, the same
singular-value cut-off) and nearly collinear -- and the elbow the same SM/SD with it as with
every fold fitted on its rows (``ATIRegressor._fast_elbow = False``).
"""

import numpy as np
import pandas as pd
import pytest
from sklearn.linear_model import LinearRegression

from thermocomp.core.context import AMBIENT_C0, CAMPAIGN
from thermocomp.core.models import MLR, _campaign_ls
from thermocomp.core.models._campaign_ls import CampaignLeastSquares
from thermocomp.core.models.ati import ATIRegressor

SIZES = [40, 55, 30, 60, 45, 35]
UNIONS = [[0, 1, 2], [1, 3, 4, 5], [0, 1, 2, 3, 4, 5], [2], [4, 5]]


def design(kind: str, seed: int = 0):
    """Rows of six campaigns: ``random``, ``rank_deficient`` (a column the sum of two others,
    another constant within each campaign: rank-deficient on a union of two campaigns and on
    one) or ``near_collinear`` (a column another plus 1e-6 of noise, condition ~1e5..1e6)."""
    rng = np.random.default_rng(seed)
    n, p = sum(SIZES), 6
    X = rng.normal(size=(n, p)) + 20.0          # absolute temperatures: centring matters
    if kind == "rank_deficient":
        X[:, 3] = X[:, 0] + 2.0 * X[:, 1]
        X[:, 5] = np.repeat(rng.normal(20.0, 3.0, len(SIZES)), SIZES)
    elif kind == "near_collinear":
        X[:, 3] = X[:, 0] + 1e-6 * rng.normal(size=n)
    y = X @ rng.normal(size=p) + rng.normal(size=n)
    return X, y, np.split(np.arange(n), np.cumsum(SIZES)[:-1])


@pytest.mark.parametrize("fit_intercept", [True, False])
@pytest.mark.parametrize("kind", ["random", "rank_deficient", "near_collinear"])
def test_a_union_of_campaigns_fits_as_linear_regression_on_its_rows(kind, fit_intercept):
    X, y, rows = design(kind)
    fits = CampaignLeastSquares(X, y, rows, fit_intercept)
    for members in UNIONS:
        fitted = fits.fit(members)
        assert fitted is not None
        on_rows = np.concatenate([rows[c] for c in members])
        ref = LinearRegression(fit_intercept=fit_intercept).fit(X[on_rows], y[on_rows])
        # the predictions on a held-out and a member campaign; the coefficients (minimum norm
        # where the design is rank deficient: the same solution, not just the same fit)
        for c in {members[0], next((c for c in range(len(rows)) if c not in members), 0)}:
            want = ref.predict(X[rows[c]])
            np.testing.assert_allclose(fits.predict(fitted, c), want, rtol=0,
                                       atol=1e-9 * np.abs(want).max())
        # nearly collinear: the coefficients are only defined to cond * eps (1e5 * 2e-16)
        tol = 1e-8 if kind == "near_collinear" else 1e-11
        np.testing.assert_allclose(fitted[0], ref.coef_, rtol=0, atol=tol * np.abs(ref.coef_).max())


def test_a_singular_value_at_the_cut_off_is_left_to_the_rows(monkeypatch):
    """Only a fit on the rows decides which side of lstsq's cut-off such a value falls."""
    X, y, rows = design("random")
    assert CampaignLeastSquares(X, y, rows).fit([0, 1]) is not None
    monkeypatch.setattr(_campaign_ls, "CUTOFF_BAND", 1e12)     # every value "at" the cut-off
    assert CampaignLeastSquares(X, y, rows).fit([0, 1]) is None


def climate_runs(seed: int = 3):
    """Ten runs at their own room levels, a law whose slope falls with the level, a sensor
    nearly a copy of another and one that is constant in each run (its start level)."""
    rng = np.random.default_rng(seed)
    frames = []
    for k, level in enumerate([15.0, 16.5, 18.0, 21.0, 22.5, 24.0, 27.0, 29.0, 31.5, 34.0]):
        n = int(rng.integers(40, 70))
        t1 = level + np.cumsum(rng.uniform(0.0, 0.2, n))
        t2 = level + np.cumsum(rng.uniform(0.0, 0.1, n))
        frames.append(pd.DataFrame({
            "T_1": t1, "T_2": t2, "T_3": t1 + 1e-6 * rng.normal(size=n), "T_4": np.full(n, level),
            "E_X": (1 - 0.02 * (level - 20)) * 2.0 * (t1 - t1[0]) + 0.5 * (t2 - t2[0])
            + rng.normal(0, 0.05, n),
            CAMPAIGN: f"C{k:02d}", AMBIENT_C0: level + rng.normal(0, 0.01)}))
    df = pd.concat(frames, ignore_index=True)
    return df[["T_1", "T_2", "T_3", "T_4"]].to_numpy(), df["E_X"].to_numpy(), df[[CAMPAIGN, AMBIENT_C0]]


def elbow(monkeypatch, fast: bool, sparse: bool = False, **params):
    """The elbow's figures with the fast path on or off, and the base fits made on rows
    (``sparse``: the target measured on every fifth row only, NaN between)."""
    monkeypatch.setattr(ATIRegressor, "_fast_elbow", fast)
    on_rows = []
    fit_base = ATIRegressor._fit_base

    def counted(self, X, y, rows, context):
        on_rows.append(int(np.sum(rows)))
        return fit_base(self, X, y, rows, context)

    monkeypatch.setattr(ATIRegressor, "_fit_base", counted)
    X, y, context = climate_runs()
    if sparse:
        y = np.where(np.arange(y.size) % 5 == 0, y, np.nan)
    ati = ATIRegressor(MLR(), candidates=(1, 2, 3, 4), **params).fit(X, y, context=context)
    return ati, len(on_rows)


@pytest.mark.parametrize("params", [{"ambient_interaction": True}, {"min_campaigns": 1},
                                    {"clustering": "hard"}])
def test_the_elbow_from_campaign_factors_scores_as_with_every_fold_on_its_rows(monkeypatch, params):
    fast, fast_row_fits = elbow(monkeypatch, True, **params)
    plain, plain_row_fits = elbow(monkeypatch, False, **params)
    assert fast_row_fits == fast.n_intervals_           # the folds: none fitted on rows
    assert plain_row_fits > 10 * plain.n_intervals_
    assert fast.elbow_["chosen"] == plain.elbow_["chosen"]
    assert fast.elbow_["n_intervals"] == plain.elbow_["n_intervals"]
    for key in ("sm", "sd"):
        np.testing.assert_allclose(fast.elbow_[key], plain.elbow_[key], rtol=1e-9)
    np.testing.assert_allclose([fast.elbow_["single_model"]["sm"], fast.elbow_["single_model"]["sd"]],
                               [plain.elbow_["single_model"]["sm"], plain.elbow_["single_model"]["sd"]],
                               rtol=1e-9)
    np.testing.assert_array_equal(fast.boundaries_, plain.boundaries_)


def test_the_elbow_on_a_target_measured_now_and_then_scores_its_measured_rows(monkeypatch):
    """stranger76: a laser tracker every 5 min beside temperatures every 10 s, the target NaN
    between; the fast folds took the NaN into their least squares, every count scored NaN ("no
    number of intervals could be cross-validated; one model")."""
    fast, _ = elbow(monkeypatch, True, sparse=True, ambient_interaction=True)
    plain, _ = elbow(monkeypatch, False, sparse=True, ambient_interaction=True)
    assert fast.elbow_["reason"] is None and np.isfinite(fast.elbow_["sm"]).all()
    assert fast.elbow_["chosen"] == plain.elbow_["chosen"]
    for key in ("sm", "sd"):
        np.testing.assert_allclose(fast.elbow_[key], plain.elbow_[key], rtol=1e-9)
