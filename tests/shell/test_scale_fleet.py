"""A fleet dataset: simulated machines as Parquet partitions, `run data.group_by=machine` fits one
model per machine from that machine's campaigns only, and sums up the fleet."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from conftest import LIGHT, refused
from thermocomp.apps.fleet import groups
from thermocomp.apps.sim.fleet import Fleet
from thermocomp.base.signing import load
from thermocomp.core import io
from thermocomp.shell.cli import main

TINY = dict(n_machines=3, days=4, test_days=1, n_sensors=8, sample_period_s=300.0, n_jobs=2, seed=3)


@pytest.fixture(scope="session")
def fleet(tmp_path_factory):
    path = tmp_path_factory.mktemp("fleet") / "fleet"
    truth = Fleet(**TINY).write(path)
    return path, truth


def test_the_fleet_is_a_contract_dataset_of_partitions(fleet):
    path, truth = fleet
    manifest = io.read_manifest(path)
    assert len(manifest) == 12 and truth["campaigns"] == 12 and truth["rows"] == 12 * 288
    assert sorted(manifest["machine"].unique()) == ["M001", "M002", "M003"]
    assert (path / "machine=M002" / "day=03.parquet").is_file()
    assert list(manifest.loc[manifest["machine"] == "M001", "split"]) == ["train"] * 3 + ["test"]
    ds, _ = io.read_dataset(path, campaigns=list(manifest.index[manifest["machine"] == "M003"]))
    assert set(ds.campaigns) == {"M003-D01", "M003-D02", "M003-D03", "M003-D04"}
    day = ds.campaigns["M003-D02"]
    assert len(day) == 288 and day["time"].iloc[0] == 0
    assert len(ds.columns_of("T_")) == 8 and {"E_X", "E_Y", "E_Z", "S_spindle_rpm"} <= set(day)
    # machines differ (own network, gains, hall), one seed gives the same fleet
    gains = [truth["machines"][m]["gains_um_per_K"]["E_Z"]["column_core"] for m in ("M001", "M002", "M003")]
    assert len(set(gains)) == 3
    again, _ = Fleet(**{**TINY, "n_machines": 1}).machine(2)
    pd.testing.assert_frame_equal(again["D02"], day, check_exact=False, atol=1e-9)


def test_run_fits_one_model_per_machine_on_its_own_campaigns(fleet, tmp_path):
    path, _ = fleet
    out = tmp_path / "out"
    # each day zeroed at its first sample, as the fleet scenario says (its days continue each
    # other, so data.reference=auto would read them absolute)
    assert main(["run", f"data.path={path}", "data.group_by=machine", "data.group_jobs=2",
                 "data.reference=first_sample", "track=false", *LIGHT, f"out={out}"]) == 0
    metrics = json.loads((out / "metrics.json").read_text())
    assert sorted(metrics["groups"]) == ["M001", "M002", "M003"] and metrics["group_by"] == "machine"
    table = pd.read_csv(out / "fleet.csv")
    assert len(table) == 9 and set(table["target"]) == {"E_X", "E_Y", "E_Z"}
    for t, s in metrics["fleet"].items():
        rmse = table.loc[table["target"] == t, "test_rmse"]
        assert s["test_rmse"]["max"] == pytest.approx(rmse.max())
        assert s["test_rmse"]["mean"] == pytest.approx(rmse.mean())
        assert s["test_rms_after"]["mean"] < s["test_rms_before"]["mean"]   # compensation helps
    # M002's model is the one fitted on M002's train days alone
    ds, _ = io.read_dataset(path)
    m2 = ds.subset([c for c in ds.ids() if c.startswith("M002")])
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models.linear import MLR

    model = load(out / "models" / "M002.pkl", Compensator)
    test = {c: m2.campaigns[c] for c in m2.ids("test")}
    pred = model.predict(test, "simulation")
    alone = Compensator(MLR(), inputs=["T_*"]).fit({c: m2.campaigns[c] for c in m2.ids("train")})
    ref = alone.predict(test, "simulation")
    for c in test:
        np.testing.assert_allclose(pred[c]["E_Z"], ref[c]["E_Z"], atol=1e-9)
    assert metrics["groups"]["M002"]["campaigns"] == 4
    # CLI.md's `targets`: the whole fleet as one split, each campaign predicted by its machine's
    # model (recomputed here from the saved models)
    residual = {}
    for m in ("M001", "M002", "M003"):
        model = load(out / "models" / f"{m}.pkl", Compensator)
        test = {c: ds.campaigns[c] for c in ds.ids("test") if c.startswith(m)}
        pred, meas = model.predict(test, "simulation"), model.measured(test)
        residual.update({c: meas[c]["E_Z"].to_numpy() - pred[c]["E_Z"].to_numpy() for c in test})
    pooled = metrics["targets"]["E_Z"]
    assert set(pooled["test"]["per_campaign"]) == set(residual) == set(ds.ids("test"))
    pooled_rmse = np.sqrt(np.mean(np.concatenate(list(residual.values())) ** 2))
    assert pooled["test"]["rmse"] == pytest.approx(pooled_rmse)
    for c, r in residual.items():
        assert pooled["test"]["per_campaign"][c]["rmse"] == pytest.approx(np.sqrt(np.mean(r ** 2)))
    assert len(pooled["test"]["e_p95"]["window_s"]) == len(pooled["test"]["e_p95"]["after"]) > 1
    assert {"rmse", "rsd_mean", "rsd_sd"} <= set(pooled["train"]) and pooled["train"]["rsd_sd"] > 0


def test_group_by_refuses_an_unknown_column_and_empty_cells(fleet, tmp_path, capsys):
    path, _ = fleet
    refused(["run", f"data.path={path}", "data.group_by=site", "track=false", f"out={tmp_path / 'o'}"],
            capsys, "data.group_by='site'", "campaigns.csv")
    assert not (tmp_path / "o").exists()
    manifest = pd.DataFrame({"split": ["train", "test"], "machine": ["A", None]},
                            index=pd.Index(["a", "b"], name="campaign"))
    with pytest.raises(io.ContractError, match="row 2"):
        groups(manifest, "machine")


def test_simulate_sim_fleet_streams_the_partitions_then_run_reads_them_by_machine(tmp_path):
    from hydra import compose, initialize_config_dir
    from hydra.utils import instantiate

    from thermocomp.base.paths import conf_dir

    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose("config", ["sim=fleet"])
    assert cfg.data.group_by == "machine" and cfg.sim.generator.n_machines == 100
    assert isinstance(instantiate(cfg.sim.generator), Fleet)
    data = tmp_path / "fleet"
    small = [f"sim.generator.{k}={v}" for k, v in TINY.items() if k != "seed"]
    assert main(["simulate", "sim=fleet", *small, "sim.generator.n_machines=2", f"data.path={data}",
                 "track=false"]) == 0
    truth = json.loads((tmp_path / "fleet.truth.json").read_text())
    assert sorted(truth["machines"]) == ["M001", "M002"] and truth["campaigns"] == 8
    assert main(["run", "sim=fleet", f"data.path={data}", "track=false", f"out={tmp_path / 'out'}",
                 "eval.validation=false"]) == 0
    metrics = json.loads((tmp_path / "out" / "metrics.json").read_text())
    assert sorted(metrics["groups"]) == ["M001", "M002"]
    assert all(g["targets"]["E_Z"]["validation"] is None for g in metrics["groups"].values())


def test_each_group_resolves_data_reference_auto_for_itself(fleet, tmp_path):
    from hydra import compose, initialize_config_dir

    from thermocomp.base.paths import conf_dir
    from thermocomp.shell.stages.fleet import _group

    path, _ = fleet
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose("config", overrides=[f"data.path={path}", "data.group_by=machine",
                                           "track=false", "eval.validation=false"])
    ds, _ = io.read_dataset(path)
    for machine in ("M001", "M002"):
        _group(cfg, path, machine, [c for c in ds.ids() if c.startswith(machine)], tmp_path)
        # the next group (same process, data.group_jobs=1) still sees auto, not this one's answer
        assert cfg.data.reference == "auto"
