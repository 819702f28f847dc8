"""``run model=auto`` on a volumetric dataset (stop 96, ``benchmarks/bench_audit96.py sweep``:
large_mill_volumetric seed 9775): the ``volumetric`` section read each parameter's thermal model
as an ARX's choices (``chosen_.get``), where ``model=auto`` keeps a family's name there (or a
blend's weights): the run stopped with a traceback, exit 1, after fitting every candidate."""

from __future__ import annotations

import json

import pytest

from conftest import simulated
from thermocomp.apps.sim.volumetric import LargeMillVolumetric
from thermocomp.shell.cli import main


@pytest.fixture(scope="module")
def raw(tmp_path_factory):
    """A day of training, half a day of validation, a cycle every 20 min."""
    gen = LargeMillVolumetric(train_hours=24.0, test_hours=12.0, seed=96)
    return simulated(gen, tmp_path_factory.mktemp("volauto") / "raw")


@pytest.mark.parametrize("candidates", ("[mlr]", "[mlr,arx]"))
def test_model_auto_runs_on_a_volumetric_dataset_and_says_each_parameters_model(raw, tmp_path,
                                                                                candidates):
    out = tmp_path / "out"
    assert main(["run", "experiment=volumetric_large_mill", f"data.path={raw}", f"out={out}",
                 "track=false", "plots=none", "eval.mutual_prediction=false",
                 "eval.ati_baselines=false", "model=auto", f"model.candidates={candidates}"]) == 0
    vol = json.loads((out / "metrics.json").read_text())["volumetric"]
    assert vol["parameters"]
    for row in vol["parameters"].values():
        assert row["n_inputs"] >= 1 and isinstance(row["ar"], bool)
