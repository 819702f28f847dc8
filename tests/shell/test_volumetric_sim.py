"""Scenario large_mill_volumetric: truth and data agree, the physics is where it should be."""

from __future__ import annotations

import json

import numpy as np
import pytest

from conftest import thermocomp
from thermocomp.apps.sim.large_mill import LargeMillWeek
from thermocomp.apps.sim.volumetric import LargeMillVolumetric, simulate_distances, volumetric_error
from thermocomp.apps.volumetric import SETUP_FILE, ArtefactCalibration, Setup, load_setup
from thermocomp.core.io.read import read_dataset


@pytest.fixture(scope="session")
def small():
    gen = LargeMillVolumetric(train_hours=6.0, test_hours=4.0, seed=3)
    ds, truth = gen.generate()
    return gen, ds, truth


def test_rows_are_cycles_with_every_sensor_and_every_distance(small):
    gen, ds, truth = small
    setup = gen.setup_
    sensors = LargeMillWeek(train_hours=6.0, test_hours=4.0).machine().sensor_array.columns
    for cid, df in ds.campaigns.items():
        assert np.allclose(np.diff(df["time"]), 60 * gen.cycle_min)
        assert [c for c in df.columns if c.startswith("T_")] == list(sensors)
        assert [c for c in df.columns if c.startswith("E_")] == setup.columns()
        assert not df.isna().any().any()
        assert len(truth["campaigns"][cid]["parameters"]["E_XX1"]) == len(df)
    assert len(setup.columns()) == len(setup.poses) * 55      # 11 balls: 55 pairs per pose


def test_distances_are_the_truths_distances(small):
    """Noise-free distances of the truth's parameters, through the first-order model, match the
    data within the noise: the data were made from the truth written."""
    gen, ds, truth = small
    setup = Setup.from_dict(truth["volumetric"]["setup"])
    cal = ArtefactCalibration(setup).fit()
    for cid, df in ds.campaigns.items():
        series = truth["campaigns"][cid]["parameters"]
        full = np.column_stack([series[n] for n in setup.model.names])
        predicted = full @ cal.design_.A.T          # the linearised distances of the true geometry
        residual = df[cal.design_.columns].to_numpy() - predicted
        # what is left is the probing and ball noise, whose size the set-up states
        expected = np.sqrt(np.mean(np.diag(cal.design_.cov)))
        assert np.sqrt(np.mean(residual ** 2)) == pytest.approx(expected, rel=0.25)
        # the signal is far above it
        assert np.sqrt(np.mean(predicted ** 2)) > 5 * expected


def test_ball_error_is_one_artefact_and_the_htm_form_is_exact_to_second_order(small):
    gen, ds, truth = small
    setup = gen.setup_
    P = gen.parameters_["train_week"].to_numpy()[:3]
    ball = np.asarray(truth["volumetric"]["ball_error_um"])
    a = simulate_distances(Setup(setup.model, setup.array, setup.poses, 0.0, 0.0), P,
                           np.random.default_rng(0), ball)
    b = simulate_distances(Setup(setup.model, setup.array, setup.poses, 0.0, 0.0), P,
                           np.random.default_rng(1), ball)
    assert np.array_equal(a, b)                     # no probing noise: only the geometry and the balls
    cal = ArtefactCalibration(setup).fit()
    no_balls = simulate_distances(Setup(setup.model, setup.array, setup.poses, 0.0, 0.0), P,
                                  np.random.default_rng(0), np.zeros_like(ball))
    linear = P @ cal.design_.A.T
    assert np.max(np.abs(no_balls - linear)) < 0.05          # µm: second-order terms only
    assert np.max(np.abs(a - no_balls)) > 0.3                # the artefact's own error is there


def test_parameters_follow_the_heaters_and_the_cold_geometry_has_its_ve():
    gen = LargeMillVolumetric(train_hours=60.0, test_hours=4.0, seed=1)
    gen.generate()
    model = gen.setup_.model
    truth_cold = gen.cold_geometry(model, np.random.default_rng(0))
    assert volumetric_error(model, truth_cold)[0] == pytest.approx(gen.cold_ve_um)
    P = gen.parameters_["train_week"]
    temps = gen.node_temperatures_["train_week"]
    side = temps["column_side_low"] - 0.5 * (temps["column_front_low"] + temps["column_back_low"])
    heater = temps["_heater_side"] > 0
    assert heater.any() and (~heater).any()
    # the side heater leans the column in X: Z's squareness with X follows the side's excess
    assert np.corrcoef(P["E_XZ1"], side)[0, 1] > 0.99
    assert P["E_XZ1"][heater].mean() > P["E_XZ1"][~heater].mean()
    # the bed's temperature is the X scale
    bed = temps[["bed_left", "bed_mid", "bed_right"]].mean(axis=1)
    assert np.corrcoef(P["E_XX1"], bed)[0, 1] > 0.99
    # parameters nobody drives stay at their cold value
    assert np.ptp(P["E_CY1"]) == 0.0


def test_same_seed_same_data_other_seed_other_artefact():
    a = LargeMillVolumetric(train_hours=2.0, test_hours=1.0, seed=5).generate()
    b = LargeMillVolumetric(train_hours=2.0, test_hours=1.0, seed=5).generate()
    c = LargeMillVolumetric(train_hours=2.0, test_hours=1.0, seed=6).generate()
    assert a[0].campaigns["train_week"].equals(b[0].campaigns["train_week"])
    assert a[1]["volumetric"]["ball_error_um"] == b[1]["volumetric"]["ball_error_um"]
    assert a[1]["volumetric"]["ball_error_um"] != c[1]["volumetric"]["ball_error_um"]


def test_knobs_reach_the_setup():
    gen = LargeMillVolumetric(train_hours=1.0, test_hours=1.0, n_balls=7, misalignment_deg=5.0,
                              sets=["S2", "S3"], x_centres=[0.5], order=3, cross_terms=True)
    ds, truth = gen.generate()
    setup = Setup.from_dict(truth["volumetric"]["setup"])
    assert setup.array.n_balls == 7 and setup.array.misalignment_deg == 5.0
    assert len(setup.poses) == 10 and setup.model.order == 3 and "E_YZY1" in setup.model.names
    assert set(truth["campaigns"]["train_week"]["parameters"]) == set(setup.model.names)
    assert len([c for c in ds.campaigns["train_week"].columns if c.startswith("E_")]) == 10 * 21


@pytest.mark.slow
def test_simulate_cli_writes_parquet_and_the_setup(tmp_path):
    path = tmp_path / "vol"
    thermocomp("simulate", "experiment=volumetric_large_mill", f"data.path={path}", "track=false",
               "sim.generator.train_hours=2", "sim.generator.test_hours=1")
    manifest = (path / "campaigns.csv").read_text()
    assert "train_week.parquet" in manifest and "validation_week.parquet" in manifest
    setup = load_setup(path)
    truth = json.loads(path.with_name("vol.truth.json").read_text())
    assert setup.to_dict() == truth["volumetric"]["setup"]
    assert not (path / "vol.truth.json").exists() and (path / SETUP_FILE).is_file()
    ds, _ = read_dataset(path)
    assert set(setup.columns()) <= set(ds.campaigns["train_week"].columns)
    assert dict(ds.manifest["split"]) == {"train_week": "train", "validation_week": "test"}
