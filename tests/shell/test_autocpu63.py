"""``model=auto`` on train files that continue one another: the run's validation reuses auto's
own folds for a target measured now and then (autocpu63).

Joined (lagbank62), the probe grinder's two train weeks are one record: auto validates every
candidate on its forward folds, and the run's validation folds are those very folds.  It scored
the kept blend from the members' stored out-of-fold predictions only where their scored rows were
the folds' rows, which a target measured now and then never met (auto scores its measured rows):
every fold was refitted, the lstm among them: 15 more lstm fits, some 27 s of the grinder's
126 s of CPU (``benchmarks/bench_autocpu63.py``).
"""

from __future__ import annotations

from functools import partial

import numpy as np
import pandas as pd
import pytest
from hydra import compose, initialize_config_dir
from sklearn.base import clone

from test_fit_continued62 import _record
from thermocomp.base.log import Clock
from thermocomp.base.paths import conf_dir
from thermocomp.core.compensator import Compensator, with_chosen_hyperparameters
from thermocomp.core.models.auto import as_chosen
from thermocomp.core.run_report import Refits, ReportSettings, _model_reports
from thermocomp.core.scoring.evaluation import (
    ati_report,
    mutual_prediction_report,
    score,
    validation_report,
)
from thermocomp.shell.builders import build_compensator, validation_template
from thermocomp.shell.chain import fit_chain
from thermocomp.shell.source import open_source

CUT = {"first": (slice(0, 900), "train", ""), "train": (slice(900, 1800), "train", "first"),
       "test": (slice(1800, None), "test", "train")}
EVERY = 7      # a probe cycle: the error measured on one row in 7


def _probed(root, parts=CUT, every=EVERY):
    """The heater record cut into two train files and a test file (``parts``: that continue one
    another), its error measured on one row in ``every``."""
    root.mkdir()
    record = _record()
    record.loc[record.index % every != 0, "E_X"] = np.nan
    for cid, (cut, _, _) in parts.items():
        part = record.iloc[cut].reset_index(drop=True)
        part.assign(time=part["time"] - part["time"].iloc[0]).to_csv(root / f"{cid}.csv", index=False)
    pd.DataFrame([(c, f"{c}.csv", split, before) for c, (_, split, before) in parts.items()],
                 columns=["campaign", "file", "split", "continues"]).to_csv(root / "campaigns.csv",
                                                                           index=False)
    return root


def test_the_validation_of_a_probed_joined_record_is_autos_own_folds(tmp_path, monkeypatch):
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[
            "track=false", "plots=none", "model=auto", "model.candidates=[mlr,arx]",
            f"data.path={_probed(tmp_path / 'data')}"])
    ds = open_source(cfg)
    comp = fit_chain(cfg, ds)
    assert cfg.data.reference == "none" and comp.estimators_["E_X"].scheme_.startswith("forward")
    make = partial(clone, validation_template(cfg, comp, ds))
    refitted = validation_report(make, ds)["E_X"]       # no fitted model: every fold refitted
    fits = []
    fit_stacked = Compensator.fit_stacked
    monkeypatch.setattr(Compensator, "fit_stacked",
                        lambda self, m: fits.append(len(m.X)) or fit_stacked(self, m))
    stored = validation_report(make, ds, fitted=comp)["E_X"]
    assert fits == []                                   # no fold refitted: auto's own folds
    assert stored["method"].endswith("not refitted")
    assert stored["n_folds"] == refitted["n_folds"] > 1
    assert stored["rmse"] == pytest.approx(refitted["rmse"], rel=1e-9)
    assert stored["per_unit"] == pytest.approx(refitted["per_unit"], rel=1e-9)


APART = {"first": (slice(0, 900), "train", ""), "train": (slice(900, 1800), "train", ""),
         "test": (slice(1800, None), "test", "")}


def test_an_ati_baselines_campaign_is_fitted_once_for_mutual_prediction(tmp_path, monkeypatch):
    """The report's single-campaign models: mutual prediction's model of a train campaign is the
    ATI baseline's of it (the family auto chose, nothing chosen of its own): fitted once, the
    report's figures the same to the bit."""
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[
            "track=false", "plots=none", "model=auto", "model.candidates=[mlr,arx]",
            f"data.path={_probed(tmp_path / 'data', APART, every=1)}"])
    ds = open_source(cfg)
    comp = fit_chain(cfg, ds)
    single = as_chosen(clone(build_compensator(cfg, ati=False)), comp)
    settings = ReportSettings(model="auto", select="all")
    _, predictions = score(comp, ds)
    family = type(comp.estimators_["E_X"].estimator_)
    fits, fit = [], family.fit
    monkeypatch.setattr(family, "fit", lambda self, *a, **k: fits.append(1) or fit(self, *a, **k))
    metrics = {}
    _model_reports(settings, comp, ds, predictions, metrics, Refits(single, single), (None, None),
                   Clock())
    # the coldest and the warmest train file (the ATI baselines), then the test file: mutual
    # prediction's models of the train files are the baselines'
    assert len(fits) == 3
    assert metrics["ati"] == ati_report(comp, ds, partial(clone, single))
    assert metrics["mutual_prediction"] == mutual_prediction_report(
        partial(clone, with_chosen_hyperparameters(clone(single), comp)), ds,
        max_models=settings.mutual_prediction_max_models)
