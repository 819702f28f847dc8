"""``monitor monitor.input=-`` on a machine that runs on: the model was scored on the record's
last part warmed on the rest (``data.test_fraction`` cut one record), and a stream from a reset
starts a model that remembers (a lag bank) cold; its first row looks like any other, so the
mid-campaign rule cannot see it (newmachine59's wire EDM: a Hammerstein model 1.46 um streamed
cold against 0.31 warmed, nothing said)."""

from __future__ import annotations

import io

import numpy as np
import pandas as pd
import pytest

from conftest import FAST
from test_monitor_lab57 import _run
from thermocomp.shell.cli import main

ROLES = ("data.delimiter=;", "data.decimal=,", "data.roles.error=[dX]", "data.test_fraction=0.25",
         "data.reference=none", "monitor.window=5")
SAID = "streamed from a reset, but the model remembers"


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """``maschine.csv``: one run of 600 rows, no run column (the machine never stopped)."""
    path = tmp_path_factory.mktemp("cold") / "maschine.csv"
    _run(np.random.default_rng(5931), 600).to_csv(path, sep=";", decimal=",", index=False)
    return path


@pytest.mark.parametrize("model, continues, said", [("lagbank", None, True), ("mlr", None, False),
                                                    ("lagbank", "maschine_train", False)])
def test_a_stream_of_a_record_that_runs_on_is_said_to_start_cold(
        record, tmp_path, monkeypatch, capsys, model, continues, said):
    """The lag bank from a reset: said, with the way to warm it; MLR (its prediction of a row is
    the same whatever came before): nothing said; with monitor.continues: warmed, not said."""
    rows = pd.read_csv(record, sep=";", decimal=",")
    stream = rows.iloc[450:550].copy()     # the test part's first rows: train's continuation
    if continues is None:                 # a reset's own clock (continues puts it on the record's)
        stream["Zeit [s]"] -= stream["Zeit [s]"].iloc[0]
    monkeypatch.setattr("sys.stdin", io.StringIO(stream.to_csv(sep=";", decimal=",", index=False)))
    also = [f"monitor.continues={continues}"] if continues else []
    assert main(["monitor", f"data.path={record}", f"out={tmp_path / 'o'}", *ROLES, *FAST,
                 f"model={model}", "monitor.input=-", *also]) == 0
    err = capsys.readouterr().err
    assert (SAID in err) is said, err
