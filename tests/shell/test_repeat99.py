"""A row written again (same time, same values) is skipped by the deployed stream (dup99).

A logger re-sending its last sample: the served stream took each copy as a new sample one period
on, its sensor monitor saw every sensor frozen (audit98: all ten excluded at the 12th copy) and
the lags stood still for the burst.  ``run`` refuses a time that repeats (the row written twice
is to be deleted), so the record scored is the one without the copies: the adaptive
compensator (served, replay), the Simulator, the compiled C and the Structured Text now skip
such a row, the last corrections given again.  Before dup99 each form of the lag bank below
parted from the record without the copies by the lags' drift (> 1e-3 µm; the test fails there).
benchmarks/bench_dup99.py measures it on simulated machines.
"""

from __future__ import annotations

import io
import json
import subprocess

import numpy as np
import pandas as pd
import pytest

from test_export import StructuredText, _compiled, _make_dataset, needs_cc
from test_export_first_time import AGREE_UM, _corrections, _deployed
from test_export_guard import _rows, _simulated, _st
from thermocomp.apps.deploy.export import exported_files, state_space

ROW, COPIES = 20, 8        # the row written again, how many times more


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return _make_dataset(tmp_path_factory.mktemp("repeat99") / "data")


def _burst(df: pd.DataFrame, time=True) -> pd.DataFrame:
    """``df`` with row :data:`ROW` written :data:`COPIES` times more (time and values)."""
    out = pd.concat([df.iloc[:ROW + 1], df.iloc[[ROW] * COPIES], df.iloc[ROW + 1:]],
                    ignore_index=True)
    return out if time else out.assign(time=np.nan)


def _served(deployed, df) -> pd.DataFrame:
    """The served model's answer (``predict``, row by row as a session's block) from a reset."""
    deployed.reset()
    return deployed.predict(df)


def _forms(deployed, df, tmp_path) -> dict:
    """Every form's corrections of ``df``'s rows; the compiled stream's stderr."""
    cols, ss = deployed.columns_, state_space(deployed)
    run = subprocess.run([str(_compiled(deployed, tmp_path))], input=_rows([df], cols), text=True,
                         capture_output=True, check=True)
    return {"replay": _corrections(deployed, df),
            "served": -_served(deployed, df)[deployed.targets_].to_numpy(float),
            "simulator": _simulated(ss, [df], cols),
            "c": pd.read_csv(io.StringIO(run.stdout)).to_numpy(float),
            "st": _st(StructuredText(exported_files(deployed, "st")["compensator.st"]), [df], cols),
            "said": run.stderr}


@pytest.fixture(scope="module")
def burst(dataset, tmp_path_factory):
    """``(every form's corrections of the burst, the healthy ones each row should give, the
    deployed lag bank, the burst)``."""
    deployed, test = _deployed(dataset, adaptive=True)
    healthy = _corrections(deployed, test)
    want = np.vstack([healthy[:ROW + 1], healthy[[ROW] * COPIES], healthy[ROW + 1:]])
    df = _burst(test)
    return _forms(deployed, df, tmp_path_factory.mktemp("c")), want, deployed, df


@needs_cc
@pytest.mark.parametrize("form", ("served", "replay", "simulator", "c", "st"))
def test_a_row_written_again_is_skipped_in_every_form(burst, form):
    forms, want, _, _ = burst
    assert np.max(np.abs(forms[form] - want)) <= AGREE_UM


@needs_cc
def test_a_burst_of_rows_written_again_is_said_once_and_counted(burst):
    forms, _, deployed, df = burst
    assert forms["said"].count("a row written again") == 1, forms["said"]
    events = [e for row in _served(deployed, df)["events"] for e in json.loads(row)]
    assert [e["to"] for e in events] == ["repeated"] and deployed.n_repeated_ == COPIES
    assert state_space(deployed).skip_repeats


@needs_cc
@pytest.mark.parametrize("case", ("plain", "no time"))
def test_a_row_that_cannot_be_told_from_a_sample_is_one_in_every_form(dataset, tmp_path, case):
    # a plain stream (no monitor to misjudge it) steps it as before; a stream without a time
    # cannot tell a row written again from a machine standing still (run scores such a file's
    # every row): stepped one period on, every form alike
    deployed, test = _deployed(dataset, adaptive=case != "plain")
    df = _burst(test, time=case == "plain")
    forms = _forms(deployed, df, tmp_path)
    forms.pop("said")
    if case == "plain":
        forms.pop("served")           # (a plain stream's predict is replay's)
    ref = forms.pop("replay")
    assert np.max(np.abs(ref[ROW + 1:ROW + 1 + COPIES] - ref[ROW])) > 1e-3   # the lags moved
    for form, got in forms.items():
        assert np.max(np.abs(got[1:] - ref[1:])) <= AGREE_UM, form
