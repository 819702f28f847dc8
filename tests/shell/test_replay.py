"""Any configuration `run` accepts can be deployed: `replay` streams it row by row as it predicts."""

from __future__ import annotations

import json
import pickle
from functools import lru_cache
from itertools import combinations, product

import pytest
from hydra import compose, initialize_config_dir

from conftest import cli
from covering import covering_of
from thermocomp.apps.deploy import StreamingCompensator
from thermocomp.apps.deploy.report import replay_report
from thermocomp.apps.diagnose.augmented import AugmentedRegressor
from thermocomp.base.paths import conf_dir
from thermocomp.core import io
from thermocomp.core.compensator import Compensator
from thermocomp.core.models.ati import ATIRegressor
from thermocomp.core.models.pcr import PCR
from thermocomp.shell.builders import build_compensator
from thermocomp.shell.model_store import model_family

MODELS = ("mlr", "pcr", "arx", "arx_rf", "lstm", "lagbank", "hammerstein")
ATIS = ("none", "cmeans")
DENOISERS = ("none", "emd")
SELECTORS = ("all", "pearson", "greedy_residual", "cluster_grey")
AXES = (MODELS, ATIS, DENOISERS, SELECTORS)
# An all-pairs (pairwise) covering design instead of the 112-case product: each model streams
# once with each selector and once with each (ati, denoise) combination, the combinations
# turning with the selector, so every pair of values of any two axes is met (28 cases, the
# fewest that give every model its 4 selectors; checked below).
WRAPPERS = [(ati, denoise) for ati in ATIS for denoise in DENOISERS]
CASES = [(model, *WRAPPERS[(m + s) % len(WRAPPERS)], select)
         for m, model in enumerate(MODELS) for s, select in enumerate(SELECTORS)]
# `make test` streams their covering set (tests/covering.py), the (ati, denoise) wrapper one axis:
# every model, every selector and every wrapper (checked below), arx_rf among them with ATI (the
# case named below); the rest is `full`.
PARAMS = covering_of("a pairwise case past the covering set",
                     {(m, f"{a}-{d}", s): (m, a, d, s) for m, a, d, s in CASES})
SMALL = {  # keep every fit small: the point is the plumbing, not the accuracy
    "lstm": ["model.estimator.max_epochs=2", "model.estimator.hidden_size=4", "model.estimator.chunk=16"],
    "arx_rf": ["model.estimator.forest.n_estimators=5"],
}
# The elbow refits the model ~30 times (leave one campaign out, per candidate count): 3-8 s a
# case for the costly families (a cross-validated lag bank, a forest, a network); it streams with
# mlr, pcr and arx (choosing 1, 2 and 3 intervals here), the others with a fixed number of
# intervals, more than one, so their stream switches intervals on the ambient (the elbow chose
# one for both arx_rf cases: that path went unstreamed).
FIXED_INTERVALS = ["ati.estimator.n_intervals=2"]
SMALL_ATI = {(model, "cmeans"): FIXED_INTERVALS for model in ("arx_rf", "lstm", "lagbank",
                                                               "hammerstein")}
TOLERANCE_UM = 1e-6


@pytest.fixture(scope="session")
def door_data(short_door_dataset):
    """9 short year-round campaigns (6 train, 3 test) with an undeclared door signal S_door
    (the conftest catalogue)."""
    return short_door_dataset


@lru_cache(maxsize=2)
def _dataset(path: str):
    ds, _ = io.read_dataset(path)
    return ds


def _compose(*overrides):
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        return compose(config_name="config", overrides=list(overrides))


def _pairs(case) -> set:
    return {(i, case[i], j, case[j]) for i, j in combinations(range(len(case)), 2)}


def test_the_cases_cover_every_pair_of_values():
    every = set().union(*(_pairs(case) for case in product(*AXES)))
    assert set().union(*(_pairs(case) for case in CASES)) == every
    assert len(set(CASES)) == len(CASES)
    kept = [p.values for p in PARAMS if not p.marks]
    assert all({case[i] for case in kept} == set(axis) for i, axis in enumerate(AXES))
    assert {(a, d) for _, a, d, _ in kept} == set(WRAPPERS)
    assert ("arx_rf", "cmeans") in {(m, a) for m, a, _, _ in kept}


@pytest.mark.parametrize("model, ati, denoise, select", PARAMS)
def test_every_configuration_streams_exactly_as_it_predicts(door_data, model, ati, denoise, select):
    cfg = _compose(f"model={model}", f"ati={ati}", f"denoise={denoise}", f"select={select}",
                   *SMALL.get(model, []), *SMALL_ATI.get((model, ati), []))
    ds = _dataset(str(door_data))
    comp = build_compensator(cfg).fit({c: ds.campaigns[c] for c in ds.ids("train")})
    streaming = StreamingCompensator.from_training(comp, {c: ds.campaigns[c] for c in ds.ids("train")})
    if model == "arx_rf":   # the door reaches the forest through the context, in every wrapper
        assert "S_door" in streaming.columns_ and streaming.time_required_
    if (model, ati) in SMALL_ATI:
        assert all(e.n_intervals_ == 2 for e in comp.estimators_.values())
    if ati == "cmeans" and any(e.n_intervals_ > 1 for e in comp.estimators_.values()):
        assert "T_amb" in streaming.columns_
    result = replay_report(streaming, {c: ds.campaigns[c] for c in ds.ids("test")})
    assert not result["adaptive"] and result["events"] == [] and result["excluded_inputs"] == []
    for target, r in result["targets"].items():
        assert r["n_samples"] == sum(len(ds.campaigns[c]) for c in ds.ids("test"))
        assert r["max_abs_stream_minus_batch"] <= TOLERANCE_UM, (target, r)
        assert r["rmse"] == pytest.approx(r["rmse_batch"], abs=TOLERANCE_UM)   # envelope never hit here
    # the deployed object survives pickling (what promote registers) and streams the same
    again = pickle.loads(pickle.dumps(streaming))
    assert (replay_report(again, {c: ds.campaigns[c] for c in ds.ids("test")[:1]})["targets"].keys()
            == result["targets"].keys())


@pytest.mark.slow
def test_replay_command_fits_or_loads_and_writes_replay_json(door_data, tmp_path):
    common = [f"data.path={door_data}", "track=false"]
    cli("replay", *common, f"out={tmp_path / 'fit'}", "model=arx_rf", "ati=cmeans",
        "ati.estimator.n_intervals=2", "model.estimator.forest.n_estimators=5")
    report = json.loads((tmp_path / "fit" / "replay.json").read_text())
    assert report["source"] == "fitted" and report["model"] == "arx_rf"
    assert set(report) >= {"model", "source", "targets", "excluded_inputs", "events"}
    for r in report["targets"].values():
        assert set(r) >= {"n_samples", "max_abs_stream_minus_batch", "rmse", "us_per_sample"}
        assert r["max_abs_stream_minus_batch"] <= TOLERANCE_UM and r["us_per_sample"] > 0
    # a model written by `run` is loaded, not refitted: same streamed figures
    cli("run", *common, f"out={tmp_path / 'run'}", "model=arx", "eval.mutual_prediction=false",
        "eval.ati_baselines=false", "plots=none")
    cli("replay", *common, f"out={tmp_path / 'load'}",
        f"replay.model={tmp_path / 'run' / 'model.pkl'}")
    cli("replay", *common, f"out={tmp_path / 'refit'}", "model=arx")
    loaded = json.loads((tmp_path / "load" / "replay.json").read_text())
    refit = json.loads((tmp_path / "refit" / "replay.json").read_text())
    assert loaded["source"].endswith("model.pkl")
    assert loaded["model"] == refit["model"] == "arx"        # named alike, fitted or loaded
    for t, r in loaded["targets"].items():
        assert r["rmse"] == pytest.approx(refit["targets"][t]["rmse"], rel=1e-12)
    bad = cli("replay", *common, f"out={tmp_path / 'bad'}",
              f"replay.model={tmp_path / 'nothing.pkl'}", check=False)
    assert bad.returncode == 2 and not (tmp_path / "bad" / "replay.json").exists()


@pytest.mark.slow
def test_diagnosed_ati_model_replays(door_data, tmp_path):
    """The model diagnose builds around an ATI model (augmented ∘ ATI) starts a stream and streams
    exactly as it predicts."""
    out = tmp_path / "diag"
    # two ambient intervals, fixed: the elbow search refits the ATI model ~30 times in each of
    # diagnose's ~600 CV fits (62 s of CPU), and the point is the composed model, not its choice;
    # a short search too (2 shortlisted, 3 folds: 7.5 -> 4.5 s of CPU), which writes the same
    # model config as the default one on this dataset
    cli("diagnose", f"data.path={door_data}", f"out={out}", "track=false", "plots=none",
        "ati=cmeans", "ati.estimator.n_intervals=2", "diagnose.max_effects=2",
        "diagnose.shortlist=2", "diagnose.n_folds=3")
    cli("replay", f"hydra.searchpath=[file://{out / 'diagnosis' / 'conf'}]",
        "experiment=diagnosed", f"data.path={door_data}", f"out={tmp_path / 'replay'}",
        "track=false")
    report = json.loads((tmp_path / "replay" / "replay.json").read_text())
    assert report["model"].endswith("diagnosed") and report["source"] == "fitted"
    for r in report["targets"].values():
        assert r["max_abs_stream_minus_batch"] <= TOLERANCE_UM


def test_a_loaded_model_is_named_by_its_family_as_a_fitted_one():
    assert model_family(Compensator(PCR())) == "pcr"
    assert model_family(Compensator(ATIRegressor(PCR()))) == "pcr"
    assert model_family(Compensator(AugmentedRegressor(ATIRegressor(PCR())))) == "pcr+diagnosed"


def test_a_test_campaign_without_a_target_streams_and_is_scored_where_measured(door_data, tmp_path):
    """A stream carries no error column on the machine: replay and monitor score a target on
    the campaigns that recorded it (before: exit 2, 'column E_Z: 1 of 3 campaigns lack it')."""
    import shutil

    import pandas as pd

    index = pd.read_csv(door_data / "campaigns.csv")
    first, *others = index[index["split"] == "test"]["campaign"]
    lacking, without = tmp_path / "lacking", tmp_path / "without"
    shutil.copytree(door_data, lacking)
    shutil.copytree(door_data, without)
    df = pd.read_csv(lacking / f"{first}.csv")
    df.drop(columns=["E_Z"]).to_csv(lacking / f"{first}.csv", index=False)
    index[index["campaign"] != first].to_csv(without / "campaigns.csv", index=False)
    reports = {}
    for stage, name in (("replay", "replay.json"), ("monitor", "monitor.json")):
        for label, path in (("full", door_data), ("lacking", lacking), ("without", without)):
            out = tmp_path / f"{stage}_{label}"
            cli(stage, f"data.path={path}", f"out={out}", "track=false", "plots=none")
            reports[stage, label] = json.loads((out / name).read_text())["targets"]
    key = {"replay": "rmse", "monitor": "rmse_fixed"}
    for stage in ("replay", "monitor"):
        got = reports[stage, "lacking"]
        # E_Z is scored on the other test campaigns only, E_X on all of them
        assert got["E_Z"][key[stage]] == pytest.approx(reports[stage, "without"]["E_Z"][key[stage]],
                                                       rel=1e-9)
        assert got["E_X"][key[stage]] == pytest.approx(reports[stage, "full"]["E_X"][key[stage]],
                                                       rel=1e-9)
        assert got["E_Z"][key[stage]] != pytest.approx(reports[stage, "full"]["E_Z"][key[stage]],
                                                       rel=1e-6)
