"""A stranger's pass over the volumetric twin and fleets (volfleet63)."""

from __future__ import annotations

import shutil

import pandas as pd
import pytest

from conftest import refused, simulated
from thermocomp.apps.sim.volumetric import LargeMillVolumetric


@pytest.fixture(scope="module")
def raw(tmp_path_factory):
    gen = LargeMillVolumetric(train_hours=3.0, test_hours=2.0, seed=6331)
    return simulated(gen, tmp_path_factory.mktemp("volfleet63") / "raw")


def test_a_volumetric_dataset_grouped_by_machine_is_refused_not_fitted_on_its_distances(
        raw, tmp_path, capsys):
    """``run data.group_by=machine`` went past the calibration: it fitted one model per raw
    ball distance (1430 targets, exit 0, no ``volumetric`` section) where ``run`` without it
    models the identified error parameters."""
    data = shutil.copytree(raw, tmp_path / "grouped")
    manifest = pd.read_csv(data / "campaigns.csv")
    manifest["machine"] = "M001"
    manifest.to_csv(data / "campaigns.csv", index=False)
    out = tmp_path / "out"
    refused(["run", f"data.path={data}", "data.group_by=machine", "track=false",
             "eval.validation=false", "plots=none", f"out={out}"], capsys,
            "volumetric.json", "data.group_by=machine", "without data.group_by")
    assert not out.exists()


@pytest.fixture(scope="module")
def fleet(tmp_path_factory):
    from thermocomp.apps.sim.fleet import Fleet

    path = tmp_path_factory.mktemp("volfleet63") / "fleet"
    Fleet(n_machines=2, days=3, test_days=1, n_sensors=5, sample_period_s=600.0, n_jobs=1,
          seed=6331).write(path)
    return path


def test_run_sim_fleet_writes_its_own_folder_not_the_main_pipelines():
    """``thermocomp run sim=fleet`` (docs/sweeps.md) wrote into reports/default, the main
    pipeline's DVC output: its metrics.json replaced, the year-round model.pkl and headline left
    beside it."""
    from thermocomp.shell.config.overrides import compose

    cfg = compose(["sim=fleet"], "run")
    assert cfg.out == "reports/fleet" and cfg.model_path == "models/fleet/model.pkl"
    assert compose([], "run").out == "reports/default"


def test_a_fleet_run_into_a_single_runs_folder_says_what_it_left_there(fleet, tmp_path, capsys):
    """And the other way round: each kind of run leaves the other's files (out keeps what it
    did not write); they were left without a word, a metrics.json beside a model it is not of."""
    from thermocomp.shell.cli import main

    out = tmp_path / "out"
    common = [f"data.path={fleet}", "data.reference=first_sample", "track=false",
              "eval.validation=false", "plots=none", f"out={out}"]
    assert main(["run", *common]) == 0
    capsys.readouterr()
    assert main(["run", "data.group_by=machine", *common]) == 0
    said = [ln for ln in capsys.readouterr().err.splitlines() if "not this run's" in ln]
    assert len(said) == 1 and "model.pkl" in said[0] and "headline" in said[0], said
    assert main(["run", *common]) == 0
    said = [ln for ln in capsys.readouterr().err.splitlines() if "not this run's" in ln]
    assert len(said) == 1 and "fleet.csv" in said[0] and "models" in said[0], said


def test_simulate_says_when_another_seed_replaces_the_dataset(tmp_path, capsys):
    """``simulate seed=6331`` replaces the scenario's own folder (the seed is not in its digest,
    so ``run seed=1`` reads the same data), and a later ``calibrate`` without ``seed=`` read
    seed 6331's distances without a word."""
    from thermocomp.shell.cli import main

    data = tmp_path / "vol"
    small = ["sim=large_mill_volumetric", "sim.generator.train_hours=1.0",
             "sim.generator.test_hours=1.0", f"data.path={data}", "track=false"]
    assert main(["simulate", *small]) == 0
    capsys.readouterr()
    assert main(["simulate", *small, "seed=6331"]) == 0
    err = capsys.readouterr().err
    assert "simulated with seed 0" in err and "seed 6331" in err, err
    assert main(["simulate", *small, "seed=6331"]) == 0
    assert "simulated with seed" not in capsys.readouterr().err
