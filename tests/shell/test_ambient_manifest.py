"""Issue 34, item 1: the manifest's ``ambient_c`` is a campaign's ambient where no ambient sensor
(``T_amb`` / ``T_amb_*``) was recorded, so the seasonal model (paper 003, ``ati=cmeans``) runs on a
record whose air sensor has another name."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import refused
from test_hostile import FAST, snapshot
from thermocomp.core.continuation import joined
from thermocomp.core.frame import initial_ambient, stack
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

SPLITS = ["train", "train", "test", "train", "train", "test", "train", "train"]
AMBIENTS = [12.0, 15.0, 18.0, 21.0, 24.0, 27.0, 30.0, 33.0]


def make_dataset(root: Path, ambient_c=True, sensor_name: str = "T_air") -> Path:
    """Eight campaigns a climate room held at 12..33 °C; the error's gain on the heating grows
    with the ambient (what ATI models); the air sensor is ``sensor_name``."""
    root.mkdir(parents=True)
    rng = np.random.default_rng(3)
    t = np.arange(40) * 60.0
    rows = []
    for k, (split, amb) in enumerate(zip(SPLITS, AMBIENTS)):
        cid = f"R{k + 1:02d}"
        heat = amb + 4 * (1 - np.exp(-t / 900)) + rng.normal(0, 0.03, t.size)
        gain = 2.0 + 0.1 * (amb - 20.0)
        e = gain * (heat - heat[0]) + rng.normal(0, 0.1, t.size)
        air = amb + 0.2 * np.sin(t / 600) + rng.normal(0, 0.03, t.size)
        pd.DataFrame({"time": t, "T_spindle": heat, sensor_name: air, "E_X": e}).to_csv(
            root / f"{cid}.csv", index=False)
        rows.append({"campaign": cid, "file": f"{cid}.csv", "split": split,
                     **({"ambient_c": amb} if ambient_c else {})})
    pd.DataFrame(rows).to_csv(root / "campaigns.csv", index=False)
    return root


def test_the_manifest_ambient_runs_the_seasonal_model_and_the_run_says_so(tmp_path, capsys):
    ds = make_dataset(tmp_path / "ds")
    out = tmp_path / "out"
    assert main(["run", f"data.path={ds}", f"out={out}", "ati=cmeans", *FAST,
                 "eval.ati_baselines=true"]) == 0
    assert "ambient: campaigns.csv column ambient_c for the 8 campaign(s)" in capsys.readouterr().err
    metrics = json.loads((out / "metrics.json").read_text())
    ati = metrics["ati"]
    assert ati["ambient_source"] == ["ambient_c"] and ati["ati_model"]
    assert ati["baseline_campaigns"]["coldest"] == {"campaign": "R01", "ambient_c0": 12.0}
    assert ati["baseline_campaigns"]["warmest"] == {"campaign": "R08", "ambient_c0": 33.0}
    report = json.loads((out / "ingest_report.json").read_text())
    assert report["ambient"]["source"] == ["ambient_c"]


def test_without_it_the_seasonal_model_stops_as_before(tmp_path, capsys):
    ds = make_dataset(tmp_path / "ds", ambient_c=False)
    refused(["run", f"data.path={ds}", f"out={tmp_path / 'out'}", "ati=cmeans", *FAST], capsys,
            "no campaign has a valid T_amb / T_amb_* value", "ambient_c")


def test_an_ambient_sensor_wins_over_the_manifest(tmp_path):
    ds, report = read_dataset(make_dataset(tmp_path / "ds", sensor_name="T_amb"))
    assert report["ambient"]["source"] == ["T_amb"]
    m = stack(ds.campaigns, ["T_spindle"], ["E_X"])
    first = m.context.groupby("campaign", sort=False)["ambient_c0"].first()
    measured = [ds.campaigns[c]["T_amb"].iloc[0] for c in first.index]
    assert np.allclose(first.to_numpy(), measured) and not np.allclose(first.to_numpy(), AMBIENTS)


@pytest.mark.parametrize("value", ["warm", "inf"])
def test_a_non_numeric_ambient_c_is_refused_naming_file_column_and_row(tmp_path, capsys, value):
    ds = make_dataset(tmp_path / "ds")
    manifest = pd.read_csv(ds / "campaigns.csv")
    manifest["ambient_c"] = manifest["ambient_c"].astype(object)
    manifest.loc[2, "ambient_c"] = value                    # the third data row
    manifest.to_csv(ds / "campaigns.csv", index=False)
    out = tmp_path / "out"
    before = snapshot(out)
    refused(["run", f"data.path={ds}", f"out={out}", "ati=cmeans", *FAST], capsys,
            "campaigns.csv", "column 'ambient_c'", "row 3", repr(value))
    assert snapshot(out) == before


def test_a_record_cut_in_files_starts_at_its_first_files_ambient(tmp_path):
    # a continuing test file is predicted joined to its predecessor (state carried over): the
    # joined campaign's ambient is the predecessor's, as its first sample's sensor would be
    ds, _ = read_dataset(make_dataset(tmp_path / "ds"))
    assert initial_ambient(joined(ds, ["R02", "R03"])) == 15.0 == initial_ambient(ds.campaigns["R02"])
