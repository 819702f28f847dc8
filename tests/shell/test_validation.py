"""The validation score that compare ranks and promote gates on: it never sees the test split.

Unit level (fast): :func:`thermocomp.core.scoring.evaluation.validation_report` on the small
contract dataset of ``test_deploy`` -- leave-campaigns-out, the ``val`` split,
forward chaining on one record -- and its blindness to poisoned test targets.
CLI level (one slow test): a sweep, ``compare`` and ``promote`` on a clean
dataset and on a copy whose test targets are garbage choose the same model,
take the same promotion decisions and fit the same ARX/LagBank.
"""

from __future__ import annotations

import json
import pickle
import shutil
from functools import partial

import numpy as np
import pandas as pd
import pytest
from sklearn.base import clone

from conftest import thermocomp
from test_deploy import LIGHT_EVAL, campaigns, mlflow_store, write_small_dataset
from thermocomp.core import io
from thermocomp.core.compensator import Compensator
from thermocomp.core.io.contract import Dataset
from thermocomp.core.metrics import rmse
from thermocomp.core.models import MLR
from thermocomp.core.models.arx import ARX
from thermocomp.core.scoring.evaluation import score, validation_report
from thermocomp.shell.cli import main

MAKE = partial(clone, Compensator(MLR(), inputs=["T_*"]))


def _dataset(splits, seed=0, **kw) -> Dataset:
    camps = campaigns(seed, len(splits), **kw)
    manifest = pd.DataFrame({"split": splits}, index=pd.Index(list(camps), name="campaign"))
    return Dataset(manifest, camps, name="small")


def _poisoned(ds: Dataset, split: str = "test", seed: int = 1) -> Dataset:
    """A copy whose ``split`` campaigns have garbage targets (noise of 1 mm)."""
    rng = np.random.default_rng(seed)
    camps = {c: df.copy() for c, df in ds.campaigns.items()}
    for c in ds.ids(split):
        for t in [col for col in camps[c] if col.startswith("E_")]:
            camps[c][t] = rng.normal(0.0, 1000.0, len(camps[c]))
    return Dataset(ds.manifest, camps, name=ds.name)


def test_leave_campaigns_out_refits_per_fold_and_ignores_the_test_split():
    ds = _dataset(["train"] * 5 + ["test"] * 2)
    val = validation_report(MAKE, ds, n_folds=3, scheme="interleaved")
    assert set(val) == {"E_X", "E_Z"}
    assert val["E_Z"]["method"] == "leave-campaigns-out (3 folds)"
    assert set(val["E_Z"]["per_unit"]) == set(ds.ids("train"))   # every train campaign held out once

    # The same numbers by hand: campaign i in fold i mod 3, a new compensator fitted per fold.
    train = ds.ids("train")
    res = []
    for k in range(3):
        held = [c for i, c in enumerate(train) if i % 3 == k]
        comp = MAKE().fit({c: ds.campaigns[c] for c in train if c not in held})
        part = {c: ds.campaigns[c] for c in held}
        pred, meas = comp.predict(part), comp.measured(part)
        res += [meas[c]["E_Z"].to_numpy() - pred[c]["E_Z"].to_numpy() for c in held]
    assert val["E_Z"]["rmse"] == pytest.approx(rmse(np.concatenate(res)), rel=1e-9)

    poisoned = _poisoned(ds)
    assert validation_report(MAKE, poisoned, n_folds=3, scheme="interleaved") == val
    full = MAKE().fit({c: ds.campaigns[c] for c in train})
    # the poison is real: the test figures it gives are garbage
    assert score(full, poisoned)[0]["E_Z"]["test"]["rmse"] > 100 * score(full, ds)[0]["E_Z"]["test"]["rmse"]


def test_val_split_scores_the_train_fit_on_val_campaigns():
    ds = _dataset(["train"] * 4 + ["val"] + ["test"] * 2)
    comp = MAKE().fit({c: ds.campaigns[c] for c in ds.ids("train")})
    val = validation_report(MAKE, ds, fitted=comp)
    assert val["E_X"]["method"] == "val split" and list(val["E_X"]["per_unit"]) == ["K04"]
    part = {"K04": ds.campaigns["K04"]}
    r = comp.measured(part)["K04"]["E_X"] - comp.predict(part)["K04"]["E_X"]
    assert val["E_X"]["rmse"] == pytest.approx(rmse(r), rel=1e-12)
    assert val["E_X"]["rsd_sd"] is None                          # one val campaign
    assert validation_report(MAKE, ds) == val                    # refitted when not given
    assert validation_report(MAKE, _poisoned(ds)) == val


def test_forward_chaining_on_one_record_never_looks_ahead():
    ds = _dataset(["train", "test"], n=400)
    make = partial(clone, Compensator(ARX(max_inputs=3), inputs=["T_*"]))
    val = validation_report(make, ds, n_folds=4)
    entry = val["E_Z"]
    assert entry["method"] == "forward chaining" and entry["n_folds"] == 4
    assert entry["gap_samples"] >= 1
    units = list(entry["per_unit"])
    assert units == [f"K00#{k}" for k in range(1, 5)]
    # Garbage in the last validation block changes that block's score only: the earlier folds
    # were fitted and scored on rows before it.
    camps = {c: df.copy() for c, df in ds.campaigns.items()}
    block = 400 - 200 // 4                                       # the last of 4 blocks of the 2nd half
    camps["K00"].loc[block:, "E_Z"] += np.random.default_rng(0).normal(0, 50.0, 400 - block)
    late = validation_report(make, Dataset(ds.manifest, camps, name="small"), n_folds=4)["E_Z"]
    for u in units[:-1]:
        assert late["per_unit"][u] == pytest.approx(entry["per_unit"][u], rel=1e-12)
    assert late["per_unit"][units[-1]] > 10 * entry["per_unit"][units[-1]]


def test_forward_chaining_ignores_groups_without_a_warning():
    import warnings

    from thermocomp.core.model_selection import ForwardChaining

    X, groups = np.zeros((60, 1)), np.repeat(["a", "b"], 30)
    for splitter in (ForwardChaining(3), ForwardChaining(3, gap=2, min_train_fraction=0.5)):
        with warnings.catch_warnings():
            warnings.simplefilter("error")        # scikit-learn warns when handed groups
            grouped = list(splitter.split(X, groups=groups))
        plain = list(splitter.split(X))
        assert len(grouped) == 3 and all(np.array_equal(a[i], b[i]) for a, b in zip(grouped, plain)
                                         for i in (0, 1))


def test_shared_forward_chaining_validates_the_second_half_like_lagbank():
    from thermocomp.core.model_selection import ForwardChaining
    from thermocomp.core.models import lagbank
    from thermocomp.core.scoring.evaluation import _forward_folds

    X = np.zeros((101, 1))
    shared = list(ForwardChaining(4, gap=3, min_train_fraction=0.5).split(X))
    assert len(shared) == 4
    held = np.concatenate([te for _, te in shared])
    assert held[-1] == 100 and np.all(np.diff(held) == 1) and held[0] >= 50   # the second half
    for tr, te in shared:
        assert tr[-1] + 3 < te[0] and tr[0] == 0 and len(tr) >= 50 - 3       # gap, expanding
    # the validation report's folds of one record hold out the blocks LagBank's own CV holds
    # out (its splitter on one campaign, at the report's gap), and fit on the rows before them
    folds = _forward_folds({"K00": pd.DataFrame(X)}, 4)
    gap = folds[0][3]
    theirs = list(lagbank.default_splitter(None, 101, gap, n_splits=4).split(X))
    assert len(folds) == len(theirs) == 4
    for (fit, _, parts, _), (tr, te) in zip(folds, theirs):
        (_, a, b), = parts.values()
        assert (a, b) == (te[0], te[-1] + 1) and fit["K00"] == tr[-1] + 1
    assert folds[0][2]["K00#1"][1] >= 50                                    # the second half


# -- the acceptance's poisoning test, through the CLI ----------------------------------------
def _poison_folder(src, dst, seed=1):
    shutil.copytree(src, dst)
    manifest = pd.read_csv(dst / "campaigns.csv")
    rng = np.random.default_rng(seed)
    for c in manifest.loc[manifest["split"] == "test", "campaign"]:
        f = dst / f"{c}.csv"
        df = pd.read_csv(f)
        for t in [col for col in df if col.startswith("E_")]:
            df[t] = rng.normal(0.0, 1000.0, len(df))
        df.to_csv(f, index=False)
    return dst


def _promote(common, run_id, model_name, out) -> dict:
    assert main(["promote", *common, f"promote.run_id={run_id}",
                 f"promote.model_name={model_name}", f"out={out}"]) == 0
    return json.loads((out / "promote.json").read_text())


@pytest.mark.slow
def test_poisoned_test_split_changes_no_choice(tmp_path):
    """One sweep over both datasets and three models; each dataset its own registered model."""
    clean = write_small_dataset(tmp_path / "clean")
    poisoned = _poison_folder(clean, tmp_path / "poisoned")
    assert io.read_dataset(poisoned)[0].ids("test") == ["K04", "K05"]
    uri, sweep = mlflow_store(tmp_path), tmp_path / "sweep"
    thermocomp("run", "-m", f"data.path={clean},{poisoned}", "model=mlr,arx,lagbank",
               f"tracking_uri={uri}", *LIGHT_EVAL, f"hydra.sweep.dir={sweep}")
    table = pd.read_csv(sweep / "compare.csv")
    per = {name: table[table["settings"].str.contains(f"/{name}", regex=False)].reset_index(drop=True)
           for name in ("clean", "poisoned")}
    t_clean, t_pois = per["clean"], per["poisoned"]
    assert len(t_clean) == len(t_pois) == 3

    # compare: the same ranking by the same validation figures; the test columns are garbage
    assert list(t_clean["model"]) == list(t_pois["model"])
    np.testing.assert_allclose(t_clean["val_rmse"], t_pois["val_rmse"], rtol=1e-9)
    assert t_clean["val_rmse"].is_monotonic_increasing
    assert (t_pois["rmse"] > 100 * t_clean["rmse"]).all()

    # promote the best, then the worst: the same decisions on the same validation scores
    decisions = {}
    for name, t in per.items():
        common = [f"data.path={tmp_path / name}", f"tracking_uri={uri}", *LIGHT_EVAL]
        decisions[name] = [_promote(common, t["run_id"].iloc[k], f"m-{name}", tmp_path / f"{name}{k}")
                           for k in (0, -1)]
    assert [r["moved"] for r in decisions["clean"]] == [r["moved"] for r in decisions["poisoned"]] \
        == [True, False]
    for c, p in zip(decisions["clean"], decisions["poisoned"]):
        assert c["candidate"]["score"] == pytest.approx(p["candidate"]["score"], rel=1e-9)
        assert p["candidate"]["test_reported"]["rmse"] > 100 * c["candidate"]["test_reported"]["rmse"]

    # fit never sees the test split: the same ARX selection, the same LagBank penalty
    models = {}
    for job in (p for p in sweep.iterdir() if p.is_dir()):
        metrics = json.loads((job / "metrics.json").read_text())
        with open(job / "model.pkl", "rb") as f:
            models[metrics["model"], metrics["dataset"]] = pickle.load(f)
    for t in ("E_X", "E_Z"):
        assert (models["arx", "clean"].estimators_[t].chosen_
                == models["arx", "poisoned"].estimators_[t].chosen_)
        assert (models["lagbank", "clean"].estimators_[t].alpha_
                == models["lagbank", "poisoned"].estimators_[t].alpha_)
