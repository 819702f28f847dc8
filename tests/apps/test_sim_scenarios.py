"""Scenarios of issue 3: each one's physics, determinism, layout, config and the clean control."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from thermocomp.apps.sim import SCENARIOS
from thermocomp.apps.sim.campaign import integrate
from thermocomp.apps.sim.column import LEVELS, POSITION, Q2, machine_column
from thermocomp.apps.sim.effects import EFFECTS
from thermocomp.base.errors import ConfigError
from thermocomp.core.io.contract import PREFIXES, write_dataset
from thermocomp.core.io.read import read_dataset

CONF = Path(__file__).resolve().parents[2] / "conf" / "sim"

SMALL = {
    "yearround_spindle": dict(n_campaigns=6, duration_h=(4.0, 4.5)),
    "large_mill_week": dict(train_hours=30.0, test_hours=12.0, sample_period_s=60.0),
    "swiss_lathe_door": dict(calibration_hours=12.0, production_hours=6.0),
    "column_moving_source": dict(train_hours=12.0, test_hours=12.0),
    "long_record": dict(duration_days=4.0, n_temperature_outliers=0, n_error_outliers=0),
    "climate_room": dict(n_runs=6, duration_h=(2.0, 2.5)),
}


def small(name, **kw):
    return SCENARIOS[name](**{**SMALL[name], **kw})


def mlr_residual(ds, targets):
    """Test residual of least squares on every T_ rise (+ intercept) fitted on train."""
    sensors = [c for c in ds.columns if c.startswith("T_")]

    def stack(split):
        frames = [ds.campaigns[c] for c in ds.ids(split)]
        x = np.vstack([(f[sensors] - f[sensors].iloc[0]).to_numpy() for f in frames])
        y = np.vstack([(f[targets] - f[targets].iloc[0]).to_numpy() for f in frames])
        return np.column_stack([np.ones(len(x)), x]), y

    (a, b), (c, d) = stack("train"), stack("test")
    coef, *_ = np.linalg.lstsq(a, b, rcond=None)
    return d - c @ coef


# --- every scenario -----------------------------------------------------------------------

@pytest.mark.parametrize("name", list(SCENARIOS))
def test_deterministic_per_seed_and_in_the_contract(name):
    (a, truth_a), (b, truth_b) = small(name, seed=5).generate(), small(name, seed=5).generate()
    (c, _) = small(name, seed=6).generate()
    assert json.dumps(truth_a, sort_keys=True) == json.dumps(truth_b, sort_keys=True)
    for cid in a.ids():
        pd.testing.assert_frame_equal(a.campaigns[cid], b.campaigns[cid])
        frame = a.campaigns[cid]
        assert frame.columns[0] == "time" and all(col.startswith(PREFIXES) for col in frame.columns[1:])
        assert not frame.isna().any().any()
    assert not all(a.campaigns[cid].equals(c.campaigns[cid]) for cid in a.ids())
    assert set(a.manifest["split"]) == {"train", "test"}
    assert truth_a["scenario"] == name and truth_a["clean"] is False


@pytest.mark.parametrize("name", list(SCENARIOS))
def test_yaml_matches_the_generator(name):
    """conf/sim/<name>.yaml builds this generator, and its effect parameters are the machine's defaults."""
    omegaconf = pytest.importorskip("omegaconf")
    from hydra.utils import instantiate

    cfg = omegaconf.OmegaConf.load(CONF / f"{name}.yaml")
    cfg = cfg.sim if "sim" in cfg else cfg      # a scenario in the _global_ package also sets data keys
    assert cfg.name == name
    generator = instantiate(omegaconf.OmegaConf.merge({"seed": 3}, {"sim": cfg}).sim.generator)
    assert type(generator) is SCENARIOS[name] and generator.seed == 3
    defaults = generator.effect_defaults()
    params = omegaconf.OmegaConf.to_container(cfg.generator.effect_params)
    assert set(params) == set(EFFECTS)
    for effect, cls in EFFECTS.items():
        assert params[effect] == {**cls.defaults, **defaults.get(effect, {})}, effect


# every conf/sim scenario, written small (the fleet and the volumetric one too)
WRITTEN = {
    "climate_room": dict(n_runs=3, duration_h=(1.0, 1.0), sample_period_s=600.0),
    "column_moving_source": dict(train_hours=4.0, test_hours=4.0, sample_period_s=300.0),
    "fleet": dict(n_machines=2, days=2, test_days=1, n_jobs=1, sample_period_s=1800.0, n_sensors=6),
    "large_mill_volumetric": dict(train_hours=6.0, test_hours=6.0, cycle_min=60.0, n_balls=3, sets=["S1"]),
    "large_mill_week": dict(train_hours=6.0, test_hours=6.0, sample_period_s=600.0),
    "long_record": dict(duration_days=1.0, sample_period_s=600.0),
    "swiss_lathe_door": dict(calibration_hours=6.0, production_hours=4.0),
    "yearround_spindle": dict(n_campaigns=4, sample_period_s=600.0),
}


def test_every_configured_scenario_is_written_small():
    assert set(WRITTEN) == {p.stem for p in CONF.glob("*.yaml")}


@pytest.mark.parametrize("name", sorted(WRITTEN))
def test_a_seed_writes_the_same_bytes_and_a_truth_that_matches_the_manifest(name, tmp_path):
    """What `simulate` writes (campaign files, manifest, truth) is byte-identical for one seed, and
    the truth's campaigns are the manifest's, in its order with its split and start."""
    omegaconf = pytest.importorskip("omegaconf")
    from hydra.utils import instantiate

    from thermocomp.apps.sim.scenario import write_scenario
    from thermocomp.base.files import folder_digest, write_json

    cfg = omegaconf.OmegaConf.load(CONF / f"{name}.yaml")
    generator = (cfg.sim if "sim" in cfg else cfg).generator

    def written(seed, run):     # as `simulate` writes data.path=<run>/data (digests name the files)
        gen = instantiate(omegaconf.OmegaConf.merge(generator, {**WRITTEN[name], "seed": seed}),
                          _convert_="all")
        truth = write_scenario(gen, tmp_path / run / "data")[0]
        path = write_json(tmp_path / run / "data.truth.json", truth)
        return truth, (folder_digest(tmp_path / run / "data"), folder_digest(path))

    truth, digests = written(3, "a")
    assert written(3, "b")[1] == digests
    assert written(4, "c")[1][0] != digests[0]
    manifest = pd.read_csv(tmp_path / "a" / "data" / "campaigns.csv", index_col="campaign")
    if name == "fleet":     # streamed: the truth counts the campaigns, per machine
        assert truth["campaigns"] == len(manifest) and set(truth["machines"]) == set(manifest["machine"])
        return
    assert list(truth["campaigns"]) == list(manifest.index) == list(truth["initial_ambient_c"])
    for cid, campaign in truth["campaigns"].items():
        assert (campaign["split"], campaign["start"]) == tuple(manifest.loc[cid, ["split", "start"]])


@pytest.mark.parametrize("name", list(SCENARIOS))
def test_clean_variant_is_linear_in_the_sensors(name):
    """clean=true: the errors are a linear map of the measured rises plus white noise, nothing else."""
    gen = small(name, clean=True)
    ds, truth = gen.generate()
    assert truth["clean"] is True and truth["undeclared_effects"] == []
    sensors = ds.columns_of("T_")
    targets = ds.columns_of("E_")
    period = getattr(gen, "error_period_s", None) or 1.0   # the probe samples (lathe: every 5 min)
    x, y, origin = [], [], {}
    for cid, frame in ds.campaigns.items():
        # Campaigns cut from one record (manifest column `record`) are rises from the record's start.
        record = ds.manifest.loc[cid, "record"] if "record" in ds.manifest else cid
        first = origin.setdefault(record, frame[sensors].iloc[0])
        measured = np.isclose(np.mod(frame["time"], period), 0.0)
        x.append((frame[sensors] - first).to_numpy()[measured])
        y.append(frame[targets].to_numpy()[measured])     # the law holds for the written errors
    x, y = np.vstack(x), np.vstack(y)
    coef, *_ = np.linalg.lstsq(x, y, rcond=None)
    residual = y - x @ coef
    assert np.all(np.sqrt((residual**2).mean(0)) < 1.15 * gen.error_noise_um)
    lag1 = [np.corrcoef(r[:-1], r[1:])[0, 1] for r in residual.T]
    assert np.all(np.abs(lag1) < 0.2)                                 # white
    with pytest.raises(ConfigError, match="clean"):
        small(name, clean=True, effects=["lag_node"]).generate()


# --- large_mill_week ---------------------------------------------------------------------------

def test_large_mill_rise_is_proportional_to_heater_power():
    """Same seed, heaters at 0, 450 and 900 W: the rise they cause doubles with their power."""
    runs = {}
    for power in (0.0, 450.0, 900.0):
        gen = small("large_mill_week", heater_power_W=power)
        ds, truth = gen.generate()
        runs[power] = (ds, gen.node_temperatures_["train_week"])
    nodes = ["column_side_low", "column_back_low", "column_upper_front", "bed_mid"]
    rise1 = runs[450.0][1][nodes] - runs[0.0][1][nodes]
    rise2 = runs[900.0][1][nodes] - runs[0.0][1][nodes]
    assert rise1["column_side_low"].max() > 1.0
    np.testing.assert_allclose(rise2.to_numpy(), 2 * rise1.to_numpy(), atol=1e-6)
    # The heaters sit on the column: the column sensors see far more than the table's.
    ds0, ds1 = runs[0.0][0], runs[450.0][0]
    diff = ds1.campaigns["train_week"] - ds0.campaigns["train_week"]
    assert diff.filter(like="T_col").max().mean() > 5 * diff.filter(like="T_table").max().mean()


def test_large_mill_layout_and_climate():
    ds, truth = small("large_mill_week").generate()
    temps = [c for c in ds.columns if c.startswith("T_")]
    groups = {g: sum(c.startswith(f"T_{g}") for c in temps) for g in ("table", "bed", "col", "ram", "amb")}
    assert groups == {"table": 10, "bed": 10, "col": 16, "ram": 12, "amb": 4}
    assert [c for c in ds.columns if c.startswith("E_")] == ["E_X", "E_Y", "E_Z"]
    train, test = ds.campaigns["train_week"], ds.campaigns["validation_week"]
    assert np.all(np.diff(train["time"]) == 60.0)
    air = {k: f.filter(like="T_amb").mean(axis=1) for k, f in (("train", train), ("test", test))}
    assert air["test"].mean() > air["train"].mean() + 1.5          # June is warmer
    assert air["train"].max() - air["train"].min() > 5.0            # forced heating / cooling


# --- swiss_lathe_door ----------------------------------------------------------------------------

def test_lathe_door_shifts_the_error_within_minutes():
    """Same seed with and without door openings: ten minutes into an opening X has moved by µm."""
    kw = dict(error_period_s=60.0)
    with_door = small("swiss_lathe_door", **kw)
    ds, truth = with_door.generate()
    closed, _ = small("swiss_lathe_door", effect_params={"door": {"rate_per_h": 0.0}}, **kw).generate()
    openings = truth["campaigns"]["calibration"]["effects"]["door"]["openings_s"]
    assert len(openings) >= 2
    a, b = ds.campaigns["calibration"], closed.campaigns["calibration"]
    shifts = []
    for start, end in openings:
        if end - start >= 600.0:
            k = int(start // 60)
            shifts.append((a["E_X"] - b["E_X"]).iloc[k + 10] - (a["E_X"] - b["E_X"]).iloc[k])
    assert shifts and np.median(np.abs(shifts)) > 1.0
    assert truth["undeclared_effects"][0]["name"] == "door"      # built in and declared nowhere


def test_lathe_layout_holds_five_minute_errors_and_reads_without_repair(tmp_path):
    ds, truth = small("swiss_lathe_door").generate()
    frame = ds.campaigns["calibration"]
    assert np.all(np.diff(frame["time"]) == 60.0) and set(frame["S_door"]) <= {0.0, 1.0}
    assert {"S_spindle_rpm", "S_tool_rpm", "S_door"} <= set(frame.columns)
    assert sum(c.startswith("T_nc_") for c in frame.columns) == 5 and len(ds.columns_of("T_")) == 12
    blocks = frame["E_X"].to_numpy().reshape(-1)[: len(frame) // 5 * 5].reshape(-1, 5)
    assert np.all(blocks == blocks[:, :1])                        # one probe reading per 5 min
    back, report = read_dataset(write_dataset(ds, tmp_path / "hold"))
    assert back.ids() == ds.ids()
    empty, _ = small("swiss_lathe_door", error_gaps="nan").generate()
    path = write_dataset(empty, tmp_path / "nan")
    assert empty.campaigns["calibration"]["E_X"].isna().sum() > 0
    # read as the probe cycle it is (sparse61): the readings kept, nothing interpolated ...
    read, report = read_dataset(path)
    probe = read.campaigns["production"]["E_X"]
    assert probe.notna().sum() * 4 < len(probe) and report["sparse_targets"]
    # ... or, the reading told not to (data.sparse_targets=false), its gaps interpolated
    read, report = read_dataset(path, {"max_gap_samples": 4, "sparse_targets": False})
    assert not read.campaigns["production"].isna().any().any()


# --- column_moving_source --------------------------------------------------------------------

def test_moving_source_heats_where_the_axis_stands_and_rise_scales_with_heat():
    machine = machine_column()
    network = machine.network
    times = np.arange(0.0, 8 * 3600 + 1, 100.0)
    ambient = np.full(len(times), 20.0)
    hot = {}
    for z in (250.0, 2250.0):
        states = {POSITION: np.full(len(times), z), Q2: np.ones(len(times))}
        temps = integrate(machine, np.full(network.n_nodes, 20.0), times, ambient, states)
        hot[z] = temps[-1] - 20.0
    low, high = network.index["front_1"], network.index[f"front_{LEVELS}"]
    assert hot[250.0][low] > 2 * hot[250.0][high] and hot[2250.0][high] > 2 * hot[2250.0][low]
    # Steady state: twice the heat, twice the rise.
    q = machine.injector.heat({POSITION: 1000.0, Q2: 1.0}, np.full(network.n_nodes, 20.0))
    rise = network.steady_state(20.0, q) - 20.0
    np.testing.assert_allclose(network.steady_state(20.0, 2 * q) - 20.0, 2 * rise)


def test_third_source_only_in_the_test_half():
    gen = small("column_moving_source")
    ds, truth = gen.generate()
    assert truth["campaigns"]["train_cycle"]["q3_on_s"] == [] and truth["campaigns"]["test_cycle"]["q3_on_s"]
    assert truth["novel_sources"][0]["split"] == "test"
    q3 = truth["novel_sources"][0]["node"]
    rise = {cid: truth["campaigns"][cid]["node_max_rise_c"][q3] for cid in ds.ids()}
    assert rise["test_cycle"] > rise["train_cycle"] + 2.0
    frame = ds.campaigns["test_cycle"]
    assert frame[POSITION].between(250.0, 2250.0).all() and frame[POSITION].nunique() > 20


# --- climate_room ------------------------------------------------------------------------------

def test_climate_room_is_issue_34s_layout_split_last_in_time():
    """43 runs of 8-10 h at 1 min, 12 sensors with T_amb, E_X and E_Z; the last 4 (10 %) are test."""
    ds, truth = SCENARIOS["climate_room"](seed=7).generate()
    ids = ds.ids()
    assert ids == [f"C{k:02d}" for k in range(1, 44)]
    assert list(ds.manifest.loc[ids, "start"]) == sorted(ds.manifest["start"])
    assert ds.ids("test") == ["C40", "C41", "C42", "C43"] and len(ds.ids("train")) == 39
    rows = [len(f) for f in ds.campaigns.values()]
    assert min(rows) >= 481 and max(rows) <= 601
    frame = ds.campaigns["C01"]
    assert np.all(np.diff(frame["time"]) == 60.0)
    assert ds.columns_of("E_") == ["E_X", "E_Z"] and len(ds.columns_of("T_")) == 12 and "T_amb" in frame
    assert {"S_spindle_rpm", "S_tool_rpm"} <= set(frame.columns)
    duty = ds.manifest["duty"]
    assert duty.min() >= 0.3 and duty.max() <= 1.0 and duty.max() - duty.min() > 0.4


def test_climate_room_runs_start_soaked_at_their_own_held_or_ramped_level():
    """Every node starts at the room's air (soaked); the levels span 15-35 °C; ramped runs move the
    air by ramp_c over the run, held ones stay; the manifest's ambient_c is T_amb's first reading."""
    gen = small("climate_room", n_runs=12, ramp_fraction=0.5)
    ds, truth = gen.generate()
    levels, ramps = [], []
    for cid, frame in ds.campaigns.items():
        run = truth["campaigns"][cid]
        nodes = gen.node_temperatures_[cid].drop(columns=["ambient", "S_spindle_rpm", "S_tool_rpm",
                                                          "_axes_moving"])
        np.testing.assert_allclose(nodes.iloc[0], run["ambient_start_c"], atol=0.2)
        assert abs(run["ambient_start_c"] - run["room_c"]) < 0.2
        assert ds.manifest.loc[cid, "ambient_c"] == round(frame["T_amb"].iloc[0], 2)
        assert abs(frame["T_amb"].iloc[0] - run["room_c"]) < 0.3
        moved = gen.node_temperatures_[cid]["ambient"].iloc[-1] - run["ambient_start_c"]
        # the room lags its setpoint (0.3 h, and a 10-min staircase): 2.5 K/h here, ~0.3 h behind
        assert abs(moved - run["ramp_c"]) < (1.5 if run["ramp_c"] else 0.3)
        levels.append(run["room_c"])
        ramps.append(run["ramp_c"])
        assert 15.0 <= run["room_c"] + run["ramp_c"] <= 35.0
    assert min(levels) >= 15.0 and max(levels) <= 35.0 and max(levels) - min(levels) > 10.0
    assert {abs(r) for r in ramps} == {0.0, 5.0}


def test_climate_room_the_same_heat_moves_the_tool_less_in_a_warmer_room():
    """Same seed, the room held at 15 or at 35 °C: the same rises (a linear network, soaked start),
    but the errors are smaller at 35 °C by the sensitivities' fall with the level (beta)."""
    cold, _ = small("climate_room", level_c=(15.0, 15.0), ramp_fraction=0.0).generate()
    warm, _ = small("climate_room", level_c=(35.0, 35.0), ramp_fraction=0.0).generate()
    for cid in cold.ids():
        a, b = cold.campaigns[cid], warm.campaigns[cid]
        rise_a = a.filter(like="T_") - a.filter(like="T_").iloc[0]
        rise_b = b.filter(like="T_") - b.filter(like="T_").iloc[0]
        np.testing.assert_allclose(rise_a, rise_b, atol=0.03)
    errors = {room: pd.concat([ds.campaigns[c][["E_X", "E_Z"]] for c in ds.ids()]) for room, ds in
              (("cold", cold), ("warm", warm))}
    ratio = np.sqrt((errors["warm"] ** 2).mean() / (errors["cold"] ** 2).mean())
    assert errors["cold"].abs().max().min() > 10.0
    assert ratio["E_X"] < 0.8 and ratio["E_Z"] < 0.7       # 1 - 15 beta against 1 + 5 beta
