"""Every fit of train files that continue one another is in the frame they are predicted in
(joinfit62).

lagbank62 fitted ``run``'s final model on such files joined (:func:`~thermocomp.core.continuation.
fit_campaigns`); ``diagnose`` (its "before", "after" and its search's CV) and the run's
validation folds still fitted them apart, every lag restarted at each file's first sample, so
their figures were of another frame than the deployed model's: diagnose's "before" was not the
run's test figure.  The record: a heater's slow thermal lag (test_fit_continued62), cut into
two train files and a test file that continue one another.
"""

from __future__ import annotations

import json
from functools import partial

import numpy as np
import pytest
from hydra import compose, initialize_config_dir
from sklearn.base import clone

from conftest import FAST, UNTRACKED, thermocomp
from test_fit_continued62 import _folder
from thermocomp.base.paths import conf_dir
from thermocomp.core.continuation import fit_joined, predict
from thermocomp.core.scoring.evaluation import validation_report
from thermocomp.shell.builders import build_compensator
from thermocomp.shell.chain import fit_chain
from thermocomp.shell.source import open_source

LAGBANK = ("model=lagbank", "model.estimator.n_taus=4")
CUT = {"first": (slice(0, 900), "train", ""), "train": (slice(900, 1800), "train", "first"),
       "test": (slice(1800, None), "test", "train")}
WHOLE = {"train": (slice(0, 1800), "train", ""), "test": (slice(1800, None), "test", "train")}
# the same cuts, separate runs (no ``continues``): each file's state its own
APART = {"first": (slice(0, 900), "train", ""), "train": (slice(900, 1800), "train", ""),
         "test": (slice(1800, None), "test", "")}


def _cfg(root, *extra):
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        return compose(config_name="config", overrides=[
            "track=false", "plots=none", *LAGBANK, f"data.path={root}", *extra])


def _validation(root):
    cfg = _cfg(root)
    ds = open_source(cfg)
    comp = fit_chain(cfg, ds)
    return validation_report(partial(clone, build_compensator(cfg, ds=ds)), ds, fitted=comp)["E_X"]


def test_validation_of_a_cut_record_is_the_uncut_records(tmp_path):
    """The run's validation folds fit and predict the two train files as the one record they
    are: the same figures as the uncut record's (fitted apart: other folds, other figures)."""
    cut = _validation(_folder(tmp_path / "cut", CUT))
    whole = _validation(_folder(tmp_path / "whole", WHOLE))
    assert cut["method"] == whole["method"]
    assert cut["rmse"] == pytest.approx(whole["rmse"], rel=1e-9)


@pytest.mark.parametrize("parts, reference", [(APART, "auto"), (CUT, "first_sample")])
def test_files_not_continued_are_fitted_as_before_bit_for_bit(tmp_path, parts, reference):
    """Separate runs (or ``data.reference=first_sample``, no state carried): each file fitted on
    its own, as ever, to the bit."""
    cfg = _cfg(_folder(tmp_path / "data", parts), f"data.reference={reference}")
    ds = open_source(cfg)
    train = ds.ids("train")
    joined = fit_joined(build_compensator(cfg, ds=ds), ds, train)
    apart = build_compensator(cfg, ds=ds).fit({c: ds.campaigns[c] for c in train})
    assert np.array_equal(predict(joined, ds, ["test"])[0]["test"].to_numpy(),
                          predict(apart, ds, ["test"])[0]["test"].to_numpy())


@pytest.mark.slow
@pytest.mark.parametrize("model", [LAGBANK, ("model=mlr",)])
def test_diagnose_before_is_the_runs_test_figure_and_after_its_rerun(tmp_path, model):
    """On the cut record, diagnose's "before" (batch, as run scores it) is the run's test RMSE,
    and its "after" the rerun of the config it writes."""
    data = _folder(tmp_path / "data", CUT)
    thermocomp("run", f"data.path={data}", f"out={tmp_path / 'run'}", *model, *FAST)
    ran = json.loads((tmp_path / "run" / "metrics.json").read_text())["targets"]["E_X"]["test"]
    proc = thermocomp("diagnose", f"data.path={data}", f"out={tmp_path / 'diag'}", *model,
                      *UNTRACKED, "plots=none", check=False)
    assert proc.returncode == 0, proc.stderr[-2000:]
    j = json.loads((tmp_path / "diag" / "diagnosis.json").read_text())
    before = j["before"].get("test_rmse_as_run", j["before"]["test_rmse"])
    assert before == pytest.approx(ran["rmse"], rel=1e-9)
    conf = tmp_path / "diag" / "diagnosis" / "conf"
    thermocomp("run", f"hydra.searchpath=[file://{conf}]", "experiment=diagnosed",
               f"data.path={data}", f"out={tmp_path / 'rerun'}", *FAST)
    rerun = json.loads((tmp_path / "rerun" / "metrics.json").read_text())["targets"]["E_X"]["test"]
    assert rerun["rmse"] == pytest.approx(j["after"].get("test_rmse_as_run", j["after"]["test_rmse"]),
                                          rel=1e-9)


def test_a_denoised_fit_is_runs_fit(tmp_path):
    """With a denoiser, the files are denoised each on its own, then joined, as run's denoise
    step does: ``fit_joined`` (diagnose's, monitor's, deploy's fit) predicts what run's model
    predicts."""
    cfg = _cfg(_folder(tmp_path / "data", CUT), "denoise=emd")
    ds = open_source(cfg)
    ran = fit_chain(cfg, ds)
    mine = fit_joined(build_compensator(cfg, ds=ds), ds, ds.ids("train"))
    assert np.array_equal(predict(mine, ds, ["test"])[0]["test"].to_numpy(),
                          predict(ran, ds, ["test"])[0]["test"].to_numpy())


def test_the_val_splits_persistence_starts_from_the_file_it_continues(tmp_path):
    """model=auto on a val file that continues the train files: persistence's first val row
    is the last train measurement (as the test split's persistence), not 0."""
    from thermocomp.core.metrics import PERSISTENCE
    from thermocomp.core.scoring.auto_validation import val_split_scores

    root = _folder(tmp_path / "val", {"first": (slice(0, 900), "train", ""),
                                       "train": (slice(900, 1500), "train", "first"),
                                       "val": (slice(1500, 1800), "val", "train"),
                                       "test": (slice(1800, None), "test", "val")})
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[
            "track=false", "plots=none", "model=auto", "model.candidates=[mlr]", f"data.path={root}"])
    ds = open_source(cfg)
    comp = fit_chain(cfg, ds)
    got = val_split_scores(comp, ds)["E_X"][PERSISTENCE]
    y = np.concatenate([ds.campaigns[c]["E_X"].to_numpy(float) for c in ("first", "train", "val")])
    val = y[1500:]
    expected = np.sqrt(np.mean((val - y[1499:-1]) ** 2))
    assert got == pytest.approx(expected, rel=1e-12)


def test_the_join_is_said_once_a_stage_run_however_often_it_is_fitted(tmp_path, capsys):
    """``monitor`` fits the train campaigns twice (fixed and adaptive): stranger78's lathe said
    the join twice.  Within a stage run (:func:`log.said_once`) the same note is said once;
    outside one, at every fit."""
    from thermocomp.base import log

    cfg = _cfg(_folder(tmp_path / "data", CUT))
    ds = open_source(cfg)
    log.configure("INFO")
    with log.said_once():
        for _ in range(2):
            fit_joined(build_compensator(cfg, ds=ds), ds, ds.ids("train"))
    fit_joined(build_compensator(cfg, ds=ds), ds, ds.ids("train"))
    assert capsys.readouterr().err.count("fitted as one") == 2
