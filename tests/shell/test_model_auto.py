"""``model=auto``: per target the family with the best free-run validation, as one model.

Tiny data: two sensors, two targets built so that they prefer different families
(``E_A`` static in the sensors: MLR; ``E_B`` a slow lag of them: the lag bank).
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, refused
from test_hostile import snapshot
from thermocomp.shell.cli import main

SPLITS = ("train",) * 6 + ("test",) * 2
PAIR = "model.candidates=[mlr,lagbank]"
# the rules below judged as they were built: without the hedge toward MLR (auto105b, on by default;
# it has its own test, tests/core/test_auto_hedge105b.py), which mixes MLR into any kept blend here
UNHEDGED = "model.estimator.hedge=none"


def lagged(x: np.ndarray, tau_s: float, dt_s: float) -> np.ndarray:
    """First-order lag of ``x`` (steady start), the slow part the lag bank can model."""
    out, a = np.empty_like(x), dt_s / (tau_s + dt_s)
    out[0] = x[0]
    for i in range(1, len(x)):
        out[i] = out[i - 1] + a * (x[i] - out[i - 1])
    return out


def make_two_targets(root: Path, rows: int = 80, test_gain: float = 1.0) -> Path:
    """Eight campaigns (six train, two test) of heating then cooling; ``test_gain`` multiplies
    the measured errors of the test campaigns (values the choice must not see)."""
    root.mkdir(parents=True)
    rng = np.random.default_rng(1)
    dt, t = 60.0, np.arange(rows) * 60.0
    for i, split in enumerate(SPLITS):
        amb = 20.0 + 0.3 * i
        on = (t < (0.4 + 0.05 * i) * t[-1]).astype(float)
        heat = lagged(on * (4 + i % 3), 600.0, dt)
        t0 = amb + heat + rng.normal(0, 0.02, rows)
        t1 = amb + 0.3 * heat + rng.normal(0, 0.02, rows)
        e_a = 3 * (t0 - t0[0]) - 1.0 * (t1 - t1[0]) + rng.normal(0, 0.3, rows)
        e_b = 6 * lagged(t0 - t0[0], 2400.0, dt) + rng.normal(0, 0.05, rows)
        gain = test_gain if split == "test" else 1.0
        pd.DataFrame({"time": t, "T_0": t0, "T_1": t1, "E_A": gain * e_a, "E_B": gain * e_b}
                     ).to_csv(root / f"K{i + 1:02d}.csv", index=False)
    pd.DataFrame({"campaign": [f"K{i + 1:02d}" for i in range(len(SPLITS))],
                  "file": [f"K{i + 1:02d}.csv" for i in range(len(SPLITS))], "split": SPLITS}
                 ).to_csv(root / "campaigns.csv", index=False)
    return root


def _run(data: Path, out: Path, *extra: str) -> dict:
    assert main(["run", f"data.path={data}", f"out={out}", *FAST, *extra]) == 0
    return json.loads((out / "metrics.json").read_text())


@pytest.fixture(scope="module")
def two_targets(tmp_path_factory):
    """``run model=auto`` of :data:`PAIR`, validated (the model it fits and its test scores are
    the same either way; the validation reuses the choice's folds): data, metrics, folder."""
    root = tmp_path_factory.mktemp("auto")
    data = make_two_targets(root / "data")
    return data, _run(data, root / "auto", "model=auto", PAIR, UNHEDGED, "eval.validation=true"), root


@pytest.fixture(scope="module")
def pair_fitted(two_targets):
    """The train campaigns, the unfitted :data:`PAIR` auto compensator and it fitted on them, in
    this process (read by two tests; each clones the template before fitting it)."""
    from sklearn.base import clone

    from thermocomp.core.compensator import Compensator
    from thermocomp.core.io import read_dataset
    from thermocomp.core.models import MLR, LagBank
    from thermocomp.core.models.auto import AutoRegressor

    ds, _ = read_dataset(two_targets[0])
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    template = Compensator(AutoRegressor({"mlr": MLR(), "lagbank": LagBank()}, hedge="none"))
    return train, template, clone(template).fit(train)


def test_each_target_keeps_the_family_with_the_best_free_run_validation(two_targets):
    data, metrics, root = two_targets
    chosen = {t: m["auto"]["chosen"] for t, m in metrics["targets"].items()}
    assert chosen == {"E_A": "mlr", "E_B": "lagbank"}
    for t, m in metrics["targets"].items():
        scores = {n: v for n, v in m["auto"]["candidates"].items() if n in ("mlr", "lagbank")}
        assert m["auto"]["chosen"] == min(scores, key=scores.get)
        assert "persistence" in m["auto"]["candidates"]
    # the composite scores exactly as each chosen family fitted alone
    for family, target in (("mlr", "E_A"), ("lagbank", "E_B")):
        alone = _run(data, root / family, f"model={family}")
        assert metrics["targets"][target]["test"]["rmse"] == pytest.approx(
            alone["targets"][target]["test"]["rmse"], rel=1e-9)


def test_the_test_split_chooses_nothing(two_targets, tmp_path):
    _, metrics, _ = two_targets
    shifted = make_two_targets(tmp_path / "data", test_gain=-3.0)
    other = _run(shifted, tmp_path / "auto", "model=auto", PAIR)
    for t, m in metrics["targets"].items():
        assert other["targets"][t]["auto"]["candidates"] == m["auto"]["candidates"]
        assert other["targets"][t]["auto"]["chosen"] == m["auto"]["chosen"]
        assert other["targets"][t]["test"]["rmse"] > 3 * m["test"]["rmse"]   # the test did change


def test_the_composite_streams_in_replay_as_it_predicts_in_run(two_targets, tmp_path):
    data, run, root = two_targets          # the fixture's run: model=auto, PAIR, FAST
    common = [f"data.path={data}", "track=false", "model=auto", PAIR]
    assert main(["replay", *common, f"replay.model={root / 'auto' / 'model.pkl'}",
                 f"out={tmp_path / 'replay'}"]) == 0     # the run's model, not a refit
    replay = json.loads((tmp_path / "replay" / "replay.json").read_text())
    for t in ("E_A", "E_B"):
        assert replay["targets"][t]["max_abs_stream_minus_batch"] < 1e-6
        assert replay["targets"][t]["rmse"] == pytest.approx(run["targets"][t]["test"]["rmse"], rel=1e-6)


def _with_ambient(data: Path, to: Path, level) -> Path:
    """A copy of ``data`` with an air sensor ``T_amb`` at ``level(i)`` °C in campaign ``i``."""
    shutil.copytree(data, to)
    for i, f in enumerate(sorted(to.glob("K*.csv"))):
        df = pd.read_csv(f)
        df["T_amb"] = level(i) + 0.01 * np.sin(df["time"] / 600.0)
        df.to_csv(f, index=False)
    return to


def test_an_ati_candidate_applies_only_where_the_train_campaigns_span_ambient_levels(two_targets, tmp_path):
    data, _, _ = two_targets
    ati = ["model=auto", "model.candidates=[mlr,ati]"]
    for m in _run(data, tmp_path / "none", *ati)["targets"].values():
        assert m["auto"]["chosen"] == "mlr" and "ati" not in m["auto"]["candidates"]
        assert "no campaign ambient" in m["auto"]["skipped"]["ati"]
    one = _with_ambient(data, tmp_path / "one", lambda i: 20.0)
    for m in _run(one, tmp_path / "one_out", *ati)["targets"].values():
        assert "span 1 ambient level(s)" in m["auto"]["skipped"]["ati"]
    with_val = _with_val_split(data, tmp_path / "val")       # scored on the val split: the same why
    for m in _run(with_val, tmp_path / "val_out", *ati)["targets"].values():
        assert m["auto"]["scheme"] == "val split" and "T_amb" in m["auto"]["skipped"]["ati"]
    seasons = _with_ambient(data, tmp_path / "seasons", lambda i: 12.0 + 2.0 * i)
    for m in _run(seasons, tmp_path / "seasons_out", *ati)["targets"].values():
        assert "ati" in m["auto"]["candidates"] and not m["auto"]["skipped"]
        assert m["auto"]["validated_as"] == {}      # its folds fit at 3+ levels: its own model


def test_an_ati_candidate_whose_folds_fit_mlr_is_said_to_tie_it(two_targets, tmp_path, capsys):
    """The train campaigns span 3 ambient levels, the fit campaigns of each forward fold 2 (the
    third is the last train campaign's, hbm75 seed 7601's case): every fold's ATI model is one
    MLR, validated as MLR row for row and weighed nothing; said, the choice unchanged."""
    data, _, _ = two_targets
    levels = (20.0, 20.0, 20.6, 20.6, 20.6, 22.0, 21.0, 21.0)     # six train, two test
    tied = _with_ambient(data, tmp_path / "tied", lambda i: levels[i])
    capsys.readouterr()
    metrics = _run(tied, tmp_path / "tied_out", "model=auto", "model.candidates=[mlr,ati]")
    for m in metrics["targets"].values():
        a = m["auto"]
        assert a["candidates"]["ati"] == a["candidates"]["mlr"] and a["weights"] == {"mlr": 1.0}
        assert "at most 2 ambient level(s), the train split 3" in a["validated_as"]["ati"]
    assert "ati validated as mlr, row for row" in capsys.readouterr().out


@pytest.mark.parametrize("overrides, says", [
    (["model.candidates=[mlr,nope]"], "model.candidates: 'nope' is not a model family"),
    (["model.candidates=[auto]"], "model.candidates: 'auto'"),
    (["model.candidates=[]"], "model.candidates is empty"),
    (["model.candidate_params={lstm:{max_epochs:2}}"], "model.candidate_params.lstm"),
    (["model.candidate_params={mlr:{fit_intercept:maybe}}"], "fit_intercept"),
    (["model.candidate_defaults=3"], "model.candidate_defaults=3"),
    (["model.candidate_defaults={lagbank:{n_taus:-1}}"], "model.candidates.lagbank.n_taus=-1"),
    (["ati=cmeans"], "model=auto with ati=cmeans"),
    (["model.estimator.one_record=middle"], "one_record"),
    (["model.estimator.validation_rows=some"], "validation_rows"),
])
def test_a_bad_auto_config_is_refused_before_any_work(two_targets, tmp_path, capsys, overrides, says):
    data, _, _ = two_targets
    out = tmp_path / "out"
    before = snapshot(out)
    refused(["run", f"data.path={data}", f"out={out}", *FAST, "model=auto",
             "model.candidates=[mlr,lagbank]", *overrides], capsys, says)
    assert snapshot(out) == before


def test_blocked_forward_folds_never_fit_on_later_units():
    from thermocomp.core.model_selection import BlockedForward

    groups = np.repeat([f"K{i}" for i in range(6)], 3)
    folds = BlockedForward(n_folds=5, min_train_fraction=0.5).folds(groups)
    assert len(folds) == 3                                   # the later half: K3, K4, K5
    for fit, pred, score in folds:
        assert np.flatnonzero(fit).max() < np.flatnonzero(score).min()
        assert (pred == score).all()
    one = BlockedForward(n_folds=2).folds(None, 40)         # one record: the prefix, a gap
    for fit, pred, score in one:
        first = np.flatnonzero(score).min()
        assert np.flatnonzero(fit).max() < first - 1 and pred[:first].all()


def test_validation_holds_campaigns_out_as_the_test_split_is():
    from test_validation import MAKE, _dataset, _poisoned
    from thermocomp.core.scoring.evaluation import holdout_scheme, validation_report

    last = _dataset(["train"] * 6 + ["test"] * 2)             # the test campaigns come last
    among = _dataset(["train", "train", "test"] * 2 + ["train", "train"])
    assert (holdout_scheme(last), holdout_scheme(among)) == ("forward", "interleaved")

    val = validation_report(MAKE, last, n_folds=3)
    assert val["E_Z"]["method"] == "blocked forward (3 folds)"
    train = last.ids("train")
    assert set(val["E_Z"]["per_unit"]) == set(train[3:])      # the later half, each once
    # by hand: each later campaign predicted by a fit on the campaigns before it
    res = []
    for i in range(3, 6):
        comp = MAKE().fit({c: last.campaigns[c] for c in train[:i]})
        part = {train[i]: last.campaigns[train[i]]}
        pred, meas = comp.predict(part), comp.measured(part)
        res.append(meas[train[i]]["E_Z"].to_numpy() - pred[train[i]]["E_Z"].to_numpy())
    assert val["E_Z"]["rmse"] == pytest.approx(float(np.sqrt(np.mean(np.concatenate(res) ** 2))), rel=1e-9)
    assert validation_report(MAKE, _poisoned(last), n_folds=3) == val
    assert validation_report(MAKE, among, n_folds=3)["E_Z"]["method"] == "leave-campaigns-out (3 folds)"


def test_auto_validates_as_the_test_split_is_held_out(two_targets, tmp_path):
    data, metrics, _ = two_targets
    assert {m["auto"]["scheme"] for m in metrics["targets"].values()} == {"blocked forward"}
    among = tmp_path / "among"
    shutil.copytree(data, among)
    manifest = pd.read_csv(among / "campaigns.csv")
    manifest["split"] = ["train", "train", "test", "train", "train", "train", "test", "train"]
    manifest.to_csv(among / "campaigns.csv", index=False)
    other = _run(among, tmp_path / "auto", "model=auto", PAIR)
    assert {m["auto"]["scheme"] for m in other["targets"].values()} == {"leave-campaigns-out"}


def test_the_run_validates_the_families_auto_chose_as_they_validated(two_targets):
    metrics = two_targets[1]        # the fixture's run: model=auto, PAIR, eval.validation=true
    for m in metrics["targets"].values():    # the chosen family on the same folds: its own score
        assert m["validation"]["method"].startswith("blocked forward (3 folds); model=auto: its members'")
        chosen = m["auto"]["candidates"][m["auto"]["chosen"]]
        assert m["validation"]["rmse"] == pytest.approx(chosen, rel=1e-9)


def test_the_run_refits_the_chosen_families_not_the_whole_choice(pair_fitted):
    from sklearn.base import clone

    from thermocomp.core.models import MLR, LagBank
    from thermocomp.core.models.auto import as_chosen

    train, template, fitted = pair_fitted
    refit = as_chosen(clone(template), fitted).fit(train)
    assert {t: type(e) for t, e in refit.estimators_.items()} == {"E_A": MLR, "E_B": LagBank}
    for t in ("E_A", "E_B"):     # the same fit as the chosen family's inside the auto model
        assert (refit.predict(train)["K01"][t] == fitted.predict(train)["K01"][t]).all()


def test_mlr_is_kept_unless_a_candidate_validates_enough_lower(two_targets, tmp_path):
    data, metrics, _ = two_targets
    b = metrics["targets"]["E_B"]["auto"]
    gain = 100 * (1 - b["candidates"]["lagbank"] / b["candidates"]["mlr"])
    assert b["chosen"] == "lagbank" and gain > 1          # the default: 1 %
    strict = _run(data, tmp_path / "strict", "model=auto", PAIR, "model.estimator.combine=best",
                  f"model.estimator.min_gain_pct={min(100.0, gain + 1):.3f}")["targets"]["E_B"]["auto"]
    assert strict["candidates"] == b["candidates"] and strict["chosen"] == "mlr"
    assert "the simpler family kept" in strict["reason"]


def test_candidate_params_reach_their_candidate(two_targets, tmp_path):
    import pickle

    data, _, _ = two_targets
    _run(data, tmp_path / "out", "model=auto", PAIR, "model.candidate_params={lagbank:{n_taus:3}}")
    comp = pickle.loads((tmp_path / "out" / "model.pkl").read_bytes())
    chosen = comp.estimators_["E_B"]
    assert chosen.family_ == "lagbank" and chosen.estimator_.n_taus == 3
    assert chosen.candidates["mlr"].get_params() == {"fit_intercept": True}


def _with_val_split(data: Path, to: Path) -> Path:
    """A copy of ``data`` whose K06 (after the train campaigns, before the test) is a val split."""
    shutil.copytree(data, to)
    manifest = pd.read_csv(to / "campaigns.csv")
    manifest.loc[5, "split"] = "val"
    manifest.to_csv(to / "campaigns.csv", index=False)
    return to


def test_with_a_val_split_auto_chooses_on_it_as_the_run_validates(two_targets, tmp_path):
    data, _, _ = two_targets
    with_val = _with_val_split(data, tmp_path / "val")
    auto = _run(with_val, tmp_path / "auto", "model=auto", PAIR, "eval.validation=true")
    for family in ("mlr", "lagbank"):
        alone = _run(with_val, tmp_path / family, f"model={family}", "eval.validation=true")
        for t, m in auto["targets"].items():
            assert m["auto"]["scheme"] == "val split"
            assert m["auto"]["candidates"][family] == pytest.approx(
                alone["targets"][t]["validation"]["rmse"], rel=1e-9)
    for m in auto["targets"].values():
        scores = {n: m["auto"]["candidates"][n] for n in ("mlr", "lagbank")}
        assert m["auto"]["chosen"] == min(scores, key=scores.get)
        assert m["validation"]["rmse"] == pytest.approx(scores[m["auto"]["chosen"]], rel=1e-9)


def test_mutual_prediction_fits_each_targets_chosen_family_with_its_chosen_penalty(pair_fitted):
    from sklearn.base import clone

    from thermocomp.core.compensator import with_chosen_hyperparameters
    from thermocomp.core.models import MLR, LagBank
    from thermocomp.core.models.auto import as_chosen

    train, template, fitted = pair_fitted
    single = clone(with_chosen_hyperparameters(as_chosen(clone(template), fitted), fitted))
    one = {c: train[c] for c in list(train)[:1]}
    models = single.fit(one).estimators_
    # no choice among candidates again: the chosen family, with the penalty it chose on all
    assert {t: type(e) for t, e in models.items()} == {"E_A": MLR, "E_B": LagBank}
    assert list(models["E_B"].alphas) == [fitted.estimators_["E_B"].estimator_.alpha_]


# --- combine=vote: a blend, each candidate weighted by the fold resamples it wins ----------------

class _OneSensor:
    """y ~ a * x[:, column] + b: each candidate sees the signal through its own noisy sensor."""

    def __init__(self, column: int = 0):
        self.column = column

    def get_params(self, deep=True):
        return {"column": self.column}

    def set_params(self, **params):
        self.column = params.get("column", self.column)
        return self

    def fit(self, X, y, context=None):
        self.coef_ = np.polyfit(X[:, self.column], y, 1)
        return self

    def predict(self, X, context=None):
        return np.polyval(self.coef_, X[:, self.column])


def _two_sensors(n_campaigns: int, seed: int):
    """``y = s`` seen by two sensors with independent noise, ``n_campaigns`` of 100 rows."""
    rng = np.random.default_rng(seed)
    s = rng.uniform(-1.0, 1.0, (n_campaigns * 100, 1))
    X = s + rng.normal(0.0, 0.3, (len(s), 2))
    context = pd.DataFrame({"campaign": np.repeat([f"K{i}" for i in range(n_campaigns)], 100)})
    return X, s[:, 0], context


def test_candidates_the_folds_cannot_tell_apart_share_the_model_and_beat_the_one_picked():
    from thermocomp.core.models.auto import AutoRegressor

    candidates = {"left": _OneSensor(0), "right": _OneSensor(1)}
    X_new, y_new, context_new = _two_sensors(4, seed=0)
    ratios = []
    for seed in range(1, 7):       # which sensor validates better is chance: votes split by it
        X, y, context = _two_sensors(20, seed=seed)
        vote = AutoRegressor(candidates, combine="vote").fit(X, y, context=context)
        best = AutoRegressor(candidates, combine="best").fit(X, y, context=context)
        assert sum(vote.weights_.values()) == pytest.approx(1)
        assert vote.report()["combine"] == "vote" and "votes" in vote.report()["reason"]
        assert best.report()["weights"] == {best.family_: 1.0}
        err = [np.sqrt(np.mean((y_new - m.predict(X_new, context=context_new)) ** 2)) for m in (vote, best)]
        ratios.append(err[0] / err[1])
    assert max(ratios) < 1.01 and np.mean(ratios) < 0.92   # the noise of two sensors averaged


def _fold_errors(a_noise, b_noise, seed=0):
    """Five folds of 200 rows: MLR's and two candidates' predictions with the given noise s.d.
    per fold (MLR: 10 in fold 0, 1 elsewhere)."""
    rng = np.random.default_rng(seed)
    fold = np.repeat(np.arange(5), 200)
    y = rng.normal(0.0, 1.0, fold.size)
    base = y + np.where(fold == 0, 10.0, 1.0) * rng.normal(0.0, 1.0, fold.size)
    preds = np.column_stack([y + np.asarray(sd)[fold] * rng.normal(0.0, 1.0, fold.size)
                             for sd in (a_noise, b_noise)])
    return preds, y, fold, base


def test_fold_votes_count_every_fold_alike_not_the_one_where_all_fail():
    from thermocomp.core.models.blend import vote_weights

    # fold 0: every family fails by ~10 (a first fold fitted on little data), A a bit less;
    # folds 1..4: B three times closer than A and MLR
    preds, y, fold, base = _fold_errors([9, 1, 1, 1, 1], [11, 1 / 3, 1 / 3, 1 / 3, 1 / 3])
    pooled = [np.mean((y - p) ** 2) for p in preds.T]
    assert pooled[0] < pooled[1]                          # the pooled error, fold 0's: A
    w = vote_weights(preds, y, fold, base)
    assert w.sum() == pytest.approx(1) and w[1] > 0.9       # B, better in four folds of five
    # alike in every fold: the votes are shared, each a real part of the blend
    w = vote_weights(*_fold_errors([9, 1, 1, 1, 1], [9, 1, 1, 1, 1]))
    assert w.min() > 0.1 and w.sum() == pytest.approx(1)


class _AsRead(_OneSensor):
    """y ~ x[:, column] as read: nothing fitted (a family whose fit no fault reaches)."""

    def fit(self, X, y, context=None):
        self.coef_ = np.array([1.0, 0.0])
        return self


def _faulty_sensor(n_campaigns: int, faulty: tuple, seed: int):
    """``y = s``: sensor 0 noisy (s.d. 0.3) everywhere, sensor 1 close (0.05) but off by 3 in the
    ``faulty`` campaigns (a condition some campaigns meet, where that family fails)."""
    rng = np.random.default_rng(seed)
    s = rng.uniform(-1.0, 1.0, n_campaigns * 100)
    campaign = np.repeat(np.arange(n_campaigns), 100)
    X = np.column_stack([s + rng.normal(0.0, 0.3, s.size),
                         s + rng.normal(0.0, 0.05, s.size) + 3.0 * np.isin(campaign, faulty)])
    return X, s, pd.DataFrame({"campaign": [f"K{c:02d}" for c in campaign]})


def test_a_candidate_keeps_votes_only_as_far_as_the_folds_are_sure_it_beats_mlr():
    from thermocomp.core.models.auto import AutoRegressor

    candidates = {"mlr": _OneSensor(0), "close": _AsRead(1)}    # "mlr": the baseline
    # five folds of two campaigns: sensor 1 beats the baseline by ~30x in three folds and fails
    # by ~50x in two; the resamples that miss both (8 %) voted for it, its mean fold ratio ~20
    X, y, context = _faulty_sensor(20, faulty=(11, 15), seed=1)
    auto = AutoRegressor(candidates, hedge="none").fit(X, y, context=context)
    assert auto.weights_ == {"mlr": 1.0}
    X_new, y_new, context_new = _faulty_sensor(10, faulty=(3, 7), seed=2)    # faults come again
    err = {n: np.sqrt(np.mean((y_new - m.predict(X_new, context=context_new)) ** 2))
           for n, m in (("auto", auto), ("close", _AsRead(1).fit(X, y)), ("mlr", _OneSensor(0).fit(X, y)))}
    assert err["auto"] == pytest.approx(err["mlr"]) and err["close"] > 3 * err["mlr"]
    # never faulty: beating MLR in every fold, it keeps every vote
    X, y, context = _faulty_sensor(20, faulty=(), seed=1)
    assert AutoRegressor(candidates, hedge="none").fit(X, y, context=context).weights_ == {"close": 1.0}


def test_a_blend_the_folds_are_not_surely_in_favour_of_falls_back_to_mlr_one_se():
    from thermocomp.core.models.auto import AutoRegressor
    from thermocomp.core.models.blend import fold_ratios

    candidates = {"mlr": _OneSensor(0), "close": _AsRead(1)}
    # one faulty campaign (fold 1 of five): the close sensor wins four folds, fails that one; the
    # resamples without it keep it a share (0.12), and the blend then loses fold 1 by 1.8x MLR's
    X, y, context = _faulty_sensor(20, faulty=(13,), seed=1)
    old = AutoRegressor(candidates, fallback="none", hedge="none").fit(X, y, context=context)
    assert old.weights_["close"] > 0.05 and "one-SE" not in old.reason_
    blend = sum(w * old.oof_[n] for n, w in old.weights_.items())
    r = fold_ratios((old.oof_y_ - blend) ** 2, (old.oof_y_ - old.oof_["mlr"]) ** 2, old.oof_fold_)
    assert r.size == 5 and min(r) < 0.8 < 1.5 < max(r)             # wins some folds, loses one
    assert r.mean() + r.std(ddof=1) / np.sqrt(r.size) >= 1.0
    auto = AutoRegressor(candidates, hedge="none").fit(X, y, context=context)    # fallback='one_se'
    assert auto.weights_ == {"mlr": 1.0} and auto.family_ == auto.chosen_ == "mlr"
    assert "one-SE rule" in auto.reason_ and "MLR kept" in auto.report()["reason"]
    X_new, y_new, context_new = _faulty_sensor(10, faulty=(3, 7), seed=2)    # faults come again
    err = {n: np.sqrt(np.mean((y_new - m.predict(X_new, context=context_new)) ** 2))
           for n, m in (("old", old), ("auto", auto))}
    assert err["auto"] < err["old"]


def test_a_candidate_better_in_every_fold_keeps_its_blend_and_fallback_none_keeps_the_votes():
    from thermocomp.core.models.auto import AutoRegressor
    from thermocomp.core.models.blend import vote_weights

    candidates = {"mlr": _OneSensor(0), "close": _AsRead(1)}
    X, y, context = _faulty_sensor(20, faulty=(), seed=1)           # ~0.03 x MLR in every fold
    auto = AutoRegressor(candidates, hedge="none").fit(X, y, context=context)
    assert auto.weights_ == {"close": 1.0} and "one-SE" not in auto.reason_
    # fallback='none': the votes' weights as they are, the same as a model pickled before the key
    X, y, context = _faulty_sensor(20, faulty=(13,), seed=1)
    old = AutoRegressor(candidates, fallback="none", hedge="none").fit(X, y, context=context)
    w = vote_weights(np.column_stack([old.oof_["mlr"], old.oof_["close"]]), old.oof_y_, old.oof_fold_,
                     old.oof_["mlr"], base_column=0, min_folds=5)
    assert old.weights_ == {n: float(v) for n, v in zip(("mlr", "close"), w) if v > 0}
    pickled = AutoRegressor(candidates)
    del pickled.__dict__["fallback"], pickled.__dict__["hedge"]     # unpickled from before the keys
    assert pickled.fit(X, y, context=context).weights_ == old.weights_


def _one_fold(noise_sd: float, seed: int, n: int = 600):
    """One validation fold of ``n`` rows: MLR's and a candidate's predictions, each off by its
    own slowly drifting error (AR(1), 0.95: it takes ~30 rows to decorrelate), the candidate's
    scaled to ``noise_sd`` of MLR's."""
    from scipy.signal import lfilter

    rng = np.random.default_rng(seed)
    y = rng.normal(0.0, 1.0, n)
    drift = [lfilter([1.0], [1.0, -0.95], rng.normal(0.0, 1.0, n)) for _ in range(2)]
    return y + noise_sd * drift[1], y, np.zeros(n, int), y + drift[0]


def test_one_fold_does_not_hand_the_model_to_a_candidate_whose_win_is_that_folds_accident():
    from thermocomp.core.models.blend import vote_weights

    # a candidate as good as MLR, ahead by 0.001 % in the one fold (a lab with 3 train runs: one
    # forward fold; measured: such a win gave lstm the model); every resample of the fold as the
    # unit is that fold, so it took every vote
    kept = []
    for seed in range(6):
        cand, y, fold, base = _one_fold(1.0, seed)
        tiny_win = np.sqrt(0.99999 * np.mean((y - base) ** 2) / np.mean((y - cand) ** 2))
        cand = y + tiny_win * (cand - y)
        kept.append(vote_weights(np.column_stack([base, cand]), y, fold, base, base_column=0)[0])
    assert min(kept) > 0.5                              # the doubt goes to MLR
    # two folds (a vendor's 4 train runs), ahead by a hair in both: fewer folds than asked
    # (min_folds) are resampled by their blocks too
    two = [_one_fold(1.0, seed, n=300) for seed in (0, 1)]
    y, base = np.concatenate([t[1] for t in two]), np.concatenate([t[3] for t in two])
    cand = np.concatenate([t[1] + (t[0] - t[1]) * np.sqrt(
        0.99999 * np.mean((t[1] - t[3]) ** 2) / np.mean((t[1] - t[0]) ** 2)) for t in two])
    fold = np.repeat([0, 1], 300)
    assert vote_weights(np.column_stack([base, cand]), y, fold, base, base_column=0, min_folds=5)[0] > 0.5
    # better in every stretch of the fold (error half MLR's): the blocks agree, it keeps its votes
    cand, y, fold, base = _one_fold(0.5, seed=0)
    w = vote_weights(np.column_stack([base, cand]), y, fold, base, base_column=0)
    assert w[1] == 1.0
    # so with a white error (one-row blocks), where a mean of per-block ratios gave it nothing
    rng = np.random.default_rng(0)
    y, fold = rng.normal(0.0, 1.0, 600), np.zeros(600, int)
    base, cand = y + rng.normal(0.0, 1.0, 600), y + rng.normal(0.0, 0.5, 600)
    w = vote_weights(np.column_stack([base, cand]), y, fold, base, base_column=0)
    assert w[1] == 1.0


def test_auto_with_three_train_campaigns_keeps_mlr_against_a_twin_that_won_its_one_fold():
    from thermocomp.core.models.auto import AutoRegressor

    candidates = {"mlr": _OneSensor(0), "twin": _OneSensor(1)}     # sensors equally noisy
    weights = []
    for seed in range(1, 9):
        X, y, context = _two_sensors(3, seed=seed)      # blocked forward: one validation fold
        auto = AutoRegressor(candidates).fit(X, y, context=context)
        if auto.validation_["twin"] < auto.validation_["mlr"]:
            weights.append(auto.weights_.get("mlr", 0.0))
    # the fold as the unit gave the twin every one of these (mlr 0); now MLR keeps a share
    # each time, the larger the closer the win (measured mean 0.46)
    assert len(weights) >= 3 and min(weights) > 0 and np.mean(weights) > 0.4


THREE = "model.candidates=[mlr,arx,lagbank]"      # E_B: arx and lagbank validate alike


@pytest.fixture(scope="module")
def blend_run(two_targets, tmp_path_factory):
    """``run model=auto`` of :data:`THREE`, validated (the model it fits is the same either way):
    its folder and metrics, for the replay and the validation of a blend."""
    out = tmp_path_factory.mktemp("blend") / "auto"
    return out, _run(two_targets[0], out, "model=auto", THREE, UNHEDGED, "eval.validation=true")


def test_a_blend_streams_in_replay_as_it_predicts_in_run(two_targets, blend_run, tmp_path):
    data, _, _ = two_targets
    common = [f"data.path={data}", "track=false", "model=auto", THREE, UNHEDGED]
    out, run = blend_run
    blend = run["targets"]["E_B"]["auto"]
    assert blend["combine"] == "vote" and len(blend["weights"]) == 2
    assert sum(blend["weights"].values()) == pytest.approx(1, abs=1e-3)
    assert blend["chosen"] == max(blend["weights"], key=blend["weights"].get)
    assert main(["replay", *common, f"replay.model={out / 'model.pkl'}",
                 f"out={tmp_path / 'replay'}"]) == 0
    replay = json.loads((tmp_path / "replay" / "replay.json").read_text())
    for t in ("E_A", "E_B"):
        assert replay["targets"][t]["max_abs_stream_minus_batch"] < 1e-6
        assert replay["targets"][t]["rmse"] == pytest.approx(run["targets"][t]["test"]["rmse"], rel=1e-6)


def test_the_run_validates_a_blend_as_blended_with_its_weights(blend_run):
    metrics = blend_run[1]
    b = metrics["targets"]["E_B"]
    assert len(b["auto"]["weights"]) == 2
    # the blend refitted per fold with its weights: between its members' own validations or below
    members = [b["auto"]["candidates"][n] for n in b["auto"]["weights"]]
    assert b["validation"]["rmse"] <= max(members) * (1 + 1e-9)


def test_mutual_prediction_fits_a_blend_as_blended_with_its_members_penalties(two_targets):
    from sklearn.base import clone

    from thermocomp.core.compensator import Compensator, with_chosen_hyperparameters
    from thermocomp.core.io import read_dataset
    from thermocomp.core.models import ARX, MLR, LagBank
    from thermocomp.core.models.auto import AutoRegressor, as_chosen
    from thermocomp.core.models.blend import Blend

    ds, _ = read_dataset(two_targets[0])
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    template = Compensator(AutoRegressor({"mlr": MLR(), "arx": ARX(), "lagbank": LagBank()}))
    fitted = clone(template).fit(train)
    weights = fitted.estimators_["E_B"].weights_
    assert "lagbank" in weights and len(weights) > 1
    single = clone(with_chosen_hyperparameters(as_chosen(clone(template), fitted), fitted))
    blend = single.fit({c: train[c] for c in list(train)[:1]}).estimators_["E_B"]
    assert isinstance(blend, Blend) and blend.weights == weights    # no vote again: its weights
    assert list(blend.estimators_["lagbank"].alphas) == [fitted.estimators_["E_B"].estimator_
                                                         .estimators_["lagbank"].alpha_]


# --- cost: nothing refitted that the choice already fitted, nothing kept that has no weight ------

class _Counted(_OneSensor):
    """A :class:`_OneSensor` counting its fits (per column) in ``fits``."""

    fits: list = []

    def fit(self, X, y, context=None):
        type(self).fits.append(self.column)
        return super().fit(X, y, context)


def test_zero_weight_members_are_neither_refitted_nor_kept():
    import pickle

    from thermocomp.core.models.auto import AutoRegressor

    X, y, context = _two_sensors(20, seed=3)
    X = np.column_stack([X, np.random.default_rng(9).normal(0.0, 1.0, len(y))])   # 2: noise only
    _Counted.fits = []
    auto = AutoRegressor({"left": _Counted(0), "right": _Counted(1), "noise": _Counted(2)}).fit(
        X, y, context=context)
    folds = len(auto.oof_folds_[1])
    assert "noise" not in auto.weights_ and set(auto.estimator_.estimators_) == set(auto.weights_)
    assert _Counted.fits.count(2) == folds                  # validated, never refitted on all rows
    assert all(_Counted.fits.count(c) == folds + 1 for c in (0, 1) if ("left", "right")[c] in auto.weights_)
    # the pickled model: no out-of-fold predictions unless asked, the same predictions
    small = pickle.loads(pickle.dumps(auto))
    assert not [k for k in vars(small) if k.startswith("oof_")] and small.out_of_fold() is None
    assert np.array_equal(small.predict(X, context=context), auto.predict(X, context=context))
    kept = pickle.loads(pickle.dumps(auto.set_params(keep_oof=True)))
    assert np.array_equal(kept.oof_["noise"], auto.oof_["noise"])


def test_the_run_validation_scores_the_choice_without_refitting_it(two_targets, monkeypatch):
    from functools import partial

    from sklearn.base import clone

    from thermocomp.core.compensator import Compensator
    from thermocomp.core.io import read_dataset
    from thermocomp.core.models import ARX, MLR, LagBank
    from thermocomp.core.models.auto import AutoRegressor
    from thermocomp.core.scoring.evaluation import validation_reports

    ds, _ = read_dataset(two_targets[0])
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    template = Compensator(AutoRegressor({"mlr": MLR(), "arx": ARX(), "lagbank": LagBank()}))
    fitted = clone(template).fit(train)
    assert len(fitted.estimators_["E_B"].weights_) > 1          # a blend among them
    fits = []
    original = LagBank.fit
    monkeypatch.setattr(LagBank, "fit", lambda self, *a, **k: fits.append(1) or original(self, *a, **k))
    from thermocomp.core.models.auto import as_chosen

    chosen = partial(clone, as_chosen(clone(template), fitted))
    stored = validation_reports(chosen, ds, fitted=fitted)["simulation"]
    assert fits == []                                         # nothing refitted
    refit = validation_reports(chosen, ds)["simulation"]      # no fitted model: the folds refitted
    assert fits
    for t, entry in refit.items():
        assert "out-of-fold" in stored[t]["method"] and "out-of-fold" not in entry["method"]
        assert stored[t]["rmse"] == pytest.approx(entry["rmse"], rel=1e-9)
        assert stored[t]["per_unit"] == pytest.approx(entry["per_unit"], rel=1e-9)


def test_candidate_defaults_set_a_family_in_the_candidate_role_under_candidate_params():
    from hydra import compose, initialize_config_dir

    from thermocomp.base.paths import conf_dir
    from thermocomp.shell.config.candidates import build_candidates

    def built(*overrides):
        with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
            return build_candidates(compose(config_name="config", overrides=["model=auto", *overrides]))

    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        alone = compose(config_name="config", overrides=["model=lstm"]).model.estimator.max_epochs
    assert built()["lstm"].max_epochs == 30 != alone          # the family's own default: 100
    assert built("model.candidate_params={lstm:{max_epochs:7}}")["lstm"].max_epochs == 7
    assert built("model.candidates=[mlr,ati+lstm]")["ati+lstm"].base_estimator.max_epochs == 30
    assert set(built("model.candidates=[mlr,lagbank]")) == {"mlr", "lagbank"}    # no lstm: ignored
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):   # as the cli adds keys
        from thermocomp.shell.cli import lenient

        both = compose(config_name="config", overrides=["model=auto", *lenient(
            ["model.candidate_defaults={lagbank:{n_taus:3}}"])])
    assert both.model.candidate_defaults == {"lstm": {"max_epochs": 30}, "lagbank": {"n_taus": 3}}


def test_the_ati_baselines_fit_the_chosen_family_not_the_whole_choice(two_targets, tmp_path,
                                                                      monkeypatch):
    # before: the coldest and the warmest campaign each ran every candidate's validation again
    # (a lab's 4 runs with lstm among the candidates: 93 s of a 125 s run)
    from thermocomp.core.models.auto import AutoRegressor

    data = tmp_path / "data"
    shutil.copytree(two_targets[0], data)
    manifest = pd.read_csv(data / "campaigns.csv")       # the climate room's set point per run
    manifest.assign(ambient_c=20 + 0.3 * np.arange(len(manifest))).to_csv(
        data / "campaigns.csv", index=False)
    fits = []
    original = AutoRegressor.fit
    monkeypatch.setattr(AutoRegressor, "fit",
                        lambda self, *a, **k: fits.append(1) or original(self, *a, **k))
    plain = _run(data, tmp_path / "plain", "model=auto", PAIR)
    n_plain = len(fits)
    metrics = _run(data, tmp_path / "ati", "model=auto", PAIR, "eval.ati_baselines=true")
    assert len(fits) - n_plain == n_plain                 # the run's own choice, once
    assert metrics["ati"]["baseline_campaigns"]["coldest"]["campaign"] == "K01"
    for t, m in metrics["targets"].items():              # the choice as without the report
        assert m["auto"]["chosen"] == plain["targets"][t]["auto"]["chosen"]
        assert np.isfinite(metrics["ati"]["targets"][t]["test"]["coldest"]["rsd_mean"])
