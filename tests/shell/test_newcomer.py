"""What a newcomer tripped on (issue 35, item 9), each with the behaviour that fixes it."""

from __future__ import annotations

import json
import re

import pandas as pd
import pytest

from conftest import refused, thermocomp
from test_deploy import LIGHT_EVAL, mlflow_store, write_small_dataset
from test_hostile import FAST, make_dataset
from thermocomp.shell.cli import main

COMPARED = ("compare.csv", "compare.md", "compare.json")


@pytest.fixture(scope="module")
def sweep(tmp_path_factory):
    """``(tracking uri, sweep folder, parent run id)`` of a two-job sweep on 2 h campaigns (no
    test campaign lasts 8 h: the table's ``e_p95_8h`` has no figure in any row)."""
    root = tmp_path_factory.mktemp("newcomer_sweep")
    data = write_small_dataset(root / "small")
    uri = mlflow_store(root)
    folder = root / "sweep"
    thermocomp("run", "-m", f"data.path={data}", f"tracking_uri={uri}", *LIGHT_EVAL,
               f"hydra.sweep.dir={folder}", "model.estimator.fit_intercept=true,false")
    return uri, folder, json.loads((folder / "sweep.json").read_text())["parent_run_id"]


def _compare(sweep, capsys, *extra: str) -> str:
    uri, folder, parent = sweep
    for name in COMPARED:               # the tables the sweep's end wrote there
        (folder / name).unlink(missing_ok=True)
    capsys.readouterr()
    assert main(["compare", f"tracking_uri={uri}", f"compare.sweep={parent}", *extra]) == 0
    return capsys.readouterr().out


def test_standalone_compare_writes_beside_the_sweep_it_reads(sweep, capsys, tmp_path):
    # it wrote reports/compare/ of the project, whichever sweep it read
    uri, folder, parent = sweep
    _compare(sweep, capsys)                                   # a run id: the folder it recorded
    assert all((folder / name).is_file() for name in COMPARED)
    assert json.loads((folder / "compare.json").read_text())["parent_run_id"] == parent
    _compare(sweep, capsys, f"compare.out={tmp_path / 'mine'}")     # out= still wins
    assert all((tmp_path / "mine" / name).is_file() for name in COMPARED)
    assert not any((folder / name).exists() for name in COMPARED)


def test_the_printed_compare_table_fits_the_terminal_without_empty_columns(sweep, capsys,
                                                                             monkeypatch, tmp_path):
    # ~290 characters a line, with a test:e_p95_8h column of n/a alone
    monkeypatch.setenv("COLUMNS", "100")
    folder = tmp_path / "cmp"
    out = _compare(sweep, capsys, f"compare.out={folder}")
    rows = [line for line in out.splitlines() if line.startswith("|")]
    assert rows and max(map(len, rows)) <= 100
    for column in ("val_rmse", "test:rsd_mean", "test:rmse", "test:e_p95_1h", "fit_time_s"):
        assert column in out                                  # every figure there is, in blocks
    assert "e_p95_8h" not in out and "e_p95_8h" not in (folder / "compare.md").read_text()
    csv = pd.read_csv(folder / "compare.csv")
    assert csv["e_p95_8h"].isna().all() and csv["e_p95_1h"].notna().all()   # the CSV keeps all


def test_the_persistence_row_says_it_needs_the_measured_error_online(sweep, capsys, tmp_path):
    folder = tmp_path / "cmp"
    out = _compare(sweep, capsys, f"compare.out={folder}")
    last = (folder / "compare.md").read_text().strip().splitlines()[-1]
    assert "persistence (baseline): needs measured error online" in last
    assert "persistence (baseline): needs measured error online" in out
    (baseline,) = json.loads((folder / "compare.json").read_text())["baselines"]
    assert baseline["needs_measured_error_online"] is True


def test_the_readme_says_how_to_reach_the_command_before_it_first_names_it_bare():
    # the prose said `thermocomp ...` where only .venv/bin/thermocomp exists
    from conftest import ROOT

    readme = (ROOT / "README.md").read_text()
    first_bare = re.search(r"`thermocomp (?:simulate|run)", readme).start()   # as prose says it
    activate = readme.find("source .venv/bin/activate")
    assert 0 <= activate < first_bare
    assert ".venv/bin/thermocomp" in readme[:activate]


def test_run_on_a_volumetric_dataset_prints_its_headline(tmp_path, capsys):
    # a 22-row parameter table, and not a word of the distances, the VCE or the A.3 range
    from conftest import simulated
    from thermocomp.apps.sim.volumetric import LargeMillVolumetric

    raw = simulated(LargeMillVolumetric(train_hours=12.0, test_hours=16.0, seed=3), tmp_path / "raw")
    capsys.readouterr()
    assert main(["run", "experiment=volumetric_large_mill", f"data.path={raw}", f"out={tmp_path / 'o'}",
                 "track=false", "plots=none", "eval.validation=false", "eval.mutual_prediction=false",
                 "eval.ati_baselines=false"]) == 0
    out = capsys.readouterr().out
    vol = json.loads((tmp_path / "o" / "metrics.json").read_text())["volumetric"]
    shown = {line.split("  ")[0]: line for line in out.splitlines()}
    for label, block, before, after in [
            ("distance errors", vol["distance_error"], "rms_before", "rms_after"),
            ("VCE on a 20 x 8 x 8 grid (against the simulated machine)", vol["vce"], "rms_before",
             "rms_after"),
            ("VCE against the identified parameters", vol["vce_identified"], "rms_before", "rms_after"),
            ("ISO 10791-10 A.3, Z on the table: mean slot range", vol["iso_a3"], "range_before",
             "range_after")]:
        assert f"{block[before]:.2f} -> {block[after]:>6.2f}" in shown[label]


def test_a_changed_generator_never_replaces_the_default_dataset(tmp_path, monkeypatch, capsys):
    # `simulate sim=yearround_spindle "sim.generator.effects=[door,lag_node]"` replaced the
    # dataset behind `make run` and the champion, exit 0
    import shutil

    from conftest import ROOT

    shutil.copytree(ROOT / "conf", tmp_path / "conf")
    scenario = tmp_path / "conf" / "sim" / "yearround_spindle.yaml"      # a short default
    scenario.write_text(scenario.read_text().replace("n_campaigns: 24 ", "n_campaigns: 3 "))
    monkeypatch.setenv("THERMOCOMP_ROOT", str(tmp_path))
    default = tmp_path / "data" / "raw" / "yearround_spindle"
    assert main(["simulate", "track=false"]) == 0
    made = {f.name: f.read_bytes() for f in default.iterdir()}
    door = ["sim.generator.effects=[door,lag_node]"]
    capsys.readouterr()
    assert main(["simulate", "track=false", *door]) == 0
    err = capsys.readouterr().err
    assert {f.name: f.read_bytes() for f in default.iterdir()} == made       # untouched
    (apart,) = [p for p in default.parent.iterdir() if p.is_dir() and p != default]
    assert apart.name.startswith("yearround_spindle-") and f"to {apart} " in err
    truth = json.loads(apart.with_name(f"{apart.name}.truth.json").read_text())
    assert {e["name"] for e in truth["undeclared_effects"]} == {"door", "lag_node"}
    assert "S_door" in pd.read_csv(next(apart.glob("K*.csv"))).columns
    # the stages given the same overrides read it; without them, the default one
    for overrides, read in ((door, apart), ([], default)):
        assert main(["run", *overrides, f"out={tmp_path / 'o'}", *FAST]) == 0
        assert f"reading {read}\n" in capsys.readouterr().err


def test_design_shows_its_progress_and_marks_the_what_ifs_beyond_the_travel(tmp_path, capsys,
                                                                            monkeypatch):
    # ~40 s without a word, then a best position set whose every strategy puts a ball outside
    # the travel, recommended unmarked in the table, the findings and the figures
    from thermocomp.apps.volumetric import design_figures

    drawn = {}

    def keep(fig, path):
        drawn[path.name] = {t.get_text() for ax in fig.axes for t in ax.texts} | {
            t.get_text() for ax in fig.axes if ax.get_legend() for t in ax.get_legend().get_texts()}
        return real(fig, path)

    real = design_figures.save_figure
    monkeypatch.setattr(design_figures, "save_figure", keep)
    out = tmp_path / "d"
    assert main(["-v", "design", "track=false", "design.n_machines=3", "design.n_jobs=1",
                 "design.grid=[8,5,5]", "design.x_centres=[0.25,0.75]", f"out={out}",
                 "design.studies={balls:null,misalignment:{n_balls:[5],misalignment_deg:[0,80],"
                 "position_sets:[S2]},position_sets:{n_balls:[5],misalignment_deg:[80],"
                 "position_sets:[S2,S1]}}"]) == 0
    said = capsys.readouterr()
    # one bar over the 3 distinct strategies (S2 at 80° is in both studies); tqdm may skip
    # drawing the last count when it comes fast, so the total is what is checked
    assert re.search(r"design strategies: .*\d/3 ", said.err)
    report = json.loads((out / "design.json").read_text())
    rows = {(r["position_set"], r["misalignment_deg"]): r["reachable"] for r in report["strategies"]}
    assert rows == {("S2", 0.0): True, ("S2", 80.0): False, ("S1", 80.0): False}
    table = [line for line in said.out.splitlines() if line.startswith(("S1 ", "S2 "))]
    assert len(table) == 3
    for line in table:
        assert line.endswith("what-if") == (line.split()[2] == "80")
    best = report["findings"]["best_position_set"]
    assert best["reachable"] is False
    (line,) = [ln for ln in said.out.splitlines() if ln.startswith("best position set")]
    assert "what-if" in line
    label = design_figures.WHAT_IF_LABEL
    assert label in drawn["misalignment.png"] and label in drawn["position_sets.png"]
    assert f"{best['position_set']} (what-if)" in drawn["position_sets.png"]


def test_metrics_json_marks_persistence_as_needing_the_measured_error_online(tmp_path):
    from test_hostile import make_dataset

    data = make_dataset(tmp_path / "data")
    assert main(["run", f"data.path={data}", f"out={tmp_path / 'o'}", *FAST]) == 0
    targets = json.loads((tmp_path / "o" / "metrics.json").read_text())["targets"]
    for figures in targets.values():
        assert figures["persistence"]["needs_measured_error_online"] is True
        assert "needs_measured_error_online" not in figures["test"]        # the model's own: no


@pytest.mark.parametrize("command", [["compare"], ["promote", "promote.run_id=0123abcd"],
                                     ["serve", "serve.model=models:/m@champion"],
                                     ["export", "export.model=models:/m@champion"]],
                         ids=lambda c: c[0])
def test_a_command_that_reads_the_store_refuses_a_missing_one_and_creates_none(command, tmp_path,
                                                                                 capsys):
    # compare created and migrated a new mlflow.db (about 1 s) only to find no sweep in it,
    # and left the store (and its folder) behind
    data = make_dataset(tmp_path / "d")
    db = tmp_path / "store" / "mlflow.db"
    refused([*command, f"data.path={data}", f"tracking_uri=sqlite:///{db}",
             f"out={tmp_path / 'out'}", "plots=none"], capsys, "no store at", str(db))
    assert not db.parent.exists()
