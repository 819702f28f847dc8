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
