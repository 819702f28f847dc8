"""``model=auto`` scoring its campaign folds on the held-out rows past the fit campaigns' range
(``validation_rows='outside'``, auto85b), only where two or more folds hold campaigns out (auto85c).

Later campaigns swing wider than the earlier ones, and the error saturates past the range the
early campaigns span: a family that extrapolates as the truth does there, a little worse than MLR
where the inputs have been seen, should win the votes the new campaigns' rows would give it.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from thermocomp.core.model_selection.extrapolation import outside_box
from thermocomp.core.models import MLR
from thermocomp.core.models.auto import AutoRegressor, outside_rows


class Capped(MLR):
    """MLR, its predictions stopped at the largest it made on its fit rows and 0.02 off: worse
    than MLR inside the fit range, saturating (as the truth) beyond it."""

    def fit(self, X, y, context=None):
        super().fit(X, y, context=context)
        self.cap_ = float(np.max(super().predict(X, context=context)))
        return self

    def predict(self, X, context=None):
        return np.minimum(super().predict(X, context=context), self.cap_) + 0.02


def _campaigns(amplitudes=(0.5, 0.5, 0.5, 0.55, 0.6, 0.65), n: int = 200):
    """One sensor cycling around 0.5 per campaign with the given amplitudes; the error follows it
    up to 1 and saturates beyond (only the wider, later campaigns get there)."""
    rng = np.random.default_rng(2)
    x = np.concatenate([0.5 + a * np.sin(np.arange(n) / 15.0 + k) for k, a in enumerate(amplitudes)])
    y = np.minimum(x, 1.0) + rng.normal(0.0, 0.01, x.size)
    context = pd.DataFrame({"campaign": np.repeat([f"C{k + 1}" for k in range(len(amplitudes))], n),
                            "time": np.tile(np.arange(n) * 60.0, len(amplitudes))})
    return x[:, None], y, context


def _auto(rows: str) -> AutoRegressor:
    return AutoRegressor({"mlr": MLR(), "capped": Capped()}, validation_rows=rows)


def test_the_votes_on_rows_past_the_fit_range_go_to_the_family_that_extrapolates():
    X, y, context = _campaigns()
    everywhere, outside = (_auto(rows).fit(X, y, context=context) for rows in ("all", "outside"))
    assert everywhere.scheme_ == outside.scheme_ == "blocked forward"
    assert everywhere.weights_ == {"mlr": 1.0}            # its 0.02 offset on every row seen
    assert outside.weights_["capped"] > 0.5               # its saturation where the inputs are new
    said = outside.report()["voting_rows"]
    assert said["rule"] == "outside" and 0 < said["scored"] < said["of"] == outside.oof_y_.size
    where = f"on the {said['scored']} of {said['of']} rows where the fold takes an input past"
    assert where in outside.reason_
    assert everywhere.report()["voting_rows"] == {"rule": "all", "scored": said["of"], "of": said["of"],
                                                  "folds": said["folds"]}


def test_the_rows_scored_are_each_folds_held_out_rows_outside_its_fit_rows_box():
    X, y, context = _campaigns()
    auto = _auto("outside").fit(X, y, context=context)
    n, folds = auto.oof_folds_
    for k, (fit, score) in enumerate(folds):
        fitted, scored = np.isin(np.arange(n), fit), np.isin(np.arange(n), score)
        past = (X[score, 0] > X[fit, 0].max()) | (X[score, 0] < X[fit, 0].min())
        np.testing.assert_array_equal(outside_box(X, fitted, scored)[score], past)
        np.testing.assert_array_equal(auto.oof_outside_[auto.oof_fold_ == k], past)


def test_one_records_folds_hold_no_campaign_out_and_are_scored_whole():
    X, y, context = _campaigns()
    one = context.assign(campaign="R1", time=np.arange(len(y)) * 60.0)
    fits = [_auto(rows).fit(X, y, context=one) for rows in ("all", "outside")]
    assert fits[1].oof_outside_ is None and fits[1].report()["voting_rows"]["scored"] == len(fits[1].oof_y_)
    assert fits[0].weights_ == fits[1].weights_


def test_one_campaign_fold_is_scored_whole_as_shipped():
    X, y, context = _campaigns()
    three = context["campaign"].isin(["C1", "C2", "C5"]).to_numpy()   # 3 train campaigns: one fold
    fits = [_auto(rows).fit(X[three], y[three], context=context[three]) for rows in ("all", "outside")]
    assert fits[1].scheme_ == "blocked forward" and np.unique(fits[1].oof_fold_).size == 1
    assert fits[1].oof_outside_ is None
    assert fits[1].report()["voting_rows"]["scored"] == len(fits[1].oof_y_)
    assert fits[0].weights_ == fits[1].weights_


def test_a_fold_with_too_few_rows_outside_is_scored_whole():
    fold = np.repeat([0, 1], 30)
    outside = np.zeros(60, bool)
    outside[:25] = True                                  # fold 0: 25 outside, fold 1: 5
    outside[30:35] = True
    keep = outside_rows(outside, fold, min_rows=20)
    assert keep[:30].sum() == 25 and keep[30:].all()
    assert outside_rows(outside[:30], fold[:30], min_rows=20).sum() == 25    # one fold: its rows outside


def test_a_nan_input_is_never_outside():
    X = np.array([[0.0, 0.0], [1.0, 1.0], [np.nan, 2.0], [np.nan, 0.5]])
    train, scored = np.array([1, 1, 0, 0], bool), np.array([0, 0, 1, 1], bool)
    np.testing.assert_array_equal(outside_box(X, train, scored), [False, False, True, False])


def test_the_shipped_config_scores_the_rows_outside():
    from hydra import compose, initialize_config_dir

    from thermocomp.base.paths import conf_dir

    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=["model=auto"])
    assert cfg.model.estimator.validation_rows == "outside"
