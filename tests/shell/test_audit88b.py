"""audit88's leftovers (audit88b; ``benchmarks/bench_audit88b.py`` lists every finding): a
relative ``hydra.searchpath`` read from the project root as every relative path thermocomp
takes, and the outputs a user opens after a run against what the docs say of them."""

from __future__ import annotations

import json

import pytest
import yaml

from conftest import ROOT
from thermocomp.shell.cli import main


def test_a_relative_searchpath_is_read_from_the_project_root_from_any_folder(tmp_path, monkeypatch, capsys):
    # Hydra read `file://conf_lab` from the current folder: typed in a subfolder of the project,
    # "unknown data 'lab'" (exit 2), where data.path, out and hydra.sweep.dir are the root's
    project = tmp_path / "project"
    (project / "conf_lab" / "data").mkdir(parents=True)
    (project / "conf").symlink_to(ROOT / "conf")
    (project / "conf_lab" / "data" / "lab.yaml").write_text(
        "defaults:\n  - default\n  - _self_\nsample_period_s: 17\n")
    (project / "sub").mkdir()
    monkeypatch.setenv("THERMOCOMP_ROOT", str(project))
    monkeypatch.chdir(project / "sub")
    assert main(["run", "hydra.searchpath=[file://conf_lab]", "data=lab",
                 "--cfg", "job", "--package", "data"]) == 0
    printed = yaml.safe_load(capsys.readouterr().out.split("\n", 1)[1])   # after "# @package data"
    assert printed["sample_period_s"] == 17


# -- the outputs a user opens after a run, against docs/cli.md ("every command, override group,
# output file and key")

CLI = (ROOT / "docs" / "cli.md").read_text()


def _section(start: str, end: str) -> str:
    return CLI[CLI.index(start):CLI.index(end, CLI.index(start))]


def _keys(node, campaigns: set[str], targets: set[str]) -> set[str]:
    """Every key of a JSON document but the names of its campaigns and targets (data, not keys)."""
    if not isinstance(node, dict):
        return set()
    out = set()
    for key, value in node.items():
        if key not in campaigns and key not in targets:
            out.add(key)
        out |= _keys(value, campaigns, targets)
    return out


@pytest.fixture(scope="module")
def run_out(short_dataset, tmp_path_factory):
    """The folder of a `run` on the short record, every report but the figures."""
    from conftest import UNTRACKED, thermocomp

    out = tmp_path_factory.mktemp("audit88b") / "out"
    thermocomp("run", f"data.path={short_dataset}", f"out={out}", *UNTRACKED, "plots=none")
    return out


def test_every_key_of_a_runs_metrics_json_is_named_in_the_cli_reference(run_out):
    # written and not listed: ati's improvement_pct sm_vs_warmest / sd_vs_warmest (the list
    # ended in "…")
    out = run_out
    metrics = json.loads((out / "metrics.json").read_text())
    campaigns = set(json.loads((out / "ingest_report.json").read_text())["campaigns"])
    keys = _keys(metrics, campaigns, set(metrics["targets"]))
    assert {"max_models", "sm_vs_warmest", "iso10791_a3", "anova"} <= keys   # the whole report
    unnamed = sorted(k for k in keys if f"`{k}`" not in CLI)
    assert not unnamed, f"metrics.json keys docs/cli.md does not name: {unnamed}"


def test_the_settings_of_an_ingest_report_are_data_config_keys(run_out):
    # `order_in_rows`, an internal reading option (no data config key), was written among them;
    # (data89b) `data.join` as its keys are typed, `join.offset_s`, as `ingested_with.settings`
    # name them (it was read as two fields, `join_offset_s`, `join_tolerance_s`)
    conf = yaml.safe_load((ROOT / "conf" / "data" / "default.yaml").read_text())
    keys = set(conf) - {"join"} | {f"join.{sub}" for sub in conf["join"]}
    settings = json.loads((run_out / "ingest_report.json").read_text())["settings"]
    assert set(settings) - keys == set()


def test_every_metric_a_run_logs_to_mlflow_is_named_in_the_cli_reference():
    # outputs.md named three (`E_Z.test.rmse`, `E_Z.test.mae`, `E_Z.val.rmse`, …), cli.md none
    from thermocomp.core.scoring.results import HEADLINES

    logged = [name for name, _, _ in HEADLINES["mlflow"]]
    store = _section("### The MLflow store", "### The `data` group")
    missing = [name for name in logged if f"`<t>.{name}`" not in store]
    assert not missing and "`fit_time_s`" in store, f"docs/cli.md's MLflow store lacks {missing}"


def test_every_column_of_compare_csv_and_its_plot_file_is_named_in_the_cli_reference():
    # compare.csv has `mae` (printed test:mae), the list did not; compare_plot.csv was not named
    from thermocomp.core.scoring.leaderboard import FIGURES, VAL_FIGURES

    written = _section("### `compare.csv`, `compare.md`, `compare.json`", "### A fleet")
    missing = [c for c in (*VAL_FIGURES, *FIGURES, "val_method", "val_mode", "fit_time_s")
               if f"`{c}`" not in written]
    assert not missing, f"docs/cli.md's compare.csv lacks {missing}"
    assert "`compare_plot.csv`" in _section("### `thermocomp compare`", "### `thermocomp promote`")
