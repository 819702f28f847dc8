"""`design` on a lab's dataset with its own pose set (vol57): the study takes the set-up's
machine, bar and uncertainties but not its poses, ball count or angle, and now says so (it
named the set-up as the source of C and nothing else)."""

from __future__ import annotations

import json

from conftest import simulated
from thermocomp.apps.sim.volumetric import LargeMillVolumetric
from thermocomp.shell.cli import main

SMALL = ["design.n_machines=4", "design.n_jobs=1", "design.grid=[6,4,4]", "track=false", "plots=none",
         "design.studies={mine:{n_balls:[5],misalignment_deg:[0],position_sets:[S2+S3]},"
         "balls:null,misalignment:null,position_sets:null}"]


def test_design_says_the_datasets_own_poses_are_not_studied(tmp_path, capsys):
    raw = simulated(LargeMillVolumetric(train_hours=1.0, test_hours=1.0, seed=2), tmp_path / "raw")
    setup = json.loads((raw / "volumetric.json").read_text())
    setup["poses"] = [dict(p, name=f"Lab{i}") for i, p in enumerate(setup["poses"][::3])]
    (raw / "volumetric.json").write_text(json.dumps(setup))
    assert main(["design", f"data.path={raw}", f"out={tmp_path / 'o'}", *SMALL]) == 0
    err = capsys.readouterr().err
    line = next((ln for ln in err.splitlines() if "own" in ln and "poses" in ln), None)
    assert line is not None, err
    assert f"own {len(setup['poses'])} poses (Lab0, Lab1" in line and "not studied" in line
    rows = json.loads((tmp_path / "o" / "design.json").read_text())["strategies"]
    assert [r["position_set"] for r in rows] == ["S2+S3"]     # what was studied instead
