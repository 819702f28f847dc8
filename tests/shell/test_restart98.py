"""Files of one clock whose errors start again at 0 are a restart, not a continuation
(restart98, ``bench_restart98.py``): ``data.reference=auto`` reads such a link as a restart and
says so; a record that runs on stays continuing; an explicit ``data.reference`` is the override.
The first test fails on 6c78e132 (the restarted week was read as continuing: reference none)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd

from conftest import FAST
from test_stranger64 import lab_frame
from thermocomp.core.restart import restart_jump
from thermocomp.shell.cli import main


def _weeks(tmp_path, zeroed: bool):
    """Two files of one clock (the hours continue), ``week2`` the test half; its probe set to 0
    at its first row where ``zeroed`` (the error ends near -44 µm in week1)."""
    folder = tmp_path / ("zeroed" if zeroed else "one")
    folder.mkdir()
    frame = lab_frame(240).drop(columns=["Z ram [mm]"])
    first, second = frame.iloc[:120].copy(), frame.iloc[120:].copy()
    if zeroed:
        second["dZ [mm]"] -= second["dZ [mm]"].iloc[0]
    first.to_csv(folder / "week1.csv", index=False)
    second.to_csv(folder / "week2.csv", index=False)
    return folder


def _run(tmp_path, folder, *extra) -> dict:
    out = tmp_path / f"run-{folder.name}-{len(extra)}"
    assert main(["run", f"data.path={folder}", "data.roles.error=[dZ]", "data.test_fraction=0.5",
                 *FAST, "plots=none", f"out={out}", *extra]) == 0
    return json.loads((out / "metrics.json").read_text())


def test_a_week_whose_errors_start_again_at_zero_is_read_as_a_restart_and_said(tmp_path, capsys):
    # before (6c78e132): reference none, week2's state carried over from week1, nothing said
    metrics = _run(tmp_path, _weeks(tmp_path, zeroed=True))
    assert metrics["reference"] == "first_sample" and metrics["carry_over"] == {}
    err = capsys.readouterr().err
    assert "week2 restarts after week1: every error starts at 0 (E_dZ" in err
    assert ("data.reference=auto: first_sample (no test or val campaign continues another; "
            "week2 restarts)") in err
    assert "by its time, but" not in err        # (no junction warning for a link not carried)


def test_an_explicit_reference_none_still_carries_the_state_over(tmp_path, capsys):
    metrics = _run(tmp_path, _weeks(tmp_path, zeroed=True), "data.reference=none")
    assert metrics["reference"] == "none" and metrics["carry_over"] == {"week2": ["week1", "week2"]}
    assert "restarts after" not in capsys.readouterr().err


def test_a_record_that_runs_on_stays_continuing(tmp_path, capsys):
    metrics = _run(tmp_path, _weeks(tmp_path, zeroed=False))
    assert metrics["reference"] == "none" and metrics["carry_over"] == {"week2": ["week1", "week2"]}
    assert "restarts after" not in capsys.readouterr().err


def test_the_rule_reads_first_values_against_the_step_noise():
    steps = np.tile([0.0, 0.3], 10)
    before = pd.DataFrame({"E_X": 2.0 + steps, "E_Y": -3.0 + steps})
    zeroed = pd.DataFrame({"E_X": 0.1 + steps, "E_Y": steps})
    odds, col, last, first = restart_jump(before, zeroed)
    assert (col, last, first) == ("E_Y", -2.7, 0.0) and odds > np.log(20)
    # one error first read 3 steps from 0: it may run on (a probe not zeroed)
    assert restart_jump(before, zeroed.assign(E_X=0.9 + steps)) is None
    # starting at 0 where the predecessor ended about a step from 0 is no evidence
    assert restart_jump(pd.DataFrame({"E_X": 0.1 + steps, "E_Y": steps}), zeroed) is None
    # an error the later file does not measure: nothing read
    assert restart_jump(before, zeroed.assign(E_Y=np.nan)) is None
