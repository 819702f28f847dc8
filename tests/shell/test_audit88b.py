"""audit88's leftovers (audit88b; ``benchmarks/bench_audit88b.py`` lists every finding): a
relative ``hydra.searchpath`` read from the project root as every relative path thermocomp
takes, and the outputs a user opens after a run against what the docs say of them."""

from __future__ import annotations

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
