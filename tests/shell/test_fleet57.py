"""A fleet as a lab has it (vol57): a machine of the folder without a train (or test) campaign
is refused before any machine is fitted, naming that machine, not "the dataset"."""

from __future__ import annotations

import pandas as pd
import pytest

from conftest import LIGHT, refused
from thermocomp.apps.sim.fleet import Fleet

TINY = dict(n_machines=3, days=3, test_days=1, n_sensors=5, sample_period_s=600.0, n_jobs=1, seed=5)


@pytest.fixture(scope="module")
def fleet(tmp_path_factory):
    path = tmp_path_factory.mktemp("fleet57") / "fleet"
    Fleet(**TINY).write(path)
    return path


def _without(path, machine: str, split: str):
    """``path``'s manifest less ``machine``'s campaigns of ``split`` (the files stay)."""
    manifest = pd.read_csv(path / "campaigns.csv")
    keep = ~((manifest["machine"] == machine) & (manifest["split"] == split))
    manifest[keep].to_csv(path / "campaigns.csv", index=False)


@pytest.mark.parametrize("split", ["train", "test"])
def test_a_machine_without_a_split_is_named_before_any_machine_is_fitted(fleet, tmp_path, capsys,
                                                                       split):
    import shutil

    path = shutil.copytree(fleet, tmp_path / "fleet")
    _without(path, "M002", split)
    out = tmp_path / "out"
    line = refused(["run", f"data.path={path}", "data.group_by=machine", "track=false",
                    "eval.validation=false", *LIGHT, f"out={out}"], capsys,
                   "machine 'M002'", f"no '{split}' campaign", "campaigns.csv")
    assert "M002-D0" in line                       # its campaigns, with their splits
    assert not out.exists()


def test_a_fraction_held_out_of_the_whole_folder_is_what_each_machine_is_checked_on(fleet, tmp_path):
    """``data.test_fraction`` on a manifest without test campaigns: the whole folder's last
    campaigns are held out (here the last day of each machine), so every machine has both."""
    import json
    import shutil

    from thermocomp.shell.cli import main

    path = shutil.copytree(fleet, tmp_path / "fleet")
    manifest = pd.read_csv(path / "campaigns.csv")
    manifest["split"] = "train"
    manifest.to_csv(path / "campaigns.csv", index=False)
    out = tmp_path / "out"
    assert main(["run", f"data.path={path}", "data.group_by=machine", "data.test_fraction=0.34",
                 "data.reference=first_sample", "track=false", "eval.validation=false", *LIGHT,
                 f"out={out}"]) == 0
    assert sorted(json.loads((out / "metrics.json").read_text())["groups"]) == ["M001", "M002", "M003"]


def test_promote_of_a_fleets_run_says_it_is_one_and_where_its_models_are(fleet, tmp_path, capsys):
    """A fleet's run logs no model.pkl (one model per machine, in its out): promote named an
    MLflow download failure and told to "promote a `run` run", which it was."""
    import mlflow

    from thermocomp.shell.cli import main

    uri = f"sqlite:///{tmp_path / 'mlflow.db'}"
    out = tmp_path / "out"
    assert main(["run", f"data.path={fleet}", "data.group_by=machine", "data.reference=first_sample",
                 f"tracking_uri={uri}", "eval.validation=false", *LIGHT, f"out={out}"]) == 0
    client = mlflow.tracking.MlflowClient(uri)
    (run,) = client.search_runs([e.experiment_id for e in client.search_experiments()])
    assert (out / "models" / "M001.pkl").is_file()
    refused(["promote", f"data.path={fleet}", f"tracking_uri={uri}",
             f"promote.run_id={run.info.run_id}", f"out={tmp_path / 'p'}"], capsys,
            "is a fleet's run (data.group_by=machine)", "models/<machine>.pkl", "replay.model=")


def test_the_fleet_table_stays_aligned_under_a_labs_long_target_names():
    """``E_Displacement_X`` (a lab's header through init) pushed every row 8 columns right of
    the header; the first column is now as wide as the longest target."""
    from thermocomp.apps.fleet import TEST_RMS_AFTER, TEST_RMS_BEFORE, TEST_RMSE, table_text

    stats = {"mean": 1.0, "median": 1.0, "p95": 1.0, "max": 1.0}
    row = {"groups": 3, TEST_RMSE: stats, TEST_RMS_BEFORE: stats, TEST_RMS_AFTER: stats,
           "worst_group": "M001"}
    metrics = {"model": "mlr", "mode": "simulation", "dataset": "lab", "group_by": "machine",
               "groups": {"M001": {}}, "fleet": {"E_Displacement_X": row, "E_Z": row}}
    lines = table_text(metrics).splitlines()
    end = lines[1].index("groups") + len("groups")
    for line in lines[3:]:
        assert line[end - 1] == "3" and line[end] == " ", line


def test_init_on_a_fleet_folder_names_the_machine_column_and_group_by(fleet, capsys, tmp_path):
    """init wrote a config that pools every machine into one model and said nothing of the
    manifest's machine column; a folder whose manifest groups nothing says nothing more."""
    from thermocomp.shell.cli import main

    assert main(["init", str(fleet), f"out={tmp_path / 'i1'}"]) == 0
    out = capsys.readouterr().out
    assert "manifest column 'machine': 3 groups of campaigns (M001, M002, M003)" in out
    assert "data.group_by=machine" in out.strip().splitlines()[-1]
    single = tmp_path / "one"
    single.mkdir()
    manifest = pd.read_csv(fleet / "campaigns.csv")
    manifest = manifest[manifest["machine"] == "M001"]
    manifest.to_csv(single / "campaigns.csv", index=False)
    import shutil

    shutil.copytree(fleet / "machine=M001", single / "machine=M001")
    assert main(["init", str(single), f"out={tmp_path / 'i2'}"]) == 0
    assert "group_by" not in capsys.readouterr().out


def test_a_hammerstein_without_states_is_said_per_machine(fleet, tmp_path):
    """A fleet whose records have no S_ column: each machine's hammerstein is its plain lag
    bank, said once per machine on stderr and in the group's metrics.json entry (frames62 said
    it for a single run only)."""
    import json
    import shutil

    from conftest import thermocomp

    path = shutil.copytree(fleet, tmp_path / "fleet")
    for f in path.glob("machine=*/*.parquet"):
        df = pd.read_parquet(f)
        df.drop(columns=[c for c in df.columns if c.startswith("S_")]).to_parquet(f, index=False)
    out = tmp_path / "out"
    run = thermocomp("run", f"data.path={path}", "data.group_by=machine", "model=hammerstein",
                     "track=false", "eval.validation=false", *LIGHT, f"out={out}")
    said = [line for line in run.stderr.splitlines() if "model=hammerstein:" in line]
    machines = {line.split("warning: ")[1].split(":")[0]: line for line in said}
    assert sorted(machines) == ["M001", "M002", "M003"] and len(said) == 3
    groups = json.loads((out / "metrics.json").read_text())["groups"]
    for machine, line in machines.items():
        assert len(groups[machine]["warnings"]) == 1 and line.endswith(groups[machine]["warnings"][0])


def test_a_named_input_one_machine_lacks_is_said_for_that_machine(fleet, tmp_path):
    """``data.inputs=[<one sensor>, T_*]`` on a fleet where one machine lacks that sensor: that
    machine was fitted without it in silence (volfleet63); now said for it alone, on stderr and
    in its metrics.json entry. A pattern matching nothing of a machine is not said."""
    import json
    import shutil

    from conftest import thermocomp

    path = shutil.copytree(fleet, tmp_path / "fleet")
    sensor = next(c for c in pd.read_parquet(next(path.glob("machine=M002/*.parquet"))).columns
                  if c.startswith("T_") and not c.startswith("T_amb"))
    for f in path.glob("machine=M002/*.parquet"):
        pd.read_parquet(f).drop(columns=[sensor]).to_parquet(f, index=False)
    out = tmp_path / "out"
    run = thermocomp("run", f"data.path={path}", "data.group_by=machine",
                     f"data.inputs=[{sensor},'T_*','X_*']", "track=false", "eval.validation=false",
                     *LIGHT, f"out={out}")
    said = [line for line in run.stderr.splitlines() if "data.inputs names" in line]
    assert len(said) == 1 and "M002" in said[0] and sensor in said[0] and "X_" not in said[0]
    groups = json.loads((out / "metrics.json").read_text())["groups"]
    assert [m for m, g in groups.items() if g.get("warnings")] == ["M002"]


def test_a_named_input_the_data_lack_is_said_by_a_single_run(tmp_path):
    from conftest import thermocomp
    from test_deploy import LIGHT_EVAL, write_small_dataset

    data = write_small_dataset(tmp_path / "small")
    run = thermocomp("run", f"data.path={data}", "data.inputs=[T_nowhere,'T_*']", "track=false",
                     *LIGHT_EVAL, "eval.validation=false", f"out={tmp_path / 'run'}")
    assert any("data.inputs names T_nowhere" in line for line in run.stderr.splitlines())
