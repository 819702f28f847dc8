"""`thermocomp diagnose` end to end: files, MLflow, exit codes, and the rerun of the diagnosed model."""

from __future__ import annotations

import json

import pytest

from conftest import LIGHT, PLAIN_DIAGNOSE, thermocomp

pytestmark = pytest.mark.slow

QUIET_EVAL = LIGHT


@pytest.fixture(scope="session")
def door(short_door_dataset, tmp_path_factory):
    """The diagnosis of E_Y on 9 short campaigns with a door (6 train: the acceptance test
    forward-chains over them, as the CLI says): files, MLflow and reruns do not depend on the
    size, and the default-size dataset cost ~2x the CPU in each of this module's diagnoses."""
    root, data = tmp_path_factory.mktemp("diag"), short_door_dataset
    out = root / "out"
    uri = f"sqlite:///{root / 'mlruns' / 'mlflow.db'}"
    proc = thermocomp("diagnose", f"data.path={data}", f"out={out}", f"tracking_uri={uri}",
                      "diagnose.targets=[E_Y]", *PLAIN_DIAGNOSE)
    return data, out, uri, proc


def test_diagnose_writes_the_contract_report_figures_and_a_rerunnable_config(door):
    data, out, _, proc = door
    j = json.loads((out / "diagnosis.json").read_text())
    assert j["target"] == "E_Y" and j["model"] == "mlr"
    assert json.loads((out / "diagnosis" / "diagnosis_E_Y.json").read_text())["target"] == "E_Y"
    top = next(e for e in j["effects"] if e["accepted"])
    assert (top["kind"], top["column"]) == ("signal", "S_door")
    folder = out / "diagnosis"
    for name in ("report.md", "report.html", "conf/model/diagnosed.yaml", "conf/experiment/diagnosed.yaml",
                 "plots/e_p95_E_Y.png", "plots/residual_vs_effect_E_Y_1.png"):
        assert (folder / name).is_file(), name
    assert "S_door" in (folder / "report.md").read_text()
    assert "<table>" in (folder / "report.html").read_text()
    assert "E_Y" in proc.stdout and "signal:S_door" in proc.stdout


def test_thermocomp_run_with_the_written_config_reproduces_the_after_figures(door, tmp_path):
    data, out, _, _ = door
    j = json.loads((out / "diagnosis.json").read_text())
    thermocomp("run", f"hydra.searchpath=[file://{out / 'diagnosis' / 'conf'}]", "experiment=diagnosed",
               f"data.path={data}", f"out={tmp_path}", "track=false", *QUIET_EVAL)
    metrics = json.loads((tmp_path / "metrics.json").read_text())
    assert metrics["model"] == "mlr+diagnosed"
    assert metrics["targets"]["E_Y"]["test"]["rmse"] == pytest.approx(j["after"]["test_rmse"], rel=1e-9)
    assert metrics["targets"]["E_Y"]["test"]["rsd_mean"] == pytest.approx(j["after"]["test_rsd_mean"],
                                                                           rel=1e-9)


def test_the_diagnosis_is_logged_to_mlflow(door):
    _, _, uri, _ = door
    from mlflow import MlflowClient

    client = MlflowClient(uri)
    exp = client.get_experiment_by_name("thermocomp")
    runs = client.search_runs([exp.experiment_id], filter_string="tags.stage = 'diagnose'")
    assert len(runs) == 1
    run = runs[0]
    metrics = run.data.metrics
    assert metrics["diagnose.E_Y.after_test_rmse"] < metrics["diagnose.E_Y.before_test_rmse"]
    names = {a.path for a in client.list_artifacts(run.info.run_id)}
    assert {"diagnosis.json", "diagnosis"} <= names
    assert "S_door" in run.data.tags["diagnose.accepted"]


def test_a_target_the_model_does_not_have_exits_2_with_one_line(door, tmp_path):
    data, _, _, _ = door
    proc = thermocomp("diagnose", f"data.path={data}", f"out={tmp_path}", "track=false",
                      "diagnose.targets=[E_Q]", check=False)
    assert proc.returncode == 2, proc.stderr
    lines = [line for line in proc.stderr.splitlines() if line.startswith("thermocomp: error")]
    assert len(lines) == 1 and "E_Q" in lines[0]
    assert not (tmp_path / "diagnosis.json").exists()


def test_one_step_scores_the_test_split_only_and_says_the_search_stays_in_simulation(tmp_path, capsys):
    from thermocomp.shell.cli import main
    data = tmp_path / "door"
    assert main(["simulate", f"data.path={data}", "track=false", "++sim.generator.effects=[door]",
                 "sim.generator.n_campaigns=12"]) == 0
    capsys.readouterr()
    runs = {}
    for mode in ("simulation", "one_step"):
        out = tmp_path / mode
        assert main(["diagnose", f"data.path={data}", f"out={out}", "track=false", "plots=none",
                     f"eval.mode={mode}", "diagnose.max_effects=1", "diagnose.targets=[E_Y]",
                     *PLAIN_DIAGNOSE]) == 0
        runs[mode] = (json.loads((out / "diagnosis.json").read_text()), capsys.readouterr())
    (sim, _), (one, said) = runs["simulation"], runs["one_step"]
    assert sim["cv"]["mode"] == one["cv"]["mode"] == "simulation" and one["mode"] == "one_step"
    assert one["before"]["cv_rmse"] == sim["before"]["cv_rmse"]          # the same search
    assert one["before"]["test_rmse"] != sim["before"]["test_rmse"]      # another test scoring
    assert "cross-validation (cv_rmse, the bar) stays in simulation mode" in said.err
    assert "(test; CV: simulation)" in said.out


def test_the_printed_rerun_reads_the_data_as_the_diagnosis_did(door, tmp_path):
    """A lab's ';'-separated files with decimal commas, read through the user's own data config:
    the rerun command diagnose prints carries that config (it gave only the written one, and
    the rerun exactly as printed was refused: 'campaigns.csv looks ;-separated')."""
    import shlex

    import pandas as pd

    data, out, _, _ = door
    lab = tmp_path / "lab"
    lab.mkdir()
    for f in data.iterdir():
        pd.read_csv(f).to_csv(lab / f.name, index=False, sep=";", decimal=",")
    conf = tmp_path / "myconf" / "data"
    conf.mkdir(parents=True)
    (conf / "lab.yaml").write_text('defaults:\n  - default\ndelimiter: ";"\ndecimal: ","\n')
    diag = tmp_path / "diag"
    thermocomp("diagnose", f"hydra.searchpath=[file://{tmp_path / 'myconf'}]", "data=lab",
               f"data.path={lab}", f"out={diag}", "track=false", "diagnose.targets=[E_Y]",
               "data.max_gap_samples=0", *PLAIN_DIAGNOSE)
    j = json.loads((diag / "diagnosis.json").read_text())
    words = shlex.split(j["rerun"])
    assert words[:2] == ["thermocomp", "run"] and "data=lab" in words
    assert "data.max_gap_samples=0" in words
    thermocomp(*words[1:], "track=false", *QUIET_EVAL)
    metrics = json.loads((diag / "diagnosed" / "metrics.json").read_text())
    assert metrics["targets"]["E_Y"]["test"]["rmse"] == pytest.approx(j["after"]["test_rmse"], rel=1e-9)
