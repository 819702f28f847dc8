"""Simulator v1: determinism, physics of the network, and the dataset contract."""

from __future__ import annotations

import json
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from thermocomp.apps.sim.ambient import AmbientModel
from thermocomp.apps.sim.campaign import Programme, integrate, run_campaign
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.sensors import first_order_lag
from thermocomp.apps.sim.vmc import vertical_machining_centre
from thermocomp.apps.sim.yearround import YearRoundSpindle
from thermocomp.core.io.contract import PREFIXES, TIME, write_dataset

CONF = Path(__file__).resolve().parents[2] / "conf" / "sim" / "yearround_spindle.yaml"
SPINDLE_NODES = ("motor", "spindle_shaft", "bearing_front", "bearing_rear")
HEAVY_NODES = ("column_front", "column_back", "bed")


@pytest.fixture(scope="session")
def yearround():
    t0 = time.perf_counter()
    dataset, truth = YearRoundSpindle(seed=0).generate()
    print(f"\nyearround_spindle: 24 campaigns generated in {time.perf_counter() - t0:.2f} s")
    return dataset, truth


@pytest.fixture(scope="session")
def machine():
    return vertical_machining_centre()


def small(seed):
    return YearRoundSpindle(n_campaigns=4, duration_h=(4.0, 4.5), seed=seed).generate()


# --- determinism ------------------------------------------------------------------------------

def test_same_seed_gives_identical_data_and_truth():
    (a, truth_a), (b, truth_b) = small(7), small(7)
    pd.testing.assert_frame_equal(a.manifest, b.manifest)
    for cid in a.ids():
        pd.testing.assert_frame_equal(a.campaigns[cid], b.campaigns[cid])
    assert json.dumps(truth_a, sort_keys=True) == json.dumps(truth_b, sort_keys=True)


def test_different_seed_gives_different_data():
    (a, _), (b, _) = small(7), small(8)
    assert not a.campaigns["K01"].equals(b.campaigns["K01"])


# --- network physics --------------------------------------------------------------------------

def test_steady_rise_is_proportional_to_heat(machine):
    """Integrated to steady state, 2Q gives twice the rise of Q, equal to L^-1 Q, and heat balances."""
    network = machine.network
    heat = network.heat_vector({"motor": 150.0, "bearing_front": 60.0, "bearing_rear": 25.0})
    propagator = network.propagator(3600.0)
    ambient = 12.0

    def settle(q):
        temps = np.full(network.n_nodes, ambient)
        for _ in range(24 * 30):  # 30 days; slowest mode ~8 h
            temps = propagator.step(temps, ambient, q)
        return temps - ambient

    rise, rise2 = settle(heat), settle(2 * heat)
    np.testing.assert_allclose(rise2, 2 * rise, rtol=1e-9)
    np.testing.assert_allclose(rise, network.steady_state(ambient, heat) - ambient, rtol=1e-6)
    # All heat leaves through convection at steady state.
    assert np.isclose(network.convection @ rise, heat.sum(), rtol=1e-6)
    assert rise.min() > 0 and rise[network.index["bearing_front"]] > rise[network.index["bed"]]


def test_exact_step_is_independent_of_step_size(machine):
    """Matrix-exponential steps: one 1-h step equals 120 steps of 30 s for constant inputs."""
    network = machine.network
    heat = network.heat_vector({"motor": 150.0})
    start = np.full(network.n_nodes, 20.0)
    coarse = network.propagator(3600.0).step(start, 20.0, heat)
    fine, step = start, network.propagator(30.0)
    for _ in range(120):
        fine = step.step(fine, 20.0, heat)
    np.testing.assert_allclose(coarse, fine, atol=1e-9)


def test_time_constants_minutes_for_spindle_hours_for_structure(machine):
    tau_min = {k: v / 60 for k, v in machine.network.local_time_constants().items()}
    print("\nlocal time constants (min):", {k: round(v, 1) for k, v in tau_min.items()})
    for node in SPINDLE_NODES:
        assert 1 <= tau_min[node] <= 60, node
    for node in HEAVY_NODES:
        assert 60 <= tau_min[node] <= 12 * 60, node
    modal_h = machine.network.modal_time_constants() / 3600
    assert modal_h[0] < 0.1 and 2 < modal_h[-1] < 24


def test_integrate_matches_step_by_step_reference(machine):
    """The run-wise fast path equals stepping the propagator with the full heat vector each step."""
    times = np.arange(0.0, 4 * 3600 + 1, 30.0)
    ambient = 20 + np.sin(times / 5000)
    rpm = np.select([times < 7200, times < 10800], [6000.0, 2000.0], 0.0)
    fast = integrate(machine, np.full(machine.network.n_nodes, 19.0), times, ambient,
                     {"S_spindle_rpm": rpm}, 1.2)
    slow = np.empty_like(fast)
    slow[0] = 19.0
    for k in range(len(times) - 1):
        state = {"S_spindle_rpm": rpm[k]}
        hA = machine.injector.convection(state, machine.convection_rules, 1.2)
        step = machine.network.propagator(30.0, hA)
        slow[k + 1] = step.step(slow[k], 0.5 * (ambient[k] + ambient[k + 1]),
                                machine.injector.heat(state, slow[k]))
    np.testing.assert_allclose(fast, slow, atol=1e-9)


def test_network_rejects_isolated_node():
    with pytest.raises(ValueError, match="no heat path"):
        ThermalNetwork([Node("a", 1.0, 1.0), Node("b", 1.0, 0.0)], [])
    with pytest.raises(ValueError, match="two different known nodes"):
        ThermalNetwork([Node("a", 1.0, 1.0)], [Link("a", "x", 1.0)])


def test_sensor_lag_is_exact_first_order():
    """A 0.5 K/min ramp seen through an 8-min lag trails it by 4 K once settled."""
    t = np.arange(0, 7200.0, 30.0)
    ramp = (t / 120.0)[:, None]
    lagged = first_order_lag(ramp, [480.0], 30.0)
    assert lagged[0, 0] == 0.0
    assert np.isclose(ramp[-1, 0] - lagged[-1, 0], 4.0, atol=1e-3)


# --- campaigns: errors and ambient dependence ---------------------------------------------------

def run_constant(machine, rpm, day, seed=1):
    start = day * 86400.0 + 8 * 3600.0
    return run_campaign(machine, AmbientModel(), Programme(((0.0, rpm),)), start, 6 * 3600.0,
                        np.random.default_rng(seed))


def test_error_starts_at_zero_and_grows_with_speed(machine):
    finals, rises = [], []
    for rpm in (2000, 4000, 6000):
        frame, info = run_constant(machine, rpm, day=100)
        first = frame.iloc[0]
        assert all(abs(first[e]) < 2.0 for e in ("E_X", "E_Y", "E_Z"))  # noise 0.4 µm
        finals.append(info["true_error_final_um"]["E_Z"])
        rises.append(frame["T_bearing_f1"].iloc[-1] - frame["T_bearing_f1"].iloc[0])
    print("\nE_Z after 6 h at 2000/4000/6000 rpm (µm):", np.round(finals, 1))
    assert finals[0] > 5 and np.all(np.diff(finals) > 5)
    assert np.all(np.diff(rises) > 1)


def test_low_ambient_gives_larger_z_growth(machine):
    (_, cold), (_, warm) = run_constant(machine, 6000, day=15), run_constant(machine, 6000, day=196)
    assert cold["ambient_start_c"] < 10 < 28 < warm["ambient_start_c"]
    assert cold["true_error_final_um"]["E_Z"] > 1.15 * warm["true_error_final_um"]["E_Z"]


# --- the year-round dataset -----------------------------------------------------------------

def test_contract_frames(yearround):
    dataset, _ = yearround
    assert dataset.ids() == [f"K{k:02d}" for k in range(1, 25)]
    for cid, frame in dataset.campaigns.items():
        assert frame.columns[0] == TIME
        assert all(c.startswith(PREFIXES) for c in frame.columns[1:])
        assert all(dtype == np.float64 for dtype in frame.dtypes)
        time_s = frame[TIME].to_numpy()
        assert time_s[0] == 0.0 and np.all(np.diff(time_s) == 300.0)
        assert time_s[-1] >= 4 * 3600 and time_s[-1] <= 8 * 3600
        assert len(frame.filter(like="T_").columns) == 10 and "T_amb" in frame
        assert {"E_X", "E_Y", "E_Z", "S_spindle_rpm"} <= set(frame.columns)
        assert not frame.isna().any().any()
        temps = frame.filter(like="T_").to_numpy()
        np.testing.assert_allclose(temps, np.round(temps, 2), atol=1e-9)  # 0.01 °C quantum
        errors = frame[["E_X", "E_Y", "E_Z"]].to_numpy()
        np.testing.assert_allclose(errors, np.round(errors, 1), atol=1e-9)  # 0.1 µm quantum
        assert set(frame["S_spindle_rpm"]) <= {0.0, 2000.0, 4000.0, 6000.0}


def test_manifest_and_writer(yearround, tmp_path):
    dataset, _ = yearround
    manifest = dataset.manifest
    assert {"file", "split", "start", "notes", "ambient_c", "spindle_rpm"} <= set(manifest.columns)
    starts = pd.to_datetime(manifest["start"])
    assert starts.is_monotonic_increasing and (starts.max() - starts.min()).days > 300
    path = write_dataset(dataset, tmp_path / "yearround_spindle")
    written = pd.read_csv(path / "campaigns.csv")
    assert list(written.columns[:3]) == ["campaign", "file", "split"]
    back = pd.read_csv(path / written["file"][0])
    pd.testing.assert_frame_equal(back, dataset.campaigns["K01"], check_dtype=False, atol=1e-6)


def test_ambient_spread_and_split(yearround):
    dataset, truth = yearround
    manifest = dataset.manifest
    ambient = manifest["ambient_c"]
    print("\ninitial ambient (°C):", ambient.round(1).tolist())
    assert ambient.min() <= 7 and ambient.max() >= 30 and ambient.between(2, 36).all()
    test = manifest[manifest["split"] == "test"]
    train = manifest[manifest["split"] == "train"]
    assert len(test) >= 6 and set(manifest["split"]) == {"train", "test"}
    for part in (test, train):
        assert part["ambient_c"].min() < 12 and part["ambient_c"].max() > 25
    assert set(test["spindle_rpm"]) >= {4000, 6000}
    assert truth["initial_ambient_c"].keys() == set(manifest.index)


def test_truth_schema(yearround):
    _, truth = yearround
    json.dumps(truth)
    for key in ("scenario", "seed", "noise", "network", "heat_sources", "sensors", "sensor_nodes",
                "thermoelastic", "ambient", "initial_ambient_c", "campaigns", "undeclared_effects"):
        assert key in truth, key
    assert truth["scenario"] == "yearround_spindle" and truth["undeclared_effects"] == []
    assert truth["noise"] == {"temperature_c": 0.03, "temperature_quantum_c": 0.01,
                              "error_um": 0.4, "error_quantum_um": 0.1}
    assert set(truth["thermoelastic"]["linear_um_per_K"]) == {"E_X", "E_Y", "E_Z"}
    assert len(truth["sensor_nodes"]) == 10
    nodes = truth["network"]["nodes"]
    assert all(n["capacity_J_per_K"] > 0 for n in nodes.values())


def test_mlr_explains_most_but_not_all(yearround):
    """Least squares on the 10 sensors' rises (+ intercept): test RMS after/before in (5 %, 40 %)."""
    dataset, _ = yearround
    temps = [c for c in dataset.columns if c.startswith("T_")]
    targets = ["E_X", "E_Y", "E_Z"]

    def stack(split):
        frames = [dataset.campaigns[c] for c in dataset.ids(split)]
        x = np.vstack([(f[temps] - f[temps].iloc[0]).to_numpy() for f in frames])
        y = np.vstack([(f[targets] - f[targets].iloc[0]).to_numpy() for f in frames])
        return np.column_stack([np.ones(len(x)), x]), y

    (x_train, y_train), (x_test, y_test) = stack("train"), stack("test")
    coef, *_ = np.linalg.lstsq(x_train, y_train, rcond=None)
    before = np.sqrt((y_test**2).mean(0))
    after = np.sqrt(((y_test - x_test @ coef) ** 2).mean(0))
    ratio = after / before
    print("\nMLR test RMS after/before:", dict(zip(targets, ratio.round(3))))
    assert np.all(ratio < 0.4) and np.all(ratio > 0.05)


def test_hydra_config_instantiates_the_generator():
    omegaconf = pytest.importorskip("omegaconf")
    hydra_utils = pytest.importorskip("hydra.utils")
    cfg = omegaconf.OmegaConf.load(CONF)
    assert cfg.name == "yearround_spindle"
    cfg = omegaconf.OmegaConf.merge({"seed": 3}, {"sim": cfg})
    generator = hydra_utils.instantiate(cfg.sim.generator)
    assert isinstance(generator, YearRoundSpindle) and generator.seed == 3
    assert generator.get_params()["duration_h"] == [4.0, 8.0]
